// frictal tilt — the tilting-block friction test on the spheropolygon engine (paper Sec. IV).
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "frictal/generators.hpp"
#include "frictal/io.hpp"
#include "frictal/tilt.hpp"

namespace frictal::cli {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

struct TiltOptions {
  std::string surface = "koch";
  int iterations = 0;
  double alpha_deg = 20;
  double wavelength = 0.01;
  double length = 0.2;
  double rise_fraction = 0.5;
  double amplitude = 1e-3;
  int points_per_wavelength = 64;
  std::string lower_file, upper_file;
  std::string face = "curve";
  double offset = std::nan("");
  double atomic_friction = 0;
  bool reverse = false;
  double tilt_rate = 0.05;
  double dt = TiltConfig{}.time_step;
  bool fixed_dt = false;
  double dt_safety = TiltConfig{}.time_step_safety;
  double skin = 5e-5;
  double settle = 0.1;
  double max_tilt_deg = 89;
  double kn = 6e5, kt = 6e4, gn = 929.5, gt = 4, radius = 5e-5, density = 50, height = 0.01;
  double series_interval = 1e-3, frame_interval = 0.01;
  double stick_speed = 1e-5;
  double restitution = 0;
  int max_steps_beyond_limit = 1000;
  double runaway = 0;
  std::string output, frames;
  bool json = false;
  bool no_predict = false;
};

int run(const TiltOptions& o) {
  Curve lower, upper;
  double period = o.wavelength;
  if (o.surface == "file" || !o.lower_file.empty()) {
    if (o.lower_file.empty()) throw UsageError("--surface file needs --lower FILE (and optionally --upper FILE)");
    auto l = read_curve(o.lower_file);
    if (!l.ok()) throw UsageError(l.error().message);
    lower = *l;
    if (!o.upper_file.empty()) {
      auto u = read_curve(o.upper_file);
      if (!u.ok()) throw UsageError(u.error().message);
      upper = *u;
    } else {
      upper = lower;
    }
    period = 0;  // offsets over half the block for measured data
  } else if (o.surface == "koch") {
    KochParams p;
    p.iterations = o.iterations;
    p.alpha = o.alpha_deg * kDeg;
    p.wavelength = o.wavelength;
    p.length = o.length;
    auto c = koch_curve(p);
    if (!c.ok()) throw UsageError("--surface koch: " + c.error().message);
    lower = upper = *c;
  } else if (o.surface == "sawtooth") {
    SawtoothParams p;
    p.rise_angle = o.alpha_deg * kDeg;
    p.rise_fraction = o.rise_fraction;
    p.wavelength = o.wavelength;
    p.length = o.length;
    auto c = sawtooth_profile(p);
    if (!c.ok()) throw UsageError("--surface sawtooth: " + c.error().message);
    lower = upper = as_curve(*c);
  } else if (o.surface == "sine") {
    SineParams p;
    p.amplitude = o.amplitude;
    p.wavelength = o.wavelength;
    p.length = o.length;
    p.points_per_wavelength = o.points_per_wavelength;
    auto c = sine_profile(p);
    if (!c.ok()) throw UsageError("--surface sine: " + c.error().message);
    lower = upper = as_curve(*c);
  } else {
    throw UsageError("--surface: expected koch, sawtooth, sine or file, got '" + o.surface + "'");
  }

  TiltConfig cfg;
  cfg.block_height = o.height;
  cfg.radius = o.radius;
  cfg.density = o.density;
  cfg.contact.normal_stiffness = o.kn;
  cfg.contact.tangential_stiffness = o.kt;
  cfg.contact.normal_damping = o.gn;
  cfg.contact.tangential_damping = o.gt;
  cfg.contact.atomic_friction = o.atomic_friction;
  cfg.tilt_rate = o.tilt_rate;
  cfg.reverse = o.reverse;
  cfg.time_step = o.dt;
  cfg.adaptive_time_step = !o.fixed_dt;
  cfg.time_step_safety = o.dt_safety;
  cfg.implicit_damping = !o.fixed_dt;
  cfg.skin = o.skin;
  cfg.settle_time = o.settle;
  cfg.max_tilt = o.max_tilt_deg * kDeg;
  cfg.runaway_distance = o.runaway > 0 ? o.runaway : o.wavelength;
  cfg.stick_speed = o.stick_speed;
  cfg.restitution = o.restitution;
  cfg.max_steps_beyond_limit = o.max_steps_beyond_limit;
  cfg.face = o.face == "envelope" ? TiltFace::Envelope : TiltFace::Curve;
  if (o.face != "envelope" && o.face != "curve") throw UsageError("--face: expected curve or envelope, got '" + o.face + "'");
  cfg.initial_offset = o.offset;
  cfg.period = period;
  cfg.predict = !o.no_predict;
  cfg.series_interval = o.output.empty() ? 0 : o.series_interval;
  cfg.frame_interval = o.frames.empty() ? 0 : o.frame_interval;

  auto r = run_tilt(lower, upper, cfg);
  if (!r.ok()) {
    fmt::print(stderr, "frictal: {}\n", r.error().message);
    return 1;
  }
  if (!o.output.empty()) {
    if (Status s = write_tilt_series_csv(o.output, r->series); !s.ok()) throw UsageError("-o: " + s.error().message);
  }
  if (!o.frames.empty()) {
    if (Status s = write_tilt_frames(o.frames, *r); !s.ok()) throw UsageError("--frames: " + s.error().message);
  }
  const double us_per_step = r->steps ? 1e6 * r->wall_time / static_cast<double>(r->steps) : 0.0;
  if (o.json) {
    nlohmann::json j;
    j["slid"] = r->slid;
    j["friction_angle_deg"] = r->slid ? nlohmann::json(r->friction_angle / kDeg) : nlohmann::json(nullptr);
    j["predicted_friction_angle_deg"] = o.no_predict ? nlohmann::json(nullptr) : nlohmann::json(r->predicted_friction_angle / kDeg);
    j["predicted_theta_max_deg"] = o.no_predict ? nlohmann::json(nullptr) : nlohmann::json(r->predicted_theta_max / kDeg);
    j["atomic_friction"] = o.atomic_friction;
    j["direction"] = o.reverse ? "backward" : "forward";
    j["face"] = o.face;
    j["initial_offset_m"] = r->initial_offset;
    j["slide_time_s"] = r->slide_time;
    j["simulated_time_s"] = r->simulated_time;
    j["steps"] = r->steps;
    j["wall_time_s"] = r->wall_time;
    j["setup_time_s"] = r->setup_time;
    j["us_per_step"] = us_per_step;
    j["time_step_s"] = o.dt;
    j["adaptive_time_step"] = !o.fixed_dt;
    j["min_time_step_s"] = r->min_time_step;
    j["max_time_step_s"] = r->max_time_step;
    j["list_builds"] = r->timings.list_builds;
    j["steps_beyond_stability_limit"] = r->steps_beyond_limit;
    j["mean_pairs_in_list"] = r->steps ? static_cast<double>(r->timings.pairs_visited) / static_cast<double>(r->steps) : 0.0;
    j["mean_pairs_evaluated"] = r->steps ? static_cast<double>(r->timings.pairs_evaluated) / static_cast<double>(r->steps) : 0.0;
    j["hot_list_refreshes"] = r->timings.hot_refreshes;
    j["stage_time_s"] = {{"neighbor_list", r->timings.neighbor_list}, {"contacts", r->timings.contacts},
                         {"integration", r->timings.integration}};
    j["lower_vertices"] = r->lower_vertices;
    j["upper_vertices"] = r->upper_vertices;
    j["upper_mass_kg"] = r->upper_mass;
    j["normal_damping_per_s"] = r->normal_damping;
    j["settled_contacts"] = r->settled_contacts;
    j["settled_overlap_m"] = r->settled_overlap;
    fmt::print("{}\n", j.dump());
  } else {
    if (r->slid)
      fmt::print("friction angle: {:.3f} deg (slides {} at t = {:.4f} s)\n", r->friction_angle / kDeg,
                 o.reverse ? "towards -x" : "towards +x", r->slide_time);
    else
      fmt::print("no run-away before the maximal tilt of {:.2f} deg\n", o.max_tilt_deg);
    if (!o.no_predict)
      fmt::print("predicted (signature theta_max {:.3f} + atan(mu_a) {:.3f}): {:.3f} deg\n",
                 r->predicted_theta_max / kDeg, std::atan(o.atomic_friction) / kDeg, r->predicted_friction_angle / kDeg);
    fmt::print("{} steps of {:.3g} to {:.3g} s ({:.4f} s simulated) in {:.2f} s wall, {:.2f} us/step; blocks {} + {} vertices\n",
               r->steps, r->min_time_step, r->max_time_step, r->simulated_time, r->wall_time, us_per_step, r->lower_vertices, r->upper_vertices);
  }
  return 0;
}

std::function<int()> setup(CLI::App& app) {
  auto o = std::make_shared<TiltOptions>();
  app.add_option("--surface", o->surface, "koch, sawtooth, sine or file")->capture_default_str();
  app.add_option("--iterations,-n", o->iterations, "Koch iterations n (K_n)")->capture_default_str();
  app.add_option("--alpha", o->alpha_deg, "Koch base angle / sawtooth rise angle (deg)")->capture_default_str();
  app.add_option("--wavelength", o->wavelength, "wavelength lambda (m); also the run-away distance")->capture_default_str();
  app.add_option("--length", o->length, "block length L_b (m)")->capture_default_str();
  app.add_option("--rise-fraction", o->rise_fraction, "sawtooth rising fraction of the wavelength")->capture_default_str();
  app.add_option("--amplitude", o->amplitude, "sine amplitude (m)")->capture_default_str();
  app.add_option("--points-per-wavelength", o->points_per_wavelength, "sine sampling")->capture_default_str();
  app.add_option("--lower", o->lower_file, "lower surface file (x_m,z_m), as measured");
  app.add_option("--upper", o->upper_file, "upper surface file, as measured (default: the lower one)");
  app.add_option("--face", o->face, "block face for folded surfaces: curve (full curve) or envelope")->capture_default_str();
  app.add_option("--offset", o->offset, "initial x shift of the upper block (m); default: least lift from the signature");
  app.add_option("--atomic-friction", o->atomic_friction, "mu_a")->capture_default_str();
  app.add_flag("--reverse", o->reverse, "tilt the other way: the upper block slides towards -x");
  app.add_option("--tilt-rate", o->tilt_rate, "tilt rate (rad/s)")->capture_default_str();
  app.add_option("--dt", o->dt, "largest time step (s); with --fixed-dt the fixed step")->capture_default_str();
  app.add_option("--dt-safety", o->dt_safety, "adaptive step: fraction of the explicit stability limit, in (0, 1]")->capture_default_str();
  app.add_flag("--fixed-dt", o->fixed_dt, "fixed step --dt with explicit dashpots (default: adaptive step from the stability limit, implicit normal dashpots)");
  app.add_option("--skin", o->skin, "neighbour-list skin (m)")->capture_default_str();
  app.add_option("--settle", o->settle, "settling time before tilting (s)")->capture_default_str();
  app.add_option("--max-tilt", o->max_tilt_deg, "give up beyond this tilt (deg)")->capture_default_str();
  app.add_option("--kn", o->kn, "normal stiffness k_n (N/m)")->capture_default_str();
  app.add_option("--kt", o->kt, "tangential stiffness k_t (N/m)")->capture_default_str();
  app.add_option("--gamma-n", o->gn, "normal damping gamma_n (1/s)")->capture_default_str();
  app.add_option("--gamma-t", o->gt, "tangential damping gamma_t (1/s)")->capture_default_str();
  app.add_option("--restitution", o->restitution,
                 "restitution eps of Eq. 12 on the upper block's mass; replaces --gamma-n when set");
  app.add_option("--radius", o->radius, "spheroradius r (m)")->capture_default_str();
  app.add_option("--density", o->density, "areal density rho (kg/m^2)")->capture_default_str();
  app.add_option("--height", o->height, "block height h below the surface (m)")->capture_default_str();
  app.add_option("--stick-speed", o->stick_speed, "relative speed counted as stuck (m/s)")->capture_default_str();
  app.add_option("--runaway", o->runaway, "run-away distance (m); default: the wavelength");
  app.add_option("--max-steps-beyond-limit", o->max_steps_beyond_limit,
                 "stop after this many steps (in total) beyond the explicit stability limit")->capture_default_str();
  app.add_option("-o,--output", o->output, "write the time series CSV here");
  app.add_option("--series-interval", o->series_interval, "time between series rows (s)")->capture_default_str();
  app.add_option("--frames", o->frames, "write frames (frictal-dem-frames 1, see docs/dem.md) here");
  app.add_option("--frame-interval", o->frame_interval, "time between frames (s)")->capture_default_str();
  app.add_flag("--no-predict", o->no_predict, "skip the signature prediction");
  app.add_flag("--json", o->json, "print one JSON object");
  return [o]() {
    auto pos = [](double v, const char* name) {
      if (!(std::isfinite(v) && v > 0)) throw UsageError(fmt::format("{}: expected a positive number, got {}", name, v));
    };
    pos(o->dt, "--dt");
    if (!(o->dt_safety > 0 && o->dt_safety <= 1)) throw UsageError(fmt::format("--dt-safety: expected a value in (0, 1], got {}", o->dt_safety));
    pos(o->tilt_rate, "--tilt-rate");
    pos(o->wavelength, "--wavelength");
    pos(o->length, "--length");
    if (o->atomic_friction < 0 || !std::isfinite(o->atomic_friction)) throw UsageError("--atomic-friction: expected mu_a >= 0");
    if (!(o->max_tilt_deg > 0 && o->max_tilt_deg < 90)) throw UsageError("--max-tilt: expected a tilt in (0, 90) degrees");
    return run(*o);
  };
}

FRICTAL_COMMAND({"tilt", "tilting-block friction test on the spheropolygon engine (paper Sec. IV)", setup, 60});

}  // namespace
}  // namespace frictal::cli
