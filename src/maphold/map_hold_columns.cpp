// The rows of numbers that the map model's outputs nest (frictal/outputs.hpp): points (x, y) and
// the block's stops [tilt, x, y].
#include "frictal/map_hold.hpp"

namespace frictal {

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

}  // namespace frictal
