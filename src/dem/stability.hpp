// frictal — spheropolygon engine, private: the explicit stability limit of the time step from
// each body's contact modes (docs/dem.md sec. 3).
#pragma once

#include "frictal/dem.hpp"
#include "workspace.hpp"

namespace frictal::dem::detail {

/// Adds J J^T, J = (jx, jy, jt), to the mode sums: unweighted and weighted by `w` (the reduced
/// mass, unit: kg). Inline: called once per contact and body in the force law's sums.
inline void add_outer(ModeSums& s, double jx, double jy, double jt, double w) {
  const double v[6] = {jx * jx, jx * jy, jx * jt, jy * jy, jy * jt, jt * jt};
  for (int i = 0; i < 6; ++i) {
    s.g[i] += v[i];
    s.gm[i] += w * v[i];
  }
}

/// Explicit stability limit of one body from its mode sums (unit: s): mass in kg, inertia in
/// kg m^2, kn in N/m, gn in 1/s.
double mode_limit(const ModeSums& s, double mass, double inertia, double kn, double gn);

/// State::step_limit of every body from ws.modes and ws.body_contacts (infinite for kinematic
/// bodies and bodies without contacts).
void update_step_limits(const Model& m, State& st, const Workspace& ws);

}  // namespace frictal::dem::detail
