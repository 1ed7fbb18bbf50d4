// Spheropolygon engine benchmarks: cost per time step of the tilting test on Koch pairs
// (Table I/II geometry and parameters), and of rebuilding the neighbour list.
//   build/bench/bench/bench_dem --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "frictal/dem.hpp"
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

// Steps at a fixed state with 1, 2, ... threads (dem::set_thread_count): K3 blocks (alpha = 20
// deg, Table I/II, nested at half a wavelength) settled for 1 s under the tilt test's adaptive
// step and implicit dashpots (untimed), the lower block tilting at 0.05 rad/s; each iteration
// copies that state and times 2000 steps. Arguments: threads, tune (1: the tuner may keep steps
// serial; 0: every step that can be split is split). Counters: us per step, hot pairs per
// step, fraction of steps split. Results are the same for every thread count (tests/dem).
const frictal::dem::Model& k3_blocks() {
  static const frictal::dem::Model model = [] {
    const frictal::Curve c = koch(3, 20);
    double zmin = 1e9, zmax = -1e9;
    for (double z : c.z) zmin = std::min(zmin, z), zmax = std::max(zmax, z);
    frictal::dem::BodyDef lower, upper;
    lower.x = c.x;
    lower.y = c.z;
    lower.x.push_back(c.x.back());
    lower.y.push_back(zmin - 0.01);
    lower.x.push_back(c.x.front());
    lower.y.push_back(zmin - 0.01);
    lower.type = frictal::dem::BodyType::Kinematic;
    lower.motion.angular_velocity = -0.05;
    lower.motion.start_time = 1.0;
    const double length = c.x.back();
    for (std::size_t i = c.x.size(); i-- > 0;) {  // the face turned over, half a wavelength on
      upper.x.push_back(length - c.x[i] + 0.005);
      upper.y.push_back(-c.z[i] + 2 * zmax + 2e-5);
    }
    double top = -1e9;
    for (double y : upper.y) top = std::max(top, y);
    upper.x.push_back(upper.x.back());
    upper.y.push_back(top + 0.01);
    upper.x.push_back(upper.x.front());
    upper.y.push_back(top + 0.01);
    frictal::dem::WorldDef wd;
    wd.adaptive_time_step = true;
    wd.implicit_damping = true;
    wd.time_step = 1e-4;
    frictal::dem::Model m = *frictal::dem::make_model(wd, {lower, upper});
    m.motion[0].pivot = m.initial_position[0];
    return m;
  }();
  return model;
}

void BM_StepsAtFixedState(benchmark::State& state) {
  const frictal::dem::Model& m = k3_blocks();
  static const frictal::dem::State settled = [&] {
    frictal::dem::State st = frictal::dem::make_state(m);
    while (st.time < 1.05) (void)frictal::dem::step(m, st);
    return st;
  }();
  const unsigned threads = static_cast<unsigned>(state.range(0));
  const bool tune = state.range(1) != 0;
  constexpr int kSteps = 2000;
  double steps = 0, evaluated = 0, split = 0;
  for (auto _ : state) {
    state.PauseTiming();
    frictal::dem::State st = settled;
    frictal::dem::set_thread_count(st, threads, 64, tune);
    (void)frictal::dem::step(m, st);  // starts the team
    const auto e0 = st.timings.pairs_evaluated, s0 = st.timings.split_steps;
    state.ResumeTiming();
    for (int i = 0; i < kSteps; ++i)
      if (!frictal::dem::step(m, st).ok()) {
        state.SkipWithError("step failed");
        return;
      }
    steps += kSteps;
    evaluated += static_cast<double>(st.timings.pairs_evaluated - e0);
    split += static_cast<double>(st.timings.split_steps - s0);
  }
  state.counters["us_per_step"] =
      benchmark::Counter(steps * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["hot_pairs_per_step"] = evaluated / steps;
  state.counters["split_fraction"] = split / steps;
  state.counters["contacts"] = settled.contact_count;
  state.counters["speed_m_s"] = std::hypot(settled.velocity[1].x, settled.velocity[1].y);
  state.counters["time_s"] = settled.time;
}
BENCHMARK(BM_StepsAtFixedState)
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({2, 1})
    ->Args({3, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(0.5);

BENCHMARK_MAIN();
