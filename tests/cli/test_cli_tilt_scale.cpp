// frictal tilt on measured files at any scale: the defaults scaled to the
// files, the cost estimate and --quiet, the refusals (exit 2 naming the option), and a turned
// block's warning leading the output. Expected values are derived here from the files' bytes
// and the Table I/II defaults (tilt.hpp: r_0 = 5e-5 m on the 0.2 m block), not from frictal's
// output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/cli_runner.hpp"

namespace {

const std::string kXy2 = std::string(FRICTAL_TEST_DATA) + "/profiles/xy-2.txt";

// xy-2.txt: a units line ("µm µm"), a count line, then "x, z" rows in micrometres.
std::vector<double> xy2_x() {
  std::ifstream f(kXy2);
  std::string line;
  std::getline(f, line);
  std::getline(f, line);
  std::vector<double> x;
  while (std::getline(f, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream ss(line);
    double a, b;
    if (ss >> a >> b) x.push_back(a * 1e-6);
  }
  return x;
}

double setting(const nlohmann::json& j, const char* name) { return j["settings"][name].get<double>(); }

bool scaled_list_has(const nlohmann::json& j, const std::string& name) {
  for (const auto& t : j["scaled_defaults"]["settings"])
    if (t["name"] == name) return true;
  return false;
}

}  // namespace

TEST(CliTiltScale, ShortMeasuredProfileRunsWithScaledDefaults) {
  // 24 points over 29 um, the whole scan as the block: s = L / 0.2 m; the point spacing (~1.2 um)
  // is far above s r_0, so r = s r_0 (q = 1); the tilt rate 0.05 / sqrt(s) rad/s. The stated d (12.5
  // slope correlation lengths) exceeds what the whole block holds, so it gives way to the blocks'
  // overlap over 20, L / 20 (scan-too-short). With q = 1 the run is the macro test in other units: a
  // few 1e5 steps, well under a second of CPU.
  const std::vector<double> x = xy2_x();
  ASSERT_EQ(x.size(), 24u);
  const double length = *std::max_element(x.begin(), x.end()) - *std::min_element(x.begin(), x.end());
  const double s = length / 0.2;
  const CliRun r = run_cli("tilt --lower " + kXy2 + " --block-length whole --json", 120);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& sd = j["scaled_defaults"];
  EXPECT_EQ(j["surface"]["block"], "whole");
  EXPECT_NEAR(sd["length_m"].get<double>(), length, 1e-12 * length);
  EXPECT_NEAR(sd["length_factor"].get<double>(), s, 1e-12 * s);
  EXPECT_DOUBLE_EQ(sd["radius_factor"].get<double>(), 1.0);
  EXPECT_NEAR(setting(j, "spheroradius"), 5e-5 * s, 1e-12 * 5e-5 * s);
  EXPECT_NEAR(setting(j, "block_height"), 0.01 * s, 1e-12 * 0.01 * s);
  EXPECT_NEAR(setting(j, "placement_gap"), 2e-5 * s, 1e-12 * 2e-5 * s);
  EXPECT_NEAR(setting(j, "runaway_distance"), length / 20, 1e-12 * length);
  EXPECT_NEAR(setting(j, "tilt_rate"), 0.05 / std::sqrt(s), 1e-9);
  EXPECT_NEAR(setting(j, "normal_stiffness"), 6e5 * s, 1e-9 * 6e5 * s);
  for (const char* name : {"spheroradius", "placement_gap", "block_height"}) {
    EXPECT_TRUE(scaled_list_has(j, name)) << name;
  }
  EXPECT_FALSE(scaled_list_has(j, "runaway_distance"));  // the stated test's, not scaled
  for (const auto& t : sd["settings"]) {
    EXPECT_TRUE(t.contains("from") && t.contains("to") && t.contains("unit")) << t.dump();
  }
  EXPECT_TRUE(j["slid"].get<bool>());
  EXPECT_LT(j["steps"].get<double>(), 1e6);
  EXPECT_GT(j["estimate"]["steps_expected"].get<double>(), 0);
  // The estimate goes to standard error before the run.
  EXPECT_NE(r.err.find("frictal: estimate: time step"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << "no progress line when standard error is not a terminal";
  // The file's count line says 23 rows and 24 follow (counted above): the reader's warning is
  // one of the run's (warnings.hpp code "reader").
  bool reader = false, short_scan = false;
  for (const auto& w : j["warnings"]) {
    reader = reader || w["code"] == "reader";
    short_scan = short_scan || w["code"] == "scan-too-short";
  }
  EXPECT_TRUE(reader) << j["warnings"].dump();
  EXPECT_TRUE(short_scan) << j["warnings"].dump();
}

TEST(CliTiltScale, TheFilesPlausibilityChecksWarn) {
  // csv-2.csv: every height is the same (-1.4274 um), so the rms height is 0: heights-tiny.
  const CliRun r =
      run_cli("tilt --lower " + std::string(FRICTAL_TEST_DATA) + "/profiles/csv-2.csv --max-tilt 1 --json", 60);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  bool tiny = false;
  for (const auto& w : j["warnings"]) tiny = tiny || w["code"] == "heights-tiny";
  EXPECT_TRUE(tiny) << j["warnings"].dump();
  EXPECT_NE(r.err.find("frictal: warning [heights-tiny]"), std::string::npos) << r.err;
}

TEST(CliTiltScale, ExplicitValuesAreKept) {
  const CliRun r = run_cli("tilt --lower " + kXy2 + " --block-height 1e-5 --max-tilt 1 --json", 120);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_DOUBLE_EQ(setting(j, "block_height"), 1e-5);
  EXPECT_FALSE(scaled_list_has(j, "block_height"));
  EXPECT_TRUE(scaled_list_has(j, "spheroradius"));
}

TEST(CliTiltScale, QuietPrintsNothingOnStandardError) {
  const CliRun r = run_cli("tilt --lower " + kXy2 + " --max-tilt 1 --quiet", 120);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_NE(r.out.find("defaults scaled to the surfaces"), std::string::npos) << r.out;
}

TEST(CliTiltScale, ASpheroradiusBeyondTheResolutionIsRefused) {
  // The macro default r = 5e-5 m on a 29 um scan with points ~1.2 um apart: more than ten
  // point spacings (the refusal's stated limit).
  const CliRun r = run_cli("tilt --lower " + kXy2 + " --spheroradius 5e-5", 60);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("spheroradius 5e-05 m"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("expected a value in (0, "), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST(CliTiltScale, ARunBeyondMaxStepsIsRefusedUnlessForced) {
  const CliRun r = run_cli("tilt --lower " + kXy2 + " --max-steps 1000", 60);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("beyond --max-steps 1e+03"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--force"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
  const CliRun f = run_cli("tilt --lower " + kXy2 + " --max-steps 1000 --force --max-tilt 1 --quiet", 120);
  EXPECT_EQ(f.code, 0) << f.err;
  EXPECT_EQ(run_cli("tilt --lower " + kXy2 + " --max-steps 0", 60).code, 2);
}

TEST(CliTiltScale, ReliefTallerThanTheLengthIsRefused) {
  // csv-1.csv gives x in microns and z without a unit (read as metres): 0.15 m of relief on 0.27 um.
  const CliRun r = run_cli("tilt --lower " + std::string(FRICTAL_TEST_DATA) + "/profiles/csv-1.csv", 60);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("height range"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("expected a height range in [0, "), std::string::npos) << r.err;
}

TEST(CliTiltScale, ARotationWarningLeadsTheOutput) {
  // warn_rotation at 1e-9 deg: any turn of the upper block against the lower one warns (the
  // paper's protocol, the block free to turn: a measured file holds it by default).
  const std::string args =
      "tilt --lower " + kXy2 + " --block-length whole --protocol constant-rate --no-hold-rotation --warn-rotation 1e-9";
  const CliRun t = run_cli(args, 120);
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_EQ(t.out.rfind("warning [rotation]: ", 0), 0u) << t.out;
  EXPECT_NE(t.out.find("friction angle (not valid"), std::string::npos) << t.out;
  EXPECT_NE(t.err.find("frictal: warning [rotation]"), std::string::npos) << t.err;
  const CliRun j = run_cli(args + " --json --quiet", 120);
  ASSERT_EQ(j.code, 0) << j.err;
  EXPECT_EQ(j.err, "");
  const auto o = nlohmann::json::parse(j.out);
  EXPECT_FALSE(o["friction_angle_valid"].get<bool>());
  bool found = false;
  for (const auto& w : o["warnings"]) found = found || w["code"] == "rotation";
  EXPECT_TRUE(found) << o["warnings"].dump();
}

TEST(CliTiltScale, GeneratedSurfacesScaleAsFilesKeepingTheirWavelength) {
  // Koch at its default 0.2 m (the paper's tests): K0's points are 5 mm apart, above r_0, so
  // s = 1, q = 1 and nothing changes.
  const CliRun d = run_cli("tilt koch --alpha 5 --max-tilt 1 --json --quiet", 120);
  ASSERT_EQ(d.code, 0) << d.err;
  const auto jd = nlohmann::json::parse(d.out);
  EXPECT_TRUE(jd["scaled_defaults"]["settings"].empty()) << jd["scaled_defaults"].dump();
  // A generated surface keeps the paper's protocol.
  EXPECT_EQ(jd["scaled_defaults"]["measured_defaults"], "");
  EXPECT_EQ(jd["protocol"], "constant-rate");
  EXPECT_DOUBLE_EQ(setting(jd, "spheroradius"), 5e-5);
  EXPECT_DOUBLE_EQ(setting(jd, "block_height"), 0.01);
  // On 2 cm (s = 0.1): r and h scale, the period and the run-away stay the surface's wavelength.
  const CliRun r = run_cli("tilt koch --alpha 5 --length 0.02 --max-tilt 1 --json --quiet", 120);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["scaled_defaults"]["length_factor"].get<double>(), 0.1, 1e-12);
  EXPECT_NEAR(setting(j, "spheroradius"), 5e-6, 1e-18);
  EXPECT_NEAR(setting(j, "block_height"), 1e-3, 1e-15);
  EXPECT_DOUBLE_EQ(setting(j, "period"), 0.01);
  EXPECT_DOUBLE_EQ(setting(j, "runaway_distance"), 0.01);
  EXPECT_FALSE(scaled_list_has(j, "period"));
  EXPECT_FALSE(scaled_list_has(j, "runaway_distance"));
}

TEST(CliTiltScale, AMacroFileKeepsTheDefaults) {
  // A 0.2 m file sampled every 1 cm, the whole scan as the block: s = 1 and r_0 = 5e-5 m below the
  // spacing: nothing changes; d gives way to the whole block's L / 20 (the stated 12.5 slope
  // correlation lengths do not fit it).
  const std::string f = temp_path("macro-file.csv");
  std::string text = "x_m,z_m\n";
  for (int i = 0; i <= 20; ++i) text += std::to_string(0.01 * i) + "," + (i % 2 ? "0.001" : "0") + "\n";
  write_file(f, text);
  const CliRun r = run_cli("tilt --lower " + f + " --block-length whole --max-tilt 1 --json --quiet", 120);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["scaled_defaults"]["settings"].empty()) << j["scaled_defaults"].dump();
  EXPECT_DOUBLE_EQ(setting(j, "spheroradius"), 5e-5);
  EXPECT_DOUBLE_EQ(setting(j, "runaway_distance"), 0.01);
}

namespace {
const std::string kDektak = std::string(FRICTAL_TEST_DATA) + "/profiles/dektak-1.csv";
// A 50 um piece of the Dektak scan (321 points): short enough for a quasi-static run in a second.
const std::string kPiece = "tilt --lower " + kDektak + " --crop 0.5mm,0.55mm --json --quiet";
// The paper's protocol on it: the lower block turning at tilt_rate, the upper block free to turn.
const std::string kPaper = " --protocol constant-rate --no-hold-rotation";
constexpr double kDegree = 3.14159265358979323846 / 180;
}  // namespace

TEST(CliTiltScale, AFileGivenAsAWordNamesLower) {
  const CliRun r = run_cli("tilt " + kDektak, 60);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--lower " + kDektak), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("unknown subcommand"), std::string::npos) << r.err;
}

TEST(CliTiltScale, AnAngleOutsideTheRigidBracketIsNotValidAndSaysWhy) {
  // The block's own rest gives the rigid model's bracket [phi_in, phi_qs] (hold.hpp, computed
  // from the lift, a second method beside the time stepping). With the paper's protocol the piece
  // slides at once (0 deg, the block still moving when the tilt starts): outside it, so not
  // valid, and the reason names the options of the validated protocol.
  const CliRun d = run_cli(kPiece + kPaper, 120);
  ASSERT_EQ(d.code, 0) << d.err;
  const auto j = nlohmann::json::parse(d.out);
  const double phi = j["friction_angle_deg"].get<double>();
  const double lo = j["predicted_inertial_hold_angle_deg"].get<double>() - 0.1;
  const double hi =
      std::max(j["predicted_hold_angle_deg"].get<double>(), j["predicted_sphero_hold_angle_deg"].get<double>()) + 0.1;
  ASSERT_TRUE(phi < lo || phi > hi) << phi << " in [" << lo << ", " << hi << "]";
  EXPECT_FALSE(j["friction_angle_valid"].get<bool>());
  const std::string why = j["validity"].get<std::string>();
  for (const char* option : {"--protocol quasi-static", "--hold-rotation", "--normal-stiffness"})
    EXPECT_NE(why.find(option), std::string::npos) << why;
  // Below the model's 5-95 % over drops too (the reading 0 deg, the range's low end above it): the
  // warning outside-spread says so and why.
  ASSERT_GT(j["predicted_spread_q05_deg"].get<double>(), phi + 0.1);
  bool outside = false;
  for (const auto& w : j["warnings"])
    if (w["code"] == "outside-spread") {
      outside = true;
      EXPECT_NE(w["message"].get<std::string>().find("not valid"), std::string::npos) << w["message"];
    }
  EXPECT_TRUE(outside) << j["warnings"].dump();
  // The text says so on the friction angle's line, and names the bound as a bound.
  const CliRun t = run_cli("tilt --lower " + kDektak + " --crop 0.5mm,0.55mm --quiet" + kPaper, 120);
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("friction angle (not valid: "), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("rigid upper bound (signature theta_max"), std::string::npos) << t.out;
  EXPECT_EQ(t.out.find("predicted ("), std::string::npos) << t.out;
  // The validated protocol with contacts 140 times stiffer than the scaled Table II value reads
  // the quasi-static hold angle from its rest within one increment (0.01 deg) and is valid.
  const double k = 140 * setting(j, "normal_stiffness");
  const CliRun q =
      run_cli(kPiece + " --protocol quasi-static --hold-rotation --normal-stiffness " + std::to_string(k), 120);
  ASSERT_EQ(q.code, 0) << q.err;
  const auto jq = nlohmann::json::parse(q.out);
  EXPECT_TRUE(jq["friction_angle_valid"].get<bool>()) << jq["validity"];
  EXPECT_EQ(jq["validity"], "valid");
  EXPECT_NEAR(jq["friction_angle_deg"].get<double>(), jq["predicted_hold_angle_deg"].get<double>(), 0.01 + 1e-9);
  (void)kDegree;
}

TEST(CliTiltScale, AMeasuredScanWithTheDefaultsReadsItsHoldAngle) {
  // The defaults on a measured scan: the quasi-static protocol with the rotation held (tilt_setup),
  // named in the output. Its angle is valid and lies within one increment (0.01 deg) below the
  // quasi-static hold angle that hold.hpp reads from the block's rest on the rigid lift (a second
  // method beside the time stepping; the rounded blocks' hold angle is the same here).
  const CliRun d = run_cli(kPiece, 120);
  ASSERT_EQ(d.code, 0) << d.err;
  const auto j = nlohmann::json::parse(d.out);
  EXPECT_EQ(j["protocol"], "quasi-static");
  EXPECT_EQ(j["settings"]["protocol"], "quasi-static");
  EXPECT_EQ(j["settings"]["hold_rotation"], true);
  EXPECT_EQ(j["scaled_defaults"]["measured_defaults"], "protocol = quasi-static, hold_rotation = true");
  EXPECT_TRUE(j["friction_angle_valid"].get<bool>()) << j["validity"];
  const double phi = j["friction_angle_deg"].get<double>();
  const double qs = j["predicted_hold_angle_deg"].get<double>();
  const double increment = setting(j, "tilt_increment");  // deg, as every angle of the text settings
  EXPECT_GT(qs, 0.1);  // a scan with relief: not an angle that a block on a flat would read
  EXPECT_LE(phi, qs + 1e-9);
  EXPECT_GE(phi, qs - increment - 1e-9);
  EXPECT_DOUBLE_EQ(j["rotation_before_slide_deg"].get<double>(), 0.0);
  // The cost estimate made before the run: its steps within a factor of 3 of the run's.
  const double steps = j["steps"].get<double>(), expected = j["estimate"]["steps_expected"].get<double>();
  EXPECT_LT(steps, 3 * expected);
  EXPECT_GT(steps, expected / 3);
  // The text names the defaults and how to get the paper's protocol.
  const CliRun t = run_cli("tilt --lower " + kDektak + " --crop 0.5mm,0.55mm --quiet", 120);
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_EQ(t.out.find("not valid"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("measured surfaces default to protocol = quasi-static, hold_rotation = true"), std::string::npos)
      << t.out;
  EXPECT_NE(t.out.find("--protocol constant-rate --no-hold-rotation"), std::string::npos) << t.out;
  // A protocol the caller gives is kept; the rotation is still held by default.
  const CliRun c = run_cli(kPiece + " --protocol constant-rate --max-tilt 1", 120);
  ASSERT_EQ(c.code, 0) << c.err;
  const auto jc = nlohmann::json::parse(c.out);
  EXPECT_EQ(jc["protocol"], "constant-rate");
  EXPECT_EQ(jc["scaled_defaults"]["measured_defaults"], "hold_rotation = true");
}

TEST(CliTiltScale, TheReadingIsPlacedInTheModelsSpreadOverDrops) {
  // A sawtooth of slope alpha (Koch K0): every drop rests in a V and holds up to alpha (the paper,
  // Sec. III), so the rigid model's range over drops is alpha at every quantile, and the run reads
  // inside it.
  const CliRun k = run_cli("tilt koch --iterations 0 --alpha 20 --json --quiet", 120);
  ASSERT_EQ(k.code, 0) << k.err;
  const auto jk = nlohmann::json::parse(k.out);
  for (const char* q : {"predicted_spread_q05_deg", "predicted_spread_median_deg", "predicted_spread_q95_deg"})
    EXPECT_NEAR(jk[q].get<double>(), 20.0, 1e-6) << q;
  EXPECT_EQ(jk["spread_note"].get<std::string>().rfind("inside ", 0), 0u) << jk["spread_note"];
  // A measured piece: the note agrees with the numbers it names, and the text prints it.
  const CliRun d = run_cli(kPiece, 120);
  ASSERT_EQ(d.code, 0) << d.err;
  const auto j = nlohmann::json::parse(d.out);
  const double q05 = j["predicted_spread_q05_deg"].get<double>(), q95 = j["predicted_spread_q95_deg"].get<double>();
  const double median = j["predicted_spread_median_deg"].get<double>(), phi = j["friction_angle_deg"].get<double>();
  EXPECT_LE(q05, median);
  EXPECT_LE(median, q95);
  const double tol = std::max(0.1, setting(j, "tilt_increment"));
  const bool inside = phi >= q05 - tol && phi <= q95 + tol;
  EXPECT_EQ(j["spread_note"].get<std::string>().rfind(inside ? "inside " : "outside ", 0), 0u) << j["spread_note"];
  const CliRun t = run_cli("tilt --lower " + kDektak + " --crop 0.5mm,0.55mm --quiet", 120);
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("this reading lies " + std::string(inside ? "inside" : "outside")), std::string::npos) << t.out;
}

namespace {
// A 0.3 mm piece of the Dektak scan (1,920 points): long enough for the stated test (a block of 20 d
// and 8 d of sliding room), a run in well under a second.
const std::string kStated = kDektak + " --crop 0.5mm,0.8mm";

bool has_warning(const nlohmann::json& j, const std::string& code) {
  for (const auto& w : j["warnings"])
    if (w["code"] == code) return true;
  return false;
}
}  // namespace

TEST(CliTiltScale, AMeasuredScanRunsTheTestPredictStates) {
  // `frictal predict` (a second front end and computation: the hold analysis over its drops) states
  // the test; tilt with its defaults runs that test: the same block, d, rule and drop range, the
  // drop at the middle of that range, and the model's spread over the same drops.
  const CliRun p = run_cli("predict " + kStated + " --json", 120);
  ASSERT_EQ(p.code, 0) << p.err;
  const auto jp = nlohmann::json::parse(p.out);
  const CliRun t = run_cli("tilt --lower " + kStated + " --json --quiet", 120);
  ASSERT_EQ(t.code, 0) << t.err;
  const auto j = nlohmann::json::parse(t.out);
  const auto& s = j["surface"];
  EXPECT_EQ(s["block"], "stated");
  const double lb = jp["block_length_m"].get<double>(), d = jp["runaway_distance_m"].get<double>();
  EXPECT_DOUBLE_EQ(s["block_length_m"].get<double>(), lb);
  EXPECT_DOUBLE_EQ(s["runaway_distance_m"].get<double>(), d);
  EXPECT_DOUBLE_EQ(setting(j, "runaway_distance"), d);
  EXPECT_EQ(s["test_lengths"], jp["test_lengths"]);
  // The stated shape (hold.hpp): L_b = 20 d, drops 2 d in from each end of [0, L - L_b].
  EXPECT_NEAR(lb, 20 * d, 2 * 1e-3 / 9599);  // to the nearest samples (spacing ~0.16 um)
  const double lo = jp["drop_range_m"][0].get<double>(), hi = jp["drop_range_m"][1].get<double>();
  EXPECT_DOUBLE_EQ(s["drop_range_m"][0].get<double>(), lo);
  EXPECT_DOUBLE_EQ(s["drop_range_m"][1].get<double>(), hi);
  EXPECT_NEAR(lo, 2 * d, 1e-12);
  EXPECT_EQ(s["drop"], "the middle of the drop range");
  EXPECT_NEAR(setting(j, "initial_offset"), 0.5 * (lo + hi), 1e-15);
  // The model's range that tilt prints is predict's.
  EXPECT_NEAR(j["predicted_spread_q05_deg"].get<double>(), jp["friction_angle_q05_deg"].get<double>(), 1e-9);
  EXPECT_NEAR(j["predicted_spread_median_deg"].get<double>(), jp["friction_angle_deg"].get<double>(), 1e-9);
  EXPECT_NEAR(j["predicted_spread_q95_deg"].get<double>(), jp["friction_angle_q95_deg"].get<double>(), 1e-9);
  // The defaults are scaled to the block, the shorter face.
  EXPECT_NEAR(j["scaled_defaults"]["length_m"].get<double>(), lb, 1e-15);
  // The reading lies in predict's 5-95 % (within one increment), or a warning says why not.
  const double phi = j["friction_angle_deg"].get<double>(), tol = std::max(0.1, setting(j, "tilt_increment"));
  const bool inside = phi >= jp["friction_angle_q05_deg"].get<double>() - tol &&
                      phi <= jp["friction_angle_q95_deg"].get<double>() + tol;
  EXPECT_TRUE(inside || has_warning(j, "outside-spread")) << t.out;
  EXPECT_EQ(has_warning(j, "outside-spread"), !inside) << t.out;
  // The text states the test.
  const CliRun x = run_cli("tilt --lower " + kStated + " --quiet", 120);
  ASSERT_EQ(x.code, 0) << x.err;
  EXPECT_NE(x.out.find("the test (as frictal predict states it): a block of"), std::string::npos) << x.out;
}

TEST(CliTiltScale, StatedLengthsAndTheWholeBlockAreTheTestsPredictStatesForThem) {
  // A block and d given with units, as predict takes them: the same test in both commands.
  const std::string opts = " --block-length 100um --runaway-distance 5um";
  const CliRun p = run_cli("predict " + kStated + opts + " --json", 120);
  ASSERT_EQ(p.code, 0) << p.err;
  const auto jp = nlohmann::json::parse(p.out);
  const CliRun t = run_cli("tilt --lower " + kStated + opts + " --json --quiet", 120);
  ASSERT_EQ(t.code, 0) << t.err;
  const auto j = nlohmann::json::parse(t.out);
  EXPECT_NEAR(j["surface"]["block_length_m"].get<double>(), 100e-6, 0.2e-6);  // to the nearest samples
  EXPECT_DOUBLE_EQ(j["surface"]["block_length_m"].get<double>(), jp["block_length_m"].get<double>());
  EXPECT_DOUBLE_EQ(setting(j, "runaway_distance"), 5e-6);
  EXPECT_EQ(j["surface"]["test_lengths"], "d: given; block: given");
  EXPECT_NEAR(j["predicted_spread_median_deg"].get<double>(), jp["friction_angle_deg"].get<double>(), 1e-9);
  // The whole block: predict's --block-length whole, dropped at the offset of least lift.
  const CliRun w = run_cli("tilt --lower " + kStated + " --block-length whole --max-tilt 1 --json --quiet", 120);
  ASSERT_EQ(w.code, 0) << w.err;
  const auto jw = nlohmann::json::parse(w.out);
  EXPECT_EQ(jw["surface"]["block"], "whole");
  EXPECT_TRUE(jw["surface"]["drop_range_m"][0].is_null());
  EXPECT_NEAR(jw["surface"]["block_length_m"].get<double>(), 3e-4, 1e-6);
  // Lengths that the scan cannot hold are refused, naming them and the options that change them.
  const CliRun r = run_cli("tilt --lower " + kStated + " --block-length 1mm --runaway-distance 5um", 60);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("as given"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--block-length whole"), std::string::npos) << r.err;
  const CliRun bad = run_cli("tilt --lower " + kStated + " --block-length=-3um", 60);
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--block-length"), std::string::npos) << bad.err;
  // A generated surface keeps the paper's Table I blocks.
  const CliRun g = run_cli("tilt koch --block-length 1mm", 60);
  EXPECT_EQ(g.code, 2);
  EXPECT_NE(g.err.find("whole block"), std::string::npos) << g.err;
}

TEST(CliTiltScale, AScanTooShortForTheStatedTestSaysSoAsPredictDoes) {
  // xy-2.txt (29 um, 24 points): the stated test (L_b = 20 d with 8 d of room) does not fit; both
  // commands answer the largest test of its shape with the warning scan-too-short.
  const CliRun p = run_cli("predict " + kXy2 + " --json", 120);
  ASSERT_EQ(p.code, 0) << p.err;
  const auto jp = nlohmann::json::parse(p.out);
  ASSERT_TRUE(has_warning(jp, "scan-too-short"));
  const CliRun t = run_cli("tilt --lower " + kXy2 + " --json --quiet", 120);
  ASSERT_EQ(t.code, 0) << t.err;
  const auto j = nlohmann::json::parse(t.out);
  EXPECT_TRUE(has_warning(j, "scan-too-short")) << j["warnings"].dump();
  EXPECT_DOUBLE_EQ(j["surface"]["block_length_m"].get<double>(), jp["block_length_m"].get<double>());
  EXPECT_DOUBLE_EQ(j["surface"]["runaway_distance_m"].get<double>(), jp["runaway_distance_m"].get<double>());
  // The largest test of the default's shape on a 29 um scan: L_b + 8 d = 28 d = L (block to samples).
  const std::vector<double> x = xy2_x();
  const double length = x.back() - x.front();
  EXPECT_NEAR(jp["runaway_distance_m"].get<double>(), length / 28, 1e-9 * length);
}
