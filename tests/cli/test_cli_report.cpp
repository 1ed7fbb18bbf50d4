// CLI: frictal report writes one self-contained page (file or stdout); usage errors exit 2.
#include <gtest/gtest.h>

#include <string>

#include "cli/cli_runner.hpp"

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
