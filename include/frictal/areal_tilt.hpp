// frictal — the 3D tilt test of two areal blocks on MuJoCo (experimental; docs/mujoco.md). The
// lower block's face is a MuJoCo height field of the lower map (each cell split along its diagonal
// from (i, j) to (i+1, j+1), as MuJoCo does), the upper block one rigid body whose face is its
// map's nodes swept by spheres of radius r, on three slide joints (rotation held; or one along d
// and z: locked), frictionless (mu_a = 0, condim 1) or with contact friction mu_a (condim 3).
// Sphere-triangle contacts are exact by default (the nearest point of each triangle), replacing
// MuJoCo's prisms. The gravity is turned about the axis across the sliding direction d in
// increments; after each the block relaxes (local non-viscous damping) until its unbalanced
// force (contact + gravity, without the damping) and its speed stay small, and the
// stick/run-away rule of the hold angle is read: the run-away is the first displacement along d
// of at least D since the last stop. The map model (map_hold.hpp: areal_tilt_lift,
// areal_tilt_hold) predicts the same test on the same surfaces, rigid and quasi-static (the
// matched prediction; it needs no MuJoCo); areal_tilt_matched runs both.
//
// Only areal_tilt() needs FRICTAL_MUJOCO (libmujoco-dev); without it, it returns
// ErrorCode::NotAvailable. Lengths in m, angles in rad.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "frictal/map.hpp"
#include "frictal/map_hold.hpp"
#include "frictal/outputs.hpp"
#include "frictal/result.hpp"
#include "frictal/settings.hpp"

namespace frictal {

/// True when this build has the MuJoCo adapter.
bool mujoco_available();

/// The test's settings: the map model's (MapHoldOptions: direction, run-away distance, mu_a,
/// sphere radius, height field, lateral mode, start offset, tilt steps), which the matched
/// prediction reads, and the simulation's.
struct ArealTiltOptions : MapHoldOptions {
  /// true: the exact sphere-triangle contact on the height field's triangles (the surface that
  /// areal_tilt_lift evaluates); false: MuJoCo's own (MPR on prisms: internal edges; docs/mujoco.md).
  bool exact_contacts = true;
  /// The simulation in scaled units (lengths divided by the lower map's larger extent, gravity 9.81):
  double time_step = 1e-4;     ///< (unit: scaled s)
  double contact_time = 2e-4;  ///< solref time constant, >= 2 time steps (unit: scaled s)
  double damping = 0;          ///< viscous joint damping per unit mass (unit: 1/scaled s)
  /// Local non-viscous damping (Cundall): a force against each joint's velocity, this fraction of
  /// its unbalanced force, in [0, 1) (unitless).
  double local_damping = 0.9;
  /// Viscous damping per unit mass that replaces the local damping while the block settles at
  /// zero tilt, the block put down gently: an overdamped descent from the drop (its velocity
  /// tends to the unbalanced force over this), the prediction's steepest descent as it grows; 0:
  /// the drop relaxes as every increment (quench or local damping). Default 100, with the quench:
  /// the protocol the prediction is checked against (docs/mujoco.md) (unit: 1/scaled s).
  double settle_damping = 100;
  /// Viscous damping per unit mass that replaces the local damping during the tilt increments: an
  /// overdamped slip (velocity = unbalanced force / this), the prediction's descent into the next
  /// seat as it grows; an increment then waits up to the time the block needs to creep two
  /// lower-map cells at the drive of one tilt step (at least 40 chunks). 0: the relaxation
  /// (quench or local damping) (unit: 1/scaled s).
  double tilt_damping = 0;
  /// true: quenched dynamics (kinetic damping) in place of the local damping, while the block
  /// settles (unless settle_damping) and during the tilt increments (unless tilt_damping): no
  /// force against the motion, but the velocity is set to zero whenever the unbalanced force F
  /// does negative work on the block's offset (F.v < 0) and its speed is capped at quench_speed:
  /// it stops at the first minimum along its path (no momentum past a seat), turns with the force
  /// within a radius speed^2 / |F| (the prediction's steepest descent as the cap shrinks) and
  /// does not creep at small forces (its speed does not fall with the force). An increment waits
  /// at least the time to cross the lower map at the cap (a slip may go far across d). The
  /// default since 2026-11-27 (before: false, the local damping).
  bool quench = true;
  double quench_speed = 1e-2;     ///< with quench: the block's largest speed (unit: scaled m/s)
  double relax_time = 0.5;        ///< longest relaxation per increment (unit: scaled s)
  double force_tolerance = 1e-4;  ///< at rest: unbalanced force below this fraction of the weight (unitless)
  double speed_tolerance = 1e-5;  ///< at rest: speed below this (unit: scaled m/s)
  int rest_steps = 10;            ///< ... for this many steps in a row (unitless)
};

/// The settings table of ArealTiltOptions (settings.hpp; docs/settings.md): the `areal-tilt`
/// command's options and the `areal-tilt` study kind's keys. Not in it: start_offset (X,Y) and
/// turn_over_upper (`--in-place`).
const std::vector<Field>& areal_tilt_settings();
/// `base` with the given values (SI; names from areal_tilt_settings(), else an error naming the
/// nearest one; out of range: an error naming the value and the range).
Result<ArealTiltOptions> make_areal_tilt_options(const ValueSet& si_values, const ArealTiltOptions& base = {});
/// Every setting of `options` (SI).
ValueSet areal_tilt_values(const ArealTiltOptions& options);

/// One tilt increment of the simulation, at its end.
struct ArealTiltIncrement {
  double tilt = 0;              ///< (unit: rad)
  double x = 0, y = 0;          ///< the block's offset (unit: m)
  bool rested = false;          ///< reached rest (else ran D or waited out its relaxations)
  long steps = 0;               ///< MuJoCo steps so far (unitless)
  double unbalanced_force = 0;  ///< at the end, a fraction of the weight (unitless)
  double speed = 0;             ///< at the end (unit: m per scaled s)
};

struct ArealTiltResult {
  double friction_angle = 0;                   ///< tilt at which the run-away began (unit: rad)
  std::array<double, 2> rest_offset = {0, 0};  ///< where the block rested at zero tilt (unit: m)
  bool ran_away = false;                       ///< false: held up to max_tilt
  int unsettled = 0;                           ///< increments that ended without reaching rest (unitless)
  long steps = 0;                              ///< MuJoCo steps (unitless)
  std::size_t spheres = 0;                     ///< spheres of the upper face (unitless)
  int max_contacts = 0;                        ///< most contacts at once (unitless)
  double sphere_radius = 0;                    ///< r used (unit: m)
  /// Angle from d to the run-away's displacement from the last stop, towards e (unit: rad).
  double steering = 0;
  std::vector<ArealTiltIncrement> trace;  ///< every increment, coarse then fine, in order
  /// A reading to distrust: "friction-not-validated" with atomic friction (measured in
  /// docs/mujoco.md, "Atomic friction": MuJoCo's regularised friction under the local damping
  /// creeps instead of sliding, so the angle reads late).
  std::vector<Warning> warnings;
};

/// The run's output columns (frictal/outputs.hpp; src/tilt/tilt_columns.cpp): the keys of
/// `frictal areal-tilt --json` that are the run's numbers (its table "areal_tilt") and the
/// areal-tilt study kind's outputs of the same quantities.
const Columns<ArealTiltResult>& areal_tilt_run_columns();
/// One increment of the run as a row of numbers (table "areal_tilt_increment";
/// src/tilt/areal_tilt_columns.cpp): tilt, x, y, rested, steps, unbalanced force, speed.
const Columns<ArealTiltIncrement>& areal_tilt_increment_columns();

/// Called after each tilt increment with the increment just recorded (for a progress line; it
/// must not throw).
using ArealTiltProgress = std::function<void(const ArealTiltIncrement&)>;

/// Errors: invalid maps or options (InvalidInput), MuJoCo refusing the model (InvalidInput, its
/// message), a build without MuJoCo (NotAvailable).
Result<ArealTiltResult> areal_tilt(const Map& lower, const Map& upper, const ArealTiltOptions& o = {},
                                   const ArealTiltProgress& progress = {});

/// Where a simulated block sat before its run-away: the position of the last increment of
/// `r.trace` that ended at rest below the run-away's tilt, and the lowest tilt at which the block
/// already rested there (within r / 100) (tilt in rad, x, y in m); nullopt if it never rested or
/// did not run away.
std::optional<std::array<double, 3>> areal_tilt_last_seat(const ArealTiltResult& r);

/// The map model's settings for a simulation's settings `sim`: `sim` with the map model's
/// run-away distance and sphere radius as predict() sets them (sim's where it sets them, > 0;
/// else fill_map_model_defaults), so that the hold angle predicted beside a MuJoCo run (`frictal
/// areal-tilt`, Python areal_tilt) is the prediction's model, in the simulation's protocol (tilt
/// steps, height field, lateral mode, start offset).
ArealTiltOptions map_model_options(const Map& lower, const ArealTiltOptions& sim);

/// The 3D tilt test beside the prediction matched to it (`frictal areal-tilt`, Python areal_tilt):
/// the MuJoCo run (areal_tilt), then predict()'s map model (map_model_options of the run's
/// settings) from the rest offset the run reached, the block free and locked (a diagnostic), on
/// one field of spheres (areal_tilt_hold_drops); the spread in the simulated lateral mode
/// (areal_tilt_hold_spread); the rigid block put down in the run's last seat at its tilt.
struct ArealTiltMatched {
  bool simulated = false;   ///< the run was made (else only the predictions, dropped at o.start_offset)
  bool run_locked = false;  ///< the run's lateral mode: locked to the direction
  /// The run; without it, rest_offset = o.start_offset and sphere_radius the model's, the rest zero.
  ArealTiltResult run;
  double runaway_distance = 0;          ///< the model's run-away distance D (unit: m)
  ArealTiltHold free, locked;           ///< the model from run.rest_offset, block free and locked
  ArealTiltHoldSpread spread;           ///< in the simulated lateral mode: a slip's end moved by r
  bool seated = false;                  ///< the run rested in a seat before its run-away
  double seat_tilt = 0;                 ///< that seat's tilt (unit: rad)
  std::array<double, 2> seat_offset{};  ///< its offset (x, y) (unit: m)
  double seated_hold_angle = 0;         ///< the model put down there at that tilt, simulated lateral mode (unit: rad)
  /// The model in the simulated lateral mode (free or locked above, in detail).
  const ArealTiltHold& matched() const { return run_locked ? locked : free; }
};
/// `simulate` false: no run (needs no MuJoCo). Errors: areal_tilt's and areal_tilt_hold's.
Result<ArealTiltMatched> areal_tilt_matched(const Map& lower, const Map& upper, const ArealTiltOptions& o,
                                            bool simulate = true, const ArealTiltProgress& progress = {});

/// What `frictal areal-tilt --json` and Python's areal_tilt() report: the run and the predictions
/// matched to it, with the options that name the test and the wall time.
struct ArealTiltReport {
  ArealTiltMatched matched;
  double direction = 0;         ///< the tilt direction d, from +x towards +y (unit: rad)
  double tilt_step = 0;         ///< the tilt increment (unit: rad)
  bool exact_contacts = false;  ///< MuJoCo's collision: exact (else native)
  double seconds = 0;           ///< wall time of the run and the predictions (unit: s)
};
/// Its output table (src/tilt/areal_tilt_columns.cpp): the keys of `frictal areal-tilt --json`, and
/// of Python's areal_tilt() dict without their unit suffix (values in SI).
const Columns<ArealTiltReport>& areal_tilt_report_columns();

/// One drop of the matched prediction as the front ends report it: the drop and, where it was
/// computed, its spread.
struct ArealTiltHoldReport {
  const ArealTiltHold& hold;
  const ArealTiltHoldSpread* spread = nullptr;  ///< none: not computed
};
/// Its output columns (frictal/outputs.hpp; src/tilt/tilt_columns.cpp): Python areal_tilt_hold().
const Columns<ArealTiltHoldReport>& areal_tilt_hold_columns();

}  // namespace frictal
