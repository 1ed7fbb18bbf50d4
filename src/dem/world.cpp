// frictal — spheropolygon rigid-body dynamics: model creation, neighbour list, contact forces,
// velocity-Verlet integration. See include/frictal/dem.hpp and docs/dem.md.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include <fmt/core.h>

#include "frictal/dem.hpp"

namespace frictal::dem {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// Orientation of (a, b, c): +1 counter-clockwise, -1 clockwise, 0 collinear.
int orient(double ax, double ay, double bx, double by, double cx, double cy) {
  const double v = cross(bx - ax, by - ay, cx - ax, cy - ay);
  return (v > 0) - (v < 0);
}

bool on_segment(double ax, double ay, double bx, double by, double px, double py) {
  return std::min(ax, bx) <= px && px <= std::max(ax, bx) && std::min(ay, by) <= py &&
         py <= std::max(ay, by);
}

bool segments_intersect(double ax, double ay, double bx, double by, double cx, double cy,
                        double dx, double dy) {
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
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return xmin(a) < xmin(b) || (xmin(a) == xmin(b) && a < b);
  });
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = order[k];
    const std::size_t i1 = (i + 1) % n;
    for (std::size_t m = k + 1; m < n && xmin(order[m]) <= xmax(i); ++m) {
      const std::size_t j = order[m];
      const std::size_t j1 = (j + 1) % n;
      if (j == i1 || i == j1) continue;  // adjacent edges share a vertex
      if (segments_intersect(x[i], y[i], x[i1], y[i1], x[j], y[j], x[j1], y[j1]))
        return static_cast<long>(i);
    }
  }
  return -1;
}

struct Pose {
  double px, py, c, s;
};

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

// cos and sin of every body's angle, once per step for the list test, the hot-list test, the
// list builder and the contact loop.
void update_rotation(State& st) {
  st.rotation.resize(st.angle.size());
  for (std::size_t b = 0; b < st.angle.size(); ++b) st.rotation[b] = {std::cos(st.angle[b]), std::sin(st.angle[b])};
}

// Largest possible displacement of any vertex of body b between poses.
double motion_bound(const Model& m, std::size_t b, Vec2 p0, double a0, Vec2 p1, double a1) {
  return std::hypot(p1.x - p0.x, p1.y - p0.y) + std::fabs(a1 - a0) * m.extent[b];
}

// Largest change, between poses 0 and 1, of the distance between a vertex of one body and an
// edge of another. Distances are invariant under rigid motion, so it is measured in the edge
// body's frame, where the edge is fixed and the vertex moves with the relative motion of its body:
// by at most |change of the relative centroid position| + |change of the relative angle| x extent.
// Two bodies that move together (a block stuck on a tilting block) give ~0, however fast they
// move. Small body counts only (O(bodies^2)); else the sum of the two largest absolute bounds.
// r0, r1: cos and sin of the angles a0, a1 (cached, see State::rotation).
double relative_motion_bound(const Model& m, const std::vector<Vec2>& p0, const std::vector<double>& a0,
                             const std::vector<Rotation>& r0, const std::vector<Vec2>& p1,
                             const std::vector<double>& a1, const std::vector<Rotation>& r1) {
  const std::size_t nb = m.body_count();
  double worst = 0;
  if (nb <= 8) {
    for (std::size_t b = 0; b < nb; ++b) {  // edge body
      const double c0 = r0[b].c, s0 = r0[b].s;
      const double c1 = r1[b].c, s1 = r1[b].s;
      for (std::size_t a = 0; a < nb; ++a) {  // vertex body
        if (a == b || (m.type[a] == BodyType::Kinematic && m.type[b] == BodyType::Kinematic)) continue;
        // Centroid of a in b's frame: R(-angle_b) (p_a - p_b).
        const double dx0 = p0[a].x - p0[b].x, dy0 = p0[a].y - p0[b].y;
        const double dx1 = p1[a].x - p1[b].x, dy1 = p1[a].y - p1[b].y;
        const double qx0 = c0 * dx0 + s0 * dy0, qy0 = -s0 * dx0 + c0 * dy0;
        const double qx1 = c1 * dx1 + s1 * dy1, qy1 = -s1 * dx1 + c1 * dy1;
        const double turn = std::fabs((a1[a] - a1[b]) - (a0[a] - a0[b]));
        worst = std::max(worst, std::hypot(qx1 - qx0, qy1 - qy0) + turn * m.extent[a]);
      }
    }
    return worst;
  }
  double b1 = 0, b2 = 0;
  for (std::size_t b = 0; b < nb; ++b) {
    const double d = motion_bound(m, b, p0[b], a0[b], p1[b], a1[b]);
    if (d > b1) b2 = b1, b1 = d;
    else if (d > b2) b2 = d;
  }
  return b1 + b2;
}

void build_neighbor_list(const Model& m, State& st) {
  const std::size_t nb = m.body_count();
  const std::size_t nv = m.local_x.size();
  // World coordinates of every vertex: the one O(N) part of the engine, run only on rebuilds.
  std::vector<double> wx(nv), wy(nv);
  std::vector<double> bx0(nb), bx1(nb), by0(nb), by1(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    const double c = st.rotation[b].c, s = st.rotation[b].s;
    const Vec2 p = st.position[b];
    double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
    for (std::uint32_t v = m.vertex_begin[b]; v < m.vertex_begin[b + 1]; ++v) {
      wx[v] = p.x + (c * m.local_x[v] - s * m.local_y[v]);
      wy[v] = p.y + (s * m.local_x[v] + c * m.local_y[v]);
      x0 = std::min(x0, wx[v]);
      x1 = std::max(x1, wx[v]);
      y0 = std::min(y0, wy[v]);
      y1 = std::max(y1, wy[v]);
    }
    bx0[b] = x0, bx1[b] = x1, by0[b] = y0, by1[b] = y1;
  }
  std::vector<NeighborPair>& out = st.scratch_pairs;
  out.clear();
  std::vector<std::uint32_t> edges, verts;
  for (std::size_t a = 0; a < nb; ++a) {
    for (std::size_t b = 0; b < nb; ++b) {
      if (a == b) continue;
      if (m.type[a] == BodyType::Kinematic && m.type[b] == BodyType::Kinematic) continue;
      const double cut = m.radius[a] + m.radius[b] + m.def.skin;
      const double inv_a = m.type[a] == BodyType::Dynamic ? 1.0 / m.mass[a] : 0.0;
      const double inv_b = m.type[b] == BodyType::Dynamic ? 1.0 / m.mass[b] : 0.0;
      const double mred = 1.0 / (inv_a + inv_b);
      const double rx0 = std::max(bx0[a], bx0[b]) - cut, rx1 = std::min(bx1[a], bx1[b]) + cut;
      const double ry0 = std::max(by0[a], by0[b]) - cut, ry1 = std::min(by1[a], by1[b]) + cut;
      if (rx0 > rx1 || ry0 > ry1) continue;
      edges.clear();
      verts.clear();
      double total_len = 0;
      for (std::uint32_t i = m.vertex_begin[b]; i < m.vertex_begin[b + 1]; ++i) {
        const std::uint32_t j = m.next_vertex[i];
        const double ex0 = std::min(wx[i], wx[j]) - cut, ex1 = std::max(wx[i], wx[j]) + cut;
        const double ey0 = std::min(wy[i], wy[j]) - cut, ey1 = std::max(wy[i], wy[j]) + cut;
        if (ex1 < rx0 || ex0 > rx1 || ey1 < ry0 || ey0 > ry1) continue;
        edges.push_back(i);
        total_len += std::hypot(wx[j] - wx[i], wy[j] - wy[i]);
      }
      for (std::uint32_t v = m.vertex_begin[a]; v < m.vertex_begin[a + 1]; ++v) {
        if (wx[v] < rx0 || wx[v] > rx1 || wy[v] < ry0 || wy[v] > ry1) continue;
        verts.push_back(v);
      }
      if (edges.empty() || verts.empty()) continue;
      // Uniform grid over the region; each edge goes into every cell its cut-inflated box
      // touches, so a vertex needs only its own cell.
      const double w = rx1 - rx0, h = ry1 - ry0;
      double cell = std::max(cut, total_len / static_cast<double>(edges.size()));
      const double max_cells = 4.0 * static_cast<double>(edges.size() + verts.size()) + 64.0;
      auto ncell = [&](double len) { return std::max(1.0, std::ceil(len / cell)); };
      while (ncell(w) * ncell(h) > max_cells) cell *= 1.5;
      const std::size_t nx = static_cast<std::size_t>(ncell(w));
      const std::size_t ny = static_cast<std::size_t>(ncell(h));
      const double inv = 1.0 / cell;
      auto cx = [&](double x) {
        const double f = std::floor((x - rx0) * inv);
        return static_cast<std::size_t>(std::clamp(f, 0.0, static_cast<double>(nx - 1)));
      };
      auto cy = [&](double y) {
        const double f = std::floor((y - ry0) * inv);
        return static_cast<std::size_t>(std::clamp(f, 0.0, static_cast<double>(ny - 1)));
      };
      std::vector<std::uint32_t>& start = st.scratch_cells;
      std::vector<std::uint32_t>& items = st.scratch_items;
      start.assign(nx * ny + 1, 0);
      for (int pass = 0; pass < 2; ++pass) {
        for (std::uint32_t i : edges) {
          const std::uint32_t j = m.next_vertex[i];
          const std::size_t ix0 = cx(std::min(wx[i], wx[j]) - cut), ix1 = cx(std::max(wx[i], wx[j]) + cut);
          const std::size_t iy0 = cy(std::min(wy[i], wy[j]) - cut), iy1 = cy(std::max(wy[i], wy[j]) + cut);
          for (std::size_t iy = iy0; iy <= iy1; ++iy)
            for (std::size_t ix = ix0; ix <= ix1; ++ix) {
              const std::size_t k = iy * nx + ix;
              if (pass == 0) ++start[k + 1];
              else items[start[k]++] = i;
            }
        }
        if (pass == 0) {
          for (std::size_t k = 0; k < nx * ny; ++k) start[k + 1] += start[k];
          items.resize(start[nx * ny]);
        }
      }
      // After the fill pass start[k] points at the end of cell k, i.e. the start of cell k+1.
      const double cut2 = cut * cut;
      for (std::uint32_t v : verts) {
        const std::size_t k = cy(wy[v]) * nx + cx(wx[v]);
        const std::uint32_t lo = k == 0 ? 0 : start[k - 1], hi = start[k];
        for (std::uint32_t it = lo; it < hi; ++it) {
          const std::uint32_t i = items[it];
          const std::uint32_t j = m.next_vertex[i];
          const double dx = wx[j] - wx[i], dy = wy[j] - wy[i];
          const double px = wx[v] - wx[i], py = wy[v] - wy[i];
          const double len2 = dx * dx + dy * dy;
          double t = len2 > 0 ? (px * dx + py * dy) / len2 : 0.0;
          t = std::clamp(t, 0.0, 1.0);
          const double qx = px - t * dx, qy = py - t * dy;
          if (qx * qx + qy * qy >= cut2) continue;
          NeighborPair p;
          p.key = (static_cast<std::uint64_t>(v) << 32) | i;
          p.vertex = v;
          p.edge0 = i;
          p.edge1 = j;
          p.vbody = static_cast<std::uint32_t>(a);
          p.ebody = static_cast<std::uint32_t>(b);
          p.reduced_mass = mred;
          p.overlap = -1;
          out.push_back(p);
        }
      }
    }
  }
  std::sort(out.begin(), out.end(),
            [](const NeighborPair& l, const NeighborPair& r) { return l.key < r.key; });
  // Carry the tangential springs of pairs that stay in the list.
  std::size_t o = 0;
  for (NeighborPair& p : out) {
    while (o < st.pairs.size() && st.pairs[o].key < p.key) ++o;
    if (o < st.pairs.size() && st.pairs[o].key == p.key) {
      p.elongation = st.pairs[o].elongation;
      p.overlap = st.pairs[o].overlap;
    }
  }
  st.pairs.swap(out);
  // Compact the referenced vertices into slots.
  std::vector<std::uint32_t>& slot = st.scratch_slot;
  slot.assign(nv, std::numeric_limits<std::uint32_t>::max());
  st.active_vertex.clear();
  for (const NeighborPair& p : st.pairs) {
    slot[p.vertex] = 0;
    slot[p.edge0] = 0;
    slot[p.edge1] = 0;
  }
  for (std::uint32_t v = 0; v < nv; ++v)
    if (slot[v] == 0) {
      slot[v] = static_cast<std::uint32_t>(st.active_vertex.size());
      st.active_vertex.push_back(v);
    }
  for (NeighborPair& p : st.pairs) {
    p.slot_vertex = slot[p.vertex];
    p.slot_edge0 = slot[p.edge0];
    p.slot_edge1 = slot[p.edge1];
  }
  st.active_x.resize(st.active_vertex.size());
  st.active_y.resize(st.active_vertex.size());
  for (std::size_t b = 0; b < nb; ++b) {
    st.list_position[b] = st.position[b];
    st.list_angle[b] = st.angle[b];
    st.list_rotation[b] = st.rotation[b];
  }
  st.hot.valid = false;
  ++st.timings.list_builds;
}

// Sums over a body's contacts of J J^T with J = (n_x, n_y, r x n): unweighted (g) and weighted
// by the reduced mass (gm). Symmetric 3x3, stored xx, xy, xt, yy, yt, tt.
struct ModeSums {
  double g[6] = {0, 0, 0, 0, 0, 0};
  double gm[6] = {0, 0, 0, 0, 0, 0};
};

void add_outer(ModeSums& s, double jx, double jy, double jt, double w) {
  const double v[6] = {jx * jx, jx * jy, jx * jt, jy * jy, jy * jt, jt * jt};
  for (int i = 0; i < 6; ++i) {
    s.g[i] += v[i];
    s.gm[i] += w * v[i];
  }
}

// Largest eigenvalue of a symmetric 3x3 matrix (closed form, Smith 1961).
double max_eigenvalue(const double a[6]) {
  const double xx = a[0], xy = a[1], xt = a[2], yy = a[3], yt = a[4], tt = a[5];
  const double q = (xx + yy + tt) / 3.0;
  const double p1 = xy * xy + xt * xt + yt * yt;
  const double p2 = (xx - q) * (xx - q) + (yy - q) * (yy - q) + (tt - q) * (tt - q) + 2.0 * p1;
  if (p2 <= 0) return q;
  const double p = std::sqrt(p2 / 6.0);
  const double bxx = (xx - q) / p, byy = (yy - q) / p, btt = (tt - q) / p, bxy = xy / p, bxt = xt / p,
               byt = yt / p;
  const double det = bxx * (byy * btt - byt * byt) - bxy * (bxy * btt - byt * bxt) + bxt * (bxy * byt - byy * bxt);
  const double r = std::clamp(det / 2.0, -1.0, 1.0);
  const double phi = std::acos(r) / 3.0;
  return q + 2.0 * p * std::cos(phi);
}

// Explicit stability limit of one body from its contact modes: the stiffest mode
// omega^2 = lambda_max(M^-1/2 k_n G M^-1/2) and the fastest damping rate
// lambda_max(M^-1/2 gamma_n G_m M^-1/2); dt < min(2 / omega, 2 / rate).
double mode_limit(const ModeSums& s, double mass, double inertia, double kn, double gn) {
  const double sm = 1.0 / mass, si = 1.0 / std::sqrt(mass * inertia), sii = 1.0 / inertia;
  const double scale[6] = {sm, sm, si, sm, si, sii};
  double k[6], c[6];
  for (int i = 0; i < 6; ++i) {
    k[i] = kn * s.g[i] * scale[i];
    c[i] = gn * s.gm[i] * scale[i];
  }
  const double w2 = max_eigenvalue(k);
  double limit = w2 > 0 ? 2.0 / std::sqrt(w2) : std::numeric_limits<double>::infinity();
  const double rate = max_eigenvalue(c);
  if (rate > 0) limit = std::min(limit, 2.0 / rate);
  return limit;
}

// Fills the hot list's arrays for the pairs in st.hot.pair (found by a full pass at the current
// poses): vertex in its body's frame, edge in the edge body's frame (both constant), the filter
// radius, and the runs of equal (vertex body, edge body).
void refresh_hot_list(const Model& m, State& st) {
  HotList& h = st.hot;
  const std::size_t n = h.pair.size();
  for (auto* v : {&h.vx, &h.vy, &h.e0x, &h.e0y, &h.e1x, &h.e1y, &h.dx, &h.dy, &h.inv_len2, &h.cut2}) v->resize(n);
  h.keep.resize(n);
  h.run_begin.clear();
  h.run_vbody.clear();
  h.run_ebody.clear();
  for (std::size_t k = 0; k < n; ++k) {
    const NeighborPair& p = st.pairs[h.pair[k]];
    h.vx[k] = m.local_x[p.vertex];
    h.vy[k] = m.local_y[p.vertex];
    h.e0x[k] = m.local_x[p.edge0];
    h.e0y[k] = m.local_y[p.edge0];
    h.e1x[k] = m.local_x[p.edge1];
    h.e1y[k] = m.local_y[p.edge1];
    h.dx[k] = m.local_x[p.edge1] - m.local_x[p.edge0];
    h.dy[k] = m.local_y[p.edge1] - m.local_y[p.edge0];
    h.inv_len2[k] = m.edge_inv_length2[p.edge0];
    const double cut = (m.radius[p.vbody] + m.radius[p.ebody]) * (1.0 + 1e-3);
    h.cut2[k] = cut * cut;
    if (k == 0 || p.vbody != h.run_vbody.back() || p.ebody != h.run_ebody.back()) {
      h.run_begin.push_back(static_cast<std::uint32_t>(k));
      h.run_vbody.push_back(p.vbody);
      h.run_ebody.push_back(p.ebody);
    }
  }
  h.run_begin.push_back(static_cast<std::uint32_t>(n));
  h.position = st.position;
  h.angle = st.angle;
  h.rotation = st.rotation;
  h.valid = true;
  ++st.timings.hot_refreshes;
}

// Contact forces at the current poses and velocities. `dt_spring` is the time over which the
// tangential springs are stretched (dt in a step, 0 for the initial evaluation).
// Returns the largest overlap / (r1 + r2) among pairs above the guard ratio, else 0.
double compute_forces(const Model& m, State& st, double dt_spring) {
  const std::size_t nb = m.body_count();
  const ContactParams& cp = m.def.contact;
  // Per-body pose cache and inverse masses (kinematic bodies: 0).
  Pose pose[64];
  std::vector<Pose> pose_heap;
  Pose* ps = pose;
  if (nb > 64) {
    pose_heap.resize(nb);
    ps = pose_heap.data();
  }
  int body_contacts_buf[64];
  std::vector<int> body_contacts_heap;
  int* body_contacts = body_contacts_buf;
  ModeSums jac_buf[64];
  std::vector<ModeSums> jac_heap;
  ModeSums* jac = jac_buf;
  double inv_mass_buf[64];
  std::vector<double> inv_mass_heap;
  double* inv_mass_of = inv_mass_buf;
  if (nb > 64) {
    body_contacts_heap.resize(nb);
    body_contacts = body_contacts_heap.data();
    jac_heap.resize(nb);
    jac = jac_heap.data();
    inv_mass_heap.resize(nb);
    inv_mass_of = inv_mass_heap.data();
  }
  for (std::size_t b = 0; b < nb; ++b) {
    body_contacts[b] = 0;
    jac[b] = ModeSums{};
    inv_mass_of[b] = m.type[b] == BodyType::Dynamic ? 1.0 / m.mass[b] : 0.0;
    ps[b] = {st.position[b].x, st.position[b].y, st.rotation[b].c, st.rotation[b].s};
    st.force[b] = {0, 0};
    st.torque[b] = 0;
  }
  // Hot list (docs/dem.md sec. 2): a full pass over the list records which pairs are within
  // r1 + r2 + hot_skin; until the bodies have moved by more than hot_skin / 2 since that pass, the
  // others are at least hot_skin / 2 apart and are skipped. A skipped pair is apart, and its
  // spring was reset in the full pass, so the forces, their summation order and every per-pair
  // state are exactly those of a pass over the whole list.
  const double hot_skin = m.def.hot_skin;
  bool full = !st.hot.valid;
  if (!full) full = 2.0 * relative_motion_bound(m, st.hot.position, st.hot.angle, st.hot.rotation, st.position, st.angle, st.rotation) > hot_skin;
  int contacts = 0;
  double max_ov = 0, max_ratio = 0, energy = 0;
  const double* lx = m.local_x.data();
  const double* ly = m.local_y.data();
  // Local copies of everything the loop reads, so that the force stores cannot alias them.
  const double* const __restrict radius = m.radius.data();
  const double* const __restrict inv_len2 = m.edge_inv_length2.data();
  const double kn = cp.normal_stiffness, kt = cp.tangential_stiffness, mu = cp.atomic_friction;
  const double gn = cp.normal_damping, gt = cp.tangential_damping;
  const double guard = m.def.max_overlap_ratio;
  // Three passes, each in list order (docs/dem.md sec. 7). (1) Distances: the touching pairs and
  // their geometry go to a scratch list; the other pairs only reset their springs. (2) Forces of
  // the touching pairs, each independent of the others, so that the long sqrt / division chains
  // of successive contacts can overlap. (3) The sums per body, in the same order as a single
  // pass, so the results are bitwise those of one loop over the pairs.
  NeighborPair* const pairs = st.pairs.data();
  HotList& hot = st.hot;
  const std::size_t count = full ? st.pairs.size() : hot.pair.size();
  // Grown, never shrunk; filled field by field (no temporary to copy).
  if (st.scratch_contacts.size() < count) st.scratch_contacts.resize(count);
  ContactScratch* const touching = st.scratch_contacts.data();
  std::size_t n_touching = 0;
  // The exact test of one pair from the world positions of its vertex and edge: every decision
  // (touching, spring reset) is taken here, in the world frame, as in a plain loop over the list.
  auto classify = [&](std::uint32_t index, double vx, double vy, double e0x, double e0y, double e1x,
                      double e1y) -> double {
    NeighborPair& p = pairs[index];
    const double dx = e1x - e0x, dy = e1y - e0y;
    double t = ((vx - e0x) * dx + (vy - e0y) * dy) * inv_len2[p.edge0];
    t = std::clamp(t, 0.0, 1.0);
    const double sx = vx - (e0x + t * dx), sy = vy - (e0y + t * dy);
    const double dist2 = sx * sx + sy * sy;
    const double rsum = radius[p.vbody] + radius[p.ebody];
    // Written for every pair and kept only if it touches (n_touching <= pairs seen, so the slot
    // exists): no branch on touch / apart, close to a coin toss in the hot list.
    ContactScratch& c = touching[n_touching];
    c.pair = index;
    c.sx = sx, c.sy = sy, c.dist2 = dist2, c.dx = dx, c.dy = dy, c.vx = vx, c.vy = vy;
    const bool touch = dist2 < rsum * rsum;
    n_touching += touch ? 1 : 0;
    if (!touch && p.overlap > -1) {  // write only on the transition (most pairs stay apart)
      p.elongation = 0;
      p.overlap = -1;
    }
    return dist2;
  };
  if (full) {
    // World positions of the vertices the list refers to, one transform each.
    double* wx = st.active_x.data();
    double* wy = st.active_y.data();
    for (std::size_t k = 0; k < st.active_vertex.size(); ++k) {
      const std::uint32_t v = st.active_vertex[k];
      const Pose& P = ps[m.vertex_body[v]];
      wx[k] = P.px + (P.c * lx[v] - P.s * ly[v]);
      wy[k] = P.py + (P.s * lx[v] + P.c * ly[v]);
    }
    hot.pair.clear();
    for (std::size_t i = 0; i < count; ++i) {
      const NeighborPair& p = pairs[i];
      const double dist2 = classify(static_cast<std::uint32_t>(i), wx[p.slot_vertex], wy[p.slot_vertex], wx[p.slot_edge0],
                                    wy[p.slot_edge0], wx[p.slot_edge1], wy[p.slot_edge1]);
      const double near = radius[p.vbody] + radius[p.ebody] + hot_skin;
      if (dist2 < near * near) hot.pair.push_back(static_cast<std::uint32_t>(i));
    }
    refresh_hot_list(m, st);
    st.timings.pairs_evaluated += count;
  } else {
    // Filter in the edge body's frame, where the edge is constant: the vertex is moved by the
    // relative pose of the run's two bodies, and no world positions are needed (a flat loop over
    // the hot arrays). It keeps every pair within (r1 + r2)(1 + 1e-3); this margin (1e-7 m for
    // r1 = r2 = 5e-5 m) dwarfs the rounding difference between the two frames (a few 1e-16 of the
    // coordinates, i.e. ~1e-17 m for 0.1 m blocks; at coordinates of 1e5 m it is still 1000
    // times larger), so every pair that the exact test finds touching is kept, every pair
    // dropped is one that the exact test finds apart, and the decisions stay those of the exact
    // test.
    unsigned char* const __restrict keep = hot.keep.data();
    for (std::size_t r = 0; r + 1 < hot.run_begin.size(); ++r) {
      const std::uint32_t a = hot.run_vbody[r], b = hot.run_ebody[r];
      const Pose& A = ps[a];
      const Pose& B = ps[b];
      const double cr = A.c * B.c + A.s * B.s, sr = A.s * B.c - A.c * B.s;  // rotation a -> b
      const double ox = A.px - B.px, oy = A.py - B.py;
      const double qx = B.c * ox + B.s * oy, qy = -B.s * ox + B.c * oy;   // centroid of a in b
      const double* const __restrict hvx = hot.vx.data();
      const double* const __restrict hvy = hot.vy.data();
      const double* const __restrict he0x = hot.e0x.data();
      const double* const __restrict he0y = hot.e0y.data();
      const double* const __restrict hdx = hot.dx.data();
      const double* const __restrict hdy = hot.dy.data();
      const double* const __restrict hil = hot.inv_len2.data();
      const double* const __restrict hcut = hot.cut2.data();
      const std::size_t k0 = hot.run_begin[r], k1 = hot.run_begin[r + 1];
      // Flat arrays, no gathers. (GCC 12 does not vectorise it: the clamp's comparisons count as
      // control flow under the default -ftrapping-math.)
      for (std::size_t k = k0; k < k1; ++k) {
        const double px = qx + (cr * hvx[k] - sr * hvy[k]) - he0x[k];
        const double py = qy + (sr * hvx[k] + cr * hvy[k]) - he0y[k];
        const double t = std::clamp((px * hdx[k] + py * hdy[k]) * hil[k], 0.0, 1.0);
        const double sx = px - t * hdx[k], sy = py - t * hdy[k];
        keep[k] = sx * sx + sy * sy < hcut[k];
      }
    }
    // World positions of the kept pairs' vertex and edge ends: the same arithmetic (pose of
    // the owning body, local coordinates) as the full pass, hence the same values.
    for (std::size_t r = 0; r + 1 < hot.run_begin.size(); ++r) {
      const Pose& A = ps[hot.run_vbody[r]];
      const Pose& B = ps[hot.run_ebody[r]];
      for (std::size_t k = hot.run_begin[r]; k < hot.run_begin[r + 1]; ++k) {
        const std::uint32_t index = hot.pair[k];
        if (!keep[k]) {  // apart
          NeighborPair& p = pairs[index];
          if (p.overlap > -1) {
            p.elongation = 0;
            p.overlap = -1;
          }
          continue;
        }
        const double vx = A.px + (A.c * hot.vx[k] - A.s * hot.vy[k]);
        const double vy = A.py + (A.s * hot.vx[k] + A.c * hot.vy[k]);
        const double e0x = B.px + (B.c * hot.e0x[k] - B.s * hot.e0y[k]);
        const double e0y = B.py + (B.s * hot.e0x[k] + B.c * hot.e0y[k]);
        const double e1x = B.px + (B.c * hot.e1x[k] - B.s * hot.e1y[k]);
        const double e1y = B.py + (B.s * hot.e1x[k] + B.c * hot.e1y[k]);
        classify(index, vx, vy, e0x, e0y, e1x, e1y);
      }
    }
    st.timings.pairs_evaluated += count;
  }
  for (std::size_t k = 0; k < n_touching; ++k) {
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
    if (overlap > guard * rsum) max_ratio = std::max(max_ratio, overlap / rsum);  // rare
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
    const double fn_el = kn * overlap;
    double xi = p.elongation + vt * dt_spring;
    double ft_el = -kt * xi;
    const double limit = mu * fn_el;
    if (std::fabs(ft_el) > limit) {
      ft_el = ft_el > 0 ? limit : -limit;
      xi = kt > 0 ? -ft_el / kt : 0.0;
    }
    p.elongation = xi;
    p.overlap = overlap;
    energy += 0.5 * fn_el * overlap + 0.5 * kt * xi * xi;
    const double fn = fn_el - mred * gn * vn;
    const double ft = ft_el - mred * gt * vt;
    const double fx = fn * nx + ft * tx, fy = fn * ny + ft * ty;
    c.fx = fx, c.fy = fy;
    c.torque_a = cross(rax, ray, fx, fy);
    c.torque_b = cross(rbx, rby, fx, fy);
    c.nx = nx, c.ny = ny;
    c.jt_a = cross(rax, ray, nx, ny);
    c.jt_b = cross(rbx, rby, nx, ny);
    c.mred = mred;
  }
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
  for (std::size_t k = 0; k < n_touching; ++k) {
    const ContactScratch& c = touching[k];
    const NeighborPair& p = pairs[c.pair];
    const std::uint32_t a = p.vbody, b = p.ebody;
    ++body_contacts[a];
    ++body_contacts[b];
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
    if (inv_mass_of[a] > 0) add_outer(sa.modes, c.nx, c.ny, c.jt_a, c.mred);
    if (inv_mass_of[b] > 0) add_outer(sb.modes, c.nx, c.ny, c.jt_b, c.mred);
  }
  flush();
  contacts = static_cast<int>(n_touching);
  st.contact_count = contacts;
  for (std::size_t b = 0; b < nb; ++b) {
    st.body_contacts[b] = body_contacts[b];
    st.step_limit[b] = inv_mass_of[b] > 0 && body_contacts[b] > 0
                           ? mode_limit(jac[b], m.mass[b], m.inertia[b], kn, gn)
                           : std::numeric_limits<double>::infinity();
  }
  st.max_overlap = max_ov;
  st.elastic_energy = energy;
  st.timings.pairs_visited += st.pairs.size();
  return max_ratio;
}

void kick(const Model& m, State& st, double h) {
  const Vec2 g = m.def.gravity;
  for (std::size_t b = 0; b < m.body_count(); ++b) {
    if (m.type[b] != BodyType::Dynamic) continue;
    const double im = 1.0 / m.mass[b];
    st.velocity[b].x += h * (st.force[b].x * im + g.x);
    st.velocity[b].y += h * (st.force[b].y * im + g.y);
    st.angular_velocity[b] += h * (st.torque[b] / m.inertia[b]);
  }
}

}  // namespace

BodyDef default_body_def() { return BodyDef{}; }
ContactParams default_contact_params() { return ContactParams{}; }
WorldDef default_world_def() { return WorldDef{}; }

Result<Model> make_model(const WorldDef& world, const std::vector<BodyDef>& bodies) {
  auto bad = [](const std::string& s) { return Result<Model>(make_error(s)); };
  auto finite_pos = [](double v) { return std::isfinite(v) && v > 0; };
  auto finite_nonneg = [](double v) { return std::isfinite(v) && v >= 0; };
  if (!finite_pos(world.time_step)) return bad(fmt::format("world time_step = {} s: expected a finite value > 0", world.time_step));
  if (!finite_nonneg(world.skin)) return bad(fmt::format("world skin = {} m: expected a finite value >= 0", world.skin));
  if (!finite_nonneg(world.hot_skin)) return bad(fmt::format("world hot_skin = {} m: expected a finite value >= 0", world.hot_skin));
  if (!std::isfinite(world.gravity.x) || !std::isfinite(world.gravity.y)) return bad("world gravity: expected finite components");
  const ContactParams& c = world.contact;
  if (!finite_pos(c.normal_stiffness)) return bad(fmt::format("contact normal_stiffness k_n = {} N/m: expected > 0", c.normal_stiffness));
  if (!finite_nonneg(c.tangential_stiffness)) return bad(fmt::format("contact tangential_stiffness k_t = {} N/m: expected >= 0", c.tangential_stiffness));
  if (!finite_nonneg(c.normal_damping)) return bad(fmt::format("contact normal_damping gamma_n = {} 1/s: expected >= 0", c.normal_damping));
  if (!finite_nonneg(c.tangential_damping)) return bad(fmt::format("contact tangential_damping gamma_t = {} 1/s: expected >= 0", c.tangential_damping));
  if (!finite_nonneg(c.atomic_friction)) return bad(fmt::format("contact atomic_friction mu_a = {}: expected >= 0", c.atomic_friction));
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
    if (d.x.size() != d.y.size()) return bad(fmt::format("{}: x has {} vertices but y has {}", who, d.x.size(), d.y.size()));
    const std::size_t n = d.x.size();
    if (n < 3) return bad(fmt::format("{}: {} vertices, expected at least 3", who, n));
    if (m.local_x.size() + n >= (std::size_t{1} << 31)) return bad(fmt::format("{}: too many vertices in total", who));
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isfinite(d.x[i]) || !std::isfinite(d.y[i])) return bad(fmt::format("{}: vertex {} is not finite", who, i));
    for (std::size_t i = 0; i < n; ++i)
      if (d.x[i] == d.x[(i + 1) % n] && d.y[i] == d.y[(i + 1) % n])
        return bad(fmt::format("{}: vertices {} and {} coincide (zero-length edge; do not repeat the closing point)", who, i, (i + 1) % n));
    if (!finite_pos(d.radius)) return bad(fmt::format("{}: radius = {} m, expected a finite spheroradius > 0", who, d.radius));
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
    m.vertex_begin.push_back(static_cast<std::uint32_t>(m.local_x.size()));
    m.radius.push_back(d.radius);
    m.area.push_back(area);
    m.mass.push_back(d.density * area);
    m.inertia.push_back(d.density * i_c);
    m.extent.push_back(ext + d.radius);
    m.type.push_back(d.type);
    m.motion.push_back(d.motion);
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
  return m;
}

State make_state(const Model& m) {
  const std::size_t nb = m.body_count();
  State st;
  st.position = m.initial_position;
  st.angle.assign(nb, 0.0);
  st.velocity = m.initial_velocity;
  st.angular_velocity = m.initial_angular_velocity;
  st.force.assign(nb, {0, 0});
  st.torque.assign(nb, 0.0);
  st.body_contacts.assign(nb, 0);
  st.step_limit.assign(nb, std::numeric_limits<double>::infinity());
  st.list_position = st.position;
  st.list_angle = st.angle;
  for (std::size_t b = 0; b < nb; ++b)
    if (m.type[b] == BodyType::Kinematic) kinematic_pose(m, b, 0.0, st);
  update_rotation(st);
  st.list_rotation = st.rotation;
  build_neighbor_list(m, st);
  compute_forces(m, st, 0.0);
  return st;
}

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

Status step(const Model& m, State& st) {
  const std::size_t nb = m.body_count();
  const double dt = m.def.time_step;
  const bool timed = m.def.timings;
  Clock::time_point t0;
  if (timed) t0 = Clock::now();
  // Kick (half step) and drift.
  kick(m, st, 0.5 * dt);
  for (std::size_t b = 0; b < nb; ++b) {
    if (m.type[b] != BodyType::Dynamic) continue;
    st.position[b].x += dt * st.velocity[b].x;
    st.position[b].y += dt * st.velocity[b].y;
    st.angle[b] += dt * st.angular_velocity[b];
  }
  const double t_new = static_cast<double>(st.steps + 1) * dt;
  for (std::size_t b = 0; b < nb; ++b)
    if (m.type[b] == BodyType::Kinematic) kinematic_pose(m, b, t_new, st);
  st.time = t_new;
  update_rotation(st);
  if (timed) {
    const auto t1 = Clock::now();
    st.timings.integration += std::chrono::duration<double>(t1 - t0).count();
    t0 = t1;
  }
  // Neighbour list: rebuild when some vertex-edge distance may have shrunk by more than the skin
  // since the last build (pairs left out were at least r1 + r2 + skin apart). The bound is on
  // the relative motion of the bodies: a block resting on a tilting block keeps its list.
  if (relative_motion_bound(m, st.list_position, st.list_angle, st.list_rotation, st.position, st.angle, st.rotation) > m.def.skin) {
    // A single step must not move anything by more than half the skin, or contacts are missed.
    for (std::size_t b = 0; b < nb; ++b) {
      const double per_step = (std::hypot(st.velocity[b].x, st.velocity[b].y) +
                               std::fabs(st.angular_velocity[b]) * m.extent[b]) * dt;
      if (2.0 * per_step > m.def.skin)
        return make_error(fmt::format(
            "dem: at t = {:.6g} s body {} moves {:.3g} m in one step, more than half the skin {:.3g} m; "
            "reduce the time step (now {:.3g} s) or enlarge the skin", st.time, b, per_step, m.def.skin, dt));
    }
    build_neighbor_list(m, st);
  }
  if (timed) {
    const auto t1 = Clock::now();
    st.timings.neighbor_list += std::chrono::duration<double>(t1 - t0).count();
    t0 = t1;
  }
  const double ratio = compute_forces(m, st, dt);
  if (timed) {
    const auto t1 = Clock::now();
    st.timings.contacts += std::chrono::duration<double>(t1 - t0).count();
    t0 = t1;
  }
  kick(m, st, 0.5 * dt);
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
      status = make_error(fmt::format(
          "dem: body {} has a non-finite position or velocity at t = {:.6g} s (step {}); the integration "
          "blew up: try a time step <= {:.3g} s (now {:.3g} s)", b, st.time, st.steps, dt_hint(), dt));
      break;
    }
    if (const double lim = st.step_limit[b]; dt > lim) {
      beyond = true;
      if (st.steps_beyond_limit + 1 > static_cast<std::uint64_t>(m.def.max_steps_beyond_limit)) {
        status = make_error(ErrorCode::Unstable, fmt::format(
            "dem: at t = {:.6g} s body {} has {} contacts and the time step is above the explicit stability "
            "limit dt = {:.3g} s (2 / damping rate or 2 / omega of its contact modes), for the {}th step: "
            "use a time step <= {:.3g} s (now {:.3g} s)",
            st.time, b, st.body_contacts[b], lim, st.steps_beyond_limit + 1, 0.5 * lim, dt));
        break;
      }
    }
    const double speed = std::hypot(st.velocity[b].x, st.velocity[b].y) +
                         std::fabs(st.angular_velocity[b]) * m.extent[b];
    if (speed > m.def.max_speed)
      status = make_error(fmt::format(
          "dem: body {} reached speed {:.3g} m/s > max_speed {:.3g} m/s at t = {:.6g} s (energy blow-up); "
          "try a time step <= {:.3g} s (now {:.3g} s)", b, speed, m.def.max_speed, st.time, dt_hint(), dt));
  }
  if (beyond) {
    ++st.steps_beyond_limit;
    ++st.consecutive_beyond_limit;
  } else {
    st.consecutive_beyond_limit = 0;
  }
  if (status.ok() && ratio > m.def.max_overlap_ratio)
    status = make_error(fmt::format(
        "dem: an overlap reached {:.3g} of r1 + r2 (limit {:.3g}) at t = {:.6g} s with {} contacts; the "
        "stiffness is too low for the load or the time step too large: try dt <= {:.3g} s (now {:.3g} s)",
        ratio, m.def.max_overlap_ratio, st.time, st.contact_count, dt_hint(), dt));
  if (timed) st.timings.integration += seconds_since(t0);
  return status;
}

Status advance(const Model& m, State& st, std::uint64_t steps) {
  for (std::uint64_t i = 0; i < steps; ++i) {
    Status s = step(m, st);
    if (!s.ok()) return s;
  }
  return Ok{};
}

Vec2 world_vertex(const Model& m, const State& st, std::uint32_t v) {
  const std::uint32_t b = m.vertex_body[v];
  const double c = std::cos(st.angle[b]), s = std::sin(st.angle[b]);
  return {st.position[b].x + (c * m.local_x[v] - s * m.local_y[v]),
          st.position[b].y + (s * m.local_x[v] + c * m.local_y[v])};
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

double restitution_from_damping(double gamma_n, double k_n, double m) {
  const double w2 = k_n / m - 0.25 * gamma_n * gamma_n;
  if (!(w2 > 0)) return 0.0;
  return std::exp(-0.5 * gamma_n * 3.14159265358979323846 / std::sqrt(w2));
}

}  // namespace frictal::dem
