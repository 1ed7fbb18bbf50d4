// Study kinds read their TOML parameters through the library's tables: every table name is a key
// that the kind reads (a bad value for it is refused naming it), angles are in degrees, and the
// values reach the computation.
#include <gtest/gtest.h>

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

}  // namespace

TEST(StudyTables, TiltKindReadsEveryTiltSettingAndKochParameter) {
  std::vector<Field> fields = tilt_settings();
  for (const Field& f : find_generator("koch")->fields) fields.push_back(f);
  for (const Field& f : fields) {
    Params p{{"iterations", std::int64_t{0}}, {"alpha", 5.0}, {"length", 0.02}, {"max_tilt", 1.0}};
    p[f.name] = bad_value(f);
    auto r = run_tilt_task(p, 0);
    ASSERT_FALSE(r.ok()) << f.name;
    EXPECT_NE(r.error().message.find("parameter '" + f.name + "'"), std::string::npos) << r.error().message;
  }
}

TEST(StudyTables, TiltKindTakesDegreesAndTheGeneratorsPeriod) {
  // K0 at alpha = 10 deg on two wavelengths, mu_a = 0.25, stopped at 2 deg of tilt: the
  // prediction is alpha + atan(mu_a) (Sec. III, Eq. 6) whatever the run does.
  Params p{{"iterations", std::int64_t{0}}, {"alpha", 10.0}, {"length", 0.02}, {"max_tilt", 2.0},
           {"atomic_friction", 0.25}, {"time_step", 2e-5}};
  auto r = run_tilt_task(p, 0);
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_NEAR(r->scalars.at("predicted_friction_angle_deg"), 10 + std::atan(0.25) * 180 / std::numbers::pi, 1e-9);
  EXPECT_EQ(r->scalars.at("slid"), 0);  // 2 deg of tilt is below 10 deg + atan(0.25)
  EXPECT_DOUBLE_EQ(r->scalars.at("time_step_s"), 2e-5);
  // A sawtooth by name: the prediction is its rise angle.
  Params s{{"generator", std::string("sawtooth")}, {"rise_angle", 12.0}, {"length", 0.02}, {"max_tilt", 1.0}};
  auto q = run_tilt_task(s, 0);
  ASSERT_TRUE(q.ok()) << q.error().message;
  EXPECT_NEAR(q->scalars.at("predicted_theta_max_deg"), 12.0, 1e-9);
  s["generator"] = std::string("sawtoth");
  EXPECT_FALSE(run_tilt_task(s, 0).ok());
}

TEST(StudyTables, SignatureAndWmKindsReadTheirGeneratorTables) {
  for (const Field& f : find_generator("koch")->fields) {
    Params p{{"iterations", std::int64_t{0}}, {"alpha", 5.0}, {"length", 0.01}};
    p[f.name] = bad_value(f);
    auto r = run_koch_signature(p, 0);
    ASSERT_FALSE(r.ok()) << f.name;
    EXPECT_NE(r.error().message.find("parameter '" + f.name + "'"), std::string::npos) << r.error().message;
    auto d = run_divider_task(p, 0);
    ASSERT_FALSE(d.ok()) << f.name;
    EXPECT_NE(d.error().message.find("parameter '" + f.name + "'"), std::string::npos) << d.error().message;
  }
  for (const Field& f : find_generator("wm")->fields) {
    if (f.name == "seed" || f.name == "stochastic") continue;  // the pair's phases come from the task seed
    if (f.name == "rms_height") continue;                      // any value is valid (<= 0 keeps G = 1)
    Params p{{"dimension", 1.5}, {"n_max", std::int64_t{3}}};
    p[f.name] = bad_value(f);
    auto r = run_wm_pair_statistics(p, 1);
    ASSERT_FALSE(r.ok()) << f.name;
    EXPECT_NE(r.error().message.find("parameter '" + f.name + "'"), std::string::npos) << r.error().message;
  }
}
