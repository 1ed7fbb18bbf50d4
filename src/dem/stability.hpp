// frictal — spheropolygon engine, private: the explicit stability limit of the time step from
// each body's contact modes (docs/dem.md sec. 3).
#pragma once

#include <limits>

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
  s.mred_min = w < s.mred_min ? w : s.mred_min;
}

/// Adds J_t J_t^T, J_t = (tx, ty, jt), to the tangential mode sum (times `w`, the Hertz law's
/// tangential stiffness in N/m; 1 for the linear law, whose k_t multiplies the sum).
inline void add_outer_tangential(ModeSums& s, double tx, double ty, double jt, double w = 1) {
  const double v[6] = {tx * tx, tx * ty, tx * jt, ty * ty, ty * jt, jt * jt};
  if (w == 1) {
    for (int i = 0; i < 6; ++i) s.gt[i] += v[i];
  } else {
    for (int i = 0; i < 6; ++i) s.gt[i] += w * v[i];
  }
}

/// The Hertz law's mode sums: J J^T weighted by the contact's tangent stiffness k (N/m) in g and
/// by its dashpot coefficient eta (kg/s) in gm, and mred_min the smallest eta / k (unit: s); the
/// limit then takes kn = gn = 1 (mode_limit).
inline void add_outer_weighted(ModeSums& s, double jx, double jy, double jt, double k, double eta) {
  const double v[6] = {jx * jx, jx * jy, jx * jt, jy * jy, jy * jt, jt * jt};
  for (int i = 0; i < 6; ++i) {
    s.g[i] += k * v[i];
    s.gm[i] += eta * v[i];
  }
  const double ratio = k > 0 ? eta / k : std::numeric_limits<double>::infinity();
  s.mred_min = ratio < s.mred_min ? ratio : s.mred_min;
}

/// Stability limit of one body's time step from its mode sums (unit: s): mass in kg, inertia in
/// kg m^2, kn in N/m, gn in 1/s. Explicit dashpots: min(2 / omega, 2 / c). Implicit dashpots
/// (`implicit`): (c + sqrt(c^2 + 4 omega^2)) / omega^2, the limit of the scheme for a mode of
/// frequency omega and damping rate c, with c = gn mred_min omega^2 / kn (the damping of the
/// stiffest mode is at least that; exact when every contact has the same reduced mass), and at
/// most 2 / omega_t, omega_t^2 = lambda_max(kt M^-1/2 G_t M^-1/2) for the (explicit, weakly damped)
/// tangential springs (kt in N/m; pass 0 when they do not act).
double mode_limit(const ModeSums& s, double mass, double inertia, double kn, double gn, bool implicit, double kt);

/// State::step_limit of every body from ws.modes and ws.body_contacts (infinite for kinematic
/// bodies and bodies without contacts).
void update_step_limits(const Model& m, State& st, const Workspace& ws);

/// Adaptive time step (WorldDef::adaptive_time_step): State::time_step = the smallest of
/// WorldDef::time_step; time_step_safety x the smaller of State::step_limit and the limit of one
/// new contact, for each dynamic body; and the step in which a dynamic body moves a quarter of the
/// skin.
void choose_time_step(const Model& m, State& st);

}  // namespace frictal::dem::detail
