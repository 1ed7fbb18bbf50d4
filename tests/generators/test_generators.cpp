#include <gtest/gtest.h>

#include <cmath>

#include "frictal/generators.hpp"
#include "frictal/stats.hpp"

using namespace frictal;

namespace {
double deg(double d) { return d * M_PI / 180; }
double curve_length(const Curve& c) {
  double s = 0;
  for (std::size_t i = 0; i + 1 < c.size(); ++i) s += std::hypot(c.x[i + 1] - c.x[i], c.z[i + 1] - c.z[i]);
  return s;
}
// rms about the mean of the linear interpolant, by dense trapezoid sampling (second method).
double rms_dense(const Profile& p, int sub) {
  double s = 0, s2 = 0, L = 0;
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const double dx = (p.x[i + 1] - p.x[i]) / sub;
    for (int k = 0; k < sub; ++k) {
      const double za = p.z[i] + (p.z[i + 1] - p.z[i]) * k / sub, zb = p.z[i] + (p.z[i + 1] - p.z[i]) * (k + 1) / sub;
      s += dx * (za + zb) / 2;
      s2 += dx * (za * za + zb * zb) / 2;
      L += dx;
    }
  }
  const double m = s / L;
  return std::sqrt(s2 / L - m * m);
}
}  // namespace

TEST(Koch, PointCountLengthAndSlopes) {
  for (int n = 0; n <= 4; ++n) {
    for (double a : {5.0, 20.0, 35.0}) {
      KochParams p;
      p.iterations = n;
      p.alpha = deg(a);
      p.wavelength = 0.01;
      p.length = 0.2;
      auto c = koch_curve(p);
      ASSERT_TRUE(c.ok());
      EXPECT_EQ(c->size(), static_cast<std::size_t>(2 * std::pow(4, n) * 20 + 1));
      // Each iteration turns a segment of length l into 2 l/3 + 2 (l/3)/(2 cos a).
      const double per = 0.01 / std::cos(deg(a)) * std::pow(2.0 / 3 + 1 / (3 * std::cos(deg(a))), n);
      EXPECT_NEAR(curve_length(*c), 20 * per, 1e-12);
      // Every edge angle is a multiple of alpha, the steepest (n+1) alpha.
      double steepest = 0;
      for (std::size_t i = 0; i + 1 < c->size(); ++i) {
        const double ang = std::atan2(c->z[i + 1] - c->z[i], c->x[i + 1] - c->x[i]);
        const double k = ang / deg(a);
        EXPECT_NEAR(k, std::round(k), 1e-9);
        steepest = std::max(steepest, std::abs(ang));
      }
      EXPECT_NEAR(steepest, (n + 1) * deg(a), 1e-9);
    }
  }
}

TEST(Koch, OutwardBumpsAndFoldingThresholds) {
  KochParams p;
  p.iterations = 1;
  p.alpha = deg(20);
  p.length = 0.01;
  auto c = koch_curve(p);
  ASSERT_TRUE(c.ok());
  // K1 bump on the rising K0 flank points up-left (outward): its apex lies above the flank line.
  const double flank = std::tan(deg(20));
  EXPECT_GT(c->z[2], flank * c->x[2]);
  auto folds = [](int n, double a) {
    KochParams q;
    q.iterations = n;
    q.alpha = deg(a);
    q.length = 0.01;
    auto cc = koch_curve(q);
    for (std::size_t i = 0; i + 1 < cc->size(); ++i)
      if (cc->x[i + 1] < cc->x[i]) return true;
    return false;
  };
  EXPECT_FALSE(folds(1, 44));
  EXPECT_TRUE(folds(1, 46));
  EXPECT_FALSE(folds(2, 29));
  EXPECT_TRUE(folds(2, 31));
  EXPECT_FALSE(folds(3, 22));
  EXPECT_TRUE(folds(3, 23));
}

TEST(Koch, RejectsBadParameters) {
  KochParams p;
  p.alpha = deg(61);
  EXPECT_FALSE(koch_curve(p).ok());
  p.alpha = deg(10);
  p.iterations = -1;
  EXPECT_FALSE(koch_curve(p).ok());
  p.iterations = 11;
  EXPECT_FALSE(koch_curve(p).ok());
  p.iterations = 1;
  p.length = 0.015;  // not whole wavelengths
  auto r = koch_curve(p);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("whole number"), std::string::npos);
}

TEST(WeierstrassMandelbrot, PaperResolutionAndRmsNormalisation) {
  WmParams w;  // D = 1.5, n_max = 10, L = 1 um, L_b = 20 um, rms 1 nm
  auto p = wm_profile(w);
  ASSERT_TRUE(p.ok());
  // Eq. 16: dx = L / gamma^10 / 10 = 1.734e-9 m; 20 um / dx = 11533.0 -> 11534 points.
  EXPECT_EQ(p->size(), 11534u);
  EXPECT_NEAR(p->x[1] - p->x[0], 1e-6 / std::pow(1.5, 10) / 10, 1e-20);
  EXPECT_NEAR(profile_stats(*p).rms_height, 1e-9, 1e-15);
  EXPECT_NEAR(rms_dense(*p, 4), 1e-9, 1e-13);
  // n_max = 0 uses the n_max = 1 spacing.
  WmParams w0 = w;
  w0.n_max = 0;
  WmParams w1 = w;
  w1.n_max = 1;
  EXPECT_EQ(wm_profile(w0)->size(), wm_profile(w1)->size());
}

TEST(WeierstrassMandelbrot, DeterministicFormMatchesEq17TermByTerm) {
  for (auto ex : {WmExponent::Printed, WmExponent::Common}) {
    WmParams w;
    w.dimension = 1.7;
    w.n_max = 3;
    w.stochastic = false;
    w.rms_height = 0;  // G = 1
    w.exponent = ex;
    auto p = wm_profile(w);
    ASSERT_TRUE(p.ok());
    const double k = ex == WmExponent::Printed ? 2 : 1;
    for (std::size_t i = 0; i < p->size(); i += 97) {
      double z = 0;
      for (int n = 0; n <= 3; ++n)
        z += std::pow(1.5, k * (1.7 - 2) * n) * (1 - std::cos(2 * M_PI * std::pow(1.5, n) * p->x[i] / 1e-6));
      EXPECT_NEAR(p->z[i], z, 1e-12);
    }
  }
}

TEST(WeierstrassMandelbrot, SeedsReproduceAndDiffer) {
  WmParams w;
  w.n_max = 5;
  auto a = wm_profile(w), b = wm_profile(w);
  w.seed = 2;
  auto c = wm_profile(w);
  EXPECT_EQ(a->z, b->z);
  EXPECT_NE(a->z, c->z);
  WmParams bad;
  bad.dimension = 2.5;
  EXPECT_FALSE(wm_profile(bad).ok());
  bad = WmParams{};
  bad.gamma = 1.0;
  EXPECT_FALSE(wm_profile(bad).ok());
  bad = WmParams{};
  bad.spacing = 1e-20;  // 2e15 points
  EXPECT_FALSE(wm_profile(bad).ok());
}

TEST(Sawtooth, FlankSlopes) {
  SawtoothParams s;
  s.rise_angle = deg(30);
  s.rise_fraction = 0.75;
  auto p = sawtooth_profile(s);
  ASSERT_TRUE(p.ok());
  // Fall: height 0.75 lambda tan 30 over 0.25 lambda, steeper than the rise.
  const double fall = std::atan(3 * std::tan(deg(30)));
  EXPECT_NEAR(profile_stats(*p).max_slope, fall, 1e-12);
  EXPECT_NEAR(std::atan2(p->z[1] - p->z[0], p->x[1] - p->x[0]), deg(30), 1e-12);
  EXPECT_NEAR(std::atan2(p->z[2] - p->z[1], p->x[2] - p->x[1]), -fall, 1e-12);
}

TEST(SelfAffine, RmsAndSeed) {
  SelfAffineParams s;
  s.points = 5000;
  auto a = self_affine_profile(s);
  ASSERT_TRUE(a.ok());
  EXPECT_NEAR(rms_dense(*a, 3), 1e-6, 1e-12);
  EXPECT_EQ(a->size(), 5000u);
}

TEST(WeierstrassMandelbrot, SpectrumFollowsTheExponent) {
  // gamma = 2 and L_b = L make every mode an exact harmonic of the record: the Fourier
  // coefficient at harmonic 2^n has magnitude amp_n / 2 with amp_n = gamma^{k (D - 2) n}.
  for (auto ex : {WmExponent::Printed, WmExponent::Common}) {
    WmParams w;
    w.dimension = 1.3;
    w.gamma = 2;
    w.n_max = 4;
    w.longest_wavelength = 1e-6;
    w.length = 1e-6;
    w.rms_height = 0;
    w.seed = 11;
    w.exponent = ex;
    auto p = wm_profile(w);
    ASSERT_TRUE(p.ok());
    const std::size_t N = p->size() - 1;  // drop the closing point: one exact period
    auto coef = [&](int h) {
      double re = 0, im = 0;
      for (std::size_t i = 0; i < N; ++i) {
        re += p->z[i] * std::cos(2 * M_PI * h * static_cast<double>(i) / N);
        im += p->z[i] * std::sin(2 * M_PI * h * static_cast<double>(i) / N);
      }
      return std::hypot(re, im) / N;
    };
    const double k = ex == WmExponent::Printed ? 2 : 1;
    for (int n = 0; n <= 4; ++n) EXPECT_NEAR(coef(1 << n), 0.5 * std::pow(2.0, k * (1.3 - 2) * n), 1e-9) << n;
    EXPECT_NEAR(coef(3), 0, 1e-9);  // nothing between the modes
  }
}
