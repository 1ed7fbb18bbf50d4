// CLI: info, formats, detection without hints, invalid points, --spacing/--channel.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>

#include "cli/cli_runner.hpp"
#include "frictal/io.hpp"

namespace {
const std::string kData = FRICTAL_TEST_DATA;
}

TEST(CliFormats, InfoListsTheChannelAndSizes) {
  auto r = run_cli("info " + kData + "/x3p/x3p-2.x3p --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["format"], "x3p");
  EXPECT_EQ(j["reader"], "native");
  ASSERT_EQ(j["channels"].size(), 1u);
  EXPECT_EQ(j["nx"], 650);
  // Physical size n dx: 650 x 1.27656509837346e-7 m (the file's CX increment).
  EXPECT_NEAR(j["channels"][0]["size_x"].get<double>(), 650 * 1.27656509837346e-007, 1e-18);
  auto t = run_cli("info " + kData + "/profiles/xy-1.txt");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("read by native"), std::string::npos) << t.out;
}

TEST(CliFormats, FormatsListsTheNativeReaders) {
  auto r = run_cli("formats --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  std::size_t native = 0;
  for (const auto& f : j["formats"]) native += f["reader"] == "native";
  EXPECT_EQ(native, 9u);
  if (j["gwyddion"].get<bool>())
    EXPECT_GT(j["formats"].size(), 100u);
  else
    EXPECT_NE(j["gwyddion_missing"].get<std::string>().find("gwyddion"), std::string::npos);
}

TEST(CliFormats, SingleColumnNeedsSpacingAndInfIsAWarning) {
  const std::string path = temp_path("col.txt");
  write_file(path, "# unit: nm\n1\ninf\n3\n-inf\n5\n");
  auto bad = run_cli("stats " + path);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--spacing"), std::string::npos) << bad.err;
  auto r = run_cli("stats " + path + " --spacing 0.5um --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["points"], 3);
  EXPECT_NEAR(j["length_m"].get<double>(), 2e-6, 1e-18);  // x = 0, 1, 2 um (kept points 0, 2, 4)
  // One warning line for the two infinities.
  std::size_t lines = 0;
  for (std::size_t p = r.err.find("invalid point"); p != std::string::npos; p = r.err.find("invalid point", p + 1))
    ++lines;
  EXPECT_EQ(lines, 1u) << r.err;
  auto u = run_cli("stats " + path + " --spacing 0.5furlong");
  EXPECT_EQ(u.code, 2);
  EXPECT_NE(u.err.find("--spacing"), std::string::npos);
}

TEST(CliFormats, NativeFileHasOneChannel) {
  auto r = run_cli("stats " + kData + "/x3p/pyramid.x3p --channel 2");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("one channel"), std::string::npos) << r.err;
}

TEST(CliFormats, StatsPrintsPhysicalSizesAndPerProfileValues) {
  // 4 x 3 map in nm with w = 4 um, h = 3 um: dx = dy = 1 um. Rows 0 1 2 3 (+ 10 per row). A plane,
  // so its statistics are those of the heights as read (--detrend none; the default removes it).
  const std::string path = temp_path("stats-matrix.txt");
  write_file(path, "# w=4um h=3um unit=nm\n0 1 2 3\n10 11 12 13\n20 21 22 23\n");
  auto r = run_cli("stats " + path + " --json --detrend none --tip-radius 1mm");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["physical_size_x_m"].get<double>(), 4e-6, 1e-18);
  EXPECT_NEAR(j["physical_size_y_m"].get<double>(), 3e-6, 1e-18);
  EXPECT_NEAR(j["size_x_m"].get<double>(), 3e-6, 1e-18);  // the (n-1) dx extent is kept
  // Each row 0..3 nm about its mean: Rq = sqrt(5/4) nm; slopes 1 nm / 1 um = 1e-3.
  EXPECT_NEAR(j["Rq_x_m"].get<double>(), std::sqrt(1.25) * 1e-9, 1e-21);
  EXPECT_NEAR(j["Rdq_x"].get<double>(), 1e-3, 1e-15);
  // Columns 0, 10, 20 nm: Rq = sqrt(200/3) nm; slopes 10 nm / 1 um = 1e-2.
  EXPECT_NEAR(j["Rq_y_m"].get<double>(), std::sqrt(200.0 / 3) * 1e-9, 1e-20);
  EXPECT_NEAR(j["Rdq_y"].get<double>(), 1e-2, 1e-15);
  EXPECT_NEAR(j["rms_gradient_fd"].get<double>(), std::sqrt(1e-6 + 1e-4), 1e-15);
  EXPECT_NEAR(j["bandwidth_short_m"].get<double>(), 1e-6, 1e-18);
  EXPECT_NEAR(j["bandwidth_long_m"].get<double>(), 3.5e-6, 1e-18);
  EXPECT_EQ(j["short_reliability_cutoff_m"].get<double>(), 0.0);  // a plane: no curvature
}

TEST(CliFormats, InfoAndStatsOfAGwyddionFile) {
  std::string why;
  if (!frictal::gwyddion_available("", &why)) GTEST_SKIP() << why;
  // 4 x 3 map, dx = dy = 1 um, z = i nm, written through Gwyddion's .sur module.
  frictal::Map m;
  m.nx = 4;
  m.ny = 3;
  m.dx = m.dy = 1e-6;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) m.heights.push_back(i * 1e-9);
  const std::string path = temp_path("cli.sur");
  ASSERT_TRUE(frictal::write_gwyddion(path, m).ok());
  auto r = run_cli("info " + path + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["reader"], "gwyddion:surffile");
  EXPECT_EQ(j["nx"], 4);
  EXPECT_NEAR(j["channels"][0]["size_x"].get<double>(), 4e-6, 1e-15);
  auto s = run_cli("stats " + path + " --json --detrend none");
  ASSERT_EQ(s.code, 0) << s.err;
  auto k = nlohmann::json::parse(s.out);
  EXPECT_NEAR(k["physical_size_x_m"].get<double>(), 4e-6, 1e-15);
  EXPECT_NEAR(k["Rdq_x"].get<double>(), 1e-3, 1e-9);  // 1 nm per 1 um, stored as float/scaled int
}

// An instrument file end to end (tests/data/instruments, SurfaceTopography corpus): `stats --json`
// gives the names users compare -- physical_size_x_m/_y_m (n dx), Sq_m, Rq_x_m, rms_gradient_fd,
// bandwidth -- with the values SurfaceTopography's test/IO/test_asc.py::test_example4 states for
// matrix-4.txt.gz (75 x 305 points, 2.773965e-05 x 0.00011280791 m, rms height 1.1745891510991089e-07
// m, rms_height_from_profile 7.198047e-08 m, rms_gradient 0.06776316911544318: the heights as read,
// hence --detrend none), and the tip cutoff.
TEST(CliFormats, InstrumentMatrixStatsJson) {
  auto r = run_cli("stats " + kData + "/instruments/matrix-4.txt.gz --detrend none --tip-radius 20nm --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // the header names the height unit: no warning
  auto j = nlohmann::json::parse(r.out);
  auto near = [](double a, double b) { return std::abs(a - b) <= 1e-6 * std::abs(b); };
  EXPECT_TRUE(near(j["physical_size_x_m"].get<double>(), 2.773965e-05)) << j["physical_size_x_m"];
  EXPECT_TRUE(near(j["physical_size_y_m"].get<double>(), 0.00011280791)) << j["physical_size_y_m"];
  EXPECT_TRUE(near(j["Sq_m"].get<double>(), 1.1745891510991089e-07)) << j["Sq_m"];
  EXPECT_TRUE(near(j["Rq_x_m"].get<double>(), 7.198047e-08)) << j["Rq_x_m"];
  EXPECT_TRUE(near(j["rms_gradient_fd"].get<double>(), 0.06776316911544318)) << j["rms_gradient_fd"];
  // Bandwidth: the pixel size 3.69862e-7 m (square pixels) up to (75 + 305) / 2 pixels.
  EXPECT_TRUE(near(j["bandwidth_short_m"].get<double>(), 3.69862e-07)) << j["bandwidth_short_m"];
  EXPECT_TRUE(near(j["bandwidth_long_m"].get<double>(), 190 * 3.69862e-07)) << j["bandwidth_long_m"];
  EXPECT_TRUE(j.contains("short_reliability_cutoff_m"));
  EXPECT_DOUBLE_EQ(j["tip_radius_m"].get<double>(), 20e-9);
}
