// The 3D tilt test of two areal blocks on MuJoCo (frictal/areal_tilt.hpp; docs/mujoco.md): the
// model (a height field and a body of spheres on three slide joints) is written as MJCF into
// MuJoCo's virtual file system, the heights are set in the compiled model, and the quasi-static
// tilt protocol runs on mj_step. Without FRICTAL_HAVE_MUJOCO only the NotAvailable answer is built.
#include <fmt/core.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <numbers>
#include <string>
#include <vector>

#include "frictal/areal_tilt.hpp"
#include "maphold/map_hold_geometry.hpp"

#ifdef FRICTAL_HAVE_MUJOCO
#include <mujoco/mujoco.h>
#endif

namespace frictal {

#ifndef FRICTAL_HAVE_MUJOCO

bool mujoco_available() { return false; }

Result<ArealTiltResult> areal_tilt(const Map&, const Map&, const ArealTiltOptions&, const ArealTiltProgress&) {
  return make_error(ErrorCode::NotAvailable,
                    "areal-tilt needs MuJoCo: install Debian's libmujoco-dev (scripts/install-deps does) and "
                    "rebuild with FRICTAL_MUJOCO=ON or AUTO");
}

#else

bool mujoco_available() { return true; }

namespace {

/// Owns the MuJoCo objects of one run.
struct Sim {
  mjVFS vfs;
  mjModel* m = nullptr;
  mjData* d = nullptr;
  Sim() { mj_defaultVFS(&vfs); }
  ~Sim() {
    if (d) mj_deleteData(d);
    if (m) mj_deleteModel(m);
    mj_deleteVFS(&vfs);
  }
  Sim(const Sim&) = delete;
  Sim& operator=(const Sim&) = delete;
};

// The exact sphere-triangle contact for the (height field, sphere) pair (docs/mujoco.md): MuJoCo
// 2.2.2's own (mjc_ConvexHField) runs MPR on prisms, each triangle extruded down to the field's
// base, and a sphere that crosses from one prism into the next meets the next prism's vertical
// side first: a horizontal contact (an internal edge) that holds the block on a surface that is
// straight along its path. This one finds, for each of the same triangles (the same diagonal),
// the point nearest the sphere's centre, and makes one contact per distinct nearest point with
// the normal from that point to the centre: the surface that areal_tilt_lift evaluates. Chosen
// per model by the height field geom's user value 1 (nuser_geom = 1); other models go to the
// function it replaced, so the table entry can be set once for the process.
mjfCollision g_native_hfield_sphere = nullptr;

/// The point of triangle abc nearest to p (Ericson, Real-Time Collision Detection, 5.1.5).
void nearest_on_triangle(const mjtNum* p, const mjtNum* a, const mjtNum* b, const mjtNum* c, mjtNum* q) {
  mjtNum ab[3], ac[3], ap[3];
  mju_sub3(ab, b, a);
  mju_sub3(ac, c, a);
  mju_sub3(ap, p, a);
  const mjtNum d1 = mju_dot3(ab, ap), d2 = mju_dot3(ac, ap);
  if (d1 <= 0 && d2 <= 0) return mju_copy3(q, a);
  mjtNum bp[3];
  mju_sub3(bp, p, b);
  const mjtNum d3 = mju_dot3(ab, bp), d4 = mju_dot3(ac, bp);
  if (d3 >= 0 && d4 <= d3) return mju_copy3(q, b);
  const mjtNum vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const mjtNum v = d1 / (d1 - d3);
    for (int i = 0; i < 3; ++i) q[i] = a[i] + v * ab[i];
    return;
  }
  mjtNum cp[3];
  mju_sub3(cp, p, c);
  const mjtNum d5 = mju_dot3(ab, cp), d6 = mju_dot3(ac, cp);
  if (d6 >= 0 && d5 <= d6) return mju_copy3(q, c);
  const mjtNum vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const mjtNum w = d2 / (d2 - d6);
    for (int i = 0; i < 3; ++i) q[i] = a[i] + w * ac[i];
    return;
  }
  const mjtNum va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const mjtNum w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    for (int i = 0; i < 3; ++i) q[i] = b[i] + w * (c[i] - b[i]);
    return;
  }
  const mjtNum denom = 1 / (va + vb + vc);
  const mjtNum v = vb * denom, w = vc * denom;
  for (int i = 0; i < 3; ++i) q[i] = a[i] + ab[i] * v + ac[i] * w;
}

int exact_hfield_sphere(const mjModel* m, const mjData* d, mjContact* con, int g1, int g2, mjtNum margin) {
  if (m->nuser_geom < 1 || m->geom_user[g1 * m->nuser_geom] != 1)
    return g_native_hfield_sphere ? g_native_hfield_sphere(m, d, con, g1, g2, margin) : 0;
  const int hid = m->geom_dataid[g1];
  const int nrow = m->hfield_nrow[hid], ncol = m->hfield_ncol[hid];
  const mjtNum* size = m->hfield_size + 4 * hid;
  const float* data = m->hfield_data + m->hfield_adr[hid];
  const mjtNum* pos1 = d->geom_xpos + 3 * g1;
  const mjtNum* mat1 = d->geom_xmat + 9 * g1;
  const mjtNum rs = m->geom_size[3 * g2];
  // The sphere's centre in the height field's frame.
  mjtNum v[3], c[3];
  mju_sub3(v, d->geom_xpos + 3 * g2, pos1);
  mju_mulMatTVec(c, mat1, v, 3, 3);
  const mjtNum dx = 2 * size[0] / (ncol - 1), dy = 2 * size[1] / (nrow - 1);
  const mjtNum reach = rs + margin;
  const int c0 = std::max(0, int(std::floor((c[0] - reach + size[0]) / dx)));
  const int c1 = std::min(ncol - 2, int(std::floor((c[0] + reach + size[0]) / dx)));
  const int r0 = std::max(0, int(std::floor((c[1] - reach + size[1]) / dy)));
  const int r1 = std::min(nrow - 2, int(std::floor((c[1] + reach + size[1]) / dy)));
  int cnt = 0;
  for (int r = r0; r <= r1; ++r)
    for (int cc = c0; cc <= c1; ++cc) {
      auto vert = [&](int i, int j, mjtNum* out) {
        out[0] = dx * i - size[0];
        out[1] = dy * j - size[1];
        out[2] = mjtNum(data[j * ncol + i]) * size[2];
      };
      mjtNum p00[3], p10[3], p01[3], p11[3];
      vert(cc, r, p00);
      vert(cc + 1, r, p10);
      vert(cc, r + 1, p01);
      vert(cc + 1, r + 1, p11);
      if (c[2] - reach > std::max({p00[2], p10[2], p01[2], p11[2]})) continue;
      // MuJoCo's two triangles of the cell: {(c, r+1), (c, r), (c+1, r+1)}, {(c, r), (c+1, r+1), (c+1, r)}.
      const mjtNum* tri[2][3] = {{p01, p00, p11}, {p00, p11, p10}};
      for (auto& t : tri) {
        mjtNum q[3], n[3];
        nearest_on_triangle(c, t[0], t[1], t[2], q);
        mju_sub3(n, c, q);
        const mjtNum dist = mju_normalize3(n) - rs;
        if (dist >= margin) continue;
        if (mju_norm3(n) < 0.5) continue;  // the centre on the surface: no direction
        if (n[2] <= 0) continue;           // below the surface: another triangle holds it
        bool seen = false;                 // one contact per nearest point (shared edges, vertices)
        for (int k = 0; k < cnt && !seen; ++k) {
          mjtNum e[3], qk[3];
          mju_sub3(e, con[k].pos, pos1);
          mju_mulMatTVec(qk, mat1, e, 3, 3);
          // con[k].pos is the midpoint: back to its nearest point.
          mjtNum nk[3];
          mju_mulMatTVec(nk, mat1, con[k].frame, 3, 3);
          for (int i = 0; i < 3; ++i) qk[i] -= 0.5 * con[k].dist * nk[i];
          mju_sub3(e, qk, q);
          seen = mju_dot3(e, e) < 1e-18 * rs * rs;
        }
        if (seen || cnt >= mjMAXCONPAIR) continue;
        mjContact& k = con[cnt++];
        k.dist = dist;
        mjtNum mid[3];
        for (int i = 0; i < 3; ++i) mid[i] = q[i] + 0.5 * dist * n[i];
        mju_rotVecMat(k.pos, mid, mat1);
        mju_addTo3(k.pos, pos1);
        mju_rotVecMat(k.frame, n, mat1);
        mju_zero3(k.frame + 3);
      }
    }
  return cnt;
}

std::once_flag g_install_once;
void install_exact_hfield_sphere() {
  std::call_once(g_install_once, [] {
    g_native_hfield_sphere = mjCOLLISIONFUNC[mjGEOM_HFIELD][mjGEOM_SPHERE];
    mjCOLLISIONFUNC[mjGEOM_HFIELD][mjGEOM_SPHERE] = exact_hfield_sphere;
  });
}

}  // namespace

Result<ArealTiltResult> areal_tilt(const Map& f, const Map& g, const ArealTiltOptions& o,
                                   const ArealTiltProgress& progress) {
  if (std::isfinite(o.angle) && (detail::direction_quarters(o.angle) != 0 || f.x0 != 0 || f.y0 != 0)) {
    // In the frame of the direction, as the matched prediction (detail::TurnedExperiment): the
    // same triangles of the height field for the same experiment turned by quarter turns.
    const detail::TurnedExperiment e(f, g, o);
    ArealTiltProgress back;
    if (progress)
      back = [&](const ArealTiltIncrement& i) {
        ArealTiltIncrement c = i;
        const auto p = e.back({i.x, i.y});
        c.x = p[0];
        c.y = p[1];
        progress(c);
      };
    auto r = areal_tilt(e.f, e.g, e.t, back);
    if (!r) return r;
    r->rest_offset = e.back(r->rest_offset);
    for (ArealTiltIncrement& i : r->trace) {
      const auto p = e.back({i.x, i.y});
      i.x = p[0];
      i.y = p[1];
    }
    return r;
  }
  if (auto s = validate(f, "lower map"); !s) return s.error();
  if (auto s = validate(g, "upper map"); !s) return s.error();
  if (f.nx < 2 || f.ny < 2 || g.nx < 1 || g.ny < 1) return make_error("areal_tilt: the lower map needs 2 x 2 nodes");
  auto bad = [](double v) { return !std::isfinite(v); };
  if (bad(o.angle)) return make_error(fmt::format("areal_tilt: angle {}: expected a finite direction (rad)", o.angle));
  if (bad(o.atomic_friction) || o.atomic_friction < 0)
    return make_error(fmt::format("areal_tilt: atomic friction {}: expected a finite number >= 0", o.atomic_friction));
  if (bad(o.runaway_distance) || o.runaway_distance < 0 || bad(o.sphere_radius) || o.sphere_radius < 0)
    return make_error("areal_tilt: run-away distance and sphere radius must be finite and >= 0 (m)");
  if (!(o.tilt_step > 0) || !(o.max_tilt > o.tilt_step) || !(o.max_tilt < std::numbers::pi / 2))
    return make_error("areal_tilt: expected 0 < tilt_step < max_tilt < pi/2 (rad)");
  if (!(o.time_step > 0) || !(o.contact_time >= 2 * o.time_step) || !(o.damping >= 0) || !(o.relax_time > 0))
    return make_error("areal_tilt: expected time_step > 0, contact_time >= 2 time_step, damping >= 0, relax_time > 0");
  if (o.rest_steps < 1) return make_error(fmt::format("areal_tilt: rest steps {}: expected >= 1", o.rest_steps));
  if (!(o.local_damping >= 0 && o.local_damping < 1))
    return make_error(fmt::format("areal_tilt: local damping {}: expected a fraction in [0, 1)", o.local_damping));
  if (!(o.settle_damping >= 0) || bad(o.settle_damping))
    return make_error(
        fmt::format("areal_tilt: settle damping {}: expected a finite number >= 0 (1/scaled s)", o.settle_damping));
  if (!(o.tilt_damping >= 0) || bad(o.tilt_damping))
    return make_error(
        fmt::format("areal_tilt: tilt damping {}: expected a finite number >= 0 (1/scaled s)", o.tilt_damping));
  if (!(o.quench_speed > 0) || bad(o.quench_speed))
    return make_error(
        fmt::format("areal_tilt: quench speed {}: expected a finite speed > 0 (scaled m/s)", o.quench_speed));
  if (!(o.force_tolerance > 0) || !(o.speed_tolerance > 0) || bad(o.force_tolerance) || bad(o.speed_tolerance))
    return make_error(fmt::format("areal_tilt: force tolerance {} and speed tolerance {}: expected finite numbers > 0",
                                  o.force_tolerance, o.speed_tolerance));
  if (!(o.coarse_tilt_step > 0) || bad(o.coarse_tilt_step))
    return make_error(
        fmt::format("areal_tilt: coarse tilt step {}: expected a finite angle > 0 (rad)", o.coarse_tilt_step));
  if (bad(o.start_offset[0]) || bad(o.start_offset[1]))
    return make_error("areal_tilt: the start offset must be finite (m)");

  // Scaled units: lengths divided by the lower map's larger extent (angles do not change).
  const double L = std::max(f.width(), f.height());
  const double S = 1.0 / L;
  const double dxv = std::cos(o.angle), dyv = std::sin(o.angle);
  const double r = detail::tilt_sphere_radius(f, o) * S;
  const double D = detail::tilt_runaway_distance(f, o) * S;
  // The upper face's nodes at offset 0, in the lower map's frame (turned over about the axis
  // across d through the centres, as areal_signature), heights of the face.
  const double cfx = f.x0 + 0.5 * f.width(), cfy = f.y0 + 0.5 * f.height();
  const std::vector<detail::TiltNode> nodes = detail::tilt_nodes(f, g, o.angle, o.turn_over_upper);
  if (nodes.empty()) return make_error("areal_tilt: the upper map has no valid node");
  // Put down just above contact at the start offset: the largest gap over the spheres.
  double lift = -std::numeric_limits<double>::infinity();
  for (const detail::TiltNode& n : nodes) {
    const double fz = interpolate(f, n.x + o.start_offset[0], n.y + o.start_offset[1]);
    if (!std::isnan(fz)) lift = std::max(lift, fz - n.z);
  }
  if (!std::isfinite(lift))
    return make_error(
        fmt::format("areal_tilt: at the start offset ({}, {}) m no node of the upper face lies over the "
                    "lower map (expected maps that overlap)",
                    o.start_offset[0], o.start_offset[1]));

  const int ncon = int(std::min<std::size_t>(4 * nodes.size() + 100, 200000));
  // The height field samples the lower map's bilinear surface hfield_refine times finer.
  if (o.hfield_refine < 1 || o.hfield_refine > 16)
    return make_error(fmt::format("areal_tilt: hfield_refine {}: expected 1..16", o.hfield_refine));
  const detail::Hfield hf = detail::tilt_hfield(f, std::size_t(o.hfield_refine));
  const std::size_t hnx = hf.nx, hny = hf.ny;
  const double zmin = hf.zmin, relief = hf.relief;
  const int rows = o.atomic_friction > 0 ? 4 : 1;
  // Free: slide joints along x and y; locked: one along d, the body put at the start offset's
  // part across d (so that its offset is (bx, by) + q0 d).
  const double sd = o.start_offset[0] * dxv + o.start_offset[1] * dyv;
  const double bx = o.lock_lateral ? (o.start_offset[0] - sd * dxv) * S : 0.0;
  const double by = o.lock_lateral ? (o.start_offset[1] - sd * dyv) * S : 0.0;
  const std::string lateral_joints =
      o.lock_lateral ? fmt::format("<joint name=\"u\" type=\"slide\" axis=\"{:.17g} {:.17g} 0\" damping=\"{:.9g}\"/>",
                                   dxv, dyv, o.damping)
                     : fmt::format(
                           "<joint name=\"x\" type=\"slide\" axis=\"1 0 0\" damping=\"{:.9g}\"/>"
                           "<joint name=\"y\" type=\"slide\" axis=\"0 1 0\" damping=\"{:.9g}\"/>",
                           o.damping, o.damping);
  std::string xml = fmt::format(
      "<mujoco><option timestep=\"{:.9g}\" gravity=\"0 0 -9.81\" integrator=\"Euler\"/>"
      "<size nconmax=\"{}\" njmax=\"{}\" nuser_geom=\"1\"/>"
      "<asset><hfield name=\"lower\" nrow=\"{}\" ncol=\"{}\" size=\"{:.17g} {:.17g} {:.17g} {:.17g}\"/></asset>"
      "<default><geom condim=\"{}\" friction=\"{:.17g} 0 0\" solref=\"{:.9g} 1\" solimp=\"0.99 0.99 0.001\"/></default>"
      "<worldbody><geom type=\"hfield\" hfield=\"lower\" user=\"{}\" pos=\"{:.17g} {:.17g} {:.17g}\"/>"
      "<body name=\"block\" pos=\"{:.17g} {:.17g} 0\">{}"
      "<joint name=\"z\" type=\"slide\" axis=\"0 0 1\" damping=\"{:.9g}\"/>"
      "<inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"1 1 1\"/>",
      o.time_step, ncon, ncon * rows, hny, hnx, 0.5 * f.width() * S, 0.5 * f.height() * S, relief * S,
      0.1 * relief * S + r, o.atomic_friction > 0 ? 3 : 1, std::max(o.atomic_friction, 1e-12), o.contact_time,
      o.exact_contacts ? 1 : 0, cfx * S, cfy * S, zmin * S, bx, by, lateral_joints, o.damping);
  for (const detail::TiltNode& n : nodes)
    xml += fmt::format("<geom type=\"sphere\" size=\"{:.17g}\" pos=\"{:.17g} {:.17g} {:.17g}\"/>", r, n.x * S, n.y * S,
                       n.z * S + r);
  xml += "</body></worldbody></mujoco>";

  install_exact_hfield_sphere();
  Sim sim;
  if (mj_makeEmptyFileVFS(&sim.vfs, "areal_tilt.xml", int(xml.size())) != 0)
    return make_error(ErrorCode::Internal, "areal_tilt: MuJoCo's virtual file system refused the model");
  const int idx = mj_findFileVFS(&sim.vfs, "areal_tilt.xml");
  std::memcpy(sim.vfs.filedata[idx], xml.data(), xml.size());
  char err[1000] = "";
  sim.m = mj_loadXML("areal_tilt.xml", &sim.vfs, err, sizeof err);
  if (!sim.m) return make_error(fmt::format("areal_tilt: MuJoCo refused the model: {}", err));
  // Heights: row 0 of the height field is at -y, as the map's row 0.
  std::copy(hf.data.begin(), hf.data.end(), sim.m->hfield_data);
  sim.d = mj_makeData(sim.m);
  if (!sim.d)
    return make_error(ErrorCode::Internal,
                      fmt::format("areal_tilt: MuJoCo could not allocate the data of {} spheres", nodes.size()));
  mjModel* m = sim.m;
  mjData* d = sim.d;
  const int nv = m->nv;  // 3 (x, y, z) or 2 (u, z)
  if (o.lock_lateral) {
    d->qpos[0] = sd * S;
  } else {
    d->qpos[0] = o.start_offset[0] * S;
    d->qpos[1] = o.start_offset[1] * S;
  }
  d->qpos[nv - 1] = (lift + 1e-3 * relief) * S;
  // The block's offset (scaled).
  auto X = [&]() { return o.lock_lateral ? bx + d->qpos[0] * dxv : d->qpos[0]; };
  auto Y = [&]() { return o.lock_lateral ? by + d->qpos[0] * dyv : d->qpos[1]; };
  mj_forward(m, d);

  ArealTiltResult out;
  out.spheres = nodes.size();
  out.sphere_radius = r / S;
  const double grav = 9.81;
  // Relaxes at tilt beta until at rest (unbalanced force and speed small), until the block has
  // gone D along d from `u_stop`, or for relax_time; returns whether it came to rest. `alpha`:
  // the local damping (0 while the joints' viscous damping settles the drop).
  constexpr double kDriftDamping = 100;   // per scaled s (block mass 1)
  double last_force = 0, last_speed = 0;  // at the end of the last relaxation (scaled)
  // `quench`: quenched dynamics (kinetic damping) instead of the local damping: no force against
  // the motion, but whenever the unbalanced force does negative work on the block (F.v < 0: it
  // has passed the lowest point along its path) its velocity is set to zero, and its speed is
  // capped at quench_speed: the block stops at the first minimum along its path (no momentum
  // carried past a seat), and it turns with the force within a radius speed^2 / force (the path
  // of steepest descent as the cap shrinks), at a speed that does not fall with the force (no
  // creep).
  const double qv = o.quench_speed;
  auto relax = [&](double beta, double u_stop, bool& far, double alpha, bool quench) {
    m->opt.gravity[0] = grav * std::sin(beta) * dxv;
    m->opt.gravity[1] = grav * std::sin(beta) * dyv;
    m->opt.gravity[2] = -grav * std::cos(beta);
    far = false;
    const long n = long(o.relax_time / o.time_step);
    int calm = 0;
    for (long k = 0; k < n; ++k) {
      // Local non-viscous damping (Cundall; YADE, PFC): a force against the velocity of each
      // joint, a fraction of its unbalanced force, so that a slip is not slowed to a creep.
      // A balanced block (unbalanced force below the rest tolerance) that still moves drifts
      // along a neutral direction (a frictionless groove): local damping, proportional to the
      // unbalanced force, would never stop it; the quasi-static block stays at its stop, so
      // the drift is damped viscously (e-folding time 0.01 scaled s) while balanced.
      double fb = 0;
      for (int q = 0; q < nv; ++q) fb += std::pow(d->qfrc_constraint[q] - d->qfrc_bias[q], 2);
      const bool balanced = std::sqrt(fb) < o.force_tolerance * grav;
      if (quench && !balanced) {
        // The power of the unbalanced force on the joints in the plane (x, y; or u along d), the
        // quasi-static block's offset (z's soft contact is critically damped on its own); the
        // whole velocity is zeroed (a velocity of zero is consistent with every contact).
        double p = 0, v2 = 0;
        for (int q = 0; q + 1 < nv; ++q) p += (d->qfrc_constraint[q] - d->qfrc_bias[q]) * d->qvel[q];
        for (int q = 0; q < nv; ++q) v2 += d->qvel[q] * d->qvel[q];
        if (p < 0) {
          for (int q = 0; q < nv; ++q) d->qvel[q] = 0;
        } else if (v2 > qv * qv) {
          const double k = qv / std::sqrt(v2);
          for (int q = 0; q < nv; ++q) d->qvel[q] *= k;
        }
        for (int q = 0; q < nv; ++q) d->qfrc_applied[q] = 0;
      } else {
        for (int q = 0; q < nv; ++q) {
          const double u = d->qfrc_constraint[q] - d->qfrc_bias[q];
          d->qfrc_applied[q] = balanced          ? -kDriftDamping * d->qvel[q]
                               : d->qvel[q] == 0 ? 0.0
                                                 : -alpha * std::abs(u) * (d->qvel[q] > 0 ? 1 : -1);
        }
      }
      mj_step(m, d);
      ++out.steps;
      out.max_contacts = std::max(out.max_contacts, d->ncon);
      if (X() * dxv + Y() * dyv - u_stop >= D) {
        far = true;
        return false;
      }
      double fu = 0, v = 0;
      for (int q = 0; q < nv; ++q) {
        const double u = d->qfrc_constraint[q] - d->qfrc_bias[q];
        fu += u * u;
        v += d->qvel[q] * d->qvel[q];
      }
      last_force = std::sqrt(fu) / grav;
      last_speed = std::sqrt(v);
      // At rest: balanced and still for rest_steps steps in a row (one instant is not enough: a
      // block that lands or turns round passes through small force and speed).
      calm = last_force < o.force_tolerance && last_speed < o.speed_tolerance ? calm + 1 : 0;
      if (calm >= o.rest_steps) return true;
    }
    return false;
  };
  // The stop's position (scaled) for the steering of the run-away.
  double x_stop = 0, y_stop = 0, x_saved = 0, y_saved = 0;
  auto record = [&](double beta, bool rested) {
    out.trace.push_back({beta, X() / S, Y() / S, rested, out.steps, last_force, last_speed / S});
    if (progress) progress(out.trace.back());
  };
  bool far = false;
  constexpr int kMaxWaits = 40;  // relaxations at one tilt before it counts as unsettled
  // Quenched, the block moves at most at quench_speed: an increment waits at least as long as it
  // takes to cross the lower map (its larger extent, 1 scaled) at that speed (a slip that is not a
  // run-away can go far across d, along a groove).
  const int quench_waits = int(std::min(1e6, std::max<double>(kMaxWaits, std::ceil(1.0 / (qv * o.relax_time)))));
  {
    // At zero tilt the block slides into the basin that holds its drop: as long as it takes.
    // With settle_damping c the joints' viscous damping (implicit in MuJoCo's Euler step)
    // replaces the local damping meanwhile: the block put down gently, an overdamped descent at
    // the speed (unbalanced force) / c, whose path tends to the steepest descent of the prediction
    // as c grows (docs/mujoco.md). Being slower by c, it may wait c / 20 times as many chunks.
    const bool viscous = o.settle_damping > 0;
    if (viscous)
      for (int q = 0; q < nv; ++q) m->dof_damping[q] = o.settle_damping;
    const int waits = viscous    ? int(std::min(1e6, std::ceil(kMaxWaits * std::max(1.0, o.settle_damping / 20))))
                      : o.quench ? quench_waits
                                 : kMaxWaits;
    bool rested = false;
    for (int w = 0; w < waits && !rested; ++w)
      rested = relax(0.0, std::numeric_limits<double>::infinity(), far, viscous ? 0.0 : o.local_damping,
                     !viscous && o.quench);
    if (!rested) ++out.unsettled;
    record(0.0, rested);
  }
  // The tilt increments: under the local damping, or with tilt_damping c under a viscous joint
  // damping c instead (an overdamped slip at the speed (unbalanced force) / c, the prediction's
  // descent into the next seat as c grows: docs/mujoco.md, "The tilt's damping"). An overdamped
  // block that starts to slip just past its seat creeps: at a drive of one tilt step's excess,
  // g tilt_step, it crosses one lower-map cell (of the larger spacing) in c cell / (g tilt_step);
  // an increment waits up to twice that (at least the usual 40 chunks) before it counts as
  // unsettled, so that the tilt does not grow while a slip is still under way.
  const bool tilt_viscous = o.tilt_damping > 0;
  for (int q = 0; q < nv; ++q) m->dof_damping[q] = tilt_viscous ? o.tilt_damping : o.damping;
  const double tilt_alpha = tilt_viscous ? 0.0 : o.local_damping;
  const double cell = std::max(f.dx, f.dy) * S;
  const int tilt_waits =
      tilt_viscous
          ? int(std::min(1e6, std::max<double>(kMaxWaits, std::ceil(2 * cell * o.tilt_damping /
                                                                    (grav * std::sin(o.tilt_step) * o.relax_time)))))
      : o.quench ? quench_waits
                 : kMaxWaits;
  if (d->ncon == 0)
    return make_error(
        fmt::format("areal_tilt: the block left the lower map at zero tilt (it slid to ({}, {}) m, "
                    "beyond the height field): expected maps whose upper face rests on the lower one",
                    X() / S, Y() / S));
  out.rest_offset = {X() / S, Y() / S};
  double u_stop = X() * dxv + Y() * dyv;
  x_stop = x_saved = X();
  y_stop = y_saved = Y();
  // Coarse increments (coarse_tilt_step) until the run-away, then again from the state at rest
  // before it in increments of tilt_step: the fine protocol from that state.
  // The state to tilt again from: positions, velocities and the solver's warm start (copying
  // the whole mjData would copy its arena, sized by nconmax: 0.2 GB for 1,024 spheres).
  struct Saved {
    std::vector<mjtNum> qpos, qvel, warm;
    mjtNum time = 0;
  } saved;
  auto save = [&]() {
    saved.qpos.assign(d->qpos, d->qpos + m->nq);
    saved.qvel.assign(d->qvel, d->qvel + m->nv);
    saved.warm.assign(d->qacc_warmstart, d->qacc_warmstart + m->nv);
    saved.time = d->time;
  };
  auto restore = [&]() {
    std::copy(saved.qpos.begin(), saved.qpos.end(), d->qpos);
    std::copy(saved.qvel.begin(), saved.qvel.end(), d->qvel);
    std::copy(saved.warm.begin(), saved.warm.end(), d->qacc_warmstart);
    d->time = saved.time;
    mj_forward(m, d);
  };
  auto run = [&](double beta0, double step, double& beta_saved, double& u_saved) {
    for (double beta = beta0 + step; beta <= o.max_tilt + 1e-12; beta += step) {
      // A block that is not at rest after relax_time is creeping under the damping (its
      // unbalanced force is not small): the tilt waits until it rests or has run D, up to
      // tilt_waits relaxations (kMaxWaits under the local damping), so that the drag does not let
      // the tilt grow during a run.
      bool rest = false;
      for (int w = 0; w < tilt_waits && !rest && !far; ++w)
        rest = relax(beta, u_stop, far, tilt_alpha, !tilt_viscous && o.quench);
      record(beta, rest);
      if (far) {
        out.steering =
            std::atan2(-(X() - x_stop) * dyv + (Y() - y_stop) * dxv, (X() - x_stop) * dxv + (Y() - y_stop) * dyv);
        return beta;
      }
      if (rest) {
        u_stop = X() * dxv + Y() * dyv;
        x_stop = X();
        y_stop = Y();
      } else {
        ++out.unsettled;
      }
      save();
      beta_saved = beta;
      u_saved = u_stop;
      x_saved = x_stop;
      y_saved = y_stop;
    }
    return std::numeric_limits<double>::quiet_NaN();
  };
  save();
  double beta_saved = 0, u_saved = u_stop;
  const double coarse = std::max(o.coarse_tilt_step, o.tilt_step);
  double b = run(0.0, coarse, beta_saved, u_saved);
  if (!std::isnan(b) && coarse > o.tilt_step) {
    restore();
    u_stop = u_saved;
    x_stop = x_saved;
    y_stop = y_saved;
    far = false;
    const double b0 = beta_saved;
    b = run(b0, o.tilt_step, beta_saved, u_saved);
  }
  if (!std::isnan(b)) {
    out.friction_angle = b;
    out.ran_away = true;
  }
  if (!out.ran_away) out.friction_angle = o.max_tilt;
  if (o.atomic_friction > 0)
    out.warnings.push_back(
        {"friction-not-validated",
         fmt::format("with atomic friction {} the simulation is not validated: on grooves across d (mu_a = 0.1) MuJoCo "
                     "reads 30.1 deg against the rigid 23.58 deg (the block creeps under the local damping; "
                     "docs/mujoco.md, Atomic friction); the rigid predictions stand",
                     o.atomic_friction)});
  if (d->warning[mjWARN_CONTACTFULL].number > 0)
    return make_error(ErrorCode::Internal,
                      fmt::format("areal_tilt: MuJoCo's contact buffer ({} contacts) overflowed", ncon));
  return out;
}

#endif

}  // namespace frictal
