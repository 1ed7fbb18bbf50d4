// CLI: `frictal areal` with the hold angle over two dimensions of offset, `anisotropy --hold`.
// The maps are written here: sinusoidal grooves at 30 deg to x on a grid whose diagonal runs
// along them (the lift's closed form and hold angles: tests/analysis/test_areal_hold.cpp).
#include <fmt/core.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>

#include "cli/cli_runner.hpp"
#include "frictal/areal.hpp"
#include "frictal/io.hpp"

namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kA = 2e-7, kStep = 1e-7;
constexpr int kM = 40;

/// Grooves A sin(2 pi (i - j) / m) on dx = a, dy = a tan(30 deg), written as X3P (float64).
const std::string& groove_file() {
  static const std::string path = [] {
    frictal::Map f;
    f.nx = f.ny = 100;
    f.dx = kStep;
    f.dy = kStep * std::tan(kPi / 6);
    for (std::size_t j = 0; j < f.ny; ++j)
      for (std::size_t i = 0; i < f.nx; ++i) f.heights.push_back(kA * std::sin(2 * kPi * (double(i) - double(j)) / kM));
    const std::string p = temp_path("grooves30.x3p");
    EXPECT_TRUE(frictal::write_x3p(p, f).ok());
    return p;
  }();
  return path;
}

std::string groove_args() {
  return groove_file() +
         fmt::format(" --in-place --detrend none --step {:.17g} --across-step {:.17g}", kStep,
                     kStep * std::tan(kPi / 6)) +
         " --min-offset -5e-7 --max-offset 2e-6 --across-max 1.5e-6";
}
}  // namespace

TEST(CliAreal, GroovesSteerWhenFreeAndHoldWhenLocked) {
  auto r = run_cli("areal " + groove_args() + " --lateral free --runaway-distance 1e-6 --start-offset 0,0 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["hold_angle_deg"].get<double>(), 0, 1e-7);
  EXPECT_NEAR(j["steering_deg"].get<double>(), 30, 1e-9);
  // Locked: atan of the forward slope at the cusp, A sin(2 pi / m) / a (~ atan(A k sin 30 deg)).
  EXPECT_NEAR(j["hold_angle_locked_deg"].get<double>(), std::atan(kA * std::sin(2 * kPi / kM) / kStep) * 180 / kPi,
              1e-9);
  ASSERT_EQ(j["rest_offset_m"].size(), 2u);
  EXPECT_FALSE(j.contains("hold_angle_mean_deg"));  // a start: no distribution
  // The grid model is a diagnostic: said in the model key and by its warning code (the prediction
  // is `frictal predict`, the continuous model).
  EXPECT_EQ(j["model"], "grid-lift");
  ASSERT_TRUE(j["warnings"].is_array());
  bool grid = false;
  for (const auto& w : j["warnings"]) grid = grid || w["code"] == "grid-model";
  EXPECT_TRUE(grid) << j["warnings"].dump();
  auto l = run_cli("areal " + groove_args() + " --lateral locked --runaway-distance 1e-6 --start-offset 0,0 --json");
  ASSERT_EQ(l.code, 0) << l.err;
  auto jl = nlohmann::json::parse(l.out);
  EXPECT_EQ(jl["hold_angle_deg"], j["hold_angle_locked_deg"]);
}

TEST(CliAreal, DistributionMatchesTheLibrary) {
  auto r = run_cli("areal " + groove_args() + " --runaway-distance 1e-6 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  for (const char* k :
       {"hold_angle_mean_deg", "hold_angle_std_deg", "hold_angle_q05_deg", "hold_angle_q50_deg", "hold_angle_q95_deg",
        "hold_angle_min_deg", "hold_angle_max_deg", "hold_angle_deg", "hold_angle_locked_deg", "rest_offset_m"})
    EXPECT_TRUE(j.contains(k)) << k;
  // Every drop on the grooves steers along them at once.
  EXPECT_NEAR(j["hold_angle_max_deg"].get<double>(), 0, 1e-7);
  auto m = frictal::read_map(groove_file());
  ASSERT_TRUE(m.ok());
  frictal::ArealLiftOptions lo;
  lo.turn_over_upper = false;
  lo.step = kStep;
  lo.across_step = kStep * std::tan(kPi / 6);
  lo.offset_min = -5e-7;
  lo.offset_max = 2e-6;
  lo.across_max = 1.5e-6;
  auto lift = frictal::areal_lift(*m, *m, 0.0, lo);
  ASSERT_TRUE(lift.ok());
  EXPECT_EQ(j["offsets_along"], lift->n_along);
  EXPECT_EQ(j["offsets_across"], lift->n_across);
  frictal::ArealHoldOptions ho;
  ho.runaway_distance = 1e-6;
  ho.lateral = frictal::LateralMotion::Locked;
  auto locked = frictal::areal_hold_distribution(*lift, ho);
  ASSERT_TRUE(locked.ok());
  auto rl = run_cli("areal " + groove_args() + " --runaway-distance 1e-6 --lateral locked --json");
  ASSERT_EQ(rl.code, 0) << rl.err;
  auto jl = nlohmann::json::parse(rl.out);
  EXPECT_NEAR(jl["hold_angle_mean_deg"].get<double>(), locked->hold.mean * 180 / kPi, 1e-9);
  EXPECT_NEAR(jl["hold_angle_q95_deg"].get<double>(), locked->hold.q95 * 180 / kPi, 1e-9);
  EXPECT_EQ(jl["drops"], locked->drops);
  // Text output: one line a person reads.
  auto t = run_cli("areal " + groove_args() + " --runaway-distance 1e-6");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("free to move sideways"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("drops"), std::string::npos) << t.out;
}

TEST(CliAreal, BadInputExitsTwoNamingTheValue) {
  const std::string base = "areal " + groove_args() + " --runaway-distance 1e-6";
  auto a = run_cli(base + " --angle nan");
  EXPECT_EQ(a.code, 2);
  EXPECT_NE(a.err.find("--angle"), std::string::npos) << a.err;
  EXPECT_NE(a.err.find("finite"), std::string::npos) << a.err;
  auto s = run_cli(base + " --start-offset 1,0");
  EXPECT_EQ(s.code, 2);
  EXPECT_NE(s.err.find("start offset (1, 0)"), std::string::npos) << s.err;
  EXPECT_NE(s.err.find("expected u in"), std::string::npos) << s.err;
  EXPECT_EQ(run_cli(base + " --start-offset 1e-7").code, 2);
  EXPECT_EQ(run_cli(base + " --lateral sideways").code, 2);
  EXPECT_EQ(run_cli("areal " + groove_args() + " --runaway-distance -1").code, 2);
  // Maps that never overlap along the direction over the offsets asked for.
  auto o =
      run_cli("areal " + groove_file() + " --in-place --min-offset 1 --max-offset 1.000001 --runaway-distance 1e-6");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("overlap"), std::string::npos) << o.err;
}

TEST(CliAreal, AnisotropyGainsTheHoldAngles) {
  auto r = run_cli("anisotropy " + groove_file() + " --detrend none --directions 2 --lines 8 --hold --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["directions"].size(), 2u);
  for (const auto& row : j["directions"]) {
    EXPECT_TRUE(row.contains("hold_angle_free_mean_deg"));
    EXPECT_TRUE(row.contains("hold_angle_locked_mean_deg"));
    EXPECT_LE(row["hold_angle_free_mean_deg"].get<double>(), row["hold_angle_locked_mean_deg"].get<double>() + 1e-9);
  }
  EXPECT_EQ(run_cli("anisotropy " + groove_file() + " --runaway-distance 1e-6").code, 2);
}

TEST(CliAreal, ArealTiltRefusesBadInputBeforeSimulating) {
  auto a = run_cli("areal-tilt " + groove_file() + " --angle inf --json");
  EXPECT_EQ(a.code, 2);
  EXPECT_NE(a.err.find("--angle"), std::string::npos) << a.err;
  EXPECT_EQ(run_cli("areal-tilt " + groove_file() + " --tilt-step 0").code, 2);
}

TEST(CliAreal, ArealTiltPredictsOnTheSimulatedSurfaces) {
  // --predict-only (no MuJoCo needed): a 6 x 6 window of the grooves in place. The grooves run
  // along the height field's diagonal, so the triangulated valley is straight: free slides within
  // the first 0.1 deg increment; locked along x climbs the steepest face, slope A sin(2 pi / m) / a.
  frictal::Map g;
  g.nx = g.ny = 6;
  g.dx = kStep;
  g.dy = kStep * std::tan(kPi / 6);
  g.x0 = 40 * g.dx;
  g.y0 = 40 * g.dy;
  for (std::size_t j = 0; j < 6; ++j)
    for (std::size_t i = 0; i < 6; ++i)
      g.heights.push_back(kA * std::sin(2 * kPi * (double(i) - double(j)) / kM));  // i - j as the lower's
  const std::string upper = temp_path("grooves30-window.x3p");
  ASSERT_TRUE(frictal::write_x3p(upper, g).ok());
  const std::string args =
      "areal-tilt " + groove_file() + " " + upper +
      " --in-place --detrend none --predict-only --runaway-distance 5e-7 --prediction-refine 2 --json";
  auto f = run_cli(args);
  ASSERT_EQ(f.code, 0) << f.err;
  auto jf = nlohmann::json::parse(f.out);
  EXPECT_FALSE(jf.contains("friction_angle_deg"));
  EXPECT_LE(jf["continuous_hold_angle_deg"].get<double>(), 0.1);
  EXPECT_NEAR(jf["continuous_steering_deg"].get<double>(), 30, 0.5);
  auto l = run_cli(args + " --lateral locked");
  ASSERT_EQ(l.code, 0) << l.err;
  auto jl = nlohmann::json::parse(l.out);
  const double expected = std::atan(kA * std::sin(2 * kPi / kM) / kStep) * 180 / kPi;
  EXPECT_GE(jl["continuous_hold_angle_deg"].get<double>(), expected - 1e-7);
  EXPECT_LE(jl["continuous_hold_angle_deg"].get<double>(), expected + 0.012);  // bisected to 1e-4 rad
  EXPECT_NEAR(jl["matched_hold_angle_locked_deg"].get<double>(), expected, 0.012);
  // Bad input names the option.
  for (const std::string bad :
       {"--lateral sideways", "--collision mpr", "--prediction-refine 17", "--start-offset 1e-6", "--local-damping 1",
        "--mujoco-time-step 0", "--rest-steps 0", "--coarse-tilt-step 0"}) {
    auto b = run_cli(args + " " + bad);
    EXPECT_EQ(b.code, 2) << bad;
    EXPECT_NE(b.err.find(bad.substr(0, bad.find(' '))), std::string::npos) << bad << ": " << b.err;
  }
}
