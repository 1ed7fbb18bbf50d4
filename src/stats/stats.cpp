// Length-weighted statistics of piecewise-linear profiles.
#include "frictal/stats.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace frictal {

namespace {

// The exact integrals in arithmetic type T. Called with double first; extended precision (long
// double: range to about 1e4932 on x86-64) only where double overflows or underflows, so that
// ordinary profiles keep their double results bit for bit.
// Angles = false: mean_slope and max_slope are left 0 (no atan per edge); the other fields are
// the same sums in the same order.
template <class T, bool Angles = true>
ProfileStats profile_stats_in(const Profile& p) {
  ProfileStats s;
  s.points = p.size();
  if (p.size() < 2) return s;
  const T length = static_cast<T>(p.x.back()) - static_cast<T>(p.x.front());
  s.length = static_cast<double>(length);
  if (!(length > 0)) return s;
  // Integrals over each edge of the linear interpolant: int z = dx (z0+z1)/2,
  // int z^2 = dx (z0^2 + z0 z1 + z1^2)/3; vertical edges (dx = 0) contribute nothing.
  T iz = 0, slope2 = 0, slope_angle = 0, max_slope = 0;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const T dx = static_cast<T>(p.x[i + 1]) - static_cast<T>(p.x[i]);
    const T dz = static_cast<T>(p.z[i + 1]) - static_cast<T>(p.z[i]);
    if (dx == 0) {
      if (Angles && dz != 0) max_slope = std::numbers::pi_v<T> / 2;
      continue;
    }
    iz += dx * (static_cast<T>(p.z[i]) + static_cast<T>(p.z[i + 1])) / 2;
    const T m = dz / dx;
    slope2 += dx * m * m;
    if constexpr (Angles) {
      const T a = std::atan(m);
      slope_angle += dx * a;
      max_slope = std::max(max_slope, std::abs(a));
    }
  }
  const T mean = iz / length;
  T var = 0;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const T dx = static_cast<T>(p.x[i + 1]) - static_cast<T>(p.x[i]);
    if (dx == 0) continue;
    const T a = static_cast<T>(p.z[i]) - mean, b = static_cast<T>(p.z[i + 1]) - mean;
    var += dx * (a * a + a * b + b * b) / 3;
  }
  s.mean_height = static_cast<double>(mean);
  s.rms_height = static_cast<double>(std::sqrt(std::max(T(0), var / length)));
  s.rms_slope = static_cast<double>(std::sqrt(slope2 / length));
  s.max_slope = static_cast<double>(max_slope);
  s.mean_slope = static_cast<double>(slope_angle / length);
  return s;
}

template <bool Angles>
ProfileStats profile_stats_with(const Profile& p) {
  ProfileStats s = profile_stats_in<double, Angles>(p);
  if (p.size() < 2) return s;
  // Double loses the answer when a square or a difference overflows (heights near 1e308 give inf
  // or NaN, which max(0, NaN) would turn into a silent 0) or when squares underflow (heights near
  // 1e-300 give rms 0 for a rough profile). Then redo the sums with a wider exponent range; a
  // result that is still beyond double's range comes back as +inf, never as a wrong finite number.
  const auto [lo, hi] = std::minmax_element(p.z.begin(), p.z.end());
  const bool rough = *hi > *lo;
  const bool lost = !std::isfinite(s.length) || !std::isfinite(s.mean_height) || !std::isfinite(s.rms_height) ||
                    !std::isfinite(s.rms_slope) || !std::isfinite(s.mean_slope) || (rough && !(s.rms_height > 0)) ||
                    (rough && !(s.rms_slope > 0));
  if (lost) s = profile_stats_in<long double, Angles>(p);
  return s;
}

}  // namespace

ProfileStats profile_stats(const Profile& p) { return profile_stats_with<true>(p); }

ProfileStats profile_stats_no_angles(const Profile& p) { return profile_stats_with<false>(p); }

double max_slope_angle(const Profile& p) {
  double m = 0;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const double dx = p.x[i + 1] - p.x[i];
    const double dz = p.z[i + 1] - p.z[i];
    if (dx == 0) {
      if (dz != 0) return std::numbers::pi / 2;
      continue;
    }
    m = std::max(m, std::abs(dz / dx));
  }
  return std::atan(m);
}

Histogram histogram(const std::vector<double>& samples, const std::vector<double>& weights, int bins, double lo,
                    double hi) {
  Histogram h;
  if (bins < 1) bins = 1;
  if (!(lo < hi)) {
    lo = std::numeric_limits<double>::infinity();
    hi = -lo;
    for (double v : samples)
      if (std::isfinite(v)) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    if (!(lo <= hi)) {
      lo = 0;
      hi = 1;
    }
    if (lo == hi) {
      const double pad = std::max(1e-12, std::abs(lo) * 1e-6);
      lo -= pad;
      hi += pad;
    }
  }
  h.edges.resize(static_cast<std::size_t>(bins) + 1);
  for (int i = 0; i <= bins; ++i) h.edges[static_cast<std::size_t>(i)] = lo + (hi - lo) * i / bins;
  h.density.assign(static_cast<std::size_t>(bins), 0.0);
  double total = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double v = samples[i];
    const double w = weights.empty() ? 1.0 : weights[i];
    if (!std::isfinite(v) || !(w > 0) || v < lo || v > hi) continue;
    int b = static_cast<int>((v - lo) / (hi - lo) * bins);
    b = std::clamp(b, 0, bins - 1);
    h.density[static_cast<std::size_t>(b)] += w;
    total += w;
  }
  const double width = (hi - lo) / bins;
  if (total > 0)
    for (auto& d : h.density) d /= total * width;
  return h;
}

Histogram slope_distribution(const Profile& p, int bins) {
  std::vector<double> s, w;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const double dx = p.x[i + 1] - p.x[i];
    if (dx <= 0) continue;
    s.push_back(std::atan((p.z[i + 1] - p.z[i]) / dx));
    w.push_back(dx);
  }
  return histogram(s, w, bins);
}

MeanStd weighted_mean_std(const std::vector<double>& samples, const std::vector<double>& weights) {
  double sw = 0, sx = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    if (!std::isfinite(samples[i]) || !(w > 0)) continue;
    sw += w;
    sx += w * samples[i];
  }
  MeanStd r;
  if (!(sw > 0)) return r;
  r.mean = sx / sw;
  double v = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    if (!std::isfinite(samples[i]) || !(w > 0)) continue;
    v += w * (samples[i] - r.mean) * (samples[i] - r.mean);
  }
  r.std = std::sqrt(v / sw);
  return r;
}

}  // namespace frictal
