// Spheropolygon engine benchmarks: cost per time step of the tilting test on Koch pairs
// (Table I/II geometry and parameters), and of rebuilding the neighbour list.
//   build/bench/bench/bench_dem --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <cmath>

#include "frictal/generators.hpp"
#include "frictal/tilt.hpp"

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

frictal::Curve koch(int n, double alpha_deg) {
  frictal::KochParams p;
  p.iterations = n;
  p.alpha = alpha_deg * kDeg;
  return *frictal::koch_curve(p);  // Table I: lambda = 0.01 m, L_b = 0.2 m
}

// Settling (0.1 s) and a 2-degree tilt of K_n at alpha = 20 deg: the steps of a real run while
// the blocks are in contact. Counters: us per step, pairs in the list, list rebuilds.
void BM_TiltSteps(benchmark::State& state) {
  const frictal::Curve c = koch(static_cast<int>(state.range(0)), 20);
  frictal::TiltConfig cfg;
  cfg.max_tilt = 2 * kDeg;
  cfg.series_interval = 0;
  cfg.predict = false;
  cfg.initial_offset = 0.005;  // nested (least lift for every K_n here)
  // Cost per step on the fixed explicit 1e-5 s step, comparable with the recorded results (the
  // tilt test's default adaptive step takes ~10x fewer, slightly dearer steps: docs/dem.md sec. 7).
  cfg.adaptive_time_step = false;
  cfg.implicit_damping = false;
  cfg.time_step = 1e-5;
  double steps = 0, wall = 0, pairs = 0, evaluated = 0, builds = 0, contacts = 0;
  for (auto _ : state) {
    auto r = frictal::run_tilt(c, c, cfg);
    if (!r.ok()) {
      state.SkipWithError(r.error().message.c_str());
      return;
    }
    steps += static_cast<double>(r->steps);
    wall += r->wall_time;
    pairs += static_cast<double>(r->timings.pairs_visited);
    evaluated += static_cast<double>(r->timings.pairs_evaluated);
    builds += static_cast<double>(r->timings.list_builds);
    contacts = r->settled_contacts;
  }
  state.counters["us_per_step"] = 1e6 * wall / steps;
  state.counters["pairs_per_step"] = pairs / steps;
  state.counters["evaluated_per_step"] = evaluated / steps;  // hot list (or full list on refreshes)
  state.counters["steps_per_rebuild"] = steps / builds;
  state.counters["contacts"] = contacts;
  state.counters["vertices_per_block"] = static_cast<double>(c.size() + 2);
}
BENCHMARK(BM_TiltSteps)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond)->Iterations(1);

// Neighbour-list rebuild on the K_3 pair: a 1e-6 m skin rebuilds every few steps while the
// upper block settles onto the lower one (the rebuild test follows the relative motion).
void BM_ListRebuildK3(benchmark::State& state) {
  const frictal::Curve c = koch(3, 20);
  frictal::TiltConfig cfg;
  cfg.max_tilt = 0.1 * kDeg;
  cfg.settle_time = 0.0;
  cfg.skin = 1e-6;
  cfg.series_interval = 0;
  cfg.predict = false;
  cfg.initial_offset = 0.005;
  cfg.adaptive_time_step = false;
  cfg.implicit_damping = false;
  cfg.time_step = 1e-5;
  double builds = 0, t = 0;
  for (auto _ : state) {
    auto r = frictal::run_tilt(c, c, cfg);
    if (!r.ok()) {
      state.SkipWithError(r.error().message.c_str());
      return;
    }
    builds += static_cast<double>(r->timings.list_builds);
    t += r->timings.neighbor_list;
  }
  state.counters["us_per_rebuild"] = 1e6 * t / builds;
  state.counters["rebuilds"] = builds;
}
BENCHMARK(BM_ListRebuildK3)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
