// CLI: `frictal areal --lateral` and `anisotropy --hold`, the hold angle of the continuous model
// (the numbers of `frictal predict`). The maps are written here: sinusoidal grooves at 30 deg to
// x on a grid whose diagonal runs along them (closed forms below).
#include <fmt/core.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "cli/cli_runner.hpp"
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

/// A 6 x 6 window of the grooves, in place at node (40, 40) (the same heights i - j as the lower).
const std::string& window_file() {
  static const std::string path = [] {
    frictal::Map g;
    g.nx = g.ny = 6;
    g.dx = kStep;
    g.dy = kStep * std::tan(kPi / 6);
    g.x0 = 40 * g.dx;
    g.y0 = 40 * g.dy;
    for (std::size_t j = 0; j < 6; ++j)
      for (std::size_t i = 0; i < 6; ++i) g.heights.push_back(kA * std::sin(2 * kPi * (double(i) - double(j)) / kM));
    const std::string p = temp_path("grooves30-window6.x3p");
    EXPECT_TRUE(frictal::write_x3p(p, g).ok());
    return p;
  }();
  return path;
}

// The window on the grooves in place (its face the lower one's own heights), no form removed: the
// surface that the continuous model evaluates is MuJoCo's triangulated height field, and with the
// grooves along the cells' diagonal (dy = dx tan 30 deg) it is exactly grooves of one profile
// across them. (A whole map nested in itself would put all its 10^4 spheres in contact at once: slow.)
std::string groove_args() { return groove_file() + " " + window_file() + " --in-place --detrend none"; }

/// A 25 x 42-node crop of the grooves (turned over against itself: a few seconds per prediction).
const std::string kCrop = " --crop 0,2.4e-6,0,2.4e-6";

/// The forward slope of the steepest face of the triangulated grooves along x, A sin(2 pi / m) / a:
/// the locked block's hold angle (the faces next to a groove's zero crossing are the steepest).
double locked_groove_angle_deg() { return std::atan(kA * std::sin(2 * kPi / kM) / kStep) * 180 / kPi; }

nlohmann::json json_of(const std::string& args) {
  auto r = run_cli(args);
  EXPECT_EQ(r.code, 0) << args << ": " << r.err;
  return r.code == 0 ? nlohmann::json::parse(r.out) : nlohmann::json::object();
}
}  // namespace

TEST(CliAreal, GroovesSteerWhenFreeAndHoldWhenLocked) {
  // One drop: free, the block slides along the grooves (30 deg off x) at the first tilt; locked to
  // x it climbs the steepest face. Bisected to 1e-4 rad = 0.0057 deg.
  auto j = json_of("areal " + groove_args() + " --lateral free --runaway-distance 1e-6 --start-offset 0,0 --json");
  EXPECT_EQ(j["model"], "map-continuous-free");
  EXPECT_LE(j["hold_angle_deg"].get<double>(), 0.1);
  EXPECT_NEAR(j["steering_deg"].get<double>(), 30, 0.5);
  ASSERT_EQ(j["rest_offset_m"].size(), 2u);
  EXPECT_FALSE(j.contains("hold_angle_q50_deg"));  // a start: no distribution
  EXPECT_FALSE(j.contains("friction_angle_deg"));  // the prediction's keys are predict's
  for (const auto& w : j["warnings"]) EXPECT_NE(w["code"], "grid-model");
  auto jl = json_of("areal " + groove_args() + " --lateral locked --runaway-distance 1e-6 --start-offset 0,0 --json");
  EXPECT_EQ(jl["model"], "map-continuous-locked");
  EXPECT_GE(jl["hold_angle_deg"].get<double>(), locked_groove_angle_deg() - 1e-7);
  EXPECT_LE(jl["hold_angle_deg"].get<double>(), locked_groove_angle_deg() + 0.012);
  EXPECT_EQ(jl["hold_angle_free_deg"], j["hold_angle_deg"]);
}

// Grooves a tenth as deep (facet slopes below 0.07): the continuous model reads each piece's
// window from the facet slopes around it (a tenth of the rough grooves' depth here) where every
// bound is below 0.5; the closed forms above hold the same.
TEST(CliAreal, ShallowGroovesKeepTheClosedFormsWithTheLocalWindows) {
  const double a = kA / 10;
  auto write = [&](std::size_t n, std::size_t at, const std::string& name) {
    frictal::Map g;
    g.nx = g.ny = n;
    g.dx = kStep;
    g.dy = kStep * std::tan(kPi / 6);
    g.x0 = double(at) * g.dx;
    g.y0 = double(at) * g.dy;
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = 0; i < n; ++i) g.heights.push_back(a * std::sin(2 * kPi * (double(i) - double(j)) / kM));
    const std::string path = temp_path(name);
    EXPECT_TRUE(frictal::write_x3p(path, g).ok());
    return path;
  };
  const std::string args = write(100, 0, "shallow-grooves.x3p") + " " + write(6, 40, "shallow-grooves-window6.x3p") +
                           " --in-place --detrend none --runaway-distance 1e-6";
  const double locked = std::atan(a * std::sin(2 * kPi / kM) / kStep) * 180 / kPi;  // 1.79 deg
  for (const std::string start : {"0,0", "1e-7,2e-7"}) {
    auto j = json_of("areal " + args + " --lateral free --start-offset " + start + " --json");
    EXPECT_LE(j["hold_angle_deg"].get<double>(), 0.1) << start;
    EXPECT_NEAR(j["steering_deg"].get<double>(), 30, 0.5) << start;
    auto l = json_of("areal " + args + " --lateral locked --start-offset " + start + " --json");
    EXPECT_GE(l["hold_angle_deg"].get<double>(), locked - 1e-7) << start;
    EXPECT_LE(l["hold_angle_deg"].get<double>(), locked + 0.012) << start;
  }
}

TEST(CliAreal, HoldOverDropsIsThePredictionToTheDigit) {
  // Free over drops: every drop slides along the grooves at once (closed form above), and the
  // numbers are `frictal predict`'s for the same options, to the last digit.
  const std::string opts = " --runaway-distance 1e-6 --drops 3 --json";
  auto j = json_of("areal " + groove_args() + " --lateral free" + opts);
  auto p = json_of("predict " + groove_args() + opts);
  ASSERT_TRUE(j.contains("hold_angle_q50_deg")) << j.dump();
  EXPECT_EQ(j["drops"], 9);
  // The closed form holds on every drop. The top row is put down r + D = 1.01 um from the lower
  // map's +y edge (predict's drop range); the free block descends up to 0.55 um sideways at zero
  // tilt (measured: drop 7 rests at (0.10, 2.66) um from (0.70, 2.11) um) and then slides along the
  // grooves, D tan 30 deg = 0.58 um further towards +y: the 6-node window (0.29 um across) leaves the
  // lower map before it has gone D along x, and a block off the map is a run-away (nothing holds it;
  // a wall there would hold it to 45 deg).
  for (int k = 0; k < 9; ++k) EXPECT_LE(j["drop_hold_angles_deg"][k].get<double>(), 0.1) << k;
  for (const std::string q : {"q05", "q95", "mean", "std", "min", "max"})
    EXPECT_EQ(j["hold_angle_" + q + "_deg"], p["friction_angle_" + q + "_deg"]) << q;
  EXPECT_EQ(j["hold_angle_q50_deg"], p["friction_angle_deg"]);
  EXPECT_EQ(j["drop_hold_angles_deg"], p["drop_friction_angles_deg"]);
  EXPECT_EQ(j["upper_bound_friction_angle_deg"], p["upper_bound_friction_angle_deg"]);
  EXPECT_EQ(j["runaway_distance_m"], p["runaway_distance_m"]);
  EXPECT_EQ(j["drop_range_m"], p["drop_range_m"]);
  EXPECT_EQ(j["conditioning"], p["conditioning"]);
  // Locked: every drop climbs the steepest face (closed form), = predict --locked's diagnostic.
  auto l = json_of("areal " + groove_args() + " --lateral locked" + opts);
  auto pl = json_of("predict " + groove_args() + " --locked" + opts);
  for (int k : {1, 4, 7}) {
    EXPECT_GE(l["drop_hold_angles_deg"][k].get<double>(), locked_groove_angle_deg() - 1e-7) << k;
    EXPECT_LE(l["drop_hold_angles_deg"][k].get<double>(), locked_groove_angle_deg() + 0.012) << k;
  }
  EXPECT_EQ(l["hold_angle_q50_deg"], pl["locked_friction_angle_deg"]);
  EXPECT_EQ(l["hold_angle_q05_deg"], pl["locked_friction_angle_q05_deg"]);
  EXPECT_EQ(l["hold_angle_q95_deg"], pl["locked_friction_angle_q95_deg"]);
  EXPECT_EQ(l["hold_angle_free_q50_deg"], pl["friction_angle_deg"]);
  // Turned over, along 30 deg, with atomic friction and the default form (a plane): still predict's.
  const std::string turned = groove_file() + " --crop 0,1.2e-6,0,1.2e-6 --atomic-friction 0.1 --drops 2 --json";
  auto t = json_of("areal " + turned + " --angle 30 --lateral free");
  auto pt = json_of("predict " + turned + " --direction 30");
  EXPECT_EQ(t["hold_angle_q50_deg"], pt["friction_angle_deg"]);
  EXPECT_EQ(t["hold_angle_q05_deg"], pt["friction_angle_q05_deg"]);
  EXPECT_EQ(t["hold_angle_q95_deg"], pt["friction_angle_q95_deg"]);
  EXPECT_GE(t["hold_angle_min_deg"].get<double>(), std::atan(0.1) * 180 / kPi - 1e-9);  // atan(mu_a) included
  // Text output: lines a person reads.
  auto r = run_cli("areal " + groove_args() + " --lateral free --runaway-distance 1e-6 --drops 2");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("free to move sideways"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("over 4 drops"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("map-continuous-free"), std::string::npos) << r.out;
}

TEST(CliAreal, BadInputExitsTwoNamingTheValue) {
  const std::string base = "areal " + groove_args() + " --runaway-distance 1e-6";
  auto a = run_cli(base + " --angle nan");
  EXPECT_EQ(a.code, 2);
  EXPECT_NE(a.err.find("--direction"), std::string::npos) << a.err;
  EXPECT_NE(a.err.find("finite"), std::string::npos) << a.err;
  auto s = run_cli(base + " --start-offset 1,0");
  EXPECT_EQ(s.code, 2);
  EXPECT_NE(s.err.find("start offset (1, 0)"), std::string::npos) << s.err;
  EXPECT_NE(s.err.find("expected within"), std::string::npos) << s.err;
  EXPECT_EQ(run_cli(base + " --start-offset 1e-7").code, 2);
  EXPECT_EQ(run_cli(base + " --lateral sideways").code, 2);
  EXPECT_EQ(run_cli(base + " --drops 1").code, 2);
  EXPECT_EQ(run_cli("areal " + groove_args() + " --runaway-distance -1").code, 2);
  // The grid lift's options have no counterpart in the continuous model: refused by name, or gone.
  for (const std::string opt : {"--step 1e-7", "--max-offset 2e-6", "--contact-slope mean", "--across-max 1e-6",
                                "--min-offset 0", "--across-step 1e-7"}) {
    auto b = run_cli(base + " --lateral free " + opt);
    EXPECT_EQ(b.code, 2) << opt;
    EXPECT_NE(b.err.find(opt.substr(0, opt.find(' '))), std::string::npos) << opt << ": " << b.err;
  }
  // A line profile is not a map.
  const std::string prof = temp_path("areal-profile.csv");
  {
    std::FILE* f = std::fopen(prof.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("x_m,z_m\n0,0\n1e-6,1e-7\n2e-6,0\n", f);
    std::fclose(f);
  }
  auto pr = run_cli("areal " + prof + " --lateral free");
  EXPECT_EQ(pr.code, 2);
  EXPECT_NE(pr.err.find("needs maps"), std::string::npos) << pr.err;
}

TEST(CliAreal, AnisotropyHoldIsThePredictionPerDirection) {
  auto j = json_of("anisotropy " + groove_file() + kCrop +
                   " --detrend none --directions 4 --lines 8 --hold --locked --drops 2 --runaway-distance 2e-7 --json");
  ASSERT_EQ(j["directions"].size(), 4u);
  EXPECT_EQ(j["hold_model"], "map-continuous-free");
  EXPECT_EQ(j["hold_drops"], 4);
  for (const auto& row : j["directions"]) {
    const double dir = row["direction_deg"].get<double>();
    auto p =
        json_of(fmt::format("predict {}{} --detrend none --direction {:g} --locked --drops 2 --runaway-distance "
                            "2e-7 --json",
                            groove_file(), kCrop, dir));
    EXPECT_EQ(row["hold_angle_q50_deg"], p["friction_angle_deg"]) << dir;
    EXPECT_EQ(row["hold_angle_q05_deg"], p["friction_angle_q05_deg"]) << dir;
    EXPECT_EQ(row["hold_angle_q95_deg"], p["friction_angle_q95_deg"]) << dir;
    EXPECT_EQ(row["hold_angle_mean_deg"], p["friction_angle_mean_deg"]) << dir;
    EXPECT_EQ(row["hold_angle_locked_q50_deg"], p["locked_friction_angle_deg"]) << dir;
    EXPECT_FALSE(row.contains("friction_angle_deg"));
  }
  for (const auto& w : j["warnings"]) EXPECT_NE(w["code"], "grid-model");
  EXPECT_EQ(run_cli("anisotropy " + groove_file() + " --runaway-distance 1e-6").code, 2);
  EXPECT_EQ(run_cli("anisotropy " + groove_file() + " --locked").code, 2);
  EXPECT_EQ(run_cli("anisotropy " + groove_file() + " --hold --drops 65").code, 2);
  // The whole job's cost against the prediction's limit, refused before it runs: 3600 directions
  // x 64^2 drops x 10^4 spheres x 2.5e-7 s = 3.7e4 s > 3600 s.
  auto w = run_cli("anisotropy " + groove_file() + " --hold --directions 3600 --drops 64");
  EXPECT_EQ(w.code, 2);
  EXPECT_NE(w.err.find("--directions"), std::string::npos) << w.err;
}

// `predict`'s name for the sliding direction works in `areal` and `areal-tilt` too; `--angle`,
// their older name, still reads the same direction.
TEST(CliAreal, DirectionIsTheNamePredictUsesAndAngleStillReads) {
  for (const std::string& cmd : {"areal " + groove_args(), "areal-tilt " + groove_args() + " --predict-only"}) {
    const auto d = run_cli(cmd + " --direction 30 --json");
    const auto a = run_cli(cmd + " --angle 30 --json");
    const auto z = run_cli(cmd + " --json");
    ASSERT_EQ(d.code, 0) << cmd << d.err;
    ASSERT_EQ(a.code, 0) << cmd << a.err;
    auto jd = nlohmann::json::parse(d.out), ja = nlohmann::json::parse(a.out), jz = nlohmann::json::parse(z.out);
    for (auto* j : {&jd, &ja, &jz}) j->erase("seconds");  // the run's own timing
    EXPECT_EQ(jd, ja) << cmd;
    EXPECT_DOUBLE_EQ(jd["direction_deg"].get<double>(), 30.0) << cmd;
    EXPECT_DOUBLE_EQ(jz["direction_deg"].get<double>(), 0.0) << cmd;
  }
  EXPECT_NE(run_cli("areal-tilt --help").out.find("--direction"), std::string::npos);
}

TEST(CliAreal, ArealTiltRefusesBadInputBeforeSimulating) {
  auto a = run_cli("areal-tilt " + groove_file() + " --angle inf --json");
  EXPECT_EQ(a.code, 2);
  EXPECT_NE(a.err.find("--direction"), std::string::npos) << a.err;
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
  const std::string args = "areal-tilt " + groove_file() + " " + upper +
                           " --in-place --detrend none --predict-only --runaway-distance 5e-7 --json";
  auto f = run_cli(args);
  ASSERT_EQ(f.code, 0) << f.err;
  auto jf = nlohmann::json::parse(f.out);
  EXPECT_FALSE(jf.contains("friction_angle_deg"));
  // The prediction's model only (the grid model is retired from the output), free and locked.
  for (const char* gone : {"matched_hold_angle_deg", "matched_hold_angle_locked_deg", "matched_steering_deg",
                           "prediction_refine", "continuous_hold_angle_deg", "continuous_steering_deg"})
    EXPECT_FALSE(jf.contains(gone)) << gone;
  EXPECT_LE(jf["predicted_hold_angle_deg"].get<double>(), 0.1);
  EXPECT_NEAR(jf["predicted_steering_deg"].get<double>(), 30, 0.5);
  const double expected = std::atan(kA * std::sin(2 * kPi / kM) / kStep) * 180 / kPi;
  EXPECT_GE(jf["predicted_hold_angle_locked_deg"].get<double>(), expected - 1e-7);
  EXPECT_LE(jf["predicted_hold_angle_locked_deg"].get<double>(), expected + 0.012);  // bisected to 1e-4 rad
  EXPECT_EQ(jf["lateral"], "free");
  // The same number as `frictal predict` from the same drop (its defaults of d and r).
  auto p = run_cli("predict " + groove_file() + " " + upper +
                   " --in-place --detrend none --start-offset 0,0 --runaway-distance 5e-7 --json");
  ASSERT_EQ(p.code, 0) << p.err;
  EXPECT_NEAR(nlohmann::json::parse(p.out)["friction_angle_deg"].get<double>(),
              jf["predicted_hold_angle_deg"].get<double>(), 1e-9);
  auto pl = run_cli("predict " + groove_file() + " " + upper +
                    " --in-place --detrend none --start-offset 0,0 --runaway-distance 5e-7 --locked --json");
  ASSERT_EQ(pl.code, 0) << pl.err;
  EXPECT_NEAR(nlohmann::json::parse(pl.out)["locked_friction_angle_deg"].get<double>(),
              jf["predicted_hold_angle_locked_deg"].get<double>(), 1e-9);
  // Simulated locked: the same predictions; the continuous_* details follow the locked block.
  auto l = run_cli(args + " --lateral locked");
  ASSERT_EQ(l.code, 0) << l.err;
  auto jl = nlohmann::json::parse(l.out);
  EXPECT_EQ(jl["lateral"], "locked");
  EXPECT_EQ(jl["predicted_hold_angle_deg"], jf["predicted_hold_angle_deg"]);
  EXPECT_EQ(jl["predicted_hold_angle_locked_deg"], jf["predicted_hold_angle_locked_deg"]);
  EXPECT_GE(jl["continuous_hold_angle_range_deg"][1].get<double>(), expected - 1e-7);
  // Bad input names the option.
  for (const std::string bad :
       {"--lateral sideways", "--collision mpr", "--prediction-refine 2", "--start-offset 1e-6", "--local-damping 1",
        "--mujoco-time-step 0", "--rest-steps 0", "--coarse-tilt-step 0"}) {
    auto b = run_cli(args + " " + bad);
    EXPECT_EQ(b.code, 2) << bad;
    EXPECT_NE(b.err.find(bad.substr(0, bad.find(' '))), std::string::npos) << bad << ": " << b.err;
  }
}
