// frictal — conditioning of a measured surface before an analysis, one step description for every
// front end (CLI --crop / --remove-spikes / --spike-threshold / --detrend, Python keywords crop,
// remove_spikes, spike_threshold, detrend). The steps run in one fixed order:
//
//   1. crop:   keep the points inside a window of x (and y for maps), in the data's coordinates;
//   2. spikes: replace (profiles) or mask (maps) the points that the `spikes` plausibility rule
//              (warnings.hpp) flags, repeated until none is left;
//   3. form:   subtract the least-squares polynomial (detrend(), analysis.hpp) over the valid points.
//
// Invalid points of a map (NaN: masked by the reader or by step 2) stay NaN through every step and
// never enter a fit or a median. The record lists each step with its numbers; its text is what a
// prediction's `conditioning` says. Rules and why: docs/analysis.md, "Conditioning". Units: m.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "frictal/analysis.hpp"
#include "frictal/geometry.hpp"
#include "frictal/map.hpp"
#include "frictal/outputs.hpp"
#include "frictal/result.hpp"
#include "frictal/settings.hpp"

namespace frictal {

/// A crop window in the data's own coordinates (a profile's x; a map's x = x0 + i dx, y = y0 + j dy).
/// Points whose coordinates lie inside [min, max] are kept (ends included, to within 1e-9 of a
/// spacing).
struct CropWindow {
  double x_min = 0;    ///< (unit: m)
  double x_max = 0;    ///< (unit: m)
  bool has_y = false;  ///< maps: also crop along y (profiles: an error)
  double y_min = 0;    ///< (unit: m)
  double y_max = 0;    ///< (unit: m)
};

/// Parses "x0,x1" or "x0,x1,y0,y1": four numbers in metres, each optionally followed by a unit
/// m, mm, um (or µm) or nm ("0.1mm,0.9mm"). Errors name `option` and the text and say what is
/// expected: finite numbers, x0 < x1 and y0 < y1.
Result<CropWindow> parse_crop(const std::string& text, const std::string& option = "crop");

/// The default spike threshold k: the plausibility check's (PlausibilityLimits::spike_sq, 10), so
/// that the filter removes exactly what the `spikes` warning reports (unitless).
inline constexpr double kDefaultSpikeThreshold = 10;

/// The conditioning applied before an analysis.
struct Conditioning {
  std::optional<CropWindow> crop;  ///< step 1; nullopt: the whole surface
  /// Where the window came from, named in error messages (e.g. "--crop '1mm,2mm'" or "crop=(...)").
  std::string crop_source = "crop";
  bool remove_spikes = false;  ///< step 2 (off by default)
  /// k: a point is a spike when it lies more than k rms heights (Sq of the form-removed surface)
  /// from the median of its neighbours; finite and > 0 (unitless).
  double spike_threshold = kDefaultSpikeThreshold;
  Detrend form;  ///< step 3: the form removed (None: none)
};

/// The conditioning as every front end takes it (the CLI's --crop, --remove-spikes,
/// --spike-threshold, --detrend; Python's keywords of the same names; conditioning_settings()):
/// the form is optional, chosen per surface by form_or_default() when not given.
struct ConditioningSettings {
  std::optional<CropWindow> crop;  ///< nullopt: the whole surface
  std::string crop_source = "crop";
  bool remove_spikes = false;
  double spike_threshold = kDefaultSpikeThreshold;  ///< k (unitless, > 0)
  std::optional<Detrend> detrend;                   ///< nullopt: form_or_default()
  /// The conditioning of one surface: the form asked for, else default_form(periodic).
  Conditioning of_surface(bool periodic = false) const;
};

/// The conditioning's settings table (settings.hpp): crop (a window "X0,X1" or "X0,X1,Y0,Y1", in
/// m or with a length unit each), remove_spikes, spike_threshold, detrend ("none", "mean", "line",
/// "plane", "poly:N"; automatic by default). The CLI's options and Python's keywords of every
/// function that conditions a surface.
const std::vector<Field>& conditioning_settings();
/// The settings of those values (SI, by field name; absent: the default). Errors name the field
/// and the expected values, and the nearest name for an unknown one.
Result<ConditioningSettings> make_conditioning_settings(const ValueSet& si);

/// What the conditioning did, step by step.
struct ConditioningRecord {
  bool is_map = false;
  bool cropped = false;                      ///< a window was applied
  CropWindow window;                         ///< the window asked for (unit: m)
  std::size_t nx_before = 0, ny_before = 0;  ///< points (profiles: ny = 1) before the crop (unitless)
  std::size_t nx_after = 0, ny_after = 0;    ///< points kept by the crop (unitless)
  bool spikes_checked = false;               ///< step 2 ran
  double spike_threshold = 0;                ///< k used (unitless)
  std::size_t spikes_removed = 0;  ///< points removed: replaced or dropped (profiles), masked (maps) (unitless)
  std::size_t spikes_dropped = 0;  ///< profiles: of those, points dropped at an end (unitless)
  int spike_passes = 0;            ///< passes of the rule until none was left (unitless)
  bool spikes_left = false;        ///< the passes ran out (32) with spikes still flagged
  Detrend form;                    ///< the form removed
  /// "crop x [0.0001, 0.0009] m: 801 of 1001 points; spikes (k = 10): 3 points replaced by linear
  /// interpolation; form: line" — every step in order (the form always).
  std::string text() const;
};

struct ConditionedProfile {
  Profile profile;
  ConditioningRecord record;
};
struct ConditionedMap {
  Map map;
  ConditioningRecord record;
};

/// Conditions a profile (`name` names it in messages). Spikes are removed from the polyline: one
/// between kept points is replaced by the straight line between its nearest kept neighbours (so
/// a uniform grid stays uniform), one with no kept point on one side (at an end) is dropped. A
/// crop or a drop that changes the extent clears `period`. Errors: an invalid window (x_max <= x_min, non-finite), a
/// window along y, a window that keeps fewer than 2 points (the message gives the data's x extent), k not finite or <=
/// 0.
Result<ConditionedProfile> condition(const Profile& p, const Conditioning& c, const std::string& name = "profile");
/// The same, taking p over: without a crop its points become the result's (no copy of a profile
/// that is not kept; at 10^7 points 160 MB and a tenth of a second less).
Result<ConditionedProfile> condition(Profile&& p, const Conditioning& c, const std::string& name = "profile");
/// The same for a map: spikes become NaN (masked). Errors also when the window keeps fewer than 2
/// columns (2 rows) of a map that had more, or no valid point.
Result<ConditionedMap> condition(const Map& m, const Conditioning& c, const std::string& name = "map");

/// The text of the conditioning of a pair: records[0].text() alone when every record reads the same
/// (or there is one), otherwise "lower: ... | upper: ..." (more than two: "surface 3: ..." on).
std::string conditioning_text(const std::vector<ConditioningRecord>& records);

/// Canonical text of a Detrend ("none", "mean", "line", "plane" for maps, "poly:N").
std::string detrend_name(const Detrend& d, bool is_map);

/// What conditioning did as output columns (frictal/outputs.hpp; src/analysis/analysis_columns.cpp):
/// Python condition()'s record (table "conditioning").
const Columns<ConditioningRecord>& conditioning_record_columns();

/// The form every front end removes from a measured surface unless told otherwise (the CLI's
/// --detrend, Python's detrend=; docs/analysis.md, "Conditioning"): the least-squares line of a
/// profile, the plane of a map (both first order), and only the mean of a periodic profile, whose
/// period a line would break. Generated surfaces are exact and keep their form (front ends pass
/// DetrendKind::None for them).
inline Detrend default_form(bool periodic = false) {
  return periodic ? Detrend{DetrendKind::Mean, 0} : Detrend{DetrendKind::Line, 1};
}

/// The one conditioning rule of every front end, for every surface it is given as data (a file, an
/// array of heights, a Profile or map object, in the CLI and in Python alike): the form `asked`
/// for, else default_form(periodic). Only a surface that a front end generates itself (the CLI's
/// generator subcommands) is exempt: it keeps its form (DetrendKind::None).
inline Detrend form_or_default(const std::optional<Detrend>& asked, bool periodic = false) {
  return asked ? *asked : default_form(periodic);
}

/// The points the `spikes` rule flags: |z_i - median of its neighbours| > k * Sq, where Sq is the
/// rms of the (finite) heights about their mean; neighbours: the points up to two places away on
/// each side for a profile (4; 2 or 3 at the ends; profiles of fewer than 5 points are not
/// tested), the valid points of the 3 x 3 neighbourhood for a map (at least 3 of them). Run on
/// form-removed heights.
struct SpikeSearch {
  std::vector<std::size_t> points;  ///< indices (profiles) or flat indices j * nx + i (maps), increasing
  double worst = 0;                 ///< the largest deviation, in units of Sq (unitless)
  double rms = 0;                   ///< Sq used (unit: m)
};
SpikeSearch find_spikes(const Profile& p, double k);
SpikeSearch find_spikes(const Map& m, double k);

}  // namespace frictal
