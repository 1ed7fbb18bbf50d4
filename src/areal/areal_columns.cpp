// The output tables of the areal module (frictal/outputs.hpp): the areal signature along one
// direction (the keys of `frictal areal --json`) and the polar table over sliding directions (the
// keys of `frictal anisotropy --json` and of Python's anisotropy() dict).
#include <algorithm>
#include <array>
#include <string_view>

#include "frictal/areal.hpp"

namespace frictal {

const Columns<ArealSignature>& areal_signature_columns() {
  using T = ArealSignature;
  static const Columns<T> cols = {
      column<T>(
          "direction_deg", "deg", "sliding direction, from +x towards +y", [](const T& r) { return r.direction; }, "-"),
      column<T>(
          "offsets", "count", "offsets along the direction", [](const T& r) { return double(r.offset.size()); }, "-"),
      column<T>("evaluated_nodes", "count", "lower-surface nodes evaluated (after pruning)",
                [](const T& r) { return double(r.evaluated_nodes); }),
      column<T>(
          "theta_max_lift_deg", "deg", "steepest slope of the lift along the direction",
          [](const T& r) { return r.theta_max_lift; }, "-"),
      column<T>("theta_max_forward_deg", "deg", "steepest contact slope resisting sliding along the direction",
                [](const T& r) { return r.theta_max_forward; }),
      column<T>("theta_max_backward_deg", "deg", "steepest contact slope resisting sliding against it",
                [](const T& r) { return r.theta_max_backward; }),
      column<T>(
          "contact_slope_mean_deg", "deg", "mean contact slope", [](const T& r) { return r.contact_slope_mean; }, "-"),
      column<T>("contact_slope_std_deg", "deg", "sigma of Eq. 18", [](const T& r) { return r.contact_slope_std; }),
      column<T>(
          "", "m", "offsets along the direction", [](const T& r) { return r.offset; }, "offset"),
      column<T>(
          "", "m", "the lift at each offset", [](const T& r) { return r.lift; }, "lift"),
      column<T>(
          "", "rad", "the contact slope at each offset", [](const T& r) { return r.theta; }, "theta"),
  };
  return cols;
}

const Columns<FrictionPrediction>& areal_bound_columns() {
  // The grid's theta_max + theta_a: a diagnostic of the map's nodes, not a bound of what a tilt
  // test reads (that is `frictal predict`'s).
  static const Columns<FrictionPrediction> cols = [] {
    constexpr std::array<std::string_view, 3> keys = {
        "upper_bound_friction_angle_deg", "upper_bound_friction_coefficient", "eq18_low_friction_coefficient"};
    Columns<FrictionPrediction> c;
    for (const Column<FrictionPrediction>& f : friction_columns())
      if (std::find(keys.begin(), keys.end(), f.key) != keys.end()) {
        c.push_back(f);
        c.back().python.clear();
      }
    return c;
  }();
  return cols;
}

const Columns<AnisotropyRow>& anisotropy_row_columns() {
  using T = AnisotropyRow;
  static const Columns<T> cols = [] {
    Columns<T> c = {
        column<T>(
            "direction_deg", "deg", "sliding direction, from +x towards +y", [](const T& r) { return r.direction; },
            "-"),
        only_if(column<T>(
                    "lines", "count", "map lines the direction's theta_max is over",
                    [](const T& r) { return double(*r.lines); }, "-"),
                [](const T& r) { return r.lines.has_value(); }),
        column<T>(
            "theta_forward_deg", "deg", "theta_max along the direction", [](const T& r) { return r.theta_forward; },
            "-"),
        column<T>(
            "theta_backward_deg", "deg", "theta_max against the direction", [](const T& r) { return r.theta_backward; },
            "-"),
        column<T>(
            "sigma_deg", "deg", "sigma of Eq. 18", [](const T& r) { return r.sigma; }, "-"),
        column<T>(
            "upper_bound_friction_angle_deg", "deg",
            "rigid upper bound: theta_max + theta_a of the signature; with --hold the hold model's (the steepest "
            "seat the drops rested in, above every drop)",
            [](const T& r) { return r.upper_bound_friction_angle; }, "-"),
        only_if(
            column<T>(
                "signature_bound_friction_angle_deg", "deg", "--hold: the signature's theta_max + theta_a, beside it",
                [](const T& r) { return *r.signature_bound_friction_angle; }, "-"),
            [](const T& r) { return r.signature_bound_friction_angle.has_value(); }),
        column<T>(
            "upper_bound_friction_coefficient", "1", "tan of the upper bound",
            [](const T& r) { return r.upper_bound_friction_coefficient; }, "-"),
        column<T>(
            "eq18_low_friction_coefficient", "1", "tan of the Eq. 18 low end",
            [](const T& r) { return r.eq18_low_friction_coefficient; }, "-"),
        only_if(column<T>(
                    "hold_runaway_distance_m", "m", "--hold: run-away distance d",
                    [](const T& r) { return *r.hold_runaway_distance; }, "-"),
                [](const T& r) { return r.hold_runaway_distance.has_value(); }),
    };
    // The hold angle's statistics over drops, flattened: hold_angle_<statistic>_deg, and with the
    // block locked its quantiles, hold_angle_locked_<quantile>_deg.
    for (const Column<HoldStatistics>& s : hold_statistics_columns()) {
      c.push_back(only_if(
          column<T>(
              "hold_angle_" + s.key, s.unit, "--hold: hold angle over drops (frictal predict --direction): " + s.help,
              [si = s.si](const T& r) { return si(*r.hold_angle); }, "-"),
          [](const T& r) { return r.hold_angle.has_value(); }));
    }
    for (const Column<HoldStatistics>& s : hold_statistics_columns()) {
      if (!s.key.starts_with("q")) continue;
      c.push_back(only_if(
          column<T>(
              "hold_angle_locked_" + s.key, s.unit, "--hold --locked: the block locked to the direction, " + s.help,
              [si = s.si](const T& r) { return si(*r.hold_angle_locked); }, "-"),
          [](const T& r) { return r.hold_angle_locked.has_value(); }));
    }
    return c;
  }();
  return cols;
}

const Columns<AnisotropyTable>& anisotropy_columns() {
  using T = AnisotropyTable;
  // Python's dicts: one array over directions per quantity (SI).
  auto over = [](std::string python, std::string unit, std::string help, double AnisotropyRow::*field) {
    return column<T>(
        "", std::move(unit), std::move(help),
        [field](const T& t) {
          std::vector<double> v;
          for (const AnisotropyRow& r : t.directions) v.push_back(r.*field);
          return v;
        },
        std::move(python));
  };
  static const Columns<T> cols = {
      list_column<T>(
          "directions", "anisotropy_direction", "one row per sliding direction", anisotropy_row_columns(),
          [](const T& t) { return std::optional(t.directions); }, "-"),
      only_if(column<T>(
                  "hold_model", "text", "--hold: the model of the hold angles (frictal predict's)",
                  [](const T& t) { return *t.hold_model; }, "-"),
              [](const T& t) { return t.hold_model.has_value(); }),
      only_if(column<T>(
                  "hold_drops", "count", "--hold: drops per direction", [](const T& t) { return *t.hold_drops; }, "-"),
              [](const T& t) { return t.hold_drops.has_value(); }),
      column<T>(
          "atomic_friction", "1", "mu_a", [](const T& t) { return t.atomic_friction; }, "-"),
      over("direction", "rad", "each sliding direction", &AnisotropyRow::direction),
      over("theta_forward", "rad", "theta_max along each direction", &AnisotropyRow::theta_forward),
      over("theta_backward", "rad", "theta_max against each direction", &AnisotropyRow::theta_backward),
      over("sigma", "rad", "sigma of Eq. 18 for each direction", &AnisotropyRow::sigma),
      over("upper_bound_friction_angle", "rad", "rigid upper bound for each direction",
           &AnisotropyRow::upper_bound_friction_angle),
  };
  return cols;
}

}  // namespace frictal
