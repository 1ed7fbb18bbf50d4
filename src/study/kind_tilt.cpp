// Task kind 'tilt': the spheropolygon tilting-block test (Sec. IV) on a Koch pair, for the
// studies of Fig. 6, 7 and 8. Parameters (SI units, angles in degrees as in the study files):
// iterations, alpha_deg, atomic_friction, wavelength, length, height, normal_stiffness,
// tangential_stiffness, normal_damping, tangential_damping, spheroradius, density, tilt_rate,
// time_step, reverse (bool), record_series (bool: return the Fig. 7 series as arrays). A run stopped
// by the stability guard is retried with a 2.5x smaller step (twice at most); time_step_s records it.
#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "frictal/generators.hpp"
#include "frictal/study.hpp"
#include "frictal/tilt.hpp"

namespace frictal::study {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Result<bool> get_bool(const Params& p, const std::string& name, bool fallback) {
  auto it = p.find(name);
  if (it == p.end()) return fallback;
  if (const bool* b = std::get_if<bool>(&it->second)) return *b;
  return make_error(fmt::format("parameter '{}': expected true or false, got {}", name, canonical(it->second)));
}

}  // namespace

Result<TaskOutput> run_tilt_task(const Params& p, std::uint64_t /*seed: deterministic simulation*/) {
  auto iterations = get_int(p, "iterations");
  auto alpha_deg = get_real(p, "alpha_deg");
  if (!iterations) return iterations.error();
  if (!alpha_deg) return alpha_deg.error();
  if (*iterations < 0 || *iterations > 5)
    return make_error(fmt::format("parameter 'iterations': expected 0..5, got {}", *iterations));
  TiltConfig c = default_tilt_config();
  KochParams kp;
  kp.iterations = static_cast<int>(*iterations);
  kp.alpha = *alpha_deg * kDeg;
  struct Real {
    const char* name;
    double* into;
  };
  for (const Real& r : {Real{"wavelength", &kp.wavelength}, Real{"length", &kp.length}, Real{"height", &c.block_height},
                        Real{"atomic_friction", &c.contact.atomic_friction},
                        Real{"normal_stiffness", &c.contact.normal_stiffness},
                        Real{"tangential_stiffness", &c.contact.tangential_stiffness},
                        Real{"normal_damping", &c.contact.normal_damping},
                        Real{"tangential_damping", &c.contact.tangential_damping}, Real{"spheroradius", &c.radius},
                        Real{"density", &c.density}, Real{"tilt_rate", &c.tilt_rate}, Real{"time_step", &c.time_step}}) {
    auto v = get_real(p, r.name, *r.into);
    if (!v) return v.error();
    *r.into = *v;
  }
  auto reverse = get_bool(p, "reverse", false);
  auto series = get_bool(p, "record_series", false);
  if (!reverse) return reverse.error();
  if (!series) return series.error();
  c.reverse = *reverse;
  c.period = kp.wavelength;
  c.runaway_distance = kp.wavelength;
  c.series_interval = *series ? 1e-3 : 0;
  auto curve = koch_curve(kp);
  if (!curve) return curve.error();
  // The engine's stability guard stops a run whose step is too large for the number of contacts
  // (K3 carries hundreds); retry twice with a step 2.5 times smaller rather than lose the task.
  auto r = run_tilt(*curve, *curve, c);
  for (int retry = 0; retry < 2 && !r && r.error().message.find("stability limit") != std::string::npos; ++retry) {
    c.time_step /= 2.5;
    r = run_tilt(*curve, *curve, c);
  }
  if (!r) return r.error();
  TaskOutput out;
  auto& s = out.scalars;
  s["slid"] = r->slid ? 1 : 0;
  s["friction_angle_deg"] = r->friction_angle / kDeg;
  s["predicted_friction_angle_deg"] = r->predicted_friction_angle / kDeg;
  s["predicted_theta_max_deg"] = r->predicted_theta_max / kDeg;
  s["friction_angle_minus_theory_deg"] = (r->friction_angle - r->predicted_friction_angle) / kDeg;
  s["phi_minus_theta_max_deg"] = (r->friction_angle - r->predicted_theta_max) / kDeg;
  s["atomic_friction_angle_deg"] = std::atan(c.contact.atomic_friction) / kDeg;
  s["friction_coefficient"] = std::tan(r->friction_angle);
  s["simulated_time_s"] = r->simulated_time;
  s["steps"] = static_cast<double>(r->steps);
  s["steps_beyond_limit"] = static_cast<double>(r->steps_beyond_limit);
  s["time_step_s"] = c.time_step;
  s["upper_mass_kg"] = r->upper_mass;
  if (*series) {
    // Fig. 7: atan(F_t/F_n)/alpha against the relative displacement / L_b.
    const auto& ts = r->series;
    std::vector<double> d, a, t, tilt;
    for (std::size_t i = 0; i < ts.time.size(); ++i) {
      d.push_back(ts.displacement[i] / kp.length);
      a.push_back(ts.force_angle[i] / kp.alpha);
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

}  // namespace frictal::study
