// CLI: frictal report writes one self-contained page (file or stdout); usage errors exit 2.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>

#include "cli/cli_runner.hpp"
#include "frictal/io.hpp"

namespace {
const std::string kData = FRICTAL_TEST_DATA;
}

TEST(CliReport, MeasuredMapAndProfilePairPages) {
  const std::string map_html = temp_path("report_map.html");
  auto r = run_cli("report " + kData + "/x3p/sample-land.x3p -o " + map_html +
                   " --atomic-friction 0.2 --directions 12 --lines 16 --resolution-steps 4 --threads 2");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string page = read_file(map_html);
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(page.find("sample-land.x3p"), std::string::npos);
  EXPECT_NE(page.find("<b>form: plane</b>"), std::string::npos);  // the default detrending for maps, stated
  EXPECT_NE(page.find("Reader warning: "), std::string::npos);    // the reader's warnings are on the page
  EXPECT_NE(page.find("Friction over sliding directions"), std::string::npos);

  const std::string wm1 = temp_path("rep_wm1.csv"), wm2 = temp_path("rep_wm2.csv");
  ASSERT_EQ(run_cli("surface wm --dimension 1.5 --n-max 8 --seed 1 -o " + wm1).code, 0);
  ASSERT_EQ(run_cli("surface wm --dimension 1.5 --n-max 8 --seed 2 -o " + wm2).code, 0);
  auto s = run_cli("report " + wm1 + " " + wm2 + " -o - --resolution-steps 3 --threads 2");
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_EQ(s.out.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(s.out.find("surface slopes: upper"), std::string::npos);
  EXPECT_NE(s.out.find("<b>form: line</b>"), std::string::npos);  // the default detrending for profiles
}

TEST(CliReport, TwoMapsSectionIsThePredictionOfFrictalPredict) {
  // Grooves across x (A sin(2 pi i / m), every row alike) and a 12 x 12 window of them, turned
  // over: they mate, and from every drop the block climbs the steepest segment of the
  // piecewise-linear grooves, slope A sin(2 pi / m) / a (by hand). The page's two-map section
  // shows the headline's prediction, the object of `frictal predict --json` on the same input.
  const double a = 1e-6, A = 3.6e-7, kPi = std::numbers::pi;
  const int m = 8;
  frictal::Map g, u;
  g.nx = 32;
  g.ny = 24;
  g.dx = g.dy = a;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) g.heights.push_back(A * std::sin(2 * kPi * double(i) / m));
  u.nx = u.ny = 12;
  u.dx = u.dy = a;
  for (std::size_t j = 0; j < 12; ++j)
    for (std::size_t i = 0; i < 12; ++i) u.heights.push_back(g.at(i + 4, j + 4));
  const std::string lower = temp_path("rep-grooves.x3p"), upper = temp_path("rep-window.x3p");
  ASSERT_TRUE(frictal::write_x3p(lower, g).ok());
  ASSERT_TRUE(frictal::write_x3p(upper, u).ok());
  auto pr = run_cli("predict " + lower + " " + upper + " --detrend none --drops 3 --json");
  ASSERT_EQ(pr.code, 0) << pr.err;
  const nlohmann::json p = nlohmann::json::parse(pr.out);
  const double want = std::atan(A * std::sin(2 * kPi / m) / a) * 180 / kPi;
  EXPECT_GE(p["friction_angle_deg"].get<double>(), want - 1e-7);
  EXPECT_LE(p["friction_angle_deg"].get<double>(), want + 0.012);  // bisected to 1e-4 rad
  const std::string page_file = temp_path("rep-grooves.html");
  auto r = run_cli("report " + lower + " " + upper + " -o " + page_file +
                   " --detrend none --drops 3 --resolution-steps 0 --directions 4 --lines 4 -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string page = read_file(page_file);
  const std::string open = "<script type=\"application/json\" id=\"prediction\">";
  const auto at = page.find(open);
  ASSERT_NE(at, std::string::npos);
  const nlohmann::json q =
      nlohmann::json::parse(page.substr(at + open.size(), page.find("</script>", at) - at - open.size()));
  EXPECT_EQ(q["friction_angle_deg"], p["friction_angle_deg"]);
  EXPECT_EQ(q["drop_friction_angles_deg"], p["drop_friction_angles_deg"]);
  // The section: its table's median and drops are the prediction's; no grid hold angle.
  const auto sec = page.find("Areal blocks that may move sideways</h2>");
  ASSERT_NE(sec, std::string::npos);
  const std::string section = page.substr(sec, page.find("<h2", sec + 10) - sec);
  char median[64];
  std::snprintf(median, sizeof median, "median %.3f\u00b0", p["friction_angle_deg"].get<double>());
  EXPECT_NE(section.find(median), std::string::npos) << median;
  EXPECT_NE(section.find("hold angle over 9 drops"), std::string::npos);
  EXPECT_EQ(section.find("locked (1D rule)"), std::string::npos);
  EXPECT_EQ(section.find("hold angle from s = 0"), std::string::npos);
}

TEST(CliReport, UsageErrorsExitTwoAndNameTheProblem) {
  auto a = run_cli("report " + kData + "/profiles/missing.csv -o " + temp_path("x.html"));
  EXPECT_EQ(a.code, 2);
  EXPECT_NE(a.err.find("missing.csv"), std::string::npos);
  auto b =
      run_cli("report " + kData + "/x3p/sample-land.x3p " + kData + "/profiles/xy-1.txt -o " + temp_path("x.html"));
  EXPECT_EQ(b.code, 2);
  EXPECT_NE(b.err.find("UPPER must be a map too"), std::string::npos);
  auto c = run_cli("report " + kData + "/profiles/xy-1.txt -o " + temp_path("x.html") + " --atomic-friction -1");
  EXPECT_EQ(c.code, 2);
  EXPECT_NE(c.err.find("--atomic-friction"), std::string::npos);
  auto d = run_cli("report " + kData + "/profiles/xy-1.txt -o /nonexistent-dir/x.html --resolution-steps 0");
  EXPECT_EQ(d.code, 2);
  EXPECT_NE(d.err.find("/nonexistent-dir/x.html"), std::string::npos);
  EXPECT_EQ(run_cli("report " + kData + "/profiles/xy-1.txt -o " + temp_path("x.html") + " --detrend cubic").code, 2);
}
