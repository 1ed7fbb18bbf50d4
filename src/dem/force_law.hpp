// frictal — spheropolygon engine, private: the contact force law of Eq. 7-11 and the sums of the
// forces, torques and mode matrices per body.
#pragma once

#include <cmath>
#include <cstdint>

#include "frictal/dem.hpp"
#include "workspace.hpp"

namespace frictal::dem::detail {

/// The Hertz law (ContactLaw::Hertz) of one touching pair.
struct HertzPair {
  double radius = 0;                ///< composite radius of curvature R (unit: m)
  double force = 0;                 ///< elastic normal force (4/3) E* sqrt(R) overlap^(3/2) (unit: N)
  double stiffness = 0;             ///< tangent stiffness k = 2 E* sqrt(R overlap) (unit: N/m)
  double damping = 0;               ///< dashpot coefficient 2 zeta sqrt(m k) (unit: kg/s)
  double tangential_stiffness = 0;  ///< tangential_ratio x k (unit: N/m)
};

/// The Hertz law of vertex `vertex` against the edge (edge0, edge1) whose closest point lies at
/// `t` in [0, 1] along it: R from the vertex's curvature radius, and at an end of the edge (t = 0
/// or 1: two corners touch) also that end's (1/R = 1/R_1 + 1/R_2); `mred` the reduced mass (kg),
/// `overlap` in m (<= 0: no force). Inline: once per touching pair and step.
inline HertzPair hertz_pair(const Model& m, std::uint32_t vertex, std::uint32_t edge0, std::uint32_t edge1, double t,
                            double overlap, double mred) {
  const ContactParams& cp = m.def.contact;
  double inv = 1.0 / m.curvature_radius[vertex];
  if (t <= 0)
    inv += 1.0 / m.curvature_radius[edge0];
  else if (t >= 1)
    inv += 1.0 / m.curvature_radius[edge1];
  HertzPair h;
  h.radius = 1.0 / inv;
  const double d = overlap > 0 ? overlap : 0.0;
  h.stiffness = 2.0 * cp.contact_modulus * std::sqrt(h.radius * d);
  h.force = (2.0 / 3.0) * h.stiffness * d;
  h.damping = 2.0 * cp.damping_ratio * std::sqrt(mred * h.stiffness);
  h.tangential_stiffness = cp.tangential_ratio * h.stiffness;
  return h;
}

/// Forces of the touching pairs found by find_touching (ws.touching), their springs advanced by
/// `dt_spring` (unit: s; 0 for the initial evaluation), then summed per body into State::force,
/// State::torque (zeroed beforehand by the caller), ws.body_contacts and ws.modes, in list order.
/// Sets State::contact_count, max_overlap and elastic_energy. Returns the largest
/// overlap / (r1 + r2) among pairs above max_overlap_ratio, else 0.
/// (pair_forces over [0, ws.touching_count), then sum_contacts.)
double apply_force_law(const Model& m, State& st, Workspace& ws, double dt_spring);

/// The force pass alone over ws.touching[k0, k1): each pair's force, torques, mode-matrix terms
/// and elastic energy into its ContactScratch, its spring and overlap into State::pairs;
/// `max_overlap` and `max_ratio` (see apply_force_law) raised to those of the range. Passes
/// over disjoint ranges write disjoint data, so they may run at the same time.
void pair_forces(const Model& m, State& st, Workspace& ws, double dt_spring, std::size_t k0, std::size_t k1,
                 double& max_overlap, double& max_ratio);

/// The sums of apply_force_law over the touching pairs of ws.segments, in order (serial: every
/// floating-point sum in list order); `max_overlap` and `max_ratio` are those of the force passes.
/// Returns max_ratio.
double sum_contacts(const Model& m, State& st, Workspace& ws, double max_overlap, double max_ratio);

}  // namespace frictal::dem::detail
