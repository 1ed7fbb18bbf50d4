// frictal — private working memory of the spheropolygon engine (not installed).
//
// Everything step() keeps between calls only to avoid recomputing or reallocating it: cached
// rotations, the poses of the last list build and of the last full pass, the vertex slots of the
// neighbour list, the hot list, and the scratch buffers of the list builder and the contact
// passes. None of it is physical state (that is dem::State); it is owned by the State through
// dem::StateWorkspace and copied with it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "frictal/dem.hpp"
#include "util/team.hpp"

namespace frictal::dem::detail {

/// cos and sin of a body's angle.
struct Rotation {
  double c = 1;
  double s = 0;
};

/// Pose of a body for the contact passes: centroid (unit: m) and cos / sin of its angle.
struct Pose {
  double px, py, c, s;
};

/// Indices of a list pair's vertex and edge ends in Workspace::active_vertex (parallel to
/// State::pairs).
struct PairSlots {
  std::uint32_t vertex = 0;
  std::uint32_t edge0 = 0;
  std::uint32_t edge1 = 0;
};

/// One touching pair in the contact passes: its geometry from the distance pass, then its force,
/// torques and mode-matrix terms from the force pass.
struct ContactScratch {
  std::uint32_t pair = 0;  ///< index in State::pairs
  double sx = 0, sy = 0, dist2 = 0, dx = 0, dy = 0, vx = 0, vy = 0;
  double t = 0;  ///< where the closest point lies on the edge, in [0, 1] (0, 1: at its ends)
  /// +1; -1 for the vertex-vertex term that rule `closest` subtracts at a concave corner of the
  /// edge's body (inclusion-exclusion of the two flanks' bands, docs/dem.md sec. 1): its normal
  /// force (spring and dashpot) counts against the body, it has no tangential force, and it is
  /// not a contact (counts, stability modes).
  double weight = 1;
  double fx = 0, fy = 0, torque_a = 0, torque_b = 0, nx = 0, ny = 0, jt_a = 0, jt_b = 0, mred = 0;
  double jtt_a = 0, jtt_b = 0;  ///< r x t of each body (unit: m)
  double energy = 0;            ///< k_n overlap^2 / 2 + k_t xi^2 / 2 (unit: J), summed in list order
  /// Hertz law: the tangent normal stiffness k (unit: N/m), the dashpot 2 zeta sqrt(m k) (unit:
  /// kg/s) and the tangential stiffness (unit: N/m), the mode sums' weights.
  double k_normal = 0, damping = 0, k_tangential = 0;
};

/// A run of touching pairs in Workspace::touching: [begin, begin + count). One segment in a
/// serial step; one per team member in a parallel one (member j's share of the hot list, in
/// list order), walked in order by the sums.
struct Segment {
  std::size_t begin = 0;
  std::size_t count = 0;
};

/// The worker team of a State (docs/dem.md sec. 7, threads): started at the first step that
/// splits its contact passes, joined with the workspace. A copy starts without one (it starts its
/// own when it needs it): a team serves one State.
struct TeamSlot {
  std::unique_ptr<util::Team> team;
  TeamSlot() = default;
  TeamSlot(const TeamSlot&) {}
  TeamSlot& operator=(const TeamSlot&) { return *this; }
  TeamSlot(TeamSlot&&) noexcept = default;
  TeamSlot& operator=(TeamSlot&&) noexcept = default;
};

/// Sums over a body's contacts of J J^T with J = (n_x, n_y, r x n): unweighted (g) and weighted
/// by the reduced mass (gm); and of J_t J_t^T with J_t = (t_x, t_y, r x t) (gt, implicit damping
/// with tangential springs only). Symmetric 3x3, stored xx, xy, xt, yy, yt, tt.
struct ModeSums {
  double g[6] = {0, 0, 0, 0, 0, 0};
  double gm[6] = {0, 0, 0, 0, 0, 0};
  double gt[6] = {0, 0, 0, 0, 0, 0};
  double mred_min = std::numeric_limits<double>::infinity();  ///< smallest reduced mass (unit: kg)
};

/// Hot list inside the neighbour list: the list pairs closer than r1 + r2 + hot_skin at the last
/// full pass over the list (poses `position` / `angle`). Until the relative motion of the bodies
/// since then exceeds hot_skin / 2, the other pairs cannot touch and only these are evaluated.
/// Per hot pair: the vertex in its body's frame and the edge in the edge body's frame (constants
/// of the rigid bodies), for a filter pass that needs no world coordinates. Invalidated by every
/// list rebuild.
struct HotList {
  std::vector<std::uint32_t> pair;                 ///< indices into State::pairs, ascending
  std::vector<double> vx, vy;                      ///< vertex, its body's frame (unit: m)
  std::vector<double> e0x, e0y, e1x, e1y, dx, dy;  ///< edge ends and edge vector, the edge body's frame (unit: m)
  std::vector<double> inv_len2;                    ///< 1 / |edge|^2 (unit: 1/m^2)
  std::vector<double> cut2;                        ///< filter radius squared, ((r1 + r2)(1 + 1e-3))^2 (unit: m^2)
  std::vector<std::uint32_t> run_begin;  ///< runs of equal (vertex body, edge body): [run_begin[r], run_begin[r+1])
  std::vector<std::uint32_t> run_vbody, run_ebody;
  std::vector<unsigned char> keep;  ///< filter result per hot pair
  std::vector<Vec2> position;       ///< poses at the last full pass (unit: m, rad)
  std::vector<double> angle;
  std::vector<Rotation> rotation;
  bool valid = false;
};

struct Workspace {
  /// cos and sin of State::angle, refreshed by step() after each drift.
  std::vector<Rotation> rotation;

  // Neighbour list (neighbor_list.cpp).
  std::vector<Vec2> list_position;  ///< poses at the last list build (unit: m)
  std::vector<double> list_angle;   ///< (unit: rad)
  std::vector<Rotation> list_rotation;
  /// Vertices referenced by the list (global ids, ascending); their world positions are computed
  /// once per full pass into active_x / active_y, so a vertex shared by several pairs costs one
  /// transform.
  std::vector<std::uint32_t> active_vertex;
  std::vector<double> active_x, active_y;  ///< (unit: m)
  std::vector<PairSlots> slots;            ///< per list pair
  // List builder scratch (kept to avoid reallocating).
  std::vector<double> world_x, world_y;                ///< every vertex's world position (unit: m)
  std::vector<double> box_x0, box_x1, box_y0, box_y1;  ///< per body (unit: m)
  std::vector<std::uint32_t> edges, verts;             ///< candidates of one body pair
  std::vector<std::uint32_t> cells;
  std::vector<std::uint32_t> items;
  std::vector<NeighborPair> new_pairs;
  std::vector<std::uint32_t> slot_of_vertex;

  // Contact passes (contact_geometry.cpp, force_law.cpp, stability.cpp).
  HotList hot;                           ///< pairs that can touch before the next full pass (docs/dem.md sec. 2)
  std::vector<Pose> pose;                ///< per body, at the current step
  std::vector<double> inv_mass;          ///< per body, 0 for kinematic bodies (unit: 1/kg)
  std::vector<int> body_contacts;        ///< per body, touching pairs
  std::vector<ModeSums> modes;           ///< per body, for the stability limit
  std::vector<ContactScratch> touching;  ///< grown, never shrunk
  std::size_t touching_count = 0;        ///< touching pairs in `touching`
  std::vector<Segment> segments;         ///< where they are in `touching`, in list order
  std::vector<std::uint32_t> closest_dropped_by;  ///< ContactRule::Closest: the kept pair that drops a touching pair
  std::vector<std::uint32_t> closest_order;       ///< ContactRule::Closest: touching pairs, deepest first

  // Threads (dem::set_thread_count).
  unsigned threads = 1;  ///< threads the contact passes may use
  /// Hot pairs per thread below which a step stays serial (a share must outweigh the team's
  /// start and join, ~1 us; speed only).
  unsigned min_hot_pairs_per_thread = 64;
  TeamSlot team;
  std::vector<double> part_max_overlap, part_max_ratio;  ///< per team member
  /// Whether splitting pays on this machine now (speed only; results do not depend on it): the
  /// contact passes of the steps that can be split are timed over kTrialSteps serial steps, then
  /// kTrialSteps split ones, twice, and the steps are split for the next kRunSteps only if both
  /// split windows were at least 5 % faster than the serial window before them (a preemption in
  /// one window does not decide it). A loaded machine, where a split step waits for a
  /// descheduled worker, thus keeps the serial passes; a split window that is already twice as
  /// slow as its serial one ends the trial at once, and each serial verdict in a row doubles the
  /// next run (up to kMaxRunSteps), so that the trials cost little where splitting never pays.
  struct Tuner {
    static constexpr std::uint32_t kTrialSteps = 64, kRunSteps = 16384, kMaxRunSteps = 1u << 20;
    bool enabled = true;
    int phase = 0;  ///< 0, 2: timing serial steps; 1, 3: timing split steps; 4: running the choice
    std::uint32_t left = kTrialSteps;
    std::uint32_t run_steps = kRunSteps;  ///< length of the next run
    double seconds[4] = {0, 0, 0, 0};
    bool split = true;
  } tuner;
};

}  // namespace frictal::dem::detail
