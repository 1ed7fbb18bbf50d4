// Friction of areal maps: directional predictions from line profiles, the anisotropy table,
// and the areal signature of two rigid blocks with block-wise max bounds.
#include <fmt/core.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include "frictal/analysis.hpp"
#include "frictal/areal.hpp"

#include "areal_grid.hpp"
#include "util/parallel.hpp"

namespace frictal {

Result<DirectionalFriction> friction_along(const Map& m, double angle, const DirectionalOptions& o) {
  if (auto s = validate(m, "map"); !s) return s.error();
  if (!std::isfinite(angle)) return make_error("friction_along: the direction must be a finite angle");
  if (o.max_lines < 1) return make_error("friction_along: max_lines must be at least 1");
  const double c = std::cos(angle), s = std::sin(angle);
  const double across = std::abs(s) * m.width() + std::abs(c) * m.height();
  double spacing = o.spacing > 0 ? o.spacing : std::max(m.dx, m.dy);
  spacing = std::max(spacing, across / double(o.max_lines));
  auto lines = map_lines(m, angle, spacing, o.step, std::max<std::size_t>(o.min_points, 4));
  if (lines.empty())
    return make_error(fmt::format("friction_along: no line of at least {} valid points along {} deg", o.min_points,
                                  angle * 180 / std::numbers::pi));
  DirectionalFriction r;
  r.angle = angle;
  SignatureOptions so = o.signature;
  so.keep_contacts = false;
  std::vector<SignatureResult> results(lines.size());
  std::vector<Error> errors(lines.size());
  const unsigned threads = util::thread_count(o.threads, lines.size());
  if (threads > 1) so.threads = 1;  // parallel over lines, not inside each line
  util::parallel_chunks(lines.size(), threads, [&](unsigned, std::size_t k0, std::size_t k1) {
    for (std::size_t k = k0; k < k1; ++k) {
      auto sig = self_signature(lines[k], so);
      if (sig)
        results[k] = std::move(*sig);
      else
        errors[k] = sig.error();
    }
  });
  for (std::size_t k = 0; k < lines.size(); ++k) {  // reduce in line order: deterministic
    if (!errors[k].message.empty()) return errors[k];
    const SignatureResult& sig = results[k];
    const double w = lines[k].length();
    r.lines++;
    r.total_length += w;
    r.theta_forward += w * sig.theta_max_forward;
    r.theta_backward += w * sig.theta_max_backward;
    r.sigma += w * sig.contact_slope_std;
    r.theta_forward_max = std::max(r.theta_forward_max, sig.theta_max_forward);
    r.theta_backward_max = std::max(r.theta_backward_max, sig.theta_max_backward);
  }
  r.theta_forward /= r.total_length;
  r.theta_backward /= r.total_length;
  r.sigma /= r.total_length;
  auto pred = predict_friction(o.atomic_friction, r.theta_forward, r.sigma);
  if (!pred) return pred.error();
  r.prediction = *pred;
  return r;
}

Result<std::vector<DirectionalFriction>> anisotropy(const Map& m, int directions, const DirectionalOptions& o) {
  if (directions < 1 || directions > 3600) return make_error("anisotropy: directions must be in 1..3600");
  std::vector<DirectionalFriction> out;
  for (int k = 0; k < directions; ++k) {
    auto r = friction_along(m, 2 * std::numbers::pi * k / directions, o);
    if (!r) return r.error();
    out.push_back(*r);
  }
  return out;
}

std::array<double, 2> ArealLift::offset_xy(std::size_t k) const {
  const double u = along(k % n_along), v = across(k / n_along);
  const double c = std::cos(angle), s = std::sin(angle);
  return {u * c - v * s, u * s + v * c};
}

namespace {

/// Range maximum over a 2D grid of values in O(1) per query (sparse table of sparse tables).
class RangeMax2D {
 public:
  RangeMax2D(const std::vector<double>& v, std::size_t w, std::size_t h) : w_(w), h_(h) {
    lw_ = 1;
    while ((std::size_t(1) << lw_) <= w) ++lw_;
    lh_ = 1;
    while ((std::size_t(1) << lh_) <= h) ++lh_;
    t_.assign(std::size_t(lw_) * lh_ * w * h, -std::numeric_limits<double>::infinity());
    for (std::size_t j = 0; j < h; ++j)
      for (std::size_t i = 0; i < w; ++i) at(0, 0, i, j) = v[j * w + i];
    for (int a = 0; a < lw_; ++a)
      for (int b = 0; b < lh_; ++b) {
        if (a == 0 && b == 0) continue;
        for (std::size_t j = 0; j + (std::size_t(1) << b) <= h; ++j)
          for (std::size_t i = 0; i + (std::size_t(1) << a) <= w; ++i) {
            if (a > 0)
              at(a, b, i, j) = std::max(at(a - 1, b, i, j), at(a - 1, b, i + (std::size_t(1) << (a - 1)), j));
            else
              at(a, b, i, j) = std::max(at(a, b - 1, i, j), at(a, b - 1, i, j + (std::size_t(1) << (b - 1))));
          }
      }
  }
  /// Max over [i0, i1] x [j0, j1] (inclusive, valid indices).
  double query(std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1) const {
    int a = log2(i1 - i0 + 1), b = log2(j1 - j0 + 1);
    std::size_t i2 = i1 + 1 - (std::size_t(1) << a), j2 = j1 + 1 - (std::size_t(1) << b);
    return std::max(std::max(cat(a, b, i0, j0), cat(a, b, i2, j0)), std::max(cat(a, b, i0, j2), cat(a, b, i2, j2)));
  }

 private:
  static int log2(std::size_t n) {
    int k = 0;
    while ((std::size_t(2) << k) <= n) ++k;
    return k;
  }
  double& at(int a, int b, std::size_t i, std::size_t j) { return t_[((std::size_t(a) * lh_ + b) * h_ + j) * w_ + i]; }
  double cat(int a, int b, std::size_t i, std::size_t j) const {
    return t_[((std::size_t(a) * lh_ + b) * h_ + j) * w_ + i];
  }
  std::size_t w_, h_;
  int lw_, lh_;
  std::vector<double> t_;
};

struct Block {
  std::size_t i0, i1, j0, j1;  // node ranges of the lower map, inclusive
  double fmax;
};

/// The max-plus correlation of two faces for any in-plane shift of the upper one: the lower
/// face's blocks with their maxima, the upper face's block maxima in a range-max table, and the
/// affine map from a lower node and a shift to the upper face's index space. Shared by the
/// one-line signature and the lift over two dimensions of offset, so that the second is exactly
/// the first on its line. Not copyable (it may point at its own negated copy of the upper map).
class LiftEvaluator {
 public:
  LiftEvaluator() = default;
  LiftEvaluator(const LiftEvaluator&) = delete;
  LiftEvaluator& operator=(const LiftEvaluator&) = delete;

  /// `who` names the caller in errors.
  Status init(const Map& f, const Map& g_in, double angle, bool turn_over_upper, std::size_t block, const char* who) {
    f_ = &f;
    if (!turn_over_upper) {
      // Everything below maximises f(p) + g(q): for an upper face given in place (not turned
      // over) the gap is f(p) - g_in(q), so work with -g_in.
      negated_ = g_in;
      for (double& v : negated_.heights) v = -v;
      g_ = &negated_;
    } else {
      g_ = &g_in;
    }
    const Map& g = *g_;
    if (f.nx < 2 || f.ny < 2 || g.nx < 2 || g.ny < 2)
      return make_error(fmt::format("{}: maps need at least 2 x 2 nodes", who));
    if (!std::isfinite(angle)) return make_error(fmt::format("{}: the direction must be a finite angle", who));
    if (block < 2 || block > 4096) return make_error(fmt::format("{}: block must be in 2..4096", who));
    dxv_ = std::cos(angle);
    dyv_ = std::sin(angle);
    // q = c_g + R (p - shift - c_f) in g's continuous index space (u, v): affine in (x, y, shift).
    // Turned over: R = I - 2 d d^T about the centres; in place: R = I, no centring (q = p - shift).
    const bool turn = turn_over_upper;
    cfx_ = turn ? f.x0 + 0.5 * f.width() : 0;
    cfy_ = turn ? f.y0 + 0.5 * f.height() : 0;
    cgx_ = turn ? g.x0 + 0.5 * g.width() : 0;
    cgy_ = turn ? g.y0 + 0.5 * g.height() : 0;
    r11_ = turn ? 1 - 2 * dxv_ * dxv_ : 1;
    r12_ = turn ? -2 * dxv_ * dyv_ : 0;
    r22_ = turn ? 1 - 2 * dyv_ * dyv_ : 1;
    B_ = block;
    const std::size_t B = block;
    for (std::size_t j0 = 0; j0 < f.ny; j0 += B)
      for (std::size_t i0 = 0; i0 < f.nx; i0 += B) {
        Block b{i0, std::min(i0 + B, f.nx) - 1, j0, std::min(j0 + B, f.ny) - 1,
                -std::numeric_limits<double>::infinity()};
        for (std::size_t j = b.j0; j <= b.j1; ++j)
          for (std::size_t i = b.i0; i <= b.i1; ++i)
            if (!std::isnan(f.at(i, j))) b.fmax = std::max(b.fmax, f.at(i, j));
        if (std::isfinite(b.fmax)) blocks_.push_back(b);
      }
    const std::size_t gbw = (g.nx + B - 1) / B, gbh = (g.ny + B - 1) / B;
    std::vector<double> gmax(gbw * gbh, -std::numeric_limits<double>::infinity());
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i)
        if (!std::isnan(g.at(i, j))) {
          double& m = gmax[(j / B) * gbw + i / B];
          m = std::max(m, g.at(i, j));
        }
    const double levels = std::ceil(std::log2(double(gbw) + 1)) * std::ceil(std::log2(double(gbh) + 1));
    if (double(gbw) * double(gbh) * levels > 5e7)
      return make_error(fmt::format("{}: block {} is too small for a {} x {} upper map", who, B, g.nx, g.ny));
    gtable_.emplace(gmax, gbw, gbh);
    return Ok{};
  }

  const Map& lower() const { return *f_; }
  const Map& upper() const { return *g_; }
  double rdx() const { return r11_ * dxv_ + r12_ * dyv_; }  // R d: how q moves along d
  double rdy() const { return r12_ * dxv_ + r22_ * dyv_; }

  void q_of(double px, double py, double sx, double sy, double& u, double& v) const {
    const Map& g = *g_;
    const double ax = px - sx - cfx_, ay = py - sy - cfy_;
    u = (cgx_ + r11_ * ax + r12_ * ay - g.x0) / g.dx;
    v = (cgy_ + r12_ * ax + r22_ * ay - g.y0) / g.dy;
  }

  /// Bilinear g in index space (the same rule as interpolate(): NaN if a node with non-zero
  /// weight is NaN or (u, v) is off the grid).
  double g_at(double u, double v) const {
    const Map& g = *g_;
    if (!(u >= 0) || !(v >= 0) || u > double(g.nx - 1) || v > double(g.ny - 1))
      return std::numeric_limits<double>::quiet_NaN();
    std::size_t i = std::min(std::size_t(u), g.nx - 2), j = std::min(std::size_t(v), g.ny - 2);
    const double fu = u - double(i), fv = v - double(j);
    const double* r0 = &g.heights[j * g.nx + i];
    const double* r1 = r0 + g.nx;
    double val = 0;
    if (fu < 1 && fv < 1) val += (1 - fu) * (1 - fv) * r0[0];
    if (fu > 0 && fv < 1) val += fu * (1 - fv) * r0[1];
    if (fu < 1 && fv > 0) val += (1 - fu) * fv * r1[0];
    if (fu > 0 && fv > 0) val += fu * fv * r1[1];
    return val;
  }

  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  struct Best {
    double value = -std::numeric_limits<double>::infinity();
    std::size_t index = kNone;  ///< lower node j * nx + i of the maximum (ties: lowest), kNone: no contact
    std::size_t evaluated = 0;
  };

  /// max over lower nodes p of f(p) + g(q(p, shift)) for the upper face moved by (sx, sy).
  /// `order` is scratch space (one per thread).
  Best best(double sx, double sy, bool prune, std::vector<std::pair<double, std::size_t>>& order) const {
    const Map& f = *f_;
    const Map& g = *g_;
    Best r;
    auto eval_block = [&](const Block& b) {
      for (std::size_t j = b.j0; j <= b.j1; ++j)
        for (std::size_t i = b.i0; i <= b.i1; ++i) {
          const double fz = f.at(i, j);
          if (std::isnan(fz)) continue;
          double u, v;
          q_of(f.x0 + double(i) * f.dx, f.y0 + double(j) * f.dy, sx, sy, u, v);
          const double gz = g_at(u, v);
          ++r.evaluated;
          if (std::isnan(gz)) continue;
          const double val = fz + gz;
          const std::size_t idx = j * f.nx + i;
          if (val > r.value || (val == r.value && idx < r.index)) {
            r.value = val;
            r.index = idx;
          }
        }
    };
    if (!prune) {
      for (const Block& b : blocks_) eval_block(b);
      return r;
    }
    order.clear();
    for (std::size_t bi = 0; bi < blocks_.size(); ++bi) {
      const Block& b = blocks_[bi];
      // Image of the block's node rectangle in g's index space: bounding box of the corners.
      double umin = 1e300, umax = -1e300, vmin = 1e300, vmax = -1e300;
      for (std::size_t ci : {b.i0, b.i1})
        for (std::size_t cj : {b.j0, b.j1}) {
          double u, v;
          q_of(f.x0 + double(ci) * f.dx, f.y0 + double(cj) * f.dy, sx, sy, u, v);
          umin = std::min(umin, u);
          umax = std::max(umax, u);
          vmin = std::min(vmin, v);
          vmax = std::max(vmax, v);
        }
      if (umax < 0 || vmax < 0 || umin > double(g.nx - 1) || vmin > double(g.ny - 1)) continue;
      // Bilinear values lie within the max of the nodes of the cells touched.
      const std::size_t gi0 = std::size_t(std::max(0.0, std::floor(umin))),
                        gj0 = std::size_t(std::max(0.0, std::floor(vmin)));
      const std::size_t gi1 = std::min(g.nx - 1, std::size_t(std::ceil(umax))),
                        gj1 = std::min(g.ny - 1, std::size_t(std::ceil(vmax)));
      const double gb = gtable_->query(gi0 / B_, gi1 / B_, gj0 / B_, gj1 / B_);
      if (!std::isfinite(gb)) continue;
      order.emplace_back(b.fmax + gb, bi);
    }
    std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    for (const auto& [bound, bi] : order) {
      if (bound < r.value) break;  // no later block can beat (or tie) the best so far
      eval_block(blocks_[bi]);
    }
    return r;
  }

 private:
  const Map* f_ = nullptr;
  const Map* g_ = nullptr;
  Map negated_;
  double dxv_ = 1, dyv_ = 0;
  double cfx_ = 0, cfy_ = 0, cgx_ = 0, cgy_ = 0, r11_ = 1, r12_ = 0, r22_ = 1;
  std::size_t B_ = 16;
  std::vector<Block> blocks_;
  std::optional<RangeMax2D> gtable_;
};

}  // namespace

Result<ArealSignature> areal_signature(const Map& f, const Map& g_in, double angle, const ArealSignatureOptions& o) {
  if (auto s = validate(f, "lower map"); !s) return s.error();
  if (auto s = validate(g_in, "upper map"); !s) return s.error();
  LiftEvaluator ev;
  if (auto s = ev.init(f, g_in, angle, o.turn_over_upper, o.block, "areal_signature"); !s) return s.error();
  const Map& g = ev.upper();
  const double dxv = std::cos(angle), dyv = std::sin(angle);
  const double step = o.step > 0 ? o.step : std::min(f.dx, f.dy);
  const double extent = std::abs(dxv) * f.width() + std::abs(dyv) * f.height();
  const double smax = o.offset_max > 0 ? o.offset_max : 0.5 * extent;
  const std::size_t count = std::size_t(std::floor(smax / step + 1e-9)) + 1;
  if (count > 10'000'000) return make_error("areal_signature: more than 1e7 offsets; increase step");
  const double rdx = ev.rdx(), rdy = ev.rdy();

  ArealSignature out;
  out.direction = angle;
  out.offset.resize(count);
  out.lift.resize(count);
  out.theta.resize(count);
  out.contact_x.resize(count);
  out.contact_y.resize(count);
  std::vector<std::size_t> work(count, 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();

  auto run_offset = [&](std::size_t k, std::vector<std::pair<double, std::size_t>>& order) {
    const double s = double(k) * step;
    const LiftEvaluator::Best bst = ev.best(s * dxv, s * dyv, o.prune, order);
    work[k] = bst.evaluated;
    out.offset[k] = s;
    if (bst.index == LiftEvaluator::kNone) {
      out.lift[k] = out.theta[k] = out.contact_x[k] = out.contact_y[k] = nan;
      return;
    }
    out.lift[k] = bst.value;
    const std::size_t bi = bst.index % f.nx, bj = bst.index / f.nx;
    const double px = f.x0 + double(bi) * f.dx, py = f.y0 + double(bj) * f.dy;
    out.contact_x[k] = px;
    out.contact_y[k] = py;
    // Directional slopes along d at the contact, central differences over +-step/2 on the
    // bilinear surfaces (one-sided next to holes and edges). The upper face's height at p is
    // -g(q(p)) and q moves by R d per unit of p along d.
    const double e = 0.5 * step;
    auto slope_f = [&]() {
      double a = interpolate(f, px + e * dxv, py + e * dyv), b = interpolate(f, px - e * dxv, py - e * dyv);
      if (!std::isnan(a) && !std::isnan(b)) return (a - b) / (2 * e);
      if (!std::isnan(a)) return (a - f.at(bi, bj)) / e;
      if (!std::isnan(b)) return (f.at(bi, bj) - b) / e;
      return 0.0;
    };
    double u, v;
    ev.q_of(px, py, s * dxv, s * dyv, u, v);
    const double gq = ev.g_at(u, v);
    auto slope_g = [&]() {
      double ua = u + e * rdx / g.dx, va = v + e * rdy / g.dy, ub = u - e * rdx / g.dx, vb = v - e * rdy / g.dy;
      double a = ev.g_at(ua, va), b = ev.g_at(ub, vb);
      if (!std::isnan(a) && !std::isnan(b)) return -(a - b) / (2 * e);
      if (!std::isnan(a)) return -(a - gq) / e;
      if (!std::isnan(b)) return -(gq - b) / e;
      return 0.0;
    };
    out.theta[k] = std::atan(o.contact_slope == ArealContactSlope::Lower ? slope_f() : 0.5 * (slope_f() + slope_g()));
  };

  // Offsets are independent: contiguous chunks over threads, results written per offset.
  util::parallel_chunks(count, util::thread_count(o.threads, count), [&](unsigned, std::size_t k0, std::size_t k1) {
    std::vector<std::pair<double, std::size_t>> order;
    for (std::size_t k = k0; k < k1; ++k) run_offset(k, order);
  });

  double sum = 0;
  std::size_t n = 0;
  out.theta_max_forward = out.theta_max_backward = -std::numeric_limits<double>::infinity();
  out.theta_max_lift = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < count; ++k) {
    out.evaluated_nodes += work[k];
    if (std::isnan(out.theta[k])) continue;
    out.theta_max_forward = std::max(out.theta_max_forward, out.theta[k]);
    out.theta_max_backward = std::max(out.theta_max_backward, -out.theta[k]);
    sum += out.theta[k];
    ++n;
    if (k + 1 < count && !std::isnan(out.lift[k + 1]))
      out.theta_max_lift = std::max(out.theta_max_lift, std::atan((out.lift[k + 1] - out.lift[k]) / step));
  }
  if (n == 0) return make_error("areal_signature: the blocks never overlap over the offsets requested");
  out.contact_slope_mean = sum / double(n);
  double var = 0;  // two-pass: no cancellation when every slope is the same
  for (double th : out.theta)
    if (!std::isnan(th)) var += (th - out.contact_slope_mean) * (th - out.contact_slope_mean);
  out.contact_slope_std = std::sqrt(var / double(n));
  return out;
}

namespace detail {

Result<ArealLift> areal_offset_grid(const Map& f, double angle, const ArealLiftOptions& o, const char* who) {
  auto finite_nonneg = [](double v) { return std::isfinite(v) && v >= 0; };
  if (!finite_nonneg(o.step) || !finite_nonneg(o.across_step) || !finite_nonneg(o.across_max) ||
      !std::isfinite(o.offset_min) || !std::isfinite(o.offset_max))
    return make_error(
        fmt::format("{}: step {}, across_step {}, across_max {} must be finite and >= 0, offset_min {} and "
                    "offset_max {} finite (m)",
                    who, o.step, o.across_step, o.across_max, o.offset_min, o.offset_max));
  const double dxv = std::cos(angle), dyv = std::sin(angle);
  const double ex = -dyv, ey = dxv;  // across d
  const double step = o.step > 0 ? o.step : std::min(f.dx, f.dy);
  const double across_step = o.across_step > 0 ? o.across_step : step;
  const double along_extent = std::abs(dxv) * f.width() + std::abs(dyv) * f.height();
  const double across_extent = std::abs(ex) * f.width() + std::abs(ey) * f.height();
  const double umax = o.offset_max > o.offset_min ? o.offset_max : o.offset_min + 0.5 * along_extent;
  const double vmax = o.across_max > 0 ? o.across_max : 0.25 * across_extent;
  const std::size_t nu = std::size_t(std::floor((umax - o.offset_min) / step + 1e-9)) + 1;
  const std::size_t m = std::size_t(std::floor(vmax / across_step + 1e-9));
  ArealLift out;
  out.angle = angle;
  out.n_along = nu;
  out.n_across = 2 * m + 1;
  out.along_min = o.offset_min;
  out.step = step;
  out.across_min = -double(m) * across_step;
  out.across_step = across_step;
  return out;
}

bool areal_lift_touches(ArealLift& out, const std::vector<std::size_t>& work) {
  bool any = false;
  for (std::size_t k = 0; k < out.lift.size(); ++k) {
    out.evaluated_nodes += work[k];
    any = any || !std::isnan(out.lift[k]);
  }
  return any;
}

}  // namespace detail

Result<ArealLift> areal_lift(const Map& f, const Map& g_in, double angle, const ArealLiftOptions& o) {
  if (auto s = validate(f, "lower map"); !s) return s.error();
  if (auto s = validate(g_in, "upper map"); !s) return s.error();
  LiftEvaluator ev;
  if (auto s = ev.init(f, g_in, angle, o.turn_over_upper, o.block, "areal_lift"); !s) return s.error();
  const double dxv = std::cos(angle), dyv = std::sin(angle);
  const double ex = -dyv, ey = dxv;  // across d
  auto grid = detail::areal_offset_grid(f, angle, o, "areal_lift");
  if (!grid) return grid.error();
  ArealLift out = std::move(*grid);
  const std::size_t nu = out.n_along, nv = out.n_across;
  if (double(nu) * double(nv) > 5e7)
    return make_error(
        fmt::format("areal_lift: {} x {} offsets are more than 5e7; increase step or across_step", nu, nv));
  out.lift.assign(nu * nv, std::numeric_limits<double>::quiet_NaN());
  out.contact.assign(nu * nv, -1);
  std::vector<std::size_t> work(nu * nv, 0);
  util::parallel_chunks(nu * nv, util::thread_count(o.threads, nu * nv), [&](unsigned, std::size_t k0, std::size_t k1) {
    std::vector<std::pair<double, std::size_t>> order;
    for (std::size_t k = k0; k < k1; ++k) {
      const double u = out.along(k % nu), v = out.across(k / nu);
      // The same products as areal_signature's s d on the line v = 0.
      const double sx = u * dxv + v * ex, sy = u * dyv + v * ey;
      const LiftEvaluator::Best b = ev.best(sx, sy, o.prune, order);
      work[k] = b.evaluated;
      if (b.index == LiftEvaluator::kNone) continue;
      out.lift[k] = b.value;
      out.contact[k] = std::int64_t(b.index);
    }
  });
  if (!detail::areal_lift_touches(out, work))
    return make_error(
        fmt::format("areal_lift: the blocks never touch over offsets {} to {} m along {} deg and +-{} m "
                    "across (expected maps that overlap along the sliding direction)",
                    out.along(0), out.along(nu - 1), angle * 180 / std::numbers::pi, -out.across_min));
  return out;
}

}  // namespace frictal
