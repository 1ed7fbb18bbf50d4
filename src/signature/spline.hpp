// Private: natural cubic splines for the paper's spline contact slopes (Sec. V B).
#pragma once

#include <optional>
#include <vector>

namespace frictal::detail {

/// Second derivatives at the knots of the natural cubic spline through (x, v); nullopt if x is
/// not strictly increasing.
std::optional<std::vector<double>> spline_second_derivatives(const std::vector<double>& x,
                                                             const std::vector<double>& v);
/// dz/dx of the spline at u, with z = sign * v and M from spline_second_derivatives(x, v).
double spline_slope(const std::vector<double>& x, const std::vector<double>& M, double sign,
                    const std::vector<double>& v, double u);

}  // namespace frictal::detail
