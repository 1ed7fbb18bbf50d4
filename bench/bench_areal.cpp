// The lift over two dimensions of offset (areal_lift) and the free-lateral hold angle on it.
// Target: 256 x 256 lower and 128 x 128 upper nodes over 256 x 64 offsets in <= 5 s
// on 2 cores. The faces are windows of the measured 650 x 650 X3P map of the test data (the
// upper one from the opposite corner, so the two differ), detrended as the CLI does by default.
#include <benchmark/benchmark.h>

#include <map>
#include <numbers>
#include <string>

#include "frictal/analysis.hpp"
#include "frictal/areal.hpp"
#include "frictal/areal_tilt.hpp"
#include "frictal/io.hpp"

using namespace frictal;

namespace {

const std::string kX3p = std::string(FRICTAL_TEST_DATA) + "/x3p/x3p-2.x3p";

Map window(const Map& m, std::size_t i0, std::size_t j0, std::size_t n) {
  Map w;
  w.nx = w.ny = n;
  w.dx = m.dx;
  w.dy = m.dy;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) w.heights.push_back(m.at(i0 + i, j0 + j));
  return *detrend(w, *parse_detrend("plane"));
}

const Map& lower() {
  static const Map m = window(*read_map(kX3p), 10, 10, 256);
  return m;
}
const Map& upper() {
  static const Map m = window(*read_map(kX3p), 500, 480, 128);
  return m;
}

/// 256 offsets along d (x) at the lower map's spacing, 65 across (+-32 steps).
ArealLiftOptions target_options(unsigned threads, bool prune) {
  ArealLiftOptions o;
  o.step = lower().dx;
  o.offset_min = -128 * o.step;
  o.offset_max = 127 * o.step;
  o.across_step = lower().dy;
  o.across_max = 32 * o.across_step;
  o.threads = threads;
  o.prune = prune;
  return o;
}

void BM_ArealLift256x65(benchmark::State& st) {
  const ArealLiftOptions o = target_options(unsigned(st.range(0)), true);
  std::size_t nodes = 0, offsets = 0;
  for (auto _ : st) {
    auto r = areal_lift(lower(), upper(), 0.0, o);
    if (!r) {
      st.SkipWithError(r.error().message.c_str());
      return;
    }
    nodes = r->evaluated_nodes;
    offsets = r->lift.size();
  }
  st.counters["offsets"] = double(offsets);
  st.counters["nodes_per_offset"] = double(nodes) / double(offsets);
}
BENCHMARK(BM_ArealLift256x65)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

// The direct method on a 16 x 17 subset of the same offsets (every node at every offset), for
// the pruning's gain per offset.
void BM_ArealLiftDirectSubset(benchmark::State& st) {
  ArealLiftOptions o = target_options(1, false);
  o.offset_min = -8 * o.step;
  o.offset_max = 7 * o.step;
  o.across_max = 8 * o.across_step;
  std::size_t nodes = 0, offsets = 0;
  for (auto _ : st) {
    auto r = areal_lift(lower(), upper(), 0.0, o);
    if (!r) {
      st.SkipWithError(r.error().message.c_str());
      return;
    }
    nodes = r->evaluated_nodes;
    offsets = r->lift.size();
  }
  st.counters["offsets"] = double(offsets);
  st.counters["nodes_per_offset"] = double(nodes) / double(offsets);
}
BENCHMARK(BM_ArealLiftDirectSubset)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

// The matched prediction off the grid (areal_tilt_hold) and its spread (areal_tilt_hold_spread) on
// the pair "X3P windows 1, heights x 2.5" of docs/mujoco.md (lower 48 x 48 at node (20, 20), upper
// 12 x 12 at (380, 400), turned over, plane removed; sliding along x, free, D a twentieth of the
// lower map), dropped at offset 0.
const Map& tilt_face(std::size_t i0, std::size_t j0, std::size_t n) {
  static std::map<std::size_t, Map> faces;
  auto it = faces.find(i0);
  if (it == faces.end()) {
    Map w = window(*read_map(kX3p), i0, j0, n);
    for (double& z : w.heights) z *= 2.5;
    it = faces.emplace(i0, w).first;
  }
  return it->second;
}

void BM_ArealTiltHold(benchmark::State& st) {
  const Map& f = tilt_face(20, 20, 48);
  const Map& g = tilt_face(380, 400, 12);
  ArealTiltOptions t;
  double hold = 0;
  long evaluations = 0;
  for (auto _ : st) {
    auto r = areal_tilt_hold(f, g, t);
    if (!r) {
      st.SkipWithError(r.error().message.c_str());
      return;
    }
    hold = r->hold_angle;
    evaluations = r->evaluations;
  }
  st.counters["hold_deg"] = hold * 180 / std::numbers::pi;
  st.counters["evaluations"] = double(evaluations);
}
BENCHMARK(BM_ArealTiltHold)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ArealTiltHoldSpread(benchmark::State& st) {
  const Map& f = tilt_face(20, 20, 48);
  const Map& g = tilt_face(380, 400, 12);
  ArealTiltOptions t;
  const auto hold = areal_tilt_hold(f, g, t);
  if (!hold) {
    st.SkipWithError(hold.error().message.c_str());
    return;
  }
  ArealTiltHoldSpread r;
  for (auto _ : st) {
    auto s = areal_tilt_hold_spread(f, g, t, *hold);
    if (!s) {
      st.SkipWithError(s.error().message.c_str());
      return;
    }
    r = *s;
  }
  st.counters["low_deg"] = r.low * 180 / std::numbers::pi;
  st.counters["high_deg"] = r.high * 180 / std::numbers::pi;
  st.counters["slips"] = r.slips;
  st.counters["ambiguous"] = r.ambiguous;
  st.counters["evaluations"] = double(r.evaluations);
}
BENCHMARK(BM_ArealTiltHoldSpread)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
