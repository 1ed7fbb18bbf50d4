// Task kind 'tilt': the spheropolygon tilting-block test (Sec. IV) on a pair of generated
// surfaces (a Koch pair by default), for the studies of Fig. 6, 7 and 8. Parameters: `generator`
// (koch, wm, sawtooth, sine or self-affine; default koch), that generator's parameters and the
// tilt settings, all named and checked by the library's tables (surface_spec.hpp, tilt.hpp;
// SI units, angles in degrees as in the study files), and record_series (bool: return the
// Fig. 7 series as arrays). A run stopped by the stability guard is retried with a 2.5x smaller
// step (twice at most); time_step_s records it.
#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "frictal/surface_spec.hpp"
#include "frictal/study.hpp"
#include "frictal/tilt.hpp"
#include "study/table_params.hpp"

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
  auto generator = get_string(p, "generator", "koch");
  if (!generator) return generator.error();
  const GeneratorInfo* gen = find_generator(*generator);
  if (!gen) return make_error(fmt::format("parameter 'generator': unknown surface generator \"{}\"", *generator));
  if (Status st = only_known_parameters(p, {&gen->fields, &tilt_settings()}, {"generator", "record_series"}, "tilt"); !st)
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

}  // namespace frictal::study
