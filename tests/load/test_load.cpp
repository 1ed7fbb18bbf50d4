// Friction under load (frictal/load.hpp; predict() with loads): one Hertzian asperity against its
// closed form and its loaded lift the plane's slope, two asperities whose force-resolved slope is
// computed by hand and whose loaded lift is, for constant radii, the block's minimum energy solved
// here by bisection, the envelope theorem (the energy lift's slope is the force-resolved slope plus
// the stiffness change, which the force lift leaves out), no loaded hold angle above the surfaces'
// slopes, and the zero-load limit (the loaded prediction tends to the rigid one on generated and
// measured profiles).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "frictal/generators.hpp"
#include "frictal/io.hpp"
#include "frictal/load.hpp"
#include "frictal/predict.hpp"
#include "frictal/signature.hpp"

using namespace frictal;

namespace {

constexpr double kDeg = std::numbers::pi / 180;

LoadedLiftOptions options(double modulus, double load) {
  LoadedLiftOptions o;
  o.contact_modulus = modulus;
  o.loads = {load};
  o.threads = 1;
  return o;
}

// z(x) on n points over [0, length].
template <class F>
Profile sampled(std::size_t n, double length, F&& z) {
  Profile p;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = length * double(i) / double(n - 1);
    p.x.push_back(x);
    p.z.push_back(z(x));
  }
  return p;
}

}  // namespace

TEST(LoadedLift, OneTiltedAsperityIsHertzAlongItsNormal) {
  // A parabolic bump of radius rho on a slope t, f = t x - (x - x0)^2 / (2 rho), under a straight
  // upper face of the same slope: one contact at x0 whose normal is tilted by theta = atan(t), of
  // radius R = rho / cos^3 theta (the parabola's curvature at x0), carrying F = W / cos theta along
  // its normal: delta = (3 F / (4 E* sqrt(R)))^(2/3), the block sinks v = delta / cos theta, and
  // its potential energy per unit load is h - v + (8/15) E* sqrt(R) delta^(5/2) / W.
  const double rho = 1e-3, t = 0.2, x0 = 1e-3, E = 1e9, W = 1e-3;
  const Profile lower = sampled(201, 2e-3, [&](double x) { return t * x - (x - x0) * (x - x0) / (2 * rho); });
  const Profile upper = sampled(101, 1e-3, [&](double u) { return t * u; });
  const double s = 0.5e-3;  // the upper face over [0.5, 1.5] mm
  LoadedLiftOptions o = options(E, W);
  o.max_radius = 1;  // above R (the default cap, 100 upper lengths, is too)
  auto st = loaded_state(lower, upper, s, W, o);
  ASSERT_TRUE(st) << st.error().message;
  const double theta = std::atan(t), c = std::cos(theta);
  const double R = rho / (c * c * c), F = W / c;
  const double delta = std::pow(3 * F / (4 * E * std::sqrt(R)), 2.0 / 3.0), v = delta / c;
  const double h = t * x0 - t * (x0 - s);  // d_s(x0) = f(x0) - g(x0 - s)
  EXPECT_NEAR(st->rigid_lift, h, 1e-15);
  ASSERT_EQ(std::count_if(st->contacts.begin(), st->contacts.end(), [](const HertzContact& k) { return k.force > 0; }),
            1);
  const HertzContact& k =
      *std::max_element(st->contacts.begin(), st->contacts.end(),
                        [](const HertzContact& a, const HertzContact& b) { return a.force < b.force; });
  EXPECT_NEAR(k.x, x0, 1e-12);
  EXPECT_NEAR(k.slope, theta, 1e-9);
  EXPECT_NEAR(k.radius / R, 1, 1e-6);
  EXPECT_NEAR(k.force / F, 1, 1e-9);
  EXPECT_NEAR(k.interference / delta, 1, 1e-9);
  EXPECT_NEAR((st->rigid_lift - st->height) / v, 1, 1e-9);
  const double energy = (8.0 / 15.0) * E * std::sqrt(R) * std::pow(delta, 2.5);
  EXPECT_NEAR(st->energy_lift, h - v + energy / W, 1e-9 * v);
  EXPECT_NEAR(st->energy_lift, h - 0.6 * v, 1e-9 * v);  // a single contact: the energy is 2/5 of W v
  EXPECT_NEAR(st->effective_slope, t, 1e-9);
  // The loaded lift over offsets 0.3-0.7 mm (the contact at x0 throughout, d_s(x0) = t s): every
  // piece has the plane's slope t, at 1 mN and at 1 N alike (one contact: its force is along the
  // plane's normal whatever its size).
  LiftCurve rigid;
  for (int k = 0; k <= 40; ++k) {
    rigid.offset.push_back(0.3e-3 + 1e-5 * k);
    rigid.lift.push_back(t * rigid.offset.back());
  }
  o.loads = {W, 1.0};
  auto lift = loaded_lift(lower, upper, rigid, o);
  ASSERT_TRUE(lift) << lift.error().message;
  for (std::size_t l = 0; l < 2; ++l) {
    const LiftCurve& c = lift->curves[l];
    ASSERT_GE(c.offset.size(), rigid.offset.size());
    for (std::size_t k = 0; k + 1 < c.offset.size(); ++k)
      EXPECT_NEAR((c.lift[k + 1] - c.lift[k]) / (c.offset[k + 1] - c.offset[k]), t, 1e-9) << l << " " << k;
    for (double slope : lift->slopes[l]) EXPECT_NEAR(slope, t, 1e-9);
  }
}

TEST(LoadedLift, OneTiltedAsperityOnIrregularSamplesIsHertzAlongItsNormal) {
  // The asperity above on a lower surface sampled at spacings between 0.6 and 1.4 times the mean,
  // with one vertex doubled (a zero-width edge) just outside the overlap: the spline of the
  // composite reproduces a parabola whatever the spacing (its constant second derivative solves
  // the spline's system exactly), so the contact is Hertz's as on even samples. The spline solve's
  // factors along the lower (Pair::factor) then run over uneven spacings and the zero-width edge.
  const double rho = 1e-3, t = 0.2, x0 = 1e-3, E = 1e9, W = 1e-3;
  auto f = [&](double x) { return t * x - (x - x0) * (x - x0) / (2 * rho); };
  Profile lower;
  for (std::size_t i = 0; i <= 200; ++i) {
    const double jitter = i == 0 || i == 200 ? 0.0 : 0.4 * std::sin(2.3 * double(i)) * 0.5;
    const double x = 1e-5 * (double(i) + jitter);
    lower.x.push_back(x), lower.z.push_back(f(x));
    if (i == 40) lower.x.push_back(x), lower.z.push_back(f(x));
  }
  const Profile upper = sampled(101, 1e-3, [&](double u) { return t * u; });
  const double s = 0.5e-3;
  LoadedLiftOptions o = options(E, W);
  o.max_radius = 1;
  auto st = loaded_state(lower, upper, s, W, o);
  ASSERT_TRUE(st) << st.error().message;
  const double theta = std::atan(t), c = std::cos(theta);
  const double R = rho / (c * c * c), F = W / c;
  const double delta = std::pow(3 * F / (4 * E * std::sqrt(R)), 2.0 / 3.0);
  const HertzContact& k =
      *std::max_element(st->contacts.begin(), st->contacts.end(),
                        [](const HertzContact& a, const HertzContact& b) { return a.force < b.force; });
  EXPECT_NEAR(k.x, x0, 1e-12);
  EXPECT_NEAR(k.slope, theta, 1e-9);
  EXPECT_NEAR(k.radius / R, 1, 1e-6);
  EXPECT_NEAR(k.force / F, 1, 1e-9);
  EXPECT_NEAR(k.interference / delta, 1, 1e-9);
  EXPECT_NEAR(st->effective_slope, t, 1e-9);
}

namespace {

// A pair whose composite at offset 0 is b(x) = max(c1 - (x - x1)^2 / (2 rho1), c2 - (x - x2)^2 /
// (2 rho2)) on an upper face g of slope t1 around x1 and t2 around x2 (lower = g + b): two
// asperity contacts of slopes atan(t1), atan(t2) and radii rho_i / cos^3 theta_i.
struct TwoBumps {
  Profile lower, upper;
};
TwoBumps two_bumps(double c1, double c2) {
  const double x1 = 1e-3, x2 = 3e-3, rho1 = 2e-3, rho2 = 0.5e-3, t1 = 0.25, t2 = -0.1;
  auto g = [&](double x) { return x < 2e-3 ? t1 * (x - 2e-3) : t2 * (x - 2e-3); };
  auto b = [&](double x) {
    return std::max(c1 - (x - x1) * (x - x1) / (2 * rho1), c2 - (x - x2) * (x - x2) / (2 * rho2));
  };
  TwoBumps p;
  p.upper = sampled(401, 4e-3, g);
  p.lower = sampled(401, 4e-3, [&](double x) { return g(x) + b(x); });
  return p;
}

}  // namespace

TEST(LoadedLift, TwoAsperitiesShareTheLoadAsComputedByHand) {
  // Equal touch heights: both interfere by the same vertical v, and each carries a vertical force
  // k_i v^(3/2), k_i = (4/3) E* sqrt(R_i) cos^(5/2) theta_i; so v = (W / (k1 + k2))^(2/3) and the
  // force-resolved slope is sum F_i sin theta_i / W, F_i = k_i v^(3/2) / cos theta_i.
  const double E = 2e9, W = 5e-3;
  const TwoBumps p = two_bumps(0, 0);
  auto st = loaded_state(p.lower, p.upper, 0, W, options(E, W));
  ASSERT_TRUE(st) << st.error().message;
  const double th1 = std::atan(0.25), th2 = std::atan(-0.1);
  const double R1 = 2e-3 / std::pow(std::cos(th1), 3), R2 = 0.5e-3 / std::pow(std::cos(th2), 3);
  const double k1 = (4.0 / 3.0) * E * std::sqrt(R1) * std::pow(std::cos(th1), 2.5);
  const double k2 = (4.0 / 3.0) * E * std::sqrt(R2) * std::pow(std::cos(th2), 2.5);
  const double v = std::pow(W / (k1 + k2), 2.0 / 3.0);
  const double F1 = k1 * std::pow(v, 1.5) / std::cos(th1), F2 = k2 * std::pow(v, 1.5) / std::cos(th2);
  EXPECT_NEAR((st->rigid_lift - st->height) / v, 1, 1e-9);
  EXPECT_NEAR(st->effective_slope, (F1 * std::sin(th1) + F2 * std::sin(th2)) / W, 1e-9);
  std::vector<HertzContact> loaded;
  for (const HertzContact& k : st->contacts)
    if (k.force > 0) loaded.push_back(k);
  ASSERT_EQ(loaded.size(), 2u);
  EXPECT_NEAR(loaded[0].force / F1, 1, 1e-6);
  EXPECT_NEAR(loaded[1].force / F2, 1, 1e-6);
  // The trend: with the steeper asperity a little higher, a small load rests on it alone (the
  // slope tends to t1 = 0.25); as the load grows the second takes its share and the force-resolved
  // slope falls monotonically towards the equal-height value above.
  const TwoBumps q = two_bumps(1e-9, 0);
  double last = 1;
  for (double w : {1e-9, 1e-7, 1e-5, 1e-3, 1e-1}) {
    auto sw = loaded_state(q.lower, q.upper, 0, w, options(E, w));
    ASSERT_TRUE(sw);
    if (w == 1e-9) {
      EXPECT_NEAR(sw->effective_slope, 0.25, 1e-9);
    }
    EXPECT_LT(sw->effective_slope, last + 1e-12);
    last = sw->effective_slope;
  }
  EXPECT_LT(last, 0.25);
  EXPECT_GT(last, (F1 * std::sin(th1) + F2 * std::sin(th2)) / W - 0.01);
}

TEST(LoadedLift, TwoAsperitiesOfConstantRadiiFollowTheBlocksLeastEnergy) {
  // The pair of two_bumps(0, 0) at offsets s near 0: bump i touches at the height t_i s (the upper
  // face of slope t_i slides over it; its radius stays R_i), so the rigid lift is max(t1 s, t2 s)
  // with a kink at 0, where the load passes from the second asperity (t2 = -0.1) to the first
  // (t1 = 0.25). Under W both share it over |s| of a few v / (t1 - t2). With constant radii the
  // contacts' forces derive from the block's energy, so the force lift's slope, sum F sin / sum F
  // cos, is the derivative of the least energy per unit load E(s) = min_z [z + (2/5) sum_i k_i
  // (t_i s - z)_+^(5/2) / W]: solved here by bisection on the balance sum_i k_i (t_i s - z)^(3/2)
  // = W, the loaded lift's rise between two offsets must be E's, and at s = 0 its slope the
  // force-resolved slope by hand (both heights equal, as the test above).
  const double E = 2e9, W = 5e-3, t1 = 0.25, t2 = -0.1;
  const TwoBumps p = two_bumps(0, 0);
  const double th1 = std::atan(t1), th2 = std::atan(t2);
  const double R1 = 2e-3 / std::pow(std::cos(th1), 3), R2 = 0.5e-3 / std::pow(std::cos(th2), 3);
  const double k1 = (4.0 / 3.0) * E * std::sqrt(R1) * std::pow(std::cos(th1), 2.5);
  const double k2 = (4.0 / 3.0) * E * std::sqrt(R2) * std::pow(std::cos(th2), 2.5);
  auto least_energy = [&](double s) {
    const double a = t1 * s, b = t2 * s;
    auto carried = [&](double z) {
      return k1 * std::pow(std::max(a - z, 0.0), 1.5) + k2 * std::pow(std::max(b - z, 0.0), 1.5);
    };
    double lo = std::max(a, b) - 1e-5, hi = std::max(a, b);  // carried(lo) > W > carried(hi) = 0
    for (int i = 0; i < 200; ++i) (carried(0.5 * (lo + hi)) > W ? lo : hi) = 0.5 * (lo + hi);
    const double z = 0.5 * (lo + hi);
    return z + 0.4 * (k1 * std::pow(std::max(a - z, 0.0), 2.5) + k2 * std::pow(std::max(b - z, 0.0), 2.5)) / W;
  };
  const double v = std::pow(W / (k1 + k2), 2.0 / 3.0);  // the shared sink at s = 0
  LiftCurve rigid;
  const int half = 400;
  const double step = 8 * v / (t1 - t2) / half;  // over |s| <= 8 v / (t1 - t2): both ends on one asperity
  for (int k = -half; k <= half; ++k) {
    rigid.offset.push_back(k * step);
    rigid.lift.push_back(std::max(t1, t2) * std::max(0, k) * step + std::min(t1, t2) * std::min(0, k) * step);
  }
  auto lift = loaded_lift(p.lower, p.upper, rigid, options(E, W));
  ASSERT_TRUE(lift) << lift.error().message;
  const LiftCurve& c = lift->curves[0];
  const double e0 = least_energy(c.offset.front());
  double worst = 0;
  for (std::size_t k = 0; k < c.offset.size(); ++k)
    worst = std::max(worst, std::abs((c.lift[k] - c.lift.front()) - (least_energy(c.offset[k]) - e0)));
  EXPECT_LT(worst, 1e-4 * v);
  // The ends: one contact each, the rigid slopes; the middle: the force-weighted slope by hand.
  EXPECT_NEAR((c.lift[1] - c.lift[0]) / (c.offset[1] - c.offset[0]), t2, 1e-9);
  const std::size_t m = c.offset.size() - 1;
  EXPECT_NEAR((c.lift[m] - c.lift[m - 1]) / (c.offset[m] - c.offset[m - 1]), t1, 1e-9);
  const std::size_t mid = std::size_t(std::find(c.offset.begin(), c.offset.end(), 0.0) - c.offset.begin());
  ASSERT_LT(mid, c.offset.size());
  const double F1 = k1 * std::pow(v, 1.5) / std::cos(th1), F2 = k2 * std::pow(v, 1.5) / std::cos(th2);
  EXPECT_NEAR(lift->slopes[0][mid], (F1 * std::sin(th1) + F2 * std::sin(th2)) / W, 1e-9);
}

TEST(LoadedLift, TheEnergyLiftsSlopeIsTheForceResolvedSlopePlusTheStiffnessChange) {
  // What the force lift leaves out. The envelope theorem on H_W(s) = min_z [z + sum_c (2/5) k_c(s) (z_c(s) - z)^(5/2) /
  // W], k_c = (4/3) E* sqrt(R_c) cos^(5/2) theta_c: dH_W/ds = sum_c k_c v_c^(3/2) z_c'(s) / W + sum_c (2/5) v_c^(5/2)
  // k_c'(s) / W, with z_c' = tan theta_c (d_s's derivative in s at its maximum is the contact slope): the
  // force-resolved slope sum F sin theta / sum F cos theta, plus the work of the contacts' changing stiffness as they
  // move over curved surfaces. On smooth, finely sampled surfaces (several contacts at the load) the central difference
  // of H_W over one sampling interval matches the two terms, the second from the central difference of each contact's
  // k.
  const double L = 0.02, E = 1e9, W = 2.0;
  auto fz = [](double x) {
    return 2e-5 * std::sin(2 * std::numbers::pi * x / 3e-3) + 1e-5 * std::sin(2 * std::numbers::pi * x / 1.1e-3 + 1);
  };
  auto gz = [](double u) {
    return 1.5e-5 * std::cos(2 * std::numbers::pi * u / 2.3e-3) + 0.8e-5 * std::sin(2 * std::numbers::pi * u / 0.9e-3);
  };
  const Profile lower = sampled(20001, L, fz), upper = sampled(10001, L / 2, gz);
  const double dx = L / 20000;
  auto k_of = [&](const HertzContact& c) {
    return (4.0 / 3.0) * E * std::sqrt(c.radius) * std::pow(std::cos(c.slope), 2.5);
  };
  // The contact of `state` nearest to x (the same asperity one sampling interval later).
  auto nearest = [](const LoadedState& state, double x) {
    const HertzContact* best = &state.contacts.front();
    for (const HertzContact& c : state.contacts)
      if (std::abs(c.x - x) < std::abs(best->x - x)) best = &c;
    return *best;
  };
  int several = 0;
  double largest_stiffness_term = 0;
  for (double s0 : {1.1e-3, 2.7e-3, 4.9e-3, 6.3e-3, 8.2e-3}) {
    const double s = std::round(s0 / dx) * dx;
    auto m = loaded_state(lower, upper, s, W, options(E, W));
    auto a = loaded_state(lower, upper, s - dx, W, options(E, W));
    auto b = loaded_state(lower, upper, s + dx, W, options(E, W));
    ASSERT_TRUE(m && a && b);
    const double fd = (b->energy_lift - a->energy_lift) / (2 * dx);
    double stiffness_term = 0;
    int loaded = 0;
    for (const HertzContact& c : m->contacts) {
      if (!(c.force > 0)) continue;
      ++loaded;
      const double v = c.interference / std::cos(c.slope);
      const double dk = (k_of(nearest(*b, c.x + dx)) - k_of(nearest(*a, c.x - dx))) / (2 * dx);
      stiffness_term += 0.4 * std::pow(v, 2.5) * dk / W;
    }
    several += loaded > 1;
    largest_stiffness_term = std::max(largest_stiffness_term, std::abs(stiffness_term));
    EXPECT_NEAR(fd, m->effective_slope + stiffness_term, 1e-2 * std::abs(fd) + 2e-5) << "s = " << s;
  }
  EXPECT_GE(several, 2);                    // shared loads, not only single contacts
  EXPECT_GT(largest_stiffness_term, 1e-4);  // the second term is there to be checked
}

namespace {

PredictSurface surface(Profile p, const std::string& name) {
  PredictSurface s;
  s.profile = std::move(p);
  s.name = name;
  return s;
}

// The loaded prediction at a vanishing load against the rigid one (median within 0.1 deg).
void expect_zero_load_limit(const PredictSurface& lower, const PredictSurface* upper, double load) {
  PredictOptions rigid;
  rigid.threads = 1;
  auto r = predict(lower, upper, rigid);
  ASSERT_TRUE(r) << r.error().message;
  PredictOptions o = rigid;
  o.loads = {load};
  o.lower_material = {70e9, 0.3};
  auto l = predict(lower, upper, o);
  ASSERT_TRUE(l) << l.error().message;
  EXPECT_EQ(l->model, "profile-hertz-asperity-hold");
  EXPECT_NEAR(l->friction_angle.q50 / kDeg, r->friction_angle.q50 / kDeg, 0.1) << lower.name;
  EXPECT_NEAR(l->load_curve_q50.front() / kDeg, r->friction_angle.q50 / kDeg, 0.1) << lower.name;
  EXPECT_DOUBLE_EQ(l->rigid_friction_angle, r->friction_angle.q50);
  EXPECT_DOUBLE_EQ(l->load, load);
  EXPECT_EQ(l->load_curve.size(), 7u);
  EXPECT_GT(l->load_approach, 0);
}

}  // namespace

TEST(LoadedLift, TheBoundsSkipNothingThatCounts) {
  // The loaded lift skips a region's spline solve, and a piece's maxima, where a bound shows the
  // spline stays below the contacts' reach. On two generated Fourier profiles (4000 points,
  // 0.4 mm, slopes up to tens of degrees), at loads that load several contacts (the excess slope
  // nonzero, the refinement at work), the lift with the skips is the lift of every region solved
  // in full, to 1e-12 of the lift's range, at every vertex, for every load.
  FourierSelfAffineParams f;
  f.points = 4000;
  f.length = 4e-4;
  f.rolloff_wavelength = 1e-4;
  f.short_cutoff_wavelength = 4e-7;
  f.rms_height = 1e-6;
  f.seed = 3;
  Profile a = fourier_self_affine_profile(f).value();
  f.seed = 4;
  Profile b = fourier_self_affine_profile(f).value();
  a.period.reset(), b.period.reset();
  auto sig = signature(a, b);
  ASSERT_TRUE(sig) << sig.error().message;
  auto whole = lift_curve(*sig);
  ASSERT_TRUE(whole) << whole.error().message;
  const LiftCurve rigid = cut_lift_curve(*whole, -1e-4, 1e-4);
  ASSERT_GT(rigid.offset.size(), 100u);
  LoadedLiftOptions o = options(38e9, 1e-4);
  o.loads = {1e-6, 1e-4, 1e-3};
  auto fast = loaded_lift(a, b, rigid, o);
  o.prune = false;
  auto full = loaded_lift(a, b, rigid, o);
  ASSERT_TRUE(fast && full);
  EXPECT_GT(full->refined, 0u);  // several loaded contacts somewhere: the excess is tested
  ASSERT_EQ(fast->refined, full->refined);
  for (std::size_t l = 0; l < o.loads.size(); ++l) {
    const LiftCurve &p = fast->curves[l], &q = full->curves[l];
    ASSERT_EQ(p.offset.size(), q.offset.size());
    const auto [lo, hi] = std::minmax_element(q.lift.begin(), q.lift.end());
    const double range = *hi - *lo;
    ASSERT_GT(range, 0);
    for (std::size_t k = 0; k < p.offset.size(); ++k) {
      ASSERT_EQ(p.offset[k], q.offset[k]);
      ASSERT_NEAR(p.lift[k], q.lift[k], 1e-12 * range) << "load " << o.loads[l] << " N, offset " << p.offset[k];
      ASSERT_NEAR(fast->slopes[l][k], full->slopes[l][k], 1e-12) << "load " << o.loads[l] << " N";
    }
  }
}

TEST(LoadedPrediction, AVanishingLoadGivesTheRigidPrediction) {
  // Generated WM pairs (two seeds each, D = 1.3 and 1.7), 2^12-ish points, and a piece of the
  // measured dektak-1 scan against itself: at 1 nN on aluminium the approach is picometres.
  for (double D : {1.3, 1.7}) {
    WmParams w = default_wm_params();
    w.dimension = D;
    w.n_max = 8;
    w.longest_wavelength = 1e-4;
    w.length = 1e-3;
    w.rms_height = 1e-6;
    w.seed = 3;
    auto a = wm_profile(w);
    w.seed = 4;
    auto b = wm_profile(w);
    ASSERT_TRUE(a && b);
    const PredictSurface lower = surface(*a, "wm-lower"), upper = surface(*b, "wm-upper");
    expect_zero_load_limit(lower, &upper, 1e-9);
  }
  ReadOptions ro;
  auto d = read_surface(std::string(FRICTAL_TEST_DATA) + "/profiles/dektak-1.csv", ro);
  ASSERT_TRUE(d);
  auto s = predict_surface(std::move(*d), "dektak-1");
  ASSERT_TRUE(s);
  PredictSurface piece = *s;
  piece.profile.x.resize(4000), piece.profile.z.resize(4000);
  expect_zero_load_limit(piece, nullptr, 1e-9);
}

TEST(LoadedPrediction, RefusesWhatTheModelDoesNotCover) {
  WmParams w = default_wm_params();
  w.n_max = 6;
  auto a = wm_profile(w);
  ASSERT_TRUE(a);
  const PredictSurface lower = surface(*a, "wm");
  PredictOptions o;
  o.loads = {1e-3};
  o.lower_material = {70e9, 0.3};
  o.period = a->x.back() - a->x.front();
  auto periodic = predict(lower, nullptr, o);
  ASSERT_FALSE(periodic);
  EXPECT_NE(periodic.error().message.find("non-periodic"), std::string::npos) << periodic.error().message;
  o.period = 0;
  o.loads = {-1};
  auto negative = predict(lower, nullptr, o);
  ASSERT_FALSE(negative);
  EXPECT_NE(negative.error().message.find("load -1 N"), std::string::npos);
  o.loads = {1e-3};
  o.lower_material = {0, 0.3};
  EXPECT_FALSE(predict(lower, nullptr, o));
}

TEST(LoadedPrediction, NoLoadedHoldAngleLiesAboveTheSurfacesSlopes) {
  // A contact's slope is the mean of the two surfaces' slopes where they touch, and the loaded
  // lift's slope a force-weighted mean of contact slopes: no hold angle can exceed the steepest
  // slope of either surface plus the atomic friction angle, at any load. Two Fourier profiles of
  // 2 mm (20000 points, rms 0.2 um, steepest edges 4.4 and 4.8 deg; the energy lift's stiffness
  // term put their 95 % quantile near 7 deg at 0.1 mN), with mu_a = 0 and 0.2, and two WM pairs
  // (D = 1.3, 1.7) with mu_a = 0, at 0.1 mN (the curves' loads from 1 uN to 1 mN).
  FourierSelfAffineParams f;
  f.points = 20000;
  f.length = 2e-3;
  f.rolloff_wavelength = 2e-4;
  f.short_cutoff_wavelength = 1e-6;
  f.rms_height = 2e-7;
  Profile a = fourier_self_affine_profile(f).value();
  f.seed = 2;
  Profile b = fourier_self_affine_profile(f).value();
  a.period.reset(), b.period.reset();  // two scans (the loaded lift is for a block on a scan)
  std::vector<std::pair<Profile, Profile>> pairs{{a, b}};
  for (double D : {1.3, 1.7}) {
    WmParams w = default_wm_params();
    w.dimension = D;
    w.n_max = 8;
    w.longest_wavelength = 1e-4;
    w.length = 1e-3;
    w.rms_height = 1e-6;
    w.seed = 5;
    auto p = wm_profile(w);
    w.seed = 6;
    auto q = wm_profile(w);
    ASSERT_TRUE(p && q);
    pairs.emplace_back(*p, *q);
  }
  auto has = [](const Prediction& p, const char* code) {
    return std::any_of(p.warnings.begin(), p.warnings.end(), [&](const Warning& w) { return w.code == code; });
  };
  for (const auto& [lo, up] : pairs) {
    double steepest = 0;
    for (const Profile* p : {&lo, &up})
      for (std::size_t i = 0; i + 1 < p->x.size(); ++i)
        steepest = std::max(steepest, std::abs(std::atan((p->z[i + 1] - p->z[i]) / (p->x[i + 1] - p->x[i]))));
    const PredictSurface lower = surface(lo, "lower"), upper = surface(up, "upper");
    for (double mu : {0.0, 0.2}) {
      if (mu > 0 && &lo != &pairs.front().first) continue;  // mu_a on the Fourier pair only
      for (double load : {1e-4}) {
        PredictOptions o;
        o.threads = 1;
        o.atomic_friction = mu;
        o.lower_material = {70e9, 0.3};
        o.loads = {load};
        auto p = predict(lower, &upper, o);
        ASSERT_TRUE(p) << p.error().message;
        const double bound = steepest + std::atan(mu) + 1e-9;
        EXPECT_LE(p->friction_angle.max, bound) << load << " N, mu_a " << mu << ", steepest " << steepest / kDeg;
        for (double q95 : p->load_curve_q95) EXPECT_LE(q95, bound) << load << " N, mu_a " << mu;
        EXPECT_FALSE(has(*p, "load-above-slopes"));
      }
    }
  }
}
