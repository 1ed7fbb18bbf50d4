// frictal._core — bindings of the tilting-block test (tilt.hpp) on the spheropolygon engine.
// Surfaces are given as measured: a Profile, or an (x, z) pair of arrays for a curve that may
// fold over (e.g. koch_curve(...)). SI units: m, rad, s, kg. The keywords of tilt() are the
// library's tilt settings table (tilt_settings(), frictal/tilt.hpp): the same names as the
// `frictal tilt` options and the 'tilt' study kind's TOML keys.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>

#include <fmt/core.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "frictal/areal_tilt.hpp"
#include "frictal/predict.hpp"
#include "frictal/tilt.hpp"

namespace py = pybind11;
using namespace frictal;

namespace {

Curve to_curve(const py::object& o, const char* name) {
  if (py::isinstance<Profile>(o)) return as_curve(o.cast<Profile>());
  if (py::isinstance<py::tuple>(o) || py::isinstance<py::list>(o)) {
    auto seq = o.cast<py::sequence>();
    if (seq.size() == 2) {
      auto x = seq[0].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
      auto z = seq[1].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
      if (x.ndim() == 1 && z.ndim() == 1)
        return Curve{std::vector<double>(x.data(), x.data() + x.size()),
                     std::vector<double>(z.data(), z.data() + z.size())};
    }
  }
  throw py::type_error(std::string(name) + ": expected a frictal.Profile or an (x, z) pair of 1-D arrays");
}

/// What a generated surface given from Python is, in place of the CLI's generator parameters:
/// the period the run takes it to repeat with, its length and its point count (the generator
/// itself is not known to a Profile or a curve).
const std::vector<Field>& given_surface_fields() {
  static const std::vector<Field> fields = [] {
    Field period;
    period.name = "period";
    period.unit = "m";
    period.min = 0;
    period.min_open = true;
    period.help = "the period the run takes the surface to repeat with";
    Field length;
    length.name = "length";
    length.unit = "m";
    length.min = 0;
    length.help = "the lower surface's length (last x - first x)";
    Field points;
    points.name = "points";
    points.type = FieldType::Integer;
    points.min = 2;
    points.help = "the lower surface's points";
    return std::vector<Field>{period, length, points};
  }();
  return fields;
}

using MapArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// The 3D tilt test's inputs from Python: its settings (the keywords, checked by the table), the
/// lower map and the upper one (the lower by default), the turn-over and the start offset.
struct ArealTiltInputs {
  ArealTiltOptions o;
  Map lower, upper;
};
ArealTiltInputs areal_tilt_inputs(const MapArray& lower, double dx, double dy, const py::object& upper,
                                  bool turn_over_upper, const py::object& start_offset, const py::kwargs& kw,
                                  const char* name) {
  ArealTiltInputs in;
  in.o = py_detail::ok(make_areal_tilt_options(py_detail::keyword_values(areal_tilt_settings(), kw, name)));
  in.o.turn_over_upper = turn_over_upper;
  if (!start_offset.is_none()) in.o.start_offset = start_offset.cast<std::array<double, 2>>();
  in.lower = py_detail::to_map(lower, dx, dy);
  in.upper = upper.is_none() ? in.lower : py_detail::to_map(upper.cast<MapArray>(), dx, dy);
  return in;
}

}  // namespace

void frictal_bind_dem(py::module_& m) {
  m.def(
      "tilt",
      [](const py::object& lower, const py::object& upper, const py::kwargs& all) {
        // `threads` is not a setting (results do not depend on it): taken out before the table.
        py::kwargs kw;
        int threads = 1;
        std::optional<std::string> detrend;  // the form removed from a measured Profile
        double block_length = 0;             // the stated test's block (a measured Profile)
        for (const auto& item : all) {
          if (py::str(item.first).cast<std::string>() == "threads") {
            threads = item.second.cast<int>();
            if (threads < 0) throw py::value_error("tilt: threads: expected >= 0 (0 = all cores)");
          } else if (py::str(item.first).cast<std::string>() == "detrend") {
            if (!item.second.is_none()) detrend = item.second.cast<std::string>();
          } else if (py::str(item.first).cast<std::string>() == "block_length") {
            if (py::isinstance<py::str>(item.second)) {
              if (item.second.cast<std::string>() != "whole")
                throw py::value_error(fmt::format("tilt: block_length '{}': expected a length in m or 'whole'",
                                                  item.second.cast<std::string>()));
              block_length = -1;
            } else if (!item.second.is_none()) {
              block_length = item.second.cast<double>();
              if (!(block_length > 0) || !std::isfinite(block_length))
                throw py::value_error(
                    fmt::format("tilt: block_length {}: expected a length > 0 in m, or 'whole'", block_length));
            }
          } else {
            kw[item.first] = item.second;
          }
        }
        const ValueSet given = py_detail::keyword_values(tilt_settings(), kw, "tilt");
        // The surfaces as `frictal tilt` takes them: a Profile that repeats (a generator's) or an
        // (x, z) curve is a generated surface of its period (the curve's: period=, else 0.01 m),
        // which also sets the run-away distance unless that is given; a Profile that does not
        // repeat is measured: conditioned by the one rule of every front end (a line, unless
        // detrend= names another form; conditioning.hpp) and checked as the CLI checks files.
        const bool lower_profile = py::isinstance<Profile>(lower);
        const bool measured = lower_profile && !lower.cast<Profile>().period && !given.count("period");
        double period = 0;
        if (!measured)
          period = given.count("period") ? as_real(given.at("period"))
                   : lower_profile       ? lower.cast<Profile>().period.value_or(0.0)
                                         : default_tilt_config().period;
        Curve lo = to_curve(lower, "lower");
        Curve up = upper.is_none() ? lo : to_curve(upper, "upper");
        std::vector<Warning> data_warnings;
        std::string conditioning;
        if (measured) {
          if (!py::isinstance<Profile>(upper) && !upper.is_none())
            throw py::type_error("tilt: upper: a measured lower Profile takes a Profile as upper");
          py_detail::ProfilePair pair = py_detail::conditioned_profiles(lower, upper, detrend, py::none(), false,
                                                                        kDefaultSpikeThreshold, 0.0, "auto", "");
          lo = as_curve(pair.lower);
          up = as_curve(pair.upper);
          data_warnings = std::move(pair.warnings);
          conditioning = pair.conditioning;
        } else if (detrend) {
          throw py::value_error("tilt: detrend applies to a measured Profile (one that does not repeat)");
        }
        TiltScaling sc = py_detail::ok(tilt_setup(lo, up, given, period, period, block_length));
        for (const Warning& w : sc.test.warnings) add_warning(data_warnings, w);
        TiltConfig c = sc.config;
        c.threads = threads;
        TiltResult r = py_detail::ok(py_detail::nogil([&] { return run_tilt(lo, sc.upper, c); }));
        // The files' warnings, then the run's, as the CLI lists them; a measured pair's surface
        // object as the CLI's: its conditioning and the stated test.
        std::vector<Warning> warnings = std::move(data_warnings);
        warnings.insert(warnings.end(), r.warnings.begin(), r.warnings.end());
        TiltSurface surface;
        surface.conditioning = conditioning;
        surface.test = &sc.test;
        if (!measured) {
          // A generated surface: what was given (a repeating Profile or an (x, z) curve) and the
          // period, length and points the run took.
          surface.generator = lower_profile ? "a repeating Profile" : "an (x, z) curve";
          surface.parameters = &given_surface_fields();
          const auto [xmin, xmax] = std::minmax_element(lo.x.begin(), lo.x.end());
          const std::vector<Field>& f = given_surface_fields();  // period, length, points
          surface.values = {
              {f[0].name, c.period}, {f[1].name, *xmax - *xmin}, {f[2].name, static_cast<std::int64_t>(lo.x.size())}};
        }
        return py_detail::to_dict(tilt_columns(), TiltReport{r, c, &sc, &surface, &warnings});
      },
      py::arg("lower"), py::arg("upper") = py::none(),
      ("tilt(lower, upper=None, **settings) -> dict\n\nTilting-block test on the spheropolygon engine (paper Sec. "
       "IV, Table I/II defaults; runs without the GIL; the numbers of `frictal tilt`). lower, upper: a Profile or an "
       "(x, z) pair of arrays (m), as measured; upper defaults to lower. A Profile that does not repeat is a measured "
       "surface, as `frictal tilt --lower FILE` takes it: conditioned (detrend=: none, mean, line, poly:N; default "
       "a line), checked (warnings) and the defaults scaled to its length and point spacing (scaled_defaults: "
       "length, point_spacing, factors and the (name, from, to) of each setting changed, SI), and loaded as the CLI "
       "loads a measured pair: protocol quasi-static with hold_rotation, where not given (scaled_defaults' "
       "measured_defaults names them; protocol=\"constant-rate\", hold_rotation=False: the paper's), on the test "
       "that predict() states: the block the middle piece of upper, block_length long (default 20 run-away "
       "distances; a length in m, or \"whole\": all of upper over the first half of lower), d predict's (12.5 "
       "slope correlation lengths of lower) unless runaway_distance is given, dropped at the middle of predict's "
       "drop range unless initial_offset is given, and the model's spread over the same drops; a repeating "
       "Profile "
       "(a generator's) or an (x, z) curve is a generated surface of its period (period=, default 0.01 m for a "
       "curve), its defaults scaled as the CLI's generator subcommands scale them. Returns validity (\"valid\", or "
       "why the angle is not a friction angle of the surfaces and what would make it one), slid, friction_angle (NaN "
       "without a slide), "
       "predicted_friction_angle, "
       "predicted_theta_max (rad) (rigid profiles, Eq. 6), predicted_sphero_friction_angle, "
       "predicted_sphero_theta_max (rad) (the rounded blocks of spheroradius r), rest_offset (m, where the upper "
       "block rests when the loading starts, in the signature's offset convention), predicted_hold_angle, "
       "predicted_inertial_hold_angle, predicted_sphero_hold_angle (rad, hold angles from rest_offset with the run's "
       "runaway_distance; NaN if not computed), stiff_friction_angle (rad at 10 k_n with check_stiffness, else NaN), "
       "increments, unrelaxed_increments (protocol quasi-static), contact_rule (the rule used: pairs or closest), "
       "rotation_before_slide (rad), "
       "settled_speed (m/s, the upper block's speed when the tilt starts), "
       "settings (every setting the run used, SI: `frictal tilt --json`'s settings), surface (measured: "
       "conditioning and the stated test: block, block_length, runaway_distance, test_lengths, drop_range, drop; "
       "`frictal tilt --json`'s surface in SI; generated: generator (what was given: a repeating Profile or an "
       "(x, z) curve), period, length (m) and points of the lower surface), "
       "warnings (list of dicts code, message), scales (resting_overlap, spheroradius, shortest_edge, "
       "smallest_feature (lower, upper) in m, time_step, contact_period in s), estimate and stage_time (the cost "
       "estimated before the run and the wall time by stage, s: `frictal tilt --json`'s estimate and stage_time_s), "
       "slide_time, simulated_time, wall_time (s), steps, upper_mass (kg), "
       "steps_beyond_limit and the Fig. 7 series (time s, tilt rad, normal_force N, tangential_force N, force_angle "
       "rad, displacement m, velocity m/s, contacts). threads (default 1; 0 = all cores): the two predictions side by "
       "side and the contact passes split where it pays; results do not depend on it. Settings (SI units; `period` "
       "also sets the run-away distance unless runaway_distance is given):\n" +
       py_detail::keyword_doc(tilt_settings()))
          .c_str());
  m.def(
      "areal_tilt",
      [](py::array_t<double, py::array::c_style | py::array::forcecast> lower, double dx, double dy,
         const py::object& upper, bool turn_over_upper, const py::object& start_offset, const py::kwargs& kw) {
        const auto [o, f, g] = areal_tilt_inputs(lower, dx, dy, upper, turn_over_upper, start_offset, kw, "areal_tilt");
        // As `frictal areal-tilt`: the run and predict()'s map model from its rest (areal_tilt_matched),
        // written from the same table as its JSON (the keys without their unit suffix, in SI).
        const auto t0 = std::chrono::steady_clock::now();
        const ArealTiltMatched r = py_detail::ok(py_detail::nogil([&] { return areal_tilt_matched(f, g, o); }));
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        py::dict d = py_detail::to_dict(areal_tilt_report_columns(),
                                        ArealTiltReport{r, o.angle, o.tilt_step, o.exact_contacts, seconds});
        RunRecord run;
        run.warnings = r.run.warnings;
        py_detail::put_columns(d, run_record_columns(), run);
        return d;
      },
      py::arg("lower"), py::kw_only(), py::arg("dx"), py::arg("dy"), py::arg("upper") = py::none(),
      py::arg("turn_over_upper") = true, py::arg("start_offset") = py::none(),
      ("areal_tilt(lower, *, dx, dy, upper=None, turn_over_upper=True, start_offset=None, **settings) -> dict\n\n"
       "The 3D tilt test on MuJoCo (as `frictal areal-tilt`; docs/mujoco.md; needs a build with MuJoCo, else "
       "ValueError naming what it needs; runs without the GIL): lower, upper: 2-D arrays of heights (m, rows along "
       "y), spacings dx, dy (m); upper as measured (turned over) unless turn_over_upper=False; start_offset (x, y) in "
       "m. Returns the keys of `frictal areal-tilt --json` without their unit suffix, values in SI (rad, m, s; "
       "`frictal columns` table areal_tilt): friction_angle (rad), ran_away, rest_offset (x, y in m), steering "
       "(rad), predicted_hold_angle, predicted_hold_angle_locked and predicted_steering (rad: predict()'s map model "
       "from the simulated rest, block free, locked, and the free block's steering), the prediction in the "
       "simulated lateral mode (continuous_runaway_increment rad, continuous_rest_offset m, continuous_evaluations, "
       "continuous_hold_angle_range (rad, rad: the least and largest hold angle when one slip's end is moved by a "
       "sphere radius, areal_tilt_hold_spread), continuous_slips, continuous_ambiguous_slips, and "
       "continuous_increments, an array of rows (tilt rad, x m, y m)), seat_tilt (rad), seat_offset (m) and "
       "continuous_seated_hold_angle (rad: the model put down in the run's last seat at its tilt; absent without "
       "one), direction, tilt_step (rad), runaway_distance, sphere_radius (m), collision, lateral, spheres, steps, "
       "max_contacts, unsettled_increments, increment_trace (one tuple per increment: tilt rad, x m, y m, rested, "
       "steps, unbalanced force / weight, speed), seconds (wall time, s) and warnings (list of dicts code, "
       "message). "
       "Settings (SI units; the `frictal areal-tilt` options and the 'areal-tilt' study kind's keys):\n" +
       py_detail::keyword_doc(areal_tilt_settings()))
          .c_str());
  m.def(
      "areal_tilt_hold",
      [](py::array_t<double, py::array::c_style | py::array::forcecast> lower, double dx, double dy,
         const py::object& upper, bool turn_over_upper, const py::object& start_offset, double start_tilt, bool spread,
         const py::kwargs& kw) {
        const auto [o, f, g] =
            areal_tilt_inputs(lower, dx, dy, upper, turn_over_upper, start_offset, kw, "areal_tilt_hold");
        struct Out {
          ArealTiltHold hold;
          ArealTiltHoldSpread spread;
        };
        Out r = py_detail::ok(py_detail::nogil([&]() -> Result<Out> {
          Out out;
          auto hold = areal_tilt_hold(f, g, o, kArealHoldResolution, 1e-7, start_tilt);
          if (!hold) return hold.error();
          out.hold = *hold;
          if (spread) {
            auto sp = areal_tilt_hold_spread(f, g, o, out.hold);
            if (!sp) return sp.error();
            out.spread = *sp;
          }
          return out;
        }));
        return py_detail::to_dict(areal_tilt_hold_columns(), ArealTiltHoldReport{r.hold, spread ? &r.spread : nullptr});
      },
      py::arg("lower"), py::kw_only(), py::arg("dx"), py::arg("dy"), py::arg("upper") = py::none(),
      py::arg("turn_over_upper") = true, py::arg("start_offset") = py::none(), py::arg("start_tilt") = 0.0,
      py::arg("spread") = true,
      "areal_tilt_hold(lower, *, dx, dy, upper=None, turn_over_upper=True, start_offset=None, start_tilt=0, "
      "spread=True, **settings) -> dict\n\n"
      "The matched prediction of the 3D tilt test without MuJoCo (as `frictal areal-tilt --predict-only`; "
      "docs/mujoco.md): the rigid, frictionless quasi-static block of spheres on the triangulated lower face, "
      "offsets anywhere in the plane, dropped at start_offset (x, y in m; default 0, 0) and put down at start_tilt "
      "(rad), tilted in the settings' increments. lower, upper: 2-D arrays of heights (m, rows along y), spacings "
      "dx, dy (m); upper as measured (turned over) unless turn_over_upper=False. Returns hold_angle (rad, bisected "
      "to 1e-6), seat_bound (rad: the drop's rigid upper bound, >= hold_angle), runaway_increment (rad), ran_away, "
      "rest_offset (m), steering (rad), evaluations, the stops after "
      "each increment (stop_tilt rad, stop_x, stop_y m) and, with spread=True, hold_angle_range (rad, rad: one "
      "slip's end moved by a sphere radius, areal_tilt_hold_spread), slips and ambiguous_slips. atomic_friction "
      "must be 0. Settings: the areal_tilt() keywords (areal_tilt_settings()).");
  m.def(
      "areal_tilt_settings", [] { return py_detail::field_list(areal_tilt_settings()); },
      "areal_tilt_settings() -> list\n\nThe 3D tilt test's settings table: one dict per keyword of areal_tilt() "
      "(name, type, unit (SI), default, min, max, choices, help).");
  m.def(
      "read_tilt_frames",
      [](const std::string& path) {
        py_detail::require_file(path);
        return py_detail::to_dict(tilt_frames_columns(), py_detail::ok(read_tilt_frames(path)));
      },
      py::arg("path"),
      "read_tilt_frames(path) -> dict\n\nA frames file of the tilt test read back (`frictal tilt --frames FILE`; "
      "format in docs/dem.md): lower_polygon and upper_polygon (n x 2 arrays, "
      "m, core polygons relative to the centroids at the initial orientation), and per frame time (s), tilt (rad), "
      "position (frames x 2 x 2: the centroids of lower and upper, m) and angle (frames x 2, rad). A vertex's "
      "world position is position + R(angle) @ polygon. A missing file raises FileNotFoundError, a malformed one "
      "ValueError naming the line.");
  m.def(
      "tilt_settings", [] { return py_detail::field_list(tilt_settings()); },
      "tilt_settings() -> list\n\nThe tilt test's settings table: one dict per keyword of tilt() (name, type, unit "
      "(SI), default, min, max, choices, help). The same names are the `frictal tilt` options (--kebab-case, "
      "degrees) and the 'tilt' study kind's TOML keys.");
}
