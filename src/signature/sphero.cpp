// The signature of spheropolygon blocks (SignatureOptions::spheroradius > 0).
//
// Each block is a polygon core swept by a disk of radius r; two blocks touch when their cores
// are R = 2r apart. In configuration space (offset s, lift h) the cores overlap exactly in the
// hypograph of the rigid lift h0 (the paper's signature of the two cores), and they come closer
// than R exactly in that hypograph dilated by a disk of radius R (Minkowski sum: the distance
// between A and B + t is below R iff t lies in (A - B) + disk(R)). Hence
//   h(s) = max_{|s' - s| <= R} [ h0(s') + sqrt(R^2 - (s - s')^2) ],
// the upper envelope of
//   - the offsets of h0's linear pieces by R along their normals (slope unchanged: a core vertex
//     sliding along the other core's edge, rounded), and
//   - circular arcs of radius R centred at h0's ridges and at the tops of its jumps (a rounded
//     vertex rolling over a rounded vertex or ridge), on which the contact slope is the arc's
//     tangent angle -asin((s - t) / R).
// h0 is piecewise linear and convex between events (signature.cpp); its pieces are recovered
// exactly from the events' one-sided slopes, checking each crossing of two end lines by an exact
// evaluation (and subdividing where a third piece hides between them). The envelope's breakpoints
// are domain ends and intersections of primitives (line-line, line-arc, arc-arc in closed form);
// between breakpoints one primitive is active and its slope is monotone (constant on a line,
// decreasing on an arc), so the extreme slopes are at breakpoints: theta_max is exact.
#include <algorithm>
#include <cmath>
#include <fmt/core.h>
#include <limits>
#include <numbers>

#include "frictal/signature.hpp"
#include "signature/rigid.hpp"

namespace frictal::detail {
namespace {

constexpr double kHalfPi = std::numbers::pi / 2;
constexpr double kInf = std::numeric_limits<double>::infinity();

// A knot of the rigid lift: value and one-sided slopes (angles, rad) at offset s.
struct Knot {
  double s, h, left, right;
};

// A linear piece of h0 from (a, ha) to (b, hb).
struct Piece {
  double a, ha, b, hb;
};

// A primitive of the dilated lift.
struct Prim {
  bool arc = false;
  double lo = 0, hi = 0;  // domain in s
  // line: h = c + m s, angle phi; arc: centre (t, H)
  double m = 0, c = 0, phi = 0;
  double t = 0, H = 0;
};

struct Sphero {
  double R = 0;
  double value(const Prim& p, double s) const {
    if (!p.arc) return p.c + p.m * s;
    const double u = s - p.t;
    return p.H + std::sqrt(std::max(0.0, R * R - u * u));
  }
  double slope(const Prim& p, double s) const {
    if (!p.arc) return p.phi;
    return -std::asin(std::clamp((s - p.t) / R, -1.0, 1.0));
  }
  // Rigid offset s' whose point of h0 this primitive rounds at s.
  double rigid_offset(const Prim& p, double s) const { return p.arc ? p.t : s + R * std::sin(p.phi); }
};

// Intersections of two primitives inside [lo, hi]; appended to out.
void intersect(const Sphero& S, const Prim& p, const Prim& q, double lo, double hi, std::vector<double>& out) {
  const double R = S.R;
  auto keep = [&](double s) {
    if (std::isfinite(s) && s >= lo && s <= hi) out.push_back(s);
  };
  if (!p.arc && !q.arc) {
    if (p.m != q.m) keep((q.c - p.c) / (p.m - q.m));
    return;
  }
  if (p.arc && q.arc) {
    const double dx = q.t - p.t, dz = q.H - p.H, d2 = dx * dx + dz * dz;
    if (d2 <= 0 || d2 > 4 * R * R) return;
    const double d = std::sqrt(d2), k = std::sqrt(std::max(0.0, R * R - d2 / 4));
    const double mx = 0.5 * (p.t + q.t), mz = 0.5 * (p.H + q.H);
    for (int sg : {-1, 1}) {
      const double x = mx + sg * k * (-dz / d), z = mz + sg * k * (dx / d);
      if (z >= std::max(p.H, q.H) - 1e-12 * R) keep(x);
    }
    return;
  }
  const Prim& L = p.arc ? q : p;
  const Prim& A = p.arc ? p : q;
  // (m s + c - H)^2 + (s - t)^2 = R^2, with m s + c - H >= 0.
  const double e = L.c - A.H;
  const double qa = 1 + L.m * L.m, qb = 2 * (L.m * e - A.t), qc = e * e + A.t * A.t - R * R;
  const double disc = qb * qb - 4 * qa * qc;
  if (disc < 0) return;
  const double sq = std::sqrt(disc);
  for (double s : {(-qb - sq) / (2 * qa), (-qb + sq) / (2 * qa)})
    if (L.m * s + e >= -1e-9 * R) keep(s);
}

// Recovers h0's linear pieces between two consecutive knots (h0 convex in between) exactly.
class PieceBuilder {
 public:
  PieceBuilder(const RigidLift& rigid, double vtol, std::vector<Piece>& out) : rigid_(rigid), vtol_(vtol), out_(out) {}

  // Pieces on (A.s, B.s).
  void interval(const Knot& A, const Knot& B) {
    const double w = B.s - A.s;
    if (!(w > 0)) return;
    double ha, ma, hb, mb;
    if (std::abs(A.right) < kHalfPi) {
      ha = A.h;
      ma = std::tan(A.right);
    } else {  // h0 drops right of A: probe just inside for the adjacent piece
      const double e = 1e-9 * w;
      const auto q = rigid_.at(A.s + e);
      ma = std::tan(q.right);
      ha = q.lift - ma * e;
    }
    if (std::abs(B.left) < kHalfPi) {
      hb = B.h;
      mb = std::tan(B.left);
    } else {
      const double e = 1e-9 * w;
      const auto q = rigid_.at(B.s - e);
      mb = std::tan(q.left);
      hb = q.lift + mb * e;
    }
    refine(A.s, ha, ma, B.s, hb, mb, 0);
  }

 private:
  void refine(double sa, double ha, double ma, double sb, double hb, double mb, int depth) {
    if (std::abs(ma - mb) <= 1e-12 * (1 + std::abs(ma)) || depth > 50) {
      out_.push_back({sa, ha, sb, hb});
      return;
    }
    double sc = (hb - ha + ma * sa - mb * sb) / (ma - mb);
    sc = std::clamp(sc, sa, sb);
    const double pred = ha + ma * (sc - sa);
    const auto p = rigid_.at(sc);
    if (!std::isfinite(p.lift) || std::abs(p.lift - pred) <= vtol_ || std::abs(p.left) >= kHalfPi ||
        std::abs(p.right) >= kHalfPi || sc <= sa || sc >= sb) {
      if (sc > sa) out_.push_back({sa, ha, sc, pred});
      if (sb > sc) out_.push_back({sc, sc > sa ? pred : ha, sb, hb});
      return;
    }
    refine(sa, ha, ma, sc, p.lift, std::tan(p.left), depth + 1);
    refine(sc, p.lift, std::tan(p.right), sb, hb, mb, depth + 1);
  }

  const RigidLift& rigid_;
  double vtol_;
  std::vector<Piece>& out_;
};

}  // namespace

Result<SignatureResult> sphero_signature(const Profile& lower, const Profile& upper, const SignatureOptions& o) {
  if (o.slopes != SlopeMethod::Exact)
    return make_error("signature: spline slopes are not available with a spheroradius > 0 (the rounded faces "
                      "have their own exact slopes); use exact slopes");
  const double r = o.spheroradius;
  Sphero S;
  S.R = 2 * r;
  const double R = S.R;

  const bool periodic = lower.period && upper.period && std::abs(*lower.period - *upper.period) <= 1e-9 * *lower.period;
  double smin = o.offset_min, smax = o.offset_max;
  if (!(smax > smin)) {
    smin = 0;
    smax = periodic ? *lower.period : 0.5 * std::min(lower.length(), upper.length());
  }
  if (!std::isfinite(smin) || !std::isfinite(smax)) return make_error("signature: offset range must be finite");
  if (!periodic && (!(smin > -upper.length()) || !(smax < lower.length())))
    return make_error(fmt::format("signature: offsets [{}, {}] m leave no overlap between the blocks (allowed: "
                                  "inside ({}, {}) m)", smin, smax, -upper.length(), lower.length()));

  // Rigid lift over [smin - R, smax + R] (inside the overlap for finite blocks).
  double rmin = smin - R, rmax = smax + R;
  if (!periodic) {
    rmin = std::max(rmin, -upper.length() * (1 - 1e-9));
    rmax = std::min(rmax, lower.length() * (1 - 1e-9));
  }
  SignatureOptions ro = o;
  ro.spheroradius = 0;
  ro.offsets = 0;
  ro.keep_contacts = false;
  ro.offset_min = rmin;
  ro.offset_max = rmax;
  auto rigid_sig = signature(lower, upper, ro);
  if (!rigid_sig) return rigid_sig.error();
  auto rigid = RigidLift::make(lower, upper, o);
  if (!rigid) return rigid.error();

  double zr = 0;
  {
    auto [a1, b1] = std::minmax_element(lower.z.begin(), lower.z.end());
    auto [a2, b2] = std::minmax_element(upper.z.begin(), upper.z.end());
    zr = (*b1 - *a1) + (*b2 - *a2);
  }
  const double Lmax = std::max(lower.length(), upper.length());
  const double vtol = o.tolerance * std::max(zr + R, 1e-9 * Lmax);
  const double xtol = 1e-12 * std::max({Lmax, std::abs(smin), std::abs(smax)});

  // h0's knots (events) and pieces.
  const SignatureResult& rs = *rigid_sig;
  std::vector<Knot> knots(rs.offset.size());
  for (std::size_t i = 0; i < knots.size(); ++i) knots[i] = {rs.offset[i], rs.lift[i], rs.theta_left[i], rs.theta_right[i]};
  std::vector<Piece> pieces;
  PieceBuilder builder(*rigid, vtol, pieces);
  for (std::size_t i = 0; i + 1 < knots.size(); ++i) builder.interval(knots[i], knots[i + 1]);
  // Merge collinear continuous pieces (events where h0 does not bend).
  std::vector<Piece> merged;
  for (const Piece& p : pieces) {
    if (!merged.empty()) {
      Piece& q = merged.back();
      const double mq = (q.hb - q.ha) / (q.b - q.a), mp = (p.hb - p.ha) / (p.b - p.a);
      if (std::abs(q.b - p.a) <= xtol && std::abs(q.hb - p.ha) <= vtol && std::abs(mq - mp) <= 1e-12 * (1 + std::abs(mq))) {
        q.b = p.b;
        q.hb = p.hb;
        continue;
      }
    }
    merged.push_back(p);
  }

  // Primitives: offset lines of the pieces, arcs at ridges and jump tops (the knots' sup values,
  // and the pieces' junctions that bend downwards).
  std::vector<Prim> prims;
  for (const Piece& p : merged) {
    Prim q;
    q.m = (p.hb - p.ha) / (p.b - p.a);
    q.phi = std::atan(q.m);
    q.c = p.ha - q.m * p.a + R * std::sqrt(1 + q.m * q.m);
    q.lo = p.a - R * std::sin(q.phi);
    q.hi = p.b - R * std::sin(q.phi);
    prims.push_back(q);
  }
  auto add_arc = [&](double t, double H) {
    Prim q;
    q.arc = true;
    q.t = t;
    q.H = H;
    q.lo = t - R;
    q.hi = t + R;
    prims.push_back(q);
  };
  for (const Knot& k : knots) {
    const bool jump = std::abs(k.left) >= kHalfPi || std::abs(k.right) >= kHalfPi;
    if (jump || k.left > k.right + 1e-12) add_arc(k.s, k.h);
  }
  for (std::size_t i = 0; i + 1 < merged.size(); ++i) {  // bends found inside intervals
    const Piece& p = merged[i];
    const Piece& q = merged[i + 1];
    const double mp = (p.hb - p.ha) / (p.b - p.a), mq = (q.hb - q.ha) / (q.b - q.a);
    if (mp > mq + 1e-12 && std::abs(p.b - q.a) <= xtol) {
      bool at_knot = std::binary_search(rs.offset.begin(), rs.offset.end(), p.b);
      if (!at_knot) add_arc(p.b, std::max(p.hb, q.ha));
    }
  }
  if (prims.empty()) return make_error("signature: the blocks do not overlap over the offset range");
  std::sort(prims.begin(), prims.end(), [](const Prim& a, const Prim& b) { return a.lo < b.lo; });
  double wmax = 0;
  for (const Prim& p : prims) wmax = std::max(wmax, p.hi - p.lo);

  // Primitives whose domain contains s (within xtol), by index.
  auto for_active = [&](double s, double tol, auto&& fn) {
    auto it = std::lower_bound(prims.begin(), prims.end(), s - wmax - tol, [](const Prim& p, double v) { return p.lo < v; });
    for (; it != prims.end() && it->lo <= s + tol; ++it)
      if (it->hi >= s - tol) fn(*it);
  };

  // Breakpoint candidates in [smin, smax].
  std::vector<double> cand{smin, smax};
  for (std::size_t i = 0; i < prims.size(); ++i) {
    const Prim& p = prims[i];
    if (p.hi < smin || p.lo > smax) continue;
    if (p.lo >= smin) cand.push_back(p.lo);
    if (p.hi <= smax) cand.push_back(p.hi);
    for (std::size_t j = i + 1; j < prims.size() && prims[j].lo <= p.hi; ++j) {
      const Prim& q = prims[j];
      const double lo = std::max({p.lo, q.lo, smin}), hi = std::min({p.hi, q.hi, smax});
      if (lo <= hi) intersect(S, p, q, lo, hi, cand);
    }
  }
  std::sort(cand.begin(), cand.end());
  std::vector<double> bp;
  for (double v : cand)
    if (bp.empty() || v > bp.back() + xtol) bp.push_back(v);
  bp.back() = smax;

  // The active primitive of each interval between candidates (max at its middle).
  const std::size_t nb = bp.size();
  std::vector<const Prim*> seg(nb > 1 ? nb - 1 : 0, nullptr);
  for (std::size_t k = 0; k + 1 < nb; ++k) {
    const double m = 0.5 * (bp[k] + bp[k + 1]);
    double best = -kInf;
    for_active(m, 0.0, [&](const Prim& p) {
      const double v = S.value(p, m);
      if (v > best) {
        best = v;
        seg[k] = &p;
      }
    });
    if (!seg[k]) return make_error(fmt::format("signature: no overlap between the blocks at offset {} m", m));
  }
  // Keep only real breakpoints (the active primitive changes) and the range ends.
  std::vector<double> brk{bp.front()};
  std::vector<const Prim*> bseg;
  for (std::size_t k = 0; k + 1 < nb; ++k) {
    if (!bseg.empty() && bseg.back() == seg[k]) {
      brk.back() = bp[k + 1];
      continue;
    }
    if (bseg.empty()) {
      bseg.push_back(seg[k]);
      brk.push_back(bp[k + 1]);
    } else {
      bseg.push_back(seg[k]);
      brk.push_back(bp[k + 1]);
    }
  }
  // brk[i], brk[i+1] bound interval i with primitive bseg[i].

  struct Eval {
    double lift, theta, theta_min;
  };
  auto evaluate_at = [&](double s, std::vector<const Prim*>* act) {
    double best = -kInf;
    for_active(s, xtol, [&](const Prim& p) { best = std::max(best, S.value(p, std::clamp(s, p.lo, p.hi))); });
    Eval e{best, -kInf, kInf};
    for_active(s, xtol, [&](const Prim& p) {
      const double sc = std::clamp(s, p.lo, p.hi);
      if (S.value(p, sc) >= best - vtol) {
        const double a = S.slope(p, sc);
        e.theta = std::max(e.theta, a);
        e.theta_min = std::min(e.theta_min, a);
        if (act) act->push_back(&p);
      }
    });
    return e;
  };

  SignatureResult out;
  out.spheroradius = r;
  out.exact = rs.exact;
  out.events = brk.size();

  // Exact extremes: theta at every breakpoint and the slopes at both ends of every interval.
  out.theta_max_forward = -kInf;
  out.theta_max_backward = -kInf;
  for (std::size_t i = 0; i < brk.size(); ++i) {
    const Eval e = evaluate_at(brk[i], nullptr);
    double hi = e.theta, lo = e.theta_min;
    if (i > 0) {
      const double a = S.slope(*bseg[i - 1], brk[i]);
      hi = std::max(hi, a);
      lo = std::min(lo, a);
    }
    if (i < bseg.size()) {
      const double a = S.slope(*bseg[i], brk[i]);
      hi = std::max(hi, a);
      lo = std::min(lo, a);
    }
    if (hi > out.theta_max_forward) {
      out.theta_max_forward = hi;
      out.offset_at_forward = brk[i];
    }
    if (-lo > out.theta_max_backward) {
      out.theta_max_backward = -lo;
      out.offset_at_backward = brk[i];
    }
  }

  // Listed offsets: the breakpoints and 8 points inside each arc interval, or N equally spaced.
  std::vector<double> offs;
  if (o.offsets == 0) {
    for (std::size_t i = 0; i < bseg.size(); ++i) {
      offs.push_back(brk[i]);
      if (bseg[i]->arc)
        for (int k = 1; k < 9; ++k) offs.push_back(brk[i] + (brk[i + 1] - brk[i]) * k / 9.0);
    }
    offs.push_back(brk.back());
  } else {
    const std::size_t n = std::max<std::size_t>(o.offsets, 2);
    offs.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      offs[i] = (i + 1 == n) ? smax : smin + (smax - smin) * static_cast<double>(i) / static_cast<double>(n - 1);
    out.exact = false;
  }
  const std::size_t n = offs.size();
  out.offset = offs;
  out.lift.resize(n);
  out.theta.resize(n);
  out.theta_min.resize(n);
  out.theta_left.resize(n);
  out.theta_right.resize(n);
  if (o.keep_contacts) out.contact_begin.push_back(0);
  std::vector<const Prim*> act;
  for (std::size_t i = 0; i < n; ++i) {
    const double s = offs[i];
    act.clear();
    const Eval e = evaluate_at(s, o.keep_contacts ? &act : nullptr);
    out.lift[i] = e.lift;
    out.theta[i] = e.theta;
    out.theta_min[i] = e.theta_min;
    // Interval to the left and right of s.
    const auto it = std::upper_bound(brk.begin(), brk.end(), s);
    const std::size_t k = static_cast<std::size_t>(it - brk.begin());  // brk[k-1] <= s < brk[k]
    const bool on_brk = k > 0 && std::abs(brk[k - 1] - s) <= xtol;
    const std::size_t right_seg = std::min(k - 1, bseg.size() - 1);
    const std::size_t left_seg = on_brk ? (k >= 2 ? k - 2 : 0) : right_seg;
    out.theta_right[i] = S.slope(*bseg[right_seg], s);
    out.theta_left[i] = S.slope(*bseg[left_seg], s);
    if (o.keep_contacts) {
      std::sort(act.begin(), act.end());
      act.erase(std::unique(act.begin(), act.end()), act.end());
      for (const Prim* p : act) {
        const double a = S.slope(*p, std::clamp(s, p->lo, p->hi));
        const auto rp = rigid->at(S.rigid_offset(*p, std::clamp(s, p->lo, p->hi)));
        if (!std::isfinite(rp.contact_x)) continue;
        Contact c;
        c.x = rp.contact_x - r * std::sin(a);
        c.z = rigid->lower_height(rp.contact_x) + r * std::cos(a);
        c.slope = a;
        c.type = rp.type;
        out.contacts.push_back(c);
      }
      std::sort(out.contacts.begin() + out.contact_begin.back(), out.contacts.end(),
                [](const Contact& p, const Contact& q) { return p.x < q.x; });
      out.contact_begin.push_back(static_cast<std::uint32_t>(out.contacts.size()));
    }
  }

  // Contact-slope distribution: each interval by its slope (arcs: 16 sub-intervals at their
  // middles), weighted by length; sampled offsets: theta at each.
  if (o.offsets == 0) {
    for (std::size_t i = 0; i < bseg.size(); ++i) {
      const double L = brk[i + 1] - brk[i];
      if (!(L > 0)) continue;
      if (!bseg[i]->arc) {
        out.slope_samples.push_back(bseg[i]->phi);
        out.slope_weights.push_back(L);
      } else {
        for (int k = 0; k < 16; ++k) {
          out.slope_samples.push_back(S.slope(*bseg[i], brk[i] + L * (k + 0.5) / 16));
          out.slope_weights.push_back(L / 16);
        }
      }
    }
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      out.slope_samples.push_back(out.theta[i]);
      out.slope_weights.push_back(1.0);
    }
  }
  if (out.slope_samples.empty()) {
    out.slope_samples.push_back(out.theta.front());
    out.slope_weights.push_back(1.0);
  }
  const MeanStd ms = weighted_mean_std(out.slope_samples, out.slope_weights);
  out.contact_slope_mean = ms.mean;
  out.contact_slope_std = ms.std;
  out.contact_slope_pdf = histogram(out.slope_samples, out.slope_weights, o.bins);
  return out;
}

}  // namespace frictal::detail
