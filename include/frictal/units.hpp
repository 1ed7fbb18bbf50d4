// frictal — the one place where angles change unit. Inside the library every angle is in
// radians; degrees appear only at input and output (CLI, study TOML/CSV, reports, Python
// keywords ending in _deg), converted by these helpers.
#pragma once

#include <numbers>
#include <optional>
#include <string_view>

namespace frictal::units {

/// Radians per degree (unit: rad/deg).
inline constexpr double kRadPerDeg = std::numbers::pi / 180.0;

/// An angle in degrees from one in radians.
constexpr double to_deg(double rad) { return rad / kRadPerDeg; }

/// An angle in radians from one in degrees.
constexpr double from_deg(double deg) { return deg * kRadPerDeg; }

/// A density per radian as a density per degree (a PDF over angles: p(deg) = p(rad) * rad/deg).
constexpr double per_deg(double per_rad) { return per_rad * kRadPerDeg; }

/// Metres per unit of a length written by a user (options, TOML values): "m" (or no unit), "mm",
/// "um" (also with the micro sign or the Greek mu), "nm"; nullopt for any other (unit: m per unit).
inline std::optional<double> length_scale(std::string_view unit) {
  if (unit.empty() || unit == "m") return 1.0;
  if (unit == "mm") return 1e-3;
  if (unit == "um" || unit == "\xC2\xB5m" || unit == "\xCE\xBCm") return 1e-6;
  if (unit == "nm") return 1e-9;
  return std::nullopt;
}

/// Pascals per unit of a pressure or modulus written by a user (options, TOML values): "Pa" (or
/// no unit), "kPa", "MPa", "GPa"; nullopt for any other (unit: Pa per unit).
inline std::optional<double> pressure_scale(std::string_view unit) {
  if (unit.empty() || unit == "Pa") return 1.0;
  if (unit == "kPa") return 1e3;
  if (unit == "MPa") return 1e6;
  if (unit == "GPa") return 1e9;
  return std::nullopt;
}

}  // namespace frictal::units
