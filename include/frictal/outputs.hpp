// Output tables: every quantity a result type hands to the front ends, declared once (key,
// interface unit, meaning, the value in SI), the way settings.hpp declares every input. The CLI's
// JSON, Python's dicts and the documentation's outputs reference are written from these tables
// by generic writers; `frictal columns` lists them, and a test checks that every key a command or
// a Python function prints is declared here with its unit.
#pragma once

#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "frictal/result.hpp"
#include "frictal/units.hpp"

namespace frictal {

/// An output value: a number (SI inside: rad for angles, m for lengths), a text, a flag, a list
/// of numbers or a list of texts. The writers convert numbers to the column's interface unit.
using OutputValue = std::variant<double, std::string, bool, std::vector<double>, std::vector<std::string>>;

/// What a column declares, without its value: the JSON key (with its unit suffix), the interface
/// unit the text front ends write it in, what it means, and the key of Python's dicts (SI values).
///
/// Interface units: "deg" (SI value in rad), "m", "s", "kg", "m/s", "1/s", "1" (unitless), "count"
/// (an integer), "text", "flag", "value" (a settings field's value in its own SI unit and type:
/// a number, a flag or a word; NaN = none), and for nested values "object:TABLE" (a JSON object whose keys
/// are the columns of output table TABLE), "list:TABLE" (a list of such objects), "rows:TABLE" (a
/// list of rows, each a list of the values of TABLE's columns in its order, e.g. [x, y] points or
/// [tilt, x, y] stops, each value in its column's unit), "map:TABLE" (an object holding one
/// object per row, under the row's first column, a text, with the row's other columns), "settings"
/// (an object whose keys are fields of a settings table, `frictal settings`) and "map" (an object
/// whose keys are data: versions, a study task's parameters and outputs; data_map_column).
struct ColumnInfo {
  std::string key;     ///< the CLI's JSON key, e.g. "theta_max_forward_deg"; "" = Python only
  std::string unit;    ///< the interface unit (above)
  std::string help;    ///< what it means
  std::string python;  ///< the key in Python's dicts, whose numbers are SI; "" = not in Python's dicts
};

/// One column of a nested object: its declaration and its value in SI, or for a nested column
/// (`nested`: "object:", "list:", "rows:", "map:" units) the objects under it (`si` unused).
struct OutputField {
  ColumnInfo info;
  OutputValue si;
  bool nested = false;
  std::vector<std::vector<OutputField>> rows;
  std::vector<std::size_t> shape;  ///< a list's dimensions, row-major (empty: one)
  bool fixed = false;              ///< a list of a fixed length (a point, a range): Python's tuple
};
/// A nested object: the columns of its table that have a value or objects, in the table's order.
using OutputRow = std::vector<OutputField>;

/// Whether a column's unit names nested objects ("object:TABLE", "list:TABLE", "rows:TABLE",
/// "map:TABLE" or a data map, "map").
inline bool is_nested_unit(std::string_view unit) {
  return unit.starts_with("object:") || unit.starts_with("list:") || unit.starts_with("rows:") ||
         unit.starts_with("map:") || unit == "map";
}

/// One output quantity of result type T: its declaration and its value in SI, or for a nested
/// column ("object:TABLE", "list:TABLE") the objects under it.
template <class T>
struct Column : ColumnInfo {
  std::function<OutputValue(const T&)> si;
  /// Whether a value of T has this output (empty: always): the key is left out when not, e.g. a
  /// cutoff that only a given tip radius has.
  std::function<bool(const T&)> present;
  /// A nested column's objects: one for "object:TABLE", any number for "list:TABLE".
  std::function<std::vector<OutputRow>(const T&)> rows;
  /// A list's dimensions, row-major (empty: one dimension), e.g. {ny, nx} for a map's values:
  /// Python's arrays take this shape; JSON lists stay flat.
  std::function<std::vector<std::size_t>(const T&)> shape;
  /// A list of a fixed length, a point (x, y) or a range (min, max): Python's tuple, not an array.
  bool fixed = false;
};
template <class T>
using Columns = std::vector<Column<T>>;

/// Whether column `c` is written for `value`: it has a value or objects, and `value` has it.
template <class T>
bool has_output(const Column<T>& c, const T& value) {
  return (c.si || c.rows) && (!c.present || c.present(value));
}

/// `value` as a nested object: every column of `cols` that has a value or objects for it (a
/// nested column's objects nested in turn).
template <class R>
OutputRow row_of(const Columns<R>& cols, const R& value) {
  OutputRow row;
  for (const Column<R>& c : cols) {
    if (!has_output(c, value)) continue;
    if (c.si)
      row.push_back({c, c.si(value), false, {}, c.shape ? c.shape(value) : std::vector<std::size_t>(), c.fixed});
    else
      row.push_back(
          {c, OutputValue(), true, c.rows(value), c.shape ? c.shape(value) : std::vector<std::size_t>(), false});
  }
  return row;
}

/// The unit suffixes of JSON keys ("_deg" for deg, "_m" for m, ...), longest first where one
/// ends another.
inline constexpr std::string_view unit_suffixes[] = {"_m_s", "_per_s", "_n_per_m", "_deg", "_kg",
                                                     "_m2",  "_pa",    "_n",       "_m",   "_s"};

/// The Python key of JSON key `key`: the key without its unit suffix (Python's dicts hold SI
/// values, so the unit is not named). The one rule of every table; a column names another Python
/// key only where the stripped key would clash with another key of its table.
inline std::string python_key(const std::string& key) {
  for (std::string_view suffix : unit_suffixes)
    if (key.size() > suffix.size() && key.ends_with(suffix)) return key.substr(0, key.size() - suffix.size());
  return key;
}

/// The Python key of a column declared with JSON key `key` and argument `python`: "" = the rule
/// (python_key), "-" = not in Python's dicts, anything else = that key (a Python-only column, whose
/// JSON key is "", or an exception to the rule).
inline std::string python_key(const std::string& key, const std::string& python) {
  if (python == "-") return {};
  return python.empty() ? python_key(key) : python;
}

/// A column of T: `key` in `unit`, its meaning, its SI value; Python key by python_key (`python`:
/// "" = the rule, "-" = not in Python's dicts, else that key).
template <class T, class F>
Column<T> column(std::string key, std::string unit, std::string help, F&& f, std::string python = {}) {
  Column<T> c;
  c.python = python_key(key, python);
  c.key = std::move(key);
  c.unit = std::move(unit);
  c.help = std::move(help);
  c.si = [g = std::forward<F>(f)](const T& v) { return OutputValue(g(v)); };
  return c;
}

/// Column `c`, written only for values where `pred` holds.
template <class T, class P>
Column<T> only_if(Column<T> c, P&& pred) {
  c.present = std::forward<P>(pred);
  return c;
}

/// Column `c`, a list whose dimensions (row-major) `f` returns for a value.
template <class T, class F>
Column<T> with_shape(Column<T> c, F&& f) {
  c.shape = std::forward<F>(f);
  return c;
}

/// Column `c`, a list of a fixed length (a point, a range): a tuple in Python.
template <class T>
Column<T> fixed_length(Column<T> c) {
  c.fixed = true;
  return c;
}

/// A nested object column of T: `key` (unit "object:TABLE") holds the object of R that `f`
/// returns (a std::optional<R>: no value, no key), written with the columns `cols`.
template <class T, class R, class F>
Column<T> object_column(std::string key, const std::string& table, std::string help, const Columns<R>& cols, F&& f,
                        std::string python = {}) {
  Column<T> c;
  c.key = std::move(key);
  c.unit = "object:" + table;
  c.help = std::move(help);
  c.python = python_key(c.key, python);
  c.present = [f](const T& v) { return f(v).has_value(); };
  c.rows = [f, &cols](const T& v) {
    const std::optional<R> r = f(v);
    return r ? std::vector<OutputRow>{row_of(cols, *r)} : std::vector<OutputRow>{};
  };
  return c;
}

/// A nested list column of T: `key` (unit "list:TABLE") holds one object of R per element of
/// the std::optional<std::vector<R>> that `f` returns (no value, no key), written with `cols`.
template <class T, class R, class F>
Column<T> list_column(std::string key, const std::string& table, std::string help, const Columns<R>& cols, F&& f,
                      std::string python = {}) {
  Column<T> c;
  c.key = std::move(key);
  c.unit = "list:" + table;
  c.help = std::move(help);
  c.python = python_key(c.key, python);
  c.present = [f](const T& v) { return f(v).has_value(); };
  c.rows = [f, &cols](const T& v) {
    std::vector<OutputRow> out;
    if (const auto l = f(v))
      for (const R& r : *l) out.push_back(row_of(cols, r));
    return out;
  };
  return c;
}

/// A nested list column of T written as rows: `key` (unit "rows:TABLE") holds one list per element
/// of the std::optional<std::vector<R>> that `f` returns (no value, no key): the values of the
/// columns `cols` in their order, each in its own unit (a compact form of a list of objects, for
/// series of points and stops). Python's dicts hold the rows of numbers as one array (rows,
/// columns) in SI.
template <class T, class R, class F>
Column<T> rows_column(std::string key, const std::string& table, std::string help, const Columns<R>& cols, F&& f,
                      std::string python = {}) {
  Column<T> c = list_column<T, R>(std::move(key), table, std::move(help), cols, f, std::move(python));
  c.unit = "rows:" + table;
  // (rows, columns): the dimensions of Python's array of the rows.
  c.shape = [f = std::forward<F>(f), &cols](const T& v) {
    const auto l = f(v);
    return std::vector<std::size_t>{l ? l->size() : 0, cols.size()};
  };
  return c;
}

/// A nested map column of T: `key` (unit "map:TABLE") holds one object per element of the
/// std::optional<std::vector<R>> that `f` returns (no value, no key), under the value of the first
/// column of `cols` (a text: the element's name), with the other columns.
template <class T, class R, class F>
Column<T> map_column(std::string key, const std::string& table, std::string help, const Columns<R>& cols, F&& f,
                     std::string python = {}) {
  Column<T> c = list_column<T, R>(std::move(key), table, std::move(help), cols, std::forward<F>(f), std::move(python));
  c.unit = "map:" + table;
  return c;
}

/// One entry of a data map: its key (data, not a declared name: a version, a parameter or an
/// output of a study task, possibly empty), the unit its value is written in (frictal/outputs.hpp's
/// interface units: "count" for an integer, "1" for a number written as it is) and its value.
struct MapEntry {
  std::string key;
  std::string unit;
  OutputValue value;
};

/// A data map column of T: `key` (unit "map") holds an object whose keys are data, the entries
/// that `f` returns for a value (a std::vector<MapEntry>, in their order; none: an empty object),
/// each value in its entry's unit. The writers hold the entries as one nested row whose fields are
/// named by the entries' keys (an empty key included). Python key: python_key (`python`: "" = the
/// rule, "-" = not in Python's dicts, else that key).
template <class T, class F>
Column<T> data_map_column(std::string key, std::string help, F&& f, std::string python = {}) {
  Column<T> c;
  c.key = std::move(key);
  c.unit = "map";
  c.help = std::move(help);
  c.python = python_key(c.key, python);
  c.rows = [g = std::forward<F>(f)](const T& v) {
    OutputRow row;
    for (MapEntry& e : g(v)) {
      OutputField field;
      field.info = ColumnInfo{e.key, e.unit, {}, e.key};
      field.si = std::move(e.value);
      row.push_back(std::move(field));
    }
    return std::vector<OutputRow>{std::move(row)};
  };
  return c;
}

/// The columns of a warning (table "warning"): its code and message.
inline const Columns<Warning>& warning_columns() {
  static const Columns<Warning> cols = {
      column<Warning>("code", "text", "the warning's code", [](const Warning& w) { return w.code; }),
      column<Warning>("message", "text", "what was found, with numbers", [](const Warning& w) { return w.message; }),
  };
  return cols;
}

/// What a command reports beside its result: the inputs it was given and how it ran (table
/// "command"); each field that has a value is written.
struct RunRecord {
  std::optional<std::string> lower;              ///< the lower surface (file or generator)
  std::optional<std::string> upper;              ///< the upper surface, as measured
  std::optional<std::string> file;               ///< the surface file read, or the generator's name
  std::optional<std::string> format;             ///< the file's format as read
  std::optional<std::string> kind;               ///< "profile" or "map"
  std::optional<std::string> method;             ///< the method the numbers come from
  std::optional<std::string> slopes;             ///< the signature's slope method: exact or spline
  std::optional<double> surface_slope_max;       ///< steepest slope of either surface (unit: rad)
  std::optional<std::string> conditioning;       ///< every conditioning step applied first, with its numbers
  std::optional<std::vector<Warning>> warnings;  ///< implausible inputs or results
  std::optional<double> wall_time;               ///< wall time of the computation (unit: s)
  std::optional<double> hold_wall_time;          ///< of the signature and hold analysis together (unit: s)
};
/// The typed columns of RunRecord (src/catalogue/outputs.cpp).
const Columns<RunRecord>& run_record_columns();

/// A declared column of T without a value: a nested object or list that the front end writes
/// under `key` (JSON; "" = none) or `python` (Python's dicts; "" = none); the generic writers skip it.
template <class T>
Column<T> declared_column(std::string key, std::string unit, std::string help, std::string python = {}) {
  Column<T> c;
  c.key = std::move(key);
  c.unit = std::move(unit);
  c.help = std::move(help);
  c.python = std::move(python);
  return c;
}

/// The factor from SI to a column's interface unit: 180/pi for "deg", 1 otherwise.
inline double interface_factor(std::string_view unit) { return unit == "deg" ? 1.0 / units::kRadPerDeg : 1.0; }

/// A value converted from SI to the interface unit `unit` (NaN and inf stay as they are): for
/// "deg", units::to_deg, the one degree conversion.
inline OutputValue to_interface(std::string_view unit, OutputValue v) {
  if (unit != "deg") return v;
  if (auto* d = std::get_if<double>(&v)) *d = units::to_deg(*d);
  if (auto* l = std::get_if<std::vector<double>>(&v))
    for (double& x : *l) x = units::to_deg(x);
  return v;
}

/// The SI unit that Python's dicts hold a column in: "rad" for "deg", the interface unit otherwise.
inline std::string python_unit(std::string_view unit) { return unit == "deg" ? "rad" : std::string(unit); }

/// A named output table: the columns of one result type, or of the objects nested in one.
struct OutputTable {
  std::string name;  ///< e.g. "signature", "hold", "tilt"
  std::string help;  ///< which outputs carry it (command, Python function)
  std::vector<ColumnInfo> columns;
};

/// The declarations of typed columns, for an OutputTable.
template <class T>
std::vector<ColumnInfo> infos(const Columns<T>& cols) {
  return {cols.begin(), cols.end()};
}

/// Every output table of the library and its front ends (src/catalogue/outputs.cpp): the
/// vocabulary that `frictal columns`, the docs' outputs reference and the key test read.
const std::vector<OutputTable>& output_tables();

/// The build of the compiled library: its version, the commit and CMake build type it was built
/// from, and whether the 3D tilt test (MuJoCo) is compiled in. Table "build_info".
struct BuildInfo {
  std::string version, git_commit, build_type;
  bool mujoco = false;
};
/// This build's BuildInfo (src/catalogue/outputs.cpp).
BuildInfo build_info();
/// The output table of BuildInfo (Python build_info()).
const Columns<BuildInfo>& build_info_columns();

/// The table named `name`, or nullptr.
const OutputTable* find_output_table(std::string_view name);

}  // namespace frictal
