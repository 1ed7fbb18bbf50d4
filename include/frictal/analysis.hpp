// frictal — analysis of measured surfaces: detrending, spectra, autocorrelation, distributions,
// areal (ISO 25178-2 style) statistics and line profiles of maps. Definitions: docs/analysis.md.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "frictal/geometry.hpp"
#include "frictal/map.hpp"
#include "frictal/outputs.hpp"
#include "frictal/stats.hpp"

namespace frictal {

enum class DetrendKind { None, Mean, Line, Polynomial };
struct Detrend {
  DetrendKind kind = DetrendKind::None;
  int degree = 0;  ///< for Polynomial: 0..10 (unitless)
};
/// Parses "none", "mean", "line" (or "plane"), "poly:N".
Result<Detrend> parse_detrend(const std::string& text);

/// Subtracts the least-squares polynomial of the profile, weighted by the trapezoid rule
/// (each point weighs half its two neighbouring intervals), i.e. the L2 fit of the
/// piecewise-linear profile's samples. Mean = degree 0, Line = degree 1.
Result<Profile> detrend(const Profile& p, const Detrend& d);
/// The same, in the storage of `p` (no copy of a profile that is not needed afterwards: 160 MB
/// at 10^7 points).
Result<Profile> detrend(Profile&& p, const Detrend& d);
/// Subtracts the least-squares polynomial in (x, y) of total degree <= N over the valid points
/// (equal weights). Mean = 0, Line = plane (1).
Result<Map> detrend(const Map& m, const Detrend& d);

/// Power spectral density of the piecewise-linear profile (mean removed):
///   C(q_k) = |int_{x0}^{x0+L} (z(x) - mean) exp(-i q_k x) dx|^2 / L,  q_k = 2 pi k / L, k >= 1,
/// evaluated exactly segment by segment (FFT for uniform spacing, direct sums otherwise).
/// With this normalisation 2 sum_{k>=1} C(q_k) / L = rms height^2.
struct Spectrum {
  std::vector<double> q;    ///< angular wavenumbers (unit: rad/m)
  std::vector<double> psd;  ///< C(q) (unit: m^3)
};
/// max_k: largest k (0 = half the number of points, the Nyquist wavenumber of the mean spacing;
/// for non-uniform profiles at most 4096 and at most 5e8 / points). Non-uniform profiles with
/// max_k * points above 2e9 are refused (resample first).
Result<Spectrum> power_spectrum(const Profile& p, std::size_t max_k = 0);

/// Normalised autocorrelation R(tau)/R(0) of the mean-removed profile at lags tau_k = k h,
/// k = 0..max_lag, R(tau) = mean over overlapping samples of z(x) z(x + tau). Uniform profiles
/// are used as sampled; non-uniform ones are first resampled linearly with the mean spacing h.
struct Autocorrelation {
  std::vector<double> lag;        ///< (unit: m)
  std::vector<double> acf;        ///< (unitless, acf[0] = 1)
  double correlation_length = 0;  ///< first lag where acf drops below 1/e; 0 if never (unit: m)
};
Result<Autocorrelation> autocorrelation(const Profile& p, std::size_t max_lag = 0);

/// The slope correlation length of a profile (unit: m): the lag at which the autocorrelation of
/// its slope (averaged over cells of an eighth of the mean spacing, at most 2^20 cells; mean
/// removed) first falls below 1/e, interpolated linearly. A local statistic: for a stationary
/// surface it does not grow with the scan (unlike the heights' correlation length, which on a
/// self-affine scan is a fixed fraction of it). 0 for a flat profile or slopes correlated over
/// half the scan.
double slope_correlation_length(const Profile& p);

/// Height distribution: trapezoid-weighted histogram of heights (unit: 1/m over m).
Histogram height_distribution(const Profile& p, int bins = 64);

/// Areal statistics over the valid (non-NaN) points of a map, about their mean:
///   Sa = mean |z - m|, Sq = sqrt(mean (z - m)^2), Sp = max(z) - m, Sv = m - min(z), Sz = Sp + Sv,
///   Ssk = mean (z - m)^3 / Sq^3, Sku = mean (z - m)^4 / Sq^4,
///   Sdq = sqrt(<(dz/dx)^2> + <(dz/dy)^2>) with forward differences between valid neighbours,
///   max_slope = max over valid neighbour pairs of |difference| / spacing (as an angle).
struct MapStats {
  std::size_t points = 0;                                   ///< nx * ny
  std::size_t valid = 0;                                    ///< non-NaN points
  double width = 0;                                         ///< (nx - 1) dx (unit: m)
  double height = 0;                                        ///< (ny - 1) dy (unit: m)
  double mean = 0, Sa = 0, Sq = 0, Sp = 0, Sv = 0, Sz = 0;  ///< (unit: m)
  double Ssk = 0, Sku = 0;                                  ///< (unitless)
  double Sdq = 0;                                           ///< (unitless)
  double max_slope = 0;                                     ///< (unit: rad)
};
MapStats map_stats(const Map& m);

/// The line profile of a map through (x, y) along direction `angle` (from +x towards +y),
/// sampled every `step` (0 = min(dx, dy)) by bilinear interpolation, over the whole chord of
/// the grid rectangle. Abscissa = distance along the line from the chord's start. Points where
/// the interpolation touches an invalid node split the line: every valid run of >= min_points
/// points is returned.
std::vector<Profile> map_line(const Map& m, double x, double y, double angle, double step = 0,
                              std::size_t min_points = 8);
/// All lines parallel to `angle`, `spacing` apart (0 = min(dx, dy)), covering the map.
std::vector<Profile> map_lines(const Map& m, double angle, double spacing = 0, double step = 0,
                               std::size_t min_points = 8);

/// A map's statistics and its grid as output columns (frictal/outputs.hpp; src/analysis/analysis_columns.cpp):
/// `frictal stats --json` and Python's map_stats().
const Columns<MapStats>& map_stats_columns();
const Columns<Map>& map_grid_columns();
/// A map as Python's read_map() returns it: its heights (ny x nx) and grid (table "map_data").
const Columns<Map>& map_data_columns();
/// An autocorrelation (Python autocorrelation(); table "autocorrelation").
const Columns<Autocorrelation>& autocorrelation_columns();

}  // namespace frictal
