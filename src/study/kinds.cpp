// Task kinds: the registry and the built-in analyses (koch-signature, wm-pair-statistics).
#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/core.h>
#include <fmt/ranges.h>

#include "frictal/fractal.hpp"
#include "frictal/generators.hpp"
#include "frictal/signature.hpp"
#include "frictal/stats.hpp"
#include "frictal/study.hpp"
#include "frictal/surface_spec.hpp"
#include "study/table_params.hpp"

namespace frictal::study {

void TaskRegistry::add(TaskKind kind) {
  unavailable_.erase(kind.name);
  kinds_[kind.name] = std::move(kind);
}
void TaskRegistry::add_unavailable(std::string name, std::string reason, int version) {
  if (kinds_.count(name)) return;
  unavailable_version_[name] = version;
  unavailable_[std::move(name)] = std::move(reason);
}
int TaskRegistry::version(const std::string& name) const {
  if (const TaskKind* k = find(name)) return k->version;
  auto it = unavailable_version_.find(name);
  return it == unavailable_version_.end() ? 0 : it->second;
}
const TaskKind* TaskRegistry::find(const std::string& name) const {
  auto it = kinds_.find(name);
  return it == kinds_.end() ? nullptr : &it->second;
}
std::string TaskRegistry::unavailable_reason(const std::string& name) const {
  auto it = unavailable_.find(name);
  if (it == unavailable_.end()) return {};
  return fmt::format("task kind '{}' is not available in this build ({})", name, it->second);
}
std::vector<std::string> TaskRegistry::names() const {
  std::vector<std::string> n;
  for (const auto& [k, v] : kinds_) n.push_back(k);
  return n;
}

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

/// Length-weighted standard deviation of edge slope angles of a profile (unit: rad).
double slope_angle_std(const Profile& p) {
  double w = 0, m = 0;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const double dx = p.x[i + 1] - p.x[i];
    if (dx <= 0) continue;
    w += dx;
    m += dx * std::atan((p.z[i + 1] - p.z[i]) / dx);
  }
  if (w <= 0) return 0;
  m /= w;
  double v = 0;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const double dx = p.x[i + 1] - p.x[i];
    if (dx <= 0) continue;
    const double d = std::atan((p.z[i + 1] - p.z[i]) / dx) - m;
    v += dx * d * d;
  }
  return std::sqrt(v / w);
}

void put_pdf(TaskOutput& out, const std::string& prefix, const Histogram& h) {
  std::vector<double> edges, dens;
  for (double e : h.edges) edges.push_back(e / kDeg);
  for (double d : h.density) dens.push_back(d * kDeg);
  out.arrays[prefix + "_edges_deg"] = std::move(edges);
  out.arrays[prefix + "_density_per_deg"] = std::move(dens);
}

SlopeMethod slope_method(const std::string& s, Status* st) {
  if (s == "exact") return SlopeMethod::Exact;
  if (s == "spline") return SlopeMethod::Spline;
  *st = make_error(fmt::format("parameter 'slopes': expected \"exact\" or \"spline\", got \"{}\"", s));
  return SlopeMethod::Exact;
}

template <class T>
bool take(Result<T> r, T& into, Error& err) {
  if (!r) {
    err = r.error();
    return false;
  }
  into = *r;
  return true;
}

}  // namespace

Result<TaskOutput> run_koch_signature(const Params& p, std::uint64_t /*seed: deterministic surfaces*/) {
  Error err;
  std::int64_t offsets = 0;
  double mu_a = 0;
  std::string slopes;
  if (!take(get_real(p, "atomic_friction", 0.0), mu_a, err) || !take(get_int(p, "offsets", 0), offsets, err) ||
      !take(get_string(p, "slopes", "exact"), slopes, err))
    return err;
  if (offsets < 0) return make_error("parameter 'offsets': expected >= 0");
  // iterations, alpha (deg), wavelength, length: the koch generator's table.
  if (Status st = only_known_parameters(p, {&find_generator("koch")->fields}, {"atomic_friction", "offsets", "slopes"},
                                        "koch-signature");
      !st)
    return st.error();
  auto koch_values = table_values(find_generator("koch")->fields, p);
  if (!koch_values) return koch_values.error();
  if (auto it = koch_values->find("iterations"); it != koch_values->end() && std::get<std::int64_t>(it->second) > 8)
    return make_error(fmt::format("parameter 'iterations': expected 0..8, got {}", std::get<std::int64_t>(it->second)));
  auto spec = make_surface_spec("koch", *koch_values);
  if (!spec) return spec.error();
  auto kpr = koch_params(*spec);
  if (!kpr) return kpr.error();
  const KochParams kp = *kpr;
  const double wavelength = kp.wavelength;
  auto prof = koch_profile(kp);
  if (!prof) return prof.error();
  SignatureOptions o;
  Status st = Ok{};
  o.slopes = slope_method(slopes, &st);
  if (!st) return st.error();
  o.threads = 1;
  o.keep_contacts = false;
  o.offsets = static_cast<std::size_t>(offsets);
  auto sig = self_signature(*prof, o);
  if (!sig) return sig.error();
  const SignatureResult& r = *sig;
  auto fr = predict_friction(mu_a, r.theta_max_forward, r.contact_slope_std);
  if (!fr) return fr.error();
  const ProfileStats ps = profile_stats(*prof);
  TaskOutput out;
  auto& s = out.scalars;
  s["theta_max_forward_deg"] = r.theta_max_forward / kDeg;
  s["theta_max_backward_deg"] = r.theta_max_backward / kDeg;
  s["theta_max_over_alpha"] = r.theta_max_forward / kp.alpha;
  s["surface_slope_max_deg"] = ps.max_slope / kDeg;
  s["surface_slope_max_over_alpha"] = ps.max_slope / kp.alpha;
  s["contact_slope_mean_deg"] = r.contact_slope_mean / kDeg;
  s["contact_slope_std_deg"] = r.contact_slope_std / kDeg;
  s["atomic_friction_angle_deg"] = fr->atomic_angle / kDeg;
  s["friction_angle_deg"] = fr->friction_angle / kDeg;
  s["friction_coefficient"] = fr->friction_coefficient;
  auto d13 = koch_dimension(kp.alpha);
  if (!d13) return d13.error();
  s["dimension_eq13"] = *d13;
  s["points"] = static_cast<double>(prof->size());
  s["offsets"] = static_cast<double>(r.offset.size());
  s["events"] = static_cast<double>(r.events);
  std::vector<double> xo, th;
  xo.reserve(r.offset.size());
  th.reserve(r.offset.size());
  for (std::size_t i = 0; i < r.offset.size(); ++i) {
    xo.push_back((r.offset[i] - r.offset.front()) / wavelength);
    th.push_back(r.theta[i] / kp.alpha);
  }
  out.arrays["signature_offset_over_wavelength"] = std::move(xo);
  out.arrays["signature_theta_over_alpha"] = std::move(th);
  return out;
}

Result<TaskOutput> run_wm_pair_statistics(const Params& p, std::uint64_t seed) {
  Error err;
  std::int64_t bins = 0, offsets = 0;
  std::string slopes;
  if (!take(get_string(p, "slopes", "exact"), slopes, err) || !take(get_int(p, "bins", 90), bins, err) ||
      !take(get_int(p, "offsets", 0), offsets, err))
    return err;
  if (bins < 1 || bins > 100000) return make_error("parameter 'bins': expected 1..100000");
  if (offsets < 0) return make_error("parameter 'offsets': expected >= 0");
  // dimension, gamma, n_max, longest_wavelength, length, rms_height, exponent, spacing: the wm
  // generator's table; the phases are always random, from the task seed.
  if (Status st = only_known_parameters(p, {&find_generator("wm")->fields}, {"pair", "slopes", "bins", "offsets"},
                                        "wm-pair-statistics");
      !st)
    return st.error();
  auto wm_values = table_values(find_generator("wm")->fields, p);
  if (!wm_values) return wm_values.error();
  wm_values->erase("seed");
  wm_values->erase("stochastic");
  auto spec = make_surface_spec("wm", *wm_values);
  if (!spec) return spec.error();
  auto wp = wm_params(*spec);
  if (!wp) return wp.error();
  WmParams w = *wp;
  w.stochastic = true;
  // The pair shares every parameter but the phases: two streams of the task seed.
  w.seed = derive_seed(seed, 1);
  auto lower = wm_profile(w);
  if (!lower) return lower.error();
  w.seed = derive_seed(seed, 2);
  auto upper = wm_profile(w);
  if (!upper) return upper.error();
  SignatureOptions o;
  Status st = Ok{};
  o.slopes = slope_method(slopes, &st);
  if (!st) return st.error();
  o.threads = 1;
  o.keep_contacts = false;
  o.bins = static_cast<int>(bins);
  o.offsets = static_cast<std::size_t>(offsets);
  auto sig = signature(*lower, rotate180(*upper), o);
  if (!sig) return sig.error();
  const SignatureResult& r = *sig;
  const ProfileStats sl = profile_stats(*lower), su = profile_stats(*upper);
  const double fwd = r.theta_max_forward, bwd = r.theta_max_backward;
  TaskOutput out;
  auto& s = out.scalars;
  const double cmax = std::max(fwd, bwd);
  const double smax = std::max(sl.max_slope, su.max_slope);
  s["theta_max_forward_deg"] = fwd / kDeg;
  s["theta_max_backward_deg"] = bwd / kDeg;
  s["contact_slope_max_deg"] = cmax / kDeg;
  s["tan_contact_slope_max"] = std::tan(cmax);
  s["contact_slope_mean_deg"] = r.contact_slope_mean / kDeg;
  s["contact_slope_std_deg"] = r.contact_slope_std / kDeg;
  s["surface_slope_max_deg"] = smax / kDeg;
  s["tan_surface_slope_max"] = std::tan(smax);
  s["surface_slope_max_lower_deg"] = sl.max_slope / kDeg;
  s["surface_slope_max_upper_deg"] = su.max_slope / kDeg;
  s["surface_slope_std_deg"] = slope_angle_std(*upper) / kDeg;
  s["surface_slope_std_lower_deg"] = slope_angle_std(*lower) / kDeg;
  s["surface_rms_slope"] = su.rms_slope;
  s["points"] = static_cast<double>(lower->size());
  s["offsets"] = static_cast<double>(r.offset.size());
  s["events"] = static_cast<double>(r.events);
  put_pdf(out, "contact_slope_pdf", r.contact_slope_pdf);
  put_pdf(out, "surface_slope_pdf", slope_distribution(*upper, static_cast<int>(bins)));
  return out;
}

TaskRegistry default_registry() {
  TaskRegistry r;
  r.add({"koch-signature",
         "Self-signature of a Koch surface K_n (Sec. III): theta_max/alpha, friction angle, Eq. 13 dimension", 1,
         run_koch_signature});
  r.add({"wm-pair-statistics",
         "A pair of stochastic WM profiles (Sec. V): max/std of contact and surface slopes, slope PDFs", 2,
         run_wm_pair_statistics});
  r.add({"tilt", "Spheropolygon tilting-block test of a Koch pair (Sec. IV): friction angle, Fig. 7 series", 1,
         run_tilt_task});
  r.add({"divider", "Divider (ruler) method on a Koch curve K_n (Sec. IV C 3): L(eps), D = 1 - slope, Eq. 13", 1,
         run_divider_task});
  return r;
}

}  // namespace frictal::study
