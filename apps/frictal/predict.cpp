// frictal predict LOWER [UPPER] — the one answer: what a tilt test of these surfaces reads (the
// distribution over drops of the quasi-static hold angle, its median the headline), beside the
// rigid upper bound theta_max + theta_a (Eq. 6) and the paper's Eq. 18 range. The prediction is
// the library's (frictal/predict.hpp); this file reads the inputs and prints it.
#include <algorithm>
#include <cmath>

#include "common.hpp"
#include "frictal/predict.hpp"
#include "frictal/tilt.hpp"
#include "map_hold.hpp"
#include "options.hpp"
#include "surface_io.hpp"

namespace frictal::cli {
namespace {

struct Args {
  std::string lower, upper, detrend, start;
  unsigned threads = 0;
  bool json = false;
  bool quiet = false;
  InputOptions input;
  ConditioningOptions cond;
  FieldWords words;  ///< the prediction's settings (predict_settings()) as typed
  LoadWords load;    ///< friction under load: --load, --modulus, --poisson, --upper-* (lists, units: by hand)
  bool in_place() const { return words.words.count("in_place") && words.words.at("in_place") == "true"; }
};

PredictSurface read_input(const std::string& path, const InputOptions& o) {
  return unwrap(predict_surface(unwrap(read_surface(input_path(path), read_options(o))), path));
}

std::string deg_text(double rad) { return fmt::format("{:.4g}", to_deg(rad)); }
std::string mu_text(double rad) { return rad >= std::numbers::pi / 2 ? "inf" : fmt::format("{:.4g}", std::tan(rad)); }

void print_text(const Prediction& p, const Args& a) {
  for (const Warning& w : p.warnings) fmt::print(stderr, "frictal: warning [{}]: {}\n", w.code, w.message);
  const std::string pair = a.upper.empty()
                               ? fmt::format("{} against itself {}", a.lower, a.in_place() ? "in place" : "turned over")
                               : fmt::format("{} on {}{}", a.upper, a.lower, a.in_place() ? " in place" : "");
  if (p.trust != "ok") {
    std::string codes;
    for (const std::string& c : p.trust_codes) codes += (codes.empty() ? "" : ", ") + c;
    fmt::print(
        "DOUBTFUL ({}): the input was probably read wrong, or the model does not hold for it; the number below "
        "is not these surfaces' friction until it is fixed: {}\n",
        codes, p.trust_fix.empty() ? "see the warnings" : "add " + p.trust_fix);
  }
  fmt::print("frictal predict: {}, sliding at {:g} deg, mu_a = {:g}\n", pair, to_deg(p.direction), p.atomic_friction);
  if (p.single_drop) {
    fmt::print("  a tilt test from this drop reads phi = {} deg (mu = {}); it rests at {}\n",
               deg_text(p.friction_angle.q50), mu_text(p.friction_angle.q50),
               p.is_map ? fmt::format("({:.6g}, {:.6g}) m", p.rest_offset[0], p.rest_offset[1])
                        : fmt::format("{:.6g} m", p.rest_offset[0]));
  } else {
    fmt::print(
        "  a tilt test of these surfaces{} reads phi = {} deg (mu = {}), the median over drops; 90 % of tests "
        "between {} and {} deg (mu {} - {})\n",
        std::isfinite(p.load) ? fmt::format(" under W = {:g} N", p.load) : std::string(),
        deg_text(p.friction_angle.q50), mu_text(p.friction_angle.q50), deg_text(p.friction_angle.q05),
        deg_text(p.friction_angle.q95), mu_text(p.friction_angle.q05), mu_text(p.friction_angle.q95));
    fmt::print("  over drops: mean {} deg, std {} deg, range [{}, {}] deg\n", deg_text(p.friction_angle.mean),
               deg_text(p.friction_angle.std), deg_text(p.friction_angle.min), deg_text(p.friction_angle.max));
  }
  fmt::print("  rigid upper bound {} = {} deg (mu = {}); the paper's Eq. 18 range [{}, {}] deg\n",
             p.is_map ? "(the steepest seat the drops rested in, friction cones included)" : "theta_max + theta_a",
             deg_text(p.upper_bound_friction_angle), mu_text(p.upper_bound_friction_angle), deg_text(p.eq18_range[0]),
             deg_text(p.eq18_range[1]));
  if (p.has_locked && !p.single_drop)
    fmt::print("  diagnostic: the block locked to the direction reads {} deg (5-95 %: {} - {} deg)\n",
               deg_text(p.locked_friction_angle.q50), deg_text(p.locked_friction_angle.q05),
               deg_text(p.locked_friction_angle.q95));
  else if (p.has_locked)
    fmt::print("  diagnostic: the block locked to the direction reads {} deg\n", deg_text(p.locked_friction_angle.q50));
  const std::string range = p.is_map ? fmt::format("u in [{:.4g}, {:.4g}] m along, v in [{:.4g}, {:.4g}] m across",
                                                   p.drop_range[0], p.drop_range[1], p.drop_range[2], p.drop_range[3])
                                     : fmt::format("[{:.6g}, {:.6g}] m", p.drop_range[0], p.drop_range[1]);
  fmt::print("  model: {} ({}); {} {} over {}; run-away d = {:.4g} m\n  conditioning: {}\n", p.model,
             p.is_map ? (std::isfinite(p.load) ? "block locked to the direction, quasi-static hold angle on the loaded "
                                                 "lift of the elastic half-space"
                                               : "rigid block free to move sideways, off the grid, quasi-static")
                      : (std::isfinite(p.load) ? "quasi-static hold angle on the loaded lift of Hertzian asperities"
                                               : "rigid quasi-static hold angle on the exact lift"),
             p.drops, p.is_map ? "drops" : "basins", range, p.runaway_distance, p.conditioning);
  if (!p.is_map)
    fmt::print("  the test: a block of {:.4g} m, sliding for good after d = {:.4g} m ({})\n", p.block_length,
               p.runaway_distance, p.test_lengths);
  if (std::isfinite(p.load) && p.is_map) {
    fmt::print(
        "  under load: W = {:.4g} N (normal force {:.4g} N at the rigid median {} deg), E* = {:.4g} Pa; the rigid "
        "prediction (free block) reads {} deg, the loaded model at zero load (block locked to d) {} deg\n  the "
        "half-space: {:.3g} contact patches per offset, approach {:.3g} m, largest contact fraction {:.3g}, rms "
        "contact slope {:.3g}\n",
        p.load, p.normal_load, deg_text(p.rigid_friction_angle), p.contact_modulus, deg_text(p.rigid_friction_angle),
        deg_text(p.load_zero_limit), p.load_contacts, p.load_approach, p.load_contact_fraction, p.load_contact_slope);
  } else if (std::isfinite(p.load)) {
    fmt::print(
        "  under load: W = {:.4g} N (normal force {:.4g} N at the rigid median {} deg), E* = {:.4g} Pa; the rigid "
        "prediction reads {} deg\n  the asperities: {:.3g} contacts per offset, approach {:.3g} m, largest "
        "delta/R {:.3g}, {:.3g} % of the load on merged contacts, rms contact slope {:.3g}\n",
        p.load, p.normal_load, deg_text(p.rigid_friction_angle), p.contact_modulus, deg_text(p.rigid_friction_angle),
        p.load_contacts, p.load_approach, p.load_interference_ratio, 100 * p.load_merged_share, p.load_contact_slope);
  }
  if (std::isfinite(p.load)) {
    fmt::print("  friction angle against load (same drops, d):\n    {:>12}  {:>10}  {:>17}\n", "load (N)",
               "median (deg)", "5-95 % (deg)");
    for (std::size_t i = 0; i < p.load_curve.size(); ++i)
      fmt::print("    {:>12.4g}  {:>10}  {:>17}{}\n", p.load_curve[i], deg_text(p.load_curve_q50[i]),
                 fmt::format("{} - {}", deg_text(p.load_curve_q05[i]), deg_text(p.load_curve_q95[i])),
                 p.load_curve[i] == p.load ? "  <- W" : "");
  }
  if (!p.d_sweep_distance.empty() && !p.single_drop) {
    fmt::print("  how the answer depends on d (same drops):\n    {:>12}  {:>10}  {:>17}\n", "d (m)", "median (deg)",
               "5-95 % (deg)");
    for (std::size_t i = 0; i < p.d_sweep_distance.size(); ++i)
      fmt::print("    {:>12.4g}  {:>10}  {:>17}{}\n", p.d_sweep_distance[i], deg_text(p.d_sweep_q50[i]),
                 fmt::format("{} - {}", deg_text(p.d_sweep_q05[i]), deg_text(p.d_sweep_q95[i])),
                 p.d_sweep_distance[i] == p.runaway_distance ? "  <- d" : "");
  }
  if (!p.warnings.empty())
    fmt::print("  {} warning(s) on standard error: {}\n", p.warnings.size(), [&] {
      std::string s;
      for (const Warning& w : p.warnings) s += (s.empty() ? "" : ", ") + w.code;
      return s;
    }());
}

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  app.add_option("lower", a->lower,
                 "Lower surface: a line profile or an areal map (any readable format); - reads "
                 "standard input")
      ->required();
  app.add_option("upper", a->upper,
                 "Upper surface, as measured (material below): it is turned over to face LOWER. Default: LOWER "
                 "itself. Two profiles or two maps");
  // --direction, --atomic-friction, --runaway-distance, --block-length, --period, --drops, --locked,
  // --in-place, --sphere-radius, --map-work-limit: the prediction's settings table.
  add_field_options(app, predict_settings(), a->words);
  add_detrend_option(app, a->detrend);
  add_conditioning_options(app, a->cond);
  app.add_option("--start-offset", a->start,
                 "One drop at this offset instead of the distribution: X for profiles, X,Y for maps (m)");
  app.add_flag("-q,--quiet", a->quiet, "No progress line on standard error");
  app.add_option("--threads", a->threads, "Worker threads (0 = all cores); results do not depend on it")
      ->capture_default_str();
  add_input_options(app, a->input);
  add_load_options(app, a->load);
  app.add_flag("--json", a->json, "Print the prediction as one JSON object (the keys of `frictal columns`)");
  return [a]() {
    PredictOptions o = conditioned_predict_options(a->cond, a->detrend);
    o = unwrap(make_predict_options(si_values(predict_settings(), a->words), std::move(o)));
    o.progress = drop_progress("predict", a->quiet);
    o.threads = a->threads;
    apply_load_options(a->load, o);
    PredictSurface lower = read_input(a->lower, a->input);
    std::optional<PredictSurface> upper;
    if (!a->upper.empty()) upper = read_input(a->upper, a->input);
    if (!a->start.empty()) {
      if (lower.is_map) {
        o.start_offset = parse_offset(a->start, "--start-offset");
      } else {
        char* end = nullptr;
        const double x = std::strtod(a->start.c_str(), &end);
        require(end && *end == '\0' && std::isfinite(x),
                fmt::format("--start-offset '{}': expected one offset X in m for profiles", a->start));
        o.start_offset = {x, 0};
      }
    }
    // The surfaces handed over (no copies of a profile's points).
    const Prediction p = unwrap(predict(std::move(lower), std::move(upper), o));
    if (a->json) {
      fmt::print("{}\n",
                 prediction_json(p, fmt::format("\"lower\": {}, \"upper\": {}", nlohmann::json(a->lower).dump(),
                                                nlohmann::json(a->upper.empty() ? a->lower : a->upper).dump())));
    } else {
      print_text(p, *a);
    }
    return 0;
  };
}

FRICTAL_COMMAND({"predict",
                 "The prediction: what a tilt test of two surfaces reads (median and spread over drops), with the "
                 "rigid upper bound",
                 setup, 5});

}  // namespace
}  // namespace frictal::cli
