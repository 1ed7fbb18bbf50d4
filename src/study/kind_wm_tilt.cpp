// Task kind 'wm-tilt', one unit: the spheropolygon tilting-block test (Sec. IV) on a pair of random
// surfaces (stochastic Weierstrass-Mandelbrot by default), beside the Eq. 18 range of the same
// pair -- a result the paper does not have (docs/dem.md sec. 6, "Random pairs: the wm-tilt study").
//
// Parameters: `generator` (default wm; any generator with a `seed` field -- wm, self-affine, the
// Fourier-filtered one -- gives a pair of independent faces from two streams of the task seed;
// a generator without one, e.g. sine, gives the same face twice: the deterministic limit used by
// the tests), that generator's parameters except `seed` (wm: `stochastic` defaults to true), the
// tilt settings of the 'tilt' kind except `runaway_distance` and `series_interval`, and `pair`
// (the replicate index; use seed_from = ["pair"]).
//
// One run per task: run-away distance 2 lambda (lambda = the surface's scale: wm's longest
// wavelength, a sine's wavelength), with checkpoints at 0.5 and 1 lambda
// (TiltConfig::runaway_checkpoints), so the friction angle at each run-away distance is the one a
// separate run with that distance reports. The Eq. 18 sigma comes from the rigid signature over
// the same offsets as the prediction of run_tilt. Registered in registry.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include <fmt/core.h>

#include "frictal/geometry.hpp"
#include "frictal/hold.hpp"
#include "frictal/signature.hpp"
#include "frictal/study.hpp"
#include "frictal/surface_spec.hpp"
#include "frictal/tilt.hpp"
#include "frictal/units.hpp"
#include "study/kind_common.hpp"
#include "study/table_params.hpp"

namespace frictal::study {

using namespace kind_detail;

namespace {

/// Run-away distances in units of lambda; the run stops at the last one.
constexpr double kRunaway[3] = {0.5, 1.0, 2.0};
constexpr const char* kRunawayName[3] = {"half_lambda", "lambda", "two_lambda"};

// The outputs taken from output tables (frictal columns): declared once there, with the study key
// and the kind's context where they differ.
// The tilt test's (tilt_columns()), of the run.
constexpr std::initializer_list<ColumnOutput> kTiltOutputs = {
    {"predicted_theta_max_deg", "theta_max_deg", "theta_max of the rigid signature (Eq. 6)"},
    "predicted_friction_angle_deg",
    {"predicted_friction_angle_deg", "eq18_high_deg", "upper end of the Eq. 18 range"},
    "predicted_sphero_theta_max_deg",
    "predicted_sphero_friction_angle_deg",
    "initial_offset_m",
    "stiff_friction_angle_deg",
    "rotation_before_slide_deg",
    "simulated_time_s",
    "steps",
    "settled_contacts",
    "settled_speed_m_s"};
// Its scales (tilt_scales_columns()).
constexpr std::initializer_list<ColumnOutput> kScalesOutputs = {
    "resting_overlap_m", {"time_step_s", nullptr, "after the retries with 2.5x smaller steps"}};
// theta_a (friction_columns()).
constexpr std::initializer_list<ColumnOutput> kFrictionOutputs = {"atomic_friction_angle_deg"};
// sigma of Eq. 18 from the kind's own signature (signature_columns()).
constexpr std::initializer_list<ColumnOutput> kSignatureOutputs = {
    {"contact_slope_std_deg", "sigma_deg", "the signature of the run's offsets"}};
// The drop from the rest (hold_drop_columns()): rigid blocks, then rounded ones.
constexpr std::initializer_list<ColumnOutput> kHoldOutputs = {
    {"rest_offset_m", nullptr, "the upper block when the loading starts (signature convention), in the range"},
    {"hold_angle_deg", nullptr, "the rigid blocks from the rest, d = 1 lambda"},
    {"inertial_hold_angle_deg", nullptr, "the rigid blocks from the rest, d = 1 lambda"}};
constexpr std::initializer_list<ColumnOutput> kSpheroHoldOutputs = {
    {"hold_angle_deg", "sphero_hold_angle_deg", "the rounded blocks (signature with the spheroradius)"},
    {"inertial_hold_angle_deg", "sphero_inertial_hold_angle_deg", "the rounded blocks"}};
// The hold angles over drops spread over the offset range (hold_statistics_columns()).
constexpr std::initializer_list<ColumnOutput> kHoldOverDrops = {
    {"mean_deg", "hold_mean_deg", "phi_qs (the derived Eq. 18)"},
    {"std_deg", "hold_std_deg", "phi_qs"},
    {"q05_deg", "hold_q05_deg", "phi_qs"},
    {"q50_deg", "hold_q50_deg", "phi_qs"},
    {"q95_deg", "hold_q95_deg", "phi_qs"},
    {"min_deg", "hold_min_deg", "phi_qs"},
    {"max_deg", "hold_max_deg", "phi_qs"}};
constexpr std::initializer_list<ColumnOutput> kInertialOverDrops = {{"mean_deg", "inertial_hold_mean_deg", "phi_in"},
                                                                    {"q05_deg", "inertial_hold_q05_deg", "phi_in"},
                                                                    {"q95_deg", "inertial_hold_q95_deg", "phi_in"}};

Result<Profile> envelope_of(const Curve& c, const char* what) {
  auto e = upper_envelope(c);
  if (!e) return with_prefix(std::string(what) + ": ", e.error());
  return e;
}

}  // namespace

/// The seed of face `stream` (1 lower, 2 upper) of the pair of task seed `seed`: a derived stream
/// of the task seed, shifted into the generators' seed range [0, 2^62) (their `seed` field is a
/// signed 64-bit integer below 9.2e18), so `frictal surface GENERATOR --seed` makes the same face.
static std::int64_t wm_tilt_face_seed(std::uint64_t seed, std::uint64_t stream) {
  return static_cast<std::int64_t>(derive_seed(seed, stream) >> 2);
}

Result<TaskOutput> run_wm_tilt_task(const Params& p, std::uint64_t seed) {
  auto generator = get_string(p, "generator", "wm");
  if (!generator) return generator.error();
  const GeneratorInfo* gen = find_generator(*generator);
  if (!gen) return make_error(fmt::format("parameter 'generator': unknown surface generator \"{}\"", *generator));
  if (Status st = kind_detail::no_threads_parameter(p); !st) return st.error();
  if (Status st = only_known_parameters(p, {&gen->fields, &tilt_settings()}, {"generator", "pair"}, "wm-tilt"); !st)
    return st.error();
  for (const char* fixed : {"seed", "runaway_distance", "series_interval"})
    if (p.count(fixed))
      return make_error(fmt::format(
          "parameter '{}': set by the wm-tilt kind (seeds: two streams of the task seed; run-away: 0.5, 1 and 2 "
          "lambda in one run; no series)",
          fixed));
  auto gen_values = table_values(gen->fields, p);
  if (!gen_values) return gen_values.error();
  const bool seeded =
      std::any_of(gen->fields.begin(), gen->fields.end(), [](const Field& f) { return f.name == "seed"; });
  if (*generator == "wm" && !gen_values->count("stochastic")) (*gen_values)["stochastic"] = true;

  // The pair: independent faces from two streams of the task seed, or one face twice.
  auto make_face = [&](std::uint64_t stream) -> Result<Curve> {
    ValueSet v = *gen_values;
    if (seeded) v["seed"] = wm_tilt_face_seed(seed, stream);
    auto spec = make_surface_spec(*generator, v);
    if (!spec) return spec.error();
    return generate_curve(*spec);
  };
  auto spec = make_surface_spec(*generator, *gen_values);
  if (!spec) return spec.error();
  auto period = surface_period(*spec);
  if (!period) return period.error();
  auto scale = surface_scale(*spec);
  if (!scale) return scale.error();
  auto all = surface_values(*spec);
  if (!all) return all.error();
  auto lower = make_face(1);
  if (!lower) return lower.error();
  auto upper = seeded ? make_face(2) : lower;
  if (!upper) return upper.error();

  auto settings = table_values(tilt_settings(), p);
  if (!settings) return settings.error();
  auto config = make_tilt_config(*settings, tilt_config_for_surface(*period, *scale));
  if (!config) return config.error();
  TiltConfig c = *config;
  const double lambda = *scale;
  c.series_interval = 0;
  c.runaway_distance = kRunaway[2] * lambda;
  c.runaway_checkpoints = {kRunaway[0] * lambda, kRunaway[1] * lambda, kRunaway[2] * lambda};

  // Eq. 18's sigma: the rigid signature of the faces the prediction uses (run_tilt: the upper
  // envelopes, offsets over one period, or the signature's default range without one).
  auto le = envelope_of(*lower, "lower surface");
  if (!le) return le.error();
  auto ue = envelope_of(*upper, "upper surface");
  if (!ue) return ue.error();
  SignatureOptions so;
  so.keep_contacts = false;
  so.threads = 1;
  if (c.period > 0) {
    so.offset_min = 0;
    so.offset_max = c.period;
    le->period.reset();
  }
  auto sig = signature(*le, rotate180(*ue), so);
  if (!sig) return with_prefix("signature for sigma (Eq. 18): ", sig.error());

  // Where the block starts. run_tilt takes the least lift h(s) over the offset range; without a
  // period that is often near the end of the range [0, L_b/2] (the overlap shrinks there and long
  // waves tilt h), on a slope or in a dip shallower than the contacts' resting overlap, and the
  // block slides at zero tilt (24 of 180 Fourier-filtered pairs did). Here, for non-periodic faces:
  // the least lift among the local minima of h inside the first half of the range with a forward
  // barrier -- h rises by at
  // least W/k_n (rho L_b h_b g / k_n, the block's resting overlap) ahead of it, within the range,
  // before falling below it; else the least interior local minimum; a given initial_offset, or a
  // periodic face, keeps run_tilt's rule. (The signature evaluates h exactly at its breakpoints,
  // where its minima lie.)
  int start_rule = 0;  // 0: run_tilt's, 1: interior local minimum, 2: with a forward barrier
  if (!p.count("initial_offset") && !(c.period > 0)) {
    const auto& h = sig->lift;
    const double length = le->x.back() - le->x.front();
    const double barrier = c.density * length * c.block_height * c.gravity / c.contact.normal_stiffness;
    double best[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    double at[2] = {0, 0};
    // The upper block's centroid over the middle half of the lower block (offset <= L_b/4 of the
    // range [0, L_b/2]): further out the block rests on the lower block's end and tips or slides
    // off (11 of 180 Fourier-filtered pairs started at 0.09-0.1 m slid at zero tilt).
    const double s_max = sig->offset.front() + 0.5 * (sig->offset.back() - sig->offset.front());
    for (std::size_t i = 1; i + 1 < h.size() && sig->offset[i] <= s_max; ++i) {
      if (!(h[i] <= h[i - 1] && h[i] <= h[i + 1])) continue;
      if (h[i] < best[0]) best[0] = h[i], at[0] = sig->offset[i];
      if (h[i] >= best[1]) continue;
      for (std::size_t j = i + 1; j < h.size() && h[j] >= h[i]; ++j)
        if (h[j] - h[i] >= barrier) {
          best[1] = h[i], at[1] = sig->offset[i];
          break;
        }
    }
    if (std::isfinite(best[1])) {
      c.initial_offset = at[1];
      start_rule = 2;
    } else if (std::isfinite(best[0])) {
      c.initial_offset = at[0];
      start_rule = 1;
    }
  }

  auto r = run_tilt_retrying(*lower, *upper, c);
  if (!r) return r.error();

  // What the test reads (hold.hpp): from where the block rests when the loading starts
  // (TiltResult::rest_offset; a periodic face's offset wrapped into its period, else kept in the
  // range), at the run-away distance of the 1 lambda reading; the rigid lift and the rounded
  // blocks' (spheroradius r). The lift covers the drops' range [0, L_b/2] or one period widened
  // by d on both sides (finite blocks).
  const double d_hold = kRunaway[1] * lambda;
  HoldOptions ho;
  ho.runaway_distance = d_hold;
  ho.atomic_friction = c.contact.atomic_friction;
  SignatureOptions hso = so;
  double rest = r->rest_offset;
  if (c.period > 0)
    rest -= std::floor(rest / c.period) * c.period;
  else
    rest = std::clamp(rest, 0.0, 0.5 * std::min(le->x.back() - le->x.front(), ue->x.back() - ue->x.front()));
  auto hold = analyse_hold(*le, rotate180(*ue), hso, ho, rest);
  if (!hold) return with_prefix("hold angle: ", hold.error());
  hso.spheroradius = c.radius;
  auto hold_r = analyse_hold(*le, rotate180(*ue), hso, ho, rest);
  if (!hold_r) return with_prefix("hold angle of the rounded blocks: ", hold_r.error());
  // The 10 k_n check reads the run's own run-away distance (2 lambda): its prediction is the
  // rounded blocks' hold angle at that distance.
  double stiff_hold = std::nan("");
  if (c.check_stiffness) {
    HoldOptions ho2 = ho;
    ho2.runaway_distance = kRunaway[2] * lambda;
    auto hold_r2 = analyse_hold(*le, rotate180(*ue), hso, ho2, rest);
    if (!hold_r2) return with_prefix("hold angle of the rounded blocks at 2 lambda: ", hold_r2.error());
    stiff_hold = (c.reverse ? hold_r2->start.backward : hold_r2->start.forward).hold_angle;
  }
  const HoldAngle& hq = c.reverse ? hold->start.backward : hold->start.forward;
  const HoldAngle& hr = c.reverse ? hold_r->start.backward : hold_r->start.forward;
  const HoldDistribution& hd = c.reverse ? hold->distribution.backward : hold->distribution.forward;

  TaskOutput out;
  auto& s = out.scalars;
  const double theta_a = std::atan(c.contact.atomic_friction);
  const double theta_max = r->predicted_theta_max;
  const double sigma = sig->contact_slope_std;  // one distribution for both directions
  const double low = theta_a + theta_max - sigma, high = r->predicted_friction_angle;
  double dim = std::nan("");
  if (all->count("dimension"))
    dim = as_real(all->at("dimension"));
  else if (all->count("hurst"))
    dim = 2 - as_real(all->at("hurst"));  // self-affine profile: D = 2 - H
  s["surface_dimension"] = dim;
  s["wavelength_m"] = lambda;
  // theta_max, the predictions, where the block was put down, the run's own numbers: the tilt
  // table's; sigma: the signature table's; theta_a: the friction table's.
  put_outputs(out, tilt_columns(), TiltReport{*r, c}, kTiltOutputs);
  put_outputs(out, tilt_scales_columns(), r->scales, kScalesOutputs);
  put_outputs(out, signature_columns(), *sig, kSignatureOutputs);
  auto theta_a_of = predict_friction(c.contact.atomic_friction, 0, 0);  // theta_a alone
  if (!theta_a_of) return theta_a_of.error();
  put_outputs(out, friction_columns(), *theta_a_of, kFrictionOutputs);
  s["theta_max_signature_deg"] = (c.reverse ? sig->theta_max_backward : sig->theta_max_forward) / kDeg;
  s["eq18_low_deg"] = low / kDeg;
  s["start_rule"] = start_rule;
  s["final_displacement_m"] = r->final_displacement;
  for (int k = 0; k < 3; ++k) {
    const TiltCheckpoint& cp = r->checkpoints[static_cast<std::size_t>(k)];
    const std::string n = kRunawayName[k];
    s["slid_" + n] = cp.reached ? 1 : 0;
    s["friction_angle_" + n + "_deg"] = cp.reached ? cp.friction_angle / kDeg : std::nan("");
    s["slide_start_" + n + "_m"] = cp.reached ? cp.slide_start_displacement : std::nan("");
  }
  const TiltCheckpoint& one = r->checkpoints[1];
  s["slid"] = one.reached ? 1 : 0;
  const double phi = one.reached ? one.friction_angle : std::nan("");
  s["friction_angle_deg"] = phi / kDeg;
  s["displacement_before_slide_m"] = one.reached ? one.slide_start_displacement : std::nan("");
  s["slide_distance_m"] = r->slid ? r->final_displacement - r->slide_start_displacement : std::nan("");
  s["friction_minus_rigid_deg"] = (phi - high) / kDeg;
  s["friction_minus_sphero_deg"] = (phi - r->predicted_sphero_friction_angle) / kDeg;
  s["inside_eq18"] = one.reached && phi >= low && phi <= high ? 1 : 0;
  put_outputs(out, hold_drop_columns(), hq, kHoldOutputs);
  put_outputs(out, hold_drop_columns(), hr, kSpheroHoldOutputs);
  s["friction_minus_hold_deg"] = (phi - hq.hold_angle) / kDeg;
  s["friction_minus_sphero_hold_deg"] = (phi - hr.hold_angle) / kDeg;
  // Between the inertial bound and the quasi-static angle of the rounded blocks (the simulated
  // ones), with 0.1 deg of slack.
  {
    const double lo = std::min(hr.inertial_hold_angle, hr.hold_angle) / kDeg - 0.1, hi = hr.hold_angle / kDeg + 0.1;
    s["inside_hold_bracket"] = one.reached && phi / kDeg >= lo && phi / kDeg <= hi ? 1 : 0;
  }
  // check_stiffness: the same run at 10 k_n, read at the run's run-away distance (2 lambda), so
  // judged against the rounded blocks' hold angle at 2 lambda (the quasi-static chain may go on
  // past a stop that holds at 1 lambda).
  s["sphero_hold_angle_two_lambda_deg"] = stiff_hold / kDeg;
  s["stiff_minus_sphero_hold_deg"] = (r->stiff_friction_angle - stiff_hold) / kDeg;
  put_outputs(out, hold_statistics_columns(), hd.hold, kHoldOverDrops);
  put_outputs(out, hold_statistics_columns(), hd.inertial, kInertialOverDrops);
  s["hold_basins"] = static_cast<double>(hd.basins.rest.size());
  s["smallest_feature_m"] = std::min(r->scales.smallest_feature[0], r->scales.smallest_feature[1]);
  s["points"] = static_cast<double>(lower->size());
  kind_detail::put_tilt_warnings(s, *r);
  return out;
}

// ---------------------------------------------------------------- report section

namespace {

struct Acc {
  std::vector<double> v;
  void add(double x) {
    if (std::isfinite(x)) v.push_back(x);
  }
  double mean() const {
    if (v.empty()) return std::nan("");
    double s = 0;
    for (double x : v) s += x;
    return s / static_cast<double>(v.size());
  }
};

double get(const std::map<std::string, double>& s, const std::string& k) {
  auto it = s.find(k);
  return it == s.end() ? std::nan("") : it->second;
}

void wm_tilt_part(const std::string& part, const std::vector<Store::Row>& rows, Report& rep) {
  // A quasi-static part reads the hold angle at its run-away distance: only that is judged there
  // (the Eq. 18 and run-away-distance findings are the dynamic test's, and the distribution over
  // drops does not depend on the protocol).
  bool quasi_static = false, from_rest = false;
  if (!rows.empty()) {
    if (auto pr = get_string(rows.front().params, "protocol", "constant-rate"); pr)
      quasi_static = *pr == "quasi-static";
    if (auto st = get_string(rows.front().params, "settling", "free"); st) from_rest = *st == "relax";
  }
  // The paper's test (constant rate, free settling) answers the paper's Eq. 18 and the questions
  // of frictal's own findings (run-away distance, rigid or rounded prediction), and its pairs give the hold angles
  // over drops; a constant-rate test from rest (settling = relax) answers only whether it reads an
  // angle between phi_in and phi_qs, a quasi-static one only whether it reads phi_qs.
  const bool paper_protocol = !quasi_static && !from_rest;
  struct Cell {
    int n = 0, slid = 0, inside = 0, below = 0, above = 0, warned = 0;
    int rot = 0, rot_inside = 0, rot_below = 0, rot_above = 0;  // runs with the rotation warning
    int unsettled = 0, uns_inside = 0;                          // runs with the unsettled warning
    Acc phi[3], tmax, sigma, low, sphero, d_rigid, d_sphero, offset, before, slide;
  };
  std::map<double, Cell> by_d;  // surface dimension (rounded to 1e-9) -> cell
  Cell all;
  int closer_sphero = 0, closer_rigid = 0, ties = 0, monotone_fail = 0, same_all = 0, with_three = 0;
  double max_pred_gap = 0;
  Acc spread, d_half, d_two, pred_gap, err_rigid, err_sphero;
  constexpr double kDistinct = 0.01;  // deg: predictions closer than this are not told apart
  for (const auto& row : rows) {
    const auto& s = row.output.scalars;
    if (!s.count("friction_angle_deg") || !s.count("theta_max_deg")) continue;
    const double D = std::round(get(s, "surface_dimension") * 1e9) / 1e9;
    for (Cell* c : {&by_d[D], &all}) {
      ++c->n;
      const bool slid = get(s, "slid") > 0;
      c->slid += slid;
      for (int k = 0; k < 3; ++k) c->phi[k].add(get(s, std::string("friction_angle_") + kRunawayName[k] + "_deg"));
      c->tmax.add(get(s, "theta_max_deg"));
      c->sigma.add(get(s, "sigma_deg"));
      c->low.add(get(s, "eq18_low_deg"));
      c->sphero.add(get(s, "predicted_sphero_friction_angle_deg"));
      c->d_rigid.add(std::abs(get(s, "friction_minus_rigid_deg")));
      c->d_sphero.add(std::abs(get(s, "friction_minus_sphero_deg")));
      c->offset.add(get(s, "initial_offset_m"));
      c->before.add(get(s, "displacement_before_slide_m"));
      c->slide.add(get(s, "final_displacement_m"));
      const double phi = get(s, "friction_angle_deg");
      if (slid) {
        const bool turned = get(s, "warning_rotation") > 0;
        c->rot += turned;
        if (get(s, "inside_eq18") > 0) {
          ++c->inside;
          c->rot_inside += turned;
        } else if (phi < get(s, "eq18_low_deg")) {
          ++c->below;
          c->rot_below += turned;
        } else {
          ++c->above;
          c->rot_above += turned;
        }
      }
      c->warned += get(s, "warning_core_overlap") + get(s, "warning_rounding") + get(s, "warning_time_step") +
                       get(s, "warning_rotation") >
                   0;
      if (get(s, "warning_unsettled") > 0) {
        ++c->unsettled;
        c->uns_inside += get(s, "inside_eq18") > 0;
      }
    }
    // Rigid or spheropolygon: judged only where the two predictions differ by more than
    // kDistinct (else the simulation cannot tell them apart).
    const double dr = std::abs(get(s, "friction_minus_rigid_deg")), ds = std::abs(get(s, "friction_minus_sphero_deg"));
    const double gap = std::abs(get(s, "predicted_friction_angle_deg") - get(s, "predicted_sphero_friction_angle_deg"));
    if (std::isfinite(dr) && std::isfinite(ds) && std::isfinite(gap)) {
      max_pred_gap = std::max(max_pred_gap, gap);
      pred_gap.add(gap);
      if (gap <= kDistinct) {
        ++ties;
      } else {
        (ds < dr ? closer_sphero : closer_rigid)++;
        err_rigid.add(dr);
        err_sphero.add(ds);
      }
    }
    const double a = get(s, "friction_angle_half_lambda_deg"), b = get(s, "friction_angle_lambda_deg"),
                 c2 = get(s, "friction_angle_two_lambda_deg");
    if (std::isfinite(a) && std::isfinite(b) && std::isfinite(c2)) {
      ++with_three;
      spread.add(c2 - a);
      d_half.add(a - b);
      d_two.add(c2 - b);
      if (a == b && b == c2) ++same_all;
    }
    // Slide starts move forward with the run-away distance (a longer run-away starts no earlier).
    const double s0 = get(s, "slide_start_half_lambda_m"), s1 = get(s, "slide_start_lambda_m"),
                 s2 = get(s, "slide_start_two_lambda_m");
    if (std::isfinite(s0) && std::isfinite(s1) && std::isfinite(s2) && !(s0 <= s1 && s1 <= s2)) ++monotone_fail;
  }
  if (!all.n) return;
  rep.lines.push_back(fmt::format("\n## Part '{}' (wm-tilt): {} pairs, {} values of D", part, all.n, by_d.size()));
  std::string t =
      "\n| D | pairs | slid | phi 0.5 lambda (deg) | phi 1 lambda (deg) | phi 2 lambda (deg) | theta_max (deg) | "
      "sigma (deg) | theta_max - sigma (deg) | sphero prediction (deg) | inside Eq. 18 | below | above | "
      "mean abs(sim - rigid) (deg) | mean abs(sim - sphero) (deg) | crept before slide (m) | warned | unsettled |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [D, c] : by_d)
    t += fmt::format(
        "| {:.2f} | {} | {} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {} | {} | {} | {:.3f} | "
        "{:.3f} | {:.3g} | {} | {} |\n",
        D, c.n, c.slid, c.phi[0].mean(), c.phi[1].mean(), c.phi[2].mean(), c.tmax.mean(), c.sigma.mean(), c.low.mean(),
        c.sphero.mean(), c.inside, c.below, c.above, c.d_rigid.mean(), c.d_sphero.mean(), c.before.mean(), c.warned,
        c.unsettled);
  rep.lines.push_back(t);
  rep.lines.push_back(
      "\nMeans over the pairs of each D; phi at run-away distance d is the tilt at the start of the first run-away "
      "of length d (one run per pair, stopped at 2 lambda); the Eq. 18 range is [theta_max - sigma, theta_max] + "
      "theta_a, judged on phi at 1 lambda.");

  // F1: Eq. 18 range.
  if (paper_protocol) {
    Finding f;
    f.claim_id = "eq18-range";
    f.part = part;
    f.claim = fmt::format(
        "Part '{}': the simulated friction angle of random pairs lies in the Eq. 18 range "
        "[theta_max - sigma, theta_max] + theta_a (run-away 1 lambda).",
        part);
    const double frac = all.slid ? double(all.inside) / all.slid : 0;
    f.supported = all.slid > 0 && all.slid == all.n && frac >= 0.9;
    f.evidence.push_back(fmt::format(
        "criterion: every block slid and at least 90% of the angles lie in the range; {} of {} slid, {} of them "
        "inside ({:.0f}%), {} below, {} above",
        all.slid, all.n, all.inside, 100 * frac, all.below, all.above));
    std::string per;
    for (const auto& [D, c] : by_d) per += fmt::format(" D={:.1f}: {}/{}", D, c.inside, c.slid);
    f.evidence.push_back("inside per D:" + per);
    {  // where the angles fall relative to the rigid prediction, in degrees and in units of sigma
      double m = 0, m2 = 0, z = 0;
      int n = 0, within_sigma = 0;
      for (const auto& row : rows) {
        const auto& sc = row.output.scalars;
        const double d = get(sc, "friction_minus_rigid_deg"), sg = get(sc, "sigma_deg");
        if (!std::isfinite(d) || !std::isfinite(sg) || sg <= 0) continue;
        ++n;
        m += d;
        m2 += d * d;
        z += d / sg;
        within_sigma += std::abs(d) <= sg;
      }
      if (n > 1) {
        m /= n;
        f.evidence.push_back(fmt::format(
            "phi - (theta_max + theta_a): mean {:+.3f} deg, standard deviation {:.3f} deg, mean in units of sigma "
            "{:+.2f}; |phi - theta_max - theta_a| <= sigma in {} of {} pairs",
            m, std::sqrt(std::max(0.0, (m2 - n * m * m) / (n - 1))), z / n, within_sigma, n));
      }
    }
    f.evidence.push_back(fmt::format(
        "runs flagged 'unsettled' (the block still moved when the tilt started): {}, {} of them inside; not "
        "flagged: {}, {} inside",
        all.unsettled, all.uns_inside, all.n - all.unsettled, all.inside - all.uns_inside));
    f.evidence.push_back(fmt::format(
        "runs flagged 'rotation' (the upper block turned before the slide; the signature assumes it does not): {} -- "
        "{} inside, {} below, {} above; unflagged: {} inside, {} below, {} above",
        all.rot, all.rot_inside, all.rot_below, all.rot_above, all.inside - all.rot_inside, all.below - all.rot_below,
        all.above - all.rot_above));
    if (!f.supported) {  // what a test reads instead: the hold angle from the rest, in its bracket
      int n = 0, qs_inside = 0, bracket = 0;
      for (const auto& row : rows) {
        const auto& sc = row.output.scalars;
        const double q = get(sc, "sphero_hold_angle_deg");
        if (!std::isfinite(q)) continue;
        ++n;
        qs_inside += q >= get(sc, "eq18_low_deg") && q <= get(sc, "eq18_high_deg");
        bracket += get(sc, "inside_hold_bracket") > 0;
      }
      if (n > 0)
        f.cause = fmt::format(
            "Eq. 18 brackets theta_max, the steepest contact over all offsets, and a test reads where a block resting "
            "at one offset lets go: the hold angle phi_qs from each run's rest offset lies inside Eq. 18's range in "
            "{} of {} pairs, and the simulated angle inside its own bracket [phi_in - 0.1, phi_qs + 0.1] in {} of {}; "
            "{} runs are flagged 'unsettled' (the block still moved when the tilt started)",
            qs_inside, n, bracket, n, all.unsettled);
    }
    rep.findings.push_back(f);
  }
  // F-hold: what a test reads (hold.hpp) against the simulation, and the distribution over drops
  // against Eq. 18.
  {
    std::string protocol = "constant-rate";
    if (!rows.empty())
      if (auto pr = get_string(rows.front().params, "protocol", "constant-rate"); pr) protocol = *pr;
    const bool qs = protocol == "quasi-static";
    int n = 0, judged = 0, in_bracket = 0, within = 0, within_rigid = 0, flagged = 0, above_qs = 0, below_in = 0;
    int stiff_n = 0, stiff_within = 0, stiff_warned = 0, converged_within = 0, unsettled = 0, unrelaxed = 0;
    Acc err_qs, stiff_err, excess, overlap;
    struct HoldCell {
      Acc low, high, mean, std, q05, q95, in_mean, sim;
      int covered = 0, n = 0;
    };
    std::map<double, HoldCell> hold_by_d;
    for (const auto& row : rows) {
      const auto& sc = row.output.scalars;
      if (!sc.count("hold_angle_deg") || !(get(sc, "slid") > 0)) continue;
      ++n;
      bool flag = false;  // warnings a kind version may not have are absent (NaN): not raised
      for (const char* w : {"warning_rotation", "warning_unsettled", "warning_core_overlap", "warning_time_step",
                            "warning_unrelaxed", "warning_stiffness"})
        flag = flag || get(sc, w) > 0;
      flagged += flag;
      unsettled += get(sc, "warning_unsettled") > 0;
      unrelaxed += get(sc, "warning_unrelaxed") > 0;
      overlap.add(get(sc, "resting_overlap_m"));
      const double dq = get(sc, "friction_minus_sphero_hold_deg");
      if (std::abs(dq) <= 0.1) ++within;
      const double ds = get(sc, "stiff_minus_sphero_hold_deg");
      if (std::isfinite(ds)) {
        ++stiff_n;
        stiff_within += std::abs(ds) <= 0.1;
        stiff_err.add(std::abs(ds));
        stiff_warned += get(sc, "warning_stiffness") > 0;
        converged_within += !(get(sc, "warning_stiffness") > 0) && std::abs(ds) <= 0.1;
      }
      excess.add(dq);
      if (std::abs(get(sc, "friction_minus_hold_deg")) <= 0.1) ++within_rigid;
      err_qs.add(std::abs(dq));
      if (!flag) {
        ++judged;
        in_bracket += get(sc, "inside_hold_bracket") > 0;
        above_qs += dq > 0.1;
        below_in += get(sc, "friction_angle_deg") < get(sc, "sphero_inertial_hold_angle_deg") - 0.1;
      }
      const double D = std::round(get(sc, "surface_dimension") * 1e9) / 1e9;
      HoldCell& hc = hold_by_d[D];
      ++hc.n;
      hc.low.add(get(sc, "eq18_low_deg"));
      hc.high.add(get(sc, "eq18_high_deg"));
      hc.mean.add(get(sc, "hold_mean_deg"));
      hc.std.add(get(sc, "hold_std_deg"));
      hc.q05.add(get(sc, "hold_q05_deg"));
      hc.q95.add(get(sc, "hold_q95_deg"));
      hc.in_mean.add(get(sc, "inertial_hold_mean_deg"));
      hc.sim.add(get(sc, "friction_angle_deg"));
      hc.covered += get(sc, "hold_q05_deg") >= get(sc, "eq18_low_deg") - 0.1 &&
                    get(sc, "hold_q95_deg") <= get(sc, "eq18_high_deg") + 0.1;
    }
    if (n > 0) {
      if (qs || from_rest) {  // the reading of a test from rest (the paper's test is flagged 'unsettled')
        Finding f;
        f.claim_id = qs ? "quasi-static-hold" : "dynamic-hold-bracket";
        f.part = part;
        if (qs) {
          f.claim = fmt::format(
              "Part '{}': the quasi-static tilt reads the hold angle phi_qs of the rounded blocks from where the block "
              "rests, within 0.1 deg, in at least 95 % of the pairs.",
              part);
          // Judged at the stiffer of the two stiffnesses when check_stiffness ran (the rigid limit).
          const int ok = stiff_n > 0 ? stiff_within : within, of = stiff_n > 0 ? stiff_n : n;
          f.supported = of > 0 && ok >= 0.95 * of;
          if (stiff_n > 0)
            f.evidence.push_back(fmt::format(
                "criterion: |phi - phi_qs| <= 0.1 deg in >= 95 % of the pairs that slid, judged at 10 k_n "
                "(check_stiffness); there {} of {} ({:.0f} %), mean |phi - phi_qs| = {:.3f} deg; the 10 k_n run moved "
                "the angle by more than 0.1 deg (not converged, 'stiffness') in {} pairs, and {} pairs are converged "
                "and within 0.1 deg",
                ok, of, of ? 100.0 * ok / of : 0.0, stiff_err.mean(), stiff_warned, converged_within));
          else
            f.evidence.push_back(fmt::format(
                "criterion: |phi - phi_qs| <= 0.1 deg in >= 95 % of the pairs that slid, at the part's own k_n (no "
                "10 k_n check); {} of {} ({:.0f} %)",
                ok, of, of ? 100.0 * ok / of : 0.0));
          f.evidence.push_back(fmt::format(
              "at the part's own k_n: within 0.1 deg of phi_qs (rounded) in {} of {} pairs, of the rigid phi_qs in {}; "
              "mean phi - phi_qs = {:+.3f} deg, mean |phi - phi_qs| = {:.3f} deg",
              within, n, within_rigid, excess.mean(), err_qs.mean()));
          if (!f.supported && (unrelaxed > 0 || stiff_warned > 0))
            f.cause = fmt::format(
                "the contacts are not in the rigid limit at this k_n: the block rests {:.3g} m deep in the lower one "
                "(W / k_n, mean), {} of {} runs did not relax within relax_time ('unrelaxed'), the 10 k_n rerun moved "
                "{} by more than 0.1 deg ('stiffness'); mean phi - phi_qs = {:+.3f} deg",
                overlap.mean(), unrelaxed, n, stiff_warned, excess.mean());
        } else {
          f.claim = fmt::format(
              "Part '{}': the constant-rate (dynamic) tilt reads an angle between the inertial bound phi_in and the "
              "quasi-static hold angle phi_qs of the rounded blocks (0.1 deg of slack) in at least 90 % of the pairs "
              "no warning flags.",
              part);
          f.supported = judged > 0 && in_bracket >= 0.9 * judged;
          f.evidence.push_back(fmt::format(
              "criterion: inside [phi_in - 0.1, phi_qs + 0.1] deg in >= 90 % of the unflagged pairs; {} of {} ({:.0f} "
              "%); above phi_qs: {}, below phi_in: {}; flagged (rotation, unsettled, core-overlap, time-step, "
              "unrelaxed, stiffness): {}",
              in_bracket, judged, judged ? 100.0 * in_bracket / judged : 0.0, above_qs, below_in, flagged));
          f.evidence.push_back(fmt::format(
              "within 0.1 deg of phi_qs (rounded) in {} of {} pairs; of the rigid phi_qs in {}; mean |phi - phi_qs| "
              "= {:.3f} deg",
              within, n, within_rigid, err_qs.mean()));
          if (!f.supported && 2 * flagged >= n)
            f.cause = fmt::format(
                "{} of {} runs are flagged and cannot be judged, {} of them 'unsettled': with the paper's free "
                "settling and mu_a = 0 the block still glides when the tilt starts, so it does not start from rest "
                "where phi_in and phi_qs are computed (a test from rest: settling = relax, turn = gravity, a slow "
                "tilt_rate)",
                flagged, n, unsettled);
        }
        rep.findings.push_back(f);
      }
      // The distribution over drops: Eq. 18 derived.
      std::string t = fmt::format(
          "\nPart '{}': Eq. 18 derived. The hold angle phi_qs over drops spread uniformly over the offset range "
          "(each basin of h weighted by its width; run-away 1 lambda; means over the pairs of each D) beside Eq. "
          "18's heuristic range.\n\n| D | pairs | Eq. 18 low (deg) | Eq. 18 high = theta_max + theta_a (deg) | "
          "phi_qs mean (deg) | phi_qs std (deg) | phi_qs 5 % (deg) | phi_qs 95 % (deg) | phi_in mean (deg) | "
          "simulated mean (deg) | pairs whose 5-95 % lie in Eq. 18 |\n|---|---|---|---|---|---|---|---|---|---|---|\n",
          part);
      int covered = 0, total = 0;
      for (const auto& [D, hc] : hold_by_d) {
        t += fmt::format(
            "| {:.2f} | {} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.3f} | {} |\n", D, hc.n,
            hc.low.mean(), hc.high.mean(), hc.mean.mean(), hc.std.mean(), hc.q05.mean(), hc.q95.mean(),
            hc.in_mean.mean(), hc.sim.mean(), hc.covered);
        covered += hc.covered;
        total += hc.n;
      }
      rep.lines.push_back(t);
      if (!paper_protocol) return;  // the rest is the paper's test's
      Finding g;
      g.claim_id = "eq18-over-drops";
      g.part = part;
      g.claim = fmt::format(
          "Part '{}': Eq. 18's range [theta_max - sigma, theta_max] + theta_a holds the central 90 % of the hold "
          "angles that repeated drops give (0.1 deg of slack), in at least 90 % of the pairs.",
          part);
      g.supported = total > 0 && covered >= 0.9 * total;
      g.evidence.push_back(fmt::format(
          "criterion: per pair, the 5 % and 95 % quantiles of phi_qs over drops inside the Eq. 18 range +- 0.1 deg; "
          "{} of {} pairs ({:.0f} %)",
          covered, total, total ? 100.0 * covered / total : 0.0));
      std::string per;
      for (const auto& [D, hc] : hold_by_d)
        per += fmt::format(" D={:.1f}: mean {:.3f} vs Eq. 18 mid {:.3f};", D, hc.mean.mean(),
                           0.5 * (hc.low.mean() + hc.high.mean()));
      g.evidence.push_back("phi_qs over drops against the Eq. 18 range (deg):" + per);
      if (!g.supported) {  // which end of the range the drops leave, and the widths
        int low_out = 0, high_out = 0;
        Acc width, sig;
        for (const auto& row : rows) {
          const auto& sc = row.output.scalars;
          if (!sc.count("hold_angle_deg") || !(get(sc, "slid") > 0)) continue;
          low_out += get(sc, "hold_q05_deg") < get(sc, "eq18_low_deg") - 0.1;
          high_out += get(sc, "hold_q95_deg") > get(sc, "eq18_high_deg") + 0.1;
          width.add(get(sc, "hold_q95_deg") - get(sc, "hold_q05_deg"));
          sig.add(get(sc, "sigma_deg"));
        }
        g.cause = fmt::format(
            "Eq. 18's range is a heuristic width, not the spread of where dropped blocks hold: the 5 % quantile of "
            "phi_qs over drops lies below theta_max - sigma - 0.1 in {} of {} pairs and the 95 % quantile above "
            "theta_max + theta_a + 0.1 in {}; the central 90 % spans {:.3f} deg on average against a mean sigma of "
            "{:.3f} deg",
            low_out, total, high_out, width.mean(), sig.mean());
      }
      rep.findings.push_back(g);
    }
  }
  if (!paper_protocol) return;
  // F2: run-away distance.
  if (with_three > 0) {
    Finding f;
    f.claim_id = "runaway-independent";
    f.part = part;
    f.claim = fmt::format(
        "Part '{}': the simulated friction angle does not depend on the run-away distance (0.5, 1, 2 lambda).", part);
    const double m = spread.mean();
    double worst = 0;
    for (double x : spread.v) worst = std::max(worst, std::abs(x));
    f.supported = std::abs(m) <= 0.1 && worst <= 0.5;
    f.evidence.push_back(fmt::format(
        "criterion: mean |phi(2 lambda) - phi(0.5 lambda)| <= 0.1 deg and none above 0.5 deg; mean phi(2 lambda) - "
        "phi(0.5 lambda) = {:+.3f} deg, largest {:.3f} deg; equal at all three distances in {} of {} pairs",
        m, worst, same_all, with_three));
    f.evidence.push_back(
        fmt::format("mean phi(0.5 lambda) - phi(1 lambda) = {:+.3f} deg, phi(2 lambda) - phi(1 "
                    "lambda) = {:+.3f} deg",
                    d_half.mean(), d_two.mean()));
    std::string per;
    for (const auto& [D, c] : by_d)
      per += fmt::format(" D={:.1f}: {:.3f}/{:.3f}/{:.3f}", D, c.phi[0].mean(), c.phi[1].mean(), c.phi[2].mean());
    f.evidence.push_back("mean phi at 0.5/1/2 lambda (deg):" + per);
    f.evidence.push_back(fmt::format("slide starts monotone in the run-away distance in {} of {} pairs",
                                     with_three - monotone_fail, with_three));
    rep.findings.push_back(f);
  }
  // F3: rigid or spheropolygon prediction.
  {
    Finding f;
    f.claim_id = "sphero-closer-than-rigid";
    f.part = part;
    f.claim = fmt::format(
        "Part '{}': the spheropolygon prediction (signature with the spheroradius) is closer to the simulated angle "
        "than the rigid one (Eq. 6).",
        part);
    const int judged = closer_sphero + closer_rigid;
    // A sign test: with no preference the difference of the two counts has standard deviation
    // sqrt(judged); a preference needs it above two of them.
    const double margin = 2 * std::sqrt(static_cast<double>(judged));
    f.supported = judged > 0 && closer_sphero - closer_rigid > margin && err_sphero.mean() < err_rigid.mean();
    f.evidence.push_back(fmt::format(
        "criterion: among the pairs whose two predictions differ by more than {:g} deg, clearly more are closer to "
        "the spheropolygon prediction (a sign test: their excess must exceed 2 sqrt(pairs) = {:.1f}), with a smaller "
        "mean error; {} such pairs of {}: closer to sphero in {}, to rigid in {}; there mean |sim - rigid| = {:.3f} "
        "deg, "
        "mean |sim - sphero| = {:.3f} deg",
        kDistinct, margin, judged, judged + ties, closer_sphero, closer_rigid, err_rigid.mean(), err_sphero.mean()));
    f.evidence.push_back(fmt::format(
        "|rigid - sphero prediction|: mean {:.4f} deg, largest {:.4f} deg; over all pairs mean |sim - rigid| = {:.3f} "
        "deg, mean |sim - sphero| = {:.3f} deg",
        pred_gap.mean(), max_pred_gap, all.d_rigid.mean(), all.d_sphero.mean()));
    if (judged == 0)
      f.evidence.push_back("the rounding changes the prediction by too little anywhere to tell the two apart");
    if (!f.supported)
      f.cause = fmt::format(
          "the spheroradius moves the prediction by {:.4f} deg on average (largest {:.4f}): by more than {:g} deg in "
          "only {} of {} pairs, too few and too little for the test, while the simulated angles differ from both "
          "predictions by {:.3f} deg on average -- they read the hold angle from the rest, not theta_max",
          pred_gap.mean(), max_pred_gap, kDistinct, judged, judged + ties, all.d_rigid.mean());
    rep.findings.push_back(f);
  }
}

/// Variants (other axes than D, hurst, pair) are reported separately, e.g. spheroradius.
void wm_tilt_section(const std::string& part, const std::vector<TaskRow>& rows, Report& rep) {
  for (const auto& [label, vrows] : variants_of(part, rows, {"dimension", "hurst", "pair"}))
    wm_tilt_part(label, vrows, rep);
}

}  // namespace

// ---------------------------------------------------------------- the kind

TaskKind wm_tilt_kind() {
  TaskKind k;
  k.name = "wm-tilt";
  k.description =
      "Spheropolygon tilt test of a random pair (WM or any seeded generator) beside its Eq. 18 range; friction angle "
      "at run-away 0.5, 1, 2 lambda";
  k.version = 8;  // 2: the creep warning; 3: the hold angle; 4: from the engine's rest offset, protocols; 5: contact
                  // rule (quasi-static: closest); 6: the 10 k_n check judged at 2 lambda; 7: closest counts
                  // concave corners by inclusion-exclusion; 8: rest test on the averaged force
  k.run = run_wm_tilt_task;
  k.outputs = {
      {"surface_dimension", "1", "fractal dimension D of the faces (wm: dimension; self-affine, fourier: 2 - hurst)"},
      {"wavelength_m", "m", "lambda: the surface's scale (wm: longest wavelength), unit of the run-away distances"},
      {"slid", "1", "1 if the block ran away by 1 lambda before max_tilt"},
      {"friction_angle_deg", "deg", "simulated friction angle, run-away 1 lambda"},
      {"slid_half_lambda", "1", "1 if a run-away of 0.5 lambda happened"},
      {"slid_lambda", "1", "1 if a run-away of 1 lambda happened"},
      {"slid_two_lambda", "1", "1 if a run-away of 2 lambda happened"},
      {"friction_angle_half_lambda_deg", "deg", "tilt at the start of the first run-away of 0.5 lambda"},
      {"friction_angle_lambda_deg", "deg", "tilt at the start of the first run-away of 1 lambda"},
      {"friction_angle_two_lambda_deg", "deg", "tilt at the start of the first run-away of 2 lambda"},
      {"slide_start_half_lambda_m", "m", "displacement since settling where that run-away started"},
      {"slide_start_lambda_m", "m", "displacement since settling where that run-away started"},
      {"slide_start_two_lambda_m", "m", "displacement since settling where that run-away started"},
      {"theta_max_signature_deg", "deg",
       "theta_max in the sliding direction from the kind's own signature (the one giving sigma)"},
      {"eq18_low_deg", "deg", "theta_a + theta_max - sigma: lower end of the Eq. 18 range"},
      {"friction_minus_rigid_deg", "deg", "simulated (1 lambda) minus rigid prediction"},
      {"friction_minus_sphero_deg", "deg", "simulated (1 lambda) minus spheropolygon prediction"},
      {"inside_eq18", "1", "1 if the simulated angle (1 lambda) lies in the Eq. 18 range"},
      {"friction_minus_hold_deg", "deg", "simulated (1 lambda) minus phi_qs (rigid)"},
      {"friction_minus_sphero_hold_deg", "deg", "simulated (1 lambda) minus phi_qs (rounded)"},
      {"inside_hold_bracket", "1",
       "1 if the simulated angle lies in [phi_in, phi_qs] of the rounded blocks, with 0.1 deg of slack"},
      {"sphero_hold_angle_two_lambda_deg", "deg", "check_stiffness: phi_qs of the rounded blocks at d = 2 lambda"},
      {"stiff_minus_sphero_hold_deg", "deg", "that angle minus phi_qs of the rounded blocks at 2 lambda (its d)"},
      {"hold_basins", "1", "basins of h over the offset range"},
      {"start_rule", "1",
       "how the start was chosen: 2 least lift among the local minima of h(s) in the first half of the offset range "
       "with a forward barrier >= W/k_n, 1 the least such minimum (none had one), 0 run_tilt's least lift "
       "(periodic faces or initial_offset given)"},
      {"displacement_before_slide_m", "m", "how far the block moved between settling and the 1 lambda run-away"},
      {"slide_distance_m", "m", "how far it slid from the start of the last run-away to the end of the run"},
      {"final_displacement_m", "m", "displacement since settling when the run stopped"},
      {"smallest_feature_m", "m", "shortest run between neighbouring extrema of either face"},
      {"points", "1", "points of each face"},
  };
  const std::vector<OutputColumn> warning_columns = kind_detail::tilt_warning_columns();
  k.outputs.insert(k.outputs.end(), warning_columns.begin(), warning_columns.end());
  for (const auto& table : {outputs_of("tilt", tilt_columns(), kTiltOutputs),
                            outputs_of("tilt_scales", tilt_scales_columns(), kScalesOutputs),
                            outputs_of("friction", friction_columns(), kFrictionOutputs),
                            outputs_of("signature", signature_columns(), kSignatureOutputs),
                            outputs_of("hold_drop", hold_drop_columns(), kHoldOutputs),
                            outputs_of("hold_drop", hold_drop_columns(), kSpheroHoldOutputs),
                            outputs_of("hold_statistics", hold_statistics_columns(), kHoldOverDrops),
                            outputs_of("hold_statistics", hold_statistics_columns(), kInertialOverDrops)})
    k.outputs.insert(k.outputs.end(), table.begin(), table.end());
  k.report = wm_tilt_section;
  const PlotAxis x{"surface_dimension", "D"};
  k.plots.push_back(PlotView::of("wm-tilt-friction", x, {"friction_angle_deg", "friction angle φ (deg)"})
                        .named("{generator}: simulation, each pair")
                        .markers("o", 3, 0));
  k.plots.back().open = true;
  k.plots.back().line = false;
  k.plots.back().color = "k";
  k.plots.push_back(PlotView::of("wm-tilt-friction-mean", x, {"friction_angle_deg", "friction angle φ (deg)"})
                        .named("{generator}: simulation, mean")
                        .markers("o", 5, 1.5)
                        .averaged_over("pair"));
  k.plots.back().color = "k";
  k.plots.push_back(PlotView::of("wm-tilt-theta-max", x, {"eq18_high_deg", "friction angle φ (deg)"})
                        .named("θ_max + θ_a (Eq. 6, rigid), mean")
                        .markers("^", 5, 1.5)
                        .averaged_over("pair"));
  k.plots.back().color = "C0";
  k.plots.push_back(PlotView::of("wm-tilt-eq18-low", x, {"eq18_low_deg", "friction angle φ (deg)"})
                        .named("θ_max − σ + θ_a (Eq. 18), mean")
                        .markers("v", 5, 1.5)
                        .averaged_over("pair"));
  k.plots.back().color = "C0";
  k.plots.push_back(PlotView::of("wm-tilt-sphero", x, {"predicted_sphero_friction_angle_deg", "friction angle φ (deg)"})
                        .named("spheropolygon prediction (r), mean")
                        .markers("s", 4, 1)
                        .averaged_over("pair"));
  k.plots.back().color = "C1";
  k.plots.back().open = true;
  for (int i = 0; i < 3; ++i) {
    const std::string n = kRunawayName[i];
    k.plots.push_back(PlotView::of("wm-tilt-friction-" + n, x, {"friction_angle_" + n + "_deg", "mean φ (deg)"})
                          .named(fmt::format("run-away {:g} λ", kRunaway[i]))
                          .markers(i == 0   ? "o"
                                   : i == 1 ? "s"
                                            : "^",
                                   9 - 2.5 * i, 1.2)
                          .averaged_over("pair"));
    k.plots.back().color = fmt::format("C{}", i + 2);
    k.plots.back().open = i == 0;  // equal values stay visible: large open, medium, small
  }
  return k;
}

}  // namespace frictal::study
