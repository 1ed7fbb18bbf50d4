// The map model (frictal/map_hold.hpp; docs/mujoco.md): the lift of the upper face's spheres of
// radius r on the lower face's height field triangulated as MuJoCo triangulates it
// (areal_tilt_lift), the quasi-static block on it (areal_tilt_hold, its drops and spread) and the
// model's defaults. The matched prediction of the MuJoCo tilt test; needs no MuJoCo.
#include <fmt/core.h>
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <numbers>
#include <string>
#include <vector>

#include "areal/areal_grid.hpp"
#include "frictal/analysis.hpp"
#include "frictal/areal.hpp"
#include "frictal/hold.hpp"
#include "frictal/map_hold.hpp"
#include "map_hold_geometry.hpp"
#include "util/parallel.hpp"

namespace frictal {
namespace {

constexpr double kNoContact = -std::numeric_limits<double>::infinity();

struct Vertex {
  double x, y, z;
};

/// The highest centre of a sphere of radius r above (cx, cy) that touches the segment a-b:
/// max over points p of the segment within r of (cx, cy) of p_z + sqrt(r^2 - |p - c|^2) (a
/// concave function of the position along the segment: its maximum, clamped to the segment).
double edge_top(const Vertex& a, const Vertex& b, double cx, double cy, double r, double& px, double& py) {
  const double ex = b.x - a.x, ey = b.y - a.y;
  const double L = std::sqrt(ex * ex + ey * ey);
  const double ux = ex / L, uy = ey / L;
  const double qx = cx - a.x, qy = cy - a.y;
  const double tc = qx * ux + qy * uy;
  const double perp2 = qx * qx + qy * qy - tc * tc;
  const double R2 = r * r - perp2;
  if (R2 <= 0) return kNoContact;
  const double R = std::sqrt(R2);
  const double lo = std::max(0.0, tc - R), hi = std::min(L, tc + R);
  if (lo > hi) return kNoContact;
  const double k = (b.z - a.z) / L;
  const double t = std::clamp(tc + k * R / std::sqrt(1 + k * k), lo, hi);
  px = a.x + t * ux;
  py = a.y + t * uy;
  return a.z + k * t + std::sqrt(std::max(0.0, R2 - (t - tc) * (t - tc)));
}

/// The highest centre of a sphere of radius r above (cx, cy) that touches the triangle abc
/// (kNoContact: none within r); (px, py) the touching point.
double triangle_top(const Vertex& a, const Vertex& b, const Vertex& c, double cx, double cy, double r, double& px,
                    double& py) {
  // The plane z = a.z + gx (x - a.x) + gy (y - a.y).
  const double e1x = b.x - a.x, e1y = b.y - a.y, e1z = b.z - a.z;
  const double e2x = c.x - a.x, e2y = c.y - a.y, e2z = c.z - a.z;
  const double det = e1x * e2y - e1y * e2x;
  const double gx = (e1z * e2y - e2z * e1y) / det, gy = (e1x * e2z - e2x * e1z) / det;
  const double w = std::sqrt(1 + gx * gx + gy * gy);
  // The sphere resting on the plane touches it at c + r g / w (horizontally).
  const double fx = cx + r * gx / w - a.x, fy = cy + r * gy / w - a.y;
  const double l1 = (fx * e2y - fy * e2x) / det, l2 = (e1x * fy - e1y * fx) / det;
  if (l1 >= 0 && l2 >= 0 && l1 + l2 <= 1) {
    px = a.x + fx;
    py = a.y + fy;
    return a.z + gx * (cx - a.x) + gy * (cy - a.y) + r * w;
  }
  // Otherwise the maximum of the concave height over the triangle lies on its boundary.
  double best = kNoContact, qx = 0, qy = 0;
  const Vertex* v[3] = {&a, &b, &c};
  for (int e = 0; e < 3; ++e) {
    const double t = edge_top(*v[e], *v[(e + 1) % 3], cx, cy, r, qx, qy);
    if (t > best) best = t, px = qx, py = qy;
  }
  return best;
}

/// The spheres of the upper face over the lower face's triangulated height field: the block's
/// height h(s) at offset s, with the touching point and, on request, every (sphere, triangle)
/// piece within eps of the max and its gradient (p - c) / sqrt(r^2 - |p - c|^2).
///
/// Cost: the spheres are grouped in square tiles (kTile lower-map cells on a side) and the lower
/// face's cell tops in blocks of kBlock x kBlock cells with their maximum. A tile's bound at s is
/// the highest block top under its footprint (moved by s, widened by r) plus r less its lowest
/// sphere's height: the tile of the highest bound is visited first and then only the tiles whose
/// bound reaches the best height less eps, so that an evaluation touches the few tiles that can reach the
/// top instead of every sphere (a 650 x 650 self-pair: every sphere 422,500 times per evaluation
/// before). Exact: a skipped tile holds no sphere within eps of the max (the bound is an upper
/// bound of each of its spheres' tops), so h, the touching point (ties aside) and the pieces
/// within eps are those of the direct loop over every sphere.
class SphereField {
 public:
  struct Piece {
    double value, gx, gy;
    double cap;  ///< the cap of |g - g_top| its window was collected with (unitless; see Window)
    double s;    ///< the facet slopes' bound around its cell (unitless; see Window)
    /// One order of the pieces, whatever the order of the visits: highest first, then by gradient.
    static bool before(const Piece& a, const Piece& b) {
      return a.value != b.value ? a.value > b.value
             : a.gx != b.gx     ? a.gx < b.gx
             : a.gy != b.gy     ? a.gy < b.gy
                                : a.cap < b.cap;
    }
  };
  /// The window of pieces a descent step of `delta` asks for: a piece within deficit
  /// delta * min(2, 2 (s + s_top)) + abs of the max, where s bounds the facet slopes around the
  /// piece's cell and s_top those around the top piece's (two contacts on those facets, or on
  /// edges between them, differ in gradient by at most s + s_top; 2 caps it, as before, and is the
  /// cap where no bound holds: the cells on the lower map's border, whose outer edges a sphere can
  /// touch sideways). On a rough map every cap is 2; on a smooth one (slopes of 0.01) the window is
  /// a hundredth as deep, and so is the work.
  struct Window {
    double delta = 0;  ///< (unit: m)
    double s_top = 0;  ///< (unitless)
    double abs = 0;    ///< (unit: m)
    double cap(double s) const { return std::min(2.0, 2 * (s + s_top)); }
    double eps(double s) const { return delta * cap(s) + abs; }
  };
  SphereField(const std::vector<detail::TiltNode>& nodes, const detail::Hfield& hf, double r)
      : nodes_(nodes), hf_(hf), r_(r), cnx_(hf.nx - 1), cny_(hf.ny - 1), cell_top_(cnx_ * cny_) {
    for (std::size_t j = 0; j < cny_; ++j)
      for (std::size_t i = 0; i < cnx_; ++i)
        cell_top_[j * cnx_ + i] = std::max({hf.at(i, j), hf.at(i + 1, j), hf.at(i, j + 1), hf.at(i + 1, j + 1)});
    // Each cell's facet slopes (its two triangles), then their max over the 3 x 3 cells around
    // it: a contact in the cell touches one of those facets or an edge or vertex between them,
    // whose gradient lies between theirs. (On the border's outer edges a sphere beyond the map
    // can touch sideways, steeper than any facet: there the descent's re-check in the full window
    // keeps a rest from being taken for one.)
    std::vector<double>& cell_slope = cell_slope_;
    cell_slope.assign(cnx_ * cny_, 0);
    for (std::size_t j = 0; j < cny_; ++j)
      for (std::size_t i = 0; i < cnx_; ++i) {
        const double z00 = hf.at(i, j), z10 = hf.at(i + 1, j), z01 = hf.at(i, j + 1), z11 = hf.at(i + 1, j + 1);
        cell_slope[j * cnx_ + i] = std::max(std::hypot((z11 - z01) / hf.dx, (z01 - z00) / hf.dy),
                                            std::hypot((z10 - z00) / hf.dx, (z11 - z10) / hf.dy));
      }
    slope3_.assign(cnx_ * cny_, 0);
    for (std::size_t j = 0; j < cny_; ++j)
      for (std::size_t i = 0; i < cnx_; ++i) {
        double m = 0;
        for (std::size_t jj = j > 0 ? j - 1 : 0; jj <= std::min(j + 1, cny_ - 1); ++jj)
          for (std::size_t ii = i > 0 ? i - 1 : 0; ii <= std::min(i + 1, cnx_ - 1); ++ii)
            m = std::max(m, cell_slope[jj * cnx_ + ii]);
        slope3_[j * cnx_ + i] = m;
        slope_max_ = std::max(slope_max_, m);
      }
    lip_ = slope_max_ * (1 + 1e-9);
    // How far h may fall across a Near disc (near_fall): the steepest facet bounds it, but on a
    // smooth measured map a few spikes set that max, and a list deep enough for them holds nearly
    // every sphere. Twice the 99th percentile of the facet slopes instead (at least a tenth of the
    // max, at most the max and 0.5): where h falls faster (by a spike) the list cannot decide and
    // the full evaluation answers, so the results are the same (plu-1 one drop: the same JSON in
    // 0.5 s instead of 5.7 s). On a rough map it is 0.5 as before.
    {
      std::vector<double> s = cell_slope;
      const auto k = std::ptrdiff_t(0.99 * double(s.size() - 1));
      std::nth_element(s.begin(), s.begin() + k, s.end());
      fall_ = std::min({0.5, slope_max_, std::max(2 * s[std::size_t(k)], 0.1 * slope_max_)});
    }
    // The highest cell top of every square of kSquare x kSquare cells, by its first cell (a
    // tile's footprint in four reads: cells_max).
    if (cnx_ >= kSquare && cny_ >= kSquare) {
      const std::size_t n = cnx_ - kSquare + 1, m = cny_ - kSquare + 1;
      std::vector<double> rows(n * cny_);
      for (std::size_t j = 0; j < cny_; ++j)
        for (std::size_t i = 0; i < n; ++i)
          rows[j * n + i] = *std::max_element(cell_top_.begin() + std::ptrdiff_t(j * cnx_ + i),
                                              cell_top_.begin() + std::ptrdiff_t(j * cnx_ + i + kSquare));
      top8_.assign(n * m, kNoContact);
      for (std::size_t j = 0; j < m; ++j)
        for (std::size_t k = 0; k < kSquare; ++k)
          for (std::size_t i = 0; i < n; ++i) top8_[j * n + i] = std::max(top8_[j * n + i], rows[(j + k) * n + i]);
    }
    bnx_ = (cnx_ + kBlock - 1) / kBlock;
    bny_ = (cny_ + kBlock - 1) / kBlock;
    block_top_.assign(bnx_ * bny_, kNoContact);
    for (std::size_t j = 0; j < cny_; ++j)
      for (std::size_t i = 0; i < cnx_; ++i) {
        double& b = block_top_[(j / kBlock) * bnx_ + i / kBlock];
        b = std::max(b, cell_top_[j * cnx_ + i]);
      }
    // Flat: the lower field's relief and the spheres' spread in height together within a tenth of
    // the hold angle's resolution of a cell (a plane removed from a constant map leaves rounding,
    // 1e-21 m on 2 um): every contact slope then lies below that, and so does the answer's
    // distance from the flat pair's.
    if (!nodes_.empty()) {
      const auto [lo, hi] = std::minmax_element(hf.z.begin(), hf.z.end());
      double nlo = nodes_[0].z, nhi = nlo;
      for (const detail::TiltNode& n : nodes_) nlo = std::min(nlo, n.z), nhi = std::max(nhi, n.z);
      flat_ = (*hi - *lo) + (nhi - nlo) <= 0.1 * kArealHoldResolution * std::min(hf.dx, hf.dy);
    }
    // Tiles of the spheres by their position at offset 0.
    if (nodes_.empty()) return;
    double xmin = nodes_[0].x, ymin = nodes_[0].y, xmax = xmin, ymax = ymin;
    for (const detail::TiltNode& n : nodes_)
      xmin = std::min(xmin, n.x), xmax = std::max(xmax, n.x), ymin = std::min(ymin, n.y), ymax = std::max(ymax, n.y);
    const double w = double(kTile) * std::max(hf.dx, hf.dy);
    const std::size_t tnx = std::size_t((xmax - xmin) / w) + 1, tny = std::size_t((ymax - ymin) / w) + 1;
    std::vector<std::size_t> count(tnx * tny + 1, 0);
    std::vector<std::size_t> tile_of(nodes_.size());
    for (std::size_t k = 0; k < nodes_.size(); ++k) {
      const std::size_t ti = std::min(tnx - 1, std::size_t((nodes_[k].x - xmin) / w));
      const std::size_t tj = std::min(tny - 1, std::size_t((nodes_[k].y - ymin) / w));
      tile_of[k] = tj * tnx + ti;
      ++count[tile_of[k] + 1];
    }
    for (std::size_t t = 0; t < tnx * tny; ++t) count[t + 1] += count[t];
    order_.resize(nodes_.size());
    std::vector<std::size_t> fill(count.begin(), count.end() - 1);
    std::vector<std::size_t> tile_super;                                             // each tile's super-tile
    for (std::size_t k = 0; k < nodes_.size(); ++k) order_[fill[tile_of[k]]++] = k;  // node order kept in a tile
    // The nodes in that order too, and within each tile by height from the lowest (the one that
    // reaches highest when turned over): a rebuild reads them tile by tile, contiguously, and stops
    // at the first that cannot reach the threshold.
    tiled_.resize(nodes_.size());
    for (std::size_t q = 0; q < nodes_.size(); ++q) tiled_[q] = {nodes_[order_[q]], std::uint32_t(order_[q])};
    for (std::size_t t = 0; t < tnx * tny; ++t)
      std::sort(tiled_.begin() + std::ptrdiff_t(count[t]), tiled_.begin() + std::ptrdiff_t(count[t + 1]),
                [](const TiledNode& a, const TiledNode& b) { return a.n.z < b.n.z || (a.n.z == b.n.z && a.k < b.k); });
    for (std::size_t t = 0; t < tnx * tny; ++t) {
      if (count[t] == count[t + 1]) continue;
      Tile tile{count[t], count[t + 1], INFINITY, -INFINITY, INFINITY, -INFINITY, kNoContact};
      for (std::size_t q = tile.begin; q < tile.end; ++q) {
        const detail::TiltNode& n = nodes_[order_[q]];
        tile.xlo = std::min(tile.xlo, n.x), tile.xhi = std::max(tile.xhi, n.x);
        tile.ylo = std::min(tile.ylo, n.y), tile.yhi = std::max(tile.yhi, n.y);
        tile.base = std::max(tile.base, -(n.z + r_));
      }
      tiles_.push_back(tile);
      tile_super.push_back((t / tnx / kSuper) * ((tnx + kSuper - 1) / kSuper) + (t % tnx) / kSuper);
    }
    // Super-tiles of kSuper x kSuper tiles over super-blocks of kSuper x kSuper blocks: a rebuild
    // of a Near list skips a super-tile whose bound is below the threshold without its tiles.
    const std::size_t nsup = ((tnx + kSuper - 1) / kSuper) * ((tny + kSuper - 1) / kSuper);
    std::vector<std::size_t> at(nsup, std::size_t(-1));
    for (std::size_t k = 0; k < tiles_.size(); ++k) {
      std::size_t& a = at[tile_super[k]];
      if (a == std::size_t(-1)) {
        a = supers_.size();
        supers_.push_back({{}, INFINITY, -INFINITY, INFINITY, -INFINITY, kNoContact});
      }
      Super& sp = supers_[a];
      const Tile& tl = tiles_[k];
      sp.tiles.push_back(std::uint32_t(k));
      sp.xlo = std::min(sp.xlo, tl.xlo), sp.xhi = std::max(sp.xhi, tl.xhi);
      sp.ylo = std::min(sp.ylo, tl.ylo), sp.yhi = std::max(sp.yhi, tl.yhi);
      sp.base = std::max(sp.base, tl.base);
    }
    snx_ = (bnx_ + kSuper - 1) / kSuper;
    sblock_top_.assign(snx_ * ((bny_ + kSuper - 1) / kSuper), kNoContact);
    for (std::size_t j = 0; j < bny_; ++j)
      for (std::size_t i = 0; i < bnx_; ++i) {
        double& b = sblock_top_[(j / kSuper) * snx_ + i / kSuper];
        b = std::max(b, block_top_[j * bnx_ + i]);
      }
  }
  /// The bound s of the facet slopes around the cell under (x, y) (unitless; infinity off the
  /// map).
  double slope_at(double x, double y) const {
    const double fi = std::floor((x - hf_.x0) / hf_.dx), fj = std::floor((y - hf_.y0) / hf_.dy);
    if (!(fi >= 0 && fj >= 0 && fi <= double(cnx_ - 1) && fj <= double(cny_ - 1)))
      return std::numeric_limits<double>::infinity();
    return slope3_[std::size_t(fj) * cnx_ + std::size_t(fi)];
  }
  /// The largest of the bounds (unitless).
  double slope_max() const { return slope_max_; }
  /// The centre of sphere n at offset (sx, sy) lies over the lower map (its nodes' rectangle).
  bool over_map(const detail::TiltNode& n, double sx, double sy) const {
    const double cx = n.x + sx, cy = n.y + sy;
    return cx >= hf_.x0 && cy >= hf_.y0 && cx <= hf_.x0 + double(cnx_) * hf_.dx && cy <= hf_.y0 + double(cny_) * hf_.dy;
  }
  /// No outliers among the facet slopes: near_fall() is their max (unitless).
  bool uniform() const { return fall_ >= slope_max_; }
  /// Two flat faces: the lower height field one horizontal plane and every sphere at one height
  /// (to a tenth of the hold angle's resolution of a cell), so that h is one constant wherever a
  /// sphere lies over the field and every contact's slope is zero.
  bool flat() const { return flat_; }
  /// A smooth map (every bound below 0.5): there the descent's windows and the Near lists follow
  /// the slopes; on a rough one they are those of before the bounds, to the bit.
  bool local() const { return slope_max_ < 0.5; }
  /// The spheres that can reach the top anywhere within `radius` of an offset `centre`: every
  /// sphere whose wide bound (the highest cell top within r + radius of its centre, plus r, less
  /// its height) is at least `threshold`, sorted by that bound, highest first. Kept by the caller
  /// (one per descending block) and rebuilt by eval_near when the offset leaves the disc.
  struct Near {
    double cx = 0, cy = 0, radius = -1;
    double scale = 1;  ///< the disc's radius in half lower-map cells (unitless; see rebuild)
    double threshold = kNoContact;
    double last = kNoContact;  ///< h at the last offset evaluated (unit: m)
    struct Entry {
      double wide;      ///< the sphere's wide bound (unit: m)
      std::uint32_t k;  ///< its node index
      float s;          ///< the facet slopes' bound over the cells it can touch (unitless; see Window)
    };
    std::vector<Entry> list;
    /// list[0, sorted) is in its final order; the rest is sorted as a visit reaches it, twice as
    /// many entries each time (on a smooth map the list holds most spheres and a visit reads a
    /// few: a full sort per rebuild took 97 % of a drop). The order is total (ties by node index):
    /// the same visits either way.
    std::size_t sorted = 0;
    long rebuilds = 0, fallbacks = 0;  ///< (unitless)
    /// The model's work: tiles and spheres read to build lists, and spheres evaluated (unitless;
    /// ArealTiltHold::work).
    long work = 0;
    /// A list over a wider disc, from which the lists of narrow discs inside it are built without
    /// the scan of every tile (see rebuild): every sphere whose wide bound over it reaches
    /// `threshold`, sorted (Near::before).
    struct Outer {
      double cx = 0, cy = 0, radius = -1;  ///< (unit: m; radius < 0: none)
      double threshold = kNoContact;       ///< (unit: m)
      std::vector<Entry> list;
    } outer;
    static bool before(const Entry& a, const Entry& b) { return a.wide > b.wide || (a.wide == b.wide && a.k < b.k); }
    /// On smooth maps (local()): per sphere, an upper bound of its top where the lists last had it
    /// evaluated (kNoContact: none, or its centre was not over the lower map), and that offset
    /// (an index into `at`, the offsets of the evaluations). A sphere whose centre stays over the
    /// lower map rises by at most the steepest facet's slope per unit of offset (lip_): its
    /// contacts' normals are the face's (a facet's, or between those of the facets at an edge or
    /// vertex), so the bound there is that top plus lip_ times the way, and a sphere below its
    /// window by it is left out. Exact as the lists (a bound); on a conformal pair sliding, the
    /// spheres tied within the fall of a disc are thousands and their tops change by a step's
    /// rise, a few of them a step.
    std::vector<double> memo;
    std::vector<std::uint32_t> memo_at;
    std::vector<std::array<double, 2>> at;
  };
  /// h(s) as eval, from the spheres of `near` (rebuilt around s when s lies outside its disc):
  /// visited in the order of their wide bounds until a bound falls below the best height less
  /// eps. Exact: a sphere left out has a wide bound, an upper bound of its top anywhere in the
  /// disc, below the best less eps; where the list ends above that (the threshold was set too
  /// high for this offset), the full evaluation answers. Same h and pieces within eps as eval.
  /// With `win`, the pieces are those within its window of each cell (eps: the deepest of them).
  double eval_near(double sx, double sy, double& bx, double& by, std::size_t& work, Near& near, double eps = 0,
                   std::vector<Piece>* pieces = nullptr, const Window* win = nullptr) const {
    const double ox = sx - near.cx, oy = sy - near.cy;
    if (near.radius < 0 || near.last == kNoContact) {
      // The first list: around h here (the full evaluation), down by eps and a quarter of the
      // disc's radius (h changes by less over most of the disc; where it does, the full
      // evaluation answers).
      const double h0 = eval(sx, sy, bx, by, work, eps, pieces, win, &near.work);
      if (h0 == kNoContact) return h0;
      rebuild(near, sx, sy, h0 - eps - 0.5 * near_fall() * near_radius(near));
      near.last = h0;
      return h0;
    }
    if (!(ox * ox + oy * oy <= near.radius * near.radius))  // around the last height found, lower by half the radius
      rebuild(near, sx, sy, near.last - eps - near_fall() * near_radius(near));
    double best = kNoContact;
    if (pieces) pieces->clear();
    bool complete = false;
    // Smooth maps: each sphere's top where it was last evaluated bounds it here (lazy).
    const bool lazy = local();
    if (lazy) {
      if (near.memo.empty()) near.memo.assign(nodes_.size(), kNoContact), near.memo_at.assign(nodes_.size(), 0);
      near.at.push_back({sx, sy});
    }
    for (std::size_t i = 0; i < near.list.size(); ++i) {
      if (i == near.sorted) {  // the next entries, twice as many as are sorted
        near.sorted = std::min(near.list.size(), 2 * i);
        std::partial_sort(near.list.begin() + std::ptrdiff_t(i), near.list.begin() + std::ptrdiff_t(near.sorted),
                          near.list.end(), Near::before);
      }
      const Near::Entry& e = near.list[i];
      if (e.wide < best - eps) {
        complete = true;
        break;
      }
      // Below its own window (best only grows: it stays below).
      const double eps_e = win ? win->eps(e.s) : eps;
      if (win && e.wide < best - eps_e) continue;
      if (!lazy) {
        ++near.work;
        // (Without a window, a call with a literal null: the compiler's copy of sphere() for it
        // drops the window's branches, a seventh of a rough pair's drop.)
        if (win)
          sphere(nodes_[e.k], sx, sy, best, bx, by, work, eps, pieces, win);
        else
          sphere(nodes_[e.k], sx, sy, best, bx, by, work, eps, pieces, nullptr);
        continue;
      }
      lazy_sphere(near, e.k, sx, sy, best, bx, by, work, eps, pieces, win, eps_e);
    }
    if (!complete && !(best != kNoContact && best - eps >= near.threshold)) {
      ++near.fallbacks;
      best = eval(sx, sy, bx, by, work, eps, pieces, win, &near.work, lazy ? &near : nullptr);
      near.last = best;
      if (best != kNoContact) rebuild(near, sx, sy, best - eps - 0.5 * near_fall() * near_radius(near));
      return best;
    }
    near.last = best;
    erase_outside(pieces, best, eps, win);
    return best;
  }

  /// Pieces collected with a window of a higher s_top, narrowed to `win` (each piece's cap
  /// recomputed from its cell's bound, then those below the window of `best` dropped): the same
  /// pieces, caps and order as collected with `win` itself, whose pieces are among them.
  static void narrow_window(std::vector<Piece>& pieces, double best, const Window& win) {
    for (Piece& p : pieces) p.cap = win.cap(p.s);
    erase_outside(&pieces, best, 0, &win);
  }

  /// h(s) (kNoContact: no sphere over the field); (bx, by) the touching point; `work` counts
  /// cells evaluated.
  /// With `lazy` (a Near whose offset of this evaluation is the last of its `at`): its bounds of
  /// the spheres' tops (Near::memo) leave out those below eps (the deepest window), as in eval_near.
  double eval(double sx, double sy, double& bx, double& by, std::size_t& work, double eps = 0,
              std::vector<Piece>* pieces = nullptr, const Window* win = nullptr, long* visits = nullptr,
              Near* lazy = nullptr) const {
    double best = kNoContact;
    if (pieces) pieces->clear();
    // Each tile's bound at this offset; the tile of the highest bound first (it sets a high best),
    // then every other tile whose bound reaches best - eps (a sort would cost more than it saves).
    std::vector<double> bound(tiles_.size(), kNoContact);
    std::size_t first = tiles_.size();
    for (std::size_t t = 0; t < tiles_.size(); ++t) {
      const Tile& tl = tiles_[t];
      std::size_t i0, i1, j0, j1;
      if (!cell_range(tl.xlo + sx, tl.xhi + sx, tl.ylo + sy, tl.yhi + sy, i0, i1, j0, j1)) continue;
      bound[t] = cells_top(block_top_, bnx_, kBlock, i0, i1, j0, j1) + r_ + tl.base;
      if (first == tiles_.size() || bound[t] > bound[first]) first = t;
    }
    if (first == tiles_.size()) return best;
    if (lazy) return eval_lazy(sx, sy, bx, by, work, eps, pieces, win, visits, *lazy, bound, first);
    for (std::size_t q = tiles_[first].begin; q < tiles_[first].end; ++q)
      sphere(nodes_[order_[q]], sx, sy, best, bx, by, work, eps, pieces, win);
    if (visits) *visits += long(tiles_.size() + tiles_[first].end - tiles_[first].begin);
    for (std::size_t t = 0; t < tiles_.size(); ++t) {
      if (t == first || bound[t] == kNoContact || bound[t] < best - eps) continue;
      if (visits) *visits += long(tiles_[t].end - tiles_[t].begin);
      for (std::size_t q = tiles_[t].begin; q < tiles_[t].end; ++q)
        sphere(nodes_[order_[q]], sx, sy, best, bx, by, work, eps, pieces, win);
    }
    erase_outside(pieces, best, eps, win);
    return best;
  }
  /// eval's visits of the tiles with Near::memo's bounds (lazy_sphere counts the spheres it reads).
  double eval_lazy(double sx, double sy, double& bx, double& by, std::size_t& work, double eps,
                   std::vector<Piece>* pieces, const Window* win, long* visits, Near& lazy,
                   const std::vector<double>& bound, std::size_t first) const {
    double best = kNoContact;
    for (std::size_t q = tiles_[first].begin; q < tiles_[first].end; ++q)
      lazy_sphere(lazy, std::uint32_t(order_[q]), sx, sy, best, bx, by, work, eps, pieces, win, eps);
    if (visits) *visits += long(tiles_.size());
    for (std::size_t t = 0; t < tiles_.size(); ++t) {
      if (t == first || bound[t] == kNoContact || bound[t] < best - eps) continue;
      for (std::size_t q = tiles_[t].begin; q < tiles_[t].end; ++q)
        lazy_sphere(lazy, std::uint32_t(order_[q]), sx, sy, best, bx, by, work, eps, pieces, win, eps);
    }
    erase_outside(pieces, best, eps, win);
    return best;
  }

 private:
  /// sphere() for node k, unless its bound from Near::memo (its top where last evaluated, plus lip_
  /// times the way from there) lies below best - eps_e, eps_e its deepest window (then none of its
  /// pieces is within its window, nor is it the max: the same h, point and pieces). Counts a visit
  /// in near.work where it reads the sphere's cells.
  void lazy_sphere(Near& near, std::uint32_t k, double sx, double sy, double& best, double& bx, double& by,
                   std::size_t& work, double eps, std::vector<Piece>* pieces, const Window* win, double eps_e) const {
    const detail::TiltNode& n = nodes_[k];
    const bool over = over_map(n, sx, sy);
    double& m = near.memo[k];
    if (over && m != kNoContact) {
      const auto& p = near.at[near.memo_at[k]];
      // (sqrt rather than hypot, a third of the time of this test: the slack covers its rounding.)
      const double wx = sx - p[0], wy = sy - p[1];
      if (m + lip_ * std::sqrt(wx * wx + wy * wy) + kBoundSlack * r_ + 1e-12 * (std::abs(m) + std::abs(n.z)) <
          best - eps_e)
        return;
    }
    ++near.work;
    double own = kNoContact;
    sphere<true>(n, sx, sy, best, bx, by, work, eps, pieces, win, &own);
    m = over ? own : kNoContact;
    near.memo_at[k] = std::uint32_t(near.at.size() - 1);
  }
  /// Drops the pieces below the window of the final max `best`. The pieces stay in the order of
  /// the visits (which the lists' discs set): the descent reads them through Piece::before where
  /// the order could matter (the top piece, the few points of least_norm), so that it does not
  /// choose. (A sort of every piece here took a tenth of a drop on a conformal pair, where every
  /// sphere is a piece at the seat.)
  static void erase_outside(std::vector<Piece>* pieces, double best, double eps, const Window* win) {
    if (!pieces) return;
    if (win)
      std::erase_if(*pieces, [&](const Piece& p) { return p.value < best - (win->delta * p.cap + win->abs); });
    else
      std::erase_if(*pieces, [&](const Piece& p) { return p.value < best - eps; });
  }
  static constexpr std::size_t kTile = 8, kBlock = 8;
  static constexpr std::size_t kNearSorted = 64;  ///< entries of a Near list sorted at its rebuild
  /// Lists longer than kNearLong halve the next disc (down to kNearScaleMin of half a cell),
  /// shorter than kNearShort double it (up to half a cell) (unitless).
  static constexpr std::size_t kNearLong = 64, kNearShort = 8;
  /// Discs of at most kOuterFrom of half a cell take their lists from an outer list over
  /// kOuterRatio times their radius, kOuterDepth times its fall below (unitless; see rebuild).
  /// Lists of 64 and 8 instead of 256 and 32: 1.4 s against 2.3 s. Measured on the tilted noisy
  /// plane of bench/flat_maps.py with its spikes removed, 4 drops, user CPU on a loaded VM: ratio
  /// 4 and depth 0.1 1.7 s, ratio 3 2.3 s, 6 1.8 s, depth 0.05 2.0 s, 0.2 2.3 s, 0.5 5.5 s, 1
  /// 10.7 s (deeper outer lists); from 1 (every disc: outer discs of two cells on a rough map)
  /// made bcrf-1's 25 drops 4 times slower, from 0.25 left them as they were. With the outer disc
  /// ahead of the block (kOuterAhead), ratio 6 (noise and tilt maps of bench/flat_maps.py without
  /// their spikes, 25 drops: 4.76 and 6.02 s at 4, 4.38 and 5.31 at 6, 4.39 and 5.27 at 8).
  static constexpr double kOuterFrom = 0.25, kOuterRatio = 6, kOuterDepth = 0.1;
  /// An outer disc lies this fraction of the way it can ahead of the block, along the way the
  /// block went since the last list (unitless; see rebuild).
  static constexpr double kOuterAhead = 0.9;
  static constexpr double kNearScaleMin = 1.0 / 64;
  /// The disc of offsets over which a Near list holds: one lower-map cell (unit: m).
  /// The disc of offsets over which a Near list holds: half a lower-map cell, or less where lists
  /// grew long (Near::scale) (unit: m).
  double near_radius(const Near& near) const { return near.scale * 0.5 * std::max(hf_.dx, hf_.dy); }
  /// How far h may fall across a Near disc, per unit of its radius: 0.5 (a guess: where h falls
  /// faster, the full evaluation answers), less on a smooth map (fall_) (unitless).
  double near_fall() const { return fall_; }

  void rebuild(Near& near, double sx, double sy, double threshold) const {
    ++near.rebuilds;
    // The way the block went since the last list (a unit vector; zero where there was none).
    double ux = 0, uy = 0;
    if (near.radius >= 0) {
      const double mx = sx - near.cx, my = sy - near.cy, m = std::hypot(mx, my);
      if (m > 0) ux = mx / m, uy = my / m;
    }
    near.cx = sx;
    near.cy = sy;
    near.radius = near_radius(near);
    near.threshold = threshold;
    near.list.clear();
    const double R = near.radius;
    // Narrow discs (lists ran long: nearly flat faces, where every tile holds spheres within the
    // fall of the top and a scan reads thousands of them to list a hundred) from an outer list over
    // kOuterRatio times the disc, down by kOuterDepth of its fall more: a narrow list is every
    // outer entry whose bound over the narrow disc reaches its threshold. Exact: a sphere not in
    // the outer list reaches below the outer threshold anywhere in the outer disc, which holds
    // the narrow one, and the narrow threshold is not below it (else the outer list is rebuilt).
    // The outer disc lies ahead of the block, along its way since the last list (descents and
    // slides go on much as they went): the narrow discs stay inside it about twice as far as in
    // one about the block (a descent that turns back costs a scan sooner; exact either way, the
    // narrow disc lies inside). On the noisy flat 563 x 484 pairs of bench/flat_maps.py the scans
    // took 74 % of the time with the disc about the block; ahead of it and 6 times the narrow one
    // instead of 4, 12-30 % less time (the same answers).
    if (near.scale <= kOuterFrom) {
      Near::Outer& o = near.outer;
      if (!(o.radius >= 0 && threshold >= o.threshold &&
            std::hypot(sx - o.cx, sy - o.cy) + R <= o.radius * (1 - 1e-6))) {
        o.radius = kOuterRatio * R;
        const double ahead = kOuterAhead * (o.radius - R);
        o.cx = sx + ahead * ux;
        o.cy = sy + ahead * uy;
        o.threshold = threshold - kOuterDepth * near_fall() * o.radius - kBoundSlack * r_;
        o.list.clear();
        collect(near, o.cx, o.cy, o.radius, o.threshold, o.list, false);
        std::sort(o.list.begin(), o.list.end(), Near::before);
      }
      for (const Near::Entry& e : o.list) {
        if (e.wide < threshold) break;
        ++near.work;
        const detail::TiltNode& n = nodes_[e.k];
        std::size_t i0, i1, j0, j1;
        if (!cell_range(n.x + sx - R, n.x + sx + R, n.y + sy - R, n.y + sy + R, i0, i1, j0, j1)) continue;
        const double wide = wide_bound(n, sx, sy, R, i0, i1, j0, j1, threshold);
        if (wide < threshold) continue;
        near.list.push_back({wide, e.k, local() ? slope_bound(i0, i1, j0, j1) : 0.0f});
      }
    } else {
      collect(near, sx, sy, R, threshold, near.list, local());
    }
    // The next disc: half as wide while lists run long, back towards half a cell while they are
    // short. Where many spheres reach nearly the same height (two nearly flat faces: their tops
    // differ by noise), a disc of half a cell admits every sphere within its fall (fall_ times the
    // radius) and its wide bound's slack: lists of 10^4 spheres, rebuilt every few steps, 60 % of a
    // drop; a narrower disc lowers both, at more rebuilds of short lists. Exact either way (a
    // list answers only where it can decide; the full evaluation otherwise).
    if (near.list.size() > kNearLong && near.scale > kNearScaleMin)
      near.scale *= 0.5;
    else if (near.list.size() < kNearShort && near.scale < 1)
      near.scale = std::min(1.0, 2 * near.scale);
    // Highest bound first; equal bounds by node index (the order does not depend on the scan's):
    // the first kNearSorted now, the rest when a visit reaches them.
    near.sorted = std::min(near.list.size(), kNearSorted);
    std::partial_sort(near.list.begin(), near.list.begin() + std::ptrdiff_t(near.sorted), near.list.end(),
                      Near::before);
  }
  /// A sphere's wide bound over a disc of offsets: its centre at offset s lies within R of c0
  /// (the centre at the disc's centre); it touches the lower face at points within r of its
  /// centre, so within r + R of c0, all in the window of cells [i0, i1] x [j0, j1]. Two bounds of
  /// the block's height where it touches: the highest cell top of the window (b) plus r, less
  /// its height; and, where c0 lies over the lower face, the face's height z(c0) there plus the
  /// rise along the straight path to the touching point, at most g (r' + R) for a point at r'
  /// from the centre (g the steepest facet of the window), so that the centre lies at most
  /// z(c0) + g R + max over r' of (g r' + sqrt(r^2 - r'^2)) = z(c0) + g R + r sqrt(1 + g^2) high
  /// (a little slack for rounding). On two nearly flat faces the second is tighter by the
  /// lower face's roughness within a cell (max cell top against the height under the centre):
  /// the lists hold the few spheres whose tops tie within the fall of the disc, not every sphere
  /// whose cell top does.
  /// Below `threshold` already by the first bound, that one (the caller drops the sphere).
  double wide_bound(const detail::TiltNode& n, double sx, double sy, double R, std::size_t i0, std::size_t i1,
                    std::size_t j0, std::size_t j1, double threshold) const {
    double b = kNoContact;
    for (std::size_t j = j0; j <= j1; ++j)
      for (std::size_t i = i0; i <= i1; ++i) b = std::max(b, cell_top_[j * cnx_ + i]);
    const double loose = b + r_ - (n.z + r_);
    if (loose < threshold) return loose;
    double g = 0;
    for (std::size_t j = j0; j <= j1; ++j)
      for (std::size_t i = i0; i <= i1; ++i) g = std::max(g, cell_slope_[j * cnx_ + i]);
    const double cx = n.x + sx, cy = n.y + sy;
    const double u = (cx - hf_.x0) * inv_dx_, v = (cy - hf_.y0) * inv_dy_;
    const double fi = std::floor(u), fj = std::floor(v);
    if (!(fi >= 0 && fj >= 0 && fi <= double(cnx_ - 1) && fj <= double(cny_ - 1))) return loose;
    const std::size_t i = std::size_t(fi), j = std::size_t(fj);
    const double a = std::clamp(u - fi, 0.0, 1.0), c = std::clamp(v - fj, 0.0, 1.0);
    const double z00 = hf_.at(i, j), z10 = hf_.at(i + 1, j), z01 = hf_.at(i, j + 1), z11 = hf_.at(i + 1, j + 1);
    // MuJoCo's split along (i, j)-(i+1, j+1).
    const double z = a >= c ? z00 + a * (z10 - z00) + c * (z11 - z10) : z00 + c * (z01 - z00) + a * (z11 - z01);
    const double slack = kBoundSlack * r_ + 1e-14 * (std::abs(z) + std::abs(n.z) + r_ + g * R);
    const double tight = z + g * R + r_ * std::sqrt(1 + g * g) - (n.z + r_) + slack;
    return std::min(loose, tight);
  }
  /// The highest cell top over cells [i0, i1] x [j0, j1] (unit: m): from four overlapping
  /// squares of kSquare cells (top8_) where the range is kSquare to 2 kSquare cells on a side, else
  /// cell by cell; the same value either way (a max).
  double cells_max(std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1) const {
    const std::size_t w = i1 - i0 + 1, h = j1 - j0 + 1;
    if (!top8_.empty() && w >= kSquare && h >= kSquare && w <= 2 * kSquare && h <= 2 * kSquare) {
      const std::size_t n = cnx_ - kSquare + 1, ia = i1 + 1 - kSquare, ja = j1 + 1 - kSquare;
      return std::max({top8_[j0 * n + i0], top8_[j0 * n + ia], top8_[ja * n + i0], top8_[ja * n + ia]});
    }
    double top = kNoContact;
    for (std::size_t j = j0; j <= j1; ++j)
      for (std::size_t i = i0; i <= i1; ++i) top = std::max(top, cell_top_[j * cnx_ + i]);
    return top;
  }
  /// The facet slopes' bound over cells [i0, i1] x [j0, j1], as a float rounded up (a bound).
  float slope_bound(std::size_t i0, std::size_t i1, std::size_t j0, std::size_t j1) const {
    double sm = 0;
    for (std::size_t j = j0; j <= j1; ++j)
      for (std::size_t i = i0; i <= i1; ++i) sm = std::max(sm, slope3_[j * cnx_ + i]);
    return std::nextafter(float(sm), std::numeric_limits<float>::infinity());
  }
  /// Appends to `list` every sphere whose wide bound over the disc of radius wr about (sx, sy)
  /// reaches `threshold` (unsorted); with `slopes`, each entry's slope bound.
  void collect(Near& near, double sx, double sy, double wr, double threshold, std::vector<Near::Entry>& list,
               bool slopes) const {
    for (const Super& sp : supers_) {
      std::size_t i0, i1, j0, j1;
      if (!cell_range(sp.xlo + sx - wr, sp.xhi + sx + wr, sp.ylo + sy - wr, sp.yhi + sy + wr, i0, i1, j0, j1)) continue;
      if (cells_top(sblock_top_, snx_, kBlock * kSuper, i0, i1, j0, j1) + r_ + sp.base < threshold) continue;
      for (const std::uint32_t ti : sp.tiles) {
        const Tile& tl = tiles_[ti];
        if (!cell_range(tl.xlo + sx - wr, tl.xhi + sx + wr, tl.ylo + sy - wr, tl.yhi + sy + wr, i0, i1, j0, j1))
          continue;
        if (cells_top(block_top_, bnx_, kBlock, i0, i1, j0, j1) + r_ + tl.base < threshold) continue;
        ++near.work;
        // The highest cell top under the tile's widened footprint bounds every one of its
        // spheres' (their windows lie inside it): a sphere below the threshold even against it is
        // left without reading its window (the same list, in the same order).
        const double tile_top = cells_max(i0, i1, j0, j1);
        for (std::size_t q = tl.begin; q < tl.end; ++q) {
          const detail::TiltNode& n = tiled_[q].n;
          // As `wide` below, and rounding is monotone: the rest of the tile (higher) cannot reach either.
          if (tile_top + r_ - (n.z + r_) < threshold) break;
          if (!cell_range(n.x + sx - wr, n.x + sx + wr, n.y + sy - wr, n.y + sy + wr, i0, i1, j0, j1)) continue;
          ++near.work;
          const double wide = wide_bound(n, sx, sy, wr, i0, i1, j0, j1, threshold);
          if (wide < threshold) continue;
          // The slopes' bound, read only where the windows use it (a smooth map).
          list.push_back({wide, tiled_[q].k, slopes ? slope_bound(i0, i1, j0, j1) : 0.0f});
        }
      }
    }
  }
  struct Tile {
    std::size_t begin, end;     ///< the tile's spheres: order_[begin, end)
    double xlo, xhi, ylo, yhi;  ///< their centres' extent at offset 0 (unit: m)
    double base;                ///< the highest -(z + r) of its spheres (unit: m)
  };
  static constexpr std::size_t kSuper = 8;  ///< tiles (and blocks) per super-tile side
  struct Super {
    std::vector<std::uint32_t> tiles;  ///< indices into tiles_
    double xlo, xhi, ylo, yhi;         ///< its spheres' extent at offset 0 (unit: m)
    double base;                       ///< the highest -(z + r) of its spheres (unit: m)
  };
  std::vector<Super> supers_;
  std::size_t snx_ = 0;
  std::vector<double> sblock_top_;  ///< max of block_top_ over kSuper x kSuper blocks

  /// The highest cell top over cells [i0, i1] x [j0, j1] from a table of block maxima, `size` cells
  /// on a side per block and `stride` blocks per row (unit: m).
  static double cells_top(const std::vector<double>& blocks, std::size_t stride, std::size_t size, std::size_t i0,
                          std::size_t i1, std::size_t j0, std::size_t j1) {
    double top = kNoContact;
    for (std::size_t bj = j0 / size; bj <= j1 / size; ++bj)
      for (std::size_t bi = i0 / size; bi <= i1 / size; ++bi) top = std::max(top, blocks[bj * stride + bi]);
    return top;
  }

  /// The cells whose rectangle meets the rectangle [x0, x1] x [y0, y1] widened by r; false if none.
  bool cell_range(double x0, double x1, double y0, double y1, std::size_t& i0, std::size_t& i1, std::size_t& j0,
                  std::size_t& j1) const {
    const double fi0 = std::floor((x0 - r_ - hf_.x0) / hf_.dx), fi1 = std::floor((x1 + r_ - hf_.x0) / hf_.dx);
    const double fj0 = std::floor((y0 - r_ - hf_.y0) / hf_.dy), fj1 = std::floor((y1 + r_ - hf_.y0) / hf_.dy);
    if (fi1 < 0 || fj1 < 0 || fi0 > double(cnx_ - 1) || fj0 > double(cny_ - 1)) return false;
    i0 = std::size_t(std::max(0.0, fi0)), i1 = std::size_t(std::min(double(cnx_ - 1), fi1));
    j0 = std::size_t(std::max(0.0, fj0)), j1 = std::size_t(std::min(double(cny_ - 1), fj1));
    return true;
  }

  /// With `own`: an upper bound of this sphere's own top (its block height where it touches; the
  /// top itself where every triangle that could reach was evaluated; kNoContact: it touches none).
  /// (A template, so that the visits that do not read the bound do not compute it.)
  template <bool kOwn = false>
  void sphere(const detail::TiltNode& n, double sx, double sy, double& best, double& bx, double& by, std::size_t& work,
              double eps, std::vector<Piece>* pieces, const Window* win = nullptr, double* own = nullptr) const {
    const double cx = n.x + sx, cy = n.y + sy;
    // Cells whose rectangle meets the disc of radius r about (cx, cy).
    std::size_t i0, i1, j0, j1;
    if (!cell_range(cx, cx, cy, cy, i0, i1, j0, j1)) return;
    double bound = kNoContact, sm = 0;
    for (std::size_t j = j0; j <= j1; ++j)
      for (std::size_t i = i0; i <= i1; ++i) {
        bound = std::max(bound, cell_top_[j * cnx_ + i]);
        if (win) sm = std::max(sm, slope3_[j * cnx_ + i]);
      }
    // The block's height when this sphere (centre n.z + r above the block's origin) touches.
    const double base = -(n.z + r_);
    if (bound + r_ + base < best - (win ? win->eps(sm) : eps)) {
      if constexpr (kOwn) *own = bound + r_ + base;
      return;
    }
    double ub = kNoContact;  // the bound of `own`
    const double r2 = r_ * r_;
    for (std::size_t j = j0; j <= j1; ++j)
      for (std::size_t i = i0; i <= i1; ++i) {
        // The cell's own window (eps where none is asked for).
        const double cap = win ? win->cap(slope3_[j * cnx_ + i]) : 2.0;
        const double eps_c = win ? win->delta * cap + win->abs : eps;
        if (cell_top_[j * cnx_ + i] + r_ + base < best - eps_c) {  // no point of the cell reaches
          if constexpr (kOwn) ub = std::max(ub, cell_top_[j * cnx_ + i] + r_ + base);
          continue;
        }
        const Vertex p00{hf_.x0 + double(i) * hf_.dx, hf_.y0 + double(j) * hf_.dy, hf_.at(i, j)};
        // A point of the cell at horizontal distance rho >= delta from the centre lifts the
        // sphere to at most its height + sqrt(r^2 - delta^2): the cell's bound at its distance
        // (delta to the cell's rectangle), and each triangle's (delta also at least the distance
        // to the diagonal when the centre lies on the other triangle's side). Exact: the bound
        // is an upper bound (less rounding: kBoundSlack r), so a triangle left out holds no
        // piece within eps of the max; h, the touching point and the pieces are unchanged.
        const double ux = cx - p00.x, uy = cy - p00.y;
        const double ddx = std::max({0.0, -ux, ux - hf_.dx}), ddy = std::max({0.0, -uy, uy - hf_.dy});
        const double d2 = ddx * ddx + ddy * ddy;
        if (d2 >= r2 * (1 + kBoundSlack)) continue;
        const double z10 = hf_.at(i + 1, j), z01 = hf_.at(i, j + 1), z11 = hf_.at(i + 1, j + 1);
        // s > 0: the centre on the lower-right triangle's side of the diagonal; its distance to
        // the diagonal's line s / |(1/dx, -1/dy)|.
        const double s = ux * inv_dx_ - uy * inv_dy_;
        const double dd2 = s * s * diag_scale2_;
        const double top_t[2] = {std::max({p00.z, z01, z11}), std::max({p00.z, z11, z10})};
        const double d2_t[2] = {s > 0 ? std::max(d2, dd2) : d2, s < 0 ? std::max(d2, dd2) : d2};
        // Each triangle's bound on the block's height (best may rise between the two).
        double reach[2];
        for (int t = 0; t < 2; ++t)
          reach[t] = top_t[t] + std::sqrt(std::max(0.0, r2 - d2_t[t])) + kBoundSlack * r_ + base;
        if (std::max(reach[0], reach[1]) < best - eps_c) {
          if constexpr (kOwn) ub = std::max({ub, reach[0], reach[1]});
          continue;
        }
        ++work;
        const Vertex p10{p00.x + hf_.dx, p00.y, z10};
        const Vertex p01{p00.x, p00.y + hf_.dy, z01};
        const Vertex p11{p00.x + hf_.dx, p00.y + hf_.dy, z11};
        // MuJoCo's two triangles of the cell, split along (i, j)-(i+1, j+1).
        for (int t = 0; t < 2; ++t) {
          if (reach[t] < best - eps_c) {
            if constexpr (kOwn) ub = std::max(ub, reach[t]);
            continue;
          }
          double px = 0, py = 0;
          const double top = t == 0 ? triangle_top(p01, p00, p11, cx, cy, r_, px, py)
                                    : triangle_top(p00, p11, p10, cx, cy, r_, px, py);
          if (top == kNoContact) continue;
          const double v = top + base;
          if constexpr (kOwn) ub = std::max(ub, v);
          // Ties (quantised heights) to the lowest touching point: h, the point and the pieces do
          // not depend on the order in which spheres are visited (lists, tiles).
          if (v > best || (v == best && (px < bx || (px == bx && py < by)))) best = v, bx = px, by = py;
          if (pieces && v >= best - eps_c) {
            const double ex = px - cx, ey = py - cy;
            const double q = std::sqrt(std::max(r_ * r_ - ex * ex - ey * ey, 1e-12 * r_ * r_));
            pieces->push_back({v, ex / q, ey / q, cap, win ? slope3_[j * cnx_ + i] : 0.0});
          }
        }
      }
    if constexpr (kOwn) *own = ub;
  }

  /// Relative slack of the distance bounds in sphere() against rounding (unitless).
  static constexpr double kBoundSlack = 1e-9;
  const std::vector<detail::TiltNode>& nodes_;
  const detail::Hfield& hf_;
  double r_;
  double inv_dx_ = 1 / hf_.dx, inv_dy_ = 1 / hf_.dy;                  ///< (unit: 1/m)
  double diag_scale2_ = 1 / (inv_dx_ * inv_dx_ + inv_dy_ * inv_dy_);  ///< (unit: m^2)
  std::size_t cnx_, cny_;
  std::vector<double> cell_top_;
  static constexpr std::size_t kSquare = 8;
  std::vector<double> top8_;        ///< the highest cell top of the kSquare x kSquare cells from each cell (unit: m)
  std::vector<double> cell_slope_;  ///< per cell: the steeper of its two facets' slopes (unitless)
  std::vector<double> slope3_;      ///< per cell: the facet slopes' max over the 3 x 3 cells around it (unitless)
  double slope_max_ = 0;            ///< slope3_'s max (unitless)
  /// The steepest facet's slope: a sphere's top over the lower map rises by at most this per unit
  /// of offset (unitless; Near::memo).
  double lip_ = 0;
  bool flat_ = false;  ///< see flat()
  double fall_ = 0.5;  ///< near_fall(): see the constructor (unitless)
  std::size_t bnx_ = 0, bny_ = 0;
  std::vector<double> block_top_;   ///< max of cell_top_ over kBlock x kBlock cells
  std::vector<std::size_t> order_;  ///< sphere indices grouped by tile
  struct TiledNode {
    detail::TiltNode n;
    std::uint32_t k;  ///< its index in nodes_
  };
  std::vector<TiledNode> tiled_;  ///< each tile's nodes (order_'s tiles), lowest z first
  std::vector<Tile> tiles_;
};

/// The least-norm point of the convex hull of points in the plane (few points).
std::array<double, 2> least_norm(const std::vector<std::array<double, 2>>& q) {
  std::array<double, 2> best = q[0];
  auto n2 = [](const std::array<double, 2>& a) { return a[0] * a[0] + a[1] * a[1]; };
  for (const auto& p : q)
    if (n2(p) < n2(best)) best = p;
  for (std::size_t i = 0; i < q.size(); ++i)
    for (std::size_t j = i + 1; j < q.size(); ++j) {
      const double ex = q[j][0] - q[i][0], ey = q[j][1] - q[i][1], L2 = ex * ex + ey * ey;
      if (L2 <= 0) continue;
      const double t = std::clamp(-(q[i][0] * ex + q[i][1] * ey) / L2, 0.0, 1.0);
      const std::array<double, 2> c{q[i][0] + t * ex, q[i][1] + t * ey};
      if (n2(c) < n2(best)) best = c;
      for (std::size_t k = j + 1; k < q.size(); ++k) {  // the origin inside triangle ijk
        auto side = [](const std::array<double, 2>& a, const std::array<double, 2>& b) {
          return a[0] * b[1] - a[1] * b[0];
        };
        const std::array<double, 2> a{q[j][0] - q[i][0], q[j][1] - q[i][1]}, b{q[k][0] - q[i][0], q[k][1] - q[i][1]};
        const double area = side(a, b);
        if (std::abs(area) <= 1e-12 * (n2(a) + n2(b))) continue;  // collinear: the segments decide
        const double s1 = side(q[i], q[j]), s2 = side(q[j], q[k]), s3 = side(q[k], q[i]);
        if ((s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0)) return {0, 0};
      }
    }
  return best;
}

/// The convex hull of points q, sorted and without repeats (at least two), by Andrew's monotone
/// chain: counter-clockwise, the first point not repeated (two points: both).
std::vector<std::array<double, 2>> convex_hull(const std::vector<std::array<double, 2>>& q) {
  auto cross = [](const std::array<double, 2>& o, const std::array<double, 2>& a, const std::array<double, 2>& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  };
  std::vector<std::array<double, 2>> h(2 * q.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], q[i]) <= 0) --k;
    h[k++] = q[i];
  }
  for (std::size_t i = q.size() - 1, lo = k + 1; i-- > 0;) {
    while (k >= lo && cross(h[k - 2], h[k - 1], q[i]) <= 0) --k;
    h[k++] = q[i];
  }
  h.resize(k - 1);
  return h;
}

/// Drops the points that lie inside the polygon of the extreme points along eight directions (x,
/// y and the diagonals, both ways) by more than rounding (Akl and Toussaint's heuristic): none of
/// them is a vertex of the hull, so the hull (and the sorted points its chain reads at its edges)
/// is the same, in linear time before the sort. On a conformal pair every sphere is a piece at the
/// seat and the sort of their slopes took a twentieth of a drop; most of them lie inside.
void drop_interior(std::vector<std::array<double, 2>>& q) {
  if (q.size() < 16) return;
  constexpr std::array<std::array<double, 2>, 8> dirs = {
      {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}}};  // counter-clockwise
  std::array<std::size_t, 8> at{};
  std::array<double, 8> best;
  best.fill(-std::numeric_limits<double>::infinity());
  double scale = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    scale = std::max({scale, std::abs(q[i][0]), std::abs(q[i][1])});
    for (std::size_t k = 0; k < 8; ++k) {
      const double v = dirs[k][0] * q[i][0] + dirs[k][1] * q[i][1];
      if (v > best[k]) best[k] = v, at[k] = i;
    }
  }
  std::vector<std::array<double, 2>> poly;  // the extreme points, counter-clockwise, without repeats
  for (std::size_t k = 0; k < 8; ++k)
    if (poly.empty() || (q[at[k]] != poly.back() && q[at[k]] != poly.front())) poly.push_back(q[at[k]]);
  if (poly.size() < 3) return;
  // Strictly inside every edge by far more than the rounding of the cross products (relative
  // 1e-16 of scale^2): such a point is inside the hull whatever the rounding of the chain.
  const double margin = 1e-9 * scale * scale;
  std::erase_if(q, [&](const std::array<double, 2>& p) {
    for (std::size_t e = 0; e < poly.size(); ++e) {
      const auto& a = poly[e];
      const auto& b = poly[(e + 1) % poly.size()];
      if ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]) <= margin) return false;
    }
    return true;
  });
}

/// The least-norm point of the convex hull of many points (the friction cones' samples): the hull
/// (Andrew's monotone chain), then the origin inside it (0) or the nearest point of its boundary.
/// Same answer as least_norm, in O(n log n).
/// `interior`: drop the points inside first (drop_interior; the pieces' slopes of a conformal seat,
/// not the cones' samples, which lie on their rims and cost the test without leaving it).
std::array<double, 2> least_norm_hull(std::vector<std::array<double, 2>> q, bool interior = false) {
  if (interior) drop_interior(q);
  std::sort(q.begin(), q.end());
  q.erase(std::unique(q.begin(), q.end()), q.end());
  if (q.size() < 3) return least_norm(q);
  auto cross = [](const std::array<double, 2>& o, const std::array<double, 2>& a, const std::array<double, 2>& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  };
  const std::vector<std::array<double, 2>> h = convex_hull(q);
  if (h.size() < 3) return least_norm(h);
  bool inside = true;
  std::array<double, 2> best = h[0];
  auto n2 = [](const std::array<double, 2>& a) { return a[0] * a[0] + a[1] * a[1]; };
  for (std::size_t i = 0; i < h.size(); ++i) {
    const auto& a = h[i];
    const auto& b = h[(i + 1) % h.size()];
    if (cross(a, b, {0, 0}) < 0) inside = false;
    const double ex = b[0] - a[0], ey = b[1] - a[1], L2 = ex * ex + ey * ey;
    const double t = L2 > 0 ? std::clamp(-(a[0] * ex + a[1] * ey) / L2, 0.0, 1.0) : 0.0;
    const std::array<double, 2> c{a[0] + t * ex, a[1] + t * ey};
    if (n2(c) < n2(best)) best = c;
  }
  return inside ? std::array<double, 2>{0, 0} : best;
}

/// The slopes of the forces within the Coulomb cone of a contact whose lift slope is g (normal
/// (-g, 1)), of half-angle phi = atan(mu_a): a force f (f_z > 0) has the slope -f_xy / f_z, the
/// normal itself g. `k` samples of the cone's rim (those pointing up), appended to `out`.
void cone_slopes(double gx, double gy, double phi, int k, std::vector<std::array<double, 2>>& out) {
  const double nn = std::sqrt(1 + gx * gx + gy * gy);
  const double nx = -gx / nn, ny = -gy / nn, nz = 1 / nn;
  // a = horizontal unit vector across the slope (or x), b = n x a.
  double ax = -ny, ay = nx;
  const double al = std::hypot(ax, ay);
  if (al < 1e-12) {
    ax = 1;
    ay = 0;
  } else {
    ax /= al;
    ay /= al;
  }
  const double bx = -nz * ay, by = nz * ax, bz = nx * ay - ny * ax;
  const double c = std::cos(phi), sn = std::sin(phi);
  out.push_back({gx, gy});  // the normal force (the cone's axis)
  // The rim's directions (cos, sin of 2 pi i / k), the same for every cone: computed once per k
  // (a third of a friction hold's time went to these sines).
  thread_local int rim_k = 0;
  thread_local std::vector<std::array<double, 2>> rim;
  if (rim_k != k) {
    rim.resize(std::size_t(std::max(k, 0)));
    for (int i = 0; i < k; ++i) {
      const double th = 2 * std::numbers::pi * i / k;
      rim[std::size_t(i)] = {std::cos(th), std::sin(th)};
    }
    rim_k = k;
  }
  for (int i = 0; i < k; ++i) {
    const double ct = rim[std::size_t(i)][0], st = rim[std::size_t(i)][1];
    const double ux = c * nx + sn * (ct * ax + st * bx), uy = c * ny + sn * (ct * ay + st * by),
                 uz = c * nz + sn * st * bz;
    if (uz < 1e-9) continue;  // a force along or below the horizontal: no slope (the region is truncated)
    out.push_back({-ux / uz, -uy / uz});
  }
}

/// The largest t with t d in the convex hull of points q in the plane (NaN where the line along d
/// through the origin misses it): the steepest tilt, as tan, at which contacts of those slopes
/// (or friction cones' slopes) still hold a block, the free block's seat in one evaluation.
double ray_hull_max(std::vector<std::array<double, 2>> q, double dxv, double dyv) {
  std::sort(q.begin(), q.end());
  q.erase(std::unique(q.begin(), q.end()), q.end());
  auto cross = [](double ax, double ay, double bx, double by) { return ax * by - ay * bx; };
  // Points on the line along d (the locked block's slopes, projected): the hull is a segment of
  // it, and the largest t its far end.
  if (std::all_of(q.begin(), q.end(), [&](const std::array<double, 2>& p) {
        return std::abs(cross(p[0], p[1], dxv, dyv)) <= 1e-12 * std::hypot(p[0], p[1]);
      })) {
    double best = -std::numeric_limits<double>::infinity();
    for (const auto& p : q) best = std::max(best, p[0] * dxv + p[1] * dyv);
    return q.empty() ? std::numeric_limits<double>::quiet_NaN() : best;
  }
  double best = std::numeric_limits<double>::quiet_NaN();
  auto edge = [&](const std::array<double, 2>& a, const std::array<double, 2>& b) {
    const double ex = b[0] - a[0], ey = b[1] - a[1];
    const double den = cross(dxv, dyv, ex, ey);
    if (den == 0) return;
    const double lam = cross(a[0], a[1], dxv, dyv) / den;
    if (lam < -1e-12 || lam > 1 + 1e-12) return;
    const double tt = cross(a[0], a[1], ex, ey) / den;
    if (!(tt <= best)) best = tt;
  };
  if (q.size() == 1) {
    if (std::abs(cross(q[0][0], q[0][1], dxv, dyv)) <= 1e-12 * std::hypot(q[0][0], q[0][1]))
      best = q[0][0] * dxv + q[0][1] * dyv;
    return best;
  }
  // The hull, then its edges.
  const std::vector<std::array<double, 2>> h = convex_hull(q);
  for (std::size_t i = 0; i < h.size(); ++i) edge(h[i], h[(i + 1) % h.size()]);
  return best;
}

/// The steepest slope along d (unit vector (dx, dy)) of the forces in the Coulomb cone of
/// half-angle phi (rad) about the normal (-g, 1) of a contact whose lift slope is g: max over
/// forces f of the cone of -f.d / f_z (unitless; +inf where the cone reaches the horizontal). The
/// cone's support in the vertical plane of d: the largest t with (t - g.d) = N sin(phi)
/// sqrt(1 + t^2), N = |(-g, 1)|; for g along d it is tan(atan(g.d) + phi) (Eq. 6's
/// theta + theta_a). The model samples the rim (cone_slopes), so its slopes lie below this.
double cone_max_slope(double gx, double gy, double dxv, double dyv, double phi) {
  const double gd = gx * dxv + gy * dyv;
  if (!(phi > 0)) return gd;
  const double ns = std::sqrt(1 + gx * gx + gy * gy) * std::sin(phi);
  const double a = 1 - ns * ns;
  if (a <= 0) return std::numeric_limits<double>::infinity();
  return (gd + ns * std::sqrt(1 + gd * gd - ns * ns)) / a;
}

}  // namespace

Result<ArealLift> areal_tilt_lift(const Map& f, const Map& g, const MapHoldOptions& t, const ArealLiftOptions& o) {
  if (auto s = validate(f, "lower map"); !s) return s.error();
  if (auto s = validate(g, "upper map"); !s) return s.error();
  if (f.nx < 2 || f.ny < 2) return make_error("areal_tilt_lift: the lower map needs 2 x 2 nodes");
  if (!std::isfinite(t.angle))
    return make_error(fmt::format("areal_tilt_lift: angle {}: expected a finite direction (rad)", t.angle));
  if (!std::isfinite(t.sphere_radius) || t.sphere_radius < 0)
    return make_error(
        fmt::format("areal_tilt_lift: sphere radius {}: expected a finite number >= 0 (m)", t.sphere_radius));
  if (t.hfield_refine < 1 || t.hfield_refine > 16)
    return make_error(fmt::format("areal_tilt_lift: hfield_refine {}: expected 1..16", t.hfield_refine));
  if (detail::direction_quarters(t.angle) != 0 || f.x0 != 0 || f.y0 != 0) {
    // In the frame of the direction (detail::TurnedExperiment; there it has no quarter turn and
    // the lower map starts at the origin): the offsets count along and across d in both frames;
    // the contacts' nodes are turned back.
    const detail::TurnedExperiment e(f, g, t);
    auto lift = areal_tilt_lift(e.f, e.g, e.t, o);
    if (!lift) return lift;
    Map index = f;
    for (std::size_t k = 0; k < index.heights.size(); ++k) index.heights[k] = double(k);
    const Map at = detail::turned(std::move(index), -e.q);
    for (std::int64_t& c : lift->contact)
      if (c >= 0) c = std::int64_t(at.heights[std::size_t(c)]);
    return lift;
  }
  auto grid = detail::areal_offset_grid(f, t.angle, o, "areal_tilt_lift");
  if (!grid) return grid.error();
  const std::vector<detail::TiltNode> nodes = detail::tilt_nodes(f, g, t.angle, t.turn_over_upper);
  if (nodes.empty()) return make_error("areal_tilt_lift: the upper map has no valid node");
  const detail::Hfield hf = detail::tilt_hfield(f, std::size_t(t.hfield_refine));
  const double r = detail::tilt_sphere_radius(f, t);

  // The offset grid, as areal_lift.
  const double dxv = std::cos(t.angle), dyv = std::sin(t.angle), ex = -dyv, ey = dxv;
  ArealLift out = std::move(*grid);
  const std::size_t nu = out.n_along, nv = out.n_across;
  if (double(nu) * double(nv) * double(nodes.size()) > 2e10)
    return make_error(
        fmt::format("areal_tilt_lift: {} x {} offsets of {} spheres are too many; increase step or "
                    "across_step",
                    nu, nv, nodes.size()));
  out.lift.assign(nu * nv, std::numeric_limits<double>::quiet_NaN());
  out.contact.assign(nu * nv, -1);

  const SphereField field(nodes, hf, r);
  std::vector<std::size_t> work(nu * nv, 0);
  util::parallel_chunks(nu * nv, util::thread_count(o.threads, nu * nv), [&](unsigned, std::size_t k0, std::size_t k1) {
    for (std::size_t k = k0; k < k1; ++k) {
      const double u = out.along(k % nu), v = out.across(k / nu);
      const double sx = u * dxv + v * ex, sy = u * dyv + v * ey;
      double bx = 0, by = 0;
      const double best = field.eval(sx, sy, bx, by, work[k]);
      if (best == kNoContact) continue;
      out.lift[k] = best;
      const double ci = std::clamp(std::round((bx - f.x0) / f.dx), 0.0, double(f.nx - 1));
      const double cj = std::clamp(std::round((by - f.y0) / f.dy), 0.0, double(f.ny - 1));
      out.contact[k] = std::int64_t(cj) * std::int64_t(f.nx) + std::int64_t(ci);
    }
  });
  if (!detail::areal_lift_touches(out, work))
    return make_error(
        fmt::format("areal_tilt_lift: the spheres never touch the height field over offsets {} to {} m along {} deg "
                    "(expected maps that overlap along the sliding direction)",
                    out.along(0), out.along(nu - 1), t.angle * 180 / std::numbers::pi));
  return out;
}

}  // namespace frictal

namespace frictal {

namespace {

/// The checks of areal_tilt_hold that do not depend on the start offset.
Status check_hold_inputs(const Map& f, const Map& g, const MapHoldOptions& t, double resolution, double stationary,
                         double start_tilt) {
  if (auto s = validate(f, "lower map"); !s) return s.error();
  if (auto s = validate(g, "upper map"); !s) return s.error();
  if (f.nx < 2 || f.ny < 2) return make_error("areal_tilt_hold: the lower map needs 2 x 2 nodes");
  if (!std::isfinite(t.angle))
    return make_error(fmt::format("areal_tilt_hold: angle {}: expected a finite direction (rad)", t.angle));
  if (!std::isfinite(t.atomic_friction) || t.atomic_friction < 0)
    return make_error(
        fmt::format("areal_tilt_hold: atomic friction {}: expected a finite number >= 0", t.atomic_friction));
  if (!std::isfinite(t.sphere_radius) || t.sphere_radius < 0)
    return make_error(
        fmt::format("areal_tilt_hold: sphere radius {}: expected a finite number >= 0 (m)", t.sphere_radius));
  if (t.hfield_refine < 1 || t.hfield_refine > 16)
    return make_error(fmt::format("areal_tilt_hold: hfield_refine {}: expected 1..16", t.hfield_refine));
  if (!(t.tilt_step > 0) || !(t.coarse_tilt_step > 0) || !(t.max_tilt > t.tilt_step) ||
      !(t.max_tilt < std::numbers::pi / 2) || !(resolution > 0) || !(stationary > 0))
    return make_error(
        "areal_tilt_hold: expected 0 < tilt_step < max_tilt < pi/2, coarse_tilt_step > 0, resolution > 0 "
        "and stationary > 0");
  if (!(start_tilt >= 0 && start_tilt < t.max_tilt))
    return make_error(
        fmt::format("areal_tilt_hold: start tilt {} rad: expected in [0, max_tilt = {})", start_tilt, t.max_tilt));
  if (!std::isfinite(t.runaway_distance) || t.runaway_distance < 0)
    return make_error("areal_tilt_hold: the run-away distance must be finite and >= 0 (m)");
  return Ok{};
}

/// The protocol of areal_tilt_hold on a field already built (inputs checked), from t.start_offset.
Result<ArealTiltHold> hold_on_field(const SphereField& field, const Map& f, const MapHoldOptions& t, double r,
                                    double resolution, double stationary, double start_tilt,
                                    const std::function<void(double)>& reached = {}) {
  if (!std::isfinite(t.start_offset[0]) || !std::isfinite(t.start_offset[1]))
    return make_error("areal_tilt_hold: the start offset must be finite (m)");
  const double dxv = std::cos(t.angle), dyv = std::sin(t.angle);
  const double D = detail::tilt_runaway_distance(f, t);
  ArealTiltHold out;
  std::size_t work = 0;
  SphereField::Near near;
  std::vector<SphereField::Piece> pieces, trial_pieces, wide_pieces;
  // The descent follows the local steepest direction: the pieces that decide it (and that the
  // turn check reads) are those a step of at most kLocal r could make the highest, however long the
  // step. (A window as long as the step, as before, let pieces beside the path turn the direction
  // and, at the turn check, stall the step at a few thousandths of r for as long as they stayed
  // beside it: the same agreement with MuJoCo at 2.4x the work.) Steps up to kLocal r are taken
  // without the turn check, longer ones (up to kMaxStep r: longer steps jumped seats of the
  // statistical check's maps) only where the direction at their end lies within kTurn (rad) of
  // theirs. On the check's 128 drops: 128 within the rule, every pair's median within 0.3 deg;
  // kLocal 0.0025 and kTurn 0.1 the same, kMaxStep 0.05 or 0.15, kLocal 0.01 or kTurn 0.02 one drop
  // (a basin boundary) off by 4 deg (bench/results/predict-vs-sim.md, "the local direction").
  constexpr double kLocal = 0.005, kMaxStep = 0.1, kTurn = 0.05;
  // Guesses of the run-away tilt from the seat before the bisection (see there).
  constexpr int kSeatGuesses = 6;
  // The window of pieces for a step of delta (m).
  auto window = [&](double delta) { return std::min(delta, kLocal * r); };
  std::vector<std::array<double, 2>> q, slopes;
  // With atomic friction the block is held iff the tilted load lies in the sum of the contacts'
  // Coulomb cones: in slopes, iff tan(beta) d lies in the convex hull of their cones' slope sets
  // (docs/mujoco.md); each cone sampled on its rim (inscribed: the hold angle errs low by at most
  // (1 - cos(pi / k)) phi_a, 3e-5 rad at mu_a = 0.1).
  const double phi_a = std::atan(t.atomic_friction);
  constexpr int kConeSamples = 128;
  // h where the spheres touch, +inf (a wall) where none is over the field.
  // With pieces: those a step of `delta` could make the highest (SphereField::Window), from the
  // max first (where it touches sets the top's slope bound), then every piece within its window;
  // `full`: the window of cap 2 for every piece.
  // Where a bound reaches 0.5, some caps are 2 anyway: there every piece's cap is 2, in one pass
  // (the windows as they were before the bounds; the same descents, to the bit).
  const bool local = field.local();
  // A smooth map whose steepest facets are not outliers (the 99th percentile's fall reaches the
  // max): the window of the steepest top is not much deeper than the top's own, and one pass
  // with it costs less than a pass for the top and one for the window.
  const bool one_pass = local && field.uniform();
  auto height = [&](double x, double y, double delta, std::vector<SphereField::Piece>* p, bool full = false) {
    double bx = 0, by = 0;
    ++out.evaluations;
    if (!local || !p) {
      const double h = field.eval_near(x, y, bx, by, work, near, p ? 2 * delta + 2e-12 * r : 0, p);
      return h == kNoContact ? std::numeric_limits<double>::infinity() : h;
    }
    if (one_pass) {
      // In one pass, with the window of the steepest top (a superset), then narrowed to the top's.
      const double s_wide = full ? std::numeric_limits<double>::infinity() : field.slope_max();
      const SphereField::Window wide{delta, s_wide, 2e-12 * r};
      const double h = field.eval_near(x, y, bx, by, work, near, wide.eps(field.slope_max()), p, &wide);
      if (h == kNoContact) return std::numeric_limits<double>::infinity();
      if (full) return h;
      const SphereField::Window w{delta, field.slope_at(bx, by), 2e-12 * r};
      if (w.s_top <= s_wide) {
        SphereField::narrow_window(*p, h, w);
        return h;
      }
      // The top off the map (slope_at: infinity, a sphere beyond the border touching its outer
      // edge sideways): a deeper window than the pass's; again with it.
      const double h2 = field.eval_near(x, y, bx, by, work, near, w.eps(field.slope_max()), p, &w);
      return h2 == kNoContact ? std::numeric_limits<double>::infinity() : h2;
    }
    double h = field.eval_near(x, y, bx, by, work, near, 0, nullptr);
    if (h != kNoContact) {
      const double s_top = full ? std::numeric_limits<double>::infinity() : field.slope_at(bx, by);
      const SphereField::Window w{delta, s_top, 2e-12 * r};
      // The deepest window: the steepest cell's.
      h = field.eval_near(x, y, bx, by, work, near, w.eps(field.slope_max()), p, &w);
    }
    return h == kNoContact ? std::numeric_limits<double>::infinity() : h;
  };
  struct State {
    double x = 0, y = 0;            // offset (m)
    double x_stop = 0, y_stop = 0;  // the last stop
  };
  enum class End { Rest, Far, Stuck };
  // The seat where a descent ended (not Far): whatever the pieces, the least-norm point P of the
  // hull of their tilted slopes cos(beta) H - sin(beta) d (H in the hull of their slopes, or of
  // their friction cones' samples) gives tan(beta) = H.d - P.d / cos(beta) <= cone + |P| /
  // cos(beta), cone the steepest slope along d of the pieces' cones (cone_max_slope: the whole
  // cone, above its samples). So every tilt at which the block rested lies at or below
  // atan(cone + |P| / cos(beta)) of that seat, by construction (ArealTiltHold::seat_bound).
  struct Seat {
    double cone = -std::numeric_limits<double>::infinity();  // tan of the bound (unitless)
    double geo = -std::numeric_limits<double>::infinity();   // steepest slope along d, no cone (unitless)
  };
  double dir_geo = 0, dir_cone = 0;
  Seat last_seat;
  // The slopes (or cone samples) of the pieces of the last direction, untilted; at a rest, the
  // tan of the tilt up to which they hold the block where it stands (ray_hull_max; NaN: none).
  std::vector<std::array<double, 2>> raw;
  // Recent directions with friction (see direction in descend): the distinct gradients of the
  // pieces, the tilt (rad), minus the direction, the cones' slopes and the steepest slopes.
  struct ConeHull {
    std::vector<std::array<double, 2>> grads;
    double beta = std::numeric_limits<double>::quiet_NaN();
    std::array<double, 2> P{};
    std::vector<std::array<double, 2>> raw;
    double geo = 0, cone = 0;
  };
  std::array<ConeHull, 4> cone_cache;
  std::size_t cone_next = 0;
  std::vector<std::array<double, 2>> grads;
  double last_tstar = std::numeric_limits<double>::quiet_NaN();
  // Nonsmooth steepest descent of V at tilt beta from st; Far once it has gone D along d from
  // its stop (check_far).
  auto descend = [&](double beta, State& st, bool check_far) {
    const double cb = std::cos(beta), sb = std::sin(beta);
    last_tstar = std::numeric_limits<double>::quiet_NaN();
    double delta = 0.05 * r;
    // The smallest step, which also bounds the window of pieces at a rest: a coplanar neighbour's
    // piece (clamped at a shared edge) enters it where its slope differs by ~sqrt(delta_min / r).
    // With friction that error holds the block (the cones' hull grows by it), so there 1e-9 r:
    // slopes within 4e-5 (docs/mujoco.md, "Atomic friction").
    const double delta_min = (phi_a > 0 ? 1e-9 : 1e-6) * r;
    // Pieces that a step of window(delta) could make the highest: deficit <= window(delta)
    // |g_i - g_best|, with |g_i - g_best| capped by each piece's cap (SphereField::Window).
    double h = 0;
    bool have = false;  // h and `pieces` hold for st and delta (from the accepted trial step)
    // With friction: whether the last iteration halved a stationary step, and the pieces the
    // halvings left out (the stalled descent, see below).
    std::vector<SphereField::Piece> gone;
    bool stalled = false;
    // A direction from the local windows that no step down to delta_min follows may have left out
    // a piece steeper than the facets around it: the rest is taken only once the full window
    // (cap 2 for every piece) finds no step either.
    bool full = false;
    // Minus the descent direction at a point of height h: the least-norm point of the hull of the
    // tilted slopes of the pieces a step of d could make the highest.
    // dir_geo, dir_cone: the steepest slope along d of those pieces, without and with their
    // friction cones (the seat's slopes where the block rests: Seat below).
    constexpr std::size_t kFewPoints = 16;
    std::vector<const SphereField::Piece*> inside;
    auto direction = [&](const std::vector<SphereField::Piece>& ps, double h, double d) {
      // The top piece: the first of the highest in Piece::before's order.
      const SphereField::Piece* top = &ps[0];
      for (const SphereField::Piece& p : ps)
        if (SphereField::Piece::before(p, *top)) top = &p;
      q.clear();
      raw.clear();
      dir_geo = dir_cone = -std::numeric_limits<double>::infinity();
      auto within = [&](const SphereField::Piece& p) {
        return h - p.value <= d * std::min(std::hypot(p.gx - top->gx, p.gy - top->gy), p.cap) + 1e-12 * r;
      };
      // The slope of a contact's force: frictionless the normal force's; with mu_a every force in
      // its Coulomb cone (docs/mujoco.md, "Atomic friction").
      auto add = [&](double gx0, double gy0) {
        dir_geo = std::max(dir_geo, gx0 * dxv + gy0 * dyv);
        dir_cone = std::max(dir_cone, cone_max_slope(gx0, gy0, dxv, dyv, phi_a));
        slopes.clear();
        if (phi_a > 0)
          cone_slopes(gx0, gy0, phi_a, kConeSamples, slopes);
        else
          slopes.push_back({gx0, gy0});
        for (const auto& sl : slopes) {
          if (t.lock_lateral) {
            const double a = sl[0] * dxv + sl[1] * dyv;
            raw.push_back({a * dxv, a * dyv});
          } else {
            raw.push_back(sl);
          }
          double gx = cb * sl[0] - sb * dxv, gy = cb * sl[1] - sb * dyv;
          if (t.lock_lateral) {
            const double a = gx * dxv + gy * dyv;
            gx = a * dxv;
            gy = a * dyv;
          }
          q.push_back({gx, gy});
        }
      };
      if (!(phi_a > 0)) {
        inside.clear();
        for (const SphereField::Piece& p : ps)
          if (within(p)) inside.push_back(&p);
        // (least_norm is cubic in the points: the hull for more than a few, the same point.) Its
        // answer depends on the order of its points in the last bits: the few in Piece::before's
        // order; the hull sorts its points itself.
        if (inside.size() <= kFewPoints)
          std::sort(inside.begin(), inside.end(), [](const SphereField::Piece* a, const SphereField::Piece* b) {
            return SphereField::Piece::before(*a, *b);
          });
        for (const SphereField::Piece* p : inside) add(p->gx, p->gy);
        return q.size() > kFewPoints ? least_norm_hull(q, true) : least_norm(q);
      }
      // With friction, the cones of the distinct gradients only: the pieces of a conforming pair
      // share a few (every sphere on one facet: 15 pieces of 3 gradients on average, matrix-5),
      // and a cone's samples depend on its gradient alone, so the hull is the same set's
      // (least_norm_hull and ray_hull_max sort and drop repeats: the same point, bit for bit).
      // A descent asks again for the same contacts at the same tilt while it halves its step or
      // creeps along a facet: the last few answers are kept, by gradients and tilt.
      grads.clear();
      for (const SphereField::Piece& p : ps)
        if (within(p)) grads.push_back({p.gx, p.gy});
      std::sort(grads.begin(), grads.end());
      grads.erase(std::unique(grads.begin(), grads.end()), grads.end());
      for (const ConeHull& c : cone_cache)
        if (c.beta == beta && c.grads == grads) {
          raw = c.raw;
          dir_geo = c.geo;
          dir_cone = c.cone;
          return c.P;
        }
      for (const auto& g : grads) add(g[0], g[1]);
      ConeHull& c = cone_cache[cone_next];
      cone_next = (cone_next + 1) % cone_cache.size();
      c = {grads, beta, least_norm_hull(q), raw, dir_geo, dir_cone};
      return c.P;
    };
    for (int it = 0; it < 200000; ++it) {
      if (!have) h = height(st.x, st.y, window(delta), &pieces, full);
      have = false;
      if (!std::isfinite(h)) {
        last_seat = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
        return End::Stuck;
      }
      const double V = h * cb - (st.x * dxv + st.y * dyv) * sb;
      const std::array<double, 2> P = direction(pieces, h, window(delta));
      const double Pn = std::hypot(P[0], P[1]);
      last_seat = {dir_cone + Pn / cb, dir_geo};
      if (Pn < stationary) {
        // Stationary for this step's pieces: at rest only if it stays so for the smallest step.
        if (delta <= delta_min) {
          last_tstar = ray_hull_max(raw, dxv, dyv);
          return End::Rest;
        }
        delta = std::max(0.5 * delta, delta_min);
        // The pieces of the smaller window are among these (no new evaluation); with friction
        // those left out are kept for the step to the contact (below).
        std::erase_if(pieces, [&](const SphereField::Piece& p) {
          const bool out = p.value < h - (window(delta) * p.cap + 2e-12 * r);
          if (out && phi_a > 0) gone.push_back(p);
          return out;
        });
        stalled = phi_a > 0;
        have = true;
        continue;
      }
      const double wx = -P[0] / Pn, wy = -P[1] / Pn;
      // With friction a descent can stall: the block is held in the window of delta (a piece
      // whose cone holds it lies at a deficit the window reaches) and not in the half window that
      // leaves that piece out, so it moves on by about delta, the piece's deficit changes by a
      // small fraction of itself, and the next step is again no longer (a 12 x 10 random map:
      // 5000 steps of 1e-8 to 1e-6 r per descent, against 35 steps without friction; 100 times
      // the frictionless cost). After such a halving the step goes instead to where the first
      // piece that is not a top becomes one along the direction w, from the pieces' linear models
      // (h rises at the largest rate of the tops, piece i at g_i.w; exact on facets), over every
      // piece a step that long could make the highest (one evaluation in that window), at most
      // kLocal r: no piece the window leaves out can become a top within it. The step is then
      // tried as any other (the decrease), and the halving goes on from it where it fails.
      if (stalled) {
        stalled = false;
        double rate = -std::numeric_limits<double>::infinity();
        for (const SphereField::Piece& p : pieces)
          if (h - p.value <= 2e-12 * r) rate = std::max(rate, p.gx * wx + p.gy * wy);
        auto reach = [&](const std::vector<SphereField::Piece>& ps) {
          double t_min = std::numeric_limits<double>::infinity();
          for (const SphereField::Piece& p : ps) {
            const double den = p.gx * wx + p.gy * wy - rate, gap = h - p.value;
            if (gap > 2e-12 * r && den > 0) t_min = std::min(t_min, gap / den);
          }
          return t_min;
        };
        double T = std::min({reach(gone), reach(pieces), kLocal * r});
        gone.clear();
        if (std::isfinite(rate) && T > delta) {
          if (height(st.x, st.y, window(T), &wide_pieces, full) == h) {
            T = std::min(T, reach(wide_pieces));
            if (T > delta) delta = T;
          }
        }
      }
      bool moved = false;
      const double delta_start = delta;
      while (delta >= delta_min) {
        const double nx = st.x + delta * wx, ny = st.y + delta * wy;
        // The trial collects the pieces of the next iteration's window (used if it is accepted).
        const double next = std::min(1.5 * delta, kMaxStep * r);
        const double h2 = height(nx, ny, window(next), &trial_pieces, full);
        // No sphere left over the lower map: the descent carries the block off its edge, where
        // nothing holds it (MuJoCo's block falls off the height field): a run-away, not a wall.
        if (h2 == std::numeric_limits<double>::infinity()) return End::Far;
        // A step longer than kLocal r is kept only where the descent has not turned along it
        // (the direction at its end within kTurn of this one's): a long step across a crease or
        // a basin's rim, narrower than r, would leave the path of steepest descent.
        bool straight = true;
        if (delta > kLocal * r && std::isfinite(h2) && !trial_pieces.empty()) {
          const std::array<double, 2> P2 = direction(trial_pieces, h2, window(next));
          const double n2 = std::hypot(P2[0], P2[1]);
          straight = n2 < stationary || -(P2[0] * wx + P2[1] * wy) >= std::cos(kTurn) * n2;
        }
        if (straight && h2 * cb - (nx * dxv + ny * dyv) * sb < V - 1e-4 * delta * Pn) {
          st.x = nx;
          st.y = ny;
          delta = next;
          h = h2;
          std::swap(pieces, trial_pieces);
          have = true;
          moved = true;
          break;
        }
        delta *= 0.5;
      }
      if (!moved) {
        if (full || !local) {
          last_tstar = std::numeric_limits<double>::quiet_NaN();  // not stationary: no seat to read
          return End::Rest;
        }
        full = true;
        delta = delta_start;
        continue;  // have is false: the pieces again, in the full window
      }
      full = false;
      if (check_far && (st.x - st.x_stop) * dxv + (st.y - st.y_stop) * dyv >= D) return End::Far;
    }
    return End::Stuck;
  };
  // Two flat faces: every contact has slope zero, so the block rests wherever it is put down and
  // is held exactly up to the tilt at which the load leaves the contacts' cones: tan(beta) d in the
  // hull of the cones' slopes (cone_slopes of slope 0; atan mu_a along a sampled direction, the
  // axes among them; 0 without friction), and at any larger tilt slides without end. The
  // protocol's answer, without its descents: each of them evaluates every sphere (all tie for
  // the max), thousands of times per drop (a 650 x 650 flat pair did not end in 600 s).
  if (field.flat()) {
    if (!std::isfinite(height(t.start_offset[0], t.start_offset[1], 0, nullptr)))
      return make_error(fmt::format("areal_tilt_hold: at the start offset ({}, {}) m no sphere lies over the lower map",
                                    t.start_offset[0], t.start_offset[1]));
    double tan_hold = 0;
    if (phi_a > 0) {
      std::vector<std::array<double, 2>> cone;
      cone_slopes(0, 0, phi_a, kConeSamples, cone);
      if (t.lock_lateral)
        for (auto& c : cone) {
          const double a = c[0] * dxv + c[1] * dyv;
          c = {a * dxv, a * dyv};
        }
      tan_hold = std::max(0.0, ray_hull_max(cone, dxv, dyv));
    }
    out.rest_offset = t.start_offset;
    out.hold_angle = std::min(std::max(std::atan(tan_hold), start_tilt), t.max_tilt);
    out.ran_away = out.hold_angle < t.max_tilt;
    out.runaway_increment = out.hold_angle;
    out.seat_slope = 0;
    out.seat_bound = std::max(out.hold_angle, std::atan(cone_max_slope(0, 0, dxv, dyv, phi_a)));
    out.stops.push_back({out.hold_angle, t.start_offset[0] + (out.ran_away ? D * dxv : 0),
                         t.start_offset[1] + (out.ran_away ? D * dyv : 0)});
    out.work = near.work + long(work);
    return out;
  }
  // Every descent that did not run away: its seat and tilt (the seat bound's inputs).
  Seat seats;
  double held_tilt = -std::numeric_limits<double>::infinity();
  auto held = [&](End e, double beta) {
    if (e == End::Far) return e;
    seats.cone = std::max(seats.cone, last_seat.cone);
    seats.geo = std::max(seats.geo, last_seat.geo);
    held_tilt = std::max(held_tilt, beta);
    return e;
  };
  State st;
  st.x = t.start_offset[0];
  st.y = t.start_offset[1];
  if (!std::isfinite(height(st.x, st.y, 0, nullptr)))
    return make_error(
        fmt::format("areal_tilt_hold: at the start offset ({}, {}) m no sphere lies over the lower map", st.x, st.y));
  held(descend(start_tilt, st, false), start_tilt);
  double tstar = last_tstar;  // the seat's run-away tan at `before` (run)
  st.x_stop = st.x;
  st.y_stop = st.y;
  out.rest_offset = {st.x, st.y};
  // Increments from `from` at beta0; returns the run-away increment (NaN: none) and leaves in
  // `before` the state at the increment before it.
  auto run = [&](State from, double beta0, double step, State& before, double& beta_before) {
    State s = from;
    before = from;
    beta_before = beta0;
    for (double beta = beta0 + step; beta <= t.max_tilt + 1e-12; beta += step) {
      State trial = s;
      const End e = held(descend(beta, trial, true), beta);
      out.stops.push_back({beta, trial.x, trial.y});
      if (reached) reached(beta);
      if (e == End::Far) return beta;
      trial.x_stop = trial.x;  // a stop (Rest) or a block that did not settle: either way the next
      trial.y_stop = trial.y;  // increment starts from here, as in areal_tilt
      s = trial;
      before = s;
      beta_before = beta;
      tstar = last_tstar;
    }
    return std::numeric_limits<double>::quiet_NaN();
  };
  State before;
  double beta_before = 0;
  const double coarse = std::max(t.coarse_tilt_step, t.tilt_step);
  double b = run(st, start_tilt, coarse, before, beta_before);
  if (!std::isnan(b) && coarse > t.tilt_step) b = run(before, beta_before, t.tilt_step, before, beta_before);
  // The seat bound: above every tilt that held (by construction, Seat), and above the hold angle
  // reported, which lies at most the last bracket above the highest tilt that held.
  auto finish_seats = [&] {
    out.seat_bound = std::min(std::atan(seats.cone) + std::max(0.0, out.hold_angle - held_tilt), std::numbers::pi / 2);
    out.seat_slope = std::atan(seats.geo);
    out.work = near.work + long(work);
  };
  if (std::isnan(b)) {
    out.hold_angle = out.runaway_increment = t.max_tilt;
    finish_seats();
    return out;
  }
  out.ran_away = true;
  out.runaway_increment = b;
  // Bisect the run-away tilt between the increment before and b, from the state before.
  double lo = beta_before, hi = b;
  State at_hi;
  bool have_hi = false;
  // First the tilt up to which the seat's own contacts hold the block where it stands (ray_hull_max
  // at its rest), a quarter of the resolution above it: where the block still rests (it crept in
  // its seat, on an edge or vertex contact whose slope changes as it moves), the reading at that
  // rest is the next guess (a fixed-point iteration on the seat) while it rises; where it runs
  // away, a quarter below closes the bracket. Then from the highest tilt that held, steps of 4, 16,
  // 64, ... resolutions up to the first run-away. A few descents, most of them rests, instead of
  // a bisection's eleven, half of them run-aways (each a slide of D). What is left is bisected: lo
  // always held, hi always ran away, as in the bisection alone.
  auto probe = [&](double beta) {
    State trial = before;
    const End e = held(descend(beta, trial, true), beta);
    if (reached) reached(beta);
    if (e == End::Far) {
      hi = beta;
      at_hi = trial;
      have_hi = true;
      return true;
    }
    lo = beta;
    return false;
  };
  bool bracketed = false;
  for (int k = 0; k < kSeatGuesses && std::isfinite(tstar) && hi - lo > resolution; ++k) {
    const double up = std::atan(tstar) + 0.25 * resolution;
    if (!(up > lo && up < hi)) break;
    if (probe(up)) {
      if (up - 0.5 * resolution > lo) probe(up - 0.5 * resolution);
      bracketed = true;
      break;
    }
    tstar = last_tstar;
  }
  for (double step = 4 * resolution; !bracketed && lo + step < hi && step < 0.25 * (hi - lo); step *= 4)
    bracketed = probe(lo + step);
  while (hi - lo > resolution) {
    const double mid = 0.5 * (lo + hi);
    State trial = before;
    const End e = held(descend(mid, trial, true), mid);
    if (reached) reached(mid);
    if (e == End::Far) {
      hi = mid;
      at_hi = trial;
      have_hi = true;
    } else {
      lo = mid;
    }
  }
  if (!have_hi) {
    at_hi = before;
    held(descend(b, at_hi, true), b);
  }
  out.hold_angle = hi;
  finish_seats();
  out.steering = std::atan2(-(at_hi.x - before.x_stop) * dyv + (at_hi.y - before.y_stop) * dxv,
                            (at_hi.x - before.x_stop) * dxv + (at_hi.y - before.y_stop) * dyv);
  return out;
}

}  // namespace

namespace {

// The hold of one drop in the frame where the direction lies within 45 deg of +x
// (detail::TurnedExperiment); inputs checked.
Result<ArealTiltHold> hold_turned(const Map& f, const Map& g, const MapHoldOptions& t, double resolution,
                                  double stationary, double start_tilt) {
  const std::vector<detail::TiltNode> nodes = detail::tilt_nodes(f, g, t.angle, t.turn_over_upper);
  if (nodes.empty()) return make_error("areal_tilt_hold: the upper map has no valid node");
  const detail::Hfield hf = detail::tilt_hfield(f, std::size_t(t.hfield_refine));
  const double r = detail::tilt_sphere_radius(f, t);
  const SphereField field(nodes, hf, r);
  return hold_on_field(field, f, t, r, resolution, stationary, start_tilt);
}

// A hold's positions turned back to the caller's frame.
void turn_back(ArealTiltHold& h, const detail::TurnedExperiment<MapHoldOptions>& e) {
  h.rest_offset = e.back(h.rest_offset);
  for (auto& s : h.stops) {
    const auto p = e.back({s[1], s[2]});
    s[1] = p[0];
    s[2] = p[1];
  }
}

Result<std::vector<ArealTiltHold>> hold_drops_turned(const Map& f, const Map& g, const MapHoldOptions& t,
                                                     const std::vector<ArealTiltDrop>& drops, unsigned threads,
                                                     const DropProgressFn& progress) {
  const std::vector<detail::TiltNode> nodes = detail::tilt_nodes(f, g, t.angle, t.turn_over_upper);
  if (nodes.empty()) return make_error("areal_tilt_hold: the upper map has no valid node");
  const detail::Hfield hf = detail::tilt_hfield(f, std::size_t(t.hfield_refine));
  const double r = detail::tilt_sphere_radius(f, t);
  const SphereField field(nodes, hf, r);  // shared (read-only) by every drop
  std::vector<ArealTiltHold> out(drops.size());
  std::vector<std::string> errors(drops.size());
  // Each thread takes the next drop not yet taken (drops differ in cost by several times: halves
  // of the grid left one thread idle for up to a tenth of the run); every drop is computed alone,
  // so the results do not depend on the order.
  const unsigned nthreads = util::thread_count(threads, drops.size());
  std::atomic<std::size_t> next{0};
  // The progress: the drops finished, and the tilt of the drop each thread has under way (NaN:
  // none), one slot per thread, so that a report reads the threads, not every drop.
  std::mutex m;
  std::size_t done = 0;
  std::vector<double> reached(nthreads, std::numeric_limits<double>::quiet_NaN());
  auto report = [&](unsigned worker, double tilt, bool finished) {
    std::lock_guard<std::mutex> lock(m);
    reached[worker] = finished ? std::numeric_limits<double>::quiet_NaN() : tilt;
    if (finished) ++done;
    DropProgress p;
    p.done = done;
    p.total = drops.size();
    for (double b : reached)
      if (!std::isnan(b)) {
        ++p.running;
        p.tilt = std::isnan(p.tilt) ? b : std::min(p.tilt, b);
      }
    progress(p);
  };
  util::parallel_chunks(nthreads, nthreads, [&](unsigned worker, std::size_t, std::size_t) {
    const std::function<void(double)> at = [&, worker](double tilt) { report(worker, tilt, false); };
    for (std::size_t k = next++; k < drops.size(); k = next++) {
      MapHoldOptions tk = t;
      tk.start_offset = drops[k].start;
      tk.lock_lateral = drops[k].locked;
      if (progress) report(worker, 0, false);
      auto h = hold_on_field(field, f, tk, r, kArealHoldResolution, 1e-7, 0, progress ? at : nullptr);
      if (h)
        out[k] = std::move(h).value();
      else
        errors[k] = "#" + std::to_string(k) + ": " + h.error().message;
      if (progress) report(worker, 0, true);
    }
  });
  for (std::size_t k = 0; k < drops.size(); ++k)
    if (!errors[k].empty()) return make_error(std::move(errors[k]));
  return out;
}

}  // namespace

Result<ArealTiltHold> areal_tilt_hold(const Map& f, const Map& g, const MapHoldOptions& t, double resolution,
                                      double stationary, double start_tilt) {
  if (auto s = check_hold_inputs(f, g, t, resolution, stationary, start_tilt); !s) return s.error();
  const detail::TurnedExperiment e(f, g, t);
  auto h = hold_turned(e.f, e.g, e.t, resolution, stationary, start_tilt);
  if (h) turn_back(*h, e);
  return h;
}

Result<std::vector<ArealTiltHold>> areal_tilt_hold_drops(const Map& f, const Map& g, const MapHoldOptions& t,
                                                         const std::vector<ArealTiltDrop>& drops, unsigned threads,
                                                         const DropProgressFn& progress) {
  if (auto s = check_hold_inputs(f, g, t, kArealHoldResolution, 1e-7, 0); !s) return s.error();
  auto named = [&](Result<std::vector<ArealTiltHold>> r) -> Result<std::vector<ArealTiltHold>> {
    if (r) return r;
    // The failing drop named by its start offset in the caller's frame.
    for (std::size_t k = 0; k < drops.size(); ++k)
      if (r.error().message.rfind("#" + std::to_string(k) + ":", 0) == 0)
        return make_error(fmt::format("drop at ({:.6g}, {:.6g}) m: {}", drops[k].start[0], drops[k].start[1],
                                      r.error().message.substr(r.error().message.find(':') + 2)));
    return r;
  };
  const detail::TurnedExperiment e(f, g, t);
  std::vector<ArealTiltDrop> td = drops;
  for (ArealTiltDrop& d : td) d.start = detail::turned(d.start, -e.q);
  auto r = named(hold_drops_turned(e.f, e.g, e.t, td, threads, progress));
  if (r)
    for (ArealTiltHold& h : *r) turn_back(h, e);
  return r;
}

Result<ArealTiltHoldSpread> areal_tilt_hold_spread(const Map& f, const Map& g, const MapHoldOptions& t,
                                                   const ArealTiltHold& hold, double perturbation, double resolution,
                                                   double stationary) {
  if (!std::isfinite(perturbation) || perturbation < 0)
    return make_error(fmt::format(
        "areal_tilt_hold_spread: perturbation {}: expected a finite distance >= 0 (m; 0: the sphere radius)",
        perturbation));
  const double r = detail::tilt_sphere_radius(f, t);
  const double delta = perturbation > 0 ? perturbation : r;
  const double same = 0.1 * r;  // two stops closer than this are one seat
  const double dxv = std::cos(t.angle), dyv = std::sin(t.angle);
  const double D = detail::tilt_runaway_distance(f, t);
  ArealTiltHoldSpread out;
  out.low = out.high = hold.hold_angle;
  // The chain of stops that leads to the run-away: the coarse increments up to the one before
  // the coarse run-away, then the fine ones (the tilt falls where they begin) but their last
  // (the run-away itself).
  struct Slip {
    double tilt, x, y;
    bool coarse;
  };
  std::vector<Slip> slips;
  const auto& st = hold.stops;
  std::size_t fine = st.size();
  for (std::size_t i = 1; i < st.size(); ++i)
    if (st[i][0] < st[i - 1][0]) {
      fine = i;
      break;
    }
  const std::size_t last = hold.ran_away ? st.size() - 1 : st.size();  // the run-away increment
  std::array<double, 2> prev = hold.rest_offset;
  for (std::size_t i = 0; i < last; ++i) {
    if (fine < st.size() && i + 1 == fine) continue;  // the coarse run-away: not a seat
    if (i == fine) {
      // The fine chain starts from the coarse stop before the coarse run-away.
      prev = fine >= 2 ? std::array<double, 2>{st[fine - 2][1], st[fine - 2][2]} : hold.rest_offset;
    }
    if (std::hypot(st[i][1] - prev[0], st[i][2] - prev[1]) > same)
      slips.push_back({st[i][0], st[i][1], st[i][2], i < fine});
    prev = {st[i][1], st[i][2]};
  }
  out.slips = int(slips.size());
  std::vector<std::array<double, 2>> dirs;
  if (t.lock_lateral) {
    dirs = {{dxv, dyv}, {-dxv, -dyv}};
  } else {
    for (int k = 0; k < 8; ++k)
      dirs.push_back({std::cos(k * std::numbers::pi / 4), std::sin(k * std::numbers::pi / 4)});
  }
  for (const Slip& s : slips) {
    std::vector<std::array<double, 2>> seats;  // other seats found from this slip's end
    for (const auto& e : dirs) {
      MapHoldOptions c = t;
      c.start_offset = {s.x + delta * e[0], s.y + delta * e[1]};
      if (!s.coarse) c.coarse_tilt_step = t.tilt_step;
      // The seat from the perturbed end: one descent at the slip's tilt (a hold with no increment).
      MapHoldOptions probe = c;
      probe.max_tilt = std::min(s.tilt + 0.5 * t.tilt_step, std::numbers::pi / 2 - 1e-9);
      auto seat = areal_tilt_hold(f, g, probe, resolution, stationary, s.tilt);
      if (!seat) continue;  // the perturbed end lies off the lower map
      out.evaluations += seat->evaluations;
      const auto& rest = seat->rest_offset;
      if (std::hypot(rest[0] - s.x, rest[1] - s.y) <= same) continue;
      bool known = false;
      for (const auto& k : seats) known = known || std::hypot(rest[0] - k[0], rest[1] - k[1]) <= same;
      if (known) continue;
      seats.push_back(rest);
      if ((rest[0] - s.x) * dxv + (rest[1] - s.y) * dyv >= D) {  // slid D from its stop: a run-away
        out.low = std::min(out.low, s.tilt);
        out.high = std::max(out.high, s.tilt);
        continue;
      }
      c.start_offset = rest;
      auto h = areal_tilt_hold(f, g, c, resolution, stationary, s.tilt);
      if (!h) return h.error();
      out.evaluations += h->evaluations;
      ++out.continuations;
      out.low = std::min(out.low, h->hold_angle);
      out.high = std::max(out.high, h->hold_angle);
    }
    out.ambiguous += !seats.empty();
  }
  return out;
}

DefaultRunaway default_map_runaway_distance(const Map& lower, double direction) {
  // Lines along the grid axis nearer to the direction: up to 32, evenly spaced; each line's
  // longest run of valid points (at least 16) is a profile.
  const bool along_x = std::abs(std::cos(direction)) >= std::abs(std::sin(direction));
  const std::size_t lines = along_x ? lower.ny : lower.nx, len = along_x ? lower.nx : lower.ny;
  const double h = along_x ? lower.dx : lower.dy;
  const std::size_t used = std::min<std::size_t>(lines, 32);
  std::vector<double> xi;
  for (std::size_t k = 0; k < used; ++k) {
    const std::size_t line = used > 1 ? k * (lines - 1) / (used - 1) : 0;
    auto z = [&](std::size_t i) { return along_x ? lower.at(i, line) : lower.at(line, i); };
    std::size_t best0 = 0, best1 = 0;
    for (std::size_t i = 0; i < len;) {
      if (!std::isfinite(z(i))) {
        ++i;
        continue;
      }
      std::size_t j = i;
      while (j < len && std::isfinite(z(j))) ++j;
      if (j - i > best1 - best0) best0 = i, best1 = j;
      i = j;
    }
    if (best1 - best0 < 16) continue;
    Profile p;
    for (std::size_t i = best0; i < best1; ++i) p.x.push_back(double(i) * h), p.z.push_back(z(i));
    const double l = slope_correlation_length(p);
    if (l > 0) xi.push_back(l);
  }
  DefaultRunaway t;
  const char* axis = along_x ? "x" : "y";
  if (xi.empty()) {
    t.distance = kRunawayPerSlopeCorrelation * h;
    t.rule = fmt::format("{:g} spacings of the lower map along {} ({:.4g} m; its slopes have no correlation length)",
                         kRunawayPerSlopeCorrelation, axis, h);
    return t;
  }
  std::nth_element(xi.begin(), xi.begin() + std::ptrdiff_t(xi.size() / 2), xi.end());
  const double l = std::max(xi[xi.size() / 2], h);
  t.distance = kRunawayPerSlopeCorrelation * l;
  t.rule = fmt::format("{:g} slope correlation lengths of the lower map along {} ({:.4g} m, the median over {} lines)",
                       kRunawayPerSlopeCorrelation, axis, l, xi.size());
  return t;
}

void fill_map_model_defaults(const Map& lower, MapHoldOptions& t) {
  if (!(t.runaway_distance > 0)) t.runaway_distance = default_map_runaway_distance(lower, t.angle).distance;
  if (!(t.sphere_radius > 0)) t.sphere_radius = 0.2 * std::min(lower.dx, lower.dy);
}

}  // namespace frictal
