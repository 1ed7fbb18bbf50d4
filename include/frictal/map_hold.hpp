// frictal — the map model: the rigid, quasi-static block of two areal maps that predict() reads
// for maps (the hold angle over drops, the block free to move sideways) and that the 3D tilt test
// on MuJoCo (areal_tilt.hpp) checks on the same surfaces. The upper block's face is its map's
// nodes swept by spheres of radius r, the lower block's face the lower map's height field, each
// cell split along its diagonal from (i, j) to (i+1, j+1) as MuJoCo triangulates it (one surface
// definition for the model and the simulation, docs/mujoco.md). The lift over the offset grid
// (areal_tilt_lift), the hold angle off the grid from one drop (areal_tilt_hold) or from many on
// one shared field (areal_tilt_hold_drops), its conditioning (areal_tilt_hold_spread) and the
// default run-away distance (default_map_runaway_distance). A model below predict: it needs no
// MuJoCo and knows no experiment. Lengths in m, angles in rad.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "frictal/areal.hpp"
#include "frictal/map.hpp"
#include "frictal/result.hpp"

namespace frictal {

/// The map model's settings: the stated test (direction, run-away distance, mu_a), the surfaces
/// (sphere radius, height field, turned over or in place), the drop and the tilt protocol. The 3D
/// tilt test's settings (ArealTiltOptions, areal_tilt.hpp) are these and the simulation's.
struct MapHoldOptions {
  double angle = 0;             ///< sliding direction d, from +x towards +y (unit: rad)
  bool turn_over_upper = true;  ///< false: the upper map is the upper face in place (areal.hpp)
  /// D (unit: m); 0: a twentieth of the lower map along d here; the front ends and predict() set
  /// it from default_map_runaway_distance (fill_map_model_defaults; map_model_options in predict.hpp).
  double runaway_distance = 0;
  double atomic_friction = 0;  ///< mu_a >= 0 at every contact (unitless)
  /// Sphere radius r of the upper face's nodes (0: a fifth of the lower map's smaller spacing) (unit: m).
  double sphere_radius = 0;
  /// The height field samples the lower map's bilinear surface this many times finer than its
  /// grid (1: the map's nodes; MuJoCo triangulates every cell along one diagonal) (unitless).
  int hfield_refine = 1;
  /// true: the block slides along d only (in the simulation a slide joint along d and one along
  /// z): the locked block of areal_locked_hold_angle, on the line through the start offset.
  bool lock_lateral = false;
  std::array<double, 2> start_offset = {0, 0};       ///< where the block is put down, (x, y) (unit: m)
  double tilt_step = 0.1 * 3.141592653589793 / 180;  ///< tilt increment near the run-away (unit: rad)
  /// Coarse increments up to the first run-away, which is then tilted again in tilt_step from the
  /// state at rest one coarse increment before (unit: rad).
  double coarse_tilt_step = 1.0 * 3.141592653589793 / 180;
  double max_tilt = 45 * 3.141592653589793 / 180;  ///< give up above this tilt (unit: rad)
};

/// The map model's lift, rigid: the surfaces that areal_tilt simulates (its matched prediction).
/// The upper face's spheres of radius r (t.sphere_radius, its default; turned over as
/// t.turn_over_upper) on the lower face's height field (t.hfield_refine) as MuJoCo 2.2.2
/// triangulates it: every cell (i, j) split along its diagonal from node (i, j) to (i+1, j+1)
/// (x, y increasing). h(s) is the height of the block (the spheres' centres less r less their
/// nodes' heights) when its highest sphere touches a triangle: for each sphere, max over points p
/// of the triangles within r of its centre of p_z + sqrt(r^2 - |p - c|^2), exact (a concave
/// maximum: on a face or on an edge, in closed form). The offset grid, the lift's layout and its
/// errors are areal_lift's (o's step, offset_min/max, across_step/max, threads; its
/// turn_over_upper, block and prune are not used); `contact` is the lower-map node nearest to the
/// touching point. Needs no MuJoCo.
Result<ArealLift> areal_tilt_lift(const Map& lower, const Map& upper, const MapHoldOptions& t,
                                  const ArealLiftOptions& o = {});

/// The map model's hold angle (the matched prediction off the grid): the rigid, frictionless
/// quasi-static block on the same spheres and triangles as areal_tilt_lift, with offsets anywhere
/// in the plane. At tilt beta the block descends the potential V(s) = h(s) cos(beta) - (s.d)
/// sin(beta) by nonsmooth steepest descent: h is the max over (sphere, triangle) pieces, the
/// gradient of a piece is (p - c) / sqrt(r^2 - |p - c|^2) (p its touching point, c the sphere's
/// centre: the envelope theorem), the direction is minus the least-norm point of the convex hull
/// of the tilted gradients of the pieces within eps of the max (eps shrinking with the step), with a
/// backtracking step; it stops where that point is below `stationary` or the step below a
/// millionth of r. The protocol is areal_tilt's: rest at zero tilt from t.start_offset, then
/// t.coarse_tilt_step increments to the first run-away (a displacement along d of D since the
/// last stop), again from the stop before it in t.tilt_step, and the run-away tilt is then
/// bisected to `resolution`. t.lock_lateral restricts the moves to +-d. With atomic friction
/// mu_a = t.atomic_friction the block is held iff the tilted load lies in the sum of the contacts'
/// Coulomb cones (half-angle atan mu_a about each contact's normal (-g, 1)): in slopes, iff
/// tan(beta) d lies in the convex hull of the cones' slope sets, each sampled on its rim (128
/// points); while it is not held it moves along minus the least-norm point of that hull's tilted
/// image (docs/mujoco.md, "Atomic friction").
/// `start_tilt` (rad, in [0, t.max_tilt)): the block is put down already tilted (it settles at
/// that tilt and the increments go on from there), e.g. in the seat where a simulated block
/// stood before its run-away, to ask whether the rigid block holds as long from the same seat.
/// The resolution to which areal_tilt_hold bisects the run-away tilt by default: 1e-6 rad
/// (5.7e-5 deg), from the tilt_step bracket in 11 halvings (unit: rad).
inline constexpr double kArealHoldResolution = 1e-6;

struct ArealTiltHold {
  double hold_angle = 0;  ///< bisected (unit: rad)
  /// The rigid upper bound of this drop from the same model: the steepest slope along d (with
  /// the friction cone of mu_a, whole) of the contacts of every seat where the block rested, plus
  /// the residual of the rest test, as an angle; plus how far the reported hold angle lies above
  /// the highest tilt that held (at most `resolution`). At least hold_angle by construction: at a
  /// rest at tilt beta, tan(beta) d lies within the residual of the hull of the contacts' slopes
  /// (cones), so tan(beta) is at most their steepest slope along d. Capped at pi/2 (unit: rad).
  double seat_bound = 0;
  /// The steepest contact slope along d over the same seats, without friction (unit: rad).
  double seat_slope = 0;
  double runaway_increment = 0;                ///< the tilt_step increment at which it ran (unit: rad)
  bool ran_away = false;                       ///< false: held up to t.max_tilt
  std::array<double, 2> rest_offset = {0, 0};  ///< settled at start_tilt (zero by default) (unit: m)
  double steering = 0;                         ///< from d to the run-away's displacement (unit: rad)
  long evaluations = 0;                        ///< lift evaluations (unitless)
  /// The model's work, a measure of its cost that does not depend on the machine: tiles and
  /// spheres read to build the candidate lists, spheres evaluated, and cells whose triangles
  /// were evaluated (unitless).
  long work = 0;
  /// Where the block stands after each increment, coarse then fine, as areal_tilt's trace: tilt
  /// (rad), x, y (m); the run-away increments' ends included. To compare the two blocks' chains
  /// of stops (docs/mujoco.md).
  std::vector<std::array<double, 3>> stops;
};
Result<ArealTiltHold> areal_tilt_hold(const Map& lower, const Map& upper, const MapHoldOptions& t,
                                      double resolution = kArealHoldResolution, double stationary = 1e-7,
                                      double start_tilt = 0);

/// One drop of areal_tilt_hold_drops: where the block is put down, (x, y) (unit: m), and whether
/// it slides along d only (t.lock_lateral for this drop).
struct ArealTiltDrop {
  std::array<double, 2> start = {0, 0};
  bool locked = false;
};
/// How far a run of drops (areal_tilt_hold_drops) has come, for a progress line.
struct DropProgress {
  std::size_t done = 0;     ///< drops finished (unitless)
  std::size_t total = 0;    ///< drops in the run (unitless)
  std::size_t running = 0;  ///< drops under way (unitless)
  /// The least of the tilts at which the drops under way were last tried: each rises from zero to
  /// its hold angle in increments, then brackets it (unit: rad; NaN: none under way). A drop that
  /// stays at one tilt for long is one whose block is still settling there.
  double tilt = std::numeric_limits<double>::quiet_NaN();
};
/// Called as a run of drops goes on (DropProgress), from the worker threads, one call at a time.
using DropProgressFn = std::function<void(const DropProgress&)>;

/// areal_tilt_hold (default resolution and stationary threshold, from zero tilt) from each drop,
/// on one field of spheres and triangles shared by all of them (built once, read by `threads`
/// workers, 0 = all cores): element k of the result is drop k's, identical to areal_tilt_hold
/// from that drop. t.start_offset and t.lock_lateral are those of each drop. `progress` (if set)
/// is called after each drop and after each tilt increment or bracketing step of a drop under way.
/// Errors: as areal_tilt_hold, the first failing drop named by its start offset.
Result<std::vector<ArealTiltHold>> areal_tilt_hold_drops(const Map& lower, const Map& upper, const MapHoldOptions& t,
                                                         const std::vector<ArealTiltDrop>& drops, unsigned threads = 0,
                                                         const DropProgressFn& progress = {});

/// How well conditioned the hold angle of areal_tilt_hold is. Where a slip ends can hinge on a basin
/// boundary that passes within a sphere radius of the end; then how the block slides (damped
/// dynamics in MuJoCo, steepest descent here) decides the seat it takes and the hold angle from
/// there (docs/mujoco.md, "The 0.2° target"). For each slip of `hold`'s chain of stops (an increment
/// that moved the block more than r/10, not the run-away), the rigid block is put down
/// `perturbation` (m; 0: the sphere radius r) from the slip's end in 8 directions (2, along +-d,
/// when t.lock_lateral) at that tilt; where it settles in another seat (more than r/10 from the
/// end), the protocol goes on from there (areal_tilt_hold with that start tilt and offset); where
/// it slides D along d instead, that chain runs away at the slip's increment. First order: the
/// chains from other seats are not perturbed again. `t`, `resolution` and `stationary`
/// must be those that made `hold`.
struct ArealTiltHoldSpread {
  double low = 0;         ///< least hold angle over `hold` and the chains from other seats (unit: rad)
  double high = 0;        ///< largest (unit: rad)
  int slips = 0;          ///< slips examined (unitless)
  int ambiguous = 0;      ///< slips from whose perturbed ends the block settles in another seat (unitless)
  int continuations = 0;  ///< chains run from other seats (unitless)
  long evaluations = 0;   ///< lift evaluations of the continuations (unitless)
};
Result<ArealTiltHoldSpread> areal_tilt_hold_spread(const Map& lower, const Map& upper, const MapHoldOptions& t,
                                                   const ArealTiltHold& hold, double perturbation = 0,
                                                   double resolution = kArealHoldResolution, double stationary = 1e-7);

/// The default run-away distance D of the map model and of the simulation for sliding along
/// `direction` (unit: rad) on the lower map `lower`: kRunawayPerSlopeCorrelation (hold.hpp)
/// times the median slope correlation length of up to 32 evenly spaced lines of the map along the
/// grid axis nearer to the direction (each line's longest run of valid points, at least 16; never
/// less than the spacing), or that many spacings where no line has one. A length of the surface,
/// not a fraction of the map (docs/site/theory.md, "The stated test").
struct DefaultRunaway {
  double distance = 0;  ///< D (unit: m)
  std::string rule;     ///< how it was derived, with its numbers (text)
};
DefaultRunaway default_map_runaway_distance(const Map& lower, double direction);

/// The map model's defaults where `t` leaves them unset (<= 0): the run-away distance
/// default_map_runaway_distance(lower, t.angle), the sphere radius a fifth of the lower map's
/// smaller spacing (unit: m). `lower` is the (conditioned) lower map.
void fill_map_model_defaults(const Map& lower, MapHoldOptions& t);

/// The rows of numbers the map model's outputs nest (src/maphold/map_hold_columns.cpp).
/// A point (x, y) as a row of numbers (table "offset_xy"): x_m, y_m.
const Columns<std::array<double, 2>>& offset_xy_columns();
/// A stop of the block (table "tilt_stop"): [tilt (deg), x (m), y (m)] (ArealTiltHold::stops).
const Columns<std::array<double, 3>>& tilt_stop_columns();

}  // namespace frictal
