// frictal — friction under load. Profiles: the Hertzian-asperity model of Hanaor, Gan & Einav
// ("Contact mechanics of fractal surfaces by spline assisted discretisation", Int. J. Solids
// Struct. 2015; "Static friction at fractal interfaces", Tribology International 93, 2016), cast
// as a loaded lift that the rigid hold analysis (hold.hpp) reads unchanged (docs/load.md).
//
// At an offset s of the upper block (the signature's frame: `upper` is turned over, offset 0 puts
// its left end over the lower's left end), the composite d_s(x) = f(x) - g(x - s) is the height at
// which the block's reference touches the lower surface at x; the rigid lift is h(s) = max d_s.
// Every local maximum c of d_s (a minimum of the gap) is an asperity contact: a projected
// Hertzian sphere of composite radius R_c, 1/R_c = -d_s''(x_c) cos^3 theta_c (the sum of the two
// surfaces' curvatures at the contact), d_s read through a cubic spline through its samples at
// the lower profile's points (its maxima and their curvature move with s continuously), the
// normal tilted by the local slope theta_c (tan theta_c the mean of the two surfaces' slopes, each
// from the quadratic through a sample and its two neighbours). The
// block sinks to the height z at which the vertical components of the contact forces carry the
// load W: with v_c = d_s(x_c) - z the vertical interference and delta_c = v_c cos theta_c the normal
// one,
//   F_c = (4/3) E* sqrt(R_c) delta_c^(3/2),     sum_c F_c cos theta_c = W.
// Tilted by beta, the block is in equilibrium where sum_c F_c (sin theta_c cos beta - cos theta_c
// sin beta) = 0 (the contact forces along their normals and the weight), i.e. tan beta = tau_W(s) =
// sum F_c sin theta_c / sum F_c cos theta_c, the force-resolved contact slope; it is held where
// tau_W just ahead is at least tan beta, as a rigid block is held by the slope of the rigid lift.
// The loaded lift (the force lift) is therefore the lift whose slope is tau_W, with the slope of
// the contact that the rigid lift h follows on a piece (the loaded one nearest the piece's slope
// h') read from h, exact on the polylines (the contacts' slopes are the sampled profiles'):
//   H_W(s) = h(s) + int_(s_0)^s sum_(c != c*) w_c (tan theta_c - h') ds',
// w_c the contacts' shares of the vertical force. It equals h where one contact carries the load,
// tends to h as W -> 0, and its every slope is a weighted mean of h' and contact slopes.
// The minimum potential energy per unit load, z + sum_c (8/15) E* sqrt(R_c) delta_c^(5/2) / W (the
// energy lift, LoadedState::energy_lift), has the slope tau_W plus the work of the contacts'
// changing stiffness k_c = (4/3) E* sqrt(R_c) cos^(5/2) theta_c as they move,
// sum_c (2/5) v_c^(5/2) k_c'(s) / W: no force of the contacts exerts that term (docs/load.md).
// With atomic friction mu_a at each contact, tan phi = sum F (sin + mu_a cos) / sum F (cos - mu_a
// sin) is exactly tan(atan(mu_a) + atan(tau_W)), the rule the hold analysis applies to the slope of
// H_W: the hold analysis of H_W is the loaded prediction. Maps: the elastic
// half-space's loaded lift on lines along the sliding direction ("Maps" below).
//
// SI units: lengths in m, forces in N, moduli in Pa, angles in rad.
#pragma once

#include <cstddef>
#include <vector>

#include "frictal/geometry.hpp"
#include "frictal/hold.hpp"
#include "frictal/map.hpp"
#include "frictal/result.hpp"

namespace frictal {

/// One asperity contact of a loaded block (a local maximum of d_s within reach of the load).
struct HertzContact {
  double x = 0;             ///< the contact's abscissa in the lower profile's frame (unit: m)
  double touch_height = 0;  ///< d_s(x): the block height at which it touches (unit: m)
  double slope = 0;         ///< theta: the contact normal's tilt from vertical (unit: rad)
  double radius = 0;        ///< composite radius R (unit: m)
  double interference = 0;  ///< normal interference delta = v cos theta, 0 when open (unit: m)
  double force = 0;         ///< normal force F (unit: N)
  /// The lowest d_s between this contact and the previous one (in x) of the list, -inf for the
  /// first: the saddle between two asperities; the block below it merges them (unit: m).
  double saddle_left = 0;
};

struct LoadedLiftOptions {
  double contact_modulus = 0;  ///< E* (contact_modulus() of contact.hpp), > 0 (unit: Pa)
  /// Normal loads W on the block, each > 0 (unit: N): one loaded lift per load.
  std::vector<double> loads;
  /// Largest composite radius (a flat or concave local fit at a contact gives an infinite one):
  /// radii are capped here; 0: 100 times the upper block's length (unit: m).
  double max_radius = 0;
  unsigned threads = 0;  ///< worker threads (0 = all cores); results do not depend on it
  /// Skip the spline work where a bound shows the spline stays below the contacts' reach (a
  /// region's solve, a piece's maxima): the same lift to rounding. false: every region solved in
  /// full, to check the bound against (unitless switch).
  bool prune = true;
};

/// The block at one offset under one load.
struct LoadedState {
  double offset = 0;      ///< s (unit: m)
  double load = 0;        ///< W (unit: N)
  double rigid_lift = 0;  ///< the top contact's touch height: h(s) to the sampling's accuracy (unit: m)
  double height = 0;      ///< z: the block's reference height under the load (unit: m)
  double energy = 0;      ///< the contacts' elastic energy sum (2/5) F cos theta v (unit: J)
  /// z + energy / W: the minimum potential energy per unit load (the energy lift, whose slope adds
  /// the contacts' stiffness change to effective_slope; not the lift the prediction reads) (unit: m)
  double energy_lift = 0;
  /// sum F sin theta / sum F cos theta: the force-resolved contact slope, the slope of the loaded
  /// lift H_W at this offset (unitless).
  double effective_slope = 0;
  std::vector<HertzContact> contacts;  ///< in x order; open ones (force 0) included
};

/// Diagnostics of one load over the offsets of a loaded lift (the model's assumptions).
struct LoadedLiftDiagnostics {
  double load = 0;                    ///< W (unit: N)
  double mean_contacts = 0;           ///< contacts carrying force per offset, mean (unitless)
  double mean_approach = 0;           ///< h(s) - z, mean over offsets (unit: m)
  double max_interference_ratio = 0;  ///< largest delta / R of any loaded contact (unitless)
  /// Share of the offsets where some loaded contact has delta / R above 0.1 (Hertz wants a << R,
  /// a = sqrt(R delta)) (unitless).
  double deep_share = 0;
  /// Share of the load, averaged over offsets, carried by contacts that have merged with a
  /// neighbouring asperity (the next local maximum of d_s on either side, loaded or not): the
  /// block below the saddle between them, or the contact's Hertz half-width a = sqrt(R delta)
  /// reaching it (unitless).
  double merged_share = 0;
  /// sqrt of the force-weighted mean of tan^2 theta over contacts and offsets (unitless).
  double rms_contact_slope = 0;
};

struct LoadedLift {
  std::vector<double> loads;  ///< as given (unit: N)
  /// H_W per load, on the rigid lift's vertices and the refinement's offsets between them (the
  /// same offsets for every load).
  std::vector<LiftCurve> curves;
  std::vector<std::vector<double>> slopes;         ///< effective_slope at each offset, per load (unitless)
  std::vector<LoadedLiftDiagnostics> diagnostics;  ///< per load, over the rigid lift's vertices
  std::size_t candidates = 0;                      ///< asperity contacts at the rigid lift's vertices (unitless)
  std::size_t refined = 0;                         ///< offsets the refinement added (unitless)
};

/// The block at offset `offset` under load `load` (N), `upper` turned over as signature() takes
/// it. Errors (InvalidInput, naming the value): E* or W not finite or <= 0, fewer than 3 points in
/// a profile, an offset at which the blocks do not overlap.
Result<LoadedState> loaded_state(const Profile& lower, const Profile& upper, double offset, double load,
                                 const LoadedLiftOptions& options);

/// The loaded lift of every load of `options` over `rigid` (the pair's rigid lift over offsets
/// where the blocks overlap; not periodic): at the offsets s_j, the vertices of `rigid` and the
/// refinement's midpoints,
///   H_W(s_j) = h(s_j) + sum_(i < j) (s_(i+1) - s_i) (e_i + e_(i+1)) / 2,
/// h linear between the rigid vertices and e the excess slope sum_(c != c*) w_c (tan theta_c - h')
/// on the piece (at a vertex, e on the piece before it and on the piece after it, each with its
/// h'), c* the loaded contact whose slope is nearest h' (the one the rigid lift follows): H_W
/// equals `rigid` to the bit wherever one contact carries the load. Where a load's e differs
/// between two samples of a piece by more than 1e-3, a midpoint; where the midpoint's e misses
/// their mean by more than that, both halves again, up to 12 halvings (e falls to 0 within the
/// approach of a kink of h). The contacts are the maxima of d_s within the approach of the largest
/// load (pruned by chunks of the upper profile whose bound, the lower's maximum over their span
/// minus their minimum, cannot reach it). Errors as loaded_state, and a periodic or malformed
/// curve.
Result<LoadedLift> loaded_lift(const Profile& lower, const Profile& upper, const LiftCurve& rigid,
                               const LoadedLiftOptions& options);

// ---- Maps: the elastic half-space under the sliding block (docs/load.md, "Maps") ----
//
// At an offset (u, v) of the upper map (u along the sliding direction d, v across it; the turn-over
// and the frame of areal_lift in areal.hpp) the composite c(p) = f(p) + g(q(p)) at the lower
// map's nodes p of the overlap (g bilinear; in place: f(p) - g(p - s)) is the height at which the
// block's reference touches the lower surface at p; the rigid lift is h = max_p c(p). Under the
// normal load W the two blocks (composite modulus E*) are pressed together as one elastic
// half-space against a rigid flat (contact.hpp's solver, non-periodic, on the overlap's bounding
// box): the block sinks by the approach delta, the contact pressure p_i carries W, and the elastic
// energy is U = (1/2) sum_i F_i (c_i - z), F_i = p_i dx dy, z = h - delta. The loaded lift is the
// minimum potential energy per unit load, as for profiles,
//   H_W = z + U / W = h - delta + U / W,
// and its slope is, by the envelope theorem (the Lagrange multipliers of the contact constraints
// are the forces), the pressure-weighted contact slope sum_i F_i dc_i/du / W, exactly (no
// stiffness term: the half-space's influence coefficients do not move with the block).

/// Options of the loaded lift of a map pair.
struct MapLoadedLiftOptions {
  double contact_modulus = 0;  ///< E* (contact_modulus() of contact.hpp), > 0 (unit: Pa)
  /// Normal loads W on the block, each > 0 (unit: N); solved in the order given at each offset.
  std::vector<double> loads;
  double angle = 0;             ///< sliding direction d, from +x towards +y (unit: rad)
  bool turn_over_upper = true;  ///< false: the upper map is the upper face in place (areal.hpp)
  /// Offset step along d of the first pass of solves (0: the lower map's smaller spacing) (unit: m).
  double step = 0;
  /// Refinement: each interval between two solves of the first pass gets a solve at its middle;
  /// both halves are halved again, down to `min_step`, where the rigid contact (the composite's
  /// highest node) differs at the two ends (the load passes from one asperity to the next within
  /// the interval, a narrow feature of the elastic correction c = H_W - h), or where c at the
  /// middle misses the straight line between the ends by more than refine_slope times half the
  /// interval (for any load: the interpolation's slope off by about that). The solves gather where
  /// the contact changes, and the loaded lift no longer depends on `step`. 0: no refinement, the
  /// first pass alone (unitless; a slope: radians of hold angle).
  double refine_slope = 1e-4;
  /// The shortest interval refinement makes (0: the lower map's smaller spacing / 16) (unit: m).
  double min_step = 0;
  /// The contact solver's tolerance (ContactOptions::tolerance) (unitless).
  double tolerance = 1e-8;
  unsigned threads = 0;  ///< worker threads over lines (0 = all cores); results do not depend on it
};

/// The block at one offset under one load (maps).
struct MapLoadedState {
  double along = 0, across = 0;  ///< the offset u along d and v across it (unit: m)
  double load = 0;               ///< W (unit: N)
  double rigid_lift = 0;         ///< h = max of the composite over the overlap (unit: m)
  /// The node of the lower map where the composite is highest (j * nx + i): the rigid contact (unitless)
  std::size_t highest_node = 0;
  double approach = 0;     ///< delta: the block's sink from first touch (unit: m)
  double energy = 0;       ///< U, the elastic energy (unit: J)
  double loaded_lift = 0;  ///< H_W = h - delta + U / W (unit: m)
  /// sum F_i dc_i/du / W: the pressure-weighted contact slope along d, dH_W/du (unitless).
  double effective_slope = 0;
  /// sqrt of the pressure-weighted mean of |grad c|^2 over the contact: the slopes the small-slope
  /// half-space is asked to carry (unitless).
  double contact_slope_rms = 0;
  std::size_t contact_points = 0;  ///< nodes carrying pressure (unitless)
  std::size_t patches = 0;         ///< connected contact patches (4-neighbours) (unitless)
  double contact_fraction = 0;     ///< contact points over the overlap's nodes (unitless)
  bool converged = false;          ///< the contact solver reached its tolerance
  int iterations = 0;              ///< conjugate-gradient iterations (unitless)
};

/// Diagnostics of one load over the offsets of a map's loaded lift.
struct MapLoadedDiagnostics {
  double load = 0;                  ///< W (unit: N)
  double mean_patches = 0;          ///< contact patches per offset, mean (unitless)
  double mean_approach = 0;         ///< delta, mean over offsets (unit: m)
  double rms_contact_slope = 0;     ///< sqrt of the force-weighted mean |grad c|^2, all offsets (unitless)
  double max_contact_fraction = 0;  ///< the largest contact fraction of the overlap (unitless)
  /// Share of the offsets where more than half of the overlap's nodes are in contact: the load
  /// approaches full contact, where the roughness no longer decides the lift (unitless).
  double full_share = 0;
  std::size_t unconverged = 0;  ///< offsets whose solve did not reach the tolerance (unitless)
};

/// One line of offsets along d at a given v.
struct MapLoadedLine {
  double across = 0;                        ///< v (unit: m)
  LiftCurve rigid;                          ///< h(u) at the offsets u of the line
  std::vector<LiftCurve> curves;            ///< H_W(u) per load, on the same offsets
  std::vector<std::vector<double>> slopes;  ///< effective_slope at each offset, per load (unitless)
};

struct MapLoadedLift {
  std::vector<double> loads;                      ///< as given (unit: N)
  std::vector<MapLoadedLine> lines;               ///< in the order of `across`
  std::vector<MapLoadedDiagnostics> diagnostics;  ///< per load
  std::size_t solves = 0;                         ///< contact solves, all lines and loads (unitless)
  long iterations = 0;                            ///< conjugate-gradient iterations of them (unitless)
};

/// The block at the offset (along, across) under `load` (N). Errors (InvalidInput, naming the
/// value): E* or W not finite or <= 0, maps smaller than 2 x 2, an offset at which fewer than 2 x 2
/// nodes overlap, a failing contact solve.
Result<MapLoadedState> map_loaded_state(const Map& lower, const Map& upper, double along, double across, double load,
                                        const MapLoadedLiftOptions& options);

/// The loaded lift of every load of `options` on lines along d: for each v of `across`, the
/// offsets u = along_min + k step up to along_max (those where the maps overlap by at least 2 x 2
/// nodes, a contiguous run; an error if none), and between them the midpoints refinement adds
/// (MapLoadedLiftOptions::refine_slope; offsets in increasing order, no longer evenly spaced), one
/// contact solve per offset and load, each started from the previous solve's pressure at that load
/// (the lines run in parallel). rigid.lift is h,
/// curves[l].lift is h + (H_W - h) so that it equals h as W -> 0. Errors as map_loaded_state.
Result<MapLoadedLift> map_loaded_lift(const Map& lower, const Map& upper, const std::vector<double>& across,
                                      double along_min, double along_max, const MapLoadedLiftOptions& options);

}  // namespace frictal
