// frictal — spheropolygon engine: contact geometry (docs/dem.md sec. 2 and 7). Finds the touching
// vertex-edge pairs of the neighbour list: a full pass over the list when the hot list is stale
// (it records the pairs within r1 + r2 + hot_skin), else a filter over the hot list in the edge
// body's frame followed by the exact world-frame test of the kept pairs.
#include "contact_geometry.hpp"

#include <algorithm>
#include <cstdint>

#include "neighbor_list.hpp"

namespace frictal::dem::detail {

namespace {

// Fills the hot list's arrays for the pairs in ws.hot.pair (found by a full pass at the current
// poses): vertex in its body's frame, edge in the edge body's frame (both constant), the filter
// radius, and the runs of equal (vertex body, edge body).
void refresh_hot_list(const Model& m, State& st, Workspace& ws) {
  HotList& h = ws.hot;
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
  h.rotation = ws.rotation;
  h.valid = true;
  ++st.timings.hot_refreshes;
}

}  // namespace

namespace {

// The exact test of one pair from the world positions of its vertex and edge: every decision
// (touching, spring reset) is taken here, in the world frame, as in a plain loop over the list.
// The pair's geometry is written to touching[n] for every pair and kept (n advanced) only if it
// touches (n <= pairs seen, so the slot exists): no branch on touch / apart, close to a coin toss
// in the hot list. Returns the squared distance.
struct Classifier {
  const double* __restrict radius;
  const double* __restrict inv_len2;
  NeighborPair* pairs;
  ContactScratch* touching;
  std::size_t n;  // touching pairs written so far (absolute index into touching)

  inline double operator()(std::uint32_t index, double vx, double vy, double e0x, double e0y, double e1x, double e1y) {
    NeighborPair& p = pairs[index];
    const double dx = e1x - e0x, dy = e1y - e0y;
    double t = ((vx - e0x) * dx + (vy - e0y) * dy) * inv_len2[p.edge0];
    t = std::clamp(t, 0.0, 1.0);
    const double sx = vx - (e0x + t * dx), sy = vy - (e0y + t * dy);
    const double dist2 = sx * sx + sy * sy;
    const double rsum = radius[p.vbody] + radius[p.ebody];
    ContactScratch& c = touching[n];
    c.pair = index;
    c.sx = sx, c.sy = sy, c.dist2 = dist2, c.dx = dx, c.dy = dy, c.vx = vx, c.vy = vy, c.t = t;
    c.weight = 1;
    const bool touch = dist2 < rsum * rsum;
    n += touch ? 1 : 0;
    if (!touch && p.overlap > -1) {  // write only on the transition (most pairs stay apart)
      p.elongation = 0;
      p.overlap = -1;
    }
    return dist2;
  }
};

}  // namespace

bool hot_list_stale(const Model& m, const State& st, const Workspace& ws) {
  // Hot list (docs/dem.md sec. 2): a full pass over the list records which pairs are within
  // r1 + r2 + hot_skin; until the bodies have moved by more than hot_skin / 2 since that pass, the
  // others are at least hot_skin / 2 apart and are skipped. A skipped pair is apart, and its
  // spring was reset in the full pass, so the forces, their summation order and every per-pair
  // state are exactly those of a pass over the whole list.
  if (!ws.hot.valid) return true;
  return 2.0 * relative_motion_bound(m, ws.hot.position, ws.hot.angle, ws.hot.rotation, st.position, st.angle,
                                     ws.rotation) >
         m.def.hot_skin;
}

std::size_t find_touching_hot(const Model& m, State& st, Workspace& ws, std::size_t k0, std::size_t k1) {
  const Pose* const ps = ws.pose.data();
  HotList& hot = ws.hot;
  Classifier classify{m.radius.data(), m.edge_inv_length2.data(), st.pairs.data(), ws.touching.data(), k0};
  // Filter in the edge body's frame, where the edge is constant: the vertex is moved by the
  // relative pose of the run's two bodies, and no world positions are needed (a flat loop over
  // the hot arrays). It keeps every pair within (r1 + r2)(1 + 1e-3); this margin (1e-7 m for
  // r1 = r2 = 5e-5 m) dwarfs the rounding difference between the two frames (a few 1e-16 of the
  // coordinates, i.e. ~1e-17 m for 0.1 m blocks; at coordinates of 1e5 m it is still 1000
  // times larger), so every pair that the exact test finds touching is kept, every pair
  // dropped is one that the exact test finds apart, and the decisions stay those of the exact
  // test.
  unsigned char* const __restrict keep = hot.keep.data();
  // The runs of equal (vertex body, edge body) that meet [k0, k1).
  const std::size_t n_runs = hot.run_begin.size() - 1;
  std::size_t r_first = static_cast<std::size_t>(
      std::upper_bound(hot.run_begin.begin(), hot.run_begin.begin() + static_cast<std::ptrdiff_t>(n_runs),
                       static_cast<std::uint32_t>(k0)) -
      hot.run_begin.begin());
  r_first = r_first > 0 ? r_first - 1 : 0;
  for (std::size_t r = r_first; r < n_runs && hot.run_begin[r] < k1; ++r) {
    const std::uint32_t a = hot.run_vbody[r], b = hot.run_ebody[r];
    const Pose& A = ps[a];
    const Pose& B = ps[b];
    const double cr = A.c * B.c + A.s * B.s, sr = A.s * B.c - A.c * B.s;  // rotation a -> b
    const double ox = A.px - B.px, oy = A.py - B.py;
    const double qx = B.c * ox + B.s * oy, qy = -B.s * ox + B.c * oy;  // centroid of a in b
    const double* const __restrict hvx = hot.vx.data();
    const double* const __restrict hvy = hot.vy.data();
    const double* const __restrict he0x = hot.e0x.data();
    const double* const __restrict he0y = hot.e0y.data();
    const double* const __restrict hdx = hot.dx.data();
    const double* const __restrict hdy = hot.dy.data();
    const double* const __restrict hil = hot.inv_len2.data();
    const double* const __restrict hcut = hot.cut2.data();
    const std::size_t kb = std::max<std::size_t>(hot.run_begin[r], k0);
    const std::size_t ke = std::min<std::size_t>(hot.run_begin[r + 1], k1);
    // Flat arrays, no gathers. (GCC 12 does not vectorise it: the clamp's comparisons count as
    // control flow under the default -ftrapping-math.)
    for (std::size_t k = kb; k < ke; ++k) {
      const double px = qx + (cr * hvx[k] - sr * hvy[k]) - he0x[k];
      const double py = qy + (sr * hvx[k] + cr * hvy[k]) - he0y[k];
      const double t = std::clamp((px * hdx[k] + py * hdy[k]) * hil[k], 0.0, 1.0);
      const double sx = px - t * hdx[k], sy = py - t * hdy[k];
      keep[k] = sx * sx + sy * sy < hcut[k];
    }
  }
  // World positions of the kept pairs' vertex and edge ends: the same arithmetic (pose of
  // the owning body, local coordinates) as the full pass, hence the same values.
  NeighborPair* const pairs = st.pairs.data();
  for (std::size_t r = r_first; r < n_runs && hot.run_begin[r] < k1; ++r) {
    const Pose& A = ps[hot.run_vbody[r]];
    const Pose& B = ps[hot.run_ebody[r]];
    const std::size_t kb = std::max<std::size_t>(hot.run_begin[r], k0);
    const std::size_t ke = std::min<std::size_t>(hot.run_begin[r + 1], k1);
    for (std::size_t k = kb; k < ke; ++k) {
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
  return classify.n - k0;
}

namespace {

// One touching pair as the contact rule `closest` sees it: vertex v of body vb against the edge
// (e0, e1) of body eb, touched inside (end 0) or at its end e0 (1) or e1 (2).
struct PairView {
  std::uint32_t vb, eb, v, e0, e1;
  int end;
};

// Whether two touching pairs describe the same contact of the rigid blocks (docs/dem.md sec. 1,
// "Contact rule"); their contact points are near each other (checked by the caller).
//  - the same two vertices (a vertex-vertex contact, found through up to four pairs);
//  - a vertex-vertex pair (v, w) and a pair of v or w with an edge that ends at the other, when
//    that end is a convex corner: the rounded corner is part of the edge's band, so the
//    vertex-vertex pair repeats it (at a concave corner it is the other flank's contact);
//  - two pairs inside edges, crossed between two convex corners: v against the edge of w, and w
//    against the edge of v, with both edges leaving (or both entering) the other pair's vertex in
//    the polygons' order.
//    As the bodies' faces run in opposite directions, these are the two corners sliding past
//    each other on the same side of their meeting: of the two lift pieces, only the higher one
//    is a contact of the rigid blocks; the lower one touches only because the blocks overlap.
//    (Both leaving one / entering the other are the two pieces on either side of the meeting:
//    a block resting in the wedge, which needs both.)
// A vertex against two edges inside (a vertex in a valley, on both flanks) is two contacts.
bool same_contact(const Model& m, const PairView& a, const PairView& b) {
  const auto at = [](const PairView& p) { return p.end == 1 ? p.e0 : p.e1; };  // the edge's end touched
  if (a.end != 0 && b.end != 0) {  // two vertex-vertex pairs: the same two vertices?
    const std::uint32_t wa = at(a), wb = at(b);
    return (a.v == b.v && wa == wb) || (a.v == wb && wa == b.v);
  }
  if (a.end != 0 || b.end != 0) {  // one vertex-vertex pair (v, w), one pair inside an edge
    const PairView& vv = a.end != 0 ? a : b;
    const PairView& in = a.end != 0 ? b : a;
    const std::uint32_t v = vv.v, w = at(vv);
    if (in.v != v && in.v != w) return false;
    const std::uint32_t end = in.v == v ? w : v;  // the vertex-vertex pair's other vertex
    // ... an end of the edge, at a convex corner (at a concave one, a valley's bottom, the pair
    // (v, w) is the other flank's contact carried past its end: it stays).
    return (in.e0 == end || in.e1 == end) && m.convex_vertex[end];
  }
  if (a.vb == b.vb) return false;  // both inside edges, one body's vertices: separate contacts
  // Crossed: b's vertex is an end of a's edge and a's vertex an end of b's edge, both convex.
  return ((b.v == a.e0 && a.v == b.e0) || (b.v == a.e1 && a.v == b.e1)) && m.convex_vertex[a.v] && m.convex_vertex[b.v];
}

}  // namespace

void merge_touching(const Model& m, State& st, Workspace& ws) {
  // ContactRule::Closest (docs/dem.md sec. 1, "Contact rule"). (1) A concave corner is never the
  // point of a contact: its pairs are dropped. (2) Of the others, a touching pair with a deeper
  // pair that describes the same contact (same_contact, contact points within r1 + r2) stands for
  // nothing that one does not: it is dropped. O(n^2) in the touching pairs of a body pair, which
  // are few (a handful at rest; tens on a flat face). (3) A vertex within reach of a concave
  // corner of the other body touches both of its flanks; their bands overlap around the corner,
  // and the vertex-vertex term is subtracted once (inclusion-exclusion).
  const std::size_t n = ws.touching_count;
  if (n == 0) return;
  ContactScratch* c = ws.touching.data();
  NeighborPair* const pairs = st.pairs.data();
  auto view = [&](std::size_t i) {
    const NeighborPair& p = pairs[c[i].pair];
    return PairView{p.vbody, p.ebody, p.vertex, p.edge0, p.edge1, c[i].t <= 0.0 ? 1 : (c[i].t >= 1.0 ? 2 : 0)};
  };
  // by[i]: n = kept; n + 1 = a concave corner's pair (stands for nothing); else the kept pair
  // that describes the same contact, taken from the deepest pair down. A pair dropped does not
  // drop others: at a valley's bottom the vertex-vertex pair of one flank must not go with the
  // crossed pair it repeats.
  const auto kept = static_cast<std::uint32_t>(n), concave = static_cast<std::uint32_t>(n + 1);
  std::vector<std::uint32_t>& by = ws.closest_dropped_by;
  by.assign(n, kept);
  std::vector<std::uint32_t>& order = ws.closest_order;
  order.resize(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = static_cast<std::uint32_t>(i);
  std::stable_sort(order.begin(), order.end(),
                   [c](std::uint32_t x, std::uint32_t y) { return c[x].dist2 < c[y].dist2; });
  for (std::size_t a = 0; a < n; ++a) {
    const std::uint32_t i = order[a];
    const PairView pi = view(i);
    if (!m.convex_vertex[pi.v]) {
      by[i] = concave;
      continue;
    }
    for (std::size_t b = 0; b < a; ++b) {
      const std::uint32_t j = order[b];
      if (by[j] != kept) continue;  // dropped
      const PairView pj = view(j);
      if (std::min(pi.vb, pi.eb) != std::min(pj.vb, pj.eb) || std::max(pi.vb, pi.eb) != std::max(pj.vb, pj.eb))
        continue;
      // Within one sum of spheroradii of each other (points halfway along the shortest
      // segments): an edge meets its ends, but contacts far along it are separate.
      const double mx = (c[i].vx - 0.5 * c[i].sx) - (c[j].vx - 0.5 * c[j].sx);
      const double my = (c[i].vy - 0.5 * c[i].sy) - (c[j].vy - 0.5 * c[j].sy);
      const double reach = m.radius[pi.vb] + m.radius[pi.eb];
      if (mx * mx + my * my >= reach * reach || !same_contact(m, pi, pj)) continue;
      by[i] = j;
      break;
    }
  }
  // A contact's tangential spring (mu_a > 0) lives on the pair that stands for it: a pair that
  // now stands for a dropped one that touched last step takes over its elongation if it did not
  // touch itself.
  for (std::size_t i = 0; i < n; ++i) {
    if (by[i] == kept) continue;
    NeighborPair& dropped = pairs[c[i].pair];
    if (by[i] != concave) {
      NeighborPair& keeper = pairs[c[by[i]].pair];
      if (dropped.overlap > 0 && !(keeper.overlap > 0)) keeper.elongation = dropped.elongation;
    }
    dropped.elongation = 0;
    dropped.overlap = -1;
  }
  std::size_t w = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (by[i] == kept) c[w++] = c[i];
  // (3) The vertex-vertex terms at concave corners: one per (vertex, corner) within reach, found
  // through the kept pairs of the vertex with an edge ending at the corner (both flanks touch:
  // each is no farther than the corner). The corner's world position is the edge's end.
  struct Corner {
    std::uint32_t v, corner, from;
    double sx, sy;
  };
  std::vector<Corner> corners;
  for (std::size_t i = 0; i < w; ++i) {
    const PairView pi = view(i);
    const double reach = m.radius[pi.vb] + m.radius[pi.eb];
    const double px = c[i].vx - c[i].sx, py = c[i].vy - c[i].sy;  // closest point on the edge
    for (int end = 0; end < 2; ++end) {
      const std::uint32_t corner = end == 0 ? pi.e0 : pi.e1;
      if (m.convex_vertex[corner]) continue;
      const double f = end == 0 ? -c[i].t : 1.0 - c[i].t;
      const double sx = c[i].vx - (px + f * c[i].dx), sy = c[i].vy - (py + f * c[i].dy);
      if (sx * sx + sy * sy < reach * reach) corners.push_back({pi.v, corner, static_cast<std::uint32_t>(i), sx, sy});
    }
  }
  std::sort(corners.begin(), corners.end(), [](const Corner& x, const Corner& y) {
    return x.v != y.v ? x.v < y.v : (x.corner != y.corner ? x.corner < y.corner : x.from < y.from);
  });
  corners.erase(std::unique(corners.begin(), corners.end(),
                            [](const Corner& x, const Corner& y) { return x.v == y.v && x.corner == y.corner; }),
                corners.end());
  if (ws.touching.size() < w + corners.size()) {
    ws.touching.resize(w + corners.size());
    c = ws.touching.data();
  }
  for (const Corner& k : corners) {
    ContactScratch& e = c[w++];
    e = c[k.from];
    e.sx = k.sx, e.sy = k.sy, e.dist2 = k.sx * k.sx + k.sy * k.sy;
    e.weight = -1;
  }
  ws.touching_count = w;
  ws.segments.resize(1);
  ws.segments[0] = {0, w};
}

void find_touching(const Model& m, State& st, Workspace& ws) {
  const bool full = hot_list_stale(m, st, ws);
  HotList& hot = ws.hot;
  const std::size_t count = full ? st.pairs.size() : hot.pair.size();
  // Grown, never shrunk; filled field by field (no temporary to copy).
  if (ws.touching.size() < count) ws.touching.resize(count);
  std::size_t n_touching = 0;
  if (full) {
    const Pose* const ps = ws.pose.data();
    const double* lx = m.local_x.data();
    const double* ly = m.local_y.data();
    const double* const __restrict radius = m.radius.data();
    const NeighborPair* const pairs = st.pairs.data();
    const PairSlots* const slots = ws.slots.data();
    const double hot_skin = m.def.hot_skin;
    Classifier classify{radius, m.edge_inv_length2.data(), st.pairs.data(), ws.touching.data(), 0};
    // World positions of the vertices the list refers to, one transform each.
    double* wx = ws.active_x.data();
    double* wy = ws.active_y.data();
    for (std::size_t k = 0; k < ws.active_vertex.size(); ++k) {
      const std::uint32_t v = ws.active_vertex[k];
      const Pose& P = ps[m.vertex_body[v]];
      wx[k] = P.px + (P.c * lx[v] - P.s * ly[v]);
      wy[k] = P.py + (P.s * lx[v] + P.c * ly[v]);
    }
    hot.pair.clear();
    for (std::size_t i = 0; i < count; ++i) {
      const NeighborPair& p = pairs[i];
      const PairSlots& q = slots[i];
      const double dist2 = classify(static_cast<std::uint32_t>(i), wx[q.vertex], wy[q.vertex], wx[q.edge0], wy[q.edge0],
                                    wx[q.edge1], wy[q.edge1]);
      const double near = radius[p.vbody] + radius[p.ebody] + hot_skin;
      if (dist2 < near * near) hot.pair.push_back(static_cast<std::uint32_t>(i));
    }
    refresh_hot_list(m, st, ws);
    n_touching = classify.n;
  } else {
    n_touching = find_touching_hot(m, st, ws, 0, count);
  }
  st.timings.pairs_evaluated += count;
  ws.touching_count = n_touching;
  ws.segments.resize(1);
  ws.segments[0] = {0, n_touching};
}

}  // namespace frictal::dem::detail
