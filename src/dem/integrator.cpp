// frictal — spheropolygon engine: time integration and the step (docs/dem.md sec. 3). Velocity
// Verlet in kick-drift-kick form; kinematic bodies in closed form; the neighbour-list rebuild
// test; the contact forces (contact geometry, force law, stability limit, in that order); the
// stability guards.
#include "integrator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <fmt/core.h>

#include "contact_geometry.hpp"
#include "force_law.hpp"
#include "neighbor_list.hpp"
#include "stability.hpp"

namespace frictal::dem {

namespace detail {

// Prescribed pose of a kinematic body at time t.
void kinematic_pose(const Model& m, std::size_t b, double t, State& st) {
  const KinematicMotion& k = m.motion[b];
  const double tau = t > k.start_time ? t - k.start_time : 0.0;
  const double th = k.angular_velocity * tau;
  const double c = std::cos(th), s = std::sin(th);
  const double dx = m.initial_position[b].x - k.pivot.x;
  const double dy = m.initial_position[b].y - k.pivot.y;
  const double rx = c * dx - s * dy, ry = s * dx + c * dy;
  st.position[b] = {k.pivot.x + rx, k.pivot.y + ry};
  st.angle[b] = th;
  const double w = t >= k.start_time ? k.angular_velocity : 0.0;
  st.angular_velocity[b] = w;
  st.velocity[b] = {-w * ry, w * rx};
}

void follow_rotations(const Model& m, State& st) {
  for (std::size_t b = 0; b < m.body_count(); ++b)
    if (const int f = m.rotation_follows[b]; f >= 0) {
      st.angle[b] = st.angle[static_cast<std::size_t>(f)];
      st.angular_velocity[b] = st.angular_velocity[static_cast<std::size_t>(f)];
    }
}

// cos and sin of every body's angle, once per step for the list test, the hot-list test, the
// list builder and the contact loop.
void update_rotation(const State& st, Workspace& ws) {
  ws.rotation.resize(st.angle.size());
  for (std::size_t b = 0; b < st.angle.size(); ++b) ws.rotation[b] = {std::cos(st.angle[b]), std::sin(st.angle[b])};
}

namespace {

// One team member's share of a parallel step: the hot pairs [H j / n, H (j + 1) / n), their
// exact test (touching pairs to their own segment of ws.touching) and their forces.
struct StepShare {
  const Model* m;
  State* st;
  Workspace* ws;
  double dt_spring;
  std::size_t hot_pairs;
  unsigned members;
};

void run_share(void* context, unsigned j) {
  StepShare& s = *static_cast<StepShare*>(context);
  const std::size_t k0 = s.hot_pairs * j / s.members, k1 = s.hot_pairs * (j + 1) / s.members;
  const std::size_t n = find_touching_hot(*s.m, *s.st, *s.ws, k0, k1);
  s.ws->segments[j] = {k0, n};
  double max_ov = 0, max_ratio = 0;
  pair_forces(*s.m, *s.st, *s.ws, s.dt_spring, k0, k0 + n, max_ov, max_ratio);
  s.ws->part_max_overlap[j] = max_ov;
  s.ws->part_max_ratio[j] = max_ratio;
}

// Whether this step's contact passes can be split: threads, enough hot pairs for two shares of
// ws.min_hot_pairs_per_thread, and no full pass over the list due.
bool can_split(const Model& m, const State& st, const Workspace& ws) {
  const std::size_t per_member = std::max<std::size_t>(1, ws.min_hot_pairs_per_thread);
  // The contact rule `closest` merges pairs across the shares: serial passes.
  return ws.threads > 1 && m.def.contact.rule == ContactRule::Pairs && ws.hot.valid &&
         ws.hot.pair.size() >= 2 * per_member && !hot_list_stale(m, st, ws);
}

// The contact passes split over the team (docs/dem.md sec. 7, threads): each member classifies
// and computes the forces of a fixed contiguous share of the hot list; the sums then walk the
// shares in order on this thread. Every decision and force is that of the serial passes, and
// every floating-point sum is taken in the same order (the maxima do not depend on the order),
// so the result is bitwise the serial one. Needs can_split(). Returns the largest overlap ratio
// (apply_force_law), or a negative value when no team can be started.
double split_contact_passes(const Model& m, State& st, Workspace& ws, double dt_spring) {
  const std::size_t per_member = std::max<std::size_t>(1, ws.min_hot_pairs_per_thread);
  const std::size_t hot_pairs = ws.hot.pair.size();
  const unsigned n = static_cast<unsigned>(std::min<std::size_t>(ws.threads, hot_pairs / per_member));
  if (!ws.team.team || ws.team.team->members() < n) {
    ws.team.team.reset();
    ws.team.team = util::Team::make(ws.threads);
    if (!ws.team.team) {  // no threads to be had: serial from now on
      ws.threads = 1;
      return -1;
    }
  }
  if (ws.touching.size() < hot_pairs) ws.touching.resize(hot_pairs);
  ws.segments.resize(n);
  ws.part_max_overlap.resize(n);
  ws.part_max_ratio.resize(n);
  StepShare share{&m, &st, &ws, dt_spring, hot_pairs, n};
  ws.team.team->run(n, &run_share, &share);
  double max_ov = 0, max_ratio = 0;
  std::size_t touching = 0;
  for (unsigned j = 0; j < n; ++j) {
    max_ov = std::max(max_ov, ws.part_max_overlap[j]);
    max_ratio = std::max(max_ratio, ws.part_max_ratio[j]);
    touching += ws.segments[j].count;
  }
  ws.touching_count = touching;
  st.timings.pairs_evaluated += hot_pairs;
  ++st.timings.split_steps;
  return sum_contacts(m, st, ws, max_ov, max_ratio);
}

}  // namespace

double compute_forces(const Model& m, State& st, Workspace& ws, double dt_spring) {
  const std::size_t nb = m.body_count();
  // Per-body pose cache, inverse masses (kinematic bodies: 0), counters and mode sums.
  ws.pose.resize(nb);
  ws.inv_mass.resize(nb);
  ws.body_contacts.resize(nb);
  ws.modes.resize(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    ws.body_contacts[b] = 0;
    ws.modes[b] = ModeSums{};
    ws.inv_mass[b] = m.type[b] == BodyType::Dynamic ? 1.0 / m.mass[b] : 0.0;
    ws.pose[b] = {st.position[b].x, st.position[b].y, ws.rotation[b].c, ws.rotation[b].s};
    st.force[b] = {0, 0};
    st.torque[b] = 0;
  }
  // Split over the team when the step can be split and the tuner finds that it pays
  // (Workspace::Tuner: only the steps that can be split are timed and counted).
  Workspace::Tuner& tu = ws.tuner;
  const bool splittable = ws.threads > 1 && can_split(m, st, ws);
  const bool tuning = splittable && tu.enabled;
  const bool split = splittable && (!tuning || (tu.phase == 4 ? tu.split : tu.phase % 2 == 1));
  std::chrono::steady_clock::time_point t0;
  if (tuning && tu.phase < 4) t0 = std::chrono::steady_clock::now();
  double max_ratio = split ? split_contact_passes(m, st, ws, dt_spring) : -1.0;
  if (max_ratio < 0) {
    find_touching(m, st, ws);
    if (m.def.contact.rule == ContactRule::Closest) merge_touching(m, st, ws);
    max_ratio = apply_force_law(m, st, ws, dt_spring);
  }
  if (tuning) {
    using Tuner = Workspace::Tuner;
    auto run_serial = [&tu](bool had_split) {  // verdict: serial; back off while it does not pay
      tu.split = false;
      tu.run_steps = had_split ? Tuner::kRunSteps : std::min(2 * tu.run_steps, Tuner::kMaxRunSteps);
      tu.phase = 4;
      tu.left = tu.run_steps;
    };
    if (tu.phase < 4)
      tu.seconds[tu.phase] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (tu.phase % 2 == 1 && tu.seconds[tu.phase] > 2 * tu.seconds[tu.phase - 1]) {
      // A split window already twice as slow as the serial one (waiting for descheduled workers
      // on a loaded machine): stop the trial now rather than pay for the rest of it.
      run_serial(tu.split);
    } else if (--tu.left == 0) {
      if (tu.phase == 3) {  // split only for a clear gain, twice
        if (tu.seconds[1] < 0.95 * tu.seconds[0] && tu.seconds[3] < 0.95 * tu.seconds[2]) {
          tu.split = true;
          tu.run_steps = Tuner::kRunSteps;
          tu.phase = 4;
          tu.left = tu.run_steps;
        } else {
          run_serial(tu.split);
        }
      } else {
        tu.phase = (tu.phase + 1) % 5;
        tu.left = tu.phase == 4 ? tu.run_steps : Tuner::kTrialSteps;
      }
      if (tu.phase == 0) tu.seconds[0] = tu.seconds[1] = tu.seconds[2] = tu.seconds[3] = 0;
    }
  }
  for (std::size_t b = 0; b < nb; ++b) st.body_contacts[b] = ws.body_contacts[b];
  update_step_limits(m, st, ws);
  st.timings.pairs_visited += st.pairs.size();
  return max_ratio;
}

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Kick of length h: v += h M^-1 (F + m g). With implicit damping, (M + 2 h gamma_n G_m) dv =
// h (F + m g) per body, G_m from the last force evaluation (ws.modes): two half kicks of the same
// forces then make v(t + dt/2) = v(t - dt/2) + dt (M + dt C)^-1 F, i.e. backward Euler in the
// normal dashpots C = gamma_n G_m (docs/dem.md sec. 3).
void kick(const Model& m, State& st, const Workspace& ws, double h) {
  const Vec2 g = m.def.gravity;
  const bool implicit = m.def.implicit_damping;
  // Hertz: the mode sums G_m carry each contact's dashpot coefficient (force_law.cpp).
  const double c = 2.0 * h * (m.def.contact.law == ContactLaw::Hertz ? 1.0 : m.def.contact.normal_damping);
  for (std::size_t b = 0; b < m.body_count(); ++b) {
    if (m.type[b] != BodyType::Dynamic) continue;
    if (m.rotation_follows[b] >= 0) {  // rotation held: translation only (the angle follows its leader)
      const double mass = m.mass[b];
      const double r1 = h * (st.force[b].x + mass * g.x);
      const double r2 = h * (st.force[b].y + mass * g.y);
      if (implicit && ws.body_contacts[b] > 0 && c > 0) {
        const double* gm = ws.modes[b].gm;
        const double a11 = mass + c * gm[0], a12 = c * gm[1], a22 = mass + c * gm[3];
        const double inv_det = 1.0 / (a11 * a22 - a12 * a12);
        st.velocity[b].x += (a22 * r1 - a12 * r2) * inv_det;
        st.velocity[b].y += (a11 * r2 - a12 * r1) * inv_det;
      } else {
        st.velocity[b].x += r1 / mass;
        st.velocity[b].y += r2 / mass;
      }
      continue;
    }
    if (implicit && ws.body_contacts[b] > 0 && c > 0) {
      const double* gm = ws.modes[b].gm;  // xx, xy, xt, yy, yt, tt
      const double mass = m.mass[b];
      const double a11 = mass + c * gm[0], a12 = c * gm[1], a13 = c * gm[2];
      const double a22 = mass + c * gm[3], a23 = c * gm[4], a33 = m.inertia[b] + c * gm[5];
      const double r1 = h * (st.force[b].x + mass * g.x);
      const double r2 = h * (st.force[b].y + mass * g.y);
      const double r3 = h * st.torque[b];
      // Symmetric positive definite 3 x 3: Cramer's rule with the cofactors.
      const double c11 = a22 * a33 - a23 * a23, c12 = a13 * a23 - a12 * a33, c13 = a12 * a23 - a13 * a22;
      const double c22 = a11 * a33 - a13 * a13, c23 = a12 * a13 - a11 * a23, c33 = a11 * a22 - a12 * a12;
      const double inv_det = 1.0 / (a11 * c11 + a12 * c12 + a13 * c13);
      st.velocity[b].x += (c11 * r1 + c12 * r2 + c13 * r3) * inv_det;
      st.velocity[b].y += (c12 * r1 + c22 * r2 + c23 * r3) * inv_det;
      st.angular_velocity[b] += (c13 * r1 + c23 * r2 + c33 * r3) * inv_det;
      continue;
    }
    const double im = 1.0 / m.mass[b];
    st.velocity[b].x += h * (st.force[b].x * im + g.x);
    st.velocity[b].y += h * (st.force[b].y * im + g.y);
    st.angular_velocity[b] += h * (st.torque[b] / m.inertia[b]);
  }
}

}  // namespace

}  // namespace detail

Status step(const Model& m, State& st) {
  using namespace detail;
  Workspace& ws = st.workspace.get();
  const std::size_t nb = m.body_count();
  const double dt = m.def.adaptive_time_step ? st.time_step : m.def.time_step;
  const bool timed = m.def.timings;
  Clock::time_point t0;
  if (timed) t0 = Clock::now();
  // Kick (half step) and drift.
  kick(m, st, ws, 0.5 * dt);
  for (std::size_t b = 0; b < nb; ++b) {
    if (m.type[b] != BodyType::Dynamic) continue;
    st.position[b].x += dt * st.velocity[b].x;
    st.position[b].y += dt * st.velocity[b].y;
    st.angle[b] += dt * st.angular_velocity[b];
  }
  // Fixed step: time = steps x dt, without accumulated rounding.
  const double t_new = m.def.adaptive_time_step ? st.time + dt : static_cast<double>(st.steps + 1) * dt;
  for (std::size_t b = 0; b < nb; ++b)
    if (m.type[b] == BodyType::Kinematic) kinematic_pose(m, b, t_new, st);
  follow_rotations(m, st);
  st.time = t_new;
  update_rotation(st, ws);
  if (timed) {
    const auto t1 = Clock::now();
    st.timings.integration += std::chrono::duration<double>(t1 - t0).count();
    t0 = t1;
  }
  // Neighbour list: rebuild when some vertex-edge distance may have shrunk by more than the skin
  // since the last build (pairs left out were at least r1 + r2 + skin apart). The bound is on
  // the relative motion of the bodies: a block resting on a tilting block keeps its list.
  if (relative_motion_bound(m, ws.list_position, ws.list_angle, ws.list_rotation, st.position, st.angle, ws.rotation) >
      m.def.skin) {
    // A single step must not move anything by more than half the skin, or contacts are missed.
    for (std::size_t b = 0; b < nb; ++b) {
      const double per_step =
          (std::hypot(st.velocity[b].x, st.velocity[b].y) + std::fabs(st.angular_velocity[b]) * m.extent[b]) * dt;
      if (2.0 * per_step > m.def.skin)
        return make_error(
            ErrorCode::Unstable,
            fmt::format("dem: at t = {:.6g} s body {} moves {:.3g} m in one step, more than half the skin {:.3g} m; "
                        "reduce the time step (now {:.3g} s) or enlarge the skin",
                        st.time, b, per_step, m.def.skin, dt));
    }
    build_neighbor_list(m, st, ws);
  }
  if (timed) {
    const auto t1 = Clock::now();
    st.timings.neighbor_list += std::chrono::duration<double>(t1 - t0).count();
    t0 = t1;
  }
  const double ratio = compute_forces(m, st, ws, dt);
  if (timed) {
    const auto t1 = Clock::now();
    st.timings.contacts += std::chrono::duration<double>(t1 - t0).count();
    t0 = t1;
  }
  kick(m, st, ws, 0.5 * dt);
  ++st.steps;
  // Stability guards.
  Status status = Ok{};
  // Suggested step for the messages, computed only when there is one to write.
  auto dt_hint = [&]() { return suggested_time_step(m, st.contact_count); };
  bool beyond = false;
  for (std::size_t b = 0; b < nb && status.ok(); ++b) {
    if (m.type[b] != BodyType::Dynamic) continue;
    const bool finite = std::isfinite(st.position[b].x) && std::isfinite(st.position[b].y) &&
                        std::isfinite(st.angle[b]) && std::isfinite(st.velocity[b].x) &&
                        std::isfinite(st.velocity[b].y) && std::isfinite(st.angular_velocity[b]);
    if (!finite) {
      status = make_error(
          ErrorCode::Unstable,
          fmt::format("dem: body {} has a non-finite position or velocity at t = {:.6g} s (step {}); the integration "
                      "blew up: try a time step <= {:.3g} s (now {:.3g} s)",
                      b, st.time, st.steps, dt_hint(), dt));
      break;
    }
    if (const double lim = st.step_limit[b]; dt > lim) {
      beyond = true;
      // The adaptive step is already below the limit again at the next step: counted only.
      if (!m.def.adaptive_time_step &&
          st.steps_beyond_limit + 1 > static_cast<std::uint64_t>(m.def.max_steps_beyond_limit)) {
        status = make_error(
            ErrorCode::Unstable,
            fmt::format(
                "dem: at t = {:.6g} s body {} has {} contacts and the time step is above the explicit stability "
                "limit dt = {:.3g} s (2 / damping rate or 2 / omega of its contact modes), for the {}th step: "
                "use a time step <= {:.3g} s (now {:.3g} s)",
                st.time, b, st.body_contacts[b], lim, st.steps_beyond_limit + 1, 0.5 * lim, dt));
        break;
      }
    }
    const double speed =
        std::hypot(st.velocity[b].x, st.velocity[b].y) + std::fabs(st.angular_velocity[b]) * m.extent[b];
    if (speed > m.def.max_speed)
      status = make_error(
          ErrorCode::Unstable,
          fmt::format("dem: body {} reached speed {:.3g} m/s > max_speed {:.3g} m/s at t = {:.6g} s (energy blow-up); "
                      "try a time step <= {:.3g} s (now {:.3g} s)",
                      b, speed, m.def.max_speed, st.time, dt_hint(), dt));
  }
  if (beyond) {
    ++st.steps_beyond_limit;
    ++st.consecutive_beyond_limit;
  } else {
    st.consecutive_beyond_limit = 0;
  }
  if (status.ok() && ratio > m.def.max_overlap_ratio)
    status = make_error(
        ErrorCode::Unstable,
        fmt::format("dem: an overlap reached {:.3g} of r1 + r2 (limit {:.3g}) at t = {:.6g} s with {} contacts; the "
                    "stiffness is too low for the load or the time step too large: try dt <= {:.3g} s (now {:.3g} s)",
                    ratio, m.def.max_overlap_ratio, st.time, st.contact_count, dt_hint(), dt));
  if (m.def.adaptive_time_step) choose_time_step(m, st);
  if (timed) st.timings.integration += seconds_since(t0);
  return status;
}

void set_thread_count(State& st, unsigned threads, unsigned min_hot_pairs_per_thread, bool tune) {
  detail::Workspace& ws = st.workspace.get();
  ws.threads = threads < 1 ? 1 : threads;
  ws.min_hot_pairs_per_thread = min_hot_pairs_per_thread < 1 ? 1 : min_hot_pairs_per_thread;
  ws.tuner.enabled = tune;
  if (ws.team.team && ws.team.team->members() > ws.threads) ws.team.team.reset();
}

unsigned thread_count(const State& st) { return st.workspace.get().threads; }

Status advance(const Model& m, State& st, std::uint64_t steps) {
  for (std::uint64_t i = 0; i < steps; ++i) {
    Status s = step(m, st);
    if (!s.ok()) return s;
  }
  return Ok{};
}

}  // namespace frictal::dem
