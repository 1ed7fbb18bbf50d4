// frictal CLI — the prediction's options and outputs shared by the commands that show the hold
// angle over drops (`predict`, `areal --lateral`, `anisotropy --hold`): one mapping of the
// conditioning options, one progress line, one naming of a distribution, so that for the same
// map, direction and options they print the same numbers (the library's predict()).
#pragma once

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "common.hpp"
#include "frictal/predict.hpp"
#include "surface_io.hpp"

namespace frictal::cli {

/// Fields of the prediction's settings table (predict_settings()) that a command running the
/// prediction's model offers (`areal --drops`, `anisotropy --locked`, ...): the option, its help,
/// unit, default and range are the table's, as in `frictal predict`.
inline void add_predict_options(CLI::App& app, FieldWords& words, const std::vector<std::string>& names) {
  std::vector<std::string> skip;
  for (const Field& f : predict_settings())
    if (std::find(names.begin(), names.end(), f.name) == names.end()) skip.push_back(f.name);
  add_field_options(app, predict_settings(), words, skip);
}

/// The value typed for a field of predict_settings() (SI, checked), or the table's default.
inline std::int64_t predict_integer(const FieldWords& words, const std::string& name) {
  const ValueSet v = si_values(predict_settings(), words);
  return v.count(name) ? std::get<std::int64_t>(v.at(name))
                       : static_cast<std::int64_t>(find_field(predict_settings(), name)->default_value);
}
inline bool predict_flag(const FieldWords& words, const std::string& name) {
  const ValueSet v = si_values(predict_settings(), words);
  return v.count(name) ? std::get<bool>(v.at(name)) : find_field(predict_settings(), name)->default_value != 0;
}

/// The prediction's options with the conditioning the options ask for: crop and spikes from `c`,
/// the form from `detrend` (empty: the prediction's default, a line for profiles, a plane for maps).
inline PredictOptions conditioned_predict_options(const ConditioningOptions& c, const std::string& detrend) {
  PredictOptions o;
  if (!detrend.empty()) o.detrend = unwrap(parse_detrend(detrend));
  const Conditioning cond = conditioning(c, Detrend{});
  o.crop = cond.crop;
  o.crop_source = cond.crop_source;
  o.remove_spikes = cond.remove_spikes;
  o.spike_threshold = cond.spike_threshold;
  return o;
}

/// A progress line on standard error, "frictal WHO: drop k of n" (`prefix` before "drop", e.g.
/// "direction 3 of 36, "), with the tilt the drops under way have reached and, once a drop is
/// done, the time left; redrawn in place, at most five times a second between drops; none with
/// `quiet` or when standard error is not a terminal. `prefix` is read at each call.
inline DropProgressFn drop_progress(const std::string& who, bool quiet, const std::string* prefix = nullptr,
                                    bool last_newline = true) {
  if (quiet || !isatty(fileno(stderr))) return {};
  // The time left: the drops so far at their mean time (drops differ in cost by several times, so
  // the estimate settles as they come in); from the first call of this progress line.
  struct Line {
    std::optional<std::chrono::steady_clock::time_point> start, drawn;
    std::size_t done = 0;
  };
  auto line = std::make_shared<Line>();
  return [who, prefix, last_newline, line](const DropProgress& p) {
    const auto now = std::chrono::steady_clock::now();
    if (!line->start || (p.done == 0 && line->done > 0)) *line = Line{now, std::nullopt, 0};  // (a new run of drops)
    const bool finished = p.done != line->done;
    if (!finished && line->drawn && now - *line->drawn < std::chrono::milliseconds(200)) return;
    line->drawn = now;
    line->done = p.done;
    std::string state;
    if (p.running > 0 && !std::isnan(p.tilt))
      state = p.running == 1 ? fmt::format(", the drop under way at {:.2f} deg", p.tilt / kDeg)
                             : fmt::format(", {} under way at {:.2f} deg or more", p.running, p.tilt / kDeg);
    std::string left;
    if (p.done > 0 && p.done < p.total) {
      const double per = std::chrono::duration<double>(now - *line->start).count() / double(p.done);
      const double s = per * double(p.total - p.done);
      left = s < 90 ? fmt::format(", about {:.0f} s left", s) : fmt::format(", about {:.1f} min left", s / 60);
    }
    fmt::print(stderr, "\rfrictal {}: {}drop {} of {}{}{}\033[K{}", who, prefix ? *prefix : std::string(),
               std::min(p.done + 1, p.total), p.total, state, left, p.done == p.total && last_newline ? "\n" : "");
    std::fflush(stderr);
  };
}

/// A map read as the prediction reads it (its reader's warnings kept for the result, already
/// printed); `needs` says what the command wants of a line profile, e.g. "areal needs maps".
inline PredictSurface read_map_surface(const std::string& path, const InputOptions& in, const char* needs) {
  PredictSurface s = unwrap(predict_surface(load_surface(path, in), path));
  if (!s.is_map) throw UsageError(fmt::format("{}: a line profile; {}", path, needs));
  return s;
}

/// Friction under load (docs/load.md): the words of --load, --modulus, --poisson,
/// --upper-modulus and --upper-poisson, converted after parsing (predict and report).
struct LoadWords {
  std::vector<std::string> loads;
  std::string modulus, poisson, upper_modulus, upper_poisson;
};

inline void add_load_options(CLI::App& app, LoadWords& w) {
  app.add_option("--load", w.loads,
                 "Friction under load (docs/load.md; profiles: Hertzian asperities, maps: the elastic half-space "
                 "with the block locked to the direction): the upper block's weight W, a force with its unit (N, mN, "
                 "uN, kN); a comma-separated list gives the friction-against-load curve, the first load the headline "
                 "(one load: the curve over W x 10^(-2..1) for profiles, W x 10^(-1..1) for maps). Needs --modulus "
                 "and --poisson. Default: rigid blocks");
  app.add_option("--modulus", w.modulus,
                 "With --load: Young's modulus E of LOWER (and of UPPER unless --upper-modulus): Pa, MPa, GPa");
  app.add_option("--poisson", w.poisson,
                 "With --load: Poisson's ratio nu of LOWER (and of UPPER unless --upper-poisson), in (-1, 0.5]");
  app.add_option("--upper-modulus", w.upper_modulus,
                 "With --load: Young's modulus of UPPER (default: --modulus); rigid: a rigid upper block");
  app.add_option("--upper-poisson", w.upper_poisson, "With --load: Poisson's ratio of UPPER (default: --poisson)");
}

/// --load's words: forces with their unit (N, mN, uN, nN, kN), comma-separated lists allowed; the
/// first is the headline.
inline std::vector<double> parse_forces(const std::vector<std::string>& words) {
  std::vector<double> out;
  for (const std::string& item : list_items(words)) {
    const double v = parse_quantity(item, "--load", kForceUnits,
                                    "a force with its unit: N, mN, uN, nN, kN, e.g. 2N; the block's weight");
    require(v > 0, fmt::format("--load '{}': expected a force > 0", item));
    out.push_back(v);
  }
  require(!out.empty(), "--load: give at least one force (e.g. 2N, or 0.1N,1N,10N for a curve)");
  return out;
}

/// The loaded model's options from the CLI's words (errors name the option).
inline void apply_load_options(const LoadWords& a, PredictOptions& o) {
  const bool material =
      !a.modulus.empty() || !a.poisson.empty() || !a.upper_modulus.empty() || !a.upper_poisson.empty();
  if (a.loads.empty()) {
    require(!material,
            "--modulus/--poisson/--upper-modulus/--upper-poisson: the materials of friction under load; give the "
            "load with --load (e.g. --load 2N)");
    return;
  }
  o.loads = parse_forces(a.loads);
  require(!a.modulus.empty() && !a.poisson.empty(),
          "--load: friction under load needs the material: give --modulus (Young's modulus, e.g. 70GPa) and "
          "--poisson (Poisson's ratio, e.g. 0.3)");
  o.lower_material.modulus =
      parse_quantity(a.modulus, "--modulus", kPressureUnits, "a modulus such as 70GPa, 3GPa, 2e11");
  o.lower_material.poisson = parse_quantity(a.poisson, "--poisson", {{"", 1}}, "a number in (-1, 0.5]");
  require(o.lower_material.modulus > 0, fmt::format("--modulus '{}': expected a modulus > 0", a.modulus));
  require(o.lower_material.poisson > -1 && o.lower_material.poisson <= 0.5,
          fmt::format("--poisson '{}': expected a number in (-1, 0.5]", a.poisson));
  if (a.upper_modulus == "rigid") {
    require(a.upper_poisson.empty(), "--upper-poisson: a rigid upper block has none");
    o.rigid_upper = true;
  } else if (!a.upper_modulus.empty() || !a.upper_poisson.empty()) {
    ElasticMaterial up = o.lower_material;
    if (!a.upper_modulus.empty())
      up.modulus =
          parse_quantity(a.upper_modulus, "--upper-modulus", kPressureUnits, "a modulus such as 70GPa, or rigid");
    if (!a.upper_poisson.empty())
      up.poisson = parse_quantity(a.upper_poisson, "--upper-poisson", {{"", 1}}, "a number in (-1, 0.5]");
    require(up.modulus > 0, fmt::format("--upper-modulus '{}': expected a modulus > 0", a.upper_modulus));
    require(up.poisson > -1 && up.poisson <= 0.5,
            fmt::format("--upper-poisson '{}': expected a number in (-1, 0.5]", a.upper_poisson));
    o.upper_material = up;
  }
}

}  // namespace frictal::cli
