// frictal — elastic normal contact of rough surfaces: a boundary-element solver on FFTs.
//
// The model (docs/contact.md): frictionless, non-adhesive normal contact of a linearly elastic
// half-space with the composite topography of the two surfaces, pressed against a rigid flat, in
// the small-slope approximation (surface slopes << 1, the half-space's Green's function applied
// to the projected surface). One elastic body on a rigid flat has the contact modulus
// E* = E / (1 - nu^2); two elastic bodies the composite 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,
// their composite gap being the sum of the two topographies.
//
// Maps use the half-space's Green's function (Boussinesq): u(q) = 2 p(q) / (E* |q|) in Fourier
// space (periodic, Stanley & Kato 1997), or for a surface that does not repeat the real-space
// influence coefficients of uniform pressure on one pixel (Love 1929) convolved on a grid padded
// to at least 2N - 1 (linear convolution, no wrap-around). Profiles are in plane strain: the half-plane,
// u(q) = 2 p(q) / (E* |q|) periodic, or the logarithmic kernel -(2 / (pi E*)) ln|x - s| padded
// (a force per unit length of the out-of-plane depth). The contact pressure solves the
// complementarity problem p >= 0, gap >= 0, p gap = 0 at a given total force, by the constrained
// conjugate gradient method of Polonsky & Keer (Wear 231, 1999), optionally with a hardness cap
// p <= H (perfect plasticity: the points at p = H carry H whatever their interference).
//
// SI units throughout: lengths in m, pressures and moduli in Pa, forces in N (maps) or N/m
// (profiles: per unit length of the out-of-plane depth).
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "frictal/geometry.hpp"
#include "frictal/map.hpp"
#include "frictal/outputs.hpp"
#include "frictal/result.hpp"

namespace frictal {

/// A linearly elastic, isotropic material.
struct ElasticMaterial {
  double modulus = 0;  ///< Young's modulus E, > 0 (unit: Pa)
  double poisson = 0;  ///< Poisson's ratio nu, in (-1, 0.5] (unitless)
};

/// E* = E / (1 - nu^2) of one body against a rigid flat (unit: Pa). Errors (InvalidInput) name
/// the parameter: E not finite or <= 0, nu outside (-1, 0.5].
Result<double> contact_modulus(const ElasticMaterial& body);
/// The composite of two bodies, 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (unit: Pa).
Result<double> contact_modulus(const ElasticMaterial& first, const ElasticMaterial& second);

/// The load of a contact: a total force or a nominal (apparent) pressure.
enum class ContactLoadKind {
  Force,     ///< total force: N for maps, N/m (per unit depth) for profiles
  Pressure,  ///< nominal pressure: the force over the nominal area (maps) or length (profiles) (Pa)
};
struct ContactLoad {
  ContactLoadKind kind = ContactLoadKind::Pressure;
  double value = 0;  ///< > 0; unit by kind: N (maps) or N/m (profiles) for Force, Pa for Pressure
};

struct ContactOptions {
  double contact_modulus = 0;  ///< E* (contact_modulus()), > 0 (unit: Pa)
  /// Hardness H: the pressure is capped at H (perfect plasticity); 0: purely elastic (unit: Pa).
  double hardness = 0;
  /// true: the surface repeats with the grid's period (nx dx by ny dy); false: the surface is
  /// surrounded by points that never touch (the convolution on a grid padded to at least 2N - 1).
  bool periodic = false;
  /// Convergence: the rms gap on the contact set and the largest interpenetration outside it,
  /// both below tolerance times the rms height of the composite topography (of a flat surface:
  /// the displacement of the mean pressure over one spacing, p dx / E*) (unitless, > 0).
  double tolerance = 1e-8;
  /// Largest number of conjugate-gradient iterations per solve (0: 20 sqrt(points) + 1000).
  int max_iterations = 0;
  /// Worker threads of the FFTs and of the solver's passes over the points (0: hardware
  /// concurrency, 1: none); results do not depend on it beyond rounding.
  unsigned threads = 1;
  bool stiffness = true;    ///< also the contact stiffness (one linear solve on the contact set)
  bool keep_fields = true;  ///< keep the pressure and gap fields in the result
  /// Small-slope approximation: the small-slope warning above this rms slope (unitless).
  double max_rms_slope = 0.3;
};

/// The solution at one load.
struct ContactResult {
  bool is_map = false;
  std::size_t nx = 0, ny = 1;  ///< grid points (profiles: ny = 1) (unitless)
  double dx = 0, dy = 0;       ///< spacings (profiles: dy = 0) (unit: m)
  bool periodic = false;
  double contact_modulus = 0;  ///< E* (unit: Pa)
  double hardness = 0;         ///< H; 0: none (unit: Pa)
  /// Total force: N for maps, N/m for profiles (per unit depth).
  double force = 0;
  double nominal_pressure = 0;  ///< the force over the nominal area (unit: Pa)
  double nominal_area = 0;      ///< nx dx ny dy (maps, unit: m^2); nx dx for profiles (unit: m)
  /// The area in contact (maps, unit: m^2; the points with p > 0 times dx dy); profiles: NaN.
  double contact_area = std::numeric_limits<double>::quiet_NaN();
  /// Profiles: the length in contact (points with p > 0 times dx) (unit: m); maps: NaN.
  double contact_length = std::numeric_limits<double>::quiet_NaN();
  double contact_fraction = 0;       ///< the fraction of the points in contact (unitless)
  double plastic_fraction = 0;       ///< the fraction of the points at p = H (unitless)
  double max_pressure = 0;           ///< (unit: Pa)
  double mean_contact_pressure = 0;  ///< the force over the contact area or length (unit: Pa)
  /// The mean gap between the deformed surface and the flat over the (unmasked) points (unit: m).
  double mean_separation = 0;
  /// The approach of the flat from first touch, the rigid-body displacement: the flat sits at
  /// max(h) - approach, h the composite topography (unit: m). Periodic surfaces: the elastic
  /// displacement's mean over the period counts as zero (the usual convention of periodic
  /// contact). NaN for a non-periodic profile (the half-plane's displacement has no reference).
  double approach = std::numeric_limits<double>::quiet_NaN();
  /// dF/d(approach) at this load, the contact set held (unit: N/m for maps; N/m per m of depth,
  /// i.e. Pa, for profiles). Infinite at full contact of a periodic surface; NaN for a
  /// non-periodic profile or when not asked for.
  double stiffness = std::numeric_limits<double>::quiet_NaN();
  double rms_slope = 0;  ///< rms slope of the composite topography (unitless)
  int iterations = 0;    ///< conjugate-gradient iterations of the solve
  int stiffness_iterations = 0;
  bool converged = false;
  double residual = 0;   ///< the convergence measure reached (ContactOptions::tolerance) (unitless)
  double wall_time = 0;  ///< (unit: s)
  /// Pressure (unit: Pa) and gap (unit: m) at every point, x fastest (empty unless keep_fields).
  std::vector<double> pressure;
  std::vector<double> gap;
  /// What the solution warns of (codes in `frictal warnings`): contact-full, small-slope,
  /// contact-not-converged, contact-at-edge.
  std::vector<Warning> warnings;
};

/// `p` on equally spaced points, as the solver needs them: itself when its spacing is uniform
/// (within 1e-6), else resampled on as many equally spaced points over its range (linear
/// interpolation; resample()), with a contact-resampled warning naming `name` added to `warnings`.
Result<Profile> equally_spaced(const Profile& p, const std::string& name, std::vector<Warning>& warnings);

/// The composite topography of the gap between `lower` and `upper` (both as measured: material
/// below, heights outward): with turn_over_upper the upper face is turned over onto the lower one
/// about the y axis (x -> -x about the map's centre, z -> -z), so the composite height is
/// lower(x, y) + upper(mirrored x, y); without it `upper` is the upper face in place in the lower's
/// coordinates, and the composite height is lower - upper. The two must share the grid (nx, ny,
/// dx, dy). Errors name `lower_name` and `upper_name`.
Result<Map> composite_topography(const Map& lower, const Map& upper, bool turn_over_upper,
                                 const std::string& lower_name = "lower", const std::string& upper_name = "upper");
/// The same for profiles (rotate180 for turn_over_upper): both equally spaced with the same
/// number of points and spacing.
Result<Profile> composite_topography(const Profile& lower, const Profile& upper, bool turn_over_upper,
                                     const std::string& lower_name = "lower", const std::string& upper_name = "upper");

/// The contact of the elastic half-space whose surface is `surface` (the composite topography;
/// NaN points are masked: they carry no pressure) pressed against a rigid flat under `load`.
/// Errors (InvalidInput, naming the parameter): E* or H not finite or negative, a load not finite
/// or <= 0, a load above H times the nominal area, fewer than 2 x 2 valid points.
Result<ContactResult> solve_contact(const Map& surface, const ContactLoad& load, const ContactOptions& options);
/// The same for a profile in plane strain: equally spaced points (error otherwise), the force
/// per unit length (N/m). A profile with a period is periodic whatever options.periodic says (a
/// last point one period after the first is left out); periodic without a period: a last point
/// at the first one's height closes the period and is left out, otherwise the period is n dx.
Result<ContactResult> solve_contact(const Profile& surface, const ContactLoad& load, const ContactOptions& options);

/// The solutions at several loads (a load curve), in the order given, each solve starting from
/// the previous load's pressure (warm start). The same errors as solve_contact.
Result<std::vector<ContactResult>> solve_contact_curve(const Map& surface, const std::vector<ContactLoad>& loads,
                                                       const ContactOptions& options);
Result<std::vector<ContactResult>> solve_contact_curve(const Profile& surface, const std::vector<ContactLoad>& loads,
                                                       const ContactOptions& options);

/// solve_contact_curve with a start for each load: `starts[k]` (empty, or one pressure per point
/// of `surface`, x fastest, unit: Pa) is where the solve of load k begins, scaled to carry it (its
/// points of zero or NaN pressure start out of contact), in place of the previous load's pressure.
/// The solution of a nearby problem (the same pair moved a little) is a start close to the answer:
/// the solver then needs fewer iterations; the answer is the same to the tolerance. `starts` is
/// empty or has one entry per load. The same errors as solve_contact, and a start of another size.
Result<std::vector<ContactResult>> solve_contact_curve(const Map& surface, const std::vector<ContactLoad>& loads,
                                                       const ContactOptions& options,
                                                       const std::vector<std::vector<double>>& starts);

/// The contact solution as output columns (frictal/outputs.hpp; src/contact/contact_columns.cpp): the
/// keys of `frictal contact --json` and Python's frictal.contact() dicts.
const Columns<ContactResult>& contact_columns();
/// The contact at several loads (frictal contact --load A,B,...): one ContactResult per load.
struct ContactCurve {
  std::vector<ContactResult> loads;
};
/// Its output table (table "contact_curve"): the list "curve" of contact objects.
const Columns<ContactCurve>& contact_curve_columns();

}  // namespace frictal
