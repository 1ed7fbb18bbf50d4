// frictal anisotropy MAP — polar table of the rigid upper bound of friction over sliding
// directions, from the parallel line profiles of an areal map (each against itself turned over);
// with --areal, the true areal signature of the map against itself turned over instead; with
// --hold, beside either, the hold angle over drops of the continuous model per direction (the
// library's predict(): the numbers of `frictal predict --direction`), the block free to move
// sideways, and with --locked also locked to the direction (a diagnostic).
#include <optional>

#include "common.hpp"
#include "frictal/analysis.hpp"
#include "frictal/areal.hpp"
#include "frictal/predict.hpp"
#include "frictal/tilt.hpp"
#include "map_hold.hpp"
#include "options.hpp"
#include "surface_io.hpp"

namespace frictal::cli {
namespace {

struct Args {
  std::string file;
  FieldWords words;  ///< the polar table's settings (anisotropy_settings()) as typed
  std::string detrend = "plane";
  std::string upper;
  bool json = false;
  bool hold = false;
  bool locked = false;
  bool quiet = false;
  int drops = PredictOptions{}.map_drops;
  FieldWords predict_words;  ///< --drops, --locked (the prediction's table)
  double runaway_distance = 0;
  FieldWords runaway_words;  ///< --runaway-distance (the tilt table's field)
  unsigned threads = 0;
  InputOptions input;
  ConditioningOptions cond;
};

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  app.add_option("map", a->file, "Areal map (X3P, Gwyddion text)")->required();
  // --directions, --lines, --atomic-friction, --areal, --contact-slope: the polar table's settings.
  add_field_options(app, anisotropy_settings(), a->words);
  add_detrend_option(app, a->detrend);
  add_conditioning_options(app, a->cond);
  app.add_option("--threads", a->threads, "Worker threads (0 = all cores; default all)");
  app.add_option("--upper", a->upper, "With --areal: the upper block's map (default: the same map turned over)");
  app.add_flag("--json", a->json, "Print one JSON object");
  app.add_flag("--hold", a->hold,
               "Also the hold angle over drops per direction: the continuous model of `frictal predict --direction`, "
               "the block free to move sideways (slower: --drops x --drops drops per direction)");
  // With --hold: --drops and --locked, the prediction's table.
  add_predict_options(app, a->predict_words, {"drops", "locked"});
  app.add_flag("-q,--quiet", a->quiet, "No progress line on standard error (--hold)");
  // --runaway-distance: the tilt table's field (one description everywhere), here the hold angle's run-away.
  add_field_options(app, tilt_settings(), a->runaway_words, all_but(tilt_settings(), "runaway_distance"));
  add_input_options(app, a->input);
  return [a]() {
    if (const ValueSet rv = si_values(tilt_settings(), a->runaway_words); rv.count("runaway_distance"))
      a->runaway_distance = as_real(rv.at("runaway_distance"));
    const AnisotropySettings settings = unwrap(make_anisotropy_settings(si_values(anisotropy_settings(), a->words)));
    if (a->words.words.count("contact_slope") && !settings.areal)
      throw UsageError("--contact-slope: the contact slope of the grid areal signature; it needs --areal");
    const int directions = settings.directions;
    const double atomic_friction = settings.lines.atomic_friction;
    const bool areal = settings.areal;
    const SurfaceData s = load_surface(a->file, a->input);
    if (!s.is_map) throw UsageError(fmt::format("{}: a line profile; anisotropy needs an areal map", a->file));
    const Conditioning cond = conditioning(a->cond, unwrap(parse_detrend(a->detrend)));
    ConditionedMap cm = unwrap(condition(s.map, cond, a->file));
    std::vector<ConditioningRecord> records{cm.record};
    const Map m = std::move(cm.map);
    std::vector<Warning> warnings;
    for (const auto& w : s.warnings) add_warning(warnings, w);
    for (Warning& w : check_map(m, a->file)) add_warning(warnings, std::move(w));
    if (!a->upper.empty() && !areal) throw UsageError("--upper needs --areal");
    require(std::isfinite(a->runaway_distance) && a->runaway_distance >= 0,
            fmt::format("--runaway-distance {}: expected a finite number of metres > 0", a->runaway_distance));
    if (a->runaway_distance > 0 && !a->hold) throw UsageError("--runaway-distance needs --hold");
    a->drops = static_cast<int>(predict_integer(a->predict_words, "drops"));
    a->locked = predict_flag(a->predict_words, "locked");
    if (a->locked && !a->hold) throw UsageError("--locked needs --hold");
    require(a->drops >= 2 && a->drops <= 64, fmt::format("--drops {}: expected 2..64", a->drops));
    Map u = m;
    std::optional<PredictSurface> upper;  // --upper as read, for the hold angle
    if (!a->upper.empty()) {
      const SurfaceData us = load_surface(a->upper, a->input);
      if (a->hold) upper = unwrap(predict_surface(us, a->upper));
      if (!us.is_map) throw UsageError(fmt::format("{}: a line profile; --upper needs an areal map", a->upper));
      ConditionedMap cu = unwrap(condition(us.map, cond, a->upper));
      records.push_back(cu.record);
      u = std::move(cu.map);
      for (const auto& w : us.warnings) add_warning(warnings, w);
      for (Warning& w : check_map(u, a->upper)) add_warning(warnings, std::move(w));
    }
    // --hold: one prediction per direction, on the maps as read (predict() conditions them as above).
    PredictSurface lower;
    PredictOptions hold_options = conditioned_predict_options(a->cond, a->detrend);
    std::string progress_prefix;
    if (a->hold) {
      lower = unwrap(predict_surface(s, a->file));
      hold_options.atomic_friction = atomic_friction;
      hold_options.runaway_distance = a->runaway_distance;
      hold_options.map_drops = a->drops;
      hold_options.map_locked = a->locked;
      hold_options.threads = a->threads;
      hold_options.progress = drop_progress("anisotropy", a->quiet, &progress_prefix, false);
      // The whole job's estimated cost against the prediction's limit (each direction's own
      // check would let 36 just-allowed directions through).
      const std::size_t drops = std::size_t(a->drops * a->drops) * (a->locked ? 2 : 1);
      const double work = map_work_estimate(u.valid_count(), drops) * directions;
      require(hold_options.map_work_limit <= 0 || work <= hold_options.map_work_limit,
              fmt::format("--hold: {} directions x {} drops on {} spheres would take about {:.0f} s of CPU, above "
                          "the prediction's limit of {:.0f} s: fewer --directions or --drops, or crop or resample "
                          "the map",
                          directions, drops, u.valid_count(), work, hold_options.map_work_limit));
    }
    AnisotropyTable table;
    table.atomic_friction = atomic_friction;
    if (a->hold) {
      table.hold_model = "map-continuous-free";
      table.hold_drops = a->drops * a->drops;
    }
    std::string text;  // the table, printed whole after the progress line
    if (!a->json)
      text += fmt::format(
          "{}: {} x {} map, {} directions ({})\n  dir_deg  theta+_deg  theta-_deg  sigma_deg  bound_deg  mu<={}\n",
          a->file, m.nx, m.ny, directions, areal ? "areal signature" : "line profiles",
          a->hold ? std::string("  hold_q50_deg  hold_q05 - q95_deg") + (a->locked ? "  locked_q50_deg" : "")
                  : std::string());
    for (int k = 0; k < directions; ++k) {
      const double angle = 2 * std::numbers::pi * k / directions;
      double fwd, bwd, sigma;
      std::size_t lines = 0;
      if (areal) {
        ArealSignatureOptions o;
        o.threads = a->threads;
        o.contact_slope = settings.contact_slope;
        const ArealSignature r = unwrap(areal_signature(m, u, angle, o));
        fwd = r.theta_max_forward;
        bwd = r.theta_max_backward;
        sigma = r.contact_slope_std;
      } else {
        DirectionalOptions o;
        o.max_lines = settings.lines.max_lines;
        o.threads = a->threads;
        const DirectionalFriction r = unwrap(friction_along(m, angle, o));
        fwd = r.theta_forward;
        bwd = r.theta_backward;
        sigma = r.sigma;
        lines = r.lines;
      }
      const FrictionPrediction p = unwrap(predict_friction(atomic_friction, fwd, sigma));
      add_bound_warnings(warnings, p, fmt::format("direction {:g} deg", to_deg(angle)));
      // The hold angle over drops of the same pair along this direction: predict() on the maps as
      // read, with the same conditioning (the numbers of `frictal predict --direction`).
      std::optional<Prediction> hold;
      if (a->hold) {
        PredictOptions o = hold_options;
        o.direction = (360.0 * k / directions) * kDeg;  // as `frictal predict --direction DEG` converts
        progress_prefix = fmt::format("direction {} of {}, ", k + 1, directions);
        hold = unwrap(predict(lower, a->upper.empty() ? nullptr : &*upper, o));
        for (const Warning& w : hold->warnings)
          if (w.code != "reader")
            add_warning(warnings, {w.code, fmt::format("direction {:g} deg: {}", to_deg(angle), w.message)});
      }
      if (a->json) {
        AnisotropyRow row;
        row.direction = angle;
        row.theta_forward = fwd;
        row.theta_backward = bwd;
        row.sigma = sigma;
        // theta_max + theta_a (Eq. 6) of the signature; with --hold the hold model's own bound (the
        // same model as the hold angles beside it: above every drop), the signature's kept apart.
        row.upper_bound_friction_angle = hold ? hold->upper_bound_friction_angle : p.friction_angle;
        row.upper_bound_friction_coefficient =
            hold ? std::tan(hold->upper_bound_friction_angle) : p.friction_coefficient;
        if (hold) row.signature_bound_friction_angle = p.friction_angle;
        row.eq18_low_friction_coefficient = p.friction_coefficient_low;
        if (!areal) row.lines = lines;
        if (hold) {
          row.hold_runaway_distance = hold->runaway_distance;
          row.hold_angle = hold->friction_angle;
          if (a->locked) row.hold_angle_locked = hold->locked_friction_angle;
        }
        table.directions.push_back(std::move(row));
      } else {
        const double bound = hold ? hold->upper_bound_friction_angle : p.friction_angle;
        text += fmt::format("  {:7.1f}  {:10.4f}  {:10.4f}  {:9.4f}  {:7.4f}  {:.5f}", to_deg(angle), to_deg(fwd),
                            to_deg(bwd), to_deg(sigma), to_deg(bound), std::tan(bound));
        if (hold) {
          text += fmt::format("  {:12.4f}  {:7.4f} - {:7.4f}", to_deg(hold->friction_angle.q50),
                              to_deg(hold->friction_angle.q05), to_deg(hold->friction_angle.q95));
          if (a->locked) text += fmt::format("  {:15.4f}", to_deg(hold->locked_friction_angle.q50));
        }
        text += fmt::format("\n");
      }
    }
    if (hold_options.progress) fmt::print(stderr, "\n");
    fmt::print("{}", text);
    if (a->json) {
      RunRecord run;
      run.file = a->file;
      run.method = areal ? "areal" : "lines";
      run.conditioning = conditioning_text(records);
      run.warnings = warnings;
      nlohmann::json j = object_of(anisotropy_columns(), table);
      put_columns(j, run_record_columns(), run);
      print_json(j);
    } else {
      if (a->hold)
        fmt::print(
            "  (theta+, theta-, sigma: the {}; bound_deg and mu<=: the hold model's rigid upper bound, the steepest "
            "seat the drops rested in, above every drop; the hold_* columns: {} drops per direction, model "
            "map-continuous-free{}, atomic friction mu_a = {:g} included: frictal predict --direction DEG)\n",
            areal ? "grid areal signature (a diagnostic of the map's nodes)" : "line profiles' signatures",
            a->drops * a->drops, a->locked ? " (locked: the block locked to the direction)" : "", atomic_friction);
      else
        fmt::print(
            "  (theta_max-based rigid upper bounds of the {}; what a tilt test reads: frictal predict --direction "
            "DEG)\n",
            areal ? "grid areal signature (a diagnostic of the map's nodes)" : "line profiles");
      fmt::print("  conditioning: {}\n", conditioning_text(records));
      for (const Warning& w : warnings)
        if (w.code != "reader") print_warnings({w});
    }
    return 0;
  };
}

FRICTAL_COMMAND({"anisotropy", "Rigid upper bound of friction of an areal map over sliding directions (polar table)",
                 setup, 70});

}  // namespace
}  // namespace frictal::cli
