// The prediction's output table (frictal/predict.hpp): every quantity declared once, with its
// interface unit; the JSON writer below and the Python binding read it.
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/core.h>

#include "frictal/predict.hpp"
#include "frictal/units.hpp"
#include "util/json_text.hpp"

namespace frictal {

namespace {

using P = Prediction;

Column<P> deg(std::string key, std::string help, std::function<double(const P&)> f) {
  return column<P>(std::move(key), "deg", std::move(help), std::move(f));
}
Column<P> num(std::string key, std::string unit, std::string help, std::function<double(const P&)> f,
              std::string python = {}) {
  return column<P>(std::move(key), std::move(unit), std::move(help), std::move(f), std::move(python));
}
Column<P> list(std::string key, std::string unit, std::string help, std::function<std::vector<double>(const P&)> f,
               std::string python = {}) {
  return column<P>(std::move(key), std::move(unit), std::move(help), std::move(f), std::move(python));
}
double tan_or_inf(double a) { return a >= std::numbers::pi / 2 ? INFINITY : std::tan(a); }

}  // namespace

const Columns<Prediction>& prediction_columns() {
  static const Columns<Prediction> cols = {
      column<P>("trust", "text",
                "ok, or doubtful: a warning says the input was probably read wrong (units, spikes left in, scans "
                "that do not match, an angle at 90 deg) or the load model does not hold (merged or deeply "
                "interfering asperities); the number is then not the surfaces' friction until trust_fix is "
                "applied",
                [](const P& p) { return p.trust; }),
      column<P>("trust_codes", "text", "the warning codes that made the prediction doubtful, comma-separated",
                [](const P& p) {
                  std::string s;
                  for (const std::string& c : p.trust_codes) s += (s.empty() ? "" : ",") + c;
                  return s;
                }),
      column<P>("trust_fix", "text",
                "the fix for a doubtful prediction: the options to add (Python keywords in parentheses), the unit "
                "named where the file's unit and the slopes tell it",
                [](const P& p) { return p.trust_fix; }),
      column<P>("model", "text",
                "the model of the hold angle: profile-quasi-static-hold, profile-hertz-asperity-hold (under load) or "
                "map-continuous-free",
                [](const P& p) { return p.model; }),
      column<P>(
          "conditioning", "text",
          "every conditioning step applied to each surface first, in order, with its numbers: crop (the window, points "
          "kept), spikes (k, points replaced or masked), form",
          [](const P& p) { return p.conditioning; }),
      column<P>("form", "text", "the form removed from each surface: none, mean, line, plane, poly:N",
                [](const P& p) { return p.form; }),
      num("spikes_removed", "count", "points the spike filter replaced (profiles) or masked (maps), both surfaces",
          [](const P& p) { return double(p.spikes_removed); }),
      column<P>("is_map", "flag", "the pair is two areal maps", [](const P& p) { return p.is_map; }),
      deg("direction_deg", "sliding direction, from +x towards +y", [](const P& p) { return p.direction; }),
      num("atomic_friction", "1", "mu_a at every contact", [](const P& p) { return p.atomic_friction; }),
      num("runaway_distance_m", "m", "run-away distance d that a test reads",
          [](const P& p) { return p.runaway_distance; }),
      num("block_length_m", "m",
          "the test's block length L_b: the piece of the upper surface that slides (periodic pairs: the whole "
          "profile)",
          [](const P& p) { return p.block_length; }),
      column<P>("test_lengths", "text", "how d and L_b were set: given, or the default's rule with its numbers",
                [](const P& p) { return p.test_lengths; }),
      list("d_sweep_m", "m",
           "how the answer depends on d: the run-away distances d/4, d/2, d, 2d, 4d (those shorter than the blocks' "
           "overlap) of the d_sweep median, q05 and q95 columns, from the same lift and drops (profiles; maps: empty)",
           [](const P& p) { return p.d_sweep_distance; }),
      list("d_sweep_median_deg", "deg",
           "the hold angle's median over drops at each d of d_sweep_m (at d: the headline)",
           [](const P& p) { return p.d_sweep_q50; }),
      list("d_sweep_q05_deg", "deg", "its 5 % quantile at each d of d_sweep_m",
           [](const P& p) { return p.d_sweep_q05; }),
      list("d_sweep_q95_deg", "deg", "its 95 % quantile at each d of d_sweep_m",
           [](const P& p) { return p.d_sweep_q95; }),
      column<P>("single_drop", "flag", "one drop (--start-offset): the statistics are that drop's hold angle",
                [](const P& p) { return p.single_drop; }),
      num("drops", "count", "drops the distribution is over (profiles: the basins that drain them)",
          [](const P& p) { return double(p.drops); }),
      list("drop_range_m", "m",
           "drop range: profiles [min, max]; maps [u_min, u_max, v_min, v_max] along/across d (the block's spheres r + "
           "D "
           "inside the lower map)",
           [](const P& p) {
             return p.is_map ? std::vector<double>(p.drop_range.begin(), p.drop_range.end())
                             : std::vector<double>{p.drop_range[0], p.drop_range[1]};
           }),
      deg("friction_angle_deg",
          "THE PREDICTION: median over drops of the hold angle a tilt test reads, atan(mu_a) "
          "included",
          [](const P& p) { return p.friction_angle.q50; }),
      deg("friction_angle_q05_deg", "5 % quantile of the hold angle over drops",
          [](const P& p) { return p.friction_angle.q05; }),
      deg("friction_angle_q95_deg", "95 % quantile of the hold angle over drops",
          [](const P& p) { return p.friction_angle.q95; }),
      deg("friction_angle_mean_deg", "mean of the hold angle over drops",
          [](const P& p) { return p.friction_angle.mean; }),
      deg("friction_angle_std_deg", "standard deviation of the hold angle over drops",
          [](const P& p) { return p.friction_angle.std; }),
      deg("friction_angle_min_deg", "least hold angle over drops", [](const P& p) { return p.friction_angle.min; }),
      deg("friction_angle_max_deg", "largest hold angle over drops", [](const P& p) { return p.friction_angle.max; }),
      num("friction_coefficient", "1", "tan of friction_angle_deg (the median)",
          [](const P& p) { return p.friction_coefficient; }),
      num("friction_coefficient_q05", "1", "tan of the 5 % quantile",
          [](const P& p) { return tan_or_inf(p.friction_angle.q05); }),
      num("friction_coefficient_q95", "1", "tan of the 95 % quantile",
          [](const P& p) { return tan_or_inf(p.friction_angle.q95); }),
      deg("upper_bound_friction_angle_deg",
          "rigid upper bound, from the hold angles' own model: profiles theta_max + theta_a (Eq. 6), reached only "
          "where the block can get to the steepest contact; maps the steepest slope along the direction, friction "
          "cones included, of the contacts of every seat a drop rested in (above every drop by construction)",
          [](const P& p) { return p.upper_bound_friction_angle; }),
      num("upper_bound_friction_coefficient", "1", "tan of the upper bound",
          [](const P& p) { return tan_or_inf(p.upper_bound_friction_angle); }),
      deg("theta_max_deg",
          "steepest contact slope along the direction (profiles: the signature's maximum; maps: of the seats the "
          "drops rested in)",
          [](const P& p) { return p.theta_max; }),
      deg("contact_slope_std_deg",
          "sigma of Eq. 18: standard deviation of the contact slopes (maps: of the drops' steepest seat slopes)",
          [](const P& p) { return p.contact_slope_std; }),
      list("eq18_friction_angle_range_deg", "deg",
           "the paper's Eq. 18 range [max(0, theta_max - sigma), theta_max] "
           "+ theta_a",
           [](const P& p) {
             return std::vector<double>{p.eq18_range[0], p.eq18_range[1]};
           }),
      list("start_offset_m", "m", "single drop: where it was put down (x, y)",
           [](const P& p) {
             return p.single_drop ? std::vector<double>{p.start_offset[0], p.start_offset[1]} : std::vector<double>{};
           }),
      list("rest_offset_m", "m", "single drop: where it rested at zero tilt (x, y)",
           [](const P& p) {
             return p.single_drop ? std::vector<double>{p.rest_offset[0], p.rest_offset[1]} : std::vector<double>{};
           }),
      deg("locked_friction_angle_deg",
          "maps, a diagnostic: the median hold angle with the block locked to d (NaN "
          "for profiles)",
          [](const P& p) { return p.has_locked ? p.locked_friction_angle.q50 : NAN; }),
      deg("locked_friction_angle_q05_deg", "maps: 5 % quantile, block locked to d",
          [](const P& p) { return p.has_locked ? p.locked_friction_angle.q05 : NAN; }),
      deg("locked_friction_angle_q95_deg", "maps: 95 % quantile, block locked to d",
          [](const P& p) { return p.has_locked ? p.locked_friction_angle.q95 : NAN; }),
      list("drop_friction_angles_deg", "deg",
           "maps: each drop's hold angle (block free; under load: locked to d on the loaded lift), in drop order",
           [](const P& p) { return p.drop_angles; }),
      num("load_n", "N",
          "friction under load (profiles; null: the rigid prediction): the load W on the upper block, its weight; "
          "the headline is the hold angle at this load",
          [](const P& p) { return p.load; }),
      num("normal_load_n", "N",
          "under load: the normal force W cos(phi_0) the loaded lift was evaluated at (phi_0 the rigid median)",
          [](const P& p) { return p.normal_load; }),
      num("contact_modulus_pa", "Pa", "under load: the contact modulus E* of the Hertzian contacts",
          [](const P& p) { return p.contact_modulus; }),
      deg("rigid_friction_angle_deg", "under load: the rigid prediction's median beside the loaded one",
          [](const P& p) { return p.rigid_friction_angle; }),
      deg("load_zero_limit_deg",
          "under load: the loaded model's limit as the load goes to 0, the median over the same drops (profiles: "
          "the rigid median; maps: the block locked to d on the rigid lift, which the free block's median can "
          "differ from: warning load-locked-block)",
          [](const P& p) { return p.load_zero_limit; }),
      list("load_curve_n", "N",
           "under load: the loads of the friction-against-load curve, increasing (one load W given: W x 10^(-2..1) "
           "in half decades)",
           [](const P& p) { return p.load_curve; }),
      list("load_curve_median_deg", "deg", "the hold angle's median over drops at each load of load_curve_n",
           [](const P& p) { return p.load_curve_q50; }),
      list("load_curve_q05_deg", "deg", "its 5 % quantile at each load of load_curve_n",
           [](const P& p) { return p.load_curve_q05; }),
      list("load_curve_q95_deg", "deg", "its 95 % quantile at each load of load_curve_n",
           [](const P& p) { return p.load_curve_q95; }),
      num("load_contacts_mean", "1",
          "under load: asperity contacts (profiles) or contact patches (maps) carrying force per offset, mean",
          [](const P& p) { return p.load_contacts; }),
      num("load_approach_m", "m", "under load: the block's approach from first touch, mean over offsets",
          [](const P& p) { return p.load_approach; }),
      num("load_interference_ratio_max", "1",
          "under load: the largest interference over radius delta/R of a loaded contact (Hertz wants << 1)",
          [](const P& p) { return p.load_interference_ratio; }),
      num("load_merged_share", "1",
          "under load: the share of the load on contacts that merge with a neighbour, mean over offsets",
          [](const P& p) { return p.load_merged_share; }),
      num("load_contact_slope_rms", "1",
          "under load: the force-weighted rms of the contact slopes tan(theta) (maps: of |grad| of the composite)",
          [](const P& p) { return p.load_contact_slope; }),
      num("load_contact_fraction_max", "1",
          "under load, maps: the largest fraction of the overlap's points in contact over the offsets",
          [](const P& p) { return p.load_contact_fraction; }),
  };
  return cols;
}

OutputValue interface_value(const Column<Prediction>& c, const Prediction& p) { return to_interface(c.unit, c.si(p)); }

std::string prediction_json(const Prediction& p, const std::string& extra, int indent) {
  using util::json_real;
  using util::json_string;
  const std::string nl = indent > 0 ? "\n" : "", pad(std::size_t(std::max(indent, 0)), ' '), sp = indent > 0 ? " " : "";
  std::string s = "{" + nl;
  bool first = true;
  auto key = [&](const std::string& k) {
    if (!first) s += "," + nl;
    first = false;
    s += pad + json_string(k) + ":" + sp;
  };
  for (const Column<Prediction>& c : prediction_columns()) {
    key(c.key);
    const OutputValue v = interface_value(c, p);
    if (auto* d = std::get_if<double>(&v)) {
      s += c.unit == "count" ? fmt::format("{}", static_cast<long long>(*d)) : json_real(*d);
    } else if (auto* t = std::get_if<std::string>(&v)) {
      s += json_string(*t);
    } else if (auto* b = std::get_if<bool>(&v)) {
      s += *b ? "true" : "false";
    } else {
      const auto& l = std::get<std::vector<double>>(v);
      s += "[";
      for (std::size_t i = 0; i < l.size(); ++i) s += (i ? "," + sp : "") + json_real(l[i]);
      s += "]";
    }
  }
  key("warnings");
  s += "[";
  for (std::size_t i = 0; i < p.warnings.size(); ++i)
    s += (i ? "," + sp : "") + std::string("{\"code\":") + sp + json_string(p.warnings[i].code) + "," + sp +
         "\"message\":" + sp + json_string(p.warnings[i].message) + "}";
  s += "]";
  if (!extra.empty()) s += "," + nl + pad + extra;
  s += nl + "}";
  return s;
}

const Columns<ArealHoldReport>& areal_hold_columns() {
  using T = ArealHoldReport;
  auto chosen = [](const T& r) -> const HoldStatistics& {
    return r.locked ? r.prediction.locked_friction_angle : r.prediction.friction_angle;
  };
  auto one = [](Column<T> c) { return only_if(std::move(c), [](const T& r) { return r.prediction.single_drop; }); };
  auto over = [](Column<T> c, bool locked_only = false) {
    return only_if(std::move(c),
                   [locked_only](const T& r) { return !r.prediction.single_drop && (r.locked || !locked_only); });
  };
  auto pair = [](const std::array<double, 2>& a) { return std::vector<double>{a[0], a[1]}; };
  static const Columns<T> cols = [&] {
    Columns<T> c = {
        column<T>("direction_deg", "deg", "sliding direction, from +x towards +y",
                  [](const T& r) { return r.prediction.direction; }),
        column<T>("lateral", "text", "free (the block may move sideways) or locked to the direction",
                  [](const T& r) { return std::string(r.locked ? "locked" : "free"); }),
        column<T>("model", "text", "map-continuous-free or map-continuous-locked (frictal predict's model)",
                  [](const T& r) { return r.locked ? std::string("map-continuous-locked") : r.prediction.model; }),
        column<T>("in_place", "flag", "the upper map is the upper face in place (not turned over)",
                  [](const T& r) { return r.in_place; }),
        column<T>("atomic_friction", "1", "mu_a, included in every hold angle as atan(mu_a)",
                  [](const T& r) { return r.prediction.atomic_friction; }),
        column<T>("runaway_distance_m", "m", "run-away distance d",
                  [](const T& r) { return r.prediction.runaway_distance; }),
        column<T>("drops", "count", "drops the distribution is over",
                  [](const T& r) { return double(r.prediction.drops); }),
        fixed_length(column<T>(
            "drop_range_m", "m",
            "[u_min, u_max, v_min, v_max] along/across the direction (the spheres r + D inside the lower map)",
            [](const T& r) {
              const auto& d = r.prediction.drop_range;
              return std::vector<double>(d.begin(), d.end());
            })),
        one(fixed_length(column<T>("start_offset_m", "m", "one drop: where it was put down (x, y)",
                                   [pair](const T& r) { return pair(r.prediction.start_offset); }))),
        one(fixed_length(column<T>("rest_offset_m", "m", "one drop: where it rested (x, y)",
                                   [pair](const T& r) { return pair(r.prediction.rest_offset); }))),
        one(column<T>("hold_angle_deg", "deg", "one drop: its hold angle (the lateral mode's)",
                      [chosen](const T& r) { return chosen(r).q50; })),
        only_if(column<T>("hold_angle_free_deg", "deg", "one drop, locked: the free block's hold angle",
                          [](const T& r) { return r.prediction.friction_angle.q50; }),
                [](const T& r) { return r.prediction.single_drop && r.locked; }),
        one(column<T>("steering_deg", "deg", "one drop: the direction the free block ran away in",
                      [](const T& r) {
                        return r.prediction.drop_steering.empty() ? std::numeric_limits<double>::quiet_NaN()
                                                                  : r.prediction.drop_steering.front();
                      })),
    };
    using S = double HoldStatistics::*;
    const std::pair<const char*, S> stats[] = {{"mean", &HoldStatistics::mean}, {"std", &HoldStatistics::std},
                                               {"q05", &HoldStatistics::q05},   {"q50", &HoldStatistics::q50},
                                               {"q95", &HoldStatistics::q95},   {"min", &HoldStatistics::min},
                                               {"max", &HoldStatistics::max}};
    // (Named copies, not structured bindings: clang 14 cannot capture those.)
    for (const auto& entry : stats) {
      const char* name = entry.first;
      const S field = entry.second;
      const std::string k = std::string("hold_angle_") + name;
      c.push_back(over(column<T>(k + "_deg", "deg", std::string("hold angle over drops: ") + name,
                                 [chosen, field](const T& r) { return chosen(r).*field; })));
    }
    for (const auto& entry : stats) {
      const S field = entry.second;
      const std::string st(entry.first);
      if (st != "q05" && st != "q50" && st != "q95") continue;
      const std::string k = "hold_angle_free_" + st;
      c.push_back(over(column<T>(k + "_deg", "deg", "locked mode: the free block's hold angle over drops, " + st,
                                 [field](const T& r) { return r.prediction.friction_angle.*field; }),
                       true));
    }
    c.push_back(over(column<T>("drop_hold_angles_deg", "deg", "each drop's hold angle, in drop order", [](const T& r) {
      return r.locked ? r.prediction.drop_angles_locked : r.prediction.drop_angles;
    })));
    c.push_back(over(rows_column<T>("drop_offsets_m", "offset_xy", "each drop's (x, y)", offset_xy_columns(),
                                    [](const T& r) { return std::optional(r.prediction.drop_offsets); })));
    c.push_back(column<T>("upper_bound_friction_angle_deg", "deg", "rigid upper bound theta_max + theta_a (Eq. 6)",
                          [](const T& r) { return r.prediction.upper_bound_friction_angle; }));
    return c;
  }();
  return cols;
}

}  // namespace frictal
