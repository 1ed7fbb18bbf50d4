// The output tables of the 3D tilt run (frictal/outputs.hpp): the run with the predictions matched
// to it (`frictal areal-tilt --json`; Python areal_tilt's dict, the same keys without their unit
// suffix, in SI), and one increment, the rows of its increment_trace, each [tilt, x, y, rested,
// steps, unbalanced force, speed].
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "frictal/areal_tilt.hpp"

namespace frictal {

namespace {

std::vector<double> pair(const std::array<double, 2>& v) { return {v[0], v[1]}; }

}  // namespace

const Columns<ArealTiltIncrement>& areal_tilt_increment_columns() {
  using T = ArealTiltIncrement;
  static const Columns<T> cols = {
      column<T>(
          "increment_tilt_deg", "deg", "the tilt at the increment's end", [](const T& i) { return i.tilt; }, "-"),
      column<T>(
          "x_m", "m", "the block's offset x", [](const T& i) { return i.x; }, "-"),
      column<T>(
          "y_m", "m", "the block's offset y", [](const T& i) { return i.y; }, "-"),
      column<T>(
          "rested", "flag", "the block came to rest (else it ran the run-away distance or waited out its relaxations)",
          [](const T& i) { return i.rested; }, "-"),
      column<T>(
          "steps", "count", "MuJoCo steps so far", [](const T& i) { return double(i.steps); }, "-"),
      column<T>(
          "unbalanced_force", "1", "the unbalanced force at the end, a fraction of the weight",
          [](const T& i) { return i.unbalanced_force; }, "-"),
      column<T>(
          "speed", "1", "the block's speed at the end (m per scaled s)", [](const T& i) { return i.speed; }, "-"),
  };
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
        column<T>("direction_deg", "deg", "tilt direction, from +x towards +y", [](const T& r) { return r.direction; }),
        column<T>("runaway_distance_m", "m", "run-away distance d",
                  [](const T& r) { return r.matched.runaway_distance; }),
        run("friction_angle_deg", true),
        run("ran_away", true),
        fixed_length(column<T>("rest_offset_m", "m", "where the block rested (x, y)",
                               [](const T& r) { return pair(r.matched.run.rest_offset); })),
        column<T>(
            "predicted_hold_angle_deg", "deg",
            "the prediction's model (frictal predict's: the spheres and triangles MuJoCo sees, off the grid) from "
            "the simulated rest, block free",
            [](const T& r) { return r.matched.free.hold_angle; }),
        column<T>("predicted_hold_angle_locked_deg", "deg", "the same, block locked to the direction (a diagnostic)",
                  [](const T& r) { return r.matched.locked.hold_angle; }),
        column<T>("predicted_steering_deg", "deg", "the same, block free: how far it turned off the direction",
                  [](const T& r) { return r.matched.free.steering; }),
        column<T>("continuous_runaway_increment_deg", "deg",
                  "the prediction in the simulated lateral mode: the tilt increment at which it ran away",
                  [](const T& r) { return r.matched.matched().runaway_increment; }),
        fixed_length(column<T>("continuous_rest_offset_m", "m",
                               "the prediction in the simulated lateral mode: where it rested (x, y)",
                               [](const T& r) { return pair(r.matched.matched().rest_offset); })),
        column<T>("continuous_evaluations", "count", "lift evaluations of the prediction in the simulated lateral mode",
                  [](const T& r) { return double(r.matched.matched().evaluations); }),
        fixed_length(column<T>("continuous_hold_angle_range_deg", "deg",
                               "[least, largest] hold angle with one slip's end moved by a sphere radius",
                               [](const T& r) {
                                 return std::vector<double>{r.matched.spread.low, r.matched.spread.high};
                               })),
        column<T>("continuous_slips", "count", "slips of the prediction in the simulated lateral mode",
                  [](const T& r) { return double(r.matched.spread.slips); }),
        column<T>("continuous_ambiguous_slips", "count", "slips whose end a sphere radius changes",
                  [](const T& r) { return double(r.matched.spread.ambiguous); }),
        only_if(column<T>("seat_tilt_deg", "deg", "the MuJoCo run's seat: its tilt",
                          [](const T& r) { return r.matched.seat_tilt; }),
                seated),
        only_if(fixed_length(column<T>("seat_offset_m", "m", "the seat's offset (x, y)",
                                       [](const T& r) { return pair(r.matched.seat_offset); })),
                seated),
        only_if(column<T>("continuous_seated_hold_angle_deg", "deg",
                          "the prediction's model dropped at the seat, at its tilt",
                          [](const T& r) { return r.matched.seated_hold_angle; }),
                seated),
        rows_column<T>("continuous_increments", "tilt_stop", "[tilt_deg, x_m, y_m] after each increment",
                       tilt_stop_columns(), [](const T& r) { return std::optional(r.matched.matched().stops); }),
        column<T>("sphere_radius_m", "m", "radius of the upper block's spheres",
                  [](const T& r) { return r.matched.run.sphere_radius; }),
        column<T>("collision", "text", "MuJoCo's collision: native or exact",
                  [](const T& r) { return std::string(r.exact_contacts ? "exact" : "native"); }),
        column<T>("lateral", "text", "free or locked",
                  [](const T& r) { return std::string(r.matched.run_locked ? "locked" : "free"); }),
        run("steering_deg", true),
        only_if(rows_column<T>("increment_trace", "areal_tilt_increment",
                               "[tilt_deg, x_m, y_m, rested, steps, unbalanced force / weight, speed] per increment",
                               areal_tilt_increment_columns(),
                               [](const T& r) { return std::optional(r.matched.run.trace); }),
                simulated),
        column<T>("tilt_step_deg", "deg", "the tilt increment", [](const T& r) { return r.tilt_step; }),
        run("spheres", false),
        run("steps", false),
        column<T>("max_contacts", "count", "most contacts at once",
                  [](const T& r) { return double(r.matched.run.max_contacts); }),
        run("unsettled_increments", false),
        column<T>("seconds", "s", "wall time", [](const T& r) { return r.seconds; }),
    };
    return c;
  }();
  return cols;
}

}  // namespace frictal
