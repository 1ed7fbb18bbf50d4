// frictal — areal height maps (measured surfaces z(x, y) on a regular grid).
//
// Storage is one flat row-major array, x fastest: heights[j * nx + i] is the height at
// x = x0 + i * dx, y = y0 + j * dy. Invalid (unmeasured) points are NaN. Units: metres.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "frictal/result.hpp"

namespace frictal {

struct Map {
  std::size_t nx = 0;           ///< points along x (unitless)
  std::size_t ny = 0;           ///< points along y (unitless)
  double dx = 1;                ///< grid spacing along x, > 0 (unit: m)
  double dy = 1;                ///< grid spacing along y, > 0 (unit: m)
  double x0 = 0;                ///< x of column 0 (unit: m)
  double y0 = 0;                ///< y of row 0 (unit: m)
  std::vector<double> heights;  ///< nx * ny values, x fastest; NaN = invalid point (unit: m)

  std::size_t size() const { return heights.size(); }
  double& at(std::size_t i, std::size_t j) { return heights[j * nx + i]; }
  double at(std::size_t i, std::size_t j) const { return heights[j * nx + i]; }
  double width() const { return nx > 1 ? double(nx - 1) * dx : 0.0; }   ///< x extent of the nodes (m)
  double height() const { return ny > 1 ? double(ny - 1) * dy : 0.0; }  ///< y extent of the nodes (m)
  std::size_t valid_count() const {
    std::size_t n = 0;
    for (double v : heights) n += std::isfinite(v) ? 1 : 0;
    return n;
  }
};

/// Checks sizes (nx * ny == heights.size(), nx, ny >= 1), positive finite spacings, no infinite
/// heights (NaN allowed) and at least one valid point. `what` names the data in messages.
Status validate(const Map& m, const std::string& what = "map");

/// Bilinear interpolation at (x, y) in the map's coordinates. NaN outside the grid or when any
/// of the (up to four) nodes used is NaN.
double interpolate(const Map& m, double x, double y);

}  // namespace frictal
