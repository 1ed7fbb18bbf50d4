// The 3D tilt test beside the prediction matched to it: the one sequence that `frictal
// areal-tilt` and Python areal_tilt show (the experiment checking the map model, map_hold.hpp),
// with the map model's settings for a run and the seat a run sat in before its run-away.
#include <cmath>

#include "frictal/areal_tilt.hpp"
#include "frictal/map_hold.hpp"

namespace frictal {

ArealTiltOptions map_model_options(const Map& lower, const ArealTiltOptions& sim) {
  ArealTiltOptions out = sim;
  fill_map_model_defaults(lower, out);
  return out;
}

std::optional<std::array<double, 3>> areal_tilt_last_seat(const ArealTiltResult& r) {
  if (!r.ran_away || r.trace.empty()) return std::nullopt;
  const double last = r.trace.back().tilt;
  const ArealTiltIncrement* seat = nullptr;
  for (auto it = r.trace.rbegin(); it != r.trace.rend() && !seat; ++it)
    if (it->rested && it->tilt < last) seat = &*it;
  if (!seat) return std::nullopt;
  // The lowest tilt at which the block already rested there (coarse or fine increments; a block
  // at rest sits still to a small fraction of r).
  const double tol = 0.01 * r.sphere_radius;
  double first = seat->tilt;
  for (const ArealTiltIncrement& i : r.trace)
    if (i.rested && i.tilt < first && std::hypot(i.x - seat->x, i.y - seat->y) <= tol) first = i.tilt;
  return std::array<double, 3>{first, seat->x, seat->y};
}

Result<ArealTiltMatched> areal_tilt_matched(const Map& lower, const Map& upper, const ArealTiltOptions& o,
                                            bool simulate, const ArealTiltProgress& progress) {
  ArealTiltMatched m;
  m.simulated = simulate;
  m.run_locked = o.lock_lateral;
  // The protocol's settings with the prediction's d and r (map_model_options).
  ArealTiltOptions co = map_model_options(lower, o);
  if (simulate) {
    auto run = areal_tilt(lower, upper, o, progress);
    if (!run) return run.error();
    m.run = std::move(*run);
  } else {
    m.run.rest_offset = o.start_offset;
    m.run.sphere_radius = co.sphere_radius;
  }
  m.runaway_distance = co.runaway_distance;
  // From the rest offset the run reached: the same basin. Both drops on one field of spheres.
  co.start_offset = m.run.rest_offset;
  auto held = areal_tilt_hold_drops(lower, upper, co, {{m.run.rest_offset, false}, {m.run.rest_offset, true}});
  if (!held) return held.error();
  m.free = (*held)[0];
  m.locked = (*held)[1];
  // Its conditioning in the simulated lateral mode: the slips' ends moved by one sphere radius.
  co.lock_lateral = o.lock_lateral;
  auto spread = areal_tilt_hold_spread(lower, upper, co, m.matched());
  if (!spread) return spread.error();
  m.spread = *spread;
  // The rigid block from the simulated block's last seat, at its tilt.
  if (simulate) {
    if (auto seat = areal_tilt_last_seat(m.run)) {
      ArealTiltOptions so = co;
      so.start_offset = {(*seat)[1], (*seat)[2]};
      so.coarse_tilt_step = o.tilt_step;
      auto seated = areal_tilt_hold(lower, upper, so, kArealHoldResolution, 1e-7, (*seat)[0]);
      if (!seated) return seated.error();
      m.seated = true;
      m.seat_tilt = (*seat)[0];
      m.seat_offset = {(*seat)[1], (*seat)[2]};
      m.seated_hold_angle = seated->hold_angle;
    }
  }
  return m;
}

}  // namespace frictal
