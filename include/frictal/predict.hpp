// frictal — the prediction: what a tilt test of two surfaces reads. The one answer that every
// front end shows (`frictal predict`, Python `frictal.predict`, the report's headline); the other
// analyses keep their own names (docs/theory: "The prediction").
//
// A tilt test puts the upper block down at some offset and reads the tilt at which it slides
// away. Repeated tests drop it at different offsets, so the answer is a distribution over drops
// of the quasi-static hold angle (hold.hpp for profiles; for maps the block free to move
// sideways, the off-grid rigid model of areal_tilt.hpp that the 3D engine checked): its median
// is the headline (friction_angle.q50, atomic friction included), 5-95 % its spread. Beside it
// the rigid upper bound theta_max + theta_a (Eq. 6 of Alonso-Marroquín et al., Phys. Rev. E
// 2015), which a test reaches only where the block can get to the steepest contact (the paper's
// Koch surfaces), and the paper's Eq. 18 range [theta_max - sigma, theta_max] + theta_a. For maps
// the bound comes from the hold angles' own model: the steepest slope along d, friction cones
// included, of the contacts of every seat a drop rested in (ArealTiltHold::seat_bound), so that it
// lies above every drop by construction.
//
// The surfaces are conditioned first (conditioning.hpp: an optional crop, optional spike removal,
// then form removal: a line for profiles, a plane for maps by default), and the result lists
// what was applied. Plausibility warnings (warnings.hpp) of the conditioned inputs and of the
// result travel with it. Lengths in m, angles in rad.
#pragma once

#include <array>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "frictal/analysis.hpp"
#include "frictal/conditioning.hpp"
#include "frictal/contact.hpp"
#include "frictal/geometry.hpp"
#include "frictal/hold.hpp"
#include "frictal/io.hpp"
#include "frictal/map.hpp"
#include "frictal/map_hold.hpp"
#include "frictal/outputs.hpp"
#include "frictal/result.hpp"
#include "frictal/warnings.hpp"

namespace frictal {

struct PredictOptions {
  /// Sliding direction, from +x towards +y (unit: rad). Profiles: 0 (+x) or pi (-x) only.
  double direction = 0;
  double atomic_friction = 0;  ///< mu_a >= 0 (unitless)
  /// The stated test (docs/theory.md, "The stated test"). Run-away distance d: how far the block
  /// must slide from its last stop to count as sliding for good (unit: m); 0: the default,
  /// default_test_lengths() for profiles, default_map_runaway_distance() for maps (never a
  /// fraction of the scan).
  double runaway_distance = 0;
  /// Profiles: the block's length L_b, the piece of the upper surface (its middle) that slides
  /// over the lower one; drops over every offset at which it lies wholly over the lower scan
  /// (unit: m). 0: the default, kBlockPerRunaway d. < 0: the whole upper profile, dropped over
  /// the first half of the lower one (partly overhanging its end: the blocks of `frictal tilt
  /// --block-length whole` and of `frictal signature`'s hold analysis). A periodic pair (`period`) slides the
  /// whole upper profile, as the paper's blocks: 0 only. Maps: 0 only (the whole upper map).
  double block_length = 0;
  /// Form removal before the prediction; nullopt: a line for profiles (the mean for periodic
  /// ones, which have no form), a plane for maps (the default of every front end).
  /// DetrendKind::None opts out.
  std::optional<Detrend> detrend;
  /// Before the form removal (conditioning.hpp, in this order): keep the window `crop` of each
  /// surface (in each surface's own coordinates; nullopt: all of it), then, with `remove_spikes`,
  /// replace (profiles) or mask (maps) the points more than `spike_threshold` rms heights from the
  /// median of their neighbours. `crop_source` names the window in messages.
  std::optional<CropWindow> crop;
  std::string crop_source = "crop";
  bool remove_spikes = false;
  double spike_threshold = kDefaultSpikeThreshold;  ///< k (unitless, > 0)
  /// One drop at this offset instead of the distribution (x for profiles; x, y for maps; in the
  /// signature's frame of offsets: 0 = left ends aligned for profiles, the blocks' centres
  /// aligned for maps) (unit: m). NaN: the distribution over drops.
  std::array<double, 2> start_offset = {std::numeric_limits<double>::quiet_NaN(), 0};
  /// Profiles: > 0 marks both profiles periodic with this period (files do not store it; the
  /// generators set it): drops over one period, the run-away one period (unit: m). 0: as given.
  double period = 0;
  /// Maps: drops on a drops x drops grid over the drop range (unitless, >= 2). Each drop costs
  /// 0.2-0.7 s of one core on 10^5-10^6-point maps (bench/results/map-predict.md).
  int map_drops = 5;
  /// Maps: sphere radius r of the upper face's nodes (0: a fifth of the lower map's smaller spacing) (unit: m).
  double sphere_radius = 0;
  /// Maps: also the block with its lateral motion locked (a diagnostic), from the same drops
  /// (doubles the cost).
  bool map_locked = false;
  /// Maps: true (the default): the upper map is the upper face as measured, turned over onto the
  /// lower one; offsets count from the two maps' centres aligned. false: it is the upper face
  /// already in place, in the lower map's coordinates (areal.hpp), and offsets count from that
  /// place (drops and start offset alike). Profiles: true only (an error otherwise).
  bool turn_over_upper = true;
  /// Maps: refuse when the continuous model's estimated CPU time, 2.5e-7 s per sphere of the upper
  /// map and drop (measured on self-affine 10^6-point maps, bench/results/map-predict.md; maps rough
  /// at the pixel scale cost up to 30x more), exceeds this (unit: s). 0: no limit.
  double map_work_limit = 3600;
  unsigned threads = 0;  ///< worker threads (0 = all cores); results do not depend on it
  /// Friction under load (docs/load.md, load.hpp: profiles the Hertzian-asperity model, maps the
  /// elastic half-space with the block locked to the direction; a map's curve for one load is
  /// W x 10^(-1..1)): the loads W pressing the upper block onto the lower one, its weight (unit: N). Empty: the rigid
  /// prediction. The first is the headline (friction_angle, d_sweep, the single drop); the load
  /// curve is over every load given, in increasing order, or for one load over W x 10^(-2..1) in
  /// half decades. At the tilt phi a block of weight W presses with W cos(phi): each lift is
  /// evaluated at W cos(phi_0), phi_0 the rigid median (Prediction::normal_load).
  std::vector<double> loads;
  /// Maps under load: the offset step of the first pass of contact solves along each line (0: the
  /// lower map's smaller spacing); intervals where the elastic correction bends are then halved
  /// down to a sixteenth of the spacing (MapLoadedLiftOptions::refine_slope), so the answer does
  /// not depend on it beyond the cost (unit: m).
  double map_load_step = 0;
  /// The materials of the loaded model (Pa, unitless): the lower block's, and the upper block's
  /// (nullopt: the same as the lower's); rigid_upper: the upper block rigid.
  ElasticMaterial lower_material;
  std::optional<ElasticMaterial> upper_material;
  bool rigid_upper = false;
  /// Maps: called as the drops go on (DropProgress: drops done, the tilt the drops under way have
  /// reached), from the worker threads (one call at a time); the front ends draw a progress line
  /// with it. Empty: none.
  DropProgressFn progress;
};

/// The prediction's settings table (settings.hpp): direction, atomic_friction, runaway_distance,
/// block_length ("whole" or a length), period, drops (map_drops), locked (map_locked), in_place
/// (not turn_over_upper), sphere_radius, map_work_limit; automatic lengths are NaN. The CLI options
/// of `frictal predict` (and those of them that `areal`, `anisotropy`, `report` and `areal-tilt`
/// offer) and the keywords of Python's predict(), beside conditioning_settings();
/// src/predict/predict_settings.cpp says which members stay outside and why.
const std::vector<Field>& predict_settings();
/// `base` with the values of predict_settings() and conditioning_settings() (SI, by field name;
/// absent: `base`'s). Errors name the field and the expected values, and the nearest name for an
/// unknown one.
Result<PredictOptions> make_predict_options(const ValueSet& si, PredictOptions base = {});

/// The prediction of one pair, one direction.
struct Prediction {
  bool is_map = false;
  /// Which model produced the distribution: "profile-quasi-static-hold" (the 1D hold angle over
  /// drops, exact on the rigid lift), "profile-hertz-asperity-hold" (the same on the loaded lift of
  /// PredictOptions::loads, load.hpp), or
  /// drops, exact on the rigid lift) or "map-continuous-free" (the 3D rigid block free to move
  /// sideways, off the grid, quasi-static: areal_tilt_hold).
  std::string model;
  /// Every conditioning step with its numbers (ConditioningRecord::text), e.g. "crop x [0.0001,
  /// 0.0009] m: kept 801 of 1001 points; spikes (k = 10 Sq): 3 points removed (replaced by
  /// linear interpolation); form: line"; for two surfaces whose records differ "lower: ... | upper: ...".
  std::string conditioning;
  std::string form;                ///< the form removed: "none", "mean", "line", "plane", "poly:N"
  std::size_t spikes_removed = 0;  ///< points replaced or masked by the spike filter, both surfaces (unitless)
  std::vector<ConditioningRecord> conditioning_records;  ///< lower, then upper (when given)
  double direction = 0;                                  ///< (unit: rad)
  double atomic_friction = 0;                            ///< mu_a (unitless)
  double runaway_distance = 0;                           ///< d used (unit: m)
  /// Profiles: the block's length L_b used (periodic pairs: the whole upper profile) (unit: m).
  double block_length = 0;
  /// How d and L_b were set: "given", or the default's rule with its numbers (text).
  std::string test_lengths;
  /// How the answer depends on d: the hold angle's median and 5-95 % over the same drops for
  /// d/4, d/2, d, 2d, 4d (those that fit in the blocks' overlap), from the one lift; the entry at
  /// d is the headline (profiles; maps: empty) (unit: m, rad).
  std::vector<double> d_sweep_distance, d_sweep_q05, d_sweep_q50, d_sweep_q95;
  bool single_drop = false;  ///< start_offset was given: the statistics are that drop's value
  std::size_t drops = 0;     ///< drops the distribution is over (profiles: basins that drain them)
  /// Drop range: profiles [min, max, 0, 0]; maps [u_min, u_max, v_min, v_max] along and across d (unit: m),
  /// offsets of the upper map's centre; for an upper map smaller than the lower one, +-((Lf - Lg) / 2 - r - D)
  /// along d and +-((Wf - Wg) / 2 - r - D) across (Lf, Lg, Wf, Wg the maps' node extents, r the sphere
  /// radius, D the run-away distance): the block's spheres lie wholly over the lower map with room D on
  /// every side, none on its edge (docs/analysis.md, "The drops of the map prediction").
  std::array<double, 4> drop_range = {0, 0, 0, 0};
  HoldStatistics friction_angle;    ///< the hold angle over drops, atan(mu_a) included (unit: rad)
  double friction_coefficient = 0;  ///< tan(friction_angle.q50) (unitless)
  /// Profiles: theta_max + theta_a (Eq. 6); maps: the largest of the drops' seat bounds (free
  /// block), at least every drop's hold angle; capped at pi/2 (unit: rad).
  double upper_bound_friction_angle = 0;
  /// Steepest contact slope along the direction: profiles the signature's maximum over its range, or
  /// the slope of a stop the rigid hold analysis read beyond it where that is steeper; maps the steepest
  /// seat slope of the drops (ArealTiltHold::seat_slope) (unit: rad).
  double theta_max = 0;
  /// sigma of Eq. 18: profiles the contact slopes' standard deviation; maps that of the drops'
  /// steepest seat slopes (unit: rad).
  double contact_slope_std = 0;
  std::array<double, 2> eq18_range = {0, 0};    ///< [max(0, theta_max - sigma), theta_max] + theta_a (unit: rad)
  std::array<double, 2> start_offset = {0, 0};  ///< single_drop: the drop (unit: m)
  std::array<double, 2> rest_offset = {0, 0};   ///< single_drop: where it rested at zero tilt (unit: m)
  /// Maps: the same drops with the block locked to d (a diagnostic; the test's block is free).
  bool has_locked = false;
  HoldStatistics locked_friction_angle;  ///< (unit: rad)
  /// Maps: each drop's hold angle, free (and locked), in drop order (unit: rad).
  std::vector<double> drop_angles, drop_angles_locked;
  /// Maps: each free drop's run-away direction, the angle from d to its displacement, towards d turned by
  /// +90 deg (areal_tilt_hold's steering) (unit: rad).
  std::vector<double> drop_steering;
  std::vector<std::array<double, 2>> drop_offsets;  ///< maps: the drops (x, y) (unit: m)
  /// Friction under load (PredictOptions::loads; NaN and empty without): the headline load W
  /// (unit: N), the normal force W cos(phi_0) its lift was evaluated at (unit: N), the contact
  /// modulus E* (unit: Pa), and the rigid prediction's median beside it (unit: rad).
  double load = std::numeric_limits<double>::quiet_NaN();
  double normal_load = std::numeric_limits<double>::quiet_NaN();
  double contact_modulus = std::numeric_limits<double>::quiet_NaN();
  double rigid_friction_angle = std::numeric_limits<double>::quiet_NaN();
  /// The loaded model's limit as W -> 0, the median over the same drops (unit: rad): profiles, the
  /// rigid prediction's median (the loaded lift tends to the rigid one); maps, the block locked to
  /// d on the rigid lift of the loaded model's lines, which can differ from the free rigid block's
  /// median (warning load-locked-block).
  double load_zero_limit = std::numeric_limits<double>::quiet_NaN();
  /// The friction angle against load: the loads in increasing order (unit: N) and the hold
  /// angle's median and 5-95 % over the same drops at d at each (unit: rad).
  std::vector<double> load_curve, load_curve_q05, load_curve_q50, load_curve_q95;
  /// The asperity model at the headline load (LoadedLiftDiagnostics): contacts carrying force per
  /// offset (mean), the block's approach from first touch (mean, unit: m), the largest delta / R,
  /// the share of the load on merged contacts, the force-weighted rms contact slope (unitless).
  double load_contacts = std::numeric_limits<double>::quiet_NaN();
  double load_approach = std::numeric_limits<double>::quiet_NaN();
  double load_interference_ratio = std::numeric_limits<double>::quiet_NaN();
  double load_merged_share = std::numeric_limits<double>::quiet_NaN();
  double load_contact_slope = std::numeric_limits<double>::quiet_NaN();
  /// Maps under load (the half-space model): the largest fraction of the overlap's points in
  /// contact over the offsets at the headline load (unitless); NaN otherwise. load_contacts is then
  /// the mean number of contact patches, and load_interference_ratio, load_merged_share are NaN.
  double load_contact_fraction = std::numeric_limits<double>::quiet_NaN();
  std::vector<Warning> warnings;
  /// "ok", or "doubtful" where a warning says the input was probably read wrong (a code marked
  /// `doubtful` in warning_codes(): units, spikes left in, scans that do not match, an angle at 90
  /// deg): then the number is not the surfaces' friction until the fix is applied.
  std::string trust = "ok";
  std::vector<std::string> trust_codes;  ///< the codes that made it doubtful, in the order met
  /// The fix that exists, as options to add (Python keywords in parentheses), with the unit named
  /// where the file's unit and the slopes tell it (e.g. "--z-unit um (Python z_unit='um')"); empty
  /// when ok.
  std::string trust_fix;
};

// The stated test of profiles (default_test_lengths, stated_test, kBlockPerRunaway, ...) is
// hold.hpp's, below predict, so that the tilt test states the same test.

/// A surface as the front ends hand it over: a profile or a map, with the name that messages use
/// and the warnings its reader issued (with the reader's codes).
struct PredictSurface {
  bool is_map = false;
  Profile profile;
  Map map;
  std::string name;
  std::vector<Warning> reader_warnings;
  /// Metres per unit of the file's lateral numbers and heights as read (SurfaceData's); 0: not read
  /// from a file. The trust's fix names the unit to give from them (unit: m per file unit).
  double x_unit_scale = 0, z_unit_scale = 0;
};

/// A surface as a reader gave it (a map, or a curve that must be single-valued), named `name`,
/// with the reader's warnings. Errors: a folded curve (as_profile's, naming `name`).
Result<PredictSurface> predict_surface(SurfaceData data, const std::string& name);

/// The prediction for `lower` against `upper` turned over (nullptr: `lower` against itself).
/// Errors (InvalidInput, naming the value and the valid range): a profile and a map in one pair,
/// a profile direction other than 0 or pi, mu_a < 0, d < 0, a start offset outside the drop
/// range, maps that do not overlap along the direction, a map job above map_work_limit.
Result<Prediction> predict(const PredictSurface& lower, const PredictSurface* upper,
                           const PredictOptions& options = {});

/// As predict(lower, upper, options) (std::nullopt: `lower` against itself), taking the surfaces
/// over: a profile pair's points move through the conditioning into the signature instead of
/// being copied (10^7 points are 160 MB a copy; `frictal predict` on two such profiles peaks at
/// about the memory of `frictal signature`). The same prediction to the bit.
/// Maps are read as by the other overload.
Result<Prediction> predict(PredictSurface&& lower, std::optional<PredictSurface>&& upper,
                           const PredictOptions& options = {});

/// The map model's settings as predict() sets them for the lower map `lower` (conditioned) and
/// `o`: the direction, turn-over and mu_a of `o`; its run-away distance, else the default
/// (default_map_runaway_distance); its sphere radius, else the default (a fifth of the
/// lower map's smaller spacing: fill_map_model_defaults); MapHoldOptions' defaults for the rest.
/// The front ends that show the map model for one drop (`frictal areal-tilt`, the report's
/// two-map section) take the defaults from here, so that their hold angles are the prediction's.
MapHoldOptions map_model_options(const Map& lower, const PredictOptions& o);

/// The map prediction's estimated CPU time before it runs, the figure PredictOptions::map_work_limit
/// is compared with: 2.5e-7 s per sphere of the upper map and drop (free and locked drops count
/// each) (unit: s). For a front end that runs several predictions (e.g. over directions) to
/// refuse the whole job at once.
double map_work_estimate(std::size_t upper_spheres, std::size_t drops);

/// The prediction's output table (frictal/outputs.hpp): every key of `frictal predict --json`, of
/// Python's Prediction.to_dict() and of the report's embedded JSON, with its interface unit, its
/// meaning and its SI value (the Prediction's Python attributes are the columns' Python keys);
/// every key but "warnings", which is a list of {code, message}.
const Columns<Prediction>& prediction_columns();

/// A map prediction read as the hold angle of one lateral mode (`frictal areal --lateral`,
/// Python areal_hold()): the prediction, the mode it reports and whether the upper was in place.
struct ArealHoldReport {
  const Prediction& prediction;
  bool locked = false;    ///< the locked mode's hold angles (else the free block's)
  bool in_place = false;  ///< the upper map is the upper face in place (not turned over)
};
/// Its output table "areal_hold" (src/predict/predict_columns.cpp): the keys of `frictal areal
/// --lateral|--drops|--start-offset --json` and of Python's areal_hold() dict.
const Columns<ArealHoldReport>& areal_hold_columns();

/// The value of a column in its interface unit (degrees for "deg"; NaN/inf stay as they are).
OutputValue interface_value(const Column<Prediction>& c, const Prediction& p);

/// The prediction as one JSON object: every column in its interface unit (NaN and inf as null),
/// then "warnings": [{"code", "message"}], then `extra` (already JSON text: `"key": value` pairs
/// joined by commas, or empty). `indent` > 0: pretty, that many spaces.
std::string prediction_json(const Prediction& p, const std::string& extra = "", int indent = 2);

}  // namespace frictal
