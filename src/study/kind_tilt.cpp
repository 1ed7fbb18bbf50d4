// Task kind 'tilt': the spheropolygon tilting-block test (Sec. IV) on a pair of generated
// surfaces (a Koch pair by default), for the studies of Fig. 6, 7 and 8. Parameters: `generator`
// (koch, wm, sawtooth, sine, self-affine or fourier; default koch), that generator's parameters and the
// tilt settings, all named and checked by the library's tables (surface_spec.hpp, tilt.hpp;
// SI units, angles in degrees as in the study files), and record_series (bool: return the
// Fig. 7 series as arrays). A run stopped by the stability guard is retried with a 2.5x smaller
// step (twice at most); time_step_s records it.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include <fmt/core.h>

#include "frictal/signature.hpp"
#include "frictal/study.hpp"
#include "frictal/surface_spec.hpp"
#include "frictal/tilt.hpp"
#include "frictal/units.hpp"
#include "study/kind_common.hpp"
#include "study/table_params.hpp"

namespace frictal::study {
namespace {

// The outputs this kind takes from output tables (frictal columns: declared once there). The tilt
// test's (tilt_columns()):
constexpr std::initializer_list<ColumnOutput> kTiltTableOutputs = {
    "slid",
    "predicted_friction_angle_deg",
    "predicted_theta_max_deg",
    "simulated_time_s",
    "steps",
    "upper_mass_kg",
    "predicted_sphero_friction_angle_deg",
    "predicted_sphero_theta_max_deg",
    "rotation_before_slide_deg",
    "rest_offset_m",
    "predicted_hold_angle_deg",
    "predicted_inertial_hold_angle_deg",
    "predicted_sphero_hold_angle_deg",
    {"steps_beyond_stability_limit", "steps_beyond_limit"}};
// Its scales (tilt_scales_columns()).
constexpr std::initializer_list<ColumnOutput> kScalesOutputs = {
    "resting_overlap_m", {"time_step_s", nullptr, "after the retries with 2.5x smaller steps"}};
// theta_a (friction_columns()).
constexpr std::initializer_list<ColumnOutput> kFrictionOutputs = {"atomic_friction_angle_deg"};

using kind_detail::number;
using kind_detail::run_tilt_retrying;

constexpr double kDeg = units::kRadPerDeg;

Result<bool> get_bool(const Params& p, const std::string& name, bool fallback) {
  auto it = p.find(name);
  if (it == p.end()) return fallback;
  if (const bool* b = std::get_if<bool>(&it->second)) return *b;
  return make_error(fmt::format("parameter '{}': expected true or false, got {}", name, canonical(it->second)));
}

/// Estimated CPU time of a tilt task (unit: s; the scheduler's model, TaskKind::cost):
/// c0(n) + c1(n) T, with T the time to tilt to the expected slide (theta_max + atan(mu_a), n alpha
/// for a Koch pair, at tilt_rate), scaled with the number of wavelengths. Fitted to the 208 tilts
/// of the Fig. 6 and Fig. 8 grids with the adaptive step (2026-11-23): the steps grow as 2e4 + 9.6e3 T for every K_n,
/// but the cost of a step grows steeply with n and the contacts, so that a K3 test costs about 2.2 s whatever alpha
/// (flatter K3 blocks carry more contacts). Other surfaces count as K1 at phi = 30 deg + atan(mu_a).
double tilt_cost(const Params& p) {
  const auto generator = get_string(p, "generator", "koch");
  const bool koch = generator && *generator == "koch";
  const double n = koch ? std::clamp(number(p, "iterations", 0), 0.0, 5.0) : 1.0;
  const double alpha = koch ? number(p, "alpha", 5) : 30.0;  // deg; other surfaces: a typical slope
  const double mu_a = std::max(0.0, number(p, "atomic_friction", 0));
  const double phi = std::min(90.0, std::max(1.0, n) * alpha + std::atan(mu_a) / kDeg) * kDeg;
  const double rate = std::max(1e-6, number(p, "tilt_rate", 0.05));
  const double waves = std::clamp(number(p, "length", 0.2) / std::max(1e-12, number(p, "wavelength", 0.01)), 1.0, 1e6);
  const int k = static_cast<int>(std::lround(n));
  constexpr double c0[] = {0.0, 0.08, 0.05, 2.2}, c1[] = {0.034, 0.021, 0.040, 0.0075};  // s, s per s of T
  const double a = k <= 3 ? c0[k] : 2.2 * std::pow(8.0, k - 3), b = k <= 3 ? c1[k] : 0.0075;
  return (0.01 + a + b * phi / rate) * waves / 20;
}

}  // namespace

Result<TaskOutput> run_tilt_task(const Params& p, std::uint64_t /*seed: deterministic simulation*/) {
  auto generator = get_string(p, "generator", "koch");
  if (!generator) return generator.error();
  const GeneratorInfo* gen = find_generator(*generator);
  if (!gen) return make_error(fmt::format("parameter 'generator': unknown surface generator \"{}\"", *generator));
  if (Status st = kind_detail::no_threads_parameter(p); !st) return st.error();
  if (Status st = only_known_parameters(p, {&gen->fields, &tilt_settings()}, {"generator", "record_series"}, "tilt");
      !st)
    return st.error();
  auto gen_values = table_values(gen->fields, p);
  if (!gen_values) return gen_values.error();
  if (auto it = gen_values->find("iterations"); it != gen_values->end() && std::get<std::int64_t>(it->second) > 5)
    return make_error(fmt::format("parameter 'iterations': expected 0..5, got {}", std::get<std::int64_t>(it->second)));
  auto spec = make_surface_spec(*generator, *gen_values);
  if (!spec) return spec.error();
  auto period = surface_period(*spec);
  auto scale = surface_scale(*spec);
  if (!period) return period.error();
  if (!scale) return scale.error();
  auto settings = table_values(tilt_settings(), p);
  if (!settings) return settings.error();
  auto config = make_tilt_config(*settings, tilt_config_for_surface(*period, *scale));
  if (!config) return config.error();
  TiltConfig c = *config;
  auto series = get_bool(p, "record_series", false);
  if (!series) return series.error();
  if (!*series) c.series_interval = 0;
  auto all = surface_values(*spec);
  if (!all) return all.error();
  // Fig. 7 normalises by the Koch base angle and the block length.
  const double alpha = all->count("alpha") ? as_real(all->at("alpha")) : std::nan("");
  const double length = as_real(all->at("length"));
  auto curve = generate_curve(*spec);
  if (!curve) return curve.error();
  auto r = run_tilt_retrying(*curve, *curve, c);
  if (!r) return r.error();
  TaskOutput out;
  auto& s = out.scalars;
  s["friction_angle_deg"] = r->friction_angle / kDeg;  // 0 without a slide (the tilt table's: null)
  // The quantities the tilt command prints too, from its output tables (frictal/tilt.hpp).
  put_outputs(out, tilt_columns(), TiltReport{*r, c}, kTiltTableOutputs);
  put_outputs(out, tilt_scales_columns(), r->scales, kScalesOutputs);
  auto theta_a = predict_friction(c.contact.atomic_friction, 0, 0);  // theta_a alone
  if (!theta_a) return theta_a.error();
  put_outputs(out, friction_columns(), *theta_a, kFrictionOutputs);
  s["friction_angle_minus_theory_deg"] = (r->friction_angle - r->predicted_friction_angle) / kDeg;
  s["phi_minus_theta_max_deg"] = (r->friction_angle - r->predicted_theta_max) / kDeg;
  s["friction_coefficient"] = std::tan(r->friction_angle);
  s["friction_angle_minus_sphero_deg"] = (r->friction_angle - r->predicted_sphero_friction_angle) / kDeg;
  // What the test reads from where the block rests (hold.hpp), rigid and rounded blocks.
  s["friction_angle_minus_sphero_hold_deg"] = (r->friction_angle - r->predicted_sphero_hold_angle) / kDeg;
  kind_detail::put_tilt_warnings(s, *r);
  if (*series) {
    // Fig. 7: atan(F_t/F_n)/alpha against the relative displacement / L_b.
    const auto& ts = r->series;
    std::vector<double> d, a, t, tilt;
    for (std::size_t i = 0; i < ts.time.size(); ++i) {
      d.push_back(ts.displacement[i] / length);
      a.push_back(ts.force_angle[i] / alpha);
      t.push_back(ts.time[i]);
      tilt.push_back(ts.tilt[i] / kDeg);
    }
    out.arrays["displacement_over_length"] = std::move(d);
    out.arrays["force_angle_over_alpha"] = std::move(a);
    out.arrays["time_s"] = std::move(t);
    out.arrays["tilt_deg"] = std::move(tilt);
  }
  return out;
}

// ---------------------------------------------------------------- report section and the kind

namespace {

void tilt_part(const std::string& part, const std::vector<Store::Row>& rows, Report& rep) {
  if (rows.empty()) return;
  rep.lines.push_back(fmt::format("\n## Part '{}' (tilt): {} simulations", part, rows.size()));
  std::string t =
      "\n| K_n | alpha (deg) | mu_a | phi simulated (deg) | phi theory (deg) | sim - theory (deg) | "
      "phi - theta_max (deg) | theta_a (deg) | phi theory, spheropolygons (deg) | sim - sphero (deg) | "
      "rotation before slide (deg) | warnings |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  double worst = 0, worst_a = 0, worst_s = 0;
  int slid = 0, n = 0, n_s = 0, within_s = 0;
  std::vector<std::string> outside;
  std::set<double> mus;
  for (const auto& r : rows) {
    const auto& s = r.output.scalars;
    if (!s.count("friction_angle_deg") || !s.count("predicted_friction_angle_deg")) continue;
    const double ma = r.params.count("atomic_friction") ? as_number(r.params.at("atomic_friction")) : 0.0;
    mus.insert(ma);
    ++n;
    slid += s.at("slid") > 0;
    const double d = s.at("friction_angle_minus_theory_deg");
    const double da = s.at("phi_minus_theta_max_deg") - s.at("atomic_friction_angle_deg");
    worst = std::max(worst, std::abs(d));
    worst_a = std::max(worst_a, std::abs(da));
    t += fmt::format("| K{} | {:g} | {:g} | {:.3f} | {:.3f} | {:+.3f} | {:.3f} | {:.3f} |",
                     as_int(r.params.at("iterations")), as_number(r.params.at("alpha")), ma, s.at("friction_angle_deg"),
                     s.at("predicted_friction_angle_deg"), d, s.at("phi_minus_theta_max_deg"),
                     s.at("atomic_friction_angle_deg"));
    if (s.count("predicted_sphero_friction_angle_deg")) {  // kind version >= 2
      std::string warn;
      for (const char* code :
           {"core_overlap", "rounding", "time_step", "unsettled", "rotation", "creep", "unrelaxed", "stiffness"})
        if (auto it = s.find(std::string("warning_") + code); it != s.end() && it->second > 0)
          warn += (warn.empty() ? "" : ", ") + std::string(code);
      auto get = [&](const char* key) { return s.count(key) ? s.at(key) : std::nan(""); };  // robust to old rows
      const double ds = get("friction_angle_minus_sphero_deg");
      ++n_s;
      worst_s = std::max(worst_s, std::abs(ds));
      if (!(std::abs(ds) > 0.1))  // NaN (missing) counts as within: nothing to flag
        ++within_s;
      else
        outside.push_back(fmt::format("K{} at {:g} deg ({:+.3f} deg{})", as_int(r.params.at("iterations")),
                                      as_number(r.params.at("alpha")), ds,
                                      warn.empty() ? ", no warning" : "; warnings: " + warn));
      t += fmt::format(" {:.3f} | {:+.3f} | {:.4f} | {} |\n", get("predicted_sphero_friction_angle_deg"), ds,
                       get("rotation_before_slide_deg"), warn.empty() ? "-" : warn);
    } else {
      t += " | | | |\n";
    }
  }
  rep.lines.push_back(t);
  if (!n) return;
  Finding f;
  f.claim_id = "eq6-simulation";
  f.part = part;
  f.claim = fmt::format(
      "Part '{}': the simulated friction angle equals the signature prediction theta_max + atan(mu_a) "
      "(Fig. 6, 8).",
      part);
  f.supported = slid == n && worst <= 1.0;
  f.evidence.push_back(
      fmt::format("criterion: every block slid ({} of {}) and |phi_sim - phi_theory| <= 1 deg; largest {:.3f} deg",
                  slid, n, worst));
  // The runs outside, each with what explains it: the rounded blocks' signature (spheroradius),
  // the hold angle from where the block rests (a steeper contact beyond the run-away distance,
  // e.g. the wall at the block's end), and the model warnings.
  int hold_n = 0, hold_within = 0, hold_flagged = 0;
  // Runs outside the rigid finding, and what explains them: the rounded blocks' theta_max (the
  // spheroradius rounds the steepest contact), the hold angle from the rest (a test reads where
  // the block lets go), a model warning.
  int out_n = 0, out_sphero = 0, out_hold = 0, out_flagged = 0;
  std::set<std::string> out_codes;
  double hold_worst = 0;
  std::vector<std::string> hold_outside;
  for (const auto& r : rows) {
    const auto& s = r.output.scalars;
    auto get = [&](const char* key) { return s.count(key) ? s.at(key) : std::nan(""); };
    std::string warn;
    for (const char* code :
         {"core_overlap", "rounding", "time_step", "unsettled", "rotation", "creep", "unrelaxed", "stiffness"})
      if (auto it = s.find(std::string("warning_") + code); it != s.end() && it->second > 0)
        warn += (warn.empty() ? "" : ", ") + std::string(code);
    const std::string name =
        fmt::format("K{} at {:g} deg, mu_a {:g}", as_int(r.params.at("iterations")), as_number(r.params.at("alpha")),
                    r.params.count("atomic_friction") ? as_number(r.params.at("atomic_friction")) : 0.0);
    const double dh = get("friction_angle_minus_sphero_hold_deg");
    if (std::isfinite(dh)) {
      ++hold_n;
      hold_worst = std::max(hold_worst, std::abs(dh));
      if (std::abs(dh) <= 0.1)
        ++hold_within;
      else {
        hold_flagged += !warn.empty();
        hold_outside.push_back(fmt::format("{}: sim - phi_qs(rounded) = {:+.3f} deg{}", name, dh,
                                           warn.empty() ? ", no warning" : "; warnings: " + warn));
      }
    }
    if (!s.count("friction_angle_minus_theory_deg") || std::abs(s.at("friction_angle_minus_theory_deg")) <= 1.0)
      continue;
    ++out_n;
    if (std::abs(get("friction_angle_minus_sphero_deg")) <= 0.1) {
      ++out_sphero;
    } else if (std::abs(dh) <= 0.1) {
      ++out_hold;
    } else if (!warn.empty()) {
      ++out_flagged;
      out_codes.insert(warn);
    }
    f.evidence.push_back(fmt::format(
        "outside: {}: sim {:.3f}, theta_max + theta_a {:.3f}, rounded blocks' theta_max + theta_a {:.3f}, hold angle "
        "from the rest at {:.4g} m (d = the run-away): rigid {:.3f}, rounded {:.3f} deg{}",
        name, get("friction_angle_deg"), get("predicted_friction_angle_deg"),
        get("predicted_sphero_friction_angle_deg"), get("rest_offset_m"), get("predicted_hold_angle_deg"),
        get("predicted_sphero_hold_angle_deg"), warn.empty() ? "" : "; warnings: " + warn));
  }
  if (!f.supported && slid == n && out_n > 0 && out_sphero + out_hold + out_flagged == out_n) {
    std::string codes;
    for (const auto& c : out_codes) codes += (codes.empty() ? "" : "; ") + c;
    std::vector<std::string> why;
    if (out_sphero)
      why.push_back(fmt::format(
          "{} read theta_max of the rounded blocks (within 0.1 deg): the spheroradius rounds the steepest contact",
          out_sphero));
    if (out_hold)
      why.push_back(fmt::format(
          "{} read the hold angle of the rounded blocks from where the block rests (within 0.1 deg), which differs "
          "from theta_max: the theory's steepest contact over all offsets is not where a block resting at one "
          "offset lets go (e.g. a wall beyond the run-away distance)",
          out_hold));
    if (out_flagged) why.push_back(fmt::format("{} are flagged by a model warning ({})", out_flagged, codes));
    std::string list;
    for (const auto& w : why) list += (list.empty() ? "" : "; ") + w;
    f.cause = fmt::format("each of the {} runs outside is explained: {}", out_n, list);
  }
  rep.findings.push_back(f);
  if (hold_n > 0) {
    Finding h;
    h.claim_id = "tilt-hold-angle";
    h.part = part;
    h.claim = fmt::format(
        "Part '{}': the simulated friction angle equals the hold angle of the rounded blocks from where the block "
        "rests (hold.hpp: the quasi-static process on the lift with the spheroradius, run-away as in the run) "
        "within 0.1 deg, or the run is flagged by a model warning.",
        part);
    h.supported = slid == n && hold_flagged == static_cast<int>(hold_outside.size());
    h.evidence.push_back(fmt::format("{} of {} runs within 0.1 deg of phi_qs (rounded blocks); largest {:.3f} deg",
                                     hold_within, hold_n, hold_worst));
    for (const auto& o : hold_outside) h.evidence.push_back("outside: " + o);
    rep.findings.push_back(h);
  }
  if (n_s > 0) {
    Finding h;
    h.claim_id = "tilt-sphero-prediction";
    h.part = part;
    h.claim = fmt::format(
        "Part '{}': the simulated friction angle equals the spheropolygon prediction (the signature of the rounded "
        "blocks, spheroradius r) within 0.1 deg, or the run is flagged by a model warning.",
        part);
    std::size_t unflagged = 0;
    for (const auto& o : outside) unflagged += o.find("no warning") != std::string::npos;
    h.supported = slid == n && unflagged == 0;
    h.evidence.push_back(fmt::format("{} of {} runs within 0.1 deg of the spheropolygon prediction; largest {:.3f} deg",
                                     within_s, n_s, worst_s));
    for (const auto& o : outside) h.evidence.push_back("outside: " + o);
    rep.findings.push_back(h);
  }
  if (mus.size() > 1) {
    Finding g;
    g.claim_id = "eq6-atomic-friction";
    g.part = part;
    g.claim =
        fmt::format("Part '{}': phi - theta_max = theta_a in simulation, the same for every surface (Fig. 8b).", part);
    g.supported = slid == n && worst_a <= 1.0;
    g.evidence.push_back(fmt::format(
        "criterion: |phi_sim - theta_max - atan(mu_a)| <= 1 deg over {} runs; largest {:.3f} deg", n, worst_a));
    rep.findings.push_back(g);
  }
}

}  // namespace

TaskKind tilt_kind() {
  TaskKind k;
  k.name = "tilt";
  k.description = "Spheropolygon tilting-block test of a Koch pair (Sec. IV): friction angle, Fig. 7 series";
  k.version = 7;  // 2: spheropolygon prediction, rotation and model warnings; 3: unsettled, creep; 4: hold angle; 5:
                  // contact rule; 6: closest counts concave corners by inclusion-exclusion; 7: rest test on the
                  // force averaged over relax_duration
  k.run = run_tilt_task;
  k.cost = tilt_cost;
  k.uses_seed = false;  // a deterministic simulation: shared by every study with the same parameters
  k.outputs = {
      {"friction_angle_deg", "deg", "simulated friction angle (tilt at the slide)"},
      {"friction_angle_minus_theory_deg", "deg", "simulated minus predicted friction angle"},
      {"phi_minus_theta_max_deg", "deg", "simulated friction angle minus theta_max"},
      {"friction_coefficient", "1", "tan of the simulated friction angle"},
      {"friction_angle_minus_sphero_hold_deg", "deg", "simulated minus the rounded blocks' phi_qs"},
      {"friction_angle_minus_sphero_deg", "deg", "simulated minus spheropolygon prediction"},
  };
  for (const auto& table : {outputs_of("tilt", tilt_columns(), kTiltTableOutputs),
                            outputs_of("tilt_scales", tilt_scales_columns(), kScalesOutputs),
                            outputs_of("friction", friction_columns(), kFrictionOutputs)})
    k.outputs.insert(k.outputs.end(), table.begin(), table.end());
  const std::vector<OutputColumn> warning_columns = kind_detail::tilt_warning_columns();
  k.outputs.insert(k.outputs.end(), warning_columns.begin(), warning_columns.end());
  k.outputs.insert(k.outputs.end(),
                   {
                       {"displacement_over_length", "1", "relative displacement / L_b (record_series, Fig. 7)", true},
                       {"force_angle_over_alpha", "1", "atan(F_t/F_n) / alpha (record_series, Fig. 7)", true},
                       {"time_s", "s", "time of each series sample", true},
                       {"tilt_deg", "deg", "tilt of each series sample", true},
                   });
  k.report = tilt_part;
  PlotView v;
  v.id = "friction-vs-alpha";
  v.x = {"alpha", "α (deg)"};
  v.y = {"friction_angle_deg", "friction angle φ (deg)"};
  v.series = "iterations";
  v.label = "K{iterations} simulation";
  v.marker = "o";
  v.open = true;
  v.line = false;
  k.plots.push_back(v);
  v = {};
  v.id = "friction-vs-atomic-friction";
  v.x = {"atomic_friction_angle_deg", "θ_a (deg)"};
  v.y = {"friction_angle_deg", "φ (deg)"};
  v.label = "simulation";
  v.marker = "o";
  v.open = true;
  v.line = false;
  v.color = "k";
  k.plots.push_back(v);
  v = {};
  v.id = "friction-excess-vs-atomic-friction";
  v.x = {"atomic_friction_angle_deg", "θ_a (deg)"};
  v.y = {"phi_minus_theta_max_deg", "φ - θ_max (deg)"};
  v.label = "simulation";
  v.marker = "o";
  v.open = true;
  v.line = false;
  v.reference = "identity";
  v.reference_label = "φ - θ_max = θ_a";
  k.plots.push_back(v);
  v = {};
  v.id = "mu-vs-dimension";
  v.x = {"dimension_eq13", "fractal dimension D (Eq. 13)"};
  v.y = {"friction_coefficient", "μ"};
  v.series = "iterations";
  v.label = "K{iterations} simulation";
  v.marker = "o";
  v.open = true;
  v.line = false;
  v.match = {"alpha"};  // D of Eq. 13 depends on alpha only: from a theory task
  k.plots.push_back(v);
  v = {};
  v.id = "force-angle-series";
  v.x = {"displacement_over_length", "relative displacement / L_b"};
  v.y = {"force_angle_over_alpha", "atan(F_t/F_n) / α"};
  v.y.min = -4;  // bounces (F_n near 0) send the ratio far off; the paper's range
  v.y.max = 4;
  v.series = "task";
  v.label = "K{iterations}";
  v.line_width = 0.8;
  k.plots.push_back(v);
  return k;
}

}  // namespace frictal::study
