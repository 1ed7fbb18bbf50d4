// Measured-surface benchmarks, each beside the obvious direct method in the same run:
//  (1) reading the 650 x 650 float64 X3P (x3p-2.x3p: libzip in memory, pugixml, MD5 checks)
//      vs `unzip -p` of bindata/data.bin into memory + memcpy (no XML, no checks);
//  (2) the anisotropy table of that map over 36 directions (128 lines per direction, exact
//      self-signature per line) vs the direct method: h(s) by lift_direct() at every sample
//      offset of every line and its one-sided slopes there (O(N^2) per line);
//  (3) the areal signature of two such maps (x3p-2 and x3p-2 mirrored in y) along 0 and 40 deg,
//      block max bounds vs the direct scan of every node at every offset (identical results).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>

#include "frictal/analysis.hpp"
#include "frictal/areal.hpp"
#include "frictal/io.hpp"
#include "frictal/signature.hpp"

using namespace frictal;

namespace {

#ifndef FRICTAL_TEST_DATA
#define FRICTAL_TEST_DATA "tests/data"
#endif
const std::string kX3p = std::string(FRICTAL_TEST_DATA) + "/x3p/x3p-2.x3p";

const Map& big_map() {
  static const Map m = *read_map(kX3p);
  return m;
}

// A second, different 650 x 650 surface for the upper block: the same map mirrored in y.
const Map& big_map_mirrored() {
  static const Map u = [] {
    Map m = big_map();
    for (std::size_t j = 0; j < m.ny; ++j)
      for (std::size_t i = 0; i < m.nx; ++i) m.at(i, j) = big_map().at(i, m.ny - 1 - j);
    return m;
  }();
  return u;
}

void BM_ReadX3p650(benchmark::State& st) {
  for (auto _ : st) {
    auto m = read_map(kX3p);
    if (!m) st.SkipWithError(m.error().message.c_str());
    benchmark::DoNotOptimize(m->heights.data());
  }
  st.counters["points"] = 650.0 * 650.0;
}
BENCHMARK(BM_ReadX3p650)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ReadX3p650_UnzipDirect(benchmark::State& st) {
  for (auto _ : st) {
    std::string cmd = "unzip -p '" + kX3p + "' bindata/data.bin";
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) {
      st.SkipWithError("unzip not available");
      break;
    }
    std::string bytes;
    char buf[1 << 16];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) bytes.append(buf, n);
    pclose(p);
    if (bytes.size() != 650u * 650u * 8u) {
      st.SkipWithError("unzip -p failed");
      break;
    }
    std::vector<double> h(650 * 650);
    std::memcpy(h.data(), bytes.data(), bytes.size());
    benchmark::DoNotOptimize(h.data());
  }
}
BENCHMARK(BM_ReadX3p650_UnzipDirect)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Anisotropy36(benchmark::State& st) {
  const Map& m = big_map();
  DirectionalOptions o;
  o.signature.threads = 1;
  double mean = 0;
  for (auto _ : st) {
    auto t = anisotropy(m, 36, o);
    if (!t) st.SkipWithError(t.error().message.c_str());
    mean = 0;
    for (const auto& d : *t) mean += d.theta_forward / 36;
  }
  st.counters["mean_theta_forward_deg"] = mean * 180 / std::numbers::pi;
}
BENCHMARK(BM_Anisotropy36)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

// Direct: for every line, h(s) = lift_direct(line, rotate180(line), s) at every sample offset
// s = k h up to half the line (for a uniform line these are all the event offsets), and the
// one-sided slopes of h there, atan((h(s + e) - h(s)) / e) and atan((h(s) - h(s - e)) / e) with
// e = 1e-4 h (h is piecewise linear); length-weighted mean over lines of the max slope.
void BM_Anisotropy36_Direct(benchmark::State& st) {
  const Map& m = big_map();
  double mean = 0;
  for (auto _ : st) {
    mean = 0;
    for (int k = 0; k < 36; ++k) {
      const double angle = 2 * std::numbers::pi * k / 36;
      const double c = std::cos(angle), s = std::sin(angle);
      const double across = std::abs(s) * m.width() + std::abs(c) * m.height();
      const double spacing = std::max(std::max(m.dx, m.dy), across / 128);
      auto lines = map_lines(m, angle, spacing, 0, 32);
      double sum = 0, len = 0;
      for (const auto& l : lines) {
        const Profile up = rotate180(l);
        const double h = l.x[1] - l.x[0], e = 1e-4 * h;
        const std::size_t n = l.size() / 2;
        double best = -1e300;
        for (std::size_t i = 0; i <= n; ++i) {
          const double at = lift_direct(l, up, double(i) * h);
          best = std::max(best, std::atan((lift_direct(l, up, double(i) * h + e) - at) / e));
          if (i > 0) best = std::max(best, std::atan((at - lift_direct(l, up, double(i) * h - e)) / e));
        }
        sum += best * l.length();
        len += l.length();
      }
      mean += sum / len / 36;
    }
  }
  st.counters["mean_theta_forward_deg"] = mean * 180 / std::numbers::pi;
}
BENCHMARK(BM_Anisotropy36_Direct)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

void areal(benchmark::State& st, bool prune, double angle) {
  const Map& m = big_map();
  const Map& u = big_map_mirrored();
  ArealSignatureOptions o;
  o.prune = prune;
  o.threads = 1;
  std::size_t nodes = 0;
  double theta = 0;
  for (auto _ : st) {
    auto r = areal_signature(m, u, angle, o);
    if (!r) st.SkipWithError(r.error().message.c_str());
    nodes = r->evaluated_nodes;
    theta = r->theta_max_forward;
    st.counters["offsets"] = double(r->offset.size());
  }
  st.counters["evaluated_nodes"] = double(nodes);
  st.counters["theta_max_forward_deg"] = theta * 180 / std::numbers::pi;
}
void BM_ArealSignature650(benchmark::State& st) { areal(st, true, 0.0); }
void BM_ArealSignature650_Direct(benchmark::State& st) { areal(st, false, 0.0); }
void BM_ArealSignature650_40deg(benchmark::State& st) { areal(st, true, 40 * std::numbers::pi / 180); }
void BM_ArealSignature650_40deg_Direct(benchmark::State& st) { areal(st, false, 40 * std::numbers::pi / 180); }
BENCHMARK(BM_ArealSignature650)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ArealSignature650_Direct)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);
BENCHMARK(BM_ArealSignature650_40deg)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ArealSignature650_40deg_Direct)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
