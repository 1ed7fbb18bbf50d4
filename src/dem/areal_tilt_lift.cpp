// The matched prediction of the MuJoCo tilt test (frictal/areal_tilt.hpp, areal_tilt_lift;
// docs/mujoco.md): the lift of the upper face's spheres of radius r on the lower face's height
// field triangulated as MuJoCo triangulates it. Needs no MuJoCo.
#include <fmt/core.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "areal_tilt_model.hpp"
#include "frictal/areal.hpp"
#include "frictal/areal_tilt.hpp"
#include "util/parallel.hpp"

namespace frictal {
namespace {

constexpr double kNoContact = -std::numeric_limits<double>::infinity();

struct Vertex {
  double x, y, z;
};

/// The highest centre of a sphere of radius r above (cx, cy) that touches the segment a-b:
/// max over points p of the segment within r of (cx, cy) of p_z + sqrt(r^2 - |p - c|^2) (a
/// concave function of the position along the segment: its maximum, clamped to the segment).
double edge_top(const Vertex& a, const Vertex& b, double cx, double cy, double r, double& px, double& py) {
  const double ex = b.x - a.x, ey = b.y - a.y;
  const double L = std::hypot(ex, ey);
  const double ux = ex / L, uy = ey / L;
  const double qx = cx - a.x, qy = cy - a.y;
  const double tc = qx * ux + qy * uy;
  const double perp2 = qx * qx + qy * qy - tc * tc;
  const double R2 = r * r - perp2;
  if (R2 <= 0) return kNoContact;
  const double R = std::sqrt(R2);
  const double lo = std::max(0.0, tc - R), hi = std::min(L, tc + R);
  if (lo > hi) return kNoContact;
  const double k = (b.z - a.z) / L;
  const double t = std::clamp(tc + k * R / std::sqrt(1 + k * k), lo, hi);
  px = a.x + t * ux;
  py = a.y + t * uy;
  return a.z + k * t + std::sqrt(std::max(0.0, R2 - (t - tc) * (t - tc)));
}

/// The highest centre of a sphere of radius r above (cx, cy) that touches the triangle abc
/// (kNoContact: none within r); (px, py) the touching point.
double triangle_top(const Vertex& a, const Vertex& b, const Vertex& c, double cx, double cy, double r, double& px,
                    double& py) {
  // The plane z = a.z + gx (x - a.x) + gy (y - a.y).
  const double e1x = b.x - a.x, e1y = b.y - a.y, e1z = b.z - a.z;
  const double e2x = c.x - a.x, e2y = c.y - a.y, e2z = c.z - a.z;
  const double det = e1x * e2y - e1y * e2x;
  const double gx = (e1z * e2y - e2z * e1y) / det, gy = (e1x * e2z - e2x * e1z) / det;
  const double w = std::sqrt(1 + gx * gx + gy * gy);
  // The sphere resting on the plane touches it at c + r g / w (horizontally).
  const double fx = cx + r * gx / w - a.x, fy = cy + r * gy / w - a.y;
  const double l1 = (fx * e2y - fy * e2x) / det, l2 = (e1x * fy - e1y * fx) / det;
  if (l1 >= 0 && l2 >= 0 && l1 + l2 <= 1) {
    px = a.x + fx;
    py = a.y + fy;
    return a.z + gx * (cx - a.x) + gy * (cy - a.y) + r * w;
  }
  // Otherwise the maximum of the concave height over the triangle lies on its boundary.
  double best = kNoContact, qx = 0, qy = 0;
  const Vertex* v[3] = {&a, &b, &c};
  for (int e = 0; e < 3; ++e) {
    const double t = edge_top(*v[e], *v[(e + 1) % 3], cx, cy, r, qx, qy);
    if (t > best) best = t, px = qx, py = qy;
  }
  return best;
}

}  // namespace

Result<ArealLift> areal_tilt_lift(const Map& f, const Map& g, const ArealTiltOptions& t, const ArealLiftOptions& o) {
  if (auto s = validate(f, "lower map"); !s) return s.error();
  if (auto s = validate(g, "upper map"); !s) return s.error();
  if (f.nx < 2 || f.ny < 2) return make_error("areal_tilt_lift: the lower map needs 2 x 2 nodes");
  if (!std::isfinite(t.angle))
    return make_error(fmt::format("areal_tilt_lift: angle {}: expected a finite direction (rad)", t.angle));
  if (!std::isfinite(t.sphere_radius) || t.sphere_radius < 0)
    return make_error(
        fmt::format("areal_tilt_lift: sphere radius {}: expected a finite number >= 0 (m)", t.sphere_radius));
  if (t.hfield_refine < 1 || t.hfield_refine > 16)
    return make_error(fmt::format("areal_tilt_lift: hfield_refine {}: expected 1..16", t.hfield_refine));
  auto finite_nonneg = [](double v) { return std::isfinite(v) && v >= 0; };
  if (!finite_nonneg(o.step) || !finite_nonneg(o.across_step) || !finite_nonneg(o.across_max) ||
      !std::isfinite(o.offset_min) || !std::isfinite(o.offset_max))
    return make_error(fmt::format(
        "areal_tilt_lift: step {}, across_step {}, across_max {} must be finite and >= 0, offset_min {} and "
        "offset_max {} finite (m)",
        o.step, o.across_step, o.across_max, o.offset_min, o.offset_max));
  const std::vector<detail::TiltNode> nodes = detail::tilt_nodes(f, g, t.angle, t.turn_over_upper);
  if (nodes.empty()) return make_error("areal_tilt_lift: the upper map has no valid node");
  const detail::Hfield hf = detail::tilt_hfield(f, std::size_t(t.hfield_refine));
  const double r = detail::tilt_sphere_radius(f, t);

  // The offset grid, as areal_lift.
  const double dxv = std::cos(t.angle), dyv = std::sin(t.angle), ex = -dyv, ey = dxv;
  const double step = o.step > 0 ? o.step : std::min(f.dx, f.dy);
  const double across_step = o.across_step > 0 ? o.across_step : step;
  const double along_extent = std::abs(dxv) * f.width() + std::abs(dyv) * f.height();
  const double across_extent = std::abs(ex) * f.width() + std::abs(ey) * f.height();
  const double umax = o.offset_max > o.offset_min ? o.offset_max : o.offset_min + 0.5 * along_extent;
  const double vmax = o.across_max > 0 ? o.across_max : 0.25 * across_extent;
  const std::size_t nu = std::size_t(std::floor((umax - o.offset_min) / step + 1e-9)) + 1;
  const std::size_t m = std::size_t(std::floor(vmax / across_step + 1e-9));
  const std::size_t nv = 2 * m + 1;
  if (double(nu) * double(nv) * double(nodes.size()) > 2e10)
    return make_error(
        fmt::format("areal_tilt_lift: {} x {} offsets of {} spheres are too many; increase step or "
                    "across_step",
                    nu, nv, nodes.size()));
  ArealLift out;
  out.angle = t.angle;
  out.n_along = nu;
  out.n_across = nv;
  out.along_min = o.offset_min;
  out.step = step;
  out.across_min = -double(m) * across_step;
  out.across_step = across_step;
  out.lift.assign(nu * nv, std::numeric_limits<double>::quiet_NaN());
  out.contact.assign(nu * nv, -1);

  // Highest vertex of each cell: a bound on what a sphere over it can reach.
  const std::size_t cnx = hf.nx - 1, cny = hf.ny - 1;
  std::vector<double> cell_top(cnx * cny);
  for (std::size_t j = 0; j < cny; ++j)
    for (std::size_t i = 0; i < cnx; ++i)
      cell_top[j * cnx + i] = std::max({hf.at(i, j), hf.at(i + 1, j), hf.at(i, j + 1), hf.at(i + 1, j + 1)});
  std::vector<std::size_t> work(nu * nv, 0);
  util::parallel_chunks(nu * nv, util::thread_count(o.threads, nu * nv), [&](unsigned, std::size_t k0, std::size_t k1) {
    for (std::size_t k = k0; k < k1; ++k) {
      const double u = out.along(k % nu), v = out.across(k / nu);
      const double sx = u * dxv + v * ex, sy = u * dyv + v * ey;
      double best = kNoContact, bx = 0, by = 0;
      for (const detail::TiltNode& n : nodes) {
        const double cx = n.x + sx, cy = n.y + sy;
        // Cells whose rectangle meets the disc of radius r about (cx, cy).
        const double fi0 = std::floor((cx - r - hf.x0) / hf.dx), fi1 = std::floor((cx + r - hf.x0) / hf.dx);
        const double fj0 = std::floor((cy - r - hf.y0) / hf.dy), fj1 = std::floor((cy + r - hf.y0) / hf.dy);
        if (fi1 < 0 || fj1 < 0 || fi0 > double(cnx - 1) || fj0 > double(cny - 1)) continue;
        const std::size_t i0 = std::size_t(std::max(0.0, fi0)), i1 = std::size_t(std::min(double(cnx - 1), fi1));
        const std::size_t j0 = std::size_t(std::max(0.0, fj0)), j1 = std::size_t(std::min(double(cny - 1), fj1));
        double bound = kNoContact;
        for (std::size_t j = j0; j <= j1; ++j)
          for (std::size_t i = i0; i <= i1; ++i) bound = std::max(bound, cell_top[j * cnx + i]);
        // The block's height when this sphere (centre n.z + r above the block's origin) touches.
        const double base = -(n.z + r);
        if (bound + r + base <= best) continue;
        for (std::size_t j = j0; j <= j1; ++j)
          for (std::size_t i = i0; i <= i1; ++i) {
            ++work[k];
            const Vertex p00{hf.x0 + double(i) * hf.dx, hf.y0 + double(j) * hf.dy, hf.at(i, j)};
            const Vertex p10{p00.x + hf.dx, p00.y, hf.at(i + 1, j)};
            const Vertex p01{p00.x, p00.y + hf.dy, hf.at(i, j + 1)};
            const Vertex p11{p00.x + hf.dx, p00.y + hf.dy, hf.at(i + 1, j + 1)};
            double px = 0, py = 0;
            // MuJoCo's two triangles of the cell, split along (i, j)-(i+1, j+1).
            double top = triangle_top(p01, p00, p11, cx, cy, r, px, py);
            if (top + base > best) best = top + base, bx = px, by = py;
            top = triangle_top(p00, p11, p10, cx, cy, r, px, py);
            if (top + base > best) best = top + base, bx = px, by = py;
          }
      }
      if (best == kNoContact) continue;
      out.lift[k] = best;
      const double ci = std::clamp(std::round((bx - f.x0) / f.dx), 0.0, double(f.nx - 1));
      const double cj = std::clamp(std::round((by - f.y0) / f.dy), 0.0, double(f.ny - 1));
      out.contact[k] = std::int64_t(cj) * std::int64_t(f.nx) + std::int64_t(ci);
    }
  });
  bool any = false;
  for (std::size_t k = 0; k < nu * nv; ++k) {
    out.evaluated_nodes += work[k];
    any = any || !std::isnan(out.lift[k]);
  }
  if (!any)
    return make_error(
        fmt::format("areal_tilt_lift: the spheres never touch the height field over offsets {} to {} m along {} deg "
                    "(expected maps that overlap along the sliding direction)",
                    out.along(0), out.along(nu - 1), t.angle * 180 / std::numbers::pi));
  return out;
}

}  // namespace frictal
