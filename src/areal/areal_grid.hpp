// frictal — the offset grid of an areal lift (shared header of src/areal/: areal_lift and the areal
// tilt's lift in src/tilt/ use it; src/tiers.txt).
#pragma once

#include <cstddef>
#include <vector>

#include "frictal/areal.hpp"
#include "frictal/result.hpp"

namespace frictal::detail {

/// An ArealLift with its offset grid laid out from `o` (step, across_step, across_max,
/// offset_min, offset_max; zeros take the defaults: the lower map's finer spacing, half its extent
/// along d, a quarter of it across); lift and contact are left empty (the caller checks its size
/// limit, then fills them). `who` prefixes the error for steps or ranges that are negative or not
/// finite.
Result<ArealLift> areal_offset_grid(const Map& lower, double angle, const ArealLiftOptions& o, const char* who);

/// After filling `out.lift`: adds the per-offset evaluation counts `work` to out.evaluated_nodes
/// and says whether the blocks touch at any offset (some lift is not NaN).
bool areal_lift_touches(ArealLift& out, const std::vector<std::size_t>& work);

}  // namespace frictal::detail
