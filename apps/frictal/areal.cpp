// frictal areal LOWER [UPPER] — the areal signature of two rigid blocks sliding along one
// direction (the upper block turned over onto the lower one; default: LOWER against itself);
// with --lateral/--runaway-distance/--start-offset, the lift over two dimensions of offset and
// the hold angle of a block that may move sideways (free) or not (locked), from one drop or over
// drops spread over the offset grid.
#include "frictal/areal.hpp"
#include "common.hpp"
#include "frictal/analysis.hpp"
#include "frictal/tilt.hpp"
#include "options.hpp"
#include "surface_io.hpp"

#include <array>
#include <optional>

namespace frictal::cli {
namespace {

struct Args {
  std::string lower, upper, output;
  double angle = 0;
  double step = 0, offset_max = 0;
  double atomic_friction = 0;
  std::string detrend = "plane";
  std::string contact_slope = "lower";
  bool in_place = false;
  bool json = false;
  // The hold angle over two dimensions of offset.
  std::string lateral;
  double runaway_distance = 0;
  FieldWords runaway_words;  ///< --runaway-distance (the tilt table's field)
  std::string start_offset;
  double offset_min = 0, across_step = 0, across_max = 0;
  unsigned threads = 0;
  InputOptions input;
  ConditioningOptions cond;
  std::string conditioning;  ///< what the conditioning did (set after reading the maps)
};

int run_hold(const Args& a, const Map& f, const Map& g, std::vector<Warning> warnings) {
  require(a.lateral.empty() || a.lateral == "free" || a.lateral == "locked",
          fmt::format("--lateral '{}' not understood (expected free or locked)", a.lateral));
  require(std::isfinite(a.runaway_distance) && a.runaway_distance >= 0,
          fmt::format("--runaway-distance {}: expected a finite number of metres > 0", a.runaway_distance));
  require(std::isfinite(a.offset_min) && a.across_step >= 0 && a.across_max >= 0 && std::isfinite(a.across_step) &&
              std::isfinite(a.across_max),
          "--min-offset must be finite, --across-step and --across-max finite and >= 0 (metres)");
  require(a.output.empty(), "-o is not available with the hold angle (--lateral, --runaway-distance, --start-offset)");
  ArealLiftOptions lo;
  lo.step = a.step;
  lo.offset_min = a.offset_min;
  lo.offset_max = a.offset_max;
  lo.across_step = a.across_step;
  lo.across_max = a.across_max;
  lo.threads = a.threads;
  lo.turn_over_upper = !a.in_place;
  const ArealLift lift = unwrap(areal_lift(f, g, a.angle * kDeg, lo));
  ArealHoldOptions ho;
  // A tenth of the offset range along d, as default_runaway_distance() (hold.hpp) for a pair
  // that is not periodic.
  ho.runaway_distance =
      a.runaway_distance > 0 ? a.runaway_distance : 0.1 * (lift.along(lift.n_along - 1) - lift.along(0));
  ho.atomic_friction = a.atomic_friction;
  ho.threads = a.threads;
  const bool locked_mode = a.lateral == "locked";
  std::size_t start = 0;
  if (!a.start_offset.empty()) {
    const auto xy = parse_offset(a.start_offset, "--start-offset");
    auto node = areal_lift_node(lift, xy[0], xy[1]);
    if (!node) throw UsageError("--start-offset: " + node.error().message, node.error().code);
    start = *node;
  } else {
    // 0,0 when it lies on the grid, else the first offset along d on the line v = 0.
    auto node = areal_lift_node(lift, 0.0, 0.0);
    start = node ? *node : (lift.n_across / 2) * lift.n_along;
  }
  if (std::isnan(lift.lift[start]))
    throw UsageError(
        fmt::format("--start-offset: the blocks do not touch at offset ({}, {}) m (expected an offset "
                    "where they overlap)",
                    lift.offset_xy(start)[0], lift.offset_xy(start)[1]));
  ho.lateral = LateralMotion::Free;
  const ArealHold free = unwrap(areal_hold_angle(lift, start, ho));
  // Locked: the 1D rule on the line through the free block's rest offset (hold.hpp's hold_angle;
  // the grid's Locked process gives the same angle and the path).
  ho.lateral = LateralMotion::Locked;
  ArealHold locked = unwrap(areal_hold_angle(lift, free.rest, ho));
  locked.hold_angle = unwrap(areal_locked_hold_angle(lift, free.rest, ho)).hold_angle;
  ho.lateral = locked_mode ? LateralMotion::Locked : LateralMotion::Free;
  const ArealHold& chosen = locked_mode ? locked : free;
  std::optional<ArealHoldDistribution> dist;
  if (a.start_offset.empty()) dist = unwrap(areal_hold_distribution(lift, ho));
  add_warning(warnings, {"grid-model",
                         "the hold angles here come from the grid model of the lift (offsets on the "
                         "map's lattice); the prediction, from the continuous model checked on "
                         "MuJoCo, is `frictal predict` (they differ by up to several degrees)"});
  const auto rest = lift.offset_xy(free.rest);
  const auto held = lift.offset_xy(chosen.hold_node);
  const auto dropped = lift.offset_xy(start);
  if (a.json) {
    nlohmann::json j;
    j["lower"] = a.lower;
    j["upper"] = a.upper.empty() ? a.lower : a.upper;
    j["direction_deg"] = a.angle;
    j["lateral"] = locked_mode ? "locked" : "free";
    j["model"] = "grid-lift";
    j["warnings"] = warnings_json(warnings);
    j["runaway_distance_m"] = ho.runaway_distance;
    j["atomic_friction"] = a.atomic_friction;
    j["offsets_along"] = lift.n_along;
    j["offsets_across"] = lift.n_across;
    j["offset_along_range_m"] = {lift.along(0), lift.along(lift.n_along - 1)};
    j["offset_across_range_m"] = {lift.across(0), lift.across(lift.n_across - 1)};
    j["start_offset_m"] = {dropped[0], dropped[1]};
    j["rest_offset_m"] = {rest[0], rest[1]};
    j["hold_angle_deg"] = to_deg(chosen.hold_angle);
    j["hold_angle_free_deg"] = to_deg(free.hold_angle);
    j["hold_angle_locked_deg"] = to_deg(locked.hold_angle);
    j["hold_offset_m"] = {held[0], held[1]};
    j["steering_deg"] = to_deg(chosen.steering);
    j["slips"] = chosen.slips;
    j["ran_off_end"] = chosen.ran_off_end;
    j["interlocked"] = chosen.interlocked;
    if (dist) {
      j["drops"] = dist->drops;
      j["basins"] = dist->rest.size();
      j["hold_angle_mean_deg"] = to_deg(dist->hold.mean);
      j["hold_angle_std_deg"] = to_deg(dist->hold.std);
      j["hold_angle_q05_deg"] = to_deg(dist->hold.q05);
      j["hold_angle_q50_deg"] = to_deg(dist->hold.q50);
      j["hold_angle_q95_deg"] = to_deg(dist->hold.q95);
      j["hold_angle_min_deg"] = to_deg(dist->hold.min);
      j["hold_angle_max_deg"] = to_deg(dist->hold.max);
    }
    j["evaluated_nodes"] = lift.evaluated_nodes;
    j["conditioning"] = a.conditioning;
    print_json(j);
  } else {
    for (const Warning& w : warnings)
      if (w.code != "reader") print_warnings({w});  // the reader's are printed as it reads
    fmt::print(
        "{} on {} along {} deg: {} x {} offsets, run-away distance {:.4g} m\n"
        "  dropped at ({:.4g}, {:.4g}) m, rests at ({:.4g}, {:.4g}) m\n"
        "  hold angle {:.4f} deg with the block free to move sideways (it steers {:.1f} deg off the direction), "
        "{:.4f} deg with it locked\n",
        a.upper.empty() ? a.lower : a.upper, a.lower, a.angle, lift.n_along, lift.n_across, ho.runaway_distance,
        dropped[0], dropped[1], rest[0], rest[1], to_deg(free.hold_angle), to_deg(free.steering),
        to_deg(locked.hold_angle));
    fmt::print("  conditioning: {}\n", a.conditioning);
    if (dist)
      fmt::print(
          "  over {} drops ({}, {} basins): mean {:.4f} deg, std {:.4f}, 5/50/95 % {:.4f} / {:.4f} / {:.4f}, "
          "min {:.4f}, max {:.4f} deg\n",
          dist->drops, locked_mode ? "locked" : "free", dist->rest.size(), to_deg(dist->hold.mean),
          to_deg(dist->hold.std), to_deg(dist->hold.q05), to_deg(dist->hold.q50), to_deg(dist->hold.q95),
          to_deg(dist->hold.min), to_deg(dist->hold.max));
  }
  return 0;
}

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  app.add_option("lower", a->lower, "Lower block's map (X3P, Gwyddion text)")->required();
  app.add_option("upper", a->upper, "Upper block's map as measured (default: the lower map)");
  app.add_option("--angle", a->angle, "Sliding direction (deg from +x towards +y)");
  app.add_option("--step", a->step, "Offset step (m; default min(dx, dy))");
  app.add_option("--max-offset", a->offset_max, "Largest offset (m; default half the lower map along the direction)");
  add_atomic_friction_option(app, a->atomic_friction);
  app.add_option("--detrend", a->detrend, "Remove none, mean, plane or poly:N from both maps first (default plane)");
  add_conditioning_options(app, a->cond);
  app.add_option("--contact-slope", a->contact_slope, "lower (Eq. 3, default) or mean (of both faces)");
  app.add_flag("--in-place", a->in_place, "UPPER is the upper face already in place (not turned over)");
  app.add_option("-o,--output", a->output,
                 "Write offset_m,lift_m,theta_rad,contact_x_m,contact_y_m to this CSV (- for standard output)");
  app.add_option("--threads", a->threads, "Worker threads (0 = all cores)");
  app.add_option("--lateral", a->lateral,
                 "Hold angle of a block that may move sideways (free) or not (locked) over the 2D lift");
  // --runaway-distance: the tilt table's field (one description everywhere), here the hold angle's run-away.
  add_field_options(app, tilt_settings(), a->runaway_words, all_but(tilt_settings(), "runaway_distance"));
  app.add_option("--start-offset", a->start_offset,
                 "Drop the block at offset X,Y (m, in the lower map's frame; default: the distribution over drops "
                 "and the test from 0,0)");
  app.add_option("--min-offset", a->offset_min, "Smallest offset along the direction for the 2D lift (m; default 0)");
  app.add_option("--across-step", a->across_step, "Offset step across the direction (m; default --step)");
  app.add_option("--across-max", a->across_max,
                 "Offsets across the direction cover +-this (m; default a quarter of the lower map across it)");
  app.add_flag("--json", a->json, "Print one JSON object");
  add_input_options(app, a->input);
  return [a]() {
    if (const ValueSet rv = si_values(tilt_settings(), a->runaway_words); rv.count("runaway_distance"))
      a->runaway_distance = as_real(rv.at("runaway_distance"));
    require(std::isfinite(a->angle), fmt::format("--angle {}: expected a finite number of degrees", a->angle));
    require(a->step >= 0 && a->offset_max >= 0, "--step and --max-offset must be >= 0 (metres)");
    require(std::isfinite(a->atomic_friction) && a->atomic_friction >= 0,
            "--atomic-friction must be a finite number >= 0");
    const Conditioning cond = conditioning(a->cond, unwrap(parse_detrend(a->detrend)));
    std::vector<Warning> warnings;
    std::vector<ConditioningRecord> records;
    auto load = [&](const std::string& path) {
      return load_conditioned_map(path, a->input, cond, "the areal signature needs maps", &warnings, &records);
    };
    const Map f = load(a->lower);
    const Map g = a->upper.empty() ? f : load(a->upper);
    a->conditioning = conditioning_text(records);
    if (!a->lateral.empty() || a->runaway_distance != 0 || !a->start_offset.empty())
      return run_hold(*a, f, g, std::move(warnings));
    ArealSignatureOptions o;
    o.step = a->step;
    o.offset_max = a->offset_max;
    o.threads = a->threads;
    o.turn_over_upper = !a->in_place;
    if (a->contact_slope == "mean")
      o.contact_slope = ArealContactSlope::Mean;
    else if (a->contact_slope != "lower")
      throw UsageError(fmt::format("--contact-slope '{}' not understood (expected lower or mean)", a->contact_slope));
    const ArealSignature r = unwrap(areal_signature(f, g, a->angle * kDeg, o));
    const FrictionPrediction p = unwrap(predict_friction(a->atomic_friction, r.theta_max_forward, r.contact_slope_std));
    add_eq18_warning(warnings, p.low_clamped, "areal");
    if (!a->output.empty()) {
      std::string buf = "offset_m,lift_m,theta_rad,contact_x_m,contact_y_m\n";
      for (std::size_t k = 0; k < r.offset.size(); ++k)
        buf += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", r.offset[k], r.lift[k], r.theta[k],
                           r.contact_x[k], r.contact_y[k]);
      write_text_output(a->output, buf);
    }
    require(!(a->json && a->output == "-"), "--json and -o - would both write to standard output; choose one");
    if (a->json) {
      nlohmann::json j;
      j["lower"] = a->lower;
      j["upper"] = a->upper.empty() ? a->lower : a->upper;
      j["direction_deg"] = a->angle;
      j["offsets"] = r.offset.size();
      j["theta_max_forward_deg"] = to_deg(r.theta_max_forward);
      j["theta_max_backward_deg"] = to_deg(r.theta_max_backward);
      j["theta_max_lift_deg"] = to_deg(r.theta_max_lift);
      j["contact_slope_mean_deg"] = to_deg(r.contact_slope_mean);
      j["contact_slope_std_deg"] = to_deg(r.contact_slope_std);
      // theta_max-based: the rigid upper bound (the prediction of a tilt test is `frictal predict`).
      j["upper_bound_friction_angle_deg"] = to_deg(p.friction_angle);
      j["upper_bound_friction_coefficient"] = p.friction_coefficient;
      j["eq18_low_friction_coefficient"] = p.friction_coefficient_low;
      j["evaluated_nodes"] = r.evaluated_nodes;
      j["conditioning"] = a->conditioning;
      j["warnings"] = warnings_json(warnings);
      print_json(j);
    } else {
      fmt::print(
          a->output == "-" ? stderr : stdout,
          "{} on {} along {} deg: {} offsets\n  theta_max forward {:.4f} deg, backward {:.4f} deg, sigma {:.4f} deg\n"
          "  rigid upper bound theta_max + theta_a {:.4f} deg, mu <= {:.5f} (Eq. 18 low {:.5f}); what a tilt test "
          "reads: frictal predict\n  conditioning: {}\n",
          a->upper.empty() ? a->lower : a->upper, a->lower, a->angle, r.offset.size(), to_deg(r.theta_max_forward),
          to_deg(r.theta_max_backward), to_deg(r.contact_slope_std), to_deg(p.friction_angle), p.friction_coefficient,
          p.friction_coefficient_low, a->conditioning);
      for (const Warning& w : warnings)
        if (w.code != "reader") print_warnings({w});  // the reader's are printed as it reads
    }
    return 0;
  };
}

FRICTAL_COMMAND({"areal", "Areal signature of two rigid blocks (maps) sliding along a direction", setup, 75});

}  // namespace
}  // namespace frictal::cli
