// Private: helpers shared by the task kinds on the signature function (kind_koch_signature.cpp,
// kind_wm_pair_statistics.cpp; the others use number()): slope statistics of a profile, PDFs in
// degrees, parameter parsing.
#pragma once

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <fmt/core.h>

#include "frictal/signature.hpp"
#include "frictal/stats.hpp"
#include "frictal/study.hpp"
#include "frictal/tilt.hpp"
#include "frictal/units.hpp"

namespace frictal::study::kind_detail {

constexpr double kDeg = units::kRadPerDeg;

/// Length-weighted standard deviation of edge slope angles of a profile (unit: rad).
// The tilt kinds' warning columns: warning_<code> (code with '-' as '_') is 1 if the run gave
// that warning (TiltResult::warnings), else 0.
inline void put_tilt_warnings(std::map<std::string, double>& s, const TiltResult& r) {
  for (const char* code :
       {"core-overlap", "rounding", "time-step", "unsettled", "rotation", "creep", "unrelaxed", "stiffness"}) {
    std::string key = std::string("warning_") + code;
    std::replace(key.begin(), key.end(), '-', '_');
    s[key] =
        std::any_of(r.warnings.begin(), r.warnings.end(), [&](const Warning& w) { return w.code == code; }) ? 1 : 0;
  }
}

// Their descriptions, in the same order.
inline std::vector<OutputColumn> tilt_warning_columns() {
  return {
      {"warning_core_overlap", "1", "1 if the resting overlap exceeds warn_overlap_fraction r"},
      {"warning_rounding", "1", "1 if the spheropolygon and rigid predictions differ by more than the tolerance"},
      {"warning_time_step", "1", "1 if the time step exceeds warn_time_step_fraction of the contact period"},
      {"warning_unsettled", "1", "1 if the block still moved faster than stick_speed when the tilt started"},
      {"warning_rotation", "1", "1 if the upper block rotated by more than warn_rotation before the slide"},
      {"warning_creep", "1",
       "1 if the block first slipped (a creep shorter than a tenth of the smallest feature) more than "
       "warn_creep_angle below the friction angle"},
      {"warning_unrelaxed", "1", "1 if a quasi-static relaxation did not reach rest within relax_time"},
      {"warning_stiffness", "1", "1 if check_stiffness: 10 k_n moved the friction angle by more than the tolerance"},
  };
}

inline double slope_angle_std(const Profile& p) {
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

inline void put_pdf(TaskOutput& out, const std::string& prefix, const Histogram& h) {
  std::vector<double> edges, dens;
  for (double e : h.edges) edges.push_back(e / kDeg);
  for (double d : h.density) dens.push_back(d * kDeg);
  out.arrays[prefix + "_edges_deg"] = std::move(edges);
  out.arrays[prefix + "_density_per_deg"] = std::move(dens);
}

inline SlopeMethod slope_method(const std::string& s, Status* st) {
  if (s == "exact") return SlopeMethod::Exact;
  if (s == "spline") return SlopeMethod::Spline;
  *st = make_error(fmt::format("parameter 'slopes': expected \"exact\" or \"spline\", got \"{}\"", s));
  return SlopeMethod::Exact;
}

/// A parameter as a number (for the kinds' cost models): `fallback` when absent or not a number.
inline double number(const Params& p, const std::string& name, double fallback) {
  auto it = p.find(name);
  const double v = it == p.end() ? NAN : as_number(it->second);
  return std::isfinite(v) ? v : fallback;
}

template <class T>
inline bool take(Result<T> r, T& into, Error& err) {
  if (!r) {
    err = r.error();
    return false;
  }
  into = *r;
  return true;
}

/// A part's report rows split into variants: rows whose parameters differ only in `pooled` form
/// one variant (e.g. pairs pooled over pair, D and n_max), in canonical order of the other
/// parameters. Each is labelled by the part name and, when there are several, by the parameters
/// that differ between variants, e.g. "wm [slopes=spline]".
inline std::vector<std::pair<std::string, std::vector<TaskRow>>> variants_of(
    const std::string& part, const std::vector<TaskRow>& rows, std::initializer_list<const char*> pooled) {
  std::map<std::string, std::vector<TaskRow>> variants;
  std::map<std::string, Params> rests;
  for (const auto& row : rows) {
    Params rest = row.params;
    for (const char* k : pooled) rest.erase(k);
    const std::string key = canonical(rest);
    rests[key] = rest;
    variants[key].push_back(row);
  }
  std::set<std::string> differing;
  for (const auto& [key, rest] : rests)
    for (const auto& [name, v] : rest)
      for (const auto& [key2, rest2] : rests)
        if (!rest2.count(name) || canonical(rest2.at(name)) != canonical(v)) differing.insert(name);
  std::vector<std::pair<std::string, std::vector<TaskRow>>> out;
  for (auto& [key, vrows] : variants) {
    std::string label = part;
    if (variants.size() > 1) {
      std::string d;
      for (const auto& name : differing) {
        if (!rests[key].count(name)) continue;
        if (!d.empty()) d += ", ";
        const Value& v = rests[key].at(name);
        d += name + "=" + (std::holds_alternative<std::string>(v) ? std::get<std::string>(v) : canonical(v));
      }
      label += " [" + d + "]";
    }
    out.emplace_back(std::move(label), std::move(vrows));
  }
  return out;
}

/// run_tilt with the retries both tilt kinds use: the engine's stability guard stops a run whose
/// step is too large for its contacts (K3 carries hundreds); retry twice with a step 2.5 times
/// smaller rather than lose the task. `c` keeps the step that was used.
/// The contact passes take up to this many idle cores of the study run besides their own
/// (borrow_idle_threads; results do not depend on it): a K3 block's ~250 hot pairs fill 3 shares
/// of 64 (dem::set_thread_count).
constexpr unsigned kMaxBorrowedCores = 3;
inline Result<TiltResult> run_tilt_retrying(const Curve& lower, const Curve& upper, TiltConfig& c) {
  // Cores that the study's other compute threads leave idle (fewer tasks than threads remain):
  // asked for before the first step and every 4096 steps (TiltConfig::thread_budget), kept until
  // the task ends.
  struct Borrowed {  // given back however the task ends
    unsigned n = 0;
    ~Borrowed() { return_idle_threads(n); }
  } borrowed;
  c.thread_budget = [&borrowed](unsigned) {
    if (borrowed.n < kMaxBorrowedCores) borrowed.n += borrow_idle_threads(kMaxBorrowedCores - borrowed.n);
    return 1 + borrowed.n;
  };
  auto r = run_tilt(lower, upper, c);
  for (int retry = 0; retry < 2 && !r && r.error().code == ErrorCode::Unstable; ++retry) {
    c.time_step /= 2.5;
    r = run_tilt(lower, upper, c);
  }
  c.thread_budget = nullptr;
  return r;
}

/// The tilt kinds take every tilt setting as a parameter except `threads`: the thread count
/// changes no result, so it is not a task parameter (not in the content address); a study run
/// lends its idle cores instead (run_tilt_retrying).
inline Status no_threads_parameter(const Params& p) {
  if (p.count("threads"))
    return make_error(
        "parameter 'threads': not a task parameter (results do not depend on it; a tilt uses the cores that the "
        "study run leaves idle)");
  return Ok{};
}

/// The signature's summary outputs of the kinds that store one (koch-signature,
/// wm-pair-statistics), taken from signature_columns() (events: its Python key).
inline constexpr std::initializer_list<ColumnOutput> kSignatureSummaryOutputs = {"theta_max_forward_deg",
                                                                                 "theta_max_backward_deg",
                                                                                 "contact_slope_mean_deg",
                                                                                 "contact_slope_std_deg",
                                                                                 "offsets",
                                                                                 "events"};

}  // namespace frictal::study::kind_detail
