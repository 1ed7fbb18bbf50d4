// The signature of spheropolygons (SignatureOptions::spheroradius > 0): against a dense numerical
// dilation of the lower face written here from the definition, against closed-form cases, and
// r = 0 against the rigid signature.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <random>

#include "cli/cli_runner.hpp"
#include "frictal/generators.hpp"
#include "frictal/signature.hpp"

using namespace frictal;

namespace {
double deg(double d) { return d * M_PI / 180; }
double todeg(double r) { return r * 180 / M_PI; }

Profile koch(int n, double a_deg, double length = 0.2) {
  KochParams p;
  p.iterations = n;
  p.alpha = deg(a_deg);
  p.wavelength = 0.01;
  p.length = length;
  return *koch_profile(p);
}

Profile random_polyline(unsigned seed, int n, double length, double height) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  Profile p;
  for (int i = 0; i < n; ++i) {
    const double x = (i == 0) ? 0 : (i + 1 == n ? length : length * (i + 0.3 * (u(rng) - 0.5)) / (n - 1));
    p.x.push_back(x);
    p.z.push_back(height * u(rng));
  }
  return p;
}

// Second method, from the definition: the lower block's region (below its face) dilated by a
// disk of radius R = 2r has the upper envelope D(x) = sup of z over the disks centred on the
// face. Per segment that is the segment's offset by R along its normal where the foot of x
// falls on the segment, else the disk of the nearer end. The upper core (above g, shifted by s)
// must stay on or above D: h(s) = max over x of D(x) - g(x - s), maximised here over a dense
// grid of x plus every vertex of g.
struct DenseDilation {
  Profile lower, upper;  // upper already rotated and shifted into the lower frame (offset 0)
  double R;
  double D(double x) const {
    double best = -INFINITY;
    auto disk = [&](double px, double pz) {
      const double u = x - px;
      if (std::abs(u) <= R) best = std::max(best, pz + std::sqrt(R * R - u * u));
    };
    for (std::size_t i = 0; i + 1 < lower.size(); ++i) {
      const double x0 = lower.x[i], z0 = lower.z[i], x1 = lower.x[i + 1], z1 = lower.z[i + 1];
      disk(x0, z0);
      disk(x1, z1);
      const double dx = x1 - x0, dz = z1 - z0, len = std::hypot(dx, dz);
      if (dx <= 0) continue;
      const double nx = -dz / len, nz = dx / len;  // upward normal
      const double ox0 = x0 + R * nx, ox1 = x1 + R * nx;
      if (x >= ox0 && x <= ox1) best = std::max(best, z0 + R * nz + dz / dx * (x - ox0));
    }
    return best;
  }
  double lift(double s, double dx) const {
    const double a = std::max(lower.x.front() - R, upper.x.front() + s);
    const double b = std::min(lower.x.back() + R, upper.x.back() + s);
    double best = -INFINITY;
    auto at = [&](double x) { best = std::max(best, D(x) - evaluate(upper, x - s)); };
    for (double x = a; x <= b; x += dx) at(x);
    at(b);
    for (double u : upper.x)
      if (u + s >= a && u + s <= b) at(u + s);
    return best;
  }
};

DenseDilation dense(const Profile& lower, const Profile& upper_rotated, double r) {
  DenseDilation d{lower, upper_rotated, 2 * r};
  const double shift = lower.x.front() - d.upper.x.front();
  for (double& v : d.upper.x) v += shift;
  return d;
}
}  // namespace

// (a) Against the dense numerical dilation: lift at every listed offset, the mean slope of h
// over short windows (finite differences) inside the range of the exact one-sided slopes there,
// and theta_max: no finite-difference slope above it, and one reaching it.
TEST(Sphero, MatchesDenseNumericalDilation) {
  const Profile lower = random_polyline(7, 10, 0.5, 0.08);
  const Profile upper = rotate180(random_polyline(11, 9, 0.45, 0.06));
  const double r = 0.015;
  const DenseDilation B = dense(lower, upper, r);
  const double dx = 2e-5;  // grid of x: lift error about dx^2 / R, below 1e-8 m

  SignatureOptions o;
  o.spheroradius = r;
  o.offset_min = 0.02;
  o.offset_max = 0.2;
  auto res = signature(lower, upper, o);
  ASSERT_TRUE(res.ok()) << res.error().message;
  EXPECT_EQ(res->spheroradius, r);
  ASSERT_GT(res->offset.size(), 10u);
  for (std::size_t i = 0; i < res->offset.size(); i += 3)
    EXPECT_NEAR(res->lift[i], B.lift(res->offset[i], dx), 2e-7) << "offset " << res->offset[i];

  // Finite differences over windows [s - e, s + e]: the mean slope lies within the exact
  // slopes listed in the window (h' is monotone between breakpoints, all of which are listed).
  const double e = 2e-4;
  for (double s = 0.03; s < 0.19; s += 0.0117) {
    const double fd = todeg(std::atan((B.lift(s + e, dx) - B.lift(s - e, dx)) / (2 * e)));
    SignatureOptions w = o;
    w.offset_min = s - e;
    w.offset_max = s + e;
    auto win = signature(lower, upper, w);
    ASSERT_TRUE(win.ok());
    double lo = INFINITY, hi = -INFINITY;
    for (std::size_t i = 0; i < win->offset.size(); ++i) {
      if (i > 0) lo = std::min(lo, win->theta_left[i]), hi = std::max(hi, win->theta_left[i]);
      if (i + 1 < win->offset.size()) lo = std::min(lo, win->theta_right[i]), hi = std::max(hi, win->theta_right[i]);
    }
    EXPECT_GE(fd, todeg(lo) - 0.02) << "offset " << s;
    EXPECT_LE(fd, todeg(hi) + 0.02) << "offset " << s;
  }

  // theta_max: scan the whole range coarsely and the neighbourhood of the maximum finely.
  const double tmax = todeg(res->theta_max_forward), tmin = -todeg(res->theta_max_backward);
  const double h = 5e-5;
  double fd_max = -INFINITY, fd_min = INFINITY;
  auto scan = [&](double a, double b, double step) {
    for (double s = std::max(a, o.offset_min); s + h <= std::min(b, o.offset_max); s += step) {
      const double fd = todeg(std::atan((B.lift(s + h, dx) - B.lift(s, dx)) / h));
      fd_max = std::max(fd_max, fd);
      fd_min = std::min(fd_min, fd);
    }
  };
  scan(o.offset_min, o.offset_max, 2.3e-3);
  EXPECT_LE(fd_max, tmax + 0.02);
  EXPECT_GE(fd_min, tmin - 0.02);
  scan(res->offset_at_forward - 1e-3, res->offset_at_forward + 1e-3, 2e-5);
  scan(res->offset_at_backward - 1e-3, res->offset_at_backward + 1e-3, 2e-5);
  EXPECT_NEAR(fd_max, tmax, 0.1);  // the forward difference loses at most h / R rad at an arc's start
  EXPECT_NEAR(fd_min, tmin, 0.1);
}

// (b) Closed-form cases.
TEST(Sphero, FlatSurfaceLiftsByTwoRadiiWithZeroSlope) {
  Profile f{{0, 0.5, 1}, {0, 0, 0}, std::nullopt};
  SignatureOptions o;
  o.spheroradius = 1e-3;
  auto r = self_signature(f, o);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->theta_max_forward, 0);
  EXPECT_EQ(r->theta_max_backward, 0);
  for (std::size_t i = 0; i < r->offset.size(); ++i) {
    EXPECT_NEAR(r->lift[i], 2e-3, 1e-15);  // cores 2r apart
    EXPECT_EQ(r->theta[i], 0);
  }
  EXPECT_EQ(r->contact_slope_std, 0);
}

// K0 (triangles of base angle alpha, wavelength lambda): the rigid lift h0 is a triangle wave of
// slopes +-tan(alpha), ridges (tip on tip) at s = 0 mod lambda. With R = 2r the ridge becomes an
// arc of radius R tangent to the flanks' offsets at s = +-R sin(alpha): there the contact slope
// is -asin(s / R) and the lift h0(0) + sqrt(R^2 - s^2). While R sin(alpha) < lambda / 2 the flanks
// survive and theta_max = alpha; beyond, neighbouring arcs meet at s = lambda / 2 and
// theta_max = asin(lambda / (2R)) = asin(lambda / (4r)).
TEST(Sphero, KochK0SmallRadiusKeepsAlpha) {
  SignatureOptions o;
  o.spheroradius = 5e-5;
  auto r = self_signature(koch(0, 20), o);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_NEAR(todeg(r->theta_max_forward), 20, 1e-9);
  EXPECT_NEAR(todeg(r->theta_max_backward), 20, 1e-9);
  EXPECT_TRUE(r->exact);
}

TEST(Sphero, KochK0RoundedTipsNearTipOnTip) {
  const double a = deg(20), rad = 1e-3, R = 2 * rad;
  const Profile k = koch(0, 20);
  const auto [zmin, zmax] = std::minmax_element(k.z.begin(), k.z.end());
  const double h0_tip = 2 * (*zmax - *zmin);  // tip on tip: both triangle heights
  for (double s0 : {rad * std::sin(a), -rad * std::sin(a), 0.3 * R * std::sin(a)}) {
    SignatureOptions o;
    o.spheroradius = rad;
    o.offset_min = s0;
    o.offset_max = s0 + 1e-3;
    auto r = self_signature(k, o);
    ASSERT_TRUE(r.ok()) << r.error().message;
    ASSERT_DOUBLE_EQ(r->offset.front(), s0);
    EXPECT_NEAR(r->theta.front(), -std::asin(s0 / R), 1e-12) << s0;  // s0 = r sin(a): -asin(sin(a) / 2)
    EXPECT_NEAR(r->lift.front(), h0_tip + std::sqrt(R * R - s0 * s0), 1e-12) << s0;
  }
  // The contact slope falls below alpha only within |s| < 2 r sin(alpha) of tip on tip.
  SignatureOptions o;
  o.spheroradius = rad;
  o.offset_min = -0.004;
  o.offset_max = 0.004;
  auto r = self_signature(k, o);
  ASSERT_TRUE(r.ok());
  for (std::size_t i = 0; i < r->offset.size(); ++i) {
    const double s = r->offset[i];
    if (std::abs(s) > R * std::sin(a) + 1e-9) {
      EXPECT_NEAR(std::abs(r->theta[i]), a, 1e-9) << s;
    } else if (std::abs(s) < R * std::sin(a) - 1e-9) {
      EXPECT_LT(std::abs(r->theta[i]), a) << s;
    }
  }
}

TEST(Sphero, KochK0LargeRadiusArcsMeet) {
  // lambda = 0.01 m, alpha = 20 deg: arcs meet once 4 r sin(alpha) > lambda, i.e. r > 7.31 mm.
  SignatureOptions o;
  o.spheroradius = 0.01;
  auto r = self_signature(koch(0, 20), o);
  ASSERT_TRUE(r.ok()) << r.error().message;
  const double expect = std::asin(0.01 / (4 * 0.01));  // 14.4775 deg
  EXPECT_NEAR(r->theta_max_forward, expect, 1e-12);
  EXPECT_NEAR(r->theta_max_backward, expect, 1e-12);
  EXPECT_NEAR(std::fmod(r->offset_at_forward + 0.01, 0.01), 0.005, 1e-9);
}

TEST(Sphero, SawtoothFlanksStayTheMaximumForSmallRadius) {
  // Rise 30 deg over 0.7 lambda; the fall flank has atan(0.7 tan 30 / 0.3) = 53.41 deg.
  SawtoothParams p;
  p.rise_angle = deg(30);
  p.rise_fraction = 0.7;
  auto saw = sawtooth_profile(p);
  ASSERT_TRUE(saw.ok());
  for (double rad : {1e-5, 1e-4, 5e-4}) {
    SignatureOptions o;
    o.spheroradius = rad;
    auto r = self_signature(*saw, o);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_NEAR(todeg(r->theta_max_forward), 30, 1e-9) << rad;
    EXPECT_NEAR(r->theta_max_backward, std::atan(0.7 * std::tan(deg(30)) / 0.3), 1e-12) << rad;
  }
}

// Koch K2 at 10 deg: the rigid theta_max 2 alpha needs the small K2 bumps' flanks; a radius small
// against them keeps it, and a tiny one converges to the rigid lift.
TEST(Sphero, KochK2SmallRadiusKeepsTwoAlphaAndTinyRadiusIsRigid) {
  const Profile k = koch(2, 10);
  SignatureOptions o;
  o.spheroradius = 1e-6;
  auto r = self_signature(k, o);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_NEAR(todeg(r->theta_max_forward), 20, 1e-6);
  EXPECT_NEAR(todeg(r->theta_max_backward), 20, 1e-6);
  auto rigid = self_signature(k);
  ASSERT_TRUE(rigid.ok());
  // h0 + R <= h <= h0 + R / cos(theta_max): the disk's top, and the disk against h0's steepest slope.
  for (std::size_t i = 0; i < r->offset.size(); i += 7) {
    const double h0 = lift_direct(k, rotate180(k), r->offset[i]);
    EXPECT_GE(r->lift[i], h0 + 2e-6 - 1e-15);
    EXPECT_LE(r->lift[i], h0 + 2e-6 / std::cos(deg(20)) + 1e-15);
  }
}

// Rounding cannot steepen a contact: on h the arcs join the offsets of h0's pieces tangentially,
// so (without vertical walls in h0) every slope of h lies within h0's; and h0 + R <= h <= h0 + R /
// cos(theta_max of h0). Random periodic pairs (no block ends, where h0 drops and a rounded
// corner rolls off), several radii.
TEST(Sphero, RandomPairsSlopesBoundedByTheRigidOnes) {
  auto periodic = [](Profile p) {
    p.z.back() = p.z.front();
    p.period = p.length();
    return p;
  };
  const Profile lo = periodic(random_polyline(21, 160, 0.01, 1e-4));
  const Profile up = rotate180(periodic(random_polyline(22, 120, 0.01, 1e-4)));
  auto rigid = signature(lo, up);
  ASSERT_TRUE(rigid.ok());
  const double tmax = std::max(rigid->theta_max_forward, rigid->theta_max_backward);
  for (double rad : {1e-7, 1e-6, 1e-5, 1e-4}) {
    SignatureOptions o;
    o.spheroradius = rad;
    auto r = signature(lo, up, o);
    ASSERT_TRUE(r.ok()) << r.error().message;
    // Where an arc meets a line tangentially the breakpoint is ill-conditioned: a rounding error
    // eps of the values (~1e-20 m here) moves it by sqrt(2 R eps), the slope by sqrt(2 eps / R),
    // about 1e-7 rad at R = 2e-6 m.
    EXPECT_LE(r->theta_max_forward, rigid->theta_max_forward + 1e-7) << rad;
    EXPECT_LE(r->theta_max_backward, rigid->theta_max_backward + 1e-7) << rad;
    for (std::size_t i = 0; i < r->offset.size(); i += 97) {
      const double h0 = lift_direct(lo, up, r->offset[i]), R = 2 * rad;
      EXPECT_GE(r->lift[i], h0 + R - 1e-15) << rad;
      EXPECT_LE(r->lift[i], h0 + R / std::cos(tmax) + 1e-15) << rad;
    }
  }
}

// (c) r = 0 takes the rigid path bit for bit.
TEST(Sphero, ZeroRadiusIsTheRigidSignatureBitForBit) {
  auto same = [](const SignatureResult& a, const SignatureResult& b) {
    auto eq = [](const std::vector<double>& u, const std::vector<double>& v) {
      return u.size() == v.size() && std::memcmp(u.data(), v.data(), u.size() * sizeof(double)) == 0;
    };
    EXPECT_TRUE(eq(a.offset, b.offset) && eq(a.lift, b.lift) && eq(a.theta, b.theta) && eq(a.theta_min, b.theta_min) &&
                eq(a.theta_left, b.theta_left) && eq(a.theta_right, b.theta_right) &&
                eq(a.slope_samples, b.slope_samples));
    EXPECT_EQ(std::memcmp(&a.theta_max_forward, &b.theta_max_forward, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&a.contact_slope_std, &b.contact_slope_std, sizeof(double)), 0);
    EXPECT_EQ(a.contacts.size(), b.contacts.size());
    EXPECT_EQ(b.spheroradius, 0);
  };
  SignatureOptions zero;
  zero.spheroradius = 0;
  const Profile k2 = koch(2, 25);
  same(*self_signature(k2), *self_signature(k2, zero));
  const Profile lo = random_polyline(3, 200, 0.01, 1e-4), up = rotate180(random_polyline(4, 150, 0.008, 1e-4));
  same(*signature(lo, up), *signature(lo, up, zero));
  EXPECT_NEAR(todeg(self_signature(k2)->theta_max_forward), 50, 1e-9);  // paper: K2 gives 2 alpha
}

TEST(Sphero, RejectsBadRadiusAndSplineSlopes) {
  const Profile k = koch(0, 20);
  SignatureOptions o;
  o.spheroradius = -1e-5;
  EXPECT_FALSE(self_signature(k, o).ok());
  o.spheroradius = NAN;
  EXPECT_FALSE(self_signature(k, o).ok());
  o.spheroradius = 1e-5;
  o.slopes = SlopeMethod::Spline;
  auto r = self_signature(k, o);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("spheroradius"), std::string::npos);
}

TEST(Sphero, CliOptionAndJson) {
  auto r = run_cli("signature koch -n 0 --alpha 20 --radius 0.01 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["spheroradius_m"].get<double>(), 0.01);
  EXPECT_NEAR(j["theta_max_forward_deg"].get<double>(), todeg(std::asin(0.25)), 1e-9);
  auto z = run_cli("signature koch -n 0 --alpha 20 --json");
  EXPECT_EQ(nlohmann::json::parse(z.out)["spheroradius_m"].get<double>(), 0);
  EXPECT_EQ(run_cli("signature koch --radius -1").code, 2);
  EXPECT_EQ(run_cli("signature koch --radius 1e-5 --slopes spline").code, 2);
}

// The name is --spheroradius (the settings table's one name); --radius, the name before,
// is still read but not offered in the help.
TEST(Sphero, SpheroradiusOptionAndRetiredRadius) {
  auto a = run_cli("signature koch -n 0 --alpha 20 --spheroradius 0.01 --json");
  ASSERT_EQ(a.code, 0) << a.err;
  auto ja = nlohmann::json::parse(a.out);
  EXPECT_EQ(ja["spheroradius_m"].get<double>(), 0.01);
  EXPECT_NEAR(ja["theta_max_forward_deg"].get<double>(), todeg(std::asin(0.25)), 1e-9);
  auto b = run_cli("signature koch -n 0 --alpha 20 --radius 0.01 --json");
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_EQ(nlohmann::json::parse(b.out)["theta_max_forward_deg"], ja["theta_max_forward_deg"]);
  auto h = run_cli("signature --help");
  EXPECT_NE(h.out.find("--spheroradius"), std::string::npos);
  EXPECT_EQ(h.out.find("--radius"), std::string::npos);
  auto bad = run_cli("signature koch --spheroradius -1");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--spheroradius"), std::string::npos) << bad.err;
}
