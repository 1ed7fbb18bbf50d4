// The 3D tilt test beside the prediction matched to it: the one sequence that `frictal
// areal-tilt` and Python areal_tilt show.
#include "frictal/predict.hpp"

namespace frictal {

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
