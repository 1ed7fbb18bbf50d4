// The loaded lift of a profile pair (frictal/load.hpp): projected Hertzian asperity contacts at
// the local maxima of the composite d_s(x) = f(x) - g(x - s), the block's height under the load
// from the balance of their vertical forces, and the lift whose slope is the force-resolved
// contact slope, integrated over the rigid lift's pieces.
#include "frictal/load.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/core.h>

#include "util/parallel.hpp"

namespace frictal {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// The refinement of the loaded lift's integral (loaded_lift, pass 2): at most this many halvings
// of a piece of the rigid lift, until the excess slope between two samples is straight to this
// (unitless; 1e-4 in slope is 0.006 deg of hold angle).
constexpr int kRefineDepth = 12;
constexpr double kRefineSlope = 1e-3;

// A surface's vertices with the first and second derivatives of the quadratic through each
// vertex and its two neighbours (ends: the end edge's slope and the neighbour's curvature; a
// vertical jump gives the slope of the edge beside it and no curvature).
struct Fitted {
  std::vector<double> x, z, d1, d2;
};

Fitted fitted(const Profile& p, double shift) {
  Fitted f;
  const std::size_t n = p.x.size();
  f.x.resize(n), f.z = p.z, f.d1.assign(n, 0), f.d2.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) f.x[i] = p.x[i] + shift;
  auto edge = [&](std::size_t i) {  // slope of edge i -> i + 1, 0 across a jump
    const double w = p.x[i + 1] - p.x[i];
    return w > 0 ? (p.z[i + 1] - p.z[i]) / w : 0.0;
  };
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double w0 = p.x[i] - p.x[i - 1], w1 = p.x[i + 1] - p.x[i];
    const double s0 = edge(i - 1), s1 = edge(i);
    if (w0 > 0 && w1 > 0) {
      f.d1[i] = (s0 * w1 + s1 * w0) / (w0 + w1);
      f.d2[i] = 2 * (s1 - s0) / (w0 + w1);
    } else {
      f.d1[i] = w0 > 0 ? s0 : s1;
    }
  }
  if (n >= 2) {
    f.d1[0] = edge(0);
    f.d1[n - 1] = edge(n - 2);
  }
  if (n >= 3) {
    f.d2[0] = f.d2[1];
    f.d2[n - 1] = f.d2[n - 2];
  }
  return f;
}

// Index k of the edge [x_k, x_(k+1)] that holds x (clamped to the first and last edges).
std::size_t edge_of(const std::vector<double>& xs, double x) {
  const auto it = std::upper_bound(xs.begin(), xs.end(), x);
  const std::size_t k = std::size_t(it - xs.begin());
  return std::clamp<std::size_t>(k, 1, xs.size() - 1) - 1;
}

// std::upper_bound over xs[lo, hi) for x, started where a mean spacing (1 / inv) puts x and
// widened by doubling steps to a bracket, then searched: the same position as a search of the
// whole range, in a few steps on evenly spaced vertices instead of log2 of their number.
std::size_t upper_near(const std::vector<double>& xs, double x, std::size_t lo, std::size_t hi, double inv) {
  if (lo >= hi) return lo;
  const double t = (x - xs.front()) * inv;
  const std::size_t g = !(t > double(lo)) ? lo : t >= double(hi - 1) ? hi - 1 : std::size_t(t);
  std::size_t a = g, b = g;  // the position lies in [a, b]
  if (xs[g] <= x) {
    a = b = g + 1;
    for (std::size_t step = 1; b < hi && xs[b] <= x; step *= 2) a = b + 1, b = std::min(hi, b + step);
  } else {
    for (std::size_t step = 1; a > lo && xs[a - 1] > x; step *= 2) b = a - 1, a = b > lo + step ? b - step : lo;
  }
  return std::size_t(std::upper_bound(xs.begin() + std::ptrdiff_t(a), xs.begin() + std::ptrdiff_t(b), x) - xs.begin());
}

// edge_of(xs, x) by upper_near over the whole of xs.
std::size_t edge_near(const std::vector<double>& xs, double x, double inv) {
  return std::clamp<std::size_t>(upper_near(xs, x, 0, xs.size(), inv), 1, xs.size() - 1) - 1;
}

double lerp_at(const std::vector<double>& xs, const std::vector<double>& v, std::size_t k, double x) {
  const double w = xs[k + 1] - xs[k];
  if (!(w > 0)) return v[k + 1];
  const double t = std::clamp((x - xs[k]) / w, 0.0, 1.0);
  return v[k] + t * (v[k + 1] - v[k]);
}

// Range maximum of the lower heights over vertex indices [i0, i1]: a sparse table over blocks
// of kBlock vertices and a scan of the partial blocks at the ends.
class RangeMax {
 public:
  static constexpr std::size_t kBlock = 16;
  explicit RangeMax(const std::vector<double>& z) : z_(z) {
    const std::size_t nb = (z.size() + kBlock - 1) / kBlock;
    std::vector<double> base(nb, -kInf);
    for (std::size_t i = 0; i < z.size(); ++i) base[i / kBlock] = std::max(base[i / kBlock], z[i]);
    table_.push_back(std::move(base));
    for (std::size_t w = 2; w <= nb; w *= 2) {
      const std::vector<double>& prev = table_.back();
      std::vector<double> next(nb - w + 1);
      for (std::size_t b = 0; b + w <= nb; ++b) next[b] = std::max(prev[b], prev[b + w / 2]);
      table_.push_back(std::move(next));
    }
  }
  double max(std::size_t i0, std::size_t i1) const {
    double m = -kInf;
    const std::size_t b0 = (i0 + kBlock - 1) / kBlock, b1 = (i1 + 1) / kBlock;  // whole blocks [b0, b1)
    if (b0 >= b1) {
      for (std::size_t i = i0; i <= i1; ++i) m = std::max(m, z_[i]);
      return m;
    }
    for (std::size_t i = i0; i < b0 * kBlock; ++i) m = std::max(m, z_[i]);
    for (std::size_t i = b1 * kBlock; i <= i1; ++i) m = std::max(m, z_[i]);
    std::size_t level = 0;
    while ((std::size_t(2) << level) <= b1 - b0) ++level;
    const std::vector<double>& t = table_[level];
    return std::max({m, t[b0], t[b1 - (std::size_t(1) << level)]});
  }

 private:
  const std::vector<double>& z_;
  std::vector<std::vector<double>> table_;
};

// The pair prepared once for every offset.
class Pair {
 public:
  static constexpr std::size_t kFine = 64, kCoarse = 2048;
  static constexpr double kOvershoot = 0.02;  // of the pair's height range (unitless)

  Pair(const Profile& lower, const Profile& upper, double modulus, double max_radius, bool prune = true)
      : prune_(prune),
        f_(fitted(lower, 0)),
        g_(fitted(upper, lower.x.front() - upper.x.front())),
        fmax_(f_.z),
        modulus_(modulus),
        max_radius_(max_radius) {
    fine_min_ = chunk_min(kFine);
    coarse_min_ = chunk_min(kCoarse);
    factor();
    auto reciprocal_spacing = [](const std::vector<double>& x) {
      const double r = double(x.size() - 1) / (x.back() - x.front());
      return std::isfinite(r) ? r : 0.0;
    };
    finvdx_ = reciprocal_spacing(f_.x), ginvdx_ = reciprocal_spacing(g_.x);
    ginvw_.assign(g_.x.size(), -1.0);
    for (std::size_t j = 0; j + 1 < g_.x.size(); ++j) {
      const double w = g_.x[j + 1] - g_.x[j];
      if (w > 0 && std::isfinite(1 / w)) ginvw_[j] = 1 / w;
    }
    double lo = kInf, hi = -kInf;
    for (double z : f_.z) lo = std::min(lo, z), hi = std::max(hi, z);
    for (double z : g_.z) lo = std::min(lo, -z), hi = std::max(hi, -z);
    scale_ = std::max(hi - lo, 1e-300);
  }

  // Overlap of the blocks at offset s, [a, b]; empty (a > b) where they do not overlap.
  std::pair<double, double> overlap(double s) const {
    return {std::max(f_.x.front(), g_.x.front() + s), std::min(f_.x.back(), g_.x.back() + s)};
  }

  // Local maxima of d_s with d >= threshold, appended to `out` in x order (cleared first).
  void candidates(double s, double threshold, std::vector<HertzContact>& out) const {
    out.clear();
    const auto span = overlap(s);
    const double a = span.first, b = span.second;  // named copies: lambdas capture them (clang 14)
    if (!(a < b)) return;
    const std::size_t m = g_.x.size();
    // The upper vertices over [a, b], in chunks [j0, j0 + chunk] (neighbours share a vertex, so
    // that the chunks' spans cover every edge); a chunk is kept where the lower's maximum over
    // its span minus its own lowest height reaches the threshold.
    const std::size_t jlo = edge_near(g_.x, a - s, ginvdx_), jhi = std::min(edge_near(g_.x, b - s, ginvdx_) + 1, m - 1);
    std::size_t region_j0 = 0, region_j1 = 0;
    bool open = false;
    auto flush = [&]() {
      if (open) region(s, threshold, region_j0, region_j1, a, b, out);
      open = false;
    };
    auto keep = [&](std::size_t j0, std::size_t j1) {
      if (open && j0 <= region_j1) {
        region_j1 = std::max(region_j1, j1);
        return;
      }
      flush();
      region_j0 = j0, region_j1 = j1, open = true;
    };
    // The bounds are the polyline's; the spline through its samples may rise above them by a
    // fraction of the local height range.
    const double reach = threshold - kOvershoot * scale_;
    for (std::size_t c0 = (jlo / kCoarse) * kCoarse; c0 < jhi; c0 += kCoarse) {
      const std::size_t c1 = std::min(c0 + kCoarse, m - 1);
      const Span cs = clip(s, c0, c1, a, b, 0, f_.x.size());
      if (bound(cs, coarse_min_[c0 / kCoarse]) < reach) continue;
      // The fine chunks' spans lie in the coarse one's: their searches stay within its vertices.
      for (std::size_t f0 = c0; f0 < c1; f0 += kFine) {
        const std::size_t f1 = std::min(f0 + kFine, m - 1);
        if (f1 < jlo || f0 > jhi) continue;
        if (bound(clip(s, f0, f1, a, b, cs.lo, cs.hi), fine_min_[f0 / kFine]) >= reach) keep(f0, f1);
      }
    }
    flush();
  }

  // The block's state at offset s for the contacts `c` (their touch heights, slopes, radii set)
  // under load W: the height z, and each contact's interference and force.
  struct Balance {
    double height = 0, energy = 0, horizontal = 0, vertical = 0;
  };
  // Each contact's cos, sin and tan theta and stiffness k (stiffness()), for balance() and the
  // excess slopes: one evaluation per contact for every load of a curve, not one per Newton step.
  struct Prepared {
    std::vector<double> cosine, sine, tangent, stiffness;
  };
  void prepare(const std::vector<HertzContact>& c, Prepared& p) const {
    const std::size_t n = c.size();
    p.cosine.resize(n), p.sine.resize(n), p.tangent.resize(n), p.stiffness.resize(n);
    for (std::size_t q = 0; q < n; ++q) {
      p.cosine[q] = std::cos(c[q].slope), p.sine[q] = std::sin(c[q].slope), p.tangent[q] = std::tan(c[q].slope);
      p.stiffness[q] = stiffness(c[q]);
    }
  }
  Balance balance(std::vector<HertzContact>& c, double W) const {
    Prepared p;
    prepare(c, p);
    return balance(c, W, p);
  }
  // `p`: prepare(c).
  Balance balance(std::vector<HertzContact>& c, double W, const Prepared& p) const {
    Balance r;
    double top = -kInf, ktop = 0;
    for (std::size_t q = 0; q < c.size(); ++q)
      if (c[q].touch_height > top) top = c[q].touch_height, ktop = p.stiffness[q];
    // Newton on the vertical balance, convex and decreasing in z, from below (where the top
    // contact alone carries W): monotone, no overshoot.
    double z = top - std::pow(W / ktop, 2.0 / 3.0);
    for (int it = 0; it < 100; ++it) {
      double sum = 0, der = 0;
      for (std::size_t q = 0; q < c.size(); ++q) {
        const double v = c[q].touch_height - z;
        if (v <= 0) continue;
        const double kv = p.stiffness[q] * std::sqrt(v);
        sum += kv * v, der += 1.5 * kv;
      }
      const double f = sum - W;
      if (!(der > 0) || f <= 1e-13 * W) break;
      const double dz = f / der;
      z += dz;
      if (dz <= 1e-15 * scale_) break;
    }
    r.height = z;
    for (std::size_t q = 0; q < c.size(); ++q) {
      HertzContact& k = c[q];
      const double v = std::max(k.touch_height - z, 0.0);
      const double cs = p.cosine[q];
      const double vertical = p.stiffness[q] * v * std::sqrt(v);  // F cos theta
      k.interference = v * cs;
      k.force = vertical / cs;
      r.energy += 0.4 * vertical * v;
      r.horizontal += k.force * p.sine[q];
      r.vertical += vertical;
    }
    return r;
  }

  double scale() const { return scale_; }

 private:
  // k = (4/3) E* sqrt(R) cos^(5/2) theta: F cos theta = k v^(3/2), v the vertical interference.
  double stiffness(const HertzContact& k) const {
    const double cs = std::cos(k.slope);
    return (4.0 / 3.0) * modulus_ * std::sqrt(k.radius) * cs * cs * std::sqrt(cs);
  }

  std::vector<double> chunk_min(std::size_t chunk) const {
    const std::size_t m = g_.x.size();
    std::vector<double> out;
    for (std::size_t j0 = 0; j0 < m; j0 += chunk) {
      double lo = kInf;
      for (std::size_t j = j0; j <= std::min(j0 + chunk, m - 1); ++j) lo = std::min(lo, g_.z[j]);
      out.push_back(lo);
    }
    return out;
  }

  // The span of upper vertices [j0, j1] within [a, b] at offset s, [x0, x1], and the positions
  // [lo, hi] of the lower's first vertices beyond x0 and beyond x1 (std::upper_bound), searched
  // within [lo0, hi0] (the positions of a span that holds this one; the whole lower: 0, n).
  struct Span {
    double x0 = 0, x1 = 0;
    std::size_t lo = 0, hi = 0;
  };
  Span clip(double s, std::size_t j0, std::size_t j1, double a, double b, std::size_t lo0, std::size_t hi0) const {
    Span r;
    r.x0 = std::max(g_.x[j0] + s, a), r.x1 = std::min(g_.x[j1] + s, b);
    if (r.x0 > r.x1) return r;
    r.lo = upper_near(f_.x, r.x0, lo0, hi0, finvdx_);
    r.hi = upper_near(f_.x, r.x1, r.lo, hi0, finvdx_);
    return r;
  }
  // An upper bound of d_s over a span: the lower's maximum over the edges that hold it minus the
  // upper's least height over its vertices, gmin.
  double bound(const Span& sp, double gmin) const {
    if (sp.x0 > sp.x1) return -kInf;
    const std::size_t n = f_.x.size();
    // edge_of(x) from the positions: clamp(position, 1, n - 1) - 1.
    const std::size_t i0 = std::clamp<std::size_t>(sp.lo, 1, n - 1) - 1;
    const std::size_t i1 = std::min(std::clamp<std::size_t>(sp.hi, 1, n - 1), n - 1);
    return fmax_.max(i0, i1) - gmin;
  }

  // The local maxima of d_s over the span of upper vertices [j0, j1] (within [a, b]): the maxima of
  // the natural cubic spline through d_s sampled at the lower vertices (and the overlap's ends),
  // kPad samples beyond the span on each side. A spline's maxima move with s continuously, with
  // their curvature (the polyline's own vertex maxima jump from sample to sample, and with them
  // the radius, at every change of the rigid lift's contact). A region whose spline stays below
  // the threshold (below()) has no contact: its solve is skipped.
  static constexpr std::size_t kPad = 8;
  static constexpr std::size_t kEnd = std::numeric_limits<std::size_t>::max();
  // Rows of a region eliminated with its own factors before the lower's are used: the factors
  // forget the rows above by a factor h0 h1 / diag^2 <= 1/12 per row, so after kWarm rows the
  // region's and the lower's agree to 1/12^20 (4e-22), below the rounding.
  static constexpr std::size_t kWarm = 20;

  // The forward elimination of the spline system along the lower's vertices, from its first
  // interior vertex: row i (h0 = x_i - x_(i-1), h1 = x_(i+1) - x_i) has the diagonal
  // 2 (h0 + h1) - h0 c_(i-1), c_i = h1 / diagonal; kept are c_i, 1 / diagonal and h0 / diagonal.
  // A region whose samples are consecutive vertices eliminates the same rows; its own first rows
  // differ, and that difference fades within kWarm rows. Three coincident vertices restart it.
  void factor() {
    const std::size_t n = f_.x.size();
    fc_.assign(n, 0.0), finv_.assign(n, 0.0), fw_.assign(n, 0.0);
    double c = 0;
    for (std::size_t i = 1; i + 1 < n; ++i) {
      const double h0 = f_.x[i] - f_.x[i - 1], h1 = f_.x[i + 1] - f_.x[i];
      const double diag = 2 * (h0 + h1) + (i == 1 ? h0 : -h0 * c);
      if (!(diag > 0)) {
        c = 0;
        continue;
      }
      fc_[i] = c = h1 / diag;
      finv_[i] = 1 / diag;
      fw_[i] = h0 / diag;
    }
  }
  void region(double s, double threshold, std::size_t j0, std::size_t j1, double a, double b,
              std::vector<HertzContact>& out) const {
    const double xl = std::max(g_.x[j0] + s, a), xr = std::min(g_.x[j1] + s, b);
    if (!(xl <= xr)) return;
    const std::size_t n = f_.x.size();
    const std::size_t il = edge_near(f_.x, xl, finvdx_), ir = edge_near(f_.x, xr, finvdx_) + 1;
    const std::size_t i0 = il > kPad ? il - kPad : 0, i1 = std::min(ir + kPad, n - 1);
    // At most i1 - i0 + 3 samples (the vertices and the two ends), written through local pointers.
    xs_.resize(i1 - i0 + 3), ys_.resize(i1 - i0 + 3);
    double* xw = xs_.data();
    double* yw = ys_.data();
    is_.resize(i1 - i0 + 3);
    std::size_t* iw = is_.data();  // each sample's lower vertex, kEnd for an end of the overlap
    std::size_t m = 0;
    std::size_t j = edge_near(g_.x, f_.x[i0] - s, ginvdx_);
    // A sample closer than a quarter of the lower's spacing to the previous one (an end of the
    // overlap next to a vertex) is left out, the end kept: a spline over a tiny interval swings.
    const double gap = 0.25 * (f_.x.back() - f_.x.front()) / double(n - 1);
    auto add = [&](double x, double fz, std::size_t vertex) {
      const bool end = vertex == kEnd;
      const double y = fz - g_at(x - s, j);
      if (m > 0 && x - xw[m - 1] < gap) {
        if (end && m > 1)
          xw[m - 1] = x, yw[m - 1] = y, iw[m - 1] = kEnd;
        else if (end && x > xw[m - 1])
          xw[m] = x, yw[m] = y, iw[m] = kEnd, ++m;  // a tiny overlap: its two ends
        return;
      }
      xw[m] = x, yw[m] = y, iw[m] = vertex, ++m;
    };
    if (f_.x[i0] <= a) add(a, f_at(a), kEnd);
    for (std::size_t i = i0; i <= i1; ++i)
      if (f_.x[i] > a && f_.x[i] < b) add(f_.x[i], f_.z[i], i);
    if (f_.x[i1] >= b) add(b, f_at(b), kEnd);
    xs_.resize(m), ys_.resize(m);
    if (m < 2) return;
    // The chords' slopes, once for the bound and the solve.
    ss_.resize(m - 1);
    double* S = ss_.data();
    for (std::size_t k = 0; k + 1 < m; ++k) S[k] = (yw[k + 1] - yw[k]) / (xw[k + 1] - xw[k]);
    if (prune_ && below(threshold)) return;
    // The spline's second derivatives M by the tridiagonal solve, with parabolic run-out ends
    // (M_0 = M_1, M_(m-1) = M_(m-2)): a natural end (M = 0) would flatten the curvature of a
    // contact at an end of the overlap (the block's corner), and with it the radius.
    // The factors of rows beyond the first kWarm of a run of consecutive lower vertices are the
    // lower's own (factor()): the forward sweep there is a multiply and a subtraction per row, no
    // division in its chain. The rows at the ends of the region, the first kWarm of the run and
    // any row beside an end of the overlap are eliminated here.
    ms_.assign(m, 0.0);
    const double* X = xs_.data();
    const double* Y = ys_.data();
    const std::size_t* I = is_.data();
    double* M = ms_.data();
    if (m >= 3) {
      cs_.assign(m, 0.0);
      double* CS = cs_.data();
      double cprev = 0, mprev = 0;
      auto row = [&](std::size_t k) {
        const double h0 = X[k] - X[k - 1], h1 = X[k + 1] - X[k];
        const double rhs = 6 * (S[k] - S[k - 1]);
        const bool first = k == 1, last = k + 2 == m;
        const double sub = first ? 0.0 : h0, super = last ? 0.0 : h1;
        const double diag = 2 * (h0 + h1) + (first ? h0 : 0.0) + (last ? h1 : 0.0) - sub * (first ? 0.0 : cprev);
        CS[k] = cprev = super / diag;
        M[k] = mprev = (rhs - sub * (first ? 0.0 : mprev)) / diag;
      };
      // The run of vertex samples [p, q] (the ends of the overlap are samples 0 and m - 1 at most).
      std::size_t p = I[0] == kEnd ? 1 : 0, q = I[m - 1] == kEnd ? m - 2 : m - 1;
      const bool run = p < q && I[p] != kEnd && I[q] != kEnd && I[q] - I[p] == q - p;
      const std::size_t g0 = run ? std::max<std::size_t>(p + kWarm, 1) : m, g1 = run ? std::min(q, m - 2) : m;
      std::size_t k = 1;
      for (; k < std::min(g0, m - 1); ++k) row(k);
      if (g0 < g1) {
        const double* gc = fc_.data();
        const double* ginv = finv_.data();
        const double* gw = fw_.data();
        // Two rows a step: M_(k+1) = a_(k+1) - w_(k+1) a_k + w_(k+1) w_k M_(k-1), a = rhs / diagonal,
        // w = h0 / diagonal, so that the chain carries one product and one sum per two rows.
        for (; k + 1 < g1; k += 2) {
          const std::size_t i = I[k];
          const double a0 = 6 * (S[k] - S[k - 1]) * ginv[i], a1 = 6 * (S[k + 1] - S[k]) * ginv[i + 1];
          const double w0 = gw[i], w1 = gw[i + 1];
          CS[k] = gc[i], CS[k + 1] = cprev = gc[i + 1];
          const double m1 = (a1 - w1 * a0) + (w1 * w0) * mprev;
          M[k] = a0 - w0 * mprev;
          M[k + 1] = mprev = m1;
        }
        for (; k < g1; ++k) {
          const std::size_t i = I[k];
          CS[k] = cprev = gc[i];
          M[k] = mprev = 6 * (S[k] - S[k - 1]) * ginv[i] - gw[i] * mprev;
        }
      }
      for (; k + 1 < m; ++k) row(k);
      // The back substitution M_k -= c_k M_(k+1), two rows a step likewise.
      double next = M[m - 2];
      std::size_t r = m - 2;  // M[r] is final
      for (; r >= 3; r -= 2) {
        const double c1 = CS[r - 1], c2 = CS[r - 2];
        const double m1 = M[r - 1] - c1 * next;
        next = (M[r - 2] - c2 * M[r - 1]) + (c2 * c1) * next;
        M[r - 1] = m1, M[r - 2] = next;
      }
      if (r == 2) M[1] = M[1] - CS[1] * next;
      M[0] = M[1];
      M[m - 1] = M[m - 2];
    }
    // Maxima of each piece inside [xl, xr] (an end of the overlap where the spline falls from it),
    // with the least sample between each and the previous as its saddle.
    // A piece that stays below the threshold emits nothing: the spline is the chord plus at most
    // (t u / 3) (max(-M0, 0) + max(-M1, 0)) <= h^2 / 12 of that (below()); only its saddle counts.
    // Such pieces are passed over first with the saddle in a local (the full step's lambdas hold
    // it by reference, which keeps it in memory).
    auto quiet = [&](std::size_t k) {
      const double h = X[k + 1] - X[k], y0 = Y[k], y1 = Y[k + 1];
      const double high = std::max(y0, y1), rise = h * h * (std::max(-M[k], 0.0) + std::max(-M[k + 1], 0.0)) / 12;
      return prune_ && high + rise + 1e-9 * (std::abs(high) + rise) + 1e-12 * scale_ < threshold;
    };
    double saddle = -kInf;
    for (std::size_t k = 0; k + 1 < m; ++k) {
      double low = saddle;
      while (k + 1 < m && quiet(k)) low = std::min(low, Y[k + 1]), ++k;
      saddle = low;
      if (k + 1 >= m) break;
      const double h = X[k + 1] - X[k], M0 = M[k], M1 = M[k + 1];
      const double y0 = Y[k], y1 = Y[k + 1];
      auto value = [&](double t) {
        const double u = h - t;
        return M0 * u * u * u / (6 * h) + M1 * t * t * t / (6 * h) + (y0 / h - M0 * h / 6) * u +
               (y1 / h - M1 * h / 6) * t;
      };
      // S'(t) = A t^2 + B t + C on t in [0, h].
      const double A = (M1 - M0) / (2 * h), B = M0, C = -M0 * h / 2 + (y1 - y0) / h - (M1 - M0) * h / 6;
      auto emit = [&](double t, double curvature_d2) {
        const double x = t >= h ? X[k + 1] : X[k] + t;
        // A maximum at a knot is a root of both pieces beside it (each within rounding): once.
        if (x < xl || x > xr || (!out.empty() && std::abs(out.back().x - x) <= 1e-9 * h)) return;
        const double d = value(t);
        if (d >= threshold) {
          out.push_back(contact_at(s, x, d, curvature_d2, saddle));
          saddle = kInf;
        }
      };
      // An end of the overlap is a contact (the block's corner, or the lower's end under it) where
      // the spline or the samples fall from it.
      if (k == 0 && X[0] <= a && (C <= 0 || y0 > y1)) emit(0, M0);
      double roots[2];
      int nr = 0;
      if (std::abs(A) * h < 1e-12 * (std::abs(B) + std::abs(C) / h)) {
        if (B != 0) roots[nr++] = -C / B;
      } else {
        const double disc = B * B - 4 * A * C;
        if (disc >= 0) {
          const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
          roots[nr++] = q / A;
          if (q != 0) roots[nr++] = C / q;
        }
      }
      if (nr == 2 && roots[0] > roots[1]) std::swap(roots[0], roots[1]);
      for (int r = 0; r < nr; ++r) {
        // A root at a knot may fall a rounding error outside both pieces beside it.
        const double t = std::clamp(roots[r], 0.0, h);
        if (!(roots[r] >= -1e-9 * h && roots[r] <= h * (1 + 1e-9))) continue;
        const double d2 = M0 + (M1 - M0) * t / h;  // S''(t)
        if (2 * A * t + B < 0) emit(t, d2);        // a maximum: S' falls through 0
      }
      saddle = std::min(saddle, y1);
      if (k + 2 == m && X[k + 1] >= b && (A * h * h + B * h + C >= 0 || y1 > y0)) emit(h, M1);
    }
  }

  // Whether the spline through the samples (xs_, ys_) stays below `threshold` everywhere, so that
  // the region emits no contact and its solve can be skipped; false where that is not certain. On
  // a piece of width h, with t and u = h - t the distances to its ends, the spline is the chord
  // minus (t u / 6 h) (M0 (u + h) + M1 (t + h)), at most h^2 max|M| / 8 above the higher sample;
  // each row of the system for M (parabolic run-out ends included) is diagonally dominant by at
  // least h0 + h1, so max|M| <= max|rhs| / min(h0 + h1). The margin covers rounding, by far.
  bool below(double threshold) const {
    const std::size_t m = xs_.size();
    double ymax = -kInf, rmax = 0, wmin = kInf, hmax = 0;
    for (std::size_t k = 0; k < m; ++k) ymax = std::max(ymax, ys_[k]);
    if (!(ymax < threshold)) return false;
    for (std::size_t k = 0; k + 1 < m; ++k) hmax = std::max(hmax, xs_[k + 1] - xs_[k]);
    for (std::size_t k = 1; k + 1 < m; ++k) {
      const double h0 = xs_[k] - xs_[k - 1], h1 = xs_[k + 1] - xs_[k];
      rmax = std::max(rmax, std::abs(6 * (ss_[k] - ss_[k - 1])));
      wmin = std::min(wmin, h0 + h1);
    }
    const double over = m >= 3 ? hmax * hmax * rmax / (8 * wmin) : 0.0;  // two samples: the chord
    const double top = ymax + over;
    return top + 1e-9 * (std::abs(top) + over) + 1e-12 * scale_ < threshold;
  }

  double f_at(double x) const { return lerp_at(f_.x, f_.z, edge_of(f_.x, x), x); }
  // g at u, walking its edge index j forward from the last call's.
  // The upper's edges' reciprocal widths (-1 across a jump) stand in for a division per sample.
  double g_at(double u, std::size_t& j) const {
    j = std::min(edge_of_from(g_.x, u, j), g_.x.size() - 2);
    const double r = ginvw_[j];
    if (!(r > 0)) return g_.z[j + 1];
    const double t = std::clamp((u - g_.x[j]) * r, 0.0, 1.0);
    return g_.z[j] + t * (g_.z[j + 1] - g_.z[j]);
  }

  // The contact at x of touch height d, the composite's second derivative d2 there (the spline's).
  HertzContact contact_at(double s, double x, double d, double d2, double saddle) const {
    HertzContact c;
    c.x = x;
    c.touch_height = d;
    c.saddle_left = std::isinf(saddle) ? -kInf : saddle;
    const std::size_t i = edge_of(f_.x, x), j = edge_of(g_.x, x - s);
    const double t = 0.5 * (lerp_at(f_.x, f_.d1, i, x) + lerp_at(g_.x, g_.d1, j, x - s));
    c.slope = std::atan(t);
    const double cs = std::cos(c.slope);
    const double curvature = -d2 * cs * cs * cs;  // 1/R of the composite, along the contact normal
    c.radius = curvature * max_radius_ > 1 ? 1 / curvature : max_radius_;
    return c;
  }

  static std::size_t edge_of_from(const std::vector<double>& xs, double x, std::size_t k) {
    // Forward walk from a known edge (the merged walk only moves right); far jumps search.
    std::size_t steps = 0;
    while (k + 2 < xs.size() && xs[k + 1] <= x) {
      ++k;
      if (++steps > 8) return edge_of(xs, x);
    }
    return k;
  }

  bool prune_ = true;  // LoadedLiftOptions::prune
  Fitted f_, g_;
  RangeMax fmax_;
  std::vector<double> fine_min_, coarse_min_;
  double modulus_ = 0, max_radius_ = 0, scale_ = 1;
  // The spline system's factors along the lower's vertices (factor()).
  std::vector<double> fc_, finv_, fw_, ginvw_;
  double finvdx_ = 0, ginvdx_ = 0;  // the reciprocal mean spacings of the lower and the upper (1/m)
  static thread_local std::vector<double> xs_, ys_, ss_, ms_, cs_;
  static thread_local std::vector<std::size_t> is_;
};

thread_local std::vector<double> Pair::xs_, Pair::ys_, Pair::ss_, Pair::ms_, Pair::cs_;
thread_local std::vector<std::size_t> Pair::is_;

Status check_inputs(const Profile& lower, const Profile& upper, const LoadedLiftOptions& o) {
  if (!(o.contact_modulus > 0) || !std::isfinite(o.contact_modulus))
    return make_error(fmt::format("contact modulus E* {} Pa: expected a finite modulus > 0", o.contact_modulus));
  if (o.loads.empty()) return make_error("loads: expected at least one load (N)");
  for (double w : o.loads)
    if (!(w > 0) || !std::isfinite(w)) return make_error(fmt::format("load {} N: expected a finite force > 0", w));
  if (!(o.max_radius >= 0) || !std::isfinite(o.max_radius))
    return make_error(
        fmt::format("largest radius {} m: expected a finite length >= 0 (0: the block's length)", o.max_radius));
  if (lower.x.size() < 3 || upper.x.size() < 3)
    return make_error("the loaded lift needs profiles of at least 3 points (the curvature at a contact)");
  if (auto st = validate(lower, "lower"); !st) return st;
  if (auto st = validate(upper, "upper"); !st) return st;
  return Ok{};
}

double radius_cap(const Profile& upper, const LoadedLiftOptions& o) {
  return o.max_radius > 0 ? o.max_radius : 100 * (upper.x.back() - upper.x.front());
}

// The threshold below the top that the largest load can reach: the top contact alone carrying it.
double reach(const HertzContact& top, double modulus, double wmax) {
  const double cs = std::cos(top.slope);
  const double k = (4.0 / 3.0) * modulus * std::sqrt(top.radius) * cs * cs * std::sqrt(cs);
  return std::pow(wmax / k, 2.0 / 3.0);
}

// Every contact at offset s within reach of the largest load `wmax`, in `c`; returns h(s), the
// top one's touch height (-inf where none). `hint`: a height a little below h(s) (the rigid
// lift's value there), for a first pass that finds the top contact; inf: none (all of d_s).
double collect(const Pair& pair, double s, double hint, double modulus, double wmax, std::vector<HertzContact>& c) {
  double first = std::isfinite(hint) ? hint - 1e-3 * pair.scale() : -kInf;
  pair.candidates(s, first, c);
  if (c.empty() && std::isfinite(first)) pair.candidates(s, first = -kInf, c);
  if (c.empty()) return -kInf;
  const HertzContact* t = &c.front();
  for (const HertzContact& k : c)
    if (k.touch_height > t->touch_height) t = &k;
  const double top = t->touch_height;
  const double threshold = top - reach(*t, modulus, wmax) * (1 + 1e-9) - 1e-12 * pair.scale();
  if (threshold < first) pair.candidates(s, threshold, c);
  return top;
}

}  // namespace

Result<LoadedState> loaded_state(const Profile& lower, const Profile& upper, double offset, double load,
                                 const LoadedLiftOptions& options) {
  LoadedLiftOptions o = options;
  o.loads = {load};
  if (auto st = check_inputs(lower, upper, o); !st) return st.error();
  if (!std::isfinite(offset)) return make_error(fmt::format("offset {} m: expected a finite offset", offset));
  const Pair pair(lower, upper, o.contact_modulus, radius_cap(upper, o));
  const auto [a, b] = pair.overlap(offset);
  if (!(a < b)) return make_error(fmt::format("offset {:.6g} m: the blocks do not overlap there", offset));
  LoadedState st;
  st.offset = offset;
  st.load = load;
  std::vector<HertzContact> c;
  st.rigid_lift = collect(pair, offset, kInf, o.contact_modulus, load, c);
  if (c.empty()) return make_error(fmt::format("offset {:.6g} m: no contact found", offset));
  const Pair::Balance bal = pair.balance(c, load);
  st.height = bal.height;
  st.energy = bal.energy;
  st.energy_lift = bal.height + bal.energy / load;
  st.effective_slope = bal.horizontal / bal.vertical;
  st.contacts = std::move(c);
  return st;
}

Result<LoadedLift> loaded_lift(const Profile& lower, const Profile& upper, const LiftCurve& rigid,
                               const LoadedLiftOptions& o) {
  if (auto st = check_inputs(lower, upper, o); !st) return st.error();
  if (rigid.period > 0)
    return make_error("the loaded lift: periodic pairs are not supported (state a block on a non-periodic pair)");
  const std::size_t n = rigid.offset.size();
  if (n < 2 || rigid.lift.size() != n) return make_error("the loaded lift: a rigid lift of at least 2 vertices");
  const Pair pair(lower, upper, o.contact_modulus, radius_cap(upper, o), o.prune);
  for (double s : {rigid.offset.front(), rigid.offset.back()}) {
    const auto [a, b] = pair.overlap(s);
    if (!(a < b)) return make_error(fmt::format("offset {:.6g} m of the rigid lift: the blocks do not overlap", s));
  }
  const std::size_t nl = o.loads.size();
  const double wmax = *std::max_element(o.loads.begin(), o.loads.end());
  // Per vertex and load: the diagnostics' terms (weighted by the vertex's share of the offsets).
  struct Terms {
    double contacts = 0, approach = 0, ratio = 0, deep = 0, merged = 0, slope2 = 0;
  };
  // The contacts at s (hint: a height a little above h(s)), and per load (nl
  // values each) the force-resolved slope tau_W into `slope` and the loaded lift's excess slope
  // over the rigid lift's on the piece before s (slope hb) into `before`, on the piece after it
  // (ha) into `after`, and the diagnostics' terms (if asked). The excess: the lift's slope is the
  // force-weighted mean of the loaded contacts' slopes, with the slope of the contact that the
  // rigid lift follows read from the rigid lift, exact on the polylines: sum_(c != c*) w_c
  // (tan theta_c - h'), w_c the contacts' shares of the vertical force. One loaded contact: no
  // excess, the rigid slope. c* is the deepest contact (the highest touch height; of equal ones,
  // the slope nearest h'): the top of the splines' rigid lift, so the excess is the loaded model's
  // own departure from its zero load. Where the splines' top is another asperity than the
  // polylines' (a sub-sample difference of the two interpolations), reading the contact nearest
  // h' instead took the splines' top for an extra contact while it carried the load alone, and
  // the lift rose by its slope until the hand-over: a spurious stop.
  auto evaluate = [&](double s, double hint, double hb, double ha, std::vector<HertzContact>& c, double* slope,
                      double* before, double* after, Terms* terms) -> bool {
    thread_local Pair::Prepared prepared;
    const double h = collect(pair, s, hint, o.contact_modulus, wmax, c);
    if (c.empty()) return false;
    auto excess = [&](double hp, double vertical) {
      std::size_t follow = c.size();
      const std::vector<double>&tn = prepared.tangent, &sn = prepared.sine, &cs = prepared.cosine;
      for (std::size_t q = 0; q < c.size(); ++q) {
        if (!(c[q].force > 0)) continue;
        if (follow == c.size() || c[q].touch_height > c[follow].touch_height ||
            (c[q].touch_height == c[follow].touch_height && std::abs(tn[q] - hp) < std::abs(tn[follow] - hp)))
          follow = q;
      }
      double e = 0;
      for (std::size_t q = 0; q < c.size(); ++q)
        if (q != follow && c[q].force > 0) e += c[q].force * (sn[q] - cs[q] * hp);
      return e / vertical;
    };
    pair.prepare(c, prepared);
    for (std::size_t l = 0; l < nl; ++l) {
      const double W = o.loads[l];
      const Pair::Balance bal = pair.balance(c, W, prepared);
      slope[l] = bal.horizontal / bal.vertical;
      before[l] = excess(hb, bal.vertical);
      after[l] = hb == ha ? before[l] : excess(ha, bal.vertical);
      if (!terms) continue;
      Terms& m = terms[l];
      m.approach = h - bal.height;
      // A loaded contact merges with a neighbouring asperity (the next local maximum of d_s on
      // either side, loaded or not) where the block is below the saddle between them or its
      // Hertz half-width a = sqrt(R delta) reaches it: the patch is then not one sphere's.
      double merged = 0;
      for (std::size_t q = 0; q < c.size(); ++q) {
        const HertzContact& k = c[q];
        if (!(k.force > 0)) continue;
        m.contacts += 1;
        m.ratio = std::max(m.ratio, k.interference / k.radius);
        m.slope2 += k.force * std::tan(k.slope) * std::tan(k.slope) / W;
        const double a = std::sqrt(k.radius * k.interference);
        const bool left = q > 0 && (k.saddle_left > bal.height || a >= k.x - c[q - 1].x);
        const bool right = q + 1 < c.size() && (c[q + 1].saddle_left > bal.height || a >= c[q + 1].x - k.x);
        if (left || right) merged += k.force * std::cos(k.slope);
      }
      m.deep = m.ratio > 0.1 ? 1 : 0;
      m.merged = std::min(merged / std::max(W, 1e-300), 1.0);
    }
    return true;
  };
  const unsigned T = util::thread_count(o.threads, n);
  std::vector<std::string> failures(T);
  // Pass 1: the rigid lift's vertices.
  std::vector<double> slope(n * nl), before(n * nl), after(n * nl);
  // The rigid lift's slope on piece k, [s_k, s_(k+1)] (k < n - 1).
  auto piece = [&](std::size_t k) {
    return (rigid.lift[k + 1] - rigid.lift[k]) / (rigid.offset[k + 1] - rigid.offset[k]);
  };
  std::vector<Terms> terms(n * nl);
  std::vector<std::size_t> found(n, 0);
  util::parallel_chunks(n, T, [&](unsigned chunk, std::size_t k0, std::size_t k1) {
    std::vector<HertzContact> c;
    for (std::size_t k = k0; k < k1; ++k) {
      const double hb = piece(k == 0 ? 0 : k - 1), ha = piece(k + 1 == n ? n - 2 : k);
      if (!evaluate(rigid.offset[k], rigid.lift[k], hb, ha, c, &slope[k * nl], &before[k * nl], &after[k * nl],
                    &terms[k * nl])) {
        failures[chunk] = fmt::format("offset {:.6g} m: no contact found", rigid.offset[k]);
        return;
      }
      found[k] = c.size();
    }
  });
  for (const std::string& f : failures)
    if (!f.empty()) return make_error("the loaded lift: " + f);
  // Pass 2: the excess is nonzero only where several contacts carry the load, and it can fall
  // from its value at a vertex to 0 within the approach of a kink of the rigid lift, far inside
  // the piece: the trapezoids would spread it over half the piece. In each piece where a load's
  // excess differs between the ends by more than kRefineSlope, a sample at the midpoint; where it
  // misses the mean of the ends by more than that, both halves again, down to kRefineDepth
  // halvings. The pieces' slopes are then the mean excess to about kRefineSlope.
  struct Inner {
    double offset = 0;
    std::vector<double> slope, excess;
  };
  auto differ = [&](const double* ea, const double* eb) {
    for (std::size_t l = 0; l < nl; ++l)
      if (std::abs(ea[l] - eb[l]) > kRefineSlope) return true;
    return false;
  };
  std::vector<std::vector<std::pair<std::size_t, std::vector<Inner>>>> inner(T);
  util::parallel_chunks(n - 1, T, [&](unsigned chunk, std::size_t k0, std::size_t k1) {
    std::vector<HertzContact> c;
    for (std::size_t k = k0; k < k1; ++k) {
      if (!differ(&after[k * nl], &before[(k + 1) * nl])) continue;
      const double s0 = rigid.offset[k], h0 = rigid.lift[k], hp = piece(k);
      std::vector<Inner> out;
      // Depth first, left to right: the samples come out in offset order. The excesses ea, eb
      // are the pass's vertices' or the callers' locals', never elements of `out`.
      auto refine = [&](auto&& self, double a, const double* ea, double b, const double* eb, int depth) -> bool {
        if (depth >= kRefineDepth || !differ(ea, eb)) return true;
        Inner m;
        m.offset = 0.5 * (a + b);
        m.slope.resize(nl), m.excess.resize(nl);
        if (!evaluate(m.offset, h0 + hp * (m.offset - s0), hp, hp, c, m.slope.data(), m.excess.data(), m.excess.data(),
                      nullptr)) {
          failures[chunk] = fmt::format("offset {:.6g} m: no contact found", m.offset);
          return false;
        }
        bool straight = true;
        for (std::size_t l = 0; l < nl; ++l)
          straight = straight && std::abs(m.excess[l] - 0.5 * (ea[l] + eb[l])) <= kRefineSlope;
        const std::vector<double> em = m.excess;
        if (!straight && !self(self, a, ea, m.offset, em.data(), depth + 1)) return false;
        out.push_back(std::move(m));
        return straight || self(self, out.back().offset, em.data(), b, eb, depth + 1);
      };
      if (!refine(refine, s0, &after[k * nl], rigid.offset[k + 1], &before[(k + 1) * nl], 0)) return;
      if (!out.empty()) inner[chunk].emplace_back(k, std::move(out));
    }
  });
  for (const std::string& f : failures)
    if (!f.empty()) return make_error("the loaded lift: " + f);
  // Pass 3: the excess slopes integrated by trapezoids (on each piece its value at the piece's
  // ends: `after` at its first vertex, `before` at its last) and added to the rigid lift (linear
  // between its vertices, as the hold analysis reads it).
  std::size_t total = n;
  for (const auto& ch : inner)
    for (const auto& [k, v] : ch) total += v.size();
  LoadedLift out;
  out.loads = o.loads;
  out.refined = total - n;
  out.curves.assign(nl, LiftCurve{});
  out.slopes.assign(nl, {});
  for (std::size_t l = 0; l < nl; ++l) {
    out.curves[l].offset.reserve(total), out.curves[l].lift.reserve(total), out.slopes[l].reserve(total);
  }
  std::vector<double> integral(nl, 0.0);
  double prev_offset = 0;
  const double* prev_excess = nullptr;
  // `in`: the excess on the piece that ends here; `on`: on the piece that starts here.
  auto push = [&](double offset, const double* tau, const double* in, const double* on, double h) {
    for (std::size_t l = 0; l < nl; ++l) {
      if (prev_excess) integral[l] += 0.5 * (prev_excess[l] + in[l]) * (offset - prev_offset);
      out.curves[l].offset.push_back(offset);
      out.curves[l].lift.push_back(h + integral[l]);
      out.slopes[l].push_back(tau[l]);
    }
    prev_offset = offset, prev_excess = on;
  };
  std::size_t chunk = 0, next = 0;  // the next interval with inner samples: inner[chunk][next]
  for (std::size_t k = 0; k < n; ++k) {
    push(rigid.offset[k], &slope[k * nl], &before[k * nl], &after[k * nl], rigid.lift[k]);
    if (k + 1 == n) break;
    while (chunk < inner.size() && next >= inner[chunk].size()) ++chunk, next = 0;
    if (chunk < inner.size() && inner[chunk][next].first == k) {
      const double hp = piece(k);
      for (const Inner& q : inner[chunk][next].second)
        push(q.offset, q.slope.data(), q.excess.data(), q.excess.data(),
             rigid.lift[k] + hp * (q.offset - rigid.offset[k]));
      ++next;
    }
  }
  for (std::size_t k = 0; k < n; ++k) out.candidates += found[k];
  const double span = rigid.offset.back() - rigid.offset.front();
  for (std::size_t l = 0; l < nl; ++l) {
    LoadedLiftDiagnostics d;
    d.load = o.loads[l];
    double slope2 = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const double w = 0.5 * (rigid.offset[std::min(k + 1, n - 1)] - rigid.offset[k == 0 ? 0 : k - 1]) / span;
      const Terms& t = terms[k * nl + l];
      d.mean_contacts += w * t.contacts;
      d.mean_approach += w * t.approach;
      d.max_interference_ratio = std::max(d.max_interference_ratio, t.ratio);
      d.deep_share += w * t.deep;
      d.merged_share += w * t.merged;
      slope2 += w * t.slope2;
    }
    d.rms_contact_slope = std::sqrt(slope2);
    out.diagnostics.push_back(d);
  }
  return out;
}

}  // namespace frictal
