// frictal — spheropolygon engine: definitions to Model (validation, mass properties), the initial
// State and its private workspace, and the small helpers of the public header (energies, Eq. 12).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include <fmt/core.h>

#include "force_law.hpp"
#include "frictal/dem.hpp"
#include "integrator.hpp"
#include "neighbor_list.hpp"
#include "stability.hpp"
#include "workspace.hpp"

namespace frictal::dem {

namespace {

double cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// Orientation of (a, b, c): +1 counter-clockwise, -1 clockwise, 0 collinear.
int orient(double ax, double ay, double bx, double by, double cx, double cy) {
  const double v = cross(bx - ax, by - ay, cx - ax, cy - ay);
  return (v > 0) - (v < 0);
}

bool on_segment(double ax, double ay, double bx, double by, double px, double py) {
  return std::min(ax, bx) <= px && px <= std::max(ax, bx) && std::min(ay, by) <= py && py <= std::max(ay, by);
}

bool segments_intersect(double ax, double ay, double bx, double by, double cx, double cy, double dx, double dy) {
  const int o1 = orient(ax, ay, bx, by, cx, cy);
  const int o2 = orient(ax, ay, bx, by, dx, dy);
  const int o3 = orient(cx, cy, dx, dy, ax, ay);
  const int o4 = orient(cx, cy, dx, dy, bx, by);
  if (o1 != o2 && o3 != o4) return true;
  if (o1 == 0 && on_segment(ax, ay, bx, by, cx, cy)) return true;
  if (o2 == 0 && on_segment(ax, ay, bx, by, dx, dy)) return true;
  if (o3 == 0 && on_segment(cx, cy, dx, dy, ax, ay)) return true;
  if (o4 == 0 && on_segment(cx, cy, dx, dy, bx, by)) return true;
  return false;
}

// Finds two non-adjacent edges that touch or cross (sweep over edges sorted by min x).
// Returns -1 if the polygon is simple, else the index of one offending edge.
long first_self_intersection(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  auto xmin = [&](std::size_t i) { return std::min(x[i], x[(i + 1) % n]); };
  auto xmax = [&](std::size_t i) { return std::max(x[i], x[(i + 1) % n]); };
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return xmin(a) < xmin(b) || (xmin(a) == xmin(b) && a < b); });
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = order[k];
    const std::size_t i1 = (i + 1) % n;
    for (std::size_t m = k + 1; m < n && xmin(order[m]) <= xmax(i); ++m) {
      const std::size_t j = order[m];
      const std::size_t j1 = (j + 1) % n;
      if (j == i1 || i == j1) continue;  // adjacent edges share a vertex
      if (segments_intersect(x[i], y[i], x[i1], y[i1], x[j], y[j], x[j1], y[j1])) return static_cast<long>(i);
    }
  }
  return -1;
}

}  // namespace

StateWorkspace::StateWorkspace() : p_(std::make_unique<detail::Workspace>()) {}
StateWorkspace::~StateWorkspace() = default;
StateWorkspace::StateWorkspace(const StateWorkspace& other) : p_(std::make_unique<detail::Workspace>(*other.p_)) {}
StateWorkspace& StateWorkspace::operator=(const StateWorkspace& other) {
  if (this != &other) *p_ = *other.p_;
  return *this;
}
// A moved-from workspace gets a fresh empty one, so that every State stays usable.
StateWorkspace::StateWorkspace(StateWorkspace&& other) noexcept
    : p_(std::exchange(other.p_, std::make_unique<detail::Workspace>())) {}
StateWorkspace& StateWorkspace::operator=(StateWorkspace&& other) noexcept {
  std::swap(p_, other.p_);
  return *this;
}

BodyDef default_body_def() { return BodyDef{}; }
ContactParams default_contact_params() { return ContactParams{}; }
WorldDef default_world_def() { return WorldDef{}; }

Result<Model> make_model(const WorldDef& world, const std::vector<BodyDef>& bodies) {
  auto bad = [](const std::string& s) { return Result<Model>(make_error(s)); };
  auto finite_pos = [](double v) { return std::isfinite(v) && v > 0; };
  auto finite_nonneg = [](double v) { return std::isfinite(v) && v >= 0; };
  if (!finite_pos(world.time_step))
    return bad(fmt::format("world time_step = {} s: expected a finite value > 0", world.time_step));
  if (!finite_nonneg(world.skin))
    return bad(fmt::format("world skin = {} m: expected a finite value >= 0", world.skin));
  if (!finite_nonneg(world.hot_skin))
    return bad(fmt::format("world hot_skin = {} m: expected a finite value >= 0", world.hot_skin));
  if (!(std::isfinite(world.time_step_safety) && world.time_step_safety > 0 && world.time_step_safety <= 1))
    return bad(fmt::format("world time_step_safety = {}: expected a value in (0, 1]", world.time_step_safety));
  if (!std::isfinite(world.gravity.x) || !std::isfinite(world.gravity.y))
    return bad("world gravity: expected finite components");
  const ContactParams& c = world.contact;
  if (!finite_pos(c.normal_stiffness))
    return bad(fmt::format("contact normal_stiffness k_n = {} N/m: expected > 0", c.normal_stiffness));
  if (!finite_nonneg(c.tangential_stiffness))
    return bad(fmt::format("contact tangential_stiffness k_t = {} N/m: expected >= 0", c.tangential_stiffness));
  if (!finite_nonneg(c.normal_damping))
    return bad(fmt::format("contact normal_damping gamma_n = {} 1/s: expected >= 0", c.normal_damping));
  if (!finite_nonneg(c.tangential_damping))
    return bad(fmt::format("contact tangential_damping gamma_t = {} 1/s: expected >= 0", c.tangential_damping));
  if (!finite_nonneg(c.atomic_friction))
    return bad(fmt::format("contact atomic_friction mu_a = {}: expected >= 0", c.atomic_friction));
  if (c.law == ContactLaw::Hertz) {
    if (!finite_pos(c.contact_modulus))
      return bad(fmt::format("contact contact_modulus E* = {} Pa: expected a finite value > 0 (Hertz law)",
                             c.contact_modulus));
    if (!finite_nonneg(c.damping_ratio))
      return bad(
          fmt::format("contact damping_ratio zeta = {}: expected a finite value >= 0 (Hertz law)", c.damping_ratio));
    if (!finite_nonneg(c.tangential_ratio))
      return bad(
          fmt::format("contact tangential_ratio = {}: expected a finite value >= 0 (Hertz law)", c.tangential_ratio));
  } else if (c.law != ContactLaw::Linear) {
    return bad("contact law: expected Linear or Hertz");
  }
  if (!finite_pos(world.max_overlap_ratio)) return bad("world max_overlap_ratio: expected > 0");
  if (!finite_pos(world.max_speed)) return bad("world max_speed: expected > 0 m/s");
  if (world.max_steps_beyond_limit < 0) return bad("world max_steps_beyond_limit: expected >= 0");
  if (bodies.empty()) return bad("no bodies: expected at least one body definition");
  Model m;
  m.def = world;
  m.vertex_begin.push_back(0);
  bool any_dynamic = false;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const BodyDef& d = bodies[b];
    const std::string who = fmt::format("body {}", b);
    if (d.x.size() != d.y.size())
      return bad(fmt::format("{}: x has {} vertices but y has {}", who, d.x.size(), d.y.size()));
    const std::size_t n = d.x.size();
    if (n < 3) return bad(fmt::format("{}: {} vertices, expected at least 3", who, n));
    if (m.local_x.size() + n >= (std::size_t{1} << 31)) return bad(fmt::format("{}: too many vertices in total", who));
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isfinite(d.x[i]) || !std::isfinite(d.y[i]))
        return bad(fmt::format("{}: vertex {} is not finite", who, i));
    for (std::size_t i = 0; i < n; ++i)
      if (d.x[i] == d.x[(i + 1) % n] && d.y[i] == d.y[(i + 1) % n])
        return bad(fmt::format("{}: vertices {} and {} coincide (zero-length edge; do not repeat the closing point)",
                               who, i, (i + 1) % n));
    if (!finite_pos(d.radius))
      return bad(fmt::format("{}: radius = {} m, expected a finite spheroradius > 0", who, d.radius));
    if (!finite_pos(d.density)) return bad(fmt::format("{}: density = {} kg/m^2, expected > 0", who, d.density));
    // Mass properties about the first vertex (better conditioned), then shifted.
    double a2 = 0, sx = 0, sy = 0, ixx = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = (i + 1) % n;
      const double xi = d.x[i] - d.x[0], yi = d.y[i] - d.y[0];
      const double xj = d.x[j] - d.x[0], yj = d.y[j] - d.y[0];
      const double cr = cross(xi, yi, xj, yj);
      a2 += cr;
      sx += (xi + xj) * cr;
      sy += (yi + yj) * cr;
      ixx += cr * (xi * xi + xi * xj + xj * xj + yi * yi + yi * yj + yj * yj);
    }
    double area = 0.5 * a2;
    if (const long e = first_self_intersection(d.x, d.y); e >= 0)
      return bad(fmt::format("{}: polygon is not simple (edge {} from ({}, {}) touches or crosses a non-adjacent edge)",
                             who, e, d.x[static_cast<std::size_t>(e)], d.y[static_cast<std::size_t>(e)]));
    if (!(std::fabs(area) > 0)) return bad(fmt::format("{}: polygon has zero area", who));
    const bool ccw = area > 0;
    const double cx = sx / (3.0 * a2), cy = sy / (3.0 * a2);
    const double i_origin = ixx / 12.0;  // signed like area
    area = std::fabs(area);
    const double i_c = std::fabs(i_origin) - area * (cx * cx + cy * cy);
    const Vec2 centroid{d.x[0] + cx, d.y[0] + cy};
    const std::uint32_t base = static_cast<std::uint32_t>(m.local_x.size());
    double ext = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = ccw ? k : n - 1 - k;
      const double lx = d.x[i] - centroid.x, ly = d.y[i] - centroid.y;
      m.local_x.push_back(lx);
      m.local_y.push_back(ly);
      m.vertex_body.push_back(static_cast<std::uint32_t>(b));
      m.next_vertex.push_back(base + static_cast<std::uint32_t>((k + 1) % n));
      ext = std::max(ext, std::hypot(lx, ly));
    }
    for (std::size_t k = base; k < m.local_x.size(); ++k) {
      const std::size_t j = m.next_vertex[k];
      const double ex = m.local_x[j] - m.local_x[k], ey = m.local_y[j] - m.local_y[k];
      m.edge_inv_length2.push_back(1.0 / (ex * ex + ey * ey));
    }
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t v = base + k, p = base + (k + n - 1) % n, q = base + (k + 1) % n;
      const double turn = (m.local_x[v] - m.local_x[p]) * (m.local_y[q] - m.local_y[v]) -
                          (m.local_y[v] - m.local_y[p]) * (m.local_x[q] - m.local_x[v]);
      m.convex_vertex.push_back(turn >= 0 ? 1 : 0);
    }
    if (c.law == ContactLaw::Hertz) {
      // Radius of the circle through each vertex and its neighbours, between r and the extent.
      const double r_max = ext + d.radius;
      double r_lo = r_max, r_hi = 0;
      for (std::size_t k = 0; k < n; ++k) {
        const std::size_t v = base + k, p = base + (k + n - 1) % n, q = base + (k + 1) % n;
        const double ax = m.local_x[v] - m.local_x[p], ay = m.local_y[v] - m.local_y[p];
        const double bx = m.local_x[q] - m.local_x[v], by = m.local_y[q] - m.local_y[v];
        const double cx2 = m.local_x[q] - m.local_x[p], cy2 = m.local_y[q] - m.local_y[p];
        const double turn = cross(ax, ay, bx, by);  // > 0: convex (counter-clockwise)
        double rc = r_max;
        if (turn > 0) rc = std::hypot(ax, ay) * std::hypot(bx, by) * std::hypot(cx2, cy2) / (2.0 * turn);
        rc = std::clamp(rc, d.radius, r_max);
        m.curvature_radius.push_back(rc);
        r_lo = std::min(r_lo, rc);
        r_hi = std::max(r_hi, rc);
      }
      m.hertz_coeff_min.push_back(4.0 / 3.0 * c.contact_modulus * std::sqrt(r_lo));
      m.hertz_coeff_max.push_back(4.0 / 3.0 * c.contact_modulus * std::sqrt(r_hi));
    }
    m.vertex_begin.push_back(static_cast<std::uint32_t>(m.local_x.size()));
    m.radius.push_back(d.radius);
    m.area.push_back(area);
    m.mass.push_back(d.density * area);
    m.inertia.push_back(d.density * i_c);
    m.extent.push_back(ext + d.radius);
    m.type.push_back(d.type);
    m.motion.push_back(d.motion);
    m.rotation_follows.push_back(d.rotation_follows);
    m.initial_position.push_back(centroid);
    if (d.type == BodyType::Dynamic) {
      any_dynamic = true;
      if (!std::isfinite(d.velocity.x) || !std::isfinite(d.velocity.y) || !std::isfinite(d.angular_velocity))
        return bad(fmt::format("{}: initial velocity must be finite", who));
      m.initial_velocity.push_back(d.velocity);
      m.initial_angular_velocity.push_back(d.angular_velocity);
    } else {
      if (!std::isfinite(d.motion.pivot.x) || !std::isfinite(d.motion.pivot.y) ||
          !std::isfinite(d.motion.angular_velocity) || !std::isfinite(d.motion.start_time))
        return bad(fmt::format("{}: kinematic motion (pivot, angular_velocity, start_time) must be finite", who));
      m.initial_velocity.push_back({0, 0});
      m.initial_angular_velocity.push_back(0);
    }
  }
  if (!any_dynamic) return bad("no dynamic body: expected at least one body of type Dynamic");
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const int f = bodies[b].rotation_follows;
    if (f == -1) continue;
    if (bodies[b].type != BodyType::Dynamic || f < 0 || static_cast<std::size_t>(f) >= bodies.size() ||
        bodies[static_cast<std::size_t>(f)].type != BodyType::Kinematic)
      return bad(
          fmt::format("body {}: rotation_follows = {}: expected -1 or the index of a kinematic body (and a "
                      "dynamic body {})",
                      b, f, b));
    m.initial_angular_velocity[b] = 0;
  }
  return m;
}

State make_state(const Model& m) {
  using namespace detail;
  const std::size_t nb = m.body_count();
  State st;
  Workspace& ws = st.workspace.get();
  st.position = m.initial_position;
  st.angle.assign(nb, 0.0);
  st.velocity = m.initial_velocity;
  st.angular_velocity = m.initial_angular_velocity;
  st.force.assign(nb, {0, 0});
  st.torque.assign(nb, 0.0);
  st.body_contacts.assign(nb, 0);
  st.step_limit.assign(nb, std::numeric_limits<double>::infinity());
  st.time_step = m.def.time_step;
  for (std::size_t b = 0; b < nb; ++b)
    if (m.type[b] == BodyType::Kinematic) kinematic_pose(m, b, 0.0, st);
  follow_rotations(m, st);
  update_rotation(st, ws);
  build_neighbor_list(m, st, ws);
  compute_forces(m, st, ws, 0.0);
  if (m.def.adaptive_time_step) choose_time_step(m, st);
  return st;
}

Vec2 world_vertex(const Model& m, const State& st, std::uint32_t v) {
  const std::uint32_t b = m.vertex_body[v];
  const double c = std::cos(st.angle[b]), s = std::sin(st.angle[b]);
  return {st.position[b].x + (c * m.local_x[v] - s * m.local_y[v]),
          st.position[b].y + (s * m.local_x[v] + c * m.local_y[v])};
}

std::vector<ContactForce> contact_forces(const Model& m, const State& st) {
  const ContactParams& cp = m.def.contact;
  std::vector<ContactForce> out;
  for (const NeighborPair& p : st.pairs) {
    if (!(p.overlap > 0)) continue;  // apart (pairs are reset to <= 0 when they separate)
    const std::uint32_t a = p.vbody, b = p.ebody;
    const Vec2 v = world_vertex(m, st, p.vertex), e0 = world_vertex(m, st, p.edge0), e1 = world_vertex(m, st, p.edge1);
    const double dx = e1.x - e0.x, dy = e1.y - e0.y, l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((v.x - e0.x) * dx + (v.y - e0.y) * dy) / l2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    const double sx = v.x - (e0.x + t * dx), sy = v.y - (e0.y + t * dy);
    const double dist = std::hypot(sx, sy);
    const double overlap = m.radius[a] + m.radius[b] - dist;
    if (!(overlap > 0)) continue;
    double nx, ny;
    if (dist > 0) {
      nx = sx / dist, ny = sy / dist;
    } else {
      const double l = std::sqrt(l2);
      nx = dy / l, ny = -dx / l;
    }
    const double cx = v.x - nx * (m.radius[a] - 0.5 * overlap), cy = v.y - ny * (m.radius[a] - 0.5 * overlap);
    const double rax = cx - st.position[a].x, ray = cy - st.position[a].y;
    const double rbx = cx - st.position[b].x, rby = cy - st.position[b].y;
    const double wa = st.angular_velocity[a], wb = st.angular_velocity[b];
    const double relx = (st.velocity[a].x - wa * ray) - (st.velocity[b].x - wb * rby);
    const double rely = (st.velocity[a].y + wa * rax) - (st.velocity[b].y + wb * rbx);
    const double vn = relx * nx + rely * ny, vt = -relx * ny + rely * nx;
    ContactForce c;
    c.vertex_body = a;
    c.edge_body = b;
    c.point = {cx, cy};
    c.normal = {nx, ny};
    c.overlap = overlap;
    if (cp.law == ContactLaw::Hertz) {
      const detail::HertzPair h = detail::hertz_pair(m, p.vertex, p.edge0, p.edge1, t, overlap, p.reduced_mass);
      c.curvature_radius = h.radius;
      c.normal_force = h.force - h.damping * vn;
      c.tangential_force = -h.tangential_stiffness * p.elongation - p.reduced_mass * cp.tangential_damping * vt;
    } else {
      c.normal_force = cp.normal_stiffness * overlap - p.reduced_mass * cp.normal_damping * vn;
      c.tangential_force = -cp.tangential_stiffness * p.elongation - p.reduced_mass * cp.tangential_damping * vt;
    }
    out.push_back(c);
  }
  return out;
}

double kinetic_energy(const Model& m, const State& st, std::size_t b) {
  const Vec2 v = st.velocity[b];
  return 0.5 * m.mass[b] * (v.x * v.x + v.y * v.y) +
         0.5 * m.inertia[b] * st.angular_velocity[b] * st.angular_velocity[b];
}

Result<double> damping_from_restitution(double eps, double k_n, double m) {
  if (!(eps > 0 && eps <= 1)) return make_error(fmt::format("restitution eps = {}: expected 0 < eps <= 1", eps));
  if (!(k_n > 0) || !std::isfinite(k_n)) return make_error(fmt::format("k_n = {} N/m: expected > 0", k_n));
  if (!(m > 0) || !std::isfinite(m)) return make_error(fmt::format("mass = {} kg: expected > 0", m));
  // ln(1/eps) = (gamma/2) pi / sqrt(k/m - gamma^2/4)  =>  gamma = 2 L sqrt(k/m) / sqrt(pi^2 + L^2)
  const double L = -std::log(eps);
  const double pi = 3.14159265358979323846;
  return 2.0 * L * std::sqrt(k_n / m) / std::sqrt(pi * pi + L * L);
}

double hertz_restitution(double zeta) {
  if (!(zeta > 0)) return 1.0;
  // Units with m = 1, c = (4/3) E* sqrt(R) = 1 and impact speed 1 (the restitution depends on
  // none of them): x'' = -x^1.5 - 2 zeta sqrt(1.5 sqrt(x)) x' from x = 0, x' = 1, to x = 0 again
  // (RK4; the overlap is ~1 and the contact lasts ~3 time units).
  auto acc = [zeta](double x, double v) {
    const double xp = x > 0 ? x : 0.0;
    return -xp * std::sqrt(xp) - 2.0 * zeta * std::sqrt(1.5 * std::sqrt(xp)) * v;
  };
  const double h = 1e-4;
  double x = 0, v = 1;
  for (int i = 0; i < 2000000; ++i) {  // 200 time units: an overdamped contact that never parts gives 0
    const double k1x = v, k1v = acc(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = acc(x + h * k3x, v + h * k3v);
    const double xn = x + h / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
    const double vn = v + h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (xn <= 0 && vn < 0) {  // parted within this step: the speed where x crosses 0 (linear)
      const double s = x / (x - xn);
      return std::max(0.0, -(v + s * (vn - v)));
    }
    x = xn, v = vn;
  }
  return 0.0;
}

Result<double> hertz_damping_ratio(double eps) {
  if (!(eps > 0 && eps <= 1)) return make_error(fmt::format("restitution eps = {}: expected 0 < eps <= 1", eps));
  if (eps == 1) return 0.0;
  double lo = 0, hi = 1;
  while (hertz_restitution(hi) > eps) {
    if (hi > 1e3) return make_error(fmt::format("restitution eps = {}: below what a Hertz dashpot gives", eps));
    hi *= 2;
  }
  for (int i = 0; i < 40; ++i) {
    const double mid = 0.5 * (lo + hi);
    (hertz_restitution(mid) > eps ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double restitution_from_damping(double gamma_n, double k_n, double m) {
  const double w2 = k_n / m - 0.25 * gamma_n * gamma_n;
  if (!(w2 > 0)) return 0.0;
  return std::exp(-0.5 * gamma_n * 3.14159265358979323846 / std::sqrt(w2));
}

}  // namespace frictal::dem
