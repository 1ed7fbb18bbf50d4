// frictal — what a tilt test measures: the hold angle of a block resting at one offset, its
// inertial bound, and their distribution over drops (the derived counterpart of Eq. 18).
//
// The signature's theta_max (Eq. 6) is the steepest contact slope over *all* offsets: an upper
// bound for a rigid pair. A tilt test puts the upper block down at one offset and reads the tilt
// at which it slides a run-away distance d. For rigid blocks that do not rotate the block moves on
// the lift h(s) (signature.hpp) under the tilted potential h(s) cos(beta) - s sin(beta):
//
// - Rest offset. Put down at s0 at zero tilt, the block slides downhill on h to the local
//   minimum whose basin holds s0 (on a flat piece it stays at s0).
// - Quasi-static hold angle phi_qs(s0, d) (inertia dissipated at every stop). The block stays
//   where the forward slope of h just ahead of it is at least tan(tilt). When the tilt passes the
//   slope that holds it, it slips forward to the first offset whose forward slope is strictly
//   larger (the next record of the forward slope). The run-away is the first slip of length
//   >= d from the last stop; a slip that runs off the end of the lift's range counts as one.
//   phi_qs = atan(mu_a) + atan(slope of the stop before the run-away).
// - Inertial bound phi_in(s0, d) (no dissipation). A block at rest at s_r coasts a distance d at
//   tilt beta if no point of h over (s_r, s_r + d] lies above the line of slope tan(beta) through
//   (s_r, h(s_r)): phi_in = atan(mu_a) + atan(steepest chord of h ahead of the rest offset).
// - Distribution over drops. Drops spread uniformly over an offset range rest in the basins of
//   h; each basin's hold angle weighted by the length of the drop range it drains is the
//   distribution that repeated tests of the pair would give.
// Backward sliding (towards -x) is the same on the mirrored lift.
//
// h is piecewise linear for rigid polylines; between two events of the exact signature it is
// convex, and the one-sided slopes at the events (SignatureResult::theta_left/right) are exact.
// lift_curve() turns a signature into a piecewise-linear LiftCurve by placing, between two
// events whose one-sided slopes differ, a vertex where the two tangent lines meet: exact where h
// has one kink between the events (the hold angles, which are slopes at stops, are exact in any
// case when d exceeds the event spacing; a stop inside such an interval is placed at the
// tangents' meeting point). On the arcs of a spheroradius signature (concave pieces) the same
// construction keeps the exact tangent slopes at the listed points.
//
// Everything here is exact on the LiftCurve and linear in its number of vertices (records and
// basins: one pass with a stack each), apart from the steepest chords (monotone hulls with
// rollback over windows of length d: a binary search per rest). The library neither prints nor
// keeps state.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "frictal/outputs.hpp"
#include "frictal/result.hpp"
#include "frictal/signature.hpp"

namespace frictal {

/// The lift h(s) as a continuous piecewise-linear function of the offset.
struct LiftCurve {
  std::vector<double> offset;  ///< vertices s_k, strictly increasing (unit: m)
  std::vector<double> lift;    ///< h(s_k) (unit: m)
  /// > 0: h(s + period) = h(s), and the vertices span exactly one period from offset.front()
  /// (offset.back() = offset.front() + period, lift.back() = lift.front()) (unit: m).
  double period = 0;
};

/// The LiftCurve of a signature (see the header comment). `period` > 0 marks a periodic lift
/// whose signature covers exactly one period (the signature's default range for a periodic
/// lower surface). Errors: fewer than two offsets, offsets not increasing, or a period that
/// does not match the signature's range.
Result<LiftCurve> lift_curve(const SignatureResult& signature, double period = 0);

struct HoldOptions {
  double runaway_distance = 0;  ///< d > 0: the run-away length that a test reads (unit: m)
  double atomic_friction = 0;   ///< mu_a >= 0, added as atan(mu_a) (Eq. 6) (unitless)
  /// Range of the drops for the distribution (unit: m). drop_max <= drop_min: the whole curve
  /// (one period for a periodic curve).
  double drop_min = 0;
  double drop_max = 0;
  /// Threads for the two directions of the distribution (0: up to two; analyse_hold and
  /// signature_with_hold take SignatureOptions::threads). The result does not depend on it.
  unsigned threads = 0;
  /// analyse_hold and signature_with_hold: keep the lift in HoldAnalysis::curve (false: the
  /// curve is left empty and its memory let go once analysed; every other number is the same).
  bool keep_curve = true;
  /// analyse_hold and signature_with_hold, exact offsets on a non-periodic pair: where the whole
  /// overlap holds about this many offsets or fewer (estimated from the signature's density of
  /// offsets), the lift is computed over all of it at once instead of in rounds that stop where
  /// local checks at each end say the process stops (a saving for long pairs only; on about 1 %
  /// of small random pairs the analysis then widens a cut end the checks passed). 0: always the
  /// rounds (unit: offsets).
  double whole_lift_offsets = 1e5;
};

/// The test of one direction from one drop.
struct HoldAngle {
  double rest_offset = 0;  ///< where the block rests at zero tilt (unit: m)
  double hold_angle = 0;   ///< phi_qs: atan(mu_a) + atan(slope of the stop that held) (unit: rad)
  double hold_slope = 0;   ///< forward slope of h at that stop, tan of the contact slope (unitless)
  double hold_offset = 0;  ///< the stop that held, from which the run-away slip starts (unit: m)
  /// End of the run-away slip (the next stop, at least d ahead), or NaN when it runs off the
  /// end of the curve or never stops (a global maximum of the slope of a periodic lift) (unit: m).
  double runaway_end = 0;
  int slips = 0;                   ///< short slips (< d) between the rest and the run-away
  bool ran_off_end = false;        ///< the run-away ran off the end of the curve's range
  double inertial_hold_angle = 0;  ///< phi_in: atan(mu_a) + atan(steepest chord) (unit: rad)
  double inertial_slope = 0;       ///< the steepest chord's slope (unitless)
  double inertial_offset = 0;      ///< where the steepest chord ends (unit: m)
};

/// Forward (towards +x) and backward (towards -x; offsets and slopes in the lift's frame, the
/// angles positive).
struct HoldAngles {
  HoldAngle forward;
  HoldAngle backward;
};

/// Weighted statistics of an angle over drops (unit: rad).
struct HoldStatistics {
  double mean = 0;
  double std = 0;  ///< weighted population standard deviation
  double q05 = 0;  ///< quantiles of the weighted distribution (the lower value at a jump)
  double q50 = 0;
  double q95 = 0;
  double min = 0;
  double max = 0;
};

/// The basins of h over the drop range and what each gives, one direction.
struct HoldBasins {
  std::vector<double> rest;      ///< rest offset of the basin (unit: m)
  std::vector<double> weight;    ///< length of the drop range that drains into it (unit: m)
  std::vector<double> hold;      ///< phi_qs of a block resting there (unit: rad)
  std::vector<double> inertial;  ///< phi_in (unit: rad)
};

struct HoldDistribution {
  HoldStatistics hold;      ///< phi_qs over drops
  HoldStatistics inertial;  ///< phi_in over drops
  HoldBasins basins;
  /// Drop length whose run-away ran off the end of the curve less than d from its last stop, so
  /// that the lift beyond the end could still catch it (unit: m): analyse_hold widens a lift cut
  /// short of the blocks' overlap until this is 0.
  double near_end = 0;
  double drop_min = 0, drop_max = 0;  ///< the drop range used (unit: m)
};

struct HoldDistributions {
  HoldDistribution forward;
  HoldDistribution backward;
};

/// The test from one drop offset `start` (within the curve's range; periodic curves wrap).
/// Errors: d <= 0 or not finite, mu_a < 0, a start outside the range, a malformed curve.
Result<HoldAngles> hold_angle(const LiftCurve& curve, double start, const HoldOptions& options);

/// The distribution over drops spread uniformly over [drop_min, drop_max]. Errors as above,
/// and a drop range outside the curve's.
Result<HoldDistributions> hold_distribution(const LiftCurve& curve, const HoldOptions& options);

/// Index of the basin (local minimum of h, numbered from 0 in increasing offset over the
/// curve) that each offset drains into at zero tilt; -1 for offsets outside the curve.
std::vector<std::int32_t> basin_index(const LiftCurve& curve, const std::vector<double>& offsets);

/// Offset range of the lift that the hold analysis of drops over [drop_min, drop_max] needs
/// for a non-periodic pair: the drop range widened by the run-away distance d on both sides
/// (and clipped to where the blocks overlap, (-upper_length, lower_length) in the signature's
/// frame). Lengths in m.
struct OffsetRange {
  double min = 0;
  double max = 0;
};
OffsetRange hold_lift_range(double drop_min, double drop_max, double runaway_distance, double lower_length,
                            double upper_length);

/// Default run-away distance for a pair whose signature range is [offset_min, offset_max] of a
/// period `period` (unit: m): one period for periodic surfaces (the tilt test's one wavelength),
/// else a tenth of the offset range, so that it scales with the file.
double default_runaway_distance(double offset_min, double offset_max, double period);

/// The whole analysis of a pair, as `frictal signature` and the tilt test use it.
struct HoldAnalysis {
  LiftCurve curve;                 ///< h over the range the process needs (see hold_lift_range); empty
                                   ///< with HoldOptions::keep_curve false
  double runaway_distance = 0;     ///< d used (unit: m)
  HoldDistributions distribution;  ///< drops over the signature's offset range
  bool has_start = false;          ///< `start` was given
  HoldAngles start;                ///< from the given start offset
  std::size_t events = 0;          ///< offsets of the lift's signature (exact events, or samples)
  bool exact = true;               ///< that signature evaluated every event
  /// Of those, the event offsets beyond the drops' reach whose lift could not change any number
  /// here (no chain's stop can lie among them, no inertial window reaches them), left out
  /// (HoldOptions::keep_curve false only: the curve joins the offsets around them by chords).
  std::size_t pruned = 0;
};

/// Computes the lift of `lower` against `upper` (already rotated, as signature() takes it) over
/// the range the hold process needs and analyses it (see signature_with_hold, whose hold part
/// this is; the signature part is computed too, without contacts): drops over the signature's own offset range
/// (`signature_options.offset_min/max`, else one period or half the shorter block), one start
/// if `start` is finite. `hold.runaway_distance` <= 0: default_runaway_distance of that range;
/// hold.drop_min/max are ignored. The signature options are used as given (spheroradius,
/// offsets, threads), contacts are not kept. Periodic when `lower` has a period.
Result<HoldAnalysis> analyse_hold(const Profile& lower, const Profile& upper, const SignatureOptions& signature_options,
                                  const HoldOptions& hold, double start = std::numeric_limits<double>::quiet_NaN());

/// The signature and the hold analysis of a pair.
struct SignatureWithHold {
  SignatureResult signature;  ///< what signature(lower, upper, options) returns
  HoldAnalysis hold;          ///< what analyse_hold(lower, upper, options, hold, start) returns
};

/// signature() and analyse_hold() in one pass over the lift: the faces are prepared once, the
/// signature's offsets are evaluated once, and the hold analysis reads them, with the lift
/// beyond the signature's range evaluated (with the same faces) only on the sides and as far
/// as the process reaches (non-periodic: each side from 1.55 d, widened while a run-away may leave
/// a stop, or a rest lies, less than d before a cut end; the blocks' overlap is the last end).
/// Local checks at each cut end decide the rounds; the analysis of the lift so cut confirms them
/// before the faces are let go, and widens a cut end they passed too early.
/// The lift's offsets beyond the range are those that a signature over the wider range lists
/// (every event; with `offsets` = N or sampled offsets, the wider range's own grid, from 2 d on
/// both sides), so the hold numbers are those of a lift computed over that range (with
/// keep_curve false, the blocks of them that no chain can stop in are left out past the drops'
/// reach and d, HoldAnalysis::pruned; the numbers are the same). Periodic
/// pairs: the signature's lift is one period, read as it is. Time and memory linear in the
/// lift's offsets (the chords: a binary search per rest). Spheropolygon faces (spheroradius > 0): the two are
/// computed one after the other. `start`, options and errors as analyse_hold() and signature().
Result<SignatureWithHold> signature_with_hold(const Profile& lower, const Profile& upper,
                                              const SignatureOptions& options, const HoldOptions& hold,
                                              double start = std::numeric_limits<double>::quiet_NaN());
/// The same, taking both profiles over (as signature(Profile&&, Profile&&)); the same result.
Result<SignatureWithHold> signature_with_hold(Profile&& lower, Profile&& upper, const SignatureOptions& options,
                                              const HoldOptions& hold,
                                              double start = std::numeric_limits<double>::quiet_NaN());

/// The stated test (docs/site/theory.md, "The stated test", says why these numbers; `frictal
/// predict` and `frictal tilt` on measured profiles state it): the run-away distance d (when not
/// given) is kRunawayPerSlopeCorrelation slope correlation lengths of the (conditioned) lower
/// profile (analysis.hpp's slope_correlation_length; where it has none, that many sampling
/// intervals; never less than one sampling interval), the block (when not given) the middle piece
/// of the upper profile, kBlockPerRunaway d long, d given or not. A scan holds the test when the
/// lower scan is at least L_b + kRoomPerRunaway d long and the upper one at least L_b; else the
/// largest test of the same shape that fits is stated, with the warning scan-too-short. None of
/// them is a fraction of the scan's length: a crop of a stationary surface has the same defaults
/// within the estimate's scatter (unitless counts). The map model's default d is the same count of
/// slope correlation lengths along the direction (map_hold.hpp's default_map_runaway_distance).
inline constexpr double kRunawayPerSlopeCorrelation = 12.5;
inline constexpr double kBlockPerRunaway = 20;
inline constexpr double kRoomPerRunaway = 8;
/// Drops keep this many d from each end of the offsets where the block lies wholly on the lower
/// scan, so that a run-away has room before it slides off the scan (unitless).
inline constexpr double kEndRoomPerRunaway = 2;
struct StatedTest {
  double runaway_distance = 0;  ///< d (unit: m)
  double block_length = 0;      ///< L_b (unit: m)
  std::string rule;             ///< how d was derived, with its numbers (text)
};
/// The default test for a profile pair whose (conditioned) lower profile is `lower`.
StatedTest default_test_lengths(const Profile& lower);

/// The stated test of a non-periodic profile pair, fitted to the scans (stated_test).
struct StatedTestFit {
  double runaway_distance = 0;  ///< d (unit: m)
  /// L_b as stated (the piece stated_block cuts is L_b to the nearest samples); the whole block:
  /// the upper profile's length (unit: m)
  double block_length = 0;
  /// The whole upper profile, dropped over the first half of the lower one (block_length < 0 asked
  /// for it): the signature's own drop range, no piece cut.
  bool whole = false;
  /// How d and L_b were set: given, or the default's rule with its numbers (text; predict's
  /// test_lengths).
  std::string rule;
  /// scan-too-short where a defaulted length gave way to the scans (warnings.hpp's code).
  std::vector<Warning> warnings;
};
/// The test on a lower profile `lower` (conditioned) and an upper profile `upper_length` long
/// (unit: m): `runaway_distance` d (> 0: given; 0: default_test_lengths) and `block_length` L_b
/// (> 0: given; 0: kBlockPerRunaway d; < 0: the whole upper profile, dropped over the first half of
/// the lower one) (unit: m). Where the scans are too short for it, a defaulted length gives way
/// (the largest test of the same shape; a given d keeps its value and the block shrinks to at
/// least 2 d; a given block keeps its length and d shrinks to at least a hundredth of the
/// default), warned scan-too-short; stated lengths that leave no room are refused, the error
/// naming the lengths needed and the options that change them.
Result<StatedTestFit> stated_test(const Profile& lower, double upper_length, double runaway_distance,
                                  double block_length);

/// The block of the stated test: the middle piece [mid - L_b / 2, mid + L_b / 2] of `upper` (as
/// measured), its ends on the profile's nearest samples (a tie outward), so that on a uniform
/// grid the turned-over block stays on the lower scan's lattice; a piece of fewer than 8 samples
/// keeps its stated ends, interpolated (unit of `block_length`: m).
Profile stated_block(const Profile& upper, double block_length);

/// The offsets and drops of the stated test in the signature's frame (0: the left ends aligned;
/// unit: m): the offsets [0, L - L_b] at which a block `block_length` long lies wholly over a lower
/// scan `lower_length` long, and the drops over them less kEndRoomPerRunaway d at each end.
struct StatedDrops {
  double offset_min = 0, offset_max = 0;  ///< (unit: m)
  double drop_min = 0, drop_max = 0;      ///< (unit: m)
};
StatedDrops stated_drops(double lower_length, double block_length, double runaway_distance);

/// `curve` cut to the offsets [a, b] (clipped to its range), its ends interpolated: the lift a
/// stated block runs on (a slip that reaches an end has slid off the scan).
LiftCurve cut_lift_curve(const LiftCurve& curve, double a, double b);

/// The hold analysis' output tables (frictal/outputs.hpp; src/hold/hold_columns.cpp): the flat keys
/// of `frictal signature --json` (hold_columns; hold_start_columns with --start-offset) and the
/// nested dicts of Python's hold_angle() (hold_columns' Python keys, hold_distribution_columns,
/// hold_statistics_columns, hold_basins_columns, hold_drop_columns).
const Columns<HoldAnalysis>& hold_columns();
const Columns<HoldAnalysis>& hold_start_columns();
const Columns<HoldDistribution>& hold_distribution_columns();
const Columns<HoldStatistics>& hold_statistics_columns();
const Columns<HoldBasins>& hold_basins_columns();
const Columns<HoldAngle>& hold_drop_columns();

}  // namespace frictal
