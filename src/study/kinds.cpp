// Two task kinds on the signature function, each one unit (compute function, outputs, report
// section with the paper's findings, plot views): koch-signature (Sec. III, Fig. 4, 6, 8, 10) and
// wm-pair-statistics (Sec. V, Fig. 14-18). Registered in registry.cpp.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

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

// ---------------------------------------------------------------- report sections

namespace {

struct Cell {
  double sum = 0;
  int n = 0;
  double max = -INFINITY;
  void add(double v) {
    if (!std::isfinite(v)) return;
    sum += v;
    ++n;
    max = std::max(max, v);
  }
  double mean() const { return n ? sum / n : std::nan(""); }
};

using Grid = std::map<double, std::map<int, Cell>>;  // D -> n_max -> cell

std::string table(const std::string& title, const Grid& g, const std::set<int>& ns, int decimals) {
  std::string s = fmt::format("\n{}\n\n| D \\ n_max |", title);
  for (int n : ns) s += fmt::format(" {} |", n);
  s += "\n|---|";
  for (std::size_t i = 0; i < ns.size(); ++i) s += "---|";
  s += "\n";
  for (const auto& [D, row] : g) {
    s += fmt::format("| {:.2f} |", D);
    for (int n : ns) {
      auto it = row.find(n);
      s += it == row.end() ? " |" : fmt::format(" {:.{}f} |", it->second.mean(), decimals);
    }
    s += "\n";
  }
  return s;
}

void wm_part(const std::string& part, const std::vector<Store::Row>& rows, Report& rep) {
  Grid tc, ts, sc, ss;  // tan contact max, tan surface max, std contact, std surface (deg)
  std::set<int> ns;
  std::size_t tasks = 0, below = 0, equal = 0, above = 0;
  double worst_excess = 0;
  for (const auto& r : rows) {
    if (!r.params.count("dimension") || !r.params.count("n_max")) continue;
    const auto& s = r.output.scalars;
    if (!s.count("tan_contact_slope_max") || !s.count("tan_surface_slope_max")) continue;
    const double D = as_number(r.params.at("dimension"));
    const int n = as_int(r.params.at("n_max"));
    ns.insert(n);
    const double c = s.at("tan_contact_slope_max"), f = s.at("tan_surface_slope_max");
    tc[D][n].add(c);
    ts[D][n].add(f);
    sc[D][n].add(s.at("contact_slope_std_deg"));
    ss[D][n].add(s.at("surface_slope_std_deg"));
    ++tasks;
    const double tol = 1e-9 * std::max(1.0, f);
    if (c < f - tol)
      ++below;
    else if (c <= f + tol)
      ++equal;
    else {
      ++above;
      worst_excess = std::max(worst_excess, c / f - 1);
    }
  }
  if (!tasks) return;
  const int nmin = *ns.begin(), nmax = *ns.rbegin();
  rep.lines.push_back(fmt::format("\n## Part '{}' (wm-pair-statistics): {} pairs, {} values of D, n_max {}..{}", part,
                                  tasks, tc.size(), nmin, nmax));
  rep.lines.push_back(table("Mean over pairs of tan(theta_max,contact) (Fig. 14c-d, 15):", tc, ns, 4));
  rep.lines.push_back(table("Mean over pairs of tan(theta_max,surface) (Fig. 14a-b, 15):", ts, ns, 4));
  rep.lines.push_back(table("Mean over pairs of sigma_contact slope, deg (Fig. 17c-d, 18):", sc, ns, 3));
  rep.lines.push_back(table("Mean over pairs of sigma_surface slope, deg (Fig. 17a-b, 18):", ss, ns, 3));

  // F1: contact below surface.
  {
    Finding f;
    f.claim = fmt::format(
        "Part '{}': the maximum contact slope is smaller than the maximum surface slope (Sec. V.C, "
        "Fig. 15).",
        part);
    f.supported = above == 0 && below > 0;
    f.evidence.push_back(
        fmt::format("criterion: tan(theta_max,contact) <= tan(theta_max,surface) for every pair; "
                    "{} of {} pairs strictly below, {} equal (within 1e-9), {} above{}",
                    below, tasks, equal, above, above ? fmt::format(" (worst by {:.3g}%)", 100 * worst_excess) : ""));
    if (ns.count(0))
      f.evidence.push_back(
          "n_max = 0: both faces are single cosines of one wavelength, which mate exactly, so the contact "
          "slope equals the surface slope there");
    std::string ratios = "mean contact/surface at n_max = " + std::to_string(nmax) + ":";
    for (const auto& [D, row] : tc)
      if (row.count(nmax))
        ratios += fmt::format(" D={:.1f}: {:.3f}", D, row.at(nmax).mean() / ts.at(D).at(nmax).mean());
    f.evidence.push_back(ratios);
    rep.findings.push_back(f);
  }
  // F2: rise with D at the largest n_max.
  {
    Finding f;
    f.claim =
        fmt::format("Part '{}': maximum contact and surface slopes increase with D (n_max = {}; Fig. 15).", part, nmax);
    int up_c = 0, up_s = 0, steps = 0;
    double prev_c = NAN, prev_s = NAN;
    std::string vals;
    for (const auto& [D, row] : tc) {
      if (!row.count(nmax)) continue;
      const double c = row.at(nmax).mean(), s = ts.at(D).at(nmax).mean();
      if (std::isfinite(prev_c)) {
        ++steps;
        up_c += c > prev_c;
        up_s += s > prev_s;
      }
      prev_c = c;
      prev_s = s;
      vals += fmt::format(" D={:.1f}: {:.4f}/{:.4f}", D, c, s);
    }
    f.supported = steps > 0 && up_c == steps && up_s == steps;
    f.evidence.push_back(
        fmt::format("criterion: every step in D raises the pair-mean; contact rises in {} of {} steps, "
                    "surface in {} of {}",
                    up_c, steps, up_s, steps));
    f.evidence.push_back("tan contact / tan surface:" + vals);
    rep.findings.push_back(f);
  }
  // F3: rise with n_max for every D.
  if (ns.size() >= 2) {
    Finding f;
    f.claim = fmt::format(
        "Part '{}': maximum contact and surface slopes increase with n_max (finer wavelengths; "
        "Fig. 14).",
        part);
    int ok = 0, rows_n = 0, dips = 0, steps = 0;
    double worst_dip = 0, dip_dmax = -1;
    std::string vals;
    for (const auto& [D, row] : tc) {
      if (!row.count(nmin) || !row.count(nmax) || nmin == nmax) continue;
      ++rows_n;
      const bool rc = row.at(nmax).mean() > row.at(nmin).mean(),
                 rs = ts.at(D).at(nmax).mean() > ts.at(D).at(nmin).mean();
      ok += rc && rs;
      double prev = NAN;
      for (const auto& [n, cell] : row) {
        if (std::isfinite(prev)) {
          ++steps;
          if (cell.mean() < prev) {
            ++dips;
            worst_dip = std::max(worst_dip, 1 - cell.mean() / prev);
            dip_dmax = std::max(dip_dmax, D);
          }
        }
        prev = cell.mean();
      }
      vals += fmt::format(" D={:.1f}: {:.4f}->{:.4f}", D, row.at(nmin).mean(), row.at(nmax).mean());
    }
    f.supported = rows_n > 0 && ok == rows_n;
    f.evidence.push_back(
        fmt::format("criterion: for every D the pair-mean at n_max = {} exceeds that at n_max = {}, for "
                    "contact and surface; holds for {} of {} values of D",
                    nmax, nmin, ok, rows_n));
    f.evidence.push_back(
        fmt::format("contact slope step by step: {} of {} steps in n_max go down{}", dips, steps,
                    dips ? fmt::format(" (largest dip {:.2f}%, all at D <= {:.1f}, where the values level "
                                       "off: see the next finding)",
                                       100 * worst_dip, dip_dmax)
                         : ""));
    f.evidence.push_back("tan contact, n_max min -> max:" + vals);
    rep.findings.push_back(f);
  }
  // F4: finite for D < 1.5, growing for D > 1.5.
  if (ns.size() >= 3) {
    Finding f;
    f.claim = fmt::format(
        "Part '{}': as n_max grows the contact slope tends to a finite value for D < 1.5 and keeps "
        "growing for D > 1.5 (Sec. V.C, VI).",
        part);
    // Two equal windows of n_max ending at nmax: [a, b] and [b, nmax].
    std::vector<int> nv(ns.begin(), ns.end());
    const int b = nv[nv.size() / 2];
    int a = nmin;
    for (int n : nv)
      if (b - n <= nmax - b && n <= b) {
        a = n;
        break;
      }
    f.evidence.push_back(fmt::format(
        "criterion: q = [c({}) - c({})] / [c({}) - c({})], the late increment of the pair-mean tan contact slope over "
        "the earlier one; a convergent sequence has q < 1 (shrinking increments), geometric growth q > 1. "
        "Printed Eq. 14 predicts per-step slope growth gamma^(2D-3): < 1 (convergent) below D = 1.5, > 1 above.",
        nmax, b, b, a));
    bool ok = true;
    int below = 0, above = 0;
    std::string vals;
    for (const auto& [D, row] : tc) {
      if (!row.count(a) || !row.count(b) || !row.count(nmax)) continue;
      const double ca = row.at(a).mean(), cb = row.at(b).mean(), cn = row.at(nmax).mean();
      const double d1 = cb - ca, d2 = cn - cb, q = d2 / d1;
      std::string extra;
      if (D < 1.5 - 1e-9) {
        ++below;
        ok = ok && q < 1;
        if (q < 1 && q > -1) extra = fmt::format(", limit ~ {:.4f} (geometric extrapolation)", cn + d2 * q / (1 - q));
      } else if (D > 1.5 + 1e-9) {
        ++above;
        ok = ok && q > 1;
      }
      vals += fmt::format("\n      D={:.1f}: c = {:.4f}, {:.4f}, {:.4f}; q = {:.3f}{}", D, ca, cb, cn, q, extra);
    }
    f.supported = ok && below > 0 && above > 0;
    f.evidence.push_back(fmt::format("n_max windows {}->{} and {}->{}:{}", a, b, b, nmax, vals));
    if (below == 0 || above == 0) f.evidence.push_back("needs values of D on both sides of 1.5");
    rep.findings.push_back(f);
  }
  // F5: standard deviations grow with D, fastest above 1.5.
  {
    Finding f;
    f.claim = fmt::format(
        "Part '{}': the standard deviations of contact and surface slopes grow with D, increasingly "
        "fast above D ~ 1.5 (n_max = {}; Fig. 17-18).",
        part, nmax);
    int up = 0, steps = 0;
    double prev = NAN, lo_gain = 0, hi_gain = 0;
    std::string vals;
    for (const auto& [D, row] : sc) {
      if (!row.count(nmax)) continue;
      const double v = row.at(nmax).mean(), w = ss.at(D).at(nmax).mean();
      if (std::isfinite(prev)) {
        ++steps;
        up += v > prev;
        (D <= 1.5 + 1e-9 ? lo_gain : hi_gain) += v - prev;
      }
      prev = v;
      vals += fmt::format(" D={:.1f}: {:.3f}/{:.3f}", D, v, w);
    }
    f.supported = steps > 0 && up == steps && hi_gain > lo_gain;
    f.evidence.push_back(
        fmt::format("criterion: sigma_contact rises at every step in D ({} of {}) and gains more above "
                    "D = 1.5 ({:.3f} deg) than up to 1.5 ({:.3f} deg)",
                    up, steps, hi_gain, lo_gain));
    f.evidence.push_back("sigma contact / sigma surface (deg):" + vals);
    rep.findings.push_back(f);
  }
}

void koch_part(const std::string& part, const std::vector<Store::Row>& rows, Report& rep) {
  std::map<int, std::map<double, double>> ratio, phi, mu, dim, phi0;  // iterations -> alpha -> value
  std::set<double> mus;
  for (const auto& r : rows) {
    if (!r.params.count("iterations") || !r.params.count("alpha")) continue;
    const int n = as_int(r.params.at("iterations"));
    const double a = as_number(r.params.at("alpha"));
    const double ma = r.params.count("atomic_friction") ? as_number(r.params.at("atomic_friction")) : 0.0;
    mus.insert(ma);
    if (ma == 0) {
      ratio[n][a] = r.output.scalars.at("theta_max_over_alpha");
      mu[n][a] = r.output.scalars.at("friction_coefficient");
      dim[n][a] = r.output.scalars.at("dimension_eq13");
      phi0[n][a] = r.output.scalars.at("friction_angle_deg");
    }
    phi[n][a] = r.output.scalars.at("friction_angle_deg");
  }
  if (ratio.empty()) return;
  rep.lines.push_back(fmt::format("\n## Part '{}' (koch-signature): {} tasks", part, rows.size()));
  std::string t = "\n| K_n | alpha (deg) | theta_max/alpha | mu (mu_a = 0) | D (Eq. 13) |\n|---|---|---|---|---|\n";
  for (const auto& [n, m] : ratio)
    for (const auto& [a, v] : m)
      t += fmt::format("| K{} | {:g} | {:.6f} | {:.4f} | {:.4f} |\n", n, a, v, mu[n][a], dim[n][a]);
  rep.lines.push_back(t);
  const int expect[] = {1, 1, 2, 3};
  Finding f;
  f.claim = fmt::format(
      "Part '{}': the signature maxima of Koch surfaces K0, K1, K2, K3 are 1, 1, 2, 3 times alpha "
      "(Sec. III, Fig. 4, 6).",
      part);
  bool ok = true;
  int checked = 0;
  double worst = 0;
  for (const auto& [n, m] : ratio) {
    if (n > 3) continue;
    for (const auto& [a, v] : m) {
      ++checked;
      worst = std::max(worst, std::abs(v - expect[n]));
      ok = ok && std::abs(v - expect[n]) < 1e-6;
    }
  }
  f.supported = ok && checked > 0;
  f.evidence.push_back(fmt::format(
      "criterion: |theta_max/alpha - n| < 1e-6 for {} (K_n, alpha) tasks; largest deviation {:.2e}", checked, worst));
  rep.findings.push_back(f);
  // mu grows with D (Fig. 10) at each iteration count, over alpha (D from Eq. 13 grows with alpha).
  Finding g;
  g.claim = fmt::format(
      "Part '{}': the friction coefficient grows with the fractal dimension of the Koch surface "
      "(Fig. 10).",
      part);
  int up = 0, steps = 0;
  for (const auto& [n, m] : phi0) {  // mu = tan(phi) is monotone in phi; phi stays finite at 90 deg
    double prev = NAN;
    for (const auto& [a, v] : m) {
      if (std::isfinite(prev)) ++steps, up += v > prev;
      prev = v;
    }
  }
  g.supported = steps > 0 && up == steps;
  g.evidence.push_back(
      fmt::format("criterion: at fixed K_n, phi = theta_max (mu = tan phi) rises with alpha, hence with D "
                  "from Eq. 13; rises in {} of {} steps",
                  up, steps));
  if (steps > 0) rep.findings.push_back(g);
  if (mus.size() > 1) {
    Finding h;
    h.claim = fmt::format(
        "Part '{}': phi - n alpha = theta_a, the atomic friction angle adds to the signature maximum "
        "(Eq. 6, Fig. 8).",
        part);
    double worst_h = 0;
    int cnt = 0;
    for (const auto& r : rows) {
      const int n = as_int(r.params.at("iterations"));
      if (n > 3) continue;
      const double a = as_number(r.params.at("alpha"));
      const double ma = r.params.count("atomic_friction") ? as_number(r.params.at("atomic_friction")) : 0.0;
      const double expect_phi = std::min(90.0, a * expect[n] + std::atan(ma) * 180 / std::numbers::pi);
      worst_h = std::max(worst_h, std::abs(r.output.scalars.at("friction_angle_deg") - expect_phi));
      ++cnt;
    }
    h.supported = worst_h < 1e-6;
    h.evidence.push_back(fmt::format(
        "criterion: |phi - (n alpha + atan mu_a)| < 1e-6 deg over {} tasks; largest {:.2e} deg", cnt, worst_h));
    rep.findings.push_back(h);
  }
}

/// wm-pair-statistics: pairs are pooled over `pair` only; other axes make variants.
void wm_section(const std::string& part, const std::vector<TaskRow>& rows, Report& rep) {
  // Pairs are pooled over `pair` only: other axes (e.g. slopes = ["exact", "spline"]) are
  // analysed as separate variants.
  std::map<std::string, std::vector<Store::Row>> variants;
  std::map<std::string, Params> rests;
  for (const auto& row : rows) {
    Params rest = row.params;
    for (const char* k : {"dimension", "n_max", "pair"}) rest.erase(k);
    const std::string key = canonical(rest);
    rests[key] = rest;
    variants[key].push_back(row);
  }
  // Label a variant by the parameters that differ between variants, e.g. "wm [slopes=spline]".
  std::set<std::string> differing;
  for (const auto& [key, rest] : rests)
    for (const auto& [name, v] : rest)
      for (const auto& [key2, rest2] : rests)
        if (!rest2.count(name) || canonical(rest2.at(name)) != canonical(v)) differing.insert(name);
  for (const auto& [key, vrows] : variants) {
    std::string label = part;
    if (variants.size() > 1) {
      std::string d;
      for (const auto& name : differing) {
        if (!d.empty()) d += ", ";
        const Value& v = rests[key].at(name);
        d += name + "=" + (std::holds_alternative<std::string>(v) ? std::get<std::string>(v) : canonical(v));
      }
      label += " [" + d + "]";
    }
    wm_part(label, vrows, rep);
  }
}

}  // namespace

// ---------------------------------------------------------------- the two kinds

TaskKind koch_signature_kind() {
  TaskKind k;
  k.name = "koch-signature";
  k.description = "Self-signature of a Koch surface K_n (Sec. III): theta_max/alpha, friction angle, Eq. 13 dimension";
  k.version = 1;
  k.run = run_koch_signature;
  k.outputs = {
      {"theta_max_forward_deg", "deg", "maximum contact slope resisting sliding towards +x"},
      {"theta_max_backward_deg", "deg", "maximum contact slope resisting sliding towards -x"},
      {"theta_max_over_alpha", "1", "theta_max / alpha (1, 1, 2, 3 for K0..K3)"},
      {"surface_slope_max_deg", "deg", "steepest edge of the profile"},
      {"surface_slope_max_over_alpha", "1", "steepest edge / alpha (n + 1 for K_n)"},
      {"contact_slope_mean_deg", "deg", "mean contact slope"},
      {"contact_slope_std_deg", "deg", "standard deviation of contact slopes (sigma of Eq. 18)"},
      {"atomic_friction_angle_deg", "deg", "atan(mu_a)"},
      {"friction_angle_deg", "deg", "phi = atan(mu_a) + theta_max (Eq. 6), capped at 90"},
      {"friction_coefficient", "1", "tan(phi); NaN when phi = 90 deg"},
      {"dimension_eq13", "1", "fractal dimension of Eq. 13"},
      {"points", "1", "profile points"},
      {"offsets", "1", "offsets evaluated"},
      {"events", "1", "event offsets"},
      {"signature_offset_over_wavelength", "1", "offset / lambda (Fig. 4)", true},
      {"signature_theta_over_alpha", "1", "theta / alpha at each offset (Fig. 4)", true},
  };
  k.report = koch_part;
  PlotView v;
  v.id = "friction-vs-alpha";
  v.x = {"alpha", "α (deg)"};
  v.y = {"friction_angle_deg", "friction angle φ (deg)"};
  v.series = "iterations";
  v.label = "K{iterations} theory (signature)";
  k.plots.push_back(v);
  v = {};
  v.id = "friction-vs-atomic-friction";
  v.x = {"atomic_friction_angle_deg", "θ_a (deg)"};
  v.y = {"friction_angle_deg", "φ (deg)"};
  v.series = "alpha";
  v.label = "theory α = {alpha}°";
  k.plots.push_back(v);
  v = {};
  v.id = "mu-vs-dimension";
  v.x = {"dimension_eq13", "fractal dimension D (Eq. 13)"};
  v.y = {"friction_coefficient", "μ"};
  v.series = "iterations";
  v.label = "K{iterations} theory";
  k.plots.push_back(v);
  v = {};
  v.id = "signature";
  v.x = {"signature_offset_over_wavelength", "x_ofs / λ"};
  v.y = {"signature_theta_over_alpha", "θ / α"};
  v.series = "task";
  v.label = "K{iterations}";
  k.plots.push_back(v);
  return k;
}

TaskKind wm_pair_statistics_kind() {
  TaskKind k;
  k.name = "wm-pair-statistics";
  k.description = "A pair of stochastic WM profiles (Sec. V): max/std of contact and surface slopes, slope PDFs";
  k.version = 2;
  k.run = run_wm_pair_statistics;
  k.outputs = {
      {"theta_max_forward_deg", "deg", "maximum contact slope towards +x"},
      {"theta_max_backward_deg", "deg", "maximum contact slope towards -x"},
      {"contact_slope_max_deg", "deg", "max(theta_max_forward, theta_max_backward)"},
      {"tan_contact_slope_max", "1", "tan of contact_slope_max"},
      {"contact_slope_mean_deg", "deg", "mean contact slope"},
      {"contact_slope_std_deg", "deg", "standard deviation of contact slopes (sigma of Eq. 18)"},
      {"surface_slope_max_deg", "deg", "steepest edge of both profiles"},
      {"tan_surface_slope_max", "1", "tan of surface_slope_max"},
      {"surface_slope_max_lower_deg", "deg", "steepest edge of the lower profile"},
      {"surface_slope_max_upper_deg", "deg", "steepest edge of the upper profile"},
      {"surface_slope_std_deg", "deg", "length-weighted std of the upper profile's edge angles"},
      {"surface_slope_std_lower_deg", "deg", "the same of the lower profile"},
      {"surface_rms_slope", "1", "rms slope of the upper profile"},
      {"points", "1", "points of each profile"},
      {"offsets", "1", "offsets evaluated"},
      {"events", "1", "event offsets"},
      {"contact_slope_pdf_edges_deg", "deg", "contact slope PDF bin edges (Fig. 16)", true},
      {"contact_slope_pdf_density_per_deg", "1/deg", "contact slope PDF density", true},
      {"surface_slope_pdf_edges_deg", "deg", "surface slope PDF bin edges (upper profile)", true},
      {"surface_slope_pdf_density_per_deg", "1/deg", "surface slope PDF density", true},
  };
  k.report = wm_section;
  // Fig. 14/17 (against n_max, one series per D) and Fig. 15/18 (against D): means over pairs.
  struct Y {
    const char* id;
    const char* column;
    const char* label;
  };
  for (const Y& y : {Y{"surface-slope-max", "tan_surface_slope_max", "tan θ_max"},
                     Y{"contact-slope-max", "tan_contact_slope_max", "tan θ_max"},
                     Y{"surface-slope-std", "surface_slope_std_deg", "σ (deg)"},
                     Y{"contact-slope-std", "contact_slope_std_deg", "σ (deg)"}}) {
    PlotView v;
    v.id = std::string(y.id) + "-vs-n_max";
    v.x = {"n_max", "n_max"};
    v.y = {y.column, y.label};
    v.series = "dimension";
    v.label = "D = {dimension}";
    v.marker = "o";
    v.marker_size = 3;
    v.line_width = 1;
    v.average_over = "pair";
    k.plots.push_back(v);
    v = {};
    v.id = std::string(y.id) + "-vs-dimension";
    v.x = {"dimension", "D"};
    v.y = {y.column, y.label};
    v.label = std::string(y.id).rfind("surface", 0) == 0 ? "surface slope" : "contact slope";
    v.marker = std::string(y.id).rfind("surface", 0) == 0 ? "s" : "o";
    v.average_over = "pair";
    k.plots.push_back(v);
  }
  return k;
}

}  // namespace frictal::study
