// frictal._core — bindings of the measured-surface modules: reading/writing (io.hpp), maps,
// analysis, fractal dimension and areal friction. Maps cross as 2-D numpy arrays of shape
// (ny, nx) (x fastest, NaN = invalid) plus spacings in metres. Readers and the long analyses
// run with the GIL released.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>

#include "bindings.hpp"
#include "frictal/analysis.hpp"
#include "frictal/areal.hpp"
#include "frictal/conditioning.hpp"
#include "frictal/fractal.hpp"
#include "frictal/io.hpp"
#include "frictal/scan_stats.hpp"

namespace py = pybind11;
using namespace frictal;

namespace frictal::py_detail {
Map to_map(const py::array_t<double, py::array::c_style | py::array::forcecast>& h, double dx, double dy, double x0,
           double y0) {
  if (h.ndim() != 2) throw py::value_error("heights: expected a 2-D array of shape (ny, nx)");
  Map m;
  m.ny = std::size_t(h.shape(0));
  m.nx = std::size_t(h.shape(1));
  m.dx = dx;
  m.dy = dy;
  m.x0 = x0;
  m.y0 = y0;
  m.heights.assign(h.data(), h.data() + h.size());
  ok(validate(m, "heights"));
  return m;
}

std::optional<CropWindow> crop_window(const py::object& crop) {
  if (crop.is_none()) return std::nullopt;
  if (py::isinstance<py::str>(crop)) return ok(parse_crop(crop.cast<std::string>(), "crop"));
  std::vector<double> v;
  try {
    v = crop.cast<std::vector<double>>();
  } catch (const py::cast_error&) {
    throw py::value_error("crop: expected (x0, x1) or (x0, x1, y0, y1) in m, or the text \"x0,x1[,y0,y1]\"");
  }
  if (v.size() != 2 && v.size() != 4)
    throw py::value_error("crop: " + std::to_string(v.size()) +
                          " number(s); expected (x0, x1) or (x0, x1, y0, y1) in m");
  CropWindow w;
  w.x_min = v[0], w.x_max = v[1];
  if (v.size() == 4) w.has_y = true, w.y_min = v[2], w.y_max = v[3];
  return w;
}
}  // namespace frictal::py_detail

namespace {

using frictal::py_detail::arr;
using frictal::py_detail::crop_window;
using frictal::py_detail::nogil;
using frictal::py_detail::ok;
using frictal::py_detail::require_file;
using frictal::py_detail::to_map;
using frictal::py_detail::to_surface;

ReadOptions read_options(const std::string& format, const std::string& unit, double spacing = 0,
                         const std::string& channel = "", const std::string& x_unit = "",
                         const std::string& z_unit = "") {
  ReadOptions o;
  o.format = ok(parse_format(format));
  py_detail::set_units(o, unit, x_unit, z_unit);
  o.spacing = spacing;
  o.channel = channel;
  return o;
}

py::dict record_dict(const ConditioningRecord& r) { return py_detail::to_dict(conditioning_record_columns(), r); }

py::dict fit_dict(const FractalFit& f) { return py_detail::to_dict(fractal_fit_columns(), f); }

}  // namespace

void frictal_bind_io(py::module_& m) {
  m.def(
      "read_surface",
      [](const std::string& path, const std::string& format, const std::string& unit, double spacing,
         const std::string& channel, const std::string& x_unit, const std::string& z_unit) {
        require_file(path);
        const ReadOptions o = read_options(format, unit, spacing, channel, x_unit, z_unit);
        SurfaceData s = ok(nogil([&] { return read_surface(path, o); }));
        // The map's heights as a (ny, nx) array, then the columns of what the file holds.
        py::dict d;
        if (s.is_map) py_detail::put_columns(d, map_data_columns(), s.map);
        RunRecord in;
        in.kind = s.is_map ? "map" : "profile";
        in.format = format_name(s.format);
        in.warnings = s.warnings;
        py_detail::put_columns(d, run_record_columns(), in);
        py_detail::put_columns(d, surface_data_columns(), s);
        return d;
      },
      py::arg("path"), py::kw_only(), py::arg("format") = "auto", py::arg("unit") = "", py::arg("spacing") = 0.0,
      py::arg("channel") = "", py::arg("x_unit") = "", py::arg("z_unit") = "",
      "Reads any supported file (CSV/TSV/text, .npy, gzip, Dektak, Gwyddion text, X3P, SDF, and every format "
      "Gwyddion's modules load when installed; runs without the GIL). format: auto or a name of `frictal formats`; "
      "unit: m, mm, um or nm for the file's lengths, x and z (overriding the units it names, with a warning; for "
      "columns that name none instead of metres); x_unit, z_unit: the same for the lateral lengths or the heights "
      "alone; spacing: point spacing (m) for a single column of heights; channel: index or name of a multi-channel "
      "file's channel. Returns a dict: kind 'profile' (x, z) or 'map' (heights (ny, nx), dx, dy, x0, y0), format, "
      "warnings, x_unit_scale and z_unit_scale (m per unit of the file's numbers as read). Metres.");
  m.def(
      "read_map",
      [](const std::string& path, const std::string& format) {
        const ReadOptions o = read_options(format, "");
        require_file(path);
        return py_detail::to_dict(map_data_columns(), ok(nogil([&] { return read_map(path, o); })));
      },
      py::arg("path"), py::kw_only(), py::arg("format") = "auto",
      "Reads an areal map (runs without the GIL): dict heights (ny, nx) in m, dx, dy, x0, y0 in m");
  m.def(
      "write_x3p",
      [](const std::string& path, py::array_t<double, py::array::c_style | py::array::forcecast> heights, double dx,
         double dy, double x0, double y0, const std::string& type, bool binary) {
        X3pWriteOptions o;
        if (type == "I")
          o.type = X3pDataType::I;
        else if (type == "L")
          o.type = X3pDataType::L;
        else if (type == "F")
          o.type = X3pDataType::F;
        else if (type == "D")
          o.type = X3pDataType::D;
        else
          throw py::value_error("type: expected I, L, F or D");
        o.binary = binary;
        ok(write_x3p(path, to_map(heights, dx, dy, x0, y0), o));
      },
      py::arg("path"), py::arg("heights"), py::kw_only(), py::arg("dx"), py::arg("dy"), py::arg("x0") = 0.0,
      py::arg("y0") = 0.0, py::arg("type") = "D", py::arg("binary") = true,
      "Writes a map of heights (ny, nx) in m on spacings dx, dy (m), origin x0, y0 (m) as ISO 25178-71 X3P; "
      "type: feature type D (areal) or S; binary: binary point data");
  m.def(
      "map_stats",
      [](py::array_t<double, py::array::c_style | py::array::forcecast> heights, double dx, double dy,
         double tip_radius) {
        const Map map = to_map(heights, dx, dy, 0, 0);
        MapStats s = map_stats(map);
        py::dict d = py_detail::to_dict(map_stats_columns(), s);
        // Scan quantities (scan_stats.hpp): n dx sizes, bandwidth, per-profile Rq/Rdq, fd gradient.
        py_detail::put_columns(d, map_scan_stats_columns(), map_scan_stats(map));
        StatsExtras extras;
        extras.is_map = true;
        extras.tip_radius = tip_radius;
        if (tip_radius > 0) extras.short_reliability_cutoff = ok(short_reliability_cutoff(map, tip_radius));
        py_detail::put_columns(d, stats_extras_columns(), extras);
        return d;
      },
      py::arg("heights"), py::kw_only(), py::arg("dx"), py::arg("dy"), py::arg("tip_radius") = 0.0,
      "Areal statistics over the valid points (NaN = invalid) of heights (m) on spacings dx, dy (m): mean, Sa, Sq, "
      "Sp, Sv, Sz (m), Ssk, Sku, Sdq (unitless), max_slope (rad), the scan quantities of `frictal stats` "
      "(physical sizes, bandwidth (m), per-direction Rq (m) and Rdq (unitless)); tip_radius (m) > 0 adds "
      "short_reliability_cutoff (m)");
  m.def(
      "detrend", [](const Profile& p, const std::string& kind) { return ok(detrend(p, ok(parse_detrend(kind)))); },
      py::arg("profile"), py::arg("kind") = "line",
      "Removes none, mean, line or poly:N (trapezoid-weighted least squares) from a profile (m)");
  m.def(
      "condition",
      [](const py::object& surface, py::kwargs kw) {
        // detrend None: the one default of every front end (default_form: a line, a plane for
        // maps, the mean of a periodic profile).
        const ConditioningSettings settings = py_detail::conditioning_keywords(kw, "condition");
        // A Profile, or a dict as read_surface/read_map return it (condition(read_surface(path)) is
        // the CLI's conditioning of that file): predict's reading of such objects.
        if (!py::isinstance<Profile>(surface) && !py::isinstance<py::dict>(surface))
          throw py::type_error(
              "surface: expected a Profile, a profile dict (x, z) or a map dict (heights, dx, dy[, x0, y0])");
        const PredictSurface s = to_surface(surface, 0, "auto", "", "surface");
        if (!s.is_map) {
          const Conditioning c = settings.of_surface(s.profile.period.has_value());
          ConditionedProfile r = ok(nogil([&] { return condition(s.profile, c, "profile"); }));
          return py::make_tuple(py::cast(std::move(r.profile)), record_dict(r.record));
        }
        const Conditioning c = settings.of_surface();
        ConditionedMap r = ok(nogil([&] { return condition(s.map, c, "map"); }));
        return py::make_tuple(py_detail::to_dict(map_data_columns(), r.map), record_dict(r.record));
      },
      py::arg("surface"),
      ("The conditioning of `frictal predict` and the CLI (crop, then spike removal, then form removal; "
       "surface: a Profile, a profile dict as read_surface returns it, or a map dict as read_map returns it; "
       "docs/analysis.md): crop (x0, x1) or (x0, x1, y0, y1) in m in the surface's coordinates; remove_spikes "
       "removes (profiles: linear interpolation between kept neighbours, dropped at the ends) or masks (maps: NaN) the "
       "points more than spike_threshold rms "
       "heights from the median of their neighbours; detrend none, mean, line, plane, poly:N (None: the default of "
       "every front end, a line for profiles, a "
       "plane for maps, the mean of a periodic profile). Returns (the "
       "conditioned Profile or map dict, a record dict: text, cropped, window (m), points_before/after (nx, ny), "
       "spikes_checked, spike_threshold, spikes_removed, spikes_dropped (profiles: at the ends), spike_passes, form). "
       "Keywords: the fields of conditioning_settings() (SI; crop also a sequence of metres):\n" +
       py_detail::keyword_doc(conditioning_settings()))
          .c_str());
  m.def(
      "power_spectrum",
      [](const Profile& p, std::size_t max_k) {
        Spectrum s = ok(nogil([&] { return power_spectrum(p, max_k); }));
        return py::make_tuple(arr(s.q), arr(s.psd));
      },
      py::arg("profile"), py::arg("max_k") = 0,
      "Power spectrum of a profile (m, runs without the GIL): returns (q in rad/m, C in m^3) of the piecewise-linear "
      "profile, with 2 sum C / L = rms^2; max_k: 0 = automatic");
  m.def(
      "autocorrelation",
      [](const Profile& p, std::size_t max_lag) {
        Autocorrelation a = ok(nogil([&] { return autocorrelation(p, max_lag); }));
        return py_detail::to_dict(autocorrelation_columns(), a);
      },
      py::arg("profile"), py::arg("max_lag") = 0,
      "Autocorrelation of a profile: lag (m), acf (unitless), correlation_length (m); max_lag: 0 = automatic");
  m.def(
      "koch_dimension", [](double alpha) { return ok(koch_dimension(alpha)); }, py::arg("alpha"),
      "Eq. 13: 2 (1/3)^D + 2 (1/(6 cos alpha))^D = 1, alpha in radians");
  m.def(
      "divider_dimension",
      [](py::array_t<double> x, py::array_t<double> z, double ruler_min, double ruler_max, int rulers) {
        Curve c{std::vector<double>(x.data(), x.data() + x.size()), std::vector<double>(z.data(), z.data() + z.size())};
        return fit_dict(ok(nogil([&] { return divider_dimension(c, {ruler_min, ruler_max, rulers}); })));
      },
      py::arg("x"), py::arg("z"), py::kw_only(), py::arg("ruler_min") = 0.0, py::arg("ruler_max") = 0.0,
      py::arg("rulers") = 16,
      "Divider (ruler) dimension walking along the curve (x, z in m); ruler_min/max in m (0: automatic). Returns "
      "dimension, slope, r_squared, fit_range (m), scales (m), values (m)");
  m.def(
      "box_dimension",
      [](py::array_t<double> x, py::array_t<double> z, double box_min, double box_max, int sizes) {
        Curve c{std::vector<double>(x.data(), x.data() + x.size()), std::vector<double>(z.data(), z.data() + z.size())};
        return fit_dict(ok(nogil([&] { return box_dimension(c, {box_min, box_max, sizes}); })));
      },
      py::arg("x"), py::arg("z"), py::kw_only(), py::arg("box_min") = 0.0, py::arg("box_max") = 0.0,
      py::arg("sizes") = 12, "Box-counting dimension of the curve (x, z in m); box_min/max in m (0: automatic)");
  m.def(
      "psd_dimension",
      [](const Profile& p, double q_min, double q_max) {
        PsdFitOptions o;
        o.q_min = q_min;
        o.q_max = q_max;
        return fit_dict(ok(nogil([&] { return psd_dimension(p, o); })));
      },
      py::arg("profile"), py::kw_only(), py::arg("q_min") = 0.0, py::arg("q_max") = 0.0,
      "Fractal dimension of a profile (m) from its power-spectrum slope (runs without the GIL); q_min, q_max in "
      "rad/m (0: automatic). Returns dimension, slope, r_squared, fit_range (rad/m), scales, values");
  m.def(
      "anisotropy",
      [](py::array_t<double, py::array::c_style | py::array::forcecast> heights, double dx, double dy, unsigned threads,
         py::kwargs kw) {
        const AnisotropySettings s = ok(make_anisotropy_settings(py_detail::keyword_values(
            anisotropy_settings(), kw, "anisotropy", {"dx", "dy", "threads"}, {std::make_pair("max_lines", "lines")})));
        if (kw.contains("contact_slope") && !s.areal)
          throw py::value_error(
              "anisotropy: contact_slope: the contact slope of the grid areal signature; it needs "
              "areal=True");
        const Map map = to_map(heights, dx, dy, 0, 0);
        AnisotropyTable table;
        table.atomic_friction = s.lines.atomic_friction;
        RunRecord run;
        run.warnings.emplace();  // each direction's bound, as `frictal anisotropy` names it
        auto add_row = [&](double angle, double fwd, double bwd, double sigma, const FrictionPrediction& p) {
          char where[64];
          std::snprintf(where, sizeof where, "direction %g deg", angle * 180 / std::numbers::pi);
          for (Warning& w : check_friction_prediction(p, where)) add_warning(*run.warnings, std::move(w));
          AnisotropyRow row;
          row.direction = angle;
          row.theta_forward = fwd;
          row.theta_backward = bwd;
          row.sigma = sigma;
          row.upper_bound_friction_angle = p.friction_angle;
          table.directions.push_back(row);
        };
        if (s.areal) {
          // The grid areal signature of the map against itself turned over, per direction, as
          // `frictal anisotropy --areal` runs it.
          ArealSignatureOptions o;
          o.threads = threads;
          o.contact_slope = s.contact_slope;
          for (int k = 0; k < s.directions; ++k) {
            const double angle = 2 * std::numbers::pi * k / s.directions;
            const ArealSignature r = ok(nogil([&] { return areal_signature(map, map, angle, o); }));
            add_row(angle, r.theta_max_forward, r.theta_max_backward, r.contact_slope_std,
                    ok(predict_friction(s.lines.atomic_friction, r.theta_max_forward, r.contact_slope_std)));
          }
        } else {
          DirectionalOptions o = s.lines;
          o.threads = threads;
          auto t = ok(nogil([&] { return anisotropy(map, s.directions, o); }));
          for (const auto& r : t) add_row(r.angle, r.theta_forward, r.theta_backward, r.sigma, r.prediction);
        }
        py::dict d = py_detail::to_dict(anisotropy_columns(), table);
        py_detail::put_columns(d, run_record_columns(), run);
        return d;
      },
      py::arg("heights"), py::kw_only(), py::arg("dx"), py::arg("dy"), py::arg("threads") = 0,
      ("Predicted friction over sliding directions of a map (runs without the GIL): per direction the rigid bound "
       "theta_max + atan(mu_a) from the map's parallel line profiles, or with areal=True from the grid areal "
       "signature of the map against itself turned over; heights (m), dx, dy (m). Returns direction, "
       "theta_forward/backward, sigma, upper_bound_friction_angle (theta_max + atan mu_a, rad), atomic_friction, "
       "warnings. What a tilt test reads along a direction: predict(..., direction=...). The keywords are the fields "
       "of anisotropy_settings() (SI):\n" +
       py_detail::keyword_doc(anisotropy_settings()))
          .c_str());
  m.def(
      "anisotropy_settings", [] { return py_detail::field_list(anisotropy_settings()); },
      "anisotropy_settings() -> list\n\nThe polar table's settings table: one dict per keyword of anisotropy() that "
      "the table holds (name, type, unit (SI), default, min, max, choices, help); `frictal settings --json` lists the "
      "same fields (its key anisotropy)");
  m.def(
      "areal_signature_settings", [] { return py_detail::field_list(areal_signature_settings()); },
      "areal_signature_settings() -> list\n\nThe areal signature's settings table: one dict per keyword of "
      "areal_signature() that the table holds (name, type, unit (SI), default (None: automatic, see help), min, max, "
      "choices, help); `frictal settings --json` lists the same fields (its key areal)");
  m.def(
      "areal_signature",
      [](py::array_t<double, py::array::c_style | py::array::forcecast> lower, double dx, double dy, py::object upper,
         bool prune, unsigned threads, py::kwargs kw) {
        const ArealSignatureSettings s = ok(make_areal_signature_settings(py_detail::keyword_values(
            areal_signature_settings(), kw, "areal_signature", {"dx", "dy", "upper", "prune", "threads"},
            {std::make_pair("angle", "direction"), std::make_pair("turn_over_upper", "in_place (its inverse)")})));
        Map f = to_map(lower, dx, dy, 0, 0);
        Map g = upper.is_none() ? f
                                : to_map(upper.cast<py::array_t<double, py::array::c_style | py::array::forcecast>>(),
                                         dx, dy, 0, 0);
        ArealSignatureOptions o = s.options;
        o.prune = prune;
        o.threads = threads;
        ArealSignature r = ok(nogil([&] { return areal_signature(f, g, s.direction, o); }));
        py::dict d = py_detail::to_dict(areal_signature_columns(), r);
        // The bound's warnings as `frictal areal` gives them.
        RunRecord run;
        run.warnings = check_friction_prediction(
            ok(predict_friction(s.atomic_friction, r.theta_max_forward, r.contact_slope_std)), "areal");
        py_detail::put_columns(d, run_record_columns(), run);
        return d;
      },
      py::arg("lower"), py::kw_only(), py::arg("dx"), py::arg("dy"), py::arg("upper") = py::none(),
      py::arg("prune") = true, py::arg("threads") = 1,
      ("Areal signature of two rigid blocks (heights in m, dx, dy in m) sliding along `direction` (rad; runs without "
       "the GIL); upper as measured (turned over) by default, in_place=True: already in place in the lower map's "
       "coordinates: the grid model (the maps' nodes, slopes by central differences), a diagnostic of the grid, not a "
       "bound of the tilt test's hold angle (that and its bound: predict). prune=False evaluates every node (the "
       "direct method). Returns offset, lift (m), theta (rad), theta_max_forward/backward (rad), contact_slope_std "
       "(rad), evaluated_nodes, warnings (of the grid's bound theta_max + atan(atomic_friction)). The keywords are "
       "the fields of areal_signature_settings() (SI; the older angle and turn_over_upper are now direction and "
       "in_place):\n" +
       py_detail::keyword_doc(areal_signature_settings()))
          .c_str());
}
