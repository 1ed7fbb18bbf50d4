// Task kind wm-tilt (the tilt test on random pairs, docs/dem.md sec. 6): invariants derived independently of
// the kind -- a sine pair's friction angle is its steepest slope atan(2 pi A / lambda) at every
// run-away distance; theta_max and sigma of a WM pair equal what `frictal signature` computes on
// the same faces written by `frictal surface wm --seed` (a second path: CLI, CSV files, no study
// code); slide starts move forward with the run-away distance; a tiny study runs and reports its
// three findings.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/cli_runner.hpp"
#include "frictal/study.hpp"
#include "study/study_helpers.hpp"

using namespace frictal::study;

namespace {

constexpr double kPi = 3.14159265358979323846;

const TaskKind& wm_tilt() {
  static const TaskRegistry reg = default_registry();
  const TaskKind* k = reg.find("wm-tilt");
  EXPECT_NE(k, nullptr);
  return *k;
}

// Table II contact law with r = 2e-5 m (the study's), on a short block.
Params table_ii(Params p) {
  p["normal_stiffness"] = 6e5;
  p["tangential_stiffness"] = 6e4;
  p["normal_damping"] = 929.5;
  p["tangential_damping"] = 4.0;
  p["spheroradius"] = 2e-5;
  p["density"] = 50.0;
  p["tilt_rate"] = 0.05;
  p["block_height"] = 0.01;
  return p;
}

void expect_slide_starts_monotone(const TaskOutput& out) {
  const auto& s = out.scalars;
  const double a = s.at("slide_start_half_lambda_m"), b = s.at("slide_start_lambda_m"),
               c = s.at("slide_start_two_lambda_m");
  EXPECT_LE(a, b);
  EXPECT_LE(b, c);
  // The angles at the three distances are tilts at the starts of run-aways that begin no
  // earlier: the tilt only grows, so they do not decrease either.
  EXPECT_LE(s.at("friction_angle_half_lambda_deg"), s.at("friction_angle_lambda_deg"));
  EXPECT_LE(s.at("friction_angle_lambda_deg"), s.at("friction_angle_two_lambda_deg"));
  // The run stops 2 lambda after the start of its last run-away.
  EXPECT_GE(s.at("slide_distance_m"), 2 * s.at("wavelength_m"));
}

}  // namespace

TEST(StudyWmTilt, SinePairSlidesAtItsSteepestSlopeAtEveryRunawayDistance) {
  // z = A sin(2 pi x / lambda) on itself: the nested blocks slide when the tilt reaches the
  // steepest flank, atan(2 pi A / lambda) = 6 deg here, and nothing stops them afterwards. The
  // rounded faces have the same slopes (2r = 4e-5 m is far below the smallest radius of
  // curvature lambda^2 / (4 pi^2 A) = 0.015 m), so the spheropolygon prediction is 6 deg too.
  const double lambda = 0.01, slope = 6.0;
  const double A = std::tan(slope * kPi / 180) * lambda / (2 * kPi);
  Params p = table_ii({{"generator", std::string("sine")},
                       {"amplitude", A},
                       {"wavelength", lambda},
                       {"length", 0.04},
                       {"points_per_wavelength", std::int64_t{400}},
                       {"pair", std::int64_t{0}}});
  auto r = wm_tilt().run(p, 1);
  ASSERT_TRUE(r.ok()) << r.error().message;
  const auto& s = r->scalars;
  EXPECT_EQ(s.at("slid"), 1);
  EXPECT_EQ(s.at("wavelength_m"), lambda);
  // Sampled at 400 points per wavelength the steepest chord is within 1e-4 deg of the tangent.
  EXPECT_NEAR(s.at("theta_max_deg"), slope, 1e-3);
  EXPECT_NEAR(s.at("predicted_sphero_friction_angle_deg"), slope, 1e-2);
  for (const char* k : {"friction_angle_half_lambda_deg", "friction_angle_lambda_deg", "friction_angle_two_lambda_deg"})
    EXPECT_NEAR(s.at(k), slope, 0.1) << k;  // detection lag below 0.1 deg (docs/dem.md)
  EXPECT_EQ(s.at("friction_angle_deg"), s.at("friction_angle_lambda_deg"));
  EXPECT_EQ(s.at("eq18_high_deg"), s.at("theta_max_deg"));  // mu_a = 0
  EXPECT_NEAR(s.at("eq18_low_deg"), s.at("theta_max_deg") - s.at("sigma_deg"), 1e-12);
  EXPECT_EQ(s.at("theta_max_deg"), s.at("theta_max_signature_deg"));
  expect_slide_starts_monotone(*r);
}

namespace {

// The kind's faces are `frictal surface GENERATOR` with seeds derive_seed(task seed, 1 / 2) >> 2
// (docs/studies.md); written to CSV and read by `frictal signature` they give the same theta_max
// and sigma (the signature's default offset range: half the block, as run_tilt uses for a
// non-periodic face).
void expect_signature_of_same_faces(const std::string& generator, const std::string& cli_options, Params p) {
  const std::uint64_t task = 0x5eed0f7a11ULL;
  p["generator"] = generator;
  p["pair"] = std::int64_t{0};
  auto r = wm_tilt().run(table_ii(p), task);
  ASSERT_TRUE(r.ok()) << r.error().message;
  std::string files[2];
  for (int k = 0; k < 2; ++k) {
    files[k] = temp_path("wm_tilt_" + generator + std::to_string(k) + ".csv");
    const auto seed = static_cast<std::int64_t>(derive_seed(task, static_cast<std::uint64_t>(k + 1)) >> 2);
    const CliRun g =
        run_cli("surface " + generator + " " + cli_options + " --seed " + std::to_string(seed) + " -o " + files[k]);
    ASSERT_EQ(g.code, 0) << g.err;
  }
  // The study reads the faces as generated: so does the signature (--detrend none; files are
  // otherwise taken for measured ones and lose their line).
  const CliRun c = run_cli("signature " + files[0] + " " + files[1] + " --detrend none --json");
  ASSERT_EQ(c.code, 0) << c.err;
  const auto j = nlohmann::json::parse(c.out);
  const auto& s = r->scalars;
  EXPECT_NEAR(s.at("theta_max_deg"), j.at("theta_max_forward_deg").get<double>(), 1e-9) << generator;
  EXPECT_NEAR(s.at("sigma_deg"), j.at("contact_slope_std_deg").get<double>(), 1e-9) << generator;
  EXPECT_GT(s.at("sigma_deg"), 0);
  // The Eq. 18 range and the verdict on it follow from those numbers.
  EXPECT_NEAR(s.at("eq18_low_deg"), s.at("theta_max_deg") - s.at("sigma_deg"), 1e-12);
  const double phi = s.at("friction_angle_deg");
  EXPECT_EQ(s.at("inside_eq18"), phi >= s.at("eq18_low_deg") && phi <= s.at("eq18_high_deg") ? 1 : 0);
  expect_slide_starts_monotone(*r);
  for (const auto& f : files) std::remove(f.c_str());
}

}  // namespace

TEST(StudyWmTilt, ThetaMaxAndSigmaEqualFrictalSignatureOnTheSameFaces) {
  expect_signature_of_same_faces(
      "wm",
      "--dimension 1.6 --gamma 1.5 --n-max 4 --longest-wavelength 0.01 --length 0.05 --rms-height 1e-5 --stochastic",
      {{"dimension", 1.6},
       {"gamma", 1.5},
       {"n_max", std::int64_t{4}},
       {"longest_wavelength", 0.01},
       {"length", 0.05},
       {"rms_height", 1e-5}});
}

TEST(StudyWmTilt, FourierPairsTooAndTheirDimensionIsTwoMinusHurst) {
  Params p = {{"hurst", 0.4},
              {"points", std::int64_t{512}},
              {"length", 0.05},
              {"rolloff_wavelength", 0.01},
              {"short_cutoff_wavelength", 1e-3},
              {"rms_height", 1e-5}};
  expect_signature_of_same_faces("fourier",
                                 "--hurst 0.4 --points 512 --length 0.05 --rolloff-wavelength 0.01 "
                                 "--short-cutoff-wavelength 1e-3 --rms-height 1e-5",
                                 p);
  p["generator"] = std::string("fourier");
  p["pair"] = std::int64_t{0};
  auto r = wm_tilt().run(table_ii(p), 9);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_NEAR(r->scalars.at("surface_dimension"), 1.6, 1e-12);
  // A non-periodic face: the block starts inside the first half of the offset range [0, L_b / 2].
  EXPECT_GE(r->scalars.at("start_rule"), 1);
  EXPECT_GT(r->scalars.at("initial_offset_m"), 0);
  EXPECT_LE(r->scalars.at("initial_offset_m"), 0.0125);
  EXPECT_EQ(r->scalars.at("wavelength_m"), 0.01);  // the rolloff wavelength
}

TEST(StudyWmTilt, RefusesParametersTheKindSets) {
  for (const char* name : {"seed", "runaway_distance", "series_interval"}) {
    Params p = {{"generator", std::string("wm")}, {name, std::int64_t{1}}};
    auto r = wm_tilt().run(p, 1);
    ASSERT_FALSE(r.ok()) << name;
    EXPECT_NE(r.error().message.find(name), std::string::npos) << r.error().message;
  }
  auto r = wm_tilt().run({{"generatr", std::string("wm")}}, 1);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("did you mean 'generator'"), std::string::npos) << r.error().message;
}

TEST(StudyWmTilt, TinyStudyRunsAndReportsItsFindings) {
  const std::string toml = temp_path("wm_tilt_tiny.toml");
  write_file(toml, R"([study]
name = "wm-tilt-tiny"
seed = 3
[[part]]
name = "wm"
kind = "wm-tilt"
seed_from = ["pair"]
[part.parameters]
generator = "wm"
dimension = [1.3, 1.7]
pair = { count = 2 }
n_max = 4
longest_wavelength = 0.01
length = 0.04
rms_height = 1e-5
spheroradius = 2e-5
)");
  const std::string store = study_test::fresh("wm_tilt_tiny.sqlite");
  const CliRun run = run_cli("study run " + toml + " --store " + store + " --threads 2");
  ASSERT_EQ(run.code, 0) << run.err << run.out;
  const CliRun rep = run_cli("study report " + store);
  ASSERT_EQ(rep.code, 0) << rep.err;
  for (const char* claim : {"lies in the Eq. 18 range", "does not depend on the run-away distance",
                            "spheropolygon prediction (signature with the spheroradius) is closer"})
    EXPECT_NE(rep.out.find(claim), std::string::npos) << claim << "\n" << rep.out;
  EXPECT_NE(rep.out.find("Part 'wm' (wm-tilt): 4 pairs, 2 values of D"), std::string::npos) << rep.out;
  std::remove(toml.c_str());
}

TEST(StudyWmTilt, ShippedStudyFileParsesAtBothScales) {
  // studies/wm-tilt.toml: 9 D x 20 pairs for WM and for Fourier-filtered pairs, the
  // quasi-static parts (2 D x 3 pairs each for WM and Fourier at 6e7 N/m, and for WM at
  // Table II's 6e5 N/m), the dynamic parts from rest (2 D x 3 pairs, WM and Fourier), and the
  // quick scale that `QUICK=1 make reproduce` runs: 2 D x 2 pairs of each paper-protocol part and
  // one pair per issue-23 part.
  const std::string path = std::string(FRICTAL_TEST_DATA) + "/../../studies/wm-tilt.toml";
  const TaskRegistry reg = default_registry();
  auto full = load_study(path, false, reg), quick = load_study(path, true, reg);
  ASSERT_TRUE(full.ok()) << full.error().message;
  ASSERT_TRUE(quick.ok()) << quick.error().message;
  EXPECT_EQ(full->tasks.size(), 2u * 9u * 20u + 5u * 2u * 3u);
  EXPECT_EQ(quick->tasks.size(), 2u * 2u * 2u + 5u);
}
