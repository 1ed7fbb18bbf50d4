// The prediction (frictal/predict.hpp): what a tilt test of two surfaces reads, defined once.
#include "frictal/predict.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <numbers>

#include <fmt/core.h>

#include "frictal/areal.hpp"
#include "frictal/load.hpp"
#include "frictal/map_hold.hpp"
#include "frictal/signature.hpp"
#include "frictal/stats.hpp"
#include "util/parallel.hpp"

namespace frictal {

namespace {

constexpr double kPi = std::numbers::pi;

// Equal-weight statistics with the quantile rule of the profiles' distribution (the lower value
// at a jump: the smallest value whose cumulative share reaches q).
HoldStatistics plain_stats(const std::vector<double>& v) {
  HoldStatistics s;
  if (v.empty()) return s;
  std::vector<double> w(v);
  std::sort(w.begin(), w.end());
  const double n = double(w.size());
  double m = 0;
  for (double x : w) m += x;
  m /= n;
  double var = 0;
  for (double x : w) var += (x - m) * (x - m);
  s.mean = m;
  s.std = std::sqrt(var / n);
  auto q = [&](double p) {
    const double k = std::ceil(p * n * (1 - 1e-12));
    return w[std::size_t(std::clamp(k, 1.0, n)) - 1];
  };
  s.q05 = q(0.05), s.q50 = q(0.50), s.q95 = q(0.95);
  s.min = w.front(), s.max = w.back();
  return s;
}

// `bound`: the upper bound where the model gives it (maps: the seats'), else theta_max + theta_a.
void finish(Prediction& p, double theta_max, double sigma, double bound = -1) {
  const double ta = std::atan(p.atomic_friction);
  p.theta_max = theta_max;
  p.contact_slope_std = sigma;
  p.upper_bound_friction_angle = std::min(bound >= 0 ? bound : theta_max + ta, kPi / 2);
  double lo = theta_max - sigma + ta;
  if (lo < 0) {
    add_warning(p.warnings,
                {"eq18-low-clamped", fmt::format("Eq. 18's low end theta_max - sigma + theta_a = {:.4f} deg is below "
                                                 "zero; reported as 0",
                                                 lo * 180 / kPi)});
    lo = 0;
  }
  p.eq18_range = {std::min(lo, kPi / 2), p.upper_bound_friction_angle};
  for (Warning& w : check_friction_bound(p.upper_bound_friction_angle, "prediction")) add_warning(p.warnings, w);
  const double med = p.friction_angle.q50;
  p.friction_coefficient = med >= kPi / 2 ? INFINITY : std::tan(med);
  // 89.5 deg: a slope of 115, steeper than any measured contact (a wall, an interlock or units).
  constexpr double kNear90 = 89.5 * kPi / 180;
  // A bound at 90 deg that no drop comes near: a vertical contact of some seat (a block that slid
  // sideways onto the lower map's rim, a wall no drop climbs), not a reading of the surfaces; the
  // drops' hold angles stand (a held-to-max-tilt drop may lie anywhere up to the bound: not so).
  bool held_to_max = false;
  for (const Warning& w : p.warnings) held_to_max = held_to_max || w.code == "held-to-max-tilt";
  const bool bound_alone = p.friction_angle.q50 < kNear90 && p.upper_bound_friction_angle >= kNear90 &&
                           p.friction_angle.max < kNear90 && !held_to_max;
  if (bound_alone)
    add_warning(p.warnings, {"bound-at-90",
                             fmt::format("the rigid upper bound is {:.4f} deg but no drop held above "
                                         "{:.4f} deg: a seat a drop rested in has a vertical contact "
                                         "(the block against the lower map's rim, or a wall it never "
                                         "climbed); the bound is no estimate of these surfaces' friction",
                                         p.upper_bound_friction_angle * 180 / kPi, p.friction_angle.max * 180 / kPi)});
  else if (p.friction_angle.q50 >= kNear90 || p.upper_bound_friction_angle >= kNear90)
    add_warning(
        p.warnings,
        {"friction-angle-at-90",
         fmt::format(
             "the {} is {:.4f} deg: a vertical wall, an interlock or a unit mix-up holds the block; the "
             "number is a single feature of the data, not a friction",
             p.friction_angle.q50 >= kNear90 ? "hold angle's median" : "rigid upper bound",
             (p.friction_angle.q50 >= kNear90 ? p.friction_angle.q50 : p.upper_bound_friction_angle) * 180 / kPi)});
}

void reader_warnings(std::vector<Warning>& out, const PredictSurface& s) {
  for (Warning w : s.reader_warnings) {
    if (w.message.find(s.name) == std::string::npos) w.message = s.name + ": " + w.message;
    add_warning(out, std::move(w));
  }
}

Conditioning conditioning_of(const PredictOptions& o, const Detrend& form) {
  Conditioning c;
  c.crop = o.crop;
  c.crop_source = o.crop_source;
  c.remove_spikes = o.remove_spikes;
  c.spike_threshold = o.spike_threshold;
  c.form = form;
  return c;
}

// The prediction's record of the conditioning: the text of each surface's steps (one text when
// they read the same), the form and the spikes removed.
void record_conditioning(Prediction& p, std::vector<ConditioningRecord> records, bool is_map, const Detrend& form) {
  p.form = detrend_name(form, is_map);
  p.conditioning = conditioning_text(records);
  for (const ConditioningRecord& r : records) p.spikes_removed += r.spikes_removed;
  p.conditioning_records = std::move(records);
}

double mean_spacing(const Profile& p) {
  return p.x.size() > 1 ? (p.x.back() - p.x.front()) / double(p.x.size() - 1) : 0;
}

// The load model's limits (docs/load.md, "Where it stops holding"): the force-weighted rms contact
// slope of small-slope elasticity, delta / R of Hertz's a << R (a = sqrt(R delta); 0.1: a/R ~ 0.3)
// at more than 5 % of the offsets, and 10 % of the load on merged contacts (unitless).
constexpr double kLoadMaxSlope = 0.3, kLoadMaxRatio = 0.1, kLoadMaxDeepShare = 0.05, kLoadMaxMerged = 0.1;
// Maps: the share of the offsets at which more than kMapFullContact of the overlap touches
// (MapLoadedDiagnostics::full_share) beyond which the load nears full contact (unitless).
constexpr double kLoadMaxFullShare = 0.05, kMapFullContact = 0.5;

// The assumptions that a load's diagnostics break, as text ("" where none).
std::string load_breaks(const LoadedLiftDiagnostics& d) {
  std::string s;
  auto add = [&](const std::string& t) { s += (s.empty() ? "" : "; ") + t; };
  if (d.rms_contact_slope > kLoadMaxSlope)
    add(fmt::format("the force-weighted rms contact slope is {:.3g} (small-slope elasticity wants < {:g})",
                    d.rms_contact_slope, kLoadMaxSlope));
  if (d.deep_share > kLoadMaxDeepShare)
    add(
        fmt::format("at {:.3g} % of the offsets a contact's interference exceeds {:g} of its radius (largest "
                    "delta/R {:.3g}; Hertz wants delta << R)",
                    100 * d.deep_share, kLoadMaxRatio, d.max_interference_ratio));
  if (d.merged_share > kLoadMaxMerged)
    add(
        fmt::format("{:.3g} % of the load is on contacts that merge with a neighbour (the block below the saddle "
                    "between them, or their Hertz widths overlapping): they are one contact, not two spheres",
                    100 * d.merged_share));
  return s;
}

// The prediction under load (PredictOptions::loads): the loaded lift of each load of the curve
// on the rigid lift's vertices (load.hpp), each analysed as the rigid one (`analyse`: the headline
// at d, and for the headline load the d sweep, on one lift, into p), the headline load's last.
// What both models under load start from (the loads are checked at predict's entry): E*, the
// curve's loads in increasing order (one load W: W times `factors`, W itself among them; a list:
// those loads), the headline's index in it, and the normal force per unit weight.
struct LoadCurveSetup {
  double contact_modulus = 0;  ///< E* (unit: Pa)
  std::vector<double> curve;   ///< the loads (unit: N)
  std::size_t head = 0;        ///< index of the headline load o.loads[0]
  double cosine = 1;           ///< cos(phi_0) (unitless)
};
Result<LoadCurveSetup> load_curve_setup(Prediction& p, const PredictOptions& o, const std::vector<double>& factors) {
  LoadCurveSetup s;
  auto em = o.rigid_upper ? contact_modulus(o.lower_material)
                          : contact_modulus(o.lower_material, o.upper_material.value_or(o.lower_material));
  if (!em) return em.error();
  s.contact_modulus = *em;
  if (o.loads.size() == 1) {
    for (double f : factors) s.curve.push_back(f == 1 ? o.loads[0] : o.loads[0] * f);
  } else {
    s.curve = o.loads;
    std::sort(s.curve.begin(), s.curve.end());
    s.curve.erase(std::unique(s.curve.begin(), s.curve.end()), s.curve.end());
  }
  s.head = std::size_t(std::find(s.curve.begin(), s.curve.end(), o.loads[0]) - s.curve.begin());
  // The block of weight W presses with W cos(phi) at the tilt phi that moves it: evaluated at the
  // rigid median phi_0 (the loaded median differs from it by the elastic correction, whose cosine
  // changes the normal force by a second-order amount).
  p.rigid_friction_angle = p.friction_angle.q50;
  s.cosine = std::cos(std::min(p.rigid_friction_angle, 1.5));
  return s;
}

Status predict_under_load(Prediction& p, const Profile& lower, const Profile& upper, const LiftCurve& rigid,
                          const PredictOptions& o, const std::function<Status(const LiftCurve&, bool)>& analyse) {
  // One load: W x 10^(-2..1) in half decades.
  std::vector<double> factors;
  for (int k = -4; k <= 2; ++k) factors.push_back(std::pow(10.0, 0.5 * k));
  auto setup = load_curve_setup(p, o, factors);
  if (!setup) return setup.error();
  const std::vector<double>& curve = setup->curve;
  const std::size_t head = setup->head;
  const double cosine = setup->cosine;
  LoadedLiftOptions lo;
  lo.contact_modulus = setup->contact_modulus;
  lo.threads = o.threads;
  for (double w : curve) lo.loads.push_back(w * cosine);
  auto loaded = loaded_lift(lower, upper, rigid, lo);
  if (!loaded) return loaded.error();
  std::string beyond;
  for (std::size_t l = 0; l < curve.size(); ++l) {
    if (l == head) continue;
    if (auto st = analyse(loaded->curves[l], true); !st) return st;
    p.load_curve.push_back(curve[l]);
    p.load_curve_q05.push_back(p.friction_angle.q05);
    p.load_curve_q50.push_back(p.friction_angle.q50);
    p.load_curve_q95.push_back(p.friction_angle.q95);
    if (!load_breaks(loaded->diagnostics[l]).empty())
      beyond += fmt::format("{}{:.4g} N", beyond.empty() ? "" : ", ", curve[l]);
  }
  if (auto st = analyse(loaded->curves[head], false); !st) return st;
  const std::size_t at =
      std::size_t(std::lower_bound(p.load_curve.begin(), p.load_curve.end(), curve[head]) - p.load_curve.begin());
  p.load_curve.insert(p.load_curve.begin() + std::ptrdiff_t(at), curve[head]);
  p.load_curve_q05.insert(p.load_curve_q05.begin() + std::ptrdiff_t(at), p.friction_angle.q05);
  p.load_curve_q50.insert(p.load_curve_q50.begin() + std::ptrdiff_t(at), p.friction_angle.q50);
  p.load_curve_q95.insert(p.load_curve_q95.begin() + std::ptrdiff_t(at), p.friction_angle.q95);
  p.load = curve[head];
  p.normal_load = curve[head] * cosine;
  p.contact_modulus = setup->contact_modulus;
  p.load_zero_limit = p.rigid_friction_angle;  // the loaded lift tends to the rigid one (load.hpp)
  const LoadedLiftDiagnostics& dg = loaded->diagnostics[head];
  p.load_contacts = dg.mean_contacts;
  p.load_approach = dg.mean_approach;
  p.load_interference_ratio = dg.max_interference_ratio;
  p.load_merged_share = dg.merged_share;
  p.load_contact_slope = dg.rms_contact_slope;
  p.model = "profile-hertz-asperity-hold";
  if (dg.rms_contact_slope > kLoadMaxSlope)
    add_warning(p.warnings, {"load-steep-contacts",
                             fmt::format("at {:.4g} N the force-weighted rms contact slope is {:.3g}: above {:g}, the "
                                         "small-slope elasticity of the Hertzian contacts is approximate",
                                         p.load, dg.rms_contact_slope, kLoadMaxSlope)});
  if (dg.deep_share > kLoadMaxDeepShare)
    add_warning(p.warnings,
                {"load-deep-interference",
                 fmt::format("at {:.4g} N a contact's interference exceeds {:g} of its radius at {:.3g} % of the "
                             "offsets (largest delta/R {:.3g}): beyond Hertz's small contacts (a << R); the load is "
                             "more than the asperity model represents",
                             p.load, kLoadMaxRatio, 100 * dg.deep_share, dg.max_interference_ratio)});
  if (dg.merged_share > kLoadMaxMerged)
    add_warning(p.warnings,
                {"load-contacts-merge",
                 fmt::format("at {:.4g} N {:.3g} % of the load is on contacts that merge with a neighbour (the block "
                             "below the saddle between two asperities, or their Hertz widths overlapping): the "
                             "asperities are no longer separate spheres",
                             p.load, 100 * dg.merged_share)});
  // No contact force resists more than the steepest slope under it plus the atomic friction angle
  // (a contact's slope is the mean of the two surfaces' slopes there), so neither does the block.
  // Every slope of the loaded lift is a weighted mean of the rigid lift's slope and contact slopes
  // (load.hpp), so its hold angles stay below the bound by construction: the check guards that
  // invariant on the number the user gets.
  auto steepest = [](const Profile& q) {
    double m = 0;
    for (std::size_t i = 0; i + 1 < q.x.size(); ++i)
      m = std::max(m, std::abs((q.z[i + 1] - q.z[i]) / (q.x[i + 1] - q.x[i])));
    return std::atan(m);
  };
  const double resisted = std::max(steepest(lower), steepest(upper)) + std::atan(o.atomic_friction);
  // (The 95 % quantile: the range the answer states; single drops above it are left to it.)
  if (p.friction_angle.q95 > resisted + 1e-9)
    add_warning(
        p.warnings,
        {"load-above-slopes",
         fmt::format("at {:.4g} N the loaded hold angles' 95 % quantile is {:.4g} deg (median {:.4g}, largest "
                     "{:.4g} deg), above the steepest slope of either surface plus the atomic friction angle, "
                     "{:.4g} deg, which no contact force exceeds: the loaded lift is wrong there (its "
                     "slopes are means of the surfaces'); the rigid prediction reads {:.4g} deg",
                     p.load, p.friction_angle.q95 * 180 / kPi, p.friction_angle.q50 * 180 / kPi,
                     p.friction_angle.max * 180 / kPi, resisted * 180 / kPi, p.rigid_friction_angle * 180 / kPi)});
  if (!beyond.empty())
    add_warning(p.warnings, {"load-curve-beyond-model",
                             fmt::format("the load curve's loads {} break the asperity model's assumptions (steep "
                                         "contacts, deep interference or merged contacts; docs/load.md): read the "
                                         "curve there as an extrapolation",
                                         beyond)});
  return Ok{};
}

// `take_lower` / `take_upper` (may be null): the surfaces' profiles to take over (moved through the
// conditioning into the signature).
Result<Prediction> predict_profiles(const PredictSurface& lower, const PredictSurface* upper, const PredictOptions& o,
                                    Profile* take_lower, Profile* take_upper) {
  Prediction p;
  p.is_map = false;
  p.model = "profile-quasi-static-hold";
  // A periodic profile (generated, or --period) has no form to remove: a line fitted over its
  // periods only picks up the phase of the last one, so its default is the mean.
  const bool periodic = lower.profile.period || o.period > 0;
  const Detrend dt = o.detrend.value_or(default_form(periodic));
  p.atomic_friction = o.atomic_friction;
  p.direction = o.direction;
  const bool forward = std::abs(o.direction) < 1e-9;
  const bool backward = std::abs(std::abs(o.direction) - kPi) < 1e-9;
  if (!forward && !backward)
    return make_error(
        fmt::format("direction {:.6g} deg: a profile slides along +x (0) or -x (180) only", o.direction * 180 / kPi));
  reader_warnings(p.warnings, lower);
  if (upper) reader_warnings(p.warnings, *upper);
  const Conditioning cond = conditioning_of(o, dt);
  // The heights as read (the plausibility checks tell a surface that is its form from tiny heights).
  const double lower_read_rms = rms_height_as_read(take_lower ? take_lower->z : lower.profile.z);
  const double upper_read_rms =
      upper ? rms_height_as_read(take_upper ? take_upper->z : upper->profile.z) : lower_read_rms;
  auto lc =
      take_lower ? condition(std::move(*take_lower), cond, lower.name) : condition(lower.profile, cond, lower.name);
  if (!lc) return lc.error();
  std::vector<ConditioningRecord> records{lc->record};
  Result<Profile> lo = std::move(lc->profile);
  Profile up_measured;
  if (upper) {
    auto u = take_upper ? condition(std::move(*take_upper), cond, upper->name)
                        : condition(upper->profile, cond, upper->name);
    if (!u) return u.error();
    records.push_back(u->record);
    up_measured = std::move(u->profile);
  } else {
    up_measured = *lo;
  }
  record_conditioning(p, std::move(records), false, dt);
  for (Warning& w : check_profile(*lo, lower.name, {}, lower_read_rms)) add_warning(p.warnings, std::move(w));
  if (upper) {
    for (Warning& w : check_profile(up_measured, upper->name, {}, upper_read_rms))
      add_warning(p.warnings, std::move(w));
    const double l1 = lo->x.back() - lo->x.front(), l2 = up_measured.x.back() - up_measured.x.front();
    for (Warning& w : check_pair_scales(l1, mean_spacing(*lo), l2, mean_spacing(up_measured), lower.name, upper->name))
      add_warning(p.warnings, std::move(w));
  }
  if (o.period != 0) {
    if (!(o.period > 0) || !std::isfinite(o.period))
      return make_error(fmt::format("period {} m: expected a positive length", o.period));
    lo->period = o.period;
    up_measured.period = o.period;
    if (auto st = validate(*lo, lower.name); !st) return st.error();
    if (auto st = validate(up_measured, upper ? upper->name : lower.name); !st) return st.error();
  }
  // The stated test: the block's length L_b and the run-away distance d (never a fraction of the
  // scan: default_test_lengths), and where the scan is too short for it, the largest test of the
  // same shape that fits, with a warning that says so.
  const bool lower_periodic = lo->period.has_value();
  if (lower_periodic && !o.loads.empty())
    return make_error(
        "load: the loaded model needs a stated block on a non-periodic pair (a periodic pair's lift wraps round); "
        "drop the period, or the load");
  const double lower_len = lo->x.back() - lo->x.front(), upper_len = up_measured.x.back() - up_measured.x.front();
  double d = o.runaway_distance, lb = o.block_length;
  bool whole_block = false;
  SignatureOptions so;
  so.threads = o.threads;
  so.keep_contacts = false;
  if (lower_periodic) {
    if (o.block_length != 0)
      return make_error(fmt::format(
          "block length {:.6g} m: a periodic pair slides the whole upper profile (a whole number of periods, as "
          "the paper's blocks); leave the block length unset, or drop the period",
          o.block_length));
    lb = upper_len;
    if (!(d > 0)) d = *lo->period;
    p.test_lengths = o.runaway_distance > 0 ? "d given; block: the whole upper profile (periodic)"
                                            : "d: one period; block: the whole upper profile (periodic)";
  } else {
    // The stated test (hold.hpp): its lengths, fitted to the scans (a defaulted length gives way,
    // warned scan-too-short; stated lengths that leave no room are refused).
    auto fit = stated_test(*lo, upper_len, o.runaway_distance, o.block_length);
    if (!fit) return fit.error();
    for (Warning& w : fit->warnings) add_warning(p.warnings, std::move(w));
    d = fit->runaway_distance;
    lb = fit->block_length;
    whole_block = fit->whole;
    p.test_lengths = fit->rule;
  }
  if (!lower_periodic && !whole_block) {
    // The block: the middle of the upper scan, L_b long to the nearest samples; drops at every
    // offset at which it lies wholly over the lower scan (0: left ends aligned).
    up_measured = stated_block(up_measured, lb);
    lb = up_measured.x.back() - up_measured.x.front();
    const StatedDrops sd = stated_drops(lower_len, lb, d);
    so.offset_min = sd.offset_min;
    so.offset_max = sd.offset_max;
  }
  p.block_length = lb;
  Profile up = rotate180(std::move(up_measured));  // in place (memory: 10^7 points are 160 MB a copy)
  HoldOptions ho;
  ho.runaway_distance = d;
  ho.atomic_friction = o.atomic_friction;
  const bool one = std::isfinite(o.start_offset[0]);
  // The bound and the hold analysis from one pass over the lift (not a signature each).
  // The caller's profiles at hand (not taken over): the conditioned ones by reference, so that a
  // lift that the one pass finds too short is analysed again from them (signature_with_hold's
  // fallback). Taken over: they go to the signature (no copies).
  const double start = one ? o.start_offset[0] : std::numeric_limits<double>::quiet_NaN();
  // Under load the profiles stay: the loaded lift reads them after the rigid one.
  auto both = take_lower && o.loads.empty() ? signature_with_hold(std::move(*lo), std::move(up), so, ho, start)
                                            : signature_with_hold(*lo, up, so, ho, start);
  if (!both) return both.error();
  const SignatureResult* sig = &both->signature;
  const HoldAnalysis* h = &both->hold;
  // The lift the test runs on, and its drops. A stated block: the lift where it lies wholly on
  // the lower scan, [0, L - L_b] (a slip that reaches an end has slid off the scan), drops over
  // it with kEndRoomPerRunaway d of room at each end; so every d of the sweep reads the same
  // lift, which does not depend on how far the analysis above widened it. The whole block
  // (periodic, or `whole`): the analysis' own lift and drops.
  LiftCurve stated_curve;
  const LiftCurve* curve = &h->curve;
  HoldOptions hk = ho;
  hk.drop_min = h->distribution.forward.drop_min;
  hk.drop_max = h->distribution.forward.drop_max;
  if (!lower_periodic && !whole_block) {
    stated_curve = cut_lift_curve(h->curve, so.offset_min, so.offset_max);
    curve = &stated_curve;
    const StatedDrops sd = stated_drops(lower_len, lb, d);
    hk.drop_min = sd.drop_min;
    hk.drop_max = sd.drop_max;
  }
  // Every d of the sweep on that one lift, over the same drops (linear in its vertices each); the
  // headline at d.
  // `at_d_only`: the headline alone (a load curve's other loads), the sweep left as it is.
  auto analyse = [&](const LiftCurve& lift, bool at_d_only) -> Status {
    constexpr std::array<double, 5> sweep = {0.25, 0.5, 1, 2, 4};
    HoldDistribution at_d;
    HoldAngles start_at_d;
    if (!at_d_only) p.d_sweep_distance.clear(), p.d_sweep_q05.clear(), p.d_sweep_q50.clear(), p.d_sweep_q95.clear();
    for (double k : sweep) {
      if (at_d_only && k != 1) continue;
      hk.runaway_distance = k * d;
      auto dist = hold_distribution(lift, hk);
      if (!dist) return dist.error();
      const HoldDistribution& dd = forward ? dist->forward : dist->backward;
      if (k == 1) at_d = dd;
      if (one && k == 1) {
        auto a = hold_angle(lift, start, hk);
        if (!a) return a.error();
        start_at_d = *a;
      }
      if (at_d_only) continue;
      p.d_sweep_distance.push_back(k * d);
      p.d_sweep_q05.push_back(dd.hold.q05);
      p.d_sweep_q50.push_back(dd.hold.q50);
      p.d_sweep_q95.push_back(dd.hold.q95);
    }
    hk.runaway_distance = d;
    p.drops = at_d.basins.rest.size();
    if (one) {
      const HoldAngle& a = forward ? start_at_d.forward : start_at_d.backward;
      p.rest_offset = {a.rest_offset, 0};
      p.friction_angle = plain_stats({a.hold_angle});
      p.drops = 1;
    } else {
      p.friction_angle = at_d.hold;
    }
    return Ok{};
  };
  if (auto st = analyse(*curve, false); !st) return st.error();
  p.runaway_distance = d;
  p.drop_range = {hk.drop_min, hk.drop_max, 0, 0};
  if (one) {
    p.single_drop = true;
    p.start_offset = {o.start_offset[0], 0};
  } else if (p.drops < 3 && !lower_periodic) {
    add_warning(p.warnings, {"few-drops", fmt::format("the drops over [{:.6g}, {:.6g}] m drain into {} basin(s) "
                                                      "only: the spread is not resolved",
                                                      hk.drop_min, hk.drop_max, p.drops)});
  }
  if (!o.loads.empty())
    if (auto st = predict_under_load(p, *lo, up, *curve, o, analyse); !st) return st.error();
  // The rigid bound: the steepest contact slope the test reaches. The signature's theta_max is
  // over its own range; a stop the hold analysis read beyond it (a whole block's run-away past
  // the first half, a block creeping past its last drop) is a contact slope too, and the drops'
  // hold angles are atan(mu_a) + atan(slope of a stop): the bound is at least each. Under load
  // the bound stays the rigid signature's (the loaded lift is not a rigid contact slope).
  const double theta_sig = forward ? sig->theta_max_forward : sig->theta_max_backward;
  // (A hold angle of atan(mu_a) is a block that slid at zero tilt: no stop's slope was read.)
  const double theta_stops = p.friction_angle.max - std::atan(o.atomic_friction);
  finish(p, o.loads.empty() && theta_stops > 0 ? std::max(theta_sig, theta_stops) : theta_sig, sig->contact_slope_std);
  return p;
}

// A map pair under load (PredictOptions::loads; docs/load.md, "Maps"): the drops `uv` (offsets
// along and across d, the model's frame) grouped into lines along d, the loaded lift of each line
// from the half-space solution at every offset (load.hpp's map_loaded_lift: a first pass at
// map_load_step, refined where the elastic correction bends), and each drop's hold angle on its line (the block locked
// to d, hold.hpp), at every load of the curve. The rigid prediction `p` (free block) gives phi_0 and stays the bound.
Status predict_maps_under_load(Prediction& p, const Map& lower, const Map& upper, const MapHoldOptions& t,
                               const std::vector<std::array<double, 2>>& uv, const PredictOptions& o) {
  // One load: a decade either side (each load is a contact solve per offset, the cost of the map
  // model); a list: those loads.
  auto setup = load_curve_setup(p, o, {0.1, 1, 10});
  if (!setup) return setup.error();
  const std::vector<double>& curve = setup->curve;
  const std::size_t head = setup->head;
  const double cosine = setup->cosine;
  MapLoadedLiftOptions lo;
  lo.contact_modulus = setup->contact_modulus;
  lo.angle = t.angle;
  lo.turn_over_upper = t.turn_over_upper;
  lo.threads = o.threads;
  if (!std::isfinite(o.map_load_step) || o.map_load_step < 0)
    return make_error(
        fmt::format("map load step {} m: expected a finite length >= 0 (0: the spacing)", o.map_load_step));
  lo.step = o.map_load_step > 0 ? o.map_load_step : std::min(lower.dx, lower.dy);
  for (double w : curve) lo.loads.push_back(w * cosine);
  // Lines: the drops' distinct offsets across d; along each, the drops' range widened by room for
  // the descent and the run-away (3 d), on the step's grid.
  const double D = t.runaway_distance;
  std::vector<double> across;
  for (const auto& q : uv)
    if (std::find(across.begin(), across.end(), q[1]) == across.end()) across.push_back(q[1]);
  double umin = INFINITY, umax = -INFINITY;
  for (const auto& q : uv) umin = std::min(umin, q[0]), umax = std::max(umax, q[0]);
  const double room = 3 * D + 2 * lo.step;
  const double a0 = std::floor((umin - room) / lo.step) * lo.step, a1 = std::ceil((umax + room) / lo.step) * lo.step;
  auto loaded = map_loaded_lift(lower, upper, across, a0, a1, lo);
  if (!loaded) return loaded.error();
  // The rigid lift of each line: the rigid map model's own (areal_tilt_lift: the spheres of the
  // upper face on the lower one's triangles, exact), on offsets kLiftPerStep times finer than the
  // lower map's spacing (the contact solves' default step) (it has a kink wherever the touching sphere or triangle
  // changes, and the hold angle reads its steepest stops); the elastic correction H_W - h of the solves, which varies
  // with the contact, linear between them (solved densely enough that it is, MapLoadedLiftOptions::refine_slope). So
  // each curve tends to the rigid line's as W -> 0.
  constexpr int kLiftPerStep = 10;
  std::vector<LiftCurve> rigid_lines(across.size());
  for (std::size_t li = 0; li < across.size(); ++li) {
    const MapLoadedLine& line = loaded->lines[li];
    const double v = across[li];
    ArealLiftOptions ao;
    ao.step = std::min(lower.dx, lower.dy) / kLiftPerStep;
    ao.offset_min = line.rigid.offset.front();
    ao.offset_max = line.rigid.offset.back();
    // Rows -|v|, 0, |v| (or the row v = 0 alone): the line is the row at v.
    ao.across_step = v != 0 ? std::abs(v) : 1;
    ao.across_max = v != 0 ? std::abs(v) : 0.5;
    ao.threads = o.threads;
    auto al = areal_tilt_lift(lower, upper, t, ao);
    if (!al) return al.error();
    const std::size_t row = v > 0 ? 2 : 0;
    LiftCurve& c = rigid_lines[li];
    for (std::size_t i = 0; i < al->n_along; ++i) {
      const double h = al->lift[row * al->n_along + i];
      if (std::isfinite(h)) c.offset.push_back(al->along(i)), c.lift.push_back(h);
    }
    if (c.offset.size() < 2)
      return make_error(
          fmt::format("the line {:.6g} m across the direction: the rigid lift has fewer than 2 offsets "
                      "where the blocks touch",
                      v));
  }
  // The loaded curve of line li at load l on the rigid line's vertices.
  auto loaded_curve = [&](std::size_t li, std::size_t l) {
    const MapLoadedLine& line = loaded->lines[li];
    const std::vector<double>& us = line.rigid.offset;
    LiftCurve c = rigid_lines[li];
    for (std::size_t k = 0; k < c.offset.size(); ++k) {
      const double u = std::clamp(c.offset[k], us.front(), us.back());
      const std::size_t j =
          std::min<std::size_t>(std::size_t(std::upper_bound(us.begin(), us.end(), u) - us.begin()), us.size() - 1);
      const std::size_t i = j - 1;
      const double f = (u - us[i]) / (us[j] - us[i]);
      const double ci = line.curves[l].lift[i] - line.rigid.lift[i], cj = line.curves[l].lift[j] - line.rigid.lift[j];
      c.lift[k] += (1 - f) * ci + f * cj;
    }
    return c;
  };
  HoldOptions hk;
  hk.runaway_distance = D;
  hk.atomic_friction = o.atomic_friction;
  // Each drop's hold angle on its line's curve at load l; a run-away that leaves the line less
  // than d after its last stop is counted (the lift beyond could still have caught it).
  std::size_t off_end = 0, held = 0;
  // (l = curve.size(): the rigid lines themselves, the curve's limit at zero load.)
  auto drops_on = [&](std::size_t l, std::vector<double>& angles) -> Status {
    angles.assign(uv.size(), 0);
    std::vector<LiftCurve> curves(across.size());
    for (std::size_t li = 0; li < across.size(); ++li)
      curves[li] = l < curve.size() ? loaded_curve(li, l) : rigid_lines[li];
    for (std::size_t k = 0; k < uv.size(); ++k) {
      const std::size_t li = std::size_t(std::find(across.begin(), across.end(), uv[k][1]) - across.begin());
      const LiftCurve& c = curves[li];
      const double u = std::clamp(uv[k][0], c.offset.front(), c.offset.back());
      auto a = hold_angle(c, u, hk);
      if (!a) return a.error();
      // The rigid model's largest tilt caps the loaded one too (held-to-max-tilt).
      angles[k] = std::min(a->forward.hold_angle, t.max_tilt);
      if (l == head && a->forward.hold_angle >= t.max_tilt) ++held;
      if (l == head && a->forward.ran_off_end && c.offset.back() - a->forward.hold_offset < D) ++off_end;
    }
    return Ok{};
  };
  std::vector<double> angles;
  std::string beyond;
  for (std::size_t l = 0; l < curve.size(); ++l) {
    if (auto st = drops_on(l, angles); !st) return st;
    const HoldStatistics h = plain_stats(angles);
    p.load_curve.push_back(curve[l]);
    p.load_curve_q05.push_back(h.q05);
    p.load_curve_q50.push_back(h.q50);
    p.load_curve_q95.push_back(h.q95);
    const MapLoadedDiagnostics& dg = loaded->diagnostics[l];
    if (l != head && (dg.rms_contact_slope > kLoadMaxSlope || dg.full_share > kLoadMaxFullShare))
      beyond += fmt::format("{}{:.4g} N", beyond.empty() ? "" : ", ", curve[l]);
    if (l == head) {
      p.friction_angle = h;
      p.drop_angles = angles;
      p.drop_steering.assign(angles.size(), 0.0);
    }
  }
  // The zero-load limit: the block locked to d on the rigid lines. The free rigid block (the rigid
  // prediction) steers round stops that the locked one must climb, so the two medians can differ
  // (docs/load.md, Maps: "Zero load"): said where they do.
  if (auto st = drops_on(curve.size(), angles); !st) return st;
  p.load_zero_limit = plain_stats(angles).q50;
  if (std::abs(p.load_zero_limit - p.rigid_friction_angle) > 0.1 * kPi / 180)
    add_warning(p.warnings,
                {"load-locked-block",
                 fmt::format("the loaded model holds the block locked to the sliding direction: at zero load it "
                             "reads {:.4g} deg (the locked rigid block, median over the drops) where the free rigid "
                             "block, the rigid prediction, reads {:.4g} deg; read the change with load from {:.4g} deg",
                             p.load_zero_limit * 180 / kPi, p.rigid_friction_angle * 180 / kPi,
                             p.load_zero_limit * 180 / kPi)});
  p.load = curve[head];
  p.normal_load = curve[head] * cosine;
  p.contact_modulus = setup->contact_modulus;
  const MapLoadedDiagnostics& dg = loaded->diagnostics[head];
  p.load_contacts = dg.mean_patches;
  p.load_approach = dg.mean_approach;
  p.load_contact_slope = dg.rms_contact_slope;
  p.load_contact_fraction = dg.max_contact_fraction;
  p.model = "map-halfspace-locked-hold";
  p.friction_coefficient = p.friction_angle.q50 >= kPi / 2 ? INFINITY : std::tan(p.friction_angle.q50);
  if (dg.rms_contact_slope > kLoadMaxSlope)
    add_warning(p.warnings, {"load-steep-contacts",
                             fmt::format("at {:.4g} N the force-weighted rms slope of the contact is {:.3g}: above "
                                         "{:g}, the small-slope half-space solution is approximate",
                                         p.load, dg.rms_contact_slope, kLoadMaxSlope)});
  if (dg.full_share > kLoadMaxFullShare)
    add_warning(p.warnings,
                {"load-full-contact",
                 fmt::format("at {:.4g} N more than {:g} % of the overlap is in contact at {:.3g} % of the offsets "
                             "(largest contact fraction {:.3g}): the load flattens the roughness that makes the "
                             "friction; the lift is then the half-space's, not the surfaces'",
                             p.load, 100 * kMapFullContact, 100 * dg.full_share, dg.max_contact_fraction)});
  if (dg.unconverged > 0)
    add_warning(p.warnings,
                {"contact-not-converged",
                 fmt::format("at {:.4g} N the contact solution did not reach its tolerance at {} offsets: the loaded "
                             "lift there is approximate",
                             p.load, dg.unconverged)});
  // The rigid prediction's own held-to-max-tilt warning is of the free block: the loaded one's replaces it.
  std::erase_if(p.warnings, [](const Warning& w) { return w.code == "held-to-max-tilt"; });
  if (held > 0)
    add_warning(p.warnings,
                {"held-to-max-tilt", fmt::format("{} of {} drops held the block up to {:g} deg (the model's largest "
                                                 "tilt) under load: their hold angle is a lower bound",
                                                 held, uv.size(), t.max_tilt * 180 / kPi)});
  if (off_end > 0)
    add_warning(p.warnings,
                {"load-lift-ends", fmt::format("{} of {} drops ran off the end of their line of loaded offsets (the "
                                               "maps' overlap): their hold angle is the last stop's",
                                               off_end, uv.size())});
  if (!beyond.empty())
    add_warning(p.warnings, {"load-curve-beyond-model",
                             fmt::format("the load curve's loads {} break the half-space model's assumptions (steep "
                                         "contacts or near full contact; docs/load.md): read the curve there as an "
                                         "extrapolation",
                                         beyond)});
  return Ok{};
}

Result<Prediction> predict_maps(const PredictSurface& lower, const PredictSurface* upper, const PredictOptions& o) {
  Prediction p;
  p.is_map = true;
  p.model = "map-continuous-free";
  const Detrend dt = o.detrend.value_or(default_form());
  p.atomic_friction = o.atomic_friction;
  p.direction = o.direction;
  if (!std::isfinite(o.direction)) return make_error("direction: expected a finite angle");
  if (o.map_drops < 2 || o.map_drops > 64)
    return make_error(fmt::format("map drops {}: expected 2..64 per side", o.map_drops));
  reader_warnings(p.warnings, lower);
  if (upper) reader_warnings(p.warnings, *upper);
  const Conditioning cond = conditioning_of(o, dt);
  auto lc = condition(lower.map, cond, lower.name);
  if (!lc) return lc.error();
  std::vector<ConditioningRecord> records{lc->record};
  Result<Map> lo = std::move(lc->map);
  Map up;
  if (upper) {
    auto u = condition(upper->map, cond, upper->name);
    if (!u) return u.error();
    records.push_back(u->record);
    up = std::move(u->map);
  } else {
    up = *lo;
  }
  record_conditioning(p, std::move(records), true, dt);
  if (lo->nx < 2 || lo->ny < 2 || up.nx < 2 || up.ny < 2)
    return make_error(fmt::format("{}: the map prediction needs at least 2 x 2 points", lower.name));
  for (Warning& w : check_map(*lo, lower.name, {}, rms_height_as_read(lower.map.heights)))
    add_warning(p.warnings, std::move(w));
  if (upper) {
    for (Warning& w : check_map(up, upper->name, {}, rms_height_as_read(upper->map.heights)))
      add_warning(p.warnings, std::move(w));
    for (Warning& w :
         check_pair_scales(std::max(lo->width(), lo->height()), std::min(lo->dx, lo->dy),
                           std::max(up.width(), up.height()), std::min(up.dx, up.dy), lower.name, upper->name))
      add_warning(p.warnings, std::move(w));
  }
  // (A direction within 1e-12 rad of an axis is on it: the drops of the same experiment turned by
  // quarter turns then lie at the same offsets to the bit; map_hold.hpp's model turns it likewise.)
  auto snap = [](double v) {
    return std::abs(v) < 1e-12 ? 0.0 : std::abs(std::abs(v) - 1) < 1e-12 ? std::copysign(1.0, v) : v;
  };
  const double c = snap(std::cos(o.direction)), s = snap(std::sin(o.direction));
  const double along = std::abs(c) * lo->width() + std::abs(s) * lo->height();
  const double across = std::abs(s) * lo->width() + std::abs(c) * lo->height();
  MapHoldOptions t = map_model_options(*lo, o);
  if (o.runaway_distance > 0) {
    p.test_lengths = "d: given; block: the whole upper map";
  } else {
    p.test_lengths = "d: " + default_map_runaway_distance(*lo, o.direction).rule + "; block: the whole upper map";
    // Drops over half the lower map along d need kRoomPerRunaway d of room on it.
    if (along < 2 * kRoomPerRunaway * t.runaway_distance) {
      const double dm = along / (2 * kRoomPerRunaway);
      add_warning(p.warnings, {"scan-too-short",
                               fmt::format("the stated test's d = {:.4g} m needs a lower map of {:.4g} m along the "
                                           "direction; it is {:.4g} m: the answer is for d = {:.4g} m",
                                           t.runaway_distance, 2 * kRoomPerRunaway * t.runaway_distance, along, dm)});
      t.runaway_distance = dm;
    }
  }
  p.runaway_distance = t.runaway_distance;
  // Drops (offsets of the upper map's centre from the lower's). The block's footprint is its
  // nodes' extent widened by the sphere radius r on every side (the spheres that touch). An upper
  // block smaller than the lower map along d is put down where that footprint lies wholly over the
  // lower map with room D (the run-away distance) on every side: ahead to run away, behind to
  // descend into its basin at zero tilt, across d to steer. So no drop starts with spheres on the
  // lower map's edge (a drop there is a knife-edge: MuJoCo's block stays balanced on the boundary
  // where the prediction's descent leaves it, bench/results/predict-vs-sim.md):
  // u in +-((Lf - Lg) / 2 - r - D), Lf, Lg the lower and upper maps' node extents along d. A block
  // not that much shorter (a self-pair) over [0, Lf / 2 - D] (it keeps at least half its overlap),
  // as the grid model's drops (areal.hpp). Across d the same: +-((Wf - Wg) / 2 - r - D), or
  // +-(Wf / 4 - D).
  const double along_g = std::abs(c) * up.width() + std::abs(s) * up.height();
  const double across_g = std::abs(s) * up.width() + std::abs(c) * up.height();
  const double D = t.runaway_distance;
  const double margin = t.sphere_radius + D;  // m: the footprint's r and the room D
  double umin = 0, umax = std::max(0.0, 0.5 * along - D);
  if (along_g < along - 2 * margin) umax = 0.5 * (along - along_g) - margin, umin = -umax;
  const double vmax =
      across_g < across - 2 * margin ? 0.5 * (across - across_g) - margin : std::max(0.0, 0.25 * across - D);
  // The model's offsets count from the centres aligned (turned over) or from the upper face's
  // place (in place: its centre then sits (cu, cv) from the lower's, along and across d); the
  // drops, the drop range and the start offset are in the model's offsets.
  double cu = 0, cv = 0;
  if (!o.turn_over_upper) {
    const double ox = (up.x0 + 0.5 * up.width()) - (lo->x0 + 0.5 * lo->width());
    const double oy = (up.y0 + 0.5 * up.height()) - (lo->y0 + 0.5 * lo->height());
    cu = ox * c + oy * s, cv = -ox * s + oy * c;
  }
  p.drop_range = {umin - cu, umax - cu, -vmax - cv, vmax - cv};
  std::vector<std::array<double, 2>> uv;
  if (std::isfinite(o.start_offset[0])) {
    const double x = o.start_offset[0], y = o.start_offset[1];
    const double u = x * c + y * s, v = -x * s + y * c;
    const double half_along = 0.5 * along, half_across = 0.5 * across;
    if (!(std::abs(u + cu) <= half_along && std::abs(v + cv) <= half_across))
      return make_error(
          fmt::format("start offset ({:.6g}, {:.6g}) m: along the direction {:.6g} m and across it "
                      "{:.6g} m; expected within [{:.6g}, {:.6g}] along and [{:.6g}, {:.6g}] across",
                      x, y, u, v, -half_along - cu, half_along - cu, -half_across - cv, half_across - cv));
    uv.push_back({u, v});
    p.single_drop = true;
    p.start_offset = {x, y};
  } else {
    const int n = o.map_drops;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        uv.push_back(
            {umin + (umax - umin) * double(i) / double(n - 1) - cu, -vmax + 2 * vmax * double(j) / double(n - 1) - cv});
  }
  // The cost, estimated before it runs: CPU seconds per sphere and drop (measured,
  // bench/results/map-predict.md).
  const double spheres = double(up.valid_count());
  const double work = map_work_estimate(up.valid_count(), uv.size() * (o.map_locked ? 2 : 1));
  if (o.map_work_limit > 0 && work > o.map_work_limit)
    return make_error(
        fmt::format("the map prediction would take about {:.0f} s of CPU ({} spheres, {} drops), above the "
                    "limit of {:.0f} s: crop or resample the maps, or fewer drops",
                    work, std::size_t(spheres), uv.size(), o.map_work_limit));
  for (const auto& q : uv) p.drop_offsets.push_back({q[0] * c - q[1] * s, q[0] * s + q[1] * c});
  const std::size_t nd = uv.size();
  std::vector<double> free_angle(nd), locked_angle(nd, 0), steering(nd, 0);
  std::vector<std::array<double, 2>> rest(nd);
  std::vector<char> held(nd, 0), held_locked(nd, 0);
  // Every drop (free, then locked for the diagnostic) on one field of spheres, shared.
  std::vector<ArealTiltDrop> jobs;
  for (std::size_t k = 0; k < nd; ++k) jobs.push_back({p.drop_offsets[k], false});
  if (o.map_locked)
    for (std::size_t k = 0; k < nd; ++k) jobs.push_back({p.drop_offsets[k], true});
  auto holds = areal_tilt_hold_drops(*lo, up, t, jobs, o.threads, o.progress);
  if (!holds) return holds.error();
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    const ArealTiltHold& r = (*holds)[k];
    const std::size_t drop = k % nd;
    if (jobs[k].locked) {
      locked_angle[drop] = r.ran_away ? r.hold_angle : t.max_tilt;
      held_locked[drop] = !r.ran_away;
    } else {
      free_angle[drop] = r.ran_away ? r.hold_angle : t.max_tilt;
      steering[drop] = r.steering;
      held[drop] = !r.ran_away;
      rest[drop] = r.rest_offset;
    }
  }
  p.drops = nd;
  p.drop_angles = free_angle;
  p.drop_steering = steering;
  p.friction_angle = plain_stats(free_angle);
  if (o.map_locked) {
    p.has_locked = true;
    p.drop_angles_locked = locked_angle;
    p.locked_friction_angle = plain_stats(locked_angle);
  }
  if (p.single_drop) p.rest_offset = rest[0];
  const auto nheld = std::count(held.begin(), held.end(), 1);
  if (nheld > 0)
    add_warning(p.warnings, {"held-to-max-tilt", fmt::format("{} of {} drops held the block up to 45 deg (the "
                                                             "model's largest tilt): their hold angle is a lower bound",
                                                             nheld, nd)});
  // The rigid upper bound from the same model: the largest of the drops' seat bounds (the
  // steepest slope along d, friction cones included, of the contacts of every seat a block rested
  // in), so that it lies above every drop's hold angle by construction; theta_max the steepest
  // seat slope without friction, sigma the spread of the drops' steepest seat slopes.
  std::vector<double> seat_slopes;
  double bound = 0;
  for (std::size_t k = 0; k < nd; ++k) {
    bound = std::max(bound, (*holds)[k].seat_bound);
    seat_slopes.push_back((*holds)[k].seat_slope);
  }
  const HoldStatistics seats = plain_stats(seat_slopes);
  finish(p, seats.max, seats.std, bound);
  if (!o.loads.empty())
    if (auto st = predict_maps_under_load(p, *lo, up, t, uv, o); !st) return st.error();
  return p;
}

}  // namespace

MapHoldOptions map_model_options(const Map& lower, const PredictOptions& o) {
  MapHoldOptions t;
  t.angle = o.direction;
  t.turn_over_upper = o.turn_over_upper;
  t.atomic_friction = o.atomic_friction;
  t.runaway_distance = o.runaway_distance;
  t.sphere_radius = o.sphere_radius;
  fill_map_model_defaults(lower, t);
  return t;
}

double map_work_estimate(std::size_t upper_spheres, std::size_t drops) {
  return double(upper_spheres) * 2.5e-7 * double(drops);
}

Result<PredictSurface> predict_surface(SurfaceData data, const std::string& name) {
  PredictSurface p;
  p.name = name;
  p.is_map = data.is_map;
  p.reader_warnings = std::move(data.warnings);
  p.x_unit_scale = data.x_unit_scale;
  p.z_unit_scale = data.z_unit_scale;
  if (data.is_map) {
    p.map = std::move(data.map);
  } else {
    auto pr = as_profile(std::move(data.curve), name);
    if (!pr) return pr.error();
    p.profile = std::move(pr).value();
  }
  return p;
}

namespace {

// predict()'s checks of the pair and the options that come before either model.
Status check_request(const PredictSurface& lower, const PredictSurface* upper, const PredictOptions& o) {
  if (upper && upper->is_map != lower.is_map)
    return make_error(fmt::format("{} is {} and {} is {}: a pair is two profiles or two maps", lower.name,
                                  lower.is_map ? "an areal map" : "a line profile", upper->name,
                                  upper->is_map ? "an areal map" : "a line profile"));
  if (!std::isfinite(o.atomic_friction) || o.atomic_friction < 0)
    return make_error(fmt::format("atomic friction {}: expected a finite number >= 0", o.atomic_friction));
  if (!std::isfinite(o.runaway_distance) || o.runaway_distance < 0)
    return make_error(
        fmt::format("run-away distance {} m: expected a finite length >= 0 (0: the default)", o.runaway_distance));
  if (!std::isfinite(o.block_length))
    return make_error(
        fmt::format("block length {} m: expected a finite length (0: the default, < 0: the whole upper "
                    "profile)",
                    o.block_length));
  if (lower.is_map && o.block_length != 0)
    return make_error(
        "block length: for profiles only (a map pair's block is the whole upper map; crop it to state another)");
  if (std::isinf(o.start_offset[0]) || !std::isfinite(o.start_offset[1]))
    return make_error("start offset: expected finite offsets (m)");
  for (double w : o.loads)
    if (!(w > 0) || !std::isfinite(w)) return make_error(fmt::format("load {} N: expected a finite force > 0", w));
  if (!lower.is_map && !o.turn_over_upper)
    return make_error(
        "in place (turn_over_upper = false): for maps only; a profile pair's upper profile is "
        "always turned over");
  return Ok{};
}

// The rms slope along x of a surface as read (profile: its points; map: its rows), unitless.
double rms_slope_along_x(const PredictSurface& s) {
  double s2 = 0;
  std::size_t n = 0;
  auto add = [&](double dz, double dx) {
    if (dx > 0 && std::isfinite(dz)) s2 += (dz / dx) * (dz / dx), ++n;
  };
  if (s.is_map) {
    for (std::size_t j = 0; j < s.map.ny; ++j)
      for (std::size_t i = 0; i + 1 < s.map.nx; ++i) add(s.map.at(i + 1, j) - s.map.at(i, j), s.map.dx);
  } else {
    for (std::size_t k = 0; k + 1 < s.profile.x.size(); ++k)
      add(s.profile.z[k + 1] - s.profile.z[k], s.profile.x[k + 1] - s.profile.x[k]);
  }
  return n ? std::sqrt(s2 / double(n)) : 0;
}

// "m", "mm", "um", "nm" for a scale that is one (m per unit), else empty.
std::string unit_name(double scale) {
  for (const auto& [v, w] : {std::pair{1.0, "m"}, {1e-3, "mm"}, {1e-6, "um"}, {1e-9, "nm"}})
    if (std::abs(scale - v) <= 1e-9 * v) return w;
  return {};
}

// The trust of a finished prediction (assess_trust on its warnings), its fix naming the unit to
// give where the file's unit is known and a factor of 10^3, 10^6 or 10^9 brings the lower
// surface's rms slope into what instruments measure: heights in a smaller unit (rms slope at most
// 1, 45 deg) for the codes of too steep a surface, lateral lengths in a smaller unit (at least
// 1e-3) for lateral-suspect. Each code's fix once, in the order of the codes.
void settle_trust(Prediction& p, const PredictSurface& lower) {
  const Trust t = assess_trust(p.warnings);
  p.trust = t.verdict;
  p.trust_codes = t.codes;
  p.trust_fix.clear();
  if (t.codes.empty()) return;
  const double slope = rms_slope_along_x(lower);
  std::string z_unit, x_unit;
  if (lower.z_unit_scale > 0 && slope > 1)
    for (double f : {1e-3, 1e-6, 1e-9})
      if (slope * f <= 1) {
        z_unit = unit_name(lower.z_unit_scale * f);
        break;
      }
  if (lower.x_unit_scale > 0 && slope > 0)
    for (double f : {1e-3, 1e-6})
      if (slope / f >= 1e-3) {
        x_unit = unit_name(lower.x_unit_scale * f);
        break;
      }
  for (const std::string& code : t.codes) {
    std::string fix;
    if ((code == "units-suspect" || code == "heights-exceed-length" || code == "friction-angle-at-90") &&
        !z_unit.empty())
      fix = fmt::format("--z-unit {} (Python z_unit='{}')", z_unit, z_unit);
    else if (code == "lateral-suspect" && !x_unit.empty())
      fix = fmt::format("--x-unit {} (Python x_unit='{}')", x_unit, x_unit);
    else if (const WarningCode* c = find_warning_code(code))
      fix = c->fix;
    if (!fix.empty() && p.trust_fix.find(fix) == std::string::npos)
      p.trust_fix += (p.trust_fix.empty() ? "" : "; ") + fix;
  }
}

Result<Prediction> with_trust(Result<Prediction> r, const PredictSurface& lower) {
  if (r) settle_trust(*r, lower);
  return r;
}

}  // namespace

Result<Prediction> predict(const PredictSurface& lower, const PredictSurface* upper, const PredictOptions& o) {
  if (auto st = check_request(lower, upper, o); !st) return st.error();
  return with_trust(lower.is_map ? predict_maps(lower, upper, o) : predict_profiles(lower, upper, o, nullptr, nullptr),
                    lower);
}

Result<Prediction> predict(PredictSurface&& lower, std::optional<PredictSurface>&& upper, const PredictOptions& o) {
  const PredictSurface* up = upper ? &*upper : nullptr;
  if (auto st = check_request(lower, up, o); !st) return st.error();
  if (lower.is_map) return with_trust(predict_maps(lower, up, o), lower);  // the map model reads the maps as they are
  // The lower profile's points move into the analysis: its slope (for the trust's fix) first.
  PredictSurface probe;
  probe.x_unit_scale = lower.x_unit_scale;
  probe.z_unit_scale = lower.z_unit_scale;
  probe.profile.x = {0, 1};
  probe.profile.z = {0, rms_slope_along_x(lower)};
  return with_trust(predict_profiles(lower, up, o, &lower.profile, up ? &upper->profile : nullptr), probe);
}

}  // namespace frictal
