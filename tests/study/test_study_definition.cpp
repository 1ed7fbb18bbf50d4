// Study definitions: canonical text, seeds, grid expansion, hashing, errors.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "frictal/study.hpp"

using namespace frictal::study;

namespace {
const TaskRegistry& reg() {
  static const TaskRegistry r = default_registry();
  return r;
}
Study parse(const std::string& text, bool quick = false) {
  auto s = parse_study(text, "test.toml", quick, reg());
  EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().message);
  return s.ok() ? *s : Study{};
}
std::string parse_error(const std::string& text, bool quick = false) {
  auto s = parse_study(text, "test.toml", quick, reg());
  EXPECT_FALSE(s.ok());
  return s.ok() ? std::string{} : s.error().message;
}
const char* kWm = R"(
[study]
name = "t"
seed = 7
[[part]]
name = "wm"
kind = "wm-pair-statistics"
seed_from = ["pair"]
[part.parameters]
dimension = { from = 1.0, to = 2.0, step = 0.1 }
n_max = { from = 0, to = 10 }
pair = { count = 3 }
slopes = "exact"
[part.quick]
dimension = [1.3]
n_max = [2, 4]
)";
}  // namespace

TEST(StudyCanonical, SortedKeysAndDistinctIntegersAndReals) {
  Params p;
  p["b"] = std::int64_t{2};
  p["a"] = 2.0;
  p["c"] = std::string("x\"y");
  p["d"] = true;
  p["e"] = 0.1;
  EXPECT_EQ(canonical(p), R"({"a":2.0,"b":2,"c":"x\"y","d":true,"e":0.1})");
  EXPECT_EQ(canonical(Value{1e-6}), "1e-06");
}

TEST(StudyCanonical, SeedsDependOnParametersOnly) {
  Params a{{"pair", std::int64_t{1}}, {"D", 1.5}}, b{{"D", 1.5}, {"pair", std::int64_t{1}}};
  EXPECT_EQ(task_seed(9, a), task_seed(9, b));  // order of insertion is irrelevant
  EXPECT_NE(task_seed(9, a), task_seed(10, a));
  Params c = a;
  c["pair"] = std::int64_t{2};
  EXPECT_NE(task_seed(9, a), task_seed(9, c));
  EXPECT_NE(derive_seed(5, 1), derive_seed(5, 2));
  EXPECT_EQ(digest("abc").size(), 32u);
  EXPECT_NE(digest("abc"), digest("abd"));
}

TEST(StudyGrid, FullScaleExpansion) {
  Study s = parse(kWm);
  ASSERT_EQ(s.parts.size(), 1u);
  EXPECT_EQ(s.tasks.size(), 11u * 11u * 3u);
  // Axes sorted by name; the last (pair) varies fastest.
  EXPECT_EQ(canonical(s.tasks[0].params), R"({"dimension":1.0,"n_max":0,"pair":0,"slopes":"exact"})");
  EXPECT_EQ(canonical(s.tasks[1].params), R"({"dimension":1.0,"n_max":0,"pair":1,"slopes":"exact"})");
  EXPECT_EQ(canonical(s.tasks[3].params), R"({"dimension":1.0,"n_max":1,"pair":0,"slopes":"exact"})");
  // 1.0 + 3 * 0.1 is stored as the number 1.3 (tidy ranges), and the last value is 2.0 exactly.
  EXPECT_EQ(std::get<double>(s.tasks[3 * 33].params.at("dimension")), 1.3);
  EXPECT_EQ(std::get<double>(s.tasks.back().params.at("dimension")), 2.0);
  std::set<std::string> keys;
  for (std::size_t i = 0; i < s.tasks.size(); ++i) {
    EXPECT_EQ(s.tasks[i].id, static_cast<std::int64_t>(i));
    keys.insert(s.tasks[i].key);
  }
  EXPECT_EQ(keys.size(), s.tasks.size());
  // seed_from = ["pair"]: same pair, same seed at every D and n_max; different pairs differ.
  EXPECT_EQ(s.tasks[0].seed, s.tasks[3].seed);
  EXPECT_EQ(s.tasks[0].seed, s.tasks[s.tasks.size() - 3].seed);
  EXPECT_NE(s.tasks[0].seed, s.tasks[1].seed);
  EXPECT_EQ(s.tasks[0].seed, task_seed(7, Params{{"pair", std::int64_t{0}}}));
}

TEST(StudyGrid, QuickOverridesAndHash) {
  Study full = parse(kWm), quick = parse(kWm, true);
  EXPECT_EQ(quick.tasks.size(), 1u * 2u * 3u);
  EXPECT_NE(full.hash, quick.hash);
  // A task present at both scales has the same seed (its parameters are the same).
  EXPECT_EQ(quick.tasks[0].seed, full.tasks[0].seed);
  // The description does not enter the hash; the seed does.
  std::string t = kWm;
  Study described = parse(t.replace(t.find("seed = 7"), 8, "description = \"x\"\nseed = 7"));
  EXPECT_EQ(described.hash, full.hash);
  std::string t2 = kWm;
  Study reseeded = parse(t2.replace(t2.find("seed = 7"), 8, "seed = 8"));
  EXPECT_NE(reseeded.hash, full.hash);
  // A new kind version (changed results) changes the hash.
  TaskRegistry r2 = default_registry();
  TaskKind k = *r2.find("wm-pair-statistics");
  k.version += 1;
  r2.add(k);
  auto bumped = parse_study(kWm, "test.toml", false, r2);
  ASSERT_TRUE(bumped.ok());
  EXPECT_NE(bumped->hash, full.hash);
}

TEST(StudyGrid, RangeForms) {
  Study s = parse(R"(
[study]
name = "r"
seed = 1
[[part]]
name = "p"
kind = "koch-signature"
[part.parameters]
iterations = { from = 0, to = 6, step = 3 }
alpha_deg = { from = 5.0, to = 6.0, count = 3 }
)");
  ASSERT_EQ(s.tasks.size(), 9u);
  // alpha_deg sorts before iterations, so iterations varies fastest.
  EXPECT_EQ(std::get<double>(s.tasks[3].params.at("alpha_deg")), 5.5);
  EXPECT_EQ(std::get<std::int64_t>(s.tasks[1].params.at("iterations")), 3);
  EXPECT_EQ(std::get<std::int64_t>(s.tasks[8].params.at("iterations")), 6);
}

TEST(StudyGrid, ErrorsNameTheProblem) {
  EXPECT_NE(parse_error("[study]\nname='a'\nseed=1\n").find("[[part]]"), std::string::npos);
  EXPECT_NE(parse_error("[study]\nname='a'\nseed=1\n[[part]]\nname='p'\nkind='nope'\n[part.parameters]\nx=1\n")
                .find("unknown task kind 'nope'"),
            std::string::npos);
  EXPECT_NE(
      parse_error("[study]\nname='a'\nseed=1\n[[part]]\nname='p'\nkind='koch-signature'\n[part.parameters]\nx=[]\n")
          .find("parameter 'x'"),
      std::string::npos);
  EXPECT_NE(parse_error("[study]\nname='a'\nseed=1\n[[part]]\nname='p'\nkind='koch-signature'\n[part.parameters]\n"
                        "x={from=1,to=2,stride=1}\n")
                .find("unknown range key 'stride'"),
            std::string::npos);
  EXPECT_NE(parse_error("[study]\nname='a'\nseed=1\n[[part]]\nname='p'\nkind='koch-signature'\n[part.parameters]\nx=1\n"
                        "[part.quick]\ny=2\n",
                        true)
                .find("quick overrides 'y'"),
            std::string::npos);
  EXPECT_NE(parse_error("[study]\nname='a'\nseed=1\nbogus=2\n").find("unknown key 'bogus'"), std::string::npos);
  // A list that repeats a value would define one task twice (caught here, not later in the store
  // as "writing tasks: not an error").
  EXPECT_NE(parse_error("[study]\nname='a'\nseed=1\n[[part]]\nname='p'\nkind='koch-signature'\n[part.parameters]\n"
                        "iterations=[1, 2, 1]\n")
                .find("appears twice"),
            std::string::npos);
  EXPECT_NE(parse_error("[study\n").find("test.toml:1"), std::string::npos);
  // An unavailable kind parses (the store keeps its tasks pending until the engine exists).
  auto ok =
      parse_study("[study]\nname='a'\nseed=1\n[[part]]\nname='sim'\nkind='tilt'\n[part.parameters]\nalpha_deg=[5.0]\n",
                  "t.toml", false, reg());
  EXPECT_TRUE(ok.ok());
}
