// frictal._core — the hold angle (frictal/hold.hpp): what a tilt test reads from where the block
// rests, its inertial bound and the distribution over drops. SI units (metres, radians).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <optional>

#include "bindings.hpp"
#include "frictal/geometry.hpp"
#include "frictal/hold.hpp"

namespace py = pybind11;
using namespace frictal;
using frictal::py_detail::arr;
using frictal::py_detail::nogil;

namespace {

py::dict stats_dict(const HoldStatistics& s) {
  py::dict d;
  d["mean"] = s.mean;
  d["std"] = s.std;
  d["q05"] = s.q05;
  d["q50"] = s.q50;
  d["q95"] = s.q95;
  d["min"] = s.min;
  d["max"] = s.max;
  return d;
}

py::dict distribution_dict(const HoldDistribution& h) {
  py::dict d;
  d["hold_angle"] = stats_dict(h.hold);
  d["inertial_hold_angle"] = stats_dict(h.inertial);
  py::dict b;
  b["rest_offset"] = arr(h.basins.rest);
  b["weight"] = arr(h.basins.weight);
  b["hold_angle"] = arr(h.basins.hold);
  b["inertial_hold_angle"] = arr(h.basins.inertial);
  d["basins"] = b;
  d["drop_range"] = py::make_tuple(h.drop_min, h.drop_max);
  return d;
}

py::dict angle_dict(const HoldAngle& a) {
  py::dict d;
  d["rest_offset"] = a.rest_offset;
  d["hold_angle"] = a.hold_angle;
  d["hold_offset"] = a.hold_offset;
  d["runaway_end"] = a.runaway_end;
  d["slips"] = a.slips;
  d["ran_off_end"] = a.ran_off_end;
  d["inertial_hold_angle"] = a.inertial_hold_angle;
  d["inertial_offset"] = a.inertial_offset;
  return d;
}

}  // namespace

void frictal_bind_hold(py::module_& m) {
  m.def(
      "hold_angle",
      [](const Profile& lower, std::optional<Profile> upper, bool rotate_upper, double runaway_distance,
         double atomic_friction, std::optional<double> start_offset,
         std::optional<std::pair<double, double>> offset_range, double spheroradius, std::size_t offsets,
         unsigned threads) {
        SignatureOptions o;
        o.spheroradius = spheroradius;
        o.offsets = offsets;
        o.threads = threads;
        if (offset_range) {
          o.offset_min = offset_range->first;
          o.offset_max = offset_range->second;
        }
        HoldOptions h;
        h.runaway_distance = runaway_distance;
        h.atomic_friction = atomic_friction;
        Profile up = upper ? *upper : lower;
        if (!upper || rotate_upper) up = rotate180(up);
        const double start = start_offset ? *start_offset : std::numeric_limits<double>::quiet_NaN();
        HoldAnalysis r = py_detail::ok(nogil([&] { return analyse_hold(lower, up, o, h, start); }));
        py::dict d;
        d["runaway_distance"] = r.runaway_distance;
        d["offset"] = arr(r.curve.offset);
        d["lift"] = arr(r.curve.lift);
        d["period"] = r.curve.period;
        d["events"] = r.events;
        d["exact"] = r.exact;
        d["forward"] = distribution_dict(r.distribution.forward);
        d["backward"] = distribution_dict(r.distribution.backward);
        if (r.has_start) {
          d["start"] = angle_dict(r.start.forward);
          d["start_backward"] = angle_dict(r.start.backward);
        }
        return d;
      },
      py::arg("lower"), py::arg("upper") = py::none(), py::kw_only(), py::arg("rotate_upper") = true,
      py::arg("runaway_distance") = 0.0, py::arg("atomic_friction") = 0.0, py::arg("start_offset") = py::none(),
      py::arg("offset_range") = py::none(), py::arg("spheroradius") = 0.0, py::arg("offsets") = 0,
      py::arg("threads") = 0,
      "Hold angle of a rigid upper block on `lower` (what a tilt test reads; runs without the GIL). `upper` is a "
      "surface as measured (rotated by 180 degrees) unless rotate_upper=False; default: lower turned over. "
      "runaway_distance d (m; 0: one period, else a tenth of the offset range), atomic_friction mu_a, start_offset "
      "(m) for one drop, offset_range (min, max) of the drops (m; default one period or half the block), "
      "spheroradius (m) for the DEM's rounded blocks, offsets and threads as in signature(). Returns "
      "runaway_distance (m); offset, lift (m): the piecewise-linear lift h(s) the process runs on; forward and "
      "backward: the distribution over drops (hold_angle and inertial_hold_angle statistics mean, std, q05, q50, "
      "q95, min, max in rad; basins with rest_offset (m), weight (m), hold_angle, inertial_hold_angle (rad)); with "
      "start_offset, start and start_backward: rest_offset, hold_angle (rad), hold_offset (m), runaway_end (m, NaN "
      "if off the end), slips, ran_off_end, inertial_hold_angle (rad), inertial_offset (m)");
}
