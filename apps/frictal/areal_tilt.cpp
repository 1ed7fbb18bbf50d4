// frictal areal-tilt LOWER [UPPER] — the 3D tilt test of two areal blocks on MuJoCo
// (experimental, docs/mujoco.md), beside the prediction from the rest offset that the simulation
// reached: frictal predict's map model (areal_tilt_hold), the block free, and locked as a diagnostic.
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>

#include "common.hpp"
#include "frictal/analysis.hpp"
#include "frictal/areal_tilt.hpp"
#include "frictal/predict.hpp"
#include "frictal/tilt.hpp"
#include "map_hold.hpp"
#include "options.hpp"
#include "surface_io.hpp"

namespace frictal::cli {
namespace {

struct Args {
  std::string lower, upper;
  std::string detrend = "plane";
  FieldWords predict_words;  ///< --in-place (the prediction's table)
  bool predict_only = false;
  std::string start_offset;
  FieldWords words;  ///< the model's and protocol's settings (areal_tilt_settings(); docs/settings.md)
  bool json = false;
  bool quiet = false;
  InputOptions input;
  ConditioningOptions cond;
};

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  app.add_option("lower", a->lower, "Lower block's map (X3P, Gwyddion text)")->required();
  app.add_option("upper", a->upper, "Upper block's map as measured (default: the lower map)");
  add_field_options(app, areal_tilt_settings(), a->words);
  add_detrend_option(app, a->detrend);
  add_conditioning_options(app, a->cond);
  app.add_option("--start-offset", a->start_offset,
                 "X,Y: where the block is put down, in the lower map's frame (m; default 0,0)");
  app.add_flag("--predict-only", a->predict_only,
               "Only the predictions, from the block dropped at offset 0 (no simulation; needs no MuJoCo)");
  add_predict_options(app, a->predict_words, {"in_place"});  // the prediction's --in-place
  app.add_flag("--json", a->json, "Print one JSON object");
  app.add_flag("-q,--quiet", a->quiet, "No progress line on standard error (shown on a terminal only)");
  add_input_options(app, a->input);
  return [a]() {
    auto made = make_areal_tilt_options(si_values(areal_tilt_settings(), a->words));
    if (!made) fail(made.error());
    ArealTiltOptions o = *made;
    if (!mujoco_available() && !a->predict_only) unwrap(areal_tilt(Map{}, Map{}, {}));  // says what it needs (exit 2)
    const Conditioning cond = conditioning(a->cond, unwrap(parse_detrend(a->detrend)));
    std::vector<ConditioningRecord> records;
    auto load = [&](const std::string& path) {
      return load_conditioned_map(path, a->input, cond, "areal-tilt needs maps", nullptr, &records);
    };
    const Map f = load(a->lower);
    const Map g = a->upper.empty() ? f : load(a->upper);
    const std::string conditioning_done = conditioning_text(records);
    if (!a->start_offset.empty()) o.start_offset = parse_offset(a->start_offset, "--start-offset");
    o.turn_over_upper = !predict_flag(a->predict_words, "in_place");
    const double angle_deg = to_deg(o.angle), tilt_step_deg = to_deg(o.tilt_step);
    const auto t0 = std::chrono::steady_clock::now();
    // A progress line (a terminal only): the simulation takes minutes on large maps.
    ArealTiltProgress progress;
    if (!a->quiet && !a->predict_only && ::isatty(2))
      progress = [&](const ArealTiltIncrement& i) {
        const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        fmt::print(stderr, "\rfrictal areal-tilt: tilt {:.2f} deg, block at ({:.4g}, {:.4g}) m, {} ({:.0f} s)   ",
                   to_deg(i.tilt), i.x, i.y, i.rested ? "at rest" : "moving", secs);
        std::fflush(stderr);
      };
    // The run, and the prediction from the rest offset it reached (areal_tilt_matched).
    const ArealTiltMatched m = unwrap(areal_tilt_matched(f, g, o, !a->predict_only, progress));
    if (progress) fmt::print(stderr, "\n");
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const ArealTiltResult& r = m.run;
    const ArealTiltHoldSpread& spread = m.spread;
    for (const auto& w : r.warnings)
      if (!a->json) fmt::print(stderr, "frictal: warning [{}]: {}\n", w.code, w.message);
    if (a->json) {
      RunRecord run;
      run.lower = a->lower;
      run.upper = a->upper.empty() ? a->lower : a->upper;
      run.conditioning = conditioning_done;
      run.warnings = r.warnings;
      nlohmann::json j =
          object_of(areal_tilt_report_columns(), ArealTiltReport{m, o.angle, o.tilt_step, o.exact_contacts, secs});
      put_columns(j, run_record_columns(), run);
      print_json(j);
    } else {
      if (a->predict_only)
        fmt::print("{} on {} along {} deg, dropped at offset 0 (no simulation)\n",
                   a->upper.empty() ? a->lower : a->upper, a->lower, angle_deg);
      else
        fmt::print(
            "{} on {} along {} deg (MuJoCo, {} spheres): rests at ({:.4g}, {:.4g}) m, runs away at {:.2f} deg "
            "(steps of {} deg)\n",
            a->upper.empty() ? a->lower : a->upper, a->lower, angle_deg, r.spheres, r.rest_offset[0], r.rest_offset[1],
            to_deg(r.friction_angle), tilt_step_deg);
      fmt::print(
          "  predicted hold angle (frictal predict's model, from there) {:.3f} deg, the block free to move "
          "sideways; {:.3f} deg locked to the direction (a diagnostic)\n",
          to_deg(m.free.hold_angle), to_deg(m.locked.hold_angle));
      fmt::print(
          "  {}: {:.3f} to {:.3f} deg when one slip's end moves by a sphere radius ({} of {} slips could end in "
          "another seat)\n",
          o.lock_lateral ? "locked" : "free", to_deg(spread.low), to_deg(spread.high), spread.ambiguous, spread.slips);
      fmt::print("  conditioning: {}\n", conditioning_done);
    }
    return 0;
  };
}

FRICTAL_COMMAND({"areal-tilt", "3D tilt test of two areal blocks on MuJoCo (experimental)", setup, 76});

}  // namespace
}  // namespace frictal::cli
