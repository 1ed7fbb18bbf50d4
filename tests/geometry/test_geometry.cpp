#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "frictal/generators.hpp"
#include "frictal/geometry.hpp"

using namespace frictal;

namespace {
// Brute force: max (or min) over all edges covering x of the edge's value at x (vertical
// edges count with their extreme). Independent of the envelope algorithm.
double brute(const Curve& c, double x, bool upper) {
  double best = upper ? -INFINITY : INFINITY;
  for (std::size_t i = 0; i + 1 < c.size(); ++i) {
    double x0 = c.x[i], x1 = c.x[i + 1], z0 = c.z[i], z1 = c.z[i + 1];
    if (x0 > x1) std::swap(x0, x1), std::swap(z0, z1);
    if (x < x0 || x > x1) continue;
    double v;
    if (x0 == x1)
      v = upper ? std::max(z0, z1) : std::min(z0, z1);
    else
      v = z0 + (z1 - z0) * (x - x0) / (x1 - x0);
    best = upper ? std::max(best, v) : std::min(best, v);
  }
  return best;
}
}  // namespace

TEST(Geometry, UpperEnvelopeOfFoldedZCurveByHand) {
  // (0,0) -> (2,0) -> (1,1) -> (3,1): the top is z = 1 on [1, 3], z = 0 on [0, 1): a jump at x = 1.
  Curve c{{0, 2, 1, 3}, {0, 0, 1, 1}};
  auto up = upper_envelope(c);
  ASSERT_TRUE(up.ok()) << up.error().message;
  std::vector<double> ex{0, 1, 1, 3}, ez{0, 0, 1, 1};
  EXPECT_EQ(up->x, ex);
  EXPECT_EQ(up->z, ez);
  auto lo = lower_envelope(c);
  ASSERT_TRUE(lo.ok());
  std::vector<double> lx{0, 2, 2, 3}, lz{0, 0, 1, 1};
  EXPECT_EQ(lo->x, lx);
  EXPECT_EQ(lo->z, lz);
  EXPECT_EQ(evaluate(*up, 1.0, JumpValue::Upper), 1.0);
  EXPECT_EQ(evaluate(*up, 1.0, JumpValue::Lower), 0.0);
}

TEST(Geometry, EnvelopesMatchBruteForceOnRandomCurves) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 30; ++trial) {
    Curve c;
    double x = 0;
    for (int i = 0; i < 40; ++i) {
      x += u(rng) * 0.6 + 0.15;  // mostly forward, sometimes folding back
      c.x.push_back(x);
      c.z.push_back(u(rng));
    }
    for (bool upper : {true, false}) {
      auto e = upper ? upper_envelope(c) : lower_envelope(c);
      ASSERT_TRUE(e.ok());
      ASSERT_TRUE(validate(*e).ok()) << validate(*e).error().message;
      const double a = e->x.front(), b = e->x.back();
      for (int k = 0; k <= 500; ++k) {
        const double xs = a + (b - a) * (k + 0.37) / 501.0;
        EXPECT_NEAR(evaluate(*e, xs, upper ? JumpValue::Upper : JumpValue::Lower), brute(c, xs, upper), 1e-9)
            << "trial " << trial << " x " << xs;
      }
    }
  }
}

TEST(Geometry, FoldedKochEnvelopeMatchesBruteForce) {
  for (auto [n, deg] : {std::pair{1, 50.0}, {2, 40.0}, {3, 25.0}}) {
    KochParams p;
    p.iterations = n;
    p.alpha = deg * M_PI / 180;
    p.length = 0.03;
    auto c = koch_curve(p);
    ASSERT_TRUE(c.ok());
    // The curve does fold: some edge goes backwards in x.
    bool folds = false;
    for (std::size_t i = 0; i + 1 < c->size(); ++i) folds |= c->x[i + 1] < c->x[i];
    EXPECT_TRUE(folds) << "K" << n << " at " << deg;
    auto e = upper_envelope(*c);
    ASSERT_TRUE(e.ok());
    for (int k = 0; k < 3000; ++k) {
      const double xs = 0.03 * (k + 0.5) / 3000.0;
      EXPECT_NEAR(evaluate(*e, xs), brute(*c, xs, true), 1e-12);
    }
  }
}

TEST(Geometry, Rotate180IsAnInvolutionAndSwapsEnvelopes) {
  KochParams p;
  p.iterations = 2;
  p.alpha = 40 * M_PI / 180;
  p.length = 0.05;
  auto c = koch_curve(p);
  ASSERT_TRUE(c.ok());
  auto up = upper_envelope(*c);
  ASSERT_TRUE(up.ok());
  Profile twice = rotate180(rotate180(*up));
  ASSERT_EQ(twice.size(), up->size());
  for (std::size_t i = 0; i < up->size(); ++i) {
    EXPECT_NEAR(twice.x[i], up->x[i], 1e-15);
    EXPECT_EQ(twice.z[i], up->z[i]);
  }
  Curve cc = rotate180(rotate180(*c));
  for (std::size_t i = 0; i < c->size(); ++i) EXPECT_NEAR(cc.x[i], c->x[i], 1e-15);
  // rotate180(upper envelope of c) is the lower envelope of rotate180(c).
  auto lo = lower_envelope(rotate180(*c));
  ASSERT_TRUE(lo.ok());
  Profile r = rotate180(*up);
  for (int k = 0; k < 2000; ++k) {
    const double xs = 0.05 * (k + 0.5) / 2000.0;
    EXPECT_NEAR(evaluate(r, xs, JumpValue::Lower), evaluate(*lo, xs, JumpValue::Lower), 1e-12);
  }
}

TEST(Geometry, Rotate180InPlaceIsTheCopyToTheBit) {
  // rotate180(Profile&&) against its definition written out here: x'[i] = (a + b) - x[n - 1 - i]
  // with the ends a and b exact, z'[i] = -z[n - 1 - i], the period kept; in the profile's own
  // storage (the same buffer), and equal to the copying overload bit for bit.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> step(0.1, 2.0), height(-1.0, 1.0);
  for (const std::size_t n : {1u, 2u, 3u, 1000u, 1001u}) {
    Profile p;
    double x = 0.37;
    for (std::size_t i = 0; i < n; ++i) {
      p.x.push_back(x);
      p.z.push_back(height(rng));
      x += step(rng);
    }
    if (n % 2) p.period = 123.0;
    const Profile copy = rotate180(p);
    Profile moved = p;
    const double* buffer = moved.x.data();
    const Profile r = rotate180(std::move(moved));
    EXPECT_EQ(r.x.data(), buffer);
    ASSERT_EQ(r.size(), n);
    const double a = p.x.front(), b = p.x.back();
    for (std::size_t i = 0; i < n; ++i) {
      const double want = i == 0 ? a : i + 1 == n ? b : (a + b) - p.x[n - 1 - i];
      EXPECT_EQ(r.x[i], want) << n << " " << i;
      EXPECT_EQ(r.z[i], -p.z[n - 1 - i]);
      EXPECT_EQ(r.x[i], copy.x[i]);
      EXPECT_EQ(r.z[i], copy.z[i]);
    }
    EXPECT_EQ(r.period, p.period);
  }
}

TEST(Geometry, ValidationNamesTheProblem) {
  EXPECT_FALSE(validate(Curve{{0}, {0}}).ok());
  auto st = validate(Profile{{0, 1, NAN}, {0, 0, 0}, std::nullopt}, "f.csv");
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.error().message.find("f.csv"), std::string::npos);
  EXPECT_NE(st.error().message.find("point 3"), std::string::npos);
  auto st2 = validate(Profile{{0, 2, 1}, {0, 0, 0}, std::nullopt}, "g");
  ASSERT_FALSE(st2.ok());
  EXPECT_NE(st2.error().message.find("non-decreasing"), std::string::npos);
  EXPECT_FALSE(validate(Profile{{0, 1}, {0, 0}, 2.0}).ok());  // period longer than the profile
  EXPECT_FALSE(as_profile(Curve{{0, 2, 1}, {0, 0, 0}}).ok());
  EXPECT_FALSE(upper_envelope(Curve{{1, 1}, {0, 2}}).ok());  // zero width
}

TEST(Geometry, ResampleIsExactOnLinearPieces) {
  Profile p{{0, 1, 3}, {0, 2, 0}, std::nullopt};
  auto r = resample(p, 7);
  ASSERT_TRUE(r.ok());
  // x = 0, .5, 1, 1.5, 2, 2.5, 3 -> z = 0, 1, 2, 1.5, 1, .5, 0
  std::vector<double> ez{0, 1, 2, 1.5, 1, 0.5, 0};
  for (std::size_t i = 0; i < 7; ++i) EXPECT_NEAR(r->z[i], ez[i], 1e-15);
  EXPECT_TRUE(is_uniform(*r));
  EXPECT_FALSE(is_uniform(p));
  EXPECT_FALSE(resample(p, 1).ok());
}
