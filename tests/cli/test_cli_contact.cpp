// frictal contact: the CLI's numbers against closed forms (Westergaard's wavy surface, Hertz's
// cylinder in plane strain, Hertz's sphere on a map), its units and its errors (exit 2 naming the
// option and what was expected).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "cli/cli_runner.hpp"

using json = nlohmann::json;

namespace {

constexpr double kPi = std::numbers::pi;

std::string num(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// One wavelength L = 1 mm of z = D cos(2 pi x / L), D = 1 um, on 1024 points plus the closing point.
std::string wave_csv() {
  std::string s = "x_m,z_m\n";
  for (int i = 0; i <= 1024; ++i) s += num(i * 1e-3 / 1024) + "," + num(1e-6 * std::cos(2 * kPi * i / 1024.0)) + "\n";
  const std::string path = temp_path("contact_wave.csv");
  write_file(path, s);
  return path;
}

// A paraboloid z = -r^2 / (2 R), R = 10 mm, on a 120 x 120 grid of 1 um (Gwyddion text, metres).
std::string sphere_map() {
  std::string s = "# Channel: sphere\n# Width: 0.00012 m\n# Height: 0.00012 m\n# Value units: m\n";
  for (int j = 0; j < 120; ++j)
    for (int i = 0; i < 120; ++i) {
      const double x = (i - 60) * 1e-6, y = (j - 60) * 1e-6;
      s += num(-(x * x + y * y) / 0.02) + (i + 1 < 120 ? " " : "\n");
    }
  const std::string path = temp_path("contact_sphere.txt");
  write_file(path, s);
  return path;
}

}  // namespace

// Westergaard: pbar = p* sin^2(pi a / L) with p* = pi E* D / L; at pbar = p* / 2 half the period
// touches and the peak is 2 sqrt(pbar p*). E = 1 GPa, nu = 0.3: E* = E / (1 - nu^2).
TEST(CliContact, WavySurfaceCurve) {
  const double Es = 1e9 / (1 - 0.09), pstar = kPi * Es * 1e-6 / 1e-3;
  const CliRun r = run_cli("contact " + wave_csv() + " --load " + num(pstar / 2) + "Pa," + num(2 * pstar) +
                           "Pa --modulus 1GPa --poisson 0.3 --periodic --detrend none --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  ASSERT_EQ(j["curve"].size(), 2u);
  const json& half = j["curve"][0];
  EXPECT_NEAR(half["contact_area_fraction"].get<double>(), 0.5, 0.005);
  EXPECT_NEAR(half["max_pressure_pa"].get<double>() / (2 * std::sqrt(0.5) * pstar), 1.0, 0.01);
  EXPECT_NEAR(half["contact_modulus_pa"].get<double>(), Es, 1e-6 * Es);
  EXPECT_TRUE(half["contact_area_m2"].is_null());
  const json& full = j["curve"][1];
  EXPECT_DOUBLE_EQ(full["contact_area_fraction"].get<double>(), 1.0);
  EXPECT_NEAR(full["max_pressure_pa"].get<double>() / (3 * pstar), 1.0, 1e-6);
  bool full_warning = false;
  for (const json& w : j["warnings"]) full_warning |= w["code"] == "contact-full";
  EXPECT_TRUE(full_warning);
}

// Hertz's sphere through the CLI: a = (3 F R / (4 E*))^(1/3) = 30 um at F from that radius;
// two bodies of the same material (LOWER and a flat UPPER) halve E*.
TEST(CliContact, HertzSphereMapAndTwoBodies) {
  const std::string sphere = sphere_map();
  const double Es = 2e9 / (1 - 0.25), R = 0.01, a = 30e-6, F = 4 * Es * a * a * a / (3 * R);
  const CliRun r =
      run_cli("contact " + sphere + " --load " + num(F) + "N --modulus 2GPa --poisson 0.5 " + "--detrend none --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["kind"], "map");
  EXPECT_NEAR(std::sqrt(j["contact_area_m2"].get<double>() / kPi) / a, 1.0, 0.015);
  EXPECT_NEAR(j["max_pressure_pa"].get<double>() / (3 * F / (2 * kPi * a * a)), 1.0, 0.015);
  EXPECT_NEAR(j["contact_stiffness_n_per_m"].get<double>() / (2 * Es * a), 1.0, 0.02);
  EXPECT_NEAR(j["load_n"].get<double>(), F, 1e-9 * F);

  std::string flat = "# Channel: flat\n# Width: 0.00012 m\n# Height: 0.00012 m\n# Value units: m\n";
  for (int j2 = 0; j2 < 120; ++j2)
    for (int i = 0; i < 120; ++i) flat += std::string("0") + (i + 1 < 120 ? " " : "\n");
  const std::string flat_path = temp_path("contact_flat.txt");
  write_file(flat_path, flat);
  // E* of two equal bodies is half of one's: at the same force a = (3 F R / (4 E*/2))^(1/3).
  const CliRun two = run_cli("contact " + sphere + " " + flat_path + " --load " + num(F) +
                             "N --modulus 2GPa --poisson 0.5 --detrend none --json --no-stiffness");
  ASSERT_EQ(two.code, 0) << two.err;
  const json k = json::parse(two.out);
  EXPECT_NEAR(k["contact_modulus_pa"].get<double>(), Es / 2, 1e-6 * Es);
  EXPECT_NEAR(std::sqrt(k["contact_area_m2"].get<double>() / kPi) / (a * std::cbrt(2.0)), 1.0, 0.015);
  EXPECT_TRUE(k["contact_stiffness_n_per_m"].is_null());
}

TEST(CliContact, BadOptionsExit2NamingThem) {
  const std::string wave = wave_csv();
  struct Case {
    std::string args, says;
  } cases[] = {
      {"--load 2N --modulus 1GPa --poisson 0.3", "force per unit length"},
      {"--load 2 --modulus 1GPa --poisson 0.3", "with its unit"},
      {"--load 2furlongs --modulus 1GPa --poisson 0.3", "not understood"},
      {"--load -5Pa --modulus 1GPa --poisson 0.3", "> 0"},
      {"--load 1MPa --modulus 1GPa --poisson 0.6", "Poisson's ratio"},
      {"--load 1MPa --modulus -1GPa --poisson 0.3", "Young's modulus"},
      {"--load 1MPa --modulus 1GPa --poisson 0.3 --upper-modulus 2GPa", "UPPER, which is not given"},
      {"--load 1MPa --modulus 1GPa --poisson 0.3 --hardness 0.5MPa", "hardness"},
  };
  for (const Case& c : cases) {
    const CliRun r = run_cli("contact " + wave + " " + c.args);
    EXPECT_EQ(r.code, 2) << c.args;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << ": " << r.err;
  }
}
