// Private: a profile prepared for fast signature evaluation.
//
// A Face stores the values to maximise, v = z for the lower surface and v = -z for the upper
// one, so that h(s) = max_x [vF(x) + vG(x - s)]. Evaluation takes the supremum of v at a
// vertical jump. Block maxima with a sparse table give O(1) upper bounds of v over any index
// range, which drive the branch-and-bound search of the maximum.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace frictal::detail {

inline constexpr std::size_t kBlock = 32;
inline constexpr unsigned kBlockShift = 5;  // kBlock = 1 << kBlockShift

/// Maxima of v over aligned nodes: level l holds the max over points [q << (5 + l), (q + 1) << (5 + l))
/// (a segment tree over blocks of 32 points). About N/16 values in all, so the levels that a
/// search touches stay in cache even at 10^7 points.
class AlignedMax {
 public:
  AlignedMax() = default;
  explicit AlignedMax(const std::vector<double>& v);
  const std::vector<double>& level(std::size_t l) const { return lv_[l]; }
  std::size_t levels() const { return lv_.size(); }

 private:
  std::vector<std::vector<double>> lv_;
};

/// Upper bounding lines of v over the same aligned nodes as AlignedMax: for every point i of node
/// q at level l (start = q << (5 + l)), v[i] <= c + tau * (i - start) in exact arithmetic (the
/// rounding of the construction is covered by a margin added to c). tau is the node's chord, so
/// on a profile that is smooth at the node's scale the line follows the local trend and lies
/// above v by about the curvature times the node length squared, where the node's plain maximum
/// lies above v at the node's ends by the slope times its length. Levels above 0 are derived from
/// their children's lines (O(1) per node), so the whole structure costs one pass over v.
class TiltedMax {
 public:
  struct Line {
    double tau = 0;  ///< slope per point index (unit: m)
    double c = 0;    ///< value of the line at the node's first point (unit: m)
  };
  TiltedMax() = default;
  explicit TiltedMax(const std::vector<double>& v);
  const std::vector<Line>& level(std::size_t l) const { return lv_[l]; }
  std::size_t levels() const { return lv_.size(); }
  bool empty() const { return lv_.empty(); }
  /// max over nodes of |c| + |tau| (node length): every term of an evaluation of a line on its
  /// node is at most this (unit: m), the scale of the rounding margin of the bound.
  double magnitude() const { return mag_; }

 private:
  std::vector<std::vector<Line>> lv_;
  double mag_ = 0;
};

/// Where an abscissa falls on a face: on a vertex group [first, last] or inside edge `edge`.
struct Position {
  bool vertex = false;
  std::size_t first = 0, last = 0;  // vertex group (if vertex)
  std::size_t edge = 0;             // edge index e: between points e and e+1 (if !vertex)
};

class Face {
 public:
  Face() = default;
  /// x non-decreasing (groups of equal x are jumps), z heights, sign +1 (lower) or -1 (upper).
  Face(std::vector<double> x, const std::vector<double>& z, double sign);
  /// The same, taking z over (its storage becomes v).
  Face(std::vector<double> x, std::vector<double>&& z, double sign);

  std::size_t size() const { return x_.size(); }
  const std::vector<double>& x() const { return x_; }
  const std::vector<double>& v() const { return v_; }
  double sign() const { return sign_; }
  double x_front() const { return x_.front(); }
  double x_back() const { return x_.back(); }
  double vmax() const { return vmax_; }
  double vmin() const { return vmin_; }

  /// Index of the last point with x <= u (0 if u < x_front).
  std::size_t floor_index(double u) const;
  /// Index of the first point with x >= u (size-1 if u > x_back).
  std::size_t ceil_index(double u) const;
  /// sup of v at u (u within [x_front, x_back]); u within `xtol` of a vertex group counts as on
  /// it (the group's sup), else v is interpolated along the edge.
  double value(double u, double xtol = 0) const;
  /// Where a run of value_walk() calls stands: lower bounds of lower_bound(x, u - xtol) and of
  /// lower_bound(x, u) for every later, not smaller, u.
  struct Cursor {
    static constexpr std::size_t kUnset = static_cast<std::size_t>(-1);
    std::size_t tol = kUnset, at = kUnset;
  };
  /// value(u, xtol) for non-decreasing u across calls with one cursor (a fresh cursor for each
  /// run): the same indices as ceil_index(), found by walking forward from the last ones instead
  /// of a binary search each, hence the same value as value(u, xtol).
  double value_walk(double u, double xtol, Cursor& c) const;
  /// Upper bound of v over the points with index in [i0, i1].
  double range_max(std::size_t i0, std::size_t i1) const;
  /// Upper bound of v over abscissae [u0, u1] (u0 <= u1), including the bracketing points.
  double range_max_x(double u0, double u1) const { return range_max(floor_index(u0), ceil_index(u1)); }
  /// Position of u; `xtol` is the distance under which u counts as on a vertex.
  Position locate(double u, double xtol) const;
  /// Slope angle of edge e in the lower frame (z, not v), radians; NaN if e is out of range.
  double edge_angle(std::ptrdiff_t e) const;
  /// Lower-frame height of point i.
  double z(std::size_t i) const { return sign_ * v_[i]; }
  /// Max of v over a vertex group.
  double group_max(std::size_t first, std::size_t last) const {
    double m = v_[first];
    for (std::size_t k = first + 1; k <= last; ++k) m = std::max(m, v_[k]);
    return m;
  }
  bool uniform() const { return uniform_; }
  /// Uniform grids: the spacing (unit: m) and how far a point may lie from x_front + i spacing
  /// and still count as uniform (unit: m).
  double spacing() const { return dx_; }
  double grid_tolerance() const { return grid_tol_; }
  /// Aligned block maxima (levels of 32 << l points).
  const AlignedMax& aligned_max() const { return tree_; }
  /// Frees the sparse table (about 19 N / 32 values at 10^7 points); range_max then reads the
  /// aligned maxima instead: the same values, O(log N) reads instead of 2.
  void drop_sparse_table() { std::vector<std::vector<double>>().swap(st_); }
  /// Builds the tilted bounding lines (N/16 lines); only the aligned index search uses them.
  void build_tilted() { tilted_ = TiltedMax(v_); }
  const TiltedMax& tilted_max() const { return tilted_; }

 private:
  void build();
  /// ceil_index(u) from a lower bound `k` of lower_bound(x, u) (advanced to lower_bound; kUnset:
  /// found directly, O(1) on a uniform grid).
  std::size_t ceil_from(double u, std::size_t& k) const;
  std::vector<double> x_, v_;
  double sign_ = 1;
  double vmax_ = 0, vmin_ = 0;
  bool uniform_ = false;
  double dx_ = 0, inv_dx_ = 0, grid_tol_ = 0;
  std::vector<std::vector<double>> st_;  // sparse table over block maxima
  AlignedMax tree_;
  TiltedMax tilted_;
};

}  // namespace frictal::detail
