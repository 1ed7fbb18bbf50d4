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
  double kn = m.def.contact.normal_stiffness, gn = m.def.contact.normal_damping;
  const bool implicit = m.def.implicit_damping;
  const ContactParams& cp = m.def.contact;
  double kt = implicit && cp.atomic_friction > 0 ? cp.tangential_stiffness : 0.0;
  if (cp.law == ContactLaw::Hertz) {  // the mode sums carry each contact's k and dashpot
    kn = 1, gn = 1;
    kt = implicit && cp.atomic_friction > 0 && cp.tangential_ratio > 0 ? 1.0 : 0.0;
  }
  for (std::size_t b = 0; b < m.body_count(); ++b)
    st.step_limit[b] = ws.inv_mass[b] > 0 && ws.body_contacts[b] > 0
                           ? mode_limit(ws.modes[b], m.mass[b], m.inertia[b], kn, gn, implicit, kt)
                           : std::numeric_limits<double>::infinity();
}

void choose_time_step(const Model& m, State& st) {
  double dt = m.def.time_step;
  const double skin = m.def.skin;
  const double gn = m.def.contact.normal_damping;
  const bool hertz = m.def.contact.law == ContactLaw::Hertz;
  const double zeta = m.def.contact.damping_ratio;
  for (std::size_t b = 0; b < m.body_count(); ++b) {
    if (m.type[b] != BodyType::Dynamic) continue;
    // The contacts present, and one more: the first step of a new contact is taken with the step
    // chosen before it (its stiffest mode: one contact at the body's extent, kinematic partner).
    // Hertz: a new contact starts at zero stiffness and stiffens with its overlap, which the
    // modes of the contacts present follow step by step; one more is one contact on the sharpest
    // vertex at the body's weight or the largest overlap present (contact_stiffness).
    const double e = m.extent[b];
    const double kn = contact_stiffness(m, b, st.max_overlap);
    const double w2 = kn * std::max(1.0 / m.mass[b], e * e / m.inertia[b]);
    double one_more = 2.0 / std::sqrt(w2);
    if (hertz) {
      if (!(w2 > 0)) one_more = std::numeric_limits<double>::infinity();
      if (!m.def.implicit_damping && zeta > 0 && w2 > 0) one_more = std::min(one_more, 1.0 / (zeta * std::sqrt(w2)));
    } else if (!m.def.implicit_damping && gn > 0) {
      one_more = std::min(one_more, 2.0 / gn);
    }
    dt = std::min(dt, m.def.time_step_safety * std::min(st.step_limit[b], one_more));
    // Keep the motion per step well inside the skin (the list check wants <= skin / 2).
    const double speed =
        std::hypot(st.velocity[b].x, st.velocity[b].y) + std::fabs(st.angular_velocity[b]) * m.extent[b];
    if (skin > 0 && speed * dt > 0.25 * skin) dt = 0.25 * skin / speed;
  }
  st.time_step = dt;
}

}  // namespace detail

double contact_stiffness(const Model& m, std::size_t b, double overlap) {
  const ContactParams& cp = m.def.contact;
  if (cp.law != ContactLaw::Hertz) return cp.normal_stiffness;
  double c = std::numeric_limits<double>::infinity();  // the softest coefficient of any body
  for (const double ci : m.hertz_coeff_min) c = std::min(c, ci);
  if (!std::isfinite(c)) return 0;
  const double weight = m.mass[b] * std::hypot(m.def.gravity.x, m.def.gravity.y);
  // f = c d^1.5 = W  =>  k = 1.5 c sqrt(d) = 1.5 c^(2/3) W^(1/3)
  const double k_weight = 1.5 * std::cbrt(c * c * weight);
  const double k_overlap = overlap > 0 ? 1.5 * c * std::sqrt(overlap) : 0.0;
  return std::max(k_weight, k_overlap);
}

double hertz_overlap(double force, double contact_modulus, double radius) {
  return std::cbrt(std::pow(3.0 * force / (4.0 * contact_modulus * std::sqrt(radius)), 2.0));
}

double stability_limit(const Model& m, std::size_t b, int contacts) {
  if (contacts <= 0) return std::numeric_limits<double>::infinity();
  const double n = contacts;
  const double e = m.extent[b];
  if (m.def.contact.law == ContactLaw::Hertz) {
    const double w2 = n * contact_stiffness(m, b, 0) * std::max(1.0 / m.mass[b], e * e / m.inertia[b]);
    if (!(w2 > 0)) return std::numeric_limits<double>::infinity();
    double limit = 2.0 / std::sqrt(w2);
    const double zeta = m.def.contact.damping_ratio;
    if (zeta > 0) limit = std::min(limit, 1.0 / (zeta * std::sqrt(n * w2)));
    return limit;
  }
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
