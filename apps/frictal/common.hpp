// frictal CLI — helpers shared by subcommands: unit conversion at the interface, loading
// surfaces with user-facing errors, JSON printing, and "-" as a file name (standard input for
// an input, standard output for -o).
#pragma once

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "frictal/geometry.hpp"
#include "frictal/io.hpp"
#include "frictal/outputs.hpp"
#include "frictal/units.hpp"
#include "frictal/warnings.hpp"

namespace frictal::cli {

inline constexpr double kDeg = units::kRadPerDeg;
using units::to_deg;

/// True if `path` ends with `ext` (lower case, with its dot), in any letter case.
inline bool has_extension(const std::string& path, const std::string& ext) {
  return path.size() >= ext.size() && std::equal(ext.rbegin(), ext.rend(), path.rbegin(), [](char a, char b) {
           return std::tolower(static_cast<unsigned char>(b)) == a;
         });
}

/// Unwraps a library Result or throws its error (message and code).
template <class T>
T unwrap(Result<T> r) {
  if (!r) fail(r.error());
  return std::move(r).value();
}
inline void unwrap(const Status& s) {
  if (!s) fail(s.error());
}

/// "-" as an input: standard input, read once and kept in a temporary file (the readers detect
/// the format from the content and may read twice); any other path is returned unchanged.
/// Messages that name the temporary file name "-" instead (see stdin_name()).
std::string input_path(const std::string& path);
/// Replaces the temporary file holding standard input by "-" in a message.
std::string stdin_name(std::string message);

/// Writes an output through `write(path)`; "-" writes to standard output (through a temporary
/// file, so that any writer works). `option` names the option in errors (e.g. "-o").
void write_output(const std::string& path, const std::function<Status(const std::string&)>& write,
                  const std::string& option = "-o");
/// Writes text to `path` or to standard output for "-".
void write_text_output(const std::string& path, const std::string& text, const std::string& option = "-o");
/// The same for a long table: `header`, then row(out, i) appends row i to `out` for i < rows; the
/// text goes out in pieces of about 1 MB (a 5*10^6-row signature CSV is never held whole).
void write_text_rows(const std::string& path, const std::string& header, std::size_t rows,
                     const std::function<void(std::string& out, std::size_t i)>& row, const std::string& option = "-o");

/// Loads a single-valued profile from any readable format ("-": standard input); `options` as
/// --format, --unit, --spacing etc. give them (see surface_io.hpp).
inline Profile load_profile(const std::string& path, const ReadOptions& options = {}) {
  return unwrap(read_profile(input_path(path), options));
}

/// Prints a JSON object on stdout (NaN/inf become null, as JSON has no such numbers).
inline void print_json(const nlohmann::json& j) { fmt::print("{}\n", j.dump(2)); }

/// An output value in JSON, in the interface unit `unit` (frictal/outputs.hpp): degrees for "deg",
/// an integer for "count", NaN and inf as null.
inline nlohmann::json json_value(const std::string& unit, const OutputValue& si) {
  const OutputValue v = to_interface(unit, si);
  if (auto* d = std::get_if<double>(&v)) {
    if (!std::isfinite(*d)) return nullptr;
    if (unit == "count") return static_cast<long long>(*d);
    return *d;
  }
  if (auto* t = std::get_if<std::string>(&v)) return *t;
  if (auto* b = std::get_if<bool>(&v)) return *b;
  if (auto* texts = std::get_if<std::vector<std::string>>(&v)) return *texts;
  nlohmann::json l = nlohmann::json::array();
  for (double x : std::get<std::vector<double>>(v)) l.push_back(std::isfinite(x) ? nlohmann::json(x) : nullptr);
  return l;
}

/// A flat JSON list nested into `shape` (row-major; empty or one dimension: as it is).
inline nlohmann::json json_shaped(nlohmann::json flat, const std::vector<std::size_t>& shape) {
  if (shape.size() < 2 || !flat.is_array()) return flat;
  const std::size_t inner = flat.size() / std::max<std::size_t>(shape.front(), 1);
  const std::vector<std::size_t> rest(shape.begin() + 1, shape.end());
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t i = 0; i < shape.front(); ++i) {
    nlohmann::json part(flat.begin() + static_cast<std::ptrdiff_t>(i * inner),
                        flat.begin() + static_cast<std::ptrdiff_t>((i + 1) * inner));
    out.push_back(json_shaped(std::move(part), rest));
  }
  return out;
}

inline nlohmann::json json_nested(const std::string& unit, const std::vector<OutputRow>& rows);

/// A nested object in JSON: each of its fields under its key, in its interface unit.
inline nlohmann::json json_row(const OutputRow& row) {
  nlohmann::json o = nlohmann::json::object();
  for (const OutputField& f : row)
    if (!f.info.key.empty())
      o[f.info.key] = f.nested ? json_nested(f.info.unit, f.rows) : json_shaped(json_value(f.info.unit, f.si), f.shape);
  return o;
}

/// A nested column's objects in JSON by its unit: "object:" and "settings" the one object (null:
/// none), "rows:" a list of lists of values, "map:" an object of objects under each row's first
/// value, "map" a data map (the one row's fields under their keys, an empty key too), "list:" a
/// list of objects.
inline nlohmann::json json_nested(const std::string& unit, const std::vector<OutputRow>& rows) {
  if (unit.starts_with("object:") || unit == "settings")
    return rows.empty() ? nlohmann::json(nullptr) : json_row(rows.front());
  if (unit == "map") {
    nlohmann::json m = nlohmann::json::object();
    if (!rows.empty())
      for (const OutputField& f : rows.front()) m[f.info.key] = json_shaped(json_value(f.info.unit, f.si), f.shape);
    return m;
  }
  if (unit.starts_with("map:")) {
    nlohmann::json m = nlohmann::json::object();
    for (const OutputRow& r : rows) {
      if (r.empty()) continue;
      const OutputRow rest(r.begin() + 1, r.end());
      m[std::get<std::string>(r.front().si)] = json_row(rest);
    }
    return m;
  }
  nlohmann::json l = nlohmann::json::array();
  for (const OutputRow& r : rows) {
    if (unit.starts_with("rows:")) {
      nlohmann::json values = nlohmann::json::array();
      for (const OutputField& f : r) values.push_back(json_value(f.info.unit, f.si));
      l.push_back(values);
    } else {
      l.push_back(json_row(r));
    }
  }
  return l;
}

/// The generic JSON writer of an output table: every column of `cols` that the CLI prints (a
/// non-empty key) and that `value` has (a value, or nested objects: "object:" one, "list:" a
/// list, "rows:" a list of lists of values, "map:" an object of objects, "map" a data map) into
/// `j`, in its interface unit. Declared columns without either are written by the caller under
/// their declared keys.
template <class T>
void put_columns(nlohmann::json& j, const Columns<T>& cols, const T& value) {
  for (const Column<T>& c : cols) {
    if (c.key.empty() || !has_output(c, value)) continue;
    if (c.si) {
      j[c.key] = json_shaped(json_value(c.unit, c.si(value)), c.shape ? c.shape(value) : std::vector<std::size_t>());
      continue;
    }
    j[c.key] = json_nested(c.unit, c.rows(value));
  }
}
/// An output table's columns as one JSON object.
template <class T>
nlohmann::json object_of(const Columns<T>& cols, const T& value) {
  nlohmann::json j = nlohmann::json::object();
  put_columns(j, cols, value);
  return j;
}

/// Warnings as results: the JSON array [{code, message}] of a command's output.
inline nlohmann::json warnings_json(const std::vector<Warning>& w) {
  nlohmann::json a = nlohmann::json::array();
  for (const Warning& x : w) a.push_back(json_row(row_of(warning_columns(), x)));
  return a;
}
/// Text output: each warning on standard error, with its code.
inline void print_warnings(const std::vector<Warning>& w) {
  for (const Warning& x : w) fmt::print(stderr, "frictal: warning [{}]: {}\n", x.code, x.message);
}
/// The warnings of a rigid bound (the library's check_friction_prediction), each added once.
template <class P>
void add_bound_warnings(std::vector<Warning>& w, const P& p, const std::string& where) {
  for (Warning& x : check_friction_prediction(p, where)) add_warning(w, std::move(x));
}

/// A finite number check for options, naming the option.
inline void require(bool ok, const std::string& message) {
  if (!ok) throw UsageError(message);
}

/// The items of option words that may each hold a comma-separated list ("1N,2N" "5N" -> 1N 2N
/// 5N), empty items skipped.
inline std::vector<std::string> list_items(const std::vector<std::string>& words) {
  std::vector<std::string> out;
  for (const std::string& w : words) {
    std::size_t start = 0;
    while (start <= w.size()) {
      std::size_t comma = w.find(',', start);
      if (comma == std::string::npos) comma = w.size();
      if (comma > start) out.push_back(w.substr(start, comma - start));
      start = comma + 1;
    }
  }
  return out;
}

/// A number with an optional unit from `units` (name, factor to SI); UsageError naming `option`.
inline double parse_quantity(const std::string& text, const char* option,
                             const std::vector<std::pair<std::string, double>>& units, const char* expected) {
  const char* s = text.c_str();
  char* end = nullptr;
  const double v = std::strtod(s, &end);
  if (end == s) throw UsageError(fmt::format("{} '{}': not a number (expected {})", option, text, expected));
  std::string unit(end);
  while (!unit.empty() && unit.front() == ' ') unit.erase(0, 1);
  for (const auto& [name, factor] : units)
    if (unit == name) {
      if (!std::isfinite(v)) throw UsageError(fmt::format("{} '{}': expected a finite number", option, text));
      return v * factor;
    }
  throw UsageError(fmt::format("{} '{}': unit '{}' not understood (expected {})", option, text, unit, expected));
}

/// Moduli and pressures: Pa (or no unit), kPa, MPa, GPa.
inline const std::vector<std::pair<std::string, double>> kPressureUnits = {
    {"", 1}, {"Pa", 1}, {"kPa", 1e3}, {"MPa", 1e6}, {"GPa", 1e9}};
/// Forces: N, mN, uN, nN, kN (the unit is required).
inline const std::vector<std::pair<std::string, double>> kForceUnits = {
    {"N", 1}, {"mN", 1e-3}, {"uN", 1e-6}, {"nN", 1e-9}, {"kN", 1e3}};

}  // namespace frictal::cli
