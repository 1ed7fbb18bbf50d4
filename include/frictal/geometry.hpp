// frictal — curves and profiles.
//
// A Curve is a polyline of points (x, z) in metres that may fold over (x not monotonic), e.g. a
// Koch curve with large alpha. A Profile is single-valued: x is non-decreasing, and two or three
// consecutive points may share an x to describe an exact vertical jump (the order of points at
// one x traces the graph: left limit, extreme value, right limit). Envelopes of folded curves
// are Profiles with such jumps. Storage is two flat arrays so that numpy can map them.
//
// Conventions (docs/ARCHITECTURE.md): every surface is stored as measured, material below and
// z up. The upper block's face is the surface rotated by 180 degrees (point reflection).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "frictal/result.hpp"

namespace frictal {

/// A general polyline (may fold over). Units: metres.
struct Curve {
  std::vector<double> x;  ///< abscissae (unit: m)
  std::vector<double> z;  ///< heights (unit: m)
  std::size_t size() const { return x.size(); }
};

/// A single-valued piecewise-linear profile z(x). Units: metres.
struct Profile {
  std::vector<double> x;  ///< non-decreasing abscissae; equal neighbours mark a vertical jump (m)
  std::vector<double> z;  ///< heights (m)
  /// Period of the surface if it repeats exactly (m); the points then cover one or more whole
  /// periods starting at x.front(). Unset for measured, non-periodic data.
  std::optional<double> period;
  std::size_t size() const { return x.size(); }
  double x_min() const { return x.front(); }
  double x_max() const { return x.back(); }
  double length() const { return x.back() - x.front(); }
};

/// Which extreme a Profile takes at a vertical jump when evaluated exactly at its abscissa.
enum class JumpValue { Upper, Lower };

/// Checks a curve: at least two points, equal-length arrays, finite values, no zero-length
/// edges repeated more than needed. `what` names the data in the message (e.g. a file name).
Status validate(const Curve& c, const std::string& what = "curve");
/// Checks a profile: as validate(Curve) plus x non-decreasing, at most three points per x,
/// positive length and a period (if set) that is positive and not longer than the profile.
Status validate(const Profile& p, const std::string& what = "profile");

/// Converts a curve whose x is already non-decreasing into a Profile; error otherwise.
Result<Profile> as_profile(const Curve& c, const std::string& what = "curve");
/// The same, taking c's points over (no copy).
Result<Profile> as_profile(Curve&& c, const std::string& what = "curve");
/// The curve through the points of a profile (same points).
Curve as_curve(const Profile& p);

/// Exact upper envelope (pointwise supremum over the curve's edges) of a curve, as a profile.
/// Vertical jumps are kept exact; no resampling. O(n log n) for curves with few crossings.
Result<Profile> upper_envelope(const Curve& c);
/// Exact lower envelope (pointwise infimum), as a profile.
Result<Profile> lower_envelope(const Curve& c);

/// Rotation by 180 degrees in the profile's own frame: x -> x_min + x_max - x, z -> -z.
/// An involution. Maps an upper envelope to the lower envelope of the rotated curve.
Profile rotate180(const Profile& p);
/// As rotate180(const Profile&), in the profile's own storage (no copy: 160 MB at 10^7 points);
/// the same values to the bit.
Profile rotate180(Profile&& p);
Curve rotate180(const Curve& c);

/// Value of the profile at x (linear interpolation; at a jump the upper or lower extreme).
/// x must lie in [x_min, x_max]; for a periodic profile any x is wrapped into one period.
double evaluate(const Profile& p, double x, JumpValue at_jump = JumpValue::Upper);

/// Resamples on n >= 2 equally spaced points over the profile's range (linear interpolation;
/// jumps are smeared over one spacing, so this is a lossy operation the caller asks for).
Result<Profile> resample(const Profile& p, std::size_t n);

/// True if x is strictly increasing with constant spacing within relative tolerance rel_tol.
bool is_uniform(const Profile& p, double rel_tol = 1e-9);

}  // namespace frictal
