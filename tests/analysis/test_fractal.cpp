// Fractal dimension: Eq. 13 solved exactly, divider and box counting on Koch curves (walking
// the folded Curve), PSD slope on Weierstrass-Mandelbrot and self-affine profiles.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "frictal/fractal.hpp"
#include "frictal/generators.hpp"

namespace {
constexpr double kPi = std::numbers::pi;
double deg(double d) { return d * kPi / 180; }

frictal::Curve koch(int n, double alpha_deg) {
  frictal::KochParams p;
  p.iterations = n;
  p.alpha = deg(alpha_deg);
  p.wavelength = 1.0;
  p.length = 2.0;
  auto c = frictal::koch_curve(p);
  EXPECT_TRUE(c.ok()) << c.error().message;
  return *c;
}
}  // namespace

TEST(KochDimension, Eq13ExactValues) {
  // alpha = 60 deg: all four pieces are 1/3 of the parent, so D = log 4 / log 3.
  EXPECT_NEAR(*frictal::koch_dimension(deg(60)), std::log(4.0) / std::log(3.0), 1e-14);
  // alpha = 0: pieces 1/3, 1/3, 1/6, 1/6 lie on a line: 2/3 + 1/3 = 1 at D = 1.
  EXPECT_NEAR(*frictal::koch_dimension(0), 1.0, 1e-14);
  // Residual of Eq. 13 at the returned D, and monotonic in alpha.
  double prev = 1;
  for (double a = 5; a <= 60; a += 5) {
    double D = *frictal::koch_dimension(deg(a));
    EXPECT_NEAR(2 * std::pow(1.0 / 3, D) + 2 * std::pow(1 / (6 * std::cos(deg(a))), D), 1.0, 1e-14);
    EXPECT_GT(D, prev);
    prev = D;
  }
  EXPECT_FALSE(frictal::koch_dimension(deg(61)).ok());
}

TEST(Divider, StraightLineHasDimensionOne) {
  frictal::Curve c{{0, 0.3, 1.0, 2.0}, {0, 0.3, 1.0, 2.0}};
  // L(eps) = steps * eps + remainder = the exact length for any ruler.
  for (double e : {0.01, 0.1, 0.37}) EXPECT_NEAR(frictal::divider_length(c, e), 2 * std::sqrt(2.0), 1e-12);
  auto f = frictal::divider_dimension(c, {0.01, 0.5, 8});
  ASSERT_TRUE(f.ok());
  EXPECT_NEAR(f->dimension, 1.0, 1e-12);
}

TEST(Divider, KochCurvesMatchEq13) {
  // K5 curves over 16 rulers in [3e-3, 0.3] wavelengths (the paper's Fig. 9 regime, between
  // the finest segments and the generator). Folded curves (alpha > 22.5 deg for K3 and up) are
  // walked along the curve. Measured: 1.0417 / 1.1168 / 1.2600 against Eq. 13's 1.0387 /
  // 1.1042 / 1.2619; the method's accuracy here is 0.015 in D (log-periodic ripple of L).
  for (double a : {30.0, 45.0, 60.0}) {
    auto c = koch(5, a);
    auto f = frictal::divider_dimension(c, {3e-3, 0.3, 16});
    ASSERT_TRUE(f.ok()) << f.error().message;
    double D = *frictal::koch_dimension(deg(a));
    EXPECT_NEAR(f->dimension, D, 0.015) << "alpha " << a;
    RecordProperty("divider_D_alpha_" + std::to_string(int(a)), std::to_string(f->dimension));
    // r^2 only means something when L(eps) varies: D close to 1 leaves mostly ripple.
    if (a == 60.0) {
      EXPECT_GT(f->r_squared, 0.94);
    }
    EXPECT_DOUBLE_EQ(f->scale_min, 3e-3);
    EXPECT_DOUBLE_EQ(f->scale_max, 0.3);
  }
  // Same scaling whatever the number of iterations, over the range that K_n resolves (Fig. 9).
  auto f3 = frictal::divider_dimension(koch(3, 60), {3e-2, 0.2, 8});
  ASSERT_TRUE(f3.ok());
  EXPECT_NEAR(f3->dimension, std::log(4.0) / std::log(3.0), 0.04);
}

TEST(BoxCounting, KochAndLine) {
  frictal::Curve line{{0, 1}, {0, 1}};
  auto l = frictal::box_dimension(line, {1e-3, 0.1, 8});
  ASSERT_TRUE(l.ok());
  EXPECT_NEAR(l->dimension, 1.0, 0.02);
  auto f = frictal::box_dimension(koch(5, 60), {3e-3, 0.1, 10});
  ASSERT_TRUE(f.ok()) << f.error().message;
  EXPECT_NEAR(f->dimension, std::log(4.0) / std::log(3.0), 0.05);
}

TEST(PsdDimension, SpectralSynthesisRecoversHurst) {
  // Built here: z = sum_k q_k^{-(1+2H)/2} cos(q_k x + phase_k), q_k = 2 pi k / L, so
  // C(q) ~ q^-(1+2H) exactly and D = 2 - H.
  for (double H : {0.3, 0.5, 0.8}) {
    const int n = 4096;
    const double L = 1e-3;
    std::mt19937 g(1);
    std::uniform_real_distribution<double> U(0, 2 * kPi);
    frictal::Profile p;
    p.x.resize(n);
    p.z.assign(n, 0);
    for (int i = 0; i < n; ++i) p.x[i] = L * i / (n - 1);
    for (int k = 1; k < n / 2; ++k) {
      const double q = 2 * kPi * k / L, a = std::pow(q, -(1 + 2 * H) / 2), ph = U(g);
      for (int i = 0; i < n; ++i) p.z[i] += a * std::cos(q * p.x[i] + ph);
    }
    auto f = frictal::psd_dimension(p);
    ASSERT_TRUE(f.ok()) << f.error().message;
    EXPECT_NEAR(f->dimension, 2 - H, 0.02) << "H " << H;
    EXPECT_GT(f->r_squared, 0.99);
  }
}

TEST(PsdDimension, MidpointDisplacementProfileIsNearHurst) {
  // frictal::self_affine_profile (random midpoint displacement, resampled): that method is
  // known to bias the spectrum slightly; accept 0.12.
  for (double H : {0.3, 0.5, 0.8}) {
    frictal::SelfAffineParams p;
    p.points = 8192;
    p.hurst = H;
    p.seed = 7;
    auto prof = frictal::self_affine_profile(p);
    ASSERT_TRUE(prof.ok()) << prof.error().message;
    auto f = frictal::psd_dimension(*prof);
    ASSERT_TRUE(f.ok()) << f.error().message;
    EXPECT_NEAR(f->dimension, 2 - H, 0.12) << "H " << H;
  }
}

TEST(PsdDimension, WeierstrassMandelbrotRisesWithD) {
  // WM amplitudes ~ gamma^{k (D-2) n} at wavelength L gamma^-n give C(q) ~ q^-(1 + 2 k (2 - D)),
  // i.e. a profile dimension D_eff = 2 - k (2 - D): D with the common exponent (k = 1), 2 D - 2
  // with the paper's printed one (k = 2; smooth, D_eff <= 1, below the D = 1.5 threshold).
  // Fit over the WM band [L_s, L] (n_max = 16, gamma = 1.5); measured within 0.02 of D_eff.
  for (auto ex : {frictal::WmExponent::Common, frictal::WmExponent::Printed}) {
    const double k = ex == frictal::WmExponent::Common ? 1 : 2;
    double prev = 0, prev_divider = 0;
    for (double D : {1.2, 1.4, 1.6, 1.8}) {
      frictal::WmParams p;
      p.dimension = D;
      p.n_max = 16;
      p.exponent = ex;
      p.seed = 3;
      auto prof = frictal::wm_profile(p);
      ASSERT_TRUE(prof.ok()) << prof.error().message;
      frictal::PsdFitOptions o;
      o.q_min = 2 * kPi / p.longest_wavelength;
      o.q_max = 2 * kPi / (p.longest_wavelength / std::pow(p.gamma, p.n_max));
      o.bins_per_decade = 5;
      auto f = frictal::psd_dimension(*prof, o);
      ASSERT_TRUE(f.ok()) << f.error().message;
      EXPECT_GT(f->dimension, prev + 0.1) << "D " << D;
      EXPECT_NEAR(f->dimension, 2 - k * (2 - D), 0.03) << "D " << D << " k " << k;
      prev = f->dimension;
      // The divider sees these nearly flat profiles (rms height 0.1 % of L) as almost smooth,
      // but its dimension still does not decrease with D.
      auto dv = frictal::divider_dimension(frictal::as_curve(*prof));
      ASSERT_TRUE(dv.ok());
      EXPECT_GE(dv->dimension, prev_divider - 1e-4) << "D " << D;
      prev_divider = dv->dimension;
    }
  }
}
