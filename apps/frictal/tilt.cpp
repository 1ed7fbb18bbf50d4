// frictal tilt — the tilting-block friction test on the spheropolygon engine (paper Sec. IV).
// The surface is a generator subcommand (frictal tilt koch --alpha 20 ...; every generator of
// `frictal surface`) or measured files (--lower, --upper); every setting of the test is an
// option derived from the library's table (tilt_settings(), frictal/tilt.hpp).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "frictal/hold.hpp"
#include "frictal/io.hpp"
#include "frictal/tilt.hpp"
#include "frictal/warnings.hpp"
#include "map_hold.hpp"
#include "movie.hpp"
#include "options.hpp"
#include "surface_io.hpp"

namespace frictal::cli {
namespace {

// The largest expected step count run without --force (unitless): about 4 to 10 minutes of one
// core at 5 to 10 us per step (docs/dem.md sec. 7, "cost estimate").
constexpr double kDefaultMaxSteps = 5e7;

struct TiltOptions {
  GeneratorOptions gen;
  FieldWords settings;
  std::string lower_file, upper_file;
  std::string detrend;       ///< --detrend (files; empty: form_to_remove's default)
  ConditioningOptions cond;  ///< --crop, --remove-spikes, --spike-threshold (files)
  std::string output, frames, vtk, movie;
  FieldWords block;  ///< --block-length (files): the prediction's table's block_length
  bool json = false;
  bool quiet = false;
  bool force = false;
  double max_steps = kDefaultMaxSteps;
  int threads = 1;
};

/// A line profile from a file; what the reader said that did not stop it joins the warnings (with
/// the reader's code), each naming the file.
Curve read_file(const std::string& path, std::vector<Warning>& warnings) {
  SurfaceData s = unwrap(read_surface(input_path(path), ReadOptions{}));
  if (s.is_map)
    throw UsageError(
        fmt::format("{}: an areal map ({} x {}), not a line profile; extract a line first", path, s.map.nx, s.map.ny));
  for (Warning& w : s.warnings) {
    if (w.message.find(path) == std::string::npos) w.message = path + ": " + w.message;
    add_warning(warnings, std::move(w));
  }
  return std::move(s.curve);
}

/// "0.4 s", "3 min", "2.1 h".
std::string duration_text(double seconds) {
  if (seconds < 120) return fmt::format("{:.2g} s", seconds);
  if (seconds < 7200) return fmt::format("{:.3g} min", seconds / 60);
  return fmt::format("{:.3g} h", seconds / 3600);
}

int run(TiltOptions& o) {
  Curve lower, upper;
  std::optional<TiltScaling> scaling;  // the defaults scaled to the surfaces
  std::vector<Warning> data_warnings;  // file inputs: the readers' and the plausibility checks' warnings
  TiltSurface surface;                 // the surfaces as given: the files or the generator
  const std::optional<SurfaceSpec> spec = o.gen.spec();
  if (spec) {
    if (!o.lower_file.empty() || !o.upper_file.empty())
      throw UsageError(fmt::format("tilt {}: a generated surface takes no --lower/--upper files", spec->generator));
    if (o.block.words.count("block_length"))
      throw UsageError(fmt::format(
          "tilt {} --block-length {}: a generated surface slides its whole block (the paper's Table I blocks); "
          "--block-length applies to --lower FILE",
          spec->generator, o.block.words.at("block_length")));
    lower = upper = unwrap(generate_curve(*spec));
    const double period = unwrap(surface_period(*spec)), scale = unwrap(surface_scale(*spec));
    // The defaults scaled to the surface's length and point spacing as for files (below): a
    // generated surface at the Table I length (Koch, sawtooth, sine, Fourier by default: 0.2 m)
    // keeps them bit for bit; the surface's own period and run-away distance (its wavelength)
    // are already at its scale.
    scaling = unwrap(tilt_setup(lower, upper, si_values(tilt_settings(), o.settings), period, scale));
    surface.generator = spec->generator;
    surface.parameters = &find_generator(spec->generator)->fields;
    surface.values = unwrap(surface_values(*spec));
  } else {
    if (o.lower_file.empty())
      throw UsageError(
          "tilt: give a generator (koch, wm, sawtooth, sine, self-affine, fourier) or --lower FILE [--upper FILE]");
    lower = read_file(o.lower_file, data_warnings);
    upper = o.upper_file.empty() ? lower : read_file(o.upper_file, data_warnings);
    // Each file conditioned as `signature` and `predict` do it (crop, spikes, form: the one
    // default, a line, unless --detrend names one), the record stated in the output. A folded
    // curve (not a profile) is taken as given unless an option asks for conditioning.
    const ValueSet asked_settings = si_values(tilt_settings(), o.settings);
    const bool periodic = asked_settings.count("period") && as_real(asked_settings.at("period")) > 0;
    const Conditioning cond = conditioning(o.cond, form_to_remove(o.detrend, false, periodic));
    const bool asked = (!o.detrend.empty() && o.detrend != "none") || o.cond.given("crop") || o.cond.remove_spikes();
    std::vector<ConditioningRecord> records;
    double read_rms[2] = {std::nan(""), std::nan("")};  // the heights as read (checks below)
    for (int i = 0; i < (o.upper_file.empty() ? 1 : 2); ++i) {
      Curve& c = i ? upper : lower;
      read_rms[i] = rms_height_as_read(c.z);
      const std::string& name = i ? o.upper_file : o.lower_file;
      auto p = as_profile(c, name);
      if (!p.ok()) {
        if (asked)
          throw UsageError(
              fmt::format("{}: a folded curve, not a profile: it cannot be conditioned ({})", name, p.error().message));
        ConditioningRecord none;
        none.form = Detrend{DetrendKind::None, 0};
        records.push_back(none);
        continue;
      }
      ConditionedProfile cp = unwrap(condition(*p, cond, name));
      records.push_back(cp.record);
      c.x = std::move(cp.profile.x);
      c.z = std::move(cp.profile.z);
    }
    if (o.upper_file.empty()) upper = lower;
    // The files' plausibility (warnings.hpp: units, tiny heights, spikes, fill values, two scans
    // of different scales), as `frictal predict` checks them, on the conditioned faces.
    double len[2] = {0, 0}, dx[2] = {0, 0};
    for (int i = 0; i < (o.upper_file.empty() ? 1 : 2); ++i) {
      const std::string& name = i ? o.upper_file : o.lower_file;
      auto p = as_profile(i ? upper : lower, name);
      if (!p.ok() || p->x.size() < 2) continue;  // a folded curve: not a profile to check
      for (Warning& w : check_profile(*p, name, {}, read_rms[i])) add_warning(data_warnings, std::move(w));
      len[i] = p->x.back() - p->x.front();
      dx[i] = len[i] / static_cast<double>(p->x.size() - 1);
    }
    if (dx[0] > 0 && dx[1] > 0)
      for (Warning& w : check_pair_scales(len[0], dx[0], len[1], dx[1], o.lower_file, o.upper_file))
        add_warning(data_warnings, std::move(w));
    // Measured files state the test that `frictal predict` states (hold.hpp's stated test): the
    // block the middle piece of the upper scan, L_b = 20 d long, d from the lower scan's slope
    // correlation length, dropped at the middle of predict's drop range (--block-length,
    // --runaway-distance, --initial-offset state others; --block-length whole: the whole upper
    // scan over the first half of the lower one). The macro defaults (Table I/II, made for a 0.2 m
    // block) are carried over to that block's length and point spacing (scale_tilt_defaults,
    // docs/dem.md sec. 5). Generated surfaces keep the paper's blocks (above).
    double block_length = 0;  // 0: the stated test's; "whole": -1
    if (const ValueSet b = si_values(predict_settings(), o.block); b.count("block_length"))
      block_length = word_value_of(*find_field(predict_settings(), "block_length"), b.at("block_length"));
    scaling = unwrap(tilt_setup(lower, upper, si_values(tilt_settings(), o.settings), 0, 0, block_length));
    for (const Warning& w : scaling->test.warnings) add_warning(data_warnings, w);
    surface.lower = o.lower_file;
    surface.upper = o.upper_file.empty() ? o.lower_file : o.upper_file;
    surface.conditioning = conditioning_text(records);
    surface.test = &scaling->test;
  }
  const ValueSet given = si_values(tilt_settings(), o.settings);
  TiltConfig cfg = scaling->config;
  if (!(o.max_steps > 0)) throw UsageError(fmt::format("tilt --max-steps {}: expected a value > 0", o.max_steps));
  cfg.threads = o.threads;
  if (o.output.empty()) cfg.series_interval = 0;
  if (o.frames.empty() && o.vtk.empty() && o.movie.empty())
    cfg.frame_interval = 0;
  else if (!given.count("frame_interval"))
    cfg.frame_interval = 0.01 * (scaling ? std::sqrt(scaling->length_factor) : 1.0);
  if (o.json && (o.output == "-" || o.frames == "-"))
    throw UsageError("--json and -o -/--frames - would both write to standard output; choose one");

  // Before the first step: the estimate on standard error, and the refusal beyond --max-steps.
  const bool progress_line = !o.quiet && ::isatty(2);
  cfg.before_run = [&](const TiltEstimate& e) -> Status {
    const std::string to = cfg.predict && e.simulated_time_expected < e.simulated_time_bound
                               ? "to the hold angle from the drop"
                               : fmt::format("to the largest tilt {:.3g} deg", cfg.max_tilt / kDeg);
    if (!o.quiet)
      fmt::print(stderr,
                 "frictal: estimate: time step {:.3g} s; about {:.3g} steps ({:.3g} s simulated {}), ~{} of CPU; "
                 "at most {:.3g} steps ({:.3g} s simulated to {:.3g} deg), ~{}\n",
                 e.time_step, e.steps_expected, e.simulated_time_expected, to, duration_text(e.seconds_expected),
                 e.steps_bound, e.simulated_time_bound, cfg.max_tilt / kDeg, duration_text(e.seconds_bound));
    if (e.steps_expected > o.max_steps && !o.force)
      return make_error(fmt::format(
          "tilt: the run needs about {:.3g} steps (time step {:.3g} s, {:.3g} s simulated {}; ~{} of CPU): beyond "
          "--max-steps {:.3g} (expected at most that many steps); --force runs it anyway, or raise --time-step, "
          "--tilt-rate or --normal-stiffness (the time step follows sqrt(m / k_n))",
          e.steps_expected, e.time_step, e.simulated_time_expected, to, duration_text(e.seconds_expected),
          o.max_steps));
    return Ok{};
  };
  double last_print = 0;
  bool printed = false;
  if (progress_line)
    cfg.progress = [&](const TiltProgress& p) {
      if (p.wall_time < 2 || p.wall_time - last_print < 0.5) return;
      last_print = p.wall_time;
      printed = true;
      const double share = p.estimate && p.estimate->steps_expected > 0
                               ? 100 * static_cast<double>(p.steps) / p.estimate->steps_expected
                               : 0.0;
      const double left =
          p.estimate && p.steps > 0 && static_cast<double>(p.steps) < p.estimate->steps_expected
              ? (p.estimate->steps_expected - static_cast<double>(p.steps)) * p.wall_time / static_cast<double>(p.steps)
              : 0.0;
      fmt::print(stderr,
                 "\rfrictal: tilt {:.3f} deg at t = {:.4g} s, {} steps ({:.0f}% of the estimate) in {:.0f} s, "
                 "~{:.0f} s left   ",
                 p.tilt / kDeg, p.time, p.steps, share, p.wall_time, left);
      std::fflush(stderr);
    };

  if (!o.movie.empty()) check_movie_tool(o.movie);  // before the run, not after it
  auto r = run_tilt(lower, scaling->upper, cfg);
  if (printed) fmt::print(stderr, "\n");
  if (!r.ok()) fail(r.error());
  // The files' warnings, then the run's: one list (JSON "warnings"; standard error in text).
  std::vector<Warning> warnings = data_warnings;
  warnings.insert(warnings.end(), r->warnings.begin(), r->warnings.end());
  if (!o.quiet)
    for (const Warning& w : warnings) fmt::print(stderr, "frictal: warning [{}]: {}\n", w.code, w.message);
  if (!o.output.empty())
    write_output(o.output, [&](const std::string& p) { return write_tilt_series_csv(p, r->series); });
  if (!o.vtk.empty()) {
    auto w = write_tilt_vtk(o.vtk, *r, cfg.radius);
    if (!w.ok()) fail(w.error());
    if (!o.quiet) fmt::print(stderr, "frictal: wrote {} VTK files, time index {}\n", w->size(), w->front());
  }
  if (!o.movie.empty()) {
    write_tilt_movie(o.movie, *r, cfg.radius);
    if (!o.quiet) fmt::print(stderr, "frictal: wrote {} ({} frames)\n", o.movie, r->frames.size());
  }
  if (!o.frames.empty())
    write_output(
        o.frames, [&](const std::string& p) { return write_tilt_frames(p, *r); }, "--frames");
  const double us_per_step = r->steps ? 1e6 * r->wall_time / static_cast<double>(r->steps) : 0.0;
  if (o.json) {
    const TiltReport run{*r, cfg, scaling ? &*scaling : nullptr, &surface, &warnings};
    fmt::print("{}\n", object_of(tilt_columns(), run).dump());
  } else {
    // With a CSV on standard output, the summary goes to standard error.
    std::FILE* text = (o.output == "-" || o.frames == "-") ? stderr : stdout;
    // The warnings that invalidate the result lead the output (all of them with --quiet, which
    // keeps standard error silent).
    for (const Warning& w : warnings)
      if (w.code == "rotation" || o.quiet) fmt::print(text, "warning [{}]: {}\n", w.code, w.message);
    const std::string validity = tilt_validity(*r, cfg);
    if (r->slid && validity != "valid")
      fmt::print(text, "friction angle (not valid: {}): {:.3f} deg (slides {} at t = {:.4f} s)\n", validity,
                 r->friction_angle / kDeg, cfg.reverse ? "towards -x" : "towards +x", r->slide_time);
    else if (r->slid)
      fmt::print(text, "friction angle: {:.3f} deg (slides {} at t = {:.4f} s)\n", r->friction_angle / kDeg,
                 cfg.reverse ? "towards -x" : "towards +x", r->slide_time);
    else
      fmt::print(text, "no run-away before the maximal tilt of {:.2f} deg\n", cfg.max_tilt / kDeg);
    if (cfg.predict) {
      fmt::print(text, "rigid upper bound (signature theta_max {:.3f} + atan(mu_a) {:.3f}): {:.3f} deg\n",
                 r->predicted_theta_max / kDeg, std::atan(cfg.contact.atomic_friction) / kDeg,
                 r->predicted_friction_angle / kDeg);
      fmt::print(text, "upper bound for spheropolygons (r = {:.3g} m, theta_max {:.3f} + atan(mu_a)): {:.3f} deg\n",
                 cfg.radius, r->predicted_sphero_theta_max / kDeg, r->predicted_sphero_friction_angle / kDeg);
      if (!std::isnan(r->predicted_hold_angle))
        fmt::print(text,
                   "hold angle from the rest offset {:.6g} m with run-away {:.3g} m: quasi-static {:.3f} deg "
                   "(spheropolygons {:.3f} deg), inertial bound {:.3f} deg\n",
                   r->rest_offset, cfg.runaway_distance, r->predicted_hold_angle / kDeg,
                   r->predicted_sphero_hold_angle / kDeg, r->predicted_inertial_hold_angle / kDeg);
      else if (!r->hold_error.empty())
        fmt::print(text, "hold angle: not computed ({})\n", r->hold_error);
      if (const std::string note = tilt_spread_note(*r, cfg); !note.empty())
        fmt::print(text, "this reading lies {}\n", note);
    }
    if (cfg.check_stiffness)
      fmt::print(text, "at 10 k_n: {}\n",
                 std::isnan(r->stiff_friction_angle) ? std::string("no run-away")
                                                     : fmt::format("{:.3f} deg", r->stiff_friction_angle / kDeg));
    if (cfg.protocol == TiltProtocol::QuasiStatic)
      fmt::print(text, "quasi-static: {} increments of {:.4g} deg, {} not relaxed within {:.3g} s; contact rule {}\n",
                 r->increments, cfg.tilt_increment / kDeg, r->unrelaxed_increments, cfg.relax_time,
                 r->contact_rule == dem::ContactRule::Closest ? "closest" : "pairs");
    if (surface.generator.empty()) fmt::print(text, "conditioning: {}\n", surface.conditioning);
    if (const TiltStatedTest& t = scaling->test; t.block == "stated")
      fmt::print(text,
                 "the test (as frictal predict states it): a block of {:.4g} m (the middle of the upper scan), sliding "
                 "for good after d = {:.4g} m ({}); dropped at {:.6g} m ({}) of the drop range [{:.6g}, {:.6g}] m\n",
                 t.block_length, cfg.runaway_distance, t.rule, cfg.initial_offset, t.drop, t.drop_min, t.drop_max);
    else if (t.block == "whole")
      fmt::print(text,
                 "the test (as frictal predict --block-length whole states it): the whole upper scan ({:.4g} m) over "
                 "the first half of the lower one, sliding for good after d = {:.4g} m ({})\n",
                 t.block_length, cfg.runaway_distance, t.rule);
    fmt::print(text, "rotation of the upper block against the lower one before the slide: {:.4g} deg{}\n",
               r->rotation_before_slide / kDeg, cfg.hold_rotation ? " (held)" : "");
    fmt::print(text,
               "{} steps of {:.3g} to {:.3g} s ({:.4f} s simulated) in {:.2f} s wall, {:.2f} us/step; blocks {} + {} "
               "vertices\n",
               r->steps, r->min_time_step, r->max_time_step, r->simulated_time, r->wall_time, us_per_step,
               r->lower_vertices, r->upper_vertices);
    if (scaling) {
      fmt::print(text,
                 "defaults scaled to the surfaces (length {:.4g} m, point spacing {:.4g} m: s = L / {:g} m = {:.4g}, "
                 "q = {:.4g}){}\n",
                 scaling->length, scaling->point_spacing, kTiltReferenceLength, scaling->length_factor,
                 scaling->radius_factor, scaling->settings.empty() ? std::string(": none changed") : std::string(":"));
      for (const TiltScaledSetting& t : scaling->settings) {
        const Field* f = find_field(tilt_settings(), t.name);
        const std::string unit = f ? text_unit(*f) : std::string();
        fmt::print(text, "  {} {:.4g} -> {:.4g}{}{}\n", t.name, f ? to_text_unit(*f, t.from) : t.from,
                   f ? to_text_unit(*f, t.to) : t.to, unit.empty() ? "" : " ", unit);
      }
      if (!scaling->measured_defaults.empty())
        fmt::print(text,
                   "measured surfaces default to {} (the protocol that reads their friction angle; the paper's: "
                   "--protocol constant-rate --no-hold-rotation)\n",
                   scaling->measured_defaults);
    }
  }
  return 0;
}

std::function<int()> setup(CLI::App& app) {
  auto o = std::make_shared<TiltOptions>();
  add_generator_subcommands(app, o->gen, true, " (both blocks)");
  app.add_option("--lower", o->lower_file,
                 "Lower surface file (x_m,z_m), as measured; - reads standard input. A measured pair runs the test "
                 "that `frictal predict` states (the middle piece of the upper scan as the block: --block-length), "
                 "the defaults not given scaled to the block's length and point spacing, loaded quasi-statically "
                 "with the rotation held (--protocol quasi-static --hold-rotation; docs/dem.md sec. 5)");
  app.add_option("--upper", o->upper_file, "Upper surface file, as measured (default: the lower one)");
  // The stated test's block (files): the prediction's table's field, as `frictal predict` takes it.
  add_predict_options(app, o->block, {"block_length"});
  add_detrend_option(app, o->detrend);
  add_conditioning_options(app, o->cond);
  add_field_options(app, tilt_settings(), o->settings);
  app.add_option("-o,--output", o->output, "Write the time series CSV here (- for standard output)");
  app.add_option(
      "--frames", o->frames,
      "Write frames (frictal-dem-frames 1, see docs/dem.md) here, every --frame-interval (0.01 s if not set)");
  app.add_option("--vtk", o->vtk,
                 "Write the frames as VTK PolyData (.vtp, bodies and contacts) with a ParaView time index tilt.pvd "
                 "into this directory, every --frame-interval (0.01 s if not set)");
  app.add_option("--movie", o->movie,
                 "Render the run to FILE.mp4 or FILE.gif with ffmpeg (tilt angle and atan(F_t/F_n) drawn in), one "
                 "frame per --frame-interval (0.01 s if not set), 25 frames per second");
  app.add_flag("--json", o->json, "Print one JSON object");
  app.add_flag("-q,--quiet", o->quiet,
               "Print nothing on standard error: no cost estimate, no progress line, no warnings there (text "
               "output: the warnings then lead standard output)");
  app.add_option("--max-steps", o->max_steps,
                 fmt::format("Refuse (exit 2) a run whose estimated step count exceeds this (default {:g}); "
                             "--force runs it anyway",
                             kDefaultMaxSteps));
  app.add_flag("--force", o->force, "Run even when the estimated step count exceeds --max-steps");
  app.add_option("--threads", o->threads,
                 "Threads (0 = all cores; default 1): the two predictions side by side, the contact passes split "
                 "where it pays; results do not depend on it")
      ->check(CLI::Range(0, 1024));
  return [o]() { return run(*o); };
}

FRICTAL_COMMAND({"tilt", "Tilting-block friction test on the spheropolygon engine (paper Sec. IV)", setup, 60});

}  // namespace
}  // namespace frictal::cli
