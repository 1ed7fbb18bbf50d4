// Study kinds read their TOML parameters through the library's tables: every table name is a key
// that the kind reads (a bad value for it is refused naming it), angles are in degrees, and the
// values reach the computation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "frictal/study.hpp"
#include "frictal/surface_spec.hpp"
#include "frictal/tilt.hpp"

using namespace frictal;
using namespace frictal::study;

namespace {

/// A value of the field's TOML type that its range refuses.
Value bad_value(const Field& f) {
  switch (f.type) {
    case FieldType::Boolean: return std::string("yes please");
    case FieldType::Choice: return std::string("bogus");
    case FieldType::Integer: return std::int64_t(std::isfinite(f.min) ? static_cast<std::int64_t>(f.min) - 1 : 0);
    case FieldType::Real:
      if (std::isfinite(f.min)) return f.min_open ? to_text_unit(f, f.min) : to_text_unit(f, f.min) - 1;
      if (std::isfinite(f.max)) return to_text_unit(f, f.max) + 1;
      return std::string("not a number");
  }
  return std::string("?");
}

/// Runs a task kind of the default registry.
frictal::Result<TaskOutput> run_kind(const std::string& name, const Params& p, std::uint64_t seed) {
  return default_registry().find(name)->run(p, seed);
}

}  // namespace

TEST(StudyTables, TiltKindReadsEveryTiltSettingAndKochParameter) {
  std::vector<Field> fields = tilt_settings();
  for (const Field& f : find_generator("koch")->fields) fields.push_back(f);
  for (const Field& f : fields) {
    Params p{{"iterations", std::int64_t{0}}, {"alpha", 5.0}, {"length", 0.02}, {"max_tilt", 1.0}};
    p[f.name] = bad_value(f);
    auto r = run_kind("tilt", p, 0);
    ASSERT_FALSE(r.ok()) << f.name;
    EXPECT_NE(r.error().message.find("parameter '" + f.name + "'"), std::string::npos) << r.error().message;
  }
}

TEST(StudyTables, TiltKindTakesDegreesAndTheGeneratorsPeriod) {
  // K0 at alpha = 10 deg on two wavelengths, mu_a = 0.25, stopped at 2 deg of tilt: the
  // prediction is alpha + atan(mu_a) (Sec. III, Eq. 6) whatever the run does.
  Params p{{"iterations", std::int64_t{0}}, {"alpha", 10.0},    {"length", 0.02}, {"max_tilt", 2.0},
           {"atomic_friction", 0.25},       {"time_step", 2e-5}};
  auto r = run_kind("tilt", p, 0);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_NEAR(r->scalars.at("predicted_friction_angle_deg"), 10 + std::atan(0.25) * 180 / std::numbers::pi, 1e-9);
  EXPECT_EQ(r->scalars.at("slid"), 0);  // 2 deg of tilt is below 10 deg + atan(0.25)
  EXPECT_DOUBLE_EQ(r->scalars.at("time_step_s"), 2e-5);
  // A sawtooth by name: the prediction is its rise angle.
  Params s{{"generator", std::string("sawtooth")}, {"rise_angle", 12.0}, {"length", 0.02}, {"max_tilt", 1.0}};
  auto q = run_kind("tilt", s, 0);
  ASSERT_TRUE(q.ok()) << q.error().message;
  EXPECT_NEAR(q->scalars.at("predicted_theta_max_deg"), 12.0, 1e-9);
  s["generator"] = std::string("sawtoth");
  EXPECT_FALSE(run_kind("tilt", s, 0).ok());
}

TEST(StudyTables, SignatureAndWmKindsReadTheirGeneratorTables) {
  for (const Field& f : find_generator("koch")->fields) {
    Params p{{"iterations", std::int64_t{0}}, {"alpha", 5.0}, {"length", 0.01}};
    p[f.name] = bad_value(f);
    auto r = run_kind("koch-signature", p, 0);
    ASSERT_FALSE(r.ok()) << f.name;
    EXPECT_NE(r.error().message.find("parameter '" + f.name + "'"), std::string::npos) << r.error().message;
    auto d = run_kind("divider", p, 0);
    ASSERT_FALSE(d.ok()) << f.name;
    EXPECT_NE(d.error().message.find("parameter '" + f.name + "'"), std::string::npos) << d.error().message;
  }
  for (const Field& f : find_generator("wm")->fields) {
    if (f.name == "seed" || f.name == "stochastic") continue;  // the pair's phases come from the task seed
    if (f.name == "rms_height") continue;                      // any value is valid (<= 0 keeps G = 1)
    Params p{{"dimension", 1.5}, {"n_max", std::int64_t{3}}};
    p[f.name] = bad_value(f);
    auto r = run_kind("wm-pair-statistics", p, 1);
    ASSERT_FALSE(r.ok()) << f.name;
    EXPECT_NE(r.error().message.find("parameter '" + f.name + "'"), std::string::npos) << r.error().message;
  }
}

TEST(StudyTables, RetiredOrMistypedKeysAreRefusedNotIgnored) {
  Params p{{"iterations", std::int64_t{0}}, {"alpha_deg", 5.0}, {"length", 0.02}};
  auto r = run_kind("tilt", p, 0);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(
      r.error().message.find("parameter 'alpha_deg' is not a parameter of task kind 'tilt'; did you mean 'alpha'?"),
      std::string::npos)
      << r.error().message;
  p = {{"iterations", std::int64_t{0}}, {"alpha", 5.0}, {"radius", 5e-5}};
  EXPECT_FALSE(run_kind("tilt", p, 0).ok());
  p = {{"iterations", std::int64_t{0}}, {"alpha", 5.0}, {"lenght", 0.01}};
  r = run_kind("koch-signature", p, 0);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("did you mean 'length'?"), std::string::npos) << r.error().message;
  EXPECT_FALSE(run_kind("divider", p, 0).ok());
  EXPECT_FALSE(run_kind("wm-pair-statistics", {{"dimension", 1.5}, {"rms", 1e-9}}, 1).ok());
}

TEST(StudyTables, ShippedStudiesUseOnlyTheKindsNames) {
  // Every task of every shipped study names only parameters its kind reads: the tables' names
  // plus each kind's own (record_series, offsets, slopes, bins, pair, rulers, ...).
  std::vector<std::string> names;
  for (const Field& f : tilt_settings()) names.push_back(f.name);
  for (const auto& g : surface_generators())
    for (const Field& f : g.fields) names.push_back(f.name);
  for (const char* extra : {"generator", "record_series", "atomic_friction", "offsets", "slopes", "bins", "pair",
                            "ruler_min_over_wavelength", "ruler_max_over_wavelength", "rulers"})
    names.push_back(extra);
  const TaskRegistry reg = default_registry();
  const std::string dir = std::string(FRICTAL_TEST_DATA) + "/../../studies/";
  for (const char* n : {"fig04-koch-signature", "fig06-koch-friction", "fig07-time-evolution", "fig08-atomic-friction",
                        "fig09-divider", "fig10-mu-vs-dimension", "fig14-18-wm-statistics"})
    for (bool quick : {false, true}) {
      auto s = load_study(dir + n + ".toml", quick, reg);
      ASSERT_TRUE(s.ok()) << s.error().message;
      for (const auto& t : s->tasks)
        for (const auto& [k, v] : t.params)
          EXPECT_NE(std::find(names.begin(), names.end(), k), names.end()) << n << ": " << k;
    }
}

// The status of a part as its output table writes it: the counts by version are data maps keyed
// by the version (a kind version 0 and an empty frictal version: results of a schema-1 store),
// and the status text names the same versions.
TEST(StudyTables, PartStatusWritesItsVersionCountsKeyedByVersion) {
  StoreStatus::PartStatus p;
  p.part = "b";
  p.kind = "koch-signature";
  p.done = 7;
  p.done_by_kind_version = {{0, 3}, {2, 4}};
  p.done_by_frictal_version = {{"", 3}, {"0.1.0", 4}};
  const OutputRow row = row_of(study_part_columns(), p);
  auto field = [&](const std::string& key) {
    const auto it = std::find_if(row.begin(), row.end(), [&](const OutputField& f) { return f.info.key == key; });
    EXPECT_NE(it, row.end()) << key;
    return *it;
  };
  const OutputField kinds = field("done_by_kind_version");
  EXPECT_EQ(kinds.info.unit, "map");
  EXPECT_EQ(kinds.info.python, "done_by_kind_version");  // in Python's status dict too
  ASSERT_EQ(kinds.rows.size(), 1u);
  ASSERT_EQ(kinds.rows[0].size(), 2u);
  EXPECT_EQ(kinds.rows[0][0].info.key, "0");
  EXPECT_EQ(kinds.rows[0][0].info.unit, "count");
  EXPECT_DOUBLE_EQ(std::get<double>(kinds.rows[0][0].si), 3.0);
  EXPECT_EQ(kinds.rows[0][1].info.key, "2");
  EXPECT_DOUBLE_EQ(std::get<double>(kinds.rows[0][1].si), 4.0);
  const OutputField builds = field("done_by_frictal_version");
  ASSERT_EQ(builds.rows.size(), 1u);
  ASSERT_EQ(builds.rows[0].size(), 2u);
  EXPECT_EQ(builds.rows[0][0].info.key, "");  // kept: an empty version is a key of its own
  EXPECT_DOUBLE_EQ(std::get<double>(builds.rows[0][0].si), 3.0);
  EXPECT_EQ(builds.rows[0][1].info.key, "0.1.0");

  EXPECT_EQ(done_versions_text(p), "3 by unrecorded version, 4 by v2, 3 by frictal ?, 4 by frictal 0.1.0");
  EXPECT_EQ(done_versions_text(StoreStatus::PartStatus{}), "");
}

// A done task as Python's study_rows() holds it: id, part and kind, then its parameters and
// outputs as data maps, each value in the unit of its type (an integer parameter a count).
TEST(StudyTables, TaskRowWritesParametersAndOutputsAsDataMaps) {
  TaskRow r;
  r.id = 5;
  r.part = "theory";
  r.kind = "koch-signature";
  r.params = {{"alpha", 10.0}, {"iterations", std::int64_t(2)}, {"name", std::string("k")}, {"free", true}};
  r.output.scalars = {{"friction_angle_deg", 20.0}};
  r.output.arrays = {{"theta_deg", {1.0, 2.0}}};
  const OutputRow row = row_of(study_row_columns(), r);
  ASSERT_EQ(row.size(), 6u);
  std::vector<std::string> python;
  for (const OutputField& f : row) {
    python.push_back(f.info.python);
    EXPECT_TRUE(f.info.key.empty()) << f.info.python;  // Python only
  }
  EXPECT_EQ(python, (std::vector<std::string>{"task_id", "part", "kind", "params", "scalars", "arrays"}));
  EXPECT_DOUBLE_EQ(std::get<double>(row[0].si), 5.0);
  EXPECT_EQ(row[0].info.unit, "count");
  const OutputRow& params = row[3].rows.at(0);
  ASSERT_EQ(params.size(), 4u);  // by name
  EXPECT_EQ(params[0].info.python, "alpha");
  EXPECT_EQ(params[0].info.unit, "1");  // as given: no conversion of the study's degrees
  EXPECT_DOUBLE_EQ(std::get<double>(params[0].si), 10.0);
  EXPECT_EQ(params[1].info.python, "free");
  EXPECT_EQ(std::get<bool>(params[1].si), true);
  EXPECT_EQ(params[2].info.python, "iterations");
  EXPECT_EQ(params[2].info.unit, "count");
  EXPECT_DOUBLE_EQ(std::get<double>(params[2].si), 2.0);
  EXPECT_EQ(std::get<std::string>(params[3].si), "k");
  EXPECT_DOUBLE_EQ(std::get<double>(row[4].rows.at(0).at(0).si), 20.0);
  EXPECT_EQ(std::get<std::vector<double>>(row[5].rows.at(0).at(0).si), (std::vector<double>{1.0, 2.0}));
  // Without arrays read: an empty map, not a missing key.
  r.output.arrays.clear();
  const OutputRow bare = row_of(study_row_columns(), r);
  ASSERT_EQ(bare.size(), 6u);
  EXPECT_TRUE(bare[5].rows.at(0).empty());
}
