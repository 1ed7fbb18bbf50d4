// Fractal dimension: divider (ruler) method along curves, box counting, PSD slope, and the
// Koch similarity dimension of Eq. 13.
#include <fmt/core.h>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_set>

#include "frictal/analysis.hpp"
#include "frictal/fractal.hpp"

namespace frictal {

namespace {

struct Line {
  double slope = 0, intercept = 0, r2 = 0;
};

Line fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = double(x.size());
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= n;
  my /= n;
  double sxx = 0, sxy = 0, syy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  Line l;
  l.slope = sxx > 0 ? sxy / sxx : 0;
  l.intercept = my - l.slope * mx;
  l.r2 = (sxx > 0 && syy > 0) ? sxy * sxy / (sxx * syy) : 1.0;
  return l;
}

std::vector<double> log_space(double lo, double hi, int n) {
  std::vector<double> v(n);
  for (int k = 0; k < n; ++k) v[k] = std::exp(std::log(lo) + (std::log(hi) - std::log(lo)) * k / double(n - 1));
  return v;
}

double median_edge(const Curve& c) {
  std::vector<double> e;
  for (std::size_t k = 1; k < c.size(); ++k) {
    double l = std::hypot(c.x[k] - c.x[k - 1], c.z[k] - c.z[k - 1]);
    if (l > 0) e.push_back(l);
  }
  if (e.empty()) return 0;
  std::nth_element(e.begin(), e.begin() + e.size() / 2, e.end());
  return e[e.size() / 2];
}

Status check_scales(double lo, double hi, int n, const char* what) {
  if (!(lo > 0) || !(hi > lo) || !std::isfinite(hi))
    return make_error(fmt::format("{} range [{}, {}] m must satisfy 0 < min < max", what, lo, hi));
  if (n < 3 || n > 1000) return make_error(fmt::format("{}: between 3 and 1000 scales needed (got {})", what, n));
  return Ok{};
}

}  // namespace

double divider_length(const Curve& c, double eps) {
  const std::size_t n = c.size();
  if (n < 2 || !(eps > 0)) return 0;
  double px = c.x[0], pz = c.z[0];
  std::size_t seg = 0;      // the walker is on edge [seg, seg + 1], at (px, pz)
  double ax = px, az = pz;  // start of the remaining part of that edge
  std::size_t steps = 0;
  const double e2 = eps * eps;
  while (true) {
    bool found = false;
    for (std::size_t j = seg; j + 1 < n; ++j) {
      const double sx = j == seg ? ax : c.x[j], sz = j == seg ? az : c.z[j];
      const double bx = c.x[j + 1], bz = c.z[j + 1];
      const double dbx = bx - px, dbz = bz - pz;
      if (dbx * dbx + dbz * dbz < e2) continue;
      // |S + t (B - S) - P| = eps with S inside the circle, B outside: the larger root.
      const double dx = bx - sx, dz = bz - sz, fx = sx - px, fz = sz - pz;
      const double A = dx * dx + dz * dz, B = 2 * (fx * dx + fz * dz), C = fx * fx + fz * fz - e2;
      const double disc = std::max(0.0, B * B - 4 * A * C);
      double t = (-B + std::sqrt(disc)) / (2 * A);
      t = std::clamp(t, 0.0, 1.0);
      px = sx + t * dx;
      pz = sz + t * dz;
      ax = px;
      az = pz;
      seg = j;
      ++steps;
      found = true;
      break;
    }
    if (!found) break;
    if (steps > (std::size_t(1) << 40)) break;
  }
  return double(steps) * eps + std::hypot(c.x[n - 1] - px, c.z[n - 1] - pz);
}

Result<FractalFit> divider_dimension(const Curve& c, const DividerOptions& o) {
  if (auto s = validate(c, "curve"); !s) return s.error();
  const double span = std::hypot(c.x.back() - c.x.front(), c.z.back() - c.z.front());
  double lo = o.ruler_min > 0 ? o.ruler_min : median_edge(c);
  double hi = o.ruler_max > 0 ? o.ruler_max : 0.25 * span;
  if (auto s = check_scales(lo, hi, o.rulers, "divider: ruler"); !s) return s.error();
  FractalFit f;
  f.scales = log_space(lo, hi, o.rulers);
  std::vector<double> lx, ly;
  for (double e : f.scales) {
    double L = divider_length(c, e);
    f.values.push_back(L);
    lx.push_back(std::log(e));
    ly.push_back(std::log(L));
  }
  Line l = fit_line(lx, ly);
  f.slope = l.slope;
  f.intercept = l.intercept;
  f.r_squared = l.r2;
  f.dimension = 1 - l.slope;
  f.scale_min = lo;
  f.scale_max = hi;
  return f;
}

Result<FractalFit> box_dimension(const Curve& c, const BoxOptions& o) {
  if (auto s = validate(c, "curve"); !s) return s.error();
  double xmin = *std::min_element(c.x.begin(), c.x.end()), zmin = *std::min_element(c.z.begin(), c.z.end());
  double xmax = *std::max_element(c.x.begin(), c.x.end()), zmax = *std::max_element(c.z.begin(), c.z.end());
  const double extent = std::max(xmax - xmin, zmax - zmin);
  double lo = o.box_min > 0 ? o.box_min : median_edge(c);
  double hi = o.box_max > 0 ? o.box_max : 0.25 * extent;
  if (auto s = check_scales(lo, hi, o.sizes, "box counting: box"); !s) return s.error();
  // Bound the work: the curve's length / smallest box must stay reasonable.
  double length = 0;
  for (std::size_t k = 1; k < c.size(); ++k) length += std::hypot(c.x[k] - c.x[k - 1], c.z[k] - c.z[k - 1]);
  if (length / lo + double(c.size()) > 5e8)
    return make_error(fmt::format("box counting: smallest box {} m is too small for a curve {} m long", lo, length));
  FractalFit f;
  f.scales = log_space(lo, hi, o.sizes);
  std::vector<double> lx, ly;
  for (double e : f.scales) {
    std::unordered_set<std::uint64_t> cells;
    auto key = [](long long i, long long j) { return (std::uint64_t(std::uint32_t(i)) << 32) | std::uint32_t(j); };
    for (std::size_t k = 0; k + 1 < c.size(); ++k) {
      // Walk the edge in sub-steps of at most e/4, marking the cells of the points visited;
      // a quarter box is fine enough to catch every crossed cell except corner grazes.
      double ax = (c.x[k] - xmin) / e, az = (c.z[k] - zmin) / e;
      double bx = (c.x[k + 1] - xmin) / e, bz = (c.z[k + 1] - zmin) / e;
      std::size_t steps = std::size_t(std::ceil(std::hypot(bx - ax, bz - az) * 4)) + 1;
      for (std::size_t s = 0; s <= steps; ++s) {
        double t = double(s) / double(steps);
        cells.insert(key((long long)std::floor(ax + t * (bx - ax)), (long long)std::floor(az + t * (bz - az))));
      }
    }
    f.values.push_back(double(cells.size()));
    lx.push_back(std::log(e));
    ly.push_back(std::log(double(cells.size())));
  }
  Line l = fit_line(lx, ly);
  f.slope = l.slope;
  f.intercept = l.intercept;
  f.r_squared = l.r2;
  f.dimension = -l.slope;
  f.scale_min = lo;
  f.scale_max = hi;
  return f;
}

Result<FractalFit> psd_dimension(const Profile& p, const PsdFitOptions& o) {
  // End matching: subtract the line through the first and last points so that the profile's
  // periodic extension has no jump; a jump (or a trend) leaks a q^-2 spectrum that would
  // otherwise flatten the fit towards D = 1.5.
  if (auto s = validate(p, "profile"); !s) return s.error();
  Profile m = p;
  for (std::size_t k = 0; k < m.size(); ++k)
    m.z[k] -= p.z.front() + (p.z.back() - p.z.front()) * (p.x[k] - p.x_min()) / p.length();
  auto sp = power_spectrum(m);
  if (!sp) return sp.error();
  if (sp->q.size() < 4) return make_error("PSD fit: the profile has too few points (need at least 8)");
  double qlo = o.q_min > 0 ? o.q_min : sp->q[1];
  double qhi = o.q_max > 0 ? o.q_max : 0.25 * sp->q.back();
  if (!(qhi > qlo)) return make_error(fmt::format("PSD fit: wavenumber range [{}, {}] rad/m is empty", qlo, qhi));
  if (o.bins_per_decade < 1 || o.bins_per_decade > 1000)
    return make_error("PSD fit: bins_per_decade must be in 1..1000");
  // Average C in log-spaced bins so that the many high-q values do not dominate the fit.
  const double w = std::log(10.0) / o.bins_per_decade;
  std::vector<double> lq, lc;
  FractalFit f;
  std::size_t k = 0;
  while (k < sp->q.size() && sp->q[k] < qlo * (1 - 1e-12)) ++k;
  while (k < sp->q.size() && sp->q[k] <= qhi * (1 + 1e-12)) {
    const double start = std::log(sp->q[k]);
    double sq = 0, sc = 0;
    int cnt = 0;
    while (k < sp->q.size() && sp->q[k] <= qhi * (1 + 1e-12) && std::log(sp->q[k]) < start + w) {
      sq += std::log(sp->q[k]);
      sc += sp->psd[k];
      ++cnt;
      ++k;
    }
    if (sc > 0) {
      lq.push_back(sq / cnt);
      lc.push_back(std::log(sc / cnt));
      f.scales.push_back(2 * std::numbers::pi / std::exp(sq / cnt));
      f.values.push_back(sc / cnt);
    }
  }
  if (lq.size() < 3) return make_error("PSD fit: fewer than 3 log bins in the wavenumber range");
  Line l = fit_line(lq, lc);
  f.slope = l.slope;
  f.intercept = l.intercept;
  f.r_squared = l.r2;
  f.dimension = (5 + l.slope) / 2;
  f.scale_min = 2 * std::numbers::pi / qhi;
  f.scale_max = 2 * std::numbers::pi / qlo;
  return f;
}

Result<double> koch_dimension(double alpha) {
  if (!(alpha >= 0) || alpha > std::numbers::pi / 3 + 1e-12)
    return make_error(fmt::format("Koch angle {} rad out of range [0, pi/3]", alpha));
  const double b = 1 / (6 * std::cos(alpha));
  auto f = [&](double D) { return 2 * std::pow(1.0 / 3, D) + 2 * std::pow(b, D) - 1; };
  double lo = 1, hi = 2;  // f(1) >= 0 >= f(2) for alpha in [0, pi/3]; f decreases in D
  for (int it = 0; it < 200 && hi - lo > 1e-16; ++it) {
    double mid = 0.5 * (lo + hi);
    (f(mid) > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace frictal
