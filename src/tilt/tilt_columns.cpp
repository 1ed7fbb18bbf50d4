// The output tables of the tilt test (frictal/outputs.hpp): the keys of `frictal tilt --json` and
// of its nested objects, and the tilt study kinds' outputs of the same name.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>

#include <fmt/core.h>

#include "frictal/areal_tilt.hpp"
#include "frictal/settings.hpp"
#include "frictal/tilt.hpp"

namespace frictal {

namespace {

using R = TiltReport;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool rotated(const TiltResult& r) {
  return std::any_of(r.warnings.begin(), r.warnings.end(), [](const Warning& w) { return w.code == "rotation"; });
}
double per_step(const TiltResult& r, std::uint64_t n) {
  return r.steps ? static_cast<double>(n) / static_cast<double>(r.steps) : 0.0;
}

/// The values of a settings table as the fields of one nested object, each in its text unit (an
/// angle in degrees; JSON writes an integer as an integer, a flag as a flag): the keys are the
/// table's names, so they are declared by the table (`frictal settings`), not by an output table.
OutputRow settings_row(const std::vector<Field>& fields, const ValueSet& si) {
  OutputRow row;
  for (const Field& f : fields) {
    const auto it = si.find(f.name);
    if (it == si.end()) continue;
    OutputField out;
    out.info = {f.name, "", f.help, python_key(f.name)};
    std::visit(
        [&](const auto& v) {
          using V = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<V, double>) {
            // "deg" converts SI radians (to_interface, the one degree conversion: to_text_unit's).
            out.info.unit = text_unit(f);
            out.si = v;
          } else if constexpr (std::is_same_v<V, std::int64_t>) {
            out.info.unit = "count";
            out.si = static_cast<double>(v);
          } else if constexpr (std::is_same_v<V, bool>) {
            out.info.unit = "flag";
            out.si = v;
          } else {
            out.info.unit = "text";
            out.si = v;
          }
        },
        it->second);
    row.push_back(std::move(out));
  }
  return row;
}

/// A column of T holding one object whose keys are the fields of a settings table (unit
/// "settings"): the row that `f` returns (a std::optional<OutputRow>: none, no key). The CLI's JSON
/// writes each value in its text unit, Python's dict in SI, under the same key (python_key).
template <class T, class F>
Column<T> settings_object(std::string key, std::string help, F&& f) {
  std::string python = python_key(key);
  Column<T> c = declared_column<T>(std::move(key), "settings", std::move(help), std::move(python));
  c.present = [f](const T& v) { return f(v).has_value(); };
  c.rows = [f](const T& v) { return std::vector<OutputRow>{*f(v)}; };
  return c;
}

}  // namespace

const Columns<TiltSurface>& tilt_surface_columns() {
  using T = TiltSurface;
  auto files = [](const T& s) { return s.generator.empty(); };
  auto stated = [](const T& s) { return s.test && !s.test->block.empty(); };
  static const Columns<T> cols = {
      only_if(column<T>("generator", "text",
                        "the generator of both blocks (frictal surface; Python: what was given, a repeating Profile or "
                        "an (x, z) curve, with its period, length and points)",
                        [](const T& s) { return s.generator; }),
              [](const T& s) { return !s.generator.empty(); }),
      only_if(column<T>(
                  "lower", "text", "the lower surface's file", [](const T& s) { return s.lower; }, "-"),
              files),
      only_if(column<T>(
                  "upper", "text", "the upper surface's file, as measured (the lower one when not given)",
                  [](const T& s) { return s.upper; }, "-"),
              files),
      only_if(column<T>("conditioning", "text", "every conditioning step applied to the files, with its numbers",
                        [](const T& s) { return s.conditioning; }),
              files),
      only_if(column<T>("block", "text",
                        "the test's block: stated (the middle piece of the upper profile, block_length_m long, "
                        "dropped where it lies wholly over the lower one, as frictal predict states it) or whole (the "
                        "whole upper profile over the first half of the lower one)",
                        [](const T& s) { return s.test->block; }),
              stated),
      only_if(column<T>("block_length_m", "m", "the test's block length L_b (predict's block_length_m)",
                        [](const T& s) { return s.test->block_length; }),
              stated),
      only_if(column<T>("runaway_distance_m", "m", "the test's run-away distance d (predict's runaway_distance_m)",
                        [](const T& s) { return s.test->runaway_distance; }),
              stated),
      only_if(column<T>("test_lengths", "text",
                        "how d and L_b were set: given, or the default's rule with its numbers (predict's "
                        "test_lengths)",
                        [](const T& s) { return s.test->rule; }),
              stated),
      only_if(fixed_length(column<T>("drop_range_m", "m",
                                     "predict's drop range [min, max] in the signature's offsets (0: left ends "
                                     "aligned); null for the whole block (the signature's own range)",
                                     [](const T& s) {
                                       return std::vector<double>{s.test->drop_min, s.test->drop_max};
                                     })),
              stated),
      only_if(column<T>("drop", "text",
                        "where the run drops the block (initial_offset): the middle of the drop range, given, or "
                        "the offset of least lift (whole block)",
                        [](const T& s) { return s.test->drop; }),
              stated),
  };
  return cols;
}

std::string tilt_validity(const TiltResult& r, const TiltConfig& c) {
  constexpr double kDegree = 3.14159265358979323846 / 180;
  if (!r.slid) return fmt::format("no run-away before the largest tilt {:.3g} deg", c.max_tilt / kDegree);
  if (rotated(r))
    return "the block turned (warning rotation): the signature's model does not hold; --hold-rotation holds it, "
           "--protocol quasi-static loads it without the turning kick";
  const double qs = std::max(r.predicted_hold_angle, r.predicted_sphero_hold_angle);
  if (!std::isfinite(qs) || !std::isfinite(r.predicted_inertial_hold_angle)) return "valid";
  const double tol = std::max(0.1 * kDegree, c.protocol == TiltProtocol::QuasiStatic ? c.tilt_increment : 0.0);
  const double lo = r.predicted_inertial_hold_angle - tol, hi = qs + tol;
  if (r.friction_angle >= lo && r.friction_angle <= hi) return "valid";
  std::string own;  // the run's own warnings that bear on it
  for (const Warning& w : r.warnings)
    if (w.code == "unsettled" || w.code == "unrelaxed" || w.code == "rounding" || w.code == "creep")
      own += (own.empty() ? "; this run warned " : ", ") + w.code;
  return fmt::format(
      "{:.3f} deg lies outside the rigid model's bracket [{:.3f}, {:.3f}] deg from the block's rest (inertial bound "
      "{:.3f}, quasi-static hold angle {:.3f}, +-{:.2g}): the run does not follow rigid blocks{}. The runs that read "
      "the hold angle use --protocol quasi-static --hold-rotation and contacts far stiffer than Table II's "
      "(--normal-stiffness 100 times the scaled value read it on the measured Dektak scan; docs/dem.md, \"The "
      "quasi-static protocol against the hold angle\")",
      r.friction_angle / kDegree, lo / kDegree, hi / kDegree, r.predicted_inertial_hold_angle / kDegree, qs / kDegree,
      tol / kDegree, own);
}

std::string tilt_spread_note(const TiltResult& r, const TiltConfig& c) {
  constexpr double kDegree = 3.14159265358979323846 / 180;
  if (!r.slid || !std::isfinite(r.predicted_spread_q05) || !std::isfinite(r.predicted_spread_q95)) return "";
  const double tol = std::max(0.1 * kDegree, c.protocol == TiltProtocol::QuasiStatic ? c.tilt_increment : 0.0);
  const std::string range =
      fmt::format("the rigid model's 5-95 % range over drops for this test, [{:.3f}, {:.3f}] deg (median {:.3f})",
                  r.predicted_spread_q05 / kDegree, r.predicted_spread_q95 / kDegree, r.predicted_spread_q50 / kDegree);
  if (r.friction_angle >= r.predicted_spread_q05 - tol && r.friction_angle <= r.predicted_spread_q95 + tol)
    return "inside " + range;
  std::string why;
  if (tilt_validity(r, c) == "valid" && std::isfinite(r.predicted_hold_angle))
    why = fmt::format(
        ": the block came to rest in a basin that fewer than 5 % of drops reach, whose own quasi-static hold angle is "
        "{:.3f} deg (a single run reads its own drop; `frictal predict` gives the distribution)",
        r.predicted_hold_angle / kDegree);
  else
    why = ": the run is not valid (see validity)";
  return "outside " + range + why;
}

const Columns<TiltReport>& tilt_columns() {
  static const Columns<R> cols = {
      column<R>("slid", "flag", "a run-away was detected before max_tilt", [](const R& t) { return t.result.slid; }),
      column<R>("friction_angle_deg", "deg",
                "the friction angle this test read: the tilt at the start of the run-away (null: no slide)",
                [](const R& t) { return t.result.slid ? t.result.friction_angle : kNaN; }),
      column<R>("friction_angle_valid", "flag",
                "slid, the block did not turn (rotation) and the angle lies inside the rigid model's bracket from "
                "its rest (tilt_validity): the angle is a friction angle of the surfaces",
                [](const R& t) { return tilt_validity(t.result, t.config) == "valid"; }),
      column<R>("validity", "text",
                "\"valid\", or why the angle is not a friction angle of the surfaces and the "
                "option that would make it one",
                [](const R& t) { return tilt_validity(t.result, t.config); }),
      column<R>("predicted_spread_q05_deg", "deg",
                "the rigid model's quasi-static hold angle over drops for this test (these blocks, this d and "
                "mu_a): 5 % quantile (null: not computed, spread_error)",
                [](const R& t) { return t.config.predict ? t.result.predicted_spread_q05 : kNaN; }),
      column<R>("predicted_spread_median_deg", "deg", "the same distribution's median",
                [](const R& t) { return t.config.predict ? t.result.predicted_spread_q50 : kNaN; }),
      column<R>("predicted_spread_q95_deg", "deg", "the same distribution's 95 % quantile",
                [](const R& t) { return t.config.predict ? t.result.predicted_spread_q95 : kNaN; }),
      column<R>("spread_note", "text",
                "where the friction angle lies against that range: inside, or outside and why (empty: no slide "
                "or no spread)",
                [](const R& t) { return tilt_spread_note(t.result, t.config); }),
      column<R>("spread_error", "text", "why the spread was not computed (empty: computed)",
                [](const R& t) { return t.result.spread_error; }),
      column<R>("predicted_friction_angle_deg", "deg", "rigid upper bound theta_max + atan(mu_a) (null: no prediction)",
                [](const R& t) { return t.config.predict ? t.result.predicted_friction_angle : kNaN; }),
      column<R>("predicted_theta_max_deg", "deg", "the signature's theta_max along the sliding direction",
                [](const R& t) { return t.config.predict ? t.result.predicted_theta_max : kNaN; }),
      column<R>("predicted_sphero_friction_angle_deg", "deg", "the same bound for the rounded (spheropolygon) blocks",
                [](const R& t) { return t.config.predict ? t.result.predicted_sphero_friction_angle : kNaN; }),
      column<R>("predicted_sphero_theta_max_deg", "deg", "theta_max of the rounded blocks",
                [](const R& t) { return t.config.predict ? t.result.predicted_sphero_theta_max : kNaN; }),
      column<R>("protocol", "text", "constant-rate (the paper's) or quasi-static",
                [](const R& t) {
                  return std::string(t.config.protocol == TiltProtocol::QuasiStatic ? "quasi-static" : "constant-rate");
                }),
      column<R>("contact_rule", "text", "the contact rule the run used: pairs or closest",
                [](const R& t) {
                  return std::string(t.result.contact_rule == dem::ContactRule::Closest ? "closest" : "pairs");
                }),
      column<R>("rest_offset_m", "m", "where the block rested after settling",
                [](const R& t) { return t.result.rest_offset; }),
      column<R>("predicted_hold_angle_deg", "deg", "the quasi-static hold angle of a block resting there (hold.hpp)",
                [](const R& t) { return t.result.predicted_hold_angle; }),
      column<R>("predicted_hold_offset_m", "m", "the stop that holds it",
                [](const R& t) { return t.result.predicted_hold_offset; }),
      column<R>("slide_start_offset_m", "m", "where the run-away started (null: no slide)",
                [](const R& t) {
                  return t.result.slid
                             ? t.result.rest_offset + (t.config.reverse ? -1 : 1) * t.result.slide_start_displacement
                             : kNaN;
                }),
      column<R>("predicted_inertial_hold_angle_deg", "deg", "the inertial bound of the hold angle from the rest",
                [](const R& t) { return t.result.predicted_inertial_hold_angle; }),
      column<R>("predicted_sphero_hold_angle_deg", "deg", "the hold angle of the rounded blocks from the rest",
                [](const R& t) { return t.result.predicted_sphero_hold_angle; }),
      column<R>("hold_error", "text", "why the hold angles were not computed (empty: they were)",
                [](const R& t) { return t.result.hold_error; }),
      column<R>("stiff_friction_angle_deg", "deg", "check_stiffness: the friction angle at 10 k_n (null: not checked)",
                [](const R& t) { return t.result.stiff_friction_angle; }),
      column<R>("increments", "count", "quasi-static: tilt increments taken (null: constant rate)",
                [](const R& t) {
                  return t.config.protocol == TiltProtocol::QuasiStatic ? double(t.result.increments) : kNaN;
                }),
      column<R>("unrelaxed_increments", "count", "quasi-static: increments whose relaxation ran out of relax_time",
                [](const R& t) {
                  return t.config.protocol == TiltProtocol::QuasiStatic ? double(t.result.unrelaxed_increments) : kNaN;
                }),
      column<R>("rotation_before_slide_deg", "deg", "how far the upper block turned before it slid",
                [](const R& t) { return t.result.rotation_before_slide; }),
      object_column<R, TiltScales>("scales", "tilt_scales", "the run's length and time scales", tilt_scales_columns(),
                                   [](const R& t) { return std::optional<TiltScales>(t.result.scales); }),
      object_column<R, TiltEstimate>("estimate", "tilt_estimate", "the cost estimate made before the run",
                                     tilt_estimate_columns(),
                                     [](const R& t) { return std::optional<TiltEstimate>(t.result.estimate); }),
      object_column<R, dem::StepTimings>("stage_time_s", "tilt_stage_times", "wall time by stage of the time stepping",
                                         tilt_stage_time_columns(),
                                         [](const R& t) { return std::optional<dem::StepTimings>(t.result.timings); }),
      settings_object<R>(
          "surface",
          "the surfaces as given: the files (lower, upper) and their conditioning, or the generator's name "
          "(generator) with its parameters in their text units (frictal surface GENERATOR)",
          [](const R& t) -> std::optional<OutputRow> {
            if (!t.surface) return std::nullopt;
            OutputRow row = row_of(tilt_surface_columns(), *t.surface);
            if (t.surface->parameters) {
              OutputRow p = settings_row(*t.surface->parameters, t.surface->values);
              row.insert(row.end(), p.begin(), p.end());
            }
            return row;
          }),
      object_column<R, TiltScaling>(
          "scaled_defaults", "tilt_scaling", "how the defaults were scaled to the surfaces (null: not)",
          tilt_scaling_columns(),
          [](const R& t) { return t.scaling ? std::optional<TiltScaling>(*t.scaling) : std::nullopt; }),
      settings_object<R>(
          "settings", "every tilt setting the run used, in its text unit (frictal settings tilt)",
          [](const R& t) { return std::optional(settings_row(tilt_settings(), tilt_values(t.config))); }),
      list_column<R, Warning>(
          "warnings", "warning",
          "the inputs' warnings (the files' reader and plausibility checks), then the run's (frictal warnings)",
          warning_columns(), [](const R& t) { return std::optional(t.warnings ? *t.warnings : t.result.warnings); }),
      column<R>("initial_offset_m", "m", "the offset the upper block was put down at",
                [](const R& t) { return t.result.initial_offset; }),
      column<R>("slide_time_s", "s", "simulated time at the start of the run-away",
                [](const R& t) { return t.result.slide_time; }),
      column<R>("simulated_time_s", "s", "simulated time of the run",
                [](const R& t) { return t.result.simulated_time; }),
      column<R>("steps", "count", "time steps taken", [](const R& t) { return double(t.result.steps); }),
      column<R>("wall_time_s", "s", "wall time of the time stepping", [](const R& t) { return t.result.wall_time; }),
      column<R>("setup_time_s", "s", "wall time of building the blocks, placing them and the predictions",
                [](const R& t) { return t.result.setup_time; }),
      column<R>("us_per_step", "1", "microseconds of wall time per step (a speed, unit in the name)",
                [](const R& t) { return t.result.steps ? 1e6 * t.result.wall_time / double(t.result.steps) : 0.0; }),
      column<R>("min_time_step_s", "s", "smallest time step taken", [](const R& t) { return t.result.min_time_step; }),
      column<R>("max_time_step_s", "s", "largest time step taken", [](const R& t) { return t.result.max_time_step; }),
      column<R>("list_builds", "count", "neighbour list builds",
                [](const R& t) { return double(t.result.timings.list_builds); }),
      column<R>("steps_beyond_stability_limit", "count", "steps above the explicit stability limit",
                [](const R& t) { return double(t.result.steps_beyond_limit); }),
      column<R>("mean_pairs_in_list", "1", "mean neighbour-list length per step",
                [](const R& t) { return per_step(t.result, t.result.timings.pairs_visited); }),
      column<R>("mean_pairs_evaluated", "1", "mean pairs evaluated per step",
                [](const R& t) { return per_step(t.result, t.result.timings.pairs_evaluated); }),
      column<R>("hot_list_refreshes", "count", "full passes that rebuilt the hot list",
                [](const R& t) { return double(t.result.timings.hot_refreshes); }),
      column<R>("split_steps", "count", "steps whose contact passes were split over threads",
                [](const R& t) { return double(t.result.timings.split_steps); }),
      column<R>("lower_vertices", "count", "vertices of the lower block",
                [](const R& t) { return double(t.result.lower_vertices); }),
      column<R>("upper_vertices", "count", "vertices of the upper block",
                [](const R& t) { return double(t.result.upper_vertices); }),
      column<R>("upper_mass_kg", "kg", "mass of the upper block", [](const R& t) { return t.result.upper_mass; }),
      column<R>("normal_damping_per_s", "1/s", "normal damping gamma_n used",
                [](const R& t) { return t.result.normal_damping; }),
      column<R>("settled_contacts", "count", "contacts at the end of settling",
                [](const R& t) { return double(t.result.settled_contacts); }),
      column<R>("settled_overlap_m", "m", "largest overlap at the end of settling",
                [](const R& t) { return t.result.settled_overlap; }),
      column<R>("settled_speed_m_s", "m/s", "speed of the upper block at the end of settling",
                [](const R& t) { return t.result.settled_speed; }),
      column<R>("settled_interference_ratio", "",
                "contact law hertz: mean overlap / R over the contacts at the end of settling (R the pair's "
                "radius of curvature); null for the linear law",
                [](const R& t) { return t.result.settled_interference_ratio; }),
      column<R>("contact_modulus_pa", "Pa", "contact law hertz: the contact modulus E* used; 0 for the linear law",
                [](const R& t) { return t.result.contact_modulus; }),
      column<R>(
          "", "count", "steps above the explicit stability limit (as steps_beyond_stability_limit)",
          [](const R& t) { return double(t.result.steps_beyond_limit); }, "steps_beyond_limit"),
      object_column<R, TiltSeries>(
          "", "tilt_series", "the time series of the run (Python; the CLI writes it with --output)",
          tilt_series_columns(), [](const R& t) { return std::optional<TiltSeries>(t.result.series); }, "series"),
  };
  return cols;
}

const Columns<ArealTiltResult>& areal_tilt_run_columns() {
  using T = ArealTiltResult;
  static const Columns<T> cols = {
      column<T>("friction_angle_deg", "deg", "the friction angle this 3D test read (absent with --predict-only)",
                [](const T& r) { return r.friction_angle; }),
      column<T>("ran_away", "flag", "the block ran away before the largest tilt",
                [](const T& r) { return r.ran_away; }),
      column<T>("steering_deg", "deg", "how far the simulated block turned off the direction",
                [](const T& r) { return r.steering; }),
      column<T>("spheres", "count", "spheres of the upper block", [](const T& r) { return double(r.spheres); }),
      column<T>("steps", "count", "MuJoCo steps", [](const T& r) { return double(r.steps); }),
      column<T>("unsettled_increments", "count", "increments that did not come to rest",
                [](const T& r) { return double(r.unsettled); }),
  };
  return cols;
}

const Columns<ArealTiltHoldReport>& areal_tilt_hold_columns() {
  using T = ArealTiltHoldReport;
  auto stops = [](std::size_t k) {
    return [k](const T& r) {
      std::vector<double> v;
      for (const auto& st : r.hold.stops) v.push_back(st[k]);
      return v;
    };
  };
  auto spread = [](Column<T> c) { return only_if(std::move(c), [](const T& r) { return r.spread != nullptr; }); };
  static const Columns<T> cols = {
      column<T>(
          "", "deg", "the hold angle (bisected to 1e-6 rad)", [](const T& r) { return r.hold.hold_angle; },
          "hold_angle"),
      column<T>(
          "", "deg", "the drop's rigid upper bound from the same model (>= hold_angle)",
          [](const T& r) { return r.hold.seat_bound; }, "seat_bound"),
      column<T>(
          "", "deg", "the increment at which the block ran away", [](const T& r) { return r.hold.runaway_increment; },
          "runaway_increment"),
      column<T>(
          "", "flag", "it ran away", [](const T& r) { return r.hold.ran_away; }, "ran_away"),
      fixed_length(column<T>(
          "", "m", "where it rested (x, y)",
          [](const T& r) {
            return std::vector<double>{r.hold.rest_offset[0], r.hold.rest_offset[1]};
          },
          "rest_offset")),
      column<T>(
          "", "deg", "how far it turned off the direction", [](const T& r) { return r.hold.steering; }, "steering"),
      column<T>(
          "", "count", "lift evaluations", [](const T& r) { return double(r.hold.evaluations); }, "evaluations"),
      column<T>("", "deg", "tilt of each stop", stops(0), "stop_tilt"),
      column<T>("", "m", "x of each stop", stops(1), "stop_x"),
      column<T>("", "m", "y of each stop", stops(2), "stop_y"),
      spread(fixed_length(column<T>(
          "", "deg", "[least, largest] with one slip's end moved by a sphere radius (spread=True)",
          [](const T& r) {
            return std::vector<double>{r.spread->low, r.spread->high};
          },
          "hold_angle_range"))),
      spread(column<T>(
          "", "count", "slips (spread=True)", [](const T& r) { return double(r.spread->slips); }, "slips")),
      spread(column<T>(
          "", "count", "slips whose end a sphere radius changes (spread=True)",
          [](const T& r) { return double(r.spread->ambiguous); }, "ambiguous_slips")),
  };
  return cols;
}

const Columns<TiltScales>& tilt_scales_columns() {
  using T = TiltScales;
  static const Columns<T> cols = {
      column<T>("resting_overlap_m", "m", "W / k_n: overlap of one contact carrying the upper block",
                [](const T& s) { return s.resting_overlap; }),
      column<T>("spheroradius_m", "m", "the spheroradius r", [](const T& s) { return s.spheroradius; }),
      column<T>("shortest_edge_m", "m", "shortest edge of the lower, upper face",
                [](const T& s) {
                  return std::vector<double>{s.shortest_edge[0], s.shortest_edge[1]};
                }),
      column<T>("smallest_feature_m", "m", "shortest run between neighbouring extrema of the lower, upper face",
                [](const T& s) {
                  return std::vector<double>{s.smallest_feature[0], s.smallest_feature[1]};
                }),
      column<T>("time_step_s", "s", "the fixed step, or the adaptive step's cap",
                [](const T& s) { return s.time_step; }),
      column<T>("contact_period_s", "s", "2 pi sqrt(m_upper / k_n): one contact's period",
                [](const T& s) { return s.contact_period; }),
  };
  return cols;
}

const Columns<TiltEstimate>& tilt_estimate_columns() {
  using T = TiltEstimate;
  static const Columns<T> cols = {
      column<T>("time_step_s", "s", "the time step", [](const T& e) { return e.time_step; }),
      column<T>("steps_expected", "1", "steps to the predicted slide", [](const T& e) { return e.steps_expected; }),
      column<T>("steps_bound", "1", "steps to max_tilt", [](const T& e) { return e.steps_bound; }),
      column<T>("simulated_time_expected_s", "s", "settling + tilt to the prediction",
                [](const T& e) { return e.simulated_time_expected; }),
      column<T>("simulated_time_bound_s", "s", "settling + tilt to max_tilt",
                [](const T& e) { return e.simulated_time_bound; }),
      column<T>("list_pairs", "1", "estimated neighbour-list pairs", [](const T& e) { return e.list_pairs; }),
      column<T>("seconds_per_step", "s", "estimated wall time per step", [](const T& e) { return e.seconds_per_step; }),
      column<T>("seconds_expected", "s", "estimated wall time to the predicted slide",
                [](const T& e) { return e.seconds_expected; }),
      column<T>("seconds_bound", "s", "estimated wall time to max_tilt", [](const T& e) { return e.seconds_bound; }),
  };
  return cols;
}

const Columns<dem::StepTimings>& tilt_stage_time_columns() {
  using T = dem::StepTimings;
  static const Columns<T> cols = {
      column<T>("neighbor_list", "s", "neighbour-list rebuild tests and rebuilds",
                [](const T& t) { return t.neighbor_list; }),
      column<T>("contacts", "s", "pair forces", [](const T& t) { return t.contacts; }),
      column<T>("integration", "s", "kicks, drift, kinematic motion, guards", [](const T& t) { return t.integration; }),
  };
  return cols;
}

const Columns<TiltScaling>& tilt_scaling_columns() {
  using T = TiltScaling;
  static const Columns<T> cols = {
      column<T>("reference_length_m", "m", "the length the macro defaults are for",
                [](const T&) { return kTiltReferenceLength; }),
      column<T>("length_m", "m", "L: extent in x of the shorter face", [](const T& s) { return s.length; }),
      column<T>("point_spacing_m", "m", "the smaller of the faces' median point spacing",
                [](const T& s) { return s.point_spacing; }),
      column<T>("length_factor", "1", "s = L / reference length", [](const T& s) { return s.length_factor; }),
      column<T>("radius_factor", "1", "q = r / (s r_0), below 1 when the spacing caps r",
                [](const T& s) { return s.radius_factor; }),
      column<T>("measured_defaults", "text",
                "the protocol settings a measured surface takes by default and the caller did not give "
                "(\"name = value, ...\"; empty for a generated surface)",
                [](const T& s) { return s.measured_defaults; }),
      list_column<T, TiltScaledSetting>(
          "settings", "tilt_scaled_setting",
          "the settings changed, each {name, unit, from, to} (CLI: text units; Python: SI)",
          tilt_scaled_setting_columns(), [](const T& s) { return std::optional(s.settings); }),
  };
  return cols;
}

const Columns<TiltScaledSetting>& tilt_scaled_setting_columns() {
  using T = TiltScaledSetting;
  // A setting's value in its text unit (JSON) or in SI (Python): the unit differs by setting, so
  // each front end has its own column, under the same name.
  auto field = [](const T& s) { return find_field(tilt_settings(), s.name); };
  static const Columns<T> cols = {
      column<T>("name", "text", "the setting (frictal settings tilt)", [](const T& s) { return s.name; }),
      column<T>(
          "unit", "text", "its text unit",
          [field](const T& s) {
            const Field* f = field(s);
            return f ? text_unit(*f) : std::string();
          },
          "-"),
      column<T>(
          "", "text", "its SI unit",
          [field](const T& s) {
            const Field* f = field(s);
            return f ? f->unit : std::string();
          },
          "unit"),
      column<T>(
          "from", "1", "the macro default, in the setting's text unit",
          [field](const T& s) {
            const Field* f = field(s);
            return f ? to_text_unit(*f, s.from) : s.from;
          },
          "-"),
      column<T>(
          "", "1", "the macro default, in the setting's SI unit", [](const T& s) { return s.from; }, "from"),
      column<T>(
          "to", "1", "the scaled value, in the setting's text unit",
          [field](const T& s) {
            const Field* f = field(s);
            return f ? to_text_unit(*f, s.to) : s.to;
          },
          "-"),
      column<T>(
          "", "1", "the scaled value, in the setting's SI unit", [](const T& s) { return s.to; }, "to"),
  };
  return cols;
}

const Columns<TiltFramesFile>& tilt_frames_columns() {
  using T = TiltFramesFile;
  // A polygon's vertices as an n x 2 array of (x, y).
  auto polygon = [](std::string python, std::string help, std::vector<double> T::*x, std::vector<double> T::*y) {
    return with_shape(column<T>(
                          "", "m", std::move(help),
                          [x, y](const T& f) {
                            std::vector<double> v;
                            for (std::size_t i = 0; i < (f.*x).size(); ++i) v.insert(v.end(), {(f.*x)[i], (f.*y)[i]});
                            return v;
                          },
                          std::move(python)),
                      [x](const T& f) {
                        return std::vector<std::size_t>{(f.*x).size(), 2};
                      });
  };
  auto frames = [](const T& f) { return f.frames.size(); };
  static const Columns<T> cols = {
      polygon("lower_polygon", "the lower core polygon relative to its centroid, initial orientation (n x 2)",
              &T::lower_polygon_x, &T::lower_polygon_y),
      polygon("upper_polygon", "the upper core polygon relative to its centroid, initial orientation (n x 2)",
              &T::upper_polygon_x, &T::upper_polygon_y),
      column<T>(
          "", "s", "each frame's time",
          [](const T& f) {
            std::vector<double> v;
            for (const TiltFrame& fr : f.frames) v.push_back(fr.time);
            return v;
          },
          "time"),
      column<T>(
          "", "deg", "each frame's tilt",
          [](const T& f) {
            std::vector<double> v;
            for (const TiltFrame& fr : f.frames) v.push_back(fr.tilt);
            return v;
          },
          "tilt"),
      with_shape(column<T>(
                     "", "m", "each frame's centroids of the lower and upper block (frames x 2 x 2)",
                     [](const T& f) {
                       std::vector<double> v;
                       for (const TiltFrame& fr : f.frames)
                         for (int b = 0; b < 2; ++b) v.insert(v.end(), {fr.position[b].x, fr.position[b].y});
                       return v;
                     },
                     "position"),
                 [frames](const T& f) {
                   return std::vector<std::size_t>{frames(f), 2, 2};
                 }),
      with_shape(column<T>(
                     "", "deg", "each frame's rotation of the lower and upper block (frames x 2)",
                     [](const T& f) {
                       std::vector<double> v;
                       for (const TiltFrame& fr : f.frames) v.insert(v.end(), {fr.angle[0], fr.angle[1]});
                       return v;
                     },
                     "angle"),
                 [frames](const T& f) {
                   return std::vector<std::size_t>{frames(f), 2};
                 }),
  };
  return cols;
}

const Columns<TiltSeries>& tilt_series_columns() {
  using T = TiltSeries;
  auto py = [](std::string python, std::string unit, std::string help, std::vector<double> T::*field) {
    return column<T>(
        "", std::move(unit), std::move(help), [field](const T& s) { return s.*field; }, std::move(python));
  };
  static const Columns<T> cols = {
      py("time", "s", "simulated time", &T::time),
      py("tilt", "deg", "tilt angle", &T::tilt),
      py("normal_force", "1", "N (per unit depth)", &T::normal_force),
      py("tangential_force", "1", "N (per unit depth)", &T::tangential_force),
      py("force_angle", "deg", "atan(F_t / F_n)", &T::force_angle),
      py("displacement", "m", "relative displacement", &T::displacement),
      py("velocity", "m/s", "relative velocity", &T::velocity),
      column<T>(
          "", "count", "contacts", [](const T& s) { return std::vector<double>(s.contacts.begin(), s.contacts.end()); },
          "contacts"),
  };
  return cols;
}

}  // namespace frictal
