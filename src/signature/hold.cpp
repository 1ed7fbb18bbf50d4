// frictal — the hold angle, its inertial bound and their distribution over drops (hold.hpp).
//
// Everything works on a continuous piecewise-linear function (Pl): vertices X[0..n], heights
// H[0..n], slopes M[0..n-1] of the pieces between them. Forward sliding only; backward is the
// same on the mirrored function. A periodic curve is unrolled over five periods, enough for any
// drop of the base period: the descent to rest moves at most one period, the record chain from
// a rest ends within one period (at the next vertex of the globally steepest slope), and the
// inertial window is at most one period long.
#include "frictal/hold.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include <fmt/core.h>

namespace frictal {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kHalfPi = std::numbers::pi / 2;

struct Pl {
  std::vector<double> X, H, M;  // n + 1 vertices, n slopes
  std::size_t n() const { return M.size(); }
  // h at x (X.front() <= x <= X.back()), on piece k.
  double at(std::size_t k, double x) const { return H[k] + M[k] * (x - X[k]); }
};

Pl make_pl(const LiftCurve& c) {
  Pl p;
  p.X = c.offset;
  p.H = c.lift;
  p.M.resize(c.offset.size() - 1);
  for (std::size_t k = 0; k + 1 < c.offset.size(); ++k)
    p.M[k] = (c.lift[k + 1] - c.lift[k]) / (c.offset[k + 1] - c.offset[k]);
  return p;
}

Pl mirror(const Pl& p) {
  Pl m;
  const std::size_t n = p.n();
  m.X.resize(n + 1);
  m.H.resize(n + 1);
  m.M.resize(n);
  for (std::size_t i = 0; i <= n; ++i) {
    m.X[i] = -p.X[n - i];
    m.H[i] = p.H[n - i];
  }
  for (std::size_t k = 0; k < n; ++k) m.M[k] = -p.M[n - 1 - k];
  return m;
}

// Copies c0 .. c1 (inclusive) of one period of a periodic Pl.
Pl unroll(const Pl& base, double period, int c0, int c1) {
  Pl u;
  const std::size_t n = base.n();
  for (int c = c0; c <= c1; ++c)
    for (std::size_t i = 0; i < n; ++i) {
      u.X.push_back(base.X[i] + c * period);
      u.H.push_back(base.H[i]);
      u.M.push_back(base.M[i]);
    }
  u.X.push_back(base.X[n] + c1 * period);
  u.H.push_back(base.H[n]);
  return u;
}

// The record chain of the forward process from every vertex, and the descents to rest.
struct Forward {
  std::vector<std::int64_t> next;      // next stop: first j > k with M[j] > M[k]; -1 none
  std::vector<std::int64_t> held;      // the stop that holds a block stopped at k
  std::vector<std::int64_t> run_end;   // end of the run-away from held[k]; -1 none
  std::vector<int> slips;              // short slips from k to held[k]
  std::vector<std::int64_t> down_fwd;  // forward descent from vertex v: first u >= v with M[u] >= 0, else n
  std::vector<std::int64_t> down_bwd;  // backward descent: first u <= v with u == 0 or M[u-1] <= 0
};

Forward forward_process(const Pl& p, double d) {
  const std::size_t n = p.n();
  Forward f;
  f.next.assign(n + 1, -1);
  f.held.assign(n + 1, 0);
  f.run_end.assign(n + 1, -1);
  f.slips.assign(n + 1, 0);
  // Next strictly greater slope: one pass from the right; the stack holds the candidates, their
  // slopes strictly decreasing from bottom to top.
  std::vector<std::int64_t> stack;
  stack.reserve(64);
  for (std::size_t kk = n; kk-- > 0;) {
    while (!stack.empty() && p.M[static_cast<std::size_t>(stack.back())] <= p.M[kk]) stack.pop_back();
    f.next[kk] = stack.empty() ? -1 : stack.back();
    stack.push_back(static_cast<std::int64_t>(kk));
  }
  f.held[n] = static_cast<std::int64_t>(n);  // the end: nothing ahead
  for (std::size_t kk = n; kk-- > 0;) {
    const std::int64_t j = f.next[kk];
    if (j < 0 || p.X[static_cast<std::size_t>(j)] - p.X[kk] >= d) {
      f.held[kk] = static_cast<std::int64_t>(kk);
      f.run_end[kk] = j;
    } else {
      const auto ju = static_cast<std::size_t>(j);
      f.held[kk] = f.held[ju];
      f.run_end[kk] = f.run_end[ju];
      f.slips[kk] = f.slips[ju] + 1;
    }
  }
  f.down_fwd.assign(n + 1, static_cast<std::int64_t>(n));
  for (std::size_t v = n; v-- > 0;) f.down_fwd[v] = p.M[v] >= 0 ? static_cast<std::int64_t>(v) : f.down_fwd[v + 1];
  f.down_bwd.assign(n + 1, 0);
  for (std::size_t v = 1; v <= n; ++v)
    f.down_bwd[v] = p.M[v - 1] <= 0 ? static_cast<std::int64_t>(v) : f.down_bwd[v - 1];
  return f;
}

// Where a drop at x rests: a vertex, or x itself on a flat piece (flat = piece index).
struct Rest {
  std::int64_t vertex = -1;  // rest vertex, or -1 on a flat piece
  std::int64_t flat = -1;    // the flat piece holding x
  double x = 0;
};

// Piece index holding x: the k with X[k] <= x < X[k+1] (the last piece for x = X[n]).
std::size_t piece_of(const Pl& p, double x) {
  const auto it = std::upper_bound(p.X.begin(), p.X.end(), x);
  std::size_t k = it == p.X.begin() ? 0 : static_cast<std::size_t>(it - p.X.begin()) - 1;
  return std::min(k, p.n() - 1);
}

Rest rest_of(const Pl& p, const Forward& f, double x) {
  const std::size_t k = piece_of(p, x);
  Rest r;
  r.x = x;
  std::int64_t v = -1;
  if (x == p.X[k]) {  // on a vertex: its two sides decide
    if (p.M[k] < 0)
      v = f.down_fwd[k + 1];
    else if (k > 0 && p.M[k - 1] > 0)
      v = f.down_bwd[k - 1];
    else
      v = static_cast<std::int64_t>(k);
  } else if (p.M[k] < 0) {
    v = f.down_fwd[k + 1];
  } else if (p.M[k] > 0) {
    v = f.down_bwd[k];
  } else {
    r.flat = static_cast<std::int64_t>(k);
    return r;
  }
  r.vertex = v;
  r.x = p.X[static_cast<std::size_t>(v)];
  return r;
}

// The forward process from a rest: the stop that held, the run-away end, the slips.
struct Outcome {
  double hold_x = 0, hold_slope = 0, end_x = kNaN;
  int slips = 0;
  bool off_end = false;
};

Outcome outcome_of(const Pl& p, const Forward& f, const Rest& r, double d, bool periodic) {
  Outcome o;
  const std::size_t n = p.n();
  std::int64_t start = r.vertex;
  if (r.flat >= 0) {  // a flat piece: the first slip starts at x
    const std::int64_t j = f.next[static_cast<std::size_t>(r.flat)];
    if (j < 0 || p.X[static_cast<std::size_t>(j)] - r.x >= d) {
      o.hold_x = r.x;
      o.hold_slope = 0;
      if (j >= 0) o.end_x = p.X[static_cast<std::size_t>(j)];
      o.off_end = j < 0 && !periodic;
      return o;
    }
    start = j;
    o.slips = 1;
  }
  const auto s = static_cast<std::size_t>(start);
  if (s == n) {  // rests at the end of the range: nothing ahead holds it
    o.hold_x = p.X[n];
    o.hold_slope = 0;
    o.off_end = true;
    return o;
  }
  const auto h = static_cast<std::size_t>(f.held[s]);
  o.hold_x = p.X[h];
  o.hold_slope = p.M[h];
  o.slips += f.slips[s];
  const std::int64_t e = f.run_end[s];
  if (e >= 0) o.end_x = p.X[static_cast<std::size_t>(e)];
  o.off_end = e < 0 && !periodic;
  return o;
}

// Steepest chord from (x0, h(x0)) to h over (x0, min(x0 + w, X[n])], by direct scan:
// {slope, where}. The window's end counts when it falls inside a piece.
std::pair<double, double> chord_direct(const Pl& p, double x0, double w) {
  const std::size_t n = p.n();
  const double h0 = p.at(piece_of(p, x0), x0);
  const double x1 = std::min(x0 + w, p.X[n]);
  if (!(x1 > x0)) return {0.0, x0};
  double best = -std::numeric_limits<double>::infinity(), bx = x1;
  auto consider = [&](double x, double h) {
    const double s = (h - h0) / (x - x0);
    if (s > best) {
      best = s;
      bx = x;
    }
  };
  auto v = static_cast<std::size_t>(std::upper_bound(p.X.begin(), p.X.end(), x0) - p.X.begin());
  for (; v <= n && p.X[v] <= x1; ++v) consider(p.X[v], p.H[v]);
  if (v <= n && p.X[v - 1] < x1) consider(x1, p.at(v - 1, x1));
  return {best, bx};
}

// Upper hull of points pushed in monotone x order with an undo log; max-slope queries from a
// point to the left of every point. cross(o, a, b) > 0: b is to the left of o->a.
class RollbackHull {
 public:
  RollbackHull(const Pl& p, int dir) : p_(p), dir_(dir) {}
  void push(std::size_t v) {
    // Keep the longest prefix whose last turn towards v stays convex (upper hull).
    std::size_t lo = 0, hi = size_;  // answer k in [0, size_]: hull keeps [0, k), v goes at k
    // keep(i): hull[i] stays when v is added, i.e. i == 0 or turn(hull[i-1], hull[i], v) is right.
    auto keep = [&](std::size_t i) { return i == 0 || dir_ * cross(hull_[i - 1], hull_[i], v) < 0; };
    while (lo < hi) {
      const std::size_t mid = (lo + hi + 1) / 2;  // largest i with keep(i - 1)... binary on count
      if (keep(mid - 1))
        lo = mid;
      else
        hi = mid - 1;
    }
    const std::size_t k = lo;  // points [0, k) kept
    if (hull_.size() <= k) hull_.resize(k + 1);
    log_.push_back({k, hull_[k], size_});
    hull_[k] = v;
    size_ = k + 1;
  }
  void undo() {
    const Entry e = log_.back();
    log_.pop_back();
    hull_[e.pos] = e.old;
    size_ = e.size;
  }
  void clear() {
    size_ = 0;
    log_.clear();
  }
  // Max of (H[v] - h0) / (X[v] - x0) over the hull; the slope along the hull is unimodal.
  std::pair<double, double> best(double x0, double h0) const {
    if (size_ == 0) return {-std::numeric_limits<double>::infinity(), kNaN};
    auto slope = [&](std::size_t i) { return (p_.H[hull_[i]] - h0) / (p_.X[hull_[i]] - x0); };
    std::size_t lo = 0, hi = size_ - 1;
    while (lo < hi) {
      const std::size_t mid = (lo + hi) / 2;
      if (slope(mid) < slope(mid + 1))
        lo = mid + 1;
      else
        hi = mid;
    }
    return {slope(lo), p_.X[hull_[lo]]};
  }

 private:
  struct Entry {
    std::size_t pos;
    std::size_t old;
    std::size_t size;
  };
  double cross(std::size_t o, std::size_t a, std::size_t b) const {
    return (p_.X[a] - p_.X[o]) * (p_.H[b] - p_.H[o]) - (p_.H[a] - p_.H[o]) * (p_.X[b] - p_.X[o]);
  }
  const Pl& p_;
  int dir_;
  std::vector<std::size_t> hull_;
  std::size_t size_ = 0;
  std::vector<Entry> log_;
};

// Steepest chords from many rest vertices, each over (X[r], min(X[r] + w, X[n])]. The x axis is
// cut into chunks of length w: a window starting in chunk c covers a suffix of chunk c and a
// prefix of the chunks after it, up to one chunk length. Per chunk, queries in decreasing x: the
// suffix hull grows leftwards, the prefix hull shrinks (undo in reverse push order).
// O((n + q) log n) time, O(n) memory.
std::vector<std::pair<double, double>> chords_batch(const Pl& p, const std::vector<std::size_t>& rests, double w) {
  const std::size_t n = p.n();
  std::vector<std::pair<double, double>> out(rests.size());
  if (rests.empty()) return out;
  const double x_begin = p.X[0];
  auto chunk_of = [&](double x) { return std::floor((x - x_begin) / w); };
  std::vector<std::size_t> order(rests.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return rests[a] > rests[b]; });
  RollbackHull suffix(p, -1), prefix(p, +1);
  std::size_t qi = 0;
  while (qi < order.size()) {
    const double c = chunk_of(p.X[rests[order[qi]]]);
    // b: the first vertex of a later chunk; e: past the last vertex any window of this chunk reaches.
    const auto b = static_cast<std::size_t>(
        std::partition_point(p.X.begin(), p.X.end(), [&](double x) { return chunk_of(x) <= c; }) - p.X.begin());
    const double reach = p.X[rests[order[qi]]] + w;
    const auto e = static_cast<std::size_t>(std::upper_bound(p.X.begin(), p.X.end(), reach) - p.X.begin());
    suffix.clear();
    prefix.clear();
    for (std::size_t v = b; v < e; ++v) prefix.push(v);
    std::size_t prefix_end = std::max(b, e);  // prefix holds [b, prefix_end)
    std::size_t suffix_begin = b;             // suffix holds [suffix_begin, b)
    for (; qi < order.size() && chunk_of(p.X[rests[order[qi]]]) == c; ++qi) {
      const std::size_t r = rests[order[qi]];
      const double x0 = p.X[r], h0 = p.H[r], x1 = std::min(x0 + w, p.X[n]);
      while (suffix_begin > r + 1) suffix.push(--suffix_begin);
      while (prefix_end > b && p.X[prefix_end - 1] > x1) {
        prefix.undo();
        --prefix_end;
      }
      std::pair<double, double> best = suffix.best(x0, h0);
      const auto pb = prefix.best(x0, h0);
      if (pb.first > best.first) best = pb;
      if (x1 > x0) {  // the window's end inside a piece
        const std::size_t k = piece_of(p, x1);
        if (p.X[k] < x1 && x1 < p.X[k + 1]) {
          const double s = (p.at(k, x1) - h0) / (x1 - x0);
          if (s > best.first) best = {s, x1};
        }
      }
      if (!std::isfinite(best.first)) best = {0.0, x0};
      out[order[qi]] = best;
    }
  }
  return out;
}

double angle_of(double slope, double mu) { return std::min(std::atan(slope) + std::atan(mu), kHalfPi); }

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
  Pl pl;
  Forward fw;
  bool periodic = false;
  double period = 0;
  double base_lo = 0;  // base period [base_lo, base_lo + period) in this frame (periodic)
  double w = 0;        // inertial window
};

Frame make_frame(const Pl& base, double period, double d) {
  Frame fr;
  fr.periodic = period > 0;
  fr.period = period;
  fr.base_lo = base.X.front();
  fr.pl = fr.periodic ? unroll(base, period, -1, 3) : base;
  fr.fw = forward_process(fr.pl, d);
  fr.w = fr.periodic ? std::min(d, period) : d;
  return fr;
}

// Offset x of the base frame in the unrolled function (periodic: into [base_lo, base_lo + P)).
double wrap(const Frame& fr, double x) {
  if (!fr.periodic) return x;
  double y = std::fmod(x - fr.base_lo, fr.period);
  if (y < 0) y += fr.period;
  return fr.base_lo + y;
}

HoldAngle single(const Frame& fr, double x, const HoldOptions& o) {
  const Rest r = rest_of(fr.pl, fr.fw, x);
  const Outcome oc = outcome_of(fr.pl, fr.fw, r, o.runaway_distance, fr.periodic);
  HoldAngle h;
  h.rest_offset = r.x;
  h.hold_slope = oc.hold_slope;
  h.hold_angle = angle_of(oc.hold_slope, o.atomic_friction);
  h.hold_offset = oc.hold_x;
  h.runaway_end = oc.end_x;
  h.slips = oc.slips;
  h.ran_off_end = oc.off_end;
  const auto [slope, cx] = chord_direct(fr.pl, r.x, fr.w);
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

HoldStatistics weighted_stats(const std::vector<double>& v, const std::vector<double>& w) {
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
  std::vector<std::size_t> idx(v.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
  auto quantile = [&](double q) {
    double cum = 0;
    for (std::size_t i : idx) {
      cum += w[i];
      if (cum >= q * tw * (1 - 1e-12)) return v[i];
    }
    return v[idx.back()];
  };
  s.q05 = quantile(0.05);
  s.q50 = quantile(0.50);
  s.q95 = quantile(0.95);
  s.min = v[idx.front()];
  s.max = v[idx.back()];
  return s;
}

// Distribution over drops in [a, b] (this frame's coordinates, a < b).
HoldDistribution distribution(const Frame& fr, double a, double b, const HoldOptions& o, bool mirrored) {
  const Pl& p = fr.pl;
  const double d = o.runaway_distance;
  // Parts of the drop range with one outcome each: weight, rest, outcome.
  struct Part {
    double weight;
    Rest rest;
    Outcome oc;
  };
  std::vector<Part> parts;
  std::size_t k = piece_of(p, a);
  for (double x = a; x < b && k < p.n(); ++k) {
    const double xe = std::min(b, p.X[k + 1]);
    if (xe <= x) continue;
    const double mid = 0.5 * (x + xe);
    Rest r = rest_of(p, fr.fw, mid);
    if (r.flat >= 0) {
      // On a flat piece the first slip starts at the drop: split where it reaches d.
      const std::int64_t j = fr.fw.next[k];
      const double split = j >= 0 ? p.X[static_cast<std::size_t>(j)] - d : x;
      for (const auto& [lo, hi] : {std::pair{x, std::min(xe, std::max(x, split))}, std::pair{std::max(x, split), xe}}) {
        if (!(hi > lo)) continue;
        Rest rr = r;
        rr.x = 0.5 * (lo + hi);
        parts.push_back({hi - lo, rr, outcome_of(p, fr.fw, rr, d, fr.periodic)});
      }
    } else {
      parts.push_back({xe - x, r, outcome_of(p, fr.fw, r, d, fr.periodic)});
    }
    x = xe;
  }
  double near_end = 0;  // run-aways that left a stop less than d before the end of the curve
  for (const Part& q : parts)
    if (q.oc.off_end && p.X.back() - q.oc.hold_x < d) near_end += q.weight;
  // Basins: parts that rest at one vertex (a periodic frame: one vertex modulo the period).
  const std::size_t nb = fr.periodic ? p.n() / 5 : 0;  // vertices per period in the unrolled frame
  auto key = [&](const Rest& r) -> std::int64_t {
    const std::int64_t v = r.vertex >= 0 ? r.vertex : -2 - r.flat;  // flats keyed apart
    if (!fr.periodic || v < 0) return v;
    return v % static_cast<std::int64_t>(nb);
  };
  std::map<std::int64_t, std::size_t> basin;  // key -> index into the rest vertices
  std::vector<std::size_t> rest_vertices;
  std::vector<std::size_t> part_basin(parts.size(), SIZE_MAX);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (parts[i].rest.vertex < 0) continue;
    const auto [it, fresh] = basin.try_emplace(key(parts[i].rest), rest_vertices.size());
    if (fresh) rest_vertices.push_back(static_cast<std::size_t>(parts[i].rest.vertex));
    part_basin[i] = it->second;
  }
  const auto chords = chords_batch(p, rest_vertices, fr.w);
  HoldDistribution out;
  // Basins in increasing offset of the lift's frame.
  std::vector<double> b_rest(rest_vertices.size()), b_w(rest_vertices.size(), 0.0), b_h(rest_vertices.size()),
      b_i(rest_vertices.size());
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const Part& q = parts[i];
    const double hold = angle_of(q.oc.hold_slope, o.atomic_friction);
    double inert;
    if (part_basin[i] != SIZE_MAX) {
      const std::size_t bi = part_basin[i];
      inert = angle_of(chords[bi].first, o.atomic_friction);
      b_rest[bi] = wrap(fr, q.rest.x);
      b_w[bi] += q.weight;
      b_h[bi] = hold;
      b_i[bi] = inert;
    } else {  // a flat drop: its own chord
      inert = angle_of(chord_direct(p, q.rest.x, fr.w).first, o.atomic_friction);
      out.basins.rest.push_back(mirrored ? -q.rest.x : q.rest.x);
      out.basins.weight.push_back(q.weight);
      out.basins.hold.push_back(hold);
      out.basins.inertial.push_back(inert);
    }
  }
  for (std::size_t bi = 0; bi < rest_vertices.size(); ++bi) {
    out.basins.rest.push_back(mirrored ? -b_rest[bi] : b_rest[bi]);
    out.basins.weight.push_back(b_w[bi]);
    out.basins.hold.push_back(b_h[bi]);
    out.basins.inertial.push_back(b_i[bi]);
  }
  {  // sort the basins by offset
    std::vector<std::size_t> idx(out.basins.rest.size());
    for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
    std::sort(idx.begin(), idx.end(),
              [&](std::size_t x, std::size_t y) { return out.basins.rest[x] < out.basins.rest[y]; });
    HoldBasins s;
    for (std::size_t i : idx) {
      s.rest.push_back(out.basins.rest[i]);
      s.weight.push_back(out.basins.weight[i]);
      s.hold.push_back(out.basins.hold[i]);
      s.inertial.push_back(out.basins.inertial[i]);
    }
    out.basins = std::move(s);
  }
  // Every drop of a basin gives its basin's angles: the statistics over basins weighted by width.
  out.hold = weighted_stats(out.basins.hold, out.basins.weight);
  out.inertial = weighted_stats(out.basins.inertial, out.basins.weight);
  out.drop_min = mirrored ? -b : a;
  out.drop_max = mirrored ? -a : b;
  out.near_end = near_end;
  return out;
}

}  // namespace

Result<LiftCurve> lift_curve(const SignatureResult& sig, double period) {
  const std::size_t n = sig.offset.size();
  if (n < 2 || sig.lift.size() != n)
    return make_error(fmt::format("lift_curve: the signature has {} offsets: expected at least two", n));
  const bool slopes = sig.theta_left.size() == n && sig.theta_right.size() == n;
  LiftCurve c;
  c.period = period;
  c.offset.reserve(2 * n);
  c.lift.reserve(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(sig.offset[i]) || !std::isfinite(sig.lift[i]))
      return make_error(fmt::format("lift_curve: offset {} of the signature is not finite", i));
    if (i > 0 && !(sig.offset[i] > sig.offset[i - 1]))
      return make_error(fmt::format("lift_curve: the signature's offsets must increase (offset {})", i));
    if (i > 0 && slopes) {
      // The tangent lines at both ends of the interval meet inside it: a vertex there.
      const double x0 = sig.offset[i - 1], x1 = sig.offset[i], h0 = sig.lift[i - 1], h1 = sig.lift[i];
      const double m0 = std::tan(sig.theta_right[i - 1]), m1 = std::tan(sig.theta_left[i]);
      if (std::isfinite(m0) && std::isfinite(m1) && m0 != m1) {
        const double xs = (h1 - h0 + m0 * x0 - m1 * x1) / (m0 - m1);
        const double span = x1 - x0, eps = 1e-9 * span;
        // A meeting point at an end within rounding (a vertical wall of h: theta = 90 deg on one
        // side) is kept just inside, so the wall stays a piece of (nearly) infinite slope.
        // No vertex where one tangent already joins both ends (a kink at the event itself).
        const double tol = 1e-9 * std::abs(h1 - h0) + 1e-14 * std::max(std::abs(h0), std::abs(h1));
        const bool joined = std::abs(h0 + m0 * span - h1) <= tol || std::abs(h1 - m1 * span - h0) <= tol;
        if (!joined && xs > x0 - 1e-6 * span && xs < x1 + 1e-6 * span) {
          const double xc = std::clamp(xs, x0 + eps, x1 - eps);
          c.offset.push_back(xc);
          // Height from the flatter tangent (the steeper one may be a wall, tan(90 deg) ~ 1e16).
          c.lift.push_back(std::abs(m0) <= std::abs(m1) ? h0 + m0 * (xc - x0) : h1 + m1 * (xc - x1));
        }
      }
    }
    c.offset.push_back(sig.offset[i]);
    c.lift.push_back(sig.lift[i]);
  }
  if (period > 0) {
    const double span = c.offset.back() - c.offset.front();
    if (std::abs(span - period) > 1e-6 * period)
      return make_error(fmt::format("lift_curve: the signature spans {} m, not one period of {} m", span, period));
    c.offset.back() = c.offset.front() + period;  // exactly one period
  }
  if (auto st = check_curve(c); !st) return st.error();
  return c;
}

Result<HoldAngles> hold_angle(const LiftCurve& curve, double start, const HoldOptions& options) {
  if (auto st = check_curve(curve); !st) return st.error();
  if (auto st = check_options(options); !st) return st.error();
  const double lo = curve.offset.front(), hi = curve.offset.back();
  if (!std::isfinite(start) || (curve.period == 0 && (start < lo || start > hi)))
    return make_error(fmt::format("hold: start offset {} m: expected an offset in [{}, {}] m", start, lo, hi));
  const Pl base = make_pl(curve);
  HoldAngles out;
  {
    const Frame fr = make_frame(base, curve.period, options.runaway_distance);
    out.forward = single(fr, wrap(fr, start), options);
  }
  {
    const Frame fr = make_frame(mirror(base), curve.period, options.runaway_distance);
    out.backward = unmirror(single(fr, wrap(fr, -start), options));
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

Result<HoldDistributions> hold_distribution(const LiftCurve& curve, const HoldOptions& options) {
  if (auto st = check_curve(curve); !st) return st.error();
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
  const Pl base = make_pl(curve);
  HoldDistributions out;
  out.forward = distribution(make_frame(base, curve.period, options.runaway_distance), a, b, options, false);
  {
    const Frame fr = make_frame(mirror(base), curve.period, options.runaway_distance);
    out.backward = distribution(fr, -b, -a, options, true);
  }
  return out;
}

std::vector<std::int32_t> basin_index(const LiftCurve& curve, const std::vector<double>& offsets) {
  std::vector<std::int32_t> out(offsets.size(), -1);
  if (!check_curve(curve).ok()) return out;
  const Pl base = make_pl(curve);
  const Forward fw = forward_process(base, 1.0);
  // Basins numbered by increasing rest offset: the local minima (rest vertices) and flat pieces.
  std::vector<std::int64_t> keys;
  auto key_of = [&](double x) -> std::int64_t {
    const Rest r = rest_of(base, fw, x);
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

Result<HoldAnalysis> analyse_hold(const Profile& lower, const Profile& upper, const SignatureOptions& so,
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

}  // namespace frictal
