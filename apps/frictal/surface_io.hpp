// frictal CLI — options shared by the commands that read measured surfaces (any format):
// --format, --unit, --x-column/--z-column; the conditioning before an analysis (--crop,
// --remove-spikes, --spike-threshold, beside each command's --detrend); warnings go to stderr.
#pragma once

#include <cctype>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "common.hpp"
#include "frictal/analysis.hpp"
#include "frictal/conditioning.hpp"
#include "frictal/io.hpp"
#include "frictal/units.hpp"
#include "options.hpp"

namespace frictal::cli {

struct InputOptions {
  std::string format = "auto";
  std::string unit, x_unit, z_unit;
  int x_column = -1, z_column = -1;
  std::string spacing;  ///< "0.5um", "2e-6" (m)
  std::string channel;
};

inline void add_input_options(CLI::App& app, InputOptions& o) {
  app.add_option("--format", o.format,
                 "Input format: auto, csv, dektak, gwyddion, x3p, matrix, xyz, sdf, npy, gwyddion-lib (default: detect "
                 "from content)");
  app.add_option("--unit", o.unit,
                 "Unit of the file's lengths, x and z: m, mm, um, nm; overrides the units the file names (a warning "
                 "says so); where it names none, instead of metres (default: the file's, else m with a warning)");
  app.add_option("--x-unit", o.x_unit,
                 "Unit of the file's lateral lengths (x, y, spacing): m, mm, um, nm; overrides the file's (and "
                 "--unit's) for them");
  app.add_option("--z-unit", o.z_unit,
                 "Unit of the file's heights: m, mm, um, nm; overrides the file's (and --unit's) for them");
  app.add_option("--x-column", o.x_column, "0-based column of x in delimited text (default: automatic)");
  app.add_option("--z-column", o.z_column, "0-based column of z in delimited text (default: the one after x)");
  app.add_option(
      "--spacing", o.spacing,
      "Sampling interval for data without one (a column of heights, .npy, a bare matrix): a length such as 0.5um "
      "(no unit: metres)");
  app.add_option("--channel", o.channel, "Channel of a multi-channel file: index or name (see 'frictal info FILE')");
}

/// "0.5um", "0.5 um", "2e-6" (metres) -> metres; UsageError naming the option otherwise.
inline double parse_length_option(const std::string& text, const char* option) {
  std::size_t k = 0;
  while (k < text.size() &&
         (std::isdigit((unsigned char)text[k]) || text[k] == '.' || text[k] == '-' || text[k] == '+' ||
          ((text[k] == 'e' || text[k] == 'E') && k + 1 < text.size() &&
           (std::isdigit((unsigned char)text[k + 1]) || text[k + 1] == '-' || text[k + 1] == '+'))))
    ++k;
  double v = 0;
  std::string unit = text.substr(k);
  while (!unit.empty() && unit.front() == ' ') unit.erase(0, 1);
  const std::optional<double> unit_scale = units::length_scale(unit);
  if (!unit_scale)
    throw UsageError(fmt::format("{} '{}': unit '{}' not understood (expected m, mm, um, nm)", option, text, unit));
  const double scale = *unit_scale;
  try {
    std::size_t used = 0;
    v = std::stod(text.substr(0, k), &used);
    if (used != k) throw std::invalid_argument("");
  } catch (const std::out_of_range&) {
    throw UsageError(fmt::format("{} '{}' is beyond the range of double (normal lengths are {} .. {} m)", option, text,
                                 std::numeric_limits<double>::min(), std::numeric_limits<double>::max()));
  } catch (const std::exception&) {
    throw UsageError(fmt::format("{} '{}' is not a length (expected e.g. 0.5um or 5e-7)", option, text));
  }
  if (!(v > 0) || !std::isfinite(v)) throw UsageError(fmt::format("{} must be positive (got '{}')", option, text));
  if (v * scale < std::numeric_limits<double>::min())  // in metres below the normal range: precision lost
    throw UsageError(fmt::format("{} '{}' is beyond the range of double (normal lengths are {} .. {} m)", option, text,
                                 std::numeric_limits<double>::min(), std::numeric_limits<double>::max()));
  return v * scale;
}

inline ReadOptions read_options(const InputOptions& o) {
  for (const auto& [option, unit] : {std::pair{"--unit", &o.unit}, {"--x-unit", &o.x_unit}, {"--z-unit", &o.z_unit}})
    if (!unit->empty() && !units::length_scale(*unit))
      throw UsageError(fmt::format("{} '{}': not a length unit (expected m, mm, um, nm)", option, *unit));
  ReadOptions r;
  r.format = unwrap(parse_format(o.format));
  r.default_unit = o.unit;
  r.x_unit = o.x_unit.empty() ? o.unit : o.x_unit;
  r.z_unit = o.z_unit.empty() ? o.unit : o.z_unit;
  r.x_column = o.x_column;
  r.z_column = o.z_column;
  if (!o.spacing.empty()) r.spacing = parse_length_option(o.spacing, "--spacing");
  r.channel = o.channel;
  return r;
}

inline SurfaceData load_surface(const std::string& path, const InputOptions& o) {
  SurfaceData s = unwrap(read_surface(input_path(path), read_options(o)));
  for (const auto& w : s.warnings) fmt::print(stderr, "frictal: warning: {}\n", w.message);
  return s;
}

/// The conditioning options (frictal/conditioning.hpp), the same in every command that reads
/// measured surfaces: the fields of conditioning_settings() (--crop, --remove-spikes,
/// --spike-threshold; each command's --detrend separately, add_detrend_option), as typed.
struct ConditioningOptions {
  FieldWords words;
  /// The option of that field was given (e.g. "crop").
  bool given(const std::string& name) const { return words.words.count(name) > 0; }
  /// --remove-spikes was given (and not --no-remove-spikes).
  bool remove_spikes() const { return given("remove_spikes") && words.words.at("remove_spikes") == "true"; }
};

inline void add_conditioning_options(CLI::App& app, ConditioningOptions& o) {
  add_field_options(app, conditioning_settings(), o.words, {"detrend"});
}

/// --detrend, the field of conditioning_settings(), with one help text in every command that reads
/// measured surfaces; the text is checked where each command reads it (form_to_remove, parse_detrend).
inline void add_detrend_option(CLI::App& app, std::string& detrend) {
  const Field& f = *find_field(conditioning_settings(), "detrend");
  app.add_option(cli_option_name(f), detrend, field_help(f))->type_name("FORM");
}

/// The form to remove: --detrend's text `given`, or when it is empty the one default of every
/// front end (default_form(): a line, a plane for maps, the mean of a periodic profile), none for a
/// generated surface (exact). UsageError (exit 2) for text parse_detrend refuses.
inline Detrend form_to_remove(const std::string& given, bool generated, bool periodic = false) {
  if (generated && given.empty()) return Detrend{DetrendKind::None, 0};
  return form_or_default(given.empty() ? std::nullopt : std::optional<Detrend>(unwrap(parse_detrend(given))), periodic);
}

/// The conditioning the options ask for, with `form` removed last. UsageError (exit 2) naming the
/// option for a bad window or threshold (the table's check), or a threshold without --remove-spikes.
inline Conditioning conditioning(const ConditioningOptions& o, const Detrend& form) {
  const ValueSet v = si_values(conditioning_settings(), o.words);
  if (o.given("spike_threshold"))
    require(o.remove_spikes(), fmt::format("--spike-threshold {}: applies to --remove-spikes, which is not given",
                                           o.words.words.at("spike_threshold")));
  const ConditioningSettings settings = unwrap(make_conditioning_settings(v));
  Conditioning c = settings.of_surface();
  c.form = form;
  if (c.crop) c.crop_source = fmt::format("--crop '{}'", o.words.words.at("crop"));
  return c;
}

/// The file's areal map conditioned by `c` (error naming the file for a line profile: `needs`
/// says what the command wants, e.g. "areal-tilt needs maps"). `records` (if given) gains the
/// record of its conditioning. `warnings` (if given) gains the reader's warnings (with its codes,
/// already printed on standard error by load_surface) and the plausibility checks of the
/// conditioned map (warnings.hpp).
inline Map load_conditioned_map(const std::string& path, const InputOptions& o, const Conditioning& c,
                                const char* needs, std::vector<Warning>* warnings = nullptr,
                                std::vector<ConditioningRecord>* records = nullptr) {
  const SurfaceData s = load_surface(path, o);
  if (!s.is_map) throw UsageError(fmt::format("{}: a line profile; {}", path, needs));
  ConditionedMap m = unwrap(condition(s.map, c, path));
  if (records) records->push_back(m.record);
  if (warnings) {
    for (const auto& w : s.warnings) add_warning(*warnings, w);
    for (Warning& w : check_map(m.map, path, {}, rms_height_as_read(s.map.heights)))
      add_warning(*warnings, std::move(w));
  }
  return std::move(m.map);
}

/// The surface as a single-valued profile (error naming the file for maps or folded curves).
inline void require_profile(const SurfaceData& s, const std::string& path) {
  if (s.is_map)
    throw UsageError(
        fmt::format("{}: an areal map ({} x {}); this command needs a line profile", path, s.map.nx, s.map.ny));
}
inline Profile surface_profile(const SurfaceData& s, const std::string& path) {
  require_profile(s, path);
  return unwrap(as_profile(s.curve, path));
}
/// The same, taking the data's points over (no copy).
inline Profile surface_profile(SurfaceData&& s, const std::string& path) {
  require_profile(s, path);
  return unwrap(as_profile(std::move(s.curve), path));
}

}  // namespace frictal::cli
