// frictal — spheropolygon engine: stability limit of the time step and the adaptive step
// (docs/dem.md sec. 3). Per dynamic body, from its contact modes: with G = sum over its contacts
// of J J^T, J = (n_x, n_y, r x n), and M = diag(m, m, I), the stiffest mode
// omega^2 = lambda_max(k_n M^-1/2 G M^-1/2) and the fastest damping rate
// c = lambda_max(gamma_n M^-1/2 G_m M^-1/2); explicit dashpots need dt < min(2/omega, 2/c),
// implicit ones dt < (c + sqrt(c^2 + 4 omega^2)) / omega^2.
#include "stability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace frictal::dem {

namespace detail {

namespace {

// Largest eigenvalue of a symmetric 3x3 matrix (closed form, Smith 1961).
double max_eigenvalue(const double a[6]) {
  const double xx = a[0], xy = a[1], xt = a[2], yy = a[3], yt = a[4], tt = a[5];
  const double q = (xx + yy + tt) / 3.0;
  const double p1 = xy * xy + xt * xt + yt * yt;
  const double p2 = (xx - q) * (xx - q) + (yy - q) * (yy - q) + (tt - q) * (tt - q) + 2.0 * p1;
  if (p2 <= 0) return q;
  const double p = std::sqrt(p2 / 6.0);
  const double bxx = (xx - q) / p, byy = (yy - q) / p, btt = (tt - q) / p, bxy = xy / p, bxt = xt / p, byt = yt / p;
  const double det = bxx * (byy * btt - byt * byt) - bxy * (bxy * btt - byt * bxt) + bxt * (bxy * byt - byy * bxt);
  const double r = std::clamp(det / 2.0, -1.0, 1.0);
  const double phi = std::acos(r) / 3.0;
  return q + 2.0 * p * std::cos(phi);
}

}  // namespace

// Stability limit of one body from its contact modes: the stiffest mode
// omega^2 = lambda_max(M^-1/2 k_n G M^-1/2) and the fastest damping rate
// lambda_max(M^-1/2 gamma_n G_m M^-1/2); explicit dashpots: dt < min(2 / omega, 2 / rate);
// implicit dashpots: see stability.hpp.
double mode_limit(const ModeSums& s, double mass, double inertia, double kn, double gn, bool implicit, double kt) {
  const double sm = 1.0 / mass, si = 1.0 / std::sqrt(mass * inertia), sii = 1.0 / inertia;
  const double scale[6] = {sm, sm, si, sm, si, sii};
  double k[6], c[6];
  for (int i = 0; i < 6; ++i) {
    k[i] = kn * s.g[i] * scale[i];
    c[i] = gn * s.gm[i] * scale[i];
  }
  const double w2 = max_eigenvalue(k);
  if (implicit) {
    // Scalar mode x'' = -omega^2 x - c x' under the kicks of integrator.cpp:
    // v' = v + dt (-omega^2 x - c v) / (1 + c dt), x' = x + dt v'; stable iff
    // omega^2 dt^2 < 2 (2 + c dt).
    const double c_low = gn * s.mred_min * w2 / kn;
    double limit =
        w2 > 0 ? (c_low + std::sqrt(c_low * c_low + 4.0 * w2)) / w2 : std::numeric_limits<double>::infinity();
    if (kt > 0) {
      double t[6];
      for (int i = 0; i < 6; ++i) t[i] = kt * s.gt[i] * scale[i];
      const double wt2 = max_eigenvalue(t);
      if (wt2 > 0) limit = std::min(limit, 2.0 / std::sqrt(wt2));
    }
    return limit;
  }
  double limit = w2 > 0 ? 2.0 / std::sqrt(w2) : std::numeric_limits<double>::infinity();
  const double rate = max_eigenvalue(c);
  if (rate > 0) limit = std::min(limit, 2.0 / rate);
  return limit;
}

void update_step_limits(const Model& m, State& st, const Workspace& ws) {
  const double kn = m.def.contact.normal_stiffness, gn = m.def.contact.normal_damping;
  const bool implicit = m.def.implicit_damping;
  const ContactParams& cp = m.def.contact;
  const double kt = implicit && cp.atomic_friction > 0 ? cp.tangential_stiffness : 0.0;
  for (std::size_t b = 0; b < m.body_count(); ++b)
    st.step_limit[b] = ws.inv_mass[b] > 0 && ws.body_contacts[b] > 0
                           ? mode_limit(ws.modes[b], m.mass[b], m.inertia[b], kn, gn, implicit, kt)
                           : std::numeric_limits<double>::infinity();
}

void choose_time_step(const Model& m, State& st) {
  double dt = m.def.time_step;
  const double skin = m.def.skin;
  const double kn = m.def.contact.normal_stiffness, gn = m.def.contact.normal_damping;
  for (std::size_t b = 0; b < m.body_count(); ++b) {
    if (m.type[b] != BodyType::Dynamic) continue;
    // The contacts present, and one more: the first step of a new contact is taken with the step
    // chosen before it (its stiffest mode: one contact at the body's extent, kinematic partner).
    const double e = m.extent[b];
    double one_more = 2.0 / std::sqrt(kn * std::max(1.0 / m.mass[b], e * e / m.inertia[b]));
    if (!m.def.implicit_damping && gn > 0) one_more = std::min(one_more, 2.0 / gn);
    dt = std::min(dt, m.def.time_step_safety * std::min(st.step_limit[b], one_more));
    // Keep the motion per step well inside the skin (the list check wants <= skin / 2).
    const double speed =
        std::hypot(st.velocity[b].x, st.velocity[b].y) + std::fabs(st.angular_velocity[b]) * m.extent[b];
    if (skin > 0 && speed * dt > 0.25 * skin) dt = 0.25 * skin / speed;
  }
  st.time_step = dt;
}

}  // namespace detail

double stability_limit(const Model& m, std::size_t b, int contacts) {
  if (contacts <= 0) return std::numeric_limits<double>::infinity();
  const double n = contacts;
  const double e = m.extent[b];
  const double w2 = n * m.def.contact.normal_stiffness * std::max(1.0 / m.mass[b], e * e / m.inertia[b]);
  double limit = 2.0 / std::sqrt(w2);
  // The reduced mass is at most the body's mass, so each dashpot adds at most gamma_n to the rate.
  if (m.def.contact.normal_damping > 0) limit = std::min(limit, 2.0 / (n * m.def.contact.normal_damping));
  return limit;
}

double suggested_time_step(const Model& m, int contacts) {
  double dt = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < m.body_count(); ++b)
    if (m.type[b] == BodyType::Dynamic) dt = std::min(dt, 0.5 * stability_limit(m, b, std::max(1, contacts)));
  return dt;
}

}  // namespace frictal::dem
