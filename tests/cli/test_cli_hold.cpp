// `frictal signature` and the hold angle: its JSON keys, the signature CSV's basin
// column, and bad input (exit 2 naming the option).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "cli/cli_runner.hpp"

using nlohmann::json;

namespace {
// The reference WM pair (rms 1e-5 m on the Table I block), written once.
std::string wm_file(int seed) {
  const std::string f = temp_path("hold-wm" + std::to_string(seed) + ".csv");
  auto g = run_cli("surface wm -D 1.5 --n-max 6 --longest-wavelength 0.01 --length 0.2 --rms-height 1e-5 --seed " +
                   std::to_string(seed) + " -o " + f);
  EXPECT_EQ(g.code, 0) << g.err;
  return f;
}
}  // namespace

TEST(CliHold, SignaturePrintsTheHoldAngleFromAStartAndOverDrops) {
  const std::string a = wm_file(1), b = wm_file(2);
  // The surfaces as generated (--detrend none), as the independent computation reads them.
  auto r =
      run_cli("signature " + a + " " + b + " --detrend none --start-offset 0.02379 --runaway-distance 0.01 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  // An independent numpy computation of the exact rigid lift: 1.549 and 0.695 deg.
  EXPECT_NEAR(j["hold_angle_deg"].get<double>(), 1.549, 0.0015);
  EXPECT_NEAR(j["inertial_hold_angle_deg"].get<double>(), 0.695, 0.0015);
  EXPECT_DOUBLE_EQ(j["runaway_distance_m"].get<double>(), 0.01);
  for (const char* k : {"rest_offset_m", "hold_offset_m", "rest_offset_backward_m", "hold_angle_backward_deg",
                        "hold_offset_backward_m", "inertial_hold_angle_backward_deg"})
    EXPECT_TRUE(j.contains(k)) << k;
  for (const char* p : {"hold_angle", "inertial_hold_angle"})
    for (const char* s : {"_mean_deg", "_std_deg", "_q05_deg", "_q50_deg", "_q95_deg", "_min_deg", "_max_deg"})
      EXPECT_TRUE(j.contains(std::string(p) + s)) << p << s;
  // A hold angle never exceeds the steepest contact slope of the range it can reach, and the
  // distribution's maximum is at most theta_max over the widened range: here over [0, L/2] the
  // forward maximum is reached, so q95 <= max = theta_max.
  EXPECT_LE(j["hold_angle_max_deg"].get<double>(), j["theta_max_forward_deg"].get<double>() + 1e-9);
  EXPECT_LE(j["hold_angle_q05_deg"].get<double>(), j["hold_angle_q50_deg"].get<double>());
  EXPECT_LE(j["hold_angle_q50_deg"].get<double>(), j["hold_angle_q95_deg"].get<double>());
  // The text output says it in a line a person reads.
  auto t = run_cli("signature " + a + " " + b + " --detrend none --start-offset 0.03 --runaway-distance 5e-3");
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("hold angle (what a tilt test reads"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("held up to 1.5095 deg"), std::string::npos) << t.out;  // independent: 1.510 deg
}

TEST(CliHold, DefaultRunawayDistanceScalesWithTheFile) {
  // A tenth of the offset range (half the block): 0.01 m on the 0.2 m block; one period for a
  // periodic pair.
  const std::string a = wm_file(1);
  auto r = run_cli("signature " + a + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_NEAR(j["runaway_distance_m"].get<double>(), 0.1 * j["offset_range_m"][1].get<double>(), 1e-15);
  auto k = run_cli("signature koch -n 1 --alpha 20 --json");
  ASSERT_EQ(k.code, 0) << k.err;
  const json jk = json::parse(k.out);
  EXPECT_NEAR(jk["runaway_distance_m"].get<double>(), 0.01, 1e-15);
  // Koch K1: every drop holds at the signature maximum alpha (paper Sec. III).
  EXPECT_NEAR(jk["hold_angle_min_deg"].get<double>(), 20, 1e-6);
  EXPECT_NEAR(jk["hold_angle_max_deg"].get<double>(), 20, 1e-6);
}

TEST(CliHold, SignatureCsvGainsTheBasinColumn) {
  const std::string a = wm_file(1), csv = temp_path("hold-sig.csv");
  auto r = run_cli("signature " + a + " -o " + csv);
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream in(read_file(csv));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "offset_m,lift_m,theta_deg,theta_min_deg,theta_left_deg,theta_right_deg,basin");
  // Basins are numbered along the offset: non-decreasing, from 0, every row has one.
  int last = -1, rows = 0;
  while (std::getline(in, line)) {
    const int b = std::stoi(line.substr(line.rfind(',') + 1));
    EXPECT_GE(b, last);
    EXPECT_GE(b, 0);
    last = b;
    ++rows;
  }
  EXPECT_GT(rows, 100);
  EXPECT_GT(last, 5);
}

TEST(CliHold, BadHoldOptionsExit2NamingTheOption) {
  const std::string a = wm_file(1);
  auto r = run_cli("signature " + a + " --start-offset 0.5");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("start offset 0.5"), std::string::npos) << r.err;
  r = run_cli("signature " + a + " --runaway-distance 0");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("runaway"), std::string::npos) << r.err;
  r = run_cli("signature " + a + " --runaway-distance 0.5");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("overlap"), std::string::npos) << r.err;
  r = run_cli("signature " + a + " --start-offset inf");
  EXPECT_EQ(r.code, 2);
  r = run_cli("signature " + a + " --no-hold --start-offset 0.01");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--no-hold"), std::string::npos) << r.err;
}

// An upper tip on a lower profile with two ramps of slope 0.05 and one of 0.06
// (the second 0.05 ramp 4 mm after the first, the 0.06 one 8.5 mm after it). From the first
// ramp the block slides past atan(0.05); the equal ramp cannot hold it, the 0.06 ramp lies
// farther than d = 5 mm: the hold angle is atan(0.05), with the features moved or not, on the
// profiles as written (--detrend none). With the default line removed from each file the ramps
// are all tilted by the same slope s of the lower file's line (the tip's line is flat: it is
// symmetric), so the hold angle is atan(0.05 - s): s from the trapezoid-weighted least-squares
// line, computed here from its normal equations.
namespace {
double trapezoid_line_slope(const std::vector<double>& x, const std::vector<double>& z) {
  double sw = 0, sx = 0, sz = 0, sxx = 0, sxz = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double w = 0.5 * ((i > 0 ? x[i] - x[i - 1] : 0) + (i + 1 < x.size() ? x[i + 1] - x[i] : 0));
    sw += w;
    sx += w * x[i];
    sz += w * z[i];
    sxx += w * x[i] * x[i];
    sxz += w * x[i] * z[i];
  }
  return (sw * sxz - sx * sz) / (sw * sxx - sx * sx);
}
}  // namespace

TEST(CliHold, EqualSlopesHoldAtTheFirstRamp) {
  const std::string tip = temp_path("hold-tip.csv");
  {
    std::ofstream f(tip);
    f << "x_m,z_m\n0,0\n0.05,0.01\n0.1,0\n";
  }
  for (const char* shift : {"", "-shifted"}) {
    const std::string lower = temp_path(std::string("hold-ramps") + shift + ".csv");
    double line_slope = 0;
    {
      const double s = shift[0] ? 1e-4 : 0;
      std::ofstream f(lower);
      f.precision(17);
      f << "x_m,z_m\n0,0\n";
      const double x[] = {0.065, 0.068, 0.070, 0.072, 0.0735, 0.0765, 0.078};
      const double z[] = {0, -0.00006, 0.00004, 0.00002, 0.000095, 0.00008, 0.00017};
      for (int i = 0; i < 7; ++i) f << x[i] + s << "," << z[i] << "\n";
      f << "0.2,0.00017\n";
      std::vector<double> xs = {0}, zs = {0};
      for (int i = 0; i < 7; ++i) xs.push_back(x[i] + s), zs.push_back(z[i]);
      xs.push_back(0.2), zs.push_back(0.00017);
      line_slope = trapezoid_line_slope(xs, zs);
    }
    const std::string args = " --runaway-distance 0.005 --start-offset 0.019 --offset-range 0 0.1 --json";
    auto r = run_cli("signature " + lower + " " + tip + " --detrend none" + args);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NEAR(json::parse(r.out)["hold_angle_deg"].get<double>(), std::atan(0.05) * 180 / M_PI, 1e-9) << shift;
    auto d = run_cli("signature " + lower + " " + tip + args);
    ASSERT_EQ(d.code, 0) << d.err;
    EXPECT_EQ(json::parse(d.out)["conditioning"], "form: line");
    EXPECT_NEAR(json::parse(d.out)["hold_angle_deg"].get<double>(), std::atan(0.05 - line_slope) * 180 / M_PI, 1e-9)
        << shift;
  }
}

TEST(CliHold, AProcessThatRunsFarPastTheRangeIsFollowedToWhereItStops) {
  // A flat block (a ramp, flat once its line is removed: the default form) on trapezoid grooves
  // (ramps of slope 0.3 and flat tops, 28 points a period, spacing 1 um; their line removed too):
  // the backward chains of the drops near the range's end run past it for several rounds of the
  // lift beyond the range. Second method: the same analysis with the lift computed over the whole
  // overlap at once (HoldOptions::whole_lift_offsets = inf, no rounds) reads every backward drop's
  // hold angle as 0 to rounding (4.9e-14 deg); rounds of d/5 extended by what each check finds
  // short stop early and read 17.27 deg for some drops. Rounds that at least double from the
  // third on go on to where the process stops.
  const std::string lower = temp_path("hold-far-lower.csv"), upper = temp_path("hold-far-upper.csv");
  {
    std::ofstream f(lower);
    f << "x_m,z_m\n";
    const double lz[] = {0,   0.3, 0.6, 0.9, 1.2, 1.5, 1.8, 2.1, 2.1, 2.1, 2.1, 2.1, 2.1, 2.1, 2.1, 2.1, 2.1,
                         2.1, 2.1, 2.1, 2.1, 2.1, 1.8, 1.5, 1.2, 0.9, 0.6, 0.3, 0,   0.3, 0.6, 0.9, 1.2, 1.5,
                         1.8, 2.1, 2.1, 2.1, 2.1, 2.1, 2.1, 2.1, 2.1, 2.1, 2.1, 2.1, 2.1, 2.1, 2.1};
    for (int i = 0; i < 49; ++i) f << i * 1e-6 << "," << lz[i] * 1e-6 << "\n";
    std::ofstream g(upper);
    g << "x_m,z_m\n";
    for (int i = 0; i < 16; ++i) g << i * 1e-6 << "," << i * 0.3e-6 << "\n";
  }
  auto r = run_cli("signature " + lower + " " + upper + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_LT(std::abs(j["hold_angle_backward_max_deg"].get<double>()), 1e-9);
  EXPECT_LT(std::abs(j["inertial_hold_angle_backward_max_deg"].get<double>()), 1e-9);
}

TEST(CliHold, ARunAwayOverALongOverlapEnds) {
  // The Dektak scan (1.5 mm) under the non-uniform profile that names no unit (read as metres: a
  // block 1.7 km long, a unit mix-up): the backward process runs away towards the far end of the
  // overlap, and the lift beyond the range is followed there in rounds that double (one round
  // per run-away distance, each planning the range so far, does not end in 300 s). It ends with
  // the exact analysis.
  const std::string data = FRICTAL_TEST_DATA;
  auto r = run_cli("signature " + data + "/profiles/dektak-1.csv " + data + "/profiles/nonuniform.asc --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_TRUE(j["hold_exact"].get<bool>());
  EXPECT_TRUE(std::isfinite(j["hold_angle_q50_deg"].get<double>()));
  // The mix-up named, as `predict` names it: lengths 0.0015 m and 1685 m (by the files' x columns).
  bool named = false;
  for (const auto& w : j["warnings"]) named = named || w["code"] == "scale-mismatch";
  EXPECT_TRUE(named) << j["warnings"].dump();
}
