#include <gtest/gtest.h>

#include <cmath>

#include "frictal/generators.hpp"
#include "frictal/stats.hpp"

using namespace frictal;

TEST(Stats, TriangleWaveByHand) {
  // Symmetric triangle of slope 1 over [0, 2]: z = x then 2 - x. Mean 1/2, rms about mean:
  // (1/2) int_0^2 (z - 1/2)^2 dx = 1/12 -> rms = 0.288675...; rms slope 1; max slope 45 deg.
  Profile p{{0, 1, 2}, {0, 1, 0}, std::nullopt};
  auto s = profile_stats(p);
  EXPECT_NEAR(s.mean_height, 0.5, 1e-15);
  EXPECT_NEAR(s.rms_height, std::sqrt(1.0 / 12), 1e-15);
  EXPECT_NEAR(s.rms_slope, 1.0, 1e-15);
  EXPECT_NEAR(s.max_slope, M_PI / 4, 1e-15);
  EXPECT_NEAR(s.mean_slope, 0, 1e-15);
}

TEST(Stats, SineRmsIsAOverSqrt2) {
  SineParams sp;
  sp.amplitude = 2e-3;
  sp.points_per_wavelength = 2000;
  auto p = sine_profile(sp);
  auto s = profile_stats(*p);
  EXPECT_NEAR(s.rms_height, 2e-3 / std::sqrt(2), 1e-8);
  const double k = 2 * M_PI / 0.01;
  EXPECT_NEAR(s.rms_slope, 2e-3 * k / std::sqrt(2), 1e-4);
  EXPECT_NEAR(s.max_slope, std::atan(2e-3 * k), 1e-5);
}

TEST(Stats, JumpCountsAsVerticalAndHistogramIsADensity) {
  Profile p{{0, 1, 1, 2}, {0, 0, 1, 1}, std::nullopt};
  auto s = profile_stats(p);
  EXPECT_NEAR(s.max_slope, M_PI / 2, 1e-15);
  EXPECT_NEAR(s.mean_height, 0.5, 1e-15);
  auto h = histogram({0.1, 0.2, 0.2, 0.9}, {}, 4, 0, 1);
  double total = 0;
  for (std::size_t i = 0; i < h.density.size(); ++i) total += h.density[i] * (h.edges[i + 1] - h.edges[i]);
  EXPECT_NEAR(total, 1.0, 1e-12);
  EXPECT_NEAR(h.density[0], 3 / 4.0 / 0.25, 1e-12);
  auto ms = weighted_mean_std({1, 3}, {1, 3});
  EXPECT_NEAR(ms.mean, 2.5, 1e-15);
  EXPECT_NEAR(ms.std, std::sqrt(0.75), 1e-15);
}

// Numbers at the edges of double. For z = (A, -A, A) over x = (0, h, 2h) the mean is 0 and each
// edge contributes (1/3)(A^2 - A^2 + A^2) h, so rms = A / sqrt(3); the slope is 2A/h on each edge.
TEST(StatsEdges, HeightsNearTheTopOfDoubleGiveTheExactRmsNotZero) {
  const double A = 1e308;
  Profile p{{0, 10, 20}, {A, -A, A}, std::nullopt};
  auto s = profile_stats(p);
  EXPECT_NEAR(s.rms_height / (A / std::sqrt(3.0)), 1.0, 1e-12);
  EXPECT_NEAR(s.rms_slope / (A / 5), 1.0, 1e-12);  // 2A/10 = 2e307, representable
  EXPECT_NEAR(s.mean_height / A, 0.0, 1e-12);      // int z = (A - A)/2 h + (-A + A)/2 h = 0
  // Slopes of 2e308 are beyond double: +inf, never a wrong finite number or 0.
  Profile steep{{0, 1, 2}, {A, -A, A}, std::nullopt};
  auto t = profile_stats(steep);
  EXPECT_NEAR(t.rms_height / (A / std::sqrt(3.0)), 1.0, 1e-12);
  EXPECT_TRUE(std::isinf(t.rms_slope) && t.rms_slope > 0);
}

TEST(StatsEdges, HeightsNearTheBottomOfDoubleDoNotUnderflowToZero) {
  const double A = 1e-300;
  Profile p{{0, 1, 2}, {A, -A, A}, std::nullopt};
  auto s = profile_stats(p);
  EXPECT_NEAR(s.rms_height / (A / std::sqrt(3.0)), 1.0, 1e-12);
  EXPECT_NEAR(s.rms_slope / (2 * A), 1.0, 1e-12);
  // Mixed magnitudes: one 1e300 spike over a 1e-300 ripple; rms of (0, S, 0) on unit edges is
  // sqrt((S^2/3 + S^2/3)/2 - (S/2)^2) = S sqrt(1/12).
  const double S = 1e300;
  Profile mixed{{0, 1, 2}, {A, S, -A}, std::nullopt};
  EXPECT_NEAR(profile_stats(mixed).rms_height / (S * std::sqrt(1.0 / 12)), 1.0, 1e-12);
}

TEST(StatsEdges, ConstantAndTwoPointProfiles) {
  Profile flat{{0, 1, 2}, {3, 3, 3}, std::nullopt};
  auto f = profile_stats(flat);
  EXPECT_EQ(f.rms_height, 0.0);
  EXPECT_EQ(f.rms_slope, 0.0);
  EXPECT_EQ(f.mean_height, 3.0);
  Profile two{{0, 2}, {0, 1}, std::nullopt};  // one edge of slope 1/2: rms about mean 0.5 is 1/sqrt(12)
  auto t = profile_stats(two);
  EXPECT_NEAR(t.rms_height, 1 / std::sqrt(12.0), 1e-15);
  EXPECT_NEAR(t.rms_slope, 0.5, 1e-15);
  EXPECT_NEAR(t.max_slope, std::atan(0.5), 1e-15);
}

TEST(StatsEdges, ALengthBeyondDoubleIsAnErrorNamingTheProfile) {
  Profile p{{-1e308, 1e308}, {0, 1}, std::nullopt};
  auto st = validate(p, "wide.csv");
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().message.find("wide.csv"), std::string::npos);
  EXPECT_NE(st.error().message.find("beyond the range of double"), std::string::npos);
  Profile one_x{{1, 1}, {0, 1}, std::nullopt};  // a profile of one repeated x
  auto st2 = validate(one_x, "same-x.csv");
  ASSERT_FALSE(st2.ok());
  EXPECT_NE(st2.error().message.find("zero length"), std::string::npos);
}
