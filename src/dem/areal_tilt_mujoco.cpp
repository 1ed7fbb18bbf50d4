// The 3D tilt test of two areal blocks on MuJoCo (frictal/areal_tilt.hpp; docs/mujoco.md): the
// model (a height field and a body of spheres on three slide joints) is written as MJCF into
// MuJoCo's virtual file system, the heights are set in the compiled model, and the quasi-static
// tilt protocol runs on mj_step. Without FRICTAL_HAVE_MUJOCO only the NotAvailable answer is built.
#include <fmt/core.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "areal_tilt_model.hpp"
#include "frictal/areal_tilt.hpp"

#ifdef FRICTAL_HAVE_MUJOCO
#include <mujoco/mujoco.h>
#endif

namespace frictal {

#ifndef FRICTAL_HAVE_MUJOCO

bool mujoco_available() { return false; }

Result<ArealTiltResult> areal_tilt(const Map&, const Map&, const ArealTiltOptions&) {
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

}  // namespace

Result<ArealTiltResult> areal_tilt(const Map& f, const Map& g, const ArealTiltOptions& o) {
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
  if (bad(o.start_offset[0]) || bad(o.start_offset[1]))
    return make_error("areal_tilt: the start offset must be finite (m)");

  // Scaled units: lengths divided by the lower map's larger extent (angles do not change).
  const double L = std::max(f.width(), f.height());
  const double S = 1.0 / L;
  const double dxv = std::cos(o.angle), dyv = std::sin(o.angle);
  const double r = detail::tilt_sphere_radius(f, o) * S;
  const double D =
      (o.runaway_distance > 0 ? o.runaway_distance : 0.05 * (std::abs(dxv) * f.width() + std::abs(dyv) * f.height())) *
      S;
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
  std::string xml = fmt::format(
      "<mujoco><option timestep=\"{:.9g}\" gravity=\"0 0 -9.81\" integrator=\"Euler\"/>"
      "<size nconmax=\"{}\" njmax=\"{}\"/>"
      "<asset><hfield name=\"lower\" nrow=\"{}\" ncol=\"{}\" size=\"{:.17g} {:.17g} {:.17g} {:.17g}\"/></asset>"
      "<default><geom condim=\"{}\" friction=\"{:.17g} 0 0\" solref=\"{:.9g} 1\" solimp=\"0.99 0.99 0.001\"/></default>"
      "<worldbody><geom type=\"hfield\" hfield=\"lower\" pos=\"{:.17g} {:.17g} {:.17g}\"/>"
      "<body name=\"block\">"
      "<joint name=\"x\" type=\"slide\" axis=\"1 0 0\" damping=\"{:.9g}\"/>"
      "<joint name=\"y\" type=\"slide\" axis=\"0 1 0\" damping=\"{:.9g}\"/>"
      "<joint name=\"z\" type=\"slide\" axis=\"0 0 1\" damping=\"{:.9g}\"/>"
      "<inertial pos=\"0 0 0\" mass=\"1\" diaginertia=\"1 1 1\"/>",
      o.time_step, ncon, ncon * rows, hny, hnx, 0.5 * f.width() * S, 0.5 * f.height() * S, relief * S,
      0.1 * relief * S + r, o.atomic_friction > 0 ? 3 : 1, std::max(o.atomic_friction, 1e-12), o.contact_time, cfx * S,
      cfy * S, zmin * S, o.damping, o.damping, o.damping);
  for (const detail::TiltNode& n : nodes)
    xml += fmt::format("<geom type=\"sphere\" size=\"{:.17g}\" pos=\"{:.17g} {:.17g} {:.17g}\"/>", r, n.x * S, n.y * S,
                       n.z * S + r);
  xml += "</body></worldbody></mujoco>";

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
  d->qpos[0] = o.start_offset[0] * S;
  d->qpos[1] = o.start_offset[1] * S;
  d->qpos[2] = (lift + 1e-3 * relief) * S;
  mj_forward(m, d);

  ArealTiltResult out;
  out.spheres = nodes.size();
  out.sphere_radius = r / S;
  const double grav = 9.81;
  // Relaxes at tilt beta until at rest (unbalanced force and speed small), until the block has
  // gone D along d from `u_stop`, or for relax_time; returns whether it came to rest.
  auto relax = [&](double beta, double u_stop, bool& far) {
    m->opt.gravity[0] = grav * std::sin(beta) * dxv;
    m->opt.gravity[1] = grav * std::sin(beta) * dyv;
    m->opt.gravity[2] = -grav * std::cos(beta);
    far = false;
    const long n = long(o.relax_time / o.time_step);
    for (long k = 0; k < n; ++k) {
      // Local non-viscous damping (Cundall; YADE, PFC): a force against the velocity of each
      // joint, a fraction of its unbalanced force, so that a slip is not slowed to a creep.
      for (int q = 0; q < 3; ++q) {
        const double u = d->qfrc_constraint[q] - d->qfrc_bias[q];
        d->qfrc_applied[q] = d->qvel[q] == 0 ? 0.0 : -o.local_damping * std::abs(u) * (d->qvel[q] > 0 ? 1 : -1);
      }
      mj_step(m, d);
      ++out.steps;
      out.max_contacts = std::max(out.max_contacts, d->ncon);
      if (d->qpos[0] * dxv + d->qpos[1] * dyv - u_stop >= D) {
        far = true;
        return false;
      }
      if (k < 10) continue;
      double fu = 0, v = 0;
      for (int q = 0; q < 3; ++q) {
        const double u = d->qfrc_constraint[q] - d->qfrc_bias[q];
        fu += u * u;
        v += d->qvel[q] * d->qvel[q];
      }
      if (std::sqrt(fu) < o.force_tolerance * grav && std::sqrt(v) < o.speed_tolerance) return true;
    }
    return false;
  };
  bool far = false;
  if (!relax(0.0, std::numeric_limits<double>::infinity(), far)) ++out.unsettled;
  out.rest_offset = {d->qpos[0] / S, d->qpos[1] / S};
  double u_stop = d->qpos[0] * dxv + d->qpos[1] * dyv;
  // Coarse increments (coarse_tilt_step) until the run-away, then again from the state at rest
  // before it in increments of tilt_step: the fine protocol from that state.
  mjData* saved = mj_makeData(m);
  if (!saved) return make_error(ErrorCode::Internal, "areal_tilt: MuJoCo could not allocate a second state");
  struct SavedGuard {
    mjData* p;
    ~SavedGuard() { mj_deleteData(p); }
  } guard{saved};
  auto run = [&](double beta0, double step, double& beta_saved, double& u_saved) {
    for (double beta = beta0 + step; beta <= o.max_tilt + 1e-12; beta += step) {
      // A block that is not at rest after relax_time is creeping under the damping (its
      // unbalanced force is not small): the tilt waits until it rests or has run D, up to
      // kMaxWaits relaxations, so that the drag does not let the tilt grow during a run.
      constexpr int kMaxWaits = 40;
      bool rest = false;
      for (int w = 0; w < kMaxWaits && !rest && !far; ++w) rest = relax(beta, u_stop, far);
      if (far) return beta;
      if (rest)
        u_stop = d->qpos[0] * dxv + d->qpos[1] * dyv;
      else
        ++out.unsettled;
      mj_copyData(saved, m, d);
      beta_saved = beta;
      u_saved = u_stop;
    }
    return std::numeric_limits<double>::quiet_NaN();
  };
  mj_copyData(saved, m, d);
  double beta_saved = 0, u_saved = u_stop;
  const double coarse = std::max(o.coarse_tilt_step, o.tilt_step);
  double b = run(0.0, coarse, beta_saved, u_saved);
  if (!std::isnan(b) && coarse > o.tilt_step) {
    mj_copyData(d, m, saved);
    u_stop = u_saved;
    far = false;
    const double b0 = beta_saved;
    b = run(b0, o.tilt_step, beta_saved, u_saved);
  }
  if (!std::isnan(b)) {
    out.friction_angle = b;
    out.ran_away = true;
  }
  if (!out.ran_away) out.friction_angle = o.max_tilt;
  if (d->warning[mjWARN_CONTACTFULL].number > 0)
    return make_error(ErrorCode::Internal,
                      fmt::format("areal_tilt: MuJoCo's contact buffer ({} contacts) overflowed", ncon));
  return out;
}

#endif

}  // namespace frictal
