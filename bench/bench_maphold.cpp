// The map model's prediction (predict() on two maps: areal_tilt_hold over drops, map_hold.hpp)
// on the cases whose cost the surface, not its flatness or mu_a, should bound:
//   - a rough random 12 x 10 map against itself, mu_a = 0, 0.02 and 0.1 (the friction cones'
//     hull at every descent step against the frictionless least-norm point);
//   - a smooth symmetric sine against itself (conforming: many spheres near the top at once);
//   - the same sine nearly flat (a hundredth of the amplitude).
// One thread, sizes that run in about a second each; the counters hold the median hold angle, so
// that a faster build can be checked for the same answers at a glance.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>

#include "frictal/predict.hpp"

using namespace frictal;

namespace {

/// Uniform random heights in +-0.5 um on a 1 um grid (slopes of order 1: rough at the pixel
/// scale), from a fixed seed.
PredictSurface random_map(std::size_t nx, std::size_t ny, unsigned seed) {
  PredictSurface s;
  s.is_map = true;
  s.name = "random";
  s.map.nx = nx;
  s.map.ny = ny;
  s.map.dx = s.map.dy = 1e-6;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.5e-6, 0.5e-6);
  for (std::size_t k = 0; k < nx * ny; ++k) s.map.heights.push_back(u(rng));
  return s;
}

/// bench/sine_maps.py's "sym" map: amp sin(2 pi x / L) sin(3 pi y / L) on n x n nodes at 1 um,
/// L = n um (conforming to itself turned over).
PredictSurface sine_map(std::size_t n, double amp) {
  PredictSurface s;
  s.is_map = true;
  s.name = "sine";
  s.map.nx = s.map.ny = n;
  s.map.dx = s.map.dy = 1e-6;
  const double L = double(n);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i)
      s.map.heights.push_back(amp * std::sin(2 * std::numbers::pi * double(i) / L) *
                              std::sin(3 * std::numbers::pi * double(j) / L));
  return s;
}

void run(benchmark::State& st, const PredictSurface& m, const PredictOptions& o) {
  double median = 0;
  for (auto _ : st) {
    auto p = predict(m, nullptr, o);
    if (!p) {
      st.SkipWithError(p.error().message.c_str());
      return;
    }
    median = p->friction_angle.q50;
  }
  st.counters["median_deg"] = median * 180 / std::numbers::pi;
}

/// Arg: mu_a in thousandths. 2 x 2 drops.
void BM_MapPredictRandomFriction(benchmark::State& st) {
  static const PredictSurface m = random_map(12, 10, 2);
  PredictOptions o;
  o.atomic_friction = double(st.range(0)) / 1000;
  o.map_drops = 2;
  o.threads = 1;
  run(st, m, o);
}
BENCHMARK(BM_MapPredictRandomFriction)->Arg(0)->Arg(20)->Arg(100)->Unit(benchmark::kMillisecond)->UseRealTime();

/// Arg: nodes on a side; 20 nm amplitude, one drop at the centres aligned.
void BM_MapPredictSine(benchmark::State& st) {
  const PredictSurface m = sine_map(std::size_t(st.range(0)), 20e-9);
  PredictOptions o;
  o.start_offset = {0, 0};
  o.threads = 1;
  run(st, m, o);
}
BENCHMARK(BM_MapPredictSine)->Arg(80)->Unit(benchmark::kMillisecond)->UseRealTime();

/// Arg: nodes on a side; 0.2 nm amplitude (nearly flat), one drop.
void BM_MapPredictNearlyFlat(benchmark::State& st) {
  const PredictSurface m = sine_map(std::size_t(st.range(0)), 0.2e-9);
  PredictOptions o;
  o.start_offset = {0, 0};
  o.threads = 1;
  run(st, m, o);
}
BENCHMARK(BM_MapPredictNearlyFlat)->Arg(80)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
