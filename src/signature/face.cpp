#include "signature/face.hpp"

#include <cmath>
#include <limits>

namespace frictal::detail {

Face::Face(std::vector<double> x, const std::vector<double>& z, double sign) : x_(std::move(x)), sign_(sign) {
  const std::size_t n = x_.size();
  v_.resize(n);
  for (std::size_t i = 0; i < n; ++i) v_[i] = sign * z[i];
  build();
}

Face::Face(std::vector<double> x, std::vector<double>&& z, double sign)
    : x_(std::move(x)), v_(std::move(z)), sign_(sign) {
  for (double& v : v_) v = sign * v;
  build();
}

void Face::build() {
  const std::size_t n = x_.size();
  vmax_ = *std::max_element(v_.begin(), v_.end());
  vmin_ = *std::min_element(v_.begin(), v_.end());
  // Uniform grids get O(1) index lookups.
  if (n >= 2) {
    dx_ = (x_.back() - x_.front()) / static_cast<double>(n - 1);
    uniform_ = dx_ > 0;
    // Uniform within 1e-9 dx, or within a few rounding units of the abscissae themselves: at
    // 10^7 points 1e-9 dx is below the spacing of doubles near x, and a grid written as
    // x0 + i dx (or turned over by rotate180) is off by an ulp or two.
    const double xmag = std::max(std::abs(x_.front()), std::abs(x_.back()));
    const double tol = std::max(1e-9 * dx_, 16 * std::numeric_limits<double>::epsilon() * xmag);
    grid_tol_ = tol;
    for (std::size_t i = 1; i < n && uniform_; ++i)
      if (std::abs(x_[i] - (x_.front() + dx_ * static_cast<double>(i))) > tol) uniform_ = false;
    inv_dx_ = uniform_ ? 1.0 / dx_ : 0.0;
  }
  const std::size_t nb = (n + kBlock - 1) / kBlock;
  std::vector<double> level(nb, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < n; ++i) level[i / kBlock] = std::max(level[i / kBlock], v_[i]);
  st_.push_back(std::move(level));
  for (std::size_t w = 1; 2 * w <= nb; w *= 2) {
    const auto& prev = st_.back();
    std::vector<double> next(nb - 2 * w + 1);
    for (std::size_t b = 0; b < next.size(); ++b) next[b] = std::max(prev[b], prev[b + w]);
    st_.push_back(std::move(next));
  }
  tree_ = AlignedMax(v_);
}

AlignedMax::AlignedMax(const std::vector<double>& v) {
  const std::size_t n = v.size();
  std::vector<double> level((n + kBlock - 1) / kBlock, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < n; ++i) level[i >> kBlockShift] = std::max(level[i >> kBlockShift], v[i]);
  lv_.push_back(std::move(level));
  while (lv_.back().size() > 1) {
    const auto& prev = lv_.back();
    std::vector<double> next((prev.size() + 1) / 2);
    for (std::size_t q = 0; q < next.size(); ++q)
      next[q] = (2 * q + 1 < prev.size()) ? std::max(prev[2 * q], prev[2 * q + 1]) : prev[2 * q];
    lv_.push_back(std::move(next));
  }
}

TiltedMax::TiltedMax(const std::vector<double>& v) {
  const std::size_t n = v.size();
  if (n == 0) return;
  // Rounding: a computed term t = a + b (or a - b, a * b) is within eps (|a| + |b|) of the exact
  // one; each term below is rounded up by 4 eps times the sum of its operands' magnitudes, so c
  // stays an upper bound of the exact maxima for the stored tau.
  constexpr double eps = std::numeric_limits<double>::epsilon();
  auto chord = [&](std::size_t start, std::size_t last) {
    return last > start ? (v[last] - v[start]) / static_cast<double>(last - start) : 0.0;
  };
  double mag = 0;
  auto keep = [&](const Line& ln, std::size_t len) {
    mag = std::max(mag, std::abs(ln.c) + std::abs(ln.tau) * static_cast<double>(len));
    return ln;
  };
  std::vector<Line> level((n + kBlock - 1) / kBlock);
  for (std::size_t q = 0; q < level.size(); ++q) {
    const std::size_t start = q << kBlockShift, last = std::min(start + kBlock, n) - 1;
    const double tau = chord(start, last);
    double c = -std::numeric_limits<double>::infinity(), err = 0;
    for (std::size_t i = start; i <= last; ++i) {
      const double tk = tau * static_cast<double>(i - start);
      c = std::max(c, v[i] - tk);
      err = std::max(err, std::abs(v[i]) + std::abs(tk));
    }
    level[q] = keep({tau, c + 4 * eps * err}, last - start);
  }
  lv_.push_back(std::move(level));
  for (unsigned l = 1; lv_.back().size() > 1; ++l) {
    const auto& prev = lv_.back();
    const unsigned sh = kBlockShift + l;
    std::vector<Line> next((prev.size() + 1) / 2);
    for (std::size_t q = 0; q < next.size(); ++q) {
      const std::size_t start = q << sh, last = std::min(start + (std::size_t{1} << sh), n) - 1;
      const double tau = chord(start, last);
      // The child's line minus the parent's is linear: its maximum over the child is at an end.
      double c = -std::numeric_limits<double>::infinity(), err = 0;
      for (std::size_t k = 2 * q; k < std::min(2 * q + 2, prev.size()); ++k) {
        const std::size_t cs = k << (sh - 1), cl = std::min(cs + (std::size_t{1} << (sh - 1)), n) - 1;
        for (std::size_t i : {cs, cl}) {
          const double a = prev[k].tau * static_cast<double>(i - cs), b = tau * static_cast<double>(i - start);
          c = std::max(c, (prev[k].c + a) - b);
          err = std::max(err, std::abs(prev[k].c) + 2 * std::abs(a) + 2 * std::abs(b));
        }
      }
      next[q] = keep({tau, c + 4 * eps * err}, last - start);
    }
    lv_.push_back(std::move(next));
  }
  mag_ = mag;
}

std::size_t Face::floor_index(double u) const {
  if (u <= x_.front()) return 0;
  if (u >= x_.back()) return x_.size() - 1;
  if (uniform_) {
    auto i = static_cast<std::size_t>((u - x_.front()) * inv_dx_);
    if (i >= x_.size()) i = x_.size() - 1;
    while (i + 1 < x_.size() && x_[i + 1] <= u) ++i;
    while (i > 0 && x_[i] > u) --i;
    return i;
  }
  auto it = std::upper_bound(x_.begin(), x_.end(), u);
  return static_cast<std::size_t>(it - x_.begin()) - 1;
}

std::size_t Face::ceil_index(double u) const {
  if (u <= x_.front()) return 0;
  if (u >= x_.back()) return x_.size() - 1;
  if (uniform_) {
    auto i = static_cast<std::size_t>((u - x_.front()) * inv_dx_);
    if (i >= x_.size()) i = x_.size() - 1;
    while (i + 1 < x_.size() && x_[i] < u) ++i;
    while (i > 0 && x_[i - 1] >= u) --i;
    return i;
  }
  auto it = std::lower_bound(x_.begin(), x_.end(), u);
  return static_cast<std::size_t>(it - x_.begin());
}

double Face::value(double u, double xtol) const {
  std::size_t k = ceil_index(u - xtol);
  if (x_[k] >= u - xtol && x_[k] <= u + xtol) {
    // On a vertex group (within xtol: an event offset computed as x_f - x_g rounds, so x_f - s
    // can miss x_g by an ulp, and a jump's extreme value must not be lost to that).
    const double xv = x_[k];
    double m = v_[k];
    for (std::size_t j = k + 1; j < x_.size() && x_[j] == xv; ++j) m = std::max(m, v_[j]);
    return m;
  }
  k = ceil_index(u);
  if (k == 0) return v_[0];
  const double t = (u - x_[k - 1]) / (x_[k] - x_[k - 1]);
  return v_[k - 1] + t * (v_[k] - v_[k - 1]);
}

std::size_t Face::ceil_from(double u, std::size_t& k) const {
  const std::size_t n = x_.size();
  if (k == Cursor::kUnset) {
    // Inside the grid ceil_index is lower_bound (O(1) on a uniform grid); at the ends search.
    k = u > x_.front() && u < x_.back()
            ? ceil_index(u)
            : static_cast<std::size_t>(std::lower_bound(x_.begin(), x_.end(), u) - x_.begin());
  }
  // Walk a few points, then finish with a binary search over the rest: lower_bound either way.
  for (int step = 0; k < n && x_[k] < u; ++k, ++step)
    if (step == 8) {
      k = static_cast<std::size_t>(std::lower_bound(x_.begin() + static_cast<std::ptrdiff_t>(k), x_.end(), u) -
                                   x_.begin());
      break;
    }
  // ceil_index's ends (a vertical jump at the right end still gives the last index).
  if (u <= x_.front()) return 0;
  if (u >= x_.back()) return n - 1;
  return k;
}

double Face::value_walk(double u, double xtol, Cursor& c) const {
  std::size_t k = ceil_from(u - xtol, c.tol);
  if (x_[k] >= u - xtol && x_[k] <= u + xtol) {
    const double xv = x_[k];
    double m = v_[k];
    for (std::size_t j = k + 1; j < x_.size() && x_[j] == xv; ++j) m = std::max(m, v_[j]);
    return m;
  }
  c.at = c.at == Cursor::kUnset ? c.tol : std::max(c.at, c.tol);
  k = ceil_from(u, c.at);
  if (k == 0) return v_[0];
  const double t = (u - x_[k - 1]) / (x_[k] - x_[k - 1]);
  return v_[k - 1] + t * (v_[k] - v_[k - 1]);
}

double Face::range_max(std::size_t i0, std::size_t i1) const {
  std::size_t b0 = i0 / kBlock, b1 = i1 / kBlock;
  if (b0 == b1) {
    // Small ranges inside one block: exact.
    double m = v_[i0];
    for (std::size_t i = i0 + 1; i <= i1; ++i) m = std::max(m, v_[i]);
    return m;
  }
  if (st_.empty()) {
    // Bottom-up over the aligned maxima: the max over blocks b0..b1, the same value as below.
    double m = -std::numeric_limits<double>::infinity();
    auto lo = static_cast<std::ptrdiff_t>(b0), hi = static_cast<std::ptrdiff_t>(b1);
    for (std::size_t l = 0; lo <= hi; ++l, lo >>= 1, hi = (hi >> 1)) {
      const auto& lv = tree_.level(l);
      if (lo & 1) m = std::max(m, lv[static_cast<std::size_t>(lo++)]);
      if (!(hi & 1)) m = std::max(m, lv[static_cast<std::size_t>(hi--)]);
      if (hi < lo) break;
    }
    return m;
  }
  std::size_t len = b1 - b0 + 1;
  std::size_t k = 0;
  while ((std::size_t{2} << k) <= len) ++k;
  return std::max(st_[k][b0], st_[k][b1 + 1 - (std::size_t{1} << k)]);
}

Position Face::locate(double u, double xtol) const {
  Position p;
  std::size_t k = ceil_index(u);
  std::size_t j = k;
  // Nearest point within tolerance on either side.
  if (k > 0 && std::abs(x_[k - 1] - u) <= xtol && std::abs(x_[k - 1] - u) < std::abs(x_[k] - u)) j = k - 1;
  if (std::abs(x_[j] - u) <= xtol) {
    std::size_t a = j, b = j;
    while (a > 0 && x_[a - 1] == x_[j]) --a;
    while (b + 1 < x_.size() && x_[b + 1] == x_[j]) ++b;
    p.vertex = true;
    p.first = a;
    p.last = b;
    return p;
  }
  p.edge = (k == 0) ? 0 : k - 1;
  return p;
}

double Face::edge_angle(std::ptrdiff_t e) const {
  if (e < 0 || static_cast<std::size_t>(e) + 1 >= x_.size()) return std::numeric_limits<double>::quiet_NaN();
  const auto i = static_cast<std::size_t>(e);
  return std::atan2(sign_ * (v_[i + 1] - v_[i]), x_[i + 1] - x_[i]);
}

}  // namespace frictal::detail
