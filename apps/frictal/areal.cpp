// frictal areal LOWER [UPPER] — the areal signature of two rigid blocks sliding along one
// direction (the upper block turned over onto the lower one; default: LOWER against itself);
// with --lateral/--runaway-distance/--start-offset/--drops, the hold angle of the continuous
// model (the library's predict(): the numbers of `frictal predict`) with the block free to move
// sideways or locked to the direction, from one drop or over drops.
#include "frictal/areal.hpp"
#include "common.hpp"
#include "frictal/analysis.hpp"
#include "frictal/predict.hpp"
#include "frictal/tilt.hpp"
#include "map_hold.hpp"
#include "options.hpp"
#include "surface_io.hpp"

#include <array>
#include <optional>

namespace frictal::cli {
namespace {

struct Args {
  std::string lower, upper, output;
  double angle = 0;                 ///< --direction as typed (deg)
  FieldWords words;                 ///< the areal signature's settings (areal_signature_settings()) as typed
  ArealSignatureSettings settings;  ///< the same, checked (SI)
  std::string detrend = "plane";
  bool in_place = false;
  bool json = false;
  // The hold angle over two dimensions of offset.
  std::string lateral;
  double runaway_distance = 0;
  FieldWords runaway_words;  ///< --runaway-distance (the tilt table's field)
  std::string start_offset;
  int drops = PredictOptions{}.map_drops;
  FieldWords predict_words;  ///< --drops (the prediction's table)
  bool quiet = false;
  unsigned threads = 0;
  InputOptions input;
  ConditioningOptions cond;
  std::string conditioning;  ///< what the conditioning did (set after reading the maps)
};

// The hold angle over drops (or from one drop) of the continuous model, through the library's
// predict(): the numbers of `frictal predict LOWER UPPER --direction ANGLE [--locked]` for the
// same options. The block is free to move sideways (what a tilt test reads) or, with --lateral
// locked, locked to the direction (a diagnostic; the free one is computed beside it, as predict
// --locked does).
int run_hold(const Args& a) {
  require(a.lateral.empty() || a.lateral == "free" || a.lateral == "locked",
          fmt::format("--lateral '{}' not understood (expected free or locked)", a.lateral));
  require(std::isfinite(a.runaway_distance) && a.runaway_distance >= 0,
          fmt::format("--runaway-distance {}: expected a finite number of metres > 0", a.runaway_distance));
  require(a.output.empty(), "-o is not available with the hold angle (--lateral, --runaway-distance, --start-offset)");
  // The grid lift's options have no counterpart in the continuous model: its drops are an N x N
  // grid over the drop range (--drops), its offsets continuous.
  require(a.settings.options.step == 0,
          "--step: the hold angle (--lateral, --runaway-distance, --start-offset, --drops) is the "
          "continuous model's, off any grid of offsets; --step applies to the areal signature only");
  require(a.settings.options.offset_max == 0,
          "--max-offset: the hold angle's drops cover the drop range of `frictal predict` (docs/analysis.md); "
          "--max-offset applies to the areal signature only");
  require(a.settings.options.contact_slope == ArealContactSlope::Lower,
          "--contact-slope mean: the hold angle's rigid upper bound uses the lower face's slope (Eq. 3); "
          "--contact-slope applies to the areal signature only");
  require(a.drops >= 2 && a.drops <= 64, fmt::format("--drops {}: expected 2..64", a.drops));
  const bool locked_mode = a.lateral == "locked";
  PredictOptions o = conditioned_predict_options(a.cond, a.detrend);
  o.direction = a.settings.direction;
  o.atomic_friction = a.settings.atomic_friction;
  o.runaway_distance = a.runaway_distance;
  o.map_drops = a.drops;
  o.map_locked = locked_mode;
  o.turn_over_upper = !a.in_place;
  o.threads = a.threads;
  o.progress = drop_progress("areal", a.quiet);
  if (!a.start_offset.empty()) o.start_offset = parse_offset(a.start_offset, "--start-offset");
  const PredictSurface lower = read_map_surface(a.lower, a.input, "the areal hold angle needs maps");
  std::optional<PredictSurface> upper;
  if (!a.upper.empty()) upper = read_map_surface(a.upper, a.input, "the areal hold angle needs maps");
  const Prediction p = unwrap(predict(lower, upper ? &*upper : nullptr, o));
  const HoldStatistics& chosen = locked_mode ? p.locked_friction_angle : p.friction_angle;
  const std::string model = locked_mode ? "map-continuous-locked" : p.model;
  if (a.json) {
    RunRecord run;
    run.lower = a.lower;
    run.upper = a.upper.empty() ? a.lower : a.upper;
    run.conditioning = p.conditioning;
    run.warnings = p.warnings;
    nlohmann::json j = object_of(areal_hold_columns(), ArealHoldReport{p, locked_mode, a.in_place});
    put_columns(j, run_record_columns(), run);
    print_json(j);
    return 0;
  }
  for (const Warning& w : p.warnings)
    if (w.code != "reader") print_warnings({w});  // the reader's are printed as it reads
  fmt::print("{} on {} along {} deg{}: model {} (the rigid block {}, off the grid, quasi-static)\n",
             a.upper.empty() ? a.lower : a.upper, a.lower, a.angle, a.in_place ? " (upper in place)" : "", model,
             locked_mode ? "locked to the direction: a diagnostic" : "free to move sideways");
  fmt::print("  run-away distance {:.4g} m; atomic friction mu_a = {:g}, atan(mu_a) included in every hold angle\n",
             p.runaway_distance, p.atomic_friction);
  if (p.single_drop) {
    fmt::print("  dropped at ({:.4g}, {:.4g}) m, rests at ({:.4g}, {:.4g}) m\n", p.start_offset[0], p.start_offset[1],
               p.rest_offset[0], p.rest_offset[1]);
    fmt::print("  hold angle {:.4f} deg{}; the free block's run-away steers {:.1f} deg off the direction\n",
               to_deg(chosen.q50),
               locked_mode ? fmt::format(" locked ({:.4f} deg free to move sideways)", to_deg(p.friction_angle.q50))
                           : std::string(),
               to_deg(p.drop_steering.at(0)));
  } else {
    fmt::print(
        "  hold angle over {} drops (u in [{:.4g}, {:.4g}] m along, v in [{:.4g}, {:.4g}] m across): median {:.4f} "
        "deg, 5-95 % {:.4f} - {:.4f} deg, mean {:.4f}, std {:.4f}, min {:.4f}, max {:.4f} deg\n",
        p.drops, p.drop_range[0], p.drop_range[1], p.drop_range[2], p.drop_range[3], to_deg(chosen.q50),
        to_deg(chosen.q05), to_deg(chosen.q95), to_deg(chosen.mean), to_deg(chosen.std), to_deg(chosen.min),
        to_deg(chosen.max));
    if (locked_mode)
      fmt::print("  free to move sideways (what a tilt test reads): median {:.4f} deg, 5-95 % {:.4f} - {:.4f} deg\n",
                 to_deg(p.friction_angle.q50), to_deg(p.friction_angle.q05), to_deg(p.friction_angle.q95));
  }
  fmt::print("  rigid upper bound theta_max + theta_a {:.4f} deg; the same numbers as frictal predict{}\n",
             to_deg(p.upper_bound_friction_angle), locked_mode ? " --locked" : "");
  fmt::print("  conditioning: {}\n", p.conditioning);
  return 0;
}

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  app.add_option("lower", a->lower, "Lower block's map (X3P, Gwyddion text)")->required();
  app.add_option("upper", a->upper, "Upper block's map as measured (default: the lower map)");
  // --direction (also read as --angle, its older name), --atomic-friction, --step, --max-offset,
  // --contact-slope, --in-place: the areal signature's settings table. --direction is read as it
  // always was (CLI11's reading of the degrees: strtold, then double), so that its radians keep
  // every bit (the table's from_chars differs in the last bit on about 1 in 10^4 random angles of 1 to 20
  // digits: 180 of 2 million).
  {
    const Field& f = *find_field(areal_signature_settings(), "direction");
    app.add_option("--direction,--angle", a->angle, field_help(f))->type_name("NUMBER");
  }
  add_field_options(app, areal_signature_settings(), a->words, {"direction"});
  add_detrend_option(app, a->detrend);
  add_conditioning_options(app, a->cond);
  app.add_option("-o,--output", a->output,
                 "Write offset_m,lift_m,theta_rad,contact_x_m,contact_y_m to this CSV (- for standard output)");
  app.add_option("--threads", a->threads, "Worker threads (0 = all cores)");
  app.add_option("--lateral", a->lateral,
                 "Hold angle over drops of the continuous model (the numbers of `frictal predict --direction`): the "
                 "block free to move sideways (free) or locked to the direction (locked, a diagnostic; also computes "
                 "the free one)");
  // --runaway-distance: the tilt table's field (one description everywhere), here the hold angle's run-away.
  add_field_options(app, tilt_settings(), a->runaway_words, all_but(tilt_settings(), "runaway_distance"));
  app.add_option("--start-offset", a->start_offset,
                 "Hold angle from one drop at offset X,Y (m; from the maps' centres aligned, or with --in-place "
                 "from the upper map's place) instead of the distribution over drops");
  // --drops (given: the hold angle over drops): the prediction's table.
  add_predict_options(app, a->predict_words, {"drops"});
  app.add_flag("-q,--quiet", a->quiet, "No progress line on standard error (hold angle)");
  app.add_flag("--json", a->json, "Print one JSON object");
  add_input_options(app, a->input);
  return [a]() {
    if (const ValueSet rv = si_values(tilt_settings(), a->runaway_words); rv.count("runaway_distance"))
      a->runaway_distance = as_real(rv.at("runaway_distance"));
    {
      // The degrees as typed, through the table's conversion and check (deg -> rad: the one
      // from_text_unit, the same product as deg * kDeg).
      const Field& f = *find_field(areal_signature_settings(), "direction");
      ValueSet v = si_values(areal_signature_settings(), a->words);
      v.insert_or_assign("direction", unwrap(si_from_text(f, FieldValue{a->angle}, shown_option_name(f))));
      a->settings = unwrap(make_areal_signature_settings(v));
    }
    a->drops = static_cast<int>(predict_integer(a->predict_words, "drops"));
    a->in_place = !a->settings.options.turn_over_upper;
    if (!a->lateral.empty() || a->runaway_distance != 0 || !a->start_offset.empty() ||
        a->predict_words.words.count("drops"))
      return run_hold(*a);
    const Conditioning cond = conditioning(a->cond, unwrap(parse_detrend(a->detrend)));
    std::vector<Warning> warnings;
    std::vector<ConditioningRecord> records;
    auto load = [&](const std::string& path) {
      return load_conditioned_map(path, a->input, cond, "the areal signature needs maps", &warnings, &records);
    };
    const Map f = load(a->lower);
    const Map g = a->upper.empty() ? f : load(a->upper);
    a->conditioning = conditioning_text(records);
    ArealSignatureOptions o = a->settings.options;
    o.threads = a->threads;
    const ArealSignature r = unwrap(areal_signature(f, g, a->settings.direction, o));
    const FrictionPrediction p =
        unwrap(predict_friction(a->settings.atomic_friction, r.theta_max_forward, r.contact_slope_std));
    add_bound_warnings(warnings, p, "areal");
    if (!a->output.empty()) {
      std::string buf = "offset_m,lift_m,theta_rad,contact_x_m,contact_y_m\n";
      for (std::size_t k = 0; k < r.offset.size(); ++k)
        buf += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", r.offset[k], r.lift[k], r.theta[k],
                           r.contact_x[k], r.contact_y[k]);
      write_text_output(a->output, buf);
    }
    require(!(a->json && a->output == "-"), "--json and -o - would both write to standard output; choose one");
    if (a->json) {
      RunRecord run;
      run.lower = a->lower;
      run.upper = a->upper.empty() ? a->lower : a->upper;
      run.conditioning = a->conditioning;
      run.warnings = warnings;
      nlohmann::json j = object_of(areal_signature_columns(), r);
      put_columns(j, areal_bound_columns(), p);  // the grid's theta_max + theta_a, not a bound of a tilt test
      put_columns(j, run_record_columns(), run);
      print_json(j);
    } else {
      fmt::print(
          a->output == "-" ? stderr : stdout,
          "{} on {} along {} deg: {} offsets of the grid areal signature (a diagnostic of the map's nodes, slopes by "
          "central differences)\n  theta_max forward {:.4f} deg, backward {:.4f} deg, sigma {:.4f} deg\n"
          "  the grid's theta_max + theta_a {:.4f} deg, mu {:.5f} (Eq. 18 low {:.5f}): not a bound of the tilt "
          "test's hold angle; what a tilt test reads, and its bound: frictal predict (or areal --lateral)\n"
          "  conditioning: {}\n",
          a->upper.empty() ? a->lower : a->upper, a->lower, a->angle, r.offset.size(), to_deg(r.theta_max_forward),
          to_deg(r.theta_max_backward), to_deg(r.contact_slope_std), to_deg(p.friction_angle), p.friction_coefficient,
          p.friction_coefficient_low, a->conditioning);
      for (const Warning& w : warnings)
        if (w.code != "reader") print_warnings({w});  // the reader's are printed as it reads
    }
    return 0;
  };
}

FRICTAL_COMMAND({"areal", "Areal signature of two rigid blocks (maps) sliding along a direction", setup, 75});

}  // namespace
}  // namespace frictal::cli
