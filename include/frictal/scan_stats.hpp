// frictal — quantities users compare a measured scan against other tools with: physical sizes
// in the pixel convention (n dx), the bandwidth, the short reliability cutoff for a tip radius,
// per-profile Rq/Rdq of a map along x and y, and the rms gradient on the common forward-
// difference grid. Definitions and sources: docs/analysis.md ("Scan quantities").
#pragma once

#include <optional>

#include "frictal/geometry.hpp"
#include "frictal/map.hpp"
#include "frictal/outputs.hpp"
#include "frictal/result.hpp"
#include "frictal/stats.hpp"

namespace frictal {

struct MapScanStats {
  double physical_size_x = 0;     ///< nx dx (unit: m)
  double physical_size_y = 0;     ///< ny dy (unit: m)
  double bandwidth_short = 0;     ///< (dx + dy) / 2, the sampling interval (unit: m)
  double bandwidth_long = 0;      ///< (nx dx + ny dy) / 2, the physical size (unit: m)
  double nyquist_wavelength = 0;  ///< 2 max(dx, dy): the shortest wavelength both axes resolve (unit: m)
  /// Per-profile statistics, pooled over every row (x) or column (y): Rq about each profile's
  /// own mean, Rdq from forward differences between valid neighbours.
  double Rq_x = 0, Rq_y = 0;    ///< (unit: m)
  double Rdq_x = 0, Rdq_y = 0;  ///< (unitless)
  /// sqrt(mean over nodes (i < nx-1, j < ny-1) of (dz/dx)^2 + (dz/dy)^2), both forward
  /// differences taken at the same node; nodes where any of the three points is invalid are
  /// skipped (unitless).
  double rms_gradient_fd = 0;
};
MapScanStats map_scan_stats(const Map& m);

struct ProfileScanStats {
  double sampling_interval = 0;   ///< mean spacing (x_max - x_min) / (n - 1) (unit: m)
  double physical_length = 0;     ///< n x sampling interval (unit: m)
  double bandwidth_short = 0;     ///< the sampling interval (unit: m)
  double bandwidth_long = 0;      ///< the physical length (unit: m)
  double nyquist_wavelength = 0;  ///< 2 x sampling interval (unit: m)
};
ProfileScanStats profile_scan_stats(const Profile& p);

/// Short reliability cutoff for a tip of radius `tip_radius` (unit: m), SurfaceTopography's
/// `scanning_probe_reliability_cutoff` (Sanner, Noehring, Thimons, Jacobs, Pastewka, Appl. Surf.
/// Sci. Adv. 7, 100190 (2022)): with the scale-dependent curvature
///   kappa_h(x) = (z(x + h) - 2 z(x) + z(x - h)) / h^2
/// (z between samples linearly interpolated), the stencil length 2h (unit: m) at which the most
/// negative kappa_h (the sharpest peak) equals -1 / (2 tip_radius), safety factor 1/2: a tip
/// images every peak with at least its own radius, so where the measured peaks are about as
/// curved as the tip the scan shows the tip, not the surface. Below it finer-scale slopes
/// (theta_max) are not to be trusted. Found by bisection (relative 1e-13) for h between the
/// sampling interval and a quarter of the physical length n dx. Returns 0 when the peaks are
/// blunter than that already at h = dx (reliable down to the sampling interval; SurfaceTopography:
/// None) and NaN when they are sharper even at h = n dx / 4 (unreliable at every scale;
/// SurfaceTopography: the physical size). Maps: along rows (dx) and along columns (dy), the larger
/// of the two (SurfaceTopography looks along x only).
Result<double> short_reliability_cutoff(const Profile& p, double tip_radius);
Result<double> short_reliability_cutoff(const Map& m, double tip_radius);

/// The scan quantities as output columns (frictal/outputs.hpp; src/analysis/analysis_columns.cpp).
const Columns<MapScanStats>& map_scan_stats_columns();
const Columns<ProfileScanStats>& profile_scan_stats_columns();

/// What the statistics of a surface add when asked (frictal stats --tip-radius, --acf,
/// --histograms; Python profile_stats and map_stats): each output only when it was computed.
struct StatsExtras {
  bool is_map = false;                           ///< the statistics are of a map, not a profile
  double tip_radius = 0;                         ///< the stylus tip radius given; 0: none (unit: m)
  double short_reliability_cutoff = 0;           ///< for tip_radius (unit: m; NaN: unreliable at every scale)
  std::optional<double> correlation_length;      ///< where the autocorrelation falls to 1/e (unit: m)
  std::optional<Histogram> height_distribution;  ///< edges in m, density per m
  std::optional<Histogram> slope_distribution;   ///< of the slope angles: edges in rad, density per rad
};
/// StatsExtras' output columns (src/analysis/analysis_columns.cpp).
const Columns<StatsExtras>& stats_extras_columns();

}  // namespace frictal
