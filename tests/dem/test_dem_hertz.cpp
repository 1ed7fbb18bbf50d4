// Spheropolygon engine, Hertz contact law: a disc (a regular polygon, every vertex on its
// circumcircle, so its discrete curvature radius is the circle's) resting on a flat against the
// Hertz overlap delta = (3 W / (4 E* sqrt(R)))^(2/3); the stability limit from the tangent
// stiffness at that overlap; the dashpot's restitution against an independent integration of the
// one-contact equation of motion, independent of the impact speed; the curvature-radius rule.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "frictal/dem.hpp"
#include "frictal/generators.hpp"
#include "frictal/tilt.hpp"

namespace dem = frictal::dem;

namespace {

constexpr double kDiscRadius = 0.01;  // R0 (m)
constexpr double kSphero = 1e-4;      // spheroradius of both bodies (m)
constexpr double kModulus = 1e9;      // E* (Pa)

dem::BodyDef ground() {
  dem::BodyDef g;
  g.x = {-1, 1, 1, -1};
  g.y = {-0.01, -0.01, 0, 0};  // core top at y = 0
  g.type = dem::BodyType::Kinematic;
  g.radius = kSphero;
  return g;
}

// A regular 12-gon of circumradius R0 with a vertex straight below its centre at height y0 (its
// neighbours are R0 (1 - cos 30 deg) = 1.3 mm higher: one contact), rotation held to the ground's.
dem::BodyDef disc(double y0, double vy = 0) {
  dem::BodyDef b;
  const int n = 12;
  for (int i = 0; i < n; ++i) {
    const double a = -std::numbers::pi / 2 + 2 * std::numbers::pi * i / n;
    b.x.push_back(kDiscRadius * std::cos(a));
    b.y.push_back(y0 + kDiscRadius + kDiscRadius * std::sin(a));
  }
  b.radius = kSphero;
  b.density = 0.1 / (0.5 * n * kDiscRadius * kDiscRadius * std::sin(2 * std::numbers::pi / n));  // 0.1 kg
  b.velocity = {0, vy};
  b.rotation_follows = 0;
  return b;
}

dem::WorldDef hertz_world(double zeta, double gravity) {
  dem::WorldDef w;
  w.gravity = {0, -gravity};
  w.contact.law = dem::ContactLaw::Hertz;
  w.contact.contact_modulus = kModulus;
  w.contact.damping_ratio = zeta;
  w.time_step = 2e-5;
  w.adaptive_time_step = true;
  w.timings = false;
  return w;
}

// The restitution of one Hertz contact with the dashpot 2 zeta sqrt(m k), k = 1.5 c sqrt(x), from
// its equation of motion m x'' = -c x^1.5 - 2 zeta sqrt(1.5 m c) x^0.25 x' (midpoint rule on a
// fine step, separately from the library's integration).
double restitution_ode(double zeta) {
  const double h = 2e-5;
  double x = 0, v = 1;
  auto acc = [&](double xx, double vv) {
    const double p = std::max(xx, 0.0);
    return -std::pow(p, 1.5) - 2 * zeta * std::sqrt(1.5) * std::pow(p, 0.25) * vv;
  };
  for (int i = 0; i < 10000000; ++i) {
    const double xm = x + 0.5 * h * v, vm = v + 0.5 * h * acc(x, v);
    const double xn = x + h * vm, vn = v + h * acc(xm, vm);
    if (xn <= 0 && vn < 0) return -(v + (vn - v) * x / (x - xn));
    x = xn, v = vn;
  }
  return 0;
}

}  // namespace

TEST(DemHertz, CurvatureRadiusOfVertices) {
  auto m = dem::make_model(hertz_world(0.2, 9.81), {ground(), disc(1e-3)});
  ASSERT_TRUE(m.ok()) << m.error().message;
  ASSERT_EQ(m->curvature_radius.size(), 16u);
  // The ground's corners: the circle through a corner of the 2 m x 1 cm box and its two
  // neighbours (a right angle) has the half diagonal as radius, below the body's extent (the
  // half diagonal plus r).
  for (int v = 0; v < 4; ++v) EXPECT_NEAR(m->curvature_radius[v], std::hypot(1.0, 0.005), 1e-12);
  // The 12-gon: every vertex on the circumcircle.
  for (int v = 4; v < 16; ++v) EXPECT_NEAR(m->curvature_radius[v], kDiscRadius, 1e-12);
  // A sharp tip (its circle through the neighbours 2e-5 m either side and 1e-4 m below:
  // radius (c^2/4 + s^2) / (2 s) = 5.2e-5 m) is capped below at the spheroradius 5e-4 m; the
  // straight run's vertex (collinear neighbours) above at the extent.
  dem::BodyDef spike;
  spike.x = {-0.01, 0, 0.01, 0.01, 2e-5, 0, -2e-5, -0.01};
  spike.y = {0, 0, 0, 0.01, 0.02, 0.0201, 0.02, 0.01};
  spike.radius = 5e-4;
  auto ms = dem::make_model(hertz_world(0.2, 9.81), {ground(), spike});
  ASSERT_TRUE(ms.ok()) << ms.error().message;
  EXPECT_DOUBLE_EQ(ms->curvature_radius[4 + 5], 5e-4);
  EXPECT_DOUBLE_EQ(ms->curvature_radius[4 + 1], ms->extent[1]);
  spike.radius = 1e-5;
  ms = dem::make_model(hertz_world(0.2, 9.81), {ground(), spike});
  ASSERT_TRUE(ms.ok());
  EXPECT_NEAR(ms->curvature_radius[4 + 5], (4e-10 + 1e-8) / 2e-4, 1e-12);
}

TEST(DemHertz, DiscRestsAtTheHertzOverlap) {
  const double g = 9.81;
  auto m = dem::make_model(hertz_world(0.5, g), {ground(), disc(2 * kSphero + 1e-6)});
  ASSERT_TRUE(m.ok()) << m.error().message;
  dem::State st = dem::make_state(*m);
  while (st.time < 0.1) ASSERT_TRUE(dem::step(*m, st).ok());
  const double weight = m->mass[1] * g;
  const double delta = std::pow(3 * weight / (4 * kModulus * std::sqrt(kDiscRadius)), 2.0 / 3.0);
  auto cf = dem::contact_forces(*m, st);
  ASSERT_EQ(cf.size(), 1u);
  EXPECT_NEAR(cf[0].curvature_radius, kDiscRadius, 1e-12);  // the edge is flat: R = R0
  EXPECT_NEAR(cf[0].overlap, delta, 1e-6 * delta);
  EXPECT_NEAR(cf[0].normal_force, weight, 1e-6 * weight);
  EXPECT_NEAR(dem::hertz_overlap(weight, kModulus, kDiscRadius), delta, 1e-12 * delta);
  // Elastic energy (2/5) W delta at rest; the stability limit 2 / omega with
  // omega^2 = k / m, k = 2 E* sqrt(R delta) the tangent stiffness (the dashpot's limit
  // 1 / (zeta omega) = 2 / omega at zeta = 0.5 is the same).
  EXPECT_NEAR(st.elastic_energy, 0.4 * weight * delta, 1e-5 * weight * delta);
  const double k = 2 * kModulus * std::sqrt(kDiscRadius * delta);
  EXPECT_NEAR(st.step_limit[1], 2 / std::sqrt(k / m->mass[1]), 1e-5 * st.step_limit[1]);
}

TEST(DemHertz, ElasticBounceKeepsItsEnergy) {
  // zeta = 0, no gravity: the disc leaves with its impact speed (restitution 1).
  auto m = dem::make_model(hertz_world(0.0, 0.0), {ground(), disc(2 * kSphero + 1e-5, -0.1)});
  ASSERT_TRUE(m.ok());
  dem::State st = dem::make_state(*m);
  while (st.time < 0.05 && !(st.velocity[1].y > 0 && st.contact_count == 0)) ASSERT_TRUE(dem::step(*m, st).ok());
  EXPECT_NEAR(st.velocity[1].y, 0.1, 1e-4);
}

TEST(DemHertz, DashpotRestitutionIndependentOfImpactSpeed) {
  for (const double zeta : {0.1, 0.3}) {
    const double expected = restitution_ode(zeta);
    EXPECT_NEAR(dem::hertz_restitution(zeta), expected, 1e-4) << "zeta " << zeta;
    for (const double v0 : {0.02, 0.2}) {
      dem::WorldDef w = hertz_world(zeta, 0.0);
      w.implicit_damping = zeta > 0.2;  // both dashpot schemes (first order in dt)
      w.time_step = 2e-6;
      auto m = dem::make_model(w, {ground(), disc(2 * kSphero + 1e-6, -v0)});
      ASSERT_TRUE(m.ok());
      dem::State st = dem::make_state(*m);
      while (st.time < 0.05 && !(st.velocity[1].y > 0 && st.contact_count == 0)) ASSERT_TRUE(dem::step(*m, st).ok());
      EXPECT_NEAR(st.velocity[1].y / v0, expected, 1e-3) << "zeta " << zeta << " v0 " << v0;
    }
  }
  auto z = dem::hertz_damping_ratio(dem::hertz_restitution(0.25));
  ASSERT_TRUE(z.ok());
  EXPECT_NEAR(*z, 0.25, 1e-6);
  EXPECT_FALSE(dem::hertz_damping_ratio(0).ok());
}

TEST(DemHertz, RejectsBadParameters) {
  dem::WorldDef w = hertz_world(0.2, 9.81);
  w.contact.contact_modulus = 0;
  auto m = dem::make_model(w, {ground(), disc(1e-3)});
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.error().message.find("contact_modulus"), std::string::npos);
  w = hertz_world(-1, 9.81);
  EXPECT_FALSE(dem::make_model(w, {ground(), disc(1e-3)}).ok());
}

TEST(DemHertz, TiltKochK0SlidesAtAlphaPlusAtomicAngle) {
  // The tilt test with Hertz contacts (E = 70 GPa): a K_0 pair at alpha = 20 deg with mu_a = 0.3
  // slides at alpha + atan(mu_a) (Eq. 6 with theta_max = alpha), whatever the contact law; the
  // Table I block (~0.1 kg) sinks by nanometres, far below r.
  frictal::KochParams p;
  p.iterations = 0;
  p.alpha = 20 * std::numbers::pi / 180;
  p.wavelength = 0.01;
  p.length = 0.05;
  auto k0 = frictal::koch_curve(p);
  ASSERT_TRUE(k0.ok());
  frictal::TiltConfig cfg;
  cfg.contact.law = dem::ContactLaw::Hertz;
  cfg.modulus = 7e10;
  cfg.contact.atomic_friction = 0.3;
  cfg.series_interval = 0;
  auto r = frictal::run_tilt(*k0, *k0, cfg);
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_TRUE(r->slid);
  EXPECT_NEAR(r->friction_angle * 180 / std::numbers::pi, 20.0 + std::atan(0.3) * 180 / std::numbers::pi, 0.5);
  EXPECT_NEAR(r->contact_modulus, 7e10 / (1 - 0.3 * 0.3), 1);
  EXPECT_GT(r->settled_interference_ratio, 0);
  EXPECT_LT(r->settled_overlap, 0.01 * cfg.radius);
  // Without a modulus the Hertz law is refused before any step, naming the option.
  cfg.modulus = 0;
  auto bad = frictal::run_tilt(*k0, *k0, cfg);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("modulus"), std::string::npos);
}
