#include "signature/spline.hpp"

#include <algorithm>

#include <fmt/core.h>

#include "frictal/signature.hpp"

namespace frictal::detail {

std::optional<std::vector<double>> spline_second_derivatives(const std::vector<double>& x,
                                                             const std::vector<double>& v) {
  const std::size_t n = x.size();
  for (std::size_t i = 1; i < n; ++i)
    if (!(x[i] > x[i - 1])) return std::nullopt;
  std::vector<double> M(n, 0.0);
  if (n < 3) return M;
  // Tridiagonal system (Thomas algorithm) for the interior second derivatives, M_0 = M_n-1 = 0.
  std::vector<double> c(n, 0.0), d(n, 0.0);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h0 = x[i] - x[i - 1], h1 = x[i + 1] - x[i];
    const double a = h0 / 6, b = (h0 + h1) / 3, cc = h1 / 6;
    const double r = (v[i + 1] - v[i]) / h1 - (v[i] - v[i - 1]) / h0;
    const double denom = b - a * c[i - 1];
    c[i] = cc / denom;
    d[i] = (r - a * d[i - 1]) / denom;
  }
  for (std::size_t i = n - 2; i >= 1; --i) {
    M[i] = d[i] - c[i] * M[i + 1];
    if (i == 1) break;
  }
  return M;
}

double spline_slope(const std::vector<double>& x, const std::vector<double>& M, double sign,
                    const std::vector<double>& v, double u) {
  auto it = std::upper_bound(x.begin(), x.end(), u);
  std::size_t i = (it == x.begin()) ? 0 : static_cast<std::size_t>(it - x.begin()) - 1;
  if (i + 1 >= x.size()) i = x.size() - 2;
  const double h = x[i + 1] - x[i];
  const double a = x[i + 1] - u, b = u - x[i];
  const double d =
      -M[i] * a * a / (2 * h) + M[i + 1] * b * b / (2 * h) + (v[i + 1] - v[i]) / h - (M[i + 1] - M[i]) * h / 6;
  return sign * d;
}

}  // namespace frictal::detail

namespace frictal {

Result<SplineSamples> sample_spline(const Profile& p, int per_interval) {
  if (p.size() < 2) return make_error(fmt::format("spline: a profile of {} points (at least 2 needed)", p.size()));
  if (per_interval < 1 || per_interval > 10000)
    return make_error(fmt::format("spline: {} samples per interval (expected 1..10000)", per_interval));
  const auto M = detail::spline_second_derivatives(p.x, p.z);
  if (!M) return make_error("spline: the profile's x must increase strictly (it has a vertical step)");
  SplineSamples out;
  const std::size_t n = (p.size() - 1) * static_cast<std::size_t>(per_interval) + 1;
  out.x.reserve(n);
  out.z.reserve(n);
  out.slope.reserve(n);
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const double x0 = p.x[i], h = p.x[i + 1] - x0;
    for (int k = 0; k < per_interval; ++k) {
      const double u = x0 + h * k / per_interval;
      const double a = p.x[i + 1] - u, b = u - x0;
      out.x.push_back(u);
      // S(u) = [M_i a^3 + M_i+1 b^3] / 6h + (z_i / h - M_i h / 6) a + (z_i+1 / h - M_i+1 h / 6) b
      out.z.push_back(((*M)[i] * a * a * a + (*M)[i + 1] * b * b * b) / (6 * h) + (p.z[i] / h - (*M)[i] * h / 6) * a +
                      (p.z[i + 1] / h - (*M)[i + 1] * h / 6) * b);
      out.slope.push_back(detail::spline_slope(p.x, *M, 1.0, p.z, u));
    }
  }
  out.x.push_back(p.x.back());
  out.z.push_back(p.z.back());
  out.slope.push_back(detail::spline_slope(p.x, *M, 1.0, p.z, p.x.back()));
  return out;
}

}  // namespace frictal
