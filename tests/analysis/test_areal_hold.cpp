// The lift over two dimensions of offset and the hold angle of a block that may move sideways.
// Expected values come from outside the code under test: the one-line signature (the lift's
// restriction), a direct evaluation written here with the library's plain interpolate(), closed
// forms for sinusoidal grooves and a pyramid bump, and a brute-force tilt sweep in small
// increments for random maps (against the code's exact break tilts).
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
struct GrooveCase {
  frictal::ArealLift lift;
  std::size_t cusp;  // a node at zero phase difference near the middle of the grid
};

GrooveCase groove_case(double psi, double A, int m, double a) {
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
  GrooveCase c{std::move(*lift), 0};
  c.cusp = (c.lift.n_across / 2) * c.lift.n_along + 5;  // s = 0
  return c;
}
}  // namespace

TEST(ArealHold, SinusoidalGroovesSteerBelowNinetyDegrees) {
  const double A = 2e-7, a = 1e-7;
  const int m = 40;
  for (double psi_deg : {30.0, 60.0, 90.0}) {
    const double psi = psi_deg * kPi / 180;
    GrooveCase c = groove_case(psi, A, m, a);
    const frictal::ArealLift& L = c.lift;
    // The lift on the grid is the closed form at every node (phase difference i - j, or i).
    for (std::size_t k = 0; k < L.lift.size(); k += 7) {
      const long i = long(k % L.n_along) - 5, j = long(k / L.n_along) - long(L.n_across / 2);
      const long n = psi_deg == 90 ? i : i - j;
      EXPECT_NEAR(L.lift[k], groove_lift(A, m, n), 1e-20) << psi_deg << " " << k;
    }
    frictal::ArealHoldOptions o;
    o.runaway_distance = 0.25 * m * a;  // a quarter of the period along d
    auto free = frictal::areal_hold_angle(L, c.cusp, o);
    o.lateral = frictal::LateralMotion::Locked;
    auto locked = frictal::areal_hold_angle(L, c.cusp, o);
    ASSERT_TRUE(free.ok() && locked.ok());
    EXPECT_NEAR(L.lift[free->rest], 0, 1e-20);  // at a cusp (it may have moved along the groove)
    // Locked: the forward slope at the cusp, h(1) / a = A sin(2 pi / m) / a, which is A k sin(psi)
    // (k sin psi = 2 pi / (m a), the wavenumber along d) to O((2 pi / m)^2).
    const double locked_expected = std::atan(A * std::sin(2 * kPi / m) / a);
    EXPECT_NEAR(locked->hold_angle, locked_expected, 1e-12) << psi_deg;
    const double k_along = 2 * kPi / (m * a), k = k_along / std::sin(psi);
    EXPECT_NEAR(locked->hold_angle, std::atan(A * k * std::sin(psi)), 0.01 * std::atan(A * k * std::sin(psi)));
    if (psi_deg < 90) {
      EXPECT_NEAR(free->hold_angle, 0.0, 1e-9) << psi_deg;
      EXPECT_NEAR(free->steering, psi, 1e-12) << psi_deg;  // along the grooves
    } else {
      EXPECT_NEAR(free->hold_angle, locked->hold_angle, 1e-12);
      EXPECT_NEAR(free->steering, 0, 1e-12);
    }
    EXPECT_FALSE(free->ran_off_end);
    // With Coulomb friction mu_a the steered block holds until the load's component along the
    // grooves leaves the cone: sin(beta) cos(psi) = sin(atan(mu_a)); the locked one adds atan(mu_a).
    o.atomic_friction = 0.1;
    auto locked_mu = frictal::areal_hold_angle(L, c.cusp, o);
    o.lateral = frictal::LateralMotion::Free;
    auto free_mu = frictal::areal_hold_angle(L, c.cusp, o);
    ASSERT_TRUE(free_mu.ok() && locked_mu.ok());
    EXPECT_NEAR(locked_mu->hold_angle, locked_expected + std::atan(0.1), 1e-12);
    if (psi_deg < 90)
      EXPECT_NEAR(free_mu->hold_angle, std::asin(std::sin(std::atan(0.1)) / std::cos(psi)), 1e-12) << psi_deg;
    else
      EXPECT_NEAR(free_mu->hold_angle, locked_mu->hold_angle, 1e-12);
  }
}

TEST(ArealHold, FlatFaceWithAPyramidBump) {
  // Upper face: flat with one downward tip taller than the relief, in place, so the lift is the
  // lower face seen by the tip: h(s) = f(tip + s) + T. Lower face: flat with a square pyramid
  // turned 45 deg (z = H - sigma (|x - xb| + |y - yb|), foot K nodes from the apex). Its front
  // faces run at 45 deg to d: a free block steers along the foot (0 deg); a locked one climbs
  // the face of slope sigma along d: atan(sigma).
  const double a = std::ldexp(1.0, -23), sigma = 0.3;  // binary steps: node positions exact
  const int K = 6;
  const double H = sigma * K * a;
  frictal::Map f;
  f.nx = 80;
  f.ny = 61;
  f.dx = f.dy = a;
  const int ib = 40, jb = 30;
  for (std::size_t j = 0; j < f.ny; ++j)
    for (std::size_t i = 0; i < f.nx; ++i)
      f.heights.push_back(std::max(0.0, H - sigma * a * (std::abs(int(i) - ib) + std::abs(int(j) - jb))));
  frictal::Map g;
  g.nx = g.ny = 9;
  g.dx = g.dy = a;
  g.x0 = g.y0 = -4 * a;  // the tip at (0, 0) over the lower node (0, 0) at s = 0
  g.heights.assign(81, 0.0);
  g.heights[40] = -10 * H;
  frictal::ArealLiftOptions lo;
  lo.turn_over_upper = false;
  lo.step = lo.across_step = a;
  lo.offset_min = 4 * a;
  lo.offset_max = 75 * a;
  lo.across_max = 20 * a;  // s_y = 30 a +- 20 a: shift the rows by y0 instead
  g.y0 += 30 * a;
  auto lift = frictal::areal_lift(f, g, 0.0, lo);
  ASSERT_TRUE(lift.ok()) << lift.error().message;
  const frictal::ArealLift& L = lift.value();
  for (std::size_t k = 0; k < L.lift.size(); ++k) {
    const std::size_t i = 4 + k % L.n_along, j = 30 - 20 + k / L.n_along;
    EXPECT_NEAR(L.lift[k], f.at(i, j) + 10 * H, 1e-20) << k;
  }
  auto node = [&](int i, int j) { return std::size_t(j - 10) * L.n_along + std::size_t(i - 4); };
  frictal::ArealHoldOptions o;
  o.runaway_distance = 3 * a;
  for (int dj : {0, 2, -3}) {
    const std::size_t foot = node(ib - K + std::abs(dj), jb + dj);
    auto free = frictal::areal_hold_angle(L, foot, o);
    ASSERT_TRUE(free.ok());
    EXPECT_EQ(free->rest, foot);
    EXPECT_EQ(free->hold_angle, 0.0) << dj;
    EXPECT_NEAR(std::abs(free->steering), kPi / 4, 1e-12);
    o.lateral = frictal::LateralMotion::Locked;
    auto locked = frictal::areal_hold_angle(L, foot, o);
    o.lateral = frictal::LateralMotion::Free;
    ASSERT_TRUE(locked.ok());
    EXPECT_NEAR(locked->hold_angle, std::atan(sigma), 1e-12) << dj;
  }
  // A drop on the pyramid rests at its foot; every drop of a free block runs away at 0 deg.
  auto on_face = frictal::areal_hold_angle(L, node(ib - 2, jb + 1), o);
  ASSERT_TRUE(on_face.ok());
  EXPECT_EQ(L.lift[on_face->rest], 10 * H);
  auto dist = frictal::areal_hold_distribution(L, o);
  ASSERT_TRUE(dist.ok()) << dist.error().message;
  EXPECT_EQ(dist->hold.max, 0.0);
  // Not dropped on: the last D along d, and D from the lateral edges.
  EXPECT_EQ(dist->drops, (L.n_along - 3) * (L.n_across - 6));
  o.lateral = frictal::LateralMotion::Locked;
  auto dist_locked = frictal::areal_hold_distribution(L, o);
  ASSERT_TRUE(dist_locked.ok());
  EXPECT_NEAR(dist_locked->hold.max, std::atan(sigma), 1e-12);
  EXPECT_EQ(dist_locked->hold.min, 0.0);
}

namespace {
/// Brute force: the same moves, the tilt raised in increments of `dbeta` from zero; at every
/// increment the block descends (largest F.w / |w| above sin(atan(mu_a))) until it stops. The
/// run-away is read at the first increment whose descent goes D along d from the last stop.
struct Brute {
  double hold;
  std::size_t rest;
};
Brute brute_force(const frictal::ArealLift& L, std::size_t start, double D, double mu, bool free, double dbeta) {
  const double s0 = std::sin(std::atan(mu));
  std::vector<std::pair<int, int>> moves = {{1, 0}, {-1, 0}};
  if (free) moves = {{1, 0}, {1, 1}, {1, -1}, {0, 1}, {0, -1}, {-1, 0}, {-1, 1}, {-1, -1}};
  auto next = [&](std::size_t k, double beta, double thr) -> std::size_t {
    std::size_t best = SIZE_MAX;
    double bd = thr;
    const long i = long(k % L.n_along), j = long(k / L.n_along);
    for (auto [di, dj] : moves) {
      const long ni = i + di, nj = j + dj;
      if (ni < 0 || nj < 0 || ni >= long(L.n_along) || nj >= long(L.n_across)) continue;
      const std::size_t n = std::size_t(nj) * L.n_along + std::size_t(ni);
      if (std::isnan(L.lift[n])) continue;
      const double du = di * L.step, dv = dj * L.across_step, dh = L.lift[n] - L.lift[k];
      const double dr = (std::sin(beta) * du - std::cos(beta) * dh) / std::sqrt(du * du + dv * dv + dh * dh);
      if (dr > bd) {
        bd = dr;
        best = n;
      }
    }
    return best;
  };
  std::size_t k = start;
  for (std::size_t n; (n = next(k, 0, 0)) != SIZE_MAX;) k = n;
  Brute b{0, k};
  if (k % L.n_along == L.n_along - 1) {  // at rest on the last column: runs off as onto a flat
    b.hold = std::atan(mu);
    return b;
  }
  std::size_t stop = k;
  for (double beta = dbeta; beta < kPi / 2; beta += dbeta) {
    for (std::size_t n; (n = next(k, beta, s0)) != SIZE_MAX;) {
      k = n;
      if (L.along(k % L.n_along) - L.along(stop % L.n_along) >= D - 1e-9 * L.step || k % L.n_along == L.n_along - 1) {
        b.hold = beta;
        return b;
      }
    }
    stop = k;
  }
  b.hold = kPi / 2;
  return b;
}
}  // namespace

TEST(ArealHold, ExactBreakTiltsMatchABruteForceTiltSweep) {
  std::size_t cases = 0, agree = 0;
  for (unsigned seed = 10; seed < 14; ++seed) {
    auto f = random_map(22, 20, 1e-7, 1e-7, 2e-8, seed);
    auto g = random_map(10, 9, 1e-7, 1e-7, 2e-8, seed + 100);
    frictal::ArealLiftOptions lo;
    lo.across_max = 4e-7;
    lo.offset_max = 9e-7;
    auto lift = frictal::areal_lift(f, g, 0.3 * seed, lo);
    ASSERT_TRUE(lift.ok()) << lift.error().message;
    for (double mu : {0.0, 0.15})
      for (bool free : {true, false})
        for (std::size_t start = 0; start < lift->lift.size(); start += 7) {
          if (std::isnan(lift->lift[start])) continue;
          frictal::ArealHoldOptions o;
          o.runaway_distance = 2.5e-7;
          o.atomic_friction = mu;
          o.lateral = free ? frictal::LateralMotion::Free : frictal::LateralMotion::Locked;
          auto exact = frictal::areal_hold_angle(*lift, start, o);
          ASSERT_TRUE(exact.ok());
          const double dbeta = 2e-5;
          const Brute b = brute_force(*lift, start, o.runaway_distance, mu, free, dbeta);
          ++cases;
          EXPECT_EQ(b.rest, exact->rest);
          // The sweep reads the first increment past the exact break tilt.
          if (b.hold >= exact->hold_angle && b.hold <= exact->hold_angle + dbeta * 1.0001)
            ++agree;
          else
            ADD_FAILURE() << seed << " mu " << mu << " free " << free << " start " << start << " exact "
                          << exact->hold_angle << " brute " << b.hold << " slips " << exact->slips << " ran_off "
                          << exact->ran_off_end << " path " << exact->path.size();
        }
  }
  EXPECT_GT(cases, 100u);
  EXPECT_EQ(agree, cases);
}

TEST(ArealHold, DistributionIsTheDropsHoldAngles) {
  auto f = random_map(26, 24, 1e-7, 1e-7, 2e-8, 21);
  auto g = random_map(12, 12, 1e-7, 1e-7, 2e-8, 22);
  frictal::ArealLiftOptions lo;
  lo.across_max = 5e-7;
  auto lift = frictal::areal_lift(f, g, 0.5, lo);
  ASSERT_TRUE(lift.ok());
  frictal::ArealHoldOptions o;
  o.runaway_distance = 3e-7;
  auto dist = frictal::areal_hold_distribution(*lift, o);
  ASSERT_TRUE(dist.ok()) << dist.error().message;
  // Drop by drop with areal_hold_angle: the same angles, mean and extremes.
  std::vector<double> all;
  for (std::size_t k = 0; k < lift->lift.size(); ++k) {
    const double u = lift->along(k % lift->n_along);
    if (std::isnan(lift->lift[k]) || u > dist->drop_max + 1e-15 ||
        std::abs(lift->across(k / lift->n_along)) > dist->across_max + 1e-15)
      continue;
    auto h = frictal::areal_hold_angle(*lift, k, o);
    ASSERT_TRUE(h.ok());
    all.push_back(h->hold_angle);
  }
  ASSERT_EQ(all.size(), dist->drops);
  double mean = 0;
  for (double v : all) mean += v;
  mean /= double(all.size());
  std::sort(all.begin(), all.end());
  EXPECT_NEAR(dist->hold.mean, mean, 1e-12);
  EXPECT_EQ(dist->hold.min, all.front());
  EXPECT_EQ(dist->hold.max, all.back());
  EXPECT_EQ(dist->hold.q50, all[std::size_t(std::ceil(0.5 * double(all.size()))) - 1]);
  o.threads = 3;
  auto threaded = frictal::areal_hold_distribution(*lift, o);
  ASSERT_TRUE(threaded.ok());
  EXPECT_EQ(threaded->angle, dist->angle);
}

TEST(ArealHold, BadInputNamesTheValue) {
  auto f = random_map(12, 12, 1e-7, 1e-7, 2e-8, 31);
  auto lift = frictal::areal_lift(f, f, 0.0);
  ASSERT_TRUE(lift.ok());
  frictal::ArealHoldOptions o;
  auto r = frictal::areal_hold_angle(*lift, 0, o);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("run-away distance 0"), std::string::npos) << r.error().message;
  o.runaway_distance = 1e-7;
  EXPECT_FALSE(frictal::areal_hold_angle(*lift, lift->lift.size(), o).ok());
  o.atomic_friction = -1;
  EXPECT_FALSE(frictal::areal_hold_angle(*lift, 0, o).ok());
  auto node = frictal::areal_lift_node(*lift, 1.0, 0.0);
  ASSERT_FALSE(node.ok());
  EXPECT_NE(node.error().message.find("expected u in"), std::string::npos) << node.error().message;
  EXPECT_FALSE(frictal::areal_lift_node(*lift, NAN, 0.0).ok());
  auto inside = frictal::areal_lift_node(*lift, lift->along(3), lift->across(1));
  ASSERT_TRUE(inside.ok());
  EXPECT_EQ(*inside, 1 * lift->n_along + 3);
}

TEST(ArealHold, LockedGridRuleEqualsTheOneDimensionalHoldAngle) {
  // The grid's Locked process against hold_angle() of hold.hpp on the LiftCurve of the line
  // (the 1D rule's own implementation: record chains on a piecewise-linear curve).
  std::size_t compared = 0;
  for (unsigned seed = 40; seed < 43; ++seed) {
    auto f = random_map(30, 26, 1e-7, 1e-7, 2e-8, seed);
    auto g = random_map(12, 12, 1e-7, 1e-7, 2e-8, seed + 50);
    frictal::ArealLiftOptions lo;
    lo.across_max = 3e-7;
    auto lift = frictal::areal_lift(f, g, 0.2 * seed, lo);
    ASSERT_TRUE(lift.ok());
    for (double mu : {0.0, 0.2}) {
      frictal::ArealHoldOptions o;
      o.runaway_distance = 2.5e-7;
      o.atomic_friction = mu;
      o.lateral = frictal::LateralMotion::Locked;
      for (std::size_t k = 0; k < lift->lift.size(); k += 3) {
        if (std::isnan(lift->lift[k])) continue;
        auto grid = frictal::areal_hold_angle(*lift, k, o);
        ASSERT_TRUE(grid.ok());
        auto line = frictal::areal_locked_hold_angle(*lift, grid->rest, o);
        ASSERT_TRUE(line.ok()) << line.error().message;
        EXPECT_NEAR(line->hold_angle, grid->hold_angle, 1e-12) << seed << " " << k << " " << mu;
        EXPECT_NEAR(line->rest_offset, lift->along(grid->rest % lift->n_along), 1e-18);
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 100u);
}
