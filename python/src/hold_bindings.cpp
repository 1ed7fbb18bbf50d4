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

void frictal_bind_hold(py::module_& m) {
  m.def(
      "hold_angle",
      [](const py::object& lower, const py::object& upper, bool rotate_upper, double runaway_distance,
         double atomic_friction, std::optional<double> start_offset,
         std::optional<std::pair<double, double>> offset_range, double spheroradius, std::size_t offsets,
         unsigned threads, double spacing, const std::string& format, const std::string& unit, py::kwargs kw) {
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
        const ConditioningSettings c = py_detail::conditioning_keywords(
            kw, "hold_angle",
            {"rotate_upper", "runaway_distance", "atomic_friction", "start_offset", "offset_range", "spheroradius",
             "offsets", "threads", "spacing", "format", "unit"});
        py_detail::ProfilePair pair = py_detail::conditioned_profiles(lower, upper, c, spacing, format, unit);
        Profile up = std::move(pair.upper);
        if (!pair.has_upper || rotate_upper) up = rotate180(std::move(up));
        const double start = start_offset ? *start_offset : std::numeric_limits<double>::quiet_NaN();
        HoldAnalysis r = py_detail::ok(nogil([&] { return analyse_hold(pair.lower, up, o, h, start); }));
        py::dict d = py_detail::to_dict(hold_columns(), r);
        RunRecord run;
        run.conditioning = pair.conditioning;
        run.warnings = pair.warnings;
        py_detail::put_columns(d, run_record_columns(), run);
        return d;
      },
      py::arg("lower"), py::arg("upper") = py::none(), py::kw_only(), py::arg("rotate_upper") = true,
      py::arg("runaway_distance") = 0.0, py::arg("atomic_friction") = 0.0, py::arg("start_offset") = py::none(),
      py::arg("offset_range") = py::none(), py::arg("spheroradius") = 0.0, py::arg("offsets") = 0,
      py::arg("threads") = 0, py::arg("spacing") = 0.0, py::arg("format") = "auto", py::arg("unit") = "",
      ("Hold angle of a rigid upper block on `lower` (what a tilt test reads; runs without the GIL), the numbers of "
       "the hold_angle keys of `frictal signature --json` on the same input. `lower`, `upper`: file paths, Profile "
       "objects, "
       "profile dicts or 1-D arrays with spacing= (m), conditioned as in signature() (detrend None: a line, the mean "
       "of a periodic profile; 'none' keeps a generated surface exact). `upper` is a "
       "surface as measured (rotated by 180 degrees) unless rotate_upper=False; default: lower turned over. "
       "runaway_distance d (m; 0: one period, else a tenth of the offset range), atomic_friction mu_a, start_offset "
       "(m) for one drop, offset_range (min, max) of the drops (m; default one period or half the block), "
       "spheroradius (m) for the DEM's rounded blocks, offsets and threads as in signature(). Returns "
       "runaway_distance (m); offset, lift (m): the piecewise-linear lift h(s) the process runs on; forward and "
       "backward: the distribution over drops (hold_angle and inertial_hold_angle statistics mean, std, q05, q50, "
       "q95, min, max in rad; basins with rest_offset (m), weight (m), hold_angle, inertial_hold_angle (rad)); with "
       "start_offset, start and start_backward: rest_offset, hold_angle (rad), hold_offset (m), runaway_end (m, NaN "
       "if off the end), slips, ran_off_end, inertial_hold_angle (rad), inertial_offset (m); conditioning (text), "
       "warnings ([{code, message}]). The conditioning's keywords are the fields of conditioning_settings() (SI; "
       "crop also a sequence of metres):\n" +
       py_detail::keyword_doc(conditioning_settings()))
          .c_str());
}
