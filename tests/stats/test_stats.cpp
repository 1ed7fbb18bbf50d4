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
