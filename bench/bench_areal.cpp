// The lift over two dimensions of offset (areal_lift) and the free-lateral hold angle on it.
// Issue 24's target: 256 x 256 lower and 128 x 128 upper nodes over 256 x 64 offsets in <= 5 s
// on 2 cores. The faces are windows of the measured 650 x 650 X3P map of the test data (the
// upper one from the opposite corner, so the two differ), detrended as the CLI does by default.
#include <benchmark/benchmark.h>

#include <numbers>
#include <string>

#include "frictal/analysis.hpp"
#include "frictal/areal.hpp"
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

// The distribution over drops of the free-lateral hold angle on the target lift (one thread).
void BM_ArealHoldDistribution(benchmark::State& st) {
  static const ArealLift lift = *areal_lift(lower(), upper(), 0.0, target_options(2, true));
  ArealHoldOptions o;
  o.runaway_distance = 32 * lift.step;
  double mean = 0;
  std::size_t basins = 0;
  for (auto _ : st) {
    auto r = areal_hold_distribution(lift, o);
    if (!r) {
      st.SkipWithError(r.error().message.c_str());
      return;
    }
    mean = r->hold.mean;
    basins = r->rest.size();
  }
  st.counters["basins"] = double(basins);
  st.counters["hold_mean_deg"] = mean * 180 / std::numbers::pi;
}
BENCHMARK(BM_ArealHoldDistribution)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
