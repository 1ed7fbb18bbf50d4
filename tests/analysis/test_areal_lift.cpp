// The lift over two dimensions of offset (areal_lift). Expected values come from outside the code
// under test: the one-line signature (the lift's restriction), a direct evaluation written here
// with the library's plain interpolate(), and the closed form for sinusoidal grooves.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "frictal/areal.hpp"
#include "frictal/map.hpp"

namespace {
constexpr double kPi = std::numbers::pi;

frictal::Map random_map(std::size_t nx, std::size_t ny, double dx, double dy, double amp, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0, amp);
  frictal::Map m;
  m.nx = nx;
  m.ny = ny;
  m.dx = dx;
  m.dy = dy;
  m.x0 = 1e-7 * seed;
  m.y0 = -2e-7;
  for (std::size_t k = 0; k < nx * ny; ++k) m.heights.push_back(n(rng));
  return m;
}

/// Grooves at psi to x: nodes (i, j) on the map with dx = a, dy = a tan(psi) carry
/// A sin(2 pi (i - j) / m); psi = 90 deg: A sin(2 pi i / m). The groove direction (dx, dy) is a
/// lattice vector, so the lift on offsets that are lattice vectors is exact and constant along it.
frictal::Map grooves(std::size_t nx, std::size_t ny, double a, double psi, double A, int m) {
  frictal::Map f;
  f.nx = nx;
  f.ny = ny;
  f.dx = a;
  const bool across = std::abs(psi - kPi / 2) < 1e-12;
  f.dy = across ? a : a * std::tan(psi);
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      const long n = across ? long(i) : long(i) - long(j);
      f.heights.push_back(A * std::sin(2 * kPi * double(n) / m));
    }
  return f;
}

/// The groove lift at phase difference n (in-place upper = the same grooves): the max over the
/// node phases l of A [sin(2 pi l / m) - sin(2 pi (l - n) / m)] (every phase lies in the overlap).
double groove_lift(double A, int m, long n) {
  double best = -1e300;
  for (int l = 0; l < m; ++l)
    best = std::max(best, A * (std::sin(2 * kPi * l / m) - std::sin(2 * kPi * double(l - n) / m)));
  return best;
}
}  // namespace

TEST(ArealLift, RestrictionToTheLineIsTheSignature) {
  auto f = random_map(40, 36, 1e-7, 1.3e-7, 1e-8, 1);
  auto g = random_map(30, 28, 1e-7, 1.1e-7, 1e-8, 2);
  f.heights[77] = NAN;
  for (bool turn : {true, false})
    for (double a : {0.0, 0.4, kPi / 2, 2.2}) {
      frictal::ArealSignatureOptions so;
      so.turn_over_upper = turn;
      so.block = 8;
      auto line = frictal::areal_signature(f, g, a, so);
      ASSERT_TRUE(line.ok()) << line.error().message;
      frictal::ArealLiftOptions lo;
      lo.turn_over_upper = turn;
      lo.block = 8;
      lo.across_max = 3e-7;
      auto lift = frictal::areal_lift(f, g, a, lo);
      ASSERT_TRUE(lift.ok()) << lift.error().message;
      ASSERT_EQ(lift->n_along, line->offset.size());
      ASSERT_EQ(lift->n_across % 2, 1u);
      const std::size_t row = lift->n_across / 2;
      EXPECT_EQ(lift->across(row), 0.0);
      for (std::size_t i = 0; i < lift->n_along; ++i) {
        const double h = lift->lift[row * lift->n_along + i];
        if (std::isnan(line->lift[i])) {
          EXPECT_TRUE(std::isnan(h));
          continue;
        }
        EXPECT_EQ(h, line->lift[i]) << turn << " " << a << " " << i;
        EXPECT_EQ(lift->along(i), line->offset[i]);
      }
    }
}

TEST(ArealLift, EqualsADirectEvaluation) {
  // max over lower nodes p of f(p) + g at q = c_g + R (p - s - c_f) (turned over) or f(p) -
  // g(p - s) (in place), with the library's plain interpolate() on the upper map.
  auto f = random_map(24, 22, 1e-7, 1.2e-7, 1e-8, 3);
  auto g = random_map(14, 12, 0.9e-7, 1e-7, 1e-8, 4);
  for (bool turn : {true, false})
    for (double a : {0.0, 0.7}) {
      frictal::ArealLiftOptions lo;
      lo.turn_over_upper = turn;
      lo.block = 4;
      lo.step = 0.73e-7;
      lo.offset_min = -3e-7;
      lo.offset_max = 5e-7;
      lo.across_step = 0.61e-7;
      lo.across_max = 4e-7;
      auto lift = frictal::areal_lift(f, g, a, lo);
      ASSERT_TRUE(lift.ok()) << lift.error().message;
      lo.prune = false;
      auto direct = frictal::areal_lift(f, g, a, lo);
      lo.prune = true;
      lo.threads = 3;
      auto threaded = frictal::areal_lift(f, g, a, lo);
      ASSERT_TRUE(direct.ok() && threaded.ok());
      EXPECT_EQ(threaded->lift, lift->lift);
      EXPECT_LT(lift->evaluated_nodes, direct->evaluated_nodes);
      const double d[2] = {std::cos(a), std::sin(a)};
      const double cf[2] = {f.x0 + 0.5 * f.width(), f.y0 + 0.5 * f.height()};
      const double cg[2] = {g.x0 + 0.5 * g.width(), g.y0 + 0.5 * g.height()};
      std::size_t compared = 0;
      for (std::size_t k = 0; k < lift->lift.size(); ++k) {
        const auto s = lift->offset_xy(k);
        double best = -1e300;
        for (std::size_t j = 0; j < f.ny; ++j)
          for (std::size_t i = 0; i < f.nx; ++i) {
            const double px = f.x0 + double(i) * f.dx, py = f.y0 + double(j) * f.dy;
            double qx = px - s[0], qy = py - s[1], val;
            if (turn) {
              const double ax = qx - cf[0], ay = qy - cf[1], along = ax * d[0] + ay * d[1];
              qx = cg[0] + ax - 2 * along * d[0];
              qy = cg[1] + ay - 2 * along * d[1];
              val = f.at(i, j) + frictal::interpolate(g, qx, qy);
            } else {
              val = f.at(i, j) - frictal::interpolate(g, qx, qy);
            }
            if (!std::isnan(val)) best = std::max(best, val);
          }
        if (best == -1e300) {
          EXPECT_TRUE(std::isnan(lift->lift[k])) << k;
          continue;
        }
        ++compared;
        EXPECT_NEAR(lift->lift[k], best, 1e-20) << turn << " " << a << " " << k;
        EXPECT_EQ(direct->lift[k], lift->lift[k]);
      }
      EXPECT_GT(compared, lift->lift.size() / 2);
    }
}

TEST(ArealLift, MapsThatDoNotOverlapAreAnError) {
  auto f = random_map(10, 10, 1e-7, 1e-7, 1e-8, 5);
  frictal::ArealLiftOptions lo;
  lo.turn_over_upper = false;
  lo.offset_min = 5e-6;
  lo.offset_max = 6e-6;
  auto r = frictal::areal_lift(f, f, 0.0, lo);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, frictal::ErrorCode::InvalidInput);
  EXPECT_NE(r.error().message.find("overlap"), std::string::npos) << r.error().message;
  EXPECT_FALSE(frictal::areal_lift(f, f, NAN).ok());
}

namespace {
frictal::ArealLift groove_case(double psi, double A, int m, double a) {
  const frictal::Map f = grooves(100, 100, a, psi, A, m);
  // The upper face in place: the same grooves (a 50 x 50 window of f, at f's coordinates),
  // mating at s = 0.
  frictal::Map g;
  g.nx = g.ny = 50;
  g.dx = f.dx;
  g.dy = f.dy;
  g.x0 = 25 * f.dx;
  g.y0 = 25 * f.dy;
  for (std::size_t j = 0; j < 50; ++j)
    for (std::size_t i = 0; i < 50; ++i) g.heights.push_back(f.at(i + 25, j + 25));
  frictal::ArealLiftOptions lo;
  lo.turn_over_upper = false;
  lo.step = f.dx;
  lo.across_step = f.dy;
  lo.offset_min = -5 * f.dx;
  lo.offset_max = 20 * f.dx;
  lo.across_max = 12 * f.dy;
  auto lift = frictal::areal_lift(f, g, 0.0, lo);
  EXPECT_TRUE(lift.ok()) << lift.error().message;
  return std::move(*lift);
}
}  // namespace

TEST(ArealLift, SinusoidalGroovesHaveTheClosedFormLift) {
  const double A = 2e-7, a = 1e-7;
  const int m = 40;
  for (double psi_deg : {30.0, 60.0, 90.0}) {
    const double psi = psi_deg * kPi / 180;
    const frictal::ArealLift L = groove_case(psi, A, m, a);
    // The closed form at every node (phase difference i - j, or i).
    for (std::size_t k = 0; k < L.lift.size(); k += 7) {
      const long i = long(k % L.n_along) - 5, j = long(k / L.n_along) - long(L.n_across / 2);
      const long n = psi_deg == 90 ? i : i - j;
      EXPECT_NEAR(L.lift[k], groove_lift(A, m, n), 1e-20) << psi_deg << " " << k;
    }
  }
}
