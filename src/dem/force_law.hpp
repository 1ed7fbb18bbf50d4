// frictal — spheropolygon engine, private: the contact force law of Eq. 7-11 and the sums of the
// forces, torques and mode matrices per body.
#pragma once

#include "frictal/dem.hpp"
#include "workspace.hpp"

namespace frictal::dem::detail {

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
