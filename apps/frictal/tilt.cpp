// frictal tilt — the tilting-block friction test on the spheropolygon engine (paper Sec. IV).
// The surface is a generator subcommand (frictal tilt koch --alpha 20 ...; every generator of
// `frictal surface`) or measured files (--lower, --upper); every setting of the test is an
// option derived from the library's table (tilt_settings(), frictal/tilt.hpp).
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "frictal/hold.hpp"
#include "frictal/io.hpp"
#include "frictal/tilt.hpp"
#include "movie.hpp"
#include "options.hpp"

namespace frictal::cli {
namespace {

struct TiltOptions {
  GeneratorOptions gen;
  FieldWords settings;
  std::string lower_file, upper_file;
  std::string output, frames, vtk, movie;
  bool json = false;
  int threads = 1;
};

/// Every value of a table in text units (degrees), keyed by the table's names.
nlohmann::json text_json(const std::vector<Field>& fields, const ValueSet& si) {
  nlohmann::json j = nlohmann::json::object();
  for (const Field& f : fields) {
    auto it = si.find(f.name);
    if (it == si.end()) continue;
    std::visit([&](const auto& v) { j[f.name] = v; }, text_from_si(f, it->second));
  }
  return j;
}

int run(TiltOptions& o) {
  Curve lower, upper;
  TiltConfig base;
  nlohmann::json surface;
  const std::optional<SurfaceSpec> spec = o.gen.spec();
  if (spec) {
    if (!o.lower_file.empty() || !o.upper_file.empty())
      throw UsageError(fmt::format("tilt {}: a generated surface takes no --lower/--upper files", spec->generator));
    lower = upper = unwrap(generate_curve(*spec));
    base = tilt_config_for_surface(unwrap(surface_period(*spec)), unwrap(surface_scale(*spec)));
    surface = text_json(find_generator(spec->generator)->fields, unwrap(surface_values(*spec)));
    surface["generator"] = spec->generator;
  } else {
    if (o.lower_file.empty())
      throw UsageError(
          "tilt: give a generator (koch, wm, sawtooth, sine, self-affine, fourier) or --lower FILE [--upper FILE]");
    lower = unwrap(read_curve(input_path(o.lower_file)));
    upper = o.upper_file.empty() ? lower : unwrap(read_curve(input_path(o.upper_file)));
    // Offsets over half the block; the run-away distance as `signature` takes it by default: a
    // tenth of that range (L_b/20: 0.01 m on the Table I block), so that it scales with the file.
    auto span = [](const Curve& c) {
      const auto [lo, hi] = std::minmax_element(c.x.begin(), c.x.end());
      return c.x.empty() ? 0.0 : *hi - *lo;
    };
    base = tilt_config_for_surface(0, default_runaway_distance(0, 0.5 * std::min(span(lower), span(upper)), 0));
    surface = {{"lower", o.lower_file}, {"upper", o.upper_file.empty() ? o.lower_file : o.upper_file}};
  }
  const ValueSet given = si_values(tilt_settings(), o.settings);
  TiltConfig cfg = unwrap(make_tilt_config(given, base));
  cfg.threads = o.threads;
  if (o.output.empty()) cfg.series_interval = 0;
  if (o.frames.empty() && o.vtk.empty() && o.movie.empty())
    cfg.frame_interval = 0;
  else if (!given.count("frame_interval"))
    cfg.frame_interval = 0.01;
  if (o.json && (o.output == "-" || o.frames == "-"))
    throw UsageError("--json and -o -/--frames - would both write to standard output; choose one");

  if (!o.movie.empty()) check_movie_tool(o.movie);  // before the run, not after it
  auto r = run_tilt(lower, upper, cfg);
  if (!r.ok()) fail(r.error());
  for (const TiltWarning& w : r->warnings) fmt::print(stderr, "frictal: warning [{}]: {}\n", w.code, w.message);
  if (!o.output.empty())
    write_output(o.output, [&](const std::string& p) { return write_tilt_series_csv(p, r->series); });
  if (!o.vtk.empty()) {
    auto w = write_tilt_vtk(o.vtk, *r, cfg.radius);
    if (!w.ok()) fail(w.error());
    fmt::print(stderr, "frictal: wrote {} VTK files, time index {}\n", w->size(), w->front());
  }
  if (!o.movie.empty()) {
    write_tilt_movie(o.movie, *r, cfg.radius);
    fmt::print(stderr, "frictal: wrote {} ({} frames)\n", o.movie, r->frames.size());
  }
  if (!o.frames.empty())
    write_output(
        o.frames, [&](const std::string& p) { return write_tilt_frames(p, *r); }, "--frames");
  const double us_per_step = r->steps ? 1e6 * r->wall_time / static_cast<double>(r->steps) : 0.0;
  if (o.json) {
    nlohmann::json j;
    j["slid"] = r->slid;
    j["friction_angle_deg"] = r->slid ? nlohmann::json(r->friction_angle / kDeg) : nlohmann::json(nullptr);
    j["predicted_friction_angle_deg"] =
        cfg.predict ? nlohmann::json(r->predicted_friction_angle / kDeg) : nlohmann::json(nullptr);
    j["predicted_theta_max_deg"] =
        cfg.predict ? nlohmann::json(r->predicted_theta_max / kDeg) : nlohmann::json(nullptr);
    j["predicted_sphero_friction_angle_deg"] =
        cfg.predict ? nlohmann::json(r->predicted_sphero_friction_angle / kDeg) : nlohmann::json(nullptr);
    j["predicted_sphero_theta_max_deg"] =
        cfg.predict ? nlohmann::json(r->predicted_sphero_theta_max / kDeg) : nlohmann::json(nullptr);
    auto deg_or_null = [](double rad) {
      return std::isnan(rad) ? nlohmann::json(nullptr) : nlohmann::json(rad / kDeg);
    };
    j["protocol"] = cfg.protocol == TiltProtocol::QuasiStatic ? "quasi-static" : "constant-rate";
    j["contact_rule"] = r->contact_rule == dem::ContactRule::Closest ? "closest" : "pairs";
    j["rest_offset_m"] = r->rest_offset;
    j["predicted_hold_angle_deg"] = deg_or_null(r->predicted_hold_angle);
    j["predicted_hold_offset_m"] =
        std::isnan(r->predicted_hold_offset) ? nlohmann::json(nullptr) : nlohmann::json(r->predicted_hold_offset);
    j["slide_start_offset_m"] =
        r->slid ? nlohmann::json(r->rest_offset + (cfg.reverse ? -1 : 1) * r->slide_start_displacement)
                : nlohmann::json(nullptr);
    j["predicted_inertial_hold_angle_deg"] = deg_or_null(r->predicted_inertial_hold_angle);
    j["predicted_sphero_hold_angle_deg"] = deg_or_null(r->predicted_sphero_hold_angle);
    if (!r->hold_error.empty()) j["hold_error"] = r->hold_error;
    if (cfg.check_stiffness) j["stiff_friction_angle_deg"] = deg_or_null(r->stiff_friction_angle);
    if (cfg.protocol == TiltProtocol::QuasiStatic) {
      j["increments"] = r->increments;
      j["unrelaxed_increments"] = r->unrelaxed_increments;
    }
    j["rotation_before_slide_deg"] = r->rotation_before_slide / kDeg;
    const TiltScales& sc = r->scales;
    j["scales"] = {{"resting_overlap_m", sc.resting_overlap},
                   {"spheroradius_m", sc.spheroradius},
                   {"shortest_edge_m", {sc.shortest_edge[0], sc.shortest_edge[1]}},
                   {"smallest_feature_m", {sc.smallest_feature[0], sc.smallest_feature[1]}},
                   {"time_step_s", sc.time_step},
                   {"contact_period_s", sc.contact_period}};
    j["warnings"] = nlohmann::json::array();
    for (const TiltWarning& w : r->warnings) j["warnings"].push_back({{"code", w.code}, {"message", w.message}});
    j["surface"] = surface;
    j["settings"] = text_json(tilt_settings(), tilt_values(cfg));
    j["initial_offset_m"] = r->initial_offset;
    j["slide_time_s"] = r->slide_time;
    j["simulated_time_s"] = r->simulated_time;
    j["steps"] = r->steps;
    j["wall_time_s"] = r->wall_time;
    j["setup_time_s"] = r->setup_time;
    j["us_per_step"] = us_per_step;
    j["min_time_step_s"] = r->min_time_step;
    j["max_time_step_s"] = r->max_time_step;
    j["list_builds"] = r->timings.list_builds;
    j["steps_beyond_stability_limit"] = r->steps_beyond_limit;
    j["mean_pairs_in_list"] =
        r->steps ? static_cast<double>(r->timings.pairs_visited) / static_cast<double>(r->steps) : 0.0;
    j["mean_pairs_evaluated"] =
        r->steps ? static_cast<double>(r->timings.pairs_evaluated) / static_cast<double>(r->steps) : 0.0;
    j["hot_list_refreshes"] = r->timings.hot_refreshes;
    j["split_steps"] = r->timings.split_steps;
    j["stage_time_s"] = {{"neighbor_list", r->timings.neighbor_list},
                         {"contacts", r->timings.contacts},
                         {"integration", r->timings.integration}};
    j["lower_vertices"] = r->lower_vertices;
    j["upper_vertices"] = r->upper_vertices;
    j["upper_mass_kg"] = r->upper_mass;
    j["normal_damping_per_s"] = r->normal_damping;
    j["settled_contacts"] = r->settled_contacts;
    j["settled_overlap_m"] = r->settled_overlap;
    j["settled_speed_m_s"] = r->settled_speed;
    fmt::print("{}\n", j.dump());
  } else {
    // With a CSV on standard output, the summary goes to standard error.
    std::FILE* text = (o.output == "-" || o.frames == "-") ? stderr : stdout;
    if (r->slid)
      fmt::print(text, "friction angle: {:.3f} deg (slides {} at t = {:.4f} s)\n", r->friction_angle / kDeg,
                 cfg.reverse ? "towards -x" : "towards +x", r->slide_time);
    else
      fmt::print(text, "no run-away before the maximal tilt of {:.2f} deg\n", cfg.max_tilt / kDeg);
    if (cfg.predict) {
      fmt::print(text, "predicted (signature theta_max {:.3f} + atan(mu_a) {:.3f}): {:.3f} deg\n",
                 r->predicted_theta_max / kDeg, std::atan(cfg.contact.atomic_friction) / kDeg,
                 r->predicted_friction_angle / kDeg);
      fmt::print(text, "predicted for spheropolygons (r = {:.3g} m, theta_max {:.3f} + atan(mu_a)): {:.3f} deg\n",
                 cfg.radius, r->predicted_sphero_theta_max / kDeg, r->predicted_sphero_friction_angle / kDeg);
      if (!std::isnan(r->predicted_hold_angle))
        fmt::print(text,
                   "hold angle from the rest offset {:.6g} m with run-away {:.3g} m: quasi-static {:.3f} deg "
                   "(spheropolygons {:.3f} deg), inertial bound {:.3f} deg\n",
                   r->rest_offset, cfg.runaway_distance, r->predicted_hold_angle / kDeg,
                   r->predicted_sphero_hold_angle / kDeg, r->predicted_inertial_hold_angle / kDeg);
      else if (!r->hold_error.empty())
        fmt::print(text, "hold angle: not computed ({})\n", r->hold_error);
    }
    if (cfg.check_stiffness)
      fmt::print(text, "at 10 k_n: {}\n",
                 std::isnan(r->stiff_friction_angle) ? std::string("no run-away")
                                                     : fmt::format("{:.3f} deg", r->stiff_friction_angle / kDeg));
    if (cfg.protocol == TiltProtocol::QuasiStatic)
      fmt::print(text, "quasi-static: {} increments of {:.4g} deg, {} not relaxed within {:.3g} s; contact rule {}\n",
                 r->increments, cfg.tilt_increment / kDeg, r->unrelaxed_increments, cfg.relax_time,
                 r->contact_rule == dem::ContactRule::Closest ? "closest" : "pairs");
    fmt::print(text, "rotation of the upper block against the lower one before the slide: {:.4g} deg{}\n",
               r->rotation_before_slide / kDeg, cfg.hold_rotation ? " (held)" : "");
    fmt::print(text,
               "{} steps of {:.3g} to {:.3g} s ({:.4f} s simulated) in {:.2f} s wall, {:.2f} us/step; blocks {} + {} "
               "vertices\n",
               r->steps, r->min_time_step, r->max_time_step, r->simulated_time, r->wall_time, us_per_step,
               r->lower_vertices, r->upper_vertices);
  }
  return 0;
}

std::function<int()> setup(CLI::App& app) {
  auto o = std::make_shared<TiltOptions>();
  add_generator_subcommands(app, o->gen, true, " (both blocks)");
  app.add_option("--lower", o->lower_file, "Lower surface file (x_m,z_m), as measured; - reads standard input");
  app.add_option("--upper", o->upper_file, "Upper surface file, as measured (default: the lower one)");
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
  app.add_option("--threads", o->threads,
                 "Threads (0 = all cores; default 1): the two predictions side by side, the contact passes split "
                 "where it pays; results do not depend on it")
      ->check(CLI::Range(0, 1024));
  return [o]() { return run(*o); };
}

FRICTAL_COMMAND({"tilt", "Tilting-block friction test on the spheropolygon engine (paper Sec. IV)", setup, 60});

}  // namespace
}  // namespace frictal::cli
