// frictal — quantities users compare a measured scan against other tools with: physical sizes
// in the pixel convention (n dx), the bandwidth, the short reliability cutoff for a tip radius,
// per-profile Rq/Rdq of a map along x and y, and the rms gradient on the common forward-
// difference grid. Definitions and sources: docs/analysis.md ("Scan quantities").
#pragma once

#include "frictal/geometry.hpp"
#include "frictal/map.hpp"
#include "frictal/result.hpp"

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

/// Short reliability cutoff for a tip of radius `tip_radius` (unit: m): the smallest stencil
/// distance h (unit: m) at which the scale-dependent curvature
///   kappa_h(x) = (z(x + h) - 2 z(x) + z(x - h)) / h^2
/// stays at or below 1 / tip_radius everywhere (a sphere of radius R reaches the bottom of a
/// valley only if the valley's curvature is at most 1/R). Below it the tip cannot follow the
/// surface and finer-scale slopes (theta_max) are not to be trusted. Evaluated at h = k dx,
/// k = 1 .. n/4, linearly interpolated in h between the last failing and the first passing k.
/// 0: reliable down to the sampling interval; NaN: unreliable up to a quarter of the scan.
/// Maps: along rows (dx) and columns (dy); the larger cutoff. Profiles: h = k x mean spacing,
/// the curvature of each triple i - k, i, i + k from its actual abscissae
/// (2 [(zc - zb)/(xc - xb) - (zb - za)/(xb - xa)] / (xc - xa), the same on a uniform grid).
Result<double> short_reliability_cutoff(const Profile& p, double tip_radius);
Result<double> short_reliability_cutoff(const Map& m, double tip_radius);

}  // namespace frictal
