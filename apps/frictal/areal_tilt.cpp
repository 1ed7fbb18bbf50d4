// frictal areal-tilt LOWER [UPPER] — the 3D tilt test of two areal blocks on MuJoCo
// (experimental, docs/mujoco.md), beside the free-lateral and locked hold angles predicted on the
// lift over two dimensions of offset from the rest offset that the simulation reached.
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>

#include "common.hpp"
#include "frictal/analysis.hpp"
#include "frictal/areal.hpp"
#include "frictal/areal_tilt.hpp"
#include "frictal/tilt.hpp"
#include "options.hpp"
#include "surface_io.hpp"

namespace frictal::cli {
namespace {

struct Args {
  std::string lower, upper;
  int prediction_refine = 0;
  std::string detrend = "plane";
  bool in_place = false;
  bool predict_only = false;
  std::string start_offset;
  FieldWords words;  ///< the model's and protocol's settings (areal_tilt_settings(); docs/settings.md)
  bool json = false;
  bool quiet = false;
  InputOptions input;
  ConditioningOptions cond;
};

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  app.add_option("lower", a->lower, "Lower block's map (X3P, Gwyddion text)")->required();
  app.add_option("upper", a->upper, "Upper block's map as measured (default: the lower map)");
  add_field_options(app, areal_tilt_settings(), a->words);
  app.add_option("--prediction-refine", a->prediction_refine,
                 "Offset grid of the matched prediction this many times finer than the lower map's (default 0: "
                 "the smallest with a step <= r / 2, at most 16 and at most 2e5 offsets)");
  app.add_option("--detrend", a->detrend, "Remove none, mean, plane or poly:N from both maps first (default plane)");
  add_conditioning_options(app, a->cond);
  app.add_option("--start-offset", a->start_offset,
                 "X,Y: where the block is put down, in the lower map's frame (m; default 0,0)");
  app.add_flag("--predict-only", a->predict_only,
               "Only the predictions, from the block dropped at offset 0 (no simulation; needs no MuJoCo)");
  app.add_flag("--in-place", a->in_place, "UPPER is the upper face already in place (not turned over)");
  app.add_flag("--json", a->json, "Print one JSON object");
  app.add_flag("-q,--quiet", a->quiet, "No progress line on standard error (shown on a terminal only)");
  add_input_options(app, a->input);
  return [a]() {
    auto made = make_areal_tilt_options(si_values(areal_tilt_settings(), a->words));
    if (!made) fail(made.error());
    ArealTiltOptions o = *made;
    require(a->prediction_refine >= 0 && a->prediction_refine <= 16,
            fmt::format("--prediction-refine {}: expected an integer in 0..16 (0: automatic)", a->prediction_refine));
    if (!mujoco_available() && !a->predict_only) unwrap(areal_tilt(Map{}, Map{}, {}));  // says what it needs (exit 2)
    const Conditioning cond = conditioning(a->cond, unwrap(parse_detrend(a->detrend)));
    std::vector<ConditioningRecord> records;
    auto load = [&](const std::string& path) {
      return load_conditioned_map(path, a->input, cond, "areal-tilt needs maps", nullptr, &records);
    };
    const Map f = load(a->lower);
    const Map g = a->upper.empty() ? f : load(a->upper);
    const std::string conditioning_done = conditioning_text(records);
    if (!a->start_offset.empty()) o.start_offset = parse_offset(a->start_offset, "--start-offset");
    o.turn_over_upper = !a->in_place;
    const double angle_deg = to_deg(o.angle), tilt_step_deg = to_deg(o.tilt_step);
    const bool sim_locked = o.lock_lateral;
    const auto t0 = std::chrono::steady_clock::now();
    ArealTiltResult r;
    if (a->predict_only) {
      r.rest_offset = o.start_offset;
      r.sphere_radius = o.sphere_radius > 0 ? o.sphere_radius : 0.2 * std::min(f.dx, f.dy);
    } else {
      // A progress line (a terminal only): the simulation takes minutes on large maps.
      ArealTiltProgress progress;
      if (!a->quiet && ::isatty(2))
        progress = [&](const ArealTiltIncrement& i) {
          const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          fmt::print(stderr, "\rfrictal areal-tilt: tilt {:.2f} deg, block at ({:.4g}, {:.4g}) m, {} ({:.0f} s)   ",
                     to_deg(i.tilt), i.x, i.y, i.rested ? "at rest" : "moving", secs);
          std::fflush(stderr);
        };
      r = unwrap(areal_tilt(f, g, o, progress));
      if (progress) fmt::print(stderr, "\n");
    }
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // The predictions from the rest offset the simulation reached, on the rigid lift (r = 0).
    const double c = std::cos(o.angle), s = std::sin(o.angle);
    const double D =
        o.runaway_distance > 0 ? o.runaway_distance : 0.05 * (std::abs(c) * f.width() + std::abs(s) * f.height());
    const double u = r.rest_offset[0] * c + r.rest_offset[1] * s, v = -r.rest_offset[0] * s + r.rest_offset[1] * c;
    ArealLiftOptions lo;
    lo.turn_over_upper = o.turn_over_upper;
    // Offsets on the lower map's lattice when d runs along x or y (the grid's diagonal moves then
    // follow the map's diagonals; docs/analysis.md, what the grid can and cannot do).
    const bool along_x = std::abs(s) < 1e-12, along_y = std::abs(c) < 1e-12;
    lo.step = along_x ? f.dx : along_y ? f.dy : std::min(f.dx, f.dy);
    lo.across_step = along_x ? f.dy : along_y ? f.dx : lo.step;
    lo.offset_min = u - 2 * D;
    lo.offset_max = u + 4 * D;
    lo.across_max = std::abs(v) + 3 * D;
    lo.threads = 0;
    ArealLift lift = unwrap(areal_lift(f, g, o.angle, lo));
    ArealHoldOptions ho;
    ho.runaway_distance = D;
    ho.atomic_friction = o.atomic_friction;
    const std::size_t rest = unwrap(areal_lift_node(lift, r.rest_offset[0], r.rest_offset[1]));
    const ArealHold free = unwrap(areal_hold_angle(lift, rest, ho));
    // Locked: on the line through the free block's rest (as `frictal areal`), or, when the
    // simulated block was locked, locked from its own rest on.
    ArealHoldOptions hl = ho;
    hl.lateral = LateralMotion::Locked;
    const double locked = sim_locked ? unwrap(areal_hold_angle(lift, rest, hl)).hold_angle
                                     : unwrap(areal_locked_hold_angle(lift, free.rest, ho)).hold_angle;
    // The matched prediction: the same spheres on the same triangulated height field as MuJoCo
    // (areal_tilt_lift), on an offset grid prediction_refine times finer.
    // The lift varies on the scale of r between the map's nodes (a valley across the cells'
    // diagonals is a chain of bumps): the grid's chords must resolve it (docs/mujoco.md).
    // Automatic: at most 2e5 offsets (the grid is a cross-check; areal_tilt_hold is off the grid).
    int refine = a->prediction_refine;
    if (refine == 0) {
      refine = std::clamp(int(std::ceil(2 * lo.step / r.sphere_radius - 1e-9)), 1, 16);
      auto offsets = [&](int k) {
        return ((lo.offset_max - lo.offset_min) / lo.step * k + 1) * (2 * lo.across_max / lo.across_step * k + 1);
      };
      while (refine > 1 && offsets(refine) > 2e5) --refine;
    }
    ArealLiftOptions mo = lo;
    mo.step /= refine;
    mo.across_step /= refine;
    const ArealLift mlift = unwrap(areal_tilt_lift(f, g, o, mo));
    const std::size_t mrest = unwrap(areal_lift_node(mlift, r.rest_offset[0], r.rest_offset[1]));
    const ArealHold mfree = unwrap(areal_hold_angle(mlift, mrest, ho));
    // The same rigid block off the grid (areal_tilt_hold), in the simulated lateral mode.
    ArealTiltOptions co = o;
    co.start_offset = r.rest_offset;  // from the simulated rest: the same basin
    co.runaway_distance = D;
    const ArealTiltHold cont = unwrap(areal_tilt_hold(f, g, co));
    // Its conditioning: the slips' ends moved by one sphere radius (areal_tilt_hold_spread).
    const ArealTiltHoldSpread spread = unwrap(areal_tilt_hold_spread(f, g, co, cont));
    const double mlocked = sim_locked ? unwrap(areal_hold_angle(mlift, mrest, hl)).hold_angle
                                      : unwrap(areal_locked_hold_angle(mlift, mfree.rest, ho)).hold_angle;
    for (const auto& w : r.warnings)
      if (!a->json) fmt::print(stderr, "frictal: warning [{}]: {}\n", w[0], w[1]);
    if (a->json) {
      nlohmann::json j;
      j["warnings"] = nlohmann::json::array();
      for (const auto& w : r.warnings) j["warnings"].push_back({{"code", w[0]}, {"message", w[1]}});
      j["lower"] = a->lower;
      j["upper"] = a->upper.empty() ? a->lower : a->upper;
      j["direction_deg"] = angle_deg;
      j["runaway_distance_m"] = D;
      if (!a->predict_only) {
        j["friction_angle_deg"] = to_deg(r.friction_angle);
        j["ran_away"] = r.ran_away;
      }
      j["rest_offset_m"] = {r.rest_offset[0], r.rest_offset[1]};
      j["predicted_hold_angle_deg"] = to_deg(free.hold_angle);
      j["predicted_hold_angle_locked_deg"] = to_deg(locked);
      j["continuous_hold_angle_deg"] = to_deg(cont.hold_angle);
      j["continuous_runaway_increment_deg"] = to_deg(cont.runaway_increment);
      j["continuous_steering_deg"] = to_deg(cont.steering);
      j["continuous_rest_offset_m"] = {cont.rest_offset[0], cont.rest_offset[1]};
      j["continuous_evaluations"] = cont.evaluations;
      j["continuous_hold_angle_range_deg"] = {to_deg(spread.low), to_deg(spread.high)};
      j["continuous_slips"] = spread.slips;
      j["continuous_ambiguous_slips"] = spread.ambiguous;
      if (!a->predict_only) {  // the rigid block from the simulated block's last seat, at its tilt
        if (auto seat = areal_tilt_last_seat(r)) {
          ArealTiltOptions so = co;
          so.start_offset = {(*seat)[1], (*seat)[2]};
          so.coarse_tilt_step = o.tilt_step;
          const ArealTiltHold seated = unwrap(areal_tilt_hold(f, g, so, 1e-4, 1e-7, (*seat)[0]));
          j["seat_tilt_deg"] = to_deg((*seat)[0]);
          j["seat_offset_m"] = {(*seat)[1], (*seat)[2]};
          j["continuous_seated_hold_angle_deg"] = to_deg(seated.hold_angle);
        }
      }
      nlohmann::json cs = nlohmann::json::array();
      for (const auto& st : cont.stops) cs.push_back({to_deg(st[0]), st[1], st[2]});
      j["continuous_increments"] = cs;  // [tilt_deg, x_m, y_m] after each increment
      j["matched_hold_angle_deg"] = to_deg(mfree.hold_angle);
      j["matched_hold_angle_locked_deg"] = to_deg(mlocked);
      j["matched_steering_deg"] = to_deg(mfree.steering);
      j["sphere_radius_m"] = r.sphere_radius;
      j["collision"] = o.exact_contacts ? "exact" : "native";
      j["lateral"] = o.lock_lateral ? "locked" : "free";
      j["prediction_refine"] = refine;
      j["matched_steering_deg"] = to_deg(mfree.steering);
      j["predicted_steering_deg"] = to_deg(free.steering);
      if (!a->predict_only) {
        j["steering_deg"] = to_deg(r.steering);
        nlohmann::json tr = nlohmann::json::array();
        for (const ArealTiltIncrement& i : r.trace)
          tr.push_back({to_deg(i.tilt), i.x, i.y, i.rested, i.steps, i.unbalanced_force, i.speed});
        j["increment_trace"] = tr;  // [tilt_deg, x_m, y_m, rested, steps, unbalanced force / weight, speed]
      }
      j["tilt_step_deg"] = tilt_step_deg;
      j["spheres"] = r.spheres;
      j["steps"] = r.steps;
      j["max_contacts"] = r.max_contacts;
      j["unsettled_increments"] = r.unsettled;
      j["seconds"] = secs;
      j["conditioning"] = conditioning_done;
      print_json(j);
    } else {
      if (a->predict_only)
        fmt::print("{} on {} along {} deg, dropped at offset 0 (no simulation)\n",
                   a->upper.empty() ? a->lower : a->upper, a->lower, angle_deg);
      else
        fmt::print(
            "{} on {} along {} deg (MuJoCo, {} spheres): rests at ({:.4g}, {:.4g}) m, runs away at {:.2f} deg "
            "(steps of {} deg)\n",
            a->upper.empty() ? a->lower : a->upper, a->lower, angle_deg, r.spheres, r.rest_offset[0], r.rest_offset[1],
            to_deg(r.friction_angle), tilt_step_deg);
      fmt::print(
          "  predicted hold angle {:.3f} deg free to move sideways, {:.3f} deg locked\n"
          "  matched (the simulated spheres on the triangulated height field, rigid) {:.3f} deg free, {:.3f} "
          "deg locked\n",
          to_deg(free.hold_angle), to_deg(locked), to_deg(mfree.hold_angle), to_deg(mlocked));
      fmt::print(
          "  matched off the grid, {}: {:.3f} deg; {:.3f} to {:.3f} deg when one slip's end moves by a sphere "
          "radius ({} of {} slips could end in another seat)\n",
          o.lock_lateral ? "locked" : "free", to_deg(cont.hold_angle), to_deg(spread.low), to_deg(spread.high),
          spread.ambiguous, spread.slips);
      fmt::print("  conditioning: {}\n", conditioning_done);
    }
    return 0;
  };
}

FRICTAL_COMMAND({"areal-tilt", "3D tilt test of two areal blocks on MuJoCo (experimental)", setup, 76});

}  // namespace
}  // namespace frictal::cli
