// frictal CLI — helpers shared by subcommands: unit conversion at the interface, loading
// surfaces with user-facing errors, JSON printing.
#pragma once

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "frictal/geometry.hpp"
#include "frictal/io.hpp"

namespace frictal::cli {

inline constexpr double kDeg = std::numbers::pi / 180.0;
inline double to_deg(double rad) { return rad / kDeg; }

/// Unwraps a library Result or throws its error (message and code).
template <class T>
T unwrap(Result<T> r) {
  if (!r) fail(r.error());
  return std::move(r).value();
}
inline void unwrap(const Status& s) {
  if (!s) fail(s.error());
}

/// Loads a single-valued profile from any readable format.
inline Profile load_profile(const std::string& path) { return unwrap(read_profile(path)); }

/// Prints a JSON object on stdout (NaN/inf become null, as JSON has no such numbers).
inline void print_json(const nlohmann::json& j) { fmt::print("{}\n", j.dump(2)); }

/// A finite number check for options, naming the option.
inline void require(bool ok, const std::string& message) {
  if (!ok) throw UsageError(message);
}

}  // namespace frictal::cli
