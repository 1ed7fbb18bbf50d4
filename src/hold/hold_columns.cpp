// The output tables of the hold analysis (frictal/outputs.hpp): the keys of `frictal hold --json`
// and of Python's hold_angle() dicts, each declared once with its unit.
#include <optional>
#include <string>
#include <vector>

#include "frictal/hold.hpp"

namespace frictal {

namespace {

using H = HoldAnalysis;

}  // namespace

const Columns<HoldStatistics>& hold_statistics_columns() {
  using T = HoldStatistics;
  static const Columns<T> cols = {
      column<T>("mean_deg", "deg", "mean over drops (weighted by drop-range length)",
                [](const T& s) { return s.mean; }),
      column<T>("std_deg", "deg", "standard deviation over drops", [](const T& s) { return s.std; }),
      column<T>("q05_deg", "deg", "5 % quantile over drops", [](const T& s) { return s.q05; }),
      column<T>("q50_deg", "deg", "median over drops", [](const T& s) { return s.q50; }),
      column<T>("q95_deg", "deg", "95 % quantile over drops", [](const T& s) { return s.q95; }),
      column<T>("min_deg", "deg", "least over drops", [](const T& s) { return s.min; }),
      column<T>("max_deg", "deg", "largest over drops", [](const T& s) { return s.max; }),
  };
  return cols;
}

const Columns<HoldAngle>& hold_drop_columns() {
  using T = HoldAngle;
  static const Columns<T> cols = {
      column<T>("rest_offset_m", "m", "where the block rests at zero tilt", [](const T& a) { return a.rest_offset; }),
      column<T>("hold_angle_deg", "deg",
                "phi_qs: the quasi-static hold angle, atan(mu_a) + the slope of the stop that held",
                [](const T& a) { return a.hold_angle; }),
      column<T>("hold_offset_m", "m", "the stop that held, where the run-away slip starts",
                [](const T& a) { return a.hold_offset; }),
      column<T>("runaway_end_m", "m", "end of the run-away slip (null: off the end of the range, or never caught)",
                [](const T& a) { return a.runaway_end; }),
      column<T>("hold_slips", "count", "short slips (< d) between the rest and the run-away",
                [](const T& a) { return double(a.slips); }),
      column<T>(
          "", "flag", "the run-away ran off the end of the range", [](const T& a) { return a.ran_off_end; },
          "ran_off_end"),
      column<T>("inertial_hold_angle_deg", "deg", "phi_in: atan(mu_a) + the steepest chord (the inertial bound)",
                [](const T& a) { return a.inertial_hold_angle; }),
      column<T>("inertial_offset_m", "m", "where the steepest chord ends",
                [](const T& a) { return a.inertial_offset; }),
  };
  return cols;
}

const Columns<HoldDistribution>& hold_distribution_columns() {
  using T = HoldDistribution;
  static const Columns<T> cols = {
      object_column<T, HoldStatistics>(
          "", "hold_statistics", "phi_qs, the quasi-static hold angle, over drops", hold_statistics_columns(),
          [](const T& d) { return std::optional<HoldStatistics>(d.hold); }, "hold_angle"),
      object_column<T, HoldStatistics>(
          "", "hold_statistics", "phi_in, the inertial bound, over drops", hold_statistics_columns(),
          [](const T& d) { return std::optional<HoldStatistics>(d.inertial); }, "inertial_hold_angle"),
      object_column<T, HoldBasins>(
          "", "hold_basins", "the basins the drops drain into", hold_basins_columns(),
          [](const T& d) { return std::optional<HoldBasins>(d.basins); }, "basins"),
      column<T>(
          "", "m", "[min, max] of the drops",
          [](const T& d) {
            return std::vector<double>{d.drop_min, d.drop_max};
          },
          "drop_range"),
  };
  return cols;
}

const Columns<HoldBasins>& hold_basins_columns() {
  using T = HoldBasins;
  static const Columns<T> cols = {
      column<T>(
          "", "m", "rest offset of each basin", [](const T& b) { return b.rest; }, "rest_offset"),
      column<T>(
          "", "m", "length of the drop range that drains into each basin", [](const T& b) { return b.weight; },
          "weight"),
      column<T>(
          "", "deg", "phi_qs of a block resting in each basin", [](const T& b) { return b.hold; }, "hold_angle"),
      column<T>(
          "", "deg", "phi_in of each basin", [](const T& b) { return b.inertial; }, "inertial_hold_angle"),
  };
  return cols;
}

namespace {

/// The CLI's flat keys of `sub` (a table of T) for the T that `get` picks from a HoldAnalysis: key
/// `prefix` + "_" + the sub-key (statistics) or the sub-key with `suffix` before its unit (a drop).
template <class T, class G>
void flatten(Columns<H>& out, const Columns<T>& sub, G get, const std::string& prefix, const std::string& suffix,
             const std::string& what) {
  for (const Column<T>& c : sub) {
    if (c.key.empty()) continue;
    std::string key;
    if (!prefix.empty()) {
      key = prefix + "_" + c.key;
    } else {
      const std::size_t u = c.key.rfind('_');
      const bool has_unit = u != std::string::npos && (c.key.substr(u) == "_deg" || c.key.substr(u) == "_m");
      key = has_unit ? c.key.substr(0, u) + suffix + c.key.substr(u) : c.key + suffix;
    }
    out.push_back(column<H>(
        key, c.unit, what + ": " + c.help, [get, si = c.si](const H& h) { return si(get(h)); }, "-"));
  }
}

}  // namespace

const Columns<HoldAnalysis>& hold_columns() {
  static const Columns<H> cols = [] {
    Columns<H> c = {
        column<H>("runaway_distance_m", "m", "run-away distance d that a test reads",
                  [](const H& h) { return h.runaway_distance; }),
        column<H>("hold_events", "count", "offsets of the lift the hold analysis ran on",
                  [](const H& h) { return double(h.events); }),
        column<H>("hold_exact", "flag", "that lift was exact (every event offset)", [](const H& h) { return h.exact; }),
        column<H>(
            "drop_range_m", "m", "[min, max] of the drops the distribution is over",
            [](const H& h) {
              return std::vector<double>{h.distribution.forward.drop_min, h.distribution.forward.drop_max};
            },
            "-"),
        column<H>(
            "hold_basins", "count", "basins (rest offsets) the forward drops drain into",
            [](const H& h) { return double(h.distribution.forward.basins.rest.size()); }, "-"),
        column<H>(
            "", "m", "the lift's vertices s_k the analysis ran on", [](const H& h) { return h.curve.offset; },
            "offset"),
        column<H>(
            "", "m", "the lift h(s_k)", [](const H& h) { return h.curve.lift; }, "lift"),
        column<H>(
            "", "m", "the lift's period (0: not periodic)", [](const H& h) { return h.curve.period; }, "period"),
        object_column<H, HoldDistribution>(
            "", "hold_distribution", "the distribution over drops, sliding towards +x", hold_distribution_columns(),
            [](const H& h) { return std::optional<HoldDistribution>(h.distribution.forward); }, "forward"),
        object_column<H, HoldDistribution>(
            "", "hold_distribution", "the distribution over drops, sliding towards -x", hold_distribution_columns(),
            [](const H& h) { return std::optional<HoldDistribution>(h.distribution.backward); }, "backward"),
        object_column<H, HoldAngle>(
            "", "hold_drop", "the drop from the given start offset, forward (start_offset given)", hold_drop_columns(),
            [](const H& h) { return h.has_start ? std::optional<HoldAngle>(h.start.forward) : std::nullopt; }, "start"),
        object_column<H, HoldAngle>(
            "", "hold_drop", "the same drop, sliding backward (start_offset given)", hold_drop_columns(),
            [](const H& h) { return h.has_start ? std::optional<HoldAngle>(h.start.backward) : std::nullopt; },
            "start_backward"),
    };
    const auto& st = hold_statistics_columns();
    flatten(
        c, st, [](const H& h) { return h.distribution.forward.hold; }, "hold_angle", "",
        "hold angle over drops, forward");
    flatten(
        c, st, [](const H& h) { return h.distribution.forward.inertial; }, "inertial_hold_angle", "",
        "inertial bound over drops, forward");
    flatten(
        c, st, [](const H& h) { return h.distribution.backward.hold; }, "hold_angle_backward", "",
        "hold angle over drops, backward");
    flatten(
        c, st, [](const H& h) { return h.distribution.backward.inertial; }, "inertial_hold_angle_backward", "",
        "inertial bound over drops, backward");
    return c;
  }();
  return cols;
}

const Columns<HoldAnalysis>& hold_start_columns() {
  static const Columns<H> cols = [] {
    Columns<H> c;
    flatten(
        c, hold_drop_columns(), [](const H& h) { return h.start.forward; }, "", "", "the given drop, forward");
    flatten(
        c, hold_drop_columns(), [](const H& h) { return h.start.backward; }, "", "_backward",
        "the given drop, backward");
    return c;
  }();
  return cols;
}

}  // namespace frictal
