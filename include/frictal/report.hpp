// frictal — a report that a person reads: a small SVG plotting module (axes with ticks and
// labelled units, lines, step histograms, points, polar plots, height maps as embedded PNG
// images with a colour bar and a scale bar) and the self-contained HTML page of `frictal report`
// (a profile, a pair of profiles or an areal map: the surface, its statistics, the signature
// function, the slope distributions, the predicted friction with its Eq. 18 range, the friction
// over sliding directions and theta_max against resolution).
//
// Everything returns strings; the library never writes files. Pages need nothing outside
// themselves: figures are inline SVG, images are base64 data URIs. Definitions: docs/report.md.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "frictal/analysis.hpp"
#include "frictal/areal.hpp"
#include "frictal/geometry.hpp"
#include "frictal/hold.hpp"
#include "frictal/map.hpp"
#include "frictal/predict.hpp"
#include "frictal/signature.hpp"
#include "frictal/stats.hpp"

namespace frictal::report {

// ---------------------------------------------------------------------------------------------
// Plotting

enum class SeriesStyle {
  Line,    ///< polyline through (x[i], y[i]); non-finite points break the line
  Step,    ///< histogram: x holds y.size() + 1 bin edges, y the bin values
  Points,  ///< markers at (x[i], y[i])
};

struct Series {
  std::vector<double> x, y;  ///< data in the plot's display units (the caller scales)
  std::string label;         ///< legend entry; empty: not in the legend
  std::string color;         ///< CSS colour; empty: the next colour of the palette
  SeriesStyle style = SeriesStyle::Line;
  double line_width = 1.5;  ///< (unit: px)
  bool dashed = false;
};

/// A horizontal or vertical reference line with an optional label.
struct RefLine {
  bool horizontal = true;
  double value = 0;  ///< in display units
  std::string label;
  std::string color = "#888";
};

/// A shaded range of x (vertical band) or y (horizontal band), e.g. a predicted interval.
struct Band {
  bool horizontal = false;  ///< false: lo <= x <= hi over the whole height
  double lo = 0, hi = 0;    ///< in display units
  std::string label;        ///< written at the band's top left; empty: none
  std::string color = "#f2c94c";
  double opacity = 0.3;  ///< fill opacity in [0, 1] (unitless)
};

struct Plot {
  std::string title;
  std::string x_label;  ///< including the unit, e.g. "x (µm)"
  std::string y_label;
  std::vector<Series> series;
  std::vector<RefLine> lines;
  std::vector<Band> bands;           ///< drawn under the data
  double width = 760, height = 380;  ///< (unit: px)
  bool x_log = false;                ///< logarithmic x axis (non-positive x are not drawn)
  /// Axis limits; unset: from the data (with a small margin), extended to include ref lines.
  std::optional<double> x_min, x_max, y_min, y_max;
};

/// An SVG element (no XML prolog) of a Cartesian plot. Errors: no finite data point at all
/// (an empty plot is a bug to report, not a picture to show), or mismatched array sizes.
Result<std::string> plot_svg(const Plot& plot);

struct PolarPlot {
  std::string title;
  std::string radius_label;     ///< e.g. "friction angle φ (deg)"
  std::vector<Series> series;   ///< x = direction (unit: rad, from +x towards +y), y = radius >= 0
  double size = 420;            ///< width = height (unit: px)
  std::optional<double> r_max;  ///< outer ring; unset: from the data
};
/// An SVG polar plot; Line series are closed when they span the full circle.
Result<std::string> polar_svg(const PolarPlot& plot);

struct MapImage {
  std::string title;
  std::size_t max_pixels = 320;  ///< longer side of the displayed image; larger maps are block-averaged (unitless)
  double width = 900;            ///< figure width (unit: px)
  /// Colour range as quantiles of the valid heights (outliers saturate); 0 and 1 = min and max.
  double low_quantile = 0.005, high_quantile = 0.995;
  /// Optional: mark the line y = line_y (unit: m, map coordinates) from line_x0 to line_x1 (unit: m)
  /// with a dashed line and `line_label` (e.g. the profile that the rest of a report uses).
  std::optional<double> line_y;
  double line_x0 = 0, line_x1 = 0;
  std::string line_label;
  /// Axis names (units are added) and the colour bar's name.
  std::string x_label = "x", y_label = "y", z_label = "height z";
  /// Ticks at the map's coordinates (x0 + i dx) instead of from its first node.
  bool absolute_axes = false;
  /// Optional: a polyline in map coordinates (unit: m), e.g. a block's path, drawn over the map.
  std::vector<double> path_x, path_y;
  std::string path_label;
  /// Optional: labelled points in map coordinates (unit: m).
  struct Mark {
    double x = 0, y = 0;
    std::string label;
    std::string color = "#d62728";
  };
  std::vector<Mark> marks;
};
/// An SVG figure of a height map: the map as an embedded PNG (viridis colour map, invalid points
/// grey), lateral axes with ticks, a colour bar labelled in a length unit and a scale bar.
/// Errors: an invalid map.
Result<std::string> map_svg(const Map& m, const MapImage& options = {});

// ---------------------------------------------------------------------------------------------
// Building blocks (exposed for tests and for other front ends)

/// "Nice" tick positions covering [lo, hi] (about `target` of them; steps 1, 2, 2.5 or 5 x 10^k).
std::vector<double> nice_ticks(double lo, double hi, int target = 6);

/// A length unit for display: values are divided by `scale` (m per unit) and shown with `name`.
struct LengthUnit {
  double scale = 1;  ///< (unit: m)
  std::string name;  ///< "m", "mm", "µm", "nm" or "pm"
};
/// The unit in which `magnitude` (unit: m) reads between 1 and 1000.
LengthUnit length_unit(double magnitude);

/// The PNG file (8-bit RGB, deflate-compressed with zlib) of an image of width x height pixels, rgb holding
/// 3 bytes per pixel row by row from the top. Errors: sizes that do not match.
Result<std::string> encode_png(std::size_t width, std::size_t height, const std::vector<std::uint8_t>& rgb);
/// Base64 (RFC 4648, with padding) of arbitrary bytes.
std::string base64(const std::string& bytes);
/// Text escaped for HTML and XML content and attribute values (& < > " ').
std::string escape_html(const std::string& text);
/// matplotlib's viridis colour map at t in [0, 1] (clamped) as r, g, b bytes: its 256-entry table,
/// entry floor(256 t) as matplotlib takes it (viridis(0.5) is #21918c).
void viridis(double t, std::uint8_t rgb[3]);

// ---------------------------------------------------------------------------------------------
// The page of `frictal report`

struct ReportInput {
  /// The lower surface: a single-valued profile, or an areal map (is_map).
  bool is_map = false;
  Profile lower;
  Map map;
  std::string lower_name;
  /// The upper block's surface as measured (material below): it is turned over (rotate180) to
  /// face the lower one. Unset: the lower surface itself turned over. Profiles only.
  std::optional<Profile> upper;
  /// For a map: the upper block's map as measured (turned over onto `map` about the axis across
  /// x). Set: the page adds the prediction's hold angles over drops (its block free to move
  /// sideways) and the path of its block dropped at s = 0 on the lift over two dimensions of offset.
  std::optional<Map> upper_map;
  std::string upper_name;
  std::string detrend;  ///< conditioning already applied (ConditioningRecord text, or the form: "none", "line", ...)
  double atomic_friction = 0;  ///< mu_a of Eq. 6 (unitless)
  /// Sliding directions of the polar plot (maps) (unitless, 1..720): each one a prediction over
  /// map_drops x map_drops drops (`frictal report` takes 12 unless told).
  int directions = 12;
  /// Maps: each direction's prediction of the polar plot drops the block on an N x N grid,
  /// N = map_drops (`frictal anisotropy --hold --drops`; the headline's N, given as `prediction`)
  /// (unitless, 2..64).
  int map_drops = PredictOptions{}.map_drops;
  /// Maps: called after each direction of the polar plot with (done, total) (unitless);
  /// a front end's progress line. Empty: none.
  std::function<void(std::size_t, std::size_t)> progress;
  int resolution_steps = 10;  ///< cutoff wavelengths of the resolution study (unitless, >= 2; 0: none)
  int bins = 90;              ///< bins of the slope PDFs (unitless)
  /// Radius of the stylus or AFM tip (unit: m); > 0: the short reliability cutoff for it
  /// (frictal/scan_stats.hpp) is drawn on the resolution plot and marks the finer cutoffs of
  /// its table as not to be trusted. 0: none.
  double tip_radius = 0;
  /// Run-away distance d of the hold-angle section (frictal/hold.hpp) (unit: m); 0: the
  /// prediction's (the stated test's), else (no prediction, or one the lines cannot take) the
  /// hold analysis's default (one period, else a tenth of the offset range).
  double runaway_distance = 0;
  unsigned threads = 0;            ///< worker threads (0 = hardware); the page does not depend on it
  std::string generated_by;        ///< e.g. the version line; shown in the footer
  std::vector<std::string> notes;  ///< extra lines for "what was assumed" (e.g. reader warnings)
  /// The prediction of this pair (frictal/predict.hpp), computed by the caller from the same
  /// files and options as `frictal predict`: the page leads with it, shows its warnings beside it
  /// and embeds it as JSON (<script type="application/json" id="prediction">, the object of
  /// `frictal predict --json`). Unset: the page leads with the rigid upper bound only.
  std::optional<Prediction> prediction;
};

// ---------------------------------------------------------------------------------------------
// The page's analyses: report_data() computes every section's results from a ReportInput (the
// library's analysis calls: signature, predict_friction, analyse_hold, areal_lift, predict() and
// areal_tilt_hold (two maps), anisotropy, gaussian_lowpass, short_reliability_cutoff, and the histograms the
// plots draw); the section writers (src/report/sections.cpp) only format them.

/// The surfaces the analyses work on, with their statistics.
struct ReportSurfaces {
  std::string lower_name;  ///< the input's lower name, or "surface" when it names none
  std::string upper_name;  ///< the upper profile's name (pair), else lower_name
  bool pair = false;       ///< an upper profile (ReportInput::upper) or an upper map (its central line) was given
  /// The lower profile, or a map's central line along x (the longest valid run of the line through
  /// y = y0 + height / 2; its abscissa starts at the map's x0) (unit: m).
  Profile lower;
  Profile upper;  ///< the upper profile as measured (material below); without a pair, `lower` (unit: m)
  ProfileStats lower_stats, upper_stats;
  bool lower_uniform = false, upper_uniform = false;  ///< is_uniform with relative tolerance 1e-6
  double line_y = 0;                                  ///< maps: y of the central line (unit: m)
  MapStats map_stats;                                 ///< maps: the map's areal statistics
  MapStats upper_map_stats;                           ///< map pairs: the upper map's areal statistics
  double upper_line_y = 0;                            ///< map pairs: y of the upper map's central line (unit: m)
};

/// The slope distributions (paper Fig. 16 style), all on one range [-limit, limit].
struct ReportSlopes {
  /// 1.1 x the largest of theta_max both ways and the 99.5 % quantiles of |surface slope| (at
  /// most pi/2) (unit: rad).
  double limit = 0;
  /// Surface slopes, every edge weighted by its length, densities relative to all the weight
  /// (steeper edges counted, not binned); `upper` for a pair only (unit: rad; density 1/rad).
  Histogram lower, upper;
  Histogram contact;  ///< theta(x_ofs) weighted by the offset length it stands for (unit: rad; 1/rad)
  /// Surface length steeper than +-limit and all the surface length, both surfaces of a pair (unit: m).
  double outside_length = 0, total_length = 0;
};

/// What a tilt test reads on the pair's lift (hold.hpp), towards +x unless said.
struct ReportHold {
  HoldAnalysis analysis;  ///< analyse_hold of the pair (run-away distance as given, else its default)
  std::vector<double>
      rest_lift;  ///< h at each forward basin's rest offset (the first lift vertex at or after it) (unit: m)
  Histogram hold,
      inertial;  ///< phi_qs and phi_in over drops, 40 bins, basins weighted by the width they drain (unit: rad; 1/rad)
};

/// Two maps: the prediction's hold angles over drops (the headline's: frictal predict's map model,
/// the block free to move sideways; locked too where the prediction has them), the block dropped at
/// s = 0 in the same model, and the lift of the map's nodes over two dimensions of offset as the
/// picture of the landscape it moves on, sliding along +x.
struct ReportArealHold {
  std::string failure;  ///< non-empty: not computed, and why (the page says so)
  /// ReportInput::prediction when it is a map prediction over drops along +x, else predict() of
  /// the page's maps (already conditioned: no form removed again) with its run-away distance and mu_a.
  Prediction prediction;
  /// areal_tilt_hold from s = 0 with the prediction's settings (map_model_options, its run-away
  /// distance), the block free: its stops after each tilt increment are the path drawn.
  ArealTiltHold from_zero;
  /// The lift of the map's nodes (areal_lift(map, upper_map, 0)) over the drops' offsets and the
  /// path, half of d around them: the picture (the model rounds the nodes by spheres of radius r).
  ArealLift lift;
  double sphere_radius = 0;  ///< r of the model (unit: m)
  /// The prediction's drops binned over [0, top] in 40 bins: edges (unit: rad) and the percent of the
  /// drops in each bin, free and (with the prediction's locked drops; else empty) locked (unitless).
  std::vector<double> edges, free_percent, locked_percent;
};

/// Maps: the pair's own analyses along the headline's sliding direction d: the grid areal signature
/// of `frictal areal LOWER [UPPER] --angle DEG` (one map: against itself turned over) with its
/// bounds, and the slopes along d of the maps' facets and of the pair's contacts.
struct ReportArealSignature {
  std::string failure;       ///< non-empty: not computed, and why (the page says so)
  double direction = 0;      ///< d: the headline's sliding direction (0 without a headline) (unit: rad)
  ArealSignature signature;  ///< areal_signature(map, upper map or map, d) with its default offsets
  /// Eq. 6 and 18 of the grid's theta_max towards +d and -d (`frictal areal`'s bound: a diagnostic
  /// of the map's nodes, not what a tilt test reads).
  FrictionPrediction forward, backward;
  /// 1.1 x the largest of theta_max both ways and the 99.5 % quantiles of |facet slope| (at most
  /// pi/2) (unit: rad).
  double limit = 0;
  /// Slopes along d of the maps' facets (each grid cell with four valid corners, its bilinear
  /// surface's gradient at the centre: the same weight each, the map as measured), `upper` for a
  /// pair only, and the contact slopes theta(s) of the signature (each offset the same weight),
  /// densities relative to all the weight (steeper ones counted, not binned) (unit: rad; 1/rad).
  Histogram lower, upper, contact;
  std::size_t facets = 0, facets_outside = 0;  ///< facets of both maps, and those steeper than +-limit (unitless)
};

/// Maps: the friction over sliding directions, the rows of `frictal anisotropy LOWER [--upper
/// UPPER] --areal --hold` with the page's directions, drops, mu_a and run-away distance (one map:
/// the map against itself turned over): the grid areal signature's theta_max and its bound (a
/// diagnostic), and predict() along each direction on the page's maps (the block free to move
/// sideways) with the hold model's bound.
struct ReportDirections {
  std::string failure;  ///< non-empty: not computed, and why (the page says so)
  bool pair = false;    ///< two maps (ReportInput::upper_map), else one map against itself turned over
  /// One row per direction, the keys of `frictal anisotropy --json` (AnisotropyRow: angles in rad,
  /// run-away distance in m).
  std::vector<AnisotropyRow> pair_table;
  /// Non-empty: the hold angles were not predicted, and why (the headline's prediction is
  /// DOUBTFUL, the job's estimated CPU time is above the prediction's limit, or predict()'s
  /// error); the rows then hold the signature's bound only.
  std::string hold_failure;
  /// The directions' predictions' warnings, each message led by its direction.
  std::vector<Warning> warnings;
  /// The direction with the highest and the lowest median hold angle (without hold angles: the
  /// signature's bound) (unit: rad).
  double best_direction = 0, best_angle = 0;
  double worst_direction = 0, worst_angle = 0;  ///< (unit: rad)
};

/// One cutoff of the resolution study: the signature of the low-pass filtered pair.
struct ReportResolutionRow {
  double cutoff = 0;                ///< Gaussian low-pass cutoff wavelength lambda_c (unit: m)
  double theta_max_forward = 0;     ///< (unit: rad)
  double theta_max_backward = 0;    ///< (unit: rad)
  double contact_slope_std = 0;     ///< sigma (unit: rad)
  double friction_coefficient = 0;  ///< Eq. 6 mu towards +x (unitless; < 0: theta_a + theta_max < 0)
  bool below_tip = false;           ///< below the tip's reliability cutoff (or the tip follows no scale)
};
/// theta_max against resolution: cutoffs log-spaced from half the length down to 4 point spacings.
struct ReportResolution {
  double cutoff_min = 0, cutoff_max = 0;  ///< 4 point spacings, half the shorter length (unit: m)
  /// The short reliability cutoff of ReportInput::tip_radius (the larger of the surfaces'; a map's: rows
  /// and columns); NaN: the tip fails up to a quarter of the scan; 0: it follows every scale; unset:
  /// no tip radius (unit: m).
  std::optional<double> tip_cutoff;
  std::size_t offsets = 0;                ///< sampled offsets of each filtered signature (unitless)
  std::vector<ReportResolutionRow> rows;  ///< empty: too few points (cutoff_max <= 1.5 cutoff_min)
};

/// Every section's results.
struct ReportData {
  ReportSurfaces surfaces;
  SignatureResult signature;  ///< the pair's (the lower profile or central line against the upper turned over)
  FrictionPrediction forward, backward;  ///< Eq. 6 and 18 both ways from the signature
  ReportSlopes slopes;
  ReportHold hold;
  std::optional<ReportArealHold> areal_hold;   ///< two maps only
  std::optional<ReportArealSignature> areal;   ///< maps only
  std::optional<ReportDirections> directions;  ///< maps only
  std::optional<ReportResolution> resolution;  ///< resolution_steps >= 2 only
};

/// The analyses of the page. Errors: inputs the analysis refuses (named). Failures of the areal
/// hold and directions analyses are results (their `failure`), not errors.
Result<ReportData> report_data(const ReportInput& input);

/// The HTML page (UTF-8) of results computed by report_data(input): the headline, one section
/// each, what was assumed. Errors: a plot with nothing to draw.
Result<std::string> report_page(const ReportInput& input, const ReportData& data);

/// The complete HTML page (UTF-8): report_page(input, report_data(input)). Errors: inputs the
/// analysis refuses (named).
Result<std::string> surface_report(const ReportInput& input);

}  // namespace frictal::report
