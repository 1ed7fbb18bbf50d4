// frictal — spheropolygon engine, private: time integration (velocity Verlet, kick-drift-kick),
// kinematic bodies and the evaluation of the contact forces at the current poses.
#pragma once

#include <cstddef>

#include "frictal/dem.hpp"
#include "workspace.hpp"

namespace frictal::dem::detail {

/// Sets the prescribed pose and velocity of kinematic body b at time t (unit: s).
void kinematic_pose(const Model& m, std::size_t b, double t, State& st);

/// Dynamic bodies with BodyDef::rotation_follows >= 0 take the angle and angular velocity of
/// their (kinematic) leader, whose pose must be current.
void follow_rotations(const Model& m, State& st);

/// ws.rotation = cos and sin of every body's State::angle.
void update_rotation(const State& st, Workspace& ws);

/// Contact forces, torques, contact counts and stability limits at the current poses and
/// velocities: contact geometry, force law, stability limit. `dt_spring`: time over which the
/// tangential springs are stretched (unit: s; dt in a step, 0 for the initial evaluation).
/// Returns the largest overlap / (r1 + r2) among pairs above max_overlap_ratio, else 0.
double compute_forces(const Model& m, State& st, Workspace& ws, double dt_spring);

}  // namespace frictal::dem::detail
