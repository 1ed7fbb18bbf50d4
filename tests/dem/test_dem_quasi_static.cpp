// The quasi-static tilt protocol (TiltConfig::protocol = QuasiStatic): expected angles derived by
// hand. The tilt grows in increments of `tilt_increment`; the block holds at a tilt beta while
// the slope that carries it is at least tan(beta), and the friction angle is the last increment
// at which it relaxed to rest, so a hold angle phi reads as floor(phi / inc) * inc.
#include <gtest/gtest.h>

#include <utility>

#include <cmath>
#include <cstdlib>
#include <string>

#include "frictal/analysis.hpp"
#include "frictal/generators.hpp"
#include "frictal/hold.hpp"
#include "frictal/io.hpp"
#include "frictal/signature.hpp"
#include "frictal/tilt.hpp"

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

frictal::Curve flat(double length) {
  frictal::Curve c;
  c.x = {0.0, length};
  c.z = {0.0, 0.0};
  return c;
}

frictal::Curve koch0(double alpha_deg, double length) {
  frictal::KochParams p;
  p.iterations = 0;
  p.alpha = alpha_deg * kDeg;
  p.wavelength = 0.01;
  p.length = length;
  auto c = frictal::koch_curve(p);
  EXPECT_TRUE(c.ok());
  return *c;
}

frictal::TiltConfig quasi_static(double increment_deg) {
  frictal::TiltConfig cfg;
  cfg.protocol = frictal::TiltProtocol::QuasiStatic;
  cfg.tilt_increment = increment_deg * kDeg;
  cfg.series_interval = 0;
  return cfg;
}

// The reference WM pair (seeds 1 and 2; D = 1.5, n_max = 6, L = 0.01 m, L_b = 0.2 m) at rms height
// `rms` (m), as curves for run_tilt.
std::pair<frictal::Curve, frictal::Curve> reference_wm_pair(double rms) {
  frictal::WmParams w;
  w.dimension = 1.5;
  w.n_max = 6;
  w.longest_wavelength = 0.01;
  w.length = 0.2;
  w.rms_height = rms;
  w.seed = 1;
  auto a = frictal::wm_profile(w);
  w.seed = 2;
  auto b = frictal::wm_profile(w);
  EXPECT_TRUE(a.ok() && b.ok());
  return {frictal::as_curve(*a), frictal::as_curve(*b)};
}

}  // namespace

TEST(DemQuasiStatic, FlatBlockSlidesAtTheLastIncrementBelowAtanMuA) {
  // A flat block on a flat plane holds while tan(beta) <= mu_a. With increments of 0.1 deg:
  // atan(0.4) = 21.801 deg -> the last held increment is 21.8 deg; atan(0.6) = 30.964 deg ->
  // 30.9 deg (neither lies within 0.001 deg of an increment, so neither is marginal).
  for (double mu : {0.4, 0.6}) {
    frictal::TiltConfig cfg = quasi_static(0.1);
    cfg.contact.atomic_friction = mu;
    cfg.predict = false;
    cfg.initial_offset = 0.01;
    cfg.runaway_distance = 1e-3;
    auto r = frictal::run_tilt(flat(0.1), flat(0.1), cfg);
    ASSERT_TRUE(r.ok()) << r.error().message;
    ASSERT_TRUE(r->slid);
    const double expected = std::floor(std::atan(mu) / kDeg / 0.1) * 0.1;
    EXPECT_NEAR(r->friction_angle / kDeg, expected, 1e-6) << "mu_a = " << mu;
    EXPECT_EQ(r->unrelaxed_increments, 0);
    for (const frictal::Warning& w : r->warnings) EXPECT_NE(w.code, "unrelaxed") << w.message;
    // A flat pair put down at 1 cm rests there.
    EXPECT_NEAR(r->rest_offset, 0.01, 1e-6);
  }
}

TEST(DemQuasiStatic, KochK0HoldsUpToAlphaBothWays) {
  // K_0 at alpha = 20 deg (Table I block, 0.2 m), mu_a = 0, rotation held: the block rests on flanks of slope alpha and
  // is held while tan(beta) <= tan(alpha); with increments of 0.3 deg the last held one is
  // 19.8 deg (20.1 deg passes alpha), in either direction by symmetry.
  const frictal::Curve k0 = koch0(20, 0.2);
  for (bool reverse : {false, true}) {
    frictal::TiltConfig cfg = quasi_static(0.3);
    cfg.reverse = reverse;
    cfg.hold_rotation = true;
    auto r = frictal::run_tilt(k0, k0, cfg);
    ASSERT_TRUE(r.ok()) << r.error().message;
    ASSERT_TRUE(r->slid) << (reverse ? "reverse" : "forward");
    EXPECT_NEAR(r->friction_angle / kDeg, 19.8, 1e-6) << (reverse ? "reverse" : "forward");
    EXPECT_EQ(r->unrelaxed_increments, 0);
    // The lift of K_0 on itself is a zigzag of slopes +-tan(alpha) with its minima half a
    // wavelength from the start: the block rests at 5 mm, and from there both the quasi-static
    // hold angle and the inertial bound (steepest chord within one wavelength ahead) are alpha;
    // the rounded blocks' flanks have the same slope.
    EXPECT_NEAR(r->rest_offset, 0.005, 1e-6);
    EXPECT_NEAR(r->predicted_hold_angle / kDeg, 20.0, 1e-6);
    EXPECT_NEAR(r->predicted_inertial_hold_angle / kDeg, 20.0, 1e-6);
    // (the spheropolygon lift has arcs at the tips: its LiftCurve keeps the tangent slopes to ~1e-5 deg)
    EXPECT_NEAR(r->predicted_sphero_hold_angle / kDeg, 20.0, 1e-4);
  }
}

TEST(DemQuasiStatic, ConstantRateRunReportsTheHoldPredictionsToo) {
  // The paper's protocol on K_0 at alpha = 20 deg: the block settles in the groove at half a
  // wavelength (5 mm) and the hold angles from there are alpha (see above).
  frictal::TiltConfig cfg;
  cfg.series_interval = 0;
  auto r = frictal::run_tilt(koch0(20, 0.05), koch0(20, 0.05), cfg);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_NEAR(r->rest_offset, 0.005, 1e-5);
  EXPECT_NEAR(r->predicted_hold_angle / kDeg, 20.0, 1e-6);
  EXPECT_NEAR(r->predicted_inertial_hold_angle / kDeg, 20.0, 1e-6);
  EXPECT_TRUE(r->hold_error.empty()) << r->hold_error;
}

#ifdef FRICTAL_TEST_DATA
TEST(DemQuasiStatic, HoldPredictionFollowsSlipsBeyondRestPlusD) {
  // The README's measured pair (two halves of a Dektak scan, each scaled to 0.2 m, form removed):
  // from where the block rests, the chain of short slips ends more than d = 1 cm ahead, so a lift
  // cut at rest + d would call the slip a run-off. The prediction must equal hold_angle() on the
  // lift over the whole overlap (an independent choice of range).
  auto scan = frictal::read_profile(std::string(FRICTAL_TEST_DATA) + "/profiles/dektak-1.csv");
  ASSERT_TRUE(scan.ok()) << scan.error().message;
  const std::size_t m = scan->z.size();
  std::vector<double> x, z;
  for (std::size_t i = 0; i < m; i += 4) {
    x.push_back(scan->x.back() * static_cast<double>(i) / static_cast<double>(m - 1));
    z.push_back(scan->z[i]);
  }
  const std::size_t n = x.size() / 2;
  const double scale = 0.2 / (x[n - 1] - x[0]);
  auto form = frictal::parse_detrend("poly:2");
  ASSERT_TRUE(form.ok());
  frictal::Profile half[2];
  for (int h = 0; h < 2; ++h) {
    frictal::Profile p;
    for (std::size_t i = 0; i < n; ++i) {
      p.x.push_back(scale * (x[h * n + i] - x[h * n]));
      p.z.push_back(scale * z[h * n + i]);
    }
    auto d = frictal::detrend(p, *form);
    ASSERT_TRUE(d.ok()) << d.error().message;
    half[h] = std::move(*d);
  }
  frictal::TiltConfig cfg;
  cfg.period = 0;
  cfg.series_interval = 0;
  cfg.max_tilt = 0.5 * kDeg;  // the predictions do not depend on how far the run goes
  auto r = frictal::run_tilt(frictal::as_curve(half[0]), frictal::as_curve(half[1]), cfg);
  ASSERT_TRUE(r.ok()) << r.error().message;
  frictal::SignatureOptions so;
  so.keep_contacts = false;
  so.offset_min = -0.2 * (1 - 1e-6);
  so.offset_max = 0.2 * (1 - 1e-6);
  auto sig = frictal::signature(half[0], frictal::rotate180(half[1]), so);
  ASSERT_TRUE(sig.ok()) << sig.error().message;
  auto lift = frictal::lift_curve(*sig);
  ASSERT_TRUE(lift.ok()) << lift.error().message;
  frictal::HoldOptions ho;
  ho.runaway_distance = cfg.runaway_distance;
  auto h = frictal::hold_angle(*lift, r->rest_offset, ho);
  ASSERT_TRUE(h.ok()) << h.error().message;
  EXPECT_GT(h->forward.hold_offset - r->rest_offset, cfg.runaway_distance);  // the case in point
  EXPECT_NEAR(r->predicted_hold_angle, h->forward.hold_angle, 1e-9);
  EXPECT_NEAR(r->predicted_hold_offset, h->forward.hold_offset, 1e-9);
}
#endif

TEST(DemQuasiStatic, StiffnessCheckKeepsTheAngleOfRigidFlanks) {
  // K_0's flanks are straight: ten times the stiffness leaves the hold at alpha, so the check
  // finds the same last increment (19.8 deg) and does not warn.
  frictal::TiltConfig cfg = quasi_static(0.3);
  cfg.hold_rotation = true;
  cfg.check_stiffness = true;
  auto r = frictal::run_tilt(koch0(20, 0.2), koch0(20, 0.2), cfg);
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_TRUE(r->slid);
  EXPECT_NEAR(r->stiff_friction_angle / kDeg, 19.8, 1e-6);
  for (const frictal::Warning& w : r->warnings) EXPECT_NE(w.code, "stiffness") << w.message;
}

TEST(DemQuasiStatic, RejectsBadRelaxationSettings) {
  frictal::TiltConfig cfg = quasi_static(0.1);
  cfg.relax_force = 0;
  auto r = frictal::run_tilt(flat(0.05), flat(0.05), cfg);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("relax_force"), std::string::npos);
  cfg = quasi_static(0.1);
  cfg.tilt_increment = 0;
  r = frictal::run_tilt(flat(0.05), flat(0.05), cfg);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("tilt_increment"), std::string::npos);
}

TEST(DemQuasiStatic, UnrelaxedWarningWhenTheBudgetIsTooShort) {
  // A relaxation budget of one engine step cannot bring the dropped block to rest.
  frictal::TiltConfig cfg = quasi_static(1.0);
  cfg.contact.atomic_friction = 0.2;
  cfg.predict = false;
  cfg.initial_offset = 0.01;
  cfg.relax_time = 1e-4;
  cfg.relax_duration = 0;
  cfg.max_tilt = 5 * kDeg;
  auto r = frictal::run_tilt(flat(0.05), flat(0.05), cfg);
  ASSERT_TRUE(r.ok()) << r.error().message;
  bool unsettled = false, unrelaxed = false;
  for (const frictal::Warning& w : r->warnings) {
    unsettled |= w.code == "unsettled";
    unrelaxed |= w.code == "unrelaxed";
  }
  EXPECT_TRUE(unsettled);
  EXPECT_TRUE(unrelaxed);
  EXPECT_GT(r->unrelaxed_increments, 0);
}

#ifdef FRICTAL_CLI_PATH
TEST(DemQuasiStaticCli, JsonGivesTheRestOffsetAndTheHoldAngles) {
  const std::string cli = FRICTAL_CLI_PATH;
  const std::string out = ::testing::TempDir() + "frictal_qs.json";
  ASSERT_EQ(std::system((cli +
                         " tilt koch --alpha 20 --protocol quasi-static --tilt-increment 0.3 --hold-rotation "
                         "--json > " +
                         out + " 2> /dev/null")
                            .c_str()),
            0);
  std::FILE* f = std::fopen(out.c_str(), "r");
  ASSERT_NE(f, nullptr);
  std::string text;
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, f)) text.append(buf, n);
  std::fclose(f);
  for (const char* key : {"\"rest_offset_m\"", "\"predicted_hold_angle_deg\"", "\"predicted_inertial_hold_angle_deg\"",
                          "\"predicted_sphero_hold_angle_deg\"", "\"protocol\":\"quasi-static\""})
    EXPECT_NE(text.find(key), std::string::npos) << key << " in " << text.substr(0, 400);
  const std::string key = "\"friction_angle_deg\":";
  const std::size_t at = text.find(key);
  ASSERT_NE(at, std::string::npos);
  EXPECT_NEAR(std::stod(text.substr(at + key.size())), 19.8, 1e-6);  // as in KochK0HoldsUpToAlphaBothWays
}

TEST(DemQuasiStaticCli, UnknownProtocolExitsWithTwoNamingTheChoices) {
  const std::string cli = FRICTAL_CLI_PATH;
  const std::string out = ::testing::TempDir() + "frictal_protocol_err.txt";
  EXPECT_EQ(std::system((cli + " tilt koch --protocol slow > /dev/null 2> " + out).c_str()), 2 << 8);
  std::FILE* f = std::fopen(out.c_str(), "r");
  ASSERT_NE(f, nullptr);
  std::string text;
  char buf[512];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, f)) text.append(buf, n);
  std::fclose(f);
  EXPECT_NE(text.find("--protocol"), std::string::npos) << text;
  EXPECT_NE(text.find("slow"), std::string::npos) << text;
  EXPECT_NE(text.find("quasi-static"), std::string::npos) << text;
  EXPECT_NE(text.find("constant-rate"), std::string::npos) << text;
}
#endif

TEST(DemQuasiStatic, ClosestContactsReadTheHoldAngleOfTheReferenceWmPair) {
  // The reference WM pair (seeds 1, 2; D = 1.5, n_max = 6, L = 0.01 m, L_b = 0.2 m), rotation held,
  // r = 2e-5 m, d = 1 cm: from the rest offset 23.8 mm an independent numpy computation of the
  // rigid lift gives phi_qs = 1.549 deg. With the contact rule of the quasi-static protocol
  // (auto: closest) the run reads it at k_n = 6e7 N/m, the flat pair's stiffness of the issue's
  // target: the last increment below 1.549 deg (at most 0.01 deg low). Ten times rougher (rms
  // 1e-4 m) phi_qs is 15.132 deg (hold_angle on the same lift), read at 6e6 N/m.
  for (double rms : {1e-5, 1e-4}) {
    const auto [lower, upper] = reference_wm_pair(rms);
    frictal::TiltConfig cfg = quasi_static(0.01);
    cfg.hold_rotation = true;
    cfg.radius = 2e-5;
    cfg.runaway_distance = 0.01;
    cfg.initial_offset = 0.023791495198902606;  // where `frictal tilt` puts these files (the start)
    cfg.contact.normal_stiffness = rms < 5e-5 ? 6e7 : 6e6;
    auto r = frictal::run_tilt(lower, upper, cfg);
    ASSERT_TRUE(r.ok()) << r.error().message;
    ASSERT_TRUE(r->slid);
    EXPECT_EQ(r->contact_rule, frictal::dem::ContactRule::Closest);
    EXPECT_NEAR(r->rest_offset, 0.02382, 2e-5);
    const double phi = r->friction_angle / kDeg, phi_qs = r->predicted_hold_angle / kDeg;
    if (rms < 5e-5) {
      EXPECT_NEAR(phi_qs, 1.549, 5e-4);
    }
    EXPECT_LE(phi, phi_qs + 1e-9) << "rms " << rms;
    EXPECT_GT(phi, phi_qs - 0.01 - 1e-9) << "rms " << rms;
    EXPECT_EQ(r->unrelaxed_increments, 0);
  }
}

TEST(DemQuasiStatic, ClosestReadsAStartWhereAConvexCornerCrossesAConcaveBend) {
  // The WM pair (flat, rms 1e-5 m) put down at 3.5 mm instead: it rests at 3.51 mm and
  // holds, in the rigid lift analysis of the rounded blocks, up to predicted_hold_angle (1.451
  // deg). Before concave corners were counted by inclusion-exclusion (docs/dem.md sec. 1, rule
  // 3) the run held up to 1.55 deg at a stop where a convex corner of the lower block slides past
  // a concave bend of the upper one. Now the last increment below the prediction.
  const auto [lower, upper] = reference_wm_pair(1e-5);
  frictal::TiltConfig cfg = quasi_static(0.01);
  cfg.hold_rotation = true;
  cfg.radius = 2e-5;
  cfg.runaway_distance = 0.01;
  cfg.initial_offset = 3.5e-3;
  cfg.contact.normal_stiffness = 6e7;
  auto r = frictal::run_tilt(lower, upper, cfg);
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_TRUE(r->slid);
  EXPECT_NEAR(r->rest_offset, 3.51e-3, 1e-5);
  const double phi = r->friction_angle / kDeg, phi_qs = r->predicted_sphero_hold_angle / kDeg;
  EXPECT_LE(phi, phi_qs + 1e-9);
  EXPECT_GT(phi, phi_qs - 0.01 - 1e-9);
}

TEST(DemTilt, ConstantRateFromRestWithGravityTurningReadsKochK0AndFlatAngles) {
  // settling = relax, turn = gravity: the block relaxes to rest and gravity turns at tilt_rate in
  // the lower block's frame. Hand-derived angles as for the paper's protocol: K0 at alpha = 20
  // deg (mu_a = 0) slides at alpha both ways (Eq. 6, theta_max = alpha); a flat pair with
  // mu_a = 0.3 at atan(0.3) = 16.70 deg.
  for (bool reverse : {false, true}) {
    frictal::TiltConfig cfg;
    cfg.settling = frictal::TiltSettling::Relax;
    cfg.turn = frictal::TiltTurn::Gravity;
    cfg.reverse = reverse;
    cfg.series_interval = 0;
    auto r = frictal::run_tilt(koch0(20, 0.05), koch0(20, 0.05), cfg);
    ASSERT_TRUE(r.ok()) << r.error().message;
    ASSERT_TRUE(r->slid);
    EXPECT_NEAR(r->friction_angle / kDeg, 20.0, 0.1) << (reverse ? "reverse" : "forward");
    EXPECT_LT(r->settled_speed, cfg.relax_speed);
    EXPECT_TRUE(r->warnings.empty()) << r->warnings.front().code;
  }
  frictal::TiltConfig cfg;
  cfg.settling = frictal::TiltSettling::Relax;
  cfg.turn = frictal::TiltTurn::Gravity;
  cfg.contact.atomic_friction = 0.3;
  cfg.predict = false;
  cfg.initial_offset = 0.01;
  cfg.series_interval = 0;
  auto f = frictal::run_tilt(flat(0.2), flat(0.2), cfg);
  ASSERT_TRUE(f.ok()) << f.error().message;
  ASSERT_TRUE(f->slid);
  EXPECT_NEAR(f->friction_angle / kDeg, std::atan(0.3) / kDeg, 0.1);
}

TEST(DemTilt, SlowTiltFromRestOfTheReferenceWmPairReadsInsideTheHoldBracket) {
  // The dynamic test from rest on the reference WM pair, rotation held,
  // r = 2e-5 m, d = 1 cm, k_n = 6e7 N/m, contact rule closest, relaxed at zero tilt, gravity
  // turning at 0.005 rad/s. From the rest offset (23.8 mm) the independent numpy values
  // are phi_in = 0.695 deg and phi_qs = 1.549 deg: the run reads between them (0.1 deg slack).
  // The paper's protocol does not: with free settling the frictionless block still glides when
  // the tilt starts ('unsettled', DemTilt.UnsettledWarningForTheReferenceWmPair).
  const auto [lower, upper] = reference_wm_pair(1e-5);
  frictal::TiltConfig cfg;
  cfg.settling = frictal::TiltSettling::Relax;
  cfg.turn = frictal::TiltTurn::Gravity;
  cfg.tilt_rate = 0.005;
  cfg.contact_rule = frictal::TiltContactRule::Closest;
  cfg.contact.normal_stiffness = 6e7;
  cfg.hold_rotation = true;
  cfg.radius = 2e-5;
  cfg.runaway_distance = 0.01;
  cfg.series_interval = 0;
  cfg.initial_offset = 0.023791495198902606;  // where `frictal tilt` puts these files
  auto r = frictal::run_tilt(lower, upper, cfg);
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_TRUE(r->slid);
  EXPECT_NEAR(r->rest_offset, 0.02382, 2e-5);
  EXPECT_LT(r->settled_speed, cfg.relax_speed);
  const double phi = r->friction_angle / kDeg;
  EXPECT_GE(phi, 0.695 - 0.1);
  EXPECT_LE(phi, 1.549 + 0.1);
}
