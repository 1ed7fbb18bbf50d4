// Signature-function benchmarks (issue 2):
//  (1) one WM pair at the paper's finest resolution (D = 1.5, n_max = 10, 11,534 points), every
//      event offset up to L_b/2 — target < 50 ms on 2 cores;
//  (2) a pair of 1,000,000-point random self-affine profiles at every sample offset up to half
//      the length (500,001 offsets) — target < 10 s on 2 cores — against a plain O(N) scan per
//      offset measured in the same run (PlainScan reports seconds per offset; bench/run-benchmarks
//      extrapolates it to all offsets and prints the ratio).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <limits>

#include "frictal/generators.hpp"
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

}  // namespace

BENCHMARK_MAIN();
