// frictal — spheropolygon engine, private: contact geometry, i.e. which list pairs touch at the
// current poses, through the hot list (docs/dem.md sec. 2 and 7).
#pragma once

#include "frictal/dem.hpp"
#include "workspace.hpp"

namespace frictal::dem::detail {

/// Distance pass over the hot list (or the whole list when the hot list is stale; that full pass
/// refreshes it). The touching pairs, in list order, go to ws.touching[0, ws.touching_count)
/// with their geometry (vertex, edge vector, vertex - closest point, squared distance); the
/// springs of the pairs found apart are reset. Needs ws.pose and ws.rotation at the current poses.
/// ws.segments is then the one segment [0, ws.touching_count).
void find_touching(const Model& m, State& st, Workspace& ws);

/// ContactRule::Closest: keeps the deepest touching pair of each contact region (pairs whose
/// features are the same or meet at a convex vertex on both bodies); the others are apart for
/// this step (springs reset). Compacts ws.touching in list order.
void merge_touching(const Model& m, State& st, Workspace& ws);

/// True when the hot list must be refreshed by a full pass over the list at the current poses
/// (it is invalid, or the bodies have moved by more than hot_skin / 2 since it was made).
bool hot_list_stale(const Model& m, const State& st, const Workspace& ws);

/// The hot pass of find_touching over the hot pairs [k0, k1) only (the hot list valid and not
/// stale, ws.touching at least as long as the hot list): their touching pairs, in list order, go
/// to ws.touching from index k0 on; returns how many. Passes over disjoint ranges write disjoint
/// data (their own pairs' springs, their own part of ws.touching and ws.hot.keep), so they may
/// run at the same time.
std::size_t find_touching_hot(const Model& m, State& st, Workspace& ws, std::size_t k0, std::size_t k1);

}  // namespace frictal::dem::detail
