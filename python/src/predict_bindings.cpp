// frictal._core — the prediction (frictal/predict.hpp): what a tilt test of two surfaces reads,
// the same object as `frictal predict --json`. SI attributes; to_dict() has the CLI's JSON keys
// (interface units), generated from the library's output table (prediction_columns()).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <string>

#include "bindings.hpp"
#include "frictal/io.hpp"
#include "frictal/predict.hpp"
#include "frictal/units.hpp"
#include "frictal/warnings.hpp"

namespace py = pybind11;
using namespace frictal;
using frictal::py_detail::arr;
using frictal::py_detail::crop_window;
using frictal::py_detail::nogil;
using frictal::py_detail::ok;
using frictal::py_detail::to_surface;

void frictal::py_detail::set_units(ReadOptions& o, const std::string& unit, const std::string& x_unit,
                                   const std::string& z_unit) {
  for (const auto& [key, u] : {std::pair{"unit", &unit}, {"x_unit", &x_unit}, {"z_unit", &z_unit}})
    if (!u->empty() && !units::length_scale(*u))
      throw py::value_error(std::string(key) + "='" + *u + "': not a length unit (expected m, mm, um, nm)");
  o.default_unit = unit;
  o.x_unit = x_unit.empty() ? unit : x_unit;
  o.z_unit = z_unit.empty() ? unit : z_unit;
}

namespace {
/// A surface dict's "warnings" (as read_surface returns them: [{code, message}]), kept with their
/// codes. Errors (ValueError naming `what`): an entry that is not such a dict.
std::vector<Warning> dict_warnings(const py::dict& d, const std::string& what) {
  std::vector<Warning> out;
  if (!d.contains("warnings")) return out;
  for (auto w : d["warnings"]) {
    if (!py::isinstance<py::dict>(w) || !w.contains("code") || !w.contains("message"))
      throw py::value_error(what +
                            ": each of a dict's 'warnings' must be a dict with 'code' and 'message' (as "
                            "read_surface returns them), not " +
                            py::repr(w).cast<std::string>());
    out.push_back({py::str(w["code"]), py::str(w["message"])});
  }
  return out;
}
}  // namespace

PredictSurface frictal::py_detail::to_surface(const py::handle& obj, double spacing, const std::string& format,
                                              const std::string& unit, const std::string& what,
                                              const std::string& x_unit, const std::string& z_unit) {
  PredictSurface s;
  s.name = what;
  if (py::isinstance<py::str>(obj) || py::hasattr(obj, "__fspath__")) {
    const std::string path = py::str(py::module_::import("os").attr("fspath")(obj));
    py_detail::require_file(path);
    ReadOptions o;
    o.format = ok(parse_format(format));
    set_units(o, unit, x_unit, z_unit);
    o.spacing = spacing;
    SurfaceData d = ok(nogil([&] { return read_surface(path, o); }));
    s.name = path;
    s.is_map = d.is_map;
    s.reader_warnings = d.warnings;
    s.x_unit_scale = d.x_unit_scale;
    s.z_unit_scale = d.z_unit_scale;
    if (d.is_map)
      s.map = std::move(d.map);
    else
      s.profile = ok(as_profile(d.curve, path));
    return s;
  }
  if (py::isinstance<Profile>(obj)) {
    s.profile = obj.cast<Profile>();
    return s;
  }
  if (py::isinstance<py::dict>(obj)) {
    py::dict d = obj.cast<py::dict>();
    if (d.contains("heights")) {
      if (!d.contains("dx") || !d.contains("dy"))
        throw py::value_error(what + ": a map dict needs 'heights', 'dx', 'dy' (as read_map returns)");
      s.is_map = true;
      s.map = py_detail::to_map(d["heights"].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(),
                                d["dx"].cast<double>(), d["dy"].cast<double>(),
                                d.contains("x0") ? d["x0"].cast<double>() : 0.0,
                                d.contains("y0") ? d["y0"].cast<double>() : 0.0);
      s.reader_warnings = dict_warnings(d, what);
      return s;
    }
    if (d.contains("x") && d.contains("z")) {
      auto x = d["x"].cast<std::vector<double>>(), z = d["z"].cast<std::vector<double>>();
      s.profile = ok(as_profile(Curve{std::move(x), std::move(z)}, what));
      s.reader_warnings = dict_warnings(d, what);
      return s;
    }
    throw py::value_error(what + ": a dict needs 'heights', 'dx', 'dy' (a map) or 'x', 'z' (a profile)");
  }
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
  if (!a) throw py::type_error(what + ": expected a file path, a Profile, a dict or a numpy array of heights");
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw py::value_error(what + ": a numpy array of heights needs spacing= (the point spacing in m, > 0)");
  if (a.ndim() == 1) {
    std::vector<double> x(std::size_t(a.shape(0))), z(a.data(), a.data() + a.shape(0));
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = double(i) * spacing;
    s.profile = ok(as_profile(Curve{std::move(x), std::move(z)}, what));
    return s;
  }
  if (a.ndim() == 2) {
    s.is_map = true;
    s.map = py_detail::to_map(a, spacing, spacing);
    return s;
  }
  throw py::value_error(what + ": expected a 1-D (profile) or 2-D (map) array of heights");
}

frictal::py_detail::ProfilePair frictal::py_detail::conditioned_profiles(
    const py::object& lower, const py::object& upper, const std::optional<std::string>& detrend, const py::object& crop,
    bool remove_spikes, double spike_threshold, double spacing, const std::string& format, const std::string& unit) {
  ConditioningSettings c;
  c.crop = crop_window(crop);
  c.crop_source = "crop=" + py::repr(crop).cast<std::string>();
  c.remove_spikes = remove_spikes;
  c.spike_threshold = spike_threshold;
  if (detrend) c.detrend = ok(parse_detrend(*detrend));
  return conditioned_profiles(lower, upper, c, spacing, format, unit);
}

frictal::py_detail::ProfilePair frictal::py_detail::conditioned_profiles(const py::object& lower,
                                                                         const py::object& upper,
                                                                         const ConditioningSettings& settings,
                                                                         double spacing, const std::string& format,
                                                                         const std::string& unit) {
  ProfilePair out;
  std::vector<ConditioningRecord> records;
  auto side = [&](const py::object& obj, const char* what) {
    PredictSurface s = to_surface(obj, spacing, format, unit, what);
    if (s.is_map)
      throw py::value_error(s.name +
                            ": an areal map; this function needs line profiles (areal_signature, "
                            "areal_hold or predict take maps)");
    for (const Warning& w : s.reader_warnings) add_warning(out.warnings, w);
    const Conditioning own = settings.of_surface(s.profile.period.has_value());
    const double read_rms = rms_height_as_read(s.profile.z);
    ConditionedProfile r = ok(nogil([&] { return condition(std::move(s.profile), own, s.name); }));
    records.push_back(r.record);
    for (Warning& w : check_profile(r.profile, s.name, {}, read_rms)) add_warning(out.warnings, std::move(w));
    return std::make_pair(std::move(r.profile), s.name);
  };
  auto [lo, lo_name] = side(lower, "lower");
  out.lower = std::move(lo);
  out.has_upper = !upper.is_none();
  if (out.has_upper) {
    auto [up, up_name] = side(upper, "upper");
    out.upper = std::move(up);
    auto length = [](const Profile& p) { return p.x.back() - p.x.front(); };
    auto spacing_of = [&](const Profile& p) { return length(p) / double(p.x.size() - 1); };
    for (Warning& w : check_pair_scales(length(out.lower), spacing_of(out.lower), length(out.upper),
                                        spacing_of(out.upper), lo_name, up_name))
      add_warning(out.warnings, std::move(w));
  } else {
    out.upper = out.lower;
  }
  out.conditioning = conditioning_text(records);
  return out;
}

namespace {

// A value as to_dict() and the attributes hold it: lists as Python lists (as in the JSON), an
// int for a "count", else py_value's.
py::object to_py(const std::string& unit, const OutputValue& v) {
  if (auto* d = std::get_if<double>(&v)) return py_detail::py_value(unit, *d);
  if (auto* t = std::get_if<std::string>(&v)) return py::str(*t);
  if (auto* b = std::get_if<bool>(&v)) return py::bool_(*b);
  return py::cast(std::get<std::vector<double>>(v));
}

// A value as the CLI's JSON writes it: a number that is not finite is null (None), in lists too.
py::object json_safe(const py::object& v) {
  if (py::isinstance<py::float_>(v)) return std::isfinite(v.cast<double>()) ? v : py::none();
  if (py::isinstance<py::list>(v)) {
    py::list out;
    for (const py::handle& x : v) out.append(json_safe(py::reinterpret_borrow<py::object>(x)));
    return out;
  }
  return v;
}

/// The keywords of areal_hold() from the tables: predict()'s, less those it states otherwise or
/// that do not apply to maps (locked: lateral says it; block_length and period: profiles).
const std::vector<Field>& areal_hold_keywords() {
  static const std::vector<Field> f = [] {
    std::vector<Field> out;
    for (const Field& g : py_detail::predict_keywords())
      if (g.name != "locked" && g.name != "block_length" && g.name != "period") out.push_back(g);
    return out;
  }();
  return f;
}

}  // namespace

void frictal_bind_predict(py::module_& m) {
  py::class_<Warning>(m, "Warning", "A warning code and its message (frictal.warning_codes() lists the codes)")
      .def_readonly("code", &Warning::code)
      .def_readonly("message", &Warning::message)
      .def("__repr__", [](const Warning& w) { return "<Warning " + w.code + ": " + w.message + ">"; });
  m.def(
      "check_profile", [](const Profile& p, const std::string& name) { return check_profile(p, name); },
      py::arg("profile"), py::arg("name") = "profile",
      "Plausibility of a measured profile (m): a list of Warning (codes units-suspect, heights-tiny, "
      "heights-exceed-length, spikes, kurtosis, fill-value); empty when nothing is implausible");
  m.def(
      "check_map",
      [](py::array_t<double, py::array::c_style | py::array::forcecast> heights, double dx, double dy,
         const std::string& name) { return check_map(py_detail::to_map(heights, dx, dy), name); },
      py::arg("heights"), py::kw_only(), py::arg("dx"), py::arg("dy"), py::arg("name") = "map",
      "Plausibility of an areal map: heights (ny, nx) in m (NaN: not measured), dx, dy in m; a list of Warning");
  m.def(
      "check_dimension_fit",
      [](double dimension, double r_squared, const std::string& method) {
        return check_dimension_fit(dimension, r_squared, method);
      },
      py::arg("dimension"), py::arg("r_squared"), py::arg("method") = "fit",
      "A fractal dimension fit: dimension D and r_squared (unitless) from a fit dict; a list of Warning,\n"
      "dimension-out-of-range (D outside [1, 2]) and poor-fit (r^2 < 0.95)");
  m.def("check_friction_bound", &check_friction_bound, py::arg("friction_angle"), py::arg("where") = "bound",
        "A rigid upper bound theta_max + theta_a (rad): a list of Warning, bound-negative when it is below zero\n"
        "(mu < 0: every contact along the sliding direction descends); empty otherwise");
  m.def(
      "warning_codes",
      [] {
        py::dict d;
        for (const WarningCode& c : warning_codes()) d[py::str(c.code)] = c.meaning;
        return d;
      },
      "Every warning code the library issues and what it means (dict code -> meaning; text, unitless)");
  m.def(
      "prediction_columns",
      [] {
        py::list l;
        for (const Column<Prediction>& c : prediction_columns()) l.append(py::make_tuple(c.key, c.unit, c.help));
        return l;
      },
      "The prediction's output table: (key, interface unit, help) per quantity, as `frictal columns` prints it; "
      "interface units deg (the Prediction attributes are SI: rad), m, 1 (unitless)");
  py::class_<Prediction> prediction(
      m, "Prediction",
      "What a tilt test of two surfaces reads (frictal.predict). Attributes in SI (radians, metres), one per "
      "column of frictal.prediction_columns() (its Python key); to_dict() has the keys and units of `frictal "
      "predict --json`");
  // One attribute per output column, named by its Python key, in SI (frictal/outputs.hpp).
  for (const Column<Prediction>& c : prediction_columns()) {
    if (c.python.empty()) continue;
    prediction.def_property_readonly(
        c.python.c_str(), [c](const Prediction& p) { return to_py(c.unit, c.si(p)); },
        (c.help + " (" + python_unit(c.unit) + ")").c_str());
  }
  prediction.def_property_readonly("drop_offsets", [](const Prediction& p) { return p.drop_offsets; })
      .def_readonly("warnings", &Prediction::warnings)
      .def(
          "to_dict",
          [](const Prediction& p) {
            py::dict d;
            for (const Column<Prediction>& c : prediction_columns())
              d[py::str(c.key)] = json_safe(to_py(c.unit, interface_value(c, p)));
            RunRecord run;
            run.warnings = p.warnings;
            py_detail::put_columns(d, run_record_columns(), run);
            return d;
          },
          "The keys and interface units of `frictal predict --json`, and its values: None where the JSON has null "
          "(a number that is not finite), so that json.dumps(..., allow_nan=False) writes it")
      .def("to_json", [](const Prediction& p) { return prediction_json(p); })
      .def("__repr__", [](const Prediction& p) {
        return "<Prediction " + p.model + ": friction angle " + py_detail::num(p.friction_angle.q50 * 180 / M_PI) +
               " deg (5-95 %: " + py_detail::num(p.friction_angle.q05 * 180 / M_PI) + " - " +
               py_detail::num(p.friction_angle.q95 * 180 / M_PI) + "), upper bound " +
               py_detail::num(p.upper_bound_friction_angle * 180 / M_PI) + " deg, " +
               std::to_string(p.warnings.size()) + " warning(s)>";
      });
  m.def(
      "predict",
      [](const py::object& lower, const py::object& upper, py::kwargs kw) {
        // The keywords outside the tables: how the inputs are read, friction under load (lists
        // of forces, "rigid"), the one drop (a point) and the threads (a run option); the rest are
        // the fields of predict_settings() and conditioning_settings().
        auto take = [&kw](const char* key) {
          py::object v = py::none();
          if (kw.contains(key)) {
            v = kw[key];
            PyDict_DelItemString(kw.ptr(), key);
          }
          return v;
        };
        const py::object spacing = take("spacing"), format = take("format"), unit = take("unit"),
                         x_unit = take("x_unit"), z_unit = take("z_unit"), threads = take("threads"),
                         load = take("load"), modulus_obj = take("modulus"), poisson_obj = take("poisson"),
                         upper_modulus = take("upper_modulus"), upper_poisson_obj = take("upper_poisson"),
                         start = take("start_offset"), crop = take("crop");
        auto opt_double = [](const py::object& v) {
          return v.is_none() ? std::optional<double>() : std::optional<double>(v.cast<double>());
        };
        const std::optional<double> modulus = opt_double(modulus_obj), poisson = opt_double(poisson_obj),
                                    upper_poisson = opt_double(upper_poisson_obj);
        PredictOptions o;
        // Friction under load: load (N, or a list: the first the headline), the materials (Pa).
        if (!load.is_none()) {
          o.loads = py::isinstance<py::float_>(load) || py::isinstance<py::int_>(load)
                        ? std::vector<double>{load.cast<double>()}
                        : load.cast<std::vector<double>>();
          if (o.loads.empty()) throw py::value_error("load: expected a force in N > 0, or a list of them");
          if (!modulus || !poisson)
            throw py::value_error(
                "load: friction under load needs the material: modulus= (Young's modulus, Pa) and poisson= "
                "(Poisson's ratio)");
          o.lower_material = {*modulus, *poisson};
          if (py::isinstance<py::str>(upper_modulus)) {
            if (upper_modulus.cast<std::string>() != "rigid")
              throw py::value_error("upper_modulus: expected a modulus in Pa or 'rigid'");
            if (upper_poisson) throw py::value_error("upper_poisson: a rigid upper block has none");
            o.rigid_upper = true;
          } else if (!upper_modulus.is_none() || upper_poisson) {
            o.upper_material = ElasticMaterial{upper_modulus.is_none() ? *modulus : upper_modulus.cast<double>(),
                                               upper_poisson.value_or(*poisson)};
          }
        } else if (modulus || poisson || !upper_modulus.is_none() || upper_poisson) {
          throw py::value_error(
              "modulus/poisson/upper_modulus/upper_poisson: the materials of friction under load; give load= (N)");
        }
        // crop: the table's text "x0,x1[,y0,y1]" or, in Python also, a sequence of metres.
        o.crop = py_detail::crop_window(crop);
        o.crop_source = "crop=" + py::repr(crop).cast<std::string>();
        if (!start.is_none()) {
          std::vector<double> xy;
          if (py::isinstance<py::float_>(start) || py::isinstance<py::int_>(start))
            xy = {start.cast<double>()};
          else
            xy = start.cast<std::vector<double>>();
          if (xy.empty() || xy.size() > 2)
            throw py::value_error("start_offset: expected x (profiles) or (x, y) (maps) in m");
          o.start_offset = {xy[0], xy.size() > 1 ? xy[1] : 0.0};
        }
        o = ok(make_predict_options(py_detail::keyword_values(py_detail::predict_keywords(), kw, "predict"), o));
        o.threads = threads.is_none() ? 0u : threads.cast<unsigned>();
        const double dx = spacing.is_none() ? 0.0 : spacing.cast<double>();
        auto text = [](const py::object& v, const char* fallback) {
          return v.is_none() ? std::string(fallback) : v.cast<std::string>();
        };
        // The surfaces handed over (a profile's points moved, not copied).
        PredictSurface lo =
            to_surface(lower, dx, text(format, "auto"), text(unit, ""), "lower", text(x_unit, ""), text(z_unit, ""));
        std::optional<PredictSurface> up;
        if (!upper.is_none())
          up = to_surface(upper, dx, text(format, "auto"), text(unit, ""), "upper", text(x_unit, ""), text(z_unit, ""));
        return ok(nogil([&] { return predict(std::move(lo), std::move(up), o); }));
      },
      py::arg("lower"), py::arg("upper") = py::none(),
      ("The prediction (the library's frictal::predict; no warnings.warn: frictal.predict issues them). Keywords: "
       "the fields of predict_settings() and conditioning_settings() (SI; crop also a sequence of metres), and "
       "spacing, format, unit, x_unit, z_unit, start_offset, threads, load, modulus, poisson, upper_modulus, "
       "upper_poisson:\n" +
       py_detail::keyword_doc(py_detail::predict_keywords()))
          .c_str());
  m.def(
      "predict_settings", [] { return py_detail::field_list(predict_settings()); },
      "predict_settings() -> list\n\nThe prediction's settings table: one dict per keyword of predict() (name, type, "
      "unit (SI), default (None: automatic, see help), min, max, choices, help); `frictal settings --json` lists the "
      "same fields (its key predict)");
  m.def(
      "conditioning_settings", [] { return py_detail::field_list(conditioning_settings()); },
      "conditioning_settings() -> list\n\nThe conditioning's settings table: crop, remove_spikes, spike_threshold, "
      "detrend, the keywords of predict() that condition a measured surface, as predict_settings() lists its own "
      "(name, type, unit (SI: m, or unitless), default (None: automatic), min, max, choices, help)");
  m.def(
      "areal_hold",
      [](py::array_t<double, py::array::c_style | py::array::forcecast> lower, double dx, double dy, py::object upper,
         const std::string& lateral, py::object start_offset, unsigned threads, py::kwargs kw) {
        if (lateral != "free" && lateral != "locked")
          throw py::value_error("lateral '" + lateral + "': expected 'free' or 'locked'");
        PredictSurface lo, up;
        lo.is_map = up.is_map = true;
        lo.name = "lower";
        up.name = "upper";
        lo.map = py_detail::to_map(lower, dx, dy, 0, 0);
        const bool pair = !upper.is_none();
        if (pair)
          up.map = py_detail::to_map(upper.cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(), dx,
                                     dy, 0, 0);
        PredictOptions o;
        // crop: the table's text or, in Python also, a sequence of metres (as predict() takes it).
        if (kw.contains("crop")) {
          const py::object crop = kw["crop"];
          o.crop = py_detail::crop_window(crop);
          o.crop_source = "crop=" + py::repr(crop).cast<std::string>();
          PyDict_DelItemString(kw.ptr(), "crop");
        }
        o = ok(make_predict_options(
            py_detail::keyword_values(
                areal_hold_keywords(), kw, "areal_hold", {"dx", "dy", "upper", "lateral", "start_offset", "threads"},
                {std::make_pair("angle", "direction"), std::make_pair("turn_over_upper", "in_place (its inverse)")}),
            o));
        o.map_locked = lateral == "locked";
        o.threads = threads;
        if (!start_offset.is_none()) {
          const auto xy = start_offset.cast<std::array<double, 2>>();
          o.start_offset = {xy[0], xy[1]};
        }
        const Prediction p = ok(nogil([&] { return predict(lo, pair ? &up : nullptr, o); }));
        py::dict d = py_detail::to_dict(areal_hold_columns(), ArealHoldReport{p, o.map_locked, !o.turn_over_upper});
        RunRecord run;
        run.conditioning = p.conditioning;
        run.warnings = p.warnings;
        py_detail::put_columns(d, run_record_columns(), run);
        return d;
      },
      py::arg("lower"), py::kw_only(), py::arg("dx"), py::arg("dy"), py::arg("upper") = py::none(),
      py::arg("lateral") = "free", py::arg("start_offset") = py::none(), py::arg("threads") = 0u,
      ("Hold angle over drops of an areal block, from the continuous model of frictal.predict (the same library "
       "path and numbers; runs without the GIL; as `frictal areal --lateral`): the block free to move sideways "
       "(lateral='free', what a tilt test reads) or locked to the direction (lateral='locked', a diagnostic; the free "
       "one is computed beside it). Heights, dx, dy, runaway_distance (None: predict's default) and start_offset in m, "
       "direction in rad, atomic_friction mu_a unitless (atan(mu_a) is included in every hold angle); upper as "
       "measured "
       "(turned over) unless in_place=True; drops: N x N over predict's drop range; detrend: none, mean, "
       "plane, poly:N (None: plane, predict's default). start_offset (x, y) (from the centres aligned, or from the "
       "upper's place when in place) or None for the distribution. Returns model, lateral, direction, in_place, "
       "atomic_friction, runaway_distance, drops, drop_range (u0, u1, v0, v1), upper_bound_friction_angle, "
       "conditioning, warnings and, "
       "over drops: hold_angle_mean/std/q05/q50/q95/min/max (rad), drop_hold_angles (rad), drop_offsets (drops x 2, m) "
       "(locked: also hold_angle_free_q05/q50/q95); from one drop: start_offset, rest_offset, hold_angle, steering "
       "(the free block's run-away direction from d, rad) (locked: also hold_angle_free). Keywords besides dx, dy, "
       "upper, "
       "lateral, start_offset, threads: the fields of predict_settings() that apply to maps and "
       "conditioning_settings() (SI; crop also a sequence of metres):\n" +
       py_detail::keyword_doc(areal_hold_keywords()))
          .c_str());
}
