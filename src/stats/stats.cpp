// Length-weighted statistics of piecewise-linear profiles.
#include "frictal/stats.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace frictal {

ProfileStats profile_stats(const Profile& p) {
  ProfileStats s;
  s.points = p.size();
  if (p.size() < 2) return s;
  s.length = p.length();
  if (!(s.length > 0)) return s;
  // Integrals over each edge of the linear interpolant: int z = dx (z0+z1)/2,
  // int z^2 = dx (z0^2 + z0 z1 + z1^2)/3; vertical edges (dx = 0) contribute nothing.
  double iz = 0, slope2 = 0, slope_angle = 0, max_slope = 0;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const double dx = p.x[i + 1] - p.x[i], dz = p.z[i + 1] - p.z[i];
    if (dx == 0) {
      if (dz != 0) max_slope = std::numbers::pi / 2;
      continue;
    }
    iz += dx * (p.z[i] + p.z[i + 1]) / 2;
    const double m = dz / dx;
    slope2 += dx * m * m;
    slope_angle += dx * std::atan(m);
    max_slope = std::max(max_slope, std::abs(std::atan(m)));
  }
  s.mean_height = iz / s.length;
  double var = 0;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const double dx = p.x[i + 1] - p.x[i];
    if (dx == 0) continue;
    const double a = p.z[i] - s.mean_height, b = p.z[i + 1] - s.mean_height;
    var += dx * (a * a + a * b + b * b) / 3;
  }
  s.rms_height = std::sqrt(std::max(0.0, var / s.length));
  s.rms_slope = std::sqrt(slope2 / s.length);
  s.max_slope = max_slope;
  s.mean_slope = slope_angle / s.length;
  return s;
}

Histogram histogram(const std::vector<double>& samples, const std::vector<double>& weights, int bins,
                    double lo, double hi) {
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
