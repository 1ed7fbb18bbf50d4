// Areal statistics of maps whose heights or spacings lie near the limits of double (1e300,
// 1e-300): squares and fourth powers of height differences and slopes would overflow to inf or
// underflow to 0 and give a silently wrong Sq, Sdq, Rq, ... They are computed on a copy scaled
// by powers of two (exact: only the exponents change), then scaled back. Maps within
// 2^-60 .. 2^60 are not copied (there the scaling would change no bit of any result).
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include "frictal/map.hpp"

namespace frictal::analysis_detail {

struct MapScale {
  int height_exp = 0;  ///< heights were multiplied by 2^-height_exp
  int length_exp = 0;  ///< x, y, dx, dy were multiplied by 2^-length_exp
  double height(double v) const { return std::ldexp(v, height_exp); }              ///< back to metres
  double length(double v) const { return std::ldexp(v, length_exp); }              ///< back to metres
  double slope(double v) const { return std::ldexp(v, height_exp - length_exp); }  ///< back to m/m
};

/// The scale that brings the largest |height| and the larger spacing to [1, 2), or nothing when
/// the map needs none (or has no finite height).
inline std::optional<MapScale> edge_scale(const Map& m) {
  double zmax = 0;
  for (double v : m.heights)
    if (std::isfinite(v)) zmax = std::max(zmax, std::abs(v));
  const double smax = std::max(m.dx, m.dy);
  if (!(zmax > 0) || !std::isfinite(zmax) || !(smax > 0) || !std::isfinite(smax)) return std::nullopt;
  const MapScale s{std::ilogb(zmax), std::ilogb(smax)};
  if (std::abs(s.height_exp) <= 60 && std::abs(s.length_exp) <= 60) return std::nullopt;
  return s;
}

inline Map scaled(const Map& m, const MapScale& s) {
  Map c = m;
  for (double& v : c.heights) v = std::ldexp(v, -s.height_exp);  // NaN stays NaN
  c.dx = std::ldexp(m.dx, -s.length_exp);
  c.dy = std::ldexp(m.dy, -s.length_exp);
  c.x0 = std::ldexp(m.x0, -s.length_exp);
  c.y0 = std::ldexp(m.y0, -s.length_exp);
  return c;
}

}  // namespace frictal::analysis_detail
