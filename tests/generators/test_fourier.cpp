// The Fourier-filtered self-affine generator against its target spectrum. The periodogram here
// is a plain O(N^2) DFT of the samples (not the library's FFT), and the target's level C0 comes
// from Parseval's theorem for the piecewise-linear interpolant (not from the generator).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "frictal/fractal.hpp"
#include "frictal/generators.hpp"
#include "frictal/stats.hpp"
#include "frictal/surface_spec.hpp"

using namespace frictal;

namespace {

constexpr double kPi = std::numbers::pi;

// P_k = L |(1/N) sum_j z_j exp(-2 pi i j k / N)|^2 for k = 0 .. N/2, over the N samples of one
// period (the closing point dropped): C(q_k) in the convention of power_spectrum.
std::vector<double> periodogram(const Profile& p) {
  const std::size_t N = p.size() - 1;
  const double L = p.x.back() - p.x.front();
  std::vector<double> P(N / 2 + 1);
  for (std::size_t k = 0; k <= N / 2; ++k) {
    double re = 0, im = 0;
    for (std::size_t j = 0; j < N; ++j) {
      const double a = 2 * kPi * double((j * k) % N) / double(N);
      re += p.z[j] * std::cos(a);
      im -= p.z[j] * std::sin(a);
    }
    P[k] = L * (re * re + im * im) / double(N) / double(N);
  }
  return P;
}

// The target shape c_k = C(q_k) / C0 and its level: the rms^2 of a piecewise-linear periodic
// profile with coefficients Z_k is sum_{k != 0} |Z_k|^2 (2 + cos(2 pi k / N)) / 3 (Parseval with
// (a^2 + ab + b^2) / 3 per interval), and |Z_k|^2 = C(q_k) / L for k and -k.
struct Target {
  std::vector<double> C;  // (unit: m^3), k = 0 .. N/2
};
Target target(std::size_t N, double L, double H, double lambda_r, double lambda_s, double rms) {
  std::vector<double> c(N / 2 + 1, 0.0);
  const double kr = L / lambda_r;
  double s = 0;
  for (std::size_t k = 1; k <= N / 2; ++k) {
    const double q = 2 * kPi * double(k) / L;
    if (q > 2 * kPi / lambda_s * (1 + 1e-12)) break;
    c[k] = double(k) < kr ? 1.0 : std::pow(double(k) / kr, -(1 + 2 * H));
    s += 2 * (c[k] / L) * (2 + std::cos(2 * kPi * double(k) / double(N))) / 3;
  }
  Target t;
  t.C.resize(c.size());
  for (std::size_t k = 0; k < c.size(); ++k) t.C[k] = c[k] * rms * rms / s;
  return t;
}

FourierSelfAffineParams params(std::size_t N, double L, double H, double lambda_r, double lambda_s) {
  FourierSelfAffineParams p;
  p.points = N;
  p.length = L;
  p.hurst = H;
  p.rolloff_wavelength = lambda_r;
  p.short_cutoff_wavelength = lambda_s;
  p.rms_height = 2e-6;
  return p;
}

}  // namespace

TEST(Fourier, FixedAmplitudesGiveTheTargetSpectrumExactly) {
  // Every realisation's periodogram is the target at every wavenumber (to rounding), zero above
  // the cutoff and at q = 0.
  for (double H : {0.3, 0.7, 1.0}) {
    auto p = params(512, 1e-3, H, 1e-3 / 16, 1e-3 / 64);
    p.amplitudes = FourierAmplitudes::Fixed;
    p.seed = 7;
    auto prof = fourier_self_affine_profile(p);
    ASSERT_TRUE(prof.ok()) << prof.error().message;
    const auto P = periodogram(*prof);
    const auto T = target(512, 1e-3, H, 1e-3 / 16, 1e-3 / 64, 2e-6);
    for (std::size_t k = 0; k < P.size(); ++k) EXPECT_NEAR(P[k], T.C[k], 1e-9 * T.C[1]) << "H " << H << " k " << k;
    EXPECT_GT(T.C[64], 0);
    EXPECT_EQ(T.C[65], 0);
  }
}

TEST(Fourier, GaussianAmplitudesFollowTheTargetOnAverage) {
  // 400 seeds, N = 256: the periodogram at one wavenumber is exponentially distributed about the
  // target (|complex Gaussian|^2), so the mean over M seeds and m neighbouring wavenumbers has a
  // relative standard deviation 1/sqrt(M m) = 2.5% for m = 4. Scaling each realisation to the
  // exact rms adds a common random factor whose bias is about sum c^2 / (sum c)^2 = 1.7% here.
  // Tolerance: 4 standard deviations + 2 x that bias = 13.4%.
  const std::size_t N = 256, M = 400, m = 4;
  const double L = 1.0, H = 0.8, lr = L / 32, ls = L / 100;
  const auto T = target(N, L, H, lr, ls, 2e-6);
  std::vector<double> mean(N / 2 + 1, 0.0);
  std::size_t above = 0, modes = 0;
  for (std::uint64_t seed = 1; seed <= M; ++seed) {
    auto p = params(N, L, H, lr, ls);
    p.seed = seed;
    auto prof = fourier_self_affine_profile(p);
    ASSERT_TRUE(prof.ok()) << prof.error().message;
    const auto P = periodogram(*prof);
    for (std::size_t k = 1; k <= 100; ++k) {
      mean[k] += P[k] / double(M);
      above += P[k] > T.C[k];
      ++modes;
    }
    for (std::size_t k = 101; k < P.size(); ++k) EXPECT_LT(P[k], 1e-20 * T.C[1]) << k;
  }
  double csum = 0, c2sum = 0;
  for (std::size_t k = 1; k <= 100; ++k) {
    csum += T.C[k] / T.C[1];
    c2sum += (T.C[k] / T.C[1]) * (T.C[k] / T.C[1]);
  }
  const double bias = c2sum / (csum * csum);
  EXPECT_NEAR(bias, 0.017, 0.003);  // the figure quoted above
  const double tol = 4 / std::sqrt(double(M * m)) + 2 * bias;
  for (std::size_t k0 = 1; k0 + m - 1 <= 100; k0 += m) {
    double got = 0, want = 0;
    for (std::size_t k = k0; k < k0 + m; ++k) {
      got += mean[k];
      want += T.C[k];
    }
    EXPECT_NEAR(got / want, 1.0, tol) << "wavenumbers " << k0 << ".." << k0 + m - 1;
  }
  // Exponential about the target: P(P_k > C(q_k)) = 1/e; binomial sd 0.0024 over 40000 draws.
  EXPECT_NEAR(double(above) / double(modes), std::exp(-1.0), 0.02);
}

TEST(Fourier, RmsIsExactAndTheProfileIsPeriodic) {
  for (auto amp : {FourierAmplitudes::Gaussian, FourierAmplitudes::Fixed}) {
    auto p = params(1000, 0.2, 0.6, 0.01, 0.001);  // N not a power of two: Bluestein
    p.amplitudes = amp;
    p.rms_height = 1e-5;
    auto prof = fourier_self_affine_profile(p);
    ASSERT_TRUE(prof.ok()) << prof.error().message;
    ASSERT_EQ(prof->size(), 1001u);
    ASSERT_TRUE(prof->period.has_value());
    EXPECT_DOUBLE_EQ(*prof->period, 0.2);
    EXPECT_EQ(prof->x.front(), 0.0);
    EXPECT_EQ(prof->x.back(), 0.2);
    EXPECT_EQ(prof->z.front(), prof->z.back());
    for (std::size_t j = 0; j < prof->size(); ++j) EXPECT_NEAR(prof->x[j], 2e-4 * double(j), 1e-16);
    // rms and mean of the piecewise-linear profile, by the interval formula (second method).
    double s = 0, s2 = 0;
    for (std::size_t j = 0; j + 1 < prof->size(); ++j) {
      const double a = prof->z[j], b = prof->z[j + 1], h = prof->x[j + 1] - prof->x[j];
      s += h * (a + b) / 2;
      s2 += h * (a * a + a * b + b * b) / 3;
    }
    EXPECT_NEAR(s / 0.2, 0.0, 1e-12 * 1e-5);
    EXPECT_NEAR(std::sqrt(s2 / 0.2 - (s / 0.2) * (s / 0.2)), 1e-5, 1e-13 * 1e-5);
    EXPECT_NEAR(profile_stats(*prof).rms_height, 1e-5, 1e-13 * 1e-5);
    // Periodic: a cyclic shift by any number of samples has the same heights set, and the
    // spectrum has no leakage above the cutoff (it would have if the ends did not join).
    const auto P = periodogram(*prof);
    for (std::size_t k = 201; k < P.size(); ++k) EXPECT_LT(P[k], 1e-24 * P[1] + 1e-40) << k;
  }
}

TEST(Fourier, HurstExponentIsRecoveredByThePsdDimension) {
  // psd_dimension (an independent estimator: exact PSD of the piecewise-linear profile, log-binned
  // fit) over [2 q_r, q_s / 2]: D = 2 - H. Fixed amplitudes: one realisation; the sinc^4 factor of
  // the linear interpolation (>= 0.975 at q_s / 2 = Nyquist / 8) biases D by < 0.01.
  // Gaussian amplitudes: the mean over 8 seeds.
  for (double H : {0.3, 0.5, 0.8, 1.0}) {
    auto p = params(4096, 1.0, H, 1.0 / 8, 1.0 / 512);
    PsdFitOptions o;
    o.q_min = 2 * 2 * kPi * 8;
    o.q_max = 0.5 * 2 * kPi * 512;
    p.amplitudes = FourierAmplitudes::Fixed;
    auto f = psd_dimension(*fourier_self_affine_profile(p), o);
    ASSERT_TRUE(f.ok()) << f.error().message;
    EXPECT_NEAR(f->dimension, 2 - H, 0.02) << "fixed, H " << H;
    p.amplitudes = FourierAmplitudes::Gaussian;
    double D = 0;
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
      p.seed = seed;
      auto g = psd_dimension(*fourier_self_affine_profile(p), o);
      ASSERT_TRUE(g.ok()) << g.error().message;
      D += g->dimension / 8;
    }
    EXPECT_NEAR(D, 2 - H, 0.05) << "gaussian, H " << H;
  }
}

TEST(Fourier, SeedsAreReproducibleAndDistinct) {
  auto p = params(256, 1e-3, 0.8, 1e-4, 2e-5);
  auto a = fourier_self_affine_profile(p), b = fourier_self_affine_profile(p);
  p.seed = 2;
  auto c = fourier_self_affine_profile(p);
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  EXPECT_EQ(a->z, b->z);
  EXPECT_NE(a->z, c->z);
}

TEST(Fourier, BadParametersAreNamed) {
  auto fails_with = [](FourierSelfAffineParams p, const std::string& words) {
    auto r = fourier_self_affine_profile(p);
    ASSERT_FALSE(r.ok()) << words;
    EXPECT_NE(r.error().message.find(words), std::string::npos) << r.error().message;
  };
  const auto good = params(256, 1e-3, 0.8, 1e-4, 2e-5);
  ASSERT_TRUE(fourier_self_affine_profile(good).ok());
  auto p = good;
  p.points = 4;
  fails_with(p, "points must be in 8..");
  p = good;
  p.length = 0;
  fails_with(p, "length must be a positive length");
  p.length = std::nan("");
  fails_with(p, "length must be a positive length");
  p = good;
  p.hurst = 0;
  fails_with(p, "hurst (Hurst exponent H) must be in (0, 1]");
  p.hurst = 1.5;
  fails_with(p, "hurst (Hurst exponent H) must be in (0, 1]");
  p = good;
  p.rolloff_wavelength = -1;
  fails_with(p, "rolloff_wavelength must be a positive length");
  p = good;
  p.short_cutoff_wavelength = 0;
  fails_with(p, "short_cutoff_wavelength must be a positive length");
  p = good;
  p.short_cutoff_wavelength = 2e-4;  // longer than the rolloff
  fails_with(p, "short_cutoff_wavelength (0.0002 m) must not exceed rolloff_wavelength (0.0001 m)");
  p = good;
  p.rolloff_wavelength = 5e-3;
  p.short_cutoff_wavelength = 2e-3;  // longer than the profile
  fails_with(p, "must not exceed length");
  p = good;
  p.short_cutoff_wavelength = 2 * 1e-3 / 256;  // the Nyquist wavelength itself
  fails_with(p, "must be longer than the Nyquist wavelength");
  p = good;
  p.rms_height = 0;
  fails_with(p, "rms_height must be a positive length");
}

TEST(Fourier, IsTheSurfaceSpecGeneratorFourier) {
  auto s = make_surface_spec("fourier", {{"points", std::int64_t{256}},
                                         {"length", 1e-3},
                                         {"rolloff_wavelength", 1e-4},
                                         {"short_cutoff_wavelength", 2e-5},
                                         {"amplitudes", std::string("fixed")},
                                         {"seed", std::int64_t{3}}});
  ASSERT_TRUE(s.ok()) << s.error().message;
  auto p = params(256, 1e-3, 0.8, 1e-4, 2e-5);
  p.rms_height = 1e-5;  // the default
  p.amplitudes = FourierAmplitudes::Fixed;
  p.seed = 3;
  EXPECT_EQ(generate_profile(*s)->z, fourier_self_affine_profile(p)->z);
  EXPECT_EQ(*surface_period(*s), 0.0);  // no repeat within a tilt block
  EXPECT_DOUBLE_EQ(*surface_scale(*s), 1e-4);
  EXPECT_FALSE(make_surface_spec("fourier", {{"amplitudes", std::string("uniform")}}).ok());
  auto bad = make_surface_spec("fourier", {{"short_cutoff_wavelength", 0.02}});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("rolloff_wavelength"), std::string::npos) << bad.error().message;
}
