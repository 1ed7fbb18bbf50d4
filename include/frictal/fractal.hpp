// frictal — fractal dimension of curves and profiles (paper Sec. IV C 3, Eq. 13).
#pragma once

#include <cstddef>
#include <vector>

#include "frictal/geometry.hpp"
#include "frictal/outputs.hpp"

namespace frictal {

/// A straight-line fit in log-log coordinates and the dimension derived from it.
struct FractalFit {
  double dimension = 0;        ///< (unitless)
  double slope = 0;            ///< fitted log-log slope (unitless)
  double intercept = 0;        ///< (natural log units)
  double r_squared = 0;        ///< coefficient of determination of the fit (unitless)
  double scale_min = 0;        ///< smallest scale in the fit: ruler, box or wavelength (unit: m)
  double scale_max = 0;        ///< largest scale in the fit (unit: m)
  std::vector<double> scales;  ///< every scale used (unit: m)
  std::vector<double> values;  ///< L(eps) (m), N(eps) (unitless) or binned C(q) (m^3)
};

/// Divider (ruler) method: walk along the curve (in its point order, so folded curves are
/// measured along the curve, not the profile) with a ruler of length eps, each step to the
/// first later point of the curve at distance eps; L(eps) = steps * eps + the last partial
/// distance. L ~ eps^(1 - D), so D = 1 - slope. `rulers` values log-spaced in [ruler_min,
/// ruler_max]; 0 picks the defaults (ruler_max = 1/4 of the end-to-end distance, ruler_min =
/// the median edge length).
struct DividerOptions {
  double ruler_min = 0;  ///< (unit: m)
  double ruler_max = 0;  ///< (unit: m)
  int rulers = 16;       ///< >= 3 (unitless)
};
Result<FractalFit> divider_dimension(const Curve& c, const DividerOptions& o = {});
/// L(eps) for one ruler (unit: m).
double divider_length(const Curve& c, double ruler);

/// Box counting: N(eps) = number of eps x eps grid cells crossed by the polyline (x and z in
/// the same units); N ~ eps^-D. Defaults as for the divider.
struct BoxOptions {
  double box_min = 0;  ///< (unit: m)
  double box_max = 0;  ///< (unit: m)
  int sizes = 12;      ///< >= 3 (unitless)
};
Result<FractalFit> box_dimension(const Curve& c, const BoxOptions& o = {});

/// PSD slope of a self-affine profile: C(q) ~ q^-(5 - 2D), so D = (5 + slope) / 2. The
/// spectrum (power_spectrum) is averaged in log-spaced bins (bins_per_decade) and fitted over
/// [q_min, q_max] (0 = from the second wavenumber to a quarter of the Nyquist wavenumber).
struct PsdFitOptions {
  double q_min = 0;  ///< (unit: rad/m)
  double q_max = 0;  ///< (unit: rad/m)
  int bins_per_decade = 10;
};
Result<FractalFit> psd_dimension(const Profile& p, const PsdFitOptions& o = {});

/// Similarity dimension of the triadic Koch construction with base angle alpha (Eq. 13): each
/// segment becomes two of length 1/3 and two of length 1/(6 cos alpha), so D solves
///   2 (1/3)^D + 2 (1/(6 cos alpha))^D = 1     (D = log 4 / log 3 at alpha = 60 degrees).
/// alpha in [0, pi/3] (unit: rad). Solved by bisection to machine precision.
Result<double> koch_dimension(double alpha);

/// The Koch dimension of Eq. 13 as a result: the angle and the dimension it gives.
struct KochDimension {
  double alpha = 0;      ///< the Koch angle (unit: rad)
  double dimension = 0;  ///< D of Eq. 13 (unitless)
};
/// Its output table (src/analysis/analysis_columns.cpp): `frictal dimension koch --method eq13 --json`.
const Columns<KochDimension>& koch_dimension_columns();

/// A fit's output table (frictal/outputs.hpp; src/analysis/analysis_columns.cpp): `frictal dimension
/// --json` and Python's divider_dimension/box_dimension/psd_dimension dicts.
const Columns<FractalFit>& fractal_fit_columns();

}  // namespace frictal
