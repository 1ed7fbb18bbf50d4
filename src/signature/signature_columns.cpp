// The output tables of the signature and the rigid-bound friction prediction (frictal/outputs.hpp):
// the keys of `frictal signature --json` and of Python's signature() and predict_friction() dicts,
// each declared once with its unit (the hold analysis's: src/hold/hold_columns.cpp).
#include <string>
#include <vector>

#include "frictal/signature.hpp"

namespace frictal {

namespace {

using S = SignatureResult;
using F = FrictionPrediction;

}  // namespace

ContactList contact_list(const SignatureResult& r) {
  ContactList l;
  for (std::size_t i = 0; i + 1 < r.contact_begin.size() && i < r.offset.size(); ++i)
    for (auto k = r.contact_begin[i]; k < r.contact_begin[i + 1]; ++k) {
      const Contact& c = r.contacts[k];
      l.offset.push_back(r.offset[i]);
      l.x.push_back(c.x);
      l.z.push_back(c.z);
      l.slope.push_back(c.slope);
      l.type.emplace_back(contact_type_name(c.type));
    }
  return l;
}

const Columns<ContactList>& contact_list_columns() {
  using T = ContactList;
  static const Columns<T> cols = {
      column<T>("offset_m", "m", "the offset of each contact", [](const T& l) { return l.offset; }),
      column<T>("x_m", "m", "contact abscissa in the lower block's frame", [](const T& l) { return l.x; }),
      column<T>("z_m", "m", "contact height on the lower surface", [](const T& l) { return l.z; }),
      column<T>("slope_deg", "deg", "contact slope by its type's rule", [](const T& l) { return l.slope; }),
      column<T>("type", "text", "vertex-edge, edge-vertex or vertex-vertex", [](const T& l) { return l.type; }),
  };
  return cols;
}

const Columns<SignatureResult>& signature_columns() {
  static const Columns<S> cols = {
      column<S>("spheroradius_m", "m", "the spheroradius r of the blocks (0: rigid profiles)",
                [](const S& r) { return r.spheroradius; }),
      column<S>("exact", "flag", "every event offset was evaluated (the signature is exact)",
                [](const S& r) { return r.exact; }),
      column<S>(
          "grid_replaced", "flag",
          "the exact event offsets were too many: a grid at the finer point spacing was evaluated instead",
          [](const S& r) { return r.grid_replaced; }, "-"),
      column<S>(
          "offsets", "count", "offsets evaluated", [](const S& r) { return double(r.offset.size()); }, "-"),
      column<S>(
          "offset_range_m", "m", "[first, last] offset evaluated",
          [](const S& r) {
            return r.offset.empty() ? std::vector<double>{} : std::vector<double>{r.offset.front(), r.offset.back()};
          },
          "-"),
      column<S>(
          "", "m", "evaluated offsets s", [](const S& r) { return r.offset; }, "offset"),
      column<S>(
          "", "m", "lift h(s): the upper block's reference height at each offset", [](const S& r) { return r.lift; },
          "lift"),
      column<S>(
          "", "deg", "theta(s), Eq. 3: the steepest contact slope at each offset", [](const S& r) { return r.theta; },
          "theta"),
      column<S>(
          "", "deg", "the least contact slope at each offset", [](const S& r) { return r.theta_min; }, "theta_min"),
      column<S>(
          "", "deg", "atan h'(s-): slope of the lift just before each offset", [](const S& r) { return r.theta_left; },
          "theta_left"),
      column<S>(
          "", "deg", "atan h'(s+): slope of the lift just after each offset", [](const S& r) { return r.theta_right; },
          "theta_right"),
      column<S>("theta_max_forward_deg", "deg", "steepest contact slope resisting sliding towards +x (max theta)",
                [](const S& r) { return r.theta_max_forward; }),
      column<S>("theta_max_backward_deg", "deg", "steepest contact slope resisting sliding towards -x (max -theta)",
                [](const S& r) { return r.theta_max_backward; }),
      column<S>("offset_at_forward_m", "m", "offset where theta_max_forward is reached",
                [](const S& r) { return r.offset_at_forward; }),
      column<S>("offset_at_backward_m", "m", "offset where theta_max_backward is reached",
                [](const S& r) { return r.offset_at_backward; }),
      column<S>("contact_slope_mean_deg", "deg", "mean contact slope, weighted by offset length",
                [](const S& r) { return r.contact_slope_mean; }),
      column<S>("contact_slope_std_deg", "deg", "sigma of Eq. 18: standard deviation of the contact slopes",
                [](const S& r) { return r.contact_slope_std; }),
      object_column<S>(
          "", "histogram", "density of the contact slopes (edges in rad, density per rad)", histogram_columns(),
          [](const S& r) { return std::optional(r.contact_slope_pdf); }, "contact_slope_pdf"),
      column<S>(
          "", "deg", "contact slope samples the statistics are over", [](const S& r) { return r.slope_samples; },
          "slope_samples"),
      column<S>(
          "", "m", "weight (offset length) of each slope sample", [](const S& r) { return r.slope_weights; },
          "slope_weights"),
      column<S>(
          "", "count", "distinct event offsets in the range", [](const S& r) { return double(r.events); }, "events"),
      only_if(object_column<S>(
                  "", "contacts", "every contact at every offset (keep_contacts=True)", contact_list_columns(),
                  [](const S& r) { return std::optional(contact_list(r)); }, "contacts"),
              [](const S& r) { return !r.contact_begin.empty(); }),
  };
  return cols;
}

const Columns<FrictionPrediction>& friction_columns() {
  static const Columns<F> cols = {
      column<F>("atomic_friction", "1", "mu_a, the atomic (flat-contact) friction coefficient",
                [](const F& f) { return f.atomic_friction; }),
      column<F>("atomic_friction_angle_deg", "deg", "theta_a = atan(mu_a)", [](const F& f) { return f.atomic_angle; }),
      column<F>(
          "", "deg", "the theta_max the bound is of", [](const F& f) { return f.theta_max; }, "theta_max"),
      column<F>("upper_bound_friction_angle_deg", "deg",
                "rigid upper bound theta_max + theta_a (Eq. 6), reached only where the block can get to the steepest "
                "contact",
                [](const F& f) { return f.friction_angle; }),
      column<F>("upper_bound_friction_coefficient", "1", "tan of the upper bound",
                [](const F& f) { return f.friction_coefficient; }),
      column<F>("eq18_low_friction_angle_deg", "deg",
                "low end of the paper's Eq. 18 range: max(0, theta_max + theta_a - sigma)",
                [](const F& f) { return f.friction_angle_low; }),
      column<F>("eq18_low_friction_coefficient", "1", "tan of the Eq. 18 low end",
                [](const F& f) { return f.friction_coefficient_low; }),
      column<F>("eq18_low_clamped", "flag", "theta_max + theta_a - sigma was below 0: the low end is 0",
                [](const F& f) { return f.low_clamped; }),
  };
  return cols;
}

const Columns<FrictionPrediction>& friction_backward_columns() {
  static const Columns<F> cols = {
      column<F>(
          "upper_bound_friction_angle_backward_deg", "deg", "rigid upper bound sliding towards -x",
          [](const F& f) { return f.friction_angle; }, "-"),
      column<F>(
          "upper_bound_friction_coefficient_backward", "1", "tan of the backward upper bound",
          [](const F& f) { return f.friction_coefficient; }, "-"),
  };
  return cols;
}

}  // namespace frictal
