// `frictal predict --load`: friction under load from the CLI (the keys of the output table, the
// rigid answer without --load) and its errors, each naming the option and what it expects.
#include <fmt/core.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli/cli_runner.hpp"
#include "frictal/io.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

using json = nlohmann::json;

namespace {
std::string data(const std::string& rel) { return std::string(FRICTAL_TEST_DATA) + "/" + rel; }

void expect_usage_error(const std::string& args, const std::string& words) {
  const CliRun r = run_cli(args);
  EXPECT_NE(r.code, 0) << args;
  EXPECT_NE(r.err.find(words), std::string::npos) << args << "\n" << r.err;
}
}  // namespace

TEST(CliLoad, PredictsUnderLoadWithItsCurve) {
  const std::string wm = temp_path("load-wm.csv");
  ASSERT_EQ(run_cli("surface wm --dimension 1.5 --n-max 7 --rms-height 1e-6 --longest-wavelength 1e-4 --length "
                    "1e-3 -o " +
                    wm)
                .code,
            0);
  const CliRun rigid = run_cli("predict " + wm + " --json");
  ASSERT_EQ(rigid.code, 0) << rigid.err;
  const json r = json::parse(rigid.out);
  EXPECT_TRUE(r["load_n"].is_null());
  EXPECT_TRUE(r["load_curve_n"].empty());
  const CliRun loaded = run_cli("predict " + wm + " --load 1mN,0.1mN,10mN --modulus 3GPa --poisson 0.35 --json");
  ASSERT_EQ(loaded.code, 0) << loaded.err;
  const json j = json::parse(loaded.out);
  EXPECT_DOUBLE_EQ(j["load_n"].get<double>(), 1e-3);  // the first load is the headline
  EXPECT_EQ(j["model"], "profile-hertz-asperity-hold");
  ASSERT_EQ(j["load_curve_n"].size(), 3u);
  EXPECT_DOUBLE_EQ(j["load_curve_n"][0].get<double>(), 1e-4);  // the curve in increasing load
  EXPECT_DOUBLE_EQ(j["load_curve_median_deg"][1].get<double>(), j["friction_angle_deg"].get<double>());
  EXPECT_DOUBLE_EQ(j["rigid_friction_angle_deg"].get<double>(), r["friction_angle_deg"].get<double>());
  // The loaded lift of profiles tends to the rigid one: its zero-load limit is the rigid median.
  EXPECT_DOUBLE_EQ(j["load_zero_limit_deg"].get<double>(), r["friction_angle_deg"].get<double>());
  // Two bodies of E = 3 GPa, nu = 0.35: E* = E / (2 (1 - nu^2)).
  EXPECT_NEAR(j["contact_modulus_pa"].get<double>(), 3e9 / (2 * (1 - 0.35 * 0.35)), 1);
  const CliRun text = run_cli("predict " + wm + " --load 1mN --modulus 3GPa --poisson 0.35 --upper-modulus rigid");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("friction angle against load"), std::string::npos) << text.out;
  // The report leads with the same prediction, and plots the curve.
  const std::string page = temp_path("load-report.html");
  const CliRun rep =
      run_cli("report " + wm + " --load 1mN --modulus 3GPa --poisson 0.35 --resolution-steps 0 -o " + page);
  ASSERT_EQ(rep.code, 0) << rep.err;
  const std::string html = read_file(page);
  EXPECT_NE(html.find("id=\"load-curve\""), std::string::npos);
  EXPECT_NE(html.find("Friction under load"), std::string::npos);
}

TEST(CliLoad, ErrorsNameTheOption) {
  const std::string f = data("profiles/dektak-1.csv");
  expect_usage_error("predict " + f + " --load 2N", "--load: friction under load needs the material: give --modulus");
  expect_usage_error("predict " + f + " --load 2N --modulus 70GPa", "--poisson");
  expect_usage_error("predict " + f + " --modulus 70GPa --poisson 0.3", "give the load with --load");
  expect_usage_error("predict " + f + " --load 2 --modulus 70GPa --poisson 0.3", "--load '2': unit '' not understood");
  expect_usage_error("predict " + f + " --load 2N/m --modulus 70GPa --poisson 0.3", "--load '2N/m'");
  expect_usage_error("predict " + f + " --load -1N --modulus 70GPa --poisson 0.3",
                     "--load '-1N': expected a force > 0");
  expect_usage_error("predict " + f + " --load 2N --modulus 70Gpa --poisson 0.3", "--modulus '70Gpa': unit 'Gpa'");
  expect_usage_error("predict " + f + " --load 2N --modulus 70GPa --poisson 0.7",
                     "--poisson '0.7': expected a number in (-1, 0.5]");
  expect_usage_error(
      "predict " + f + " --load 2N --modulus 70GPa --poisson 0.3 --upper-modulus rigid --upper-poisson 0.2",
      "--upper-poisson: a rigid upper block has none");
}

TEST(CliLoad, PredictsAMapPairUnderLoad) {
  // Crossed waves, 24 x 24 nodes at 1 um, against themselves turned over; 2 x 2 drops.
  frictal::Map m;
  m.nx = m.ny = 24;
  m.dx = m.dy = 1e-6;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i)
      m.heights.push_back(2e-7 * std::sin(0.6 * double(i)) * std::cos(0.45 * double(j)) + 1e-8 * double(i % 3));
  const std::string f = temp_path("load-waves.x3p");
  ASSERT_TRUE(frictal::write_x3p(f, m).ok());
  const CliRun rigid = run_cli("predict " + f + " --drops 2 --json");
  ASSERT_EQ(rigid.code, 0) << rigid.err;
  const json r = json::parse(rigid.out);
  const CliRun loaded = run_cli("predict " + f + " --drops 2 --load 1mN --modulus 70GPa --poisson 0.3 --json");
  ASSERT_EQ(loaded.code, 0) << loaded.err;
  const json j = json::parse(loaded.out);
  EXPECT_EQ(j["model"], "map-halfspace-locked-hold");
  EXPECT_DOUBLE_EQ(j["load_n"].get<double>(), 1e-3);
  ASSERT_EQ(j["load_curve_n"].size(), 3u);  // W / 10, W, 10 W
  EXPECT_DOUBLE_EQ(j["load_curve_n"][0].get<double>(), 1e-4);
  EXPECT_DOUBLE_EQ(j["load_curve_median_deg"][1].get<double>(), j["friction_angle_deg"].get<double>());
  EXPECT_DOUBLE_EQ(j["rigid_friction_angle_deg"].get<double>(), r["friction_angle_deg"].get<double>());
  EXPECT_NEAR(j["contact_modulus_pa"].get<double>(), 70e9 / (2 * (1 - 0.3 * 0.3)), 1);
  EXPECT_GT(j["load_approach_m"].get<double>(), 0);
  EXPECT_GT(j["load_contact_fraction_max"].get<double>(), 0);
  EXPECT_TRUE(j["load_merged_share"].is_null());
  EXPECT_EQ(j["drop_friction_angles_deg"].size(), 4u);
  // The loaded lift tends to the rigid lines' as W^(2/3) (approach and U/W): at 1e-15 N the curve is
  // the zero-load limit, the locked block on the rigid lines; where that differs from the free
  // block's median (the rigid prediction) by more than 0.1 deg, a warning says so.
  const CliRun tiny = run_cli("predict " + f + " --drops 2 --load 1e-15N --modulus 70GPa --poisson 0.3 --json");
  ASSERT_EQ(tiny.code, 0) << tiny.err;
  const json t = json::parse(tiny.out);
  const double zero = t["load_zero_limit_deg"].get<double>();
  EXPECT_NEAR(t["friction_angle_deg"].get<double>(), zero, 1e-3);
  EXPECT_DOUBLE_EQ(j["load_zero_limit_deg"].get<double>(), zero);  // a property of the lines, not of W
  bool locked_warning = false;
  for (const auto& w : t["warnings"]) locked_warning = locked_warning || w["code"] == "load-locked-block";
  EXPECT_EQ(locked_warning, std::abs(zero - r["friction_angle_deg"].get<double>()) > 0.1);
  const CliRun text = run_cli("predict " + f + " --drops 2 --load 1mN --modulus 70GPa --poisson 0.3");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("friction angle against load"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("contact patches per offset"), std::string::npos) << text.out;
  // The report plots the map's curve.
  const std::string page = temp_path("load-map-report.html");
  const CliRun rep = run_cli("report " + f + " --drops 2 --load 1mN --modulus 70GPa --poisson 0.3 -o " + page);
  ASSERT_EQ(rep.code, 0) << rep.err;
  const std::string html = read_file(page);
  EXPECT_NE(html.find("id=\"load-curve\""), std::string::npos);
  EXPECT_NE(html.find("elastic half-space"), std::string::npos);
  // Its curve draws the zero-load limit where the warning says it is not the free block's median.
  EXPECT_EQ(html.find("zero-load limit (block locked to d)") != std::string::npos, locked_warning);
}

// Two smooth WM profiles (rms height 0.1 um over 1 mm, steepest slopes below 0.4 deg) on
// aluminium. At 10 nN the asperities are separate Hertzian spheres and the loaded prediction stays
// at the rigid one's scale (frictionless elastic contacts push along slopes no steeper than the
// surfaces'); at 1 mN about a sixth of the load is on merged contacts, which separate spheres do
// not describe: the warning makes that number doubtful, and the text says so first.
TEST(CliLoad, MergedContactsMakeThePredictionDoubtful) {
  std::string f[2];
  for (int s = 0; s < 2; ++s) {
    f[s] = temp_path("smooth-wm" + std::to_string(s) + ".csv");
    const CliRun g = run_cli(
        "surface wm -D 1.5 --n-max 12 --longest-wavelength 1e-3 --length 1e-3 --rms-height 1e-7 --spacing 1e-7 "
        "--seed " +
        std::to_string(5 + s) + " -o " + f[s]);
    ASSERT_EQ(g.code, 0) << g.err;
  }
  const std::string pair = "predict " + f[0] + " " + f[1] + " --modulus 70GPa --poisson 0.3 --load ";
  const CliRun light = run_cli(pair + "10nN --json");
  ASSERT_EQ(light.code, 0) << light.err;
  const json l = json::parse(light.out);
  EXPECT_EQ(l["trust"], "ok");
  const double bound = l["upper_bound_friction_angle_deg"].get<double>();
  ASSERT_LT(bound, 0.5);
  EXPECT_LT(l["friction_angle_deg"].get<double>(), 2 * bound);
  const CliRun heavy = run_cli(pair + "1mN --json");
  ASSERT_EQ(heavy.code, 0) << heavy.err;
  const json h = json::parse(heavy.out);
  EXPECT_EQ(h["trust"], "doubtful");
  EXPECT_NE(h["trust_codes"].get<std::string>().find("load-contacts-merge"), std::string::npos);
  EXPECT_NE(h["trust_fix"].get<std::string>().find("--load"), std::string::npos);
  const CliRun text = run_cli(pair + "1mN");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_EQ(text.out.rfind("DOUBTFUL (load-contacts-merge", 0), 0u) << text.out;
}

// A light load on a measured pair is the rigid test plus a small elastic sink: the loaded
// prediction from one drop agrees with the spheropolygon tilt test with Hertzian contacts (the
// simulation, a second method) at the same drop, load and material. Two windows of the Dektak
// scan (as bench/loaded_tilt.py cuts them: 100-160 um below, 400-420 um above, its raw x column),
// the drop 2 um, d = 1 um: the simulated block slides at 0.53-0.85 deg between 0.1 and 1 uN.
// There the splines' highest asperity (the Hertz model's) is not the polylines' (the rigid
// lift's) over part of the run-away; had the loaded lift taken it for an extra contact, its
// slope would have raised a stop that the simulation does not have (3.83 deg at 1 uN).
TEST(CliLoad, ALightLoadOnAMeasuredPairReadsWhatTheHertzianTiltTestReads) {
  std::ifstream in(data("profiles/dektak-1.csv"), std::ios::binary);
  ASSERT_TRUE(in.good());
  std::vector<std::pair<double, double>> xz;  // um
  bool scan = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("Lateral um", 0) == 0) {
      scan = true;
      continue;
    }
    double x = 0, z = 0;
    if (scan && std::sscanf(line.c_str(), "%lf,%lf", &x, &z) == 2) xz.emplace_back(x, z);
  }
  ASSERT_GT(xz.size(), 9000u);
  auto window = [&](const std::string& name, double x0, double x1) {
    std::string text = "x_m,z_m\n";
    double first = -1;
    for (const auto& [x, z] : xz) {
      if (x < x0 || x > x1) continue;
      if (first < 0) first = x;
      text += fmt::format("{:.17g},{:.17g}\n", (x - first) * 1e-6, z * 1e-6);
    }
    const std::string path = temp_path(name);
    write_file(path, text);
    return path;
  };
  const std::string lower = window("dektak-window-lower.csv", 100, 160);
  const std::string upper = window("dektak-window-upper.csv", 400, 420);
  const std::string test = " --detrend line --initial-offset=2e-6 --runaway-distance 1e-6";
  // The upper block's weight at the default density, to set the density that makes it weigh W.
  const CliRun probe = run_cli("tilt --lower " + lower + " --upper " + upper + test + " --max-tilt 0.1 --json -q");
  ASSERT_EQ(probe.code, 0) << probe.err;
  const json pj = json::parse(probe.out);
  const double weight = pj["upper_mass_kg"].get<double>() * pj["settings"]["gravity"].get<double>();
  const double density = pj["settings"]["density"].get<double>();
  for (const double W : {1e-7, 1e-6}) {
    const CliRun sim = run_cli(fmt::format(
        "tilt --lower {} --upper {}{} --hold-rotation --protocol quasi-static --contact-law hertz --block-modulus 7e10 "
        "--block-poisson 0.3 --elastic-blocks 2 --density {:.17g} --json -q",
        lower, upper, test, density * W / weight));
    ASSERT_EQ(sim.code, 0) << sim.err;
    const json s = json::parse(sim.out);
    ASSERT_TRUE(s["slid"].get<bool>());
    const CliRun pred = run_cli(fmt::format(
        "predict {} {} --detrend line --start-offset=2e-6 --runaway-distance 1e-6 --load {:g}N --modulus 70GPa "
        "--poisson 0.3 --json -q",
        lower, upper, W));
    ASSERT_EQ(pred.code, 0) << pred.err;
    const json p = json::parse(pred.out);
    EXPECT_NEAR(p["friction_angle_deg"].get<double>(), s["friction_angle_deg"].get<double>(), 0.3) << "W = " << W;
  }
}
