// Private: helpers shared by the task kinds on the signature function (kind_koch_signature.cpp,
// kind_wm_pair_statistics.cpp; the others use number()): slope statistics of a profile, PDFs in
// degrees, parameter parsing.
#pragma once

#include <cmath>
#include <string>

#include <fmt/core.h>

#include "frictal/signature.hpp"
#include "frictal/stats.hpp"
#include "frictal/study.hpp"
#include "frictal/units.hpp"

namespace frictal::study::kind_detail {

constexpr double kDeg = units::kRadPerDeg;

/// Length-weighted standard deviation of edge slope angles of a profile (unit: rad).
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

}  // namespace frictal::study::kind_detail
