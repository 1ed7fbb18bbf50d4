#include "signature/spline.hpp"

#include <algorithm>

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
