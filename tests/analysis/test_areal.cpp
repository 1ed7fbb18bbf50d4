// Areal friction: the pruned areal signature equals the direct evaluation; a map of ridges
// reduces to the 1D signature of its profile; a tilted plane gives its tilt; the anisotropy
// of ridges separates across- from along-ridge sliding.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "frictal/areal.hpp"
#include "frictal/geometry.hpp"
#include "frictal/io.hpp"
#include "frictal/predict.hpp"
#include "frictal/signature.hpp"

namespace {
constexpr double kPi = std::numbers::pi;

frictal::Map ridges(std::size_t nx, std::size_t ny, double dx, double (*p)(double)) {
  frictal::Map m;
  m.nx = nx;
  m.ny = ny;
  m.dx = dx;
  m.dy = 1.7 * dx;
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) m.heights.push_back(p(double(i) * dx));
  return m;
}

double bumpy(double x) {
  return 1e-7 * (std::sin(x * 3e5) + 0.4 * std::sin(x * 1.1e6 + 1) + 0.2 * std::cos(x * 2.9e6));
}

frictal::Map rough(std::size_t n) {
  frictal::Map m;
  m.nx = n;
  m.ny = n + 7;
  m.dx = 1e-7;
  m.dy = 1.3e-7;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i)
      m.heights.push_back(
          1e-8 * (std::sin(i * 0.37 + j * 0.11) + std::cos(i * 0.05 - j * 0.23) + 0.3 * std::sin(i * j * 0.013)));
  m.heights[5 * n + 9] = NAN;  // holes must be skipped by both methods
  m.heights[40 * n + 33] = NAN;
  return m;
}
}  // namespace

TEST(ArealSignature, PrunedEqualsDirect) {
  auto f = rough(90), g = rough(90);
  for (double& v : g.heights) v = -0.5 * v;  // a different upper surface
  for (double a : {0.0, 0.3, kPi / 2, 2.5, 4.0}) {
    frictal::ArealSignatureOptions o;
    o.block = 8;
    auto fast = frictal::areal_signature(f, g, a, o);
    o.prune = false;
    auto direct = frictal::areal_signature(f, g, a, o);
    ASSERT_TRUE(fast.ok() && direct.ok());
    ASSERT_EQ(fast->lift.size(), direct->lift.size());
    for (std::size_t k = 0; k < fast->lift.size(); ++k) {
      if (std::isnan(direct->lift[k])) {
        EXPECT_TRUE(std::isnan(fast->lift[k]));
        continue;
      }
      EXPECT_EQ(fast->lift[k], direct->lift[k]) << a << " " << k;
      EXPECT_EQ(fast->theta[k], direct->theta[k]) << a << " " << k;
      EXPECT_EQ(fast->contact_x[k], direct->contact_x[k]);
    }
    EXPECT_LT(fast->evaluated_nodes, direct->evaluated_nodes);
    // Threads do not change the result.
    o.prune = true;
    o.threads = 3;
    auto threaded = frictal::areal_signature(f, g, a, o);
    ASSERT_TRUE(threaded.ok());
    EXPECT_EQ(threaded->lift, fast->lift);
  }
}

TEST(ArealSignature, RidgesReduceToTheProfileSignature) {
  // f(x, y) = p(x): sliding along x, h(s) on the grid is the 1D lift of the polyline p against
  // rotate180(p) at the same offsets (offsets are multiples of dx, so every node of the turned
  // block lands on a node, and the 1D maximum is reached at vertices).
  auto m = ridges(120, 9, 1e-7, bumpy);
  frictal::ArealSignatureOptions o;
  auto a = frictal::areal_signature(m, m, 0.0, o);
  ASSERT_TRUE(a.ok()) << a.error().message;
  frictal::Profile p;
  for (std::size_t i = 0; i < m.nx; ++i) {
    p.x.push_back(double(i) * m.dx);
    p.z.push_back(m.at(i, 0));
  }
  const frictal::Profile up = frictal::rotate180(p);
  const double h0 = frictal::lift_direct(p, up, 0.0);
  for (std::size_t k = 0; k < a->offset.size(); ++k) {
    // lift_direct gives f - g(x - s) with g = rotate180(p) placed on p's frame: same as ours up
    // to the constant h(0).
    EXPECT_NEAR(a->lift[k] - a->lift[0], frictal::lift_direct(p, up, a->offset[k]) - h0, 1e-20) << k;
  }
}

TEST(ArealSignature, TiltedPlaneGivesItsTilt) {
  // f = t x on both blocks: turned over, the upper face is -t (2c - x + s): h(s) = t (2c + s),
  // contact slopes are t everywhere.
  const double t = 0.2;
  frictal::Map m;
  m.nx = 30;
  m.ny = 20;
  m.dx = m.dy = 1e-6;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) m.heights.push_back(t * double(i) * m.dx);
  auto a = frictal::areal_signature(m, m, 0.0);
  ASSERT_TRUE(a.ok());
  EXPECT_NEAR(a->theta_max_forward, std::atan(t), 1e-12);
  EXPECT_NEAR(a->theta_max_lift, std::atan(t), 1e-9);
  EXPECT_NEAR(a->contact_slope_std, 0, 1e-9);
  // Across the tilt (along y) nothing resists.
  auto b = frictal::areal_signature(m, m, kPi / 2);
  ASSERT_TRUE(b.ok());
  EXPECT_NEAR(b->theta_max_forward, 0, 1e-12);
}

TEST(Anisotropy, RidgesResistAcrossNotAlong) {
  auto m = ridges(200, 200, 1e-7, bumpy);
  frictal::DirectionalOptions o;
  o.max_lines = 16;
  auto table = frictal::anisotropy(m, 8, o);
  ASSERT_TRUE(table.ok()) << table.error().message;
  ASSERT_EQ(table->size(), 8u);
  // Along y (90 and 270 deg) every line is flat: theta = 0. Across (0, 180 deg) it is the
  // profile's own self-signature maximum.
  EXPECT_NEAR((*table)[2].theta_forward, 0, 1e-12);
  EXPECT_NEAR((*table)[6].theta_forward, 0, 1e-12);
  frictal::Profile p;
  for (std::size_t i = 0; i < m.nx; ++i) {
    p.x.push_back(double(i) * m.dx);
    p.z.push_back(m.at(i, 0));
  }
  auto s = frictal::self_signature(p);
  ASSERT_TRUE(s.ok());
  EXPECT_NEAR((*table)[0].theta_forward, s->theta_max_forward, 1e-9);
  EXPECT_NEAR((*table)[0].theta_backward, s->theta_max_backward, 1e-9);
  EXPECT_GT((*table)[0].theta_forward, 0.05);
  EXPECT_NEAR((*table)[0].prediction.friction_angle, s->theta_max_forward, 1e-9);  // mu_a = 0
}

TEST(Anisotropy, ThreadsDoNotChangeTheResult) {
  auto m = rough(120);
  frictal::DirectionalOptions o;
  o.max_lines = 24;
  o.min_points = 16;
  auto one = frictal::friction_along(m, 0.6, o);
  o.threads = 3;
  auto three = frictal::friction_along(m, 0.6, o);
  ASSERT_TRUE(one.ok() && three.ok()) << (one.ok() ? three.error().message : one.error().message);
  EXPECT_EQ(one->lines, three->lines);
  EXPECT_EQ(one->theta_forward, three->theta_forward);
  EXPECT_EQ(one->sigma, three->sigma);
}

TEST(ArealSignature, UpperInPlaceAndContactSlopeRules) {
  // In place (not turned over): a translated copy g = f slides on f; with f = t x along x,
  // h(s) = max f(p) - f(p - s d) = t s, so theta = atan(t) by either slope rule.
  const double t = 0.15;
  frictal::Map m;
  m.nx = 25;
  m.ny = 12;
  m.dx = m.dy = 2e-6;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) m.heights.push_back(t * double(i) * m.dx);
  for (auto rule : {frictal::ArealContactSlope::Lower, frictal::ArealContactSlope::Mean}) {
    frictal::ArealSignatureOptions o;
    o.turn_over_upper = false;
    o.contact_slope = rule;
    auto a = frictal::areal_signature(m, m, 0.0, o);
    ASSERT_TRUE(a.ok()) << a.error().message;
    for (std::size_t k = 0; k < a->lift.size(); ++k) EXPECT_NEAR(a->lift[k], t * a->offset[k], 1e-18);
    EXPECT_NEAR(a->theta_max_forward, std::atan(t), 1e-12);
    o.prune = false;
    auto d = frictal::areal_signature(m, m, 0.0, o);
    ASSERT_TRUE(d.ok());
    EXPECT_EQ(d->lift, a->lift);
  }
  // Turned over, the Mean rule on the rough map still matches the direct scan exactly.
  auto f = rough(60);
  frictal::ArealSignatureOptions o;
  o.contact_slope = frictal::ArealContactSlope::Mean;
  auto fast = frictal::areal_signature(f, f, 1.0, o);
  o.prune = false;
  auto direct = frictal::areal_signature(f, f, 1.0, o);
  ASSERT_TRUE(fast.ok() && direct.ok());
  EXPECT_EQ(fast->theta, direct->theta);
}

TEST(ArealSettings, EachFieldFillsItsMemberAndTheDefaultsAreTheStructs) {
  using frictal::find_field;
  const frictal::ArealSignatureSettings d;
  const auto& t = frictal::areal_signature_settings();
  EXPECT_EQ(find_field(t, "direction")->default_value, d.direction);
  EXPECT_EQ(find_field(t, "in_place")->default_value, d.options.turn_over_upper ? 0 : 1);
  EXPECT_TRUE(std::isnan(find_field(t, "step")->default_value));  // automatic: min(dx, dy)
  EXPECT_TRUE(std::isnan(find_field(t, "max_offset")->default_value));
  // The prediction's quantities are its fields (one help), the contact slope one field in both tables.
  for (const char* shared : {"direction", "in_place", "atomic_friction"})
    EXPECT_EQ(find_field(t, shared)->help, find_field(frictal::predict_settings(), shared)->help) << shared;
  EXPECT_EQ(find_field(t, "contact_slope")->help, find_field(frictal::anisotropy_settings(), "contact_slope")->help);
  auto a = frictal::make_areal_signature_settings({{"direction", 0.5},
                                                   {"atomic_friction", 0.3},
                                                   {"step", 2e-6},
                                                   {"max_offset", 4e-5},
                                                   {"contact_slope", std::string("mean")},
                                                   {"in_place", true}});
  ASSERT_TRUE(a) << a.error().message;
  EXPECT_EQ(a->direction, 0.5);
  EXPECT_EQ(a->atomic_friction, 0.3);
  EXPECT_EQ(a->options.step, 2e-6);
  EXPECT_EQ(a->options.offset_max, 4e-5);
  EXPECT_EQ(a->options.contact_slope, frictal::ArealContactSlope::Mean);
  EXPECT_FALSE(a->options.turn_over_upper);
  auto automatic = frictal::make_areal_signature_settings({{"step", std::nan("")}});
  ASSERT_TRUE(automatic);
  EXPECT_EQ(automatic->options.step, 0);  // areal.hpp: 0 is min(dx, dy)
  const frictal::AnisotropySettings pd;
  const auto& p = frictal::anisotropy_settings();
  EXPECT_EQ(find_field(p, "directions")->default_value, pd.directions);
  EXPECT_EQ(find_field(p, "lines")->default_value, double(pd.lines.max_lines));
  auto s = frictal::make_anisotropy_settings({{"directions", std::int64_t{12}},
                                              {"lines", std::int64_t{9}},
                                              {"atomic_friction", 0.1},
                                              {"areal", true},
                                              {"contact_slope", std::string("mean")}});
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(s->directions, 12);
  EXPECT_EQ(s->lines.max_lines, 9u);
  EXPECT_EQ(s->lines.atomic_friction, 0.1);
  EXPECT_TRUE(s->areal);
  EXPECT_EQ(s->contact_slope, frictal::ArealContactSlope::Mean);
  auto bad = frictal::make_anisotropy_settings({{"directions", std::int64_t{3601}}});
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("directions: expected a whole number in 1..3600, got 3601"), std::string::npos)
      << bad.error().message;
  auto step = frictal::make_areal_signature_settings({{"step", 0.0}});
  ASSERT_FALSE(step);
  EXPECT_NE(step.error().message.find("step: expected a number > 0 m, got 0"), std::string::npos)
      << step.error().message;
}
