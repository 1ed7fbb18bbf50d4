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
double apply_force_law(const Model& m, State& st, Workspace& ws, double dt_spring);

}  // namespace frictal::dem::detail
