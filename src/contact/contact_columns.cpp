// The output table of a contact solution (frictal/outputs.hpp): the keys of `frictal contact
// --json` and of Python's frictal.contact() dicts (SI values under the same keys).
#include "frictal/contact.hpp"

namespace frictal {

const Columns<ContactResult>& contact_columns() {
  // A field over the grid, written where the result holds it (Python's fields=True), as the grid.
  auto fields = [](Column<ContactResult> c) {
    c = with_shape(std::move(c), [](const ContactResult& r) {
      return r.is_map ? std::vector<std::size_t>{r.ny, r.nx} : std::vector<std::size_t>{};
    });
    return only_if(std::move(c), [](const ContactResult& r) { return !r.pressure.empty(); });
  };
  using T = ContactResult;
  static const Columns<T> cols = {
      column<T>("load_n", "N", "maps: the total force (null for profiles)",
                [](const T& r) { return r.is_map ? r.force : std::numeric_limits<double>::quiet_NaN(); }),
      column<T>("load_per_length_n_per_m", "N/m",
                "profiles (plane strain): the force per unit length of the out-of-plane depth (null for maps)",
                [](const T& r) { return r.is_map ? std::numeric_limits<double>::quiet_NaN() : r.force; }),
      column<T>("nominal_pressure_pa", "Pa", "the force over the nominal area (maps) or length (profiles)",
                [](const T& r) { return r.nominal_pressure; }),
      column<T>("contact_area_m2", "m2", "maps: the area in contact, points with p > 0 times dx dy (null for profiles)",
                [](const T& r) { return r.contact_area; }),
      column<T>("contact_length_m", "m", "profiles: the length in contact, points with p > 0 times dx (null for maps)",
                [](const T& r) { return r.contact_length; }),
      column<T>("contact_area_fraction", "1", "the fraction of the (unmasked) points in contact",
                [](const T& r) { return r.contact_fraction; }),
      column<T>("plastic_area_fraction", "1", "the fraction of the points at the hardness cap p = H (0 without H)",
                [](const T& r) { return r.plastic_fraction; }),
      column<T>("max_pressure_pa", "Pa", "the largest contact pressure", [](const T& r) { return r.max_pressure; }),
      column<T>("mean_contact_pressure_pa", "Pa", "the force over the contact area (maps) or length (profiles)",
                [](const T& r) { return r.mean_contact_pressure; }),
      column<T>("mean_separation_m", "m", "the mean gap between the deformed surface and the flat",
                [](const T& r) { return r.mean_separation; }),
      column<T>("approach_m", "m",
                "the approach of the flat from first touch (periodic: the mean elastic displacement counts as zero; "
                "null for a non-periodic profile)",
                [](const T& r) { return r.approach; }),
      column<T>("contact_stiffness_n_per_m", "N/m",
                "maps: dF/d(approach) at this load, the contact set held (null for profiles; infinite, null, at full "
                "contact of a periodic map)",
                [](const T& r) { return r.is_map ? r.stiffness : std::numeric_limits<double>::quiet_NaN(); }),
      column<T>("contact_stiffness_per_length_pa", "Pa",
                "periodic profiles: dF/d(approach) per unit depth (null for maps and non-periodic profiles)",
                [](const T& r) { return r.is_map ? std::numeric_limits<double>::quiet_NaN() : r.stiffness; }),
      column<T>("contact_modulus_pa", "Pa", "E*: E / (1 - nu^2), or the composite of two bodies",
                [](const T& r) { return r.contact_modulus; }),
      column<T>("hardness_pa", "Pa", "the hardness cap H (null: none)",
                [](const T& r) { return r.hardness > 0 ? r.hardness : std::numeric_limits<double>::quiet_NaN(); }),
      column<T>("periodic", "flag", "the surface taken as periodic (else padded: non-periodic)",
                [](const T& r) { return r.periodic; }),
      column<T>("composite_rms_slope", "1", "rms slope of the composite topography (small-slope check)",
                [](const T& r) { return r.rms_slope; }),
      column<T>("iterations", "count", "conjugate-gradient iterations of the solve",
                [](const T& r) { return double(r.iterations); }),
      column<T>("stiffness_iterations", "count", "conjugate-gradient iterations of the stiffness (0: not computed)",
                [](const T& r) { return double(r.stiffness_iterations); }),
      column<T>("converged", "flag", "the solve reached its tolerance", [](const T& r) { return r.converged; }),
      column<T>("residual", "1", "the convergence measure reached (gap residual over the rms height)",
                [](const T& r) { return r.residual; }),
      column<T>("contact_wall_time_s", "s", "wall time of the solve (and its stiffness)",
                [](const T& r) { return r.wall_time; }),
      fields(column<T>(
          "", "Pa", "the contact pressure at each grid point (maps: ny x nx; Python with fields=True)",
          [](const T& r) { return r.pressure; }, "pressure")),
      fields(column<T>(
          "", "m", "the gap at each grid point (maps: ny x nx; Python with fields=True)",
          [](const T& r) { return r.gap; }, "gap")),
  };
  return cols;
}

const Columns<ContactCurve>& contact_curve_columns() {
  using T = ContactCurve;
  static const Columns<T> cols = {
      list_column<T>(
          "curve", "contact", "frictal contact with several loads: one contact object per load", contact_columns(),
          [](const T& c) { return std::optional(c.loads); }, "-"),
  };
  return cols;
}

}  // namespace frictal
