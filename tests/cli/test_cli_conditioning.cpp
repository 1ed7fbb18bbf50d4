// The conditioning options (--crop, --remove-spikes, --spike-threshold) of every command that reads
// measured surfaces: one name each, stated in the JSON's `conditioning`, numbers from the
// constructed files (by hand), bad values exit 2 naming the option, the value and what was expected.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "cli/cli_runner.hpp"

using json = nlohmann::json;

namespace {

constexpr double kPi = std::numbers::pi;

std::string fmt_num(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// A sine of 1 um and wavelength 0.2 mm on x = i um, i = 0..1000; spikes of +-20 um at 250, 500
// and 753 (about 15 Sq from their neighbours' median) unless `clean`. With `midpoints`, the
// spikes' points hold the mean of their two neighbours instead: the profile the filter must give.
std::string sine_csv(const std::string& name, bool clean, bool midpoints = false) {
  auto z = [](int i) { return 1e-6 * std::sin(2 * kPi * i * 1e-6 / 2e-4); };
  std::string s = "x_m,z_m\n";
  for (int i = 0; i <= 1000; ++i) {
    double v = z(i);
    const bool spike = i == 250 || i == 500 || i == 753;
    if (spike && midpoints) v = 0.5 * (z(i - 1) + z(i + 1));
    if (spike && !clean && !midpoints) v += i == 500 ? -2e-5 : 2e-5;
    s += fmt_num(i * 1e-6) + "," + fmt_num(v) + "\n";
  }
  const std::string path = temp_path(name);
  write_file(path, s);
  return path;
}

// A 40 x 30 map (dx = dy = 1 um), a tilted plane with a ripple of 0.1 um, NaN at (3, 4) and
// (15, 6), a spike of 20 um at (8, 5). (A lone spike among N points lies at most about sqrt(N) Sq
// from the rest, so the map is large enough for k = 10: N >= 600 here.)
std::string map_file(const std::string& name) {
  std::string s = "# Channel: test\n# Width: 4e-05 m\n# Height: 3e-05 m\n# Value units: m\n";
  for (int j = 0; j < 30; ++j) {
    for (int i = 0; i < 40; ++i) {
      double v = 1e-3 * i * 1e-6 + 2e-3 * j * 1e-6 + 1e-7 * std::sin(2 * kPi * i / 8.0);
      if (i == 8 && j == 5) v += 2e-5;
      s += (i == 3 && j == 4) || (i == 15 && j == 6) ? std::string("NaN") : fmt_num(v);
      s += i + 1 < 40 ? " " : "\n";
    }
  }
  const std::string path = temp_path(name);
  write_file(path, s);
  return path;
}

bool has_code(const json& j, const std::string& code) {
  for (const auto& w : j["warnings"])
    if (w["code"] == code) return true;
  return false;
}

}  // namespace

TEST(CliConditioning, EveryCommandThatReadsMeasuredSurfacesOffersTheSameOptions) {
  for (const char* cmd :
       {"predict", "report", "signature", "areal", "anisotropy", "stats", "dimension", "areal-tilt", "tilt"}) {
    const CliRun r = run_cli(std::string(cmd) + " --help");
    ASSERT_EQ(r.code, 0) << cmd;
    for (const char* opt : {"--crop", "--remove-spikes", "--spike-threshold", "--detrend"})
      EXPECT_NE(r.out.find(opt), std::string::npos) << cmd << " lacks " << opt;
  }
}

TEST(CliConditioning, ACropKeepsTheWindowAndSaysSo) {
  const std::string f = sine_csv("cond-clean.csv", true);
  const CliRun r = run_cli("stats " + f + " --crop 0.1mm,0.9mm --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["points"], 801);  // x = 100 .. 900 um
  EXPECT_NEAR(j["length_m"].get<double>(), 8e-4, 1e-15);
  EXPECT_EQ(j["conditioning"], "crop x [0.0001, 0.0009] m: kept 801 of 1001 points; form: line");
  // The same window in metres; the text output states it too.
  const CliRun t = run_cli("stats " + f + " --crop 1e-4,9e-4");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("conditioning: crop x [0.0001, 0.0009] m: kept 801 of 1001 points"), std::string::npos) << t.out;
}

TEST(CliConditioning, RemoveSpikesGivesTheProfileWithoutThem) {
  const std::string spiky = sine_csv("cond-spiky.csv", false);
  const std::string reference = sine_csv("cond-reference.csv", false, true);
  const CliRun a = run_cli("stats " + spiky + " --remove-spikes --json");
  ASSERT_EQ(a.code, 0) << a.err;
  const CliRun b = run_cli("stats " + reference + " --json");
  ASSERT_EQ(b.code, 0) << b.err;
  const json ja = json::parse(a.out), jb = json::parse(b.out);
  EXPECT_EQ(ja["conditioning"], "spikes (k = 10 Sq): 3 points removed (replaced by linear interpolation); form: line");
  EXPECT_NEAR(ja["rms_height_m"].get<double>(), jb["rms_height_m"].get<double>(), 1e-20);
  EXPECT_NEAR(ja["max_slope_deg"].get<double>(), jb["max_slope_deg"].get<double>(), 1e-9);
  // A higher threshold than the spikes reach keeps them: about 15 Sq each.
  const CliRun k = run_cli("stats " + spiky + " --remove-spikes --spike-threshold 20 --json");
  ASSERT_EQ(k.code, 0) << k.err;
  EXPECT_EQ(json::parse(k.out)["conditioning"], "spikes (k = 20 Sq): none found; form: line");
}

TEST(CliConditioning, PredictListsTheStepsAndTheSpikesWarningPointsAtTheOption) {
  const std::string spiky = sine_csv("cond-predict.csv", false);
  const CliRun a = run_cli("predict " + spiky + " --json");
  ASSERT_EQ(a.code, 0) << a.err;
  const json ja = json::parse(a.out);
  ASSERT_TRUE(has_code(ja, "spikes"));
  for (const auto& w : ja["warnings"])
    if (w["code"] == "spikes") {
      EXPECT_NE(w["message"].get<std::string>().find("--remove-spikes"), std::string::npos);
    }
  EXPECT_EQ(ja["spikes_removed"], 0);
  const CliRun b = run_cli("predict " + spiky + " --remove-spikes --crop 0.05mm,0.95mm --json");
  ASSERT_EQ(b.code, 0) << b.err;
  const json jb = json::parse(b.out);
  EXPECT_FALSE(has_code(jb, "spikes"));
  EXPECT_EQ(jb["spikes_removed"], 3);
  EXPECT_EQ(jb["form"], "line");
  EXPECT_EQ(jb["conditioning"],
            "crop x [5e-05, 0.00095] m: kept 901 of 1001 points; spikes (k = 10 Sq): 3 points removed (replaced by "
            "linear interpolation); form: line");
  const CliRun t = run_cli("predict " + spiky + " --remove-spikes");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("conditioning: spikes (k = 10 Sq): 3 points removed"), std::string::npos) << t.out;
}

TEST(CliConditioning, TheReportStatesTheConditioningOfItsPageAndOfItsHeadline) {
  const std::string spiky = sine_csv("cond-report.csv", false);
  const CliRun r = run_cli("report " + spiky + " --crop 0.05mm,0.95mm --remove-spikes --resolution-steps 0 -q -o -");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string want =
      "crop x [5e-05, 0.00095] m: kept 901 of 1001 points; spikes (k = 10 Sq): 3 points removed (replaced by linear "
      "interpolation); form: line";
  EXPECT_NE(r.out.find("<b>" + want + "</b>"), std::string::npos);                // what the page's analyses read
  EXPECT_NE(r.out.find("\"conditioning\":\"" + want + "\""), std::string::npos);  // the headline's prediction
}

TEST(CliConditioning, AMapKeepsItsMaskAndLosesItsSpike) {
  const std::string m = map_file("cond-map.txt");
  // Columns 2..33 (x = 2 .. 33 um), rows 3..22: 32 x 20 points holding both NaN and the spike.
  const CliRun r = run_cli("stats " + m + " --crop 2um,33um,3um,22um --remove-spikes --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["nx"], 32);
  EXPECT_EQ(j["ny"], 20);
  EXPECT_EQ(j["valid_points"], 32 * 20 - 3);  // two masked by the file, one by the filter
  EXPECT_EQ(j["conditioning"],
            "crop x [2e-06, 3.3e-05] m, y [3e-06, 2.2e-05] m: kept 32 x 20 of 40 x 30 points; spikes (k = 10 Sq): 1 "
            "point masked; form: plane");
  // anisotropy and areal state the conditioning as well.
  // (Its lines need 32 valid points: the whole width, a window of 40 of the 40 columns.)
  const CliRun an = run_cli("anisotropy " + m + " --crop 0,39um --remove-spikes --directions 2 --json");
  ASSERT_EQ(an.code, 0) << an.err;
  EXPECT_EQ(json::parse(an.out)["conditioning"],
            "crop x [0, 3.9e-05] m: kept 40 x 30 of 40 x 30 points; spikes (k = 10 Sq): 1 point masked; form: plane");
  const CliRun ar = run_cli("areal " + m + " --remove-spikes --json");
  ASSERT_EQ(ar.code, 0) << ar.err;
  EXPECT_EQ(json::parse(ar.out)["conditioning"], "spikes (k = 10 Sq): 1 point masked; form: plane");
}

// A zigzag of flank slope 0.1 (peaks at x = 0, 0.2, ... 1 mm, valleys between) on a tilt of
// 0.02, x = i um, i = 0..1000. The zigzag is even about the middle, so the (trapezoid-weighted)
// least-squares line of the file is the tilt alone: removed, the flanks have slopes +-0.1 exactly
// and the self-signature's theta_max is atan 0.1; kept, the rising flank is 0.12 steep.
std::string tilted_zigzag_csv(const std::string& name) {
  std::string s = "x_m,z_m\n";
  for (int i = 0; i <= 1000; ++i) {
    const int k = i % 200;
    const double tri = 0.1 * 1e-6 * (k <= 100 ? 100 - k : k - 100);  // 10 um high, flanks of slope 0.1
    s += fmt_num(i * 1e-6) + "," + fmt_num(0.02 * i * 1e-6 + tri) + "\n";
  }
  const std::string path = temp_path(name);
  write_file(path, s);
  return path;
}

TEST(CliConditioning, EveryCommandRemovesTheSameFormByDefault) {
  // One default for every command: a line from a profile, a plane from a map,
  // stated in the output; --detrend none keeps the heights as read.
  const std::string f = tilted_zigzag_csv("cond-default.csv");
  const double atan01 = std::atan(0.1) * 180 / kPi;
  const CliRun sig = run_cli("signature " + f + " --no-hold --json");
  ASSERT_EQ(sig.code, 0) << sig.err;
  const json js = json::parse(sig.out);
  EXPECT_EQ(js["conditioning"], "form: line");
  EXPECT_NEAR(js["theta_max_forward_deg"].get<double>(), atan01, 1e-6);
  const CliRun raw = run_cli("signature " + f + " --no-hold --detrend none --json");
  ASSERT_EQ(raw.code, 0) << raw.err;
  EXPECT_EQ(json::parse(raw.out)["conditioning"], "form: none");
  EXPECT_GT(std::abs(json::parse(raw.out)["theta_max_forward_deg"].get<double>() - atan01), 0.5);
  // predict's rigid upper bound is signature's theta_max of the same surfaces.
  const CliRun pr = run_cli("predict " + f + " --json");
  ASSERT_EQ(pr.code, 0) << pr.err;
  const json jp = json::parse(pr.out);
  EXPECT_EQ(jp["conditioning"], "form: line");
  EXPECT_NEAR(jp["upper_bound_friction_angle_deg"].get<double>(), atan01, 1e-6);
  // stats and dimension: the same record; the rms height of the zigzag alone (a triangle wave of
  // height h = 10 um: h / sqrt(12)), not of the tilted file.
  const CliRun st = run_cli("stats " + f + " --json");
  ASSERT_EQ(st.code, 0) << st.err;
  const json jst = json::parse(st.out);
  EXPECT_EQ(jst["conditioning"], "form: line");
  EXPECT_NEAR(jst["rms_height_m"].get<double>(), 1e-5 / std::sqrt(12.0), 1e-12);
  const CliRun dm = run_cli("dimension " + f + " --method psd --json");
  ASSERT_EQ(dm.code, 0) << dm.err;
  EXPECT_EQ(json::parse(dm.out)["conditioning"], "form: line");
  // Maps: a plane.
  const std::string m = map_file("cond-default-map.txt");
  for (const char* cmd : {"stats", "areal", "anisotropy --directions 2"}) {
    const CliRun r = run_cli(std::string(cmd) + " " + m + " --json");
    ASSERT_EQ(r.code, 0) << cmd << ": " << r.err;
    EXPECT_EQ(json::parse(r.out)["conditioning"], "form: plane") << cmd;
  }
}

TEST(CliConditioning, SignatureAndDimensionStateIt) {
  const std::string spiky = sine_csv("cond-sig.csv", false);
  const CliRun s = run_cli("signature " + spiky + " --remove-spikes --no-hold --json");
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_EQ(json::parse(s.out)["conditioning"],
            "spikes (k = 10 Sq): 3 points removed (replaced by linear interpolation); form: line");
  const CliRun d = run_cli("dimension " + spiky + " --crop 0.1mm,0.9mm --method psd --json");
  ASSERT_EQ(d.code, 0) << d.err;
  EXPECT_EQ(json::parse(d.out)["conditioning"], "crop x [0.0001, 0.0009] m: kept 801 of 1001 points; form: line");
}

TEST(CliConditioning, TiltConditionsItsFilesAndStatesIt) {
  // The spheropolygon tilt test of a spiky scan with --remove-spikes runs on the profile the
  // filter must give (the spikes' points at the mean of their neighbours, written directly):
  // the same reading; the record in the JSON and the text, the form the default line.
  const std::string spiky = sine_csv("cond-tilt-spiky.csv", false);
  const std::string reference = sine_csv("cond-tilt-reference.csv", false, true);
  const CliRun a = run_cli("tilt --lower " + spiky + " --remove-spikes --json");
  ASSERT_EQ(a.code, 0) << a.err;
  const CliRun b = run_cli("tilt --lower " + reference + " --json");
  ASSERT_EQ(b.code, 0) << b.err;
  const json ja = json::parse(a.out), jb = json::parse(b.out);
  EXPECT_EQ(ja["surface"]["conditioning"],
            "spikes (k = 10 Sq): 3 points removed (replaced by linear interpolation); form: line");
  EXPECT_EQ(jb["surface"]["conditioning"], "form: line");
  EXPECT_EQ(ja["friction_angle_deg"], jb["friction_angle_deg"]);
  const CliRun c = run_cli("tilt --lower " + reference + " --crop 0.1mm,0.9mm --detrend line");
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_NE(c.out.find("conditioning: crop x [0.0001, 0.0009] m: kept 801 of 1001 points; form: line"),
            std::string::npos)
      << c.out;
  const CliRun d = run_cli("tilt --lower " + reference + " --detrend wobble");
  EXPECT_EQ(d.code, 2);
  EXPECT_NE(d.err.find("wobble"), std::string::npos) << d.err;
}

TEST(CliConditioning, BadValuesExitTwoNamingTheOptionTheValueAndWhatWasExpected) {
  const std::string f = sine_csv("cond-bad.csv", true);
  struct Case {
    std::string args, says;
  };
  const Case cases[] = {
      {"--crop 5mm,6mm", "--crop '5mm,6mm'"},
      {"--crop 5mm,6mm", "whose x spans [0, 0.001] m"},
      {"--crop 1,2,3", "--crop '1,2,3': 3 number(s)"},
      {"--crop 2,1", "x0 < x1"},
      {"--crop 1mm,x", "'x' is not a length"},
      {"--crop 0,1mm,0,1mm", "a line profile"},
      {"--remove-spikes --spike-threshold 0", "--spike-threshold: expected a number > 0, got 0"},
      {"--remove-spikes --spike-threshold abc", "--spike-threshold: expected a number > 0, got 'abc'"},
      {"--spike-threshold 6", "applies to --remove-spikes"},
  };
  for (const char* cmd : {"stats", "predict", "signature"})
    for (const Case& c : cases) {
      const CliRun r = run_cli(std::string(cmd) + " " + f + " " + c.args);
      EXPECT_EQ(r.code, 2) << cmd << " " << c.args << ": " << r.err;
      EXPECT_NE(r.err.find(c.says), std::string::npos) << cmd << " " << c.args << ": " << r.err;
    }
  const std::string m = map_file("cond-bad-map.txt");
  const CliRun r = run_cli("stats " + m + " --crop 0,0.5um");  // one column of the map
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--crop '0,0.5um'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("whose x spans [0, 3.9e-05] m and y [0, 2.9e-05] m"), std::string::npos) << r.err;
}
