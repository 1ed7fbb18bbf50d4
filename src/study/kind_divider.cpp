// Task kind 'divider': the divider (ruler) method on a Koch curve (Sec. IV C 3, Fig. 9, 10).
// Parameters: the koch generator's (iterations, alpha in degrees, wavelength, length; here the
// length defaults to 0.01 m), ruler_min_over_wavelength,
// ruler_max_over_wavelength, rulers. Returns D = 1 - slope of log L against log eps with its
// fit quality, the Eq. 13 dimension, and the arrays ruler_m / measured_length_m (Fig. 9).
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include <fmt/core.h>

#include "frictal/fractal.hpp"
#include "frictal/generators.hpp"
#include "frictal/study.hpp"
#include "frictal/surface_spec.hpp"
#include "study/kind_common.hpp"
#include "study/table_params.hpp"

namespace frictal::study {

namespace {

// The fit's outputs, from the dimension table (fractal_fit_columns(): declared once there).
constexpr std::initializer_list<ColumnOutput> kFitOutputs = {
    {"dimension", nullptr, "the divider's, D = 1 - slope of log L against log eps"},
    {"slope", nullptr, "log L against log eps"},
    "r_squared"};

}  // namespace

Result<TaskOutput> run_divider_task(const Params& p, std::uint64_t /*seed: deterministic curve*/) {
  auto rmin = get_real(p, "ruler_min_over_wavelength", 3e-4);
  auto rmax = get_real(p, "ruler_max_over_wavelength", 0.25);
  auto rulers = get_int(p, "rulers", 40);
  if (!rmin) return rmin.error();
  if (!rmax) return rmax.error();
  if (!rulers) return rulers.error();
  if (*rulers < 3 || *rulers > 10000)
    return make_error(fmt::format("parameter 'rulers': expected 3..10000, got {}", *rulers));
  if (Status st =
          only_known_parameters(p, {&find_generator("koch")->fields},
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
  put_outputs(out, fractal_fit_columns(), *fit, kFitOutputs);
  s["dimension_eq13"] = *d13;
  s["dimension_minus_eq13"] = fit->dimension - *d13;
  s["ruler_min_m"] = fit->scale_min;
  s["ruler_max_m"] = fit->scale_max;
  s["points"] = static_cast<double>(curve->size());
  out.arrays["ruler_m"] = fit->scales;
  out.arrays["measured_length_m"] = fit->values;
  return out;
}

// ---------------------------------------------------------------- report section and the kind

namespace {

void divider_part(const std::string& part, const std::vector<Store::Row>& rows, Report& rep) {
  std::map<double, std::map<int, std::pair<double, double>>> by;  // alpha -> n -> (D, D13)
  std::string t =
      "\n| K_n | alpha (deg) | D divider | D Eq. 13 | difference | r^2 | rulers (m) |\n|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    const auto& s = r.output.scalars;
    if (!s.count("dimension") || !s.count("dimension_eq13")) continue;
    const int n = as_int(r.params.at("iterations"));
    const double a = as_number(r.params.at("alpha"));
    by[a][n] = {s.at("dimension"), s.at("dimension_eq13")};
    t += fmt::format("| K{} | {:g} | {:.4f} | {:.4f} | {:+.4f} | {:.5f} | {:.3g} - {:.3g} |\n", n, a, s.at("dimension"),
                     s.at("dimension_eq13"), s.at("dimension_minus_eq13"), s.at("r_squared"), s.at("ruler_min_m"),
                     s.at("ruler_max_m"));
  }
  if (by.empty()) return;
  rep.lines.push_back(fmt::format("\n## Part '{}' (divider): {} curves", part, rows.size()));
  rep.lines.push_back(t);
  Finding f;
  f.claim_id = "divider-dimension";
  f.part = part;
  f.claim = fmt::format(
      "Part '{}': the divider dimension of the most iterated Koch curve agrees with Eq. 13, and "
      "fewer iterations show the same scaling over a narrower range (Sec. IV C 3, Fig. 9).",
      part);
  bool ok = true;
  std::string ev;
  for (const auto& [a, m] : by) {
    const auto& [D, D13] = m.rbegin()->second;
    ok = ok && std::abs(D - D13) <= 0.02;
    double prev = INFINITY;
    for (const auto& [n, v] : m) {
      const double d = std::abs(v.first - v.second);
      if (d > prev + 1e-9) ok = false;
      prev = d;
    }
    ev += fmt::format(" alpha={:g}: K{} D={:.4f} vs Eq. 13 {:.4f};", a, m.rbegin()->first, D, D13);
  }
  f.supported = ok;
  f.evidence.push_back(
      "criterion: |D_divider - D_Eq13| <= 0.02 for the most iterated curve, and |D - D_Eq13| does not grow "
      "with the number of iterations;" +
      ev);
  rep.findings.push_back(f);
}

/// Estimated CPU time (unit: s; TaskKind::cost): proportional to the curve's vertices times the
/// rulers walked along it (measured 2026-11-23).
double divider_cost(const Params& p) {
  using kind_detail::number;
  const double n = std::clamp(number(p, "iterations", 0), 0.0, 10.0);
  const double waves = std::clamp(number(p, "length", 0.01) / std::max(1e-12, number(p, "wavelength", 0.01)), 1.0, 1e6);
  return 1e-3 + 1e-8 * waves * std::pow(4.0, n) * std::max(1.0, number(p, "rulers", 40));
}

}  // namespace

TaskKind divider_kind() {
  TaskKind k;
  k.name = "divider";
  k.description = "Divider (ruler) method on a Koch curve K_n (Sec. IV C 3): L(eps), D = 1 - slope, Eq. 13";
  k.version = 1;
  k.run = run_divider_task;
  k.cost = divider_cost;
  k.uses_seed = false;  // a deterministic curve
  k.outputs = {
      {"dimension_eq13", "1", "fractal dimension of Eq. 13"},
      {"dimension_minus_eq13", "1", "D - D(Eq. 13)"},
      {"ruler_min_m", "m", "smallest ruler"},
      {"ruler_max_m", "m", "largest ruler"},
      {"points", "1", "curve points"},
      {"ruler_m", "m", "rulers eps (Fig. 9)", true},
      {"measured_length_m", "m", "measured length L(eps) (Fig. 9)", true},
  };
  const std::vector<OutputColumn> fit = outputs_of("dimension", fractal_fit_columns(), kFitOutputs);
  k.outputs.insert(k.outputs.end(), fit.begin(), fit.end());
  k.report = divider_part;
  PlotView v = PlotView::of("divider", {"ruler_m", "ruler ε / λ", "wavelength", true},
                            {"measured_length_m", "measured length L / λ", "wavelength", true})
                   .by("task", "K{iterations}: D = {dimension:.4f}")
                   .markers("o", 3, 0.8);
  v.reference = "power:dimension_eq13";
  v.reference_label = "Eq. 13: D = {dimension_eq13:.4f}";
  k.plots.push_back(v);
  return k;
}

}  // namespace frictal::study
