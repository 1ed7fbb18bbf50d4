// Study reports: summary tables and the paper's findings checked against stored results.
//
// For wm-pair-statistics parts (Sec. V.C-D) the pairs of each (D, n_max) are averaged and the
// paper's qualitative claims are tested with explicit criteria (stated in each finding), so a
// reader can see the numbers and judge. For koch-signature parts (Sec. III, IV) the signature
// maxima are compared with n alpha.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include <fmt/core.h>

#include "frictal/study.hpp"

namespace frictal::study {
namespace {

double num(const Value& v) {
  if (auto* d = std::get_if<double>(&v)) return *d;
  if (auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  return std::nan("");
}

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
    const double D = num(r.params.at("dimension"));
    const int n = static_cast<int>(num(r.params.at("n_max")));
    ns.insert(n);
    const double c = s.at("tan_contact_slope_max"), f = s.at("tan_surface_slope_max");
    tc[D][n].add(c);
    ts[D][n].add(f);
    sc[D][n].add(s.at("contact_slope_std_deg"));
    ss[D][n].add(s.at("surface_slope_std_deg"));
    ++tasks;
    const double tol = 1e-9 * std::max(1.0, f);
    if (c < f - tol) ++below;
    else if (c <= f + tol) ++equal;
    else {
      ++above;
      worst_excess = std::max(worst_excess, c / f - 1);
    }
  }
  if (!tasks) return;
  const int nmin = *ns.begin(), nmax = *ns.rbegin();
  rep.lines.push_back(fmt::format("\n## Part '{}' (wm-pair-statistics): {} pairs, {} values of D, n_max {}..{}", part, tasks,
                                  tc.size(), nmin, nmax));
  rep.lines.push_back(table("Mean over pairs of tan(theta_max,contact) (Fig. 14c-d, 15):", tc, ns, 4));
  rep.lines.push_back(table("Mean over pairs of tan(theta_max,surface) (Fig. 14a-b, 15):", ts, ns, 4));
  rep.lines.push_back(table("Mean over pairs of sigma_contact slope, deg (Fig. 17c-d, 18):", sc, ns, 3));
  rep.lines.push_back(table("Mean over pairs of sigma_surface slope, deg (Fig. 17a-b, 18):", ss, ns, 3));

  // F1: contact below surface.
  {
    Finding f;
    f.claim = fmt::format("Part '{}': the maximum contact slope is smaller than the maximum surface slope (Sec. V.C, "
                          "Fig. 15).", part);
    f.supported = above == 0 && below > 0;
    f.evidence.push_back(fmt::format("criterion: tan(theta_max,contact) <= tan(theta_max,surface) for every pair; "
                                     "{} of {} pairs strictly below, {} equal (within 1e-9), {} above{}",
                                     below, tasks, equal, above,
                                     above ? fmt::format(" (worst by {:.3g}%)", 100 * worst_excess) : ""));
    if (ns.count(0))
      f.evidence.push_back("n_max = 0: both faces are single cosines of one wavelength, which mate exactly, so the contact "
                           "slope equals the surface slope there");
    std::string ratios = "mean contact/surface at n_max = " + std::to_string(nmax) + ":";
    for (const auto& [D, row] : tc)
      if (row.count(nmax)) ratios += fmt::format(" D={:.1f}: {:.3f}", D, row.at(nmax).mean() / ts.at(D).at(nmax).mean());
    f.evidence.push_back(ratios);
    rep.findings.push_back(f);
  }
  // F2: rise with D at the largest n_max.
  {
    Finding f;
    f.claim = fmt::format("Part '{}': maximum contact and surface slopes increase with D (n_max = {}; Fig. 15).", part,
                          nmax);
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
    f.evidence.push_back(fmt::format("criterion: every step in D raises the pair-mean; contact rises in {} of {} steps, "
                                     "surface in {} of {}", up_c, steps, up_s, steps));
    f.evidence.push_back("tan contact / tan surface:" + vals);
    rep.findings.push_back(f);
  }
  // F3: rise with n_max for every D.
  if (ns.size() >= 2) {
    Finding f;
    f.claim = fmt::format("Part '{}': maximum contact and surface slopes increase with n_max (finer wavelengths; "
                          "Fig. 14).", part);
    int ok = 0, rows_n = 0, dips = 0, steps = 0;
    double worst_dip = 0, dip_dmax = -1;
    std::string vals;
    for (const auto& [D, row] : tc) {
      if (!row.count(nmin) || !row.count(nmax) || nmin == nmax) continue;
      ++rows_n;
      const bool rc = row.at(nmax).mean() > row.at(nmin).mean(), rs = ts.at(D).at(nmax).mean() > ts.at(D).at(nmin).mean();
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
    f.evidence.push_back(fmt::format("criterion: for every D the pair-mean at n_max = {} exceeds that at n_max = {}, for "
                                     "contact and surface; holds for {} of {} values of D", nmax, nmin, ok, rows_n));
    f.evidence.push_back(fmt::format("contact slope step by step: {} of {} steps in n_max go down{}", dips, steps,
                                     dips ? fmt::format(" (largest dip {:.2f}%, all at D <= {:.1f}, where the values level "
                                                        "off: see the next finding)", 100 * worst_dip, dip_dmax)
                                          : ""));
    f.evidence.push_back("tan contact, n_max min -> max:" + vals);
    rep.findings.push_back(f);
  }
  // F4: finite for D < 1.5, growing for D > 1.5.
  if (ns.size() >= 3) {
    Finding f;
    f.claim = fmt::format("Part '{}': as n_max grows the contact slope tends to a finite value for D < 1.5 and keeps "
                          "growing for D > 1.5 (Sec. V.C, VI).", part);
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
    f.claim = fmt::format("Part '{}': the standard deviations of contact and surface slopes grow with D, increasingly "
                          "fast above D ~ 1.5 (n_max = {}; Fig. 17-18).", part, nmax);
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
    f.evidence.push_back(fmt::format("criterion: sigma_contact rises at every step in D ({} of {}) and gains more above "
                                     "D = 1.5 ({:.3f} deg) than up to 1.5 ({:.3f} deg)", up, steps, hi_gain, lo_gain));
    f.evidence.push_back("sigma contact / sigma surface (deg):" + vals);
    rep.findings.push_back(f);
  }
}

void koch_part(const std::string& part, const std::vector<Store::Row>& rows, Report& rep) {
  std::map<int, std::map<double, double>> ratio, phi, mu, dim, phi0;  // iterations -> alpha -> value
  std::set<double> mus;
  for (const auto& r : rows) {
    if (!r.params.count("iterations") || !r.params.count("alpha")) continue;
    const int n = static_cast<int>(num(r.params.at("iterations")));
    const double a = num(r.params.at("alpha"));
    const double ma = r.params.count("atomic_friction") ? num(r.params.at("atomic_friction")) : 0.0;
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
    for (const auto& [a, v] : m) t += fmt::format("| K{} | {:g} | {:.6f} | {:.4f} | {:.4f} |\n", n, a, v, mu[n][a], dim[n][a]);
  rep.lines.push_back(t);
  const int expect[] = {1, 1, 2, 3};
  Finding f;
  f.claim = fmt::format("Part '{}': the signature maxima of Koch surfaces K0, K1, K2, K3 are 1, 1, 2, 3 times alpha "
                        "(Sec. III, Fig. 4, 6).", part);
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
  f.evidence.push_back(fmt::format("criterion: |theta_max/alpha - n| < 1e-6 for {} (K_n, alpha) tasks; largest deviation {:.2e}",
                                   checked, worst));
  rep.findings.push_back(f);
  // mu grows with D (Fig. 10) at each iteration count, over alpha (D from Eq. 13 grows with alpha).
  Finding g;
  g.claim = fmt::format("Part '{}': the friction coefficient grows with the fractal dimension of the Koch surface "
                        "(Fig. 10).", part);
  int up = 0, steps = 0;
  for (const auto& [n, m] : phi0) {  // mu = tan(phi) is monotone in phi; phi stays finite at 90 deg
    double prev = NAN;
    for (const auto& [a, v] : m) {
      if (std::isfinite(prev)) ++steps, up += v > prev;
      prev = v;
    }
  }
  g.supported = steps > 0 && up == steps;
  g.evidence.push_back(fmt::format("criterion: at fixed K_n, phi = theta_max (mu = tan phi) rises with alpha, hence with D "
                                   "from Eq. 13; rises in {} of {} steps", up, steps));
  if (steps > 0) rep.findings.push_back(g);
  if (mus.size() > 1) {
    Finding h;
    h.claim = fmt::format("Part '{}': phi - n alpha = theta_a, the atomic friction angle adds to the signature maximum "
                          "(Eq. 6, Fig. 8).", part);
    double worst_h = 0;
    int cnt = 0;
    for (const auto& r : rows) {
      const int n = static_cast<int>(num(r.params.at("iterations")));
      if (n > 3) continue;
      const double a = num(r.params.at("alpha"));
      const double ma = r.params.count("atomic_friction") ? num(r.params.at("atomic_friction")) : 0.0;
      const double expect_phi = std::min(90.0, a * expect[n] + std::atan(ma) * 180 / std::numbers::pi);
      worst_h = std::max(worst_h, std::abs(r.output.scalars.at("friction_angle_deg") - expect_phi));
      ++cnt;
    }
    h.supported = worst_h < 1e-6;
    h.evidence.push_back(fmt::format("criterion: |phi - (n alpha + atan mu_a)| < 1e-6 deg over {} tasks; largest {:.2e} deg",
                                     cnt, worst_h));
    rep.findings.push_back(h);
  }
}

void tilt_part(const std::string& part, const std::vector<Store::Row>& rows, Report& rep) {
  if (rows.empty()) return;
  rep.lines.push_back(fmt::format("\n## Part '{}' (tilt): {} simulations", part, rows.size()));
  std::string t = "\n| K_n | alpha (deg) | mu_a | phi simulated (deg) | phi theory (deg) | sim - theory (deg) | "
                  "phi - theta_max (deg) | theta_a (deg) |\n|---|---|---|---|---|---|---|---|\n";
  double worst = 0, worst_a = 0;
  int slid = 0, n = 0;
  std::set<double> mus;
  for (const auto& r : rows) {
    const auto& s = r.output.scalars;
    if (!s.count("friction_angle_deg") || !s.count("predicted_friction_angle_deg")) continue;
    const double ma = r.params.count("atomic_friction") ? num(r.params.at("atomic_friction")) : 0.0;
    mus.insert(ma);
    ++n;
    slid += s.at("slid") > 0;
    const double d = s.at("friction_angle_minus_theory_deg");
    const double da = s.at("phi_minus_theta_max_deg") - s.at("atomic_friction_angle_deg");
    worst = std::max(worst, std::abs(d));
    worst_a = std::max(worst_a, std::abs(da));
    t += fmt::format("| K{} | {:g} | {:g} | {:.3f} | {:.3f} | {:+.3f} | {:.3f} | {:.3f} |\n",
                     static_cast<int>(num(r.params.at("iterations"))), num(r.params.at("alpha")), ma,
                     s.at("friction_angle_deg"), s.at("predicted_friction_angle_deg"), d, s.at("phi_minus_theta_max_deg"),
                     s.at("atomic_friction_angle_deg"));
  }
  rep.lines.push_back(t);
  if (!n) return;
  Finding f;
  f.claim = fmt::format("Part '{}': the simulated friction angle equals the signature prediction theta_max + atan(mu_a) "
                        "(Fig. 6, 8).", part);
  f.supported = slid == n && worst <= 1.0;
  f.evidence.push_back(fmt::format("criterion: every block slid ({} of {}) and |phi_sim - phi_theory| <= 1 deg; largest {:.3f} deg",
                                   slid, n, worst));
  rep.findings.push_back(f);
  if (mus.size() > 1) {
    Finding g;
    g.claim = fmt::format("Part '{}': phi - theta_max = theta_a in simulation, the same for every surface (Fig. 8b).", part);
    g.supported = slid == n && worst_a <= 1.0;
    g.evidence.push_back(fmt::format("criterion: |phi_sim - theta_max - atan(mu_a)| <= 1 deg over {} runs; largest {:.3f} deg",
                                     n, worst_a));
    rep.findings.push_back(g);
  }
}

void divider_part(const std::string& part, const std::vector<Store::Row>& rows, Report& rep) {
  std::map<double, std::map<int, std::pair<double, double>>> by;  // alpha -> n -> (D, D13)
  std::string t = "\n| K_n | alpha (deg) | D divider | D Eq. 13 | difference | r^2 | rulers (m) |\n|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    const auto& s = r.output.scalars;
    if (!s.count("dimension") || !s.count("dimension_eq13")) continue;
    const int n = static_cast<int>(num(r.params.at("iterations")));
    const double a = num(r.params.at("alpha"));
    by[a][n] = {s.at("dimension"), s.at("dimension_eq13")};
    t += fmt::format("| K{} | {:g} | {:.4f} | {:.4f} | {:+.4f} | {:.5f} | {:.3g} - {:.3g} |\n", n, a, s.at("dimension"),
                     s.at("dimension_eq13"), s.at("dimension_minus_eq13"), s.at("r_squared"), s.at("ruler_min_m"),
                     s.at("ruler_max_m"));
  }
  if (by.empty()) return;
  rep.lines.push_back(fmt::format("\n## Part '{}' (divider): {} curves", part, rows.size()));
  rep.lines.push_back(t);
  Finding f;
  f.claim = fmt::format("Part '{}': the divider dimension of the most iterated Koch curve agrees with Eq. 13, and "
                        "fewer iterations show the same scaling over a narrower range (Sec. IV C 3, Fig. 9).", part);
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
  f.evidence.push_back("criterion: |D_divider - D_Eq13| <= 0.02 for the most iterated curve, and |D - D_Eq13| does not grow "
                       "with the number of iterations;" + ev);
  rep.findings.push_back(f);
}

}  // namespace

Result<std::vector<PooledPdf>> pooled_pdfs(Store& store, const std::string& part) {
  auto rows = store.rows(part, true);
  if (!rows) return rows.error();
  // Group key: part + canonical params without pair; then array prefix.
  struct Acc {
    Params params;
    std::vector<const Store::Row*> rows;
  };
  std::map<std::string, Acc> groups;
  for (const auto& r : *rows) {
    Params p = r.params;
    p.erase("pair");
    auto& g = groups[canonical(p)];
    g.params = p;
    g.rows.push_back(&r);
  }
  std::vector<PooledPdf> out;
  for (const auto& [key, g] : groups) {
    // Prefixes present in the first member.
    std::vector<std::pair<std::string, std::string>> pdfs;  // prefix, unit
    for (const auto& [name, v] : g.rows.front()->output.arrays) {
      const auto at = name.find("_edges_");
      if (at == std::string::npos) continue;
      const std::string prefix = name.substr(0, at), unit = name.substr(at + 7);
      if (g.rows.front()->output.arrays.count(prefix + "_density_per_" + unit)) pdfs.emplace_back(prefix, unit);
    }
    for (const auto& [prefix, unit] : pdfs) {
      const std::string en = prefix + "_edges_" + unit, dn = prefix + "_density_per_" + unit;
      double lo = INFINITY, hi = -INFINITY;
      std::size_t bins = 0;
      for (const auto* r : g.rows) {
        auto e = r->output.arrays.find(en);
        auto d = r->output.arrays.find(dn);
        if (e == r->output.arrays.end() || d == r->output.arrays.end() || e->second.size() != d->second.size() + 1 ||
            e->second.size() < 2)
          continue;
        lo = std::min(lo, e->second.front());
        hi = std::max(hi, e->second.back());
        bins = std::max(bins, d->second.size());
      }
      if (!(hi > lo) || bins == 0) continue;
      PooledPdf pp;
      pp.part = part;
      pp.params = g.params;
      pp.name = prefix;
      pp.edges.resize(bins + 1);
      for (std::size_t i = 0; i <= bins; ++i) pp.edges[i] = lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(bins);
      std::vector<double> mass(bins, 0.0);
      const double w = (hi - lo) / static_cast<double>(bins);
      for (const auto* r : g.rows) {
        auto e = r->output.arrays.find(en);
        auto d = r->output.arrays.find(dn);
        if (e == r->output.arrays.end() || d == r->output.arrays.end() || e->second.size() != d->second.size() + 1) continue;
        const auto& E = e->second;
        const auto& Dn = d->second;
        double total = 0;
        for (std::size_t k = 0; k < Dn.size(); ++k) total += Dn[k] * (E[k + 1] - E[k]);
        if (!(total > 0)) continue;
        ++pp.members;
        for (std::size_t k = 0; k < Dn.size(); ++k) {
          const double a = E[k], b = E[k + 1], m = Dn[k] * (b - a) / total;
          if (m <= 0) continue;
          if (!(b > a)) {  // degenerate bin: all its mass at a point
            const auto j = std::min(bins - 1, static_cast<std::size_t>(std::max(0.0, std::floor((a - lo) / w))));
            mass[j] += m;
            continue;
          }
          const auto j0 = static_cast<std::size_t>(std::max(0.0, std::floor((a - lo) / w)));
          for (std::size_t j = std::min(j0, bins - 1); j < bins && pp.edges[j] < b; ++j) {
            const double ov = std::min(b, pp.edges[j + 1]) - std::max(a, pp.edges[j]);
            if (ov > 0) mass[j] += m * ov / (b - a);
          }
        }
      }
      if (pp.members == 0) continue;
      pp.density.resize(bins);
      for (std::size_t j = 0; j < bins; ++j) pp.density[j] = mass[j] / (pp.members * w);
      out.push_back(std::move(pp));
    }
  }
  return out;
}

Result<Report> report(Store& store) {
  auto m = store.meta();
  if (!m) return m.error();
  Report r;
  r.title = fmt::format("Study '{}' ({} scale)", (*m)["study_name"], (*m)["scale"]);
  auto c = store.counts();
  if (!c) return c.error();
  r.lines.push_back(fmt::format("{}\n\nTasks: {} total, {} done, {} failed, {} pending. Definition hash {}.",
                                (*m)["study_description"], c->total, c->done, c->failed, c->pending, (*m)["study_hash"]));
  auto parts = store.part_counts();
  if (!parts) return parts.error();
  for (const auto& p : *parts) {
    if (p.kind != "wm-pair-statistics" && p.kind != "koch-signature" && p.kind != "tilt" && p.kind != "divider") {
      r.lines.push_back(fmt::format("\n## Part '{}' ({}): {} done, {} pending", p.part, p.kind, p.done, p.pending));
      continue;
    }
    auto rows = store.rows(p.part, false);
    if (!rows) return rows.error();
    if (p.kind == "wm-pair-statistics") {
      // Pairs are pooled over `pair` only: other axes (e.g. slopes = ["exact", "spline"]) are
      // analysed as separate variants.
      std::map<std::string, std::vector<Store::Row>> variants;
      std::map<std::string, Params> rests;
      for (auto& row : *rows) {
        Params rest = row.params;
        for (const char* k : {"dimension", "n_max", "pair"}) rest.erase(k);
        const std::string key = canonical(rest);
        rests[key] = rest;
        variants[key].push_back(std::move(row));
      }
      // Label a variant by the parameters that differ between variants, e.g. "wm [slopes=spline]".
      std::set<std::string> differing;
      for (const auto& [key, rest] : rests)
        for (const auto& [name, v] : rest)
          for (const auto& [key2, rest2] : rests)
            if (!rest2.count(name) || canonical(rest2.at(name)) != canonical(v)) differing.insert(name);
      for (const auto& [key, vrows] : variants) {
        std::string label = p.part;
        if (variants.size() > 1) {
          std::string d;
          for (const auto& name : differing) {
            if (!d.empty()) d += ", ";
            const Value& v = rests[key].at(name);
            d += name + "=" + (std::holds_alternative<std::string>(v) ? std::get<std::string>(v) : canonical(v));
          }
          label += " [" + d + "]";
        }
        wm_part(label, vrows, r);
      }
    }
    else if (p.kind == "tilt") tilt_part(p.part, *rows, r);
    else if (p.kind == "divider") divider_part(p.part, *rows, r);
    else koch_part(p.part, *rows, r);
  }
  return r;
}

}  // namespace frictal::study
