// Tilting-block test: hand-derived friction angles (flat blocks slide at atan(mu_a); a K_0 pair
// at alpha with mu_a = 0 slides at alpha, Eq. 6 with theta_max = alpha), output files, CLI.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

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
  // Read back: the polygons and every pose as written (17 significant digits: exact), time and
  // tilt to the 9 digits the file keeps.
  auto back = frictal::read_tilt_frames(frames);
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(back->lower_polygon_x, r->lower_polygon_x);
  EXPECT_EQ(back->upper_polygon_y, r->upper_polygon_y);
  ASSERT_EQ(back->frames.size(), r->frames.size());
  ASSERT_GT(r->frames.size(), 1u);
  for (std::size_t k = 0; k < r->frames.size(); ++k) {
    const auto &a = back->frames[k], &b = r->frames[k];
    EXPECT_NEAR(a.time, b.time, 1e-8 * std::max(1.0, b.time));
    EXPECT_NEAR(a.tilt, b.tilt, 1e-8);
    for (int j = 0; j < 2; ++j) {
      EXPECT_EQ(a.position[j].x, b.position[j].x);
      EXPECT_EQ(a.position[j].y, b.position[j].y);
      EXPECT_EQ(a.angle[j], b.angle[j]);
    }
  }
}

TEST(DemTilt, ReadingAFramesFileNamesTheBadLine) {
  const std::string path = ::testing::TempDir() + "dem_frames_bad.txt";
  auto read_with = [&](const std::string& text) {
    std::ofstream(path) << text;
    return frictal::read_tilt_frames(path);
  };
  const std::string bodies = "frictal-dem-frames 1\nbody 0 lower 3\n0 0\n1 0\n0 1\nbody 1 upper 3\n0 0\n1 0\n0 1\n";
  auto ok = read_with(bodies + "frame 0.5 0.01\n0 0 0 0\n1 0.1 0.2 0.003\n");
  ASSERT_TRUE(ok.ok()) << ok.error().message;
  ASSERT_EQ(ok->frames.size(), 1u);
  EXPECT_DOUBLE_EQ(ok->frames[0].position[1].y, 0.2);
  EXPECT_DOUBLE_EQ(ok->frames[0].angle[1], 0.003);
  struct Case {
    std::string text, line;
  };
  for (const Case& c :
       {Case{"a csv file\n", "line 1:"}, Case{bodies + "frame 0.5 x\n0 0 0 0\n1 0 0 0\n", "line 10:"},
        Case{bodies + "frame 0.5 0\n0 0 0 0\n", "line 12:"},
        Case{"frictal-dem-frames 1\nbody 0 lower 5\n0 0\n", "line 2:"}, Case{bodies + "bogus\n", "line 10:"}}) {
    auto r = read_with(c.text);
    ASSERT_FALSE(r.ok()) << c.text;
    EXPECT_EQ(r.error().code, frictal::ErrorCode::InvalidInput);
    EXPECT_NE(r.error().message.find(path + ": " + c.line), std::string::npos) << r.error().message;
  }
  EXPECT_EQ(frictal::read_tilt_frames(path + ".missing").error().code, frictal::ErrorCode::Io);
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

namespace {

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

// The numbers of the first DataArray named `name` (or, name empty, the first after `after`).
std::vector<double> data_array(const std::string& xml, const std::string& name) {
  const std::size_t at = xml.find("Name=\"" + name + "\"");
  EXPECT_NE(at, std::string::npos) << name;
  const std::size_t b = xml.find('>', at) + 1, e = xml.find("</DataArray>", b);
  std::istringstream in(xml.substr(b, e - b));
  std::vector<double> v;
  for (double d; in >> d;) v.push_back(d);
  return v;
}

std::vector<double> points(const std::string& xml) {
  const std::size_t at = xml.find("<Points>");
  const std::size_t b = xml.find('>', xml.find("<DataArray", at)) + 1, e = xml.find("</DataArray>", b);
  std::istringstream in(xml.substr(b, e - b));
  std::vector<double> v;
  for (double d; in >> d;) v.push_back(d);
  return v;
}

double segment_distance(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / l2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(px - ax - t * dx, py - ay - t * dy);
}

}  // namespace

// tilt --vtk: the files read back give the run's geometry (cores placed by the frame's pose,
// rounded outlines at r from the cores), its tilt, and contact forces that carry the weight.
TEST(DemTilt, VtkFilesReadBackToTheRunsState) {
  frictal::TiltConfig cfg;
  cfg.predict = false;
  cfg.initial_offset = 0.0025;
  cfg.series_interval = 0;
  cfg.frame_interval = 0.25;
  cfg.runaway_distance = 0.01;
  cfg.max_tilt = 5 * kDeg;  // K0 at 10 deg: at rest throughout
  auto r = frictal::run_tilt(koch(0, 10, 0.05), koch(0, 10, 0.05), cfg);
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_GE(r->frames.size(), 4u);
  const std::string dir = ::testing::TempDir() + "dem_vtk";
  auto w = frictal::write_tilt_vtk(dir, *r, cfg.radius);
  ASSERT_TRUE(w.ok()) << w.error().message;
  const std::string pvd = slurp(dir + "/tilt.pvd");
  std::size_t datasets = 0;
  for (std::size_t p = pvd.find("<DataSet"); p != std::string::npos; p = pvd.find("<DataSet", p + 1)) ++datasets;
  EXPECT_EQ(datasets, 2 * r->frames.size());
  const std::size_t k = r->frames.size() - 1;  // at rest, tilted by ~3.4 deg
  const frictal::TiltFrame& fr = r->frames[k];
  char name[64];
  std::snprintf(name, sizeof name, "/bodies_%05zu.vtp", k);
  const std::string bodies = slurp(dir + name);
  EXPECT_NEAR(data_array(bodies, "tilt_deg").at(0), fr.tilt / kDeg, 1e-9);
  EXPECT_GT(fr.tilt, 3 * kDeg);
  const std::vector<double> p = points(bodies);
  // Cores first: local polygon rotated by the frame's angle about the centroid, then shifted.
  std::size_t at = 0;
  std::vector<double> core_x[2], core_y[2];
  for (int b = 0; b < 2; ++b) {
    const auto& lx = b == 0 ? r->lower_polygon_x : r->upper_polygon_x;
    const auto& ly = b == 0 ? r->lower_polygon_y : r->upper_polygon_y;
    for (std::size_t i = 0; i < lx.size(); ++i, ++at) {
      const double c = std::cos(fr.angle[b]), s = std::sin(fr.angle[b]);
      const double x = fr.position[b].x + c * lx[i] - s * ly[i], y = fr.position[b].y + s * lx[i] + c * ly[i];
      ASSERT_NEAR(p[3 * at], x, 1e-12);
      ASSERT_NEAR(p[3 * at + 1], y, 1e-12);
      core_x[b].push_back(x);
      core_y[b].push_back(y);
    }
  }
  // Then the outlines: every point within r of its core and most at exactly r (arcs, offsets).
  const std::vector<double> offsets = data_array(bodies, "offsets");  // lines first: the 2 outlines
  ASSERT_EQ(offsets.size(), 2u);
  std::size_t on_r = 0, total = 0;
  for (int b = 0; b < 2; ++b) {
    const std::size_t n = static_cast<std::size_t>(offsets[b] - (b ? offsets[0] : 0));
    for (std::size_t i = 0; i < n; ++i, ++at, ++total) {
      double d = 1e9;
      const auto& X = core_x[b];
      const auto& Y = core_y[b];
      for (std::size_t e = 0; e < X.size(); ++e)
        d = std::min(
            d, segment_distance(p[3 * at], p[3 * at + 1], X[e], Y[e], X[(e + 1) % X.size()], Y[(e + 1) % X.size()]));
      EXPECT_LE(d, cfg.radius * (1 + 1e-9));
      on_r += std::fabs(d - cfg.radius) < 1e-9 * cfg.radius + 1e-15;
    }
  }
  EXPECT_EQ(at * 3, p.size());
  EXPECT_GT(on_r, total * 8 / 10);
  // Contacts: as many as in the frame, each within 2r of both cores; at rest their forces on the
  // upper block carry its weight m g.
  std::snprintf(name, sizeof name, "/contacts_%05zu.vtp", k);
  const std::string contacts = slurp(dir + name);
  const std::vector<double> cp = points(contacts);
  ASSERT_EQ(cp.size(), 3 * fr.contacts.size());
  ASSERT_GT(fr.contacts.size(), 0u);
  const std::vector<double> fn = data_array(contacts, "normal_force"), ft = data_array(contacts, "tangential_force");
  const std::vector<double> vb = data_array(contacts, "vertex_body");
  double sx = 0, sy = 0;
  for (std::size_t i = 0; i < fr.contacts.size(); ++i) {
    for (int b = 0; b < 2; ++b) {
      double d = 1e9;
      const auto& X = core_x[b];
      const auto& Y = core_y[b];
      for (std::size_t e = 0; e < X.size(); ++e)
        d = std::min(
            d, segment_distance(cp[3 * i], cp[3 * i + 1], X[e], Y[e], X[(e + 1) % X.size()], Y[(e + 1) % X.size()]));
      EXPECT_LE(d, 2 * cfg.radius);
    }
    const double sgn = vb[i] == 1 ? 1.0 : -1.0;  // forces act on the vertex body
    sx += sgn * (fn[3 * i] + ft[3 * i]);
    sy += sgn * (fn[3 * i + 1] + ft[3 * i + 1]);
  }
  EXPECT_NEAR(sx, 0, 1e-3 * r->upper_mass * 9.81);
  EXPECT_NEAR(sy, r->upper_mass * 9.81, 1e-3 * r->upper_mass * 9.81);
}

// hold_rotation: the upper block keeps the lower block's angle (it only translates), and a K0
// pair still slides at alpha (no rotation is the signature's assumption).
TEST(DemTilt, HoldRotationKeepsTheUpperBlockAligned) {
  frictal::TiltConfig cfg = frictal::tilt_config_for_surface(0.01, 0.01);
  cfg.hold_rotation = true;
  cfg.frame_interval = 0.5;
  cfg.series_interval = 0;
  auto r = frictal::run_tilt(koch(0, 10, 0.05), koch(0, 10, 0.05), cfg);
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_TRUE(r->slid);
  EXPECT_NEAR(r->friction_angle, 10 * kDeg, 0.1 * kDeg);
  EXPECT_EQ(r->rotation_before_slide, 0);
  for (const auto& f : r->frames) EXPECT_EQ(f.angle[1], f.angle[0]);
}

// The model warnings before the run: core-overlap when W/k_n exceeds warn_overlap_fraction r
// (W/k_n from the block's mass), rounding when r changes the prediction (K3 at 25 deg: the
// 3 alpha = 75 deg features are rounded away at r = 5e-5 m, docs/dem.md sec. 6).
TEST(DemTilt, ScaleWarnings) {
  frictal::TiltConfig cfg = frictal::tilt_config_for_surface(0.01, 0.01);
  cfg.max_tilt = 0.5 * kDeg;
  cfg.series_interval = 0;
  cfg.radius = 2e-6;
  auto r = frictal::run_tilt(koch(0, 10, 0.05), koch(0, 10, 0.05), cfg);
  ASSERT_TRUE(r.ok()) << r.error().message;
  const double w = r->upper_mass * cfg.gravity / cfg.contact.normal_stiffness;
  EXPECT_DOUBLE_EQ(r->scales.resting_overlap, w);
  auto has = [](const frictal::TiltResult& x, const std::string& code) {
    for (const auto& w : x.warnings)
      if (w.code == code) return true;
    return false;
  };
  EXPECT_EQ(has(*r, "core-overlap"), w > 0.1 * cfg.radius);
  EXPECT_TRUE(has(*r, "core-overlap"));  // W/k_n ~ 4e-7 m for this short block (0.025 kg)
  EXPECT_FALSE(has(*r, "rounding"));
  EXPECT_NEAR(r->scales.contact_period, 2 * 3.14159265358979323846 * std::sqrt(r->upper_mass / 6e5), 1e-15);
  cfg.radius = 5e-5;
  auto k3 = frictal::run_tilt(koch(3, 25, 0.05), koch(3, 25, 0.05), cfg);
  ASSERT_TRUE(k3.ok()) << k3.error().message;
  EXPECT_NEAR(k3->predicted_friction_angle, 75 * kDeg, 1e-9);
  EXPECT_LT(k3->predicted_sphero_friction_angle, 74 * kDeg);
  EXPECT_TRUE(has(*k3, "rounding"));
  EXPECT_FALSE(has(*k3, "core-overlap"));
}

// Run-away checkpoints (TiltConfig::runaway_checkpoints): the motion does not depend on the
// run-away distance, so the friction angle recorded at a checkpoint d in a run stopped at 2
// lambda is, bit for bit, the friction angle of a separate run whose runaway_distance is d. A WM
// pair (random phases, several sticks and slips) on a short block.
TEST(DemTilt, RunawayCheckpointsEqualSeparateRuns) {
  frictal::WmParams w;
  w.dimension = 1.7;
  w.n_max = 4;
  w.longest_wavelength = 0.01;
  w.length = 0.04;
  w.rms_height = 1e-5;
  w.seed = 11;
  auto lower = frictal::wm_profile(w);
  w.seed = 12;
  auto upper = frictal::wm_profile(w);
  ASSERT_TRUE(lower.ok() && upper.ok());
  const frictal::Curve lc = frictal::as_curve(*lower), uc = frictal::as_curve(*upper);
  frictal::TiltConfig cfg = frictal::tilt_config_for_surface(0, 0.01);
  cfg.radius = 2e-5;
  cfg.series_interval = 0;
  cfg.runaway_distance = 0.02;
  cfg.runaway_checkpoints = {0.005, 0.01, 0.02};
  auto all = frictal::run_tilt(lc, uc, cfg);
  ASSERT_TRUE(all.ok()) << all.error().message;
  ASSERT_TRUE(all->slid);
  ASSERT_EQ(all->checkpoints.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    const auto& cp = all->checkpoints[k];
    ASSERT_TRUE(cp.reached) << k;
    EXPECT_EQ(cp.distance, cfg.runaway_checkpoints[k]);
    frictal::TiltConfig one = cfg;
    one.runaway_checkpoints.clear();
    one.runaway_distance = cp.distance;
    auto sep = frictal::run_tilt(lc, uc, one);
    ASSERT_TRUE(sep.ok()) << sep.error().message;
    ASSERT_TRUE(sep->slid);
    EXPECT_EQ(cp.friction_angle, sep->friction_angle) << "run-away " << cp.distance << " m";
    EXPECT_EQ(cp.slide_time, sep->slide_time);
    EXPECT_EQ(cp.slide_start_displacement, sep->slide_start_displacement);
    if (k > 0) {
      EXPECT_GE(cp.slide_time, all->checkpoints[k - 1].slide_time);
      EXPECT_GE(cp.friction_angle, all->checkpoints[k - 1].friction_angle);
    }
  }
  EXPECT_EQ(all->checkpoints[2].friction_angle, all->friction_angle);
  EXPECT_GE(all->final_displacement - all->slide_start_displacement, cfg.runaway_distance);
  cfg.runaway_checkpoints = {0.03};  // beyond the stop
  auto bad = frictal::run_tilt(lc, uc, cfg);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("runaway_checkpoints"), std::string::npos);
}

// "unsettled": the WM pair (D = 1.5, n_max = 6, seeds 1 and 2, L = 0.01 m, L_b = 0.2 m,
// rms 1e-5 m) is still gliding at about 1 mm/s (100 x stick_speed) after the default 0.1 s of
// settling: the drop onto its nearly flat pair (slopes below 2.3 deg) sets it moving, and it
// starts the tilt elsewhere than the prediction's offset, with kinetic energy (docs/dem.md
// sec. 6). Settled for 1 s it is at rest and the warning is silent. K0 at 20 deg (which agrees
// with alpha) is at rest after 0.1 s: many contacts on 20 deg flanks stop it at once.
TEST(DemTilt, UnsettledWarningForTheReferenceWmPair) {
  auto has = [](const frictal::TiltResult& x, const std::string& code) {
    for (const auto& w : x.warnings)
      if (w.code == code) return true;
    return false;
  };
  frictal::WmParams w;
  w.dimension = 1.5;
  w.n_max = 6;
  w.longest_wavelength = 0.01;
  w.length = 0.2;
  w.rms_height = 1e-5;
  w.seed = 1;
  auto a = frictal::wm_profile(w);
  w.seed = 2;
  auto b = frictal::wm_profile(w);
  ASSERT_TRUE(a.ok() && b.ok());
  frictal::TiltConfig cfg = frictal::tilt_config_for_surface(0, 0);
  cfg.series_interval = 0;
  cfg.max_tilt = 0.05 * kDeg;  // the warning is decided when the tilt starts
  for (double r : {5e-5, 2e-5}) {
    cfg.radius = r;
    auto t = frictal::run_tilt(frictal::as_curve(*a), frictal::as_curve(*b), cfg);
    ASSERT_TRUE(t.ok()) << t.error().message;
    EXPECT_GT(t->settled_speed, 1e-4) << r;  // measured 1.27e-3 and 0.91e-3 m/s
    EXPECT_TRUE(has(*t, "unsettled")) << r;
    EXPECT_FALSE(has(*t, "core-overlap")) << r;  // W/k_n = 0.03 r and 0.08 r: the old warnings are silent
    EXPECT_FALSE(has(*t, "rounding")) << r;
  }
  cfg.radius = 5e-5;
  cfg.settle_time = 1.0;
  auto s = frictal::run_tilt(frictal::as_curve(*a), frictal::as_curve(*b), cfg);
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_LT(s->settled_speed, cfg.stick_speed);
  EXPECT_FALSE(has(*s, "unsettled"));

  frictal::TiltConfig k = frictal::tilt_config_for_surface(0.01, 0.01);
  k.series_interval = 0;
  auto k0 = frictal::run_tilt(koch(0, 20, 0.05), koch(0, 20, 0.05), k);
  ASSERT_TRUE(k0.ok()) << k0.error().message;
  ASSERT_TRUE(k0->slid);
  EXPECT_NEAR(k0->friction_angle / kDeg, 20.0, 0.1);
  EXPECT_LT(k0->settled_speed, k.stick_speed);
  EXPECT_TRUE(k0->warnings.empty()) << k0->warnings.front().code;
}

// The creep warning (docs/dem.md sec. 6): K3 at 20 deg on the Table I block first slips about
// 1 um near the prediction (n alpha = 60 deg), is caught by the next fine contacts and runs away
// 0.3 deg later; the warning names where sliding began. K2 at 20 deg slides ~1 mm at 20 deg onto
// its 2 alpha features (a slide longer than a tenth of the smallest feature: not creep) and is not
// flagged.
TEST(DemTilt, CreepWarningMarksAnEarlierSlipThanTheRunAway) {
  frictal::TiltConfig cfg = frictal::tilt_config_for_surface(0.01, 0.01);
  cfg.series_interval = 0;
  auto has = [](const frictal::TiltResult& x, const std::string& code) {
    for (const auto& w : x.warnings)
      if (w.code == code) return true;
    return false;
  };
  auto k3 = frictal::run_tilt(koch(3, 20, 0.2), koch(3, 20, 0.2), cfg);
  ASSERT_TRUE(k3.ok()) << k3.error().message;
  ASSERT_TRUE(k3->slid);
  EXPECT_TRUE(has(*k3, "creep"));
  // Sliding began within 0.1 deg of the spheropolygon prediction (3 alpha), where the reported
  // run-away angle is more than 0.1 deg above it.
  EXPECT_NEAR(k3->first_creep_tilt, k3->predicted_sphero_friction_angle, 0.1 * kDeg);
  EXPECT_GT(k3->friction_angle - k3->predicted_sphero_friction_angle, 0.1 * kDeg);
  EXPECT_GE(k3->first_creep_slip, cfg.warn_creep_slip);
  EXPECT_LT(k3->first_creep_slip, 0.1 * std::min(k3->scales.smallest_feature[0], k3->scales.smallest_feature[1]));
  auto k2 = frictal::run_tilt(koch(2, 20, 0.2), koch(2, 20, 0.2), cfg);
  ASSERT_TRUE(k2.ok()) << k2.error().message;
  EXPECT_FALSE(has(*k2, "creep"));
  EXPECT_NEAR(k2->friction_angle, 40 * kDeg, 0.1 * kDeg);
}

namespace {

// n points z = 0 evenly over [0, length] (a face whose point spacing is length / (n - 1)).
frictal::Curve even(double length, int n) {
  frictal::Curve c;
  for (int i = 0; i < n; ++i) {
    c.x.push_back(length * i / (n - 1));
    c.z.push_back(0.0);
  }
  return c;
}

double scaled(const frictal::TiltScaling& sc, const std::string& name) {
  for (const auto& t : sc.settings)
    if (t.name == name) return t.to;
  return std::nan("");
}

}  // namespace

TEST(DemTiltScaling, MacroBlockKeepsEveryDefault) {
  // A 0.2 m face sampled every 1 mm (coarser than r_0 = 5e-5 m): s = 1, q = 1, nothing changes.
  auto sc = frictal::scale_tilt_defaults(even(0.2, 201), even(0.3, 301));
  ASSERT_TRUE(sc.ok()) << sc.error().message;
  EXPECT_DOUBLE_EQ(sc->length, 0.2);
  EXPECT_DOUBLE_EQ(sc->length_factor, 1.0);
  EXPECT_DOUBLE_EQ(sc->radius_factor, 1.0);
  EXPECT_TRUE(sc->settings.empty());
  const frictal::TiltConfig d;
  EXPECT_EQ(sc->config.radius, d.radius);
  EXPECT_EQ(sc->config.block_height, d.block_height);
  EXPECT_EQ(sc->config.tilt_rate, d.tilt_rate);
  EXPECT_EQ(sc->config.contact.normal_stiffness, d.contact.normal_stiffness);
}

TEST(DemTiltScaling, ALengthWithinRoundingOfTheReferenceIsTheReference) {
  // A scan rescaled to 0.2 m in floating point (the README's measured pair) keeps the defaults.
  auto sc = frictal::scale_tilt_defaults(even(0.2 * (1 + 4e-16), 201), even(0.2 * (1 + 4e-16), 201));
  ASSERT_TRUE(sc.ok()) << sc.error().message;
  EXPECT_EQ(sc->length_factor, 1.0);
  EXPECT_TRUE(sc->settings.empty());
}

TEST(DemTiltScaling, SmallScanScalesLikeTheMacroTest) {
  // A 2 mm face every 0.2 mm: s = 2e-3 / 0.2 = 0.01; r = s r_0 = 5e-7 m is below the spacing,
  // so q = 1. Hand-computed from the Table I/II defaults (tilt.hpp): lengths x 0.01, k x 0.01,
  // rates x 1 / sqrt(0.01) = 10, times x 0.1, speeds x 0.1.
  auto sc = frictal::scale_tilt_defaults(even(2e-3, 11), even(2e-3, 11));
  ASSERT_TRUE(sc.ok()) << sc.error().message;
  EXPECT_DOUBLE_EQ(sc->point_spacing, 2e-4);
  EXPECT_NEAR(sc->length_factor, 0.01, 1e-15);
  EXPECT_NEAR(sc->radius_factor, 1.0, 1e-12);
  const frictal::TiltConfig& c = sc->config;
  EXPECT_NEAR(c.radius, 5e-7, 1e-20);
  EXPECT_NEAR(c.block_height, 1e-4, 1e-18);
  EXPECT_NEAR(c.placement_gap, 2e-7, 1e-20);
  EXPECT_NEAR(c.runaway_distance, 1e-4, 1e-18);  // L / 20, as signature's default run-away
  EXPECT_NEAR(c.skin, 5e-7, 1e-20);
  EXPECT_NEAR(c.contact.normal_stiffness, 6e3, 1e-9);
  EXPECT_NEAR(c.contact.tangential_stiffness, 6e2, 1e-10);
  EXPECT_NEAR(c.contact.normal_damping, 9295, 1e-8);
  EXPECT_NEAR(c.contact.tangential_damping, 40, 1e-11);
  EXPECT_NEAR(c.tilt_rate, 0.5, 1e-14);
  EXPECT_NEAR(c.settle_time, 0.01, 1e-16);
  EXPECT_NEAR(c.stick_duration, 2e-3, 1e-16);
  EXPECT_NEAR(c.stick_speed, 1e-6, 1e-20);
  EXPECT_NEAR(c.time_step, 1e-5, 1e-19);
  EXPECT_NEAR(c.series_interval, 1e-4, 1e-18);
  EXPECT_NEAR(c.warn_creep_slip, 1e-9, 1e-23);
  EXPECT_EQ(c.density, 50);  // areal density and gravity keep their values
  EXPECT_EQ(c.gravity, 9.81);
  EXPECT_NEAR(scaled(*sc, "spheroradius"), 5e-7, 1e-20);
  EXPECT_NEAR(scaled(*sc, "tilt_rate"), 0.5, 1e-14);
  EXPECT_TRUE(std::isnan(scaled(*sc, "density")));
  for (const auto& t : sc->settings)
    EXPECT_NE(frictal::find_field(frictal::tilt_settings(), t.name), nullptr) << t.name;
}

TEST(DemTiltScaling, FinePointSpacingCapsTheSpheroradius) {
  // 2 mm every 0.1 um: s = 0.01, s r_0 = 5e-7 m > dx = 1e-7 m, so r = 1e-7 m and q = 0.2;
  // k_n = 6e5 s / q = 3e4 N/m keeps W / (k_n r); gamma_n = 929.5 / sqrt(s q) = 929.5 / sqrt(2e-3);
  // time step 1e-4 sqrt(2e-3) s; placement gap 2e-5 s q = 4e-8 m; protocol times still x sqrt(s).
  auto sc = frictal::scale_tilt_defaults(even(2e-3, 20001), even(2e-3, 20001));
  ASSERT_TRUE(sc.ok()) << sc.error().message;
  EXPECT_NEAR(sc->point_spacing, 1e-7, 1e-15);
  EXPECT_NEAR(sc->radius_factor, 0.2, 1e-8);
  const frictal::TiltConfig& c = sc->config;
  EXPECT_NEAR(c.radius, 1e-7, 1e-14);
  EXPECT_NEAR(c.contact.normal_stiffness, 3e4, 3e-3);
  EXPECT_NEAR(c.contact.normal_damping, 929.5 / std::sqrt(2e-3), 1e-3);
  EXPECT_NEAR(c.time_step, 1e-4 * std::sqrt(2e-3), 1e-12);
  EXPECT_NEAR(c.placement_gap, 4e-8, 1e-15);
  EXPECT_NEAR(c.settle_time, 0.01, 1e-16);
  EXPECT_NEAR(c.tilt_rate, 0.5, 1e-14);
}

TEST(DemTiltScaling, RefusesAFaceWithoutLength) {
  frictal::Curve one;
  one.x = {1e-3, 1e-3};
  one.z = {0, 1e-6};
  EXPECT_FALSE(frictal::scale_tilt_defaults(one, even(1e-3, 3)).ok());
}

TEST(DemTiltScaling, AScaledCopyReadsTheSameFrictionAngle) {
  // Dimensional analysis: with every default scaled (q = 1) the test on a copy of K_0 at 10 deg
  // shrunk 1000 times is the macro test in other units, so it reads the same friction angle
  // (10 deg, Eq. 6) in about as many steps.
  const frictal::Curve big = koch(0, 10, 0.2);
  frictal::Curve small = big;
  for (double& x : small.x) x *= 1e-3;
  for (double& z : small.z) z *= 1e-3;
  auto a = frictal::scale_tilt_defaults(big, big);
  auto b = frictal::scale_tilt_defaults(small, small);
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_DOUBLE_EQ(a->radius_factor, 1.0);
  ASSERT_DOUBLE_EQ(b->radius_factor, 1.0);
  a->config.series_interval = b->config.series_interval = 0;
  auto ra = frictal::run_tilt(big, big, a->config);
  auto rb = frictal::run_tilt(small, small, b->config);
  ASSERT_TRUE(ra.ok()) << ra.error().message;
  ASSERT_TRUE(rb.ok()) << rb.error().message;
  ASSERT_TRUE(ra->slid && rb->slid);
  EXPECT_NEAR(ra->friction_angle / kDeg, 10.0, 0.5);
  EXPECT_NEAR(rb->friction_angle / kDeg, ra->friction_angle / kDeg, 1e-3);
  EXPECT_NEAR(rb->slide_time, ra->slide_time * std::sqrt(1e-3), 1e-3 * ra->slide_time);
  EXPECT_NEAR(static_cast<double>(rb->steps), static_cast<double>(ra->steps), 0.01 * static_cast<double>(ra->steps));
  EXPECT_TRUE(rb->warnings.empty()) << rb->warnings.front().code;
}

TEST(DemTilt, EstimateAndProgressCallbacks) {
  // K_0 at 20 deg on 5 cm: the estimate from the time step and the tilt rate before the first
  // step (bound: settle 0.1 s + 89 deg at 0.05 rad/s), progress every 1000 steps, and a refusal
  // returned by before_run ends the run before any step.
  const frictal::Curve k0 = koch(0, 20, 0.05);
  frictal::TiltConfig cfg;
  cfg.series_interval = 0;
  cfg.progress_interval = 1000;
  frictal::TiltEstimate seen;
  int calls = 0;
  std::uint64_t last_steps = 0;
  cfg.before_run = [&](const frictal::TiltEstimate& e) -> frictal::Status {
    seen = e;
    return frictal::Ok{};
  };
  cfg.progress = [&](const frictal::TiltProgress& p) {
    ++calls;
    EXPECT_EQ(p.steps % 1000, 0u);
    EXPECT_GT(p.steps, last_steps);
    last_steps = p.steps;
    EXPECT_NE(p.estimate, nullptr);
  };
  auto r = frictal::run_tilt(k0, k0, cfg);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_NEAR(seen.simulated_time_bound, 0.1 + 89 * kDeg / 0.05, 1e-9);
  // Expected: to the hold angle of the block from where it is put down, K_0's flank 20 deg (closed
  // form; the rounded blocks' within 0.1 deg of it).
  EXPECT_NEAR(seen.simulated_time_expected, 0.1 + 20 * kDeg / 0.05, 0.1 * kDeg / 0.05);
  EXPECT_LE(seen.time_step, cfg.time_step);
  EXPECT_NEAR(seen.steps_bound, std::ceil(seen.simulated_time_bound / seen.time_step), 1.0);
  EXPECT_EQ(calls, static_cast<int>(r->steps / 1000));
  // The estimate against the run: the run stops just past the predicted angle.
  EXPECT_NEAR(static_cast<double>(r->steps), seen.steps_expected, 0.5 * seen.steps_expected);

  cfg.progress = nullptr;
  cfg.before_run = [](const frictal::TiltEstimate&) -> frictal::Status { return frictal::make_error("no"); };
  auto refused = frictal::run_tilt(k0, k0, cfg);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().message, "no");
}

TEST(DemTilt, TheSpreadNotePlacesAReadingInTheModelsRangeOverDrops) {
  // A valid reading (inside the bracket from its own rest) outside the model's 5-95 % range over
  // drops: the note says so and names its basin's hold angle; one inside says inside; no slide or
  // no spread: no note.
  constexpr double kDeg = 3.14159265358979323846 / 180;
  frictal::TiltConfig c;
  frictal::TiltResult r;
  r.slid = true;
  r.predicted_hold_angle = r.predicted_sphero_hold_angle = 10.005 * kDeg;
  r.predicted_inertial_hold_angle = 5 * kDeg;
  r.predicted_spread_q05 = 2 * kDeg;
  r.predicted_spread_q50 = 3 * kDeg;
  r.predicted_spread_q95 = 4 * kDeg;
  r.friction_angle = 10 * kDeg;
  ASSERT_EQ(frictal::tilt_validity(r, c), "valid");
  const std::string out = frictal::tilt_spread_note(r, c);
  EXPECT_EQ(out.rfind("outside the rigid model's 5-95 % range over drops for this test, [2.000, 4.000] deg", 0), 0u)
      << out;
  EXPECT_NE(out.find("basin"), std::string::npos) << out;
  EXPECT_NE(out.find("10.005 deg"), std::string::npos) << out;
  r.friction_angle = 4.05 * kDeg;  // within the bracket's 0.1 deg of q95
  r.predicted_inertial_hold_angle = 4 * kDeg;
  EXPECT_EQ(frictal::tilt_spread_note(r, c).rfind("inside ", 0), 0u) << frictal::tilt_spread_note(r, c);
  r.slid = false;
  EXPECT_EQ(frictal::tilt_spread_note(r, c), "");
  r.slid = true;
  r.predicted_spread_q05 = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(frictal::tilt_spread_note(r, c), "");
}
