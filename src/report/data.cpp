// The analyses of `frictal report`: every section's results, computed from a ReportInput by the
// library's analysis calls. The page (page.cpp, sections.cpp) only formats them.
#include <fmt/core.h>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "frictal/filter.hpp"
#include "frictal/report.hpp"
#include "frictal/scan_stats.hpp"
#include "frictal/units.hpp"

namespace frictal::report {

namespace {

constexpr double kDeg = units::kRadPerDeg;
constexpr double deg(double rad) { return units::to_deg(rad); }

/// The longest valid run of the line of a map through its centre along x.
Result<Profile> central_line(const Map& m) {
  const double yc = m.y0 + m.height() / 2;
  auto lines = map_line(m, m.x0, yc, 0.0, m.dx, 3);
  if (lines.empty())
    return make_error(
        fmt::format("report: the map ({} x {} points) has no run of 3 valid points on its central "
                    "line along x",
                    m.nx, m.ny));
  std::size_t best = 0;
  for (std::size_t i = 1; i < lines.size(); ++i)
    if (lines[i].length() > lines[best].length()) best = i;
  return lines[best];
}

Status check_input(const ReportInput& in) {
  if (!(std::isfinite(in.atomic_friction) && in.atomic_friction >= 0))
    return make_error(fmt::format("report: atomic friction must be a finite number >= 0, got {}", in.atomic_friction));
  if (in.resolution_steps == 1 || in.resolution_steps < 0 || in.resolution_steps > 100)
    return make_error(fmt::format("report: resolution steps must be 0 or 2..100, got {}", in.resolution_steps));
  if (in.is_map && in.upper) return make_error("report: an upper profile for a map: give the upper map as upper_map");
  if (in.is_map && (in.directions < 1 || in.directions > 720))
    return make_error(fmt::format("report: directions must be in 1..720, got {}", in.directions));
  if (in.is_map && (in.map_drops < 2 || in.map_drops > 64))
    return make_error(fmt::format("report: map drops must be in 2..64 (an N x N grid), got {}", in.map_drops));
  if (in.bins < 2 || in.bins > 10000)
    return make_error(fmt::format("report: bins must be in 2..10000, got {}", in.bins));
  if (!(std::isfinite(in.tip_radius) && in.tip_radius >= 0))
    return make_error(fmt::format("report: tip radius must be a finite length >= 0 (m), got {}", in.tip_radius));
  return Ok{};
}

Result<ReportSurfaces> surfaces_of(const ReportInput& in) {
  ReportSurfaces s;
  s.lower_name = in.lower_name.empty() ? std::string("surface") : in.lower_name;
  if (in.is_map) {
    if (auto v = validate(in.map, s.lower_name); !v) return v.error();
    auto c = central_line(in.map);
    if (!c) return c.error();
    s.lower = std::move(*c);
    s.line_y = in.map.y0 + in.map.height() / 2;
    s.map_stats = map_stats(in.map);
  } else {
    if (auto v = validate(in.lower, s.lower_name); !v) return v.error();
    s.lower = in.lower;
  }
  s.pair = in.upper.has_value() || (in.is_map && in.upper_map);
  if (in.is_map && in.upper_map) {
    // A pair of maps: the upper map's central line is the upper face of every line analysis.
    const std::string name = in.upper_name.empty() ? std::string("upper") : in.upper_name;
    if (auto v = validate(*in.upper_map, name); !v) return v.error();
    auto c = central_line(*in.upper_map);
    if (!c) return c.error();
    s.upper = std::move(*c);
    s.upper_line_y = in.upper_map->y0 + in.upper_map->height() / 2;
    s.upper_map_stats = map_stats(*in.upper_map);
  } else {
    s.upper = s.pair ? *in.upper : s.lower;
  }
  if (s.pair)
    if (auto v = validate(s.upper, in.upper_name); !v) return v.error();
  s.upper_name = s.pair ? in.upper_name : s.lower_name;
  s.lower_stats = profile_stats(s.lower);
  s.upper_stats = profile_stats(s.upper);
  s.lower_uniform = is_uniform(s.lower, 1e-6);
  s.upper_uniform = is_uniform(s.upper, 1e-6);
  return s;
}

/// The edges of a profile as slope samples (unit: rad) weighted by their lengths (unit: m).
void edge_samples(const Profile& pr, std::vector<double>& s, std::vector<double>& w) {
  for (std::size_t i = 0; i + 1 < pr.size(); ++i) {
    const double dx = pr.x[i + 1] - pr.x[i];
    if (dx <= 0) continue;  // vertical jumps have no length
    s.push_back(std::atan((pr.z[i + 1] - pr.z[i]) / dx));
    w.push_back(dx);
  }
}

/// |slope| below which a fraction q of the weight lies.
double quantile_abs(const std::vector<double>& s, const std::vector<double>& w, double q) {
  std::vector<std::pair<double, double>> v;
  double total = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    v.emplace_back(std::abs(s[i]), w[i]);
    total += w[i];
  }
  std::sort(v.begin(), v.end());
  double acc = 0;
  for (const auto& [a, wt] : v) {
    acc += wt;
    if (acc >= q * total) return a;
  }
  return v.empty() ? 0.0 : v.back().first;
}

ReportSlopes slopes_of(const ReportSurfaces& s, const SignatureResult& r, int bins) {
  ReportSlopes out;
  std::vector<double> ls, lw, us, uw;
  edge_samples(s.lower, ls, lw);
  if (s.pair) edge_samples(s.upper, us, uw);
  double lim = std::max({r.theta_max_forward, r.theta_max_backward, quantile_abs(ls, lw, 0.995),
                         s.pair ? quantile_abs(us, uw, 0.995) : 0.0});
  lim = std::min(std::numbers::pi / 2, lim * 1.1 + 1e-12);
  out.limit = lim;
  // Densities relative to all the weight: samples outside +-lim are counted, not drawn.
  auto rebin = [&](const std::vector<double>& samples, const std::vector<double>& weights, bool count_outside) {
    Histogram h;
    const int nb = bins;
    for (int i = 0; i <= nb; ++i) h.edges.push_back(-lim + 2 * lim * i / nb);
    h.density.assign(std::size_t(nb), 0.0);
    double total = 0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const double w = weights.empty() ? 1.0 : weights[i];
      if (!std::isfinite(samples[i]) || !(w > 0)) continue;
      total += w;
      const double v = samples[i];
      if (v < -lim || v > lim) {
        if (count_outside) out.outside_length += w;
        continue;
      }
      h.density[std::size_t(std::min(nb - 1, int((v + lim) / (2 * lim) * nb)))] += w;
    }
    if (count_outside) out.total_length += total;
    const double width = 2 * lim / nb;
    for (auto& d : h.density) d = total > 0 ? d / (total * width) : 0.0;
    return h;
  };
  out.lower = rebin(ls, lw, true);
  if (s.pair) out.upper = rebin(us, uw, true);
  out.contact = rebin(r.slope_samples, r.slope_weights, false);
  return out;
}

/// The hold section from the analysis that came with the signature (one pass over the lift).
ReportHold hold_of(HoldAnalysis analysis, const FrictionPrediction& fwd) {
  ReportHold out;
  out.analysis = std::move(analysis);
  const LiftCurve& curve = out.analysis.curve;
  const HoldDistribution& f = out.analysis.distribution.forward;
  for (double x : f.basins.rest) {
    const auto it = std::lower_bound(curve.offset.begin(), curve.offset.end(), x);
    const std::size_t k =
        std::min<std::size_t>(static_cast<std::size_t>(it - curve.offset.begin()), curve.offset.size() - 1);
    out.rest_lift.push_back(curve.lift[k]);
  }
  // The distribution over drops, each basin weighted by the width it drains; bins centred on
  // equally spaced angles from the lowest to the highest of the hold angles and the Eq. 18 range.
  const double lo_deg = deg(std::min({f.hold.min, f.inertial.min, fwd.friction_angle_low}));
  const double hi_deg = deg(std::max({f.hold.max, f.inertial.max, fwd.friction_angle}));
  const int nb = 40;
  const double span = std::max(hi_deg - lo_deg, 1e-6);
  auto hist = [&](const std::vector<double>& angles) {
    Histogram h;
    for (int i = 0; i <= nb; ++i) h.edges.push_back((lo_deg + span * (i - 0.5) / (nb - 1)) * kDeg);
    h.density.assign(nb, 0.0);
    double total = 0;
    for (std::size_t i = 0; i < angles.size(); ++i) {
      const int k = std::clamp(int(std::lround((deg(angles[i]) - lo_deg) / span * (nb - 1))), 0, nb - 1);
      h.density[std::size_t(k)] += f.basins.weight[i];
      total += f.basins.weight[i];
    }
    const double width = (h.edges[1] - h.edges[0]);
    for (double& d : h.density) d = total > 0 ? d / (total * width) : 0.0;
    return h;
  };
  out.hold = hist(f.basins.hold);
  out.inertial = hist(f.basins.inertial);
  return out;
}

/// The two-map section: the prediction's hold angles over drops (the headline's), its block
/// dropped at s = 0 and the lift of the map's nodes as their picture; a failure is kept as the
/// section's `failure`.
Status areal_hold_into(const ReportInput& in, ReportArealHold& out) {
  if (auto v = validate(*in.upper_map, in.upper_name); !v) return v.error();
  PredictOptions po;
  po.atomic_friction = in.atomic_friction;
  po.runaway_distance = in.runaway_distance;
  po.threads = in.threads;
  const Prediction* given = in.prediction ? &*in.prediction : nullptr;
  if (given && given->is_map && !given->single_drop && given->direction == 0) {
    out.prediction = *given;
  } else {
    // As `frictal predict` computes it, on the page's maps (conditioned already: no form again).
    po.detrend = Detrend{DetrendKind::None, 0};
    PredictSurface lower, upper;
    lower.is_map = upper.is_map = true;
    lower.map = in.map;
    lower.name = in.lower_name;
    upper.map = *in.upper_map;
    upper.name = in.upper_name;
    auto p = predict(lower, &upper, po);
    if (!p) return p.error();
    out.prediction = std::move(*p);
  }
  const Prediction& p = out.prediction;
  // The block dropped at s = 0 in the prediction's model with its settings (map_model_options).
  po.runaway_distance = p.runaway_distance;
  MapHoldOptions t = map_model_options(in.map, po);
  t.start_offset = {0, 0};
  auto hold = areal_tilt_hold(in.map, *in.upper_map, t);
  if (!hold) return hold.error();
  out.from_zero = std::move(*hold);
  out.sphere_radius = t.sphere_radius;
  // The lift of the map's nodes over the drops and the path (sliding along +x: u = x, v = y).
  double umin = 0, umax = 0, vmax = 0;
  auto cover = [&](double x, double y) {
    umin = std::min(umin, x);
    umax = std::max(umax, x);
    vmax = std::max(vmax, std::abs(y));
  };
  for (const auto& q : p.drop_offsets) cover(q[0], q[1]);
  cover(out.from_zero.rest_offset[0], out.from_zero.rest_offset[1]);
  for (const auto& st : out.from_zero.stops) cover(st[1], st[2]);
  const double margin = 0.5 * p.runaway_distance;
  ArealLiftOptions lo;
  lo.threads = in.threads;
  lo.offset_min = umin - margin;
  lo.offset_max = umax + margin;
  lo.across_max = vmax + margin;
  auto lift = areal_lift(in.map, *in.upper_map, 0.0, lo);
  if (!lift) return lift.error();
  out.lift = std::move(*lift);
  // The drops' hold angles: histograms over [0, top], each drop one (percent of the drops).
  double amax = 0;
  for (double a : p.drop_angles) amax = std::max(amax, a);
  for (double a : p.drop_angles_locked) amax = std::max(amax, a);
  const int bins = 40;
  const double top = deg(amax) > 0 ? deg(amax) * 1.0001 : 1.0;  // (unit: deg)
  for (int b = 0; b <= bins; ++b) out.edges.push_back(top * b / bins * kDeg);
  auto percent = [&](const std::vector<double>& angles) {
    std::vector<double> y(bins, 0.0);
    for (double a : angles) {
      const int b = std::clamp(int(deg(a) / top * bins), 0, bins - 1);
      y[std::size_t(b)] += 100.0 / double(angles.size());
    }
    return y;
  };
  out.free_percent = percent(p.drop_angles);
  if (p.has_locked) out.locked_percent = percent(p.drop_angles_locked);
  return Ok{};
}

/// Slopes along the direction (cos a, sin a) of a map's facets: each cell with four valid corners,
/// the gradient of its bilinear surface at the centre (unit: rad).
void facet_slopes(const Map& m, double angle, std::vector<double>& out) {
  const double c = std::cos(angle), sn = std::sin(angle);
  for (std::size_t j = 0; j + 1 < m.ny; ++j)
    for (std::size_t i = 0; i + 1 < m.nx; ++i) {
      const double z00 = m.at(i, j), z10 = m.at(i + 1, j), z01 = m.at(i, j + 1), z11 = m.at(i + 1, j + 1);
      if (!(std::isfinite(z00) && std::isfinite(z10) && std::isfinite(z01) && std::isfinite(z11))) continue;
      const double gx = (z10 - z00 + z11 - z01) / (2 * m.dx), gy = (z01 - z00 + z11 - z10) / (2 * m.dy);
      out.push_back(std::atan(gx * c + gy * sn));
    }
}

/// The maps' areal signature along the headline's direction, its grid bounds and the slopes.
ReportArealSignature areal_signature_of(const ReportInput& in) {
  ReportArealSignature out;
  out.direction = in.prediction && in.prediction->is_map ? in.prediction->direction : 0.0;
  const Map& upper_map = in.upper_map ? *in.upper_map : in.map;
  ArealSignatureOptions so;
  so.threads = in.threads;
  auto sig = areal_signature(in.map, upper_map, out.direction, so);
  if (!sig) {
    out.failure = sig.error().message;
    return out;
  }
  out.signature = std::move(*sig);
  const ArealSignature& r = out.signature;
  auto fwd = predict_friction(in.atomic_friction, r.theta_max_forward, r.contact_slope_std);
  auto bwd = predict_friction(in.atomic_friction, r.theta_max_backward, r.contact_slope_std);
  if (!fwd || !bwd) {
    out.failure = (!fwd ? fwd : bwd).error().message;
    return out;
  }
  out.forward = *fwd;
  out.backward = *bwd;
  std::vector<double> ls, us;
  facet_slopes(in.map, out.direction, ls);
  if (in.upper_map) facet_slopes(*in.upper_map, out.direction, us);
  const std::vector<double> lw(ls.size(), 1.0), uw(us.size(), 1.0);
  double lim = std::max({r.theta_max_forward, r.theta_max_backward, ls.empty() ? 0.0 : quantile_abs(ls, lw, 0.995),
                         us.empty() ? 0.0 : quantile_abs(us, uw, 0.995)});
  lim = std::min(std::numbers::pi / 2, lim * 1.1 + 1e-12);
  out.limit = lim;
  auto hist = [&](const std::vector<double>& samples, bool facets) {
    Histogram h;
    const int nb = in.bins;
    for (int i = 0; i <= nb; ++i) h.edges.push_back(-lim + 2 * lim * i / nb);
    h.density.assign(std::size_t(nb), 0.0);
    double total = 0;
    for (double v : samples) {
      if (!std::isfinite(v)) continue;
      total += 1;
      if (facets) ++out.facets;
      if (v < -lim || v > lim) {
        if (facets) ++out.facets_outside;
        continue;
      }
      h.density[std::size_t(std::min(nb - 1, int((v + lim) / (2 * lim) * nb)))] += 1;
    }
    const double width = 2 * lim / nb;
    for (auto& d : h.density) d = total > 0 ? d / (total * width) : 0.0;
    return h;
  };
  out.lower = hist(ls, true);
  if (in.upper_map) out.upper = hist(us, true);
  out.contact = hist(r.theta, false);
  return out;
}

/// A map over sliding directions: per direction the grid areal signature of the pair and
/// predict() along it, as `frictal anisotropy LOWER [--upper UPPER] --areal --hold` computes them
/// (the same angles to the bit: 2 pi k / n for the signature, (360 k / n) deg for the prediction).
/// One map is the pair of the map and itself turned over, as that command takes it without --upper.
ReportDirections directions_of(const ReportInput& in) {
  ReportDirections out;
  out.pair = in.upper_map.has_value();
  const int n = in.directions;
  const Map& upper_map = in.upper_map ? *in.upper_map : in.map;
  PredictSurface lower, upper;
  lower.is_map = upper.is_map = true;
  lower.map = in.map;
  lower.name = in.lower_name;
  if (in.upper_map) {
    upper.map = *in.upper_map;
    upper.name = in.upper_name;
  }
  PredictOptions po;
  po.atomic_friction = in.atomic_friction;
  po.runaway_distance = in.runaway_distance;
  po.map_drops = in.map_drops;
  po.threads = in.threads;
  po.detrend = Detrend{DetrendKind::None, 0};  // the page's maps are conditioned already
  // The whole job's estimated cost against the prediction's limit, as the command refuses it.
  const std::size_t drops = std::size_t(in.map_drops) * std::size_t(in.map_drops);
  const double work = map_work_estimate(upper_map.valid_count(), drops) * n;
  if (in.prediction && in.prediction->trust != "ok") {
    // A surface read wrong: its hold angles along other directions would cost each the headline's
    // time and say nothing until the input is fixed.
    std::string codes;
    for (const std::string& c : in.prediction->trust_codes) codes += (codes.empty() ? "" : ", ") + c;
    out.hold_failure = fmt::format("the headline is DOUBTFUL ({}): fix the input first", codes);
  } else if (po.map_work_limit > 0 && work > po.map_work_limit)
    out.hold_failure = fmt::format(
        "{} directions x {} drops on {} spheres would take about {:.0f} s of CPU, above the prediction's limit "
        "of {:.0f} s (fewer --directions or --drops, or a cropped or resampled map)",
        n, drops, upper_map.valid_count(), work, po.map_work_limit);
  for (int k = 0; k < n; ++k) {
    const double angle = 2 * std::numbers::pi * k / n;
    ArealSignatureOptions so;
    so.threads = in.threads;
    auto sig = areal_signature(in.map, upper_map, angle, so);
    if (!sig) {
      out.failure = sig.error().message;
      return out;
    }
    auto bound = predict_friction(in.atomic_friction, sig->theta_max_forward, sig->contact_slope_std);
    if (!bound) {
      out.failure = bound.error().message;
      return out;
    }
    AnisotropyRow row;
    row.direction = angle;
    row.theta_forward = sig->theta_max_forward;
    row.theta_backward = sig->theta_max_backward;
    row.sigma = sig->contact_slope_std;
    row.upper_bound_friction_angle = bound->friction_angle;
    row.upper_bound_friction_coefficient = bound->friction_coefficient;
    row.eq18_low_friction_coefficient = bound->friction_coefficient_low;
    if (out.hold_failure.empty()) {
      po.direction = (360.0 * k / n) * kDeg;  // as `frictal predict --direction DEG` converts
      auto hold = predict(lower, in.upper_map ? &upper : nullptr, po);
      if (!hold) {
        out.hold_failure = fmt::format("direction {:g}°: {}", deg(angle), hold.error().message);
      } else {
        // With the hold model its own bound (above every drop), the signature's beside it.
        row.upper_bound_friction_angle = hold->upper_bound_friction_angle;
        row.upper_bound_friction_coefficient = std::tan(hold->upper_bound_friction_angle);
        row.signature_bound_friction_angle = bound->friction_angle;
        row.hold_runaway_distance = hold->runaway_distance;
        row.hold_angle = hold->friction_angle;
        for (const Warning& w : hold->warnings)
          if (w.code != "reader")
            out.warnings.push_back({w.code, fmt::format("direction {:g}°: {}", deg(angle), w.message)});
      }
    }
    out.pair_table.push_back(std::move(row));
    if (in.progress) in.progress(std::size_t(k + 1), std::size_t(n));
  }
  if (!out.hold_failure.empty()) {  // one kind of row: the signature's bound only
    out.warnings.clear();
    for (AnisotropyRow& row : out.pair_table) {
      if (row.signature_bound_friction_angle) row.upper_bound_friction_angle = *row.signature_bound_friction_angle;
      row.upper_bound_friction_coefficient = std::tan(row.upper_bound_friction_angle);
      row.signature_bound_friction_angle.reset();
      row.hold_runaway_distance.reset();
      row.hold_angle.reset();
    }
  }
  double best = -1e9, worst = 1e9;
  for (const AnisotropyRow& row : out.pair_table) {
    const double v = row.hold_angle ? row.hold_angle->q50 : row.upper_bound_friction_angle;
    if (v > best) best = v, out.best_direction = row.direction;
    if (v < worst) worst = v, out.worst_direction = row.direction;
  }
  out.best_angle = best;
  out.worst_angle = worst;
  return out;
}

Result<ReportResolution> resolution_of(const ReportInput& in, const ReportSurfaces& s, const SignatureOptions& so) {
  constexpr std::size_t kResolutionOffsets = 1000;
  ReportResolution out;
  out.offsets = kResolutionOffsets;
  const Profile& lower = s.lower;
  const Profile& upper = s.upper;
  const double L = std::min(lower.length(), upper.length());
  const double h = std::max(lower.length() / double(lower.size() - 1), upper.length() / double(upper.size() - 1));
  const double cmax = L / 2, cmin = 4 * h;
  out.cutoff_max = cmax;
  out.cutoff_min = cmin;
  // The short reliability cutoff of the tip: the larger of the surfaces' (the map's: rows and
  // columns). NaN: the tip fails up to a quarter of the scan; 0: it follows every scale.
  if (in.tip_radius > 0) {
    auto c =
        in.is_map ? short_reliability_cutoff(in.map, in.tip_radius) : short_reliability_cutoff(lower, in.tip_radius);
    if (!c) return c.error();
    double v = *c;
    if (s.pair && !std::isnan(v)) {
      auto cu = short_reliability_cutoff(upper, in.tip_radius);
      if (!cu) return cu.error();
      v = std::isnan(*cu) ? *cu : std::max(v, *cu);
    }
    out.tip_cutoff = v;
  }
  if (!(cmax > cmin * 1.5)) return out;  // too few points
  for (int k = 0; k < in.resolution_steps; ++k) {
    const double c = cmax * std::pow(cmin / cmax, double(k) / double(in.resolution_steps - 1));
    auto lf = gaussian_lowpass(lower, c);
    if (!lf) return lf.error();
    Profile uf;
    if (s.pair) {
      auto u = gaussian_lowpass(upper, c);
      if (!u) return u.error();
      uf = std::move(*u);
    } else {
      uf = *lf;
    }
    // Sampled offsets (each evaluated exactly): a trend over cutoffs needs no event-exact
    // maximum, and smooth filtered pairs on grids that do not align cost seconds per cutoff
    // exactly.
    SignatureOptions rso = so;
    rso.offsets = kResolutionOffsets;
    auto rs = signature(*lf, rotate180(uf), rso);
    if (!rs) return rs.error();
    auto pr = predict_friction(in.atomic_friction, rs->theta_max_forward, rs->contact_slope_std);
    if (!pr) return pr.error();
    ReportResolutionRow row;
    row.cutoff = c;
    row.theta_max_forward = rs->theta_max_forward;
    row.theta_max_backward = rs->theta_max_backward;
    row.contact_slope_std = rs->contact_slope_std;
    row.friction_coefficient = pr->friction_coefficient;
    row.below_tip = out.tip_cutoff && (std::isnan(*out.tip_cutoff) || c < *out.tip_cutoff);
    out.rows.push_back(row);
  }
  return out;
}

}  // namespace

Result<ReportData> report_data(const ReportInput& in) {
  if (auto st = check_input(in); !st) return st.error();
  ReportData d;
  auto surfaces = surfaces_of(in);
  if (!surfaces) return surfaces.error();
  d.surfaces = std::move(*surfaces);
  const ReportSurfaces& s = d.surfaces;

  SignatureOptions so;
  so.threads = in.threads;
  so.keep_contacts = false;
  so.bins = in.bins;
  // The signature and the hold analysis in one pass over the lift (signature_with_hold: the
  // signature is the one signature() returns), not one lift each.
  // Its run-away distance: the one given, else the headline's (the stated test's d on the whole
  // page), else the hold analysis's default where the headline's does not fit these lines.
  HoldOptions ho;
  ho.runaway_distance = in.runaway_distance;
  ho.atomic_friction = in.atomic_friction;
  if (ho.runaway_distance <= 0 && in.prediction) ho.runaway_distance = in.prediction->runaway_distance;
  auto sig = signature_with_hold(s.lower, rotate180(s.upper), so, ho);
  if (!sig && ho.runaway_distance != in.runaway_distance) {
    ho.runaway_distance = in.runaway_distance;
    sig = signature_with_hold(s.lower, rotate180(s.upper), so, ho);
  }
  if (!sig) return sig.error();
  d.signature = std::move(sig->signature);
  const SignatureResult& r = d.signature;
  auto fwd = predict_friction(in.atomic_friction, r.theta_max_forward, r.contact_slope_std);
  if (!fwd) return fwd.error();
  d.forward = *fwd;
  auto bwd = predict_friction(in.atomic_friction, r.theta_max_backward, r.contact_slope_std);
  if (!bwd) return bwd.error();
  d.backward = *bwd;

  d.slopes = slopes_of(s, r, in.bins);

  d.hold = hold_of(std::move(sig->hold), d.forward);

  if (in.is_map && in.upper_map) {
    ReportArealHold a;
    if (auto st = areal_hold_into(in, a); !st) {
      a = ReportArealHold{};
      a.failure = st.error().message;
    }
    d.areal_hold = std::move(a);
  }
  if (in.is_map) d.areal = areal_signature_of(in);
  if (in.is_map) d.directions = directions_of(in);
  if (in.resolution_steps >= 2) {
    auto res = resolution_of(in, s, so);
    if (!res) return res.error();
    d.resolution = std::move(*res);
  }
  return d;
}

}  // namespace frictal::report
