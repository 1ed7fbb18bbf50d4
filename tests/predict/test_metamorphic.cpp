// Metamorphic tests of the prediction: one pair of surfaces presented in different ways must give
// the same answer. Where the presentation is an exact symmetry of the tilt test (other units, the
// two blocks swapped, the whole experiment seen in a mirror) the answer must be the same to
// rounding; where it removes or adds information (a crop, spikes) it must stay within the
// answer's own spread (the 5-95 % range over drops).
//
// Why each transformation is the same test (upper face g = the upper surface turned over,
// h(s) = max_x [f(x) - g(x - s)] the lift of the upper block at offset s):
//  - units: scaling every length (x, z, the run-away distance) by k scales h and s alike, so
//    every slope dh/ds, hence every angle, is unchanged;
//  - swap: with the lower surface A and the upper B turned over, f(x) - g(x - s) = A(x) + B(s - x)
//    + c; swapping the blocks gives B(x) + A(s - x) + c', the same function of s after x -> s - x:
//    the same lift, the same sliding direction;
//  - mirror: x -> -x for both surfaces commutes with turning the upper one over, so the mirrored
//    pair sliding the other way is the original experiment seen in a mirror.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "frictal/generators.hpp"
#include "frictal/predict.hpp"

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180;

frictal::PredictSurface surface(frictal::Profile p, const std::string& name) {
  frictal::PredictSurface s;
  s.profile = std::move(p);
  s.name = name;
  return s;
}

frictal::Profile rough(std::uint64_t seed, std::size_t points = 4096) {
  frictal::SelfAffineParams sp;
  sp.points = points;
  sp.length = 1e-3;
  sp.hurst = 0.8;
  sp.rms_height = 1e-6;
  sp.seed = seed;
  auto p = frictal::self_affine_profile(sp);
  EXPECT_TRUE(p) << (p ? "" : p.error().message);
  return *p;
}

frictal::Profile scaled(const frictal::Profile& p, double k) {
  frictal::Profile q = p;
  for (double& x : q.x) x *= k;
  for (double& z : q.z) z *= k;
  if (q.period) *q.period *= k;
  return q;
}

frictal::Prediction run(const frictal::Profile& lower, const frictal::Profile* upper, frictal::PredictOptions o = {}) {
  frictal::PredictSurface l = surface(lower, "lower");
  frictal::PredictSurface u;
  if (upper) u = surface(*upper, "upper");
  auto p = frictal::predict(l, upper ? &u : nullptr, o);
  EXPECT_TRUE(p) << (p ? "" : p.error().message);
  return p ? *p : frictal::Prediction{};
}

// The same distribution over drops, to `tol` (rad).
void expect_same(const frictal::Prediction& a, const frictal::Prediction& b, double tol) {
  EXPECT_NEAR(a.friction_angle.q50, b.friction_angle.q50, tol);
  EXPECT_NEAR(a.friction_angle.q05, b.friction_angle.q05, tol);
  EXPECT_NEAR(a.friction_angle.q95, b.friction_angle.q95, tol);
  EXPECT_NEAR(a.friction_angle.mean, b.friction_angle.mean, tol);
  EXPECT_NEAR(a.upper_bound_friction_angle, b.upper_bound_friction_angle, tol);
  EXPECT_EQ(a.drops, b.drops);
}

}  // namespace

TEST(Metamorphic, OtherUnitsGiveTheSameAnswer) {
  const frictal::Profile a = rough(11), b = rough(12);
  const frictal::Prediction m = run(a, &b);
  for (double k : {1e-3, 1e3, 25.4e-3}) {  // the same heights read in mm, km, inches
    SCOPED_TRACE(k);
    const frictal::Profile ak = scaled(a, k), bk = scaled(b, k);
    const frictal::Prediction p = run(ak, &bk);
    expect_same(m, p, 1e-9 * kDeg);
    EXPECT_NEAR(p.runaway_distance, k * m.runaway_distance, 1e-9 * k * m.runaway_distance);
  }
}

TEST(Metamorphic, SwappingTheBlocksIsTheSameTest) {
  const frictal::Profile a = rough(21), b = rough(22);
  for (double dir : {0.0, kPi}) {
    SCOPED_TRACE(dir);
    frictal::PredictOptions o;
    o.direction = dir;
    expect_same(run(a, &b, o), run(b, &a, o), 1e-9 * kDeg);
  }
}
