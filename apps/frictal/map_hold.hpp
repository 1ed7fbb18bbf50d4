// frictal CLI — the prediction's options and outputs shared by the commands that show the hold
// angle over drops (`predict`, `areal --lateral`, `anisotropy --hold`): one mapping of the
// conditioning options, one progress line, one naming of a distribution, so that for the same
// map, direction and options they print the same numbers (the library's predict()).
#pragma once

#include <unistd.h>
#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "common.hpp"
#include "frictal/predict.hpp"
#include "surface_io.hpp"

namespace frictal::cli {

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
/// "direction 3 of 36, "), redrawn in place; none with `quiet` or when standard error is not a
/// terminal. `prefix` is read at each call.
inline std::function<void(std::size_t, std::size_t)> drop_progress(const std::string& who, bool quiet,
                                                                   const std::string* prefix = nullptr,
                                                                   bool last_newline = true) {
  if (quiet || !isatty(fileno(stderr))) return {};
  // The time left: the drops so far at their mean time (drops differ in cost by several times, so
  // the estimate settles as they come in); from the first call of this progress line.
  auto start = std::make_shared<std::optional<std::chrono::steady_clock::time_point>>();
  return [who, prefix, last_newline, start](std::size_t done, std::size_t total) {
    const auto now = std::chrono::steady_clock::now();
    if (!*start || done <= 1) *start = now;  // (a new run of drops: another direction)
    std::string left;
    if (done > 1 && done < total) {
      const double per = std::chrono::duration<double>(now - **start).count() / double(done - 1);
      const double s = per * double(total - done);
      left = s < 90 ? fmt::format(", about {:.0f} s left", s) : fmt::format(", about {:.1f} min left", s / 60);
    }
    fmt::print(stderr, "\rfrictal {}: {}drop {} of {}{}\033[K{}", who, prefix ? *prefix : std::string(), done, total,
               left, done == total && last_newline ? "\n" : "");
    std::fflush(stderr);
  };
}

/// A distribution over drops as JSON keys `name`_mean_deg, _std_deg, _q05_deg, _q50_deg,
/// _q95_deg, _min_deg, _max_deg (or only the quantiles with `quantiles_only`).
inline void hold_statistics_json(nlohmann::json& j, const std::string& name, const HoldStatistics& h,
                                 bool quantiles_only = false) {
  j[name + "_q05_deg"] = to_deg(h.q05);
  j[name + "_q50_deg"] = to_deg(h.q50);
  j[name + "_q95_deg"] = to_deg(h.q95);
  if (quantiles_only) return;
  j[name + "_mean_deg"] = to_deg(h.mean);
  j[name + "_std_deg"] = to_deg(h.std);
  j[name + "_min_deg"] = to_deg(h.min);
  j[name + "_max_deg"] = to_deg(h.max);
}

/// A map read as the prediction reads it (its reader's warnings kept for the result, already
/// printed); `needs` says what the command wants of a line profile, e.g. "areal needs maps".
inline PredictSurface read_map_surface(const std::string& path, const InputOptions& in, const char* needs) {
  PredictSurface s = unwrap(predict_surface(load_surface(path, in), path));
  if (!s.is_map) throw UsageError(fmt::format("{}: a line profile; {}", path, needs));
  return s;
}

}  // namespace frictal::cli
