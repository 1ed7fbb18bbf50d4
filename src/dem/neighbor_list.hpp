// frictal — spheropolygon engine, private: the Verlet neighbour list of vertex-edge pairs
// (docs/dem.md sec. 2).
#pragma once

#include <vector>

#include "frictal/dem.hpp"
#include "workspace.hpp"

namespace frictal::dem::detail {

/// Largest change, between poses 0 and 1, of the distance between a vertex of one body and an
/// edge of another (unit: m). p: centroids (unit: m), a: angles (unit: rad), r: their cos / sin.
double relative_motion_bound(const Model& m, const std::vector<Vec2>& p0, const std::vector<double>& a0,
                             const std::vector<Rotation>& r0, const std::vector<Vec2>& p1,
                             const std::vector<double>& a1, const std::vector<Rotation>& r1);

/// Rebuilds State::pairs (every vertex-edge pair within r1 + r2 + skin at the current poses,
/// sorted by key, springs carried over), the vertex slots and the list poses; invalidates the hot
/// list. Needs ws.rotation at the current angles.
void build_neighbor_list(const Model& m, State& st, Workspace& ws);

}  // namespace frictal::dem::detail
