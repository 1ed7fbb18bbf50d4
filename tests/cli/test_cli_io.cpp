// CLI: stats on every format, convert round trips, dimension. Expected values follow from the
// files' numbers (see tests/io) or from Eq. 13.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <sstream>
#include <vector>

#include "cli/cli_runner.hpp"

namespace {
const std::string kData = FRICTAL_TEST_DATA;
}

TEST(CliIo, StatsMapJsonHasArealKeys) {
  auto r = run_cli("stats " + kData + "/x3p/x3p-2.x3p --detrend none --json");  // the heights as read
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["kind"], "map");
  EXPECT_EQ(j["points"], 422500);
  // python3: population rms about the mean of data.bin.
  EXPECT_NEAR(j["Sq_m"].get<double>(), 7.7280332735977479e-08, 1e-20);
  for (const char* k : {"Sa_m", "Sz_m", "Sdq", "Ssk", "Sku", "max_slope_deg", "rms_height_m", "points", "length_m",
                        "rms_slope", "size_x_m", "size_y_m"})
    EXPECT_TRUE(j.contains(k)) << k;
}

TEST(CliIo, StatsEveryProfileFormatAndDetrend) {
  for (const char* f : {"/profiles/csv-1.csv", "/profiles/csv-2.csv", "/profiles/dektak-1.csv", "/profiles/xy-1.txt",
                        "/profiles/xy-2.txt", "/profiles/nonuniform.asc"}) {
    auto r = run_cli("stats " + kData + f + " --json --detrend line");
    ASSERT_EQ(r.code, 0) << f << r.err;
    auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["kind"], "profile");
    EXPECT_NEAR(j["mean_height_m"].get<double>(), 0, 1e-9 * j["rms_height_m"].get<double>() + 1e-18) << f;
  }
  // Dektak: 9600 points over 0 .. 1499.8 um.
  auto r = run_cli("stats " + kData + "/profiles/dektak-1.csv --json");
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["points"], 9600);
  EXPECT_NEAR(j["length_m"].get<double>(), 1499.8e-6, 1e-12);
  EXPECT_EQ(run_cli("stats " + kData + "/profiles/xy-1.txt --detrend cubic").code, 2);
  EXPECT_EQ(run_cli("stats " + kData + "/profiles/xy-1.txt --format x3p").code, 2);
}

TEST(CliIo, ConvertRoundTrips) {
  const std::string x3p = temp_path("conv.x3p"), txt = temp_path("conv.txt"), back = temp_path("back.x3p");
  auto a = run_cli("convert " + kData + "/maps/gwyddion-export-english.txt " + x3p);
  ASSERT_EQ(a.code, 0) << a.err;
  auto b = run_cli("convert " + x3p + " " + txt);
  ASSERT_EQ(b.code, 0) << b.err;
  auto s1 = nlohmann::json::parse(run_cli("stats " + kData + "/maps/gwyddion-export-english.txt --json").out);
  auto s2 = nlohmann::json::parse(run_cli("stats " + txt + " --json").out);
  EXPECT_EQ(s1["Sq_m"], s2["Sq_m"]);
  EXPECT_EQ(s1["dx_m"], s2["dx_m"]);
  // Profile to X3P (int16) and back (csv-1's x is uniform to 0.3 % of its spacing).
  auto c = run_cli("convert " + kData + "/profiles/csv-1.csv " + back + " --x3p-type I --unit um");
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_EQ(run_cli("convert " + kData + "/profiles/xy-2.txt " + back).code, 2);  // non-uniform x
  auto p1 = nlohmann::json::parse(run_cli("stats " + kData + "/profiles/csv-1.csv --json --unit um").out);
  auto p2 = nlohmann::json::parse(run_cli("stats " + back + " --json").out);
  EXPECT_EQ(p1["points"], p2["points"]);
  // int16 quantisation (0.16 um over 65532 steps) and x snapped to x0 + k dx (x moves by up to
  // 0.3 % of dx, which re-weights the polyline) change the rms by well under 0.1 %.
  EXPECT_NEAR(p1["rms_height_m"].get<double>(), p2["rms_height_m"].get<double>(),
              1e-3 * p1["rms_height_m"].get<double>());
  EXPECT_EQ(run_cli("convert " + kData + "/x3p/pyramid.x3p " + temp_path("p.csv")).code, 2);
  EXPECT_EQ(run_cli("convert " + kData + "/x3p/pyramid.x3p " + temp_path("p.xyz")).code, 2);
}

TEST(CliIo, DimensionKochAndProfiles) {
  auto k = run_cli("dimension koch --alpha 60 --method eq13 --json");
  ASSERT_EQ(k.code, 0) << k.err;
  EXPECT_NEAR(nlohmann::json::parse(k.out)["dimension"].get<double>(), std::log(4.0) / std::log(3.0), 1e-12);
  for (const char* m : {"divider", "box", "psd"}) {
    auto r = run_cli("dimension " + kData + "/profiles/dektak-1.csv --detrend line --json --method " + m);
    ASSERT_EQ(r.code, 0) << m << r.err;
    auto j = nlohmann::json::parse(r.out);
    double D = j["dimension"].get<double>();
    EXPECT_GE(D, 0.9) << m;
    EXPECT_LE(D, 2.1) << m;
    EXPECT_TRUE(j.contains("r_squared"));
    EXPECT_EQ(j["fit_range_m"].size(), 2u);
  }
  EXPECT_EQ(run_cli("dimension " + kData + "/x3p/x3p-2.x3p").code, 2);
  EXPECT_EQ(run_cli("dimension").code, 2);
  EXPECT_EQ(run_cli("dimension koch --alpha 75 --method eq13").code, 2);
}

TEST(CliIo, AnisotropyTable) {
  auto r = run_cli("anisotropy " + kData + "/x3p/ISO5436-sample1.x3p --directions 4 --lines 4 --json");
  // 4 x 4 nodes: lines are shorter than the 32-point minimum -> a clear error, exit 2.
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("no line"), std::string::npos) << r.err;
  auto a = run_cli("anisotropy " + kData + "/x3p/x3p-2.x3p --directions 4 --lines 8 --json --atomic-friction 0.1");
  ASSERT_EQ(a.code, 0) << a.err;
  auto j = nlohmann::json::parse(a.out);
  ASSERT_EQ(j["directions"].size(), 4u);
  for (const auto& row : j["directions"]) {
    // Eq. 6: phi = atan(mu_a) + theta_forward.
    EXPECT_NEAR(row["upper_bound_friction_angle_deg"].get<double>(),
                std::atan(0.1) * 180 / 3.141592653589793 + row["theta_forward_deg"].get<double>(), 1e-9);
  }
  auto b = run_cli("anisotropy " + kData + "/x3p/x3p-2.x3p --directions 2 --areal --json");
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_EQ(nlohmann::json::parse(b.out)["method"], "areal");
  EXPECT_EQ(run_cli("anisotropy " + kData + "/profiles/xy-1.txt").code, 2);
  EXPECT_EQ(run_cli("anisotropy " + kData + "/x3p/x3p-2.x3p --directions 0").code, 2);
}

TEST(CliIo, StatsReadsEverySharedFile) {
  const char* files[] = {"profiles/csv-1.csv",
                         "profiles/csv-2.csv",
                         "profiles/dektak-1.csv",
                         "profiles/xy-1.txt",
                         "profiles/xy-2.txt",
                         "profiles/nonuniform.asc",
                         "maps/gwyddion-export-english.txt",
                         "maps/gwyddion-export-german.txt",
                         "maps/matrix-6.txt",
                         "x3p/ISO5436-sample1.x3p",
                         "x3p/ISO5436-sample1_bin.x3p",
                         "x3p/ISO5436-sample2.x3p",
                         "x3p/ISO5436-sample3.x3p",
                         "x3p/ISO5436-sample4.x3p",
                         "x3p/ISO5436-sample4_bin.x3p",
                         "x3p/pyramid.x3p",
                         "x3p/sample-land.x3p",
                         "x3p/x3p-2.x3p"};
  for (const char* f : files) {
    auto r = run_cli("stats " + kData + "/" + f + " --json");
    ASSERT_EQ(r.code, 0) << f << ": " << r.err;
    auto j = nlohmann::json::parse(r.out);
    EXPECT_GT(j["rms_height_m"].get<double>(), -1) << f;
  }
  // pyramid.x3p: 16 nodes of 2, 8 of 6, 1 of 10 (python3 struct) -> mean 3.6.
  auto p = nlohmann::json::parse(run_cli("stats " + kData + "/x3p/pyramid.x3p --detrend none --json").out);
  EXPECT_NEAR(p["mean_height_m"].get<double>(), (16 * 2 + 8 * 6 + 10) / 25.0, 1e-12);
}

TEST(CliIo, StatsSpectrumAutocorrelationHistograms) {
  const std::string psd = temp_path("psd.csv"), acf = temp_path("acf.csv");
  auto r = run_cli("stats " + kData + "/profiles/dektak-1.csv --detrend line --json --histograms 20 --psd " + psd +
                   " --acf " + acf);
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["height_distribution"]["density"].size(), 20u);
  EXPECT_EQ(j["slope_distribution_rad"]["edges"].size(), 21u);
  EXPECT_GT(j["correlation_length_m"].get<double>(), 0);
  EXPECT_NE(read_file(psd).find("q_rad_per_m,C_m3\n"), std::string::npos);
  EXPECT_NE(read_file(acf).find("lag_m,acf\n0,1\n"), std::string::npos);
}

TEST(CliIo, ConvertExtractsALineOfAMap) {
  // matrix-6.txt: 4 x 3 nodes, dx = 2.5 um, dy = 10/3 um, z = 1..12 m row by row. The line at
  // 0 deg through the centre (y = 10/3 um: row 1) samples every 2.5 um: 5, 6, 7, 8.
  const std::string out = temp_path("row.csv");
  auto r = run_cli("convert " + kData + "/maps/matrix-6.txt " + out + " --line-angle 0");
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream in(read_file(out));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "x_m,z_m");
  std::vector<std::pair<double, double>> pts;
  while (std::getline(in, line)) {
    auto c = line.find(',');
    pts.emplace_back(std::stod(line.substr(0, c)), std::stod(line.substr(c + 1)));
  }
  ASSERT_EQ(pts.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(pts[k].first, 2.5e-6 * k, 1e-18);
    EXPECT_NEAR(pts[k].second, 5.0 + k, 1e-12);
  }
  EXPECT_EQ(run_cli("convert " + kData + "/profiles/xy-1.txt " + out + " --line-angle 0").code, 2);
  EXPECT_EQ(run_cli("convert " + kData + "/maps/matrix-6.txt " + out + " --line-angle 0 --line-offset 1").code, 2);
}

TEST(CliIo, ArealSignatureCommand) {
  const std::string csv = temp_path("areal.csv");
  auto r = run_cli("areal " + kData + "/x3p/x3p-2.x3p --angle 90 --json --atomic-friction 0.2 -o " + csv);
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["direction_deg"], 90.0);
  // Eq. 6: phi = atan(mu_a) + theta_max_forward.
  EXPECT_NEAR(j["upper_bound_friction_angle_deg"].get<double>(),
              std::atan(0.2) * 180 / 3.141592653589793 + j["theta_max_forward_deg"].get<double>(), 1e-9);
  const std::string text = read_file(csv);
  EXPECT_EQ(text.rfind("offset_m,lift_m,theta_rad,contact_x_m,contact_y_m\n0,", 0), 0u);
  // Offsets: 0 .. half of the 650 rows' extent along y in steps of min(dx, dy) = dx.
  std::size_t lines = 0;
  for (char c : text) lines += c == '\n';
  EXPECT_EQ(lines - 1, j["offsets"].get<std::size_t>());
  EXPECT_EQ(run_cli("areal " + kData + "/profiles/xy-1.txt").code, 2);
  EXPECT_EQ(run_cli("areal " + kData + "/x3p/x3p-2.x3p --contact-slope max").code, 2);
}

// `frictal signature` reads a 1-D .npy (heights only) with --spacing (and --unit), as
// every other reading command does; without --spacing the reader's error names the option.
// A triangle wave of slope angle 30 deg (heights 0, h, 0, h, ... with h = dx tan 30 deg) against
// itself turned over: theta_max is the slope angle both ways (paper, Sec. III: K0 gives alpha).
TEST(CliIo, SignatureReadsHeightsOnlyNpyWithSpacing) {
  const double dx_um = 0.5, h_um = dx_um * std::tan(30 * M_PI / 180);
  std::string data;
  for (int i = 0; i < 41; ++i) {
    const double z = (i % 2) ? h_um : 0.0;
    char b[8];
    std::memcpy(b, &z, 8);  // little-endian '<f8' (x86-64)
    data.append(b, 8);
  }
  std::string dict = "{'descr': '<f8', 'fortran_order': False, 'shape': (41,), }";
  dict += std::string((64 - (10 + dict.size() + 1) % 64) % 64, ' ') + "\n";
  std::string npy = "\x93NUMPY";
  npy += char(1);
  npy += char(0);
  npy += char(dict.size() & 0xFF);
  npy += char(dict.size() >> 8);
  const std::string path = temp_path("heights_only.npy");
  write_file(path, npy + dict + data);

  auto r = run_cli("signature " + path + " --spacing 0.5um --unit um --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["theta_max_forward_deg"].get<double>(), 30.0, 1e-9);
  EXPECT_NEAR(j["theta_max_backward_deg"].get<double>(), 30.0, 1e-9);
  EXPECT_TRUE(j["exact"].get<bool>());

  auto bad = run_cli("signature " + path + " --json");
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.err.find("needs the sampling interval (--spacing"), std::string::npos) << bad.err;
}
