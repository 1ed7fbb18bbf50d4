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

#include <fmt/core.h>

#include "frictal/generators.hpp"
#include "frictal/io.hpp"
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

// x -> x_min + x_max - x, heights kept: the surface seen in a mirror (material still below).
frictal::Profile mirrored(const frictal::Profile& p) {
  frictal::Profile q;
  const double a = p.x.front(), b = p.x.back();
  for (std::size_t i = p.size(); i-- > 0;) {
    q.x.push_back(a + b - p.x[i]);
    q.z.push_back(p.z[i]);
  }
  q.period = p.period;
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
    // Whole blocks of equal length: the same lift, so the same answer to rounding.
    frictal::PredictOptions o;
    o.direction = dir;
    o.block_length = -1;
    o.runaway_distance = 2e-5;
    expect_same(run(a, &b, o), run(b, &a, o), 1e-9 * kDeg);
    // The stated test (a block of L_b cut from the upper surface, d from the lower one): a block
    // of b on a and a block of a on b are two samples of one test of two surfaces of the same
    // kind; each median lies within the other's 5-95 % range.
    frictal::PredictOptions s;
    s.direction = dir;
    const frictal::Prediction ab = run(a, &b, s), ba = run(b, &a, s);
    EXPECT_GE(ab.friction_angle.q50, ba.friction_angle.q05);
    EXPECT_LE(ab.friction_angle.q50, ba.friction_angle.q95);
    EXPECT_GE(ba.friction_angle.q50, ab.friction_angle.q05);
    EXPECT_LE(ba.friction_angle.q50, ab.friction_angle.q95);
  }
}

TEST(Metamorphic, TheExperimentInAMirrorIsTheSameTest) {
  // On a grid whose mirror image a + b - x is exact in binary (x_i = i 2^-22 m), with no form
  // removed (a line fitted to mirrored x rounds otherwise), the mirrored experiment is the same
  // lift to the bit, so the same answer to rounding.
  frictal::Profile a = rough(31), b = rough(32);
  for (frictal::Profile* p : {&a, &b})
    for (std::size_t i = 0; i < p->size(); ++i) p->x[i] = std::ldexp(static_cast<double>(i), -22);
  const frictal::Profile am = mirrored(a), bm = mirrored(b);
  for (double dir : {0.0, kPi}) {
    SCOPED_TRACE(dir);
    frictal::PredictOptions o, om;
    o.direction = dir;
    om.direction = kPi - dir;
    o.detrend = om.detrend = frictal::Detrend{frictal::DetrendKind::None, 0};
    expect_same(run(a, &b, o), run(am, &bm, om), 1e-9 * kDeg);
    expect_same(run(a, nullptr, o), run(am, nullptr, om), 1e-9 * kDeg);
  }
}

TEST(Metamorphic, TheMirrorOfARoundedGridAgreesWithinTheSpread) {
  // On a generic grid a + b - x rounds: the lift moves by rounding, which can flip which of two
  // equally steep stops holds a basin (seen: one basin of 615 held 6 deg apart, the mean over drops
  // 0.01 deg apart). The answer, the quantiles over drops, must agree to a hundredth of its spread.
  const frictal::Profile a = rough(31), b = rough(32);
  const frictal::Profile am = mirrored(a), bm = mirrored(b);
  for (double dir : {0.0, kPi}) {
    SCOPED_TRACE(dir);
    frictal::PredictOptions o, om;
    o.direction = dir;
    om.direction = kPi - dir;
    for (bool pair : {true, false}) {
      SCOPED_TRACE(pair ? "pair" : "self");
      const frictal::Prediction p = run(a, pair ? &b : nullptr, o), q = run(am, pair ? &bm : nullptr, om);
      const double tol = 0.01 * (p.friction_angle.q95 - p.friction_angle.q05);
      EXPECT_GT(tol, 0);
      EXPECT_NEAR(p.friction_angle.q05, q.friction_angle.q05, tol);
      EXPECT_NEAR(p.friction_angle.q50, q.friction_angle.q50, tol);
      EXPECT_NEAR(p.friction_angle.q95, q.friction_angle.q95, tol);
      EXPECT_NEAR(p.upper_bound_friction_angle, q.upper_bound_friction_angle, tol);
    }
  }
}

// The same profile written to a file three ways: x increasing in metres (columns named with their
// unit), its rows in reverse order (an instrument that exports from its far end), and in
// micrometres with the unit stated once in the header ("# units: um") instead of per column.
// Reading undoes each presentation, so the answers are the same to rounding.
TEST(Metamorphic, AProfileWrittenBackwardsOrInHeaderUnitsIsTheSameProfile) {
  const frictal::Profile a = rough(21, 1024);
  std::string fwd = "x [m],z [m]\n", back = fwd, um = "# units: um\nx,z\n";
  for (std::size_t i = 0; i < a.size(); ++i) {
    fwd += fmt::format("{:.17g},{:.17g}\n", a.x[i], a.z[i]);
    const std::size_t j = a.size() - 1 - i;
    back += fmt::format("{:.17g},{:.17g}\n", a.x[j], a.z[j]);
    um += fmt::format("{:.17g},{:.17g}\n", a.x[i] * 1e6, a.z[i] * 1e6);
  }
  std::vector<frictal::Prediction> got;
  for (const auto& [text, name] : {std::pair{fwd, "fwd.csv"}, {back, "back.csv"}, {um, "um.csv"}}) {
    SCOPED_TRACE(name);
    auto d = frictal::read_surface_bytes(text, name);
    ASSERT_TRUE(d) << d.error().message;
    auto s = frictal::predict_surface(std::move(d).value(), name);
    ASSERT_TRUE(s) << s.error().message;
    ASSERT_EQ(s->profile.size(), a.size());
    for (std::size_t i = 0; i < a.size(); i += 97) {
      EXPECT_NEAR(s->profile.x[i], a.x[i], 1e-12 * a.length());
      EXPECT_NEAR(s->profile.z[i], a.z[i], 1e-15);
    }
    const bool said_reversed = std::any_of(s->reader_warnings.begin(), s->reader_warnings.end(), [](const auto& w) {
      return w.message.find("read in reverse order") != std::string::npos;
    });
    EXPECT_EQ(said_reversed, std::string(name) == "back.csv");
    auto p = frictal::predict(*s, nullptr, {});
    ASSERT_TRUE(p) << p.error().message;
    got.push_back(*p);
  }
  expect_same(got[0], got[1], 1e-9 * kDeg);
  expect_same(got[0], got[2], 1e-9 * kDeg);
}
