// Maps (frictal/map.hpp): validation and bilinear interpolation.
#include <cmath>
#include <cstddef>
#include <limits>

#include <fmt/core.h>

#include "frictal/map.hpp"

namespace frictal {

Status validate(const Map& m, const std::string& what) {
  if (m.nx < 1 || m.ny < 1) return make_error(fmt::format("{}: empty map ({} x {})", what, m.nx, m.ny));
  if (m.heights.size() != m.nx * m.ny)
    return make_error(fmt::format("{}: {} heights for a {} x {} grid", what, m.heights.size(), m.nx, m.ny));
  if (!(m.dx > 0) || !(m.dy > 0) || !std::isfinite(m.dx) || !std::isfinite(m.dy))
    return make_error(
        fmt::format("{}: grid spacings must be positive and finite (dx = {}, dy = {})", what, m.dx, m.dy));
  // Below the smallest normal double a spacing has lost precision (and nx dx with it).
  if (m.dx < std::numeric_limits<double>::min() || m.dy < std::numeric_limits<double>::min())
    return make_error(
        fmt::format("{}: grid spacing dx = {} m, dy = {} m is below the smallest normal double ({} m) and has lost "
                    "precision; give the lateral sizes in a larger unit",
                    what, m.dx, m.dy, std::numeric_limits<double>::min()));
  std::size_t valid = 0;
  for (double v : m.heights) {
    if (std::isinf(v)) return make_error(fmt::format("{}: infinite height", what));
    valid += std::isnan(v) ? 0 : 1;
  }
  if (valid == 0) return make_error(fmt::format("{}: no valid point", what));
  return Ok{};
}

double interpolate(const Map& m, double x, double y) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double u = (x - m.x0) / m.dx, v = (y - m.y0) / m.dy;
  if (!(u >= 0) || !(v >= 0) || u > double(m.nx - 1) || v > double(m.ny - 1)) return nan;
  std::size_t i = std::size_t(u), j = std::size_t(v);
  if (i >= m.nx - 1) i = m.nx >= 2 ? m.nx - 2 : 0;
  if (j >= m.ny - 1) j = m.ny >= 2 ? m.ny - 2 : 0;
  double fu = u - double(i), fv = v - double(j);
  std::size_t i1 = m.nx >= 2 ? i + 1 : i, j1 = m.ny >= 2 ? j + 1 : j;
  double a = m.at(i, j), b = m.at(i1, j), c = m.at(i, j1), d = m.at(i1, j1);
  // A node with zero weight does not spoil the value (points exactly on a grid line).
  auto w = [](double val, double weight) { return weight == 0 ? 0.0 : val * weight; };
  double r = w(a, (1 - fu) * (1 - fv)) + w(b, fu * (1 - fv)) + w(c, (1 - fu) * fv) + w(d, fu * fv);
  return r;
}

}  // namespace frictal
