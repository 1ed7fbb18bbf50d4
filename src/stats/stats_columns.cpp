// The output table of a profile's statistics (frictal/outputs.hpp): the keys of `frictal stats
// --json` for a profile and of Python's profile_stats() dict.
#include "frictal/stats.hpp"

namespace frictal {

const Columns<ProfileStats>& profile_stats_columns() {
  using T = ProfileStats;
  static const Columns<T> cols = {
      column<T>("points", "count", "points of the profile", [](const T& s) { return double(s.points); }),
      column<T>("length_m", "m", "x_max - x_min, (n - 1) dx", [](const T& s) { return s.length; }),
      column<T>("mean_height_m", "m", "mean height (1/L) int z dx", [](const T& s) { return s.mean_height; }),
      column<T>("rms_height_m", "m", "rms height about the mean (Rq), exact for the polyline",
                [](const T& s) { return s.rms_height; }),
      column<T>("rms_slope", "1", "rms slope sqrt((1/L) int z'^2 dx) (Rdq)", [](const T& s) { return s.rms_slope; }),
      column<T>("max_slope_deg", "deg", "steepest |atan z'| over the edges (90 at a jump)",
                [](const T& s) { return s.max_slope; }),
      column<T>("mean_slope_deg", "deg", "mean slope angle (1/L) int atan z' dx",
                [](const T& s) { return s.mean_slope; }),
  };
  return cols;
}

const Columns<Histogram>& histogram_columns() {
  using T = Histogram;
  static const Columns<T> cols = {
      column<T>("edges", "list", "bins + 1 edges", [](const T& h) { return h.edges; }),
      column<T>("density", "list", "density per unit of the edges", [](const T& h) { return h.density; }),
  };
  return cols;
}

}  // namespace frictal
