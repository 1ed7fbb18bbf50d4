// frictal — the hold angle, its inertial bound and their distribution over drops (hold.hpp).
//
// Everything works on a continuous piecewise-linear function: vertices X[0..n], heights H[0..n],
// slopes M[0..n-1] of the pieces between them, read through a View of the LiftCurve's arrays
// (no copies: the backward direction reads them mirrored, a periodic curve unrolled). Forward
// sliding only; backward is the same on the mirrored function. A periodic curve is unrolled
// over five periods, enough for any drop of the base period: the descent to rest moves at most
// one period, the record chain from a rest ends within one period (at the next vertex of the
// globally steepest slope), and the inertial window is at most one period long.
//
// Memory: the distribution keeps O(basins) values and the record stack besides the curve; the
// descents are walked (each piece once), the records found in one pass from the right whose
// stack holds the record chain of the vertex at hand, the chords by monotone hulls over one
// window at a time. Time: linear in the curve's vertices, plus a binary search per rest for the
// chords.
#include "frictal/hold.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>
#include <unordered_map>

#include <fmt/core.h>

#include "signature/rigid.hpp"
#include "util/parallel.hpp"
#include "util/weighted_select.hpp"

namespace frictal {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kHalfPi = std::numbers::pi / 2;
// Rounding bound factor of a piece's slope: each stored offset and lift within 2 ulps of its
// exact value (docs/analysis.md, "Equal slopes").
constexpr double kSlopeTolerance = 4 * std::numeric_limits<double>::epsilon();

// How far apart two slopes may come out that are equal in exact arithmetic: the rounding bound of
// piece j's slope raw = (h[j+1] - h[j]) / dx as a difference quotient of the stored vertices,
// whose values carry a few ulps each (docs/analysis.md, "Equal slopes"). Same unit as the slope.
inline double slope_rounding(const double* x, const double* h, std::size_t j, double raw, double dx) {
  return kSlopeTolerance *
         ((std::abs(h[j]) + std::abs(h[j + 1])) + std::abs(raw) * (std::abs(x[j]) + std::abs(x[j + 1]))) / dx;
}

// The first vertex i of a view (View, LinearView) with X(i) > x0 (n() + 1 if none), as
// std::upper_bound.
template <class V>
std::size_t first_vertex_above(const V& v, double x0) {
  std::size_t lo = 0, len = v.n() + 1;
  while (len > 0) {
    const std::size_t half = len / 2;
    if (!(x0 < v.X(lo + half))) {
      lo += half + 1;
      len -= half + 1;
    } else {
      len = half;
    }
  }
  return lo;
}

// A read-only view of a LiftCurve as the function the forward process runs on: mirrored
// (x -> -x, the backward direction) and/or unrolled over copies c0 .. c0 + copies - 1 of a
// period. Values are computed exactly as copies of the arrays would hold them: the slopes are
// those of the base curve (negated when mirrored), the unrolled abscissae base + c * period.
struct View {
  const double* x = nullptr;  // the curve's m + 1 vertices
  const double* h = nullptr;
  std::size_t m = 0;  // pieces of the curve
  bool mirrored = false;
  double period = 0;  // > 0: unrolled
  int c0 = 0;
  std::size_t copies = 1;
  // Index arithmetic of the mirror, branch-free: vertex i of the frame is vertex o + s i of the
  // curve with abscissa sign sx; piece k is piece po + s k with slope sign sx (a negation, exact).
  std::ptrdiff_t o = 0, po = 0, s = 1;
  double sx = 1;

  std::size_t n() const { return m * copies; }
  double bx(std::size_t i) const { return sx * x[o + s * static_cast<std::ptrdiff_t>(i)]; }
  double bh(std::size_t i) const { return h[o + s * static_cast<std::ptrdiff_t>(i)]; }
  // The base piece j of the curve for piece k of the frame (k < m).
  std::size_t bj(std::size_t k) const { return static_cast<std::size_t>(po + s * static_cast<std::ptrdiff_t>(k)); }
  double bm(std::size_t k) const {
    const std::size_t j = bj(k);
    return sx * ((h[j + 1] - h[j]) / (x[j + 1] - x[j]));
  }
  double X(std::size_t i) const {
    if (period == 0) return bx(i);
    if (i == n()) return bx(m) + static_cast<double>(c0 + static_cast<int>(copies) - 1) * period;
    return bx(i % m) + static_cast<double>(c0 + static_cast<int>(i / m)) * period;
  }
  double H(std::size_t i) const {
    if (period == 0) return bh(i);
    return i == n() ? bh(m) : bh(i % m);
  }
  double M(std::size_t k) const { return period == 0 ? bm(k) : bm(k % m); }
  // The rounding bound of M(k) (slope_rounding).
  double tol(std::size_t k) const {
    const std::size_t j = bj(period == 0 ? k : k % m);
    const double dx = x[j + 1] - x[j];
    return slope_rounding(x, h, j, (h[j + 1] - h[j]) / dx, dx);
  }
  // M(k) and tol(k) at once (one division fewer; the same values).
  void slope_tol(std::size_t k, double& mk, double& tk) const {
    const std::size_t j = bj(period == 0 ? k : k % m);
    const double dx = x[j + 1] - x[j];
    const double raw = (h[j + 1] - h[j]) / dx;
    mk = sx * raw;
    tk = slope_rounding(x, h, j, raw, dx);
  }
  // Piece j is steeper than piece k: by more than k's rounding bound (the records rule).
  bool steeper(std::size_t j, std::size_t k) const { return M(j) > M(k) + tol(k); }
  // h at x (X(0) <= x <= X(n)), on piece k.
  double at(std::size_t k, double x0) const { return H(k) + M(k) * (x0 - X(k)); }
  // The first vertex i with X(i) > x (n + 1 if none), as std::upper_bound.
  std::size_t upper(double x0) const { return first_vertex_above(*this, x0); }
};

View make_view(const LiftCurve& c, bool mirrored) {
  View v;
  v.x = c.offset.data();
  v.h = c.lift.data();
  v.m = c.offset.size() - 1;
  v.mirrored = mirrored;
  if (mirrored) {
    v.o = static_cast<std::ptrdiff_t>(v.m);
    v.po = static_cast<std::ptrdiff_t>(v.m) - 1;
    v.s = -1;
    v.sx = -1;
  }
  if (c.period > 0) {
    v.period = c.period;
    v.c0 = -1;
    v.copies = 5;
  }
  return v;
}

// The View of a non-periodic curve, the mirror fixed at compile time: the same values as View
// (the same expressions), without its run-time index arithmetic.
template <bool Mirrored>
struct LinearView {
  const double* x = nullptr;
  const double* h = nullptr;
  std::size_t m = 0;
  explicit LinearView(const LiftCurve& c) : x(c.offset.data()), h(c.lift.data()), m(c.offset.size() - 1) {}
  std::size_t n() const { return m; }
  double X(std::size_t i) const { return Mirrored ? -1.0 * x[m - i] : x[i]; }
  double H(std::size_t i) const { return Mirrored ? h[m - i] : h[i]; }
  std::size_t bj(std::size_t k) const { return Mirrored ? m - 1 - k : k; }
  double M(std::size_t k) const {
    const std::size_t j = bj(k);
    const double v = (h[j + 1] - h[j]) / (x[j + 1] - x[j]);
    return Mirrored ? -1.0 * v : v;
  }
  double tol(std::size_t k) const {
    const std::size_t j = bj(k);
    const double dx = x[j + 1] - x[j];
    return slope_rounding(x, h, j, (h[j + 1] - h[j]) / dx, dx);
  }
  void slope_tol(std::size_t k, double& mk, double& tk) const {
    const std::size_t j = bj(k);
    const double dx = x[j + 1] - x[j];
    const double raw = (h[j + 1] - h[j]) / dx;
    mk = Mirrored ? -1.0 * raw : raw;
    tk = slope_rounding(x, h, j, raw, dx);
  }
  double at(std::size_t k, double x0) const { return H(k) + M(k) * (x0 - X(k)); }
  std::size_t upper(double x0) const { return first_vertex_above(*this, x0); }
};

// Runs f(view) with the fastest view of the curve that gives View's values.
template <class F>
decltype(auto) with_view(const LiftCurve& c, bool mirrored, F&& f) {
  if (c.period > 0) return f(make_view(c, mirrored));
  if (mirrored) return f(LinearView<true>(c));
  return f(LinearView<false>(c));
}

// Piece index holding x: the k with X[k] <= x < X[k+1] (the last piece for x = X[n]).
template <class V>
std::size_t piece_of(const V& p, double x) {
  const std::size_t u = p.upper(x);
  std::size_t k = u == 0 ? 0 : u - 1;
  return std::min(k, p.n() - 1);
}

// The descents to rest, walked and remembered for queries that move mostly forward.
template <class V>
class Descents {
 public:
  explicit Descents(const V& p) : p_(p) {}
  // First u >= v with M[u] >= 0, else n.
  std::size_t forward(std::size_t v) {
    if (v >= fq_ && v <= fa_ && fq_ != kUnset) return fa_;
    std::size_t u = v;
    while (u < p_.n() && !(p_.M(u) >= 0)) ++u;
    fq_ = v;
    fa_ = u;
    return u;
  }
  // First u <= v (going down) with u == 0 or M[u-1] <= 0.
  std::size_t backward(std::size_t v) {
    if (bq_ != kUnset && v >= ba_) {
      if (v <= bq_) return ba_;
      // Extend forward from bq_: the last u in (bq_, v] with M[u-1] <= 0, else ba_.
      std::size_t a = ba_;
      for (std::size_t u = bq_ + 1; u <= v; ++u)
        if (p_.M(u - 1) <= 0) a = u;
      bq_ = v;
      ba_ = a;
      return a;
    }
    std::size_t u = v;
    while (u > 0 && !(p_.M(u - 1) <= 0)) --u;
    bq_ = v;
    ba_ = u;
    return u;
  }

 private:
  static constexpr std::size_t kUnset = static_cast<std::size_t>(-1);
  const V& p_;
  std::size_t fq_ = kUnset, fa_ = 0, bq_ = kUnset, ba_ = 0;
};

// Where a drop at x rests: a vertex, or x itself on a flat piece (flat = piece index).
struct Rest {
  std::int64_t vertex = -1;  // rest vertex, or -1 on a flat piece
  std::int64_t flat = -1;    // the flat piece holding x
  double x = 0;
};

template <class V>
Rest rest_in(const V& p, Descents<V>& ds, std::size_t k, double x) {
  Rest r;
  r.x = x;
  std::int64_t v = -1;
  if (x == p.X(k)) {  // on a vertex: its two sides decide
    if (p.M(k) < 0)
      v = static_cast<std::int64_t>(ds.forward(k + 1));
    else if (k > 0 && p.M(k - 1) > 0)
      v = static_cast<std::int64_t>(ds.backward(k - 1));
    else
      v = static_cast<std::int64_t>(k);
  } else if (p.M(k) < 0) {
    v = static_cast<std::int64_t>(ds.forward(k + 1));
  } else if (p.M(k) > 0) {
    v = static_cast<std::int64_t>(ds.backward(k));
  } else {
    r.flat = static_cast<std::int64_t>(k);
    return r;
  }
  r.vertex = v;
  r.x = p.X(static_cast<std::size_t>(v));
  return r;
}

template <class V>
Rest rest_of(const V& p, Descents<V>& ds, double x) {
  return rest_in(p, ds, piece_of(p, x), x);
}

// The next record of the forward slope after piece k: the first j > k steeper than k (by more
// than k's rounding bound), or -1.
template <class V>
std::int64_t next_record(const V& p, std::size_t k) {
  const double t = p.M(k) + p.tol(k);
  for (std::size_t j = k + 1; j < p.n(); ++j)
    if (p.M(j) > t) return static_cast<std::int64_t>(j);
  return -1;
}

// The record chain from vertex s (< n): the stop that holds, the end of its run-away, the short
// slips before it.
struct Chain {
  std::int64_t held = 0, run_end = -1;
  int slips = 0;
};

template <class V>
Chain chain_from(const V& p, std::size_t s, double d) {
  Chain c;
  std::size_t k = s;
  for (;;) {
    const std::int64_t j = next_record(p, k);
    if (j < 0 || p.X(static_cast<std::size_t>(j)) - p.X(k) >= d) {
      c.held = static_cast<std::int64_t>(k);
      c.run_end = j;
      return c;
    }
    k = static_cast<std::size_t>(j);
    ++c.slips;
  }
}

// The record chains of every vertex, from the right (vertices pushed in decreasing order): the
// stack holds the strict records ahead of the vertex last pushed; a vertex's next record is the
// first entry above its M plus the equal-slopes tolerance (next_record's rule), found by
// bisection; its chain is chain_from's, built from that record's chain. O(1) amortised per vertex
// plus the bisection.
class RecordStack {
 public:
  struct Entry {
    std::size_t k;
    double m;  // M(k)
    double x;  // X(k)
    Chain c;
  };
  RecordStack() { stack_.reserve(64); }
  /// Pushes vertex kk (below every vertex pushed before) and returns its chain (d: run-away, m).
  template <class V>
  Chain push(const V& p, std::size_t kk, double d) {
    double mk, tk;
    p.slope_tol(kk, mk, tk);
    while (!stack_.empty() && stack_.back().m <= mk) stack_.pop_back();
    const double t = mk + tk;
    std::size_t top = stack_.size();  // past the entry of the next record; 0: none
    if (top > 0 && !(stack_[top - 1].m > t)) {
      std::size_t lo = 0, hi = top - 1;  // the last index in [0, hi) above t, if any
      while (lo < hi) {
        const std::size_t mid = (lo + hi) / 2;
        if (stack_[mid].m > t)
          lo = mid + 1;
        else
          hi = mid;
      }
      top = lo;
    }
    Chain c;
    const double xk = p.X(kk);
    if (top == 0 || stack_[top - 1].x - xk >= d) {
      c.held = static_cast<std::int64_t>(kk);
      c.run_end = top == 0 ? -1 : static_cast<std::int64_t>(stack_[top - 1].k);
    } else {
      c = stack_[top - 1].c;
      ++c.slips;
    }
    stack_.push_back({kk, mk, xk, c});
    return c;
  }
  const std::vector<Entry>& entries() const { return stack_; }

 private:
  std::vector<Entry> stack_;
};

// The forward process from a rest: the stop that held, the run-away end, the slips.
struct Outcome {
  double hold_x = 0, hold_slope = 0, end_x = kNaN;
  int slips = 0;
  bool off_end = false;
};

// `flat_next`: the next record of a flat rest's piece; `chain(v)`: the record chain from v.
template <class V, class ChainOf>
Outcome outcome_of(const V& p, const Rest& r, std::int64_t flat_next, double d, bool periodic, ChainOf&& chain) {
  Outcome o;
  const std::size_t n = p.n();
  std::int64_t start = r.vertex;
  if (r.flat >= 0) {  // a flat piece: the first slip starts at x
    const std::int64_t j = flat_next;
    if (j < 0 || p.X(static_cast<std::size_t>(j)) - r.x >= d) {
      o.hold_x = r.x;
      o.hold_slope = 0;
      if (j >= 0) o.end_x = p.X(static_cast<std::size_t>(j));
      o.off_end = j < 0 && !periodic;
      return o;
    }
    start = j;
    o.slips = 1;
  }
  const auto s = static_cast<std::size_t>(start);
  if (s == n) {  // rests at the end of the range: nothing ahead holds it
    o.hold_x = p.X(n);
    o.hold_slope = 0;
    o.off_end = true;
    return o;
  }
  const Chain c = chain(s);
  const auto h = static_cast<std::size_t>(c.held);
  o.hold_x = p.X(h);
  o.hold_slope = p.M(h);
  o.slips += c.slips;
  if (c.run_end >= 0) o.end_x = p.X(static_cast<std::size_t>(c.run_end));
  o.off_end = c.run_end < 0 && !periodic;
  return o;
}

// Steepest chord from (x0, h(x0)) to h over (x0, min(x0 + w, X[n])], by direct scan:
// {slope, where}. The window's end counts when it falls inside a piece.
template <class V>
std::pair<double, double> chord_direct(const V& p, double x0, double w) {
  const std::size_t n = p.n();
  const double h0 = p.at(piece_of(p, x0), x0);
  const double x1 = std::min(x0 + w, p.X(n));
  if (!(x1 > x0)) return {0.0, x0};
  double best = -std::numeric_limits<double>::infinity(), bx = x1;
  auto consider = [&](double x, double h) {
    const double s = (h - h0) / (x - x0);
    if (s > best) {
      best = s;
      bx = x;
    }
  };
  std::size_t v = p.upper(x0);
  for (; v <= n && p.X(v) <= x1; ++v) consider(p.X(v), p.H(v));
  if (v <= n && p.X(v - 1) < x1) consider(x1, p.at(v - 1, x1));
  return {best, bx};
}

// Upper hull of points pushed in monotone x order (Dir = +1 increasing, -1 decreasing); max-slope
// queries from a point to the left of every point. cross(o, a, b) > 0:
// b is to the left of o->a. The hull keeps the points' coordinates (read once per push).
template <class V, int Dir>
class MonotoneHull {
 public:
  explicit MonotoneHull(const V& p) : p_(p) {}
  void push(std::size_t v) {
    const Pt b{p_.X(v), p_.H(v)};
    // Keep the longest prefix whose last turn towards v stays convex (upper hull): pop from the
    // back while the last kept point would make a turn that is not right. keep(i): hull[i] stays
    // when v is added, i.e. i == 0 or turn(hull[i-1], hull[i], v) is right. The pops cost O(1)
    // amortised per push.
    auto keep = [&](std::size_t i) {
      if (i == 0) return true;
      const double c = cross(hull_[i - 1], hull_[i], b);
      return Dir > 0 ? c < 0 : c > 0;  // Dir * c < 0
    };
    std::size_t k = size_;  // points [0, k) kept
    while (k > 0 && !keep(k - 1)) --k;
    if (hull_.size() <= k) hull_.resize(k + 1);
    hull_[k] = b;
    size_ = k + 1;
  }
  void clear() { size_ = 0; }
  // Max of (H[v] - h0) / (X[v] - x0) over the hull; the slope along the hull is unimodal.
  std::pair<double, double> best(double x0, double h0) const {
    if (size_ == 0) return {-std::numeric_limits<double>::infinity(), kNaN};
    auto slope = [&](std::size_t i) { return (hull_[i].h - h0) / (hull_[i].x - x0); };
    // slope(i) < slope(j), the denominators (> 0) multiplied out: no division on the search's path.
    auto less = [&](std::size_t i, std::size_t j) {
      return (hull_[i].h - h0) * (hull_[j].x - x0) < (hull_[j].h - h0) * (hull_[i].x - x0);
    };
    std::size_t lo = 0, hi = size_ - 1;
    while (lo < hi) {
      const std::size_t mid = (lo + hi) / 2;
      if (less(mid, mid + 1))
        lo = mid + 1;
      else
        hi = mid;
    }
    return {slope(lo), hull_[lo].x};
  }

 private:
  struct Pt {
    double x, h;
  };
  static double cross(const Pt& o, const Pt& a, const Pt& b) {
    return (a.x - o.x) * (b.h - o.h) - (a.h - o.h) * (b.x - o.x);
  }
  const V& p_;
  std::vector<Pt> hull_;
  std::size_t size_ = 0;
};

// Steepest chords from many rest vertices (in decreasing order), each over
// (X[r], min(X[r] + w, X[n])]. The x axis is cut into chunks of length w: a window starting in
// chunk c covers a suffix of chunk c and a prefix of the chunks after it, up to one chunk
// length. Per chunk, the queries by increasing x (their windows' ends move forwards) against the
// hull of the later chunks' vertices up to the window's end (grown forwards), then by decreasing
// x against the hull of the chunk's vertices after the rest (grown backwards). O(n + q log n)
// time (pushes O(1) amortised), O(vertices per window) memory.
// A vertex where the slope after it exceeds the slope before it by more than both their
// rounding bounds (a convex corner: between two events h is convex, so every tangent meeting
// point is one) lies strictly below the chord of its two neighbours, and a chord from the left
// to it is strictly less steep than to one of them: the hulls leave such vertices out, and the
// window's first and last vertices (whose neighbours may lie outside it) are tried on their own.
// `out(i, slope)` receives the steepest slope of rests[i].
template <class V, class Rests, class Out>
void chords_batch(const V& p, const Rests& rests, double w, Out&& out) {
  const std::size_t n = p.n();
  if (rests.empty()) return;
  std::vector<std::uint8_t> skip(n + 1, 0);  // clearly convex corners (not the ends)
  {
    double m_prev, t_prev;
    p.slope_tol(0, m_prev, t_prev);
    for (std::size_t v = 1; v < n; ++v) {
      double m, t;
      p.slope_tol(v, m, t);
      skip[v] = m > m_prev + t_prev + t;
      m_prev = m;
      t_prev = t;
    }
  }
  const double x_begin = p.X(0);
  auto chunk_of = [&](double x) { return std::floor((x - x_begin) / w); };
  MonotoneHull<V, -1> suffix(p);
  MonotoneHull<V, +1> prefix(p);
  std::vector<double> prefix_best;  // per query of the chunk at hand
  std::size_t qi = 0;
  std::size_t u1 = n + 2;  // upper(x1) of the last query (x1 does not increase from query to query)
  while (qi < rests.size()) {
    const double c = chunk_of(p.X(rests[qi]));
    // b: the first vertex of a later chunk.
    std::size_t b = 0;
    {
      std::size_t lo = 0, len = n + 1;  // partition point of chunk_of(X) <= c
      while (len > 0) {
        const std::size_t half = len / 2;
        if (chunk_of(p.X(lo + half)) <= c) {
          lo += half + 1;
          len -= half + 1;
        } else {
          len = half;
        }
      }
      b = lo;
    }
    const std::size_t q0 = qi;  // the chunk's queries: [q0, q_end)
    std::size_t q_end = qi;
    while (q_end < rests.size() && chunk_of(p.X(rests[q_end])) == c) ++q_end;
    // The prefix part, queries by increasing x (their windows' ends do not decrease): the hull of
    // the vertices from b to the window's end grows forwards.
    prefix.clear();
    prefix_best.resize(q_end - q0);
    std::size_t prefix_end = b;  // prefix holds [b, prefix_end)
    for (std::size_t q = q_end; q-- > q0;) {
      const std::size_t r = rests[q];
      const double x0 = p.X(r), h0 = p.H(r), x1 = std::min(x0 + w, p.X(n));
      for (; prefix_end <= n && p.X(prefix_end) <= x1; ++prefix_end)
        if (!skip[prefix_end]) prefix.push(prefix_end);
      prefix_best[q - q0] = prefix.best(x0, h0).first;
    }
    // The suffix part, queries by decreasing x: the hull of the chunk's vertices after the rest
    // grows backwards.
    suffix.clear();
    std::size_t suffix_begin = b;  // suffix holds [suffix_begin, b)
    for (; qi < q_end; ++qi) {
      const std::size_t r = rests[qi];
      const double x0 = p.X(r), h0 = p.H(r), x1 = std::min(x0 + w, p.X(n));
      while (suffix_begin > r + 1)
        if (!skip[--suffix_begin]) suffix.push(suffix_begin);
      double best = std::max(suffix.best(x0, h0).first, prefix_best[qi - q0]);
      if (u1 > n + 1)
        u1 = p.upper(x1);
      else
        while (u1 > 0 && p.X(u1 - 1) > x1) --u1;
      // The window's first and last vertices.
      const std::size_t last = u1 == 0 ? 0 : u1 - 1;
      if (last > r) {
        for (const std::size_t v : {r + 1, last}) {
          const double s = (p.H(v) - h0) / (p.X(v) - x0);
          if (s > best) best = s;
        }
      }
      if (x1 > x0) {                                  // the window's end inside a piece
        const std::size_t k = std::min(last, n - 1);  // piece_of(p, x1)
        if (p.X(k) < x1 && x1 < p.X(k + 1)) {
          const double s = (p.at(k, x1) - h0) / (x1 - x0);
          if (s > best) best = s;
        }
      }
      if (!std::isfinite(best)) best = 0.0;
      out(qi, best);
    }
  }
}

double angle_of(double slope, double mu) { return std::min(std::atan(slope) + std::atan(mu), kHalfPi); }

// angle_of(slope, mu) for many slopes of one mu, remembering the last slope (chains that join
// hold at the same stop: neighbouring basins often share their slope).
class AngleOf {
 public:
  explicit AngleOf(double mu) : atan_mu_(std::atan(mu)) {}
  double operator()(double slope) {
    if (!(slope == last_slope_ && std::signbit(slope) == std::signbit(last_slope_))) {
      last_slope_ = slope;
      last_angle_ = std::min(std::atan(slope) + atan_mu_, kHalfPi);
    }
    return last_angle_;
  }

 private:
  double atan_mu_;
  double last_slope_ = std::numeric_limits<double>::quiet_NaN(), last_angle_ = 0;
};

Status check_curve(const LiftCurve& c) {
  if (c.offset.size() != c.lift.size() || c.offset.size() < 2)
    return make_error(
        fmt::format("hold: the lift curve needs at least two vertices with as many lifts as offsets (got {} and {})",
                    c.offset.size(), c.lift.size()));
  for (std::size_t k = 0; k < c.offset.size(); ++k) {
    if (!std::isfinite(c.offset[k]) || !std::isfinite(c.lift[k]))
      return make_error(fmt::format("hold: lift curve vertex {} is not finite", k));
    if (k > 0 && !(c.offset[k] > c.offset[k - 1]))
      return make_error(fmt::format("hold: lift curve offsets must increase (vertex {}: {} m after {} m)", k,
                                    c.offset[k], c.offset[k - 1]));
  }
  if (c.period != 0) {
    if (!(c.period > 0) || !std::isfinite(c.period))
      return make_error(fmt::format("hold: period = {} m: expected > 0 (or 0 for a non-periodic lift)", c.period));
    const double span = c.offset.back() - c.offset.front();
    if (std::abs(span - c.period) > 1e-9 * c.period)
      return make_error(
          fmt::format("hold: a periodic lift curve must span one period: {} m against period {} m", span, c.period));
  }
  return Ok{};
}

Status check_options(const HoldOptions& o) {
  if (!(o.runaway_distance > 0) || !std::isfinite(o.runaway_distance))
    return make_error(fmt::format("hold: runaway_distance = {} m: expected a finite length > 0", o.runaway_distance));
  if (!(o.atomic_friction >= 0) || !std::isfinite(o.atomic_friction))
    return make_error(fmt::format("hold: atomic_friction = {}: expected a finite value >= 0", o.atomic_friction));
  if (!std::isfinite(o.drop_min) || !std::isfinite(o.drop_max))
    return make_error("hold: the drop range must be finite");
  return Ok{};
}

// One direction's frame: the function the forward process runs on, and the window length.
struct Frame {
  View pl;
  bool periodic = false;
  double period = 0;
  double base_lo = 0;  // base period [base_lo, base_lo + period) in this frame (periodic)
  double w = 0;        // inertial window
};

Frame make_frame(const LiftCurve& c, bool mirrored, double d) {
  Frame fr;
  fr.pl = make_view(c, mirrored);
  fr.periodic = c.period > 0;
  fr.period = c.period;
  fr.base_lo = fr.pl.bx(0);
  fr.w = fr.periodic ? std::min(d, c.period) : d;
  return fr;
}

// Offset x of the base frame in the unrolled function (periodic: into [base_lo, base_lo + P)).
double wrap(const Frame& fr, double x) {
  if (!fr.periodic) return x;
  double y = std::fmod(x - fr.base_lo, fr.period);
  if (y < 0) y += fr.period;
  return fr.base_lo + y;
}

template <class V>
HoldAngle single(const Frame& fr, const V& p, double x, const HoldOptions& o) {
  Descents<V> ds(p);
  const Rest r = rest_of(p, ds, x);
  const double d = o.runaway_distance;
  const std::int64_t flat_next = r.flat >= 0 ? next_record(p, static_cast<std::size_t>(r.flat)) : -1;
  const Outcome oc = outcome_of(p, r, flat_next, d, fr.periodic, [&](std::size_t s) { return chain_from(p, s, d); });
  HoldAngle h;
  h.rest_offset = r.x;
  h.hold_slope = oc.hold_slope;
  h.hold_angle = angle_of(oc.hold_slope, o.atomic_friction);
  h.hold_offset = oc.hold_x;
  h.runaway_end = oc.end_x;
  h.slips = oc.slips;
  h.ran_off_end = oc.off_end;
  const auto [slope, cx] = chord_direct(p, r.x, fr.w);
  h.inertial_slope = slope;
  h.inertial_offset = cx;
  h.inertial_hold_angle = angle_of(slope, o.atomic_friction);
  return h;
}

// Reflects a backward result into the lift's frame.
HoldAngle unmirror(HoldAngle h) {
  h.rest_offset = -h.rest_offset;
  h.hold_offset = -h.hold_offset;
  h.runaway_end = -h.runaway_end;
  h.inertial_offset = -h.inertial_offset;
  return h;
}

// `e`: scratch space for the selection (reused from call to call: its pages are taken once).
HoldStatistics weighted_stats(const std::vector<double>& v, const std::vector<double>& w,
                              std::vector<util::ValueWeight>& e) {
  HoldStatistics s;
  double tw = 0, m = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    tw += w[i];
    m += w[i] * v[i];
  }
  if (!(tw > 0)) return s;
  m /= tw;
  double var = 0;
  for (std::size_t i = 0; i < v.size(); ++i) var += w[i] * (v[i] - m) * (v[i] - m);
  s.mean = m;
  s.std = std::sqrt(var / tw);
  // Quantiles: the first value, by increasing value, at which the cumulative weight reaches
  // q * tw (less a relative 1e-12, so that a quantile falling on a jump takes the lower value).
  // By selection rather than a sort: the cumulative weights are added up in another order, which
  // moves them by rounding only (about n ulps at most, typically far less than the 1e-12 slack).
  e.resize(v.size());
  double lo = v[0], hi = v[0];
  for (std::size_t i = 0; i < v.size(); ++i) {
    e[i] = {v[i], w[i]};
    if (v[i] < lo) lo = v[i];
    if (hi < v[i]) hi = v[i];
  }
  const double thr[3] = {0.05 * tw * (1 - 1e-12), 0.50 * tw * (1 - 1e-12), 0.95 * tw * (1 - 1e-12)};
  double q[3];
  util::weighted_select(e.data(), e.size(), 0.0, thr, 3, q);
  s.q05 = q[0];
  s.q50 = q[1];
  s.q95 = q[2];
  s.min = lo;
  s.max = hi;
  return s;
}

// A drop on a flat piece: its own outcome (pass 1 of distribution()).
struct Flat {
  double weight;
  Rest rest;
  std::int64_t next;  // the next record of its piece
  Outcome oc;
};

// Pass 1 of distribution(): the basins over the drop range (rest vertex and weight, in the order
// of their first drop) and the flat drops. With `starts`: each basin's first piece, and whether
// the mirrored frame's pass 1 is this one mirrored (mirror_pass1): no flat drop, and every
// part's midpoint strictly inside its piece (so that rest_in() takes the same rule on both sides).
struct Basins {
  std::vector<std::size_t> bv;
  std::vector<double> bw;
  std::vector<Flat> flats;
  std::vector<std::size_t> start;
  bool mirrorable = false;
};

// Pass 1 (increasing x) cuts the drop range into parts with one outcome each (the pieces of the
// curve; a flat piece split where the first slip reaches d) and adds each part's length to its
// basin (the rest vertex; the drops of one basin form one interval, so a basin is a run of
// parts, apart from the wrap-around of a periodic curve) or keeps it as a flat drop.
template <class V>
Basins basins_of(const Frame& fr, const V& p, double a, double b, const HoldOptions& o, bool starts) {
  const double d = o.runaway_distance;
  const std::size_t n = p.n();
  Basins out;
  std::vector<std::size_t>& bv = out.bv;
  std::vector<double>& bw = out.bw;
  std::vector<Flat>& flats = out.flats;
  out.mirrorable = starts && !fr.periodic;
  // At most one basin per piece in the drop range, reserved at once (pages are taken as written).
  {
    const std::size_t pieces = p.upper(b) - std::min(p.upper(b), piece_of(p, a)) + 1;
    bv.reserve(pieces);
    bw.reserve(pieces);
    if (out.mirrorable) out.start.reserve(pieces);
  }
  std::unordered_map<std::size_t, std::size_t> seen;  // periodic: key -> basin
  const std::size_t nb = fr.periodic ? p.m : 0;       // vertices per period in the unrolled frame
  std::size_t last_key = static_cast<std::size_t>(-1);
  Descents<V> ds(p);
  std::int64_t flat_next_q = -1, flat_next_a = -1;  // the last flat piece's next record
  auto flat_next = [&](std::size_t k) {
    const auto kk = static_cast<std::int64_t>(k);
    if (kk != flat_next_q) {
      flat_next_q = kk;
      flat_next_a = next_record(p, k);
    }
    return flat_next_a;
  };
  // A part of length len of piece k whose drops rest at vertex v: to its basin (the drops of one
  // basin form one interval, so a basin is a run of parts, apart from a periodic wrap-around).
  auto add_part = [&](std::size_t v, double len, std::size_t k) {
    const std::size_t key = fr.periodic ? v % nb : v;
    if (!bv.empty() && key == last_key) {
      bw.back() += len;
    } else if (fr.periodic) {
      const auto [it, fresh] = seen.try_emplace(key, bv.size());
      if (fresh) {
        bv.push_back(v);
        bw.push_back(len);
      } else {
        bw[it->second] += len;
      }
    } else {
      bv.push_back(v);
      bw.push_back(len);
      if (out.mirrorable) out.start.push_back(k);
    }
    last_key = key;
  };
  std::size_t k = piece_of(p, a);
  for (double x = a; x < b && k < n; ++k) {
    const double xe = std::min(b, p.X(k + 1));
    if (xe <= x) continue;
    const double mid = 0.5 * (x + xe);
    // The common case, mid strictly inside piece k on a slope: its descent, as rest_in() takes it.
    if (p.X(k) < mid && mid < p.X(k + 1)) {
      const double mk = p.M(k);
      if (mk != 0) {
        add_part(mk < 0 ? ds.forward(k + 1) : ds.backward(k), xe - x, k);
        x = xe;
        continue;
      }
    }
    std::size_t km = k;  // the piece of mid, as piece_of() finds it
    while (km + 1 < n && !(mid < p.X(km + 1))) ++km;
    while (km > 0 && mid < p.X(km)) --km;
    if (out.mirrorable && !(km == k && p.X(k) < mid && mid < p.X(k + 1))) out.mirrorable = false;
    const Rest r = rest_in(p, ds, km, mid);
    if (r.flat >= 0) {
      out.mirrorable = false;
      // On a flat piece the first slip starts at the drop: split where it reaches d.
      const std::int64_t j = flat_next(k);
      const double split = j >= 0 ? p.X(static_cast<std::size_t>(j)) - d : x;
      const std::int64_t jf = flat_next(static_cast<std::size_t>(r.flat));
      for (const auto& [lo, hi] : {std::pair{x, std::min(xe, std::max(x, split))}, std::pair{std::max(x, split), xe}}) {
        if (!(hi > lo)) continue;
        Rest rr = r;
        rr.x = 0.5 * (lo + hi);
        flats.push_back({hi - lo, rr, jf, {}});
      }
    } else {
      add_part(static_cast<std::size_t>(r.vertex), xe - x, k);
    }
    x = xe;
  }
  if (!out.mirrorable) std::vector<std::size_t>().swap(out.start);
  return out;
}

// Pass 1 of the mirrored frame (`pm`, drops over [a, b] of its coordinates) from that of the
// frame it mirrors (`f`, basins_of(..., true), mirrorable): a drop that rests at vertex v there
// rests at vertex n - v here (the descents stop where the slope ahead turns non-negative, which
// the mirror turns into the slope behind turning non-positive: the same vertex). The basins come
// in the reverse order, each with its parts' lengths added up as basins_of() adds them in this
// frame (from this frame's parts, walked as it walks them: the same lengths, in its order).
// False where the two do not match part for part (then basins_of() is run here).
template <class V>
bool mirror_basins(const V& pm, const Basins& f, double a, double b, Basins& out) {
  const std::size_t n = pm.n(), nf = f.bv.size();
  out = Basins{};
  out.bv.reserve(nf);
  out.bw.reserve(nf);
  std::size_t cur = nf;  // the other frame's basin of the last part (nf: none yet)
  std::size_t i = nf;    // basins [0, i) start at or before the part at hand
  std::size_t k = piece_of(pm, a);
  for (double x = a; x < b && k < n; ++k) {
    const double xe = std::min(b, pm.X(k + 1));
    if (xe <= x) continue;
    const std::size_t kf = n - 1 - k;  // the piece in the other frame
    while (i > 0 && f.start[i - 1] > kf) --i;
    if (i == 0) return false;
    const std::size_t fb = i - 1;
    if (fb != cur) {  // the next basin (the one before in the other frame)
      if (cur == nf ? fb + 1 != nf : fb + 1 != cur) return false;
      out.bv.push_back(n - f.bv[fb]);
      out.bw.push_back(xe - x);
      cur = fb;
    } else {
      out.bw.back() += xe - x;
    }
    x = xe;
  }
  return out.bv.size() == nf && (nf == 0 || cur == 0);
}

// Distribution over drops in [a, b] (this frame's coordinates, a < b), from its basins (pass 1,
// basins_of). Pass 2 (decreasing x) finds the record chains of the basins' rest vertices with one
// stack. Pass 3: the steepest chords from the rest vertices.
template <class V>
HoldDistribution distribution(const Frame& fr, const V& p, double a, double b, const HoldOptions& o, bool mirrored,
                              Basins&& pass1) {
  const double d = o.runaway_distance;
  const std::size_t n = p.n();
  // The basins, one entry each: rest vertex and weight (pass 1), hold slope and whether the
  // run-away ran off the end less than d after its stop (pass 2), inertial angle (pass 3).
  std::vector<std::size_t> bv = std::move(pass1.bv);
  std::vector<double> bw = std::move(pass1.bw), bslope, binert;
  std::vector<Flat> flats = std::move(pass1.flats);
  pass1 = Basins{};
  std::vector<std::uint8_t> bnear;
  // Pass 2: the record chains, from the right. The stack holds the strict record chain of the
  // vertex at hand (slopes strictly increasing from top to bottom), each entry with the end of
  // its own chain. The next record of kk (the first piece ahead steeper than kk by more than
  // kk's rounding bound) is the first piece exceeding a threshold, hence a strict record too:
  // the first entry from the top above the threshold (binary search; usually the top). The
  // chains are read where they are needed: at the basins' rest vertices (in decreasing order)
  // and at the records that flat drops slip to.
  const double x_end = p.X(n);
  {
    // Basins by decreasing rest vertex: non-periodic basins come in increasing order already.
    std::vector<std::uint32_t> border;
    bool increasing = true;
    for (std::size_t i = 1; i < bv.size() && increasing; ++i) increasing = bv[i - 1] < bv[i];
    if (!increasing) {
      border.resize(bv.size());
      for (std::size_t i = 0; i < border.size(); ++i) border[i] = static_cast<std::uint32_t>(i);
      std::sort(border.begin(), border.end(), [&](std::uint32_t x, std::uint32_t y) { return bv[x] > bv[y]; });
    }
    auto basin_at = [&](std::size_t r) -> std::size_t {  // the r-th basin in decreasing vertex order
      return increasing ? bv.size() - 1 - r : border[r];
    };
    bslope.resize(bv.size());
    bnear.resize(bv.size());
    std::vector<std::size_t> fq;  // records that flat drops slip to, decreasing
    for (const Flat& f : flats)
      if (f.next >= 0) fq.push_back(static_cast<std::size_t>(f.next));
    std::sort(fq.begin(), fq.end(), std::greater<>());
    fq.erase(std::unique(fq.begin(), fq.end()), fq.end());
    std::vector<Chain> fa(fq.size());
    auto set_outcome = [&](std::size_t q, const Chain& c) {
      Rest r;
      r.vertex = static_cast<std::int64_t>(bv[q]);
      r.x = p.X(bv[q]);
      const Outcome oc = outcome_of(p, r, -1, d, fr.periodic, [&](std::size_t) { return c; });
      bslope[q] = oc.hold_slope;
      bnear[q] = oc.off_end && x_end - oc.hold_x < d;
    };
    std::size_t bi = 0, fi = 0;
    const std::size_t nbv = bv.size(), nfq = fq.size();
    constexpr std::size_t kNone = static_cast<std::size_t>(-1);
    // Basins resting at the end vertex n: nothing ahead holds them.
    while (bi < nbv && bv[basin_at(bi)] >= n) set_outcome(basin_at(bi++), Chain{});
    // The next basin's rest vertex and the next flat drop's record (kNone: none left), so that a
    // vertex that is neither costs two comparisons.
    std::size_t next_b = bi < nbv ? bv[basin_at(bi)] : kNone, next_f = fi < nfq ? fq[fi] : kNone;
    RecordStack records;
    for (std::size_t kk = n; kk-- > 0 && (bi < nbv || fi < nfq);) {
      const Chain c = records.push(p, kk, d);
      if (kk == next_b) {
        while (bi < nbv && bv[basin_at(bi)] == kk) set_outcome(basin_at(bi++), c);
        next_b = bi < nbv ? bv[basin_at(bi)] : kNone;
      }
      if (kk == next_f) {
        fa[fi++] = c;
        next_f = fi < nfq ? fq[fi] : kNone;
      }
    }
    auto chain = [&](std::size_t s0) {
      const auto it = std::lower_bound(fq.begin(), fq.end(), s0, std::greater<>());
      return fa[static_cast<std::size_t>(it - fq.begin())];
    };
    for (Flat& f : flats) f.oc = outcome_of(p, f.rest, f.next, d, fr.periodic, chain);
  }
  double near_end = 0;  // run-aways that left a stop less than d before the end of the curve
  for (std::size_t q = 0; q < bv.size(); ++q)
    if (bnear[q]) near_end += bw[q];
  std::vector<std::uint8_t>().swap(bnear);
  for (const Flat& f : flats)
    if (f.oc.off_end && x_end - f.oc.hold_x < d) near_end += f.weight;
  // Pass 3: the steepest chords from the rest vertices, in decreasing order; then the basins
  // (flat drops first, each with its own chord) in the order of their first drop.
  {
    bool increasing = true;
    for (std::size_t i = 1; i < bv.size() && increasing; ++i) increasing = bv[i - 1] < bv[i];
    std::vector<std::size_t> order;
    if (!increasing) {
      order.resize(bv.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return bv[x] > bv[y]; });
    }
    // The queries in decreasing vertex order, as chords_batch takes them.
    struct Rests {
      const std::vector<std::size_t>& bs;
      const std::vector<std::size_t>& ord;
      bool inc;
      std::size_t size() const { return bs.size(); }
      bool empty() const { return bs.empty(); }
      std::size_t idx(std::size_t q) const { return inc ? bs.size() - 1 - q : ord[q]; }
      std::size_t operator[](std::size_t q) const { return bs[idx(q)]; }
    } rq{bv, order, increasing};
    binert.resize(bv.size());
    AngleOf inertial_angle(o.atomic_friction);
    chords_batch(p, rq, fr.w, [&](std::size_t qi, double best) { binert[rq.idx(qi)] = inertial_angle(best); });
  }
  // The basins' rest offsets and hold angles, in place of their vertices and hold slopes.
  std::vector<double> brest(bv.size());
  AngleOf hold_angle(o.atomic_friction);
  for (std::size_t q = 0; q < bv.size(); ++q) {
    const double rest = wrap(fr, p.X(bv[q]));
    brest[q] = mirrored ? -rest : rest;
    bslope[q] = hold_angle(bslope[q]);
  }
  std::vector<std::size_t>().swap(bv);
  HoldDistribution out;
  if (flats.empty()) {
    out.basins.rest = std::move(brest);
    out.basins.weight = std::move(bw);
    out.basins.hold = std::move(bslope);
    out.basins.inertial = std::move(binert);
  } else {
    HoldBasins& ob = out.basins;
    const std::size_t total = brest.size() + flats.size();
    for (std::vector<double>* v : {&ob.rest, &ob.weight, &ob.hold, &ob.inertial}) v->reserve(total);
    for (const Flat& f : flats) {  // a flat drop: its own chord
      ob.rest.push_back(mirrored ? -f.rest.x : f.rest.x);
      ob.weight.push_back(f.weight);
      ob.hold.push_back(angle_of(f.oc.hold_slope, o.atomic_friction));
      ob.inertial.push_back(angle_of(chord_direct(p, f.rest.x, fr.w).first, o.atomic_friction));
    }
    std::vector<Flat>().swap(flats);
    ob.rest.insert(ob.rest.end(), brest.begin(), brest.end());
    ob.weight.insert(ob.weight.end(), bw.begin(), bw.end());
    ob.hold.insert(ob.hold.end(), bslope.begin(), bslope.end());
    ob.inertial.insert(ob.inertial.end(), binert.begin(), binert.end());
  }
  for (std::vector<double>* v : {&brest, &bw, &bslope, &binert}) std::vector<double>().swap(*v);
  // Sort the basins by offset (nothing to do where they are in strictly increasing order, the
  // one order a sort can give then).
  bool strictly = true;
  for (std::size_t i = 1; i < out.basins.rest.size() && strictly; ++i)
    strictly = out.basins.rest[i - 1] < out.basins.rest[i];
  if (!strictly) {
    std::vector<std::size_t> idx(out.basins.rest.size());
    for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
    std::sort(idx.begin(), idx.end(),
              [&](std::size_t x, std::size_t y) { return out.basins.rest[x] < out.basins.rest[y]; });
    bool sorted = true;
    for (std::size_t i = 0; i < idx.size() && sorted; ++i) sorted = idx[i] == i;
    if (!sorted) {
      HoldBasins s;
      for (std::vector<double>* v : {&s.rest, &s.weight, &s.hold, &s.inertial}) v->reserve(idx.size());
      for (std::size_t i : idx) {
        s.rest.push_back(out.basins.rest[i]);
        s.weight.push_back(out.basins.weight[i]);
        s.hold.push_back(out.basins.hold[i]);
        s.inertial.push_back(out.basins.inertial[i]);
      }
      out.basins = std::move(s);
    }
  }
  // Every drop of a basin gives its basin's angles: the statistics over basins weighted by width.
  std::vector<util::ValueWeight> scratch;
  out.hold = weighted_stats(out.basins.hold, out.basins.weight, scratch);
  out.inertial = weighted_stats(out.basins.inertial, out.basins.weight, scratch);
  out.drop_min = mirrored ? -b : a;
  out.drop_max = mirrored ? -a : b;
  out.near_end = near_end;
  return out;
}

}  // namespace

namespace {

// A point of the lift with its one-sided slopes, as the signature lists them.
struct LiftPoint {
  double s, h, left, right;
};

// The LiftCurve through n points get(i) (offsets increasing), with a vertex where the tangent
// lines of an interval's two ends meet inside it (see hold.hpp). The meeting points are found
// first (one pass), then the curve is written at its exact size. Both passes run in `threads`
// contiguous chunks of the points (get(i) is read from any thread, in increasing i within a
// chunk); the curve and the first error do not depend on their number.
//
// `head` / `tail` (optional, not periodic): curves built the same way over the points that come
// before / after these, whose last / first vertex is point 0 / n - 1 (the same point): the curve
// written is head, then these points' curve, then tail, as one build over all the points would
// write it (a vertex depends on its point, a meeting point on the two points around it only).
template <class Get>
Result<LiftCurve> build_curve(std::size_t n, bool slopes, double period, unsigned threads, Get&& get,
                              const LiftCurve* head = nullptr, const LiftCurve* tail = nullptr) {
  if (n < 2) return make_error(fmt::format("lift_curve: the signature has {} offsets: expected at least two", n));
  const unsigned T = std::max(1u, std::min<unsigned>(threads, static_cast<unsigned>(n / 4096 + 1)));
  struct Chunk {
    std::vector<double> kx, kh;  // meeting points, in order
    std::size_t error_at = static_cast<std::size_t>(-1);
    std::size_t skipped = 0;  // points at the offset of the point before them (written once)
    bool not_finite = false;
  };
  constexpr std::uint8_t kMeeting = 1, kSkipPoint = 2;
  std::vector<Chunk> chunks(T);
  // kink[i]: kMeeting, a meeting point between points i - 1 and i; kSkipPoint, point i coincides
  // with point i - 1 and is not written.
  std::vector<std::uint8_t> kink(n, 0);
  util::parallel_chunks(n, T, [&](unsigned c, std::size_t i0, std::size_t i1) {
    Chunk& ch = chunks[c];
    // At most one meeting point per interval: reserved at once (pages are taken only as they are
    // written; no copy of a half-grown vector beside the new one).
    if (slopes) {
      ch.kx.reserve(i1 - i0);
      ch.kh.reserve(i1 - i0);
    }
    LiftPoint prev = i0 > 0 ? get(i0 - 1) : LiftPoint{};
    // tan(prev.right) once computed, and a tan reused where its angle repeats bit for bit (a
    // contact that slides along one edge from one event to the next has that edge's angle on both
    // sides of the interval): the same values, fewer tan calls.
    bool have_tan_right = false;
    double tan_right = 0;
    auto same = [](double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); };
    for (std::size_t i = i0; i < i1; ++i) {
      const LiftPoint q = get(i);
      if (!std::isfinite(q.s) || !std::isfinite(q.h)) {
        ch.error_at = i;
        ch.not_finite = true;
        return;
      }
      if (i > 0 && q.s == prev.s) {
        // Two events at one offset (the same contact change reached from two sides, or two sets of
        // points merged): one vertex, with the later event's slope to its right.
        kink[i] = kSkipPoint;
        ++ch.skipped;
        prev.right = q.right;
        have_tan_right = false;
        continue;
      }
      if (i > 0 && !(q.s > prev.s)) {
        ch.error_at = i;
        return;
      }
      if (i > 0 && slopes) {
        // The tangent lines at both ends of the interval meet inside it: a vertex there.
        const double x0 = prev.s, x1 = q.s, h0 = prev.h, h1 = q.h;
        const double m0 = have_tan_right ? tan_right : std::tan(prev.right);
        const double m1 = same(q.left, prev.right) ? m0 : std::tan(q.left);
        tan_right = same(q.right, q.left) ? m1 : std::tan(q.right);
        have_tan_right = true;
        if (std::isfinite(m0) && std::isfinite(m1) && m0 != m1) {
          const double xs = (h1 - h0 + m0 * x0 - m1 * x1) / (m0 - m1);
          const double span = x1 - x0, eps = 1e-9 * span;
          // A meeting point at an end within rounding (a vertical wall of h: theta = 90 deg on one
          // side) is kept just inside, so the wall stays a piece of (nearly) infinite slope.
          // No vertex where one tangent already joins both ends (a kink at the event itself).
          const double tol = 1e-9 * std::abs(h1 - h0) + 1e-14 * std::max(std::abs(h0), std::abs(h1));
          const bool joined = std::abs(h0 + m0 * span - h1) <= tol || std::abs(h1 - m1 * span - h0) <= tol;
          const double xc = std::clamp(xs, x0 + eps, x1 - eps);
          // An interval too short for a point strictly inside it (two events within a few ulps of
          // each other, as the offsets of an x column printed with 8 digits give): no vertex; the
          // piece between the events is their chord, off the tangents by rounding only.
          if (!joined && xs > x0 - 1e-6 * span && xs < x1 + 1e-6 * span && xc > x0 && xc < x1) {
            kink[i] = kMeeting;
            ch.kx.push_back(xc);
            // Height from the flatter tangent (the steeper one may be a wall, tan(90 deg) ~ 1e16).
            ch.kh.push_back(std::abs(m0) <= std::abs(m1) ? h0 + m0 * (xc - x0) : h1 + m1 * (xc - x1));
          }
        }
      }
      prev = q;
    }
  });
  std::size_t kinks = 0, skipped = 0;
  std::vector<std::ptrdiff_t> before(T);  // meeting points less skipped points before chunk c
  for (unsigned c = 0; c < T; ++c) {
    if (chunks[c].error_at != static_cast<std::size_t>(-1))
      return make_error(
          chunks[c].not_finite
              ? fmt::format("lift_curve: offset {} of the signature is not finite", chunks[c].error_at)
              : fmt::format("lift_curve: the signature's offsets must increase (offset {})", chunks[c].error_at));
    before[c] = kinks - skipped;
    kinks += chunks[c].kx.size();
    skipped += chunks[c].skipped;
  }
  LiftCurve c;
  c.period = period;
  const std::size_t nh = head ? head->offset.size() - 1 : 0, nt = tail ? tail->offset.size() - 1 : 0;
  c.offset.resize(nh + n - skipped + kinks + nt);
  c.lift.resize(nh + n - skipped + kinks + nt);
  if (head) {
    std::copy(head->offset.begin(), head->offset.end() - 1, c.offset.begin());
    std::copy(head->lift.begin(), head->lift.end() - 1, c.lift.begin());
  }
  if (tail) {
    std::copy(tail->offset.begin() + 1, tail->offset.end(), c.offset.end() - static_cast<std::ptrdiff_t>(nt));
    std::copy(tail->lift.begin() + 1, tail->lift.end(), c.lift.end() - static_cast<std::ptrdiff_t>(nt));
  }
  util::parallel_chunks(n, T, [&](unsigned t, std::size_t i0, std::size_t i1) {
    const Chunk& ch = chunks[t];
    std::size_t w = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(nh + i0) + before[t]), k = 0;
    for (std::size_t i = i0; i < i1; ++i) {
      if (kink[i] == kSkipPoint) continue;
      if (kink[i] == kMeeting) {
        c.offset[w] = ch.kx[k];
        c.lift[w] = ch.kh[k];
        ++w;
        ++k;
      }
      const LiftPoint q = get(i);
      c.offset[w] = q.s;
      c.lift[w] = q.h;
      ++w;
    }
  });
  if (period > 0) {
    const double span = c.offset.back() - c.offset.front();
    if (std::abs(span - period) > 1e-6 * period)
      return make_error(fmt::format("lift_curve: the signature spans {} m, not one period of {} m", span, period));
    c.offset.back() = c.offset.front() + period;  // exactly one period
  }
  if (auto st = check_curve(c); !st) return st.error();
  return c;
}

}  // namespace

Result<LiftCurve> lift_curve(const SignatureResult& sig, double period) {
  const std::size_t n = sig.offset.size();
  if (n < 2 || sig.lift.size() != n)
    return make_error(fmt::format("lift_curve: the signature has {} offsets: expected at least two", n));
  const bool slopes = sig.theta_left.size() == n && sig.theta_right.size() == n;
  return build_curve(n, slopes, period, 1, [&](std::size_t i) {
    return LiftPoint{sig.offset[i], sig.lift[i], slopes ? sig.theta_left[i] : 0.0, slopes ? sig.theta_right[i] : 0.0};
  });
}

namespace {

// hold_angle and hold_distribution on a curve already checked (check_curve).
Result<HoldAngles> hold_angle_checked(const LiftCurve& curve, double start, const HoldOptions& options) {
  if (auto st = check_options(options); !st) return st.error();
  const double lo = curve.offset.front(), hi = curve.offset.back();
  if (!std::isfinite(start) || (curve.period == 0 && (start < lo || start > hi)))
    return make_error(fmt::format("hold: start offset {} m: expected an offset in [{}, {}] m", start, lo, hi));
  HoldAngles out;
  {
    const Frame fr = make_frame(curve, false, options.runaway_distance);
    out.forward = with_view(curve, false, [&](const auto& p) { return single(fr, p, wrap(fr, start), options); });
  }
  {
    const Frame fr = make_frame(curve, true, options.runaway_distance);
    out.backward =
        unmirror(with_view(curve, true, [&](const auto& p) { return single(fr, p, wrap(fr, -start), options); }));
  }
  if (curve.period > 0) {  // report rest offsets in the base period
    const double p = curve.period;
    for (HoldAngle* h : {&out.forward, &out.backward}) {
      const double shift = std::floor((h->rest_offset - lo) / p) * p;
      h->rest_offset -= shift;
      h->hold_offset -= shift;
      h->runaway_end -= shift;
      h->inertial_offset -= shift;
    }
  }
  return out;
}

Result<HoldDistributions> hold_distribution_checked(const LiftCurve& curve, const HoldOptions& options) {
  if (auto st = check_options(options); !st) return st.error();
  const double lo = curve.offset.front(), hi = curve.offset.back();
  double a = options.drop_min, b = options.drop_max;
  if (!(b > a)) {
    a = lo;
    b = hi;
  }
  if (a < lo - 1e-12 * (hi - lo) || b > hi + 1e-12 * (hi - lo))
    return make_error(
        fmt::format("hold: drop range [{}, {}] m: expected a range inside the lift's [{}, {}] m", a, b, lo, hi));
  a = std::max(a, lo);
  b = std::min(b, hi);
  HoldDistributions out;
  const Frame ff = make_frame(curve, false, options.runaway_distance);
  const Frame fb = make_frame(curve, true, options.runaway_distance);
  // The two directions are independent: one thread each where there are two. (Where there is
  // one, the backward pass 1 is the forward one mirrored where they match: mirror_basins.)
  const unsigned threads = util::thread_count(options.threads, 2);
  Basins pf, pb;
  bool have_pf = false, have_pb = false;
  if (curve.period == 0 && threads < 2) {
    pf = basins_of(ff, LinearView<false>(curve), a, b, options, true);
    have_pf = true;
    if (pf.mirrorable) have_pb = mirror_basins(LinearView<true>(curve), pf, -b, -a, pb);
    std::vector<std::size_t>().swap(pf.start);
  }
  util::parallel_chunks(2, threads, [&](unsigned, std::size_t i0, std::size_t i1) {
    for (std::size_t i = i0; i < i1; ++i) {
      if (i == 0)
        out.forward = with_view(curve, false, [&](const auto& p) {
          return distribution(ff, p, a, b, options, false,
                              have_pf ? std::move(pf) : basins_of(ff, p, a, b, options, false));
        });
      else
        out.backward = with_view(curve, true, [&](const auto& p) {
          return distribution(fb, p, -b, -a, options, true,
                              have_pb ? std::move(pb) : basins_of(fb, p, -b, -a, options, false));
        });
    }
  });
  return out;
}

}  // namespace

Result<HoldAngles> hold_angle(const LiftCurve& curve, double start, const HoldOptions& options) {
  if (auto st = check_curve(curve); !st) return st.error();
  return hold_angle_checked(curve, start, options);
}

Result<HoldDistributions> hold_distribution(const LiftCurve& curve, const HoldOptions& options) {
  if (auto st = check_curve(curve); !st) return st.error();
  return hold_distribution_checked(curve, options);
}

std::vector<std::int32_t> basin_index(const LiftCurve& curve, const std::vector<double>& offsets) {
  std::vector<std::int32_t> out(offsets.size(), -1);
  if (!check_curve(curve).ok()) return out;
  const View base = make_view(curve, false);
  Descents<View> ds(base);
  // Basins numbered by increasing rest offset: the local minima (rest vertices) and flat pieces.
  std::vector<std::int64_t> keys;
  auto key_of = [&](double x) -> std::int64_t {
    const Rest r = rest_of(base, ds, x);
    std::int64_t v = r.vertex >= 0 ? r.vertex : r.flat;
    // A flat piece k and its start vertex k (where a descent onto it stops) are one basin.
    if (curve.period > 0 && static_cast<std::size_t>(v) == base.n()) v = 0;  // the same vertex a period on
    return v;
  };
  const double lo = curve.offset.front(), hi = curve.offset.back();
  std::vector<std::int64_t> k(offsets.size(), -1);
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    double x = offsets[i];
    if (curve.period > 0 && std::isfinite(x)) {
      x = lo + std::fmod(x - lo, curve.period);
      if (x < lo) x += curve.period;
    }
    if (!(x >= lo && x <= hi)) continue;
    k[i] = key_of(x);
    keys.push_back(k[i]);
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  for (std::size_t i = 0; i < offsets.size(); ++i)
    if (k[i] >= 0) out[i] = static_cast<std::int32_t>(std::lower_bound(keys.begin(), keys.end(), k[i]) - keys.begin());
  return out;
}

OffsetRange hold_lift_range(double drop_min, double drop_max, double d, double lower_length, double upper_length) {
  OffsetRange r{drop_min - d, drop_max + d};
  // Keep a sliver of overlap at both ends (the lift is defined while the blocks overlap).
  const double lo = -upper_length * (1 - 1e-6), hi = lower_length * (1 - 1e-6);
  r.min = std::max(r.min, lo);
  r.max = std::min(r.max, hi);
  return r;
}

double default_runaway_distance(double offset_min, double offset_max, double period) {
  if (period > 0) return period;
  return 0.1 * (offset_max - offset_min);
}

namespace {

// The analysis on its own lift, a signature over the range the process needs, widened until no
// run-away runs off a cut end: the way for spheropolygon faces (whose lift is not extended).
Result<HoldAnalysis> analyse_hold_widened(const Profile& lower, const Profile& upper, const SignatureOptions& so,
                                          const HoldOptions& hold, double start) {
  if (auto st = validate(lower, "lower surface"); !st) return st.error();
  if (auto st = validate(upper, "upper surface"); !st) return st.error();
  const double lower_len = lower.x.back() - lower.x.front(), upper_len = upper.x.back() - upper.x.front();
  const double period = lower.period.value_or(0.0);
  double a = so.offset_min, b = so.offset_max;
  if (!(b > a)) {
    a = 0;
    b = period > 0 ? period : 0.5 * std::min(lower_len, upper_len);
  }
  if (period > 0 && std::abs((b - a) - period) > 1e-9 * period)
    return make_error(
        fmt::format("hold: a periodic pair is analysed over one period ({} m), not over [{}, {}] m", period, a, b));
  HoldAnalysis out;
  out.runaway_distance = hold.runaway_distance > 0 ? hold.runaway_distance : default_runaway_distance(a, b, period);
  HoldOptions ho = hold;
  ho.runaway_distance = out.runaway_distance;
  if (!std::isnan(start) && !std::isfinite(start))
    return make_error(fmt::format("start offset {} m: expected a finite offset", start));
  if (std::isfinite(start) && (start < a || start > b))
    return make_error(
        fmt::format("start offset {} m: expected an offset in the signature's range [{}, {}] m", start, a, b));
  const double overlap = std::min(lower_len, upper_len);
  if (period == 0 && !(out.runaway_distance < overlap))
    return make_error(
        fmt::format("runaway_distance = {} m: expected a length > 0 and shorter than the blocks' "
                    "overlap ({} m)",
                    out.runaway_distance, overlap));
  if (auto st = check_options(ho); !st) return st.error();
  SignatureOptions o = so;
  o.keep_contacts = false;
  ho.drop_min = a;
  ho.drop_max = b;
  const OffsetRange whole = hold_lift_range(a, b, std::numeric_limits<double>::infinity(), lower_len, upper_len);
  // Non-periodic: widen the lift until no run-away runs off a cut end (a chain of short slips can
  // carry a block more than d from its rest); the blocks' overlap is the last end.
  for (double margin = 2 * out.runaway_distance;; margin *= 2) {
    if (period > 0) {
      o.offset_min = a;
      o.offset_max = b;
    } else {
      const OffsetRange r = hold_lift_range(a, b, margin, lower_len, upper_len);
      o.offset_min = r.min;
      o.offset_max = r.max;
    }
    auto sig = signature(lower, upper, o);
    if (!sig) return with_prefix("hold: ", sig.error());
    out.events = sig->offset.size();
    out.exact = sig->exact;
    auto curve = lift_curve(*sig, period);
    if (!curve) return curve.error();
    out.curve = std::move(*curve);
    auto dist = hold_distribution(out.curve, ho);
    if (!dist) return dist.error();
    out.distribution = std::move(*dist);
    out.has_start = false;
    if (std::isfinite(start)) {
      auto h = hold_angle(out.curve, start, ho);
      if (!h) return h.error();
      out.start = *h;
      out.has_start = true;
    }
    if (period > 0) break;
    const bool cut_max = o.offset_max<whole.max, cut_min = o.offset_min> whole.min;
    const double d = out.runaway_distance;
    const bool off_max =
        out.distribution.forward.near_end > 0 ||
        (out.has_start && out.start.forward.ran_off_end && out.curve.offset.back() - out.start.forward.hold_offset < d);
    const bool off_min =
        out.distribution.backward.near_end > 0 || (out.has_start && out.start.backward.ran_off_end &&
                                                   out.start.backward.hold_offset - out.curve.offset.front() < d);
    // A rest less than d from a cut end: its inertial window reaches past the end.
    auto rests_near = [&](const HoldDistribution& hd, const HoldAngle& st, bool forward) {
      std::vector<double> rests = hd.basins.rest;
      if (out.has_start) rests.push_back(st.rest_offset);
      for (double r : rests)
        if (forward ? r + d > out.curve.offset.back() : r - d < out.curve.offset.front()) return true;
      return false;
    };
    const bool near_max = off_max || rests_near(out.distribution.forward, out.start.forward, true);
    const bool near_min = off_min || rests_near(out.distribution.backward, out.start.backward, false);
    if (!((near_max && cut_max) || (near_min && cut_min))) break;
  }
  return out;
}

}  // namespace

namespace {

// The drop range, run-away distance and checks of the hold analysis of a pair (hold.hpp).
struct HoldSetup {
  double a = 0, b = 0, period = 0, lower_len = 0, upper_len = 0;
  HoldOptions ho;  // runaway_distance set, drop range [a, b]
};

Result<HoldSetup> hold_setup(const Profile& lower, const Profile& upper, const SignatureOptions& so,
                             const HoldOptions& hold, double start) {
  if (auto st = validate(lower, "lower surface"); !st) return st.error();
  if (auto st = validate(upper, "upper surface"); !st) return st.error();
  HoldSetup s;
  s.lower_len = lower.x.back() - lower.x.front();
  s.upper_len = upper.x.back() - upper.x.front();
  s.period = lower.period.value_or(0.0);
  double a = so.offset_min, b = so.offset_max;
  if (!(b > a)) {
    a = 0;
    b = s.period > 0 ? s.period : 0.5 * std::min(s.lower_len, s.upper_len);
  }
  if (s.period > 0 && std::abs((b - a) - s.period) > 1e-9 * s.period)
    return make_error(
        fmt::format("hold: a periodic pair is analysed over one period ({} m), not over [{}, {}] m", s.period, a, b));
  s.ho = hold;
  if (s.ho.threads == 0) s.ho.threads = so.threads;
  s.ho.runaway_distance = hold.runaway_distance > 0 ? hold.runaway_distance : default_runaway_distance(a, b, s.period);
  if (!std::isnan(start) && !std::isfinite(start))
    return make_error(fmt::format("start offset {} m: expected a finite offset", start));
  if (std::isfinite(start) && (start < a || start > b))
    return make_error(
        fmt::format("start offset {} m: expected an offset in the signature's range [{}, {}] m", start, a, b));
  const double overlap = std::min(s.lower_len, s.upper_len);
  if (s.period == 0 && !(s.ho.runaway_distance < overlap))
    return make_error(
        fmt::format("runaway_distance = {} m: expected a length > 0 and shorter than the blocks' "
                    "overlap ({} m)",
                    s.ho.runaway_distance, overlap));
  if (auto st = check_options(s.ho); !st) return st.error();
  s.ho.drop_min = a;
  s.ho.drop_max = b;
  s.a = a;
  s.b = b;
  return s;
}

// Distribution and start on `curve`; which cut ends the process reached: a run-away that ran
// off the end less than d after its stop, or a rest less than d before it (its inertial window
// reaches past the end). A chain of short slips can carry a block more than d from its rest.
struct Reach {
  bool max = false, min = false;
};

Result<Reach> analyse_curve(HoldAnalysis& out, const HoldOptions& ho, double start) {
  auto dist = hold_distribution_checked(out.curve, ho);  // built by build_curve: checked
  if (!dist) return dist.error();
  out.distribution = std::move(*dist);
  out.has_start = false;
  if (std::isfinite(start)) {
    auto h = hold_angle_checked(out.curve, start, ho);
    if (!h) return h.error();
    out.start = *h;
    out.has_start = true;
  }
  const double d = out.runaway_distance;
  const bool off_max =
      out.distribution.forward.near_end > 0 ||
      (out.has_start && out.start.forward.ran_off_end && out.curve.offset.back() - out.start.forward.hold_offset < d);
  const bool off_min =
      out.distribution.backward.near_end > 0 || (out.has_start && out.start.backward.ran_off_end &&
                                                 out.start.backward.hold_offset - out.curve.offset.front() < d);
  auto rests_near = [&](const HoldDistribution& hd, const HoldAngle& st, bool forward) {
    auto near = [&](double r) { return forward ? r + d > out.curve.offset.back() : r - d < out.curve.offset.front(); };
    if (out.has_start && near(st.rest_offset)) return true;
    for (double r : hd.basins.rest)
      if (near(r)) return true;
    return false;
  };
  Reach r;
  r.max = off_max || rests_near(out.distribution.forward, out.start.forward, true);
  r.min = off_min || rests_near(out.distribution.backward, out.start.backward, false);
  return r;
}

// The merged lift points W = (R without `dropped`) + E, as runs of consecutive points from one
// source (in exact mode three: E below R's range, R, E above it), read at random.
struct MergedPoints {
  const SignatureResult& R;
  const detail::LiftPoints& E;
  struct Run {
    std::size_t w0;  // index in W of its first point
    std::size_t i0;  // index of that point in its source
    bool from_r;
  };
  std::vector<Run> runs;
  std::size_t nw = 0;

  MergedPoints(const SignatureResult& r, const detail::LiftPoints& e, const std::vector<std::size_t>& dropped)
      : R(r), E(e) {
    const std::size_t nr = R.offset.size(), ne = E.offset.size();
    nw = nr - dropped.size() + ne;
    // Whole runs at a time: R's points below E's next one (up to the next dropped index), then
    // E's points up to R's next one (a point of R before an equal one of E, as one by one).
    std::size_t ir = 0, ie = 0, id = 0, w = 0;
    const double* ro = R.offset.data();
    const double* eo = E.offset.data();
    while (w < nw) {
      while (id < dropped.size() && dropped[id] == ir) {
        ++ir;
        ++id;
      }
      const bool has_r = ir < nr, has_e = ie < ne;
      if (!has_r && !has_e) break;
      if (has_r && (!has_e || ro[ir] < eo[ie])) {
        std::size_t end = id < dropped.size() ? std::min(nr, dropped[id]) : nr;
        if (has_e) end = static_cast<std::size_t>(std::lower_bound(ro + ir, ro + end, eo[ie]) - ro);
        runs.push_back({w, ir, true});
        w += end - ir;
        ir = end;
      } else {
        const std::size_t end = has_r ? static_cast<std::size_t>(std::upper_bound(eo + ie, eo + ne, ro[ir]) - eo) : ne;
        runs.push_back({w, ie, false});
        w += end - ie;
        ie = end;
      }
    }
  }
  std::size_t size() const { return nw; }
  // Point w (the runs are few in exact mode: a search among them).
  LiftPoint get(std::size_t w) const {
    const auto it = std::upper_bound(runs.begin(), runs.end(), w, [](std::size_t x, const Run& u) { return x < u.w0; });
    const Run& u = *(it - 1);
    const std::size_t i = u.i0 + (w - u.w0);
    if (u.from_r) return LiftPoint{R.offset[i], R.lift[i], R.theta_left[i], R.theta_right[i]};
    return LiftPoint{E.offset[i], E.lift[i], E.left[i], E.right[i]};
  }
  double offset(std::size_t w) const { return get(w).s; }
  // The first w with offset(w) >= x (strictly > x with `after`), as std::lower_bound (upper_bound).
  std::size_t first_at(double x, bool after) const {
    std::size_t lo = 0, len = nw;
    while (len > 0) {
      const std::size_t half = len / 2;
      const double v = offset(lo + half);
      if (after ? !(v > x) : v < x) {
        lo += half + 1;
        len -= half + 1;
      } else {
        len = half;
      }
    }
    return lo;
  }
};

// The curve through the points [first, last) of W, on up to `threads` threads.
Result<LiftCurve> merged_curve(const MergedPoints& mp, std::size_t first, std::size_t last, unsigned threads) {
  return build_curve(last - first, true, 0.0, threads, [&](std::size_t w) { return mp.get(first + w); });
}

// A curve of the points at one end of W, built for an end check, kept for the whole curve: it
// covers W's first (head) or last (tail) `points` points. A side widened after its check lets
// its curve go and builds it anew (grown from the old one, both would be held at once: +20 MB at
// the H = 0.3 pair's peak for 0.06 s of CPU).
struct EndCurve {
  LiftCurve curve;
  std::size_t points = 0;  // 0: none
  void reset() {
    curve = LiftCurve{};
    points = 0;
  }
};

// The curve through all of W: the end curves where they still cover W's end points (W only grows
// by points beyond a cut end, which moves its head's or tail's points; a moved end curve is
// rebuilt with the rest), the points between them built here.
Result<LiftCurve> whole_curve(const MergedPoints& mp, EndCurve& head, EndCurve& tail, unsigned threads) {
  const std::size_t nw = mp.size();
  auto covers = [&](const EndCurve& e, std::size_t first) {
    return e.points >= 2 && e.points <= nw && e.curve.offset.front() == mp.offset(first) &&
           e.curve.offset.back() == mp.offset(first + e.points - 1);
  };
  const bool use_head = covers(head, 0), use_tail = covers(tail, nw - std::min(nw, tail.points));
  const std::size_t m0 = use_head ? head.points - 1 : 0, m1 = use_tail ? nw - tail.points + 1 : nw;
  if (!(m1 >= m0 + 2)) {  // the end curves meet: one build
    head.reset();
    tail.reset();
    return merged_curve(mp, 0, nw, threads);
  }
  auto c = build_curve(
      m1 - m0, true, 0.0, threads, [&](std::size_t w) { return mp.get(m0 + w); }, use_head ? &head.curve : nullptr,
      use_tail ? &tail.curve : nullptr);
  head.reset();
  tail.reset();
  return c;
}

// Merges two increasing point sets (offsets distinct), one array at a time (each source array
// let go as soon as its merged array is written: the merged set and both sources are not held
// at once).
detail::LiftPoints merge_points(detail::LiftPoints a, detail::LiftPoints b) {
  if (a.offset.empty()) return b;
  if (b.offset.empty()) return a;
  struct Run {
    bool from_a;
    std::size_t begin, end;
  };
  std::vector<Run> runs;  // whole runs of one source, in the merged order
  {
    const std::vector<double>& ao = a.offset;
    const std::vector<double>& bo = b.offset;
    std::size_t i = 0, j = 0;
    while (i < ao.size() || j < bo.size()) {
      if (j >= bo.size() || (i < ao.size() && ao[i] < bo[j])) {  // a's points below b's next one
        const std::size_t e =
            j < bo.size()
                ? static_cast<std::size_t>(
                      std::lower_bound(ao.begin() + static_cast<std::ptrdiff_t>(i), ao.end(), bo[j]) - ao.begin())
                : ao.size();
        runs.push_back({true, i, e});
        i = e;
      } else {  // b's points up to a's next one (b before an equal point of a, as one by one)
        const std::size_t e =
            i < ao.size()
                ? static_cast<std::size_t>(
                      std::upper_bound(bo.begin() + static_cast<std::ptrdiff_t>(j), bo.end(), ao[i]) - bo.begin())
                : bo.size();
        runs.push_back({false, j, e});
        j = e;
      }
    }
  }
  const std::size_t n = a.offset.size() + b.offset.size();
  detail::LiftPoints m;
  auto merge = [&](std::vector<double>& x, std::vector<double>& y, std::vector<double>& out) {
    out.reserve(n);
    for (const Run& r : runs) {
      const std::vector<double>& src = r.from_a ? x : y;
      out.insert(out.end(), src.begin() + static_cast<std::ptrdiff_t>(r.begin),
                 src.begin() + static_cast<std::ptrdiff_t>(r.end));
    }
    std::vector<double>().swap(x);
    std::vector<double>().swap(y);
  };
  merge(a.lift, b.lift, m.lift);
  merge(a.left, b.left, m.left);
  merge(a.right, b.right, m.right);
  merge(a.offset, b.offset, m.offset);
  return m;
}

// Whether the lift cut at one end reaches far enough for the drops of [a, b] (forward: the end
// after b; backward: mirrored), decided on the lift near that end only (`local`: the curve over
// the points from about d before the range end to the cut end). A conservative form of the
// criteria that analyse_curve() reads off the whole analysis (so the faces can be let go before
// it): every drop of [a, b] rests at or before R_b (b, or where the descent from b ends), so
// (1) the inertial windows end before the cut end if R_b + d <= end; (2) a record chain that
// reaches past R_b passes a vertex in (R_b - d, R_b] (its slips are shorter than d) and goes on
// as that vertex's chain, so if no chain from a vertex there (or from the next record of a flat
// piece there) runs off the end less than d after its stop, none from the drops does.
// Returns how much farther the end must lie, at least, for the criteria to hold (0: they hold).
template <class V>
double end_reached_on(const V& p, double b, double d) {
  const std::size_t n = p.n();
  const double end = p.X(n);
  Descents<V> ds(p);
  const std::size_t kb = piece_of(p, b);
  double rb = b;
  if (p.M(kb) < 0) rb = std::max(b, p.X(ds.forward(kb + 1)));  // the descent from b ends ahead
  if (!(rb + d <= end)) return rb + d - end;
  // Chains of every vertex in (rb - d, rb], from the right with the record stack.
  RecordStack records;
  double short_by = 0;
  auto off_near = [&](const Chain& c) {
    const double x_held = p.X(static_cast<std::size_t>(c.held));
    if (c.run_end < 0 && end - x_held < d) short_by = std::max(short_by, x_held + d - end);
    return false;
  };
  for (std::size_t kk = n; kk-- > 0;) {
    const double xk = p.X(kk);
    // A flat piece that starts at or before rb - d but reaches past it: its drops in (rb - d, rb]
    // slip first to its next record, which may lie past rb with no vertex of the window before it.
    const bool flat_into = xk <= rb - d && p.M(kk) == 0 && p.X(kk + 1) > rb - d;
    if (xk <= rb - d && !flat_into) break;
    const Chain c = records.push(p, kk, d);
    if (xk <= rb && !flat_into) off_near(c);
    if (xk <= rb && p.M(kk) == 0) {  // a flat piece: drops on it slip first to its next record
      const std::int64_t j = next_record(p, kk);
      if (j < 0) continue;  // drops there run off the end from at most rb, which is d before it
      // j's entry: on the stack (it is a strict record of kk, being the first above a threshold).
      for (const RecordStack::Entry& e : records.entries())
        if (e.k == static_cast<std::size_t>(j)) off_near(e.c);
    }
    if (flat_into) break;
  }
  return short_by;
}

double end_reached(const LiftCurve& local, bool mirrored, double b, double d) {
  return with_view(local, mirrored, [&](const auto& p) { return end_reached_on(p, b, d); });
}

// The one pass: the signature over its range, then, with the same prepared faces, the lift
// beyond it on the sides the process reaches, then (the faces let go) the analysis.
// Exact mode: each side from 1.55 d (end_reached()'s need on the three benchmark pairs of issue
// 32: 1.50 and 1.52 d for H = 0.8, 1.32 and 2.58 d for H = 0.3, 1.03 and 1.47 d for the WM pair;
// a round plans the wide range's new offsets and rebuilds the widened side's local curve),
// widened by what end_reached() finds short and d/5 while it says the process may reach the cut
// end (a side that passed is not checked again); the offsets are those a signature over the
// wider range lists, so the curve, and every number, is that of a lift computed over it (after
// a second round the first round's cut end stays an offset as well: one vertex more on a piece
// of the same lift, test Hold.OnePassCurveIsTheLiftOfItsRangeToTheBit). Sampled offsets: the widened
// range and its grid as analyse_hold_widened takes them (2 d on both sides, doubled on the whole
// analysis).
Result<SignatureWithHold> one_pass(const Profile& lower, const Profile& upper, const SignatureOptions& so,
                                   const HoldOptions& hold, double start, Profile* take_lower, Profile* take_upper) {
  auto setup = hold_setup(lower, upper, so, hold, start);
  if (!setup) return setup.error();
  const HoldSetup S = *setup;
  SignatureWithHold res;
  HoldAnalysis& out = res.hold;
  out.runaway_distance = S.ho.runaway_distance;
  if (so.spheroradius > 0) {
    auto h = analyse_hold_widened(lower, upper, so, hold, start);
    if (!h) return h.error();
    out = std::move(*h);
    if (!S.ho.keep_curve) out.curve = LiftCurve{};
    auto sig = take_lower && take_upper ? signature(std::move(*take_lower), std::move(*take_upper), so)
                                        : signature(lower, upper, so);
    if (!sig) return sig.error();
    res.signature = std::move(*sig);
    return res;
  }
  const double d = S.ho.runaway_distance;
  const OffsetRange whole =
      hold_lift_range(S.a, S.b, std::numeric_limits<double>::infinity(), S.lower_len, S.upper_len);
  // A lift cut at an end is analysed inside, while the faces can still widen it; a lift over the
  // whole overlap (or one period) after the faces are let go.
  bool analysed = false;
  detail::LiftPoints ext_points;
  std::vector<std::size_t> ext_dropped;
  // Exact mode: the end checks' curves of the last round, the whole curve's ends (not built twice).
  EndCurve head_end, tail_end;
  // Builds the curve from R and the extension, analyses it; the side(s) the process reached.
  // The points beyond the range are let go once the curve holds them (the sampled path's next
  // round evaluates its own).
  // `keep_points`: the points beyond the range stay (a cut end may still be widened with them).
  auto build_and_analyse = [&](const SignatureResult& R, bool keep_points) -> Result<Reach> {
    {
      MergedPoints mp(R, ext_points, ext_dropped);
      auto curve = whole_curve(mp, head_end, tail_end, util::thread_count(so.threads, 2));
      if (!curve) return curve.error();
      out.curve = std::move(*curve);
    }
    if (!keep_points) ext_points = detail::LiftPoints{};
    auto reach = analyse_curve(out, S.ho, start);
    return reach;
  };
  const detail::WithLift with_lift = [&](const SignatureResult& R, const detail::LiftExtender& extend) -> Status {
    if (S.period > 0) return Ok{};  // the signature's own lift: exactly one period
    const bool sampled = !R.exact || so.offsets > 0;
    double m_lo = sampled ? 2 * d : 1.55 * d, m_hi = m_lo;
    // Exact mode on a small lift: the whole overlap at once (HoldOptions::whole_lift_offsets,
    // 10^5 by default): the end checks are a saving for long pairs only, and on about 1 % of
    // small random pairs they let a lift through that is too short for the process (3 of 400
    // against the lift over the whole overlap).
    if (const double span = R.offset.empty() ? 0.0 : R.offset.back() - R.offset.front(); !sampled && span > 0) {
      const double per_m = double(R.offset.size() - 1) / span;  // the signature's offsets per metre
      if ((whole.max - whole.min) * per_m <= S.ho.whole_lift_offsets)
        m_lo = m_hi = std::numeric_limits<double>::infinity();
    }
    // Exact mode: a side whose check passed is not widened again, and the points near its end do
    // not change when the other side is widened: it is not checked again.
    bool passed_max = false, passed_min = false;
    int widened_max = 0, widened_min = 0;  // exact mode: rounds that widened each side
    // Exact mode, the curve not kept: the lift beyond what the inertial windows read (every drop
    // rests at or before q, the first rise after b, mirrored before a) in blocks whose slopes are
    // bounded by the steepest piece of the lift between b and the inner range's end is left out
    // but for its ends (detail::LiftPruneRequest). Every chain that gets there stops at a piece
    // at least that steep or steeper than all pieces between b and there (a record is steeper than
    // the stop before it, the pieces a slip passes are not), so no piece of such a block, nor the
    // chord that joins its ends, is a record of any chain: the stops, slips and run-away ends,
    // the inertial windows (which end by q + d) and the end checks are those of the whole lift.
    // Blocks are left out only beyond q + d (forward) and before q' - d (backward). The curve
    // then differs from the lift there (chords), so not with keep_curve.
    detail::LiftPruneRequest prune_req;
    std::vector<double> ext_skipped, have_all;
    const bool use_prune = !sampled && !S.ho.keep_curve;
    if (use_prune) {
      prune_req.inner_lo = S.a - 1.02 * d;
      prune_req.inner_hi = S.b + 1.02 * d;
      prune_req.decide = [&, decided = false, found = detail::LiftPrune{}](
                             const double* io, const double* ih, std::size_t ni,
                             const std::vector<std::size_t>& dropped) mutable {
        if (decided) return found;
        decided = true;
        // W's points so far: R's (but the dropped ones, a few at its ends), then the inner ones
        // beyond R's range (or before it).
        auto kept = [&](std::size_t j) { return !std::binary_search(dropped.begin(), dropped.end(), j); };
        const auto i_above = static_cast<std::size_t>(std::upper_bound(io, io + ni, S.b) - io);
        const auto i_below = static_cast<std::size_t>(std::lower_bound(io, io + ni, S.a) - io);
        // Forward: the points from b on, in increasing offset (R's there: its last one or two).
        std::vector<std::pair<double, double>> head;
        for (auto j =
                 static_cast<std::size_t>(std::lower_bound(R.offset.begin(), R.offset.end(), S.b) - R.offset.begin());
             j < R.offset.size(); ++j)
          if (kept(j)) head.emplace_back(R.offset[j], R.lift[j]);
        auto fwd_at = [&](std::size_t w) {
          return w < head.size() ? head[w] : std::pair{io[i_above + w - head.size()], ih[i_above + w - head.size()]};
        };
        const std::size_t nf = head.size() + (ni - std::min(ni, i_above));
        double q = kNaN, steepest = -std::numeric_limits<double>::infinity();
        for (std::size_t w = 0; w + 1 < nf; ++w) {
          const auto [s0, h0] = fwd_at(w);
          const auto [s1, h1] = fwd_at(w + 1);
          if (std::isnan(q) && h1 >= h0) q = s1;
          steepest = std::max(steepest, (h1 - h0) / (s1 - s0));
        }
        if (!std::isnan(q) && steepest > 0 && std::isfinite(steepest)) {
          found.fwd_from = q + d;
          found.fwd_max = steepest - 1e-12 * steepest;
        }
        // Backward: the points up to a, in decreasing offset.
        head.clear();
        for (auto j =
                 static_cast<std::size_t>(std::upper_bound(R.offset.begin(), R.offset.end(), S.a) - R.offset.begin());
             j-- > 0;)
          if (kept(j)) head.emplace_back(R.offset[j], R.lift[j]);
        const std::size_t nb_in = std::min(i_below, ni);
        auto bwd_at = [&](std::size_t w) {  // w-th point from a down
          return w < head.size() ? head[w]
                                 : std::pair{io[nb_in - 1 - (w - head.size())], ih[nb_in - 1 - (w - head.size())]};
        };
        const std::size_t nb = head.size() + nb_in;
        q = kNaN;
        steepest = -std::numeric_limits<double>::infinity();
        for (std::size_t w = 0; w + 1 < nb; ++w) {
          const auto [s1, h1] = bwd_at(w);  // the higher offset
          const auto [s0, h0] = bwd_at(w + 1);
          if (std::isnan(q) && h0 >= h1) q = s0;
          steepest = std::max(steepest, (h0 - h1) / (s1 - s0));
        }
        if (!std::isnan(q) && steepest > 0 && std::isfinite(steepest)) {
          found.bwd_to = q - d;
          found.bwd_max = steepest - 1e-12 * steepest;
        }
        return found;
      };
    }
    for (;;) {
      const double cut_lo = hold_lift_range(S.a, S.b, m_lo, S.lower_len, S.upper_len).min;
      const double cut_hi = hold_lift_range(S.a, S.b, m_hi, S.lower_len, S.upper_len).max;
      const std::vector<double>* have = sampled ? nullptr : &ext_points.offset;
      if (!ext_skipped.empty()) {  // the offsets left out count as had
        have_all.clear();
        have_all.reserve(ext_points.offset.size() + ext_skipped.size());
        std::merge(ext_points.offset.begin(), ext_points.offset.end(), ext_skipped.begin(), ext_skipped.end(),
                   std::back_inserter(have_all));
        have = &have_all;
      }
      auto ext = extend(cut_lo, cut_hi, have, use_prune ? &prune_req : nullptr);
      if (!ext) return with_prefix("hold: ", ext.error());
      std::vector<double>().swap(have_all);
      if (!ext->skipped.empty()) {
        std::vector<double> all;
        all.reserve(ext_skipped.size() + ext->skipped.size());
        std::merge(ext_skipped.begin(), ext_skipped.end(), ext->skipped.begin(), ext->skipped.end(),
                   std::back_inserter(all));
        ext_skipped = std::move(all);
      }
      out.events = ext->events;
      out.exact = ext->exact;
      out.pruned = ext_skipped.size();
      ext_dropped = std::move(ext->dropped);
      ext_points = sampled ? std::move(ext->points) : merge_points(std::move(ext_points), std::move(ext->points));
      const bool cut_max = cut_hi<whole.max, cut_min = cut_lo> whole.min;
      bool more_max = false, more_min = false;
      double short_max = 0, short_min = 0;
      if (sampled) {  // the widened signature's schedule: the whole analysis decides, both sides together
        auto reach = build_and_analyse(R, false);  // the next round evaluates its own points
        if (!reach) return reach.error();
        analysed = true;
        more_max = reach->max && cut_max;
        more_min = reach->min && cut_min;
        if (!more_max && !more_min) break;
        m_lo *= 2;
        m_hi *= 2;
        continue;
      }
      // Exact mode: decide on the lift near each cut end (points from d and a bit before the
      // range's end on), before the whole curve is built.
      MergedPoints mp(R, ext_points, ext_dropped);
      const std::size_t nw = mp.size();
      // W's indices of the points around [a - d, b + d] (a few spacings' slack).
      const std::size_t w_lo = mp.first_at(S.a + d, false);
      const std::size_t i_lo = std::min(nw, w_lo + 2);
      const std::size_t w_hi = std::max(w_lo, mp.first_at(S.b - d, true));
      const std::size_t i_hi = w_hi > 2 ? w_hi - 2 : 0;
      // Both ends at once, a thread each (each check is serial; on two threads this takes the
      // wall of one end, for about 25 MB more than one end after the other on the 10^7-point self-affine pairs,
      // whose peak lies in reading the files); one after the other on one thread. The curves are
      // kept for the whole curve's ends (about 0.1 s of CPU that the whole curve then saves).
      const unsigned threads = util::thread_count(so.threads, 2);
      const bool check_max = cut_max && !passed_max, check_min = cut_min && !passed_min;
      Status st_max = Ok{}, st_min = Ok{};
      auto check_end_max = [&](unsigned th) {
        tail_end.reset();
        auto c = merged_curve(mp, i_hi, nw, th);
        if (!c) {
          st_max = c.error();
          return;
        }
        short_max = end_reached(*c, false, S.b, d);
        tail_end.curve = std::move(*c);
        tail_end.points = nw - i_hi;
      };
      auto check_end_min = [&](unsigned th) {
        head_end.reset();
        auto c = merged_curve(mp, 0, i_lo, th);
        if (!c) {
          st_min = c.error();
          return;
        }
        short_min = end_reached(*c, true, -S.a, d);
        head_end.curve = std::move(*c);
        head_end.points = i_lo;
      };
      if (check_max && check_min && threads >= 2) {  // the two ends side by side, a thread each
        util::run_workers(
            1, [&](unsigned) { check_end_max(1); }, [&] { check_end_min(1); });
      } else {
        if (check_max) check_end_max(threads);
        if (check_min) check_end_min(threads);
      }
      if (!st_max) return st_max.error();
      if (!st_min) return st_min.error();
      more_max = short_max > 0;
      more_min = short_min > 0;
      passed_max = !more_max;
      passed_min = !more_min;
      if (!more_max && !more_min) {
        if (!cut_max && !cut_min) break;  // the whole overlap: analysed once the faces are let go
        // The end checks read the lift near each cut end only, and on exactly sampled grooves
        // they passed a lift that the analysis over it finds too short (a rest less than d from
        // the cut end). The analysis is the judge: it runs here, while the faces can still widen
        // the lift, and a cut end it finds reached is widened again (doubled) and checked anew.
        auto reach = build_and_analyse(R, true);
        if (!reach) return reach.error();
        more_max = reach->max && cut_max;
        more_min = reach->min && cut_min;
        if (!more_max && !more_min) {
          analysed = true;
          ext_points = detail::LiftPoints{};
          break;
        }
        out.curve = LiftCurve{};
        tail_end.reset();
        head_end.reset();
        if (more_max) m_hi *= 2, passed_max = false;
        if (more_min) m_lo *= 2, passed_min = false;
        continue;
      }
      // Farther by what the check found short, and d/5 (a chain may go on: another round, which
      // costs about as much as 0.4 d of lift on one side).
      // Both end curves let go: the widened side's points move (built anew by the next check),
      // and the side that passed is built again by the whole curve rather than held beside the
      // next round's lift and check, where a two-round run peaks.
      tail_end.reset();
      head_end.reset();
      // From a side's third round on, at least twice as far as before: a process that runs on far
      // past the range (a run-away over a long overlap, e.g. a millimetre scan under a block
      // thousands of times longer) then takes O(log) rounds, each planning the offsets of the
      // range so far, instead of one round per d or so (quadratic: it seemed to hang). The first
      // two rounds as before (every pair measured needs at most two).
      if (more_max) m_hi = std::max(m_hi + short_max + 0.2 * d, ++widened_max >= 2 ? 2 * m_hi : 0.0);
      if (more_min) m_lo = std::max(m_lo + short_min + 0.2 * d, ++widened_min >= 2 ? 2 * m_lo : 0.0);
    }
    return Ok{};
  };
  // The analysis once the faces are let go, before the signature's slope distribution is
  // computed (so that the two do not hold their memory at the same time: run side by side, on
  // a 10^7-point H = 0.3 pair, they took 72 MB more than one after the other).
  const detail::AfterFaces after_faces = [&](const SignatureResult& R) -> Status {
    if (S.period > 0) {
      out.events = R.offset.size();
      out.exact = R.exact;
      auto curve = lift_curve(R, S.period);
      if (!curve) return curve.error();
      out.curve = std::move(*curve);
      auto reach = analyse_curve(out, S.ho, start);
      if (!reach) return reach.error();
    } else if (!analysed) {  // the lift over the whole overlap: no cut end to reach
      auto reach = build_and_analyse(R, false);
      if (!reach) return reach.error();
    }
    if (!S.ho.keep_curve) out.curve = LiftCurve{};
    return Ok{};
  };
  auto sig = detail::signature_with_lift(lower, upper, so, take_lower, take_upper, with_lift, after_faces);
  if (!sig) return sig.error();
  res.signature = std::move(*sig);
  return res;
}

}  // namespace

Result<SignatureWithHold> signature_with_hold(const Profile& lower, const Profile& upper,
                                              const SignatureOptions& options, const HoldOptions& hold, double start) {
  return one_pass(lower, upper, options, hold, start, nullptr, nullptr);
}

Result<SignatureWithHold> signature_with_hold(Profile&& lower, Profile&& upper, const SignatureOptions& options,
                                              const HoldOptions& hold, double start) {
  return one_pass(lower, upper, options, hold, start, &lower, &upper);
}

Result<HoldAnalysis> analyse_hold(const Profile& lower, const Profile& upper, const SignatureOptions& so,
                                  const HoldOptions& hold, double start) {
  SignatureOptions o = so;
  o.keep_contacts = false;
  auto r = one_pass(lower, upper, o, hold, start, nullptr, nullptr);
  if (!r) return r.error();
  return std::move(r->hold);
}

}  // namespace frictal
