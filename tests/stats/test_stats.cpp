#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "frictal/analysis.hpp"
#include "frictal/generators.hpp"
#include "frictal/io.hpp"
#include "frictal/scan_stats.hpp"
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

// max_slope_angle (the signature summary's surface_slope_max_deg) by hand, and bit for bit
// against profile_stats().max_slope (two atans a point there, one in all here) on rough profiles.
TEST(Stats, MaxSlopeAngleByHandAndAsProfileStats) {
  EXPECT_EQ(max_slope_angle(Profile{{0, 1, 2, 3}, {0, 1, 1, -2}, std::nullopt}), std::atan(3.0));  // slopes 1, 0, -3
  EXPECT_EQ(max_slope_angle(Profile{{0, 1, 1, 2}, {0, 0, 1, 1}, std::nullopt}), M_PI / 2);         // a jump
  EXPECT_EQ(max_slope_angle(Profile{{0, 1, 1, 2}, {0, 0, 0, 0}, std::nullopt}), 0.0);  // a repeated flat point
  EXPECT_EQ(max_slope_angle(Profile{{0}, {1}, std::nullopt}), 0.0);
  for (double h : {0.3, 0.8}) {
    SelfAffineParams sp;
    sp.hurst = h;
    sp.points = 4097;
    sp.seed = 7;
    const auto p = self_affine_profile(sp);
    ASSERT_TRUE(p) << p.error().message;
    EXPECT_EQ(max_slope_angle(*p), profile_stats(*p).max_slope) << "H = " << h;
    // The checks' statistics without the angles: the same sums, bit for bit.
    const ProfileStats a = profile_stats(*p), b = profile_stats_no_angles(*p);
    EXPECT_EQ(b.points, a.points);
    EXPECT_EQ(b.length, a.length);
    EXPECT_EQ(b.mean_height, a.mean_height);
    EXPECT_EQ(b.rms_height, a.rms_height);
    EXPECT_EQ(b.rms_slope, a.rms_slope);
  }
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

// Areal statistics at the edges of double. The checkerboard z = +-A on a 3 x 2 grid of unit
// spacing, rows (A, -A, A) and (-A, A, -A): mean 0, |z - m| = A everywhere so Sa = Sq = A,
// Sz = 2A, Ssk = 0, Sku = 1; every neighbour difference is 2A, so <gx^2> = <gy^2> = 4A^2 and
// Sdq = 2 sqrt(2) A. Along x each row has mean +-A/3 and deviations (2, -4, 2) A/3: Rq_x =
// sqrt(24/27) A; each column (A, -A) has mean 0: Rq_y = A; Rdq_x = Rdq_y = 2A; at each node
// gx^2 + gy^2 = 8A^2: rms gradient 2 sqrt(2) A.
TEST(StatsEdges, MapHeightsNearBothEndsOfDoubleGiveExactArealStatistics) {
  for (double A : {1e300, 1e-300, 1e-160, 1e160, 1.0}) {
    Map m;
    m.nx = 3;
    m.ny = 2;
    m.heights = {A, -A, A, -A, A, -A};
    const MapStats s = map_stats(m);
    EXPECT_NEAR(s.Sq / A, 1.0, 1e-12) << A;
    EXPECT_NEAR(s.Sa / A, 1.0, 1e-12) << A;
    EXPECT_NEAR(s.Sz / (2 * A), 1.0, 1e-12) << A;
    EXPECT_NEAR(s.Ssk, 0.0, 1e-12) << A;
    EXPECT_NEAR(s.Sku, 1.0, 1e-12) << A;
    EXPECT_NEAR(s.Sdq / (2 * std::sqrt(2.0) * A), 1.0, 1e-12) << A;
    EXPECT_NEAR(s.max_slope, std::atan(2 * A), 1e-12) << A;
    const MapScanStats sc = map_scan_stats(m);
    EXPECT_NEAR(sc.Rq_x / (std::sqrt(24.0 / 27.0) * A), 1.0, 1e-12) << A;
    EXPECT_NEAR(sc.Rq_y / A, 1.0, 1e-12) << A;
    EXPECT_NEAR(sc.Rdq_x / (2 * A), 1.0, 1e-12) << A;
    EXPECT_NEAR(sc.Rdq_y / (2 * A), 1.0, 1e-12) << A;
    EXPECT_NEAR(sc.rms_gradient_fd / (2 * std::sqrt(2.0) * A), 1.0, 1e-12) << A;
    EXPECT_DOUBLE_EQ(sc.physical_size_x, 3.0);
  }
  // 1e308: Sq = 1e308 is representable, Sz = 2e308 is not (+inf), never a wrong finite number.
  Map top;
  top.nx = 3;
  top.ny = 2;
  top.heights = {1e308, -1e308, 1e308, -1e308, 1e308, -1e308};
  const MapStats t = map_stats(top);
  EXPECT_NEAR(t.Sq / 1e308, 1.0, 1e-12);
  EXPECT_TRUE(std::isinf(t.Sz) && t.Sz > 0);
  EXPECT_NEAR(t.Sku, 1.0, 1e-12);
}

// Spacings near the edges: the same checkerboard with A = 1 on spacings of 1e300 m has slopes
// of 2e-300 (their squares, 4e-600, underflowed to 0 before); on spacings of 1e-300 m slopes
// of 2e300 (squares overflowed). Physical sizes n dx = 3e300; bandwidth (dx + dy) / 2 = 1e300.
TEST(StatsEdges, MapSpacingsNearBothEndsOfDoubleGiveExactSlopes) {
  for (double h : {1e300, 1e-300}) {
    Map m;
    m.nx = 3;
    m.ny = 2;
    m.dx = m.dy = h;
    m.heights = {1, -1, 1, -1, 1, -1};
    const MapStats s = map_stats(m);
    EXPECT_NEAR(s.Sq, 1.0, 1e-12) << h;
    EXPECT_NEAR(s.Sdq / (2 * std::sqrt(2.0) / h), 1.0, 1e-12) << h;
    EXPECT_NEAR(s.width / (2 * h), 1.0, 1e-12) << h;
    const MapScanStats sc = map_scan_stats(m);
    EXPECT_NEAR(sc.Rdq_x / (2 / h), 1.0, 1e-12) << h;
    EXPECT_NEAR(sc.physical_size_x / (3 * h), 1.0, 1e-12) << h;
    EXPECT_NEAR(sc.bandwidth_short / h, 1.0, 1e-12) << h;
  }
  // dx = 1.5e308: (dx + dy) / 2 is representable although dx + dy is not.
  Map wide;
  wide.nx = wide.ny = 2;
  wide.dx = wide.dy = 1.5e308;
  wide.heights = {0, 1, 2, 3};
  EXPECT_NEAR(map_scan_stats(wide).bandwidth_short / 1.5e308, 1.0, 1e-15);
}

// Spacings and lengths below the smallest normal double have lost precision: an error that says
// so, never a size such as 1.99998e-320 m for 2e-320 m.
TEST(StatsEdges, SubnormalSpacingsAndLengthsAreErrors) {
  auto r = read_surface_bytes("# Width: 3e-320 m\n# Height: 2e-320 m\n# Value units: m\n1 2 3\n4 5 6\n", "tiny.txt");
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("tiny.txt: grid spacing"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("below the smallest normal double"), std::string::npos) << r.error().message;
  Map m;
  m.nx = m.ny = 2;
  m.dx = 1e-310;
  m.heights = {0, 1, 2, 3};
  EXPECT_FALSE(validate(m, "m").ok());
  m.dx = std::numeric_limits<double>::min();  // the smallest normal spacing is fine
  EXPECT_TRUE(validate(m, "m").ok());
  Profile p{{0, 1e-310, 2e-310}, {0, 1, 0}, std::nullopt};
  auto st = validate(p, "under.csv");
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().message.find("below the smallest normal double"), std::string::npos) << st.error().message;
  // A profile over [0, 1.7e308]: length representable, slopes 1e-308 and -1/0.7e308: the
  // length-weighted rms slope is sqrt((1e308 (1e-308)^2 + 0.7e308 (1/0.7e308)^2) / 1.7e308).
  Profile wide{{0, 1e308, 1.7e308}, {0, 1, 0}, std::nullopt};
  ASSERT_TRUE(validate(wide, "wide").ok());
  auto w = profile_stats(wide);
  const double expect = std::sqrt(1e-308 + 1 / 0.7e308) / std::sqrt(1.7e308);  // (no underflow on the way)
  EXPECT_NEAR(w.rms_slope / expect, 1.0, 1e-6);  // slopes near 1e-308 are subnormal: ~1e-8 relative
  EXPECT_NEAR(w.length / 1.7e308, 1.0, 1e-15);
}
