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
void find_touching(const Model& m, State& st, Workspace& ws);

}  // namespace frictal::dem::detail
