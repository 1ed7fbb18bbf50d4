// frictal._core — helpers shared by the binding files: errors, arrays, releasing the GIL around
// library calls, and keywords derived from the library's settings tables (frictal/settings.hpp):
// a table's field names are the Python keywords, in SI units (metres, radians).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cerrno>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <cstdio>

#include "frictal/conditioning.hpp"
#include "frictal/map.hpp"
#include "frictal/outputs.hpp"
#include "frictal/predict.hpp"
#include "frictal/result.hpp"
#include "frictal/settings.hpp"

namespace frictal::py_detail {

namespace py = pybind11;

/// The value of a Result, or ValueError with the library's message.
template <class T>
T ok(Result<T> r) {
  if (!r) throw py::value_error(r.error().message);
  return std::move(r).value();
}
inline void ok(const Status& s) {
  if (!s) throw py::value_error(s.error().message);
}

/// A path to read that names nothing: FileNotFoundError (errno ENOENT, with the path as its
/// filename, the reader's words as its message), as open() raises it; any other reading error stays
/// the library's ValueError. Every Python function that reads a file calls this first.
inline void require_file(const std::string& path) {
  std::error_code ec;
  if (path == "-" || std::filesystem::exists(path, ec) || ec) return;
  PyErr_SetObject(PyExc_FileNotFoundError, py::make_tuple(ENOENT, "no such file, expected a surface file", path).ptr());
  throw py::error_already_set();
}

/// A Map from a 2-D array of heights (rows along y; m) with spacings dx, dy and origin x0, y0
/// (m), checked (ValueError naming what is wrong). io_bindings.cpp.
Map to_map(const py::array_t<double, py::array::c_style | py::array::forcecast>& h, double dx, double dy, double x0 = 0,
           double y0 = 0);

/// The `crop` keyword: None, a sequence (x0, x1) or (x0, x1, y0, y1) in m, or the CLI's text
/// "x0,x1[,y0,y1]" (units allowed: "0.1mm,0.9mm"); ValueError naming crop otherwise.
/// io_bindings.cpp.
std::optional<CropWindow> crop_window(const py::object& crop);

/// A surface from a path (read with `format`, `unit`, `spacing`, and the unit overrides `x_unit`,
/// `z_unit`: ReadOptions'), a Profile, a dict as read_surface/read_map return it, or a numpy array
/// of heights (1-D: a profile, 2-D: a map, rows along y) with `spacing` (m); `what` names it in
/// errors (ValueError/TypeError).
PredictSurface to_surface(const py::handle& obj, double spacing, const std::string& format, const std::string& unit,
                          const std::string& what, const std::string& x_unit = "", const std::string& z_unit = "");

/// ReadOptions' units from Python's keywords: `unit` for both axes (and for columns that name
/// none), `x_unit` / `z_unit` for one (ValueError for a unit that is no length).
void set_units(ReadOptions& o, const std::string& unit, const std::string& x_unit, const std::string& z_unit);

/// A profile pair as signature() and hold_angle() take it: each side read as to_surface reads it
/// and conditioned as `frictal signature` conditions its files (crop, spikes, then the form
/// `detrend` names, else the rule of every front end: form_or_default, conditioning.hpp), with the
/// warnings the CLI gives (the readers', each conditioned profile's plausibility, the pair's scales).
struct ProfilePair {
  Profile lower;
  Profile upper;           ///< as measured (not turned over); lower's copy when none was given
  bool has_upper = false;  ///< an upper surface was given
  std::vector<Warning> warnings;
  std::string conditioning;  ///< what the conditioning did (the CLI's "conditioning")
};
ProfilePair conditioned_profiles(const py::object& lower, const py::object& upper,
                                 const std::optional<std::string>& detrend, const py::object& crop, bool remove_spikes,
                                 double spike_threshold, double spacing, const std::string& format,
                                 const std::string& unit);
/// The same, conditioned as `c` says (the keywords of conditioning_settings(): conditioning_keywords).
ProfilePair conditioned_profiles(const py::object& lower, const py::object& upper, const ConditioningSettings& c,
                                 double spacing, const std::string& format, const std::string& unit);

inline py::dict py_row(const OutputRow& row);
/// The warnings as Python's dicts hold them: [{code, message}].
inline py::list warning_list(const std::vector<Warning>& ws) {
  py::list l;
  for (const Warning& x : ws) l.append(py_row(row_of(warning_columns(), x)));
  return l;
}

/// Runs `f` (a pure C++ computation returning a Result) with the GIL released, so that other
/// Python threads run meanwhile; the Result is unwrapped after the GIL is taken back.
template <class F>
auto nogil(F&& f) {
  py::gil_scoped_release release;
  return f();
}

/// A number with 10 significant digits.
inline std::string num(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}

inline py::array_t<double> arr(const std::vector<double>& v) { return py::array_t<double>(v.size(), v.data()); }

/// An output value as Python's dicts hold it (frictal/outputs.hpp): SI numbers (None for NaN, the
/// CLI's null), an int for a
/// "count" column, a list of str for a list of texts, a numpy array for a list of numbers (of ints
/// for a "count" column), of the column's `shape` where it has one.
inline py::object py_value(const std::string& unit, const OutputValue& v, const std::vector<std::size_t>& shape = {},
                           bool fixed = false) {
  if (auto* d = std::get_if<double>(&v)) {
    // Not a number: None, as the CLI's JSON writes null (the dicts stay JSON-safe; a setting's
    // "automatic"); an infinite bound stays a float.
    if (std::isnan(*d)) return py::none();
    if (unit == "count") return std::isfinite(*d) ? py::object(py::int_(static_cast<long long>(*d))) : py::none();
    return py::float_(*d);
  }
  if (auto* t = std::get_if<std::string>(&v)) return py::str(*t);
  if (auto* b = std::get_if<bool>(&v)) return py::bool_(*b);
  if (auto* texts = std::get_if<std::vector<std::string>>(&v)) {
    py::list names;
    for (const std::string& t : *texts) names.append(py::str(t));
    return names;
  }
  const std::vector<double>& l = std::get<std::vector<double>>(v);
  if (fixed) {  // a point or a range: a tuple
    py::tuple t(l.size());
    for (std::size_t i = 0; i < l.size(); ++i)
      t[i] = std::isnan(l[i])  ? py::object(py::none())
             : unit == "count" ? py::object(py::int_(static_cast<long long>(l[i])))
                               : py::object(py::float_(l[i]));
    return t;
  }
  py::array a;
  if (unit == "count") {
    std::vector<long long> n(l.begin(), l.end());
    a = py::array_t<long long>(static_cast<py::ssize_t>(n.size()), n.data());
  } else {
    a = arr(l);
  }
  if (shape.empty()) return a;
  return a.reshape(std::vector<py::ssize_t>(shape.begin(), shape.end()));
}

/// A nested column's objects as Python holds them: "object:" and "settings" one dict (None without
/// one), "map" a
/// dict of a data map's entries,
/// "list:" a list of dicts, "map:" a dict of dicts under each row's first value (a text), "rows:"
/// rows of numbers as one array of `shape` (rows, columns) in SI, other rows as a list of tuples.
inline py::object py_rows(const std::string& unit, const std::vector<OutputRow>& rows,
                          const std::vector<std::size_t>& shape = {}) {
  // "settings": a settings table's values (tilt's settings and surface objects), one dict in SI.
  if (unit.starts_with("object:") || unit == "settings")
    return rows.empty() ? py::object(py::none()) : py::object(py_row(rows.front()));
  if (unit == "map") {  // a data map: its entries under their keys (data, an empty key included)
    py::dict m;
    for (const OutputRow& r : rows)
      for (const OutputField& f : r) m[py::str(f.info.python)] = py_value(f.info.unit, f.si, f.shape, f.fixed);
    return m;
  }
  if (unit.starts_with("map:")) {
    py::dict m;
    for (const OutputRow& r : rows)
      if (!r.empty()) m[py::str(std::get<std::string>(r.front().si))] = py_row(OutputRow(r.begin() + 1, r.end()));
    return m;
  }
  if (unit.starts_with("rows:")) {
    std::vector<double> flat;
    bool numbers = true;
    for (const OutputRow& r : rows)
      for (const OutputField& f : r) {
        const double* d = std::get_if<double>(&f.si);
        numbers = numbers && d;
        if (d) flat.push_back(*d);
      }
    const std::size_t width = shape.size() == 2 ? shape[1] : rows.empty() ? 0 : rows.front().size();
    if (numbers && flat.size() == rows.size() * width)
      return arr(flat).reshape({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(width)});
    py::list l;
    for (const OutputRow& r : rows) {
      py::tuple values(r.size());
      for (std::size_t i = 0; i < r.size(); ++i) values[i] = py_value(r[i].info.unit, r[i].si, r[i].shape, r[i].fixed);
      l.append(values);
    }
    return l;
  }
  py::list l;
  for (const OutputRow& r : rows) l.append(py_row(r));
  return l;
}

/// A nested object as a Python dict: each of its fields under its Python key, in SI.
inline py::dict py_row(const OutputRow& row) {
  py::dict d;
  for (const OutputField& f : row)
    if (!f.info.python.empty())
      d[py::str(f.info.python)] = is_nested_unit(f.info.unit) ? py_rows(f.info.unit, f.rows, f.shape)
                                                              : py_value(f.info.unit, f.si, f.shape, f.fixed);
  return d;
}

/// The generic Python writer of an output table: every column with a Python key that `value`
/// has (a value, or nested objects: "object:" a dict, "list:" a list of dicts, "rows:" a list of
/// tuples, "map:" a dict of dicts) into `d`, in SI.
/// Declared columns without either are added by the caller under their declared keys.
template <class T>
void put_columns(py::dict& d, const Columns<T>& cols, const T& value) {
  for (const Column<T>& c : cols) {
    if (c.python.empty() || !has_output(c, value)) continue;
    d[py::str(c.python)] =
        c.si ? py_value(c.unit, c.si(value), c.shape ? c.shape(value) : std::vector<std::size_t>(), c.fixed)
             : py_rows(c.unit, c.rows(value), c.shape ? c.shape(value) : std::vector<std::size_t>());
  }
}
template <class T>
py::dict to_dict(const Columns<T>& cols, const T& value) {
  py::dict d;
  put_columns(d, cols, value);
  return d;
}

/// Keywords a function no longer takes under their old name: (old name, the table's name).
using Renamed = std::vector<std::pair<std::string, std::string>>;

/// Python keyword arguments -> SI values of the table's fields. An unknown keyword is a
/// TypeError naming the nearest name among the fields and `also` (the function's keywords outside
/// the table), an old name of `renamed` a TypeError naming the new one; a bad value a ValueError
/// naming the field.
inline ValueSet keyword_values(const std::vector<Field>& fields, const py::kwargs& kw, const std::string& function,
                               const std::vector<std::string>& also = {}, const Renamed& renamed = {}) {
  ValueSet out;
  for (const auto& item : kw) {
    const std::string name = py::str(item.first);
    const Field* f = find_field(fields, name);
    if (!f) {
      for (const auto& [old_name, new_name] : renamed)
        if (name == old_name)
          throw py::type_error(function + "() got an unexpected keyword argument '" + name + "'; it is now '" +
                               new_name + "'");
      std::vector<std::string> names = also;
      for (const Field& g : fields) names.push_back(g.name);
      std::string hint;
      if (std::string n = nearest_word(name, names); !n.empty()) hint = "; did you mean '" + n + "'?";
      throw py::type_error(function + "() got an unexpected keyword argument '" + name + "'" + hint);
    }
    const py::handle v = item.second;
    FieldValue value;
    if (v.is_none() && f->type == FieldType::Choice && std::isnan(f->default_value)) continue;  // automatic
    if (v.is_none() && f->type == FieldType::Real && std::isnan(f->default_value))
      value = std::nan("");
    else if (py::isinstance<py::bool_>(v))
      value = v.cast<bool>();
    else if (py::isinstance<py::int_>(v))
      value = v.cast<std::int64_t>();
    else if (py::isinstance<py::float_>(v) || py::hasattr(v, "__float__"))
      value = v.cast<double>();
    else if (py::isinstance<py::str>(v))
      value = v.cast<std::string>();
    else
      throw py::type_error(function + "(): keyword '" + name + "' has an unsupported type");
    auto checked = check_si_value(*f, value);
    if (!checked) throw py::value_error(function + ": " + checked.error().message);
    out[name] = *checked;
  }
  return out;
}

/// The conditioning a function takes from its keywords: the fields of conditioning_settings()
/// (crop also a sequence of metres), taken out of `kw`; any other keyword left in `kw` is a
/// TypeError naming the nearest of the table's names and `also` (the function's own keywords).
inline ConditioningSettings conditioning_keywords(py::kwargs& kw, const std::string& function,
                                                  const std::vector<std::string>& also = {}) {
  py::object crop = py::none();
  if (kw.contains("crop")) {
    crop = kw["crop"];
    PyDict_DelItemString(kw.ptr(), "crop");
  }
  ConditioningSettings c = ok(make_conditioning_settings(keyword_values(conditioning_settings(), kw, function, also)));
  c.crop = crop_window(crop);
  c.crop_source = "crop=" + py::repr(crop).cast<std::string>();
  return c;
}

/// The keywords of predict(): predict_settings() then conditioning_settings().
inline const std::vector<Field>& predict_keywords() {
  static const std::vector<Field> f = [] {
    std::vector<Field> all = predict_settings();
    for (const Field& c : conditioning_settings()) all.push_back(c);
    return all;
  }();
  return f;
}

/// The fields of a table as a list of dicts, written from the table "settings_field" (name,
/// option, type, unit, default, min, max, choices, help), SI units as Python takes them.
inline py::list field_list(const std::vector<Field>& fields) {
  py::list l;
  for (const Field& f : fields) l.append(to_dict(settings_field_columns(), f));
  return l;
}

/// One docstring line per keyword: "name [unit]: help (default D; valid R)", SI units.
inline std::string keyword_doc(const std::vector<Field>& fields) {
  std::string s;
  for (const Field& f : fields) {
    std::string def;
    if ((f.type == FieldType::Real || f.type == FieldType::Choice) && std::isnan(f.default_value))
      def = "None (auto)";
    else if (f.type == FieldType::Boolean)
      def = f.default_value != 0 ? "True" : "False";
    else if (f.type == FieldType::Choice)
      def = "'" + default_text(f) + "'";
    else
      def = num(f.default_value);
    std::string range;
    if (f.type == FieldType::Real || f.type == FieldType::Integer) {
      const bool lo = std::isfinite(f.min), hi = std::isfinite(f.max);
      auto n = [](double v) { return num(v); };
      if (f.type == FieldType::Integer)
        range = lo && hi ? n(f.min) + ".." + n(f.max) : (lo ? ">= " + n(f.min) : "any");
      else if (lo && hi)
        range = std::string(f.min_open ? "(" : "[") + n(f.min) + ", " + n(f.max) + (f.max_open ? ")" : "]");
      else if (lo)
        range = (f.min_open ? "> " : ">= ") + n(f.min);
      else if (hi)
        range = (f.max_open ? "< " : "<= ") + n(f.max);
      else
        range = "any finite number";
      for (const auto& [word, value] : f.words) range += " or '" + word + "'";
    } else {
      range = range_text(f);
    }
    s += "    " + f.name + (f.unit.empty() ? "" : " [" + f.unit + "]") + ": " + f.help + " (default " + def +
         "; valid " + range + ")\n";
  }
  return s;
}

}  // namespace frictal::py_detail
