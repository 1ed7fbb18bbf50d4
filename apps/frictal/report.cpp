// frictal report SURFACE [UPPER] -o report.html — one self-contained HTML page a person reads:
// the surface, its statistics, the signature function, the slope distributions, the predicted
// friction with its Eq. 18 range, for maps the friction over sliding directions, and theta_max
// against resolution. The page is built by the library (frictal/report.hpp); this file reads
// the inputs and writes the page.
#include <unistd.h>

#include <fstream>
#include <iostream>

#include "common.hpp"
#include "frictal/analysis.hpp"
#include "frictal/predict.hpp"
#include "frictal/report.hpp"
#include "frictal/tilt.hpp"
#include "frictal/version.hpp"
#include "map_hold.hpp"
#include "options.hpp"
#include "surface_io.hpp"

namespace frictal::cli {
namespace {

struct Args {
  std::string lower, upper, out;
  double mu_a = 0;
  std::string detrend;
  int directions = report::ReportInput{}.directions;  ///< maps: each direction a prediction over drops
  int resolution = 10;
  int bins = 90;
  int drops = PredictOptions{}.map_drops;
  FieldWords predict_words;  ///< --drops (the prediction's table)
  bool quiet = false;
  unsigned threads = 0;
  std::string tip_radius;
  InputOptions input;
  ConditioningOptions cond;
  FieldWords runaway_words;  ///< --runaway-distance, the tilt table's field (the hold-angle section)
  LoadWords load;            ///< friction under load (--load, --modulus, ...): the headline under load
};

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  app.add_option("surface", a->lower, "Surface file: a line profile or an areal map (any readable format)")->required();
  app.add_option("upper", a->upper,
                 "Upper surface, as measured (material below); it is turned over to face SURFACE. "
                 "Default: SURFACE itself. For a map, a map: the page adds the lift over two dimensions of offset "
                 "and the hold angles of a block free to move sideways");
  app.add_option("-o,--output", a->out, "HTML file to write ('-' = standard output)")->required();
  add_atomic_friction_option(app, a->mu_a);
  add_detrend_option(app, a->detrend);
  add_conditioning_options(app, a->cond);
  app.add_option("--directions", a->directions,
                 "Maps: sliding directions of the polar plot, each one prediction over --drops x --drops drops "
                 "(as frictal anisotropy --areal --hold)")
      ->capture_default_str();
  app.add_option("--resolution-steps", a->resolution, "Cutoff wavelengths of the resolution study (0 = none)")
      ->capture_default_str();
  app.add_option("--bins", a->bins, "Bins of the slope distributions")->capture_default_str();
  // --drops: the prediction's table (the headline's drops, and those of each direction of a map
  // pair's polar plot).
  add_predict_options(app, a->predict_words, {"drops"});
  app.add_flag("-q,--quiet", a->quiet, "No progress line on standard error");
  app.add_option("--tip-radius", a->tip_radius,
                 "Tip radius, a length such as 20nm (no unit: metres): draw its short reliability cutoff on the "
                 "resolution plot (see docs/analysis.md)");
  add_load_options(app, a->load);
  app.add_option("--threads", a->threads, "Worker threads (0 = all cores); the page does not depend on it")
      ->capture_default_str();
  add_input_options(app, a->input);
  add_field_options(app, tilt_settings(), a->runaway_words, all_but(tilt_settings(), "runaway_distance"));
  return [a]() {
    require(std::isfinite(a->mu_a) && a->mu_a >= 0,
            fmt::format("--atomic-friction: expected a number >= 0, got {}", a->mu_a));
    require(a->directions >= 1 && a->directions <= 720, fmt::format("--directions {}: expected 1..720", a->directions));
    require(a->resolution == 0 || (a->resolution >= 2 && a->resolution <= 100),
            "--resolution-steps must be 0 or 2..100");
    require(a->bins >= 2 && a->bins <= 10000, "--bins must be in 2..10000");
    const double tip = a->tip_radius.empty() ? 0.0 : parse_length_option(a->tip_radius, "--tip-radius");
    report::ReportInput in;
    const SurfaceData s = load_surface(a->lower, a->input);
    in.is_map = s.is_map;
    const std::string dt_text = a->detrend.empty() ? (s.is_map ? "plane" : "line") : a->detrend;
    const Detrend dt = unwrap(parse_detrend(dt_text));
    const Conditioning cond = conditioning(a->cond, dt);
    std::vector<ConditioningRecord> records;
    auto conditioned_map = [&](const Map& m, const std::string& name) {
      ConditionedMap c = unwrap(condition(m, cond, name));
      records.push_back(c.record);
      return std::move(c.map);
    };
    auto conditioned_profile = [&](const Profile& p, const std::string& name) {
      ConditionedProfile c = unwrap(condition(p, cond, name));
      records.push_back(c.record);
      return std::move(c.profile);
    };
    for (const auto& w : s.warnings) in.notes.push_back("Reader warning: " + w.message);
    if (s.is_map) {
      in.map = conditioned_map(s.map, a->lower);
      if (!a->upper.empty()) {  // two maps: the areal section (lift over two dimensions of offset)
        const SurfaceData u = load_surface(a->upper, a->input);
        for (const auto& w : u.warnings) in.notes.push_back("Reader warning: " + w.message);
        if (!u.is_map)
          throw UsageError(
              fmt::format("{}: a line profile; with an areal map as SURFACE, UPPER must be a map too", a->upper));
        in.upper_map = conditioned_map(u.map, a->upper);
        in.upper_name = a->upper;
      }
    } else {
      in.lower = conditioned_profile(surface_profile(s, a->lower), a->lower);
    }
    if (!a->upper.empty() && !s.is_map) {
      const SurfaceData u = load_surface(a->upper, a->input);
      for (const auto& w : u.warnings) in.notes.push_back("Reader warning: " + w.message);
      in.upper = conditioned_profile(surface_profile(u, a->upper), a->upper);
      in.upper_name = a->upper;
    }
    in.lower_name = a->lower;
    in.detrend = conditioning_text(records);
    in.atomic_friction = a->mu_a;
    in.directions = a->directions;
    a->drops = static_cast<int>(predict_integer(a->predict_words, "drops"));
    in.map_drops = a->drops;
    if (in.is_map && !a->quiet && isatty(fileno(stderr)))
      in.progress = [](std::size_t done, std::size_t total) {
        fmt::print(stderr, "\rfrictal report: the polar plot's direction {} of {}{}", done, total,
                   done == total ? "\n" : "");
        std::fflush(stderr);
      };
    in.resolution_steps = a->resolution;
    in.bins = a->bins;
    in.tip_radius = tip;
    in.threads = a->threads;
    if (const ValueSet rv = si_values(tilt_settings(), a->runaway_words); rv.count("runaway_distance"))
      in.runaway_distance = as_real(rv.at("runaway_distance"));
    in.generated_by = version_line();
    // The headline: the prediction of this pair, as `frictal predict` computes it from the same
    // files and options (the same conditioning: the page's --crop, --remove-spikes, --detrend).
    {
      static const std::string prediction_prefix = "the prediction's ";
      PredictOptions po;
      require(a->drops >= 2 && a->drops <= 64, fmt::format("--drops {}: expected 2..64", a->drops));
      po.map_drops = a->drops;
      po.progress = drop_progress("report", a->quiet, &prediction_prefix);
      po.atomic_friction = a->mu_a;
      po.runaway_distance = in.runaway_distance;
      po.detrend = dt;
      po.crop = cond.crop;
      po.crop_source = cond.crop_source;
      po.remove_spikes = cond.remove_spikes;
      po.spike_threshold = cond.spike_threshold;
      po.threads = a->threads;
      apply_load_options(a->load, po);
      const PredictSurface pl = unwrap(predict_surface(s, a->lower));
      std::optional<PredictSurface> pu;
      if (!a->upper.empty()) {
        pu = unwrap(predict_surface(unwrap(read_surface(input_path(a->upper), read_options(a->input))), a->upper));
      }
      in.prediction = unwrap(predict(pl, pu ? &*pu : nullptr, po));
      for (const Warning& w : in.prediction->warnings)
        fmt::print(stderr, "frictal: warning [{}]: {}\n", w.code, w.message);
    }
    const std::string page = unwrap(report::surface_report(in));
    if (a->out == "-") {
      std::cout << page;
      std::cout.flush();
      if (!std::cout) throw UsageError("standard output: write failed");
    } else {
      std::ofstream f(a->out, std::ios::binary);
      if (!f) throw UsageError(fmt::format("{}: cannot open for writing", a->out));
      f << page;
      if (!f) throw UsageError(fmt::format("{}: write failed", a->out));
      fmt::print(stderr, "frictal: wrote {} ({} bytes)\n", a->out, page.size());
    }
    return 0;
  };
}

FRICTAL_COMMAND({"report",
                 "One self-contained HTML page on a surface or a pair: signature, slopes, friction, resolution", setup,
                 75});

}  // namespace
}  // namespace frictal::cli
