// The 3D tilt test on MuJoCo (frictal/areal_tilt.hpp): grooves across the sliding direction, the
// upper face a window of the same grooves in place, hold at the slope of the grooves' steepest
// segment (the rigid prediction: the lift's forward slope at the cusp, A sin(2 pi / m) / dx,
// tests/analysis/test_areal_hold.cpp). Without MuJoCo in the build: NotAvailable.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "frictal/areal.hpp"
#include "frictal/areal_tilt.hpp"

TEST(ArealTilt, GroovesAcrossHoldAtTheirSteepestSegment) {
  constexpr double kPi = std::numbers::pi;
  const std::size_t n = 20;
  const int m = 8;
  const double a = 1e-3 / double(n - 1), A = 2.4e-5;
  frictal::Map f;
  f.nx = f.ny = n;
  f.dx = f.dy = a;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) f.heights.push_back(A * std::sin(2 * kPi * double(i) / m));
  frictal::Map g;
  g.nx = g.ny = 6;
  g.dx = g.dy = a;
  g.x0 = g.y0 = 7 * a;
  for (std::size_t j = 0; j < 6; ++j)
    for (std::size_t i = 0; i < 6; ++i) g.heights.push_back(f.at(i + 7, j + 7));
  frictal::ArealTiltOptions o;
  o.turn_over_upper = false;
  auto r = frictal::areal_tilt(f, g, o);
  if (!frictal::mujoco_available()) {
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().code, frictal::ErrorCode::NotAvailable);
    EXPECT_NE(r.error().message.find("libmujoco-dev"), std::string::npos);
    return;
  }
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_TRUE(r->ran_away);
  EXPECT_EQ(r->spheres, 36u);
  const double predicted = std::atan(A * std::sin(2 * kPi / m) / a);  // 17.871 deg
  // The run-away is read at the first 0.1 deg increment past the hold (measured: 17.9 deg).
  EXPECT_GE(r->friction_angle, predicted - 0.1 * kPi / 180);
  EXPECT_LE(r->friction_angle, predicted + 0.25 * kPi / 180);
  EXPECT_NEAR(r->rest_offset[0], 0, 0.05 * a);
  // Bad input names the value.
  o.atomic_friction = -1;
  auto bad = frictal::areal_tilt(f, g, o);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("atomic friction -1"), std::string::npos) << bad.error().message;
}
