// frictal — profile statistics of the piecewise-linear profile (length-weighted integrals).
#pragma once

#include <vector>

#include "frictal/geometry.hpp"
#include "frictal/outputs.hpp"

namespace frictal {

struct ProfileStats {
  std::size_t points = 0;
  double length = 0;       ///< x_max - x_min (unit: m)
  double mean_height = 0;  ///< (1/L) int z dx (unit: m)
  double rms_height = 0;   ///< sqrt((1/L) int (z - mean)^2 dx), exact for the polyline (unit: m)
  double rms_slope = 0;    ///< sqrt((1/L) int z'^2 dx) over non-vertical edges (unitless)
  double max_slope = 0;    ///< max |atan z'| over edges, pi/2 at jumps (unit: rad)
  double mean_slope = 0;   ///< (1/L) int atan(z') dx (unit: rad)
};
ProfileStats profile_stats(const Profile& p);
/// profile_stats() without the slope angles: points, length, mean and rms height and rms slope
/// bit for bit profile_stats()'s, mean_slope and max_slope left 0; no atan per edge (what the
/// plausibility checks read, warnings.hpp).
ProfileStats profile_stats_no_angles(const Profile& p);
/// ProfileStats::max_slope alone: max |atan z'| over edges, pi/2 at jumps (unit: rad); one atan
/// in all (atan is monotone), where profile_stats() takes two a point.
double max_slope_angle(const Profile& p);

/// A histogram normalised as a probability density.
struct Histogram {
  std::vector<double> edges;    ///< bins + 1 bin edges (unit: that of the samples)
  std::vector<double> density;  ///< bins values; sum(density * width) = 1 (unit: 1/sample unit)
};
/// Weighted histogram of samples over [lo, hi] (auto range if lo >= hi); weights may be empty.
Histogram histogram(const std::vector<double>& samples, const std::vector<double>& weights, int bins, double lo = 0,
                    double hi = 0);

/// Length-weighted distribution of edge slope angles (unit: rad).
Histogram slope_distribution(const Profile& p, int bins = 90);

struct MeanStd {
  double mean = 0;
  double std = 0;  ///< population standard deviation
};
MeanStd weighted_mean_std(const std::vector<double>& samples, const std::vector<double>& weights);

/// A profile's statistics as output columns (frictal/outputs.hpp; src/stats/stats_columns.cpp):
/// `frictal stats --json` and Python's profile_stats().
const Columns<ProfileStats>& profile_stats_columns();
/// A histogram's columns (table "histogram"): its edges and density, in the samples' units.
const Columns<Histogram>& histogram_columns();

}  // namespace frictal
