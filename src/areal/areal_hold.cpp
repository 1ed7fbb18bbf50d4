// The hold angle of an areal block that may move sideways: the quasi-static tilt process on the
// grid of a 2D lift (areal.hpp; the derivation and the Coulomb cone: docs/analysis.md).
#include <fmt/core.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "frictal/areal.hpp"
#include "util/parallel.hpp"

namespace frictal {

std::array<double, 2> ArealLift::offset_xy(std::size_t k) const {
  const double u = along(k % n_along), v = across(k / n_along);
  const double c = std::cos(angle), s = std::sin(angle);
  return {u * c - v * s, u * s + v * c};
}

Result<std::size_t> areal_lift_node(const ArealLift& lift, double x, double y) {
  if (!std::isfinite(x) || !std::isfinite(y))
    return make_error(fmt::format("start offset ({}, {}) m: expected finite numbers", x, y));
  const double c = std::cos(lift.angle), s = std::sin(lift.angle);
  const double u = x * c + y * s, v = -x * s + y * c;
  const double fi = (u - lift.along_min) / lift.step, fj = (v - lift.across_min) / lift.across_step;
  if (!(fi >= -0.5 && fi <= double(lift.n_along) - 0.5 && fj >= -0.5 && fj <= double(lift.n_across) - 0.5))
    return make_error(fmt::format(
        "start offset ({}, {}) m is (u, v) = ({}, {}) m along and across the sliding direction: expected u in [{}, {}] "
        "and v in [{}, {}] m (the offset grid)",
        x, y, u, v, lift.along(0), lift.along(lift.n_along - 1), lift.across(0), lift.across(lift.n_across - 1)));
  const std::size_t i = std::min(lift.n_along - 1, std::size_t(std::max(0.0, std::round(fi))));
  const std::size_t j = std::min(lift.n_across - 1, std::size_t(std::max(0.0, std::round(fj))));
  return j * lift.n_along + i;
}

namespace {

constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
constexpr double kHalfPi = std::numbers::pi / 2;
/// Tilt above a break at which the process moves on (unit: rad): well above rounding in the
/// drives (1e-16), far below any angle reported.
constexpr double kAbove = 1e-10;

/// The quasi-static process on one lift (constant: shared by threads).
class Process {
 public:
  Process(const ArealLift& l, const ArealHoldOptions& o) : l_(l), o_(o) {
    s0_ = std::sin(std::atan(o.atomic_friction));
    // Ties in the along-d displacement (sums of steps) are decided with a relative tolerance.
    tol_u_ = 1e-9 * l.step;
    static const int free_moves[8][2] = {{1, 0}, {1, 1}, {1, -1}, {0, 1}, {0, -1}, {-1, 0}, {-1, 1}, {-1, -1}};
    static const int locked_moves[2][2] = {{1, 0}, {-1, 0}};
    if (o.lateral == LateralMotion::Free)
      for (const auto& m : free_moves) moves_.push_back({m[0], m[1]});
    else
      for (const auto& m : locked_moves) moves_.push_back({m[0], m[1]});
  }

  /// Neighbour of node k by move m, or kNone (off the grid or no contact: a wall).
  std::size_t neighbour(std::size_t k, const std::pair<int, int>& m) const {
    const std::ptrdiff_t i = std::ptrdiff_t(k % l_.n_along) + m.first, j = std::ptrdiff_t(k / l_.n_along) + m.second;
    if (i < 0 || j < 0 || i >= std::ptrdiff_t(l_.n_along) || j >= std::ptrdiff_t(l_.n_across)) return kNone;
    const std::size_t n = std::size_t(j) * l_.n_along + std::size_t(i);
    return std::isnan(l_.lift[n]) ? kNone : n;
  }

  /// The chord to a neighbour: (du, |w|, dh) with w = (du, dv, dh).
  struct Chord {
    double du, norm, dh;
  };
  Chord chord(std::size_t k, std::size_t n, const std::pair<int, int>& m) const {
    const double du = m.first * l_.step, dv = m.second * l_.across_step, dh = l_.lift[n] - l_.lift[k];
    return {du, std::sqrt(du * du + dv * dv + dh * dh), dh};
  }

  /// F.w / |w| at tilt beta, F = (sin beta d, -cos beta).
  static double drive(const Chord& c, double sb, double cb) { return (sb * c.du - cb * c.dh) / c.norm; }

  /// Steepest move at tilt (sb, cb) with threshold s0, or kNone at a stop.
  std::size_t step_from(std::size_t k, double sb, double cb, double s0) const {
    std::size_t best = kNone;
    double best_drive = s0;
    for (const auto& m : moves_) {
      const std::size_t n = neighbour(k, m);
      if (n == kNone) continue;
      const double dr = drive(chord(k, n, m), sb, cb);
      if (dr > best_drive) {
        best_drive = dr;
        best = n;
      }
    }
    return best;
  }

  /// The smallest tilt >= beta at which some neighbour of k can be reached, or NaN if none below
  /// pi/2. With A = du / |w|, B = dh / |w|: F.w / |w| = A sin(beta) - B cos(beta) = R sin(beta -
  /// delta), R = hypot(A, B), delta = atan2(B, A); it exceeds s0 on (delta + a, delta + pi - a),
  /// a = asin(s0 / R), modulo 2 pi.
  double break_tilt(std::size_t k, double beta) const {
    double best = std::numeric_limits<double>::quiet_NaN();
    for (const auto& m : moves_) {
      const std::size_t n = neighbour(k, m);
      if (n == kNone) continue;
      const Chord c = chord(k, n, m);
      const double A = c.du / c.norm, B = c.dh / c.norm, R = std::hypot(A, B);
      if (!(R > s0_)) continue;
      const double delta = std::atan2(B, A), a = std::asin(s0_ / R);
      double lo = delta + a, hi = delta + std::numbers::pi - a;
      // The first interval that reaches beyond beta + kAbove (an interval that ends at beta, up to
      // rounding, is the move back to where the block just came from at this tilt: closed).
      const double turns = std::ceil((beta + kAbove - hi) / (2 * std::numbers::pi));
      lo += turns * 2 * std::numbers::pi;
      hi += turns * 2 * std::numbers::pi;
      if (hi <= beta + kAbove) {
        lo += 2 * std::numbers::pi;
        hi += 2 * std::numbers::pi;
      }
      const double t = std::max(lo, beta);
      if (t < kHalfPi && !(t >= best)) best = t;
    }
    return best;
  }

  /// Frictionless steepest descent at zero tilt (the basin's minimum); appends to path if given.
  std::size_t rest_of(std::size_t k, std::vector<std::size_t>* path) const {
    for (std::size_t guard = 0; guard <= l_.lift.size(); ++guard) {
      const std::size_t n = step_from(k, 0.0, 1.0, 0.0);
      if (n == kNone) return k;
      k = n;
      if (path) path->push_back(k);
    }
    return k;  // unreachable: h drops strictly at every move
  }

  bool last_column(std::size_t k) const { return k % l_.n_along == l_.n_along - 1; }

  /// The tilt process from a block at rest at `rest`.
  void tilt(std::size_t rest, ArealHold& r, std::vector<std::size_t>* path) const {
    std::size_t stop = rest;
    double beta = 0;
    r.slips = 0;
    const double D = o_.runaway_distance;
    for (;;) {
      r.hold_node = stop;
      if (last_column(stop)) {
        // Nothing known ahead (only a drop rests here: a slip that reaches the last column is a
        // run-away): it runs off as onto a flat continuation, as the 1D rule's end of the curve.
        r.hold_angle = std::max(beta, std::atan(o_.atomic_friction));
        r.ran_off_end = true;
        return;
      }
      const double b = break_tilt(stop, beta);
      if (std::isnan(b)) {
        r.hold_angle = kHalfPi;
        r.interlocked = true;
        return;
      }
      beta = b;
      // Just above the break tilt: the neighbour(s) that broke drive strictly.
      const double bm = std::min(beta + kAbove, kHalfPi);
      const double sb = std::sin(bm), cb = std::cos(bm);
      std::size_t k = stop;
      const double u0 = l_.along(stop % l_.n_along), v0 = l_.across(stop / l_.n_along);
      for (std::size_t guard = 0;; ++guard) {
        const std::size_t n = step_from(k, sb, cb, s0_);
        if (n == kNone || guard > l_.lift.size()) break;
        k = n;
        if (path) path->push_back(k);
        const double du = l_.along(k % l_.n_along) - u0;
        const bool far = du >= D - tol_u_;
        if (far || last_column(k)) {
          r.hold_angle = beta;
          r.ran_off_end = !far;
          r.steering = std::atan2(l_.across(k / l_.n_along) - v0, du);
          return;
        }
      }
      if (k == stop) {  // a break found within rounding of beta: look above it
        beta = bm;
        continue;
      }
      ++r.slips;
      stop = k;
    }
  }

 private:
  const ArealLift& l_;
  const ArealHoldOptions& o_;
  std::vector<std::pair<int, int>> moves_;
  double s0_ = 0, tol_u_ = 0;
};

Status check(const ArealLift& l, const ArealHoldOptions& o) {
  if (l.n_along < 2 || l.n_across < 1 || l.lift.size() != l.n_along * l.n_across || !(l.step > 0) ||
      !(l.across_step > 0))
    return make_error("areal hold angle: a malformed lift grid (expected one from areal_lift)");
  if (!std::isfinite(o.runaway_distance) || o.runaway_distance <= 0)
    return make_error(fmt::format("run-away distance {} m: expected a finite number > 0", o.runaway_distance));
  if (!std::isfinite(o.atomic_friction) || o.atomic_friction < 0)
    return make_error(fmt::format("atomic friction {}: expected a finite number >= 0", o.atomic_friction));
  return Ok{};
}

}  // namespace

Result<ArealHold> areal_hold_angle(const ArealLift& lift, std::size_t start, const ArealHoldOptions& o) {
  if (auto s = check(lift, o); !s) return s.error();
  if (start >= lift.lift.size() || std::isnan(lift.lift[start]))
    return make_error(fmt::format("start node {}: expected a node of the {} x {} offset grid where the blocks touch",
                                  start, lift.n_along, lift.n_across));
  const Process p(lift, o);
  ArealHold r;
  r.start = start;
  r.path.push_back(start);
  r.rest = p.rest_of(start, &r.path);
  p.tilt(r.rest, r, &r.path);
  return r;
}

Result<HoldAngle> areal_locked_hold_angle(const ArealLift& lift, std::size_t rest, const ArealHoldOptions& o) {
  if (auto s = check(lift, o); !s) return s.error();
  if (rest >= lift.lift.size() || std::isnan(lift.lift[rest]))
    return make_error(fmt::format("rest node {}: expected a node of the {} x {} offset grid where the blocks touch",
                                  rest, lift.n_along, lift.n_across));
  const std::size_t row = rest / lift.n_along, i = rest % lift.n_along;
  const double* h = &lift.lift[row * lift.n_along];
  std::size_t i0 = i, i1 = i;
  while (i0 > 0 && !std::isnan(h[i0 - 1])) --i0;
  while (i1 + 1 < lift.n_along && !std::isnan(h[i1 + 1])) ++i1;
  if (i1 == i0)
    return make_error(fmt::format("rest node {}: the blocks touch at no neighbour along the sliding direction", rest));
  LiftCurve curve;
  for (std::size_t k = i0; k <= i1; ++k) {
    curve.offset.push_back(lift.along(k));
    curve.lift.push_back(h[k]);
  }
  HoldOptions ho;
  ho.runaway_distance = o.runaway_distance;
  ho.atomic_friction = o.atomic_friction;
  auto r = hold_angle(curve, lift.along(i), ho);
  if (!r) return r.error();
  return r->forward;
}

Result<ArealHoldDistribution> areal_hold_distribution(const ArealLift& lift, const ArealHoldOptions& o) {
  if (auto s = check(lift, o); !s) return s.error();
  ArealHoldDistribution out;
  out.drop_min = o.drop_max > o.drop_min ? o.drop_min : lift.along(0);
  out.drop_max = o.drop_max > o.drop_min ? o.drop_max : lift.along(lift.n_along - 1) - o.runaway_distance;
  const Process p(lift, o);
  // Rest of every drop: follow the zero-tilt descent, memoised (each node's next move is fixed).
  const std::size_t N = lift.lift.size();
  std::vector<std::size_t> rest(N, kNone);
  const double tol = 1e-9 * lift.step;
  std::vector<std::size_t> chain;
  std::vector<std::size_t> count_at(N, 0);
  // Across d: |v| <= v_max - D, so that a block steering up to 45 deg off d has room before the
  // lateral edges (walls); every row when the grid is narrower than that.
  const double vmax = lift.across(lift.n_across - 1);
  out.across_max = vmax - o.runaway_distance >= 0 ? vmax - o.runaway_distance : vmax;
  for (std::size_t k = 0; k < N; ++k) {
    const double u = lift.along(k % lift.n_along), v = lift.across(k / lift.n_along);
    if (std::isnan(lift.lift[k]) || u < out.drop_min - tol || u > out.drop_max + tol ||
        std::abs(v) > out.across_max + 1e-9 * lift.across_step)
      continue;
    ++out.drops;
    chain.clear();
    std::size_t c = k;
    while (rest[c] == kNone) {
      chain.push_back(c);
      const std::size_t n = p.step_from(c, 0.0, 1.0, 0.0);
      if (n == kNone) {
        rest[c] = c;
        break;
      }
      c = n;
    }
    const std::size_t r = rest[c];
    for (std::size_t x : chain) rest[x] = r;
    ++count_at[r];
  }
  if (out.drops == 0)
    return make_error(
        fmt::format("drop range [{}, {}] m along the sliding direction: expected at least one node of the "
                    "offset grid ([{}, {}] m) where the blocks touch (is D longer than the grid?)",
                    out.drop_min, out.drop_max, lift.along(0), lift.along(lift.n_along - 1)));
  for (std::size_t k = 0; k < N; ++k)
    if (count_at[k] > 0) {
      out.rest.push_back(k);
      out.weight.push_back(count_at[k]);
    }
  out.angle.assign(out.rest.size(), 0.0);
  util::parallel_chunks(out.rest.size(), util::thread_count(o.threads, out.rest.size()),
                        [&](unsigned, std::size_t b0, std::size_t b1) {
                          for (std::size_t b = b0; b < b1; ++b) {
                            ArealHold h;
                            p.tilt(out.rest[b], h, nullptr);
                            out.angle[b] = h.hold_angle;
                          }
                        });
  // Weighted statistics (in rest order: deterministic).
  double total = 0, mean = 0;
  for (std::size_t b = 0; b < out.rest.size(); ++b) {
    total += double(out.weight[b]);
    mean += double(out.weight[b]) * out.angle[b];
  }
  mean /= total;
  double var = 0;
  for (std::size_t b = 0; b < out.rest.size(); ++b)
    var += double(out.weight[b]) * (out.angle[b] - mean) * (out.angle[b] - mean);
  std::vector<std::pair<double, double>> sorted;
  for (std::size_t b = 0; b < out.rest.size(); ++b) sorted.emplace_back(out.angle[b], double(out.weight[b]));
  std::sort(sorted.begin(), sorted.end());
  auto quantile = [&](double q) {  // the lower value at a jump
    double cum = 0;
    for (const auto& [v, w] : sorted) {
      cum += w;
      if (cum >= q * total * (1 - 1e-12)) return v;
    }
    return sorted.back().first;
  };
  out.hold.mean = mean;
  out.hold.std = std::sqrt(var / total);
  out.hold.q05 = quantile(0.05);
  out.hold.q50 = quantile(0.5);
  out.hold.q95 = quantile(0.95);
  out.hold.min = sorted.front().first;
  out.hold.max = sorted.back().first;
  return out;
}

}  // namespace frictal
