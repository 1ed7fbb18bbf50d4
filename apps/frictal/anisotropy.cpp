// frictal anisotropy MAP — polar table of the predicted friction angle over sliding directions,
// from the parallel line profiles of an areal map (each against itself turned over); with
// --areal, the true areal signature of the map against itself turned over instead; with --hold,
// beside either, the hold angle over drops of a block that may move sideways (free) and of one
// that may not (locked), on the lift over two dimensions of offset (areal.hpp).
#include "common.hpp"
#include "frictal/analysis.hpp"
#include "frictal/areal.hpp"
#include "frictal/tilt.hpp"
#include "options.hpp"
#include "surface_io.hpp"

namespace frictal::cli {
namespace {

struct Args {
  std::string file;
  int directions = 36;
  std::size_t max_lines = 128;
  double atomic_friction = 0;
  std::string detrend = "plane";
  bool areal = false;
  std::string upper;
  std::string contact_slope = "lower";
  bool json = false;
  bool hold = false;
  double runaway_distance = 0;
  FieldWords runaway_words;  ///< --runaway-distance (the tilt table's field)
  unsigned threads = 0;
  InputOptions input;
  ConditioningOptions cond;
};

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  app.add_option("map", a->file, "Areal map (X3P, Gwyddion text)")->required();
  app.add_option("--directions", a->directions, "Sliding directions over 360 deg (default 36)");
  app.add_option("--lines", a->max_lines, "At most this many parallel lines per direction (default 128)");
  add_atomic_friction_option(app, a->atomic_friction);
  app.add_option("--detrend", a->detrend, "Remove none, mean, plane or poly:N from the map first (default plane)");
  add_conditioning_options(app, a->cond);
  app.add_flag("--areal", a->areal, "Use the areal signature of the two rigid blocks instead of line profiles");
  app.add_option("--threads", a->threads, "Worker threads (0 = all cores; default all)");
  app.add_option("--contact-slope", a->contact_slope, "With --areal: lower (Eq. 3, default) or mean (of both faces)");
  app.add_option("--upper", a->upper, "With --areal: the upper block's map (default: the same map turned over)");
  app.add_flag("--json", a->json, "Print one JSON object");
  app.add_flag("--hold", a->hold,
               "Also the hold angle over drops per direction, free to move sideways and locked (2D lift; slower)");
  // --runaway-distance: the tilt table's field (one description everywhere), here the hold angle's run-away.
  add_field_options(app, tilt_settings(), a->runaway_words, all_but(tilt_settings(), "runaway_distance"));
  add_input_options(app, a->input);
  return [a]() {
    if (const ValueSet rv = si_values(tilt_settings(), a->runaway_words); rv.count("runaway_distance"))
      a->runaway_distance = as_real(rv.at("runaway_distance"));
    require(a->directions >= 1 && a->directions <= 3600, "--directions must be in 1..3600");
    require(a->max_lines >= 1 && a->max_lines <= 100000, "--lines must be in 1..100000");
    require(std::isfinite(a->atomic_friction) && a->atomic_friction >= 0,
            "--atomic-friction must be a finite number >= 0");
    const SurfaceData s = load_surface(a->file, a->input);
    if (!s.is_map) throw UsageError(fmt::format("{}: a line profile; anisotropy needs an areal map", a->file));
    const Conditioning cond = conditioning(a->cond, unwrap(parse_detrend(a->detrend)));
    ConditionedMap cm = unwrap(condition(s.map, cond, a->file));
    std::vector<ConditioningRecord> records{cm.record};
    const Map m = std::move(cm.map);
    std::vector<Warning> warnings;
    for (const auto& w : s.warnings) add_warning(warnings, {"reader", w});
    for (Warning& w : check_map(m, a->file)) add_warning(warnings, std::move(w));
    if (!a->upper.empty() && !a->areal) throw UsageError("--upper needs --areal");
    require(std::isfinite(a->runaway_distance) && a->runaway_distance >= 0,
            fmt::format("--runaway-distance {}: expected a finite number of metres > 0", a->runaway_distance));
    if (a->runaway_distance > 0 && !a->hold) throw UsageError("--runaway-distance needs --hold");
    Map u = m;
    if (!a->upper.empty()) {
      const SurfaceData us = load_surface(a->upper, a->input);
      if (!us.is_map) throw UsageError(fmt::format("{}: a line profile; --upper needs an areal map", a->upper));
      ConditionedMap cu = unwrap(condition(us.map, cond, a->upper));
      records.push_back(cu.record);
      u = std::move(cu.map);
      for (const auto& w : us.warnings) add_warning(warnings, {"reader", w});
      for (Warning& w : check_map(u, a->upper)) add_warning(warnings, std::move(w));
    }
    nlohmann::json rows = nlohmann::json::array();
    if (!a->json)
      fmt::print(
          "{}: {} x {} map, {} directions ({})\n  dir_deg  theta+_deg  theta-_deg  sigma_deg  bound_deg  mu<={}\n",
          a->file, m.nx, m.ny, a->directions, a->areal ? "areal signature" : "line profiles",
          a->hold ? "       hold_free_mean_deg  hold_locked_mean_deg" : "");
    for (int k = 0; k < a->directions; ++k) {
      const double angle = 2 * std::numbers::pi * k / a->directions;
      double fwd, bwd, sigma;
      std::size_t lines = 0;
      if (a->areal) {
        ArealSignatureOptions o;
        o.threads = a->threads;
        if (a->contact_slope == "mean")
          o.contact_slope = ArealContactSlope::Mean;
        else if (a->contact_slope != "lower")
          throw UsageError(
              fmt::format("--contact-slope '{}' not understood (expected lower or mean)", a->contact_slope));
        const ArealSignature r = unwrap(areal_signature(m, u, angle, o));
        fwd = r.theta_max_forward;
        bwd = r.theta_max_backward;
        sigma = r.contact_slope_std;
      } else {
        DirectionalOptions o;
        o.max_lines = a->max_lines;
        o.threads = a->threads;
        const DirectionalFriction r = unwrap(friction_along(m, angle, o));
        fwd = r.theta_forward;
        bwd = r.theta_backward;
        sigma = r.sigma;
        lines = r.lines;
      }
      const FrictionPrediction p = unwrap(predict_friction(a->atomic_friction, fwd, sigma));
      add_eq18_warning(warnings, p.low_clamped, fmt::format("direction {:g} deg", to_deg(angle)));
      // The hold angles over drops on the 2D lift of the same pair (free, then locked).
      HoldStatistics hold_free, hold_locked;
      if (a->hold) {
        add_warning(warnings, {"grid-model",
                               "the hold angles (--hold) come from the grid model of the lift (offsets on "
                               "the map's lattice); the prediction, from the continuous model checked "
                               "on MuJoCo, is `frictal predict --direction` (they differ by up to "
                               "several degrees)"});
        ArealLiftOptions lo;
        lo.threads = a->threads;
        const ArealLift lift = unwrap(areal_lift(m, u, angle, lo));
        ArealHoldOptions ho;
        ho.runaway_distance =
            a->runaway_distance > 0 ? a->runaway_distance : 0.1 * (lift.along(lift.n_along - 1) - lift.along(0));
        ho.atomic_friction = a->atomic_friction;
        ho.threads = a->threads;
        hold_free = unwrap(areal_hold_distribution(lift, ho)).hold;
        ho.lateral = LateralMotion::Locked;
        hold_locked = unwrap(areal_hold_distribution(lift, ho)).hold;
      }
      if (a->json) {
        nlohmann::json row;
        row["direction_deg"] = to_deg(angle);
        row["theta_forward_deg"] = to_deg(fwd);
        row["theta_backward_deg"] = to_deg(bwd);
        row["sigma_deg"] = to_deg(sigma);
        row["upper_bound_friction_angle_deg"] = to_deg(p.friction_angle);  // theta_max + theta_a (Eq. 6)
        row["upper_bound_friction_coefficient"] = p.friction_coefficient;
        row["eq18_low_friction_coefficient"] = p.friction_coefficient_low;
        if (!a->areal) row["lines"] = lines;
        if (a->hold) {
          row["hold_angle_free_mean_deg"] = to_deg(hold_free.mean);
          row["hold_angle_free_q50_deg"] = to_deg(hold_free.q50);
          row["hold_angle_free_max_deg"] = to_deg(hold_free.max);
          row["hold_angle_locked_mean_deg"] = to_deg(hold_locked.mean);
          row["hold_angle_locked_q50_deg"] = to_deg(hold_locked.q50);
          row["hold_angle_locked_max_deg"] = to_deg(hold_locked.max);
        }
        rows.push_back(row);
      } else {
        fmt::print("  {:7.1f}  {:10.4f}  {:10.4f}  {:9.4f}  {:7.4f}  {:.5f}", to_deg(angle), to_deg(fwd), to_deg(bwd),
                   to_deg(sigma), to_deg(p.friction_angle), p.friction_coefficient);
        if (a->hold) fmt::print("  {:19.4f}  {:20.4f}", to_deg(hold_free.mean), to_deg(hold_locked.mean));
        fmt::print("\n");
      }
    }
    if (a->json) {
      nlohmann::json j;
      j["file"] = a->file;
      j["method"] = a->areal ? "areal" : "lines";
      j["atomic_friction"] = a->atomic_friction;
      j["directions"] = rows;
      j["conditioning"] = conditioning_text(records);
      j["warnings"] = warnings_json(warnings);
      print_json(j);
    } else {
      fmt::print("  (theta_max-based rigid upper bounds; what a tilt test reads: frictal predict --direction DEG)\n");
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
