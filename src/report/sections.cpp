// The sections of the page of `frictal report`: each writer takes the results of report_data()
// and writes HTML (plots, tables, captions); nothing here computes an analysis.
#include "report/sections.hpp"

#include <fmt/core.h>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include "frictal/units.hpp"

namespace frictal::report::detail {

namespace {

constexpr double kDeg = units::kRadPerDeg;
constexpr double deg(double rad) { return units::to_deg(rad); }

bool map_pair(const ReportInput& in) { return in.is_map && in.upper_map.has_value(); }
/// What the line sections are of: a map's central line(s) or the whole scans.
std::string lines_of(const ReportInput& in) {
  return map_pair(in) ? "the maps' central lines" : in.is_map ? "the map's central line" : "the whole scans";
}

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

std::string figure(const std::string& svg, const std::string& caption) {
  return fmt::format("<figure>{}<figcaption>{}</figcaption></figure>\n", svg, caption);
}

/// A table with a forward and a backward column; rows added by `two`.
struct TwoWayTable {
  std::string html =
      "<table class=\"friction\"><tr><th></th><th>towards +x (forward)</th><th>towards −x (backward)</th></tr>\n";
  void two(const std::string& name, const std::string& a, const std::string& b) {
    html += fmt::format("<tr><th>{}</th><td>{}</td><td>{}</td></tr>\n", name, a, b);
  }
  std::string done() { return html + "</table>\n"; }
};

/// The file name without its folders (titles and legends; the full paths are stated in the assumptions).
std::string base(const std::string& path) {
  const auto k = path.find_last_of('/');
  return k == std::string::npos ? path : path.substr(k + 1);
}

/// The unit of offsets and lateral lengths: that of the longer surface.
LengthUnit lateral_unit(const ReportData& d) {
  return length_unit(std::max(d.surfaces.lower.length(), d.surfaces.upper.length()));
}

/// The reference lines of a signature plot: theta_max forward and minus theta_max backward
/// (unit: rad in, degrees drawn).
void add_theta_max_lines(Plot& p, double forward, double backward) {
  p.lines.push_back({true, deg(forward), fmt::format("θ_max forward = {:.3f}°", deg(forward)), "#d62728"});
  p.lines.push_back({true, -deg(backward), fmt::format("−θ_max backward = −{:.3f}°", deg(backward)), "#2ca02c"});
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

/// A histogram over angles (unit: rad; density 1/rad) drawn in degrees (density 1/deg).
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

std::string profile_stats_table(const ProfileStats& st, bool uniform, const std::string& name) {
  const LengthUnit zu = length_unit(st.rms_height > 0 ? 3 * st.rms_height : 1e-9);
  std::string t = fmt::format("<table class=\"stats\"><caption>Profile statistics: {}</caption>\n", escape_html(name));
  t += row("points", fmt::format("{}", st.points), uniform ? "uniform spacing" : "non-uniform spacing");
  t += row("length L", fmt_len(st.length, length_unit(st.length)), "x_max − x_min");
  t += row("rms height", fmt_len(st.rms_height, zu), "exact for the polyline");
  t += row("rms slope", fmt::format("{:.4f}", st.rms_slope), "√⟨z′²⟩");
  t += row("steepest edge", fmt_deg(st.max_slope), "max |atan z′|");
  t += row("mean slope angle", fmt_deg(st.mean_slope), "⟨atan z′⟩");
  return t + "</table>\n";
}

/// One map's figure and areal statistics; `line` is its central line at y = line_y, `name` names
/// it, `role` ("lower", "upper" or empty) says which block's face it is; `width`: the figure's (px).
Result<std::string> map_figure_and_stats(const Map& map, const MapStats& st, const Profile& line, double line_y,
                                         const std::string& name, const std::string& role, double width) {
  std::string html;
  MapImage mi;
  mi.width = width;
  mi.title = role.empty() ? "Height map: " + name : fmt::format("Height map: {}, {}", role, name);
  mi.line_y = line.x.empty() ? std::nullopt : std::optional<double>(line_y);
  mi.line_x0 = map.x0 + line.x.front();  // the central line's abscissa starts at the map's x0
  mi.line_x1 = map.x0 + line.x.back();
  mi.line_label = "central line (the resolution study)";
  auto svg = map_svg(map, mi);
  if (!svg) return svg.error();
  const std::size_t f = std::max<std::size_t>(1, (std::max(map.nx, map.ny) + mi.max_pixels - 1) / mi.max_pixels);
  const LengthUnit lu = length_unit(std::max(st.width, st.height));
  html += figure(*svg, fmt::format("{} × {} points, {} × {}; spacing {} × {}. {}Colours span the {:g} to {:g} % "
                                   "quantiles of the heights (outliers saturate); grey: no data.",
                                   map.nx, map.ny, fmt_len(st.width, lu), fmt_len(st.height, lu),
                                   fmt_len(map.dx, length_unit(map.dx)), fmt_len(map.dy, length_unit(map.dy)),
                                   f > 1 ? fmt::format("Shown block-averaged {} × {} to {} × {} pixels. ", f, f,
                                                       (map.nx + f - 1) / f, (map.ny + f - 1) / f)
                                         : std::string(),
                                   100 * mi.low_quantile, 100 * mi.high_quantile));
  const LengthUnit zu = length_unit(st.Sq > 0 ? st.Sq : 1e-9);
  html += "<table class=\"stats\"><caption>Areal statistics of " +
          (role.empty() ? escape_html(name) : fmt::format("the {} map, {}", role, escape_html(name))) +
          " (ISO 25178-2 style, about the mean)</caption>\n";
  html +=
      row("points (valid)", fmt::format("{} ({})", st.points, st.valid), st.valid < st.points ? "holes excluded" : "");
  html += row("Sq", fmt_len(st.Sq, zu), "rms height");
  html += row("Sa", fmt_len(st.Sa, zu), "mean absolute height");
  html += row("Sp / Sv / Sz", fmt::format("{} / {} / {}", fmt_len(st.Sp, zu), fmt_len(st.Sv, zu), fmt_len(st.Sz, zu)),
              "highest peak, deepest valley, their sum");
  html += row("Ssk / Sku", fmt::format("{:.4f} / {:.4f}", st.Ssk, st.Sku), "skewness, kurtosis");
  html += row("Sdq", fmt::format("{:.4f}", st.Sdq), "rms gradient (forward differences)");
  html += row("steepest neighbour slope", fmt_deg(st.max_slope), "");
  html += "</table>\n";
  return html;
}

Result<std::string> profile_figure(const ReportSurfaces& s, const LengthUnit& xu) {
  Plot p;
  p.title = s.pair ? "The two surfaces, as measured (material below)" : "The surface profile";
  const double zmag = std::max(s.lower_stats.rms_height, s.upper_stats.rms_height);
  const LengthUnit zu = length_unit(zmag > 0 ? 3 * zmag : 1e-9);
  p.x_label = fmt::format("x ({})", xu.name);
  p.y_label = fmt::format("height z ({})", zu.name);
  auto add = [&](const Profile& pr, const std::string& label, const std::string& color) {
    Series sr;
    sr.label = label;
    sr.color = color;
    sr.line_width = 1.0;
    for (std::size_t i = 0; i < pr.size(); ++i) {
      sr.x.push_back(pr.x[i] / xu.scale);
      sr.y.push_back(pr.z[i] / zu.scale);
    }
    p.series.push_back(std::move(sr));
  };
  add(s.lower, s.pair ? "lower: " + base(s.lower_name) : base(s.lower_name), "#1f77b4");
  if (s.pair) add(s.upper, "upper: " + base(s.upper_name), "#d62728");
  p.height = 300;
  auto svg = plot_svg(p);
  if (!svg) return svg.error();
  const double ex = xu.scale / zu.scale;
  return figure(*svg, ex > 1.5 ? fmt::format("Heights (in {}) are drawn magnified relative to x (in {}); slopes "
                                             "below are true slopes.",
                                             zu.name, xu.name)
                               : std::string("Heights and x on their own scales; slopes below are true slopes."));
}

/// mean ± std (5–95 %: q05 … q95) of a distribution of angles.
std::string angle_range(const HoldStatistics& st) {
  return fmt::format("{} ± {} (5–95 %: {} … {})", fmt_deg(st.mean), fmt_deg(st.std), fmt_deg(st.q05), fmt_deg(st.q95));
}

std::string tip_sentence(const ReportInput& in, const std::optional<double>& tip_cutoff) {
  if (!tip_cutoff) return {};
  const std::string r = fmt_len(in.tip_radius, length_unit(in.tip_radius));
  if (std::isnan(*tip_cutoff))
    return fmt::format(
        " A tip of radius {} cannot follow this surface at any scale up to a quarter of its length (its peaks "
        "are curved more than 1/(2R) there): no cutoff on this page is reliable.",
        r);
  if (*tip_cutoff == 0)
    return fmt::format(
        " A tip of radius {} follows this surface down to the sampling interval: every cutoff here is within "
        "its reach.",
        r);
  return fmt::format(
      " The dashed grey vertical line is the short reliability cutoff for a tip of radius {}: {} (below it the "
      "measured peaks are curved more than 1/(2R), half the tip's curvature: the scan shows the tip rather than "
      "the surface, and θ_max from the finer scales is not to be trusted; rows below it are marked in the "
      "table).",
      r, fmt_len(*tip_cutoff, length_unit(*tip_cutoff)));
}

}  // namespace

// --- the surface -----------------------------------------------------------------------------
Result<std::string> surface_section(const ReportInput& in, const ReportData& d) {
  const ReportSurfaces& s = d.surfaces;
  if (in.is_map && in.upper_map) {
    // The pair's two maps side by side, each named by its block and file.
    auto lo = map_figure_and_stats(in.map, s.map_stats, s.lower, s.line_y, base(s.lower_name), "lower", 540);
    if (!lo) return lo.error();
    auto up = map_figure_and_stats(*in.upper_map, s.upper_map_stats, s.upper, s.upper_line_y, base(s.upper_name),
                                   "upper", 540);
    if (!up) return up.error();
    std::string html = fmt::format(
        "<p>The lower block's face is <b>{}</b>, the upper block's <b>{}</b> as measured (material below; turned "
        "over onto the lower one for every analysis of the pair).</p>\n",
        escape_html(base(s.lower_name)), escape_html(base(s.upper_name)));
    html += "<div class=\"pair\"><div>" + *lo + "</div><div>" + *up + "</div></div>\n";
    html += "<div class=\"pair\"><div>" +
            profile_stats_table(
                s.lower_stats, s.lower_uniform,
                "the central line along x of the lower map, " + base(s.lower_name) + " (the resolution study)") +
            "</div><div>" +
            profile_stats_table(
                s.upper_stats, s.upper_uniform,
                "the central line along x of the upper map, " + base(s.upper_name) + " (the resolution study)") +
            "</div></div>\n";
    return html;
  }
  auto fig = in.is_map ? map_figure_and_stats(in.map, s.map_stats, s.lower, s.line_y, base(s.lower_name), "", 900)
                       : profile_figure(s, lateral_unit(d));
  if (!fig) return fig.error();
  std::string html = std::move(*fig);
  if (s.pair)
    html += "<div class=\"pair\"><div>" +
            profile_stats_table(s.lower_stats, s.lower_uniform, "lower, " + base(s.lower_name)) + "</div><div>" +
            profile_stats_table(s.upper_stats, s.upper_uniform, "upper, " + base(s.upper_name)) + "</div></div>\n";
  else
    html +=
        profile_stats_table(s.lower_stats, s.lower_uniform,
                            in.is_map ? "the central line along x of " + base(s.lower_name) + " (the resolution study)"
                                      : base(s.lower_name));
  return html;
}

// --- the signature ---------------------------------------------------------------------------
Result<std::string> signature_section(const ReportInput& in, const ReportData& d) {
  const SignatureResult& r = d.signature;
  const LengthUnit xu = lateral_unit(d);
  Plot p;
  p.title = "Signature function θ(x_ofs) (Eq. 1–3)";
  p.x_label = fmt::format("offset x_ofs of the upper block ({})", xu.name);
  p.y_label = "contact slope θ (deg)";
  p.series.push_back(signature_series(r, xu, "", "#1f77b4"));
  add_theta_max_lines(p, r.theta_max_forward, r.theta_max_backward);
  auto svg = plot_svg(p);
  if (!svg) return svg.error();
  return figure(
      *svg,
      fmt::format("A diagnostic of {}{}: {} offsets{}; θ is the slope of the steepest contact at each "
                  "offset; between offsets the line joins the exact one-sided slopes of the lift h(x_ofs).",
                  lines_of(in), d.surfaces.pair ? " (the lower against the upper turned over)" : "", r.offset.size(),
                  r.exact ? fmt::format(" (every one of the {} event offsets: exact)", r.events)
                          : " (the point grids do not align: offsets sampled at the finer point spacing, "
                            "each evaluated exactly)"));
}

// --- slope distributions (Fig. 16 style) -------------------------------------------------------
Result<std::string> slopes_section(const ReportInput& in, const ReportData& d) {
  const ReportSlopes& sl = d.slopes;
  const ReportSurfaces& s = d.surfaces;
  const SignatureResult& r = d.signature;
  Plot p;
  p.title = "Slope distributions (paper Fig. 16)";
  p.x_label = "slope angle (deg)";
  p.y_label = "probability density (1/deg)";
  p.series.push_back(histogram_series(
      sl.lower, s.pair ? "surface slopes: lower, " + base(s.lower_name) : "surface slopes", "#1f77b4"));
  if (s.pair)
    p.series.push_back(histogram_series(sl.upper, "surface slopes: upper, " + base(s.upper_name), "#9467bd", true));
  p.series.push_back(histogram_series(
      sl.contact, s.pair ? "contact slopes θ(x_ofs) of the pair" : "contact slopes θ(x_ofs)", "#d62728"));
  auto svg = plot_svg(p);
  if (!svg) return svg.error();
  return figure(
      *svg,
      fmt::format(
          "{}Surface slopes: every edge of {} weighted by its length. Contact slopes: θ at each offset "
          "weighted by the offset length it stands for; mean {}, standard deviation σ = {} (Eq. 18). {} bins over "
          "±{:.2f}°{}.",
          in.is_map ? fmt::format("Of {}, along x. ", lines_of(in)) : std::string(),
          s.pair ? "each profile" : "the profile", fmt_deg(r.contact_slope_mean), fmt_deg(r.contact_slope_std), in.bins,
          deg(sl.limit),
          sl.outside_length > 0
              ? fmt::format("; {:.2f} % of the surface length is steeper (counted in the densities, beyond "
                            "the axis; steepest edge {})",
                            100 * sl.outside_length / sl.total_length,
                            fmt_deg(std::max(s.lower_stats.max_slope, s.upper_stats.max_slope)))
              : std::string()));
}

// --- maps: the areal signature along the headline's direction --------------------------------
namespace {
/// The command whose numbers the areal signature section shows.
std::string areal_command(const ReportInput& in, const ReportArealSignature& a) {
  std::string c = fmt::format("frictal areal {}{} --angle {:g}", base(in.lower_name),
                              in.upper_map ? " " + base(in.upper_name) : std::string(), deg(a.direction));
  if (in.atomic_friction != 0) c += fmt::format(" --atomic-friction {:g}", in.atomic_friction);
  return c;
}
}  // namespace

Result<std::string> areal_signature_section(const ReportInput& in, const ReportData& d) {
  const ReportArealSignature& a = *d.areal;
  if (!a.failure.empty()) return fmt::format("<p>Not computed for these maps: {}.</p>\n", escape_html(a.failure));
  const ArealSignature& r = a.signature;
  const double span = r.offset.empty() ? 0.0 : r.offset.back() - r.offset.front();
  const LengthUnit xu = length_unit(span > 0 ? span : in.map.width());
  double hmin = 0, hmax = 0;
  for (std::size_t i = 0; i < r.lift.size(); ++i)
    hmin = i ? std::min(hmin, r.lift[i]) : r.lift[i], hmax = i ? std::max(hmax, r.lift[i]) : r.lift[i];
  const LengthUnit zu = length_unit(std::max(hmax - hmin, 1e-300));
  Plot th;
  th.title = fmt::format("Areal signature θ(s) along {:g}°", deg(a.direction));
  th.x_label = fmt::format("offset s of the upper block ({})", xu.name);
  th.y_label = "contact slope θ (deg)";
  Series ts;
  ts.color = "#1f77b4";
  ts.line_width = 1.2;
  for (std::size_t i = 0; i < r.offset.size(); ++i)
    ts.x.push_back(r.offset[i] / xu.scale), ts.y.push_back(deg(r.theta[i]));
  if (ts.x.size() == 1) ts.style = SeriesStyle::Points;
  th.series.push_back(ts);
  add_theta_max_lines(th, r.theta_max_forward, r.theta_max_backward);
  auto tsvg = plot_svg(th);
  if (!tsvg) return tsvg.error();
  Plot lp;
  lp.title = "Lift h(s) of the upper block";
  lp.x_label = th.x_label;
  lp.y_label = fmt::format("lift h ({})", zu.name);
  Series ls;
  ls.color = "#ff7f0e";
  ls.line_width = 1.2;
  for (std::size_t i = 0; i < r.offset.size(); ++i)
    ls.x.push_back(r.offset[i] / xu.scale), ls.y.push_back((r.lift[i] - hmin) / zu.scale);
  if (ls.x.size() == 1) ls.style = SeriesStyle::Points;
  lp.series.push_back(ls);
  auto lsvg = plot_svg(lp);
  if (!lsvg) return lsvg.error();
  const std::string pair =
      in.upper_map ? fmt::format("lower {} against upper {} turned over", base(in.lower_name), base(in.upper_name))
                   : fmt::format("{} against itself turned over", base(in.lower_name));
  std::string html = "<div class=\"pair\">";
  html += figure(*tsvg, fmt::format("A diagnostic of the maps' nodes: the slope of the steepest contact at each of "
                                    "{} offsets s along {:g}° (0° = +x) of the grid areal signature of {}.",
                                    r.offset.size(), deg(a.direction), escape_html(pair)));
  html += figure(*lsvg, fmt::format("The lift h(s) of the upper block over the same offsets (its lowest value "
                                    "subtracted), the highest contact of the nodes at each offset."));
  html += "</div>\n";
  TwoWayTable t;
  t.html = fmt::format(
      "<table class=\"friction\"><caption>The grid's bound (a diagnostic of the maps' nodes)</caption><tr><th></th>"
      "<th>towards {:g}° (forward)</th><th>towards {:g}° (backward)</th></tr>\n",
      deg(a.direction), std::fmod(deg(a.direction) + 180, 360));
  t.two("θ_max (steepest contact of the grid)", fmt_deg(r.theta_max_forward), fmt_deg(r.theta_max_backward));
  t.two("θ_max of the lift (its steepest step)", fmt_deg(r.theta_max_lift), "");
  t.two("σ (std of the contact slopes)", fmt_deg(r.contact_slope_std), fmt_deg(r.contact_slope_std));
  t.two("the grid's bound θ_a + θ_max (Eq. 6)", fmt_deg(a.forward.friction_angle), fmt_deg(a.backward.friction_angle));
  t.two("the grid's bound of μ, tan(θ_a + θ_max)", fmt_mu(a.forward.friction_coefficient),
        fmt_mu(a.backward.friction_coefficient));
  t.two("Eq. 18 range of μ below the grid's bound",
        fmt::format("{} … {}", fmt_mu(a.forward.friction_coefficient_low), fmt_mu(a.forward.friction_coefficient)),
        fmt::format("{} … {}", fmt_mu(a.backward.friction_coefficient_low), fmt_mu(a.backward.friction_coefficient)));
  html += t.done();
  html += fmt::format(
      "<p class=\"bounds\">The numbers of <code>{}</code>{} (μ_a = {:g}), along the headline's sliding direction. "
      "The grid's θ_max is a diagnostic of the maps' nodes: the headline's model rounds the nodes by spheres and "
      "its own rigid bound (the steepest seat its drops rested in) is in the headline; neither bound is what a "
      "tilt test reads.</p>\n",
      escape_html(areal_command(in, a)), in.detrend.empty() ? "" : " with this page's conditioning",
      in.atomic_friction);
  return html;
}

Result<std::string> areal_slopes_section(const ReportInput& in, const ReportData& d) {
  const ReportArealSignature& a = *d.areal;
  if (!a.failure.empty()) return fmt::format("<p>Not computed for these maps: {}.</p>\n", escape_html(a.failure));
  Plot p;
  p.title = fmt::format("Slope distributions along {:g}°", deg(a.direction));
  p.x_label = "slope angle (deg)";
  p.y_label = "probability density (1/deg)";
  p.series.push_back(histogram_series(
      a.lower, in.upper_map ? "facet slopes: lower, " + base(in.lower_name) : "facet slopes", "#1f77b4"));
  if (in.upper_map)
    p.series.push_back(histogram_series(a.upper, "facet slopes: upper, " + base(in.upper_name), "#9467bd", true));
  p.series.push_back(
      histogram_series(a.contact, in.upper_map ? "contact slopes θ(s) of the pair" : "contact slopes θ(s)", "#d62728"));
  auto svg = plot_svg(p);
  if (!svg) return svg.error();
  return figure(
      *svg, fmt::format("Facet slopes: the slope along {:g}° of each grid cell with four valid corners (its bilinear "
                        "surface at the centre), {} cells, the map{} as measured. Contact slopes: θ(s) of the areal "
                        "signature above at each of its {} offsets; mean {}, standard deviation σ = {}. {} bins over "
                        "±{:.2f}°{}.",
                        deg(a.direction), a.facets, in.upper_map ? "s" : "", a.signature.offset.size(),
                        fmt_deg(a.signature.contact_slope_mean), fmt_deg(a.signature.contact_slope_std), in.bins,
                        deg(a.limit),
                        a.facets_outside > 0 ? fmt::format("; {:.2f} % of the facets are steeper (counted in the "
                                                           "densities, beyond the axis)",
                                                           100.0 * double(a.facets_outside) / double(a.facets))
                                             : std::string()));
}

// --- friction ---------------------------------------------------------------------------------
Result<std::string> friction_section(const ReportInput& in, const ReportData& d) {
  const SignatureResult& r = d.signature;
  const FrictionPrediction& fwd = d.forward;
  const FrictionPrediction& bwd = d.backward;
  TwoWayTable t;
  t.two("θ_max (steepest reachable contact)", fmt_deg(r.theta_max_forward), fmt_deg(r.theta_max_backward));
  t.two("σ (std of the contact slopes)", fmt_deg(r.contact_slope_std), fmt_deg(r.contact_slope_std));
  t.two("atomic friction μ_a, θ_a = atan μ_a", fmt::format("{:g}, {}", in.atomic_friction, fmt_deg(fwd.atomic_angle)),
        fmt::format("{:g}, {}", in.atomic_friction, fmt_deg(bwd.atomic_angle)));
  t.two("rigid upper bound θ_a + θ_max (Eq. 6)", fmt_deg(fwd.friction_angle), fmt_deg(bwd.friction_angle));
  t.two("upper bound of μ, tan(θ_a + θ_max)", fmt_mu(fwd.friction_coefficient), fmt_mu(bwd.friction_coefficient));
  t.two("Eq. 18 range of φ", fmt::format("{} … {}", fmt_deg(fwd.friction_angle_low), fmt_deg(fwd.friction_angle)),
        fmt::format("{} … {}", fmt_deg(bwd.friction_angle_low), fmt_deg(bwd.friction_angle)));
  t.two("Eq. 18 range of μ",
        fmt::format("{} … {}", fmt_mu(fwd.friction_coefficient_low), fmt_mu(fwd.friction_coefficient)),
        fmt::format("{} … {}", fmt_mu(bwd.friction_coefficient_low), fmt_mu(bwd.friction_coefficient)));
  std::string html = t.done();
  html += fmt::format(
      "<p class=\"bounds\">Rigid upper bound of the friction coefficient of {} (a diagnostic): μ ≤ {} sliding "
      "towards +x (Eq. 18's range below it {} … {}) and μ ≤ {} towards −x, with μ_a = {:g}. A bound, not what a "
      "tilt test reads: that is the headline.</p>\n",
      lines_of(in), fmt_mu(fwd.friction_coefficient), fmt_mu(fwd.friction_coefficient_low),
      fmt_mu(fwd.friction_coefficient), fmt_mu(bwd.friction_coefficient), in.atomic_friction);
  return html;
}

// --- what a tilt test reads: the hold angle (hold.hpp) -----------------------------------------
Result<std::string> hold_section(const ReportInput& in, const ReportData& d) {
  const HoldAnalysis& ha = d.hold.analysis;
  const HoldDistribution& f = ha.distribution.forward;
  const HoldDistribution& b = ha.distribution.backward;
  const FrictionPrediction& fwd = d.forward;
  const FrictionPrediction& bwd = d.backward;
  const LengthUnit xu = lateral_unit(d);
  // h(s) over the drop range with the basins' rest offsets.
  Plot lp;
  lp.title = "Lift h(x_ofs) of the upper block and the basins where dropped blocks rest";
  lp.x_label = fmt::format("offset x_ofs of the upper block ({})", xu.name);
  double hlo = std::numeric_limits<double>::infinity(), hhi = -hlo;  // the lift's range shown: its unit
  for (std::size_t i = 0; i < ha.curve.offset.size(); ++i)
    if (ha.curve.offset[i] >= f.drop_min && ha.curve.offset[i] <= f.drop_max) {
      hlo = std::min(hlo, ha.curve.lift[i]);
      hhi = std::max(hhi, ha.curve.lift[i]);
    }
  const LengthUnit hu = length_unit(std::max(std::abs(hlo), std::abs(hhi)));
  lp.y_label = fmt::format("lift h ({})", hu.name);
  Series ls, rs;
  ls.label = "h(x_ofs)";
  ls.color = "#1f77b4";
  ls.line_width = 1.2;
  for (std::size_t i = 0; i < ha.curve.offset.size(); ++i) {
    ls.x.push_back(ha.curve.offset[i] / xu.scale);
    ls.y.push_back(ha.curve.lift[i] / hu.scale);
  }
  rs.label = fmt::format("rest offsets ({} basins)", f.basins.rest.size());
  rs.color = "#d62728";
  rs.style = SeriesStyle::Points;
  for (std::size_t k = 0; k < f.basins.rest.size() && k < d.hold.rest_lift.size(); ++k) {
    rs.x.push_back(f.basins.rest[k] / xu.scale);
    rs.y.push_back(d.hold.rest_lift[k] / hu.scale);
  }
  lp.series = {ls, rs};
  lp.x_min = f.drop_min / xu.scale;
  lp.x_max = f.drop_max / xu.scale;
  auto lsvg = plot_svg(lp);
  if (!lsvg) return lsvg.error();
  Plot hp;
  hp.title = "Hold angle over drops (towards +x): the distribution repeated tilt tests give";
  hp.x_label = "friction angle φ (deg)";
  hp.y_label = "probability density (1/deg)";
  hp.series.push_back(histogram_series(d.hold.hold, "quasi-static hold angle φ_qs", "#1f77b4"));
  hp.series.push_back(histogram_series(d.hold.inertial, "inertial bound φ_in", "#9467bd", true));
  // A bound below zero (warning bound-negative) leaves Eq. 18 no range: no band then.
  if (fwd.friction_angle_low <= fwd.friction_angle)
    hp.bands.push_back({false, deg(fwd.friction_angle_low), deg(fwd.friction_angle), "Eq. 18 range", "#f2c94c", 0.3});
  hp.lines.push_back(
      {false, deg(fwd.friction_angle), fmt::format("θ_a + θ_max = {:.3f}°", deg(fwd.friction_angle)), "#d62728"});
  auto hsvg = plot_svg(hp);
  if (!hsvg) return hsvg.error();
  std::string html = in.is_map
                         ? fmt::format(
                               "<p class=\"diagnostic\">A diagnostic: the hold angle of {} along x (line "
                               "profiles, as `frictal signature` of those lines computes it), not the {} prediction: "
                               "that is the headline.</p>\n",
                               lines_of(in), map_pair(in) ? "maps'" : "map's")
                         : std::string(
                               "<p class=\"diagnostic\">A diagnostic: the hold angle of the whole upper scan over "
                               "offsets 0 to half its length (as `frictal signature` computes it), another block "
                               "than the stated test's: what the stated test reads is the headline.</p>\n");
  html +=
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
                  "Shaded: Eq. 18's heuristic range [θ_max − σ, θ_max] + θ_a over the offset range; a block "
                  "that slips on before the run-away can reach steeper contacts beyond it.",
                  ha.runaway_distance / xu.scale, xu.name));
  TwoWayTable t;
  t.two("quasi-static hold angle φ_qs over drops", angle_range(f.hold), angle_range(b.hold));
  t.two("inertial bound φ_in over drops", angle_range(f.inertial), angle_range(b.inertial));
  t.two("Eq. 18 range of φ", fmt::format("{} … {}", fmt_deg(fwd.friction_angle_low), fmt_deg(fwd.friction_angle)),
        fmt::format("{} … {}", fmt_deg(bwd.friction_angle_low), fmt_deg(bwd.friction_angle)));
  html += t.done();
  return html;
}

// --- areal blocks that may move sideways (two maps) ----------------------------------------------
Result<std::string> areal_hold_section(const ReportInput&, const ReportData& d) {
  const ReportArealHold& a = *d.areal_hold;
  auto write = [&]() -> Result<std::string> {
    if (!a.failure.empty()) return make_error(a.failure);
    const Prediction& p = a.prediction;
    const ArealTiltHold& z = a.from_zero;
    const ArealLift& L = a.lift;
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
    mi.title = "Lift h with the prediction's drops";
    mi.x_label = "offset along the sliding direction, s_x";
    mi.y_label = "offset across it, s_y";
    mi.z_label = "lift h";
    mi.absolute_axes = true;
    for (const auto& q : p.drop_offsets) mi.marks.push_back({q[0], q[1], "", "#ffffff"});
    // The chain of stops: the coarse increments up to the first run-away are tilted again in fine
    // increments from the stop before it, so a stop at a lower tilt than the last replaces those above.
    std::vector<std::array<double, 3>> chain;
    for (const auto& st : z.stops) {
      while (!chain.empty() && chain.back()[0] >= st[0]) chain.pop_back();
      chain.push_back(st);
    }
    mi.path_x = {0.0, z.rest_offset[0]};
    mi.path_y = {0.0, z.rest_offset[1]};
    for (const auto& st : chain) {
      mi.path_x.push_back(st[1]);
      mi.path_y.push_back(st[2]);
    }
    mi.path_label = z.ran_away ? fmt::format("run-away at {}", fmt_deg(z.hold_angle)) : "held to 45°";
    mi.marks.push_back({z.rest_offset[0], z.rest_offset[1], "rest", "#d62728"});
    auto msvg = map_svg(lm, mi);
    if (!msvg) return msvg.error();
    auto hist = [&](const std::vector<double>& percent, const std::string& label, const std::string& color) {
      Series sr;
      sr.style = SeriesStyle::Step;
      sr.label = label;
      sr.color = color;
      for (double e : a.edges) sr.x.push_back(deg(e));
      sr.y = percent;
      return sr;
    };
    Plot hp;
    hp.title = "Hold angle over the prediction's drops";
    hp.x_label = "hold angle (deg)";
    hp.y_label = "drops (%)";
    hp.series = {hist(a.free_percent, "free to move sideways (the prediction)", "#d62728")};
    if (p.has_locked) hp.series.push_back(hist(a.locked_percent, "locked to +x (a diagnostic)", "#1f77b4"));
    hp.lines.push_back(
        {false, deg(p.friction_angle.q50), fmt::format("median {}", fmt_deg(p.friction_angle.q50)), "#d62728"});
    auto hsvg = plot_svg(hp);
    if (!hsvg) return hsvg.error();
    const LengthUnit su = length_unit(
        std::max({std::abs(L.along(0)), std::abs(L.along(L.n_along - 1)), std::abs(L.across(0)), p.runaway_distance}));
    std::string html =
        "<p>The upper map turned over onto the lower one and moved by an offset s in the plane. Tilted about the "
        "axis across the sliding direction (+x), a rigid block that does not rotate slides on the lift h(s), the "
        "height of its reference point at contact, and steers around asperities if it may move sideways. The hold "
        "angles here are the headline's prediction (model " +
        escape_html(p.model) +
        ": the upper map's nodes as spheres on the lower map's triangulated surface, offsets anywhere, "
        "quasi-static; docs/analysis.md, docs/mujoco.md).</p>\n";
    html += figure(
        *msvg,
        fmt::format("{} × {} offsets of the lift of the map's nodes (areal_lift: the landscape; the prediction's "
                    "model rounds each node of the upper map by a sphere of radius r = {:.4g} {}, so its lift is "
                    "this one smoothed on that scale). White: the prediction's {} drops. Red: the block dropped at "
                    "s = 0, to its rest at zero tilt and then where it stands after each tilt increment, up to the "
                    "end of its run-away (free to move sideways, run-away distance d = {:.4g} {}).",
                    L.n_along, L.n_across, a.sphere_radius / su.scale, su.name, p.drops, p.runaway_distance / su.scale,
                    su.name));
    const long side = std::lround(std::sqrt(double(p.drops)));
    html += figure(*hsvg, fmt::format("The hold angle of each of the prediction's {} drops ({} × {} over the drop "
                                      "range); the headline's median and 5–95 % are over these.",
                                      p.drops, side, side));
    std::string t = "<table class=\"friction\"><tr><th></th><th>free to move sideways (the prediction)</th>";
    if (p.has_locked) t += "<th>locked to +x (a diagnostic)</th>";
    t += "</tr>\n";
    auto stats = [](const HoldStatistics& st) {
      return fmt::format("median {}; 5–95 %: {} … {}; {} ± {}; min {}, max {}", fmt_deg(st.q50), fmt_deg(st.q05),
                         fmt_deg(st.q95), fmt_deg(st.mean), fmt_deg(st.std), fmt_deg(st.min), fmt_deg(st.max));
    };
    t += fmt::format("<tr><th>hold angle over {} drops</th><td>{}</td>{}</tr>\n", p.drops, stats(p.friction_angle),
                     p.has_locked ? fmt::format("<td>{}</td>", stats(p.locked_friction_angle)) : std::string());
    t += fmt::format("<tr><th>the block dropped at s = 0 (rest at ({:.4g}, {:.4g}) {})</th><td>{}</td>{}</tr>\n",
                     z.rest_offset[0] / su.scale, z.rest_offset[1] / su.scale, su.name,
                     z.ran_away ? fmt_deg(z.hold_angle) : "held to 45°", p.has_locked ? "<td></td>" : "");
    t += "</table>\n";
    html += t;
    return html;
  };
  auto html = write();
  if (!html) return fmt::format("<p>Not computed for this pair: {}.</p>\n", escape_html(html.error().message));
  return html;
}

// --- friction over sliding directions (maps) ---------------------------------------------------
namespace {
/// The command whose table the polar plot is (the options that change its numbers).
std::string anisotropy_command(const ReportInput& in) {
  std::string c =
      fmt::format("frictal anisotropy {}{} --areal --hold --directions {} --drops {}", base(in.lower_name),
                  in.upper_map ? " --upper " + base(in.upper_name) : std::string(), in.directions, in.map_drops);
  if (in.atomic_friction != 0) c += fmt::format(" --atomic-friction {:g}", in.atomic_friction);
  if (in.runaway_distance > 0) c += fmt::format(" --runaway-distance {:g}", in.runaway_distance);
  return c;
}

/// A map or a map pair: the hold angle over drops per direction (median and 5-95 %) and the rigid bounds.
Result<std::string> map_directions_section(const ReportInput& in, const ReportData& d) {
  const ReportDirections& dir = *d.directions;
  const std::string pair = dir.pair ? fmt::format("lower {} against upper {}", escape_html(base(in.lower_name)),
                                                  escape_html(base(in.upper_name)))
                                    : fmt::format("{} against itself turned over", escape_html(base(in.lower_name)));
  if (!dir.failure.empty())
    return fmt::format("<p>Not computed for the pair ({}): {}.</p>\n", pair, escape_html(dir.failure));
  const bool hold = dir.hold_failure.empty();
  const std::string command = escape_html(anisotropy_command(in));
  auto polar_series = [](const std::string& label, const std::string& color, bool dashed) {
    Series s;
    s.label = label;
    s.color = color;
    s.dashed = dashed;
    return s;
  };
  Series q50 = polar_series("median over drops", "#d62728", false);
  Series q05 = polar_series("5 % and 95 % of the drops", "#1f77b4", true);
  Series q95 = polar_series("", "#1f77b4", true);
  Series bound = polar_series(hold ? "hold model's bound (steepest seat)" : "θ_a + θ_max of the areal signature",
                              "#d62728", false);
  Series sig = polar_series("θ_a + θ_max of the areal signature (a diagnostic)", "#7f7f7f", true);
  std::string rows;
  for (const AnisotropyRow& row : dir.pair_table) {
    const double a = row.direction;
    bound.x.push_back(a), bound.y.push_back(std::max(0.0, deg(row.upper_bound_friction_angle)));
    if (row.signature_bound_friction_angle)
      sig.x.push_back(a), sig.y.push_back(std::max(0.0, deg(*row.signature_bound_friction_angle)));
    std::string hold_cells;
    if (row.hold_angle) {
      q50.x.push_back(a), q50.y.push_back(deg(row.hold_angle->q50));
      q05.x.push_back(a), q05.y.push_back(deg(row.hold_angle->q05));
      q95.x.push_back(a), q95.y.push_back(deg(row.hold_angle->q95));
      hold_cells = fmt::format("<td>{:.4f}°</td><td>{:.4f}° … {:.4f}°</td>", deg(row.hold_angle->q50),
                               deg(row.hold_angle->q05), deg(row.hold_angle->q95));
    }
    rows += fmt::format("<tr><td>{:.1f}°</td>{}<td>{:.4f}°</td>{}<td>{:.4f}° / {:.4f}°</td><td>{:.4f}°</td></tr>\n",
                        deg(a), hold_cells, deg(row.upper_bound_friction_angle),
                        row.signature_bound_friction_angle
                            ? fmt::format("<td>{:.4f}°</td>", deg(*row.signature_bound_friction_angle))
                            : std::string(),
                        deg(row.theta_forward), deg(row.theta_backward), deg(row.sigma));
  }
  std::string html = "<div class=\"pair\">";
  if (hold) {
    PolarPlot hp;
    hp.title = "Hold angle over drops by direction";
    hp.radius_label = "hold angle (deg)";
    hp.series = {q50, q05, q95};
    auto svg = polar_svg(hp);
    if (!svg) return svg.error();
    html += figure(*svg, fmt::format("A diagnostic of the pair's anisotropy: per direction the tilt test sliding "
                                     "that way, the hold angle of {} drops ({} × {}), the block free to move "
                                     "sideways (at 0° the headline's).",
                                     in.map_drops * in.map_drops, in.map_drops, in.map_drops));
  }
  PolarPlot bp;
  bp.title = "Rigid upper bounds by direction";
  bp.radius_label = "friction angle (deg)";
  bp.series = {bound};
  if (hold) bp.series.push_back(sig);
  auto bsvg = polar_svg(bp);
  if (!bsvg) return bsvg.error();
  html += figure(*bsvg, hold ? "Bounds, not what a tilt test reads: the hold model's rigid upper bound (the steepest "
                               "seat its drops rested in) and θ_a + θ_max of the pair's grid areal signature (a "
                               "diagnostic of the grid's nodes)."
                             : "θ_a + θ_max of the pair's grid areal signature: a bound (and a diagnostic of the "
                               "grid's nodes), not what a tilt test reads.");
  html += "</div>\n";
  html += fmt::format(
      "<p>The pair ({}) in {} sliding directions (0° = +x, 90° = +y), the upper block turned over about the axis "
      "across each direction: the numbers of <code>{}</code>{}. μ_a = {:g}.{}{}</p>\n",
      pair, in.directions, command, in.detrend.empty() ? "" : " with this page's conditioning", in.atomic_friction,
      in.prediction && std::isfinite(in.prediction->load)
          ? fmt::format(" Rigid blocks, no load: the headline is under a load of {:.3g} N.", in.prediction->load)
          : std::string(),
      hold ? std::string()
           : fmt::format(" The hold angles were not predicted: {}; the rigid bound alone is shown.",
                         escape_html(dir.hold_failure)));
  std::string head = "<tr><th>direction</th>";
  if (hold) head += "<th>hold angle, median</th><th>5–95 % of the drops</th>";
  head += hold ? "<th>rigid upper bound (hold model)</th><th>diagnostic: θ_a + θ_max of the areal signature</th>"
               : "<th>rigid upper bound θ_a + θ_max, areal signature</th>";
  head += "<th>θ_max forward / backward (areal signature)</th><th>σ</th></tr>\n";
  html += "<table class=\"friction\" id=\"directions-table\">" + head + rows + "</table>\n";
  const double best = dir.best_angle, worst = dir.worst_angle;
  html += fmt::format(
      "<p class=\"bounds\">{} sliding towards {:.0f}°: {} (μ = {}); lowest towards {:.0f}°: {} (μ = {}).</p>\n",
      hold ? "A diagnostic of the pair's anisotropy: highest median hold angle" : "Highest rigid upper bound",
      deg(dir.best_direction), fmt_deg(best), fmt_mu(std::tan(best)), deg(dir.worst_direction), fmt_deg(worst),
      fmt_mu(std::tan(worst)));
  if (!dir.warnings.empty()) {
    html +=
        fmt::format("<details class=\"warnings\"><summary>Warnings of the directions' predictions ({})</summary><ul>\n",
                    dir.warnings.size());
    for (const Warning& w : dir.warnings)
      html += fmt::format("<li><code>{}</code>: {}</li>\n", escape_html(w.code), escape_html(w.message));
    html += "</ul></details>\n";
  }
  return html;
}
}  // namespace

Result<std::string> directions_section(const ReportInput& in, const ReportData& d) {
  return map_directions_section(in, d);
}

// --- resolution -------------------------------------------------------------------------------
Result<std::string> resolution_section(const ReportInput& in, const ReportData& d) {
  const ReportResolution& res = *d.resolution;
  const SignatureResult& r = d.signature;
  const LengthUnit xu = lateral_unit(d);
  const std::string tip_text = tip_sentence(in, res.tip_cutoff);
  if (res.rows.empty()) {
    std::string html = fmt::format(
        "<p>Too few points for a resolution study (needs a cutoff range from 4 spacings, {}, to half "
        "the length, {}).</p>",
        fmt_len(res.cutoff_min, xu), fmt_len(res.cutoff_max, xu));
    if (!tip_text.empty()) html += "<p>" + tip_text.substr(1) + "</p>";
    return html;
  }
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
      "backward</th><th>σ</th><th>upper bound of μ forward (μ_a = " +
      fmt::format("{:g}", in.atomic_friction) + ")</th></tr>\n";
  for (const ReportResolutionRow& row : res.rows) {
    const double c = row.cutoff;
    fw.x.push_back(c / xu.scale);
    fw.y.push_back(deg(row.theta_max_forward));
    bw.x.push_back(c / xu.scale);
    bw.y.push_back(deg(row.theta_max_backward));
    sg.x.push_back(c / xu.scale);
    sg.y.push_back(deg(row.contact_slope_std));
    t += fmt::format(
        "<tr{}><td>{}{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
        row.below_tip ? " class=\"below-tip\"" : "", fmt_len(c, xu), row.below_tip ? " (below tip cutoff)" : "",
        fmt_deg(row.theta_max_forward), fmt_deg(row.theta_max_backward), fmt_deg(row.contact_slope_std),
        row.friction_coefficient < 0 ? std::string("0 (θ_a + θ_max &lt; 0)") : fmt_mu(row.friction_coefficient));
  }
  t += fmt::format("<tr class=\"unfiltered\"><td>unfiltered</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
                   fmt_deg(r.theta_max_forward), fmt_deg(r.theta_max_backward), fmt_deg(r.contact_slope_std),
                   fmt_mu(d.forward.friction_coefficient));
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
  const std::optional<double>& tip_cutoff = res.tip_cutoff;
  if (tip_cutoff && *tip_cutoff > 0 && std::isfinite(*tip_cutoff) && *tip_cutoff / xu.scale < fw.x.back())
    p.x_min = *tip_cutoff / xu.scale / 1.3;  // the line inside the frame, left of the finest cutoff
  if (tip_cutoff && *tip_cutoff > 0 && std::isfinite(*tip_cutoff))
    p.lines.push_back({false, *tip_cutoff / xu.scale,
                       fmt::format("tip R = {}: reliable above", fmt_len(in.tip_radius, length_unit(in.tip_radius))),
                       "#555"});
  auto svg = plot_svg(p);
  if (!svg) return svg.error();
  std::string html = figure(
      *svg, fmt::format(
                "The surface{} low-pass filtered (Gaussian, ISO 16610-21: 50 % transmission at λ_c) at {} cutoffs from "
                "half "
                "the length down to 4 point spacings, then the signature recomputed at {} equally spaced offsets "
                "(each evaluated exactly; the unfiltered row is every event). From the coarsest to the finest "
                "cutoff "
                "θ_max forward goes from {} to {} (unfiltered: {}); the paper's Fig. 14 shows θ_max growing with the "
                "resolution of Weierstrass–Mandelbrot profiles.",
                d.surfaces.pair ? "s" : "", res.rows.size(), res.offsets, fmt::format("{:.3f}°", fw.y.front()),
                fmt::format("{:.3f}°", fw.y.back()), fmt_deg(r.theta_max_forward)) +
                tip_text);
  html += t;
  return html;
}

// --- the headline, the title, what was assumed --------------------------------------------------
/// A name as a JSON string.
std::string json_quoted(const std::string& t) {
  std::string o = "\"";
  for (char c : t) {
    if (c == '"' || c == '\\') o += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      o += fmt::format("\\u{:04x}", static_cast<unsigned>(c));
      continue;
    }
    o += c;
  }
  return o + "\"";
}

/// Two surfaces: an upper profile, or an upper map (the headline and the areal section are the pair's).
bool two_surfaces(const ReportInput& in, const ReportData& d) { return d.surfaces.pair || in.upper_map.has_value(); }

std::string page_title(const ReportInput& in, const ReportData& d) {
  const ReportSurfaces& s = d.surfaces;
  return two_surfaces(in, d) ? fmt::format("frictal report: {} on {}", base(s.lower_name), base(in.upper_name))
                             : fmt::format("frictal report: {}", base(s.lower_name));
}

// A median with its 5-95 % band over the same drops against a swept quantity x (log axis),
// the test's value marked by a vertical line: the d sweep's and the load curve's plot.
struct QuantileBand {
  std::vector<double> x, q05, q50, q95;  ///< x in the axis's unit; quantiles (unit: rad)
  std::string title, x_label, median_label, mark_label;
  double mark = 0;  ///< the test's x (axis unit)
};
Plot quantile_band_plot(const QuantileBand& b) {
  Series med, lo, hi;
  med.label = b.median_label;
  med.color = "#d62728";
  lo.label = "5 % and 95 % quantiles";
  lo.color = hi.color = "#1f77b4";
  lo.dashed = hi.dashed = true;
  for (std::size_t i = 0; i < b.x.size(); ++i) {
    med.x.push_back(b.x[i]), med.y.push_back(deg(b.q50[i]));
    lo.x.push_back(b.x[i]), lo.y.push_back(deg(b.q05[i]));
    hi.x.push_back(b.x[i]), hi.y.push_back(deg(b.q95[i]));
  }
  Series marks = med;
  marks.label.clear();
  marks.style = SeriesStyle::Points;
  Plot pl;
  pl.title = b.title;
  pl.x_label = b.x_label;
  pl.y_label = "hold angle φ (deg)";
  pl.series = {hi, lo, med, marks};
  pl.x_log = true;
  pl.width = 560;
  pl.height = 300;
  pl.y_min = 0;
  pl.y_max = 1.4 * *std::max_element(hi.y.begin(), hi.y.end());  // room for the legend above the band
  pl.x_min = 0.7 * med.x.front();
  pl.x_max = 1.4 * med.x.back();
  RefLine at;
  at.horizontal = false;
  at.value = b.mark;
  at.label = b.mark_label;
  pl.lines = {at};
  return pl;
}
// The band's table: x as `x_text` writes it, the median and the 5-95 % range.
std::string quantile_band_table(const QuantileBand& b, const char* id, const char* x_head,
                                const std::function<std::string(double)>& x_text) {
  std::string rows;
  for (std::size_t i = 0; i < b.x.size(); ++i)
    rows += fmt::format("<tr><td>{}</td><td>{}</td><td>{} … {}</td></tr>", x_text(b.x[i]), fmt_deg(b.q50[i]),
                        fmt_deg(b.q05[i]), fmt_deg(b.q95[i]));
  return fmt::format(
      "<table class=\"friction\" id=\"{}\"><tr><th>{}</th><th>median</th><th>5–95 %</th></tr>{}</table>\n", id, x_head,
      rows);
}

// How the headline depends on the run-away distance d: the median and the 5-95 % range over the
// same drops at d/4 ... 4d (Prediction::d_sweep_*), d marked; empty where there is no sweep.
std::string d_sweep_figure(const Prediction& p) {
  if (p.d_sweep_distance.size() < 2 || p.single_drop) return {};
  const double scale = p.runaway_distance < 1e-3 ? 1e6 : 1e3;
  const char* unit = scale == 1e6 ? "µm" : "mm";
  QuantileBand b;
  for (double d : p.d_sweep_distance) b.x.push_back(d * scale);
  b.q05 = p.d_sweep_q05, b.q50 = p.d_sweep_q50, b.q95 = p.d_sweep_q95;
  b.title = "How the answer depends on the run-away distance d";
  b.x_label = fmt::format("run-away distance d ({})", unit);
  b.median_label = "median over drops (the headline at d)";
  b.mark = p.runaway_distance * scale;
  b.mark_label = "d of the test";
  auto svg = plot_svg(quantile_band_plot(b));
  if (!svg) return {};
  return figure(*svg, fmt::format("The same drops read with other run-away distances (one lift; key d_sweep_* of "
                                  "the JSON): a test that calls a block sliding only after a longer slide reads a "
                                  "higher angle. d = {:.3g} {} ({}).",
                                  p.runaway_distance * scale, unit, escape_html(p.test_lengths))) +
         quantile_band_table(b, "d-sweep", "d", [&](double x) { return fmt::format("{:.3g} {}", x, unit); });
}

// Friction under load: the hold angle's median and 5-95 % range over the same drops against the
// load (Prediction::load_curve*), the headline load marked, the rigid median beside; empty
// without a load.
std::string load_curve_figure(const Prediction& p) {
  if (p.load_curve.size() < 2 || p.single_drop) return {};
  QuantileBand b;
  b.x = p.load_curve;
  b.q05 = p.load_curve_q05, b.q50 = p.load_curve_q50, b.q95 = p.load_curve_q95;
  b.title = p.is_map ? "Friction under load (elastic half-space, block locked to d)"
                     : "Friction under load (Hertzian asperities)";
  b.x_label = "load W on the block (N)";
  b.median_label = "median over drops (the headline at W)";
  b.mark = p.load;
  b.mark_label = "W of the test";
  Plot pl = quantile_band_plot(b);
  pl.y_max = std::max(*pl.y_max, 1.4 * deg(p.rigid_friction_angle));
  RefLine rigid;
  rigid.horizontal = true;
  rigid.value = deg(p.rigid_friction_angle);
  rigid.label = p.is_map ? "rigid median (free block)" : "rigid median";
  pl.lines.push_back(rigid);
  // Maps: the curve's own limit at zero load (the block locked to d), where the prediction says
  // it is not the free block's median (its warning load-locked-block).
  if (p.is_map && std::isfinite(p.load_zero_limit) &&
      std::any_of(p.warnings.begin(), p.warnings.end(),
                  [](const Warning& w) { return w.code == "load-locked-block"; })) {
    RefLine zero;
    zero.horizontal = true;
    zero.value = deg(p.load_zero_limit);
    zero.label = "zero-load limit (block locked to d)";
    pl.lines.push_back(zero);
  }
  auto svg = plot_svg(pl);
  if (!svg) return {};
  return figure(*svg, fmt::format("The same drops on the loaded lift at other loads (key load_curve_* of the JSON; "
                                  "docs/load.md): E* = {:.3g} Pa; at W = {:.3g} N {:.3g} {} per offset, the block "
                                  "{:.3g} m below first touch; the rigid median {}{}.",
                                  p.contact_modulus, p.load, p.load_contacts,
                                  p.is_map ? "contact patches" : "asperity contacts", p.load_approach,
                                  fmt_deg(p.rigid_friction_angle),
                                  p.is_map ? fmt::format(" (the free rigid block); the curve's limit at zero load, the "
                                                         "block locked to d on the rigid lift, {}",
                                                         fmt_deg(p.load_zero_limit))
                                           : "")) +
         quantile_band_table(b, "load-curve", "load", [](double x) { return fmt::format("{:.3g} N", x); });
}

std::string headline(const ReportInput& in, const ReportData& d) {
  const FrictionPrediction& fwd = d.forward;
  const FrictionPrediction& bwd = d.backward;
  const SignatureResult& r = d.signature;
  std::string page;
  if (in.prediction) {
    const Prediction& p = *in.prediction;
    const std::string drops =
        p.single_drop ? "one drop" : fmt::format("{} {}", p.drops, p.is_map ? "drops" : "basins of the drops");
    if (p.trust != "ok") {
      std::string codes;
      for (const std::string& c : p.trust_codes) codes += (codes.empty() ? "" : ", ") + c;
      page += fmt::format(
          "<p class=\"verdict doubtful\" id=\"trust\"><b>DOUBTFUL</b> ({}): the input was probably read wrong, "
          "or the model does not hold for it; the number below is not these surfaces' friction until it is "
          "fixed: add <code>{}</code>.</p>\n",
          escape_html(codes), escape_html(p.trust_fix));
    }
    page += fmt::format(
        "<p class=\"verdict\" id=\"headline\">A tilt test of {}{} reads <b>φ = {}</b> (μ = <b>{}</b>){}; rigid "
        "upper bound {} = {} (μ ≤ {}); the paper's Eq. 18 range {} … {}.<br><small>Model: {} ({}); "
        "sliding at {:g}°, μ_a = {:g}; conditioning: {}; the test: {}run-away distance d = {:.3g} m ({}); over "
        "{}.</small></p>\n",
        two_surfaces(in, d) ? "these surfaces" : "this surface against itself",
        std::isfinite(p.load) ? fmt::format(" under a load of {:.3g} N (E* = {:.3g} Pa)", p.load, p.contact_modulus)
                              : std::string(),
        fmt_deg(p.friction_angle.q50), fmt_mu(p.friction_coefficient),
        p.single_drop ? " from this drop"
                      : fmt::format(", the median over drops; 90 % of tests between {} and {}",
                                    fmt_deg(p.friction_angle.q05), fmt_deg(p.friction_angle.q95)),
        p.is_map ? "(the steepest seat the drops rested in)" : "θ_max + θ_a", fmt_deg(p.upper_bound_friction_angle),
        fmt_mu(p.upper_bound_friction_angle >= std::numbers::pi / 2 - 1e-9 ? std::numeric_limits<double>::infinity()
                                                                           : std::tan(p.upper_bound_friction_angle)),
        fmt_deg(p.eq18_range[0]), fmt_deg(p.eq18_range[1]), p.model,
        p.is_map ? (std::isfinite(p.load) ? "the block locked to the direction, quasi-static hold angle on the "
                                            "loaded lift of the elastic half-space"
                                          : "a rigid block free to move sideways, quasi-static")
                 : (std::isfinite(p.load) ? "the quasi-static hold angle on the loaded lift of Hertzian asperities"
                                          : "the quasi-static hold angle on the exact lift"),
        p.direction * 180 / std::numbers::pi, p.atomic_friction, escape_html(p.conditioning),
        p.is_map ? std::string() : fmt::format("block length L_b = {:.3g} m, ", p.block_length), p.runaway_distance,
        escape_html(p.test_lengths), drops);
    if (!p.warnings.empty()) {
      page += "<div class=\"warnings\" id=\"warnings\"><b>Warnings</b><ul>\n";
      for (const Warning& w : p.warnings)
        page += fmt::format("<li><code>{}</code>: {}</li>\n", escape_html(w.code), escape_html(w.message));
      page += "</ul></div>\n";
    }
    page += d_sweep_figure(p);
    page += load_curve_figure(p);
    // The same object as `frictal predict --json`, for scripts that read the page ("</" escaped).
    const std::string upper = d.surfaces.pair ? in.upper_name : d.surfaces.lower_name;
    std::string json = prediction_json(p,
                                       fmt::format("\"lower\": {}, \"upper\": {}", json_quoted(d.surfaces.lower_name),
                                                   json_quoted(upper.empty() ? d.surfaces.lower_name : upper)),
                                       0);
    for (std::size_t k = 0; (k = json.find("</", k)) != std::string::npos; k += 3) json.replace(k, 2, "<\\/");
    page += "<script type=\"application/json\" id=\"prediction\">" + json + "</script>\n";
    if (d.areal && d.areal->failure.empty()) {
      const ReportArealSignature& a = *d.areal;
      page += fmt::format(
          "<p class=\"bounds\">The grid areal signature below (a diagnostic of the maps' nodes, as `frictal areal` "
          "computes it): its bound θ_max + θ_a = {} towards {:g}° and {} towards {:g}° (θ_max = {} / {}).</p>\n",
          fmt_deg(a.forward.friction_angle), deg(a.direction), fmt_deg(a.backward.friction_angle),
          std::fmod(deg(a.direction) + 180, 360), fmt_deg(a.signature.theta_max_forward),
          fmt_deg(a.signature.theta_max_backward));
    } else if (!in.is_map) {
      page += fmt::format(
          "<p class=\"bounds\">{}: rigid upper bound θ_max + θ_a = {} towards +x and {} towards −x (θ_max = {} / "
          "{}).</p>\n",
          "The signature function below (the whole upper scan over offsets 0 to half its length, as "
          "`frictal signature` computes it; a diagnostic of another block than the stated test's)",
          fmt_deg(fwd.friction_angle), fmt_deg(bwd.friction_angle), fmt_deg(r.theta_max_forward),
          fmt_deg(r.theta_max_backward));
    }
  } else if (d.areal && d.areal->failure.empty()) {
    const ReportArealSignature& a = *d.areal;
    page += fmt::format(
        "<p class=\"verdict\">The grid areal signature's bound θ_max + θ_a (a diagnostic of the maps' nodes, "
        "`frictal areal`): μ ≤ <b>{}</b> towards {:g}° (Eq. 18 range {} … {}) and μ ≤ <b>{}</b> towards {:g}°; "
        "θ_max = {} / {}, μ_a = {:g}.</p>\n",
        fmt_mu(a.forward.friction_coefficient), deg(a.direction), fmt_mu(a.forward.friction_coefficient_low),
        fmt_mu(a.forward.friction_coefficient), fmt_mu(a.backward.friction_coefficient),
        std::fmod(deg(a.direction) + 180, 360), fmt_deg(a.signature.theta_max_forward),
        fmt_deg(a.signature.theta_max_backward), in.atomic_friction);
  } else {
    page += fmt::format(
        "<p class=\"verdict\">Rigid upper bound θ_max + θ_a: μ ≤ <b>{}</b> towards +x (Eq. 18 range {} … {}) "
        "and μ ≤ <b>{}</b> towards −x; θ_max = {} / {}, μ_a = {:g}.</p>\n",
        fmt_mu(fwd.friction_coefficient), fmt_mu(fwd.friction_coefficient_low), fmt_mu(fwd.friction_coefficient),
        fmt_mu(bwd.friction_coefficient), fmt_deg(r.theta_max_forward), fmt_deg(r.theta_max_backward),
        in.atomic_friction);
  }
  return page;
}

std::vector<std::string> assumptions(const ReportInput& in, const ReportData& d) {
  const ReportSurfaces& s = d.surfaces;
  const SignatureResult& r = d.signature;
  const LengthUnit xu = lateral_unit(d);
  std::vector<std::string> out;
  if (in.is_map && in.upper_map)
    out.push_back(fmt::format(
        "The lower block's face is {}; the upper block's face is {} as measured (material below), turned over "
        "onto it about the axis across x: the headline's prediction and the areal section; about the axis across "
        "each direction in the areal signature and the polar plot. The resolution study takes the lower map's "
        "central line against the upper map's turned over (rotated 180°).",
        escape_html(s.lower_name), escape_html(in.upper_name)));
  else
    out.push_back(s.pair ? fmt::format("The lower block's face is {}; the upper block's face is {} as measured "
                                       "(material below), turned over by 180° to face it.",
                                       escape_html(s.lower_name), escape_html(s.upper_name))
                         : fmt::format("The upper block is the surface itself turned over (rotated 180°): {} "
                                       "slides on a copy of itself.",
                                       escape_html(s.lower_name)));
  out.push_back(
      fmt::format("Conditioning applied to each measured surface before anything else (crop, spike "
                  "removal, form removal, in that order): <b>{}</b>.",
                  escape_html(in.detrend.empty() ? std::string("none") : in.detrend)));
  if (in.is_map)
    out.push_back(fmt::format(
        "The resolution study uses the central line along x of {} (y = {}), the longest valid run: {} points "
        "over {}{}. {}",
        in.upper_map ? "each map" : "the map", fmt_len(s.line_y, length_unit(in.map.height())), s.lower.size(),
        fmt_len(s.lower.length(), xu),
        in.upper_map ? fmt::format(" (the upper map's at y = {}: {} points over {})",
                                   fmt_len(s.upper_line_y, length_unit(in.upper_map->height())), s.upper.size(),
                                   fmt_len(s.upper.length(), xu))
                     : std::string(),
        in.upper_map ? "The areal signature, the slope distributions and the polar plot take the two maps whole."
                     : "The areal signature, the slope distributions and the polar plot take the map whole, against "
                       "itself turned over."));
  out.push_back(in.is_map ? "Rigid blocks: the upper block only translates (no rotation, no deformation)."
                          : "Rigid blocks: the upper block only translates (no rotation, no deformation). Contact "
                            "slopes follow the paper's exact polyline rules (edge–edge, vertex–edge, "
                            "vertex–vertex).");
  if (d.areal && d.areal->failure.empty() && !d.areal->signature.offset.empty()) {
    const ArealSignature& a = d.areal->signature;
    out.push_back(
        fmt::format("Offsets s of the areal signature from {} to {} (half the lower map's extent along "
                    "the direction, `frictal areal`'s default).",
                    fmt_len(a.offset.front(), xu), fmt_len(a.offset.back(), xu)));
  } else if (!in.is_map) {
    out.push_back(fmt::format("Offsets x_ofs from {} to {} ({}).", fmt_len(r.offset.front(), xu),
                              fmt_len(r.offset.back(), xu),
                              s.lower.period ? "one period" : "up to half the shorter block"));
  }
  out.push_back(fmt::format("Atomic friction μ_a = {:g} (Eq. 6).", in.atomic_friction));
  out.push_back(
      "Units: lengths as read from the file(s), converted to metres and shown in the unit printed on each axis; "
      "angles in degrees.");
  for (const auto& n : in.notes) out.push_back(escape_html(n));
  return out;
}

// --- the list ---------------------------------------------------------------------------------
const std::vector<PageSection>& page_sections() {
  using In = const ReportInput&;
  using D = const ReportData&;
  static const std::vector<PageSection> sections = {
      {"surface",
       [](In in, D d) -> std::string {
         return map_pair(in) ? "The two maps: lower and upper" : d.surfaces.pair ? "The two surfaces" : "The surface";
       },
       [](D) { return true; }, surface_section},
      {"signature", [](In in, D) { return "Signature function of " + lines_of(in) + " (a diagnostic)"; },
       [](D d) { return !d.areal; }, signature_section},
      {"areal-signature",
       [](In in, D) -> std::string {
         return map_pair(in) ? "The pair's areal signature along the headline's direction (a diagnostic)"
                             : "The map's areal signature against itself along the headline's direction (a diagnostic)";
       },
       [](D d) { return d.areal.has_value(); }, areal_signature_section},
      {"slopes", [](In, D) -> std::string { return "Slope distributions"; }, [](D d) { return !d.areal; },
       slopes_section},
      {"areal-slopes", [](In, D) -> std::string { return "Slope distributions of the facets and the contacts"; },
       [](D d) { return d.areal.has_value(); }, areal_slopes_section},
      {"friction",
       [](In in, D) { return "Rigid upper bound (Eq. 6) and Eq. 18's range of " + lines_of(in) + " (a diagnostic)"; },
       [](D d) { return !d.areal; }, friction_section},
      {"hold", [](In in, D) { return "The hold angle over drops of " + lines_of(in) + " (a diagnostic)"; },
       [](D d) { return !d.areal; }, hold_section},
      {"areal-hold", [](In, D) -> std::string { return "Areal blocks that may move sideways: the headline's drops"; },
       [](D d) { return d.areal_hold.has_value(); }, areal_hold_section},
      {"directions",
       [](In in, D) -> std::string {
         return map_pair(in) ? "The pair over sliding directions (a diagnostic of its anisotropy)"
                             : "The map over sliding directions (a diagnostic of its anisotropy)";
       },
       [](D d) { return d.directions.has_value(); }, directions_section},
      {"resolution", [](In in, D) { return "Dependence on resolution of " + lines_of(in) + " (a diagnostic)"; },
       [](D d) { return d.resolution.has_value(); }, resolution_section},
  };
  return sections;
}

}  // namespace frictal::report::detail
