// Warnings as results (frictal/warnings.hpp): the table of codes and the plausibility checks of
// measured surfaces. Thresholds and why: docs/warnings.md.
#include "frictal/warnings.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include <fmt/core.h>

#include "frictal/conditioning.hpp"
#include "frictal/signature.hpp"
#include "frictal/stats.hpp"

namespace frictal {

const std::vector<WarningCode>& warning_codes() {
  static const std::vector<WarningCode> codes = {
      {"reader", "the file's reader said something that did not stop it (a unit assumed, points masked, a checksum)",
       false, ""},
      {"units-suspect",
       "the rms slope is above 10 (84 deg on average, steeper than any instrument measures): the lateral and "
       "height units probably differ (e.g. x in micrometres, z read as metres); give the heights' unit with "
       "--z-unit (or the lateral one with --x-unit)",
       true, "--z-unit UNIT or --x-unit UNIT (Python z_unit=, x_unit=)"},
      {"lateral-suspect",
       "the rms slope is below 1e-4 (0.006 deg) on points more than 20 um apart: the lateral lengths were "
       "probably read in a unit too large (e.g. x in mm read as m); give their unit with --x-unit",
       true, "--x-unit UNIT (Python x_unit=)"},
      {"heights-tiny", "the rms height is below 1 pm: a scale factor is probably missing or applied twice", true,
       "--z-unit UNIT (Python z_unit=)"},
      {"form-only",
       "the heights are their removed form (a line or a plane) to within 1 pm while the heights as read vary: no "
       "roughness is left, and two flat faces hold at atan(mu_a) alone; a measured scan is never an exact plane "
       "(check the file), or keep the form if it is the surface (--detrend none)",
       false, ""},
      {"heights-exceed-length", "the height range exceeds the scan length: units or scale are probably wrong", true,
       "--z-unit UNIT or --x-unit UNIT (Python z_unit=, x_unit=)"},
      {"spikes",
       "points lie more than 10 rms heights from the median of their neighbours: outliers that can set theta_max "
       "and the hold angles on their own; check the scan, or remove them with the conditioning's spike filter "
       "(--remove-spikes, Python remove_spikes=True; the same rule, docs/analysis.md)",
       true, "--remove-spikes (Python remove_spikes=True)"},
      {"kurtosis", "the height kurtosis is above 30: a few outlying points dominate the height distribution", false,
       ""},
      {"fill-value",
       "runs of one repeated height value cover more than 5 % of the points: a fill value for points not measured; "
       "mask it (NaN) or crop it away (--crop)",
       true, "--crop X0,X1 to the measured part (Python crop=), or mask the fill value (NaN) in the file"},
      {"scale-mismatch",
       "the two scans' lengths or point spacings differ by more than 10x: one of them is probably read in the wrong "
       "unit (--x-unit), or they are not scans of one pair",
       true, "--x-unit UNIT for the scan read in the wrong unit (Python x_unit=), or a matching pair"},
      {"eq18-low-clamped",
       "the low end of the paper's Eq. 18 range, theta_max - sigma + theta_a, is below zero; it is reported as 0",
       false, ""},
      {"bound-negative",
       "the rigid upper bound theta_max + theta_a is below zero (mu < 0): every contact along the sliding direction "
       "descends, so the block slides without tilt; check the direction, that the two scans overlap at one scale, "
       "and their units",
       true, "--direction, or the scans' units (--x-unit UNIT, --z-unit UNIT)"},
      {"friction-angle-at-90",
       "the friction angle reaches 90 deg: a vertical wall or an interlock holds the block; the number is a "
       "single feature of the data, not a friction",
       true, "--z-unit UNIT if the heights are in another unit (Python z_unit=); --remove-spikes for a spike"},
      {"bound-at-90",
       "the rigid upper bound reaches 90 deg while no drop held near it (none held to the model's largest tilt): a "
       "seat a drop rested in has a vertical contact (the block against the lower map's rim after sliding sideways "
       "off it, or a wall it never climbed); the bound is no estimate here, the hold angles over drops are the answer",
       false, ""},
      {"load-above-slopes",
       "under load, the loaded hold angles' 95 % quantile lies above the steepest slope of either surface plus the "
       "atomic friction angle, which no contact force exceeds: the loaded lift's slopes are weighted means of the "
       "rigid lift's and the contacts' slopes, so such a number is an error of the computation, not of the surfaces",
       true, "the rigid prediction: leave out --load (Python load=None)"},
      {"scan-too-short",
       "the scans are too short for the stated test (profiles: the lower scan shorter than the block plus 8 run-away "
       "distances of sliding room, or the upper scan shorter than the block; maps: the lower map shorter than 16 "
       "run-away distances along the direction): the answer is for the largest test of "
       "the same shape (L_b / d) that the scans hold, named in the message; a shorter test reads other angles "
       "(the d sweep of the result): measure longer scans, or state the test with --block-length and "
       "--runaway-distance",
       false, ""},
      {"few-drops", "the distribution rests on fewer than 3 basins (profiles) or drops: the spread is not resolved",
       false, ""},
      {"outside-spread",
       "tilt: the friction angle of one run lies outside the rigid model's 5-95 % range over drops for the same "
       "test (frictal predict's, on measured profiles): the message says why (the block rested in a basin that "
       "fewer than 5 % of drops reach, with its own hold angle; or the run is not valid)",
       false, ""},
      {"held-to-max-tilt",
       "some drops held the block up to the model's largest tilt (45 deg): their hold angle is a lower bound", false,
       ""},
      {"dimension-out-of-range",
       "a fractal dimension outside [1, 2]: a profile's dimension lies between 1 (smooth) and 2 (plane filling); "
       "the fit range or the method does not suit the data",
       false, ""},
      {"poor-fit",
       "the fit's r^2 is below 0.95: the data are not a power law over the fit range; narrow it (--min, --max)", false,
       ""},
      {"contact-full",
       "contact: every point of the surface touches (full contact): a larger load only compresses the half-space; "
       "the contact area is the nominal area",
       false, ""},
      {"load-steep-contacts",
       "under load: the force-weighted rms slope of the asperity contacts (maps: of the contact) is above 0.3, "
       "beyond small-slope elasticity (Hertzian contacts; maps: the half-space solution) (docs/load.md)",
       false, ""},
      {"load-full-contact",
       "under load, maps: at more than 5 % of the offsets more than half of the overlap is in contact: the load "
       "flattens the roughness that makes the friction (docs/load.md)",
       false, ""},
      {"load-locked-block",
       "under load, maps: the loaded model holds the block locked to the sliding direction; at zero load it reads "
       "the locked rigid block's median (load_zero_limit_deg), more than 0.1 deg from the free rigid block's (the "
       "rigid prediction): read the change with load from the zero-load limit (docs/load.md, Maps)",
       false, ""},
      {"load-lift-ends",
       "under load, maps: some drops ran off the end of their line of loaded offsets (the maps' overlap); their "
       "hold angle is the last stop's",
       false, ""},
      {"load-deep-interference",
       "under load: at more than 5 % of the offsets a contact's interference exceeds a tenth of its radius: beyond "
       "Hertz's small contacts; the load is more than the asperity model represents (docs/load.md)",
       true, "a smaller --load or a stiffer --modulus, or drop --load for the rigid prediction"},
      {"load-contacts-merge",
       "under load: more than 10 % of the load is on asperity contacts that merge with a neighbour (the block below "
       "the saddle between them, or their Hertz widths overlapping): beyond separate spheres, where the model's "
       "friction is not the surfaces' (on smooth profiles it reads tens of degrees above the rigid bound) "
       "(docs/load.md)",
       true, "a smaller --load or a stiffer --modulus, or drop --load for the rigid prediction"},
      {"load-curve-beyond-model",
       "under load: loads of the friction-against-load curve (not the headline) break the asperity model's "
       "assumptions; the curve there is an extrapolation (docs/load.md)",
       false, ""},
      {"small-slope",
       "contact: the composite topography's rms slope is above 0.3; the half-space solution assumes small slopes "
       "(the small-slope approximation), so its areas and pressures are approximate",
       false, ""},
      {"contact-not-converged",
       "contact: the conjugate-gradient solve did not reach its tolerance; the numbers are approximate", false, ""},
      {"contact-resampled",
       "contact: a profile whose points are not equally spaced was resampled on as many equally spaced points "
       "(linear interpolation) for the FFT solver",
       false, ""},
      {"contact-at-edge",
       "contact: the contact reaches the edge of a non-periodic surface, beyond which the solver takes the surface "
       "as never touching; use a larger scan, or --periodic for a surface that repeats",
       false, ""},
  };
  return codes;
}

const WarningCode* find_warning_code(const std::string& code) {
  for (const WarningCode& c : warning_codes())
    if (c.code == code) return &c;
  return nullptr;
}

Trust assess_trust(const std::vector<Warning>& warnings) {
  Trust t;
  for (const Warning& w : warnings) {
    const WarningCode* c = find_warning_code(w.code);
    if (!c || !c->doubtful || std::find(t.codes.begin(), t.codes.end(), w.code) != t.codes.end()) continue;
    t.codes.push_back(w.code);
    if (!c->fix.empty() && t.fix.find(c->fix) == std::string::npos) t.fix += (t.fix.empty() ? "" : "; ") + c->fix;
  }
  if (!t.codes.empty()) t.verdict = "doubtful";
  return t;
}

void add_warning(std::vector<Warning>& list, Warning w) {
  for (const Warning& x : list)
    if (x.code == w.code && x.message == w.message) return;
  list.push_back(std::move(w));
}

namespace {

struct Moments {
  double mean = 0, rms = 0, kurtosis = 0, range = 0;
  std::size_t n = 0;
};

Moments moments(const std::vector<double>& z) {
  Moments m;
  double lo = INFINITY, hi = -INFINITY, s = 0;
  for (double v : z)
    if (std::isfinite(v)) s += v, ++m.n, lo = std::min(lo, v), hi = std::max(hi, v);
  if (m.n == 0) return m;
  m.mean = s / double(m.n);
  double s2 = 0, s4 = 0;
  for (double v : z)
    if (std::isfinite(v)) {
      const double d = (v - m.mean) * (v - m.mean);
      s2 += d, s4 += d * d;
    }
  s2 /= double(m.n), s4 /= double(m.n);
  m.rms = std::sqrt(s2);
  m.kurtosis = s2 > 0 ? s4 / (s2 * s2) : 0;
  m.range = hi - lo;
  return m;
}

// A fill value: the most common value among points in runs of 3 or more equal consecutive values
// (along x for maps), and how many such points there are. Measured heights carry noise, so long
// runs of one number are points the instrument did not measure (or saturated); a generated
// polyline may repeat values (a sawtooth's feet), but not in runs.
std::pair<double, std::size_t> repeated_runs(const std::vector<double>& z, std::size_t row) {
  std::map<double, std::size_t> count;
  for (std::size_t r0 = 0; r0 < z.size(); r0 += row)
    for (std::size_t i = r0; i < r0 + row && i < z.size();) {
      std::size_t j = i + 1;  // NaN (not measured) equals nothing, itself included: a run of one
      while (j < r0 + row && j < z.size() && z[j] == z[i]) ++j;
      if (j - i >= 3 && std::isfinite(z[i])) count[z[i]] += j - i;
      i = j;
    }
  // The commonest value alone: quantised heights (a coarse z step) make runs of many values, a
  // fill value makes runs of one.
  std::pair<double, std::size_t> best{0, 0};
  for (const auto& [v, c] : count)
    if (c > best.second) best = {v, c};
  return best;
}

void common_checks(std::vector<Warning>& out, const Moments& m, std::size_t spikes, double worst_spike,
                   std::pair<double, std::size_t> rep, std::size_t n, double length, const std::string& name,
                   const PlausibilityLimits& L, double read_rms) {
  if (m.n == 0) return;
  // A surface that is its form: what the form removal left is nothing, but the heights as read
  // vary (a scale factor is not what is missing).
  if (m.rms < L.min_rms_height && read_rms >= L.min_rms_height)
    add_warning(out, {"form-only", fmt::format("{}: rms height {:.3g} m after the form removal, {:.3g} m as read: the "
                                               "surface is its form (a line or a plane), with no roughness left; two "
                                               "flat faces hold at atan(mu_a) alone (keep the form: --detrend none)",
                                               name, m.rms, read_rms)});
  else if (m.rms < L.min_rms_height)
    add_warning(out, {"heights-tiny", fmt::format("{}: rms height {:.3g} m, below {:.3g} m (1 pm): a scale factor "
                                                  "is probably missing or applied twice",
                                                  name, m.rms, L.min_rms_height)});
  if (length > 0 && m.range > length)
    add_warning(out, {"heights-exceed-length",
                      fmt::format("{}: height range {:.3g} m exceeds the scan length {:.3g} m: units or scale are "
                                  "probably wrong",
                                  name, m.range, length)});
  if (spikes > 0)
    add_warning(out, {"spikes", fmt::format("{}: {} point(s) lie more than {:g} rms heights from the median of "
                                            "their neighbours (the worst {:.3g} rms): outliers that can set the "
                                            "steepest contact on their own; check the scan, or remove them with "
                                            "--remove-spikes (Python: remove_spikes=True) at a spike threshold of at "
                                            "most {:g}",
                                            name, spikes, L.spike_sq, worst_spike, L.spike_sq)});
  if (m.kurtosis > L.max_kurtosis)
    add_warning(out, {"kurtosis", fmt::format("{}: height kurtosis {:.3g} (a Gaussian surface has 3; above {:g} a "
                                              "few outlying points dominate)",
                                              name, m.kurtosis, L.max_kurtosis)});
  if (n > 20 && double(rep.second) > L.max_repeated_fraction * double(n))
    add_warning(out,
                {"fill-value", fmt::format("{}: runs of one height, {:.9g} m, cover {} of {} points ({:.1f} %): a "
                                           "fill value for points not measured, or a clipped range?",
                                           name, rep.first, rep.second, n, 100.0 * double(rep.second) / double(n))});
}

// Heights read in a unit too small for the lateral lengths: slopes (`rms_slope`, read away from
// the spikes where `spikes` were found) steeper than any instrument measures.
void units_check(std::vector<Warning>& out, double rms_slope, bool spikes, const std::string& name,
                 const PlausibilityLimits& L) {
  if (rms_slope > L.max_rms_slope)
    add_warning(
        out,
        {"units-suspect",
         fmt::format("{}: rms slope {:.3g} ({:.2f} deg on average){}: steeper than any instrument "
                     "measures; the lateral and height units probably differ (give the heights' unit: --z-unit)",
                     name, rms_slope, units::to_deg(std::atan(rms_slope)), spikes ? " away from the spikes" : "")});
}

// Lateral lengths read in a unit too large: slopes implausibly small on points spaced coarser
// than roughness instruments sample (x in mm read as m: both by 1000). A flat surface (rms slope
// 0: no heights to compare) is left to heights-tiny.
void lateral_check(std::vector<Warning>& out, double rms_slope, double spacing, const std::string& name,
                   const PlausibilityLimits& L) {
  if (rms_slope > 0 && rms_slope < L.min_rms_slope && spacing > L.lateral_suspect_spacing)
    add_warning(out, {"lateral-suspect",
                      fmt::format("{}: rms slope {:.3g} ({:.3g} deg on average) on points {:.3g} m apart: flatter and "
                                  "coarser than a roughness measurement; the lateral lengths were probably read in a "
                                  "unit too large (x in mm read as m?): give their unit (--x-unit)",
                                  name, rms_slope, units::to_deg(std::atan(rms_slope)), spacing)});
}

// rms slope of the edges of `p` that touch none of the points `spikes` (increasing indices).
double rms_slope_without(const Profile& p, const std::vector<std::size_t>& spikes) {
  auto spiky = [&](std::size_t k) { return std::binary_search(spikes.begin(), spikes.end(), k); };
  double s2 = 0, len = 0;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const double dx = p.x[i + 1] - p.x[i];
    if (!(dx > 0) || spiky(i) || spiky(i + 1)) continue;
    const double g = (p.z[i + 1] - p.z[i]) / dx;
    s2 += g * g * dx, len += dx;
  }
  return len > 0 ? std::sqrt(s2 / len) : 0;
}

}  // namespace

double rms_height_as_read(const std::vector<double>& z) { return moments(z).rms; }

std::vector<Warning> check_profile(const Profile& p, const std::string& name, const PlausibilityLimits& L,
                                   double read_rms_height) {
  std::vector<Warning> out;
  if (p.x.size() < 2) return out;
  const ProfileStats st = profile_stats_no_angles(p);  // rms slope and length only
  // Spikes: a point more than spike_sq rms from the median of its two neighbours on each side
  // (the rule of the conditioning's spike filter, conditioning.hpp).
  const SpikeSearch sp = find_spikes(p, L.spike_sq);
  // The units check reads the slopes of the surface, not of its spikes: three spikes in 2000
  // points raise the rms slope tenfold, and a units warning there would name the wrong fix.
  const double units_slope = sp.points.empty() ? st.rms_slope : rms_slope_without(p, sp.points);
  units_check(out, units_slope, !sp.points.empty(), name, L);
  const double spacing = p.x.size() > 1 ? (p.x.back() - p.x.front()) / double(p.x.size() - 1) : 0;
  lateral_check(out, st.rms_slope, spacing, name, L);
  const Moments m = moments(p.z);
  const std::size_t spikes = sp.points.size();
  const double worst = sp.worst;
  common_checks(out, m, spikes, worst, repeated_runs(p.z, p.z.size()), p.z.size(), st.length, name, L, read_rms_height);
  return out;
}

std::vector<Warning> check_map(const Map& mp, const std::string& name, const PlausibilityLimits& L,
                               double read_rms_height) {
  std::vector<Warning> out;
  if (mp.nx < 2 && mp.ny < 2) return out;
  const SpikeSearch sp = find_spikes(mp, L.spike_sq);
  auto spiky = [&](std::size_t k) { return std::binary_search(sp.points.begin(), sp.points.end(), k); };
  // rms slope by forward differences over valid neighbours (u2, nu: those not touching a spike).
  double s2 = 0, u2 = 0;
  std::size_t ns = 0, nu = 0;
  for (std::size_t j = 0; j < mp.ny; ++j)
    for (std::size_t i = 0; i < mp.nx; ++i) {
      const double z = mp.at(i, j);
      if (!std::isfinite(z)) continue;
      if (i + 1 < mp.nx && std::isfinite(mp.at(i + 1, j))) {
        const double g = (mp.at(i + 1, j) - z) / mp.dx;
        s2 += g * g, ++ns;
        if (!spiky(j * mp.nx + i) && !spiky(j * mp.nx + i + 1)) u2 += g * g, ++nu;
      }
      if (j + 1 < mp.ny && std::isfinite(mp.at(i, j + 1))) {
        const double g = (mp.at(i, j + 1) - z) / mp.dy;
        s2 += g * g, ++ns;
        if (!spiky(j * mp.nx + i) && !spiky((j + 1) * mp.nx + i)) u2 += g * g, ++nu;
      }
    }
  // Two directional components: the gradient's rms is sqrt(2) times one component's.
  const double rms_slope = ns ? std::sqrt(2 * s2 / double(ns)) : 0;
  // The units check away from the spikes (as for profiles).
  const double units_slope = nu ? std::sqrt(2 * u2 / double(nu)) : 0;
  units_check(out, units_slope, !sp.points.empty(), name, L);
  if (ns) lateral_check(out, rms_slope, std::max(mp.dx, mp.dy), name, L);
  const Moments m = moments(mp.heights);
  const std::size_t spikes = sp.points.size();
  const double worst = sp.worst;
  const double length = std::max(mp.width(), mp.height());
  common_checks(out, m, spikes, worst, repeated_runs(mp.heights, mp.nx), mp.valid_count(), length, name, L,
                read_rms_height);
  return out;
}

std::vector<Warning> check_pair_scales(double l1, double s1, double l2, double s2, const std::string& n1,
                                       const std::string& n2, const PlausibilityLimits& L) {
  std::vector<Warning> out;
  auto ratio = [](double a, double b) { return a > 0 && b > 0 ? std::max(a / b, b / a) : 1.0; };
  if (ratio(l1, l2) > L.max_scale_ratio)
    add_warning(out, {"scale-mismatch", fmt::format("{} is {:.3g} m long and {} {:.3g} m ({:.3g}x): two scans of "
                                                    "one pair are expected to be of similar size",
                                                    n1, l1, n2, l2, ratio(l1, l2))});
  if (ratio(s1, s2) > L.max_scale_ratio)
    add_warning(out, {"scale-mismatch", fmt::format("{} has a point spacing of {:.3g} m and {} {:.3g} m ({:.3g}x): "
                                                    "the finer scan's small slopes meet a coarse one",
                                                    n1, s1, n2, s2, ratio(s1, s2))});
  return out;
}

std::vector<Warning> check_dimension_fit(double D, double r2, const std::string& method, double min_r2) {
  std::vector<Warning> out;
  if (!(D >= 1 && D <= 2))
    out.push_back({"dimension-out-of-range",
                   fmt::format("{} method: D = {:.4f}, outside [1, 2] (1: smooth, 2: plane filling); the fit range "
                               "or the method does not suit the data",
                               method, D)});
  if (!(r2 >= min_r2))
    out.push_back({"poor-fit", fmt::format("{} method: r^2 = {:.4f} below {:g}: not a power law over the fit range",
                                           method, r2, min_r2)});
  return out;
}

std::vector<Warning> check_friction_bound(double phi, const std::string& where) {
  std::vector<Warning> out;
  if (phi < 0)
    out.push_back(
        {"bound-negative",
         fmt::format("{}: the rigid upper bound theta_max + theta_a = {:.4f} deg is below zero (mu = {:.4g}): every "
                     "contact along the sliding direction descends, so the block slides without tilt; check the "
                     "direction, that the two scans overlap at one scale, and their units",
                     where, phi * 180 / std::numbers::pi, std::tan(phi))});
  return out;
}

std::vector<Warning> check_friction_prediction(const FrictionPrediction& p, const std::string& where) {
  std::vector<Warning> out;
  if (p.low_clamped)
    out.push_back(
        {"eq18-low-clamped", where + ": Eq. 18's low end theta_max - sigma + theta_a is below zero; reported as 0"});
  for (Warning& w : check_friction_bound(p.friction_angle, where)) out.push_back(std::move(w));
  return out;
}

std::vector<Warning> check_signature_bounds(const FrictionPrediction& forward, const FrictionPrediction& backward,
                                            const std::string& where) {
  std::vector<Warning> out = check_friction_prediction(forward, where);
  constexpr double kNear90 = 89.5 * std::numbers::pi / 180;
  for (const auto& [name, f] : {std::pair{"forward", &forward}, std::pair{"backward", &backward}})
    if (f->friction_angle >= kNear90)
      out.push_back({"friction-angle-at-90",
                     fmt::format("the {} upper bound is {:.4f} deg: a vertical wall, an interlock or a unit mix-up; "
                                 "the number is a single feature of the data, not a friction",
                                 name, f->friction_angle * 180 / std::numbers::pi)});
  return out;
}

}  // namespace frictal
