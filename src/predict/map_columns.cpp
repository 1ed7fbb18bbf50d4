// The output tables of the map prediction's views (frictal/outputs.hpp): the hold angle of a map
// pair along one direction as `frictal areal --lateral|--drops|--start-offset --json` names it,
// and the 3D tilt run with the predictions matched to it (`frictal areal-tilt --json`), with the
// rows of numbers they nest (points, stops).
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "frictal/predict.hpp"

namespace frictal {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<double> pair(const std::array<double, 2>& v) { return {v[0], v[1]}; }

}  // namespace

const Columns<std::array<double, 2>>& offset_xy_columns() {
  using T = std::array<double, 2>;
  static const Columns<T> cols = {
      column<T>(
          "x_m", "m", "x", [](const T& p) { return p[0]; }, "-"),
      column<T>(
          "y_m", "m", "y", [](const T& p) { return p[1]; }, "-"),
  };
  return cols;
}

const Columns<std::array<double, 3>>& tilt_stop_columns() {
  using T = std::array<double, 3>;
  static const Columns<T> cols = {
      column<T>(
          "stop_tilt_deg", "deg", "the tilt at the increment's end", [](const T& s) { return s[0]; }, "-"),
      column<T>(
          "x_m", "m", "the block's offset x", [](const T& s) { return s[1]; }, "-"),
      column<T>(
          "y_m", "m", "the block's offset y", [](const T& s) { return s[2]; }, "-"),
  };
  return cols;
}

const Columns<ArealHoldReport>& areal_hold_columns() {
  using T = ArealHoldReport;
  auto single = [](const T& r) { return r.prediction.single_drop; };
  auto over_drops = [](const T& r) { return !r.prediction.single_drop; };
  // The hold angle in the lateral mode predicted: the locked block's with has_locked.
  auto chosen = [](const T& r) -> const HoldStatistics& {
    return r.prediction.has_locked ? r.prediction.locked_friction_angle : r.prediction.friction_angle;
  };
  static const Columns<T> cols = [&] {
    Columns<T> c = {
        column<T>(
            "direction_deg", "deg", "sliding direction, from +x towards +y",
            [](const T& r) { return r.prediction.direction; }, "direction"),
        column<T>(
            "lateral", "text", "free (the block may move sideways) or locked to the direction",
            [](const T& r) { return std::string(r.prediction.has_locked ? "locked" : "free"); }, "lateral"),
        column<T>(
            "model", "text", "map-continuous-free or map-continuous-locked (frictal predict's model)",
            [](const T& r) {
              return r.prediction.has_locked ? std::string("map-continuous-locked") : r.prediction.model;
            },
            "model"),
        column<T>(
            "in_place", "flag", "the upper map is the upper face in place (not turned over)",
            [](const T& r) { return r.in_place; }, "in_place"),
        column<T>(
            "atomic_friction", "1", "mu_a, included in every hold angle as atan(mu_a)",
            [](const T& r) { return r.prediction.atomic_friction; }, "atomic_friction"),
        column<T>(
            "runaway_distance_m", "m", "run-away distance d", [](const T& r) { return r.prediction.runaway_distance; },
            "runaway_distance"),
        column<T>(
            "drops", "count", "drops the distribution is over", [](const T& r) { return double(r.prediction.drops); },
            "drops"),
        column<T>(
            "drop_range_m", "m",
            "[u_min, u_max, v_min, v_max] along/across the direction (the spheres r + D inside the lower map)",
            [](const T& r) {
              return std::vector<double>(r.prediction.drop_range.begin(), r.prediction.drop_range.end());
            },
            "drop_range"),
        only_if(column<T>(
                    "start_offset_m", "m", "one drop: where it was put down (x, y)",
                    [](const T& r) { return pair(r.prediction.start_offset); }, "start_offset"),
                single),
        only_if(column<T>(
                    "rest_offset_m", "m", "one drop: where it rested (x, y)",
                    [](const T& r) { return pair(r.prediction.rest_offset); }, "rest_offset"),
                single),
        only_if(column<T>(
                    "hold_angle_deg", "deg", "one drop: its hold angle (the lateral mode's)",
                    [chosen](const T& r) { return chosen(r).q50; }, "hold_angle"),
                single),
        only_if(column<T>(
                    "hold_angle_free_deg", "deg", "one drop, locked: the free block's hold angle",
                    [](const T& r) { return r.prediction.friction_angle.q50; }, "-"),
                [](const T& r) { return r.prediction.single_drop && r.prediction.has_locked; }),
        only_if(column<T>(
                    "steering_deg", "deg", "one drop: the direction the free block ran away in",
                    [](const T& r) {
                      return r.prediction.drop_steering.empty() ? kNaN : r.prediction.drop_steering.front();
                    },
                    "steering"),
                single),
    };
    // Over drops: the hold angle's statistics in the lateral mode predicted,
    // hold_angle_<statistic>_deg, and locked the free block's quantiles, hold_angle_free_<q>_deg.
    for (const Column<HoldStatistics>& s : hold_statistics_columns())
      c.push_back(only_if(column<T>(
                              "hold_angle_" + s.key, s.unit, "hold angle over drops: " + s.help,
                              [si = s.si, chosen](const T& r) { return si(chosen(r)); },
                              "hold_angle_" + default_python_key(s.key, s.unit)),
                          over_drops));
    for (const Column<HoldStatistics>& s : hold_statistics_columns())
      if (s.key.starts_with("q"))
        c.push_back(
            only_if(column<T>(
                        "hold_angle_free_" + s.key, s.unit, "locked mode: the free block's hold angle, " + s.help,
                        [si = s.si](const T& r) { return si(r.prediction.friction_angle); }, "-"),
                    [](const T& r) { return !r.prediction.single_drop && r.prediction.has_locked; }));
    c.push_back(only_if(column<T>(
                            "drop_hold_angles_deg", "deg", "each drop's hold angle (the lateral mode's), in drop order",
                            [](const T& r) {
                              return r.prediction.has_locked ? r.prediction.drop_angles_locked
                                                             : r.prediction.drop_angles;
                            },
                            "drop_hold_angles"),
                        over_drops));
    c.push_back(only_if(rows_column<T>(
                            "drop_offsets_m", "offset_xy", "each drop's (x, y)", offset_xy_columns(),
                            [](const T& r) { return std::optional(r.prediction.drop_offsets); }, "drop_offsets"),
                        over_drops));
    c.push_back(column<T>(
        "upper_bound_friction_angle_deg", "deg", "rigid upper bound theta_max + theta_a (Eq. 6)",
        [](const T& r) { return r.prediction.upper_bound_friction_angle; }, "upper_bound_friction_angle"));
    return c;
  }();
  return cols;
}

const Columns<ArealTiltReport>& areal_tilt_report_columns() {
  using T = ArealTiltReport;
  auto simulated = [](const T& r) { return r.matched.simulated; };
  auto seated = [](const T& r) { return r.matched.seated; };
  // A column of the run (areal_tilt_run_columns); `only_simulated`: written only when the run was
  // made (else the run's numbers are zero: no spheres, no steps).
  auto run = [simulated](const std::string& key, bool only_simulated) {
    for (const Column<ArealTiltResult>& c : areal_tilt_run_columns())
      if (c.key == key) {
        Column<T> out;
        static_cast<ColumnInfo&>(out) = c;
        out.si = [si = c.si](const T& r) { return si(r.matched.run); };
        if (only_simulated) out.present = simulated;
        return out;
      }
    Column<T> undeclared;  // the key test names it
    undeclared.key = key;
    undeclared.unit = "undeclared";
    return undeclared;
  };
  static const Columns<T> cols = [&] {
    Columns<T> c = {
        column<T>(
            "direction_deg", "deg", "tilt direction, from +x towards +y", [](const T& r) { return r.direction; }, "-"),
        column<T>(
            "runaway_distance_m", "m", "run-away distance d", [](const T& r) { return r.matched.runaway_distance; },
            "-"),
        run("friction_angle_deg", true),
        run("ran_away", true),
        column<T>(
            "rest_offset_m", "m", "where the block rested (x, y)",
            [](const T& r) { return pair(r.matched.run.rest_offset); }, "-"),
        column<T>(
            "predicted_hold_angle_deg", "deg",
            "the prediction's model (frictal predict's: the spheres and triangles MuJoCo sees, off the grid) from "
            "the simulated rest, block free",
            [](const T& r) { return r.matched.free.hold_angle; }, "-"),
        column<T>(
            "predicted_hold_angle_locked_deg", "deg", "the same, block locked to the direction (a diagnostic)",
            [](const T& r) { return r.matched.locked.hold_angle; }, "-"),
        column<T>(
            "predicted_steering_deg", "deg", "the same, block free: how far it turned off the direction",
            [](const T& r) { return r.matched.free.steering; }, "-"),
        column<T>(
            "continuous_runaway_increment_deg", "deg",
            "the prediction in the simulated lateral mode: the tilt increment at which it ran away",
            [](const T& r) { return r.matched.matched().runaway_increment; }, "-"),
        column<T>(
            "continuous_rest_offset_m", "m", "the prediction in the simulated lateral mode: where it rested (x, y)",
            [](const T& r) { return pair(r.matched.matched().rest_offset); }, "-"),
        column<T>(
            "continuous_evaluations", "count", "lift evaluations of the prediction in the simulated lateral mode",
            [](const T& r) { return double(r.matched.matched().evaluations); }, "-"),
        column<T>(
            "continuous_hold_angle_range_deg", "deg",
            "[least, largest] hold angle with one slip's end moved by a sphere radius",
            [](const T& r) {
              return std::vector<double>{r.matched.spread.low, r.matched.spread.high};
            },
            "-"),
        column<T>(
            "continuous_slips", "count", "slips of the prediction in the simulated lateral mode",
            [](const T& r) { return double(r.matched.spread.slips); }, "-"),
        column<T>(
            "continuous_ambiguous_slips", "count", "slips whose end a sphere radius changes",
            [](const T& r) { return double(r.matched.spread.ambiguous); }, "-"),
        only_if(column<T>(
                    "seat_tilt_deg", "deg", "the MuJoCo run's seat: its tilt",
                    [](const T& r) { return r.matched.seat_tilt; }, "seat_tilt"),
                seated),
        only_if(column<T>(
                    "seat_offset_m", "m", "the seat's offset (x, y)",
                    [](const T& r) { return pair(r.matched.seat_offset); }, "seat_offset"),
                seated),
        only_if(
            column<T>(
                "continuous_seated_hold_angle_deg", "deg", "the prediction's model dropped at the seat, at its tilt",
                [](const T& r) { return r.matched.seated_hold_angle; }, "seated_hold_angle"),
            seated),
        rows_column<T>(
            "continuous_increments", "tilt_stop", "[tilt_deg, x_m, y_m] after each increment", tilt_stop_columns(),
            [](const T& r) { return std::optional(r.matched.matched().stops); }, "-"),
        column<T>(
            "sphere_radius_m", "m", "radius of the upper block's spheres",
            [](const T& r) { return r.matched.run.sphere_radius; }, "sphere_radius"),
        column<T>(
            "collision", "text", "MuJoCo's collision: native or exact",
            [](const T& r) { return std::string(r.exact_contacts ? "exact" : "native"); }, "-"),
        column<T>(
            "lateral", "text", "free or locked",
            [](const T& r) { return std::string(r.matched.run_locked ? "locked" : "free"); }, "-"),
        run("steering_deg", true),
        only_if(rows_column<T>(
                    "increment_trace", "areal_tilt_increment",
                    "[tilt_deg, x_m, y_m, rested, steps, unbalanced force / weight, speed] per increment",
                    areal_tilt_increment_columns(), [](const T& r) { return std::optional(r.matched.run.trace); }, "-"),
                simulated),
        column<T>(
            "tilt_step_deg", "deg", "the tilt increment", [](const T& r) { return r.tilt_step; }, "-"),
        run("spheres", false),
        run("steps", false),
        column<T>(
            "max_contacts", "count", "most contacts at once",
            [](const T& r) { return double(r.matched.run.max_contacts); }, "-"),
        run("unsettled_increments", false),
        column<T>(
            "seconds", "s", "wall time", [](const T& r) { return r.seconds; }, "-"),
    };
    return c;
  }();
  return cols;
}

}  // namespace frictal
