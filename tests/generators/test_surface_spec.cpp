// Settings tables and the surface specification: the one unit conversion, value checks, "did
// you mean", specs generating the same surfaces as the generators, and the tilt table's
// defaults against the paper's Table I/II.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>

#include "frictal/settings.hpp"
#include "frictal/surface_spec.hpp"
#include "frictal/tilt.hpp"

using namespace frictal;

namespace {
constexpr double kPi = std::numbers::pi;
}

TEST(Settings, OneAngleConversionDrivenByTheUnit) {
  const Field& alpha = *find_field(find_generator("koch")->fields, "alpha");
  const Field& wavelength = *find_field(find_generator("koch")->fields, "wavelength");
  EXPECT_EQ(alpha.unit, "rad");
  EXPECT_EQ(text_unit(alpha), "deg");
  EXPECT_NEAR(to_text_unit(alpha, kPi / 3), 60.0, 1e-12);
  EXPECT_NEAR(from_text_unit(alpha, 45.0), kPi / 4, 1e-15);
  EXPECT_EQ(to_text_unit(wavelength, 0.01), 0.01);  // metres stay metres
  EXPECT_EQ(cli_option_name(*find_field(find_generator("sawtooth")->fields, "rise_angle")), "--rise-angle");
  EXPECT_EQ(default_text(alpha), "5");
  EXPECT_EQ(range_text(alpha), "(0, 60] deg");
}

TEST(Settings, ValuesAreCheckedAgainstTypeAndRange) {
  const auto& koch = find_generator("koch")->fields;
  const Field& n = *find_field(koch, "iterations");
  EXPECT_EQ(std::get<std::int64_t>(*check_si_value(n, 3.0)), 3);  // a whole real is an integer
  EXPECT_FALSE(check_si_value(n, 2.5).ok());
  EXPECT_FALSE(check_si_value(n, std::int64_t{11}).ok());
  auto bad = si_from_text(*find_field(koch, "alpha"), 75.0, "--alpha");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().message, "--alpha: expected a number in (0, 60] deg, got 75");
  auto ok = si_from_text(*find_field(koch, "alpha"), std::int64_t{30}, "--alpha");
  ASSERT_TRUE(ok.ok());
  EXPECT_NEAR(std::get<double>(*ok), kPi / 6, 1e-15);
  const Field& exponent = *find_field(find_generator("wm")->fields, "exponent");
  auto e = check_si_value(exponent, std::string("comon"));
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().message.find("did you mean 'common'?"), std::string::npos) << e.error().message;
  EXPECT_FALSE(parse_text_word(n, "2x", "-n").ok());
}

TEST(Settings, EditDistanceAndNearestWord) {
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);  // the textbook example
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("flaw", "lawn"), 2u);
  const std::vector<std::string> commands{"surface", "signature", "stats", "dimension", "study", "tilt"};
  EXPECT_EQ(nearest_word("stat", commands), "stats");
  EXPECT_EQ(nearest_word("signatrue", commands), "signature");
  EXPECT_EQ(nearest_word("report", commands), "");
}

TEST(SurfaceSpec, GeneratesWhatTheGeneratorsGenerate) {
  auto spec = make_surface_spec("koch", {{"iterations", std::int64_t{2}}, {"alpha", 20 * kPi / 180}});
  ASSERT_TRUE(spec.ok()) << spec.error().message;
  KochParams kp;
  kp.iterations = 2;
  kp.alpha = 20 * kPi / 180;
  const Profile a = *generate_profile(*spec), b = *koch_profile(kp);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.z, b.z);
  EXPECT_EQ(generate_curve(*spec)->size(), koch_curve(kp)->size());
  // Sawtooth at 30 deg rising over half of lambda = 0.01 m: top = 0.005 tan(30 deg).
  auto saw = make_surface_spec("sawtooth", {{"rise_angle", kPi / 6}, {"length", 0.02}});
  ASSERT_TRUE(saw.ok());
  const Profile s = *generate_profile(*saw);
  EXPECT_NEAR(*std::max_element(s.z.begin(), s.z.end()), 0.005 * std::tan(kPi / 6), 1e-15);
  EXPECT_DOUBLE_EQ(*surface_period(*saw), 0.01);
  auto wm = make_surface_spec("wm", {{"longest_wavelength", 2e-6}});
  EXPECT_EQ(*surface_period(*wm), 0.0);
  EXPECT_DOUBLE_EQ(*surface_scale(*wm), 2e-6);
  auto sa = make_surface_spec("self-affine", {{"length", 1e-3}});
  EXPECT_DOUBLE_EQ(*surface_scale(*sa), 1e-4);
  EXPECT_EQ(std::get<std::int64_t>(surface_values(*sa)->at("points")), 1024);
}

TEST(SurfaceSpec, UnknownNamesAreRefusedWithTheNearest) {
  auto g = make_surface_spec("kosh", {});
  ASSERT_FALSE(g.ok());
  EXPECT_NE(g.error().message.find("did you mean 'koch'?"), std::string::npos) << g.error().message;
  auto p = make_surface_spec("koch", {{"alpah", 0.1}});
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.error().message.find("unknown parameter 'alpah' (did you mean 'alpha'?)"), std::string::npos)
      << p.error().message;
  // The sawtooth's angle is rise_angle, not alpha.
  EXPECT_FALSE(make_surface_spec("sawtooth", {{"alpha", 0.1}}).ok());
  EXPECT_FALSE(make_surface_spec("sine", {{"points_per_wavelength", std::int64_t{3}}}).ok());
}

TEST(TiltSettings, DefaultsAreThePapersTablesAndValuesApply) {
  // Table I/II of the paper and Sec. IV A.
  const std::map<std::string, double> paper = {
      {"normal_stiffness", 6e5}, {"tangential_stiffness", 6e4}, {"normal_damping", 929.5},
      {"tangential_damping", 4}, {"spheroradius", 5e-5},        {"density", 50},
      {"block_height", 0.01},    {"tilt_rate", 0.05},           {"atomic_friction", 0}};
  for (const auto& [name, value] : paper) {
    const Field* f = find_field(tilt_settings(), name);
    ASSERT_NE(f, nullptr) << name;
    EXPECT_DOUBLE_EQ(f->default_value, value) << name;
  }
  EXPECT_NEAR(find_field(tilt_settings(), "max_tilt")->default_value, 89 * kPi / 180, 1e-15);
  // Names are unique.
  std::set<std::string> names;
  for (const Field& f : tilt_settings()) EXPECT_TRUE(names.insert(f.name).second) << f.name;
  auto c = make_tilt_config({{"time_step", 2e-5},
                             {"face", std::string("envelope")},
                             {"reverse", true},
                             {"normal_stiffness", std::int64_t{1000}}});
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->time_step, 2e-5);
  EXPECT_EQ(c->face, TiltFace::Envelope);
  EXPECT_TRUE(c->reverse);
  EXPECT_EQ(c->contact.normal_stiffness, 1000.0);
  EXPECT_FALSE(make_tilt_config({{"time_step", 0.0}}).ok());
  EXPECT_FALSE(make_tilt_config({{"max_tilt", kPi / 2}}).ok());
  EXPECT_FALSE(make_tilt_config({{"dt", 1e-5}}).ok());
  // Round trip: the values of a config rebuild it.
  auto back = make_tilt_config(tilt_values(*c));
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(back->time_step, c->time_step);
  EXPECT_EQ(back->face, c->face);
  EXPECT_TRUE(std::isnan(back->initial_offset));
  // A generated surface sets the period and the run-away distance.
  const TiltConfig s = tilt_config_for_surface(0.02, 0.02);
  EXPECT_EQ(s.period, 0.02);
  EXPECT_EQ(s.runaway_distance, 0.02);
  EXPECT_EQ(tilt_config_for_surface(0, 0).runaway_distance, TiltConfig{}.runaway_distance);
}
