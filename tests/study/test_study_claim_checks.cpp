// The claims of Figs. 3, 11, 12, 13 and 16 as the kinds' report sections check them: supported on
// the surfaces the paper describes (the expected values derived from the Koch construction and
// the WM definition), not supported on an input where the claim does not hold.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "frictal/study.hpp"

using namespace frictal::study;

namespace {

TaskRow task(const std::string& kind, const Params& p, std::uint64_t seed = 1) {
  const TaskRegistry reg = default_registry();
  const TaskKind* k = reg.find(kind);
  EXPECT_NE(k, nullptr);
  TaskRow row;
  row.part = "p";
  row.kind = kind;
  row.params = p;
  auto out = k->run(p, seed);
  EXPECT_TRUE(out.ok()) << (out.ok() ? "" : out.error().message);
  if (out.ok()) row.output = *out;
  return row;
}

// The verdict of `claim` in the report of `rows`: 1 supported, 0 not, -1 not checked.
int verdict(const std::string& kind, const std::vector<TaskRow>& rows, const std::string& claim) {
  const TaskRegistry reg = default_registry();
  Report rep;
  reg.find(kind)->report("p", rows, rep);
  for (const auto& f : rep.findings)
    if (f.claim_id == claim) return f.supported ? 1 : 0;
  return -1;
}

Params koch(int n, double alpha_deg) {
  return {{"iterations", std::int64_t{n}}, {"alpha", alpha_deg}, {"wavelength", 0.01}, {"length", 0.03}};
}

Params wm(double dimension, std::int64_t pair) {
  return {{"dimension", dimension},
          {"n_max", std::int64_t{10}},
          {"pair", pair},
          {"compare_phases", std::int64_t{1}},
          {"compare_slopes", std::int64_t{1}}};
}

}  // namespace

TEST(StudyClaimChecks, KochSteepestEdgeAndLengthRatio) {
  const double alpha = 20;
  std::vector<TaskRow> rows;
  for (int n = 0; n <= 2; ++n) rows.push_back(task("koch-signature", koch(n, alpha)));
  // The construction: edges at +-alpha, each iteration adds alpha to the steepest; two thirds of
  // every segment kept, the middle third (base 1/3) replaced by two sides of 1/(6 cos alpha).
  const double ratio = (2 + 1 / std::cos(alpha * std::numbers::pi / 180)) / 3;
  for (int n = 0; n <= 2; ++n) {
    EXPECT_NEAR(rows[n].output.scalars.at("curve_edge_max_deg"), (n + 1) * alpha, 1e-9);
    if (n > 0) {
      EXPECT_NEAR(rows[n].output.scalars.at("curve_length_over_length") /
                      rows[n - 1].output.scalars.at("curve_length_over_length"),
                  ratio, 1e-9);
    }
  }
  // K0 is a row of triangles of base angle alpha: length / extent = 1 / cos(alpha).
  EXPECT_NEAR(rows[0].output.scalars.at("curve_length_over_length"), 1 / std::cos(alpha * std::numbers::pi / 180),
              1e-9);
  EXPECT_EQ(verdict("koch-signature", rows, "koch-steepest-edge"), 1);
  EXPECT_EQ(verdict("koch-signature", rows, "koch-length-ratio"), 1);
  // K2 built at 25 deg but labelled 20 deg: neither its edge nor its length is the 20 deg curve's.
  TaskRow wrong = task("koch-signature", koch(2, 25));
  wrong.params["alpha"] = alpha;
  rows[2] = wrong;
  EXPECT_EQ(verdict("koch-signature", rows, "koch-steepest-edge"), 0);
  EXPECT_EQ(verdict("koch-signature", rows, "koch-length-ratio"), 0);
  // One iteration count per alpha: no length ratio to check.
  EXPECT_EQ(verdict("koch-signature", {rows[0]}, "koch-length-ratio"), -1);
}

TEST(StudyClaimChecks, WmProfileClaims) {
  std::vector<TaskRow> rows;
  for (double d : {1.2, 1.5, 1.8})
    for (std::int64_t k = 0; k < 2; ++k) rows.push_back(task("wm-pair-statistics", wm(d, k), 100 + k));
  for (const char* claim :
       {"wm-contact-narrower", "wm-rougher-with-dimension", "wm-phases-keep-rms-slope", "wm-spline-matches-linear"})
    EXPECT_EQ(verdict("wm-pair-statistics", rows, claim), 1) << claim;

  // Rougher with D: the rows of D = 1.2 and 1.8 swapped, the rms slope falls with the labelled D.
  std::vector<TaskRow> swapped = rows;
  for (auto& r : swapped) {
    const double d = as_number(r.params.at("dimension"));
    if (d != 1.5) r.params["dimension"] = 3.0 - d;
  }
  EXPECT_EQ(verdict("wm-pair-statistics", swapped, "wm-rougher-with-dimension"), 0);

  // Spline against polyline at one point per shortest wavelength (not Eq. 16's ten): they differ.
  Params coarse = wm(1.5, 0);
  coarse["spacing"] = 1e-6 / std::pow(1.5, 10);
  const TaskRow c = task("wm-pair-statistics", coarse, 100);
  EXPECT_EQ(verdict("wm-pair-statistics", {c}, "wm-spline-matches-linear"), 0);

  // A pair whose contact slopes are spread wider than its surface slopes, and whose zero-phase
  // profile has another rms slope: both claims fail on it.
  TaskRow w = rows[2];
  w.output.scalars["contact_slope_std_deg"] = 1.1 * w.output.scalars.at("surface_slope_std_deg");
  w.output.scalars["deterministic_rms_slope"] = 1.05 * w.output.scalars.at("surface_rms_slope");
  std::vector<TaskRow> bad = rows;
  bad[2] = w;
  EXPECT_EQ(verdict("wm-pair-statistics", bad, "wm-contact-narrower"), 0);
  EXPECT_EQ(verdict("wm-pair-statistics", bad, "wm-phases-keep-rms-slope"), 0);

  // Without the comparisons a part checks neither; a part at one D checks no trend in D.
  std::vector<TaskRow> one_d(rows.begin() + 2, rows.begin() + 4);
  EXPECT_EQ(verdict("wm-pair-statistics", one_d, "wm-rougher-with-dimension"), -1);
  EXPECT_EQ(verdict("wm-pair-statistics", one_d, "wm-slopes-grow-with-dimension"), -1);
  Params plain = wm(1.5, 0);
  plain.erase("compare_phases");
  plain.erase("compare_slopes");
  const TaskRow p = task("wm-pair-statistics", plain, 100);
  EXPECT_EQ(verdict("wm-pair-statistics", {p}, "wm-phases-keep-rms-slope"), -1);
  EXPECT_EQ(verdict("wm-pair-statistics", {p}, "wm-spline-matches-linear"), -1);
}

TEST(StudyClaimChecks, WmCompareParametersAreChecked) {
  const TaskRegistry reg = default_registry();
  const TaskKind* k = reg.find("wm-pair-statistics");
  Params p = wm(1.5, 0);
  p["compare_phases"] = std::int64_t{2};
  auto r = k->run(p, 1);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("compare_phases"), std::string::npos);
  p = wm(1.5, 0);
  p["slopes"] = std::string("spline");
  r = k->run(p, 1);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("'slopes' must be"), std::string::npos);
}
