// frictal._core — thin pybind11 bindings. SI units (metres, radians) as in the C++ library;
// library errors become ValueError with the library's message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>

#include "frictal/generators.hpp"
#include "frictal/geometry.hpp"
#include "frictal/io.hpp"
#include "frictal/signature.hpp"
#include "frictal/stats.hpp"

namespace py = pybind11;
using namespace frictal;

void frictal_bind_io(py::module_& m);   // python/src/io_bindings.cpp
void frictal_bind_dem(py::module_& m);  // python/src/dem_bindings.cpp
void frictal_bind_study(py::module_& m);  // python/src/study_bindings.cpp

namespace {

template <class T>
T unwrap(Result<T> r) {
  if (!r) throw py::value_error(r.error().message);
  return std::move(r).value();
}

py::array_t<double> arr(const std::vector<double>& v) { return py::array_t<double>(v.size(), v.data()); }

std::vector<double> vec(const py::array_t<double, py::array::c_style | py::array::forcecast>& a, const char* name) {
  if (a.ndim() != 1) throw py::value_error(std::string(name) + ": expected a 1-D array");
  return std::vector<double>(a.data(), a.data() + a.size());
}

py::dict hist_dict(const Histogram& h) {
  py::dict d;
  d["edges"] = arr(h.edges);
  d["density"] = arr(h.density);
  return d;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "frictal: static friction between rigid rough surfaces (C++ core). SI units: m, rad.";

  py::class_<Profile>(m, "Profile", "Single-valued piecewise-linear profile z(x) in metres")
      .def(py::init([](py::array_t<double, py::array::c_style | py::array::forcecast> x,
                       py::array_t<double, py::array::c_style | py::array::forcecast> z, std::optional<double> period) {
             Profile p{vec(x, "x"), vec(z, "z"), period};
             auto st = validate(p, "profile");
             if (!st) throw py::value_error(st.error().message);
             return p;
           }),
           py::arg("x"), py::arg("z"), py::arg("period") = py::none())
      .def_property_readonly("x", [](const Profile& p) { return arr(p.x); }, "abscissae (m)")
      .def_property_readonly("z", [](const Profile& p) { return arr(p.z); }, "heights (m)")
      .def_readwrite("period", &Profile::period, "period (m) or None")
      .def("__len__", &Profile::size)
      .def("__repr__", [](const Profile& p) {
        return "<frictal.Profile " + std::to_string(p.size()) + " points over " + std::to_string(p.length()) + " m>";
      });

  m.def("koch_curve",
        [](int iterations, double alpha, double wavelength, double length) {
          Curve c = unwrap(koch_curve(KochParams{iterations, alpha, wavelength, length}));
          return py::make_tuple(arr(c.x), arr(c.z));
        },
        py::arg("iterations") = 0, py::arg("alpha") = 5 * M_PI / 180, py::arg("wavelength") = 0.01,
        py::arg("length") = 0.2, "Koch curve K_n (may fold over) as (x, z) arrays; alpha in radians");
  m.def("koch_profile",
        [](int iterations, double alpha, double wavelength, double length) {
          return unwrap(koch_profile(KochParams{iterations, alpha, wavelength, length}));
        },
        py::arg("iterations") = 0, py::arg("alpha") = 5 * M_PI / 180, py::arg("wavelength") = 0.01,
        py::arg("length") = 0.2, "Upper envelope of the Koch curve, periodic");
  m.def("wm_profile",
        [](double dimension, double gamma, int n_max, double longest_wavelength, double length, double rms_height,
           bool stochastic, std::uint64_t seed, const std::string& exponent, double spacing) {
          if (exponent != "printed" && exponent != "common")
            throw py::value_error("wm_profile: exponent must be 'printed' or 'common', got '" + exponent + "'");
          WmParams w{dimension, gamma, n_max, longest_wavelength, length, rms_height, stochastic, seed,
                     exponent == "common" ? WmExponent::Common : WmExponent::Printed, spacing};
          return unwrap(wm_profile(w));
        },
        py::arg("dimension") = 1.5, py::arg("gamma") = 1.5, py::arg("n_max") = 10, py::arg("longest_wavelength") = 1e-6,
        py::arg("length") = 20e-6, py::arg("rms_height") = 1e-9, py::arg("stochastic") = true, py::arg("seed") = 1,
        py::arg("exponent") = "printed", py::arg("spacing") = 0.0, "Weierstrass-Mandelbrot profile (Eq. 14-17)");
  m.def("sawtooth_profile",
        [](double rise_angle, double rise_fraction, double wavelength, double length) {
          return unwrap(sawtooth_profile(SawtoothParams{rise_angle, rise_fraction, wavelength, length}));
        },
        py::arg("rise_angle") = 20 * M_PI / 180, py::arg("rise_fraction") = 0.5, py::arg("wavelength") = 0.01,
        py::arg("length") = 0.2);
  m.def("sine_profile",
        [](double amplitude, double wavelength, double length, int ppw) {
          return unwrap(sine_profile(SineParams{amplitude, wavelength, length, ppw}));
        },
        py::arg("amplitude") = 1e-3, py::arg("wavelength") = 0.01, py::arg("length") = 0.2,
        py::arg("points_per_wavelength") = 64);
  m.def("self_affine_profile",
        [](std::size_t points, double length, double hurst, double rms_height, std::uint64_t seed) {
          return unwrap(self_affine_profile(SelfAffineParams{points, length, hurst, rms_height, seed}));
        },
        py::arg("points") = 1024, py::arg("length") = 1e-3, py::arg("hurst") = 0.8, py::arg("rms_height") = 1e-6,
        py::arg("seed") = 1);

  m.def("upper_envelope",
        [](py::array_t<double, py::array::c_style | py::array::forcecast> x,
           py::array_t<double, py::array::c_style | py::array::forcecast> z) {
          return unwrap(upper_envelope(Curve{vec(x, "x"), vec(z, "z")}));
        },
        py::arg("x"), py::arg("z"), "Exact upper envelope of a polyline curve");
  m.def("lower_envelope",
        [](py::array_t<double, py::array::c_style | py::array::forcecast> x,
           py::array_t<double, py::array::c_style | py::array::forcecast> z) {
          return unwrap(lower_envelope(Curve{vec(x, "x"), vec(z, "z")}));
        },
        py::arg("x"), py::arg("z"));
  m.def("rotate180", [](const Profile& p) { return rotate180(p); }, py::arg("profile"));

  m.def("profile_stats",
        [](const Profile& p) {
          const ProfileStats s = profile_stats(p);
          py::dict d;
          d["points"] = s.points;
          d["length_m"] = s.length;
          d["mean_height_m"] = s.mean_height;
          d["rms_height_m"] = s.rms_height;
          d["rms_slope"] = s.rms_slope;
          d["max_slope_rad"] = s.max_slope;
          d["mean_slope_rad"] = s.mean_slope;
          d["slope_pdf"] = hist_dict(slope_distribution(p));
          return d;
        },
        py::arg("profile"));

  m.def("signature",
        [](const Profile& lower, std::optional<Profile> upper, bool rotate_upper, const std::string& slopes,
           std::size_t offsets, std::optional<std::pair<double, double>> offset_range, unsigned threads,
           bool keep_contacts, int bins) {
          SignatureOptions o;
          if (slopes != "exact" && slopes != "spline")
            throw py::value_error("signature: slopes must be 'exact' or 'spline', got '" + slopes + "'");
          o.slopes = slopes == "spline" ? SlopeMethod::Spline : SlopeMethod::Exact;
          o.offsets = offsets;
          o.threads = threads;
          o.keep_contacts = keep_contacts;
          o.bins = bins;
          if (offset_range) {
            o.offset_min = offset_range->first;
            o.offset_max = offset_range->second;
          }
          Profile up = upper ? *upper : lower;
          if (!upper || rotate_upper) up = rotate180(up);
          SignatureResult r;
          {
            py::gil_scoped_release release;
            auto res = signature(lower, up, o);
            if (!res) {
              py::gil_scoped_acquire acquire;
              throw py::value_error(res.error().message);
            }
            r = std::move(res).value();
          }
          py::dict d;
          d["offset"] = arr(r.offset);
          d["lift"] = arr(r.lift);
          d["theta"] = arr(r.theta);
          d["theta_min"] = arr(r.theta_min);
          d["theta_left"] = arr(r.theta_left);
          d["theta_right"] = arr(r.theta_right);
          d["theta_max_forward"] = r.theta_max_forward;
          d["theta_max_backward"] = r.theta_max_backward;
          d["offset_at_forward"] = r.offset_at_forward;
          d["offset_at_backward"] = r.offset_at_backward;
          d["contact_slope_mean"] = r.contact_slope_mean;
          d["contact_slope_std"] = r.contact_slope_std;
          d["contact_slope_pdf"] = hist_dict(r.contact_slope_pdf);
          d["slope_samples"] = arr(r.slope_samples);
          d["slope_weights"] = arr(r.slope_weights);
          d["exact"] = r.exact;
          d["events"] = r.events;
          if (keep_contacts) {
            std::vector<double> off, x, z, s;
            py::list types;
            for (std::size_t i = 0; i < r.offset.size(); ++i)
              for (auto k = r.contact_begin[i]; k < r.contact_begin[i + 1]; ++k) {
                off.push_back(r.offset[i]);
                x.push_back(r.contacts[k].x);
                z.push_back(r.contacts[k].z);
                s.push_back(r.contacts[k].slope);
                types.append(contact_type_name(r.contacts[k].type));
              }
            py::dict c;
            c["offset"] = arr(off);
            c["x"] = arr(x);
            c["z"] = arr(z);
            c["slope"] = arr(s);
            c["type"] = types;
            d["contacts"] = c;
          }
          return d;
        },
        py::arg("lower"), py::arg("upper") = py::none(), py::kw_only(), py::arg("rotate_upper") = true,
        py::arg("slopes") = "exact", py::arg("offsets") = 0, py::arg("offset_range") = py::none(),
        py::arg("threads") = 0, py::arg("keep_contacts") = false, py::arg("bins") = 90,
        "Signature function. `upper` is a surface as measured (rotated by 180 degrees to face `lower`) "
        "unless rotate_upper=False; default: lower turned over. Angles in radians.");
  m.def("lift_direct", &lift_direct, py::arg("lower"), py::arg("upper_rotated"), py::arg("offset"),
        "Plain O(N+M) evaluation of h(s) (reference method)");
  m.def("predict_friction",
        [](double mu_a, double theta_max, double sigma) {
          FrictionPrediction f = unwrap(predict_friction(mu_a, theta_max, sigma));
          py::dict d;
          d["atomic_friction"] = f.atomic_friction;
          d["atomic_angle"] = f.atomic_angle;
          d["theta_max"] = f.theta_max;
          d["friction_angle"] = f.friction_angle;
          d["friction_coefficient"] = f.friction_coefficient;
          d["friction_angle_low"] = f.friction_angle_low;
          d["friction_coefficient_low"] = f.friction_coefficient_low;
          return d;
        },
        py::arg("atomic_friction"), py::arg("theta_max"), py::arg("sigma") = 0.0, "Eq. 6 and Eq. 18 (radians)");
  m.def("read_profile", [](const std::string& path) { return unwrap(read_profile(path)); }, py::arg("path"));
  m.def("write_profile_csv",
        [](const std::string& path, const Profile& p) {
          auto st = write_profile_csv(path, p);
          if (!st) throw py::value_error(st.error().message);
        },
        py::arg("path"), py::arg("profile"));
  frictal_bind_io(m);
  frictal_bind_dem(m);
  frictal_bind_study(m);
}
