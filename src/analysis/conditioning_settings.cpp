// The conditioning's settings table (conditioning.hpp, settings.hpp): crop, remove_spikes,
// spike_threshold and detrend, each once with its unit, range and help; defaults are
// ConditioningSettings' own initialisers.
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <fmt/core.h>

#include "frictal/conditioning.hpp"
#include "settings/binding.hpp"

namespace frictal {
namespace {

using settings_detail::bind;
using settings_detail::Binding;
using settings_detail::F;
using settings_detail::Lo;
using B = Binding<ConditioningSettings>;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// A word field whose words follow forms (Field::check_word): the crop window, the form.
B word_field(Field f, std::vector<std::string> forms,
             std::function<Status(const std::string&, const std::string&)> check,
             std::function<FieldValue(const ConditioningSettings&)> get,
             std::function<void(ConditioningSettings&, const std::string&)> set) {
  f.type = FieldType::Choice;
  f.choices = std::move(forms);
  f.check_word = std::move(check);
  B b;
  b.field = std::move(f);
  b.get = std::move(get);
  b.set = [set](ConditioningSettings& c, const FieldValue& v) { set(c, std::get<std::string>(v)); };
  return b;
}

const std::vector<B>& table() {
  static const auto t = settings_detail::with_defaults<ConditioningSettings>(
      {
          // Step 1. The window's text is parsed by parse_crop (lengths with their units).
          word_field(
              F("crop", "m", 0, Lo::Closed, 0,
                "Keep only the window X0,X1 (maps: X0,X1 or X0,X1,Y0,Y1) of each surface, in its file's coordinates: "
                "m, or a length with a unit such as 0.1mm,0.9mm (first step of the conditioning)",
                false, "the whole surface"),
              {"X0,X1", "X0,X1,Y0,Y1"},
              [](const std::string& word, const std::string& prefix) -> Status {
                if (auto w = parse_crop(word, prefix); !w) return w.error();
                return Ok{};
              },
              [](const ConditioningSettings&) { return FieldValue{std::string()}; },
              [](ConditioningSettings& c, const std::string& word) {
                c.crop = parse_crop(word).value();  // checked by check_word before
                c.crop_source = "crop '" + word + "'";
              }),
          // Step 2.
          bind<ConditioningSettings>(
              F("remove_spikes", "", 0, Lo::Closed, 1,
                "Remove the points more than spike_threshold rms heights from the median of their neighbours "
                "(profiles: replaced by linear interpolation, dropped at an end; maps: masked), after the crop and "
                "before the form removal"),
              [](ConditioningSettings & c) -> auto& { return c.remove_spikes; }),
          bind<ConditioningSettings>(
              F("spike_threshold", "", 0, Lo::Open, kInf,
                "k of remove_spikes, in rms heights Sq of the form-removed surface (the "
                "default is the spikes warning's rule)"),
              [](ConditioningSettings & c) -> auto& { return c.spike_threshold; }),
          // Step 3. Automatic by default: form_or_default() per surface.
          word_field(
              F("detrend", "", 0, Lo::Closed, 0,
                "Form removed from each surface first (the form and tilt of the scan): none, mean, line (a plane "
                "for maps) or poly:N (N in 0..10)",
                false, "line for profiles, plane for maps, mean for a periodic profile; none for a generated surface"),
              {"none", "mean", "line", "plane", "poly:N"},
              [](const std::string& word, const std::string& prefix) -> Status {
                if (word.empty() || !parse_detrend(word))
                  return make_error(fmt::format(
                      "{} '{}': not understood (expected none, mean, line, plane or poly:N with N in 0..10)", prefix,
                      word));
                return Ok{};
              },
              [](const ConditioningSettings&) { return FieldValue{std::string()}; },
              [](ConditioningSettings& c, const std::string& word) { c.detrend = parse_detrend(word).value(); }),
      },
      ConditioningSettings{});
  return t;
}

}  // namespace

Conditioning ConditioningSettings::of_surface(bool periodic) const {
  Conditioning c;
  c.crop = crop;
  c.crop_source = crop_source;
  c.remove_spikes = remove_spikes;
  c.spike_threshold = spike_threshold;
  c.form = form_or_default(detrend, periodic);
  return c;
}

const std::vector<Field>& conditioning_settings() {
  static const std::vector<Field> f = settings_detail::fields_of(table());
  return f;
}

Result<ConditioningSettings> make_conditioning_settings(const ValueSet& si) {
  return settings_detail::apply(table(), ConditioningSettings{}, si, "conditioning");
}

}  // namespace frictal
