// Task kind 'divider': the divider (ruler) method on a Koch curve (Sec. IV C 3, Fig. 9, 10).
// Parameters: the koch generator's (iterations, alpha in degrees, wavelength, length; here the
// length defaults to 0.01 m), ruler_min_over_wavelength,
// ruler_max_over_wavelength, rulers. Returns D = 1 - slope of log L against log eps with its
// fit quality, the Eq. 13 dimension, and the arrays ruler_m / measured_length_m (Fig. 9).
#include <numbers>

#include <fmt/core.h>

#include "frictal/fractal.hpp"
#include "frictal/generators.hpp"
#include "frictal/study.hpp"
#include "frictal/surface_spec.hpp"
#include "study/table_params.hpp"

namespace frictal::study {

Result<TaskOutput> run_divider_task(const Params& p, std::uint64_t /*seed: deterministic curve*/) {
  auto rmin = get_real(p, "ruler_min_over_wavelength", 3e-4);
  auto rmax = get_real(p, "ruler_max_over_wavelength", 0.25);
  auto rulers = get_int(p, "rulers", 40);
  if (!rmin) return rmin.error();
  if (!rmax) return rmax.error();
  if (!rulers) return rulers.error();
  if (*rulers < 3 || *rulers > 10000) return make_error(fmt::format("parameter 'rulers': expected 3..10000, got {}", *rulers));
  if (Status st = only_known_parameters(p, {&find_generator("koch")->fields},
                                        {"ruler_min_over_wavelength", "ruler_max_over_wavelength", "rulers"}, "divider");
      !st)
    return st.error();
  auto koch_values = table_values(find_generator("koch")->fields, p);
  if (!koch_values) return koch_values.error();
  if (auto it = koch_values->find("iterations"); it != koch_values->end() && std::get<std::int64_t>(it->second) > 8)
    return make_error(fmt::format("parameter 'iterations': expected 0..8, got {}", std::get<std::int64_t>(it->second)));
  if (!koch_values->count("length")) (*koch_values)["length"] = 0.01;  // one wavelength: the divider needs no more
  auto spec = make_surface_spec("koch", *koch_values);
  if (!spec) return spec.error();
  auto kpr = koch_params(*spec);
  if (!kpr) return kpr.error();
  const KochParams kp = *kpr;
  auto curve = koch_curve(kp);
  if (!curve) return curve.error();
  DividerOptions o;
  o.ruler_min = *rmin * kp.wavelength;
  o.ruler_max = *rmax * kp.wavelength;
  o.rulers = static_cast<int>(*rulers);
  auto fit = divider_dimension(*curve, o);
  if (!fit) return fit.error();
  auto d13 = koch_dimension(kp.alpha);
  if (!d13) return d13.error();
  TaskOutput out;
  auto& s = out.scalars;
  s["dimension"] = fit->dimension;
  s["dimension_eq13"] = *d13;
  s["dimension_minus_eq13"] = fit->dimension - *d13;
  s["r_squared"] = fit->r_squared;
  s["slope"] = fit->slope;
  s["ruler_min_m"] = fit->scale_min;
  s["ruler_max_m"] = fit->scale_max;
  s["points"] = static_cast<double>(curve->size());
  out.arrays["ruler_m"] = fit->scales;
  out.arrays["measured_length_m"] = fit->values;
  return out;
}

}  // namespace frictal::study
