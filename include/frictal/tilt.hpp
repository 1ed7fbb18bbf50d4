// frictal — the tilting-block friction test of the paper (Sec. IV, Fig. 5-8) on the
// spheropolygon engine (frictal/dem.hpp).
//
// Two blocks are built from surfaces given as measured (material below, z up):
//   lower block: the lower surface on top of a body of height `block_height` below its minimum;
//   upper block: the upper surface rotated by 180 degrees (frictal::rotate180) as its bottom face
//                and a flat top `block_height` above the face's maximum.
// The upper block is shifted by `initial_offset` (by default the offset of least lift from the
// signature, i.e. the deepest nesting), lowered until its core is `placement_gap` above contact,
// settles under gravity for `settle_time`, then the lower block (kinematic) turns about its
// centroid at `tilt_rate`, clockwise so that the upper block slides towards +x (counter-clockwise
// with `reverse`, sliding towards -x). With `protocol` = quasi-static the tilt instead grows by
// `tilt_increment` and the upper block relaxes to rest (FIRE) after each increment and in place
// of the settling; gravity turns in the lower block's frame (docs/dem.md sec. 4).
//
// Detection (docs/dem.md): the relative displacement d is the upper centroid's motion along the
// lower block's x axis in the lower block's frame, signed in the sliding direction, and v its
// rate. A stick is an interval of at least `stick_duration` with v <= `stick_speed`. The run
// stops once d has grown by `runaway_distance` (default: one wavelength) since the end of the
// last stick; the friction angle is the tilt at that moment. The lag is the tilt gained while v
// grows from 0 to stick_speed: below 0.1 degree for the defaults (docs/dem.md). Quasi-static:
// the stop after each increment that relaxed to rest replaces the stick, and the friction angle
// is the tilt of the last such stop (TiltResult::friction_angle).
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "frictal/dem.hpp"
#include "frictal/geometry.hpp"
#include "frictal/outputs.hpp"
#include "frictal/result.hpp"
#include "frictal/settings.hpp"

namespace frictal {

/// How the tilt grows (docs/dem.md sec. 4).
/// Which touching pairs push in the tilt test (dem::ContactRule; docs/dem.md sec. 1).
enum class TiltContactRule {
  Auto,     ///< pairs with the constant-rate protocol (the paper's), closest with quasi-static
  Pairs,    ///< every vertex-edge pair within r1 + r2
  Closest,  ///< the deepest pair of each contact region
};

enum class TiltProtocol {
  /// The paper's: the lower block turns at `tilt_rate`; stick/run-away from the relative speed.
  ConstantRate,
  /// The tilt grows in steps of `tilt_increment`; after each the upper block relaxes to rest
  /// (FIRE, Bitzek et al. 2006) before the next. Gravity turns in the lower block's frame (the
  /// lower block stays still; frames and series report the tilt as if it turned).
  QuasiStatic,
};

/// How the upper block comes to rest before a constant-rate tilt starts (docs/dem.md sec. 4).
enum class TiltSettling {
  /// The paper's: the block falls and moves freely for `settle_time`; a block that still moves
  /// then (a frictionless block gliding in a wide basin) warns "unsettled".
  Free,
  /// A FIRE relaxation at zero tilt, as the quasi-static protocol settles (at most `relax_time`,
  /// thresholds relax_force, relax_speed, relax_duration): the tilt starts from rest.
  Relax,
};

/// What turns in the constant-rate protocol (docs/dem.md sec. 4).
enum class TiltTurn {
  /// The paper's: the lower block turns about its centroid at `tilt_rate` from rest, so a block
  /// resting on it is kicked at the start (relative speed tilt_rate times the height between the
  /// centroids) and carried round it.
  Block,
  /// Gravity turns at `tilt_rate` in the frame of the lower block, which stays still (as in the
  /// quasi-static protocol): the same test without the start's kick and the frame's fictitious
  /// forces (centrifugal tilt_rate^2 r, Coriolis 2 tilt_rate v: below 1e-5 g on Table I blocks).
  Gravity,
};

/// What the blocks' faces are when a surface folds over (Koch K1 above 45 degrees, ...).
enum class TiltFace {
  Curve,     ///< the full curve (a rigid block's real face; overhangs can interlock)
  Envelope,  ///< the upper envelope of the surface (what the signature sees)
};

/// The share of relax_time an increment of the quasi-static protocol relaxes for, on average
/// (unitless): 0.0045-0.006 on the measured profiles of tests/data with the rotation held, 24 to
/// 9,600 points, beside the fixed kTiltRelaxFixed (docs/dem.md sec. 7, "cost estimate").
inline constexpr double kTiltRelaxShare = 0.006;
/// What a quasi-static run costs beside its relaxed increments, in relax_time (unitless): the
/// settling's relaxation and the run-away increment, which does not come to rest, each up to one
/// relax_time; 1.5 to 1.6 measured on a flat scan (one increment) (docs/dem.md sec. 7).
inline constexpr double kTiltRelaxFixed = 1.5;

/// The cost of a run, estimated before its first step (TiltResult::estimate, TiltConfig::before_run).
/// The run is expected to end at the quasi-static hold angle of the block from where it is put
/// down (hold.hpp; without one, the rounded blocks' upper bound). Constant-rate protocol: the
/// simulated time is the settling plus the tilt to max_tilt at tilt_rate (the bound) or to that
/// angle (expected, if predicted); steps are that time over the time step below. Quasi-static:
/// the bound is every increment up to max_tilt relaxing for relax_time, the expected time
/// kTiltRelaxFixed relax_times plus the increments up to that angle relaxing for kTiltRelaxShare
/// of it. Measured against real runs in docs/dem.md sec. 7 ("cost estimate").
struct TiltEstimate {
  /// The step the run will mostly take: time_step, or with the adaptive step time_step_safety
  /// times the stability limit of one contact at the upper block's extent, if smaller (unit: s).
  double time_step = 0;
  double simulated_time_bound = 0;     ///< settling + tilt to max_tilt (unit: s)
  double simulated_time_expected = 0;  ///< settling + tilt to the prediction; = bound without one (unit: s)
  double steps_bound = 0;              ///< simulated_time_bound / time_step (unitless)
  double steps_expected = 0;           ///< simulated_time_expected / time_step (unitless)
  /// Neighbour-list pairs when the blocks are placed (unitless): what a step costs.
  double list_pairs = 0;
  /// Wall time per step from a cost model measured on one core (docs/dem.md sec. 7):
  /// kTiltStepSeconds0 + kTiltStepSecondsPerPair x list_pairs (unit: s).
  double seconds_per_step = 0;
  double seconds_expected = 0;  ///< steps_expected x seconds_per_step (unit: s)
  double seconds_bound = 0;     ///< steps_bound x seconds_per_step (unit: s)
};

/// Where a running tilt test stands (TiltConfig::progress).
struct TiltProgress {
  std::uint64_t steps = 0;                 ///< steps taken (unitless)
  double time = 0;                         ///< simulated time (unit: s)
  double tilt = 0;                         ///< current tilt (unit: rad)
  double displacement = 0;                 ///< relative displacement d (unit: m)
  double wall_time = 0;                    ///< wall time since the first step (unit: s)
  const TiltEstimate* estimate = nullptr;  ///< the run's estimate (valid during the call)
};

struct TiltConfig {
  double block_height = 0.01;  ///< h below the surface minimum, Table I (unit: m)
  double radius = 5e-5;        ///< spheroradius r of both blocks, Table II (unit: m)
  double density = 50;         ///< areal density rho, Table II (unit: kg/m^2)
  dem::ContactParams contact;  ///< k_n, k_t, gamma_n, gamma_t, mu_a (Table II, mu_a = 0)
  /// If > 0: restitution eps of Eq. 12, replacing contact.normal_damping by the gamma_n that gives
  /// eps for one contact on the upper block's mass (unitless, in (0, 1]); with the Hertz law,
  /// contact.damping_ratio by the zeta that gives it (dem::hertz_damping_ratio).
  double restitution = 0;
  /// Hertz law (contact.law = dem::ContactLaw::Hertz): Young's modulus E of the blocks, > 0 (unit:
  /// Pa), and their Poisson ratio nu in (-1, 0.5] (unitless). The contact modulus is
  /// E* = E / (1 - nu^2) with one elastic block on a rigid one (`elastic_blocks` = 1), half that
  /// with two of the same material (2); the tangential spring is Mindlin's 2 (1 - nu) / (2 - nu)
  /// of the tangent normal stiffness. normal_stiffness, tangential_stiffness and normal_damping
  /// are not used then.
  double modulus = 0;
  double poisson = 0.3;
  int elastic_blocks = 1;   ///< 1 or 2 (unitless)
  double gravity = 9.81;    ///< (unit: m/s^2)
  double tilt_rate = 0.05;  ///< |angular velocity| of the lower block (unit: rad/s)
  bool reverse = false;     ///< tilt so that the upper block slides towards -x
  /// With `adaptive_time_step` (default): the largest step; else the fixed step (unit: s).
  /// 1e-4 s: with implicit normal dashpots the stability limit of Table II contacts on a Table I
  /// block (0.11 kg) stays above ~3e-4 s however many contacts there are, and 1e-4 s gives the
  /// friction angles of the fixed 1e-5 s step within 0.001 deg (docs/dem.md sec. 3). The fixed
  /// step was 1e-5 s.
  double time_step = 1e-4;
  /// Adaptive step (dem::WorldDef::adaptive_time_step): each step is chosen from the explicit
  /// stability limit of the contacts present (times `time_step_safety`), at most `time_step`.
  /// false: the fixed step `time_step` of the engine before 2026-11-23.
  bool adaptive_time_step = true;
  double time_step_safety = 0.5;  ///< fraction of the stability limit taken (unitless, (0, 1])
  /// Normal dashpots integrated implicitly (dem::WorldDef::implicit_damping): the damping of many
  /// contacts no longer limits the step. false: the explicit step (bit for bit the fixed-step engine).
  bool implicit_damping = true;
  double skin = 5e-5;                 ///< neighbour-list skin (unit: m)
  int max_steps_beyond_limit = 1000;  ///< see dem::WorldDef::max_steps_beyond_limit; fixed step only (unitless)
  double settle_time = 0.1;           ///< free settling before the tilt starts (unit: s)
  /// Constant-rate protocol: free settling (the paper's) or a relaxation to rest before the tilt
  /// starts (the quasi-static protocol always relaxes).
  TiltSettling settling = TiltSettling::Free;
  /// Constant-rate protocol: turn the lower block (the paper's) or gravity in its frame.
  TiltTurn turn = TiltTurn::Block;
  double max_tilt = 89 * std::numbers::pi / 180;       ///< give up (slid = false) beyond this tilt, 89 deg (unit: rad)
  double runaway_distance = 0.01;                      ///< sliding "for good": growth past this, one lambda (unit: m)
  double stick_speed = 1e-5;                           ///< relative speed counted as stuck (unit: m/s)
  double stick_duration = 0.02;                        ///< a stick lasts at least this long (unit: s)
  TiltProtocol protocol = TiltProtocol::ConstantRate;  ///< how the tilt grows
  /// Which touching pairs push (the force law's contact rule); Auto resolves by `protocol`.
  TiltContactRule contact_rule = TiltContactRule::Auto;
  /// Quasi-static protocol: the tilt added per increment (unit: rad). The friction angle is the
  /// tilt of an increment, so it reads at most one increment below the angle that holds.
  double tilt_increment = 0.01 * std::numbers::pi / 180;
  /// Quasi-static protocol: the longest relaxation after one increment (and of the settling)
  /// (unit: s); a relaxation that does not end in time warns ("unrelaxed").
  double relax_time = 2.0;
  /// Quasi-static protocol: at rest when the unbalanced force on the upper block (contacts plus
  /// gravity, and the torque over its extent when it may turn), averaged over `relax_duration`,
  /// is below this fraction of its weight (unitless) and its speed below `relax_speed` throughout.
  double relax_force = 1e-5;
  double relax_speed = 1e-6;  ///< quasi-static: speed of the upper block counted as at rest (unit: m/s)
  /// Quasi-static: the speed must stay below relax_speed this long without a break (a block
  /// passing an unstable balance is slow for a moment), and the force is averaged over it (unit: s).
  double relax_duration = 0.005;
  /// Run the test again at 10 k_n and k_t (series and frames off) and warn ("stiffness") when the
  /// friction angle moves by more than `warn_stiffness_angle`: the run is not in the rigid limit.
  /// With the Hertz law the rerun is at 10 `modulus`.
  bool check_stiffness = false;
  /// Shorter run-away distances observed in the same run (unit: m), each in (0, runaway_distance]:
  /// for each, TiltResult::checkpoints records the tilt at the start of the first run-away that
  /// reached it, i.e. the friction angle that a run with that runaway_distance reports (the
  /// motion does not depend on the run-away distance; the run still stops at runaway_distance).
  /// Library only (not a settings-table option): the wm-tilt study kind sets it.
  std::vector<double> runaway_checkpoints;
  /// The stated test's offsets and drops (hold.hpp's stated_drops; tilt_setup sets them on a
  /// measured pair): the rigid model's spread over drops (TiltResult::predicted_spread_*) reads
  /// the lift over the offsets [0, spread_offset_max] at which the block lies wholly over the lower
  /// surface and drops over [spread_drop_min, spread_drop_max], as predict() does (unit: m).
  /// spread_offset_max <= 0: the signature's range (one period, or half the shorter block) and its
  /// own drops (the paper's blocks). Library only (not a settings-table option).
  double spread_offset_max = 0;
  double spread_drop_min = 0;
  double spread_drop_max = 0;
  TiltFace face = TiltFace::Curve;
  /// Shift of the upper block along x before placement (unit: m). NaN: the offset of least lift
  /// h(s) over [0, period) from the signature (or 0 if `predict` is false).
  double initial_offset = std::numeric_limits<double>::quiet_NaN();
  double placement_gap = 2e-5;  ///< initial clearance between the two spheropolygons (unit: m)
  /// Period of the surfaces for the signature's offset range (unit: m); <= 0: half the length.
  double period = 0.01;
  bool predict = true;            ///< compute the signature prediction (needs envelopes)
  double series_interval = 1e-3;  ///< time between rows of the series; <= 0: none (unit: s)
  double frame_interval = 0;      ///< time between frames; <= 0: none (unit: s)
  /// Threads of the run (unitless; 0: every hardware thread; 1, the default: one). Not a
  /// settings-table option (like SignatureOptions::threads: it changes no result): `frictal tilt
  /// --threads`, Python tilt(..., threads=N); a study run lends idle cores instead. The set-up's
  /// two signature predictions (rigid and spheropolygon) run side by side, each on half of
  /// them, and the contact passes of each step are split over them (dem::set_thread_count; only
  /// steps with >= 64 hot pairs per thread, e.g. K3 blocks). The results do not depend on it,
  /// bit for bit (docs/dem.md sec. 7).
  int threads = 1;
  /// Library only (not a settings-table option; the study runner's tilt kinds set it): if set,
  /// called before the first step and then every 4096 steps with the thread count in use; the
  /// contact passes then use the count it returns (at least 1), e.g. cores that other tasks of a
  /// study have left idle. Results do not depend on it.
  std::function<unsigned(unsigned)> thread_budget;
  /// Library only (not a settings-table option; the CLI sets it): if set, called once when the
  /// blocks are placed, before the first step, with the run's cost estimate (TiltResult::estimate).
  /// An error it returns ends run_tilt with that error before any step (the CLI refuses a run
  /// beyond its --max-steps this way). The library prints nothing.
  std::function<Status(const TiltEstimate&)> before_run;
  /// Library only: if set, called from the run loop every `progress_interval` steps (and not
  /// otherwise) with where the run stands; it must not throw. Results do not depend on it.
  std::function<void(const TiltProgress&)> progress;
  /// Steps between calls of `progress` (unitless, >= 1).
  std::uint64_t progress_interval = 4096;
  /// Hold the upper block's rotation relative to the lower block (dem::BodyDef::rotation_follows):
  /// it translates freely but does not rotate against the lower block, as the signature assumes.
  bool hold_rotation = false;
  // Model warnings (TiltResult::warnings; thresholds measured in docs/dem.md sec. 6).
  /// "core-overlap" when the resting overlap W / k_n exceeds this fraction of r (unitless).
  double warn_overlap_fraction = 0.1;
  /// "rounding" when the spheropolygon prediction differs from the rigid one by more (unit: rad).
  double warn_prediction_tolerance = 0.1 * std::numbers::pi / 180;
  /// "rotation" when the upper block turns against the lower one by more before the slide (unit: rad).
  double warn_rotation = 0.002 * std::numbers::pi / 180;
  /// "time-step" when a fixed step (adaptive_time_step = false) exceeds this fraction of one
  /// contact's period 2 pi sqrt(m/k_n) (unitless): 0.005, i.e. ~1.4e-5 s for a Table I block; the
  /// fixed explicit step is stable for the Koch grid at 1e-5 s, not at 2e-5 s for K3.
  double warn_time_step_fraction = 0.005;
  /// "creep": a slip of at least this length that ends in a new stick while shorter than a tenth
  /// of the smallest feature of the faces (it reaches no other feature) is a creep event (unit: m).
  double warn_creep_slip = 1e-7;
  /// "creep" when the first creep event began more than this below the reported friction angle:
  /// the stick rule reports the last stick, so sliding began earlier than phi says (unit: rad).
  double warn_creep_angle = 0.1 * std::numbers::pi / 180;
  /// "stiffness" (with check_stiffness) when 10 k_n moves the friction angle by more (unit: rad).
  double warn_stiffness_angle = 0.1 * std::numbers::pi / 180;
};
TiltConfig default_tilt_config();

/// The settings table of the tilt test (settings.hpp): one field per TiltConfig member that a
/// user sets (contact law included: normal_stiffness, ..., atomic_friction). Its names are the
/// `frictal tilt` options, the 'tilt' study kind's TOML keys, the keywords of Python's
/// frictal.tilt and the keys of the "settings" object in `frictal tilt --json`.
const std::vector<Field>& tilt_settings();
/// A default configuration for a surface of period `period` (m; <= 0: none) whose run-away
/// distance defaults to `scale` (m; <= 0: keep the default one wavelength of 0.01 m).
TiltConfig tilt_config_for_surface(double period, double scale);

/// The per-step cost model of TiltEstimate (one core of this project's 2-vCPU machine, docs/dem.md
/// sec. 7): seconds per step = kTiltStepSeconds0 + kTiltStepSecondsPerPair x the vertex-edge pairs
/// in the neighbour list when the blocks are placed.
inline constexpr double kTiltStepSeconds0 = 2e-6;        ///< (unit: s)
inline constexpr double kTiltStepSecondsPerPair = 1e-8;  ///< (unit: s per pair)

/// Length of the block the macro defaults were made for: the Table I block, L_b = 0.2 m (unit: m).
inline constexpr double kTiltReferenceLength = 0.2;

/// The test a tilt run of a measured profile pair states (tilt_setup), the one `frictal predict`
/// states (hold.hpp's stated_test): the block, the run-away distance d, their rule, the drop range
/// and the drop the run takes.
struct TiltStatedTest {
  /// "stated": the middle piece of the upper profile, block_length long, dropped where it lies
  /// wholly over the lower one (predict's default); "whole": the whole upper profile over the
  /// first half of the lower one (block length < 0); empty: no stated test (a generated surface,
  /// which keeps the paper's blocks, or a folded curve).
  std::string block;
  double block_length = 0;      ///< L_b, to the nearest samples (unit: m)
  double runaway_distance = 0;  ///< d (unit: m)
  std::string rule;             ///< how d and L_b were set (predict's test_lengths)
  /// predict's drop range in the signature's frame (0: the left ends aligned) (unit: m); NaN for the
  /// whole block (the signature's own range).
  double drop_min = std::numeric_limits<double>::quiet_NaN();
  double drop_max = std::numeric_limits<double>::quiet_NaN();
  /// Where the run drops the block: "the middle of the drop range", "given" (initial_offset) or,
  /// for the whole block, "the offset of least lift".
  std::string drop;
  std::vector<Warning> warnings;  ///< scan-too-short (warnings.hpp's code, as predict issues it)
};

/// One setting changed by scale_tilt_defaults (SI values; the unit is the field's in tilt_settings()).
struct TiltScaledSetting {
  std::string name;  ///< the settings-table name ("spheroradius", ...)
  double from = 0;   ///< the macro default (unit: the field's)
  double to = 0;     ///< the scaled default (unit: the field's)
};

/// The macro defaults carried over to a pair of surfaces of another size (docs/dem.md sec. 5,
/// "Defaults at any scale"). With s = L / kTiltReferenceLength (L: the shorter face's extent in
/// x) and the spheroradius r = min(s r_0, dx) (r_0 the default 5e-5 m, dx the point spacing)
/// and q = r / (s r_0) <= 1, the settings are those of the macro test on the surfaces scaled by
/// 1/s (gravity and areal density unchanged, every dimensionless group kept):
///   lengths x s: block_height, period (if > 0), skin, runaway_distance, warn_creep_slip;
///   placement_gap x s q;
///   stiffnesses x s / q (so W / (k_n r) stays); damping rates x 1 / sqrt(s q) and the time-step
///   cap x sqrt(s q) (one contact's period); protocol times (settle_time, stick_duration,
///   relax_time, relax_duration, series_interval, frame_interval) x sqrt(s) (sqrt(L / g));
///   tilt_rate x 1 / sqrt(s); speeds (stick_speed, relax_speed) x sqrt(s).
/// At s = 1 and q = 1 (a 0.2 m face sampled no finer than r_0) the defaults are unchanged; with
/// q = 1 a run is the macro run in other units (the same steps and friction angle).
struct TiltScaling {
  double length = 0;         ///< L: extent in x of the shorter face (unit: m)
  double point_spacing = 0;  ///< dx: the smaller of the two faces' median spacing of distinct x (unit: m)
  double height_range = 0;   ///< the larger of the two faces' z ranges (unit: m)
  double length_factor = 1;  ///< s = L / kTiltReferenceLength (unitless)
  double radius_factor = 1;  ///< q = r / (s r_0), below 1 when dx caps r (unitless)
  TiltConfig config;         ///< `base` with every setting above scaled
  std::vector<TiltScaledSetting> settings;  ///< the settings changed, in table order
  /// tilt_setup on measured surfaces: the protocol settings a measured surface takes by default
  /// and the caller did not give, as "name = value" joined by ", " (e.g. "protocol = quasi-static,
  /// hold_rotation = true"); empty for generated surfaces and from scale_tilt_defaults.
  std::string measured_defaults;
  /// tilt_setup: the test stated on a measured pair (empty `block` otherwise).
  TiltStatedTest test;
  /// tilt_setup: the upper surface the run takes, as measured: the stated block (the middle piece
  /// of the upper profile) or the upper surface as given. Pass it to run_tilt.
  Curve upper;
};
/// Scales the settings of `base` (the macro defaults) to the surfaces as above; `base` values
/// other than the defaults are scaled all the same (pass the defaults). Errors: a face with fewer
/// than two distinct x or a non-finite point.
Result<TiltScaling> scale_tilt_defaults(const Curve& lower, const Curve& upper,
                                        const TiltConfig& base = default_tilt_config());
/// The largest spheroradius over the point spacing of the surfaces (unitless): beyond it one
/// rounded contact spans more than 20 points of each face, each a pushing vertex-edge pair, and
/// the rounded faces no longer follow the scan.
inline constexpr double kTiltMaxRadiusOverSpacing = 10;

/// The tilt test's settings for two surfaces, as every front end takes them (`frictal tilt`,
/// Python's tilt(), one call): the defaults of a surface of period `period` and scale `scale`
/// (tilt_config_for_surface; measured surfaces: 0, 0) scaled to the surfaces
/// (scale_tilt_defaults), the period and run-away distance kept where the surface gives them
/// (period > 0, scale > 0), then the `given` settings (SI, by field name) over them. Measured
/// surfaces (period and scale both <= 0) default to the protocol whose angle is a friction angle
/// of the surfaces (tilt_validity; docs/dem.md sec. 5, "The protocol on measured surfaces"): the
/// quasi-static protocol with the rotation held, each where not given (TiltScaling::
/// measured_defaults). The paper's constant-rate protocol with a free block turns or slides before
/// the rigid model's hold angle on every measured scan in tests/data. The result's
/// `config` is the run's; its `settings` list what was scaled and not given. Errors, each saying
/// what is expected: a bad given value; a height range above the length (z and x in different
/// units); a spheroradius beyond kTiltMaxRadiusOverSpacing point spacings.
/// A measured pair (period and scale <= 0) of profiles states the test that `frictal predict` states
/// (hold.hpp's stated_test: TiltScaling::test): the block the middle piece of the upper profile,
/// `block_length` long (> 0: given; 0: kBlockPerRunaway d; < 0: the whole upper profile over the
/// first half of the lower one) (unit: m), d the stated one unless runaway_distance is given, the
/// defaults scaled to that block, the drop at the middle of predict's drop range unless
/// initial_offset is given (in the signature's frame), and the model's spread over drops over the
/// same drops (TiltConfig::spread_*). Scans too short for the default test give way to the
/// largest that fits (TiltStatedTest::warnings: scan-too-short); stated lengths that do not fit
/// are refused. Generated surfaces (period or scale > 0) keep the paper's blocks: block_length 0
/// only. TiltScaling::upper is the upper surface the run takes.
Result<TiltScaling> tilt_setup(const Curve& lower, const Curve& upper, const ValueSet& given, double period = 0,
                               double scale = 0, double block_length = 0);

/// `base` with the given values (SI; names from tilt_settings(), else an error naming the
/// nearest) checked and applied.
Result<TiltConfig> make_tilt_config(const ValueSet& si_values, const TiltConfig& base = default_tilt_config());
/// Every setting of the table as it is in `config` (SI).
ValueSet tilt_values(const TiltConfig& config);

/// Time series of Fig. 7, one row per `series_interval`.
struct TiltSeries {
  std::vector<double> time;              ///< (unit: s)
  std::vector<double> tilt;              ///< tilt of the lower block, >= 0 (unit: rad)
  std::vector<double> normal_force;      ///< F_n: contact force on the upper block normal to the lower block (unit: N)
  std::vector<double> tangential_force;  ///< F_t: along the lower block, positive resisting the slide (unit: N)
  std::vector<double> force_angle;       ///< atan2(F_t, F_n) (unit: rad)
  std::vector<double>
      displacement;  ///< relative displacement d since the end of settling (during settling: since placement) (unit: m)
  std::vector<double> velocity;  ///< relative velocity v (unit: m/s)
  std::vector<int> contacts;     ///< vertex-edge pairs in contact
};

/// Poses of both blocks at one time (shapes are in TiltResult::lower_polygon/upper_polygon).
struct TiltFrame {
  double time = 0;              ///< (unit: s)
  double tilt = 0;              ///< (unit: rad)
  dem::Vec2 position[2];        ///< centroids of lower, upper (unit: m)
  double angle[2] = {0, 0};     ///< rotations from the initial orientation (unit: rad)
  double normal_force = 0;      ///< F_n on the upper block, as in TiltSeries (unit: N)
  double tangential_force = 0;  ///< F_t on the upper block, as in TiltSeries (unit: N)
  /// The touching vertex-edge pairs (dem::contact_forces; vertex body 0 = lower, 1 = upper).
  std::vector<dem::ContactForce> contacts;
};

/// The scales `run_tilt` compares before it runs (TiltResult::scales, docs/dem.md sec. 6).
struct TiltScales {
  /// W / k_n: overlap of one contact carrying the upper block (unit: m); Hertz law: that contact
  /// on the sharpest vertex of the faces, (3 W / (4 E* sqrt(R_min)))^(2/3).
  double resting_overlap = 0;
  double spheroradius = 0;              ///< r (unit: m)
  double shortest_edge[2] = {0, 0};     ///< shortest edge of the lower, upper face (unit: m)
  double smallest_feature[2] = {0, 0};  ///< shortest run between neighbouring extrema of each face (unit: m)
  double time_step = 0;                 ///< the fixed step, or the adaptive step's cap (unit: s)
  /// 2 pi sqrt(m_upper / k_n): one contact's period (unit: s); Hertz law: k_n the tangent stiffness
  /// of that resting contact (dem::contact_stiffness).
  double contact_period = 0;
};

/// The run-away at one of TiltConfig::runaway_checkpoints.
struct TiltCheckpoint {
  double distance = 0;        ///< the run-away distance (unit: m)
  bool reached = false;       ///< a run-away of this length happened before the run stopped
  double friction_angle = 0;  ///< tilt at the start of that run-away (unit: rad); NaN if not reached
  double slide_time = 0;      ///< time of that start (unit: s); NaN if not reached
  /// Relative displacement at that start, since the end of settling: how far the block had
  /// crept or slipped before the run-away (unit: m); NaN if not reached.
  double slide_start_displacement = 0;
};

struct TiltResult {
  bool slid = false;  ///< a run-away was detected before max_tilt
  /// phi: tilt at the start of the run-away (unit: rad). Constant rate: the tilt at the end of
  /// the last stick. Quasi-static: the tilt of the last increment after which the upper block
  /// relaxed to rest (relax_force, relax_speed) before the increment whose relaxation carried it
  /// runaway_distance from that rest.
  double friction_angle = 0;
  double slide_time = 0;  ///< time of that moment (unit: s)
  /// Relative displacement at the start of the run-away, since the end of settling (unit: m).
  double slide_start_displacement = 0;
  /// Relative displacement when the run stopped, since the end of settling (unit: m).
  double final_displacement = 0;
  std::vector<TiltCheckpoint> checkpoints;  ///< one per TiltConfig::runaway_checkpoints, same order
  double predicted_theta_max = 0;           ///< signature theta_max in the sliding direction (unit: rad)
  double predicted_friction_angle = 0;      ///< theta_max + atan(mu_a) (unit: rad); 0 if !predict
  /// The same for the simulated spheropolygon blocks: the signature of one core against the other
  /// dilated by 2r (SignatureOptions::spheroradius = radius), theta_max in the sliding direction
  /// and theta_max + atan(mu_a) (unit: rad); 0 if !predict.
  double predicted_sphero_theta_max = 0;
  double predicted_sphero_friction_angle = 0;
  /// Where the upper block rests when the loading starts, in the signature's offset convention:
  /// initial_offset plus its displacement along the lower block's x axis during settling (unit: m).
  double rest_offset = 0;
  /// Hold angles (hold.hpp) of a block put down at rest_offset, for this run's runaway_distance
  /// and mu_a, in the sliding direction (unit: rad); NaN if !predict or the hold analysis failed
  /// (see `hold_error`):
  /// phi_qs and phi_in of the rigid profiles, phi_qs of the spheropolygons (radius r).
  double predicted_hold_angle = std::numeric_limits<double>::quiet_NaN();
  double predicted_inertial_hold_angle = std::numeric_limits<double>::quiet_NaN();
  double predicted_sphero_hold_angle = std::numeric_limits<double>::quiet_NaN();
  /// The stop that holds in the rigid prediction (HoldAngle::hold_offset), in the signature's
  /// offset convention like rest_offset (unit: m); NaN when not computed.
  double predicted_hold_offset = std::numeric_limits<double>::quiet_NaN();
  std::string hold_error;  ///< why the hold angles are NaN ("" when computed)
  /// The rigid model's quasi-static hold angle over drops for this test (these blocks, this
  /// runaway_distance and mu_a, drops spread over the offsets of the signature's range, hold.hpp's
  /// analyse_hold), in the sliding direction: its 5 %, 50 % and 95 % quantiles (unit: rad); NaN if
  /// !predict or that analysis failed (spread_error). One drop's reading lies outside this range
  /// where its rest is a basin that few drops reach (tilt_spread_note).
  double predicted_spread_q05 = std::numeric_limits<double>::quiet_NaN();
  double predicted_spread_q50 = std::numeric_limits<double>::quiet_NaN();
  double predicted_spread_q95 = std::numeric_limits<double>::quiet_NaN();
  std::string spread_error;  ///< why the spread is NaN ("" when computed)
  /// Quasi-static protocol: increments taken, and those whose relaxation ran out of relax_time.
  int increments = 0;
  int unrelaxed_increments = 0;
  dem::ContactRule contact_rule = dem::ContactRule::Pairs;  ///< the rule the run used (contact_rule resolved)
  /// check_stiffness: the friction angle at 10 k_n (unit: rad; NaN when not checked or no slide).
  double stiff_friction_angle = std::numeric_limits<double>::quiet_NaN();
  /// Largest |rotation of the upper block relative to the lower one| between the end of
  /// settling and the slide (the end of the last stick; the end of the run if it did not slide)
  /// (unit: rad). 0 with hold_rotation.
  double rotation_before_slide = 0;
  /// The first creep event (TiltConfig::warn_creep_slip): tilt at the end of the stick it left
  /// (unit: rad) and the length of the slip (unit: m); NaN when there was none.
  double first_creep_tilt = std::numeric_limits<double>::quiet_NaN();
  double first_creep_slip = std::numeric_limits<double>::quiet_NaN();
  TiltScales scales;
  TiltEstimate estimate;  ///< the cost estimated before the first step
  /// A run outside the model the prediction assumes, before the run (scales), then from it (code:
  /// "core-overlap", "rounding", "time-step", "unsettled", "rotation", "creep", "unrelaxed"
  /// (quasi-static: an increment, or the settling, did not relax to rest within relax_time),
  /// "stiffness" (check_stiffness: 10 k_n moves the angle by more than warn_stiffness_angle);
  /// message: what was compared, with numbers and SI units).
  std::vector<Warning> warnings;
  double initial_offset = 0;  ///< offset used (unit: m)
  double simulated_time = 0;  ///< (unit: s)
  std::uint64_t steps = 0;
  double wall_time = 0;   ///< wall time of the time stepping only (unit: s)
  double setup_time = 0;  ///< wall time of building blocks, placement, predictions (hold angles included) (unit: s)
  dem::StepTimings timings;
  std::uint64_t steps_beyond_limit = 0;   ///< steps above the explicit stability limit (warnings)
  double min_time_step = 0;               ///< smallest step taken (unit: s)
  double max_time_step = 0;               ///< largest step taken (unit: s)
  double lower_mass = 0, upper_mass = 0;  ///< (unit: kg)
  double normal_damping = 0;              ///< gamma_n used (from `restitution` if set) (unit: 1/s)
  std::size_t lower_vertices = 0, upper_vertices = 0;
  double settled_overlap = 0;  ///< largest overlap at the end of settling (unit: m)
  int settled_contacts = 0;
  /// Hertz law: the mean over the contacts at the end of settling of overlap / R, R the pair's
  /// composite radius of curvature (dem::ContactForce::curvature_radius); the contact radius over R
  /// is its square root (unitless). NaN for the linear law or without contacts.
  double settled_interference_ratio = std::numeric_limits<double>::quiet_NaN();
  /// Hertz law: the contact modulus E* the run used (unit: Pa); 0 for the linear law.
  double contact_modulus = 0;
  /// Sliding speed of the upper block against the lower one along the lower block's x axis at the
  /// end of settling (the start of its last step, before the tilt reaches the block); above
  /// stick_speed the "unsettled" warning fires: the block is not at rest where the prediction
  /// starts (unit: m/s)
  double settled_speed = 0;
  /// Core polygons in the bodies' local frames (relative to the centroid, counter-clockwise).
  std::vector<double> lower_polygon_x, lower_polygon_y, upper_polygon_x, upper_polygon_y;  ///< (unit: m)
  TiltSeries series;
  std::vector<TiltFrame> frames;
};

/// The force law's contact rule a run with `config` uses: TiltConfig::contact_rule, with Auto
/// resolved by the protocol (pairs for constant-rate, closest for quasi-static).
dem::ContactRule tilt_contact_rule(const TiltConfig& config);

/// Runs the tilting test. `lower_surface` and `upper_surface` are both given as measured; for a
/// block on a copy of itself pass the same curve twice. Errors: invalid config or surfaces,
/// non-simple block polygons, stability guard failures (with a suggested time step).
Result<TiltResult> run_tilt(const Curve& lower_surface, const Curve& upper_surface, const TiltConfig& config = {});

/// Writes the series as CSV (time_s, tilt_deg, fn_N, ft_N, force_angle_deg, displacement_m,
/// velocity_m_s, contacts).
Status write_tilt_series_csv(const std::string& path, const TiltSeries& series);
/// The warnings that `run_tilt` issues before it runs, from the scales and both predictions
/// (predicted_* of `result`; "rounding" only if config.predict).
std::vector<Warning> tilt_scale_warnings(const TiltScales& scales, const TiltResult& result, const TiltConfig& config);

/// Writes the frames as VTK XML PolyData for ParaView into directory `dir` (created if missing):
/// per frame i, bodies_<i>.vtp (the two core polygons as polygons and their rounded outlines,
/// cores offset by the spheroradius `radius` with arcs at convex corners, as lines; cell data
/// body = 0 lower / 1 upper, kind = 0 core / 1 outline; field data time, tilt in degrees, F_n, F_t
/// and atan(F_t/F_n) in degrees) and contacts_<i>.vtp (one vertex per touching pair at the contact
/// point, point data normal (unit), normal_force and tangential_force (vectors on the vertex
/// body, N), overlap (m), vertex_body); and tilt.pvd, the time index of both parts. Coordinates
/// in metres (z = 0). Returns the paths written (the .pvd first). Needs frames (frame_interval > 0).
Result<std::vector<std::string>> write_tilt_vtk(const std::string& dir, const TiltResult& result, double radius);

/// World coordinates of body b's core polygon (0 lower, 1 upper) in `frame` (unit: m).
void tilt_frame_polygon(const TiltResult& result, const TiltFrame& frame, int b, std::vector<double>& x,
                        std::vector<double>& y);
/// The rounded outline of that polygon: each edge offset outwards by `radius`, joined by arcs
/// (steps of at most `max_arc_step` rad) at convex corners and by the offsets' crossing-free
/// joint at concave ones (unit: m).
void rounded_outline(const std::vector<double>& x, const std::vector<double>& y, double radius, double max_arc_step,
                     std::vector<double>& ox, std::vector<double>& oy);

/// Writes the frames in the text format of docs/dem.md ("frictal-dem-frames 1").
Status write_tilt_frames(const std::string& path, const TiltResult& result);

/// A frames file read back (write_tilt_frames): the bodies' core polygons and each frame's pose.
struct TiltFramesFile {
  /// Core polygons relative to the centroids, at the initial orientation (unit: m).
  std::vector<double> lower_polygon_x, lower_polygon_y, upper_polygon_x, upper_polygon_y;
  /// time, tilt, position and angle of each frame; the file has no forces or contacts (0, empty).
  std::vector<TiltFrame> frames;
};

/// Reads a file written by write_tilt_frames (docs/dem.md, "frictal-dem-frames 1"). Errors: Io
/// (cannot open), InvalidInput naming the file, the line and what was expected there.
Result<TiltFramesFile> read_tilt_frames(const std::string& path);

/// The surfaces a tilt run was given, as the front ends state them ("surface"): measured files
/// with what conditioning did to them, or a generator with its parameters.
struct TiltSurface {
  std::string lower;         ///< the lower surface's file (empty: generated, or not a file)
  std::string upper;         ///< the upper surface's file, as measured (the lower one when not given)
  std::string conditioning;  ///< every conditioning step applied to the files, with its numbers
  std::string generator;     ///< the generator's name (empty: files)
  /// The generator's parameter table (frictal surface GENERATOR; null: files) and its values in SI.
  const std::vector<Field>* parameters = nullptr;
  ValueSet values;
  /// The test stated on a measured pair (TiltScaling::test); null or an empty block: none.
  const TiltStatedTest* test = nullptr;
};

/// A tilt run as the front ends report it: the result with the configuration that produced it.
struct TiltReport {
  const TiltResult& result;
  const TiltConfig& config;
  /// How the defaults were scaled to the surfaces ("scaled_defaults"); none: not written.
  const TiltScaling* scaling = nullptr;
  /// The surfaces as given ("surface"); none: not written.
  const TiltSurface* surface = nullptr;
  /// Every warning of the run's inputs and of the run, the inputs' first ("warnings"; the files'
  /// reader and plausibility checks, then TiltResult::warnings); none: the run's alone.
  const std::vector<Warning>* warnings = nullptr;
};
/// Whether a run's friction angle is a friction angle of the surfaces (`friction_angle_valid`):
/// "valid", or why not, with the option that would make it so (`validity`; every front end prints
/// it). Not valid: no slide; the block turned (warning rotation); or the angle lies outside the
/// rigid model's bracket from the block's own rest, [phi_in - t, max(phi_qs, phi_qs of the rounded
/// blocks) + t] with t = max(0.1 deg, one tilt increment) (docs/dem.md: the validated runs read
/// inside it). Without the hold angles (hold_error) the bracket is not checked.
std::string tilt_validity(const TiltResult& result, const TiltConfig& config);

/// Where a run's friction angle lies against the rigid model's spread over drops for the same test
/// (TiltResult::predicted_spread_*): inside the 5-95 % range (within the bracket's tolerance t of
/// tilt_validity), or outside it and why, for a valid run the hold angle of the basin its block
/// came to rest in. Empty without a slide or without the spread.
std::string tilt_spread_note(const TiltResult& result, const TiltConfig& config);

/// The tilt test's output tables (frictal/outputs.hpp; src/tilt/tilt_columns.cpp): `frictal tilt
/// --json` and its nested objects "scales", "estimate", "stage_time_s", "scaled_defaults",
/// "surface" (tilt_surface_columns, with a generator's parameters) and "settings" (every tilt
/// setting in its text unit).
const Columns<TiltReport>& tilt_columns();
/// The surfaces as given ("surface"): the files and their conditioning, or the generator's name.
const Columns<TiltSurface>& tilt_surface_columns();
const Columns<TiltScales>& tilt_scales_columns();
const Columns<TiltEstimate>& tilt_estimate_columns();
const Columns<dem::StepTimings>& tilt_stage_time_columns();
const Columns<TiltScaling>& tilt_scaling_columns();
/// One setting that scale_tilt_defaults changed: "scaled_defaults"' "settings" (JSON in the
/// setting's text unit, Python in SI).
const Columns<TiltScaledSetting>& tilt_scaled_setting_columns();
/// The time series of a run (Python tilt()'s "series").
const Columns<TiltSeries>& tilt_series_columns();
/// A frames file read back (Python read_tilt_frames(); table "tilt_frames").
const Columns<TiltFramesFile>& tilt_frames_columns();

}  // namespace frictal
