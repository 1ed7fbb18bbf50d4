// The geometry that the map model (map_hold.cpp) evaluates and that the MuJoCo tilt test
// (src/tilt/areal_tilt_mujoco.cpp, which includes this shared header) simulates: one definition
// of the upper face's spheres and of the lower face's height field, so that both see the same
// surfaces (docs/mujoco.md).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "frictal/map.hpp"
#include "frictal/map_hold.hpp"

namespace frictal::detail {

/// The number of quarter turns nearest to the sliding direction `angle` (rad): the experiment
/// turned by minus that many has its direction within 45 deg of +x (unitless).
inline int direction_quarters(double angle) { return int(std::floor(angle / (0.5 * 3.14159265358979323846) + 0.5)); }

/// The map turned by a quarter turn counterclockwise about the origin: the node at (x, y) moves
/// to (-y, x), its columns becoming rows.
inline Map quarter_turn(const Map& m) {
  Map r;
  r.nx = m.ny;
  r.ny = m.nx;
  r.dx = m.dy;
  r.dy = m.dx;
  r.x0 = -(m.y0 + m.height());
  r.y0 = m.x0;
  r.heights.resize(m.heights.size());
  for (std::size_t j = 0; j < r.ny; ++j)
    for (std::size_t i = 0; i < r.nx; ++i) r.heights[j * r.nx + i] = m.at(j, m.ny - 1 - i);
  return r;
}

/// `m` turned by q quarter turns counterclockwise (q of any sign).
inline Map turned(Map m, int q) {
  for (int k = ((q % 4) + 4) % 4; k > 0; --k) m = quarter_turn(m);
  return m;
}

/// The vector (or position) v turned by q quarter turns counterclockwise.
inline std::array<double, 2> turned(std::array<double, 2> v, int q) {
  for (int k = ((q % 4) + 4) % 4; k > 0; --k) v = {-v[1], v[0]};
  return v;
}

/// The tilt test turned as a whole, maps, direction and offsets together, by minus the quarter
/// turns of its direction, so that the direction lies in [-45, 45) deg, and moved so that the
/// lower map's first node lies at the origin (the upper map with it in place; turned over, its
/// place does not count): the height field's cells are split along one diagonal of the grid
/// (MuJoCo's triangulation), which a quarter turn of the maps exchanges for the other, so that
/// the same experiment turned by 90 deg met other triangles (a random anisotropic pair: median
/// 18.10 deg against 16.91). In this frame a turn of the whole experiment by quarter turns, or a
/// shift of it, changes nothing (node positions i dx from the same origin, to the bit): every
/// front end and the MuJoCo test run here. Offsets are the same vectors in both frames but for
/// the turn: results are turned back by `q`. Options: the model's (MapHoldOptions) or the
/// simulation's (ArealTiltOptions, which are the model's and more); only the model's are turned.
template <class Options>
struct TurnedExperiment {
  int q = 0;  ///< quarter turns from this frame back to the caller's (unitless)
  Map f, g;
  Options t;
  TurnedExperiment(const Map& lower, const Map& upper, const Options& o)
      : q(direction_quarters(o.angle)), f(turned(lower, -q)), g(turned(upper, -q)), t(o) {
    t.angle = o.angle - q * (0.5 * 3.14159265358979323846);
    if (std::abs(t.angle) < 1e-12) t.angle = 0;  // on the axis (the turn's rounding)
    t.start_offset = turned(o.start_offset, -q);
    if (o.turn_over_upper) {
      g.x0 = g.y0 = 0;
    } else {
      g.x0 -= f.x0;
      g.y0 -= f.y0;
    }
    f.x0 = f.y0 = 0;
  }
  std::array<double, 2> back(std::array<double, 2> v) const { return turned(v, q); }
};

/// A node of the upper face at offset 0, in the lower map's frame (unit: m).
struct TiltNode {
  double x, y, z;
};

/// The upper map's valid nodes, turned over about the axis across d through the centres (as
/// areal_signature) or in place.
inline std::vector<TiltNode> tilt_nodes(const Map& f, const Map& g, double angle, bool turn_over) {
  const double dxv = std::cos(angle), dyv = std::sin(angle);
  const double cfx = f.x0 + 0.5 * f.width(), cfy = f.y0 + 0.5 * f.height();
  const double cgx = g.x0 + 0.5 * g.width(), cgy = g.y0 + 0.5 * g.height();
  std::vector<TiltNode> nodes;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      const double z = g.at(i, j);
      if (std::isnan(z)) continue;
      const double qx = g.x0 + double(i) * g.dx, qy = g.y0 + double(j) * g.dy;
      if (turn_over) {
        const double ax = qx - cgx, ay = qy - cgy, along = ax * dxv + ay * dyv;
        nodes.push_back({cfx + ax - 2 * along * dxv, cfy + ay - 2 * along * dyv, -z});
      } else {
        nodes.push_back({qx, qy, z});
      }
    }
  return nodes;
}

/// The sphere radius used: the option, or a fifth of the lower map's smaller spacing (unit: m).
inline double tilt_sphere_radius(const Map& f, const MapHoldOptions& o) {
  return o.sphere_radius > 0 ? o.sphere_radius : 0.2 * std::min(f.dx, f.dy);
}

/// The run-away distance used: the option, or a twentieth of the lower map's extent along d (unit: m).
inline double tilt_runaway_distance(const Map& f, const MapHoldOptions& o) {
  // Called with D unset (the library's areal_tilt and areal_tilt_hold on their own): 5 % of the
  // lower map along d, the simulations' setting. The front ends and predict() set D first
  // (fill_map_model_defaults: default_map_runaway_distance, a length of the surface).
  return o.runaway_distance > 0
             ? o.runaway_distance
             : 0.05 * (std::abs(std::cos(o.angle)) * f.width() + std::abs(std::sin(o.angle)) * f.height());
}

/// The holes of a grid of nx x ny values (row-major, NaN: no height) as the lower face takes them:
/// a hole of at most kSmallHole nodes (4-connected: a spike the conditioning masked, a dropout)
/// is filled from its surroundings, in layers from the valid nodes, each node the mean of its
/// already known 4-neighbours, so that it is no pit (pits with steep walls around every masked
/// spike made the contacts and the descent's windows resolve them: a nearly flat map with its
/// spikes masked took many times the map with them); a larger hole, a region not measured, stays
/// at the lowest height (no contact there; filling it would invent a surface), marked NaN here for
/// the caller. All NaN: zero.
inline constexpr std::size_t kSmallHole = 16;
inline void fill_holes(std::vector<double>& z, std::size_t nx, std::size_t ny) {
  std::vector<int> comp(z.size(), -1);  // component of each hole node
  std::vector<std::size_t> size_of, stack;
  std::size_t holes = 0;
  for (std::size_t k0 = 0; k0 < z.size(); ++k0) {
    if (!std::isnan(z[k0]) || comp[k0] >= 0) continue;
    const int c = int(size_of.size());
    std::size_t n = 0;
    stack = {k0};
    comp[k0] = c;
    while (!stack.empty()) {
      const std::size_t k = stack.back();
      stack.pop_back();
      ++n;
      const std::size_t i = k % nx, j = k / nx;
      for (const std::size_t q :
           {i > 0 ? k - 1 : k, i + 1 < nx ? k + 1 : k, j > 0 ? k - nx : k, j + 1 < ny ? k + nx : k})
        if (q != k && std::isnan(z[q]) && comp[q] < 0) comp[q] = c, stack.push_back(q);
    }
    size_of.push_back(n);
    holes += n;
  }
  if (holes == z.size()) {
    std::fill(z.begin(), z.end(), 0.0);
    return;
  }
  std::vector<std::size_t> front, next;
  for (std::size_t k = 0; k < z.size(); ++k)
    if (comp[k] >= 0 && size_of[std::size_t(comp[k])] <= kSmallHole) front.push_back(k);
  while (!front.empty()) {
    std::vector<std::pair<std::size_t, double>> fill;
    next.clear();
    for (const std::size_t k : front) {
      const std::size_t i = k % nx, j = k / nx;
      double sum = 0;
      int n = 0;
      auto take = [&](std::size_t q) {
        if (!std::isnan(z[q])) sum += z[q], ++n;
      };
      if (i > 0) take(k - 1);
      if (i + 1 < nx) take(k + 1);
      if (j > 0) take(k - nx);
      if (j + 1 < ny) take(k + nx);
      if (n > 0)
        fill.push_back({k, sum / n});
      else
        next.push_back(k);
    }
    if (fill.empty()) break;                   // (cannot happen: a small hole touches a valid node)
    for (const auto& [k, v] : fill) z[k] = v;  // a layer at once: the order of the nodes does not matter
    std::swap(front, next);
  }
}

/// The lower face as MuJoCo's height field: (nx - 1) k + 1 by (ny - 1) k + 1 vertices sampling the
/// map's bilinear surface (k = 1: its nodes), small holes filled from their surroundings and
/// large ones at the lowest height (fill_holes); `data` is what MuJoCo
/// stores (float, (z - zmin) / relief) and `z` the heights it then uses (unit: m). MuJoCo 2.2.2
/// (engine_collision_convex.c, mjc_ConvexHField) splits cell (c, r) into the triangles
/// {(c, r+1), (c, r), (c+1, r+1)} and {(c, r), (c+1, r+1), (c+1, r)}: along the diagonal from
/// (c, r) to (c+1, r+1), row r at y0 + r dy.
struct Hfield {
  std::size_t nx = 0, ny = 0;
  double x0 = 0, y0 = 0, dx = 0, dy = 0;
  double zmin = 0, relief = 0;
  std::vector<float> data;
  std::vector<double> z;
  double at(std::size_t i, std::size_t j) const { return z[j * nx + i]; }
};

inline Hfield tilt_hfield(const Map& f, std::size_t k) {
  Hfield h;
  h.nx = (f.nx - 1) * k + 1;
  h.ny = (f.ny - 1) * k + 1;
  h.x0 = f.x0;
  h.y0 = f.y0;
  h.dx = f.dx / double(k);
  h.dy = f.dy / double(k);
  std::vector<double> v(h.nx * h.ny);
  for (std::size_t j = 0; j < h.ny; ++j)
    for (std::size_t i = 0; i < h.nx; ++i)
      v[j * h.nx + i] = k == 1 ? f.at(i, j)
                               : interpolate(f, f.x0 + std::min(f.width(), double(i) * f.dx / double(k)),
                                             f.y0 + std::min(f.height(), double(j) * f.dy / double(k)));
  fill_holes(v, h.nx, h.ny);
  double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin;
  for (double x : v)
    if (!std::isnan(x)) zmin = std::min(zmin, x), zmax = std::max(zmax, x);
  for (double& x : v)
    if (std::isnan(x)) x = zmin;  // a large hole: at the lowest height
  const double L = std::max(f.width(), f.height());
  h.zmin = zmin;
  h.relief = std::max(zmax - zmin, 1e-12 * L);
  h.data.resize(h.nx * h.ny);
  h.z.resize(h.nx * h.ny);
  for (std::size_t q = 0; q < v.size(); ++q) {
    const float s = float((v[q] - zmin) / h.relief);
    h.data[q] = s;
    h.z[q] = zmin + double(s) * h.relief;
  }
  return h;
}

}  // namespace frictal::detail
