// Spheropolygon engine: hand-derived physics (free fall, resting overlap, restitution of Eq. 12,
// convergence in dt), neighbour list against brute force, determinism, input validation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <tuple>
#include <utility>

#include "frictal/dem.hpp"

namespace dem = frictal::dem;

namespace {

dem::BodyDef rect(double x0, double y0, double w, double h) {
  dem::BodyDef b;
  b.x = {x0, x0 + w, x0 + w, x0};
  b.y = {y0, y0, y0 + h, y0 + h};
  return b;
}

dem::BodyDef ground(double half_width = 1.0) {
  dem::BodyDef g = rect(-half_width, -0.01, 2 * half_width, 0.01);  // top surface at y = 0
  g.type = dem::BodyType::Kinematic;
  return g;
}

// A diamond standing on its bottom vertex at (0, y0): one vertex-edge contact with the ground,
// centroid straight above it, so a vertical impact has no torque.
dem::BodyDef diamond(double y0, double half_w, double half_h) {
  dem::BodyDef b;
  b.x = {0, half_w, 0, -half_w};
  b.y = {y0, y0 + half_h, y0 + 2 * half_h, y0 + half_h};
  return b;
}

}  // namespace

TEST(DemModel, RectangleMassProperties) {
  dem::WorldDef w;
  dem::BodyDef b = rect(1.0, 2.0, 0.2, 0.01);
  b.density = 50;
  std::reverse(b.x.begin(), b.x.end());  // clockwise input is accepted
  std::reverse(b.y.begin(), b.y.end());
  auto m = dem::make_model(w, {b});
  ASSERT_TRUE(m.ok()) << m.error().message;
  const double mass = 50 * 0.2 * 0.01;
  EXPECT_NEAR(m->mass[0], mass, 1e-12 * mass);
  EXPECT_NEAR(m->initial_position[0].x, 1.1, 1e-12);
  EXPECT_NEAR(m->initial_position[0].y, 2.005, 1e-12);
  EXPECT_NEAR(m->inertia[0], mass * (0.2 * 0.2 + 0.01 * 0.01) / 12, 1e-12 * mass);
}

TEST(DemModel, RejectsBadInput) {
  dem::WorldDef w;
  dem::BodyDef bow;  // self-crossing "bow tie"
  bow.x = {0, 2, 2, 0};
  bow.y = {0, 1, 0, 3};
  auto r = dem::make_model(w, {bow});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("not simple"), std::string::npos) << r.error().message;

  dem::BodyDef tiny = rect(0, 0, 1, 1);
  tiny.radius = 0;
  r = dem::make_model(w, {tiny});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("radius"), std::string::npos);

  w.time_step = -1;
  r = dem::make_model(w, {rect(0, 0, 1, 1)});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("time_step"), std::string::npos);
}

TEST(DemPhysics, FreeFallIsExact) {
  // Velocity Verlet integrates a constant force exactly: y = y0 + v0 t - g t^2 / 2.
  dem::WorldDef w;
  w.time_step = 1e-3;
  w.skin = 0.1;  // a lone fast body: the list check would otherwise ask for a smaller step
  dem::BodyDef b = rect(0, 1, 0.1, 0.05);
  b.velocity = {0.3, 2.0};
  b.angular_velocity = 1.5;
  auto m = dem::make_model(w, {b});
  ASSERT_TRUE(m.ok());
  dem::State s = dem::make_state(*m);
  const dem::Vec2 p0 = s.position[0];
  ASSERT_TRUE(dem::advance(*m, s, 1000).ok());
  const double t = 1.0;
  EXPECT_DOUBLE_EQ(s.time, t);
  EXPECT_NEAR(s.position[0].x, p0.x + 0.3 * t, 1e-12);
  EXPECT_NEAR(s.position[0].y, p0.y + 2.0 * t - 0.5 * 9.81 * t * t, 1e-12);
  EXPECT_NEAR(s.velocity[0].y, 2.0 - 9.81 * t, 1e-12);
  EXPECT_NEAR(s.angle[0], 1.5 * t, 1e-12);
}

TEST(DemPhysics, RestingBlockOverlapIsWeightOverStiffness) {
  // A flat block on flat ground rests on its two bottom corners (two vertex-edge contacts):
  // k_n (overlap_1 + overlap_2) = m g, and by symmetry each overlap is m g / (2 k_n).
  dem::WorldDef w;
  w.time_step = 2e-5;
  const double r = 5e-5;
  dem::BodyDef b = rect(-0.05, 2 * r + 1e-6, 0.1, 0.01);
  auto m = dem::make_model(w, {ground(), b});
  ASSERT_TRUE(m.ok()) << m.error().message;
  dem::State s = dem::make_state(*m);
  ASSERT_TRUE(dem::advance(*m, s, 25000).ok());  // 0.5 s, many damping times (2/gamma_n = 2 ms)
  const double weight = m->mass[1] * 9.81;
  double sum = 0;
  int n = 0;
  for (const auto& p : s.pairs)
    if (p.overlap > 0) sum += p.overlap, ++n;
  EXPECT_EQ(n, 2);
  EXPECT_NEAR(sum, weight / 6e5, 1e-4 * weight / 6e5);
  EXPECT_NEAR(s.max_overlap, weight / (2 * 6e5), 1e-3 * weight / 6e5);
  EXPECT_NEAR(s.force[1].y, weight, 1e-4 * weight);
  // Centroid height: ground top (0) + 2r - overlap + half the block height.
  EXPECT_NEAR(s.position[1].y, 2 * r - weight / (2 * 6e5) + 0.005, 1e-9);
}

namespace {

// Drops a diamond at speed v0 on the ground without gravity and returns rebound / impact speed.
double bounce_restitution(double dt, double gamma_n, double* mass_out = nullptr) {
  dem::WorldDef w;
  w.gravity = {0, 0};
  w.time_step = dt;
  w.contact.normal_damping = gamma_n;
  dem::BodyDef b = diamond(2 * 5e-5 + 1e-5, 0.02, 0.03);
  b.velocity = {0, -0.05};
  auto m = dem::make_model(w, {ground(), b});
  if (!m.ok()) return -1;
  if (mass_out) *mass_out = m->mass[1];
  dem::State s = dem::make_state(*m);
  bool touched = false;
  for (int i = 0; i < 200000; ++i) {
    if (!dem::step(*m, s).ok()) return -1;
    if (s.contact_count > 0) touched = true;
    if (touched && s.contact_count == 0) return s.velocity[1].y / 0.05;
  }
  return -1;
}

}  // namespace

TEST(DemPhysics, BounceMatchesRestitutionOfEq12) {
  // Eq. 12 with the body's mass (the ground is kinematic): choose gamma_n for eps = 0.5.
  double mass = 0;
  bounce_restitution(1e-5, 0, &mass);
  auto g = dem::damping_from_restitution(0.5, 6e5, mass);
  ASSERT_TRUE(g.ok());
  EXPECT_NEAR(dem::restitution_from_damping(*g, 6e5, mass), 0.5, 1e-12);
  const double e1 = bounce_restitution(1e-5, *g);
  const double e2 = bounce_restitution(5e-6, *g);
  const double e4 = bounce_restitution(2.5e-6, *g);
  RecordProperty("restitution_dt_1e-5", std::to_string(e1));
  std::printf("restitution at dt = 1e-5, 5e-6, 2.5e-6: %.6f %.6f %.6f\n", e1, e2, e4);
  EXPECT_NEAR(e1, 0.5, 0.01);
  EXPECT_NEAR(e4, 0.5, 0.003);
  // Converges as dt halves (errors shrink).
  EXPECT_LT(std::fabs(e2 - 0.5), std::fabs(e1 - 0.5) + 1e-12);
  EXPECT_LT(std::fabs(e4 - 0.5), std::fabs(e2 - 0.5) + 1e-12);
  // Undamped contact is elastic.
  EXPECT_NEAR(bounce_restitution(1e-5, 0.0), 1.0, 1e-3);
}

TEST(DemPhysics, TableIIDampingIsEq12WithEpsHalf) {
  // gamma_n = 929.5 1/s (Table II) is Eq. 12 with eps = 0.5 for k_n = 6e5 N/m and
  // m1 = k_n / ((gamma/2)^2 + ((gamma/2) pi / ln 2)^2) = 0.1289 kg.
  const double gh = 929.5 / 2;
  const double pi = 3.14159265358979323846;
  const double m1 = 6e5 / (gh * gh + std::pow(gh * pi / std::log(2.0), 2));
  EXPECT_NEAR(m1, 0.1289, 1e-4);
  EXPECT_NEAR(dem::restitution_from_damping(929.5, 6e5, m1), 0.5, 1e-9);
  auto g = dem::damping_from_restitution(0.5, 6e5, m1);
  ASSERT_TRUE(g.ok());
  EXPECT_NEAR(*g, 929.5, 1e-6);
}

TEST(DemNeighborList, MatchesBruteForce) {
  // Two interleaved saw-tooth combs (non-convex): the grid-built list must hold exactly the
  // vertex-edge pairs within r1 + r2 + skin.
  dem::WorldDef w;
  w.gravity = {0, 0};
  w.skin = 3e-4;
  auto comb = [](double y0, double dir, double phase) {
    dem::BodyDef b;
    const int teeth = 40;
    const double pitch = 0.01;
    for (int i = 0; i <= 2 * teeth; ++i) {
      b.x.push_back(i * pitch / 2 + phase);
      b.y.push_back(y0 + dir * ((i % 2) ? 0.004 : 0.0) + dir * 0.00013 * std::sin(i * 1.7));
    }
    b.x.push_back(teeth * pitch + phase);
    b.y.push_back(y0 - dir * 0.02);
    b.x.push_back(phase);
    b.y.push_back(y0 - dir * 0.02);
    return b;
  };
  dem::BodyDef lo = comb(0.0, 1.0, 0.0);
  dem::BodyDef up = comb(0.0045, -1.0, 0.0051);
  lo.type = dem::BodyType::Kinematic;
  auto m = dem::make_model(w, {lo, up});
  ASSERT_TRUE(m.ok()) << m.error().message;
  dem::State s = dem::make_state(*m);
  std::set<std::pair<std::uint32_t, std::uint32_t>> grid, brute;
  for (const auto& p : s.pairs) grid.insert({p.vertex, p.edge0});
  const double cut = 2 * 5e-5 + w.skin;
  for (std::uint32_t v = 0; v < m->local_x.size(); ++v)
    for (std::uint32_t e = 0; e < m->local_x.size(); ++e) {
      if (m->vertex_body[v] == m->vertex_body[e]) continue;
      const dem::Vec2 p = dem::world_vertex(*m, s, v), a = dem::world_vertex(*m, s, e),
                      b = dem::world_vertex(*m, s, m->next_vertex[e]);
      const double dx = b.x - a.x, dy = b.y - a.y;
      double t = ((p.x - a.x) * dx + (p.y - a.y) * dy) / (dx * dx + dy * dy);
      t = std::clamp(t, 0.0, 1.0);
      if (std::hypot(p.x - a.x - t * dx, p.y - a.y - t * dy) < cut) brute.insert({v, e});
    }
  EXPECT_GT(brute.size(), 10u);
  EXPECT_EQ(grid, brute);
}

TEST(DemDeterminism, TwoWorldsSideBySideAreBitwiseEqual) {
  dem::WorldDef w;
  w.time_step = 2e-5;
  w.contact.atomic_friction = 0.3;
  dem::BodyDef g = ground();
  g.motion.angular_velocity = -0.5;
  dem::BodyDef b = diamond(2 * 5e-5 + 1e-5, 0.02, 0.01);
  b.velocity = {0.01, -0.02};
  auto m = dem::make_model(w, {g, b});
  ASSERT_TRUE(m.ok());
  dem::State s1 = dem::make_state(*m), s2 = dem::make_state(*m);
  for (int i = 0; i < 5000; ++i) {
    ASSERT_TRUE(dem::step(*m, s1).ok());
    ASSERT_TRUE(dem::step(*m, s2).ok());
  }
  EXPECT_EQ(s1.position[1].x, s2.position[1].x);
  EXPECT_EQ(s1.position[1].y, s2.position[1].y);
  EXPECT_EQ(s1.angle[1], s2.angle[1]);
  EXPECT_EQ(s1.velocity[1].x, s2.velocity[1].x);
  EXPECT_GT(s1.timings.list_builds, 1u);
}

TEST(DemGuard, TooLargeTimeStepStopsWithSuggestion) {
  dem::WorldDef w;
  w.time_step = 2e-3;  // far beyond sqrt(m / k_n) ~ 4e-4 s for this block
  w.skin = 1.0;        // so that the skin check does not fire first
  dem::BodyDef b = rect(-0.05, 2 * 5e-5 + 1e-6, 0.1, 0.01);
  b.velocity = {0, -0.01};
  auto m = dem::make_model(w, {ground(), b});
  ASSERT_TRUE(m.ok());
  dem::State s = dem::make_state(*m);
  frictal::Status st = dem::advance(*m, s, 10000);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().message.find("time step <="), std::string::npos) << st.error().message;
}

TEST(DemGuard, ManyDashpotsBeyondTheExplicitLimitStop) {
  // Two corner contacts (x = +-0.05 m) with gamma_n = 2e5 1/s. Bounce mode: rate 2 gamma_n;
  // rocking mode: rate gamma_n * 2 * 0.05^2 * m / I with I = m (0.1^2 + 0.01^2) / 12, i.e.
  // 5.9406 gamma_n, the faster one: limit 2 / (5.9406 * 2e5) = 1.683e-6 s < dt = 1e-5 s, so the
  // strict guard stops at the first contact.
  dem::WorldDef w;
  w.contact.normal_damping = 2e5;
  w.max_steps_beyond_limit = 0;  // strict: stop at the first step beyond the limit
  dem::BodyDef b = rect(-0.05, 2 * 5e-5 + 1e-6, 0.1, 0.01);
  auto m = dem::make_model(w, {ground(), b});
  ASSERT_TRUE(m.ok());
  EXPECT_NEAR(dem::stability_limit(*m, 1, 2), 2.0 / (2 * 2e5), 1e-15);
  dem::State s = dem::make_state(*m);
  frictal::Status st = dem::advance(*m, s, 20000);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().message.find("stability limit"), std::string::npos) << st.error().message;
  EXPECT_NE(st.error().message.find("1.68e-06"), std::string::npos) << st.error().message;
  EXPECT_EQ(s.steps_beyond_limit, static_cast<std::uint64_t>(w.max_steps_beyond_limit) + 1);
}

namespace {

// Diamond falling on the ground without gravity (one vertex-edge contact, normal straight up
// through the centroid, so J = (0, 1, 0)): returns the state at the first step in contact.
struct OneContact {
  dem::Model model;
  dem::State state;
};

OneContact one_contact(dem::WorldDef w) {
  w.gravity = {0, 0};
  dem::BodyDef b = diamond(2 * 5e-5 + 1e-6, 0.02, 0.03);
  b.velocity = {0, -0.01};
  auto m = dem::make_model(w, {ground(), b});
  EXPECT_TRUE(m.ok());
  dem::State s = dem::make_state(*m);
  for (int i = 0; i < 100000 && s.contact_count == 0; ++i) EXPECT_TRUE(dem::step(*m, s).ok());
  EXPECT_EQ(s.contact_count, 1);
  return {std::move(*m), std::move(s)};
}

}  // namespace

TEST(DemStability, OneContactLimitsAreThoseOfTheScalarOscillator) {
  // One contact on mass m (kinematic partner, reduced mass m): omega^2 = k_n / m, damping rate
  // c = gamma_n. Explicit dashpots: min(2 / omega, 2 / c). Implicit dashpots: the scheme
  // v' = v + dt (-omega^2 x - c v) / (1 + c dt), x' = x + dt v' is stable iff
  // omega^2 dt^2 < 2 (2 + c dt), i.e. dt < (c + sqrt(c^2 + 4 omega^2)) / omega^2.
  dem::WorldDef w;
  w.time_step = 1e-5;
  w.contact.normal_damping = 5000;  // 2 / c = 4e-4 s binds before 2 / omega ~ 6.3e-4 s
  OneContact ex = one_contact(w);
  const double m = ex.model.mass[1], k = 6e5, c = 5000;
  const double w2 = k / m;
  EXPECT_NEAR(ex.state.step_limit[1], std::min(2 / std::sqrt(w2), 2 / c), 1e-9 * (2 / c));
  w.implicit_damping = true;
  OneContact im = one_contact(w);
  const double implicit_limit = (c + std::sqrt(c * c + 4 * w2)) / w2;
  EXPECT_GT(implicit_limit, 2 / std::sqrt(w2));
  EXPECT_NEAR(im.state.step_limit[1], implicit_limit, 1e-9 * implicit_limit);
}

TEST(DemStability, ImplicitDampingHoldsBeyondTheExplicitLimit) {
  // A flat block on flat ground (two contacts) with gamma_n = 2e5 1/s: the damping rate of the
  // bounce mode is 2 gamma_n = 4e5 1/s, so an explicit step must stay below 5e-6 s. At 5e-5 s the
  // explicit run stops on the stability guard; with implicit dashpots it comes to rest with the
  // static overlap k_n (overlap_1 + overlap_2) = m g, as in RestingBlockOverlapIsWeightOverStiffness.
  dem::WorldDef w;
  w.time_step = 5e-5;
  w.contact.normal_damping = 2e5;
  w.max_steps_beyond_limit = 0;
  const double r = 5e-5;
  dem::BodyDef b = rect(-0.05, 2 * r + 1e-6, 0.1, 0.01);
  auto m = dem::make_model(w, {ground(), b});
  ASSERT_TRUE(m.ok());
  dem::State s = dem::make_state(*m);
  EXPECT_FALSE(dem::advance(*m, s, 10000).ok());
  w.implicit_damping = true;
  m = dem::make_model(w, {ground(), b});
  ASSERT_TRUE(m.ok());
  s = dem::make_state(*m);
  ASSERT_TRUE(dem::advance(*m, s, 10000).ok());  // 0.5 s
  const double weight = m->mass[1] * 9.81;
  double sum = 0;
  for (const auto& p : s.pairs)
    if (p.overlap > 0) sum += p.overlap;
  EXPECT_NEAR(sum, weight / 6e5, 1e-4 * weight / 6e5);
  EXPECT_NEAR(s.force[1].y, weight, 1e-4 * weight);
  EXPECT_EQ(s.steps_beyond_limit, 0u);
}

TEST(DemStability, AdaptiveStepIsSafetyTimesTheLimit) {
  // A flat block (0.1 m x 0.01 m, m = 0.05 kg) settling on flat ground with an adaptive step of at
  // most 1e-3 s and explicit dashpots. At rest it has two contacts, at its bottom corners
  // x = +-0.05 m, normals straight up: G = diag(0, 2, 2 x 0.05^2) in (x, y, angle), so
  // lambda_max(M^-1/2 G M^-1/2) = max(2 / m, 0.005 / I) and the limit is
  // min(2 / sqrt(k_n lambda), 2 / (gamma_n lambda m)) (reduced mass m). The step is half that,
  // unless one more contact (2 / sqrt(k_n max(1/m, extent^2/I)), 2 / gamma_n) binds first.
  dem::WorldDef w;
  w.time_step = 1e-3;
  w.adaptive_time_step = true;
  const double r = 5e-5;
  dem::BodyDef b = rect(-0.05, 2 * r + 1e-6, 0.1, 0.01);
  auto m = dem::make_model(w, {ground(), b});
  ASSERT_TRUE(m.ok());
  dem::State s = dem::make_state(*m);
  while (s.time < 0.5) ASSERT_TRUE(dem::step(*m, s).ok());
  const double mass = m->mass[1], inertia = m->inertia[1], kn = 6e5, gn = 929.5;
  ASSERT_EQ(s.contact_count, 2);
  const double lambda = std::max(2 / mass, 2 * 0.05 * 0.05 / inertia);
  const double limit = std::min(2 / std::sqrt(kn * lambda), 2 / (gn * lambda * mass));
  const double e = m->extent[1];
  const double one_more = std::min(2 / std::sqrt(kn * std::max(1 / mass, e * e / inertia)), 2 / gn);
  ASSERT_LT(limit, one_more);  // the two contacts bind
  EXPECT_NEAR(s.step_limit[1], limit, 1e-9 * limit);
  EXPECT_NEAR(s.time_step, 0.5 * limit, 1e-9 * limit);
  // At rest as with the fixed step: k_n (overlap_1 + overlap_2) = m g.
  const double weight = mass * 9.81;
  double sum = 0;
  for (const auto& p : s.pairs)
    if (p.overlap > 0) sum += p.overlap;
  EXPECT_NEAR(sum, weight / kn, 1e-4 * weight / kn);
  EXPECT_EQ(s.steps_beyond_limit, 0u);
}

TEST(DemState, CopyContinuesBitwiseLikeTheOriginal) {
  // The private workspace (hot list, list poses, scratch) is copied with the State.
  dem::WorldDef w;
  w.time_step = 2e-5;
  w.contact.atomic_friction = 0.3;
  dem::BodyDef g = ground();
  g.motion.angular_velocity = -0.5;
  dem::BodyDef b = diamond(2 * 5e-5 + 1e-5, 0.02, 0.01);
  b.velocity = {0.01, -0.02};
  auto m = dem::make_model(w, {g, b});
  ASSERT_TRUE(m.ok());
  dem::State s1 = dem::make_state(*m);
  ASSERT_TRUE(dem::advance(*m, s1, 2000).ok());
  dem::State s2 = s1;
  ASSERT_TRUE(dem::advance(*m, s1, 3000).ok());
  ASSERT_TRUE(dem::advance(*m, s2, 3000).ok());
  EXPECT_EQ(s1.position[1].x, s2.position[1].x);
  EXPECT_EQ(s1.angle[1], s2.angle[1]);
  EXPECT_EQ(s1.velocity[1].y, s2.velocity[1].y);
}

namespace {

// The ground g (kinematic) and a body b, without gravity, after one step of 1 ns under `rule`:
// the bodies move by ~1e-14 m, so the forces are those of the placed geometry.
void one_step(dem::ContactRule rule, const dem::BodyDef& g, const dem::BodyDef& b, dem::Model& model,
              dem::State& state) {
  dem::WorldDef w;
  w.gravity = {0, 0};
  w.time_step = 1e-9;
  w.contact.rule = rule;
  auto m = dem::make_model(w, {g, b});
  EXPECT_TRUE(m.ok()) << m.error().message;
  model = *m;
  state = dem::make_state(model);
  EXPECT_TRUE(dem::step(model, state).ok());
}

// A vertex v (bottom of a diamond) hovers over the left flank of a roof-shaped ground (flanks of
// slope 10 deg meeting at a convex peak w = (0, 0)), a' = 0.5 um from the peak along the flank
// and d = 2r - delta above it (delta = 10 nm). Then |v - w| = sqrt(a'^2 + d^2) < 2r as well: the
// vertex touches the flank (interior) and the peak (the right flank's end, and w touches the
// diamond's edges at their end v). Without gravity, after one step of 1 ns (the bodies move by
// ~1e-18 m), the forces are those of this geometry.
struct ConvexCorner {
  double r = 2e-5, delta = 1e-8, theta = 10.0 * 3.14159265358979323846 / 180.0, a = 0.5e-6;
  double nx = 0, ny = 0;  // the flank's outward normal
  dem::Model model;
  dem::State state;
};

ConvexCorner convex_corner(dem::ContactRule rule) {
  ConvexCorner c;
  const double t = std::tan(c.theta);
  dem::BodyDef g;  // counter-clockwise
  g.x = {-0.01, 0.01, 0.01, 0.0, -0.01};
  g.y = {-0.01, -0.01, -0.01 * t, 0.0, -0.01 * t};
  g.type = dem::BodyType::Kinematic;
  g.radius = c.r;
  c.nx = -std::sin(c.theta), c.ny = std::cos(c.theta);
  const double fx = -c.a * std::cos(c.theta), fy = -c.a * std::sin(c.theta);  // foot on the flank
  const double d = 2 * c.r - c.delta;
  const double vx = fx + d * c.nx, vy = fy + d * c.ny;
  dem::BodyDef b;
  b.x = {vx, vx + 1e-3, vx, vx - 1e-3};
  b.y = {vy, vy + 1e-3, vy + 2e-3, vy + 1e-3};
  b.radius = c.r;
  one_step(rule, g, b, c.model, c.state);
  return c;
}

}  // namespace

TEST(DemContactRule, ClosestKeepsTheFlankNormalNextToAConvexPeak) {
  // closest: one contact, the flank's: f = k_n delta along the flank's normal (no velocity, so no
  // dashpot), exactly the rigid contact's direction.
  ConvexCorner c = convex_corner(dem::ContactRule::Closest);
  const double kn = c.model.def.contact.normal_stiffness;
  const auto forces = dem::contact_forces(c.model, c.state);
  ASSERT_EQ(forces.size(), 1u);
  EXPECT_NEAR(forces[0].overlap, c.delta, 1e-6 * c.delta);
  EXPECT_NEAR(c.state.force[1].x, kn * c.delta * c.nx, 1e-6 * kn * c.delta);
  EXPECT_NEAR(c.state.force[1].y, kn * c.delta * c.ny, 1e-6 * kn * c.delta);
  EXPECT_EQ(c.state.contact_count, 1);
}

TEST(DemContactRule, PairsAlsoPushAlongTheLineToThePeak) {
  // pairs (the paper's): the flank's pair and the vertex-vertex pairs with the peak, whose
  // overlap is 2r - sqrt(a^2 + d^2) and whose normal (v - w) / |v - w| leans further back than
  // the flank's; the sum of the forces is no longer along the flank's normal.
  ConvexCorner c = convex_corner(dem::ContactRule::Pairs);
  const double d = 2 * c.r - c.delta;
  const double vv_overlap = 2 * c.r - std::sqrt(c.a * c.a + d * d);
  ASSERT_GT(vv_overlap, 0);
  const auto forces = dem::contact_forces(c.model, c.state);
  ASSERT_GE(forces.size(), 2u);
  int at_peak = 0;
  for (const auto& f : forces)
    if (std::fabs(f.overlap - vv_overlap) < 1e-3 * vv_overlap) ++at_peak;
  EXPECT_GE(at_peak, 1);
  const double tilt_flank = std::atan2(-c.nx, c.ny);
  const double tilt_sum = std::atan2(-c.state.force[1].x, c.state.force[1].y);
  EXPECT_GT(tilt_sum, tilt_flank + 0.01 * tilt_flank);
}

namespace {

// A vertex v (bottom of a diamond) right above the concave corner w = (0, 0) of a valley-shaped
// ground whose flanks rise at theta on both sides, at height h. Both flanks' lines lie at
// h cos(theta) from v (feet inside the flanks), so each flank overlaps by 2r - h cos(theta); the
// corner itself is at h, and the diamond's edges leave v upwards at 45 deg, so w's projections
// on them clamp at v (w against the diamond's edges: the vertex-vertex pair, twice).
struct Valley {
  double r = 2e-5, theta = 0, h = 0;
  dem::Model model;
  dem::State state;
};

Valley valley(dem::ContactRule rule, double theta_deg, double h) {
  Valley c;
  c.theta = theta_deg * 3.14159265358979323846 / 180.0;
  c.h = h;
  const double t = std::tan(c.theta);
  dem::BodyDef g;  // counter-clockwise; the corner (0, 0) turns right: concave
  g.x = {-0.01, 0.01, 0.01, 0.0, -0.01};
  g.y = {-0.01, -0.01, 0.01 * t, 0.0, 0.01 * t};
  g.type = dem::BodyType::Kinematic;
  g.radius = c.r;
  dem::BodyDef b;
  b.x = {0.0, 1e-3, 0.0, -1e-3};
  b.y = {h, h + 1e-3, h + 2e-3, h + 1e-3};
  b.radius = c.r;
  one_step(rule, g, b, c.model, c.state);
  return c;
}

}  // namespace

TEST(DemContactRule, ClosestCountsANearlyFlatConcaveCornerAsOneContact) {
  // theta = 0.5 deg, the corner 10 nm inside reach: each flank overlaps by
  // delta_f = 2r - h cos(theta) = 11.5 nm, the corner by delta_w = 10 nm. Rule closest: the two
  // flanks' bands overlap around the corner and the vertex-vertex term is subtracted once,
  // F_y = k_n (2 delta_f cos(theta) - delta_w), about one contact's k_n delta (two flanks
  // alone would be two contacts' worth on a face that is almost straight). Rule pairs adds the
  // corner twice: F_y = k_n (2 delta_f cos(theta) + 2 delta_w).
  // (Tolerance 1e-5 k_n delta: in its one step of 1 ns the light diamond moves by ~1e-14 m.)
  const double r = 2e-5, dw = 1e-8, h = 2 * r - dw;
  for (dem::ContactRule rule : {dem::ContactRule::Closest, dem::ContactRule::Pairs}) {
    Valley c = valley(rule, 0.5, h);
    const double kn = c.model.def.contact.normal_stiffness;
    const double df = 2 * r - h * std::cos(c.theta);
    ASSERT_GT(df, dw);
    const double expected = rule == dem::ContactRule::Closest ? kn * (2 * df * std::cos(c.theta) - dw)
                                                              : kn * (2 * df * std::cos(c.theta) + 2 * dw);
    EXPECT_NEAR(c.state.force[1].y, expected, 1e-5 * kn * dw)
        << (rule == dem::ContactRule::Closest ? "closest" : "pairs");
    EXPECT_NEAR(c.state.force[1].x, 0.0, 1e-5 * kn * dw);
    if (rule == dem::ContactRule::Closest) {
      EXPECT_EQ(c.state.contact_count, 2);  // the two flanks
    }
  }
}

TEST(DemContactRule, ClosestKeepsBothFlanksOfASharpValley) {
  // theta = 30 deg, the flanks 10 nm inside reach: the corner is h = (2r - delta) / cos(theta) =
  // 46 um > 2r away and does not touch; both flanks push along their normals,
  // F_y = 2 k_n delta cos(theta): a vertex resting in a wedge, with either rule.
  const double r = 2e-5, delta = 1e-8, theta = 30.0 * 3.14159265358979323846 / 180.0;
  for (dem::ContactRule rule : {dem::ContactRule::Closest, dem::ContactRule::Pairs}) {
    Valley c = valley(rule, 30.0, (2 * r - delta) / std::cos(theta));
    const double kn = c.model.def.contact.normal_stiffness;
    EXPECT_NEAR(c.state.force[1].y, 2 * kn * delta * std::cos(theta), 1e-5 * kn * delta);
    EXPECT_NEAR(c.state.force[1].x, 0.0, 1e-5 * kn * delta);
    EXPECT_EQ(c.state.contact_count, 2);
  }
}
