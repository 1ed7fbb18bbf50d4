// frictal._core — bindings of the tilting-block test (tilt.hpp) on the spheropolygon engine.
// Surfaces are given as measured: a Profile, or an (x, z) pair of arrays for a curve that may
// fold over (e.g. koch_curve(...)). SI units: m, rad, s, kg.
#include <optional>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "frictal/tilt.hpp"

namespace py = pybind11;
using namespace frictal;

namespace {

py::array_t<double> arr(const std::vector<double>& v) { return py::array_t<double>(v.size(), v.data()); }

Curve to_curve(const py::object& o, const char* name) {
  if (py::isinstance<Profile>(o)) return as_curve(o.cast<Profile>());
  if (py::isinstance<py::tuple>(o) || py::isinstance<py::list>(o)) {
    auto seq = o.cast<py::sequence>();
    if (seq.size() == 2) {
      auto x = seq[0].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
      auto z = seq[1].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
      if (x.ndim() == 1 && z.ndim() == 1)
        return Curve{std::vector<double>(x.data(), x.data() + x.size()), std::vector<double>(z.data(), z.data() + z.size())};
    }
  }
  throw py::type_error(std::string(name) + ": expected a frictal.Profile or an (x, z) pair of 1-D arrays");
}

}  // namespace

void frictal_bind_dem(py::module_& m) {
  m.def(
      "tilt",
      [](const py::object& lower, const py::object& upper, double atomic_friction, bool reverse, double tilt_rate,
         double time_step, double radius, double block_height, double density, double normal_stiffness,
         double tangential_stiffness, double normal_damping, double tangential_damping, double restitution,
         const std::string& face, double period, double series_interval, double max_tilt,
         std::optional<double> initial_offset) {
        TiltConfig c = default_tilt_config();
        c.contact.atomic_friction = atomic_friction;
        c.reverse = reverse;
        c.tilt_rate = tilt_rate;
        c.time_step = time_step;
        c.radius = radius;
        c.block_height = block_height;
        c.density = density;
        c.contact.normal_stiffness = normal_stiffness;
        c.contact.tangential_stiffness = tangential_stiffness;
        c.contact.normal_damping = normal_damping;
        c.contact.tangential_damping = tangential_damping;
        c.restitution = restitution;
        if (face != "curve" && face != "envelope")
          throw py::value_error("tilt: face must be 'curve' or 'envelope', got '" + face + "'");
        c.face = face == "envelope" ? TiltFace::Envelope : TiltFace::Curve;
        c.period = period;
        c.runaway_distance = period > 0 ? period : c.runaway_distance;
        c.series_interval = series_interval;
        c.max_tilt = max_tilt;
        if (initial_offset) c.initial_offset = *initial_offset;
        const Curve lo = to_curve(lower, "lower");
        const Curve up = upper.is_none() ? lo : to_curve(upper, "upper");
        TiltResult r;
        {
          py::gil_scoped_release release;
          auto res = run_tilt(lo, up, c);
          if (!res) {
            py::gil_scoped_acquire acquire;
            throw py::value_error(res.error().message);
          }
          r = std::move(res).value();
        }
        py::dict d;
        d["slid"] = r.slid;
        d["friction_angle"] = r.friction_angle;
        d["predicted_friction_angle"] = r.predicted_friction_angle;
        d["predicted_theta_max"] = r.predicted_theta_max;
        d["slide_time"] = r.slide_time;
        d["simulated_time"] = r.simulated_time;
        d["steps"] = r.steps;
        d["wall_time"] = r.wall_time;
        d["upper_mass"] = r.upper_mass;
        d["steps_beyond_limit"] = r.steps_beyond_limit;
        py::dict s;
        s["time"] = arr(r.series.time);
        s["tilt"] = arr(r.series.tilt);
        s["normal_force"] = arr(r.series.normal_force);
        s["tangential_force"] = arr(r.series.tangential_force);
        s["force_angle"] = arr(r.series.force_angle);
        s["displacement"] = arr(r.series.displacement);
        s["velocity"] = arr(r.series.velocity);
        s["contacts"] = py::array_t<int>(r.series.contacts.size(), r.series.contacts.data());
        d["series"] = s;
        return d;
      },
      py::arg("lower"), py::arg("upper") = py::none(), py::kw_only(), py::arg("atomic_friction") = 0.0,
      py::arg("reverse") = false, py::arg("tilt_rate") = 0.05, py::arg("time_step") = 1e-5, py::arg("radius") = 5e-5,
      py::arg("block_height") = 0.01, py::arg("density") = 50.0, py::arg("normal_stiffness") = 6e5,
      py::arg("tangential_stiffness") = 6e4, py::arg("normal_damping") = 929.5, py::arg("tangential_damping") = 4.0,
      py::arg("restitution") = 0.0, py::arg("face") = "curve", py::arg("period") = 0.01,
      py::arg("series_interval") = 1e-3, py::arg("max_tilt") = 1.553343, py::arg("initial_offset") = py::none(),
      "Tilting-block test (paper Sec. IV, Table I/II defaults). Surfaces as measured; upper defaults to "
      "lower. period: surfaces' period for the prediction and the run-away distance (m; <= 0: none); "
      "initial_offset: shift of the upper block (m; default: the deepest nesting from the signature). "
      "Returns friction_angle (rad), predicted_friction_angle, and the Fig. 7 series.");
}
