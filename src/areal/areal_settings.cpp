// The settings tables of the areal signature and of the polar table over directions (areal.hpp,
// settings.hpp): each input a user states, once, with its unit, range and help; defaults are the
// structs' own initialisers, and the lengths whose 0 means "the default of the maps" read as
// automatic (NaN).
//
// Shared with the prediction (shared_field), the same quantity in both: direction and in_place
// (the upper map in place, not turned over), and atomic_friction (mu_a of every bound).
// Not in the tables, each for a reason:
//   threads       how the work is spread, not what is computed (a run option of each front end);
//   block, prune  the evaluator's bounds (speed only; Python's areal_signature takes prune, the
//                 direct method, as a check), never typed at the CLI;
//   DirectionalOptions' spacing, step, min_points  the lines' sampling, set from the map;
//   the hold angle beside the signature (`areal --lateral`, `anisotropy --hold`): the prediction's
//                 settings (predict_settings(): drops, locked; runaway_distance), run by predict().
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "frictal/areal.hpp"
#include "settings/binding.hpp"

namespace frictal {
namespace {

using settings_detail::bind;
using settings_detail::bind_choice;
using settings_detail::Binding;
using settings_detail::F;
using settings_detail::Lo;
using settings_detail::shared;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The contact slope of the grid areal signature: one field in both tables (anisotropy takes it
/// with its areal method).
template <class T, class Ref>
Binding<T> contact_slope(Ref ref) {
  return bind_choice<T>(F("contact_slope", "", 0, Lo::Closed, 0,
                          "Contact slope of the grid areal signature: lower, the lower face's slope along the "
                          "direction (Eq. 3); mean, the mean of both faces' (anisotropy: with areal)"),
                        ref,
                        std::vector<std::pair<std::string, ArealContactSlope>>{{"lower", ArealContactSlope::Lower},
                                                                               {"mean", ArealContactSlope::Mean}});
}

/// A length whose 0 in the options means "the default that the maps give": NaN (automatic) in the
/// table, 0 in the struct.
template <class T>
Binding<T> automatic_length(Field f, std::function<double&(T&)> ref) {
  f.type = FieldType::Real;
  Binding<T> b;
  b.get = [ref](const T& t) {
    const double v = ref(const_cast<T&>(t));
    return FieldValue{v == 0 ? std::nan("") : v};
  };
  b.set = [ref](T& t, const FieldValue& v) {
    const double x = std::get<double>(v);
    ref(t) = std::isnan(x) ? 0 : x;
  };
  b.field = std::move(f);
  return b;
}

using A = ArealSignatureSettings;

const std::vector<Binding<A>>& areal_table() {
  static const auto t = settings_detail::with_defaults<A>(
      {
          bind<A>(
              shared("direction"), [](A & s) -> auto& { return s.direction; }),
          bind<A>(
              shared("atomic_friction"), [](A & s) -> auto& { return s.atomic_friction; }),
          automatic_length<A>(F("step", "m", 0, Lo::Open, kInf, "Offset step of the grid areal signature", false,
                                "the lower map's smaller spacing min(dx, dy)"),
                              [](A& s) -> double& { return s.options.step; }),
          automatic_length<A>(
              F("max_offset", "m", 0, Lo::Open, kInf, "Largest offset of the grid areal signature (from 0)", false,
                "half the lower map's extent along the direction"),
              [](A& s) -> double& { return s.options.offset_max; }),
          contact_slope<A>([](A & s) -> auto& { return s.options.contact_slope; }),
          [] {
            // The option says what is special (the upper face given in place); the struct says
            // what is usual (turn_over_upper), so the two read inverted.
            Binding<A> b;
            b.field = shared("in_place");
            b.get = [](const A& s) { return FieldValue{!s.options.turn_over_upper}; };
            b.set = [](A& s, const FieldValue& v) { s.options.turn_over_upper = !std::get<bool>(v); };
            return b;
          }(),
      },
      A{});
  return t;
}

using P = AnisotropySettings;

const std::vector<Binding<P>>& anisotropy_table() {
  static const auto t = settings_detail::with_defaults<P>(
      {
          bind<P>(
              F("directions", "", 1, Lo::Closed, 3600, "Sliding directions, equally spaced over 360 deg"),
              [](P & s) -> auto& { return s.directions; }),
          bind<P>(
              F("lines", "", 1, Lo::Closed, 100000, "At most this many parallel line profiles per direction"),
              [](P & s) -> auto& { return s.lines.max_lines; }),
          bind<P>(
              shared("atomic_friction"), [](P & s) -> auto& { return s.lines.atomic_friction; }),
          bind<P>(
              F("areal", "", 0, Lo::Closed, 1,
                "Use the grid areal signature of the two rigid blocks instead of line profiles"),
              [](P & s) -> auto& { return s.areal; }),
          contact_slope<P>([](P & s) -> auto& { return s.contact_slope; }),
      },
      P{});
  return t;
}

}  // namespace

const std::vector<Field>& areal_signature_settings() {
  static const std::vector<Field> f = settings_detail::fields_of(areal_table());
  return f;
}

Result<ArealSignatureSettings> make_areal_signature_settings(const ValueSet& si, ArealSignatureSettings base) {
  return settings_detail::apply(areal_table(), std::move(base), si, "areal");
}

const std::vector<Field>& anisotropy_settings() {
  static const std::vector<Field> f = settings_detail::fields_of(anisotropy_table());
  return f;
}

Result<AnisotropySettings> make_anisotropy_settings(const ValueSet& si, AnisotropySettings base) {
  return settings_detail::apply(anisotropy_table(), std::move(base), si, "anisotropy");
}

}  // namespace frictal
