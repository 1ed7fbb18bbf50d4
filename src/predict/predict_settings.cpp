// The prediction's settings table (predict.hpp, settings.hpp): each PredictOptions member that a
// user states once, with its unit, range and help; defaults are the struct's own initialisers,
// and the members whose 0 means "the default of the surfaces" read as automatic (NaN).
//
// Not in the table, each for a reason:
//   start_offset  a point (X for profiles, X,Y for maps), not one number;
//   loads and the materials (Prediction under load: --load, --modulus, --poisson, --upper-modulus,
//                 --upper-poisson)  a list of forces with a required unit and a modulus that may
//                 read "rigid": the front ends parse them (apps/frictal/map_hold.hpp, Python's
//                 predict), with one help text each;
//   map_load_step, crop_source, progress  set by the library's callers, never typed;
//   threads       how the work is spread, not what is computed (a run option of each front end).
// The conditioning (crop, remove_spikes, spike_threshold, detrend) is its own table,
// conditioning_settings(), which make_predict_options() reads beside this one.
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "frictal/predict.hpp"
#include "settings/binding.hpp"

namespace frictal {
namespace {

using settings_detail::bind;
using settings_detail::Binding;
using settings_detail::F;
using settings_detail::Lo;
using settings_detail::shared;
using B = Binding<PredictOptions>;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// A length whose 0 in PredictOptions means "the default that the surfaces give": NaN (automatic)
/// in the table, 0 in the struct.
B automatic_length(Field f, double PredictOptions::*member) {
  f.type = FieldType::Real;
  B b;
  b.get = [member](const PredictOptions& o) { return FieldValue{o.*member == 0 ? std::nan("") : o.*member}; };
  b.set = [member, f](PredictOptions& o, const FieldValue& v) {
    const double x = word_value_of(f, v);  // a word ("whole") as its value
    o.*member = std::isnan(x) ? 0 : x;
  };
  b.field = std::move(f);
  return b;
}

const std::vector<B>& table() {
  static const auto t = settings_detail::with_defaults<PredictOptions>(
      {
          // The test.
          bind<PredictOptions>(
              shared("direction"), [](PredictOptions & o) -> auto& { return o.direction; }),
          bind<PredictOptions>(
              shared("atomic_friction"), [](PredictOptions & o) -> auto& { return o.atomic_friction; }),
          // The stated test's lengths (docs/theory.md, "The stated test").
          automatic_length(shared("runaway_distance"), &PredictOptions::runaway_distance),
          [] {
            Field f = F("block_length", "m", 0, Lo::Open, kInf,
                        "The test: length of the upper block, the middle piece of the upper surface that slides over "
                        "the lower one (drops wherever it lies wholly on it); whole: all of the upper profile, dropped "
                        "over the first half of the lower one. Profiles only (predict; tilt on files)",
                        false, "the stated test's, 20 run-away distances (periodic pairs: the whole profile)");
            f.words = {{"whole", -1.0}};
            return automatic_length(std::move(f), &PredictOptions::block_length);
          }(),
          bind<PredictOptions>(
              shared("period"), [](PredictOptions & o) -> auto& { return o.period; }),
          // Maps: the drops and the model.
          bind<PredictOptions>(
              F("drops", "", 2, Lo::Closed, 64, "Maps: drops on an N x N grid over the drop range"),
              [](PredictOptions & o) -> auto& { return o.map_drops; }),
          bind<PredictOptions>(
              F("locked", "", 0, Lo::Closed, 1,
                "Maps: also the block locked to the direction (a diagnostic beside the free one; "
                "doubles the cost)"),
              [](PredictOptions & o) -> auto& { return o.map_locked; }),
          [] {
            // The option says what is special (the upper face given in place); the struct says
            // what is usual (turn_over_upper), so the two read inverted.
            B b;
            b.field = shared("in_place");
            b.get = [](const PredictOptions& o) { return FieldValue{!o.turn_over_upper}; };
            b.set = [](PredictOptions& o, const FieldValue& v) { o.turn_over_upper = !std::get<bool>(v); };
            return b;
          }(),
          automatic_length(
              F("sphere_radius", "m", 0, Lo::Open, kInf, "Maps: radius r of the spheres at the upper face's nodes",
                false, "a fifth of the lower map's smaller spacing"),
              &PredictOptions::sphere_radius),
          bind<PredictOptions>(
              F("map_work_limit", "s", 0, Lo::Closed, kInf,
                "Maps: refuse a job whose estimated CPU time exceeds this (0: no limit)"),
              [](PredictOptions & o) -> auto& { return o.map_work_limit; }),
      },
      PredictOptions{});
  return t;
}

}  // namespace

const std::vector<Field>& predict_settings() {
  static const std::vector<Field> f = settings_detail::fields_of(table());
  return f;
}

Result<PredictOptions> make_predict_options(const ValueSet& si, PredictOptions base) {
  ValueSet own, conditioning;
  for (const auto& [name, value] : si) (find_field(conditioning_settings(), name) ? conditioning : own)[name] = value;
  auto c = make_conditioning_settings(conditioning);
  if (!c) return with_prefix("predict: ", c.error());
  if (!conditioning.empty()) {
    if (conditioning.count("crop")) base.crop = c->crop, base.crop_source = c->crop_source;
    if (conditioning.count("remove_spikes")) base.remove_spikes = c->remove_spikes;
    if (conditioning.count("spike_threshold")) base.spike_threshold = c->spike_threshold;
    if (conditioning.count("detrend")) base.detrend = c->detrend;
  }
  return settings_detail::apply(table(), std::move(base), own, "predict");
}

}  // namespace frictal
