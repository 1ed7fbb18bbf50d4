// frictal — spheropolygon engine: the contact force law (paper Eq. 7-11, docs/dem.md sec. 1) for
// the touching vertex-edge pairs, and the sums per body.
//   normal:     f_n = k_n overlap - m gamma_n v_n
//   tangential: f_t = -k_t xi - m gamma_t v_t, xi <- xi + v_t dt cut back to |k_t xi| <= mu_a k_n overlap
// Two passes in list order (docs/dem.md sec. 7): the forces of the touching pairs, each
// independent of the others so that the long sqrt / division chains of successive contacts can
// overlap; then the sums per body in the same order as a single loop, so the results are
// bitwise those of one loop over the pairs. With threads (dem::set_thread_count) the force pass
// runs on contiguous shares of the touching pairs at once, and the sums stay one serial loop over
// the shares in order (the elastic energy too: each pair's term is stored, then summed).
#include "force_law.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "stability.hpp"

namespace frictal::dem::detail {

namespace {

double cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// The force pass; kHertz: the Hertz law (ContactLaw::Hertz), else the linear law of Eq. 8-11
// (a separate instance, so that the linear law's arithmetic is the same as without the other).
template <bool kHertz>
void pair_forces_law(const Model& m, State& st, Workspace& ws, double dt_spring, std::size_t k0, std::size_t k1,
                     double& max_overlap, double& max_ratio) {
  const ContactParams& cp = m.def.contact;
  const Pose* const ps = ws.pose.data();
  double max_ov = max_overlap, max_r = max_ratio;
  // Local copies of everything the loop reads, so that the force stores cannot alias them.
  const double* const __restrict radius = m.radius.data();
  const double kn = cp.normal_stiffness, kt = cp.tangential_stiffness, mu = cp.atomic_friction;
  const double gn = cp.normal_damping, gt = cp.tangential_damping;
  const double guard = m.def.max_overlap_ratio;
  NeighborPair* const pairs = st.pairs.data();
  ContactScratch* const touching = ws.touching.data();
  for (std::size_t k = k0; k < k1; ++k) {
    ContactScratch& c = touching[k];
    NeighborPair& p = pairs[c.pair];
    const std::uint32_t a = p.vbody, b = p.ebody;
    const double rsum = radius[a] + radius[b];
    const double vx = c.vx, vy = c.vy, dx = c.dx, dy = c.dy;
    const Pose& A = ps[a];
    const Pose& B = ps[b];
    const double dist = std::sqrt(c.dist2);
    double nx, ny;
    if (dist > 0) {
      const double inv = 1.0 / dist;
      nx = c.sx * inv, ny = c.sy * inv;
    } else {  // vertex exactly on the edge: outward normal of the (counter-clockwise) edge
      const double l = std::sqrt(dx * dx + dy * dy);
      nx = dy / l, ny = -dx / l;
    }
    const double overlap = rsum - dist;
    max_ov = std::max(max_ov, overlap);
    if (overlap > guard * rsum) max_r = std::max(max_r, overlap / rsum);  // rare
    // Contact point: middle of the overlap along the normal.
    const double cxp = vx - nx * (radius[a] - 0.5 * overlap);
    const double cyp = vy - ny * (radius[a] - 0.5 * overlap);
    const double rax = cxp - A.px, ray = cyp - A.py, rbx = cxp - B.px, rby = cyp - B.py;
    const double wa = st.angular_velocity[a], wb = st.angular_velocity[b];
    const double relx = (st.velocity[a].x - wa * ray) - (st.velocity[b].x - wb * rby);
    const double rely = (st.velocity[a].y + wa * rax) - (st.velocity[b].y + wb * rbx);
    const double tx = -ny, ty = nx;
    const double vn = relx * nx + rely * ny;
    const double vt = relx * tx + rely * ty;
    const double mred = p.reduced_mass;
    double fn_el, kt_c, damping;  // elastic normal force, tangential stiffness, normal dashpot
    if constexpr (kHertz) {
      const HertzPair h = hertz_pair(m, p.vertex, p.edge0, p.edge1, c.t, overlap, mred);
      fn_el = h.force;
      kt_c = h.tangential_stiffness;
      damping = h.damping;
      c.k_normal = h.stiffness;
      c.damping = h.damping;
      c.k_tangential = h.tangential_stiffness;
    } else {
      fn_el = kn * overlap;
      kt_c = kt;
      damping = 0;
    }
    double xi = p.elongation + vt * dt_spring;
    double ft_el = -kt_c * xi;
    const double limit = mu * fn_el;
    if (std::fabs(ft_el) > limit) {
      ft_el = ft_el > 0 ? limit : -limit;
      xi = kt_c > 0 ? -ft_el / kt_c : 0.0;
    }
    // Elastic energy of the normal spring: k_n overlap^2 / 2, or (2/5) f_n overlap for Hertz.
    const double en = kHertz ? 0.4 * fn_el * overlap : 0.5 * fn_el * overlap;
    const double fd = kHertz ? damping * vn : mred * gn * vn;
    double fn, ft;
    if (c.weight > 0) {
      p.elongation = xi;
      p.overlap = overlap;
      c.energy = en + 0.5 * kt_c * xi * xi;  // summed in list order below
      fn = fn_el - fd;
      ft = ft_el - mred * gt * vt;
    } else {  // the vertex-vertex term subtracted at a concave corner (rule closest): normal only
      c.energy = -en;
      fn = -(fn_el - fd);
      ft = 0;
    }
    const double fx = fn * nx + ft * tx, fy = fn * ny + ft * ty;
    c.fx = fx, c.fy = fy;
    c.torque_a = cross(rax, ray, fx, fy);
    c.torque_b = cross(rbx, rby, fx, fy);
    c.nx = nx, c.ny = ny;
    c.jt_a = cross(rax, ray, nx, ny);
    c.jt_b = cross(rbx, rby, nx, ny);
    c.jtt_a = cross(rax, ray, tx, ty);
    c.jtt_b = cross(rbx, rby, tx, ty);
    c.mred = mred;
  }
  max_overlap = max_ov;
  max_ratio = max_r;
}

}  // namespace

void pair_forces(const Model& m, State& st, Workspace& ws, double dt_spring, std::size_t k0, std::size_t k1,
                 double& max_overlap, double& max_ratio) {
  if (m.def.contact.law == ContactLaw::Hertz)
    pair_forces_law<true>(m, st, ws, dt_spring, k0, k1, max_overlap, max_ratio);
  else
    pair_forces_law<false>(m, st, ws, dt_spring, k0, k1, max_overlap, max_ratio);
}

double sum_contacts(const Model& m, State& st, Workspace& ws, double max_ov, double max_ratio) {
  const ContactParams& cp = m.def.contact;
  const double* const inv_mass_of = ws.inv_mass.data();
  int* const body_contacts = ws.body_contacts.data();
  ModeSums* const jac = ws.modes.data();
  const double kt = cp.tangential_stiffness, mu = cp.atomic_friction;
  // The tangential springs enter the stability limit of the implicit-damping scheme only; they
  // act only with mu_a > 0 (else they are cut back to zero).
  const bool hertz = cp.law == ContactLaw::Hertz;
  const bool tangential_modes = m.def.implicit_damping && (hertz ? cp.tangential_ratio : kt) > 0 && mu > 0;
  const NeighborPair* const pairs = st.pairs.data();
  const ContactScratch* const touching = ws.touching.data();
  double energy = 0;
  // Sums per body. The force and torque sums and mode matrices of the two bodies of the current
  // run of pairs with the same (vertex body, edge body) are kept in locals rather than summed
  // into memory contact by contact: same additions in the same order.
  struct BodySums {
    double fx = 0, fy = 0, torque = 0;
    ModeSums modes;
  };
  BodySums sa, sb;
  std::uint32_t cur_a = 0, cur_b = 0;
  bool have_run = false;
  auto flush = [&]() {
    if (!have_run) return;
    st.force[cur_a] = {sa.fx, sa.fy};
    st.torque[cur_a] = sa.torque;
    jac[cur_a] = sa.modes;
    st.force[cur_b] = {sb.fx, sb.fy};
    st.torque[cur_b] = sb.torque;
    jac[cur_b] = sb.modes;
  };
  std::size_t n_touching = 0;
  for (const Segment& seg : ws.segments) {
    for (std::size_t k = seg.begin; k < seg.begin + seg.count; ++k) {
      const ContactScratch& c = touching[k];
      energy += c.energy;
      const NeighborPair& p = pairs[c.pair];
      const std::uint32_t a = p.vbody, b = p.ebody;
      const bool contact = c.weight > 0;  // not the term subtracted at a concave corner
      body_contacts[a] += contact;
      body_contacts[b] += contact;
      n_touching += contact;
      if (!have_run || a != cur_a || b != cur_b) {
        flush();
        cur_a = a, cur_b = b, have_run = true;
        sa = {st.force[a].x, st.force[a].y, st.torque[a], jac[a]};
        sb = {st.force[b].x, st.force[b].y, st.torque[b], jac[b]};
      }
      sa.fx += c.fx;
      sa.fy += c.fy;
      sa.torque += c.torque_a;
      sb.fx -= c.fx;
      sb.fy -= c.fy;
      sb.torque -= c.torque_b;
      // Normal-mode matrices sum J J^T, J = (n_x, n_y, r x n), for the stability limit.
      if (!contact) continue;  // its stiffness is less than its flanks' (the limit stays safe)
      if (hertz) {             // each contact's own stiffnesses and dashpot as the weights (stability.hpp)
        if (inv_mass_of[a] > 0) add_outer_weighted(sa.modes, c.nx, c.ny, c.jt_a, c.k_normal, c.damping);
        if (inv_mass_of[b] > 0) add_outer_weighted(sb.modes, c.nx, c.ny, c.jt_b, c.k_normal, c.damping);
        if (tangential_modes) {
          if (inv_mass_of[a] > 0) add_outer_tangential(sa.modes, -c.ny, c.nx, c.jtt_a, c.k_tangential);
          if (inv_mass_of[b] > 0) add_outer_tangential(sb.modes, -c.ny, c.nx, c.jtt_b, c.k_tangential);
        }
        continue;
      }
      if (inv_mass_of[a] > 0) add_outer(sa.modes, c.nx, c.ny, c.jt_a, c.mred);
      if (inv_mass_of[b] > 0) add_outer(sb.modes, c.nx, c.ny, c.jt_b, c.mred);
      if (tangential_modes) {  // J_t = (t_x, t_y, r x t), t = (-n_y, n_x)
        if (inv_mass_of[a] > 0) add_outer_tangential(sa.modes, -c.ny, c.nx, c.jtt_a);
        if (inv_mass_of[b] > 0) add_outer_tangential(sb.modes, -c.ny, c.nx, c.jtt_b);
      }
    }
  }
  flush();
  st.contact_count = static_cast<int>(n_touching);
  st.max_overlap = max_ov;
  st.elastic_energy = energy;
  return max_ratio;
}

double apply_force_law(const Model& m, State& st, Workspace& ws, double dt_spring) {
  double max_ov = 0, max_ratio = 0;
  pair_forces(m, st, ws, dt_spring, 0, ws.touching_count, max_ov, max_ratio);
  return sum_contacts(m, st, ws, max_ov, max_ratio);
}

}  // namespace frictal::dem::detail
