#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/cli_runner.hpp"
#include "frictal/io.hpp"

using nlohmann::json;

TEST(Cli, KochSignatureJson) {
  const std::string f = temp_path("k2.csv");
  auto g = run_cli("surface koch --iterations 2 --alpha 20 -o " + f);
  ASSERT_EQ(g.code, 0) << g.err;
  // Periodicity is not stored in CSV; the non-periodic signature over half the block agrees.
  auto r = run_cli("signature " + f + " --atomic-friction 0.2 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = json::parse(r.out);
  for (const char* key : {"theta_max_forward_deg", "theta_max_backward_deg", "contact_slope_mean_deg",
                          "contact_slope_std_deg", "surface_slope_max_deg", "atomic_friction",
                          "upper_bound_friction_angle_deg", "upper_bound_friction_coefficient", "offsets", "warnings"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_NEAR(j["theta_max_forward_deg"].get<double>(), 40, 1e-6);
  EXPECT_NEAR(j["surface_slope_max_deg"].get<double>(), 60, 1e-6);
  const double phi = 40 + std::atan(0.2) * 180 / M_PI;
  EXPECT_NEAR(j["upper_bound_friction_angle_deg"].get<double>(), phi, 1e-6);
  EXPECT_NEAR(j["upper_bound_friction_coefficient"].get<double>(), std::tan(phi * M_PI / 180), 1e-6);
  // The prediction's names are the prediction's alone (frictal predict).
  EXPECT_FALSE(j.contains("friction_angle_deg"));
  EXPECT_FALSE(j.contains("friction_coefficient"));
  // With --period the periodic signature gives the same maximum.
  auto rp = run_cli("signature " + f + " --period 0.01 --json -o " + temp_path("sig.csv"));
  ASSERT_EQ(rp.code, 0) << rp.err;
  EXPECT_NEAR(json::parse(rp.out)["theta_max_forward_deg"].get<double>(), 40, 1e-6);
  EXPECT_NE(read_file(temp_path("sig.csv")).find("offset_m,lift_m,theta_deg"), std::string::npos);
}

TEST(Cli, StatsJsonOnHandMadeProfile) {
  const std::string f = temp_path("tri.csv");
  write_file(f, "x_m,z_m\n0,0\n1,1\n2,0\n");
  auto r = run_cli("stats " + f + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = json::parse(r.out);
  EXPECT_EQ(j["points"].get<int>(), 3);
  EXPECT_NEAR(j["length_m"].get<double>(), 2, 1e-15);
  EXPECT_NEAR(j["rms_height_m"].get<double>(), std::sqrt(1.0 / 12), 1e-12);
  EXPECT_NEAR(j["rms_slope"].get<double>(), 1, 1e-12);
  EXPECT_NEAR(j["max_slope_deg"].get<double>(), 45, 1e-9);
}

TEST(Cli, BadInputGivesClearErrorAndExit2) {
  struct Case {
    std::string content, expect;
  };
  const std::vector<Case> cases = {
      {"", "empty"},           {"x,z\n0,0\n", "at least 2"},          {"0,0\n1,nan\n", "finite"},
      {"0,0\n1,abc\n", ":2:"}, {"0,0\n2,1\n1,0\n", "non-decreasing"}, {"0;0\n1\n", ":2:"},
  };
  int k = 0;
  for (const auto& c : cases) {
    const std::string f = temp_path("bad" + std::to_string(k++) + ".csv");
    write_file(f, c.content);
    auto r = run_cli("signature " + f);
    EXPECT_EQ(r.code, 2) << c.content;
    EXPECT_NE(r.err.find("frictal:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(f), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
  }
  auto missing = run_cli("stats /nonexistent/file.csv");
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find("cannot open"), std::string::npos);
}

TEST(Cli, AbsurdParametersAreRejected) {
  const std::string o = " -o " + temp_path("x.csv");
  for (const std::string& args :
       {"surface koch --iterations 50" + o, "surface koch --alpha 70" + o, "surface koch --length 0.015" + o,
        "surface wm --dimension 3" + o, "surface wm --n-max 10 --spacing 1e-30" + o, "surface sine --wavelength -1" + o,
        "surface sawtooth --rise-fraction 1.5" + o, std::string("surface koch --iterations abc") + o,
        std::string("surface koch"), std::string("nonsense")}) {
    auto r = run_cli(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_FALSE(r.err.empty()) << args;
  }
  const std::string f = temp_path("ok.csv");
  ASSERT_EQ(run_cli("surface sine -o " + f).code, 0);
  EXPECT_EQ(run_cli("signature " + f + " --atomic-friction -1").code, 2);
  EXPECT_EQ(run_cli("signature " + f + " --offset-range 1 0").code, 2);
  EXPECT_EQ(run_cli("signature " + f + " --period -3").code, 2);
}

TEST(Cli, SignatureDetrendRemovesTheTiltOfAScan) {
  // A tilted flat scan z = 0.1 x: turned over it stays parallel to itself, so every contact has
  // the tilt's slope, atan(0.1) = 5.7106 deg, forward (and -5.7106 backward). After removing the
  // line (the default, as --detrend line) both are 0.
  const std::string f = temp_path("tilted.csv");
  write_file(f, "x_m,z_m\n0,0\n0.25,0.025\n0.5,0.05\n0.75,0.075\n1,0.1\n");
  auto raw = run_cli("signature " + f + " --detrend none --json");
  ASSERT_EQ(raw.code, 0) << raw.err;
  auto j = json::parse(raw.out);
  EXPECT_NEAR(j["theta_max_forward_deg"].get<double>(), std::atan(0.1) * 180 / M_PI, 1e-9);
  EXPECT_NEAR(j["theta_max_backward_deg"].get<double>(), -std::atan(0.1) * 180 / M_PI, 1e-9);
  auto flat = run_cli("signature " + f + " --detrend line --json");
  ASSERT_EQ(flat.code, 0) << flat.err;
  auto k = json::parse(flat.out);
  EXPECT_NEAR(k["theta_max_forward_deg"].get<double>(), 0, 1e-9);
  EXPECT_NEAR(k["theta_max_backward_deg"].get<double>(), 0, 1e-9);
  auto by_default = run_cli("signature " + f + " --json");
  ASSERT_EQ(by_default.code, 0) << by_default.err;
  EXPECT_NEAR(json::parse(by_default.out)["theta_max_forward_deg"].get<double>(), 0, 1e-9);
  EXPECT_EQ(run_cli("signature " + f + " --detrend bogus").code, 2);
}

// `surface -o NAME.x3p` writes an X3P profile with the same points as the CSV (read back by the
// library: same spacing, heights equal to the CSV's 17 significant digits); a name of a format
// frictal reads but does not write (.npy) is refused instead of getting CSV text under it.
TEST(Cli, SurfaceWritesX3pByItsNameAndRefusesNpy) {
  const std::string csv = temp_path("surf-x3p.csv"), x3p = temp_path("surf-x3p.X3P"), npy = temp_path("surf.npy");
  const std::string gen = "surface wm --dimension 1.4 --n-max 8 --seed 3 -o ";
  ASSERT_EQ(run_cli(gen + csv).code, 0);
  auto r = run_cli(gen + x3p);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(read_file(x3p).substr(0, 2), "PK");  // a zip container, not text
  auto a = frictal::read_profile(csv), b = frictal::read_profile(x3p);
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_EQ(a->size(), b->size());
  for (std::size_t i = 0; i < a->size(); ++i) {
    EXPECT_NEAR(a->x[i], b->x[i], 1e-12 * a->length()) << i;
    EXPECT_NEAR(a->z[i], b->z[i], 1e-15 * (std::abs(a->z[i]) + 1e-30)) << i;
  }
  std::remove(npy.c_str());
  r = run_cli(gen + npy);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("-o " + npy), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("not .npy"), std::string::npos) << r.err;
  EXPECT_FALSE(std::ifstream(npy).good());  // nothing written
  r = run_cli("surface koch --iterations 2 --alpha 20 --curve -o " + temp_path("curve.x3p"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("write it as CSV"), std::string::npos) << r.err;
}
