// frictal — spheropolygon engine: the Verlet neighbour list (docs/dem.md sec. 2). Candidate
// vertex-edge pairs within r1 + r2 + skin, found on a uniform grid over the overlap of the two
// bodies' bounding boxes; rebuilt only when the relative motion of the bodies may have closed the
// skin.
#include "neighbor_list.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace frictal::dem::detail {

namespace {

// Largest possible displacement of any vertex of body b between poses.
double motion_bound(const Model& m, std::size_t b, Vec2 p0, double a0, Vec2 p1, double a1) {
  return std::hypot(p1.x - p0.x, p1.y - p0.y) + std::fabs(a1 - a0) * m.extent[b];
}

}  // namespace

// Largest change, between poses 0 and 1, of the distance between a vertex of one body and an
// edge of another. Distances are invariant under rigid motion, so it is measured in the edge
// body's frame, where the edge is fixed and the vertex moves with the relative motion of its body:
// by at most |change of the relative centroid position| + |change of the relative angle| x extent.
// Two bodies that move together (a block stuck on a tilting block) give ~0, however fast they
// move. Small body counts only (O(bodies^2)); else the sum of the two largest absolute bounds.
// r0, r1: cos and sin of the angles a0, a1 (cached, see Workspace::rotation).
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
    if (d > b1)
      b2 = b1, b1 = d;
    else if (d > b2)
      b2 = d;
  }
  return b1 + b2;
}

void build_neighbor_list(const Model& m, State& st, Workspace& ws) {
  const std::size_t nb = m.body_count();
  const std::size_t nv = m.local_x.size();
  // World coordinates of every vertex: the one O(N) part of the engine, run only on rebuilds.
  std::vector<double>& wx = ws.world_x;
  std::vector<double>& wy = ws.world_y;
  std::vector<double>& bx0 = ws.box_x0;
  std::vector<double>& bx1 = ws.box_x1;
  std::vector<double>& by0 = ws.box_y0;
  std::vector<double>& by1 = ws.box_y1;
  wx.resize(nv);
  wy.resize(nv);
  bx0.resize(nb);
  bx1.resize(nb);
  by0.resize(nb);
  by1.resize(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    const double c = ws.rotation[b].c, s = ws.rotation[b].s;
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
  std::vector<NeighborPair>& out = ws.new_pairs;
  out.clear();
  std::vector<std::uint32_t>& edges = ws.edges;
  std::vector<std::uint32_t>& verts = ws.verts;
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
      std::vector<std::uint32_t>& start = ws.cells;
      std::vector<std::uint32_t>& items = ws.items;
      start.assign(nx * ny + 1, 0);
      for (int pass = 0; pass < 2; ++pass) {
        for (std::uint32_t i : edges) {
          const std::uint32_t j = m.next_vertex[i];
          const std::size_t ix0 = cx(std::min(wx[i], wx[j]) - cut), ix1 = cx(std::max(wx[i], wx[j]) + cut);
          const std::size_t iy0 = cy(std::min(wy[i], wy[j]) - cut), iy1 = cy(std::max(wy[i], wy[j]) + cut);
          for (std::size_t iy = iy0; iy <= iy1; ++iy)
            for (std::size_t ix = ix0; ix <= ix1; ++ix) {
              const std::size_t k = iy * nx + ix;
              if (pass == 0)
                ++start[k + 1];
              else
                items[start[k]++] = i;
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
  std::sort(out.begin(), out.end(), [](const NeighborPair& l, const NeighborPair& r) { return l.key < r.key; });
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
  std::vector<std::uint32_t>& slot = ws.slot_of_vertex;
  slot.assign(nv, std::numeric_limits<std::uint32_t>::max());
  ws.active_vertex.clear();
  for (const NeighborPair& p : st.pairs) {
    slot[p.vertex] = 0;
    slot[p.edge0] = 0;
    slot[p.edge1] = 0;
  }
  for (std::uint32_t v = 0; v < nv; ++v)
    if (slot[v] == 0) {
      slot[v] = static_cast<std::uint32_t>(ws.active_vertex.size());
      ws.active_vertex.push_back(v);
    }
  ws.slots.resize(st.pairs.size());
  for (std::size_t k = 0; k < st.pairs.size(); ++k) {
    const NeighborPair& p = st.pairs[k];
    ws.slots[k] = {slot[p.vertex], slot[p.edge0], slot[p.edge1]};
  }
  ws.active_x.resize(ws.active_vertex.size());
  ws.active_y.resize(ws.active_vertex.size());
  ws.list_position.resize(nb);
  ws.list_angle.resize(nb);
  ws.list_rotation.resize(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    ws.list_position[b] = st.position[b];
    ws.list_angle[b] = st.angle[b];
    ws.list_rotation[b] = ws.rotation[b];
  }
  ws.hot.valid = false;
  ++st.timings.list_builds;
}

}  // namespace frictal::dem::detail
