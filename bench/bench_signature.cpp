// Signature-function benchmarks:
//  (1) one WM pair at the paper's finest resolution (D = 1.5, n_max = 10, 11,534 points), every
//      event offset up to L_b/2 — target < 50 ms on 2 cores;
//  (2) a pair of 1,000,000-point random self-affine profiles at every sample offset up to half
//      the length (500,001 offsets) — target < 10 s on 2 cores — against a plain O(N) scan per
//      offset measured in the same run (PlainScan reports seconds per offset; bench/run-benchmarks
//      extrapolates it to all offsets and prints the ratio).
#include <benchmark/benchmark.h>

#include <time.h>
#include <algorithm>

#include <cmath>
#include <limits>
#include <map>
#include <tuple>
#include <utility>

#include "frictal/generators.hpp"
#include "frictal/hold.hpp"
#include "frictal/signature.hpp"

using namespace frictal;

namespace {

struct Pair {
  Profile lower, upper;  // upper already rotated
};

const Pair& wm_pair() {
  static const Pair p = [] {
    WmParams w;  // D = 1.5, n_max = 10, L = 1 um, L_b = 20 um
    Profile f = *wm_profile(w);
    w.seed = 2;
    return Pair{f, rotate180(*wm_profile(w))};
  }();
  return p;
}

const Pair& big_pair() {
  static const Pair p = [] {
    SelfAffineParams s;
    s.points = 1'000'000;
    s.length = 1e-3;
    s.hurst = 0.8;
    s.rms_height = 1e-6;
    Profile f = *self_affine_profile(s);
    s.seed = 2;
    return Pair{f, rotate180(*self_affine_profile(s))};
  }();
  return p;
}

void BM_WmPairPaperFinest(benchmark::State& st) {
  const Pair& p = wm_pair();
  SignatureOptions o;
  o.threads = static_cast<unsigned>(st.range(0));
  o.keep_contacts = false;
  std::size_t n = 0;
  for (auto _ : st) {
    auto r = signature(p.lower, p.upper, o);
    n = r->offset.size();
    benchmark::DoNotOptimize(r->theta_max_forward);
  }
  st.counters["offsets"] = static_cast<double>(n);
  st.counters["points"] = static_cast<double>(p.lower.size());
}
BENCHMARK(BM_WmPairPaperFinest)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SelfAffine1M(benchmark::State& st) {
  const Pair& p = big_pair();
  SignatureOptions o;
  o.threads = static_cast<unsigned>(st.range(0));
  o.keep_contacts = false;
  std::size_t n = 0;
  for (auto _ : st) {
    auto r = signature(p.lower, p.upper, o);
    n = r->offset.size();
    benchmark::DoNotOptimize(r->theta_max_forward);
  }
  st.counters["offsets"] = static_cast<double>(n);
}
BENCHMARK(BM_SelfAffine1M)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(2);

// The plain method: for each offset k, max_i f[i] - g[i - k] over the overlap (aligned grids,
// so this is the exact lift), a tight vectorisable loop. Timed on 200 offsets spread over the
// range; reports the time per offset.
void BM_PlainScan1MPerOffset(benchmark::State& st) {
  const Pair& p = big_pair();
  const auto& f = p.lower.z;
  const auto& g = p.upper.z;
  const std::size_t N = f.size();
  const std::size_t K = 200;
  for (auto _ : st) {
    double acc = 0;
    for (std::size_t t = 0; t < K; ++t) {
      const std::size_t k = t * (N / 2) / K;
      double best = -std::numeric_limits<double>::infinity();
      for (std::size_t i = k; i < N; ++i) best = std::max(best, f[i] - g[i - k]);
      acc += best;
    }
    benchmark::DoNotOptimize(acc);
  }
  st.counters["seconds_per_offset"] = benchmark::Counter(
      static_cast<double>(K), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_PlainScan1MPerOffset)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

void BM_KochK3Signature(benchmark::State& st) {
  KochParams k;
  k.iterations = 3;
  k.alpha = 20 * 3.14159265358979 / 180;
  Profile p = *koch_profile(k);
  for (auto _ : st) {
    auto r = self_signature(p);
    benchmark::DoNotOptimize(r->theta_max_forward);
  }
}
BENCHMARK(BM_KochK3Signature)->Unit(benchmark::kMillisecond);

void BM_KochK5Envelope(benchmark::State& st) {
  KochParams k;
  k.iterations = 5;
  k.alpha = 25 * 3.14159265358979 / 180;
  Curve c = *koch_curve(k);
  for (auto _ : st) benchmark::DoNotOptimize(upper_envelope(c)->size());
  st.counters["points"] = static_cast<double>(c.size());
}
BENCHMARK(BM_KochK5Envelope)->Unit(benchmark::kMillisecond);

// Scaling: cost per offset vs the number of points N for two surface kinds, both
// profiles of N points on the same length (finer sampling of the same kind of surface):
//   kind 0: random self-affine (H = 0.8), kind 1: Weierstrass-Mandelbrot with 12 scales
//   (n_max = 11, D = 1.5, gamma = 1.5, L_b = 20 L).
// grid 0: both on the same grid (an aligned lattice: every sample shift is an event, exact);
// grid 1: the same grids, offsets sampled halfway between lattice offsets (--offsets N whose
// offsets miss the lattice); grid 2: the upper profile with 0.7 N points on the same length (the
// grids do not align: the exact signature would need ~N^2 events, so offsets are sampled at the
// finer spacing, as beyond max_events). Grids 1 and 2 take the general search over both faces.
// One window of consecutive offsets one lower spacing apart, starting at a quarter of the
// length, one thread. Thread CPU time, so that other load on the machine does not count: cost
// per offset = (t(window) - t(set-up)) / offsets, where t(set-up) is the least of three calls
// with 2 offsets (faces and bound tables, paid once per call) and t(window) the least of three.
// tilted: SignatureOptions::tilted_bounds (1, the default; 0: block maxima only, as before).
const Pair& scaling_pair(int kind, std::size_t n, int grid) {
  static std::map<std::tuple<int, std::size_t, int>, Pair> cache;
  auto key = std::make_tuple(kind, n, grid);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  cache.clear();  // one big pair in memory at a time
  const std::size_t nu = grid == 2 ? static_cast<std::size_t>(0.7 * static_cast<double>(n)) : n;
  Pair p;
  if (kind == 0) {
    SelfAffineParams s;
    s.points = n;
    s.length = 1e-3;
    s.hurst = 0.8;
    s.rms_height = 1e-6;
    p.lower = *self_affine_profile(s);
    s.seed = 2;
    s.points = nu;
    p.upper = rotate180(*self_affine_profile(s));
  } else {
    WmParams w;
    w.n_max = 11;
    w.spacing = w.length / static_cast<double>(n - 1);
    p.lower = *wm_profile(w);
    w.seed = 2;
    w.spacing = w.length / static_cast<double>(nu - 1);
    p.upper = rotate180(*wm_profile(w));
  }
  return cache.emplace(key, std::move(p)).first->second;
}

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

void scaling(benchmark::State& st, int kind, std::size_t n, int grid, bool tilted, std::size_t W) {
  const Pair& p = scaling_pair(kind, n, grid);
  const double L = p.lower.length();
  const double dx = L / static_cast<double>(p.lower.size() - 1);
  SignatureOptions o;
  o.threads = 1;
  o.keep_contacts = false;
  o.tilted_bounds = tilted;
  o.offset_min = std::round(0.25 * L / dx) * dx + (grid == 1 ? 0.5 * dx : 0.0);
  auto timed = [&](std::size_t offsets, std::size_t& count) {
    o.offset_max = o.offset_min + static_cast<double>(offsets - 1) * dx;
    if (grid != 0) o.offsets = offsets;  // sampled one lower spacing apart
    const double c0 = thread_cpu_seconds();
    auto r = signature(p.lower, p.upper, o);
    const double t = thread_cpu_seconds() - c0;
    if (!r.ok()) {
      st.SkipWithError(r.error().message.c_str());
      return 0.0;
    }
    count = r->offset.size();
    benchmark::DoNotOptimize(r->theta_max_forward);
    return t;
  };
  double per_offset = 0, setup = 0, window = 0;
  bool exact = false;
  for (auto _ : st) {
    std::size_t c0 = 0, c1 = 0;
    setup = window = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) setup = std::min(setup, timed(2, c0));
    for (int k = 0; k < 3; ++k) window = std::min(window, timed(W, c1));
    per_offset = (window - setup) / static_cast<double>(c1 - c0);
    exact = grid == 0;
  }
  st.counters["points"] = static_cast<double>(p.lower.size());
  st.counters["upper_points"] = static_cast<double>(p.upper.size());
  st.counters["offsets"] = static_cast<double>(W);
  st.counters["exact"] = exact ? 1 : 0;
  st.counters["cpu_seconds_per_offset"] = per_offset;
  st.counters["cpu_seconds_setup"] = setup;
}

void BM_SignatureScaling(benchmark::State& st) {
  const auto n = static_cast<std::size_t>(st.range(1));
  const std::size_t W = n >= 10'000'000 ? 1'000'000 : (n >= 1'000'000 ? 200'000 : 50'000);
  scaling(st, static_cast<int>(st.range(0)), n, 0, st.range(2) != 0, W);
}
BENCHMARK(BM_SignatureScaling)
    ->ArgNames({"kind", "points", "tilted"})
    ->ArgsProduct({{0, 1}, {100'000, 1'000'000, 10'000'000}, {1, 0}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

void BM_SignatureScalingNonAligned(benchmark::State& st) {
  const auto n = static_cast<std::size_t>(st.range(1));
  const std::size_t W = n >= 10'000'000 ? 200'000 : (n >= 1'000'000 ? 50'000 : 20'000);
  scaling(st, static_cast<int>(st.range(0)), n, static_cast<int>(st.range(2)), true, W);
}
BENCHMARK(BM_SignatureScalingNonAligned)
    ->ArgNames({"kind", "points", "grid"})
    ->ArgsProduct({{0, 1}, {100'000, 1'000'000, 10'000'000}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace

// The hold-angle distribution over drops of the 10^6-point pair (target <= 2 s on 2 cores, the
// lift over the widened range included). Stages: the lift (a signature over
// [0, L/2] widened by d = L/20 on both sides), the LiftCurve, the distribution of both directions.
void BM_HoldDistribution1M(benchmark::State& st) {
  const Pair& p = big_pair();
  SignatureOptions o;
  o.threads = static_cast<unsigned>(st.range(0));
  std::size_t basins = 0;
  for (auto _ : st) {
    auto h = analyse_hold(p.lower, p.upper, o, HoldOptions{});
    if (!h) {
      st.SkipWithError(h.error().message.c_str());
      break;
    }
    basins = h->distribution.forward.basins.rest.size();
  }
  st.counters["basins"] = static_cast<double>(basins);
}
BENCHMARK(BM_HoldDistribution1M)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(2);

// The distribution alone on a prepared LiftCurve (records, basins, steepest chords).
void BM_HoldDistributionOnCurve1M(benchmark::State& st) {
  const Pair& p = big_pair();
  static const LiftCurve curve = [&] {
    SignatureOptions o;
    o.keep_contacts = false;
    o.offset_min = -5e-5;
    o.offset_max = 5.5e-4;
    auto sig = signature(p.lower, p.upper, o);
    return sig ? lift_curve(*sig).value() : LiftCurve{};
  }();
  if (curve.offset.empty()) {
    st.SkipWithError("signature of the widened range failed");
    return;
  }
  HoldOptions h;
  h.runaway_distance = 5e-5;
  h.drop_min = 0;
  h.drop_max = 5e-4;
  for (auto _ : st) benchmark::DoNotOptimize(hold_distribution(curve, h));
  st.counters["vertices"] = static_cast<double>(curve.offset.size());
}
BENCHMARK(BM_HoldDistributionOnCurve1M)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

BENCHMARK_MAIN();
