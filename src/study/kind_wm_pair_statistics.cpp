// Task kind wm-pair-statistics, one unit: a pair of stochastic Weierstrass-Mandelbrot profiles
// (Sec. V, Fig. 14-18): compute function, outputs, report section with the paper's findings, plot
// views. Registered in registry.cpp.
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
#include "study/kind_common.hpp"
#include "study/table_params.hpp"

namespace frictal::study {

using namespace kind_detail;

namespace {

// The outputs taken from output tables (frictal columns): declared once there. The signature's
// (kSignatureSummaryOutputs, kind_common.hpp)...
// ... and each profile's statistics (profile_stats_columns()).
constexpr std::initializer_list<ColumnOutput> kLowerOutputs = {
    {"max_slope_deg", "surface_slope_max_lower_deg", "the lower profile"},
    {"points", nullptr, "the lower profile (the upper has as many)"}};
constexpr std::initializer_list<ColumnOutput> kUpperOutputs = {
    {"max_slope_deg", "surface_slope_max_upper_deg", "the upper profile"},
    {"rms_slope", "surface_rms_slope", "the upper profile"}};

}  // namespace

Result<TaskOutput> run_wm_pair_statistics(const Params& p, std::uint64_t seed) {
  Error err;
  std::int64_t bins = 0, offsets = 0, compare_phases = 0, compare_slopes = 0;
  std::string slopes;
  if (!take(get_string(p, "slopes", "exact"), slopes, err) || !take(get_int(p, "bins", 90), bins, err) ||
      !take(get_int(p, "offsets", 0), offsets, err) || !take(get_int(p, "compare_phases", 0), compare_phases, err) ||
      !take(get_int(p, "compare_slopes", 0), compare_slopes, err))
    return err;
  if (bins < 1 || bins > 100000) return make_error("parameter 'bins': expected 1..100000");
  if (offsets < 0) return make_error("parameter 'offsets': expected >= 0");
  if (compare_phases != 0 && compare_phases != 1)
    return make_error(fmt::format("parameter 'compare_phases': expected 0 or 1, got {}", compare_phases));
  if (compare_slopes != 0 && compare_slopes != 1)
    return make_error(fmt::format("parameter 'compare_slopes': expected 0 or 1, got {}", compare_slopes));
  if (compare_slopes && slopes != "exact")
    return make_error(fmt::format(
        "parameter 'compare_slopes': compares the spline's contact slopes with the exact ones, so 'slopes' must be "
        "\"exact\", got \"{}\"",
        slopes));
  // dimension, gamma, n_max, longest_wavelength, length, rms_height, exponent, spacing: the wm
  // generator's table; the phases are always random, from the task seed.
  if (Status st = only_known_parameters(p, {&find_generator("wm")->fields},
                                        {"pair", "slopes", "bins", "offsets", "compare_phases", "compare_slopes"},
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
  put_outputs(out, signature_columns(), r, kSignatureSummaryOutputs);
  put_outputs(out, profile_stats_columns(), sl, kLowerOutputs);
  put_outputs(out, profile_stats_columns(), su, kUpperOutputs);
  s["contact_slope_max_deg"] = cmax / kDeg;
  s["tan_contact_slope_max"] = std::tan(cmax);
  s["surface_slope_max_deg"] = smax / kDeg;
  s["tan_surface_slope_max"] = std::tan(smax);
  s["surface_slope_std_deg"] = slope_angle_std(*upper) / kDeg;
  s["surface_slope_std_lower_deg"] = slope_angle_std(*lower) / kDeg;
  // The comparisons' outputs are NaN (stored as NULL) when not asked for.
  for (const char* key : {"deterministic_rms_slope", "surface_rms_slope_lower", "contact_slope_std_spline_deg",
                          "theta_max_forward_spline_deg"})
    s[key] = std::nan("");
  if (compare_phases) {
    // Fig. 11: the same modes with zero phases (Eq. 17); every mode's amplitude is unchanged.
    WmParams d = w;
    d.stochastic = false;
    auto det = wm_profile(d);
    if (!det) return det.error();
    s["deterministic_rms_slope"] = profile_stats(*det).rms_slope;
    s["surface_rms_slope_lower"] = sl.rms_slope;
  }
  if (compare_slopes) {
    // Fig. 13: the contact slopes of the cubic spline through the same points.
    SignatureOptions os = o;
    os.slopes = SlopeMethod::Spline;
    auto spl = signature(*lower, rotate180(*upper), os);
    if (!spl) return spl.error();
    s["contact_slope_std_spline_deg"] = spl->contact_slope_std / kDeg;
    s["theta_max_forward_spline_deg"] = spl->theta_max_forward / kDeg;
  }
  put_pdf(out, "contact_slope_pdf", r.contact_slope_pdf);
  put_pdf(out, "surface_slope_pdf", slope_distribution(*upper, static_cast<int>(bins)));
  return out;
}

// ---------------------------------------------------------------- report section

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
    f.claim_id = "wm-contact-below-surface";
    f.part = part;
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
    f.claim_id = "wm-slopes-grow-with-dimension";
    f.part = part;
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
    if (steps > 0) rep.findings.push_back(f);  // a part at one D does not check a trend in D
  }
  // F3: rise with n_max for every D.
  if (ns.size() >= 2) {
    Finding f;
    f.claim_id = "wm-slopes-grow-with-resolution";
    f.part = part;
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
    f.claim_id = "wm-contact-slope-limit";
    f.part = part;
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
    f.claim_id = "wm-slope-std-grow-with-dimension";
    f.part = part;
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
    if (steps > 0) rep.findings.push_back(f);
  }
}

/// Fig. 11, 12, 13, 16: the profiles' own claims, on the pairs of a part.
void wm_profile_findings(const std::string& part, const std::vector<Store::Row>& rows, Report& rep) {
  int nmax = -1;
  for (const auto& r : rows)
    if (r.params.count("n_max")) nmax = std::max(nmax, static_cast<int>(as_int(r.params.at("n_max"))));
  // Fig. 16 and 12 at the part's finest resolution (at n_max = 0 both faces are one cosine, which
  // mate exactly: contact and surface slopes coincide there).
  int pairs = 0, narrower = 0;
  double widest = 0;           // the largest sigma_contact / sigma_surface
  std::map<double, Cell> rms;  // D -> pair-mean rms slope of the upper profile
  for (const auto& r : rows) {
    const auto& s = r.output.scalars;
    if (!r.params.count("dimension") || !r.params.count("n_max") || as_int(r.params.at("n_max")) != nmax) continue;
    if (!s.count("contact_slope_std_deg") || !s.count("surface_slope_std_deg") ||
        !s.count("surface_slope_std_lower_deg"))
      continue;
    ++pairs;
    const double ratio =
        s.at("contact_slope_std_deg") / std::min(s.at("surface_slope_std_deg"), s.at("surface_slope_std_lower_deg"));
    narrower += ratio < 1;
    widest = std::max(widest, ratio);
    if (s.count("surface_rms_slope")) rms[as_number(r.params.at("dimension"))].add(s.at("surface_rms_slope"));
  }
  if (pairs && nmax > 0) {
    Finding f;
    f.claim_id = "wm-contact-narrower";
    f.part = part;
    f.claim = fmt::format(
        "Part '{}': the contact slopes are distributed more narrowly than the surface slopes (n_max = {}; Sec. V C, "
        "Fig. 16).",
        part, nmax);
    f.supported = narrower == pairs;
    f.evidence.push_back(
        fmt::format("criterion: sigma_contact < sigma_surface of both profiles in every pair at n_max = {}; {} of {} "
                    "pairs; largest sigma_contact / sigma_surface {:.3f}",
                    nmax, narrower, pairs, widest));
    rep.findings.push_back(f);
  }
  if (rms.size() >= 2) {
    Finding f;
    f.claim_id = "wm-rougher-with-dimension";
    f.part = part;
    f.claim = fmt::format(
        "Part '{}': at equal rms height the profile gets rougher with D: the rms slope grows with D (n_max = {}; "
        "Fig. 12).",
        part, nmax);
    int up = 0, steps = 0;
    double prev = NAN;
    std::string vals;
    for (const auto& [D, cell] : rms) {
      if (std::isfinite(prev)) ++steps, up += cell.mean() > prev;
      prev = cell.mean();
      vals += fmt::format(" D={:.1f}: {:.5f}", D, cell.mean());
    }
    f.supported = up == steps;
    f.evidence.push_back(fmt::format(
        "criterion: the pair-mean rms slope of the upper profile rises at every step in D; {} of {} steps", up, steps));
    f.evidence.push_back("rms slope:" + vals);
    rep.findings.push_back(f);
  }
  // Fig. 11 and 13: on the parts that compute the comparisons (compare_phases, compare_slopes).
  int phased = 0, same_rms = 0, splined = 0, same_slopes = 0;
  double worst_rms = 0, worst_std = 0, worst_theta = 0;
  for (const auto& r : rows) {
    const auto& s = r.output.scalars;
    auto has = [&](const char* key) { return s.count(key) && std::isfinite(s.at(key)); };
    if (has("deterministic_rms_slope") && has("surface_rms_slope") && has("surface_rms_slope_lower")) {
      ++phased;
      const double det = s.at("deterministic_rms_slope");
      const double d =
          std::max(std::abs(s.at("surface_rms_slope") / det - 1), std::abs(s.at("surface_rms_slope_lower") / det - 1));
      same_rms += d < 0.02;
      worst_rms = std::max(worst_rms, d);
    }
    if (has("contact_slope_std_spline_deg") && has("theta_max_forward_spline_deg") && has("contact_slope_std_deg") &&
        has("theta_max_forward_deg")) {
      ++splined;
      const double ds = std::abs(s.at("contact_slope_std_spline_deg") / s.at("contact_slope_std_deg") - 1);
      const double dt = std::abs(s.at("theta_max_forward_spline_deg") / s.at("theta_max_forward_deg") - 1);
      same_slopes += ds < 0.02 && dt < 0.1;
      worst_std = std::max(worst_std, ds);
      worst_theta = std::max(worst_theta, dt);
    }
  }
  if (phased) {
    Finding f;
    f.claim_id = "wm-phases-keep-rms-slope";
    f.part = part;
    f.claim = fmt::format(
        "Part '{}': random phases (Eq. 14) keep every mode's amplitude of the deterministic profile (Eq. 17), hence "
        "its rms slope (Sec. V A, Fig. 11).",
        part);
    f.supported = same_rms == phased;
    f.evidence.push_back(
        fmt::format("criterion: both random profiles' rms slopes within 2 % of the zero-phase profile's; {} of {} "
                    "pairs; largest difference {:.2f} %",
                    same_rms, phased, 100 * worst_rms));
    rep.findings.push_back(f);
  }
  if (splined) {
    Finding f;
    f.claim_id = "wm-spline-matches-linear";
    f.part = part;
    f.claim = fmt::format(
        "Part '{}': at the sampling of Eq. 16 the cubic spline and the polyline give the same contact-slope "
        "statistics (Sec. V B, Fig. 13).",
        part);
    f.supported = same_slopes == splined;
    f.evidence.push_back(
        fmt::format("criterion: sigma_contact within 2 % and theta_max forward within 10 % in every pair; {} of {} "
                    "pairs; largest differences {:.2f} % and {:.2f} %",
                    same_slopes, splined, 100 * worst_std, 100 * worst_theta));
    rep.findings.push_back(f);
  }
}

/// wm-pair-statistics: rows pooled over D, n_max and pair (wm_part reads those axes); any other
/// axis (e.g. slopes = ["exact", "spline"]) makes a separate variant.
void wm_section(const std::string& part, const std::vector<TaskRow>& rows, Report& rep) {
  for (const auto& [label, vrows] : variants_of(part, rows, {"dimension", "n_max", "pair"})) {
    wm_part(label, vrows, rep);
    wm_profile_findings(label, vrows, rep);
  }
}

/// Estimated CPU time (unit: s; TaskKind::cost): the profiles' points (about gamma^n_max per
/// longest wavelength) set the cost (measured 2026-11-21: 46 ms per pair at n_max = 10,
/// L_b / L = 20, gamma = 1.5).
double wm_pair_cost(const Params& p) {
  const double gamma = std::clamp(number(p, "gamma", 1.5), 1.0001, 100.0);
  const double n_max = std::clamp(number(p, "n_max", 10), 0.0, 60.0);
  const double waves =
      std::clamp(number(p, "length", 20e-6) / std::max(1e-30, number(p, "longest_wavelength", 1e-6)), 1e-3, 1e9);
  return 1e-3 + 4e-5 * waves * std::pow(gamma, n_max);
}

}  // namespace

// ---------------------------------------------------------------- the kind

TaskKind wm_pair_statistics_kind() {
  TaskKind k;
  k.name = "wm-pair-statistics";
  k.description = "A pair of stochastic WM profiles (Sec. V): max/std of contact and surface slopes, slope PDFs";
  k.version = 3;  // 3: compare_phases, compare_slopes (Fig. 11, 13)
  k.run = run_wm_pair_statistics;
  k.cost = wm_pair_cost;
  k.outputs = {
      {"contact_slope_max_deg", "deg", "max(theta_max_forward, theta_max_backward)"},
      {"tan_contact_slope_max", "1", "tan of contact_slope_max"},
      {"surface_slope_max_deg", "deg", "steepest edge of both profiles"},
      {"tan_surface_slope_max", "1", "tan of surface_slope_max"},
      {"surface_slope_std_deg", "deg", "length-weighted std of the upper profile's edge angles"},
      {"surface_slope_std_lower_deg", "deg", "the same of the lower profile"},
      {"contact_slope_pdf_edges_deg", "deg", "contact slope PDF bin edges (Fig. 16)", true},
      {"contact_slope_pdf_density_per_deg", "1/deg", "contact slope PDF density", true},
      {"surface_slope_pdf_edges_deg", "deg", "surface slope PDF bin edges (upper profile)", true},
      {"surface_slope_pdf_density_per_deg", "1/deg", "surface slope PDF density", true},
      {"deterministic_rms_slope", "1", "compare_phases: rms slope of the same modes with zero phases (Eq. 17)"},
      {"surface_rms_slope_lower", "1", "compare_phases: rms slope of the lower profile"},
      {"contact_slope_std_spline_deg", "deg", "compare_slopes: contact_slope_std with the cubic spline's slopes"},
      {"theta_max_forward_spline_deg", "deg", "compare_slopes: theta_max_forward with the cubic spline's slopes"},
  };
  for (const auto& table : {outputs_of("signature", signature_columns(), kSignatureSummaryOutputs),
                            outputs_of("profile_stats", profile_stats_columns(), kLowerOutputs),
                            outputs_of("profile_stats", profile_stats_columns(), kUpperOutputs)})
    k.outputs.insert(k.outputs.end(), table.begin(), table.end());
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
    const bool surface = std::string(y.id).rfind("surface", 0) == 0;
    k.plots.push_back(PlotView::of(std::string(y.id) + "-vs-n_max", {"n_max", "n_max"}, {y.column, y.label})
                          .by("dimension", "D = {dimension}")
                          .markers("o", 3, 1)
                          .averaged_over("pair"));
    k.plots.push_back(PlotView::of(std::string(y.id) + "-vs-dimension", {"dimension", "D"}, {y.column, y.label})
                          .named(surface ? "surface slope" : "contact slope")
                          .markers(surface ? "s" : "o")
                          .averaged_over("pair"));
  }
  return k;
}

}  // namespace frictal::study
