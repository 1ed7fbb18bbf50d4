// Detrending, spectra, autocorrelation, areal statistics and map lines. Expected values follow
// from the stated definitions, worked by hand or with independent loops written here.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "frictal/analysis.hpp"
#include "frictal/io.hpp"

namespace {
constexpr double kPi = std::numbers::pi;

frictal::Profile sampled(std::size_t n, double L, double (*f)(double), bool jitter = false) {
  frictal::Profile p;
  for (std::size_t i = 0; i < n; ++i) {
    double x = L * double(i) / double(n - 1);
    if (jitter && i > 0 && i + 1 < n) x += 0.3 * L / double(n - 1) * std::sin(double(i) * 1.7);
    p.x.push_back(x);
    p.z.push_back(f(x));
  }
  return p;
}

// Exact mean-square about the mean of the piecewise-linear profile (trapezoid integrals).
double pl_variance(const frictal::Profile& p) {
  double L = p.x.back() - p.x.front(), m = 0, s = 0;
  for (std::size_t k = 1; k < p.size(); ++k) m += 0.5 * (p.z[k] + p.z[k - 1]) * (p.x[k] - p.x[k - 1]);
  m /= L;
  for (std::size_t k = 1; k < p.size(); ++k) {
    double a = p.z[k - 1] - m, b = p.z[k] - m;
    s += (a * a + a * b + b * b) / 3 * (p.x[k] - p.x[k - 1]);
  }
  return s / L;
}
}  // namespace

TEST(Detrend, Parse) {
  EXPECT_EQ(frictal::parse_detrend("none")->kind, frictal::DetrendKind::None);
  EXPECT_EQ(frictal::parse_detrend("line")->degree, 1);
  EXPECT_EQ(frictal::parse_detrend("poly:3")->degree, 3);
  EXPECT_FALSE(frictal::parse_detrend("poly:x").ok());
  EXPECT_FALSE(frictal::parse_detrend("poly:11").ok());
  EXPECT_FALSE(frictal::parse_detrend("cubic").ok());
}

TEST(Detrend, RemovesPolynomialsExactlyAndIsOrthogonal) {
  // A cubic is removed exactly by poly:3 (to rounding).
  auto cubic = sampled(
      101, 2e-3, [](double x) { return 1e-6 + 3e-3 * x - 2 * x * x + 500 * x * x * x; }, true);
  auto r = frictal::detrend(cubic, {frictal::DetrendKind::Polynomial, 3});
  ASSERT_TRUE(r.ok());
  for (double z : r->z) EXPECT_NEAR(z, 0, 1e-15);
  // Line removal: residual is orthogonal to 1 and x under the trapezoid weights (normal equations).
  auto p = sampled(
      64, 1e-3, [](double x) { return 5e-3 * x + 1e-7 * std::sin(x * 2e4); }, true);
  auto l = frictal::detrend(p, {frictal::DetrendKind::Line, 1});
  ASSERT_TRUE(l.ok());
  double s0 = 0, s1 = 0, scale = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    double w = 0.5 * ((k > 0 ? p.x[k] - p.x[k - 1] : 0) + (k + 1 < p.size() ? p.x[k + 1] - p.x[k] : 0));
    s0 += w * l->z[k];
    s1 += w * l->z[k] * p.x[k];
    scale += w * std::abs(l->z[k]);
  }
  EXPECT_NEAR(s0, 0, 1e-12 * scale);
  EXPECT_NEAR(s1, 0, 1e-12 * scale * 1e-3);
}

TEST(Detrend, MapPlane) {
  frictal::Map m;
  m.nx = 5;
  m.ny = 4;
  m.dx = 1e-6;
  m.dy = 2e-6;
  for (std::size_t j = 0; j < 4; ++j)
    for (std::size_t i = 0; i < 5; ++i) m.heights.push_back(1e-7 + 0.01 * i * 1e-6 - 0.02 * j * 2e-6);
  m.heights[6] = NAN;
  auto r = frictal::detrend(m, {frictal::DetrendKind::Line, 1});
  ASSERT_TRUE(r.ok());
  for (std::size_t k = 0; k < m.size(); ++k) {
    if (k == 6)
      EXPECT_TRUE(std::isnan(r->heights[k]));
    else
      EXPECT_NEAR(r->heights[k], 0, 1e-20);
  }
}

TEST(Spectrum, SinePeakAndParseval) {
  // z = A sin(2 pi 5 x / L): continuous C(q_5) = A^2 L / 4; the polyline with 64 points per
  // period deviates by O((pi/64)^2).
  const double A = 1e-7, L = 1e-3;
  frictal::Profile p;
  for (int i = 0; i <= 320; ++i) {
    p.x.push_back(L * i / 320);
    p.z.push_back(A * std::sin(2 * kPi * 5 * i / 320.0));
  }
  auto s = frictal::power_spectrum(p, 320 * 40);
  ASSERT_TRUE(s.ok());
  EXPECT_NEAR(s->q[4], 2 * kPi * 5 / L, 1e-9);
  EXPECT_NEAR(s->psd[4], A * A * L / 4, 0.005 * A * A * L / 4);
  // Parseval: 2 sum C / L = mean square of the polyline about its mean (tail beyond k = 40 n is
  // below 1e-6 relative for a polyline).
  double sum = 0;
  for (double c : s->psd) sum += c;
  EXPECT_NEAR(2 * sum / L, pl_variance(p), 1e-5 * pl_variance(p));
}

TEST(Spectrum, NonUniformParsevalOnSharedFile) {
  auto p = frictal::read_profile(std::string(FRICTAL_TEST_DATA) + "/profiles/xy-1.txt");
  ASSERT_TRUE(p.ok());
  auto s = frictal::power_spectrum(*p, 20000);
  ASSERT_TRUE(s.ok());
  double sum = 0;
  for (double c : s->psd) sum += c;
  EXPECT_NEAR(2 * sum / p->length(), pl_variance(*p), 1e-4 * pl_variance(*p));
}

TEST(Autocorrelation, SineHalfPeriodIsMinusOne) {
  frictal::Profile p;
  for (int i = 0; i < 4000; ++i) {
    p.x.push_back(i * 1e-6);
    p.z.push_back(std::cos(2 * kPi * i / 100.0));  // period 100 samples
  }
  auto a = frictal::autocorrelation(p, 200);
  ASSERT_TRUE(a.ok());
  EXPECT_DOUBLE_EQ(a->acf[0], 1.0);
  EXPECT_NEAR(a->acf[50], -1.0, 0.02);
  EXPECT_NEAR(a->acf[100], 1.0, 0.03);
  // cos(2 pi t / 100 samples) = 1/e at t = 100 acos(1/e) / (2 pi) samples.
  EXPECT_NEAR(a->correlation_length, 100 * std::acos(std::exp(-1.0)) / (2 * kPi) * 1e-6, 0.3e-6);
}

TEST(MapStats, HandWorkedExampleWithHole) {
  // 3 x 2, dx = 1, dy = 2: {1, 2, 3; 4, NaN, 6}. Valid: 1, 2, 3, 4, 6 -> mean 3.2.
  frictal::Map m;
  m.nx = 3;
  m.ny = 2;
  m.dx = 1;
  m.dy = 2;
  m.heights = {1, 2, 3, 4, NAN, 6};
  auto s = frictal::map_stats(m);
  EXPECT_EQ(s.valid, 5u);
  EXPECT_DOUBLE_EQ(s.mean, 3.2);
  EXPECT_NEAR(s.Sa, 7.2 / 5, 1e-15);              // |d| = 2.2, 1.2, 0.2, 0.8, 2.8
  EXPECT_NEAR(s.Sq, std::sqrt(14.8 / 5), 1e-15);  // d^2 = 4.84, 1.44, 0.04, 0.64, 7.84
  EXPECT_DOUBLE_EQ(s.Sz, 5);
  EXPECT_NEAR(s.Sp, 2.8, 1e-15);
  EXPECT_NEAR(s.Sv, 2.2, 1e-15);
  // x pairs: (1,2), (2,3) -> slopes 1, 1; y pairs: (1,4), (3,6) -> 1.5, 1.5.
  EXPECT_NEAR(s.Sdq, std::sqrt(1 + 2.25), 1e-15);
  EXPECT_NEAR(s.max_slope, std::atan(1.5), 1e-15);
}

TEST(MapStats, SharedX3pMatchesPython) {
  // python3: population rms about the mean of all 422,500 values of data.bin.
  auto m = frictal::read_map(std::string(FRICTAL_TEST_DATA) + "/x3p/x3p-2.x3p");
  ASSERT_TRUE(m.ok());
  auto s = frictal::map_stats(*m);
  EXPECT_NEAR(s.Sq, 7.7280332735977479e-08, 1e-20);
  EXPECT_NEAR(s.mean, -2.4918241693055942e-09, 1e-21);
  EXPECT_NEAR(s.Sz, 2.3991551341223285e-07 + 3.144206865877671e-07, 1e-21);
}

TEST(MapLines, PlaneSlopesAlongDirectionsAndHoles) {
  // z = 2 x + 3 y is reproduced exactly by bilinear interpolation: slope along angle a is
  // 2 cos a + 3 sin a.
  frictal::Map m;
  m.nx = 21;
  m.ny = 11;
  m.dx = 0.5;
  m.dy = 1.0;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) m.heights.push_back(2 * (i * 0.5) + 3 * (j * 1.0));
  for (double a : {0.0, kPi / 2, kPi / 4, 2.0}) {
    auto lines = frictal::map_lines(m, a, 1.0, 0.25, 4);
    ASSERT_FALSE(lines.empty());
    for (const auto& l : lines)
      for (std::size_t k = 1; k < l.size(); ++k)
        EXPECT_NEAR((l.z[k] - l.z[k - 1]) / (l.x[k] - l.x[k - 1]), 2 * std::cos(a) + 3 * std::sin(a), 1e-9);
  }
  // Along x through y = 5: 41 samples over x in [0, 10]; a hole at node (10, 5) splits it.
  auto one = frictal::map_line(m, 0, 5, 0, 0.25, 2);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].size(), 41u);
  m.at(10, 5) = NAN;
  auto two = frictal::map_line(m, 0, 5, 0, 0.25, 2);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0].size() + two[1].size(), 41u - 3u);  // samples x = 4.75, 5, 5.25 weigh node 10
}
