// frictal._core — thin pybind11 bindings. SI units (metres, radians) as in the C++ library;
// library errors become ValueError with the library's message. Generator keywords come from the
// library's surface specification tables (frictal/surface_spec.hpp); long computations run with
// the GIL released.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdio>

#include "bindings.hpp"
#include "frictal/areal_tilt.hpp"
#include "frictal/generators.hpp"
#include "frictal/geometry.hpp"
#include "frictal/io.hpp"
#include "frictal/scan_stats.hpp"
#include "frictal/signature.hpp"
#include "frictal/stats.hpp"
#include "frictal/surface_spec.hpp"
#include "frictal/version.hpp"
#include "frictal/warnings.hpp"

namespace py = pybind11;
using namespace frictal;
using frictal::py_detail::arr;
using frictal::py_detail::nogil;

void frictal_bind_io(py::module_& m);       // python/src/io_bindings.cpp
void frictal_bind_dem(py::module_& m);      // python/src/dem_bindings.cpp
void frictal_bind_study(py::module_& m);    // python/src/study_bindings.cpp
void frictal_bind_hold(py::module_& m);     // python/src/hold_bindings.cpp
void frictal_bind_predict(py::module_& m);  // python/src/predict_bindings.cpp
void frictal_bind_contact(py::module_& m);  // python/src/contact_bindings.cpp

namespace {

template <class T>
T unwrap(Result<T> r) {
  return py_detail::ok(std::move(r));
}

std::vector<double> vec(const py::array_t<double, py::array::c_style | py::array::forcecast>& a, const char* name) {
  if (a.ndim() != 1) throw py::value_error(std::string(name) + ": expected a 1-D array");
  return std::vector<double>(a.data(), a.data() + a.size());
}

SurfaceSpec spec_of(const std::string& generator, const py::kwargs& kw, const std::string& function) {
  const GeneratorInfo* g = find_generator(generator);
  if (!g) {
    std::string hint;
    if (std::string n = nearest_word(generator, generator_names()); !n.empty()) hint = " (did you mean '" + n + "'?)";
    throw py::value_error(function + ": unknown surface generator '" + generator + "'" + hint +
                          "; expected koch, wm, sawtooth, sine, self-affine or fourier");
  }
  return unwrap(make_surface_spec(generator, py_detail::keyword_values(g->fields, kw, function)));
}

Profile profile_of(const SurfaceSpec& spec) {
  return unwrap(nogil([&] { return generate_profile(spec); }));
}

py::tuple curve_of(const SurfaceSpec& spec) {
  Curve c = unwrap(nogil([&] { return generate_curve(spec); }));
  return py::make_tuple(arr(c.x), arr(c.z));
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "frictal: static friction between rigid rough surfaces (C++ core). SI units: m, rad.";
  m.attr("__version__") = frictal::version();
  m.def(
      "build_info", [] { return py_detail::to_dict(build_info_columns(), frictal::build_info()); },
      "Version, git commit and CMake build type of the compiled core.\n\n"
      "Returns a dict (unitless): version (from CMakeLists.txt), git_commit, build_type (str), mujoco (bool: the 3D "
      "tilt test "
      "areal_tilt is available).");

  py::class_<Profile>(m, "Profile", "Single-valued piecewise-linear profile z(x) in metres")
      .def(py::init([](py::array_t<double, py::array::c_style | py::array::forcecast> x,
                       py::array_t<double, py::array::c_style | py::array::forcecast> z, std::optional<double> period) {
             Profile p{vec(x, "x"), vec(z, "z"), period};
             auto st = validate(p, "profile");
             if (!st) throw py::value_error(st.error().message);
             return p;
           }),
           py::arg("x"), py::arg("z"), py::arg("period") = py::none())
      .def_property_readonly(
          "x", [](const Profile& p) { return arr(p.x); }, "abscissae (m)")
      .def_property_readonly(
          "z", [](const Profile& p) { return arr(p.z); }, "heights (m)")
      .def_readwrite("period", &Profile::period, "period (m) or None")
      .def("__len__", &Profile::size)
      .def("__repr__", [](const Profile& p) {
        return "<frictal.Profile " + std::to_string(p.size()) + " points over " + std::to_string(p.length()) + " m>";
      });

  // Generators: one function per generator, keywords from its table (surface_spec.hpp).
  for (const GeneratorInfo& g : surface_generators()) {
    std::string fn = g.name;
    for (char& c : fn)
      if (c == '-') c = '_';
    fn += "_profile";
    const std::string name = g.name;
    const std::string doc = fn + "(**params) -> Profile\n\n" + g.description +
                            (name == "koch" ? ": the upper envelope of the curve" : "") +
                            ", generated with the keywords below (SI units; unknown keywords are a TypeError, "
                            "bad values a ValueError):\n" +
                            py_detail::keyword_doc(g.fields);
    m.def(
        fn.c_str(), [name, fn](const py::kwargs& kw) { return profile_of(spec_of(name, kw, fn)); }, doc.c_str());
  }
  m.def(
      "koch_curve", [](const py::kwargs& kw) { return curve_of(spec_of("koch", kw, "koch_curve")); },
      ("koch_curve(**params) -> (x, z)\n\nThe Koch curve K_n, which may fold over, as two arrays of metres. "
       "Keywords as koch_profile (SI units):\n" +
       py_detail::keyword_doc(find_generator("koch")->fields))
          .c_str());
  m.def(
      "surface",
      [](const std::string& generator, const py::kwargs& kw) { return profile_of(spec_of(generator, kw, "surface")); },
      py::arg("generator"),
      "surface(generator, **params) -> Profile\n\nA generated profile: generator is 'koch', 'wm', 'sawtooth', "
      "'sine', 'self-affine' or 'fourier'; params are that generator's keywords (see generators() and each "
      "<name>_profile function; SI units: metres, radians). Koch: the upper envelope.");
  m.def(
      "surface_curve",
      [](const std::string& generator, const py::kwargs& kw) {
        return curve_of(spec_of(generator, kw, "surface_curve"));
      },
      py::arg("generator"),
      "surface_curve(generator, **params) -> (x, z)\n\nThe generated surface as a curve (Koch: the full, possibly "
      "folded curve), two arrays of metres. params: the generator's keywords in SI units (m, rad).");
  m.def(
      "generators",
      [] {
        py::dict d;
        for (const GeneratorInfo& g : surface_generators()) d[py::str(g.name)] = py_detail::field_list(g.fields);
        return d;
      },
      "generators() -> dict\n\nEvery surface generator's parameter table: name -> list of fields (name, option, type "
      "(number, integer, boolean or word), unit "
      "(SI), default, min, max, choices, help). The same names are the CLI options (--kebab-case, degrees) and study "
      "TOML keys.");

  m.def(
      "upper_envelope",
      [](py::array_t<double, py::array::c_style | py::array::forcecast> x,
         py::array_t<double, py::array::c_style | py::array::forcecast> z) {
        return unwrap(upper_envelope(Curve{vec(x, "x"), vec(z, "z")}));
      },
      py::arg("x"), py::arg("z"), "Exact upper envelope of a polyline curve (x, z in metres) as a Profile");
  m.def(
      "lower_envelope",
      [](py::array_t<double, py::array::c_style | py::array::forcecast> x,
         py::array_t<double, py::array::c_style | py::array::forcecast> z) {
        return unwrap(lower_envelope(Curve{vec(x, "x"), vec(z, "z")}));
      },
      py::arg("x"), py::arg("z"), "Exact lower envelope of a polyline curve (x, z in metres) as a Profile");
  m.def(
      "rotate180", [](const Profile& p) { return rotate180(p); }, py::arg("profile"),
      "The profile (m) turned over by 180 degrees (x -> -x, z -> -z, re-sorted): how an upper block's face, "
      "measured with its material below, faces the lower one");

  m.def(
      "profile_stats",
      [](const Profile& p, double tip_radius) {
        const ProfileStats s = profile_stats(p);
        py::dict d = py_detail::to_dict(profile_stats_columns(), s);
        // Scan quantities (scan_stats.hpp): n dx length, sampling interval, bandwidth.
        py_detail::put_columns(d, profile_scan_stats_columns(), profile_scan_stats(p));
        StatsExtras extras;
        extras.tip_radius = tip_radius;
        if (tip_radius > 0) extras.short_reliability_cutoff = py_detail::ok(short_reliability_cutoff(p, tip_radius));
        extras.slope_distribution = slope_distribution(p);
        py_detail::put_columns(d, stats_extras_columns(), extras);
        return d;
      },
      py::arg("profile"), py::kw_only(), py::arg("tip_radius") = 0.0,
      "Statistics of a profile: points, length ((n-1) dx, m), mean_height and rms_height (m), rms_slope "
      "(unitless), max_slope and mean_slope (rad), slope_distribution_rad (the slope PDF: edges in rad, density per "
      "rad), and the scan quantities sampling_interval, physical_length (n dx), bandwidth (shortest, longest), "
      "nyquist_wavelength (m); tip_radius (m) > 0 adds short_reliability_cutoff (m)");

  m.def(
      "signature",
      [](const py::object& lower, const py::object& upper, bool rotate_upper, unsigned threads, bool keep_contacts,
         double spacing, const std::string& format, const std::string& unit, py::kwargs kw) {
        // The signature's keywords (signature_settings(); offset_range also a pair of metres), then
        // the conditioning's from what is left.
        py::kwargs own;
        for (const Field& f : signature_settings())
          if (kw.contains(f.name.c_str())) {
            py::object v = kw[f.name.c_str()];
            if (f.name == "offset_range" && !v.is_none() && !py::isinstance<py::str>(v)) {
              // (min, max) in metres as the table's text, every bit kept (%.17g reads back exactly).
              std::vector<double> r;
              try {
                r = v.cast<std::vector<double>>();
              } catch (const py::cast_error&) {
              }
              if (r.size() != 2)
                throw py::type_error("signature(): offset_range: expected (min, max) in m or the text 'MIN MAX'");
              char text[64];
              std::snprintf(text, sizeof text, "%.17g %.17g", r[0], r[1]);
              v = py::str(text);
            }
            own[f.name.c_str()] = v;
            PyDict_DelItemString(kw.ptr(), f.name.c_str());
          }
        const std::vector<std::string> also = {"rotate_upper", "threads", "keep_contacts", "spacing", "format", "unit"};
        SignatureOptions o = py_detail::ok(
            make_signature_options(py_detail::keyword_values(signature_settings(), own, "signature", also)));
        o.threads = threads;
        o.keep_contacts = keep_contacts;
        std::vector<std::string> names = also;
        for (const Field& f : signature_settings()) names.push_back(f.name);
        const ConditioningSettings c = py_detail::conditioning_keywords(kw, "signature", names);
        py_detail::ProfilePair pair = py_detail::conditioned_profiles(lower, upper, c, spacing, format, unit);
        Profile up = std::move(pair.upper);
        if (!pair.has_upper || rotate_upper) up = rotate180(std::move(up));
        SignatureResult r = unwrap(nogil([&] { return signature(std::move(pair.lower), std::move(up), o); }));
        py::dict d = py_detail::to_dict(signature_columns(), r);
        // The rigid bounds' warnings in the CLI's words (no atomic friction here: the bound is theta_max).
        const FrictionPrediction fwd = unwrap(predict_friction(0, r.theta_max_forward, r.contact_slope_std));
        const FrictionPrediction bwd = unwrap(predict_friction(0, r.theta_max_backward, r.contact_slope_std));
        for (Warning& w : check_signature_bounds(fwd, bwd)) add_warning(pair.warnings, std::move(w));
        RunRecord run;
        run.conditioning = pair.conditioning;
        run.warnings = pair.warnings;
        py_detail::put_columns(d, run_record_columns(), run);
        return d;
      },
      py::arg("lower"), py::arg("upper") = py::none(), py::kw_only(), py::arg("rotate_upper") = true,
      py::arg("threads") = 0, py::arg("keep_contacts") = false, py::arg("spacing") = 0.0, py::arg("format") = "auto",
      py::arg("unit") = "",
      ("Signature function theta(x_ofs) of two profiles (runs without the GIL), the numbers of `frictal signature "
       "--json` on the same input. `lower`, `upper`: file paths, Profile objects, profile dicts (x, z) or 1-D numpy "
       "arrays of heights with spacing= (m), each conditioned as frictal.predict and the CLI condition them: crop, "
       "remove_spikes, spike_threshold, then the form `detrend` names (none, mean, line, poly:N; None: a line, the "
       "mean of a periodic profile; detrend='none' keeps a generated surface exact); format and unit as read_surface. "
       "`upper` is a surface as measured "
       "(rotated by 180 degrees to face `lower`) unless rotate_upper=False; default: lower turned over. threads: 0 = "
       "all cores; keep_contacts: keep every contact (the dict's contacts). Returns "
       "offset, lift (m), theta, theta_min, theta_left, theta_right (rad), theta_max_forward/backward (rad), "
       "offset_at_forward/backward (m), contact_slope_mean/std (rad), contact_slope_pdf, exact, events, spheroradius "
       "(m), conditioning (text), warnings ([{code, message}]). The signature's keywords are the fields of "
       "signature_settings() (SI; offset_range also a pair (min, max) of metres):\n" +
       py_detail::keyword_doc(signature_settings()) +
       "\nThe conditioning's keywords are the fields of conditioning_settings() (SI; crop also a sequence of "
       "metres):\n" +
       py_detail::keyword_doc(conditioning_settings()))
          .c_str());
  m.def(
      "signature_settings", [] { return py_detail::field_list(signature_settings()); },
      "signature_settings() -> list\n\nThe signature's settings table: one dict per keyword of signature() that the "
      "table holds (name, type, unit (SI), default (None: automatic, see help), min, max, choices, help); `frictal "
      "settings --json` lists the same fields (its key signature)");
  m.def("lift_direct", &lift_direct, py::arg("lower"), py::arg("upper_rotated"), py::arg("offset"),
        "Lift h(s) (m) of the turned-over upper profile at offset s (m): plain O(N+M) evaluation (reference method)");
  m.def(
      "predict_friction",
      [](double mu_a, double theta_max, double sigma) {
        FrictionPrediction f = unwrap(predict_friction(mu_a, theta_max, sigma));
        // The rigid upper bound and Eq. 18's low end, named as `frictal signature --json` names them:
        // friction_angle belongs to frictal.predict (what a tilt test reads).
        py::dict d = py_detail::to_dict(friction_columns(), f);
        RunRecord run;
        run.warnings = check_friction_prediction(f, "predict_friction");
        py_detail::put_columns(d, run_record_columns(), run);
        return d;
      },
      py::arg("atomic_friction"), py::arg("theta_max"), py::arg("sigma") = 0.0,
      "The rigid upper bound of Eq. 6 and the Eq. 18 range from atomic_friction mu_a (unitless), theta_max and sigma "
      "(rad): upper_bound_friction_angle (theta_max + atan mu_a, rad), upper_bound_friction_coefficient, "
      "eq18_low_friction_angle (rad; clamped at 0, eq18_low_clamped then true), eq18_low_friction_coefficient. What a "
      "tilt test reads is frictal.predict");
  m.def(
      "read_profile",
      [](const std::string& path) {
        py_detail::require_file(path);
        return unwrap(nogil([&] { return read_profile(path); }));
      },
      py::arg("path"), "Reads a single-valued profile (any readable format) in metres (runs without the GIL)");
  m.def(
      "write_profile_csv",
      [](const std::string& path, const Profile& p) {
        auto st = write_profile_csv(path, p);
        if (!st) throw py::value_error(st.error().message);
      },
      py::arg("path"), py::arg("profile"),
      "Writes a profile as CSV with columns x_m,z_m (metres, 17 significant digits); errors name the path");
  frictal_bind_io(m);
  frictal_bind_dem(m);
  frictal_bind_study(m);
  frictal_bind_hold(m);
  frictal_bind_predict(m);
  frictal_bind_contact(m);
}
