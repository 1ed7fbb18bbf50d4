// The output table of one increment of the 3D tilt run (frictal/outputs.hpp): the rows of
// `frictal areal-tilt --json`'s increment_trace, each [tilt, x, y, rested, steps, unbalanced
// force, speed].
#include "frictal/areal_tilt.hpp"

namespace frictal {

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

}  // namespace frictal
