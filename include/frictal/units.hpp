// frictal — the one place where angles change unit. Inside the library every angle is in
// radians; degrees appear only at input and output (CLI, study TOML/CSV, reports, Python
// keywords ending in _deg), converted by these helpers.
#pragma once

#include <numbers>

namespace frictal::units {

/// Radians per degree (unit: rad/deg).
inline constexpr double kRadPerDeg = std::numbers::pi / 180.0;

/// An angle in degrees from one in radians.
constexpr double to_deg(double rad) { return rad / kRadPerDeg; }

/// An angle in radians from one in degrees.
constexpr double from_deg(double deg) { return deg * kRadPerDeg; }

/// A density per radian as a density per degree (a PDF over angles: p(deg) = p(rad) * rad/deg).
constexpr double per_deg(double per_rad) { return per_rad * kRadPerDeg; }

}  // namespace frictal::units
