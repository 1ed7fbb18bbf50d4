// The signature's settings table (signature.hpp, settings.hpp): each SignatureOptions member that a
// user states, once, with its unit, range and help; defaults are the struct's own initialisers.
//
// Not in the table, each for a reason:
//   threads        how the work is spread, not what is computed (a run option of each front end);
//   keep_contacts  what is kept for output (the CLI's --contacts FILE, Python's keep_contacts);
//   max_events, tilted_bounds, tolerance  the evaluator's own limits and bounds, never typed;
//   the hold analysis that `frictal signature` runs on the same lift (atomic_friction,
//                  runaway_distance, period: the quantities shared with the tilt test and the
//                  prediction, shared_field; --start-offset, a point) reads HoldOptions, not these.
#include <cctype>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <fmt/core.h>

#include "frictal/signature.hpp"
#include "settings/binding.hpp"

namespace frictal {
namespace {

using settings_detail::bind;
using settings_detail::bind_choice;
using settings_detail::Binding;
using settings_detail::F;
using settings_detail::Lo;
using settings_detail::shared;
using B = Binding<SignatureOptions>;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Two lengths MIN < MAX (m, or each with its unit as every length field reads it: 0.1mm),
/// apart by a comma or by spaces ("0 0.5mm": the CLI's two words joined).
Result<std::pair<double, double>> parse_offset_range(const std::string& word, const std::string& prefix) {
  const std::string expected =
      "expected MIN MAX (or MIN,MAX), two offsets in m or with a unit m, mm, um, nm (e.g. 0 0.5mm), MIN < MAX";
  std::vector<std::string> parts;
  if (word.find(',') != std::string::npos) {
    std::size_t start = 0;
    for (std::size_t comma; (comma = word.find(',', start)) != std::string::npos; start = comma + 1)
      parts.push_back(word.substr(start, comma - start));
    parts.push_back(word.substr(start));
  } else {
    std::size_t i = 0;
    while (i < word.size()) {
      while (i < word.size() && std::isspace(static_cast<unsigned char>(word[i]))) ++i;
      std::size_t j = i;
      while (j < word.size() && !std::isspace(static_cast<unsigned char>(word[j]))) ++j;
      if (j > i) parts.push_back(word.substr(i, j - i));
      i = j;
    }
  }
  if (parts.size() != 2) return make_error(fmt::format("{} '{}': {}", prefix, word, expected));
  // Each part read as a length field reads its word (settings.hpp, parse_text_word).
  const Field length = F("offset", "m", -kInf, Lo::Closed, kInf, "");
  double v[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    auto x = parse_text_word(length, parts[k], prefix);
    if (!x || !std::holds_alternative<double>(*x) || !std::isfinite(std::get<double>(*x)))
      return make_error(fmt::format("{} '{}': '{}' is not a length; {}", prefix, word, parts[k], expected));
    v[k] = std::get<double>(*x);
  }
  if (!(v[0] < v[1])) return make_error(fmt::format("{} '{}': {}", prefix, word, expected));
  return std::pair{v[0], v[1]};
}

const std::vector<B>& table() {
  static const auto t = settings_detail::with_defaults<SignatureOptions>(
      {
          bind_choice<SignatureOptions>(
              F("slopes", "", 0, Lo::Closed, 0,
                "Contact slopes: exact, the polyline's contact rules (Eq. 3); spline, the cubic-spline slopes of both "
                "surfaces at the contact, averaged (Sec. V B)"),
              [](SignatureOptions & o) -> auto& { return o.slopes; },
              std::vector<std::pair<std::string, SlopeMethod>>{{"exact", SlopeMethod::Exact},
                                                               {"spline", SlopeMethod::Spline}}),
          // The library refuses more (signature(): offsets <= 1e8).
          bind<SignatureOptions>(
              F("offsets", "", 0, Lo::Closed, 1e8,
                "0: every event offset (exact; if there are too many, offsets sampled at the finer point spacing); "
                "N: N equally spaced offsets"),
              [](SignatureOptions & o) -> auto& { return o.offsets; }),
          bind<SignatureOptions>(
              F("keep_grid", "", 0, Lo::Closed, 1,
                "With offsets N: evaluate that grid even where every event offset costs less (aligned grids)"),
              [](SignatureOptions & o) -> auto& { return o.keep_grid; }),
          bind<SignatureOptions>(
              F("exact", "", 0, Lo::Closed, 1, "Refuse to sample offsets when the exact signature has too many events"),
              [](SignatureOptions & o) -> auto& { return o.require_exact; }),
          [] {
            // Two lengths as one word (as crop takes its window): "MIN MAX" or "MIN,MAX".
            B b;
            b.field = F("offset_range", "m", 0, Lo::Closed, 0,
                        "The offsets evaluated, from MIN to MAX, MIN < MAX (each length may name its unit: 0 0.5mm)",
                        false, "one period of the lower profile if periodic, else half the shorter block");
            b.field.type = FieldType::Choice;
            b.field.choices = {"MIN MAX"};
            b.field.check_word = [](const std::string& word, const std::string& prefix) -> Status {
              if (auto r = parse_offset_range(word, prefix); !r) return r.error();
              return Ok{};
            };
            b.get = [](const SignatureOptions&) { return FieldValue{std::string()}; };
            b.set = [](SignatureOptions& o, const FieldValue& v) {
              const auto r = parse_offset_range(std::get<std::string>(v), "offset_range").value();  // checked before
              o.offset_min = r.first;
              o.offset_max = r.second;
            };
            return b;
          }(),
          // The library refuses more (signature(): bins in 1..100000).
          bind<SignatureOptions>(
              F("bins", "", 1, Lo::Closed, 100000, "Bins of the contact-slope PDF"),
              [](SignatureOptions & o) -> auto& { return o.bins; }),
          // The tilt test's quantity (shared_field): the DEM's rounded blocks, here the lift of one
          // core against the other dilated by a disk of radius 2r. Absent (automatic, NaN; the
          // struct's 0): rigid profiles, the paper's signature.
          [] {
            B b;
            b.field = shared("spheroradius");
            b.get = [](const SignatureOptions& o) {
              return FieldValue{o.spheroradius == 0 ? std::nan("") : o.spheroradius};
            };
            b.set = [](SignatureOptions& o, const FieldValue& v) {
              const double r = std::get<double>(v);
              o.spheroradius = std::isnan(r) ? 0 : r;
            };
            return b;
          }(),
      },
      SignatureOptions{});
  return t;
}

}  // namespace

const std::vector<Field>& signature_settings() {
  static const std::vector<Field> f = settings_detail::fields_of(table());
  return f;
}

Result<SignatureOptions> make_signature_options(const ValueSet& si, SignatureOptions base) {
  auto o = settings_detail::apply(table(), std::move(base), si, "signature");
  if (o && o->spheroradius > 0 && o->slopes == SlopeMethod::Spline)
    return make_error("signature: spheroradius: the rounded faces have their own exact slopes; use slopes exact");
  return o;
}

}  // namespace frictal
