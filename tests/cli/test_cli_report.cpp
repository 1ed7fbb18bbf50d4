// CLI: frictal report writes one self-contained page (file or stdout); usage errors exit 2.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"
#include "frictal/io.hpp"

namespace {
const std::string kData = FRICTAL_TEST_DATA;

/// The page's text (tags dropped, entities kept), sentence by sentence.
std::vector<std::string> sentences(const std::string& page) {
  std::string text;
  bool tag = false;
  for (char c : page) {
    if (c == '<') tag = true;
    if (!tag) text += c;
    if (c == '>') tag = false, text += ' ';
  }
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t k = 0; k < text.size(); ++k)
    if ((text[k] == '.' && k + 1 < text.size() && text[k + 1] == ' ') || text[k] == '\n') {
      out.push_back(text.substr(start, k - start));
      start = k + 1;
    }
  out.push_back(text.substr(start));
  return out;
}

/// No friction number on the page is called predicted unless it is the headline's: a sentence
/// that says "predict" and gives an angle or a coefficient must be in the headline paragraph.
void expect_no_unnamed_bound(const std::string& page) {
  const auto at = page.find("id=\"headline\"");
  const std::string rest = at == std::string::npos ? page : page.substr(0, at) + page.substr(page.find("</p>", at));
  for (const std::string& s : sentences(rest)) {
    std::string low = s;
    for (char& c : low) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (low.find("predicted") == std::string::npos) continue;
    const bool number = s.find("\u00b0") != std::string::npos || s.find("\u03bc =") != std::string::npos ||
                        s.find("\u03bc \u2264") != std::string::npos;
    EXPECT_FALSE(number) << "a friction number called predicted outside the headline: " << s;
  }
}
}  // namespace

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
  EXPECT_NE(page.find("Rigid upper bound over sliding directions"), std::string::npos);
  // The polar plot is `frictal anisotropy`'s table with its line count.
  EXPECT_NE(page.find("the numbers of `frictal anisotropy sample-land.x3p --directions 12`"), std::string::npos);
  expect_no_unnamed_bound(page);

  const std::string wm1 = temp_path("rep_wm1.csv"), wm2 = temp_path("rep_wm2.csv");
  ASSERT_EQ(run_cli("surface wm --dimension 1.5 --n-max 8 --seed 1 -o " + wm1).code, 0);
  ASSERT_EQ(run_cli("surface wm --dimension 1.5 --n-max 8 --seed 2 -o " + wm2).code, 0);
  auto s = run_cli("report " + wm1 + " " + wm2 + " -o - --resolution-steps 3 --threads 2");
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_EQ(s.out.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(s.out.find("surface slopes: upper"), std::string::npos);
  EXPECT_NE(s.out.find("<b>form: line</b>"), std::string::npos);  // the default detrending for profiles
  expect_no_unnamed_bound(s.out);
}

TEST(CliReport, AMeasuredProfilesPageCallsNoBoundPredicted) {
  auto r = run_cli("report " + kData + "/profiles/dektak-1.csv -o - --resolution-steps 0 -q");
  ASSERT_EQ(r.code, 0) << r.err;
  expect_no_unnamed_bound(r.out);
  EXPECT_NE(r.out.find("Rigid upper bound of the friction coefficient"), std::string::npos);
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
  EXPECT_EQ(q["lower"], lower);  // the pair named, as `frictal predict --json` names it
  EXPECT_EQ(q["upper"], upper);
  // Both maps and both maps' statistics are on the page: the upper one is 12 x 12 points.
  const std::string lname = lower.substr(lower.rfind('/') + 1), uname = upper.substr(upper.rfind('/') + 1);
  EXPECT_NE(page.find("Height map: " + lname), std::string::npos);
  EXPECT_NE(page.find("Height map: " + uname), std::string::npos);
  EXPECT_NE(page.find("Areal statistics of " + uname), std::string::npos);
  EXPECT_NE(page.find("12 \u00d7 12 points"), std::string::npos);
  // The line sections are the pair's: the upper map's central line is the upper face.
  EXPECT_NE(page.find("the central line along x of " + uname), std::string::npos);
  expect_no_unnamed_bound(page);
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
