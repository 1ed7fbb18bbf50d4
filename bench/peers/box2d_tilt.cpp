// Peer comparison: the tilting-block test in Box2D 2.4.1 (Debian libbox2d-dev).
// Box2D is tuned for objects of 0.1-10 m (linear slop 5 mm, polygon radius 1 cm), so the Table I
// geometry is scaled by 100 (L_b = 20 m, lambda = 1 m, h = 1 m); rigid-block friction angles do
// not depend on the scale. Blocks are unions of convex fixtures (a rectangle + one triangle per
// tooth). Detection rule as in frictal (docs/dem.md), speeds scaled by 100.
//   usage: box2d_tilt flat MU | box2d_tilt k0 ALPHA_DEG MU      (prints one JSON line)
#include <box2d/box2d.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s flat MU | k0 ALPHA_DEG MU\n", argv[0]);
    return 2;
  }
  const std::string kind = argv[1];
  const bool k0 = kind == "k0";
  const double alpha = k0 ? std::atof(argv[2]) * M_PI / 180 : 0.0;
  const double mu = std::atof(argv[k0 ? 3 : 2]);
  const double S = 100;  // scale
  const double L = 0.2 * S, lam = 0.01 * S, h = 0.01 * S;
  const int teeth = static_cast<int>(std::lround(L / lam));
  const double th = 0.5 * lam * std::tan(alpha);  // tooth height
  const double dt = 1e-3, rate = 0.05, settle = 1.0;

  b2World world(b2Vec2(0.0f, -9.81f));
  // Lower block: kinematic, origin at the pivot (its rectangle's centre).
  b2BodyDef lbd;
  lbd.type = b2_kinematicBody;
  lbd.position.Set(0.0f, static_cast<float>(-0.5 * h));
  b2Body* lower = world.CreateBody(&lbd);
  b2FixtureDef fd;
  fd.friction = static_cast<float>(mu);
  fd.density = 1.0f;
  b2PolygonShape box;
  box.SetAsBox(static_cast<float>(L / 2), static_cast<float>(h / 2));
  fd.shape = &box;
  lower->CreateFixture(&fd);
  if (k0) {
    for (int i = 0; i < teeth; ++i) {  // upward teeth on y = 0 (local y = h/2)
      b2Vec2 v[3];
      const double x0 = -L / 2 + i * lam;
      v[0].Set(static_cast<float>(x0), static_cast<float>(h / 2));
      v[1].Set(static_cast<float>(x0 + lam), static_cast<float>(h / 2));
      v[2].Set(static_cast<float>(x0 + lam / 2), static_cast<float>(h / 2 + th));
      b2PolygonShape tri;
      tri.Set(v, 3);
      fd.shape = &tri;
      lower->CreateFixture(&fd);
    }
  }
  // Upper block: downward teeth nested half a wavelength over, flat top.
  b2BodyDef ubd;
  ubd.type = b2_dynamicBody;
  const double gap = 2 * b2_polygonRadius + 0.002;
  ubd.position.Set(0.0f, static_cast<float>(th + h / 2 + gap));
  b2Body* upper = world.CreateBody(&ubd);
  box.SetAsBox(static_cast<float>(L / 2), static_cast<float>(h / 2));
  fd.shape = &box;
  upper->CreateFixture(&fd);
  if (k0) {
    for (int i = 0; i < teeth; ++i) {
      b2Vec2 v[3];
      const double x0 = -L / 2 + i * lam + lam / 2;
      v[0].Set(static_cast<float>(x0), static_cast<float>(-h / 2));
      v[1].Set(static_cast<float>(x0 + lam / 2), static_cast<float>(-h / 2 - th));
      v[2].Set(static_cast<float>(x0 + lam), static_cast<float>(-h / 2));
      b2PolygonShape tri;
      tri.Set(v, 3);
      fd.shape = &tri;
      upper->CreateFixture(&fd);
    }
  }
  long steps = 0;
  const auto t0 = std::chrono::steady_clock::now();
  auto measure = [&](double& d, double& v) {
    const b2Vec2 p = upper->GetWorldCenter();
    d = lower->GetLocalPoint(p).x;
    const b2Vec2 rel = upper->GetLinearVelocity() - lower->GetLinearVelocityFromWorldPoint(p);
    v = lower->GetLocalVector(rel).x;
  };
  for (double t = 0; t < settle; t += dt, ++steps) world.Step(static_cast<float>(dt), 8, 3);
  lower->SetAngularVelocity(static_cast<float>(-rate));
  double d0, v;
  measure(d0, v);
  const double vs = 1e-5 * S, stick_dur = 0.02;
  double low_since = settle, stick_tilt = 0, stick_d = 0, phi = -1;
  for (double t = settle; std::fabs(lower->GetAngle()) < 89 * M_PI / 180; t += dt, ++steps) {
    world.Step(static_cast<float>(dt), 8, 3);
    double d;
    measure(d, v);
    d -= d0;
    if (v <= vs) {
      if (low_since < 0) low_since = t;
      if (t - low_since >= stick_dur) {
        stick_tilt = std::fabs(lower->GetAngle());
        stick_d = d;
      }
    } else {
      low_since = -1;
    }
    if (d - stick_d >= lam) {
      phi = stick_tilt * 180 / M_PI;
      break;
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf(
      "{\"peer\":\"box2d-2.4.1\",\"case\":\"%s\",\"alpha_deg\":%g,\"mu\":%g,\"friction_angle_deg\":%.4f,"
      "\"expected_deg\":%.4f,\"steps\":%ld,\"dt_s\":%g,\"wall_time_s\":%.3f,\"us_per_step\":%.3f}\n",
      kind.c_str(), alpha * 180 / M_PI, mu, phi, (alpha + std::atan(mu)) * 180 / M_PI, steps, dt, wall,
      1e6 * wall / steps);
  return 0;
}
