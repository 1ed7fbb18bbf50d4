// The signature function: exact evaluation of h(s), its contacts and one-sided slopes.
#include "frictal/signature.hpp"

#include <fmt/core.h>
#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "signature/face.hpp"
#include "signature/rigid.hpp"
#include "signature/spline.hpp"
#include "util/parallel.hpp"

namespace frictal {
namespace {

using detail::Face;
using detail::kBlock;
using detail::Position;

constexpr double kHalfPi = std::numbers::pi / 2;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A candidate maximiser: a vertex of one face at a position of the other.
struct Cand {
  double value;
  std::size_t index;  // vertex index on its own face
  bool family_f;      // true: vertex of the lower face F; false: vertex of the upper face G
};

// Tilted bounds of the general search, on uniform grids (both faces; TiltedMax in face.hpp).
// A range [lo, hi] of A lies in one aligned node of A (the smallest that holds both ends), whose
// line bounds vA there; the abscissae xa[i] + shift read B between its vertices jlo =
// floor(ulo - xtol) and jhi = ceil(uhi + xtol), which lie in one aligned node of B, whose line
// bounds vB at its vertices and so at every interpolated or snapped value between them. On
// uniform grids the position in B's index of xa[i] + shift is linear in i, so the sum of both
// lines is linear in i and at most its larger end value. Margins: B's line times how far the
// computed fractional index may be from the true one (the grids' uniformity tolerances, xtol,
// rounding), and the rounding of the sums (as in search_aligned).
struct GeneralTilt {
  double xb0 = 0, inv_dxb = 0;  // B's first abscissa (unit: m) and 1 / spacing (unit: 1/m)
  double index_err = 0;         // bound on the error of B's fractional index (unit: points)
  double margin = 0;            // rounding margin of the line sums (unit: m)
};

// Smallest level l of aligned nodes (32 << l points) with i and j in one node.
inline unsigned common_level(std::size_t i, std::size_t j) {
  const std::size_t d = (i ^ j) >> detail::kBlockShift;
  return d == 0 ? 0u : static_cast<unsigned>(std::bit_width(d));
}

// The prepared problem: faces, candidate index ranges and frames.
struct Problem {
  Face F, G;
  bool periodic = false;
  double period = 0;
  // Periodic: candidate vertices are one period of each face (fixed index ranges).
  std::size_t f_lo = 0, f_hi = 0, g_lo = 0, g_hi = 0;
  // Non-periodic: the overlap of both blocks is [max(F0, G0 + s), min(F1, G1 + s)].
  double xtol = 0;               // abscissa tolerance (m)
  double vtol = 0;               // value tolerance (m)
  bool aligned_lattice = false;  // both uniform with the same spacing, events on a lattice
  double lattice_origin = 0, lattice_step = 0;
  std::vector<double> spline_f, spline_g;     // spline slopes at points (SlopeMethod::Spline)
  double lower_length = 0, upper_length = 0;  // block lengths (m)
  // Aligned lattice whose points sit on x0 + i dx within a small fraction of xtol: at a lattice
  // offset, vertex i of F faces vertex i - d of G exactly, and the search runs on indices.
  bool index_search = false;
  // The index search also bounds with the faces' tilted lines (TiltedMax).
  bool tilted = false;
  // The general search bounds with the tilted lines too (both faces on uniform grids).
  bool general_tilted = false;
  GeneralTilt tilt_fg, tilt_gf;  // F's vertices against G, G's against F
};

GeneralTilt general_tilt(const Face& A, const Face& B, double xtol) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  GeneralTilt t;
  t.xb0 = B.x_front();
  t.inv_dxb = 1.0 / B.spacing();
  const double xmag =
      std::max({std::abs(A.x_front()), std::abs(A.x_back()), std::abs(B.x_front()), std::abs(B.x_back())}) +
      (A.x_back() - A.x_front()) + (B.x_back() - B.x_front());
  // xtol (snapping), both grids' departures from uniform, the rounding of x + shift and of the
  // fractional index; doubled for safety.
  t.index_err = 2 * (xtol + A.grid_tolerance() + B.grid_tolerance() + 8 * eps * xmag) * t.inv_dxb + 1e-9;
  t.margin = 16 * eps *
             (A.tilted_max().magnitude() + B.tilted_max().magnitude() +
              std::max(std::abs(A.vmax()), std::abs(A.vmin())) + std::max(std::abs(B.vmax()), std::abs(B.vmin())));
  return t;
}

// Searches max over vertices i of A in [i0, i1] of vA[i] + vB(xA[i] + shift) by branch and
// bound over block ranges; appends candidates within vtol of the running best.
// With `start` (a GeneralFrontier's ranges of A), the search starts from those ranges clipped
// to [i0, i1] instead of from [i0, i1] itself: they hold every candidate of this offset.
using IndexRanges = std::vector<std::pair<std::size_t, std::size_t>>;
void search(const Face& A, const Face& B, double shift, std::size_t i0, std::size_t i1, bool family_f, double xtol,
            double vtol, double& best, std::vector<Cand>& out, const IndexRanges* start = nullptr,
            const GeneralTilt* tilt = nullptr) {
  if (i0 > i1) return;
  const auto& xa = A.x();
  const auto& va = A.v();
  struct Node {
    std::size_t lo, hi;
  };
  auto bound = [&](std::size_t lo, std::size_t hi) {
    const double ulo = xa[lo] + shift, uhi = xa[hi] + shift;
    const double plain = A.range_max(lo, hi) + B.range_max_x(ulo, uhi);
    if (!tilt || plain < best - vtol) return plain;  // the lines only matter where the maxima do not prune
    const unsigned la = common_level(lo, hi);
    const std::size_t jlo = B.floor_index(ulo - xtol), jhi = B.ceil_index(uhi + xtol);
    const unsigned lb = common_level(jlo, jhi);
    const detail::TiltedMax& ta = A.tilted_max();
    const detail::TiltedMax& tb = B.tilted_max();
    if (la >= ta.levels() || lb >= tb.levels()) return plain;
    const unsigned sha = detail::kBlockShift + la, shb = detail::kBlockShift + lb;
    const auto& a = ta.level(la)[lo >> sha];
    const auto& b = tb.level(lb)[jlo >> shb];
    const double sa = static_cast<double>((lo >> sha) << sha), sb = static_cast<double>((jlo >> shb) << shb);
    auto at = [&](std::size_t i, double u) {
      return (a.c + a.tau * (static_cast<double>(i) - sa)) + (b.c + b.tau * ((u - tilt->xb0) * tilt->inv_dxb - sb));
    };
    const double t = std::max(at(lo, ulo), at(hi, uhi)) + std::abs(b.tau) * tilt->index_err + tilt->margin;
    return std::min(plain, t);
  };
  // Depth-first, most promising half first; explicit stack (kept between calls: no allocation).
  thread_local std::vector<std::pair<Node, double>> stack;
  stack.clear();
  if (start) {
    for (const auto& [lo, hi] : *start) {
      const std::size_t a = std::max(lo, i0), b = std::min(hi, i1);
      if (a > b) continue;
      const double u = bound(a, b);
      if (u >= best - vtol) stack.push_back({{a, b}, u});
    }
    std::sort(stack.begin(), stack.end(), [](const auto& x, const auto& y) { return x.second < y.second; });
  } else {
    stack.push_back({{i0, i1}, bound(i0, i1)});
  }
  while (!stack.empty()) {
    auto [node, ub] = stack.back();
    stack.pop_back();
    if (ub < best - vtol) continue;
    if (node.hi - node.lo < kBlock) {
      // xa[i] + shift does not decrease with i: B's indices by a walk (Face::value_walk).
      Face::Cursor cur;
      for (std::size_t i = node.lo; i <= node.hi; ++i) {
        const double val = va[i] + B.value_walk(xa[i] + shift, xtol, cur);
        if (val >= best - vtol) {
          out.push_back({val, i, family_f});
          if (val > best) best = val;
        }
      }
      continue;
    }
    // Split at a block boundary so that child bounds use whole blocks.
    std::size_t mid = node.lo + (node.hi - node.lo + 1) / 2;
    mid = std::max(node.lo + 1, (mid / kBlock) * kBlock);
    Node a{node.lo, mid - 1}, b{mid, node.hi};
    const double ua = bound(a.lo, a.hi), ub2 = bound(b.lo, b.hi);
    if (ua >= ub2) {
      if (ub2 >= best - vtol) stack.push_back({b, ub2});
      if (ua >= best - vtol) stack.push_back({a, ua});
    } else {
      if (ua >= best - vtol) stack.push_back({a, ua});
      if (ub2 >= best - vtol) stack.push_back({b, ub2});
    }
  }
}

// Aligned-lattice search: max over i in [i0, i1] of va[i] + vb[i - d] (all indices valid), the
// same values as search() (Face::value at a lattice vertex is that vertex's v). Branch and bound
// over aligned nodes of A (32 << l points); B's shifted range is covered by at most two aligned
// nodes of the same level, so every bound is two or three reads from small arrays that stay in
// cache. Candidates within vtol of the running best are appended, as in search().
// Nodes of A at one level that may hold a maximiser for any offset of a batch [begin, end) of
// consecutive lattice offsets (see build_frontier): the search of each of them starts there
// instead of at the top, so the coarse levels are visited once per batch, not once per offset.
struct Frontier {
  std::size_t begin = 0, end = 0;  // offsets (indices into the offset list) it serves
  std::uint32_t level = 0;
  std::vector<std::size_t> nodes;  // node indices at `level`
};

void search_aligned(const std::vector<double>& va, const std::vector<double>& vb, const detail::AlignedMax& ma,
                    const detail::AlignedMax& mb, const detail::TiltedMax* ta, const detail::TiltedMax* tb,
                    std::ptrdiff_t d, std::size_t i0, std::size_t i1, double vtol, double& best, std::vector<Cand>& out,
                    const Frontier* frontier) {
  if (i0 > i1) return;
  using detail::kBlockShift;
  struct Node {
    std::uint32_t level;
    std::size_t q;  // node index at its level: points [q << (5 + level), (q + 1) << (5 + level))
    double ub;
  };
  // Tilted bound: on [p, r] (inside A's node q and B's node k after the shift) the sum of both
  // nodes' upper lines is linear in i, so its maximum is at p or r. Plus the rounding margin of
  // the evaluation (a few units of the terms' magnitudes, see TiltedMax).
  const bool tilt = ta != nullptr;
  const double margin = tilt ? 8 * std::numeric_limits<double>::epsilon() * (ta->magnitude() + tb->magnitude()) : 0.0;
  auto lines = [&](std::uint32_t level, std::size_t q, std::size_t k, std::size_t p, std::size_t r) {
    const unsigned sh = kBlockShift + level;
    const auto& a = ta->level(level)[q];
    const auto& b = tb->level(level)[k];
    const std::size_t sa = q << sh;
    const std::ptrdiff_t sb = static_cast<std::ptrdiff_t>(k << sh) + d;  // B's node start, in A's indices
    auto at = [&](std::size_t i) {
      return (a.c + a.tau * static_cast<double>(i - sa)) +
             (b.c + b.tau * static_cast<double>(static_cast<std::ptrdiff_t>(i) - sb));
    };
    return std::max(at(p), at(r));
  };
  auto bound = [&](std::uint32_t level, std::size_t q) {
    const unsigned sh = kBlockShift + level;
    const std::size_t lo = std::max(q << sh, i0), hi = std::min(((q + 1) << sh) - 1, i1);
    const auto jlo = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(lo) - d);
    const auto jhi = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(hi) - d);
    const auto& lb = mb.level(level);
    const std::size_t k0 = jlo >> sh, k1 = jhi >> sh;
    const double plain = ma.level(level)[q] + std::max(lb[k0], lb[k1]);
    if (!tilt || plain < best - vtol) return plain;  // the lines only matter where the maxima do not prune
    double t;
    if (k0 == k1) {
      t = lines(level, q, k0, lo, hi);
    } else {  // B's range straddles two nodes: split A's range where B's second node starts
      const auto split = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(k1 << sh) + d);
      t = std::max(lines(level, q, k0, lo, split - 1), lines(level, q, k1, split, hi));
    }
    return std::min(plain, t + margin);
  };
  thread_local std::vector<Node> stack;
  stack.clear();
  if (frontier) {
    // Every node that can hold a maximiser of this offset is below a frontier node.
    const unsigned sh = kBlockShift + frontier->level;
    for (std::size_t q : frontier->nodes) {
      if (((q + 1) << sh) <= i0 || (q << sh) > i1) continue;
      const double u = bound(frontier->level, q);
      if (u >= best - vtol) stack.push_back({frontier->level, q, u});
    }
    std::sort(stack.begin(), stack.end(), [](const Node& x, const Node& y) { return x.ub < y.ub; });
  } else {
    // Start from the nodes of the level whose size covers [i0, i1] with at most two nodes.
    std::uint32_t top = 0;
    while (top + 1 < std::min(ma.levels(), mb.levels()) &&
           ((i1 >> (kBlockShift + top)) - (i0 >> (kBlockShift + top))) > 1)
      ++top;
    const unsigned sh = kBlockShift + top;
    const std::size_t q0 = i0 >> sh, q1 = i1 >> sh;
    const double u0 = bound(top, q0);
    if (q1 != q0) {
      const double u1 = bound(top, q1);
      if (u0 >= u1) {
        stack.push_back({top, q1, u1});
        stack.push_back({top, q0, u0});
      } else {
        stack.push_back({top, q0, u0});
        stack.push_back({top, q1, u1});
      }
    } else {
      stack.push_back({top, q0, u0});
    }
  }
  while (!stack.empty()) {
    const Node node = stack.back();
    stack.pop_back();
    if (node.ub < best - vtol) continue;
    if (node.level == 0) {
      const std::size_t lo = std::max(node.q << kBlockShift, i0);
      const std::size_t hi = std::min(((node.q + 1) << kBlockShift) - 1, i1);
      const double* a = va.data();
      const double* b = vb.data() - d;
      double m = -kInf;
      for (std::size_t i = lo; i <= hi; ++i) m = std::max(m, a[i] + b[i]);
      if (m < best - vtol) continue;
      const double cut = std::max(best, m) - vtol;
      for (std::size_t i = lo; i <= hi; ++i) {
        const double val = a[i] + b[i];
        if (val >= cut) out.push_back({val, i, true});
      }
      if (m > best) best = m;
      continue;
    }
    const std::uint32_t l = node.level - 1;
    const unsigned sh = kBlockShift + l;
    const std::size_t qa = 2 * node.q, qb = 2 * node.q + 1;
    const bool has_a = ((qa + 1) << sh) > i0 && (qa << sh) <= i1;
    const bool has_b = ((qb + 1) << sh) > i0 && (qb << sh) <= i1;
    const double ua = has_a ? bound(l, qa) : -kInf, ub2 = has_b ? bound(l, qb) : -kInf;
    if (ua >= ub2) {
      if (has_b && ub2 >= best - vtol) stack.push_back({l, qb, ub2});
      if (has_a && ua >= best - vtol) stack.push_back({l, qa, ua});
    } else {
      if (has_a && ua >= best - vtol) stack.push_back({l, qa, ua});
      if (has_b && ub2 >= best - vtol) stack.push_back({l, qb, ub2});
    }
  }
}

// The index search of a non-periodic offset s: F's candidate range [f0, f1] and the index shift
// d (F vertex i faces G vertex i - d). False when s is off the lattice or the range leaves G's
// indices; evaluate_offset() then takes the general search.
bool index_range(const Problem& P, double s, std::size_t& f0, std::size_t& f1, std::ptrdiff_t& d) {
  if (!P.index_search || P.periodic) return false;
  const Face& F = P.F;
  const Face& G = P.G;
  const double a = std::max(F.x_front(), G.x_front() + s);
  const double b = std::min(F.x_back(), G.x_back() + s);
  if (!(b >= a)) return false;
  f0 = F.ceil_index(a - P.xtol);
  f1 = F.floor_index(b + P.xtol);
  const double k = (s - P.lattice_origin) / P.lattice_step;
  const double lk = std::round(k);
  if (!(std::abs(k - lk) < 1e-9) || f0 > f1) return false;
  d = static_cast<std::ptrdiff_t>(lk);
  const auto jlo = static_cast<std::ptrdiff_t>(f0) - d, jhi = static_cast<std::ptrdiff_t>(f1) - d;
  return jlo >= 0 && jhi < static_cast<std::ptrdiff_t>(G.size());
}

// Frontier for the lattice offsets offs[begin, end) (shortened to those that take the index
// search with the warm contact inside their range). Each offset's maximum is at least the value
// at the warm contact, so a node whose bound over the whole batch (B's range widened by the
// spread of shifts) is below the least of those values, less vtol, holds no maximiser and no
// candidate of any offset of the batch. Returns false if no offset qualifies.
bool build_frontier(const Problem& P, const std::vector<double>& offs, std::size_t begin, std::size_t end,
                    double warm_x, Frontier& fr) {
  using detail::kBlockShift;
  fr.nodes.clear();
  fr.begin = fr.end = 0;
  if (!std::isfinite(warm_x)) return false;
  const Face& F = P.F;
  const Face& G = P.G;
  const Position pw = F.locate(warm_x, 0.0);
  if (!pw.vertex) return false;
  const std::size_t istar = pw.first;
  const auto& va = F.v();
  const auto& vb = G.v();
  std::size_t u0 = std::numeric_limits<std::size_t>::max(), u1 = 0;
  std::ptrdiff_t dmin = std::numeric_limits<std::ptrdiff_t>::max(), dmax = std::numeric_limits<std::ptrdiff_t>::min();
  double T = kInf;
  std::size_t e = begin;
  for (; e < end; ++e) {
    std::size_t f0, f1;
    std::ptrdiff_t d;
    if (!index_range(P, offs[e], f0, f1, d) || istar < f0 || istar > f1) break;
    T = std::min(T, va[istar] + vb[static_cast<std::size_t>(static_cast<std::ptrdiff_t>(istar) - d)]);
    u0 = std::min(u0, f0);
    u1 = std::max(u1, f1);
    dmin = std::min(dmin, d);
    dmax = std::max(dmax, d);
  }
  if (e == begin) return false;
  T -= P.vtol;
  const auto& ma = F.aligned_max();
  const auto& mb = G.aligned_max();
  const auto jmax = static_cast<std::ptrdiff_t>(G.size()) - 1;
  auto bound = [&](std::uint32_t level, std::size_t q) {
    const unsigned sh = kBlockShift + level;
    const std::size_t lo = std::max(q << sh, u0), hi = std::min(((q + 1) << sh) - 1, u1);
    const std::ptrdiff_t j0 = std::max<std::ptrdiff_t>(0, static_cast<std::ptrdiff_t>(lo) - dmax);
    const std::ptrdiff_t j1 = std::min(jmax, static_cast<std::ptrdiff_t>(hi) - dmin);
    if (j0 > j1) return -kInf;
    const auto& lb = mb.level(level);
    double b = -kInf;
    for (auto k = static_cast<std::size_t>(j0) >> sh; k <= (static_cast<std::size_t>(j1) >> sh); ++k)
      b = std::max(b, lb[k]);
    return ma.level(level)[q] + b;
  };
  // The frontier level: nodes at least four times as long as the batch of shifts is wide. Both
  // faces' levels are read (bound() here, search_aligned() from the frontier): at most as many as
  // the shorter face has (an upper block much shorter than the lower one has fewer).
  const std::size_t levels = std::min(ma.levels(), mb.levels());
  std::uint32_t lf = 0;
  const auto spread = static_cast<std::size_t>(dmax - dmin) + 1;
  while (lf + 1 < levels && (std::size_t{kBlock} << lf) < 4 * spread) ++lf;
  std::uint32_t top = lf;
  while (top + 1 < levels && ((u1 >> (kBlockShift + top)) - (u0 >> (kBlockShift + top))) > 1) ++top;
  struct Node {
    std::uint32_t level;
    std::size_t q;
  };
  std::vector<Node> stack;
  for (std::size_t q = u0 >> (kBlockShift + top); q <= (u1 >> (kBlockShift + top)); ++q) stack.push_back({top, q});
  while (!stack.empty()) {
    const Node nd = stack.back();
    stack.pop_back();
    if (bound(nd.level, nd.q) < T) continue;
    if (nd.level == lf) {
      fr.nodes.push_back(nd.q);
      continue;
    }
    const unsigned sh = kBlockShift + nd.level - 1;
    for (std::size_t c : {2 * nd.q + 1, 2 * nd.q})
      if (((c + 1) << sh) > u0 && (c << sh) <= u1) stack.push_back({nd.level - 1, c});
  }
  fr.level = lf;
  fr.begin = begin;
  fr.end = e;
  return true;
}

// The general search's counterpart of Frontier, for a batch offs[begin, end) of consecutive
// offsets (any offsets, any grids): the index ranges of F (aligned nodes of one level) that can
// hold a candidate of the search over F's vertices for some offset of the batch, and the same
// for G. Each offset's maximum is at least its value at the warm contact, so a range whose
// bound over the whole batch (the other face's range widened by the spread of offsets) is below
// the least of those values, less vtol, holds no candidate of any offset of the batch.
struct GeneralFrontier {
  std::size_t begin = 0, end = 0;
  IndexRanges f, g;
};

// F's and G's candidate index ranges of offset s and the overlap [a, b] in the lower frame, as
// evaluate_offset() takes them; false where the blocks do not overlap.
bool offset_ranges(const Problem& P, double s, std::size_t& f0, std::size_t& f1, std::size_t& g0, std::size_t& g1,
                   double& a, double& b) {
  const Face& F = P.F;
  const Face& G = P.G;
  if (P.periodic) {
    f0 = P.f_lo;
    f1 = P.f_hi;
    g0 = P.g_lo;
    g1 = P.g_hi;
    a = F.x()[f0];
    b = a + P.period;
    return true;
  }
  a = std::max(F.x_front(), G.x_front() + s);
  b = std::min(F.x_back(), G.x_back() + s);
  if (!(b >= a)) return false;
  f0 = F.ceil_index(a - P.xtol);
  f1 = F.floor_index(b + P.xtol);
  g0 = G.ceil_index(a - s - P.xtol);
  g1 = G.floor_index(b - s + P.xtol);
  return true;
}

// Ranges of A's aligned nodes at one level, inside [u0, u1], whose bound for every shift in
// [shift_lo, shift_hi] can reach T (A's vertices against B moved by the shift).
void frontier_ranges(const Face& A, const Face& B, double shift_lo, double shift_hi, std::size_t u0, std::size_t u1,
                     double T, IndexRanges& out) {
  using detail::kBlockShift;
  out.clear();
  if (u0 > u1) return;
  const auto& xa = A.x();
  const std::size_t n = A.size();
  // The level: nodes at least four times as long (in x) as the batch of shifts is wide.
  const double dx = n > 1 ? (A.x_back() - A.x_front()) / static_cast<double>(n - 1) : 0.0;
  const std::size_t levels = A.aligned_max().levels();
  std::uint32_t lf = 0;
  while (lf + 1 < levels && static_cast<double>(std::size_t{kBlock} << lf) * dx < 4 * (shift_hi - shift_lo)) ++lf;
  std::uint32_t top = lf;
  while (top + 1 < levels && ((u1 >> (kBlockShift + top)) - (u0 >> (kBlockShift + top))) > 1) ++top;
  auto range = [&](std::uint32_t level, std::size_t q) {
    const unsigned sh = kBlockShift + level;
    return std::make_pair(std::max(q << sh, u0), std::min(((q + 1) << sh) - 1, u1));
  };
  struct Node {
    std::uint32_t level;
    std::size_t q;
  };
  thread_local std::vector<Node> stack;
  stack.clear();
  for (std::size_t q = u0 >> (kBlockShift + top); q <= (u1 >> (kBlockShift + top)); ++q) stack.push_back({top, q});
  while (!stack.empty()) {
    const Node nd = stack.back();
    stack.pop_back();
    const auto [lo, hi] = range(nd.level, nd.q);
    if (lo > hi) continue;
    if (A.range_max(lo, hi) + B.range_max_x(xa[lo] + shift_lo, xa[hi] + shift_hi) < T) continue;
    if (nd.level == lf) {
      out.push_back({lo, hi});
      continue;
    }
    stack.push_back({nd.level - 1, 2 * nd.q + 1});
    stack.push_back({nd.level - 1, 2 * nd.q});
  }
}

// Builds `fr` for offs[begin, end) (shortened to the offsets whose overlap holds the warm
// contact); false if no offset qualifies.
bool build_general_frontier(const Problem& P, const std::vector<double>& offs, std::size_t begin, std::size_t end,
                            double warm_x, GeneralFrontier& fr) {
  fr.begin = fr.end = 0;
  if (!std::isfinite(warm_x)) return false;
  const Face& F = P.F;
  const Face& G = P.G;
  std::size_t uf0 = std::numeric_limits<std::size_t>::max(), uf1 = 0;
  std::size_t ug0 = std::numeric_limits<std::size_t>::max(), ug1 = 0;
  double smin = kInf, smax = -kInf, T = kInf;
  const double fw = F.value(warm_x, P.xtol);
  std::size_t e = begin;
  for (; e < end; ++e) {
    std::size_t f0, f1, g0, g1;
    double a, b;
    const double s = offs[e];
    if (!offset_ranges(P, s, f0, f1, g0, g1, a, b) || !(warm_x >= a && warm_x <= b)) break;
    T = std::min(T, fw + G.value(warm_x - s, P.xtol));
    uf0 = std::min(uf0, f0);
    uf1 = std::max(uf1, f1);
    ug0 = std::min(ug0, g0);
    ug1 = std::max(ug1, g1);
    smin = std::min(smin, s);
    smax = std::max(smax, s);
  }
  if (e == begin || !std::isfinite(T)) return false;
  T -= P.vtol;
  frontier_ranges(F, G, -smax, -smin, uf0, uf1, T, fr.f);
  frontier_ranges(G, F, smin, smax, ug0, ug1, T, fr.g);
  fr.begin = begin;
  fr.end = e;
  return true;
}

struct OffsetResult {
  double lift = kNaN, theta = kNaN, theta_min = kNaN, theta_left = kNaN, theta_right = kNaN;
  double contact_x = kNaN;  // for the warm start
};

// Mean of the available angles (NaN ignored).
double mean_angle(double a, double b) {
  if (std::isnan(a)) return b;
  if (std::isnan(b)) return a;
  return 0.5 * (a + b);
}

// Face::edge_angle (an atan2) through a small memo kept by a walk over offsets (OffsetSweep) for
// the faces of its Problem: consecutive offsets mostly touch the same vertex of one face (its
// neighbouring edges' angles again). The same values, fewer atan2 (about 3 % of a signature).
class AngleMemo {
 public:
  /// The angle of edge e of face A, which is the Problem's F (which = 0) or G (which = 1).
  double operator()(int which, const Face& A, std::ptrdiff_t e) {
    Slot& sl = slots_[which][static_cast<std::size_t>(e) & 7];
    if (sl.face == &A && sl.e == e) return sl.angle;
    sl = Slot{&A, e, A.edge_angle(e)};
    return sl.angle;
  }

 private:
  struct Slot {
    const Face* face = nullptr;
    std::ptrdiff_t e = -1;
    double angle = 0;
  };
  Slot slots_[2][8];
};

// Evaluates one offset: lift, contacts and slopes. `warm_x` is a lower-frame abscissa that was
// a contact nearby (NaN if none); it only speeds up the search.
OffsetResult evaluate_offset(const Problem& P, double s, double warm_x, SlopeMethod method,
                             std::vector<Contact>* contacts, std::vector<Cand>& cands,
                             const Frontier* frontier = nullptr, const GeneralFrontier* general = nullptr,
                             AngleMemo* memo = nullptr) {
  const Face& F = P.F;
  const Face& G = P.G;
  auto angle = [&](const Face& A, std::ptrdiff_t e) {
    return memo ? (*memo)(&A == &G ? 1 : 0, A, e) : A.edge_angle(e);
  };
  cands.clear();
  std::size_t f0, f1, g0, g1;
  double a, b;  // overlap in the lower frame
  if (!offset_ranges(P, s, f0, f1, g0, g1, a, b)) return OffsetResult{};
  double best = -kInf;
  if (std::isfinite(warm_x) && warm_x >= a && warm_x <= b) best = F.value(warm_x, P.xtol) + G.value(warm_x - s, P.xtol);
  bool skip_g = false;
  double lattice_k = 0;
  if (P.aligned_lattice) {
    const double k = (s - P.lattice_origin) / P.lattice_step;
    lattice_k = std::round(k);
    skip_g = std::abs(k - lattice_k) < 1e-9;  // every G vertex sits on an F vertex
  }
  if (skip_g && P.index_search && f0 <= f1) {
    // F vertex i faces G vertex i - d; [f0, f1] maps into G's index range.
    const auto d = static_cast<std::ptrdiff_t>(lattice_k);
    const auto jlo = static_cast<std::ptrdiff_t>(f0) - d, jhi = static_cast<std::ptrdiff_t>(f1) - d;
    if (jlo >= 0 && jhi < static_cast<std::ptrdiff_t>(G.size()))
      search_aligned(F.v(), G.v(), F.aligned_max(), G.aligned_max(), P.tilted ? &F.tilted_max() : nullptr,
                     P.tilted ? &G.tilted_max() : nullptr, d, f0, f1, P.vtol, best, cands, frontier);
    else
      search(F, G, -s, f0, f1, true, P.xtol, P.vtol, best, cands, general ? &general->f : nullptr,
             P.general_tilted ? &P.tilt_fg : nullptr);
  } else {
    search(F, G, -s, f0, f1, true, P.xtol, P.vtol, best, cands, general ? &general->f : nullptr,
           P.general_tilted ? &P.tilt_fg : nullptr);
  }
  if (!skip_g)
    search(G, F, s, g0, g1, false, P.xtol, P.vtol, best, cands, general ? &general->g : nullptr,
           P.general_tilted ? &P.tilt_gf : nullptr);

  OffsetResult r;
  r.lift = best;
  // Contacts: candidates within tolerance of the maximum, classified by the paper's rules.
  struct Act {
    double x;            // lower-frame abscissa
    Position pf, pg;     // positions on F and on G
    double slope;        // by the contact rule
    double left, right;  // one-sided slopes of this candidate's continuation (NaN: drops)
    ContactType type;
  };
  thread_local std::vector<Act> act;  // kept between offsets: no allocation per offset
  act.clear();
  for (const Cand& c : cands) {
    if (c.value < best - P.vtol) continue;
    Act t{};
    if (c.family_f) {
      t.x = F.x()[c.index];
      t.pf = F.locate(t.x, 0.0);
      t.pg = G.locate(t.x - s, P.xtol);
    } else {
      const double u = G.x()[c.index];
      t.x = u + s;
      t.pg = G.locate(u, 0.0);
      t.pf = F.locate(t.x, P.xtol);
    }
    // Vertex-vertex: the edge angles on both sides of both vertex groups, each computed once
    // (atan2 is most of the work of a contact; the rule and the continuations below share them).
    const bool vv = t.pf.vertex && t.pg.vertex;
    const double f_before = vv ? angle(F, static_cast<std::ptrdiff_t>(t.pf.first) - 1) : kNaN;
    const double f_after = vv ? angle(F, static_cast<std::ptrdiff_t>(t.pf.last)) : kNaN;
    const double g_before = vv ? angle(G, static_cast<std::ptrdiff_t>(t.pg.first) - 1) : kNaN;
    const double g_after = vv ? angle(G, static_cast<std::ptrdiff_t>(t.pg.last)) : kNaN;
    if (vv) {
      t.type = ContactType::VertexVertex;
      t.slope = mean_angle(mean_angle(f_before, f_after), mean_angle(g_before, g_after));
    } else if (t.pf.vertex) {
      t.type = ContactType::VertexEdge;
      t.slope = angle(G, static_cast<std::ptrdiff_t>(t.pg.edge));
    } else {
      t.type = ContactType::EdgeVertex;
      t.slope = angle(F, static_cast<std::ptrdiff_t>(t.pf.edge));
    }
    // One-sided continuations: h's slope just after s (right) and just before (left).
    // A vertex of F stays on the F side and slides along G: its value vF - g(x - s) reads g to
    // the left of x - s when s grows. A vertex of G slides along F: f(u + s) - g_u reads f to
    // the right. At a vertex-vertex contact both happen, whichever face found it, and h
    // continues with the larger (right) or smaller (left) slope. An option is invalid if the
    // face it slides on jumps away there or ends (the contact leaves the overlap).
    {
      double right = -kInf, left = kInf;
      auto take = [&](double r, double l) {
        if (!std::isnan(r)) right = std::max(right, r);
        if (!std::isnan(l)) left = std::min(left, l);
      };
      if (t.pf.vertex) {  // F vertex sliding along G
        if (t.pg.vertex) {
          const double gm = G.group_max(t.pg.first, t.pg.last);
          take((G.v()[t.pg.first] >= gm - P.vtol) ? g_before : kNaN,
               (G.v()[t.pg.last] >= gm - P.vtol) ? g_after : kNaN);
        } else {
          take(t.slope, t.slope);  // vertex-edge: the slope of G's edge
        }
      }
      if (t.pg.vertex) {  // G vertex sliding along F
        if (t.pf.vertex) {
          const double fm = F.group_max(t.pf.first, t.pf.last);
          take((F.v()[t.pf.last] >= fm - P.vtol) ? f_after : kNaN,
               (F.v()[t.pf.first] >= fm - P.vtol) ? f_before : kNaN);
        } else {
          take(t.slope, t.slope);  // edge-vertex: the slope of F's edge
        }
      }
      t.right = std::isfinite(right) ? right : kNaN;
      t.left = std::isfinite(left) ? left : kNaN;
    }
    if (method == SlopeMethod::Spline) {
      // Paper Sec. V B: spline slopes of both surfaces at the contact, averaged.
      const double sf = detail::spline_slope(F.x(), P.spline_f, F.sign(), F.v(), t.x);
      const double sg = detail::spline_slope(G.x(), P.spline_g, G.sign(), G.v(), t.x - s);
      t.slope = 0.5 * (std::atan(sf) + std::atan(sg));
      t.left = t.right = t.slope;
    }
    act.push_back(t);
  }
  std::sort(act.begin(), act.end(), [](const Act& p, const Act& q) { return p.x < q.x; });
  // Merge duplicates (a vertex-vertex contact is found from both faces).
  thread_local std::vector<Act> uniq;
  uniq.clear();
  for (const Act& t : act) {
    if (!uniq.empty() && std::abs(uniq.back().x - t.x) <= P.xtol) {
      Act& u = uniq.back();
      // Keep the widest continuation set: a VV seen from both sides carries both options.
      auto mx = [](double p, double q) { return std::isnan(p) ? q : (std::isnan(q) ? p : std::max(p, q)); };
      auto mn = [](double p, double q) { return std::isnan(p) ? q : (std::isnan(q) ? p : std::min(p, q)); };
      u.right = mx(u.right, t.right);
      u.left = mn(u.left, t.left);
      continue;
    }
    uniq.push_back(t);
  }
  double th = -kInf, thmin = kInf, left = kInf, right = -kInf;
  auto add_contact = [&](double x, double slope, ContactType type) {
    th = std::max(th, slope);
    thmin = std::min(thmin, slope);
    if (contacts) contacts->push_back({x, F.value(x), slope, type});
  };
  for (std::size_t k = 0; k < uniq.size(); ++k) {
    const Act& t = uniq[k];
    add_contact(t.x, t.slope, t.type);
    if (!std::isnan(t.left)) left = std::min(left, t.left);
    if (!std::isnan(t.right)) right = std::max(right, t.right);
    // Edge-edge: two consecutive contacts on one edge of F and one edge of G touch all along.
    if (k + 1 < uniq.size() && method == SlopeMethod::Exact) {
      const Act& w = uniq[k + 1];
      auto same_edge = [](const Position& p, const Position& q, std::size_t& e) {
        std::size_t e1 = p.vertex ? p.last : p.edge;
        bool ok_q = q.vertex ? (q.first == e1 + 1) : (q.edge == e1);
        e = e1;
        return ok_q && !(p.vertex && q.vertex && q.first != p.last + 1);
      };
      std::size_t ef, eg;
      if (w.x > t.x + P.xtol && same_edge(t.pf, w.pf, ef) && same_edge(t.pg, w.pg, eg))
        add_contact(0.5 * (t.x + w.x), angle(F, static_cast<std::ptrdiff_t>(ef)), ContactType::EdgeEdge);
    }
  }
  r.theta = th;
  r.theta_min = thmin;
  // No valid continuation: h jumps there, a vertical wall blocks motion from that side.
  r.theta_left = std::isfinite(left) ? left : kHalfPi;
  r.theta_right = std::isfinite(right) ? right : -kHalfPi;
  r.contact_x = uniq.empty() ? kNaN : uniq.front().x;
  return r;
}

// One period of a periodic profile tiled three times (the middle one is the candidate range),
// so that every candidate vertex has both neighbours and evaluation never wraps.
Profile tile3(const Profile& p, double P, std::size_t& lo, std::size_t& hi, double xtol) {
  const double x0 = p.x.front();
  std::vector<double> px, pz;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.x[i] >= x0 + P - xtol) break;
    px.push_back(p.x[i]);
    pz.push_back(p.z[i]);
  }
  Profile t;
  for (int k = -1; k <= 1; ++k) {
    for (std::size_t i = 0; i < px.size(); ++i) {
      t.x.push_back(px[i] + k * P);
      t.z.push_back(pz[i]);
    }
  }
  t.x.push_back(x0 + 2 * P);
  t.z.push_back(pz.front());
  lo = px.size();
  hi = 2 * px.size() - 1;
  return t;
}

// f() and g() side by side when `threads` allows two (the two faces' preparations: a tenth of a
// 10^7-point signature's wall time when one waited for the other), else one after the other.
template <class F, class G>
void both(unsigned threads, F&& f, G&& g) {
  if (util::thread_count(threads, 2) >= 2)
    util::run_workers(
        1, [&](unsigned) { g(); }, [&] { f(); });
  else {
    f();
    g();
  }
}

// Prepares the faces and tolerances of `lower` against `upper`, whose abscissae are moved by
// `shift` into the lower frame (x + shift, rounded as such), without copying either profile.
// Shared by signature() and the rigid evaluator of spheropolygon signatures.
// With `take_lower` / `take_upper` (the same objects as lower / upper), their x and z move into
// the faces instead of being copied, and the profiles are left empty.
Status prepare_problem(Problem& P, const Profile& lower, const Profile& upper, double shift, const SignatureOptions& o,
                       Profile* take_lower = nullptr, Profile* take_upper = nullptr) {
  P.lower_length = lower.length();
  P.upper_length = (upper.x.back() + shift) - (upper.x.front() + shift);
  const double Lmax = std::max(P.lower_length, P.upper_length);
  double zr = 0;
  {
    auto [a1, b1] = std::minmax_element(lower.z.begin(), lower.z.end());
    auto [a2, b2] = std::minmax_element(upper.z.begin(), upper.z.end());
    zr = (*b1 - *a1) + (*b2 - *a2);
  }
  const double xscale = std::max({Lmax, std::abs(lower.x.front()), std::abs(lower.x.back())});
  P.xtol = 1e-12 * xscale;
  P.vtol = o.tolerance * std::max(zr, 1e-9 * Lmax);
  P.periodic = lower.period && upper.period && std::abs(*lower.period - *upper.period) <= 1e-9 * *lower.period;
  if (P.periodic) {
    P.period = *lower.period;
    Profile shifted = upper;
    for (auto& v : shifted.x) v += shift;
    Profile tf = tile3(lower, P.period, P.f_lo, P.f_hi, P.xtol);
    Profile tg = tile3(shifted, P.period, P.g_lo, P.g_hi, P.xtol);
    P.F = Face(std::move(tf.x), tf.z, +1.0);
    P.G = Face(std::move(tg.x), tg.z, -1.0);
  } else {
    auto make_f = [&] {
      if (take_lower)
        P.F = Face(std::move(take_lower->x), std::move(take_lower->z), +1.0);
      else
        P.F = Face(lower.x, lower.z, +1.0);
    };
    auto make_g = [&] {
      std::vector<double> gx = take_upper ? std::move(take_upper->x) : upper.x;
      for (auto& v : gx) v += shift;
      if (take_upper)
        P.G = Face(std::move(gx), std::move(take_upper->z), -1.0);
      else
        P.G = Face(std::move(gx), upper.z, -1.0);
    };
    both(o.threads, make_f, make_g);
  }
  if (o.slopes == SlopeMethod::Spline) {
    auto sf = detail::spline_second_derivatives(P.F.x(), P.F.v());
    auto sg = detail::spline_second_derivatives(P.G.x(), P.G.v());
    if (!sf)
      return make_error(
          "signature: spline slopes need strictly increasing x on the lower surface (it has a "
          "vertical jump or repeated x); use exact slopes");
    if (!sg)
      return make_error(
          "signature: spline slopes need strictly increasing x on the upper surface (it has a "
          "vertical jump or repeated x); use exact slopes");
    P.spline_f = std::move(*sf);
    P.spline_g = std::move(*sg);
  }

  return Ok{};
}

}  // namespace

const char* contact_type_name(ContactType t) {
  switch (t) {
    case ContactType::VertexEdge: return "vertex-edge";
    case ContactType::EdgeVertex: return "edge-vertex";
    case ContactType::VertexVertex: return "vertex-vertex";
    case ContactType::EdgeEdge: return "edge-edge";
  }
  return "?";
}

double lift_direct(const Profile& lower, const Profile& upper, double s) {
  double best = -kInf;
  const bool per = lower.period && upper.period;
  if (per) {
    const double P = *lower.period, x0 = lower.x.front(), y0 = upper.x.front();
    for (std::size_t i = 0; i < lower.size() && lower.x[i] < x0 + P; ++i)
      best = std::max(best, lower.z[i] - evaluate(upper, lower.x[i] - s, JumpValue::Lower));
    for (std::size_t j = 0; j < upper.size() && upper.x[j] < y0 + P; ++j)
      best = std::max(best, evaluate(lower, upper.x[j] + s, JumpValue::Upper) - upper.z[j]);
    return best;
  }
  const double a = std::max(lower.x.front(), upper.x.front() + s);
  const double b = std::min(lower.x.back(), upper.x.back() + s);
  for (std::size_t i = 0; i < lower.size(); ++i)
    if (lower.x[i] >= a && lower.x[i] <= b)
      best = std::max(best, lower.z[i] - evaluate(upper, lower.x[i] - s, JumpValue::Lower));
  for (std::size_t j = 0; j < upper.size(); ++j) {
    const double x = upper.x[j] + s;
    if (x >= a && x <= b) best = std::max(best, evaluate(lower, x, JumpValue::Upper) - upper.z[j]);
  }
  return best;
}

// ---- Rigid lift at arbitrary offsets (for spheropolygons, signature/sphero.cpp) ----

struct detail::RigidLift::Impl {
  Problem P;
  Profile lower;
};

Result<detail::RigidLift> detail::RigidLift::make(const Profile& lower_in, const Profile& upper_in,
                                                  const SignatureOptions& o) {
  auto impl = std::make_shared<Impl>();
  impl->lower = lower_in;
  const double shift = lower_in.x.front() - upper_in.x.front();
  SignatureOptions exact = o;
  exact.slopes = SlopeMethod::Exact;
  if (auto st = prepare_problem(impl->P, impl->lower, upper_in, shift, exact); !st) return st.error();
  RigidLift r;
  r.impl_ = std::move(impl);
  return r;
}

detail::RigidLift::Point detail::RigidLift::at(double s) const {
  std::vector<Cand> cands;
  std::vector<Contact> contacts;
  const OffsetResult e = evaluate_offset(impl_->P, s, kNaN, SlopeMethod::Exact, &contacts, cands);
  Point p;
  p.lift = e.lift;
  p.left = e.theta_left;
  p.right = e.theta_right;
  p.contact_x = e.contact_x;
  if (!contacts.empty()) p.type = contacts.front().type;
  return p;
}

double detail::RigidLift::lower_height(double x) const { return evaluate(impl_->lower, x, JumpValue::Upper); }

Result<FrictionPrediction> predict_friction(double mu_a, double theta_max, double sigma) {
  if (!std::isfinite(mu_a) || mu_a < 0)
    return make_error(fmt::format("atomic friction coefficient must be a finite number >= 0, got {}", mu_a));
  if (std::isnan(theta_max) || std::isnan(sigma) || sigma < 0)
    return make_error("friction prediction: theta_max and sigma must be numbers (sigma >= 0)");
  FrictionPrediction f;
  f.atomic_friction = mu_a;
  f.atomic_angle = std::atan(mu_a);
  f.theta_max = theta_max;
  // Eq. 6: phi = theta_a + theta; beyond 90 degrees the interface cannot slide at all.
  f.friction_angle = std::min(kHalfPi, f.atomic_angle + theta_max);
  f.friction_coefficient = (f.friction_angle >= kHalfPi) ? kInf : std::tan(f.friction_angle);
  // Eq. 18: theta_max - sigma <= theta <= theta_max. A friction angle below zero is no friction
  // (the block would slide on its own): the low end is reported as 0 and flagged (low_clamped).
  f.friction_angle_low = std::min(kHalfPi, f.atomic_angle + theta_max - sigma);
  f.low_clamped = f.friction_angle_low < 0;
  f.friction_angle_low = std::max(0.0, f.friction_angle_low);
  f.friction_coefficient_low = (f.friction_angle_low >= kHalfPi) ? kInf : std::tan(f.friction_angle_low);
  return f;
}

namespace {

// The offsets that signature() evaluates over [smin, smax]: every event (exact), or a sampled
// grid (options.offsets = N, or more events than max_events). One function for the signature's
// range and for the wider ranges of the hold analysis (signature_with_lift), so that both list
// the same offsets where they overlap.
struct OffsetPlan {
  std::vector<double> offs;
  std::size_t sampled = 0;  // 0: exact
  std::size_t events = 0;   // offsets listed, the skipped ones included
  bool grid_replaced = false;
  // With a lattice range to skip: offs[gap] is the first offset after the skipped lattice
  // offsets, `skipped` of them (0: none skipped).
  std::size_t gap = 0, skipped = 0;
};

// `skip_k0` <= `skip_k1` (exact mode on an aligned lattice): the lattice offsets origin + k step
// with k in [skip_k0, skip_k1] are left out of offs (the caller has them: the wider ranges of the
// hold analysis around the signature's own), the others are listed as without it.
Result<OffsetPlan> plan_offsets(const Problem& P, const SignatureOptions& o, double smin, double smax,
                                double skip_k0 = 1, double skip_k1 = 0) {
  OffsetPlan plan;
  std::vector<double>& offs = plan.offs;
  std::size_t& events = plan.events;
  const auto& fx = P.F.x();
  const auto& gx = P.G.x();
  const double dxf = (fx.back() - fx.front()) / static_cast<double>(fx.size() - 1);
  const double dxg = (gx.back() - gx.front()) / static_cast<double>(gx.size() - 1);
  // Exact mode needs every event offset. Count them first: when there are more than
  // max_events (non-aligned grids of measured data give up to N*M), either refuse
  // (require_exact) or sample offsets at the finer vertex spacing, each still evaluated exactly.
  std::size_t sampled = o.offsets;
  if (o.offsets == 0) {
    double n_events = 0;
    if (P.aligned_lattice) {
      n_events = std::floor((smax - smin) / P.lattice_step) + 2;
    } else if (P.periodic) {
      n_events = double(P.f_hi - P.f_lo + 1) * double(P.g_hi - P.g_lo + 1) * std::ceil((smax - smin) / P.period + 1);
    } else {
      for (std::size_t i = 0; i < fx.size(); ++i) {
        auto lo = std::lower_bound(gx.begin(), gx.end(), fx[i] - smax - P.xtol);
        auto hi = std::upper_bound(gx.begin(), gx.end(), fx[i] - smin + P.xtol);
        n_events += static_cast<double>(hi - lo);
      }
    }
    if (n_events > static_cast<double>(o.max_events)) {
      if (o.require_exact)
        return make_error(fmt::format(
            "signature: the exact signature needs about {:.3g} event offsets (limit {}){}; "
            "sample offsets instead (--offsets N) or shorten the range",
            n_events, o.max_events, P.aligned_lattice || P.periodic ? "" : " because the two grids do not align"));
      const double spacing = std::min(dxf, dxg);
      sampled =
          static_cast<std::size_t>(std::min(static_cast<double>(o.max_events), std::ceil((smax - smin) / spacing) + 1));
      sampled = std::max<std::size_t>(sampled, 2);
    }
  }
  // A requested grid must never cost more than the exact path: on aligned lattices an offset off
  // the lattice takes the general search, measured at about 3.3 times the cost of a lattice event
  // (two 10^7-point WM profiles: 5e6 grid offsets 12.5 s against every one of the 5e6 events in
  // 3.8 s, bench/results/signature.md). A grid of more than a quarter of the events is replaced
  // by every event (exact, and denser).
  bool grid_replaced = false;
  if (o.offsets > 0 && P.aligned_lattice && !o.keep_grid) {
    const double n_events = std::floor((smax - smin) / P.lattice_step) + 2;
    if (static_cast<double>(o.offsets) * 4 >= n_events) {
      sampled = 0;
      grid_replaced = true;
    }
  }
  if (sampled == 0) {
    if (P.aligned_lattice) {
      const double k0 = std::ceil((smin - P.lattice_origin) / P.lattice_step - 1e-9);
      const double k1 = std::floor((smax - P.lattice_origin) / P.lattice_step + 1e-9);
      const bool skip = skip_k0 <= skip_k1 && k0 < skip_k0 && skip_k1 < k1;
      if (k1 >= k0)
        offs.reserve(static_cast<std::size_t>(k1 - k0) + 3 -
                     (skip ? static_cast<std::size_t>(skip_k1 - skip_k0 + 1) : 0));
      for (double k = k0; k <= k1; k += 1) {
        if (skip && k == skip_k0) {
          plan.skipped = static_cast<std::size_t>(skip_k1 - skip_k0 + 1);
          k = skip_k1;
          continue;
        }
        offs.push_back(P.lattice_origin + k * P.lattice_step);
      }
    } else if (P.periodic) {
      std::vector<double> base;
      base.reserve((P.f_hi - P.f_lo + 1) * (P.g_hi - P.g_lo + 1));
      for (std::size_t i = P.f_lo; i <= P.f_hi; ++i)
        for (std::size_t j = P.g_lo; j <= P.g_hi; ++j) {
          double e = std::fmod(fx[i] - gx[j], P.period);
          if (e < 0) e += P.period;
          base.push_back(e);
        }
      const double k0 = std::floor(smin / P.period) - 1, k1 = std::ceil(smax / P.period) + 1;
      for (double k = k0; k <= k1; k += 1)
        for (double e : base) {
          const double v = e + k * P.period;
          if (v >= smin - P.xtol && v <= smax + P.xtol) offs.push_back(std::clamp(v, smin, smax));
        }
    } else {
      for (std::size_t i = 0; i < fx.size(); ++i) {
        auto lo = std::lower_bound(gx.begin(), gx.end(), fx[i] - smax - P.xtol);
        auto hi = std::upper_bound(gx.begin(), gx.end(), fx[i] - smin + P.xtol);
        for (auto it = lo; it != hi; ++it) offs.push_back(std::clamp(fx[i] - *it, smin, smax));
      }
    }
    // The lattice's offsets come out increasing: with the range ends put in place (before an
    // equal value, as a sort may place them; equal values are the same number) no sort is needed.
    bool in_order = P.aligned_lattice && std::is_sorted(offs.begin(), offs.end());
    if (in_order) {
      for (const double e : {smin, smax}) offs.insert(std::lower_bound(offs.begin(), offs.end(), e), e);
    } else {
      offs.push_back(smin);
      offs.push_back(smax);
    }
    // Sorted in chunks on the worker threads, then merged (the same order as one sort: the
    // values are totally ordered; up to 2e7 events of two measured grids that do not align).
    const unsigned st = offs.size() > (std::size_t{1} << 20) ? util::thread_count(o.threads, offs.size() >> 20) : 1;
    if (!in_order && st > 1) {
      std::vector<std::size_t> bounds(st + 1);
      for (unsigned c = 0; c <= st; ++c) bounds[c] = offs.size() * c / st;
      util::parallel_chunks(st, st, [&](unsigned, std::size_t c0, std::size_t c1) {
        for (std::size_t c = c0; c < c1; ++c)
          std::sort(offs.begin() + std::ptrdiff_t(bounds[c]), offs.begin() + std::ptrdiff_t(bounds[c + 1]));
      });
      for (std::size_t width = 1; width < st; width *= 2)
        for (std::size_t c = 0; c + width < st; c += 2 * width)
          std::inplace_merge(offs.begin() + std::ptrdiff_t(bounds[c]), offs.begin() + std::ptrdiff_t(bounds[c + width]),
                             offs.begin() + std::ptrdiff_t(bounds[std::min<std::size_t>(c + 2 * width, st)]));
    } else if (!in_order) {
      std::sort(offs.begin(), offs.end());
    }
    // Drop near-duplicates in place (each kept value compared with the last kept; across a skipped
    // range, lattice offsets more than a step apart, as without it).
    const double after_gap = plan.skipped > 0 ? P.lattice_origin + (skip_k1 + 1) * P.lattice_step : 0.0;
    std::size_t w = 0;
    for (std::size_t r = 0; r < offs.size(); ++r) {
      if (w == 0 || offs[r] > offs[w - 1] + P.xtol) {
        if (plan.skipped > 0 && offs[r] == after_gap) plan.gap = w;
        offs[w++] = offs[r];
      }
    }
    offs.resize(w);
    if (offs.back() < smax) offs.back() = smax;
    events = offs.size() + plan.skipped;
  } else {
    const std::size_t n = std::max<std::size_t>(sampled, 2);
    offs.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      offs[i] = (i + 1 == n) ? smax : smin + (smax - smin) * static_cast<double>(i) / static_cast<double>(n - 1);
  }

  plan.sampled = sampled;
  plan.grid_replaced = grid_replaced;
  return plan;
}

// One thread's walk over increasing offsets as signature() makes it: the contact search warm
// started from the last offset's contact, through batch frontiers of kBatch offsets (up to `end`).
struct OffsetSweep {
  static constexpr std::size_t kBatch = 64;  // offsets per frontier
  std::vector<Cand> cands;
  double warm = kNaN;
  Frontier frontier;
  GeneralFrontier general;
  AngleMemo angles;  // for one Problem's faces (a sweep serves one Problem)

  /// evaluate_offset at offs[i] (its contacts appended to `contacts` if not null).
  OffsetResult next(const Problem& P, const std::vector<double>& offs, std::size_t i, std::size_t end,
                    SlopeMethod slopes, std::vector<Contact>* contacts = nullptr) {
    if (P.index_search && !(i >= frontier.begin && i < frontier.end))
      build_frontier(P, offs, i, std::min(i + kBatch, end), warm, frontier);
    const Frontier* fr = (i >= frontier.begin && i < frontier.end) ? &frontier : nullptr;
    // Offsets that take the general search (off the lattice, or grids that do not align).
    if (!fr && !(i >= general.begin && i < general.end))
      build_general_frontier(P, offs, i, std::min(i + kBatch, end), warm, general);
    const GeneralFrontier* gf = (!fr && i >= general.begin && i < general.end) ? &general : nullptr;
    const OffsetResult e = evaluate_offset(P, offs[i], warm, slopes, contacts, cands, fr, gf, &angles);
    warm = e.contact_x;
    return e;
  }
  /// next(), the lift and slopes stored in out[i].
  OffsetResult at(const Problem& P, const std::vector<double>& offs, std::size_t i, std::size_t end, SlopeMethod slopes,
                  detail::LiftPoints& out) {
    const OffsetResult e = next(P, offs, i, end, slopes);
    out.lift[i] = e.lift;
    out.left[i] = e.theta_left;
    out.right[i] = e.theta_right;
    return e;
  }
};

// The offsets [begin, end) of a list cut into contiguous chunks that the threads take in turn as
// they come free: shorter towards the end (below), one chunk on one thread. An offset's cost
// varies along a range (the overlap's length, how far the warm start carries), so equal shares,
// one a thread, left a thread idle for a tenth of the run. Every offset's result is the same
// however the list is cut (the warm start only speeds up the search).
class OffsetChunks {
 public:
  OffsetChunks(std::size_t begin, std::size_t end, unsigned threads) {
    const std::size_t n = end > begin ? end - begin : 0;
    threads_ = util::thread_count(threads, std::max<std::size_t>(1, n / 64));
    bounds_.push_back(begin);
    if (threads_ == 1 || n == 0) {
      bounds_.push_back(end);
      return;
    }
    // Guided: each chunk a (2 threads)-th of what is left, at least 4096 offsets (and at least
    // n / (8 threads) while that is smaller, so that a short list still spreads over the threads):
    // the first chunks long, the last ones short, so that the threads finish within a short
    // chunk of each other (equal chunks, eight a thread, left one thread idle for about half a
    // chunk at the end: a tenth of a second of a 10^7-point signature).
    const std::size_t least = std::max<std::size_t>(1, std::min<std::size_t>(4096, n / (8 * std::size_t{threads_})));
    for (std::size_t pos = begin; pos < end;) {
      pos = std::min(end, pos + std::max(least, (end - pos) / (2 * std::size_t{threads_})));
      bounds_.push_back(pos);
    }
  }
  std::size_t count() const { return bounds_.size() - 1; }
  /// Moves each inner cut, in order: cut c becomes move(max(cut c - 1 as moved, cut c)), which
  /// must lie in [that, end].
  template <class Move>
  void move_cuts(Move&& move) {
    for (std::size_t c = 1; c + 1 < bounds_.size(); ++c) bounds_[c] = move(std::max(bounds_[c - 1], bounds_[c]));
  }
  /// body(chunk, begin, end) for each chunk, on up to `threads` threads.
  template <class Body>
  void run(Body&& body) const {
    std::atomic<std::size_t> next{0};
    const std::size_t chunks = count();
    util::parallel_chunks(threads_, threads_, [&](unsigned, std::size_t, std::size_t) {
      for (std::size_t c; (c = next.fetch_add(1)) < chunks;) body(c, bounds_[c], bounds_[c + 1]);
    });
  }

 private:
  unsigned threads_ = 1;
  std::vector<std::size_t> bounds_;
};

// The lift and its one-sided slopes at `offsets` (increasing; taken over as out.offset), as
// signature() evaluates them (the same search, warm starts and frontiers per chunk; contacts not
// kept). False where the blocks do not overlap at some offset.
bool evaluate_lift(const Problem& P, std::vector<double>&& offsets, const SignatureOptions& o,
                   detail::LiftPoints& out) {
  out.offset = std::move(offsets);
  const std::vector<double>& offs = out.offset;
  const std::size_t n = offs.size();
  out.lift.resize(n);
  out.left.resize(n);
  out.right.resize(n);
  OffsetChunks(0, n, o.threads).run([&](std::size_t, std::size_t i0, std::size_t i1) {
    OffsetSweep sweep;
    for (std::size_t i = i0; i < i1; ++i) sweep.at(P, offs, i, i1, o.slopes, out);
  });
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(out.lift[i])) return false;
  return true;
}

// The steepest and the least steep lift slope (sign * dv / dx of an edge of either face next to a
// candidate contact) over the lattice offsets offs[fr.begin, fr.end), from the frontier's nodes:
// every candidate within vtol of an offset's maximum lies in them (F vertex i against G vertex
// i - d), and between two lattice offsets the lift's slope lies between the right slope at the
// first and the left slope at the second, each the slope of an edge next to one of their contacts.
// False where a node reaches an overlap end of some offset (a contact there may have no
// continuation: the lift may jump) or an offset leaves the index search.
// Stops (false) as soon as the slopes exceed both limits (fwd_limit for smax, bwd_limit for -smin).
bool block_slopes(const Problem& P, const std::vector<double>& offs, const Frontier& fr, double fwd_limit,
                  double bwd_limit, double& smax, double& smin) {
  std::size_t u0 = std::numeric_limits<std::size_t>::max(), u1 = 0, f0max = 0;
  std::size_t f1min = std::numeric_limits<std::size_t>::max();
  std::ptrdiff_t dmin = std::numeric_limits<std::ptrdiff_t>::max(), dmax = std::numeric_limits<std::ptrdiff_t>::min();
  for (std::size_t e = fr.begin; e < fr.end; ++e) {
    std::size_t f0, f1;
    std::ptrdiff_t d;
    if (!index_range(P, offs[e], f0, f1, d)) return false;
    u0 = std::min(u0, f0);
    u1 = std::max(u1, f1);
    f0max = std::max(f0max, f0);
    f1min = std::min(f1min, f1);
    dmin = std::min(dmin, d);
    dmax = std::max(dmax, d);
  }
  const Face& F = P.F;
  const Face& G = P.G;
  const auto nf = static_cast<std::ptrdiff_t>(F.size()), ng = static_cast<std::ptrdiff_t>(G.size());
  smax = -kInf;
  smin = kInf;
  auto edges = [&](const Face& A, std::ptrdiff_t na, std::ptrdiff_t e0, std::ptrdiff_t e1) {
    if (e0 < 0 || e1 + 1 >= na) return false;
    const auto& v = A.v();
    const auto& x = A.x();
    const double sg = A.sign();
    for (auto e = static_cast<std::size_t>(e0); e <= static_cast<std::size_t>(e1); ++e) {
      const double m = sg * (v[e + 1] - v[e]) / (x[e + 1] - x[e]);
      smax = std::max(smax, m);
      smin = std::min(smin, m);
    }
    return true;
  };
  const unsigned sh = detail::kBlockShift + fr.level;
  for (const std::size_t q : fr.nodes) {
    const std::size_t lo = std::max(q << sh, u0), hi = std::min(((q + 1) << sh) - 1, u1);
    if (lo > hi) continue;
    if (lo <= f0max || hi >= f1min) return false;
    const auto l = static_cast<std::ptrdiff_t>(lo), h = static_cast<std::ptrdiff_t>(hi);
    if (!edges(F, nf, l - 1, h) || !edges(G, ng, l - dmax - 1, h - dmin)) return false;
    if (smax > fwd_limit && -smin > bwd_limit) return false;
  }
  return std::isfinite(smax) && std::isfinite(smin);
}

// evaluate_lift() of `todo` (increasing) with a LiftPruneRequest (see rigid.hpp), in place (the
// arrays evaluate_lift() would write, the left-out offsets squeezed out at the end): the offsets
// inside the inner range first, then the others, where a block that cannot matter is evaluated
// at its ends only. The decision for a block depends on its first end's contact alone (the batch
// frontier of the block from it), and the threads' chunks start at block starts, so the points
// do not depend on the threads.
bool evaluate_lift_pruned(const Problem& P, std::vector<double>&& todo, const SignatureOptions& o,
                          const detail::LiftPruneRequest& req, const std::vector<std::size_t>& dropped,
                          detail::LiftExtension& ext) {
  detail::LiftPoints& out = ext.points;
  out.offset = std::move(todo);
  const std::vector<double>& offs = out.offset;
  const std::size_t n = offs.size();
  out.lift.resize(n);
  out.left.resize(n);
  out.right.resize(n);
  const auto i_in0 = static_cast<std::size_t>(std::lower_bound(offs.begin(), offs.end(), req.inner_lo) - offs.begin());
  const auto i_in1 = std::max(
      i_in0, static_cast<std::size_t>(std::upper_bound(offs.begin(), offs.end(), req.inner_hi) - offs.begin()));
  std::vector<std::uint8_t> mark(n, 0);  // 1: a block start, 2: left out
  detail::LiftPrune pr;
  // Evaluates [r0, r1) on the threads, in chunks none of which starts inside a block (a block
  // start and its 63 offsets are in one chunk; its other end may open the next). Eight chunks a
  // thread, taken in turn by the threads as they come free: the offsets' costs differ along the
  // range (the overlap's length, the pruned blocks), so equal shares would leave a thread idle.
  // Every offset's result is the same however the range is cut (signature()'s rule).
  auto run = [&](std::size_t r0, std::size_t r1) {
    if (r1 <= r0) return;
    OffsetChunks chunks(r0, r1, o.threads);
    chunks.move_cuts([&](std::size_t t) {
      for (std::size_t u = t > r0 + 63 ? t - 63 : r0; u < t; ++u)
        if (mark[u] == 1) return std::min(r1, u + 64);  // t inside the block from u: its other end
      return t;
    });
    chunks.run([&](std::size_t, std::size_t i0, std::size_t i1) {
      OffsetSweep sweep;
      Frontier block;
      for (std::size_t i = i0; i < i1; ++i) {
        const OffsetResult e = sweep.at(P, offs, i, i1, o.slopes, out);
        if (mark[i] != 1 || !std::isfinite(e.lift)) continue;
        if (!build_frontier(P, offs, i, i + 65, sweep.warm, block) || block.end != i + 65) continue;
        double smax, smin;
        const double fwd_limit = offs[i] >= pr.fwd_from ? pr.fwd_max : -kInf;
        const double bwd_limit = offs[i + 64] <= pr.bwd_to ? pr.bwd_max : -kInf;
        if (!block_slopes(P, offs, block, fwd_limit, bwd_limit, smax, smin)) continue;
        // Margins: the chord between the two ends is computed from their rounded lifts, the
        // bound from rounded edge slopes (relative rounding, and an absolute term for the lifts).
        const double gap = offs[i + 64] - offs[i];
        const double err = 1e-14 * (std::abs(e.lift) + std::max(std::abs(smax), std::abs(smin)) * gap) / gap;
        const bool fwd = offs[i] >= pr.fwd_from && smax + 1e-12 * std::abs(smax) + err <= pr.fwd_max;
        const bool bwd = offs[i + 64] <= pr.bwd_to && -smin + 1e-12 * std::abs(smin) + err <= pr.bwd_max;
        if (!fwd && !bwd) continue;
        out.right[i] = kNaN;  // the curve joins it to offs[i + 64] by a chord
        for (std::size_t t = i + 1; t < i + 64; ++t) mark[t] = 2;
        i += 63;
        sweep.frontier = Frontier{};
      }
    });
  };
  run(i_in0, i_in1);
  for (std::size_t i = i_in0; i < i_in1; ++i)
    if (!std::isfinite(out.lift[i])) return false;
  pr = req.decide(offs.data() + i_in0, out.lift.data() + i_in0, i_in1 - i_in0, dropped);
  // Block starts: 65 consecutive lattice offsets k0 .. k0 + 64 from entry t, k0 a multiple of
  // 64, on one side of the inner range and all in one stretch.
  auto lattice_k = [&](double s, double& k) {
    const double kk = (s - P.lattice_origin) / P.lattice_step;
    k = std::round(kk);
    return std::abs(kk - k) < 1e-9;
  };
  for (std::size_t t = 0; t + 64 < n; ++t) {
    if (t + 64 >= i_in0 && t < i_in1) continue;
    double k0, k1;
    if (!lattice_k(offs[t], k0) || std::fmod(k0, 64.0) != 0) continue;
    if (!lattice_k(offs[t + 64], k1) || k1 - k0 != 64) continue;
    if (offs[t] >= pr.fwd_from || offs[t + 64] <= pr.bwd_to) mark[t] = 1;
  }
  run(0, i_in0);
  run(i_in1, n);
  for (std::size_t i = 0; i < n; ++i)
    if (mark[i] != 2 && !std::isfinite(out.lift[i])) return false;
  // Squeeze the left-out offsets out (in place; the arrays keep their capacity).
  std::size_t w = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (mark[i] == 2) {
      ext.skipped.push_back(offs[i]);
      continue;
    }
    out.offset[w] = out.offset[i];
    out.lift[w] = out.lift[i];
    out.left[w] = out.left[i];
    out.right[w] = out.right[i];
    ++w;
  }
  out.offset.resize(w);
  out.lift.resize(w);
  out.left.resize(w);
  out.right.resize(w);
  return true;
}

// What signature() derives from the lift after the search (and after the hold analysis, which
// runs while the faces are still at hand: beside it this took 15-50 MB more at the H = 0.3 pair's
// peak for no wall time measurable on 2 cores): the extremes of theta and the contact-slope
// distribution.
void signature_tail(SignatureResult& R, const SignatureOptions& o) {
  const std::size_t n = R.offset.size();
  // Extremes: theta at each offset plus the one-sided slopes next to it (inside the range).
  R.theta_max_forward = -kInf;
  R.theta_max_backward = -kInf;
  for (std::size_t i = 0; i < n; ++i) {
    double hi = R.theta[i], lo = R.theta_min[i];
    if (i > 0) {
      hi = std::max(hi, R.theta_left[i]);
      lo = std::min(lo, R.theta_left[i]);
    }
    if (i + 1 < n) {
      hi = std::max(hi, R.theta_right[i]);
      lo = std::min(lo, R.theta_right[i]);
    }
    if (hi > R.theta_max_forward) {
      R.theta_max_forward = hi;
      R.offset_at_forward = R.offset[i];
    }
    if (-lo > R.theta_max_backward) {
      R.theta_max_backward = -lo;
      R.offset_at_backward = R.offset[i];
    }
  }

  // Contact-slope distribution, one value per offset. Exact mode: each interval between
  // events is represented by the slopes of h at its two ends, split at the crossing of the two
  // lines (exact when the interval holds at most two linear pieces). Sampled mode: theta(s).
  if (R.exact && o.slopes == SlopeMethod::Exact) {
    // At most two values per interval: reserved at once (no copy of a half-grown vector; pages
    // are taken only as the values are written).
    R.slope_samples.reserve(2 * n);
    R.slope_weights.reserve(2 * n);
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const double s0 = R.offset[i], s1 = R.offset[i + 1], L = s1 - s0;
      const double a0 = R.theta_right[i], a1 = R.theta_left[i + 1];
      const bool w0 = std::abs(a0) < kHalfPi, w1 = std::abs(a1) < kHalfPi;
      if (!w0 && !w1) continue;
      if (!w1 || (w0 && std::abs(a0 - a1) < 1e-12)) {
        R.slope_samples.push_back(a0);
        R.slope_weights.push_back(L);
        continue;
      }
      if (!w0) {
        R.slope_samples.push_back(a1);
        R.slope_weights.push_back(L);
        continue;
      }
      const double t0 = std::tan(a0), t1 = std::tan(a1);
      double sc = (t0 == t1) ? s1 : (R.lift[i + 1] - R.lift[i] + t0 * s0 - t1 * s1) / (t0 - t1);
      sc = std::clamp(sc, s0, s1);
      R.slope_samples.push_back(a0);
      R.slope_weights.push_back(sc - s0);
      R.slope_samples.push_back(a1);
      R.slope_weights.push_back(s1 - sc);
    }
  } else {
    R.slope_samples.reserve(n);
    R.slope_weights.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      R.slope_samples.push_back(R.theta[i]);
      R.slope_weights.push_back(1.0);
    }
  }
  const MeanStd ms = weighted_mean_std(R.slope_samples, R.slope_weights);
  R.contact_slope_mean = ms.mean;
  R.contact_slope_std = ms.std;
  R.contact_slope_pdf = histogram(R.slope_samples, R.slope_weights, o.bins);
}

Result<SignatureResult> signature_impl(const Profile& lower_in, const Profile& upper_in, const SignatureOptions& o,
                                       Profile* take_lower, Profile* take_upper,
                                       const detail::WithLift* with_lift = nullptr,
                                       const detail::AfterFaces* after_faces = nullptr) {
  if (auto st = validate(lower_in, "lower surface"); !st) return st.error();
  if (auto st = validate(upper_in, "upper surface"); !st) return st.error();
  if (!(o.tolerance > 0 && o.tolerance < 1e-3))
    return make_error(fmt::format("signature: tolerance must be in (0, 1e-3), got {}", o.tolerance));
  if (o.bins < 1 || o.bins > 100000)
    return make_error(fmt::format("signature: bins must be in 1..100000, got {}", o.bins));
  if (o.offsets > 100'000'000) return make_error(fmt::format("signature: offsets must be <= 1e8, got {}", o.offsets));
  if (!(o.spheroradius >= 0) || !std::isfinite(o.spheroradius))
    return make_error(fmt::format("signature: spheroradius must be a finite length >= 0 m, got {}", o.spheroradius));
  if (o.spheroradius > 0) return detail::sphero_signature(lower_in, upper_in, o);

  // Frame: offset 0 puts the upper block's left end over the lower block's left end.
  const double shift = lower_in.x.front() - upper_in.x.front();

  Problem P;
  if (auto st = prepare_problem(P, lower_in, upper_in, shift, o, take_lower, take_upper); !st) return st.error();

  // Offset range.
  double smin = o.offset_min, smax = o.offset_max;
  if (!(smax > smin)) {
    smin = 0;
    smax = P.periodic ? P.period : 0.5 * std::min(P.lower_length, P.upper_length);
  }
  if (!std::isfinite(smin) || !std::isfinite(smax)) return make_error("signature: offset range must be finite");
  if (!P.periodic) {
    if (!(smin > -P.upper_length) || !(smax < P.lower_length))
      return make_error(
          fmt::format("signature: offsets [{}, {}] m leave no overlap between the blocks (allowed: "
                      "inside ({}, {}) m)",
                      smin, smax, -P.upper_length, P.lower_length));
  }

  // Offsets: events (exact) or N equally spaced.
  const auto& fx = P.F.x();
  const auto& gx = P.G.x();
  const bool both_uniform = P.F.uniform() && P.G.uniform();
  const double dxf = (fx.back() - fx.front()) / static_cast<double>(fx.size() - 1);
  const double dxg = (gx.back() - gx.front()) / static_cast<double>(gx.size() - 1);
  if (!P.periodic && both_uniform && std::abs(dxf - dxg) <= 1e-9 * dxf) {
    const double k = (fx.front() - gx.front()) / dxf;
    if (std::abs(k - std::round(k)) < 1e-9) {
      P.aligned_lattice = true;
      P.lattice_origin = fx.front() - gx.front();
      P.lattice_step = dxf;
      // Index search when every point sits on its lattice node far inside xtol, so that at a
      // lattice offset Face::value(x_F[i] - s) is exactly v_G[i - d].
      double dev = 0;
      for (std::size_t i = 0; i < fx.size(); ++i)
        dev = std::max(dev, std::abs(fx[i] - (fx.front() + dxf * static_cast<double>(i))));
      for (std::size_t j = 0; j < gx.size(); ++j)
        dev = std::max(dev, std::abs(gx[j] - (gx.front() + dxf * static_cast<double>(j))));
      if (dev < 0.05 * P.xtol && P.xtol < 0.05 * dxf) {
        P.index_search = true;
        // The few offsets off the lattice (the range ends) bound with the aligned maxima.
        P.F.drop_sparse_table();
        P.G.drop_sparse_table();
        if (o.tilted_bounds) {
          both(
              o.threads, [&] { P.F.build_tilted(); }, [&] { P.G.build_tilted(); });
          P.tilted = true;
        }
      }
    }
  }
  if (o.tilted_bounds && both_uniform) {  // offsets off the lattice too
    if (!P.tilted)
      both(
          o.threads, [&] { P.F.build_tilted(); }, [&] { P.G.build_tilted(); });
    P.tilt_fg = general_tilt(P.F, P.G, P.xtol);
    P.tilt_gf = general_tilt(P.G, P.F, P.xtol);
    P.general_tilted = true;
  }
  auto plan = plan_offsets(P, o, smin, smax);
  if (!plan) return plan.error();
  std::vector<double> offs = std::move(plan->offs);
  const std::size_t events = plan->events, sampled = plan->sampled;
  const bool grid_replaced = plan->grid_replaced;

  // Evaluate, split into contiguous chunks over threads; each chunk warm-starts from its own
  // previous offset, so the result does not depend on the number of threads. Results go straight
  // into R (no per-offset record kept beside it: memory at 10^7 offsets).
  const std::size_t n = offs.size();
  SignatureResult R;
  R.exact = (sampled == 0);
  R.grid_replaced = grid_replaced;
  R.events = events;
  R.offset = std::move(offs);
  R.lift.resize(n);
  R.theta.resize(n);
  R.theta_min.resize(n);
  R.theta_left.resize(n);
  R.theta_right.resize(n);
  // The offsets in chunks taken in turn by the threads as they come free (see OffsetChunks).
  const OffsetChunks chunks(0, n, o.threads);
  const std::size_t C = chunks.count();
  std::vector<std::vector<Contact>> chunk_contacts(C);
  std::vector<std::vector<std::uint32_t>> chunk_counts(C);
  chunks.run([&](std::size_t t, std::size_t i0, std::size_t i1) {
    OffsetSweep sweep;
    if (o.keep_contacts) chunk_counts[t].reserve(i1 - i0);
    for (std::size_t i = i0; i < i1; ++i) {
      const std::size_t before = chunk_contacts[t].size();
      const OffsetResult e = sweep.next(P, R.offset, i, i1, o.slopes, o.keep_contacts ? &chunk_contacts[t] : nullptr);
      R.lift[i] = e.lift;
      R.theta[i] = e.theta;
      R.theta_min[i] = e.theta_min;
      R.theta_left[i] = e.theta_left;
      R.theta_right[i] = e.theta_right;
      if (o.keep_contacts) chunk_counts[t].push_back(static_cast<std::uint32_t>(chunk_contacts[t].size() - before));
    }
  });
  const std::vector<double>& offs_r = R.offset;
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isfinite(R.lift[i]))
      return make_error(fmt::format("signature: no overlap between the blocks at offset {} m", offs_r[i]));
  if (o.keep_contacts) {
    R.contact_begin.reserve(n + 1);
    R.contact_begin.push_back(0);
    for (std::size_t t = 0; t < C; ++t) {
      for (auto c : chunk_counts[t]) R.contact_begin.push_back(R.contact_begin.back() + c);
      R.contacts.insert(R.contacts.end(), chunk_contacts[t].begin(), chunk_contacts[t].end());
    }
  }
  std::vector<std::vector<Contact>>().swap(chunk_contacts);
  std::vector<std::vector<std::uint32_t>>().swap(chunk_counts);
  if (with_lift) {
    // The lift over wider ranges, from the same prepared faces: the offsets that signature()
    // would list there, evaluated where R does not already hold them.
    const detail::LiftExtender extend = [&](double lo, double hi, const std::vector<double>* have,
                                            const detail::LiftPruneRequest* prune) -> Result<detail::LiftExtension> {
      if (P.periodic) return make_error("signature: a periodic lift is not extended");
      if (!(lo > -P.upper_length) || !(hi < P.lower_length))
        return make_error(fmt::format("signature: extension [{}, {}] m outside the overlap (-{}, {}) m", lo, hi,
                                      P.upper_length, P.lower_length));
      // A side that asks for less than R already holds (R's range may end nearer the overlap's
      // end than the hold's sliver) is R's own end there: nothing is listed beyond it.
      lo = std::min(lo, smin);
      hi = std::max(hi, smax);
      // Exact mode on an aligned lattice: R's lattice offsets from its third to its third last
      // (listed by the same expression, without near-duplicates so far from R's ends) are W's
      // there too; they are not listed again (W skips them, the walk below steps over them).
      double k0 = 1, k1 = 0;
      if (R.exact && o.offsets == 0 && P.aligned_lattice) {
        k0 = std::ceil((smin - P.lattice_origin) / P.lattice_step - 1e-9) + 2;
        k1 = std::floor((smax - P.lattice_origin) / P.lattice_step + 1e-9) - 2;
      }
      auto wide = plan_offsets(P, o, lo, hi, k0, k1);
      if (!wide) return wide.error();
      std::size_t j_skip = 0;  // R's index of its offset k0
      if (wide->skipped > 0) {
        const double x0 = P.lattice_origin + k0 * P.lattice_step, x1 = P.lattice_origin + k1 * P.lattice_step;
        j_skip = static_cast<std::size_t>(std::lower_bound(R.offset.begin(), R.offset.end(), x0) - R.offset.begin());
        const std::size_t m = wide->skipped;
        if (!(j_skip + m <= n && R.offset[j_skip] == x0 && R.offset[j_skip + m - 1] == x1)) {
          wide = plan_offsets(P, o, lo, hi);  // not expected: list them all
          if (!wide) return wide.error();
        }
      }
      detail::LiftExtension ext;
      ext.exact = wide->sampled == 0;
      ext.events = wide->events;
      const std::vector<double>& W = wide->offs;
      std::vector<double> todo;
      todo.reserve(W.size());     // at most W (pages are taken only as they are written)
      std::size_t j = 0, hj = 0;  // merge walk: W, R.offset and *have all increasing
      const std::size_t gap = wide->skipped > 0 ? wide->gap : W.size();
      for (std::size_t i = 0; i < W.size(); ++i) {
        if (i == gap) {  // R's offsets k0 .. k1, W's skipped ones
          while (j < j_skip) ext.dropped.push_back(j++);
          j += wide->skipped;
        }
        while (j < n && R.offset[j] < W[i]) ext.dropped.push_back(j++);
        if (j < n && R.offset[j] == W[i]) {
          ++j;
          continue;
        }
        if (have) {
          while (hj < have->size() && (*have)[hj] < W[i]) ++hj;
          if (hj < have->size() && (*have)[hj] == W[i]) continue;
        }
        todo.push_back(W[i]);
      }
      while (j < n) ext.dropped.push_back(j++);
      wide->offs = std::vector<double>();
      const bool pruned = prune && prune->decide && ext.exact && o.offsets == 0 && P.index_search && !P.periodic;
      if (!(pruned ? evaluate_lift_pruned(P, std::move(todo), o, *prune, ext.dropped, ext)
                   : evaluate_lift(P, std::move(todo), o, ext.points)))
        return make_error(fmt::format("signature: no overlap between the blocks in [{}, {}] m", lo, hi));
      return ext;
    };
    if (auto st = (*with_lift)(R, extend); !st) return st.error();
  }
  P = Problem{};  // the faces are no longer needed
  if (after_faces && *after_faces) {
    if (auto st = (*after_faces)(R); !st) return st.error();
  }
  signature_tail(R, o);
  return R;
}

}  // namespace

Result<SignatureResult> signature(const Profile& lower, const Profile& upper, const SignatureOptions& options) {
  return signature_impl(lower, upper, options, nullptr, nullptr);
}

Result<SignatureResult> detail::signature_with_lift(const Profile& lower, const Profile& upper,
                                                    const SignatureOptions& options, Profile* take_lower,
                                                    Profile* take_upper, const WithLift& with_lift,
                                                    const AfterFaces& after_faces) {
  if (options.spheroradius > 0) return make_error("signature: no extended lift for spheropolygons");
  const bool periodic = lower.period && upper.period;
  return signature_impl(lower, upper, options, periodic ? nullptr : take_lower, periodic ? nullptr : take_upper,
                        &with_lift, &after_faces);
}

Result<SignatureResult> signature(Profile&& lower, Profile&& upper, const SignatureOptions& options) {
  // Periodic profiles are tiled from copies anyway; the others give their storage to the faces.
  const bool periodic = lower.period && upper.period;
  return signature_impl(lower, upper, options, periodic ? nullptr : &lower, periodic ? nullptr : &upper);
}

Result<SignatureResult> self_signature(const Profile& surface, const SignatureOptions& options) {
  if (auto st = validate(surface, "surface"); !st) return st.error();
  return signature(surface, rotate180(surface), options);
}

}  // namespace frictal
