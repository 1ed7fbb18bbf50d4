#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "frictal/generators.hpp"
#include "frictal/signature.hpp"
#include "signature/face.hpp"
#include "signature/rigid.hpp"

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
}  // namespace

TEST(Signature, FlatOnFlatIsZero) {
  Profile f{{0, 0.5, 1}, {0, 0, 0}, std::nullopt};
  auto r = self_signature(f);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(r->theta_max_forward, 0);
  EXPECT_EQ(r->theta_max_backward, 0);
  for (double t : r->theta) EXPECT_EQ(t, 0);
  EXPECT_EQ(r->contact_slope_std, 0);
}

// Paper Sec. III: K0 and K1 give alpha, K2 gives 2 alpha, K3 gives 3 alpha (Fig. 4), both ways.
class KochSignature : public ::testing::TestWithParam<std::tuple<int, double>> {};
TEST_P(KochSignature, MaximumIsNAlpha) {
  const auto [n, a] = GetParam();
  const int mult[] = {1, 1, 2, 3};
  auto r = self_signature(koch(n, a));
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_NEAR(todeg(r->theta_max_forward), mult[n] * a, 1e-9);
  EXPECT_NEAR(todeg(r->theta_max_backward), mult[n] * a, 1e-9);
  EXPECT_TRUE(r->exact);
}
INSTANTIATE_TEST_SUITE_P(Paper, KochSignature,
                         ::testing::Combine(::testing::Values(0, 1, 2, 3), ::testing::Values(5.0, 10.0, 20.0)));

TEST(Signature, FoldedKochSurfaces) {
  // K1 folds above 45 degrees and K2 above 30; the paper's geometric argument still holds.
  auto k1 = self_signature(koch(1, 50));
  ASSERT_TRUE(k1.ok());
  EXPECT_NEAR(todeg(k1->theta_max_forward), 50, 1e-9);
  auto k2 = self_signature(koch(2, 40));
  ASSERT_TRUE(k2.ok());
  EXPECT_NEAR(todeg(k2->theta_max_forward), 80, 1e-9);
}

TEST(Signature, K0TipOnTipAtZeroAndMatingAtHalfWavelength) {
  auto r = self_signature(koch(0, 20, 0.05));
  ASSERT_TRUE(r.ok());
  // The turned-over copy has its teeth over the lower teeth at offset 0 (tip on tip) and nests
  // at offset lambda/2, where both flanks touch along their length (edge-edge, slopes +-alpha).
  std::size_t mid = 0;
  for (std::size_t i = 0; i < r->offset.size(); ++i)
    if (std::abs(r->offset[i] - 0.005) < 1e-12) mid = i;
  ASSERT_GT(mid, 0u);
  EXPECT_NEAR(todeg(r->theta[mid]), 20, 1e-9);
  EXPECT_NEAR(todeg(r->theta_min[mid]), -20, 1e-9);
  bool has_ee = false;
  for (auto k = r->contact_begin[mid]; k < r->contact_begin[mid + 1]; ++k)
    has_ee |= r->contacts[k].type == ContactType::EdgeEdge;
  EXPECT_TRUE(has_ee);
  bool vv0 = false;
  for (auto k = r->contact_begin[0]; k < r->contact_begin[1]; ++k)
    vv0 |= r->contacts[k].type == ContactType::VertexVertex;
  EXPECT_TRUE(vv0);
  // Lift: h(s) = h(lambda/2) + |s - lambda/2| tan(alpha); tip on tip is one tooth height above.
  const double P = 0.005 * std::tan(deg(20));
  EXPECT_NEAR(r->lift[0] - r->lift[mid], P, 1e-15);
  for (std::size_t i = 0; i < r->offset.size(); ++i)
    EXPECT_NEAR(r->lift[i], r->lift[mid] + std::abs(r->offset[i] - 0.005) * std::tan(deg(20)), 1e-15);
  // theta just after 0 is -alpha (sliding down the flank), just before lambda/2 too.
  EXPECT_NEAR(todeg(r->theta_right[0]), -20, 1e-9);
  EXPECT_NEAR(todeg(r->theta_left[mid]), -20, 1e-9);
  EXPECT_NEAR(todeg(r->theta_right[mid]), 20, 1e-9);
}

TEST(Signature, AsymmetricSawtoothGivesRiseForwardAndFallBackward) {
  SawtoothParams s;
  s.rise_angle = deg(25);
  s.rise_fraction = 0.7;
  auto p = sawtooth_profile(s);
  auto r = self_signature(*p);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(todeg(r->theta_max_forward), 25, 1e-9);
  EXPECT_NEAR(r->theta_max_backward, std::atan(0.7 / 0.3 * std::tan(deg(25))), 1e-12);
}

TEST(Signature, SineMatchesClosedForm) {
  // f = A sin(kx); rotated copy is the same function, h(s) = 2A sin(ks/2), contact at x = s/2,
  // theta(s) = atan(A k cos(k s / 2)).
  SineParams sp;
  sp.amplitude = 1e-3;
  sp.points_per_wavelength = 4096;
  sp.length = 0.02;
  auto p = sine_profile(sp);
  SignatureOptions o;
  o.offsets = 101;
  o.offset_min = 0.0005;
  o.offset_max = 0.0095;
  const double k = 2 * M_PI / 0.01;
  for (auto m : {SlopeMethod::Exact, SlopeMethod::Spline}) {
    o.slopes = m;
    auto r = self_signature(*p, o);
    ASSERT_TRUE(r.ok()) << r.error().message;
    for (std::size_t i = 0; i < r->offset.size(); ++i) {
      const double s = r->offset[i];
      EXPECT_NEAR(r->lift[i] - r->lift[0], 2e-3 * (std::sin(k * s / 2) - std::sin(k * o.offset_min / 2)), 1e-8);
      EXPECT_NEAR(r->theta[i], std::atan(1e-3 * k * std::cos(k * s / 2)), m == SlopeMethod::Spline ? 1e-5 : 2e-3);
    }
  }
}

TEST(Signature, LiftAgreesWithDirectScanOnWmPair) {
  WmParams w;
  w.n_max = 6;
  auto f = wm_profile(w);
  w.seed = 99;
  auto g = wm_profile(w);
  auto up = rotate180(*g);
  auto r = signature(*f, up);
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r->exact);
  for (std::size_t i = 0; i < r->offset.size(); i += 7)
    EXPECT_NEAR(r->lift[i], lift_direct(*f, up, r->offset[i]), 1e-21) << "offset " << r->offset[i];
  // The maximum contact slope never exceeds the maximum surface slope (Sec. V C).
  double smax = 0;
  for (std::size_t i = 0; i + 1 < f->size(); ++i)
    smax = std::max({smax, std::abs(std::atan((f->z[i + 1] - f->z[i]) / (f->x[i + 1] - f->x[i]))),
                     std::abs(std::atan((g->z[i + 1] - g->z[i]) / (g->x[i + 1] - g->x[i])))});
  EXPECT_LE(r->theta_max_forward, smax + 1e-12);
  EXPECT_LE(r->theta_max_backward, smax + 1e-12);
}

TEST(Signature, NonAlignedGridsAgreeWithDirectScan) {
  SineParams a;
  a.points_per_wavelength = 37;
  a.length = 0.05;
  SineParams b = a;
  b.points_per_wavelength = 53;
  b.amplitude = 7e-4;
  auto f = sine_profile(a);
  auto g = sine_profile(b);
  f->period.reset();
  g->period.reset();
  auto up = rotate180(*g);
  auto r = signature(*f, up);
  ASSERT_TRUE(r.ok()) << r.error().message;
  for (std::size_t i = 0; i < r->offset.size(); i += 11)
    EXPECT_NEAR(r->lift[i], lift_direct(*f, up, r->offset[i]), 1e-15);
  // The exact maxima bound every sampled evaluation from above.
  SignatureOptions o;
  o.offsets = 3001;
  auto q = signature(*f, up, o);
  ASSERT_TRUE(q.ok());
  for (double t : q->theta) EXPECT_LE(t, r->theta_max_forward + 1e-12);
}

TEST(Signature, SameResultForOneAndManyThreads) {
  SelfAffineParams sp;
  sp.points = 20000;
  auto f = self_affine_profile(sp);
  sp.seed = 5;
  auto g = self_affine_profile(sp);
  SignatureOptions o;
  o.threads = 1;
  auto a = signature(*f, rotate180(*g), o);
  o.threads = 4;
  auto b = signature(*f, rotate180(*g), o);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->lift, b->lift);
  EXPECT_EQ(a->theta, b->theta);
  EXPECT_EQ(a->theta_max_forward, b->theta_max_forward);
  EXPECT_EQ(a->contact_slope_std, b->contact_slope_std);
  ASSERT_EQ(a->contacts.size(), b->contacts.size());
}

TEST(Signature, SampledOffsetsNeverExceedExactMaximum) {
  auto p = koch(2, 20);
  SignatureOptions o;
  o.offsets = 777;
  auto s = self_signature(p, o);
  auto e = self_signature(p);
  ASSERT_TRUE(s.ok() && e.ok());
  EXPECT_LE(s->theta_max_forward, e->theta_max_forward + 1e-12);
  EXPECT_FALSE(s->exact);
}

TEST(Signature, ErrorsForBadOptions) {
  auto p = koch(1, 20);
  SignatureOptions o;
  o.tolerance = 0;
  EXPECT_FALSE(self_signature(p, o).ok());
  o = {};
  o.max_events = 10;
  o.require_exact = true;
  auto r = self_signature(koch(3, 20), o);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("--offsets"), std::string::npos);
  // Without require_exact: offsets sampled instead (at most max_events), never above the maximum.
  o.require_exact = false;
  auto fb = self_signature(koch(3, 20), o);
  ASSERT_TRUE(fb.ok()) << fb.error().message;
  EXPECT_FALSE(fb->exact);
  EXPECT_LE(fb->offset.size(), 10u);
  EXPECT_LE(fb->theta_max_forward, deg(60) + 1e-12);
  o = {};
  o.slopes = SlopeMethod::Spline;
  EXPECT_FALSE(self_signature(koch(2, 40), o).ok());  // envelope has vertical jumps
  Profile flat{{0, 1}, {0, 0}, std::nullopt};
  o = {};
  o.offset_min = 0;
  o.offset_max = 5;  // beyond the block
  EXPECT_FALSE(self_signature(flat, o).ok());
}

TEST(Friction, Eq6AndEq18) {
  auto f = predict_friction(std::tan(deg(10)), deg(20), deg(3));
  ASSERT_TRUE(f.ok());
  EXPECT_NEAR(todeg(f->friction_angle), 30, 1e-12);
  EXPECT_NEAR(f->friction_coefficient, std::tan(deg(30)), 1e-12);
  EXPECT_NEAR(todeg(f->friction_angle_low), 27, 1e-12);
  EXPECT_NEAR(f->friction_coefficient_low, std::tan(deg(27)), 1e-12);
  auto g = predict_friction(1.0, deg(60), 0);  // 45 + 60 > 90: cannot slide
  EXPECT_TRUE(std::isinf(g->friction_coefficient));
  EXPECT_FALSE(predict_friction(-0.1, 0, 0).ok());
  EXPECT_FALSE(predict_friction(NAN, 0, 0).ok());
}

// Between two consecutive events h is convex, so the secant slope over the interval lies between
// the slope just after its left end and the slope just before its right end. Checked on pairs
// whose contacts often sit on a block's end corner (regression: a vertex-vertex contact at the
// upper block's corner was reported as a +-90 degree wall).
TEST(Signature, OneSidedSlopesBracketTheSecantOfEveryInterval) {
  struct Case {
    double D;
    int n_max;
    std::uint64_t s1, s2;
  };
  for (const Case& c :
       {Case{1.8, 8, 6868312974978945722ull, 3248097931408723624ull}, Case{1.3, 6, 1, 2}, Case{1.6, 10, 7, 8}}) {
    WmParams w;
    w.dimension = c.D;
    w.n_max = c.n_max;
    w.seed = c.s1;
    auto f = wm_profile(w);
    w.seed = c.s2;
    auto g = wm_profile(w);
    auto r = signature(*f, rotate180(*g));
    ASSERT_TRUE(r.ok());
    for (std::size_t i = 0; i + 1 < r->offset.size(); ++i) {
      // Continuous profiles: h is continuous, no walls anywhere.
      ASSERT_LT(std::abs(r->theta_right[i]), M_PI / 2) << "offset " << r->offset[i];
      ASSERT_LT(std::abs(r->theta_left[i + 1]), M_PI / 2) << "offset " << r->offset[i + 1];
      const double secant = (r->lift[i + 1] - r->lift[i]) / (r->offset[i + 1] - r->offset[i]);
      const double scale = 1e-9 * (1 + std::abs(secant));
      EXPECT_LE(std::tan(r->theta_right[i]), secant + scale) << c.D << " " << i;
      EXPECT_GE(std::tan(r->theta_left[i + 1]), secant - scale) << c.D << " " << i;
    }
    EXPECT_LT(r->theta_max_forward, M_PI / 2);
    EXPECT_LT(r->theta_max_backward, M_PI / 2);
  }
}

// Regression (found by tests/properties): a jump of the lower face aligned with a jump of the
// upper face at an event offset s = x_f - x_g that does not round-trip (x_f - s != x_g in double).
// The lower face steps up at x = 0.9 (left 0, extreme 1, right 0.5); the upper face has a needle
// down to z = 0.2 at x = 0.2. At s = 0.9 - 0.2 the needle sits on the step's top: h = 1 - 0.2 =
// 0.8, while just before h = 0 - 0.2 and just after h = 0.5 - 0.2: a wall for motion towards +x.
TEST(SignatureJumps, JumpOnJumpAtARoundedEventKeepsBothExtremes) {
  frictal::Profile f{{0, 0.9, 0.9, 0.9, 2}, {0, 0, 1, 0.5, 0.5}, std::nullopt};
  frictal::Profile g{{0, 0.2, 0.2, 0.2, 2}, {2, 2, 0.2, 2, 2}, std::nullopt};
  const double s_event = 0.9 - 0.2;
  ASSERT_NE(0.9 - s_event, 0.2);  // the premise: the event does not round-trip
  frictal::SignatureOptions o;
  o.threads = 1;
  o.offset_min = 0;
  o.offset_max = 1;
  auto sig = frictal::signature(f, g, o);
  ASSERT_TRUE(sig.ok()) << sig.error().message;
  std::size_t at = sig->offset.size();
  for (std::size_t i = 0; i < sig->offset.size(); ++i)
    if (std::abs(sig->offset[i] - s_event) < 1e-12) at = i;
  ASSERT_LT(at, sig->offset.size()) << "the event offset was not evaluated";
  EXPECT_NEAR(sig->lift[at], 0.8, 1e-12);
  EXPECT_NEAR(sig->theta_left[at], M_PI / 2, 1e-12);  // h jumps up from -0.2: a wall towards +x
}

// On aligned lattices the lift is searched over indices with aligned block maxima.
// Checked against the two other methods at every event offset of a window: the plain scan of
// every vertex (lift_direct) and the general branch and bound over both faces (the rigid
// evaluator of the spheropolygon signature, which never takes the index path); and the same
// result on one and on two threads. WM with 12 scales and a self-affine profile.
namespace {
struct SigPair {
  Profile lower, upper;
};

SigPair index_path_pair(int kind, std::size_t n) {
  SigPair p;
  if (kind == 0) {
    SelfAffineParams s;
    s.points = n;
    p.lower = *self_affine_profile(s);
    s.seed = 7;
    p.upper = rotate180(*self_affine_profile(s));
  } else {
    WmParams w;
    w.n_max = 11;
    w.spacing = w.length / static_cast<double>(n - 1);
    p.lower = *wm_profile(w);
    w.seed = 7;
    p.upper = rotate180(*wm_profile(w));
  }
  return p;
}
}  // namespace

TEST(SignatureIndexSearch, MatchesPlainScanAndGeneralSearchOnWmAndSelfAffine) {
  for (int kind : {0, 1}) {
    const SigPair p = index_path_pair(kind, 20'001);
    const double L = p.lower.length();
    const double dx = L / static_cast<double>(p.lower.size() - 1);
    SignatureOptions o;
    o.offset_min = 4000 * dx;  // lattice offsets only, so that every one takes the index path
    o.offset_max = 5500 * dx;
    o.threads = 1;
    auto r1 = signature(p.lower, p.upper, o);
    ASSERT_TRUE(r1.ok()) << r1.error().message;
    EXPECT_TRUE(r1->exact);
    ASSERT_EQ(r1->offset.size(), 1501u);
    o.threads = 2;
    auto r2 = signature(p.lower, p.upper, o);
    ASSERT_TRUE(r2.ok());
    EXPECT_EQ(r1->lift, r2->lift);
    EXPECT_EQ(r1->theta, r2->theta);
    EXPECT_EQ(r1->theta_left, r2->theta_left);
    EXPECT_EQ(r1->theta_right, r2->theta_right);
    auto general = detail::RigidLift::make(p.lower, p.upper, o);
    ASSERT_TRUE(general.ok()) << general.error().message;
    double zr = 0;
    for (double z : p.lower.z) zr = std::max(zr, std::abs(z));
    for (std::size_t i = 0; i < r1->offset.size(); ++i) {
      const double s = r1->offset[i];
      if (i % 5 == 0) {  // the plain scan costs O(N) per offset
        EXPECT_NEAR(r1->lift[i], lift_direct(p.lower, p.upper, s), 1e-12 * zr) << "kind " << kind << " s " << s;
      }
      const auto g = general->at(s);
      EXPECT_EQ(r1->lift[i], g.lift) << "kind " << kind << " s " << s;
      EXPECT_NEAR(r1->theta_left[i], g.left, 1e-12) << "kind " << kind << " s " << s;
      EXPECT_NEAR(r1->theta_right[i], g.right, 1e-12) << "kind " << kind << " s " << s;
    }
  }
}

// An upper block much shorter than the lower one on the same lattice: the batch frontier spans
// more aligned levels of the lower face than the short face has (it read past the short face's
// levels and crashed: 200 and 50 points). Every lift equals the plain scan.
TEST(SignatureIndexSearch, UpperMuchShorterThanLowerMatchesPlainScan) {
  for (std::size_t nu : {50u, 33u, 2u}) {
    const std::size_t nl = 2000;
    const double dx = 1e-3 / double(nl - 1);
    Profile lower, upper;
    for (std::size_t i = 0; i < nl; ++i) {
      const double x = double(i) * dx;
      lower.x.push_back(x);
      lower.z.push_back(1e-5 * std::sin(2 * M_PI * x / 7.3e-5) + 4e-6 * std::sin(2 * M_PI * x / 1.9e-5 + 1.0));
    }
    for (std::size_t i = 0; i < nu; ++i) {
      const double x = double(i) * dx;
      upper.x.push_back(x);
      upper.z.push_back(8e-6 * std::cos(2 * M_PI * x / 3.1e-5) + 3e-6 * std::sin(2 * M_PI * x / 1.1e-5));
    }
    const Profile up = rotate180(upper);
    for (unsigned threads : {1u, 2u}) {
      SignatureOptions o;
      o.threads = threads;
      auto r = signature(lower, up, o);
      ASSERT_TRUE(r.ok()) << r.error().message;
      EXPECT_TRUE(r->exact);
      ASSERT_FALSE(r->offset.empty());
      for (std::size_t i = 0; i < r->offset.size(); i += 3)
        EXPECT_NEAR(r->lift[i], lift_direct(lower, up, r->offset[i]), 1e-18) << nu << " points, s " << r->offset[i];
    }
  }
}

// A grid far from x = 0 is uniform only to within rounding of x (1e-9 dx is below an ulp
// there): it must still be recognised as an aligned lattice, so every event is evaluated.
TEST(SignatureIndexSearch, UniformGridFarFromOriginIsExact) {
  SelfAffineParams s;
  s.points = 100'001;
  s.length = 1.0;
  Profile f = *self_affine_profile(s);
  for (double& x : f.x) x += 1000.0;  // ulp(1000) = 1.1e-13 m > 1e-9 dx = 1e-14 m
  SignatureOptions o;
  o.offset_max = 0.01;
  auto r = self_signature(f, o);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_TRUE(r->exact);
  // Offsets 0, dx, ..., 0.01 m: 1001 lattice offsets (dx = 1e-5 m).
  EXPECT_NEAR(static_cast<double>(r->offset.size()), 1001.0, 1.0);
}

// The index search also bounds each node by tilted upper lines (the chord of the node
// raised over its points, TiltedMax). They only prune; a line that cut below a point would lose a
// maximiser or a contact. Checked against the search with block maxima only (every field, every
// contact, bit for bit) and against the plain scan of every vertex (lift_direct), on one and two
// threads: WM with 12 scales (steep long-wavelength trends: where the lines prune most), smooth
// curved profiles far from z = 0 (the rounding margins of the lines), and two parallel ramps
// (f - g is the same at every vertex: every vertex is a contact at every offset).
TEST(SignatureIndexSearch, TiltedBoundsChangeNothingButTheWork) {
  std::vector<std::pair<std::string, SigPair>> cases;
  cases.emplace_back("wm", index_path_pair(1, 20'001));
  {
    SigPair p;
    const std::size_t n = 8'001;
    for (std::size_t i = 0; i < n; ++i) {
      const double x = 1e-3 * static_cast<double>(i) / static_cast<double>(n - 1);
      p.lower.x.push_back(x);
      p.lower.z.push_back(1e3 + 2e-4 * std::sin(2 * M_PI * x / 7e-4) + 0.1 * x);
      p.upper.x.push_back(x);
      p.upper.z.push_back(-1e3 - 3e-4 * std::cos(2 * M_PI * x / 9e-4) - 0.05 * x);
    }
    cases.emplace_back("smooth far from zero", std::move(p));
  }
  {
    SigPair p;
    const std::size_t n = 2'001;
    for (std::size_t i = 0; i < n; ++i) {
      const double x = static_cast<double>(i) / static_cast<double>(n - 1);  // the same grid for both
      p.lower.x.push_back(x);
      p.lower.z.push_back(0.25 * static_cast<double>(i));  // f - g = 0.25 d exactly at lattice offset d
      p.upper.x.push_back(x);
      p.upper.z.push_back(0.25 * static_cast<double>(i));
    }
    cases.emplace_back("parallel ramps", std::move(p));
  }
  for (const auto& [name, p] : cases) {
    const double L = p.lower.length();
    const double dx = L / static_cast<double>(p.lower.size() - 1);
    SignatureOptions o;
    o.offset_min = std::round(0.2 * L / dx) * dx;
    o.offset_max = std::round(0.45 * L / dx) * dx;
    o.threads = 1;
    o.tilted_bounds = false;
    auto plain = signature(p.lower, p.upper, o);
    ASSERT_TRUE(plain.ok()) << name << ": " << plain.error().message;
    EXPECT_TRUE(plain->exact) << name;
    for (unsigned threads : {1u, 2u}) {
      o.threads = threads;
      o.tilted_bounds = true;
      auto t = signature(p.lower, p.upper, o);
      ASSERT_TRUE(t.ok()) << name;
      EXPECT_EQ(t->offset, plain->offset) << name;
      EXPECT_EQ(t->lift, plain->lift) << name;
      EXPECT_EQ(t->theta, plain->theta) << name;
      EXPECT_EQ(t->theta_min, plain->theta_min) << name;
      EXPECT_EQ(t->theta_left, plain->theta_left) << name;
      EXPECT_EQ(t->theta_right, plain->theta_right) << name;
      EXPECT_EQ(t->contact_begin, plain->contact_begin) << name;
      ASSERT_EQ(t->contacts.size(), plain->contacts.size()) << name;
      for (std::size_t k = 0; k < t->contacts.size(); ++k) {
        EXPECT_EQ(t->contacts[k].x, plain->contacts[k].x) << name << " contact " << k;
        EXPECT_EQ(t->contacts[k].slope, plain->contacts[k].slope) << name << " contact " << k;
      }
    }
    if (name == "parallel ramps") {  // every vertex of the overlap touches
      for (std::size_t i = 0; i < plain->offset.size(); ++i)
        EXPECT_GE(plain->contact_begin[i + 1] - plain->contact_begin[i], p.lower.size() / 2) << "offset " << i;
    }
    double zr = 0;
    for (double z : p.lower.z) zr = std::max(zr, std::abs(z));
    for (std::size_t i = 0; i < plain->offset.size(); i += 7)
      EXPECT_NEAR(plain->lift[i], lift_direct(p.lower, p.upper, plain->offset[i]), 1e-12 * zr)
          << name << " s " << plain->offset[i];
  }
}

// The tilted lines are upper bounds of every point of their node, at every level, in exact
// arithmetic (checked in long double): random walks with steps of mixed scales, heights far
// from zero, a partial last node, and a constant profile.
TEST(TiltedMax, EveryLineLiesAboveEveryPointOfItsNode) {
  std::uint64_t state = 12345;
  auto uniform = [&] {  // splitmix64 -> [0, 1)
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  };
  for (int c = 0; c < 4; ++c) {
    const std::size_t n = c == 3 ? 1000 : 70'001 + 37 * static_cast<std::size_t>(c);
    std::vector<double> v(n);
    double z = c == 1 ? 1e6 : 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      if (c != 3) z += (uniform() - 0.5) * (i % 97 == 0 ? 1e3 : 1.0) + 1e-3 * std::sin(1e-3 * static_cast<double>(i));
      v[i] = z;
    }
    const detail::TiltedMax t(v);
    ASSERT_GT(t.levels(), 0u);
    for (std::size_t l = 0; l < t.levels(); ++l) {
      const std::size_t len = std::size_t{detail::kBlock} << l;
      const auto& lines = t.level(l);
      ASSERT_EQ(lines.size(), (n + len - 1) / len) << "level " << l;
      for (std::size_t q = 0; q < lines.size(); ++q)
        for (std::size_t i = q * len; i < std::min(n, (q + 1) * len); ++i) {
          const long double line = static_cast<long double>(lines[q].c) +
                                   static_cast<long double>(lines[q].tau) * static_cast<long double>(i - q * len);
          ASSERT_LE(static_cast<long double>(v[i]), line) << "case " << c << " level " << l << " node " << q;
        }
    }
  }
}

// Face::value_walk (the search's leaves) against Face::value: the same value, bit for bit, for
// every abscissa of a non-decreasing run, on faces with vertical jumps (groups of equal x), with
// and without a vertex tolerance, including abscissae beyond both ends and exactly on vertices.
TEST(FaceValueWalk, EqualsValueOnNonUniformFacesWithJumps) {
  std::uint64_t state = 12345;
  auto uniform01 = [&state]() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  for (int trial = 0; trial < 40; ++trial) {
    const std::size_t n = 2 + static_cast<std::size_t>(uniform01() * 300);
    std::vector<double> x(n), z(n);
    double xc = -1.0 + uniform01();
    for (std::size_t i = 0; i < n; ++i) {
      if (i > 0 && uniform01() > 0.15) xc += (uniform01() < 0.5 ? 1e-3 : 1e-1) * uniform01() + 1e-9;
      x[i] = xc;  // about 15 % of the points repeat the previous abscissa: a jump
      z[i] = uniform01() - 0.5;
    }
    const detail::Face face(x, z, trial % 2 == 0 ? 1.0 : -1.0);
    // Query abscissae: vertices, vertices +- a fraction of the tolerance, random points, ends.
    const double xtol = trial % 3 == 0 ? 0.0 : 1e-6;
    std::vector<double> u;
    for (std::size_t i = 0; i < n; ++i) {
      u.push_back(x[i]);
      u.push_back(x[i] + 0.5 * xtol);
      u.push_back(x[i] - 0.5 * xtol);
      u.push_back(x[i] + 3 * xtol);
    }
    for (int k = 0; k < 200; ++k) u.push_back(x.front() - 0.1 + (x.back() - x.front() + 0.2) * uniform01());
    std::sort(u.begin(), u.end());
    // One walk over everything, and walks restarted at random places (as the search's leaves are).
    detail::Face::Cursor whole;
    detail::Face::Cursor part;
    for (std::size_t k = 0; k < u.size(); ++k) {
      if (uniform01() < 0.05) part = {};
      const double expected = face.value(u[k], xtol);
      ASSERT_EQ(face.value_walk(u[k], xtol, whole), expected) << "trial " << trial << " u = " << u[k];
      ASSERT_EQ(face.value_walk(u[k], xtol, part), expected) << "trial " << trial << " u = " << u[k];
    }
  }
}

// The general search with its batch frontier and tilted lines (grids that do not align, offsets
// off the lattice) against the same search with block maxima only, and against the evaluation
// of each offset on its own from the whole index range (RigidLift::at: no frontier, no warm
// start, no lines): the same lift bit for bit and the same one-sided slopes, on WM
// and self-affine pairs, for an upper grid of 0.7 N points and for offsets halfway between
// lattice offsets of equal grids; and against the plain scan.
// A grid of at least a quarter of the exact events on aligned lattices is replaced by every event:
// exact, so theta_max equals the exact path's, and never costlier.
TEST(SignatureGrid, ADenseGridOnAlignedLatticesTakesTheExactPath) {
  const SigPair p = index_path_pair(0, 20'001);
  SignatureOptions exact;
  exact.keep_contacts = false;
  auto e = signature(p.lower, p.upper, exact);
  ASSERT_TRUE(e.ok()) << e.error().message;
  SignatureOptions grid = exact;
  grid.offsets = e->offset.size() / 2;
  auto g = signature(p.lower, p.upper, grid);
  ASSERT_TRUE(g.ok()) << g.error().message;
  EXPECT_TRUE(g->grid_replaced);
  EXPECT_TRUE(g->exact);
  EXPECT_EQ(g->offset, e->offset);
  EXPECT_EQ(g->theta_max_forward, e->theta_max_forward);
  EXPECT_EQ(g->theta_max_backward, e->theta_max_backward);
  grid.offsets = e->offset.size() / 8;  // a coarse grid stays a grid
  auto c = signature(p.lower, p.upper, grid);
  ASSERT_TRUE(c.ok());
  EXPECT_FALSE(c->grid_replaced);
  EXPECT_EQ(c->offset.size(), grid.offsets);
  grid.offsets = e->offset.size() / 2;
  grid.keep_grid = true;
  auto k = signature(p.lower, p.upper, grid);
  ASSERT_TRUE(k.ok());
  EXPECT_FALSE(k->grid_replaced);
  EXPECT_EQ(k->offset.size(), grid.offsets);
}

TEST(SignatureGeneralSearch, BatchFrontierMatchesOffsetByOffsetSearch) {
  for (int kind : {0, 1}) {
    for (int grid : {1, 2}) {
      SigPair p = index_path_pair(kind, 20'001);
      if (grid == 2) {
        const SigPair q = index_path_pair(kind, 14'001);
        p.upper = q.upper;
      }
      const double L = p.lower.length();
      const double dx = L / static_cast<double>(p.lower.size() - 1);
      SignatureOptions o;
      o.offset_min = 4000.5 * dx;
      o.offset_max = 5500.5 * dx;
      o.offsets = 1501;  // one lower spacing apart, off the lattice
      o.keep_grid = true;
      o.threads = 1;
      auto r = signature(p.lower, p.upper, o);
      ASSERT_TRUE(r.ok()) << r.error().message;
      ASSERT_EQ(r->offset.size(), 1501u);
      // Block maxima only (no tilted lines): identical in every value.
      o.tilted_bounds = false;
      auto plain = signature(p.lower, p.upper, o);
      ASSERT_TRUE(plain.ok()) << plain.error().message;
      EXPECT_EQ(r->lift, plain->lift);
      EXPECT_EQ(r->theta, plain->theta);
      EXPECT_EQ(r->theta_min, plain->theta_min);
      EXPECT_EQ(r->theta_left, plain->theta_left);
      EXPECT_EQ(r->theta_right, plain->theta_right);
      auto general = detail::RigidLift::make(p.lower, p.upper, o);
      ASSERT_TRUE(general.ok()) << general.error().message;
      double zr = 0;
      for (double z : p.lower.z) zr = std::max(zr, std::abs(z));
      for (std::size_t i = 0; i < r->offset.size(); ++i) {
        const double s = r->offset[i];
        const auto g = general->at(s);
        ASSERT_EQ(r->lift[i], g.lift) << "kind " << kind << " grid " << grid << " s " << s;
        EXPECT_NEAR(r->theta_left[i], g.left, 1e-12) << "kind " << kind << " grid " << grid << " s " << s;
        EXPECT_NEAR(r->theta_right[i], g.right, 1e-12) << "kind " << kind << " grid " << grid << " s " << s;
        if (i % 25 == 0) {
          EXPECT_NEAR(r->lift[i], lift_direct(p.lower, p.upper, s), 1e-12 * zr) << "kind " << kind << " s " << s;
        }
      }
    }
  }
}

// The spline that SlopeMethod::Spline takes, sampled (frictal stats --spline): through every point,
// exact on a straight line, and for a natural spline through a sine sampled finely the height and
// slope of the sine (derived here: sin and cos), with zero curvature at the ends.
TEST(SampleSpline, InterpolatesAndFollowsASmoothCurve) {
  frictal::Profile line;
  for (int i = 0; i <= 10; ++i) {
    line.x.push_back(0.1 * i + 0.01 * i * i);  // uneven spacing
    line.z.push_back(2.0 * line.x.back() - 0.5);
  }
  auto s = frictal::sample_spline(line, 7);
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_EQ(s->x.size(), 10u * 7u + 1u);
  for (std::size_t k = 0; k < s->x.size(); ++k) {
    EXPECT_NEAR(s->z[k], 2.0 * s->x[k] - 0.5, 1e-12);
    EXPECT_NEAR(s->slope[k], 2.0, 1e-12);
  }
  for (std::size_t i = 0; i < line.size(); ++i) {  // every 7th sample is a point
    EXPECT_DOUBLE_EQ(s->x[7 * i], line.x[i]);
    EXPECT_NEAR(s->z[7 * i], line.z[i], 1e-12);
  }
  frictal::Profile sine;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i <= 400; ++i) {
    sine.x.push_back(2 * pi * i / 400.0);
    sine.z.push_back(std::sin(sine.x.back()));
  }
  auto t = frictal::sample_spline(sine, 5);
  ASSERT_TRUE(t.ok());
  for (std::size_t k = 0; k < t->x.size(); ++k) {
    EXPECT_NEAR(t->z[k], std::sin(t->x[k]), 1e-6) << t->x[k];
    EXPECT_NEAR(t->slope[k], std::cos(t->x[k]), 1e-3) << t->x[k];  // sin'' = 0 at both ends: natural fits
  }
  EXPECT_FALSE(frictal::sample_spline(sine, 0).ok());
  frictal::Profile step{{0.0, 1.0, 1.0, 2.0}, {0.0, 0.0, 1.0, 1.0}, {}};
  EXPECT_FALSE(frictal::sample_spline(step, 3).ok());  // a vertical step: no spline
}

TEST(SignatureSettings, EachFieldFillsItsMemberAndTheDefaultsAreTheStructs) {
  const SignatureOptions d;
  const auto& t = signature_settings();
  EXPECT_EQ(find_field(t, "offsets")->default_value, double(d.offsets));
  EXPECT_EQ(find_field(t, "bins")->default_value, d.bins);
  EXPECT_EQ(find_field(t, "slopes")->default_value, 0);  // exact, the first choice
  // Automatic: the offset range (one period, or half the shorter block) and the spheroradius (rigid).
  EXPECT_TRUE(std::isnan(find_field(t, "offset_range")->default_value));
  EXPECT_TRUE(std::isnan(find_field(t, "spheroradius")->default_value));
  // The spheroradius is the tilt test's quantity: one name, unit, range and help.
  EXPECT_EQ(find_field(t, "spheroradius")->help, shared_field("spheroradius")->help);
  const ValueSet v = {
      {"slopes", std::string("spline")},          {"offsets", std::int64_t{40}}, {"keep_grid", true}, {"exact", true},
      {"offset_range", std::string("1um,0.5mm")}, {"bins", std::int64_t{12}}};
  auto o = make_signature_options(v);
  ASSERT_TRUE(o) << o.error().message;
  EXPECT_EQ(o->slopes, SlopeMethod::Spline);
  EXPECT_EQ(o->offsets, 40u);
  EXPECT_TRUE(o->keep_grid);
  EXPECT_TRUE(o->require_exact);
  EXPECT_DOUBLE_EQ(o->offset_min, 1e-6);
  EXPECT_DOUBLE_EQ(o->offset_max, 5e-4);
  EXPECT_EQ(o->bins, 12);
  // The two words of the CLI (a space) read as the comma; a radius reaches its member; none: 0.
  auto spaced = make_signature_options({{"offset_range", std::string("-2e-6 3e-6")}, {"spheroradius", 1e-5}});
  ASSERT_TRUE(spaced) << spaced.error().message;
  EXPECT_EQ(spaced->offset_min, -2e-6);
  EXPECT_EQ(spaced->offset_max, 3e-6);
  EXPECT_EQ(spaced->spheroradius, 1e-5);
  auto none = make_signature_options({{"spheroradius", std::nan("")}});
  ASSERT_TRUE(none);
  EXPECT_EQ(none->spheroradius, 0);
  EXPECT_EQ(none->offset_min, d.offset_min);
  EXPECT_EQ(none->offset_max, d.offset_max);
  // Errors name the field and what it takes.
  for (const auto& [values, says] : std::vector<std::pair<ValueSet, std::string>>{
           {{{"bins", std::int64_t{0}}}, "bins: expected a whole number in 1..100000, got 0"},
           {{{"offsets", std::int64_t{200000000}}}, "offsets: expected a whole number in 0..100000000"},
           {{{"offset_range", std::string("3,1")}}, "offset_range '3,1': expected MIN MAX"},
           {{{"offset_range", std::string("0,1,2")}}, "offset_range '0,1,2': expected MIN MAX"},
           {{{"offset_range", std::string("0 inf")}}, "offset_range '0 inf': 'inf' is not a length"},
           {{{"spheroradius", 0.0}}, "spheroradius: expected a number > 0 m, got 0"},
           {{{"slopes", std::string("spline")}, {"spheroradius", 1e-5}}, "use slopes exact"},
           {{{"offset", std::int64_t{3}}}, "did you mean 'offsets'"}}) {
    auto bad = make_signature_options(values);
    ASSERT_FALSE(bad) << says;
    EXPECT_NE(bad.error().message.find(says), std::string::npos) << bad.error().message;
  }
}
