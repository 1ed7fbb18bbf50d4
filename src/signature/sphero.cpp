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
#include <fmt/core.h>
#include <algorithm>
#include <cmath>
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

// The upper envelope as spans [a, b] of one primitive (p = -1: none) covering [smin, smax].
struct Span {
  double a, b;
  int p;
};
using Env = std::vector<Span>;

void push_span(Env& e, double a, double b, int p, double xtol) {
  if (!(b > a)) return;
  if (!e.empty() && e.back().p == p && std::abs(e.back().b - a) <= xtol) {
    e.back().b = b;
    return;
  }
  e.push_back({a, b, p});
}

Env merge(const Sphero& S, const std::vector<Prim>& prims, const Env& A, const Env& B, double xtol) {
  Env out;
  out.reserve(A.size() + B.size());
  std::size_t i = 0, j = 0;
  std::vector<double> cuts;
  while (i < A.size() && j < B.size()) {
    const double x = std::max(A[i].a, B[j].a), y = std::min(A[i].b, B[j].b);
    const int p = A[i].p, q = B[j].p;
    if (y > x) {
      if (p < 0 || q < 0) {
        push_span(out, x, y, p < 0 ? q : p, xtol);
      } else {
        const Prim& P = prims[static_cast<std::size_t>(p)];
        const Prim& Q = prims[static_cast<std::size_t>(q)];
        cuts.clear();
        cuts.push_back(x);
        intersect(S, P, Q, x + xtol, y - xtol, cuts);
        std::sort(cuts.begin() + 1, cuts.end());
        cuts.push_back(y);
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
          const double m = 0.5 * (cuts[k] + cuts[k + 1]);
          push_span(out, cuts[k], cuts[k + 1], S.value(Q, m) > S.value(P, m) ? q : p, xtol);
        }
      }
    }
    if (A[i].b < B[j].b)
      ++i;
    else if (B[j].b < A[i].b)
      ++j;
    else
      ++i, ++j;
  }
  return out;
}

// Envelope of prims[i0, i1) over [smin, smax].
Env envelope_range(const Sphero& S, const std::vector<Prim>& prims, std::size_t i0, std::size_t i1, double smin,
                   double smax, double xtol) {
  if (i1 - i0 == 1) {
    const Prim& p = prims[i0];
    Env e;
    // Domains widened by xtol: consecutive offsets of almost collinear pieces (no arc between
    // them) meet up to rounding.
    const double lo = std::clamp(p.lo - xtol, smin, smax), hi = std::clamp(p.hi + xtol, smin, smax);
    push_span(e, smin, lo, -1, xtol);
    push_span(e, lo, hi, static_cast<int>(i0), xtol);
    push_span(e, hi, smax, -1, xtol);
    if (e.empty()) e.push_back({smin, smax, -1});
    return e;
  }
  const std::size_t mid = i0 + (i1 - i0) / 2;
  return merge(S, prims, envelope_range(S, prims, i0, mid, smin, smax, xtol),
               envelope_range(S, prims, mid, i1, smin, smax, xtol), xtol);
}

Env envelope(const Sphero& S, const std::vector<Prim>& prims, double smin, double smax, double xtol) {
  return envelope_range(S, prims, 0, prims.size(), smin, smax, xtol);
}

}  // namespace

Result<SignatureResult> sphero_signature(const Profile& lower, const Profile& upper, const SignatureOptions& o) {
  if (o.slopes != SlopeMethod::Exact)
    return make_error(
        "signature: spline slopes are not available with a spheroradius > 0 (the rounded faces "
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
    return make_error(
        fmt::format("signature: offsets [{}, {}] m leave no overlap between the blocks (allowed: "
                    "inside ({}, {}) m)",
                    smin, smax, -upper.length(), lower.length()));

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
  for (std::size_t i = 0; i < knots.size(); ++i)
    knots[i] = {rs.offset[i], rs.lift[i], rs.theta_left[i], rs.theta_right[i]};
  std::vector<Piece> pieces;
  PieceBuilder builder(*rigid, vtol, pieces);
  for (std::size_t i = 0; i + 1 < knots.size(); ++i) builder.interval(knots[i], knots[i + 1]);
  // Merge collinear continuous pieces (events where h0 does not bend).
  std::vector<Piece> merged;
  for (const Piece& p : pieces) {
    if (!merged.empty()) {
      Piece& q = merged.back();
      const double mq = (q.hb - q.ha) / (q.b - q.a), mp = (p.hb - p.ha) / (p.b - p.a);
      if (std::abs(q.b - p.a) <= xtol && std::abs(q.hb - p.ha) <= vtol &&
          std::abs(mq - mp) <= 1e-12 * (1 + std::abs(mq))) {
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
  // An arc at every junction of two pieces that is not a clear valley (there the offsets
  // overlap), so that the primitives cover every offset whatever the rounding of the slopes
  // (each piece's offset with its two end arcs covers [a - R, b + R]).
  for (std::size_t i = 0; i < merged.size(); ++i) {
    const Piece& p = merged[i];
    if (i == 0 || std::abs(merged[i - 1].b - p.a) > xtol) add_arc(p.a, p.ha);
    const bool joined = i + 1 < merged.size() && std::abs(merged[i + 1].a - p.b) <= xtol;
    if (joined) {  // a clear valley needs none: the offsets overlap there
      const Piece& q = merged[i + 1];
      const double mp = (p.hb - p.ha) / (p.b - p.a), mq = (q.hb - q.ha) / (q.b - q.a);
      if (mq > mp + 1e-9 * (1 + std::abs(mp))) continue;
    }
    add_arc(p.b, joined ? std::max(p.hb, merged[i + 1].ha) : p.hb);
  }
  prims.erase(std::remove_if(prims.begin(), prims.end(), [&](const Prim& p) { return p.hi < smin || p.lo > smax; }),
              prims.end());
  if (prims.empty()) return make_error("signature: the blocks do not overlap over the offset range");
  std::sort(prims.begin(), prims.end(), [](const Prim& a, const Prim& b) {
    return a.lo < b.lo ||
           (a.lo == b.lo && (a.arc < b.arc || (a.arc == b.arc && (a.H < b.H || (a.H == b.H && a.c < b.c)))));
  });
  prims.erase(std::unique(prims.begin(), prims.end(),
                          [](const Prim& a, const Prim& b) { return a.arc && b.arc && a.t == b.t && a.H == b.H; }),
              prims.end());

  // Upper envelope over [smin, smax] by divide and conquer: merging two envelopes walks their
  // common sub-intervals and splits each at the intersections of its two primitives.
  const Env env = envelope(S, prims, smin, smax, xtol);
  std::vector<double> brk;        // breakpoints: brk[k], brk[k + 1] bound span k
  std::vector<const Prim*> bseg;  // the active primitive of span k
  for (const Span& sp : env) {
    if (sp.p < 0)
      return make_error(fmt::format("signature: no overlap between the blocks at offset {} m", 0.5 * (sp.a + sp.b)));
    if (brk.empty()) brk.push_back(sp.a);
    bseg.push_back(&prims[static_cast<std::size_t>(sp.p)]);
    brk.push_back(sp.b);
  }
  const std::size_t nseg = bseg.size();

  // At offset s: the primitives in contact (the span's, both spans' at a breakpoint), and h's
  // slopes just before and after s.
  struct At {
    const Prim* left = nullptr;   // primitive just before s
    const Prim* right = nullptr;  // primitive just after s
  };
  auto locate = [&](double s) {
    At r;
    const auto it = std::lower_bound(brk.begin(), brk.end(), s);
    std::size_t j = static_cast<std::size_t>(it - brk.begin());
    if (j > 0 && (j == brk.size() || s - brk[j - 1] < brk[j] - s)) --j;  // nearest breakpoint
    if (std::abs(brk[j] - s) <= xtol) {
      r.left = j > 0 ? bseg[j - 1] : bseg[0];
      r.right = j < nseg ? bseg[j] : bseg[nseg - 1];
      return r;
    }
    const std::size_t k = std::min<std::size_t>(
        nseg - 1, static_cast<std::size_t>(std::upper_bound(brk.begin(), brk.end(), s) - brk.begin()) - 1);
    r.left = r.right = bseg[k];
    return r;
  };

  SignatureResult out;
  out.spheroradius = r;
  out.exact = rs.exact;
  out.events = brk.size();

  // Exact extremes: at every breakpoint both spans' slopes (on a span the slope is constant or,
  // on an arc, decreasing, so its extremes are at its ends).
  out.theta_max_forward = -kInf;
  out.theta_max_backward = -kInf;
  for (std::size_t i = 0; i < brk.size(); ++i) {
    const double a = S.slope(*bseg[i > 0 ? i - 1 : 0], brk[i]), b = S.slope(*bseg[std::min(i, nseg - 1)], brk[i]);
    const double hi = std::max(a, b), lo = std::min(a, b);
    if (hi > out.theta_max_forward) {
      out.theta_max_forward = hi;
      out.offset_at_forward = brk[i];
    }
    if (-lo > out.theta_max_backward) {
      out.theta_max_backward = -lo;
      out.offset_at_backward = brk[i];
    }
  }

  // Listed offsets: the breakpoints and up to 8 points inside each arc span, or N equally spaced.
  std::vector<double> offs;
  if (o.offsets == 0) {
    for (std::size_t i = 0; i < nseg; ++i) {
      offs.push_back(brk[i]);
      if (bseg[i]->arc) {  // up to 8 points inside, about one per degree the slope turns
        const double turn = std::abs(S.slope(*bseg[i], brk[i]) - S.slope(*bseg[i], brk[i + 1]));
        const int m = static_cast<int>(std::min(9.0, std::ceil(turn / (std::numbers::pi / 180))));
        for (int k = 1; k < m; ++k) offs.push_back(brk[i] + (brk[i + 1] - brk[i]) * k / m);
      }
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
  for (std::size_t i = 0; i < n; ++i) {
    const double s = offs[i];
    const At at = locate(s);
    auto clampd = [&](const Prim* p) { return std::clamp(s, p->lo, p->hi); };
    const double a = S.slope(*at.left, clampd(at.left)), b = S.slope(*at.right, clampd(at.right));
    out.lift[i] = std::max(S.value(*at.left, clampd(at.left)), S.value(*at.right, clampd(at.right)));
    out.theta[i] = std::max(a, b);
    out.theta_min[i] = std::min(a, b);
    out.theta_left[i] = a;
    out.theta_right[i] = b;
    if (o.keep_contacts) {
      for (const Prim* p : {at.left, at.right}) {
        if (p == at.right && at.right == at.left) break;
        const double sl = S.slope(*p, clampd(p));
        const auto rp = rigid->at(S.rigid_offset(*p, clampd(p)));
        if (!std::isfinite(rp.contact_x)) continue;
        Contact c;
        c.x = rp.contact_x - r * std::sin(sl);
        c.z = rigid->lower_height(rp.contact_x) + r * std::cos(sl);
        c.slope = sl;
        c.type = rp.type;
        out.contacts.push_back(c);
      }
      std::sort(out.contacts.begin() + out.contact_begin.back(), out.contacts.end(),
                [](const Contact& p, const Contact& q) { return p.x < q.x; });
      out.contact_begin.push_back(static_cast<std::uint32_t>(out.contacts.size()));
    }
  }

  // Contact-slope distribution: each interval by its slope (arcs: up to 16 sub-intervals, one per 0.25 deg the slope
  // turns, at their middles), weighted by length; sampled offsets: theta at each.
  if (o.offsets == 0) {
    for (std::size_t i = 0; i < nseg; ++i) {
      const double L = brk[i + 1] - brk[i];
      if (!(L > 0)) continue;
      if (!bseg[i]->arc) {
        out.slope_samples.push_back(bseg[i]->phi);
        out.slope_weights.push_back(L);
      } else {
        const double turn = std::abs(S.slope(*bseg[i], brk[i]) - S.slope(*bseg[i], brk[i + 1]));
        const int m = static_cast<int>(std::clamp(std::ceil(turn / (0.25 * std::numbers::pi / 180)), 1.0, 16.0));
        for (int k = 0; k < m; ++k) {
          out.slope_samples.push_back(S.slope(*bseg[i], brk[i] + L * (k + 0.5) / m));
          out.slope_weights.push_back(L / m);
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
