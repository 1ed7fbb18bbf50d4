// Tilting-block test: hand-derived friction angles (flat blocks slide at atan(mu_a); a K_0 pair
// at alpha with mu_a = 0 slides at alpha, Eq. 6 with theta_max = alpha), output files, CLI.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "frictal/generators.hpp"
#include "frictal/tilt.hpp"

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

frictal::Curve flat(double length) {
  frictal::Curve c;
  c.x = {0.0, length};
  c.z = {0.0, 0.0};
  return c;
}

frictal::Curve koch(int n, double alpha_deg, double length) {
  frictal::KochParams p;
  p.iterations = n;
  p.alpha = alpha_deg * kDeg;
  p.wavelength = 0.01;
  p.length = length;
  auto c = frictal::koch_curve(p);
  EXPECT_TRUE(c.ok());
  return *c;
}

}  // namespace

TEST(DemTilt, FlatBlocksSlideAtAtomicFrictionAngle) {
  // A flat block on a flat block slides when tan(tilt) = mu_a (Eq. 6 with theta = 0). The upper
  // block is shifted by 1 cm so that no corner sits on a corner (coincident corners make
  // vertex-vertex pairs with ill-defined normals, which slip early: docs/dem.md).
  for (double mu : {0.3, 0.6}) {
    frictal::TiltConfig cfg;
    cfg.contact.atomic_friction = mu;
    cfg.predict = false;
    cfg.initial_offset = 0.01;
    cfg.series_interval = 0;
    auto r = frictal::run_tilt(flat(0.2), flat(0.2), cfg);
    ASSERT_TRUE(r.ok()) << r.error().message;
    ASSERT_TRUE(r->slid);
    EXPECT_NEAR(r->friction_angle / kDeg, std::atan(mu) / kDeg, 0.1) << "mu_a = " << mu;
  }
}

TEST(DemTilt, FlatFrictionAngleConvergesAsDtHalves) {
  double prev = 0;
  for (double dt : {4e-5, 2e-5, 1e-5}) {
    frictal::TiltConfig cfg;
    cfg.contact.atomic_friction = 0.4;
    cfg.predict = false;
    cfg.initial_offset = 0.01;
    cfg.series_interval = 0;
    cfg.time_step = dt;
    auto r = frictal::run_tilt(flat(0.1), flat(0.1), cfg);
    ASSERT_TRUE(r.ok()) << r.error().message;
    ASSERT_TRUE(r->slid);
    const double phi = r->friction_angle / kDeg;
    EXPECT_NEAR(phi, std::atan(0.4) / kDeg, 0.1) << "dt = " << dt;
    if (prev != 0) {
      EXPECT_NEAR(phi, prev, 0.05) << "dt = " << dt;
    }
    prev = phi;
  }
}

TEST(DemTilt, KochK0SlidesAtAlphaBothWays) {
  // K_0 at alpha = 20 deg, mu_a = 0: the upper block rests on flanks of slope alpha and slides
  // when the tilt reaches alpha (theta_max = alpha), in either direction by symmetry.
  const frictal::Curve k0 = koch(0, 20, 0.05);
  for (bool reverse : {false, true}) {
    frictal::TiltConfig cfg;
    cfg.reverse = reverse;
    cfg.series_interval = 0;
    auto r = frictal::run_tilt(k0, k0, cfg);
    ASSERT_TRUE(r.ok()) << r.error().message;
    ASSERT_TRUE(r->slid);
    EXPECT_NEAR(r->predicted_friction_angle / kDeg, 20.0, 1e-6);
    EXPECT_NEAR(r->friction_angle / kDeg, 20.0, 1.0) << (reverse ? "reverse" : "forward");
  }
}

TEST(DemTilt, AdaptiveStepGivesTheFixedStepAngles) {
  // The default (adaptive step up to 1e-4 s, implicit normal dashpots) against the fixed explicit
  // 1e-5 s step, on K_0 at 20 deg with mu_a = 0 and 0.3: the same friction angle within 0.01 deg
  // (docs/dem.md sec. 3 reports the Fig. 6 grid), in several times fewer steps.
  const frictal::Curve k0 = koch(0, 20, 0.05);
  for (double mu : {0.0, 0.3}) {
    frictal::TiltConfig cfg;
    cfg.contact.atomic_friction = mu;
    cfg.series_interval = 0;
    auto adaptive = frictal::run_tilt(k0, k0, cfg);
    cfg.adaptive_time_step = false;
    cfg.implicit_damping = false;
    cfg.time_step = 1e-5;
    auto fixed = frictal::run_tilt(k0, k0, cfg);
    ASSERT_TRUE(adaptive.ok()) << adaptive.error().message;
    ASSERT_TRUE(fixed.ok()) << fixed.error().message;
    ASSERT_TRUE(adaptive->slid && fixed->slid);
    EXPECT_NEAR(adaptive->friction_angle / kDeg, fixed->friction_angle / kDeg, 0.01) << "mu_a = " << mu;
    EXPECT_NEAR(fixed->friction_angle / kDeg, 20.0 + std::atan(mu) / kDeg, 0.1);
    EXPECT_LT(adaptive->steps * 3, fixed->steps);
    EXPECT_EQ(fixed->min_time_step, 1e-5);
    EXPECT_EQ(fixed->max_time_step, 1e-5);
    EXPECT_LE(adaptive->max_time_step, 1e-4);
  }
}

TEST(DemTilt, KochK0WithAtomicFrictionAddsThetaA) {
  // Eq. 6: phi = alpha + atan(mu_a).
  const frictal::Curve k0 = koch(0, 15, 0.05);
  frictal::TiltConfig cfg;
  cfg.contact.atomic_friction = 0.3;
  cfg.series_interval = 0;
  auto r = frictal::run_tilt(k0, k0, cfg);
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_TRUE(r->slid);
  EXPECT_NEAR(r->friction_angle / kDeg, 15.0 + std::atan(0.3) / kDeg, 1.0);
}

TEST(DemTilt, WritesSeriesAndFrames) {
  frictal::TiltConfig cfg;
  cfg.contact.atomic_friction = 0.2;
  cfg.predict = false;
  cfg.initial_offset = 0;
  cfg.series_interval = 0.01;
  cfg.frame_interval = 0.5;
  auto r = frictal::run_tilt(flat(0.05), flat(0.05), cfg);
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_GT(r->series.time.size(), 100u);
  // At rest before sliding the contact force balances the weight: atan(F_t / F_n) = tilt.
  const std::size_t i = r->series.time.size() / 2;
  EXPECT_NEAR(r->series.force_angle[i], r->series.tilt[i], 1e-3);
  EXPECT_NEAR(std::hypot(r->series.normal_force[i], r->series.tangential_force[i]), r->upper_mass * 9.81,
              1e-3 * r->upper_mass * 9.81);
  const std::string csv = ::testing::TempDir() + "dem_series.csv";
  const std::string frames = ::testing::TempDir() + "dem_frames.txt";
  ASSERT_TRUE(frictal::write_tilt_series_csv(csv, r->series).ok());
  ASSERT_TRUE(frictal::write_tilt_frames(frames, *r).ok());
  std::ifstream f(csv);
  std::string header;
  std::getline(f, header);
  EXPECT_EQ(header, "time_s,tilt_deg,fn_N,ft_N,force_angle_deg,displacement_m,velocity_m_s,contacts");
  std::ifstream g(frames);
  std::getline(g, header);
  EXPECT_EQ(header, "frictal-dem-frames 1");
}

TEST(DemTilt, RejectsBadConfig) {
  frictal::TiltConfig cfg;
  cfg.time_step = 0;
  auto r = frictal::run_tilt(flat(0.05), flat(0.05), cfg);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("time_step"), std::string::npos);
  cfg.time_step = 1e-4;
  cfg.time_step_safety = 0;
  r = frictal::run_tilt(flat(0.05), flat(0.05), cfg);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("time_step_safety"), std::string::npos);
}

#ifdef FRICTAL_CLI_PATH
TEST(DemTiltCli, UsageErrorsExitWithTwo) {
  const std::string cli = FRICTAL_CLI_PATH;
  EXPECT_EQ(std::system((cli + " tilt nope > /dev/null 2>&1").c_str()), 2 << 8);
  EXPECT_EQ(std::system((cli + " tilt koch --time-step -1 > /dev/null 2>&1").c_str()), 2 << 8);
  EXPECT_EQ(std::system((cli + " tilt koch --time-step-safety 1.5 > /dev/null 2>&1").c_str()), 2 << 8);
}
#endif

TEST(DemTilt, RestitutionSetsNormalDampingFromEq12) {
  frictal::TiltConfig cfg;
  cfg.restitution = 0.5;
  cfg.predict = false;
  cfg.initial_offset = 0.01;
  cfg.max_tilt = 1 * kDeg;
  cfg.series_interval = 0;
  auto r = frictal::run_tilt(flat(0.2), flat(0.2), cfg);
  ASSERT_TRUE(r.ok()) << r.error().message;
  // Eq. 12 inverted by hand: gamma = 2 L sqrt(k/m) / sqrt(pi^2 + L^2), L = ln 2.
  const double L = std::log(2.0), pi = 3.14159265358979323846;
  EXPECT_NEAR(r->normal_damping, 2 * L * std::sqrt(6e5 / r->upper_mass) / std::sqrt(pi * pi + L * L), 1e-9);
  EXPECT_NEAR(r->upper_mass, 50 * 0.2 * 0.01, 1e-12);
}
