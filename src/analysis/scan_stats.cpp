// Scan quantities (scan_stats.hpp). Invalid (NaN) points never enter a sum.
#include "frictal/scan_stats.hpp"

#include <fmt/core.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "analysis/edge_scale.hpp"

namespace frictal {

namespace {

/// Pooled Rq and Rdq over lines of a map: line l has n points z(l, k) = at(l, k).
template <class At>
void pooled_line_stats(std::size_t lines, std::size_t n, double spacing, At at, double& rq, double& rdq) {
  double ss = 0, gs = 0;
  std::size_t cnt = 0, gcnt = 0;
  for (std::size_t l = 0; l < lines; ++l) {
    double sum = 0;
    std::size_t nv = 0;
    for (std::size_t k = 0; k < n; ++k)
      if (double z = at(l, k); !std::isnan(z)) sum += z, ++nv;
    if (nv == 0) continue;
    const double mean = sum / double(nv);
    for (std::size_t k = 0; k < n; ++k) {
      const double z = at(l, k);
      if (std::isnan(z)) continue;
      ss += (z - mean) * (z - mean);
      ++cnt;
      if (k + 1 < n && !std::isnan(at(l, k + 1))) {
        const double g = (at(l, k + 1) - z) / spacing;
        gs += g * g;
        ++gcnt;
      }
    }
  }
  rq = cnt ? std::sqrt(ss / double(cnt)) : 0.0;
  rdq = gcnt ? std::sqrt(gs / double(gcnt)) : 0.0;
}

/// Most negative scale-dependent curvature over the lines at stencil distance h:
///   kappa_h(x_i) = (z(x_i + h) - 2 z(x_i) + z(x_i - h)) / h^2,
/// z(x_i +- h) linearly interpolated between the samples (SurfaceTopography's `derivative(n=2,
/// distance=2h)` with interpolation='linear'), at every sample with x_i - h and x_i + h inside
/// the line; +inf if there is none. Samples that are NaN (or interpolate from one) are skipped.
template <class At, class Xat>
double min_curvature(std::size_t lines, std::size_t n, double h, At at, Xat xat) {
  double best = std::numeric_limits<double>::infinity();
  const double x_first = xat(0), x_last = xat(n - 1), tol = 1e-9 * h;
  // z at position x of line l, interpolating from segment k (x_k <= x <= x_{k+1}).
  auto interp = [&](std::size_t l, std::size_t k, double x) {
    const double xa = xat(k), xb = xat(k + 1);
    const double t = std::clamp((x - xa) / (xb - xa), 0.0, 1.0);
    const double za = at(l, k), zb = at(l, k + 1);
    if (t == 0) return za;
    if (t == 1) return zb;
    return za + t * (zb - za);
  };
  for (std::size_t l = 0; l < lines; ++l) {
    std::size_t lo = 0, hi = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double xi = xat(i), xl = xi - h, xr = xi + h;
      if (xl < x_first - tol) continue;
      if (xr > x_last + tol) break;
      while (lo + 2 < n && xat(lo + 1) <= xl) ++lo;
      if (hi < lo) hi = lo;
      while (hi + 2 < n && xat(hi + 1) <= xr) ++hi;
      const double zi = at(l, i), zl = interp(l, lo, xl), zr = interp(l, hi, xr);
      if (std::isnan(zi) || std::isnan(zl) || std::isnan(zr)) continue;
      best = std::min(best, (zr - 2 * zi + zl) / (h * h));
    }
  }
  return best;
}

/// The cutoff along one direction (see the header): the stencil length 2h at which the most
/// negative curvature reaches -1/(2R), found by bisection between h = spacing and h = n spacing / 4
/// (SurfaceTopography's bracket: distance 2 x lower .. upper / 2 of the bandwidth).
template <class At, class Xat>
double cutoff_along(std::size_t lines, std::size_t n, double spacing, double radius, At at, Xat xat) {
  const double target = 0.5 / radius;  // safety factor 1/2 (Sanner et al. 2022)
  auto objective = [&](double h) {
    const double c = min_curvature(lines, n, h, at, xat);
    return std::isinf(c) && c > 0 ? target : target + c;
  };
  double a = spacing, b = double(n) * spacing / 4;
  if (!(b > a) || objective(a) > 0) return 0.0;                           // reliable down to the sampling interval
  if (objective(b) < 0) return std::numeric_limits<double>::quiet_NaN();  // unreliable at every scale
  for (int it = 0; it < 200 && b - a > 1e-13 * b; ++it) {
    const double mid = 0.5 * (a + b);
    (objective(mid) < 0 ? a : b) = mid;
  }
  return a + b;  // the stencil length 2h, h = (a + b) / 2
}

}  // namespace

namespace {
MapScanStats map_scan_stats_unscaled(const Map& m) {
  MapScanStats s;
  s.physical_size_x = double(m.nx) * m.dx;
  s.physical_size_y = double(m.ny) * m.dy;
  s.bandwidth_short = 0.5 * (m.dx + m.dy);
  s.bandwidth_long = 0.5 * (s.physical_size_x + s.physical_size_y);
  s.nyquist_wavelength = 2 * std::max(m.dx, m.dy);
  pooled_line_stats(
      m.ny, m.nx, m.dx, [&](std::size_t j, std::size_t i) { return m.at(i, j); }, s.Rq_x, s.Rdq_x);
  pooled_line_stats(
      m.nx, m.ny, m.dy, [&](std::size_t i, std::size_t j) { return m.at(i, j); }, s.Rq_y, s.Rdq_y);
  double g2 = 0;
  std::size_t cnt = 0;
  for (std::size_t j = 0; j + 1 < m.ny; ++j)
    for (std::size_t i = 0; i + 1 < m.nx; ++i) {
      const double z = m.at(i, j), zx = m.at(i + 1, j), zy = m.at(i, j + 1);
      if (std::isnan(z) || std::isnan(zx) || std::isnan(zy)) continue;
      const double gx = (zx - z) / m.dx, gy = (zy - z) / m.dy;
      g2 += gx * gx + gy * gy;
      ++cnt;
    }
  s.rms_gradient_fd = cnt ? std::sqrt(g2 / double(cnt)) : 0.0;
  return s;
}
}  // namespace

MapScanStats map_scan_stats(const Map& m) {
  const auto sc = analysis_detail::edge_scale(m);
  if (!sc) return map_scan_stats_unscaled(m);
  // Heights or spacings near the limits of double: computed at a power-of-two scale.
  MapScanStats s = map_scan_stats_unscaled(analysis_detail::scaled(m, *sc));
  // The sizes in metres as they are (n dx beyond double is +inf, as it must be).
  s.physical_size_x = double(m.nx) * m.dx;
  s.physical_size_y = double(m.ny) * m.dy;
  s.bandwidth_short = 0.5 * m.dx + 0.5 * m.dy;  // = 0.5 (dx + dy) exactly, without overflow
  s.bandwidth_long = 0.5 * s.physical_size_x + 0.5 * s.physical_size_y;
  s.nyquist_wavelength = 2 * std::max(m.dx, m.dy);
  s.Rq_x = sc->height(s.Rq_x);
  s.Rq_y = sc->height(s.Rq_y);
  s.Rdq_x = sc->slope(s.Rdq_x);
  s.Rdq_y = sc->slope(s.Rdq_y);
  s.rms_gradient_fd = sc->slope(s.rms_gradient_fd);
  return s;
}

ProfileScanStats profile_scan_stats(const Profile& p) {
  ProfileScanStats s;
  const std::size_t n = p.size();
  if (n < 2) return s;
  s.sampling_interval = p.length() / double(n - 1);
  s.physical_length = double(n) * s.sampling_interval;
  s.bandwidth_short = s.sampling_interval;
  s.bandwidth_long = s.physical_length;
  s.nyquist_wavelength = 2 * s.sampling_interval;
  return s;
}

Result<double> short_reliability_cutoff(const Profile& p, double tip_radius) {
  if (!(tip_radius > 0) || !std::isfinite(tip_radius))
    return make_error(fmt::format("tip radius must be positive and finite (got {} m)", tip_radius));
  const std::size_t n = p.size();
  if (n < 4) return make_error(fmt::format("profile of {} points: the reliability cutoff needs at least 4", n));
  const double dx = p.length() / double(n - 1);
  return cutoff_along(
      1, n, dx, tip_radius, [&](std::size_t, std::size_t k) { return p.z[k]; }, [&](std::size_t k) { return p.x[k]; });
}

Result<double> short_reliability_cutoff(const Map& m, double tip_radius) {
  if (!(tip_radius > 0) || !std::isfinite(tip_radius))
    return make_error(fmt::format("tip radius must be positive and finite (got {} m)", tip_radius));
  if (auto st = validate(m, "map"); !st) return st.error();
  auto xs = [&](std::size_t i) { return double(i) * m.dx; };
  auto ys = [&](std::size_t j) { return double(j) * m.dy; };
  const double cx =
      m.nx >= 4 ? cutoff_along(
                      m.ny, m.nx, m.dx, tip_radius, [&](std::size_t j, std::size_t i) { return m.at(i, j); }, xs)
                : 0.0;
  const double cy =
      m.ny >= 4 ? cutoff_along(
                      m.nx, m.ny, m.dy, tip_radius, [&](std::size_t i, std::size_t j) { return m.at(i, j); }, ys)
                : 0.0;
  if (std::isnan(cx) || std::isnan(cy)) return std::numeric_limits<double>::quiet_NaN();
  return std::max(cx, cy);
}

}  // namespace frictal
