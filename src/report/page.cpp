// The self-contained HTML page of `frictal report`: every number on it is computed here.
#include <fmt/core.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "frictal/analysis.hpp"
#include "frictal/areal.hpp"
#include "frictal/filter.hpp"
#include "frictal/hold.hpp"
#include "frictal/report.hpp"
#include "frictal/scan_stats.hpp"
#include "frictal/signature.hpp"
#include "frictal/stats.hpp"
#include "frictal/units.hpp"

namespace frictal::report {

namespace {

constexpr double kDeg = units::kRadPerDeg;
constexpr double deg(double rad) { return units::to_deg(rad); }

std::string fmt_len(double v, const LengthUnit& u, int digits = 4) {
  return fmt::format("{:.{}g} {}", v / u.scale, digits, u.name);
}
std::string fmt_deg(double rad) {
  const double d = deg(rad);
  return fmt::format("{:.3f}\u00b0", std::abs(d) < 5e-4 ? 0.0 : d);  // no "-0.000"
}
std::string fmt_mu(double mu) {
  if (!std::isfinite(mu)) return std::string("\u221e (interlocked)");
  return fmt::format("{:.4f}", std::abs(mu) < 5e-5 ? 0.0 : mu);  // no "-0.0000"
}

std::string row(const std::string& name, const std::string& value, const std::string& note = "") {
  return fmt::format("<tr><th>{}</th><td>{}</td><td class=\"note\">{}</td></tr>\n", name, value, note);
}

/// The signature's theta as a drawable line: piecewise between events, each interval from its two
/// one-sided values (theta_right at its start, theta_left at its end).
Series signature_series(const SignatureResult& r, const LengthUnit& u, const std::string& label,
                        const std::string& color) {
  Series s;
  s.label = label;
  s.color = color;
  s.line_width = 1.2;
  const std::size_t n = r.offset.size();
  for (std::size_t i = 0; i + 1 < n; ++i) {
    s.x.push_back(r.offset[i] / u.scale);
    s.y.push_back(deg(r.theta_right[i]));
    s.x.push_back(r.offset[i + 1] / u.scale);
    s.y.push_back(deg(r.theta_left[i + 1]));
  }
  if (n == 1) {
    s.x.push_back(r.offset[0] / u.scale);
    s.y.push_back(deg(r.theta[0]));
    s.style = SeriesStyle::Points;
  }
  return s;
}

Series histogram_series(const Histogram& h, const std::string& label, const std::string& color, bool dashed = false) {
  Series s;
  s.style = SeriesStyle::Step;
  s.label = label;
  s.color = color;
  s.dashed = dashed;
  for (double e : h.edges) s.x.push_back(deg(e));
  for (double d : h.density) s.y.push_back(d * kDeg);  // per degree
  return s;
}

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

/// The file name without its folders (titles and legends; the full paths are stated in the assumptions).
std::string base(const std::string& path) {
  const auto k = path.find_last_of('/');
  return k == std::string::npos ? path : path.substr(k + 1);
}

struct Section {
  std::string id, title, html;
};

std::string figure(const std::string& svg, const std::string& caption) {
  return fmt::format("<figure>{}<figcaption>{}</figcaption></figure>\n", svg, caption);
}

}  // namespace

Result<std::string> surface_report(const ReportInput& in) {
  if (!(std::isfinite(in.atomic_friction) && in.atomic_friction >= 0))
    return make_error(fmt::format("report: atomic friction must be a finite number >= 0, got {}", in.atomic_friction));
  if (in.resolution_steps == 1 || in.resolution_steps < 0 || in.resolution_steps > 100)
    return make_error(fmt::format("report: resolution steps must be 0 or 2..100, got {}", in.resolution_steps));
  if (in.is_map && in.upper) return make_error("report: an upper profile for a map: give the upper map as upper_map");
  if (in.is_map && (in.directions < 1 || in.directions > 720))
    return make_error(fmt::format("report: directions must be in 1..720, got {}", in.directions));
  if (in.bins < 2 || in.bins > 10000)
    return make_error(fmt::format("report: bins must be in 2..10000, got {}", in.bins));
  if (!(std::isfinite(in.tip_radius) && in.tip_radius >= 0))
    return make_error(fmt::format("report: tip radius must be a finite length >= 0 (m), got {}", in.tip_radius));

  std::vector<Section> sections;
  std::vector<std::string> assumptions;
  const std::string lower_name = in.lower_name.empty() ? std::string("surface") : in.lower_name;

  // The profile(s) the signature works on.
  Profile lower;
  if (in.is_map) {
    if (auto v = validate(in.map, lower_name); !v) return v.error();
    auto c = central_line(in.map);
    if (!c) return c.error();
    lower = std::move(*c);
  } else {
    if (auto v = validate(in.lower, lower_name); !v) return v.error();
    lower = in.lower;
  }
  const bool pair = in.upper.has_value();
  const Profile upper_measured = pair ? *in.upper : lower;
  if (pair)
    if (auto v = validate(upper_measured, in.upper_name); !v) return v.error();
  const std::string upper_name = pair ? in.upper_name : lower_name;

  // --- the surface -----------------------------------------------------------------------------
  const LengthUnit xu = length_unit(std::max(lower.length(), upper_measured.length()));
  {
    std::string html;
    if (in.is_map) {
      const MapStats st = map_stats(in.map);
      MapImage mi;
      mi.title = "Height map";
      mi.line_y = lower.x.empty() ? std::nullopt : std::optional<double>(in.map.y0 + in.map.height() / 2);
      mi.line_x0 = in.map.x0 + lower.x.front();  // the central line's abscissa starts at the map's x0
      mi.line_x1 = in.map.x0 + lower.x.back();
      mi.line_label = "line used for the signature";
      auto svg = map_svg(in.map, mi);
      if (!svg) return svg.error();
      const std::size_t f =
          std::max<std::size_t>(1, (std::max(in.map.nx, in.map.ny) + mi.max_pixels - 1) / mi.max_pixels);
      const LengthUnit lu = length_unit(std::max(st.width, st.height));
      html += figure(*svg,
                     fmt::format("{} × {} points, {} × {}; spacing {} × {}. {}Colours span the {:g} to {:g} % "
                                 "quantiles of the heights (outliers saturate); grey: no data.",
                                 in.map.nx, in.map.ny, fmt_len(st.width, lu), fmt_len(st.height, lu),
                                 fmt_len(in.map.dx, length_unit(in.map.dx)), fmt_len(in.map.dy, length_unit(in.map.dy)),
                                 f > 1 ? fmt::format("Shown block-averaged {} × {} to {} × {} pixels. ", f, f,
                                                     (in.map.nx + f - 1) / f, (in.map.ny + f - 1) / f)
                                       : std::string(),
                                 100 * mi.low_quantile, 100 * mi.high_quantile));
      const LengthUnit zu = length_unit(st.Sq > 0 ? st.Sq : 1e-9);
      html += "<table class=\"stats\"><caption>Areal statistics (ISO 25178-2 style, about the mean)</caption>\n";
      html += row("points (valid)", fmt::format("{} ({})", st.points, st.valid),
                  st.valid < st.points ? "holes excluded" : "");
      html += row("Sq", fmt_len(st.Sq, zu), "rms height");
      html += row("Sa", fmt_len(st.Sa, zu), "mean absolute height");
      html +=
          row("Sp / Sv / Sz", fmt::format("{} / {} / {}", fmt_len(st.Sp, zu), fmt_len(st.Sv, zu), fmt_len(st.Sz, zu)),
              "highest peak, deepest valley, their sum");
      html += row("Ssk / Sku", fmt::format("{:.4f} / {:.4f}", st.Ssk, st.Sku), "skewness, kurtosis");
      html += row("Sdq", fmt::format("{:.4f}", st.Sdq), "rms gradient (forward differences)");
      html += row("steepest neighbour slope", fmt_deg(st.max_slope), "");
      html += "</table>\n";
    } else {
      Plot p;
      p.title = pair ? "The two surfaces, as measured (material below)" : "The surface profile";
      const double zmag = std::max(profile_stats(lower).rms_height, profile_stats(upper_measured).rms_height);
      const LengthUnit zu = length_unit(zmag > 0 ? 3 * zmag : 1e-9);
      p.x_label = fmt::format("x ({})", xu.name);
      p.y_label = fmt::format("height z ({})", zu.name);
      auto add = [&](const Profile& pr, const std::string& label, const std::string& color) {
        Series s;
        s.label = label;
        s.color = color;
        s.line_width = 1.0;
        for (std::size_t i = 0; i < pr.size(); ++i) {
          s.x.push_back(pr.x[i] / xu.scale);
          s.y.push_back(pr.z[i] / zu.scale);
        }
        p.series.push_back(std::move(s));
      };
      add(lower, pair ? "lower: " + base(lower_name) : base(lower_name), "#1f77b4");
      if (pair) add(upper_measured, "upper: " + base(upper_name), "#d62728");
      p.height = 300;
      auto svg = plot_svg(p);
      if (!svg) return svg.error();
      const double ex = xu.scale / zu.scale;
      html += figure(*svg, ex > 1.5 ? fmt::format("Heights (in {}) are drawn magnified relative to x (in {}); slopes "
                                                  "below are true slopes.",
                                                  zu.name, xu.name)
                                    : std::string("Heights and x on their own scales; slopes below are true slopes."));
    }
    auto stats_table = [&](const Profile& pr, const std::string& name) {
      const ProfileStats st = profile_stats(pr);
      const LengthUnit zu = length_unit(st.rms_height > 0 ? 3 * st.rms_height : 1e-9);
      std::string t =
          fmt::format("<table class=\"stats\"><caption>Profile statistics: {}</caption>\n", escape_html(name));
      t +=
          row("points", fmt::format("{}", st.points), is_uniform(pr, 1e-6) ? "uniform spacing" : "non-uniform spacing");
      t += row("length L", fmt_len(st.length, length_unit(st.length)), "x_max − x_min");
      t += row("rms height", fmt_len(st.rms_height, zu), "exact for the polyline");
      t += row("rms slope", fmt::format("{:.4f}", st.rms_slope), "√⟨z′²⟩");
      t += row("steepest edge", fmt_deg(st.max_slope), "max |atan z′|");
      t += row("mean slope angle", fmt_deg(st.mean_slope), "⟨atan z′⟩");
      return t + "</table>\n";
    };
    html += stats_table(lower, in.is_map ? "the central line along x (used below)" : base(lower_name));
    if (pair) html += stats_table(upper_measured, base(upper_name));
    sections.push_back({"surface", "The surface", html});
  }

  // --- the signature ---------------------------------------------------------------------------
  SignatureOptions so;
  so.threads = in.threads;
  so.keep_contacts = false;
  so.bins = in.bins;
  auto sig = signature(lower, rotate180(upper_measured), so);
  if (!sig) return sig.error();
  const SignatureResult& r = *sig;
  auto fwd = predict_friction(in.atomic_friction, r.theta_max_forward, r.contact_slope_std);
  if (!fwd) return fwd.error();
  auto bwd = predict_friction(in.atomic_friction, r.theta_max_backward, r.contact_slope_std);
  if (!bwd) return bwd.error();
  {
    Plot p;
    p.title = "Signature function θ(x_ofs) (Eq. 1–3)";
    p.x_label = fmt::format("offset x_ofs of the upper block ({})", xu.name);
    p.y_label = "contact slope θ (deg)";
    p.series.push_back(signature_series(r, xu, "", "#1f77b4"));
    p.lines.push_back(
        {true, deg(r.theta_max_forward), fmt::format("θ_max forward = {:.3f}°", deg(r.theta_max_forward)), "#d62728"});
    p.lines.push_back({true, -deg(r.theta_max_backward),
                       fmt::format("−θ_max backward = −{:.3f}°", deg(r.theta_max_backward)), "#2ca02c"});
    auto svg = plot_svg(p);
    if (!svg) return svg.error();
    std::string html = figure(
        *svg, fmt::format("{} offsets{}; θ is the slope of the steepest contact at each offset; between offsets the "
                          "line joins the exact one-sided slopes of the lift h(x_ofs).",
                          r.offset.size(),
                          r.exact ? fmt::format(" (every one of the {} event offsets: exact)", r.events)
                                  : " (the point grids do not align: offsets sampled at the finer point spacing, each "
                                    "evaluated exactly)"));
    sections.push_back({"signature", "Signature function", html});
  }
  // --- slope distributions (Fig. 16 style) -------------------------------------------------------
  {
    auto edge_samples = [](const Profile& pr, std::vector<double>& s, std::vector<double>& w) {
      for (std::size_t i = 0; i + 1 < pr.size(); ++i) {
        const double dx = pr.x[i + 1] - pr.x[i];
        if (dx <= 0) continue;  // vertical jumps have no length
        s.push_back(std::atan((pr.z[i + 1] - pr.z[i]) / dx));
        w.push_back(dx);
      }
    };
    // |slope| below which a fraction q of the weight lies
    auto quantile_abs = [](const std::vector<double>& s, const std::vector<double>& w, double q) {
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
    };
    std::vector<double> ls, lw, us, uw;
    edge_samples(lower, ls, lw);
    if (pair) edge_samples(upper_measured, us, uw);
    double lim = std::max({r.theta_max_forward, r.theta_max_backward, quantile_abs(ls, lw, 0.995),
                           pair ? quantile_abs(us, uw, 0.995) : 0.0});
    lim = std::min(std::numbers::pi / 2, lim * 1.1 + 1e-12);
    // Densities relative to all the weight: samples outside +-lim are counted, not drawn.
    double outside_len = 0, total_len = 0;
    auto rebin = [&](const std::vector<double>& samples, const std::vector<double>& weights, bool count_outside) {
      Histogram h;
      const int nb = in.bins;
      for (int i = 0; i <= nb; ++i) h.edges.push_back(-lim + 2 * lim * i / nb);
      h.density.assign(std::size_t(nb), 0.0);
      double total = 0;
      for (std::size_t i = 0; i < samples.size(); ++i) {
        const double w = weights.empty() ? 1.0 : weights[i];
        if (!std::isfinite(samples[i]) || !(w > 0)) continue;
        total += w;
        const double v = samples[i];
        if (v < -lim || v > lim) {
          if (count_outside) outside_len += w;
          continue;
        }
        h.density[std::size_t(std::min(nb - 1, int((v + lim) / (2 * lim) * nb)))] += w;
      }
      if (count_outside) total_len += total;
      const double width = 2 * lim / nb;
      for (auto& d : h.density) d = total > 0 ? d / (total * width) : 0.0;
      return h;
    };
    Histogram surf = rebin(ls, lw, true);
    Histogram contact = rebin(r.slope_samples, r.slope_weights, false);
    Plot p;
    p.title = "Slope distributions (paper Fig. 16)";
    p.x_label = "slope angle (deg)";
    p.y_label = "probability density (1/deg)";
    p.series.push_back(histogram_series(surf, pair ? "surface slopes: lower" : "surface slopes", "#1f77b4"));
    if (pair) p.series.push_back(histogram_series(rebin(us, uw, true), "surface slopes: upper", "#9467bd", true));
    p.series.push_back(histogram_series(contact, "contact slopes θ(x_ofs)", "#d62728"));
    auto svg = plot_svg(p);
    if (!svg) return svg.error();
    std::string html = figure(
        *svg,
        fmt::format(
            "Surface slopes: every edge of the profile weighted by its length. Contact slopes: θ at each offset "
            "weighted "
            "by the offset length it stands for; mean {}, standard deviation σ = {} (Eq. 18). {} bins over ±{:.2f}°{}.",
            fmt_deg(r.contact_slope_mean), fmt_deg(r.contact_slope_std), in.bins, deg(lim),
            outside_len > 0
                ? fmt::format(
                      "; {:.2f} % of the surface length is steeper (counted in the densities, beyond "
                      "the axis; steepest edge {})",
                      100 * outside_len / total_len,
                      fmt_deg(std::max(profile_stats(lower).max_slope, profile_stats(upper_measured).max_slope)))
                : std::string()));
    sections.push_back({"slopes", "Slope distributions", html});
  }
  // --- friction ---------------------------------------------------------------------------------
  {
    std::string t =
        "<table class=\"friction\"><tr><th></th><th>towards +x (forward)</th><th>towards −x (backward)</th></tr>\n";
    auto two = [&](const std::string& name, const std::string& a, const std::string& b) {
      t += fmt::format("<tr><th>{}</th><td>{}</td><td>{}</td></tr>\n", name, a, b);
    };
    two("θ_max (steepest reachable contact)", fmt_deg(r.theta_max_forward), fmt_deg(r.theta_max_backward));
    two("σ (std of the contact slopes)", fmt_deg(r.contact_slope_std), fmt_deg(r.contact_slope_std));
    two("atomic friction μ_a, θ_a = atan μ_a", fmt::format("{:g}, {}", in.atomic_friction, fmt_deg(fwd->atomic_angle)),
        fmt::format("{:g}, {}", in.atomic_friction, fmt_deg(bwd->atomic_angle)));
    two("rigid upper bound θ_a + θ_max (Eq. 6)", fmt_deg(fwd->friction_angle), fmt_deg(bwd->friction_angle));
    two("upper bound of μ, tan(θ_a + θ_max)", fmt_mu(fwd->friction_coefficient), fmt_mu(bwd->friction_coefficient));
    two("Eq. 18 range of φ", fmt::format("{} … {}", fmt_deg(fwd->friction_angle_low), fmt_deg(fwd->friction_angle)),
        fmt::format("{} … {}", fmt_deg(bwd->friction_angle_low), fmt_deg(bwd->friction_angle)));
    two("Eq. 18 range of μ",
        fmt::format("{} … {}", fmt_mu(fwd->friction_coefficient_low), fmt_mu(fwd->friction_coefficient)),
        fmt::format("{} … {}", fmt_mu(bwd->friction_coefficient_low), fmt_mu(bwd->friction_coefficient)));
    t += "</table>\n";
    t += fmt::format(
        "<p class=\"verdict\">Predicted static friction coefficient <b>μ = {}</b> for sliding towards +x "
        "(statistical range {} … {}, Eq. 18) and <b>{}</b> towards −x, with μ_a = {:g}.</p>\n",
        fmt_mu(fwd->friction_coefficient), fmt_mu(fwd->friction_coefficient_low), fmt_mu(fwd->friction_coefficient),
        fmt_mu(bwd->friction_coefficient), in.atomic_friction);
    sections.push_back({"friction", "Predicted friction (Eq. 6 and 18)", t});
  }
  // --- what a tilt test reads: the hold angle (hold.hpp) -----------------------------------------
  {
    HoldOptions ho;
    ho.runaway_distance = in.runaway_distance;
    ho.atomic_friction = in.atomic_friction;
    auto ha = analyse_hold(lower, rotate180(upper_measured), so, ho);
    if (!ha) return ha.error();
    const HoldDistribution& f = ha->distribution.forward;
    const HoldDistribution& b = ha->distribution.backward;
    // h(s) over the drop range with the basins' rest offsets.
    Plot lp;
    lp.title = "Lift h(x_ofs) of the upper block and the basins where dropped blocks rest";
    lp.x_label = fmt::format("offset x_ofs of the upper block ({})", xu.name);
    double hlo = std::numeric_limits<double>::infinity(), hhi = -hlo;
    for (std::size_t i = 0; i < ha->curve.offset.size(); ++i)
      if (ha->curve.offset[i] >= f.drop_min && ha->curve.offset[i] <= f.drop_max) {
        hlo = std::min(hlo, ha->curve.lift[i]);
        hhi = std::max(hhi, ha->curve.lift[i]);
      }
    const LengthUnit hu = length_unit(std::max(std::abs(hlo), std::abs(hhi)));
    lp.y_label = fmt::format("lift h ({})", hu.name);
    Series ls, rs;
    ls.label = "h(x_ofs)";
    ls.color = "#1f77b4";
    ls.line_width = 1.2;
    for (std::size_t i = 0; i < ha->curve.offset.size(); ++i) {
      ls.x.push_back(ha->curve.offset[i] / xu.scale);
      ls.y.push_back(ha->curve.lift[i] / hu.scale);
    }
    rs.label = fmt::format("rest offsets ({} basins)", f.basins.rest.size());
    rs.color = "#d62728";
    rs.style = SeriesStyle::Points;
    for (double x : f.basins.rest) {
      rs.x.push_back(x / xu.scale);
      const auto it = std::lower_bound(ha->curve.offset.begin(), ha->curve.offset.end(), x);
      const std::size_t k =
          std::min<std::size_t>(static_cast<std::size_t>(it - ha->curve.offset.begin()), ha->curve.offset.size() - 1);
      rs.y.push_back(ha->curve.lift[k] / hu.scale);
    }
    lp.series = {ls, rs};
    lp.x_min = f.drop_min / xu.scale;
    lp.x_max = f.drop_max / xu.scale;
    auto lsvg = plot_svg(lp);
    if (!lsvg) return lsvg.error();
    // The distribution over drops, each basin weighted by the width it drains.
    const double lo_deg = deg(std::min({f.hold.min, f.inertial.min, fwd->friction_angle_low}));
    const double hi_deg = deg(std::max({f.hold.max, f.inertial.max, fwd->friction_angle}));
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
    Plot hp;
    hp.title = "Hold angle over drops (towards +x): the distribution repeated tilt tests give";
    hp.x_label = "friction angle φ (deg)";
    hp.y_label = "probability density (1/deg)";
    hp.series.push_back(histogram_series(hist(f.basins.hold), "quasi-static hold angle φ_qs", "#1f77b4"));
    hp.series.push_back(histogram_series(hist(f.basins.inertial), "inertial bound φ_in", "#9467bd", true));
    hp.bands.push_back({false, deg(fwd->friction_angle_low), deg(fwd->friction_angle), "Eq. 18 range", "#f2c94c", 0.3});
    hp.lines.push_back(
        {false, deg(fwd->friction_angle), fmt::format("θ_a + θ_max = {:.3f}°", deg(fwd->friction_angle)), "#d62728"});
    auto hsvg = plot_svg(hp);
    if (!hsvg) return hsvg.error();
    std::string html =
        "<p>θ_max bounds the friction of a rigid pair; a tilt test reads something else. A block put down at one "
        "offset slides to the bottom of its basin of the lift h; tilted slowly, it stays where the slope of h ahead "
        "of it is at least the tilt and otherwise slips to the next steeper slope; the test reads the tilt at the "
        "first slip of at least the run-away distance d (the <i>quasi-static hold angle</i> φ_qs). Without "
        "dissipation a block coasts d once no point of h within d rises above the chord from its rest: the "
        "<i>inertial bound</i> φ_in. Definitions: docs/analysis.md.</p>\n";
    html += figure(*lsvg, fmt::format("The lift h over the drops' range; red: the rest offsets of the {} basins "
                                      "(local minima of h) into which drops spread uniformly over the range fall.",
                                      f.basins.rest.size()));
    html += figure(
        *hsvg,
        fmt::format("Each basin weighted by the width of the drop range it drains; run-away distance d = {:.4g} {}. "
                    "Shaded: Eq. 18's heuristic range [θ_max − σ, θ_max] + θ_a over the offset range; a block that "
                    "slips on before the run-away can reach steeper contacts beyond it.",
                    ha->runaway_distance / xu.scale, xu.name));
    std::string t =
        "<table class=\"friction\"><tr><th></th><th>towards +x (forward)</th><th>towards −x (backward)</th></tr>\n";
    auto two = [&](const std::string& name, const std::string& x, const std::string& y) {
      t += fmt::format("<tr><th>{}</th><td>{}</td><td>{}</td></tr>\n", name, x, y);
    };
    auto range = [](const HoldStatistics& st) {
      return fmt::format("{} ± {} (5–95 %: {} … {})", fmt_deg(st.mean), fmt_deg(st.std), fmt_deg(st.q05),
                         fmt_deg(st.q95));
    };
    two("quasi-static hold angle φ_qs over drops", range(f.hold), range(b.hold));
    two("inertial bound φ_in over drops", range(f.inertial), range(b.inertial));
    two("Eq. 18 range of φ", fmt::format("{} … {}", fmt_deg(fwd->friction_angle_low), fmt_deg(fwd->friction_angle)),
        fmt::format("{} … {}", fmt_deg(bwd->friction_angle_low), fmt_deg(bwd->friction_angle)));
    t += "</table>\n";
    html += t;
    sections.push_back({"hold", "What a tilt test reads: the hold angle", html});
  }
  // --- areal blocks that may move sideways (two maps) ----------------------------------------------
  if (in.is_map && in.upper_map) {
    std::string html;
    auto section = [&]() -> Status {
      if (auto v = validate(*in.upper_map, in.upper_name); !v) return v.error();
      ArealLiftOptions lo;
      lo.threads = in.threads;
      auto lift = areal_lift(in.map, *in.upper_map, 0.0, lo);
      if (!lift) return lift.error();
      const ArealLift& L = *lift;
      ArealHoldOptions ho;
      ho.runaway_distance = in.runaway_distance > 0 ? in.runaway_distance : 0.1 * (L.along(L.n_along - 1) - L.along(0));
      ho.atomic_friction = in.atomic_friction;
      ho.threads = in.threads;
      auto start = areal_lift_node(L, 0.0, 0.0);
      if (!start) return start.error();
      auto free = areal_hold_angle(L, *start, ho);
      if (!free) return free.error();
      auto locked = areal_locked_hold_angle(L, free->rest, ho);
      if (!locked) return locked.error();
      auto dfree = areal_hold_distribution(L, ho);
      if (!dfree) return dfree.error();
      ho.lateral = LateralMotion::Locked;
      auto dlocked = areal_hold_distribution(L, ho);
      if (!dlocked) return dlocked.error();
      // The lift as a map over (u, v) (sliding along x: u = x, v = y).
      Map lm;
      lm.nx = L.n_along;
      lm.ny = L.n_across;
      lm.dx = L.step;
      lm.dy = L.across_step;
      lm.x0 = L.along(0);
      lm.y0 = L.across(0);
      lm.heights = L.lift;
      MapImage mi;
      mi.title = "The lift h over two dimensions of offset";
      mi.x_label = "offset along the sliding direction, s_x";
      mi.y_label = "offset across it, s_y";
      mi.z_label = "lift h";
      mi.absolute_axes = true;
      for (std::size_t k : free->path) {
        const auto p = L.offset_xy(k);
        mi.path_x.push_back(p[0]);
        mi.path_y.push_back(p[1]);
      }
      mi.path_label = free->ran_off_end ? "runs off the grid" : "run-away";
      const auto s0 = L.offset_xy(free->start), r0 = L.offset_xy(free->rest), h0 = L.offset_xy(free->hold_node);
      mi.marks.push_back({s0[0], s0[1], "drop", "#ffffff"});
      mi.marks.push_back({r0[0], r0[1], "rest", "#d62728"});
      if (free->hold_node != free->rest) mi.marks.push_back({h0[0], h0[1], "held", "#ff7f0e"});
      auto msvg = map_svg(lm, mi);
      if (!msvg) return msvg.error();
      // The two distributions over drops: weighted histograms of the basins' angles.
      double amax = std::max(dfree->hold.max, dlocked->hold.max);
      const int bins = 40;
      const double top = deg(amax) > 0 ? deg(amax) * 1.0001 : 1.0;
      auto hist = [&](const ArealHoldDistribution& d, const std::string& label, const std::string& color) {
        Series sr;
        sr.style = SeriesStyle::Step;
        sr.label = label;
        sr.color = color;
        for (int b = 0; b <= bins; ++b) sr.x.push_back(top * b / bins);
        sr.y.assign(bins, 0.0);
        for (std::size_t k = 0; k < d.angle.size(); ++k) {
          const int b = std::min(bins - 1, int(deg(d.angle[k]) / top * bins));
          sr.y[std::size_t(b)] += 100.0 * double(d.weight[k]) / double(d.drops);
        }
        return sr;
      };
      Plot hp;
      hp.title = "Hold angle over drops";
      hp.x_label = "hold angle (deg)";
      hp.y_label = "drops (%)";
      hp.series = {hist(*dfree, "free to move sideways", "#d62728"), hist(*dlocked, "locked (1D rule)", "#1f77b4")};
      auto hsvg = plot_svg(hp);
      if (!hsvg) return hsvg.error();
      const LengthUnit su = length_unit(std::max(std::abs(L.along(L.n_along - 1)), std::abs(L.across(0))));
      html +=
          "<p>The upper map turned over onto the lower one and moved by an offset s in the plane; the lift h(s) is "
          "the height of its reference point at contact. Tilted about the axis across the sliding direction (+x), a "
          "rigid block that does not rotate moves on h under the tilt and steers around asperities if it may move "
          "sideways. Definitions and how μ_a enters: docs/analysis.md (\"Areal blocks that may move sideways\").</p>\n";
      html +=
          figure(*msvg, fmt::format("{} × {} offsets; red: the path of a block dropped at s = 0 (white), from its "
                                    "rest offset up to the end of its run-away slip (free to move sideways, run-away "
                                    "distance {:.4g} {}).",
                                    L.n_along, L.n_across, ho.runaway_distance / su.scale, su.name));
      html += figure(*hsvg, fmt::format("{} drops spread uniformly over the offsets (the last d along x and d from the "
                                        "lateral edges left out), each node one drop.",
                                        dfree->drops));
      std::string t = "<table class=\"friction\"><tr><th></th><th>free to move sideways</th><th>locked</th></tr>\n";
      t += fmt::format("<tr><th>hold angle from s = 0 (rest at ({}, {}) {})</th><td>{}</td><td>{}</td></tr>\n",
                       fmt::format("{:.4g}", r0[0] / su.scale), fmt::format("{:.4g}", r0[1] / su.scale), su.name,
                       fmt_deg(free->hold_angle), fmt_deg(locked->hold_angle));
      auto range = [](const HoldStatistics& st) {
        return fmt::format("{} ± {} (5–95 %: {} … {}; min {}, max {})", fmt_deg(st.mean), fmt_deg(st.std),
                           fmt_deg(st.q05), fmt_deg(st.q95), fmt_deg(st.min), fmt_deg(st.max));
      };
      t +=
          fmt::format("<tr><th>over drops</th><td>{}</td><td>{}</td></tr>\n", range(dfree->hold), range(dlocked->hold));
      t += "</table>\n";
      html += t;
      return Ok{};
    };
    if (auto st = section(); !st)
      html = fmt::format("<p>Not computed for this pair: {}.</p>\n", escape_html(st.error().message));
    sections.push_back({"areal-hold", "Areal blocks that may move sideways", html});
  }
  // --- friction over sliding directions (maps) ---------------------------------------------------
  if (in.is_map) {
    DirectionalOptions o;
    o.max_lines = in.max_lines;
    o.threads = in.threads;
    o.atomic_friction = in.atomic_friction;
    o.signature.keep_contacts = false;
    // small maps: shorter lines are accepted (at least 4 points, the directional minimum)
    o.min_points = std::clamp<std::size_t>(std::min(in.map.nx, in.map.ny) / 2, 4, 32);
    auto table = anisotropy(in.map, in.directions, o);
    std::string html;
    if (!table) {
      html = fmt::format("<p>Not computed for this map: {}.</p>\n", escape_html(table.error().message));
    } else {
      Series phi, low;
      phi.label = "φ (Eq. 6), mean over parallel lines";
      phi.color = "#d62728";
      low.label = "φ − σ (Eq. 18 lower end)";
      low.color = "#1f77b4";
      low.dashed = true;
      double best = -1, worst = 1e9, best_dir = 0, worst_dir = 0;
      for (const auto& d : *table) {
        phi.x.push_back(d.angle);
        phi.y.push_back(deg(d.prediction.friction_angle));
        low.x.push_back(d.angle);
        low.y.push_back(std::max(0.0, deg(d.prediction.friction_angle_low)));
        if (d.prediction.friction_angle > best) best = d.prediction.friction_angle, best_dir = d.angle;
        if (d.prediction.friction_angle < worst) worst = d.prediction.friction_angle, worst_dir = d.angle;
      }
      PolarPlot pp;
      pp.title = "Friction over sliding directions";
      pp.radius_label = "friction angle (deg)";
      pp.series = {phi, low};
      auto svg = polar_svg(pp);
      if (!svg) return svg.error();
      html = figure(
          *svg, fmt::format("{} directions (0° = +x, 90° = +y). For each, up to {} parallel lines of the map (of at "
                            "least {} points), each against itself turned over; θ_max and σ are length-weighted means "
                            "over the lines. μ_a = {:g}.",
                            in.directions, in.max_lines, o.min_points, in.atomic_friction));
      html += fmt::format(
          "<p class=\"verdict\">Highest friction sliding towards {:.0f}°: φ = {} (μ = {}); lowest towards {:.0f}°: φ = "
          "{} "
          "(μ = {}). Anisotropy ratio μ_max/μ_min = {}.</p>\n",
          deg(best_dir), fmt_deg(best), fmt_mu(std::tan(best)), deg(worst_dir), fmt_deg(worst), fmt_mu(std::tan(worst)),
          std::tan(worst) > 1e-6 ? fmt::format("{:.3f}", std::tan(best) / std::tan(worst))
                                 : std::string("unbounded (μ_min ≈ 0)"));
    }
    sections.push_back({"directions", "Friction over sliding directions", html});
  }
  // --- resolution -------------------------------------------------------------------------------
  if (in.resolution_steps >= 2) {
    constexpr std::size_t kResolutionOffsets = 1000;
    const double L = std::min(lower.length(), upper_measured.length());
    const double h = std::max(lower.length() / double(lower.size() - 1),
                              upper_measured.length() / double(upper_measured.size() - 1));
    const double cmax = L / 2, cmin = 4 * h;
    // The short reliability cutoff of the tip: the larger of the surfaces' (the map's: rows and
    // columns). NaN: the tip fails up to a quarter of the scan; 0: it follows every scale.
    std::optional<double> tip_cutoff;
    if (in.tip_radius > 0) {
      auto c =
          in.is_map ? short_reliability_cutoff(in.map, in.tip_radius) : short_reliability_cutoff(lower, in.tip_radius);
      if (!c) return c.error();
      double v = *c;
      if (pair && !std::isnan(v)) {
        auto cu = short_reliability_cutoff(upper_measured, in.tip_radius);
        if (!cu) return cu.error();
        v = std::isnan(*cu) ? *cu : std::max(v, *cu);
      }
      tip_cutoff = v;
    }
    std::string tip_text;
    if (tip_cutoff) {
      const std::string r = fmt_len(in.tip_radius, length_unit(in.tip_radius));
      if (std::isnan(*tip_cutoff))
        tip_text = fmt::format(
            " A tip of radius {} cannot follow this surface at any scale up to a quarter of its length (its peaks "
            "are curved more than 1/(2R) there): no cutoff on this page is reliable.",
            r);
      else if (*tip_cutoff == 0)
        tip_text = fmt::format(
            " A tip of radius {} follows this surface down to the sampling interval: every cutoff here is within "
            "its reach.",
            r);
      else
        tip_text = fmt::format(
            " The dashed grey vertical line is the short reliability cutoff for a tip of radius {}: {} (below it the "
            "measured peaks are curved more than 1/(2R), half the tip's curvature: the scan shows the tip rather than "
            "the surface, and θ_max from the finer scales is not to be trusted; rows below it are marked in the "
            "table).",
            r, fmt_len(*tip_cutoff, length_unit(*tip_cutoff)));
    }
    std::string html;
    if (!(cmax > cmin * 1.5)) {
      html = fmt::format(
          "<p>Too few points for a resolution study (needs a cutoff range from 4 spacings, {}, to half "
          "the length, {}).</p>",
          fmt_len(cmin, xu), fmt_len(cmax, xu));
      if (!tip_text.empty()) html += "<p>" + tip_text.substr(1) + "</p>";
    } else {
      Series fw, bw, sg;
      fw.label = "θ_max forward";
      fw.color = "#d62728";
      bw.label = "θ_max backward";
      bw.color = "#2ca02c";
      sg.label = "σ";
      sg.color = "#1f77b4";
      sg.dashed = true;
      std::string t =
          "<table class=\"resolution\"><tr><th>cutoff λ_c</th><th>θ_max forward</th><th>θ_max "
          "backward</th><th>σ</th><th>μ forward (μ_a = " +
          fmt::format("{:g}", in.atomic_friction) + ")</th></tr>\n";
      for (int k = 0; k < in.resolution_steps; ++k) {
        const double c = cmax * std::pow(cmin / cmax, double(k) / double(in.resolution_steps - 1));
        auto lf = gaussian_lowpass(lower, c);
        if (!lf) return lf.error();
        Profile uf;
        if (pair) {
          auto u = gaussian_lowpass(upper_measured, c);
          if (!u) return u.error();
          uf = std::move(*u);
        } else {
          uf = *lf;
        }
        // Sampled offsets (each evaluated exactly): a trend over cutoffs needs no event-exact
        // maximum, and smooth filtered pairs on grids that do not align cost seconds per cutoff
        // exactly (bench/results/report.md).
        SignatureOptions rso = so;
        rso.offsets = kResolutionOffsets;
        auto rs = signature(*lf, rotate180(uf), rso);
        if (!rs) return rs.error();
        auto pr = predict_friction(in.atomic_friction, rs->theta_max_forward, rs->contact_slope_std);
        if (!pr) return pr.error();
        fw.x.push_back(c / xu.scale);
        fw.y.push_back(deg(rs->theta_max_forward));
        bw.x.push_back(c / xu.scale);
        bw.y.push_back(deg(rs->theta_max_backward));
        sg.x.push_back(c / xu.scale);
        sg.y.push_back(deg(rs->contact_slope_std));
        const bool unreliable = tip_cutoff && (std::isnan(*tip_cutoff) || c < *tip_cutoff);
        t += fmt::format(
            "<tr{}><td>{}{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
            unreliable ? " class=\"below-tip\"" : "", fmt_len(c, xu), unreliable ? " (below tip cutoff)" : "",
            fmt_deg(rs->theta_max_forward), fmt_deg(rs->theta_max_backward), fmt_deg(rs->contact_slope_std),
            pr->friction_coefficient < 0 ? std::string("0 (θ_a + θ_max < 0)") : fmt_mu(pr->friction_coefficient));
      }
      t +=
          fmt::format("<tr class=\"unfiltered\"><td>unfiltered</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                      fmt_deg(r.theta_max_forward), fmt_deg(r.theta_max_backward), fmt_deg(r.contact_slope_std),
                      fmt_mu(fwd->friction_coefficient));
      t += "</table>\n";
      Plot p;
      p.title = "θ_max against resolution (measured analogue of Fig. 14)";
      p.x_label = fmt::format("Gaussian low-pass cutoff wavelength λ_c ({})", xu.name);
      p.y_label = "angle (deg)";
      p.x_log = true;
      fw.style = bw.style = SeriesStyle::Line;
      p.series = {fw, bw, sg};
      for (const Series* se : {&fw, &bw, &sg}) {  // markers at the computed cutoffs
        Series m = *se;
        m.style = SeriesStyle::Points;
        m.label.clear();
        p.series.push_back(std::move(m));
      }
      p.lines.push_back({true, deg(r.theta_max_forward), "unfiltered θ_max forward", "#d62728"});
      p.lines.push_back({true, deg(r.theta_max_backward), "unfiltered θ_max backward", "#2ca02c"});
      if (tip_cutoff && *tip_cutoff > 0 && std::isfinite(*tip_cutoff) && *tip_cutoff / xu.scale < fw.x.back())
        p.x_min = *tip_cutoff / xu.scale / 1.3;  // the line inside the frame, left of the finest cutoff
      if (tip_cutoff && *tip_cutoff > 0 && std::isfinite(*tip_cutoff))
        p.lines.push_back(
            {false, *tip_cutoff / xu.scale,
             fmt::format("tip R = {}: reliable above", fmt_len(in.tip_radius, length_unit(in.tip_radius))), "#555"});
      auto svg = plot_svg(p);
      if (!svg) return svg.error();
      html = figure(
          *svg,
          fmt::format(
              "The surface{} low-pass filtered (Gaussian, ISO 16610-21: 50 % transmission at λ_c) at {} cutoffs from "
              "half "
              "the length down to 4 point spacings, then the signature recomputed at {} equally spaced offsets "
              "(each evaluated exactly; the unfiltered row is every event). From the coarsest to the finest "
              "cutoff "
              "θ_max forward goes from {} to {} (unfiltered: {}); the paper's Fig. 14 shows θ_max growing with the "
              "resolution of Weierstrass–Mandelbrot profiles.",
              pair ? "s" : "", in.resolution_steps, kResolutionOffsets, fmt::format("{:.3f}°", fw.y.front()),
              fmt::format("{:.3f}°", fw.y.back()), fmt_deg(r.theta_max_forward)) +
              tip_text);
      html += t;
    }
    sections.push_back({"resolution", "Dependence on resolution", html});
  }

  // --- what was assumed --------------------------------------------------------------------------
  assumptions.push_back(pair ? fmt::format("The lower block's face is {}; the upper block's face is {} as measured "
                                           "(material below), turned over by 180° to face it.",
                                           escape_html(lower_name), escape_html(upper_name))
                             : fmt::format("The upper block is the surface itself turned over (rotated 180°): {} "
                                           "slides on a copy of itself.",
                                           escape_html(lower_name)));
  assumptions.push_back(
      fmt::format("Conditioning applied to each measured surface before anything else (crop, spike "
                  "removal, form removal, in that order): <b>{}</b>.",
                  escape_html(in.detrend.empty() ? std::string("none") : in.detrend)));
  if (in.is_map)
    assumptions.push_back(fmt::format(
        "The signature, slope distributions and resolution study use the map's central line along x (y = {}), "
        "the longest valid run: {} points over {}. The polar plot uses parallel lines in every direction.",
        fmt_len(in.map.y0 + in.map.height() / 2, length_unit(in.map.height())), lower.size(),
        fmt_len(lower.length(), xu)));
  assumptions.push_back(
      "Rigid blocks: the upper block only translates (no rotation, no deformation). Contact slopes follow the "
      "paper's exact polyline rules (edge–edge, vertex–edge, vertex–vertex).");
  assumptions.push_back(fmt::format("Offsets x_ofs from {} to {} ({}).", fmt_len(r.offset.front(), xu),
                                    fmt_len(r.offset.back(), xu),
                                    lower.period ? "one period" : "up to half the shorter block"));
  assumptions.push_back(fmt::format("Atomic friction μ_a = {:g} (Eq. 6).", in.atomic_friction));
  assumptions.push_back(
      "Units: lengths as read from the file(s), converted to metres and shown in the unit printed on each axis; "
      "angles in degrees.");
  for (const auto& n : in.notes) assumptions.push_back(escape_html(n));

  // --- the page ---------------------------------------------------------------------------------
  std::string title = pair ? fmt::format("frictal report: {} on {}", base(lower_name), base(upper_name))
                           : fmt::format("frictal report: {}", base(lower_name));
  std::string page;
  page += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  page += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  page += fmt::format("<title>{}</title>\n", escape_html(title));
  page += R"(<style>
body { font-family: "DejaVu Sans", Arial, sans-serif; max-width: 1100px; margin: 1.5em auto; padding: 0 1em; color: #222; line-height: 1.4; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; border-bottom: 1px solid #ccc; padding-bottom: .2em; margin-top: 1.6em; }
figure { margin: 1em 0; } figcaption { font-size: .9em; color: #444; max-width: 700px; }
svg.plot { max-width: 100%; height: auto; }
table { border-collapse: collapse; margin: .8em 0; font-size: .92em; } caption { text-align: left; font-weight: bold; padding: .3em 0; }
th, td { border: 1px solid #ddd; padding: .25em .6em; text-align: left; } td.note { color: #666; font-size: .9em; }
table.resolution td, table.friction td { font-variant-numeric: tabular-nums; }
tr.below-tip td { color: #999; }
tr.unfiltered td { font-weight: bold; }
.verdict { background: #f3f7ee; border-left: 4px solid #5a9a2a; padding: .5em .8em; }
.warnings { background: #fff4e5; border-left: 4px solid #e08a00; padding: .4em .8em; margin: .6em 0; }
.bounds { color: #444; font-size: .95em; }
.assumptions { background: #f7f7f7; padding: .6em 1.4em; border-radius: 4px; }
nav a { margin-right: 1em; } footer { margin-top: 2em; font-size: .85em; color: #666; }
</style>
</head>
<body>
)";
  page += fmt::format("<h1>{}</h1>\n", escape_html(title));
  if (in.prediction) {
    const Prediction& p = *in.prediction;
    const std::string drops =
        p.single_drop ? "one drop" : fmt::format("{} {}", p.drops, p.is_map ? "drops" : "basins of the drops");
    page += fmt::format(
        "<p class=\"verdict\" id=\"headline\">A tilt test of {} reads <b>φ = {}</b> (μ = <b>{}</b>){}; rigid "
        "upper bound θ_max + θ_a = {} (μ ≤ {}); the paper's Eq. 18 range {} … {}.<br><small>Model: {} ({}); "
        "sliding at {:g}°, μ_a = {:g}; conditioning: {}; run-away distance {:.3g} m; over {}.</small></p>\n",
        pair ? "these surfaces" : "this surface against itself", fmt_deg(p.friction_angle.q50),
        fmt_mu(p.friction_coefficient),
        p.single_drop ? " from this drop"
                      : fmt::format(", the median over drops; 90 % of tests between {} and {}",
                                    fmt_deg(p.friction_angle.q05), fmt_deg(p.friction_angle.q95)),
        fmt_deg(p.upper_bound_friction_angle), fmt_mu(std::tan(std::min(p.upper_bound_friction_angle, 1.5707963))),
        fmt_deg(p.eq18_range[0]), fmt_deg(p.eq18_range[1]), p.model,
        p.is_map ? "a rigid block free to move sideways, quasi-static"
                 : "the quasi-static hold angle on the exact lift",
        p.direction * 180 / std::numbers::pi, p.atomic_friction, escape_html(p.conditioning), p.runaway_distance,
        drops);
    if (!p.warnings.empty()) {
      page += "<div class=\"warnings\" id=\"warnings\"><b>Warnings</b><ul>\n";
      for (const Warning& w : p.warnings)
        page += fmt::format("<li><code>{}</code>: {}</li>\n", escape_html(w.code), escape_html(w.message));
      page += "</ul></div>\n";
    }
    // The same object as `frictal predict --json`, for scripts that read the page ("</" escaped).
    std::string json = prediction_json(p, "", 0);
    for (std::size_t k = 0; (k = json.find("</", k)) != std::string::npos; k += 3) json.replace(k, 2, "<\\/");
    page += "<script type=\"application/json\" id=\"prediction\">" + json + "</script>\n";
    page += fmt::format(
        "<p class=\"bounds\">{}: rigid upper bound θ_max + θ_a = {} towards +x and {} towards −x (θ_max = {} / "
        "{}).</p>\n",
        in.is_map ? "The map's central line against itself" : "Signature function", fmt_deg(fwd->friction_angle),
        fmt_deg(bwd->friction_angle), fmt_deg(r.theta_max_forward), fmt_deg(r.theta_max_backward));
  } else {
    page += fmt::format(
        "<p class=\"verdict\">Rigid upper bound θ_max + θ_a: μ ≤ <b>{}</b> towards +x (Eq. 18 range {} … {}) "
        "and μ ≤ <b>{}</b> towards −x; θ_max = {} / {}, μ_a = {:g}.</p>\n",
        fmt_mu(fwd->friction_coefficient), fmt_mu(fwd->friction_coefficient_low), fmt_mu(fwd->friction_coefficient),
        fmt_mu(bwd->friction_coefficient), fmt_deg(r.theta_max_forward), fmt_deg(r.theta_max_backward),
        in.atomic_friction);
  }
  page += "<nav>";
  for (const auto& s : sections) page += fmt::format("<a href=\"#{}\">{}</a>", s.id, s.title);
  page += "<a href=\"#assumptions\">What was assumed</a></nav>\n";
  for (const auto& s : sections)
    page += fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n{}</section>\n", s.id, s.title, s.html);
  page += "<section id=\"assumptions\">\n<h2>What was assumed</h2>\n<ul class=\"assumptions\">\n";
  for (const auto& a : assumptions) page += fmt::format("<li>{}</li>\n", a);
  page += "</ul>\n</section>\n";
  page += fmt::format(
      "<footer>Method: F. Alonso-Marroquín et al., “Static friction between rigid fractal surfaces”, Phys. Rev. E 92, "
      "032405 (2015). Every number on this page was computed by frictal from the input file(s). {}</footer>\n",
      escape_html(in.generated_by));
  page += "</body>\n</html>\n";
  return page;
}

}  // namespace frictal::report
