// Elastic normal contact (frictal/contact.hpp) at the sizes users bring: one solve of a 1024 x 1024
// self-affine map (periodic, and padded to 2048 x 2048 when not periodic), a 10-load curve of it
// (each load warm-started from the previous one), and a profile of 10^5 points at one load (10^6
// points take minutes: bench/results/contact.md). The
// maps are Fourier-filtered self-affine surfaces (Hurst exponent 0.8, spectrum flat below the
// longest wavelength, rms slope 0.1, random phases), made here with FFTW; the loads put 1-10 % of
// the points in contact (nominal pressure p = kappa^-1 E* rms slope A_r / A_0 with kappa ~ 2).
#include <benchmark/benchmark.h>
#include <fftw3.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <vector>

#include "frictal/contact.hpp"

using namespace frictal;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kE = 1e9;  // E* (Pa)

/// An n x n periodic self-affine map (Hurst 0.8) of rms slope 0.1 on spacing dx (m).
Map self_affine_map(std::size_t n, double dx, unsigned seed) {
  const std::size_t nh = n / 2 + 1;
  std::vector<std::complex<double>> spec(n * nh);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> phase(0, 2 * kPi);
  const double L = double(n) * dx, q0 = 2 * kPi / L;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < nh; ++i) {
      const double ky = j <= n / 2 ? double(j) : double(j) - double(n);
      const double q = q0 * std::hypot(double(i), ky);
      const double amp = q > 0 ? std::pow(std::max(q, q0), -1 - 0.8) : 0.0;
      spec[j * nh + i] = std::polar(amp, phase(rng));
    }
  Map m;
  m.nx = m.ny = n;
  m.dx = m.dy = dx;
  m.heights.assign(n * n, 0.0);
  fftw_plan plan = fftw_plan_dft_c2r_2d(int(n), int(n), reinterpret_cast<fftw_complex*>(spec.data()), m.heights.data(),
                                        FFTW_ESTIMATE);
  fftw_execute(plan);
  fftw_destroy_plan(plan);
  double s = 0;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      const double gx = (m.heights[j * n + (i + 1) % n] - m.heights[j * n + (i + n - 1) % n]) / (2 * dx);
      const double gy = (m.heights[((j + 1) % n) * n + i] - m.heights[((j + n - 1) % n) * n + i]) / (2 * dx);
      s += gx * gx + gy * gy;
    }
  const double f = 0.1 / std::sqrt(s / double(n * n));
  for (double& h : m.heights) h *= f;
  return m;
}

const Map& map1024() {
  static const Map m = self_affine_map(1024, 1e-6, 1);
  return m;
}

/// The nominal pressure that puts about `fraction` of the points in contact (kappa = 2).
double pressure_for(double fraction) { return fraction * kE * 0.1 / 2; }

void BM_ContactMap1024(benchmark::State& st) {
  ContactOptions o;
  o.contact_modulus = kE;
  o.periodic = st.range(0) != 0;
  o.threads = unsigned(st.range(1));
  double iterations = 0, fraction = 0, stiffness_iterations = 0;
  for (auto _ : st) {
    auto r = solve_contact(map1024(), {ContactLoadKind::Pressure, pressure_for(0.05)}, o);
    if (!r) st.SkipWithError(r.error().message.c_str());
    iterations = r->iterations;
    stiffness_iterations = r->stiffness_iterations;
    fraction = r->contact_fraction;
  }
  st.counters["cg_iterations"] = iterations;
  st.counters["stiffness_iterations"] = stiffness_iterations;
  st.counters["contact_fraction"] = fraction;
}
BENCHMARK(BM_ContactMap1024)
    ->ArgsProduct({{1, 0}, {1, 2}})
    ->ArgNames({"periodic", "threads"})
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

void BM_ContactCurve1024(benchmark::State& st) {
  ContactOptions o;
  o.contact_modulus = kE;
  o.periodic = true;
  o.threads = unsigned(st.range(0));
  std::vector<ContactLoad> loads;
  for (int k = 0; k < 10; ++k) loads.push_back({ContactLoadKind::Pressure, pressure_for(0.01 + 0.01 * k)});
  double iterations = 0;
  for (auto _ : st) {
    auto r = solve_contact_curve(map1024(), loads, o);
    if (!r) st.SkipWithError(r.error().message.c_str());
    iterations = 0;
    for (const ContactResult& c : *r) iterations += c.iterations;
  }
  st.counters["cg_iterations"] = iterations;
}
BENCHMARK(BM_ContactCurve1024)->Arg(2)->ArgName("threads")->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

void BM_ContactProfile(benchmark::State& st) {
  // A random-phase self-affine profile (Hurst 0.8, rms slope 0.1).
  const std::size_t n = std::size_t(st.range(1));
  std::vector<std::complex<double>> spec(n / 2 + 1);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> phase(0, 2 * kPi);
  for (std::size_t k = 1; k < spec.size(); ++k) spec[k] = std::polar(std::pow(double(k), -1.5 - 0.8 + 1.0), phase(rng));
  Profile p;
  p.z.assign(n, 0.0);
  fftw_plan plan =
      fftw_plan_dft_c2r_1d(int(n), reinterpret_cast<fftw_complex*>(spec.data()), p.z.data(), FFTW_ESTIMATE);
  fftw_execute(plan);
  fftw_destroy_plan(plan);
  const double dx = 1e-8;
  double s = 0;
  for (std::size_t i = 1; i < n; ++i) s += std::pow((p.z[i] - p.z[i - 1]) / dx, 2);
  const double f = 0.1 / std::sqrt(s / double(n - 1));
  p.x.resize(n);
  for (std::size_t i = 0; i < n; ++i) p.x[i] = double(i) * dx, p.z[i] *= f;
  ContactOptions o;
  o.contact_modulus = kE;
  o.periodic = st.range(0) != 0;
  double iterations = 0, fraction = 0;
  for (auto _ : st) {
    auto r = solve_contact(p, {ContactLoadKind::Pressure, pressure_for(0.05)}, o);
    if (!r) st.SkipWithError(r.error().message.c_str());
    iterations = r->iterations;
    fraction = r->contact_fraction;
  }
  st.counters["cg_iterations"] = iterations;
  st.counters["contact_fraction"] = fraction;
}
BENCHMARK(BM_ContactProfile)
    ->Args({1, 100000})
    ->Args({0, 100000})
    ->ArgNames({"periodic", "points"})
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
