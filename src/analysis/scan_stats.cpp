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

/// Largest curvature over lines for the stencil of k points each side; -inf if no triple.
/// kappa = 2 [(zc - zb) / (xc - xb) - (zb - za) / (xb - xa)] / (xc - xa), which is
/// (za - 2 zb + zc) / h^2 on a uniform grid.
template <class At, class Xat>
double max_curvature(std::size_t lines, std::size_t n, std::size_t k, At at, Xat xat) {
  double best = -std::numeric_limits<double>::infinity();
  for (std::size_t l = 0; l < lines; ++l)
    for (std::size_t i = k; i + k < n; ++i) {
      const double a = at(l, i - k), b = at(l, i), c = at(l, i + k);
      if (std::isnan(a) || std::isnan(b) || std::isnan(c)) continue;
      const double xa = xat(i - k), xb = xat(i), xc = xat(i + k);
      if (!(xb > xa) || !(xc > xb)) continue;
      best = std::max(best, 2 * ((c - b) / (xc - xb) - (b - a) / (xb - xa)) / (xc - xa));
    }
  return best;
}

/// The cutoff along one direction (see the header); stencil distance h = k x spacing.
template <class At, class Xat>
double cutoff_along(std::size_t lines, std::size_t n, double spacing, double radius, At at, Xat xat) {
  const double limit = 1 / radius;
  double prev_h = 0, prev_c = 0;
  bool any = false;
  for (std::size_t k = 1; 4 * k <= n; ++k) {
    const double h = double(k) * spacing, c = max_curvature(lines, n, k, at, xat);
    if (c == -std::numeric_limits<double>::infinity()) continue;
    if (c <= limit) {
      if (!any) return 0.0;  // reliable at the finest stencil already
      // Linear interpolation in h between the last failing and this passing distance.
      return prev_h + (h - prev_h) * (prev_c - limit) / (prev_c - c);
    }
    any = true;
    prev_h = h;
    prev_c = c;
  }
  return std::numeric_limits<double>::quiet_NaN();
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
