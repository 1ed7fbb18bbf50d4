// frictal — warnings as results: a number that was computed without an error but that a reader
// should not trust as it stands (units, spikes, scale, a clamped range) carries a code. Every
// front end shows them: the CLI's JSON as `warnings: [{code, message}]` and its text output on
// standard error, Python on the result and through `warnings.warn`, the report beside its
// headline. Decisions are taken on codes, never on message text; warning_codes() is the one
// table of codes (docs/warnings.md is generated from it by `frictal warnings --markdown`).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "frictal/geometry.hpp"
#include "frictal/map.hpp"
#include "frictal/outputs.hpp"
#include "frictal/result.hpp"

namespace frictal {

/// A code and what it means (its cause and what to do), for the documentation and `frictal warnings`.
struct WarningCode {
  std::string code;
  std::string meaning;
  /// The input was probably read wrong (units, spikes left in, scans that do not match, an angle
  /// at 90 deg), or the model the number comes from does not hold for it (asperity contacts that
  /// merge or interfere deeply under load): a prediction that carries the code is "doubtful"
  /// (Prediction::trust), its number not the surfaces' friction until the fix is applied.
  bool doubtful = false;
  /// The fix that exists: the CLI options to add (Python's keywords in parentheses); empty: none.
  std::string fix;
};

/// Every warning code the library issues, in one table.
const std::vector<WarningCode>& warning_codes();
/// A code's output columns (table "warning_code", src/predict/warning_columns.cpp): `frictal warnings --json`.
const Columns<WarningCode>& warning_code_columns();
/// The entry of `code` in warning_codes(); nullptr for a code not in it.
const WarningCode* find_warning_code(const std::string& code);

/// Whether a result with these warnings is to be trusted: "ok", or "doubtful" with the codes
/// that make it so (warning_codes()' `doubtful` ones, in the order met, each once) and their
/// fixes joined ("; ").
struct Trust {
  std::string verdict = "ok";
  std::vector<std::string> codes;
  std::string fix;
};
Trust assess_trust(const std::vector<Warning>& warnings);

/// Appends `w` unless a warning with the same code and message is already there.
void add_warning(std::vector<Warning>& list, Warning w);

/// Thresholds of the plausibility checks (documented in docs/warnings.md, why each value).
struct PlausibilityLimits {
  /// rms slope above which the lateral and height units are taken to differ (unitless): 10 is a
  /// slope of 84 deg on average, steeper than any profilometer, AFM or interferometer measures.
  double max_rms_slope = 10;
  double min_rms_height = 1e-12;  ///< below 1 pm: a scale factor missing or applied twice (unit: m)
  double spike_sq = 10;           ///< a point this many rms heights from its neighbours' median is a spike (unitless)
  double max_kurtosis = 30;       ///< height kurtosis above this: a few outliers dominate (unitless)
  double max_repeated_fraction = 0.05;  ///< one height value repeated over this fraction: a fill value (unitless)
  double max_scale_ratio = 10;          ///< two scans whose lengths or spacings differ by more (unitless)
  /// lateral-suspect: an rms slope below this (unitless; 1e-4 is 0.006 deg, 40x below the smoothest
  /// measured surface in the project's test files, 0.0037) on points spaced more than
  /// `lateral_suspect_spacing` apart: lateral lengths read in a unit too large (x in mm read as m
  /// makes the slopes 1000x smaller and the spacing 1000x larger).
  double min_rms_slope = 1e-4;
  double lateral_suspect_spacing = 2e-5;  ///< (unit: m) 20 um: coarser than roughness instruments sample
};

/// Plausibility of one measured profile; `name` names it in the messages. Codes: units-suspect,
/// lateral-suspect, heights-tiny, form-only, heights-exceed-length, spikes, kurtosis, fill-value.
/// `read_rms_height`: the rms height of the surface as read, before its form was removed (unit: m;
/// NaN: not known): where `p` is flat but the heights as read vary, the surface is its form
/// (form-only), not a surface of tiny heights (heights-tiny).
std::vector<Warning> check_profile(const Profile& p, const std::string& name, const PlausibilityLimits& limits = {},
                                   double read_rms_height = std::numeric_limits<double>::quiet_NaN());
/// The same for an areal map (NaN points are not measured and are skipped).
std::vector<Warning> check_map(const Map& m, const std::string& name, const PlausibilityLimits& limits = {},
                               double read_rms_height = std::numeric_limits<double>::quiet_NaN());
/// The rms height about the mean of the finite heights `z` (unit: m): a surface's read_rms_height.
double rms_height_as_read(const std::vector<double>& z);
/// Two scans of one pair: scale-mismatch when their lengths or point spacings differ by more than
/// limits.max_scale_ratio. Lengths and spacings in m.
std::vector<Warning> check_pair_scales(double lower_length, double lower_spacing, double upper_length,
                                       double upper_spacing, const std::string& lower_name,
                                       const std::string& upper_name, const PlausibilityLimits& limits = {});

/// A fractal dimension fit (fractal.hpp's FractalFit: `dimension`, `r_squared`): codes
/// dimension-out-of-range (D outside [1, 2], which no profile has) and poor-fit (r^2 below
/// `min_r_squared`: the log-log data are not a power law over the fit range). `method` names it.
std::vector<Warning> check_dimension_fit(double dimension, double r_squared, const std::string& method,
                                         double min_r_squared = 0.95);

/// A rigid upper bound phi = theta_max + theta_a (unit: rad) below zero: code bound-negative
/// (mu = tan(phi) < 0: every contact along the sliding direction descends, so no tilt holds the
/// block; a wrong direction, scans that do not overlap or a unit mix-up). `where` names the
/// result in the message. Empty when phi >= 0 or NaN.
std::vector<Warning> check_friction_bound(double friction_angle, const std::string& where);

struct FrictionPrediction;  // signature.hpp
/// The warnings of one rigid bound and its Eq. 18 range (`frictal areal`, `anisotropy`, Python
/// areal_signature, anisotropy, predict_friction): eq18-low-clamped and bound-negative. `where`
/// names the result in the messages.
std::vector<Warning> check_friction_prediction(const FrictionPrediction& p, const std::string& where);
/// The warnings of a signature's rigid bounds (`frictal signature`, Python signature(); the same
/// words in both): check_friction_prediction of the forward bound, friction-angle-at-90
/// of either direction's bound at 89.5 deg or more (a wall, an interlock or a unit mix-up).
std::vector<Warning> check_signature_bounds(const FrictionPrediction& forward, const FrictionPrediction& backward,
                                            const std::string& where = "signature");

}  // namespace frictal
