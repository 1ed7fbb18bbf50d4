// Scheduling (longest tasks first, estimates refined by recorded times) and the result cache
// shared by the stores of one folder (content addresses: kind, kind version, parameters, seed).
#include <gtest/gtest.h>

#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

#include "frictal/study.hpp"
#include "study_helpers.hpp"

using namespace frictal::study;
using study_test::dump;
using study_test::fresh;

namespace {

/// Order in which the recording kinds below ran their tasks: parameter "w" plus `tag`.
std::mutex g_mu;
std::vector<std::int64_t> g_ran;

/// A kind that records its order (w + tag); its cost model is w times `per_w` (unit: s).
TaskKind recording_kind(const std::string& name, double per_w, std::int64_t tag) {
  TaskKind k{name, "records the order of its runs", 1,
             [tag](const Params& p, std::uint64_t) -> frictal::Result<TaskOutput> {
               std::lock_guard lk(g_mu);
               g_ran.push_back(std::get<std::int64_t>(p.at("w")) + tag);
               TaskOutput t;
               t.scalars["w"] = static_cast<double>(g_ran.back());
               return t;
             }};
  k.cost = [per_w](const Params& p) { return per_w * static_cast<double>(std::get<std::int64_t>(p.at("w"))); };
  return k;
}

Study parse(const std::string& text, const TaskRegistry& reg) {
  auto s = parse_study(text, "test.toml", false, reg);
  EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().message);
  return *s;
}

std::string cache_file(const std::string& name) {
  const std::string p = fresh(name);
  return p;
}

const char* kTwoKinds = R"(
[study]
name = "order"
seed = 1
[[part]]
name = "a"
kind = "rec-a"
[part.parameters]
w = [3, 1, 4, 10, 5, 9, 2, 6]
[[part]]
name = "b"
kind = "rec-b"
[part.parameters]
w = [6, 8]
)";

}  // namespace

TEST(StudySchedule, StartsTheCostliestTasksFirstAndGridOrderOnRequest) {
  TaskRegistry reg;
  reg.add(recording_kind("rec-a", 1.0, 0));
  reg.add(recording_kind("rec-b", 1.0, 100));
  const Study s = parse(kTwoKinds, reg);
  for (const bool longest : {true, false}) {
    g_ran.clear();
    auto st = Store::open(fresh(longest ? "order-longest.sqlite" : "order-grid.sqlite"), s);
    ASSERT_TRUE(st.ok()) << st.error().message;
    RunOptions o;
    o.threads = 1;  // one compute thread takes the queue in order
    o.longest_first = longest;
    auto sum = run_threads(s, **st, reg, o);
    ASSERT_TRUE(sum.ok()) << sum.error().message;
    EXPECT_EQ(sum->ran, 10);
    // Costs equal to w: decreasing w, ties (w = 6 in both parts) in id order; else grid order.
    const std::vector<std::int64_t> expect = longest ? std::vector<std::int64_t>{10, 9, 108, 6, 106, 5, 4, 3, 2, 1}
                                                     : std::vector<std::int64_t>{3, 1, 4, 10, 5, 9, 2, 6, 106, 108};
    EXPECT_EQ(g_ran, expect);
  }
}

TEST(StudySchedule, RecordedTimesCalibrateEachKindsModel) {
  // rec-a's model says w * 1 s, rec-b's w * 1 s; but the store recorded that rec-a tasks take
  // 10 s per unit of w: the remaining rec-a tasks (w = 1..10, i.e. 10-100 s) go before rec-b's
  // (6 and 8 s), costliest first.
  TaskRegistry reg;
  reg.add(recording_kind("rec-a", 1.0, 0));
  reg.add(recording_kind("rec-b", 1.0, 100));
  const Study s = parse(kTwoKinds, reg);
  auto st = Store::open(fresh("order-calibrated.sqlite"), s);
  ASSERT_TRUE(st.ok()) << st.error().message;
  for (std::int64_t id : {2, 5}) {  // w = 4 and 9, recorded as 40 s and 90 s
    TaskRecord r;
    r.id = id;
    r.status = TaskStatus::Done;
    r.wall_s = 10.0 * static_cast<double>(std::get<std::int64_t>(s.tasks[static_cast<std::size_t>(id)].params.at("w")));
    r.output.scalars["w"] = 0;
    ASSERT_TRUE((*st)->record(r).ok());
  }
  g_ran.clear();
  RunOptions o;
  o.threads = 1;
  auto sum = run_threads(s, **st, reg, o);
  ASSERT_TRUE(sum.ok());
  EXPECT_EQ(sum->ran, 8);
  EXPECT_EQ(g_ran, (std::vector<std::int64_t>{10, 6, 5, 3, 2, 1, 108, 106}));
}

namespace {
// Two studies with other names, seeds and part names that share the Koch tasks (K1, alpha 10
// and 20 deg); the seed does not enter the address of koch-signature (a deterministic kind).
const char* kStudyA = R"(
[study]
name = "cache-a"
seed = 6
[[part]]
name = "theory-k01"
kind = "koch-signature"
[part.parameters]
iterations = [0, 1]
alpha = [10.0, 20.0]
length = 0.01
)";
const char* kStudyB = R"(
[study]
name = "cache-b"
seed = 10
[[part]]
name = "theory"
kind = "koch-signature"
[part.parameters]
iterations = [1, 2]
alpha = [10.0, 20.0]
length = 0.01
)";

RunSummary run(const Study& s, const std::string& store, const TaskRegistry& reg, const std::string& cache,
               unsigned threads = 2, std::vector<Progress>* seen = nullptr) {
  auto st = Store::open(store, s);
  EXPECT_TRUE(st.ok()) << (st.ok() ? "" : st.error().message);
  if (!st.ok()) return {};
  RunOptions o;
  o.threads = threads;
  o.cache = cache;
  if (seen) o.progress = [seen](const Progress& p) { seen->push_back(p); };
  auto sum = run_threads(s, **st, reg, o);
  EXPECT_TRUE(sum.ok()) << (sum.ok() ? "" : sum.error().message);
  return sum.ok() ? *sum : RunSummary{};
}
}  // namespace

TEST(StudyCache, ASecondStudyReusesTheSharedTasksByteIdentically) {
  const TaskRegistry reg = default_registry();
  const Study a = parse(kStudyA, reg), b = parse(kStudyB, reg);
  const std::string cache = cache_file("cache-shared.sqlite");
  const RunSummary ra = run(a, fresh("cache-a.sqlite"), reg, cache);
  EXPECT_EQ(ra.ran, 4);
  EXPECT_EQ(ra.reused, 0);
  EXPECT_TRUE(ra.cache_note.empty()) << ra.cache_note;
  std::vector<Progress> seen;
  const std::string bstore = fresh("cache-b.sqlite");
  const RunSummary rb = run(b, bstore, reg, cache, 2, &seen);
  EXPECT_EQ(rb.reused, 2);  // K1 at 10 and 20 deg
  EXPECT_EQ(rb.ran, 2);     // K2 at 10 and 20 deg
  EXPECT_FALSE(rb.interrupted);
  ASSERT_FALSE(seen.empty());
  EXPECT_EQ(seen.back().reused, 2);
  EXPECT_EQ(seen.back().this_run, 4);
  EXPECT_EQ(seen.back().done, 4);
  // The store with reused results holds exactly what a fresh computation gives, on 1 thread
  // and without a cache.
  const std::string ref = fresh("cache-b-ref.sqlite");
  const RunSummary rr = run(b, ref, reg, "", 1);
  EXPECT_EQ(rr.ran, 4);
  EXPECT_EQ(rr.reused, 0);
  EXPECT_EQ(dump(bstore), dump(ref));
  EXPECT_NE(dump(bstore).find("signature_theta_over_alpha"), std::string::npos);  // arrays too
  // The reused tasks say so in the bookkeeping (worker "cache").
  auto st = Store::open_existing(bstore);
  ASSERT_TRUE(st.ok());
  int from_cache = 0;
  auto tasks = (*st)->tasks();  // kept alive: the loop must not iterate a destroyed temporary
  ASSERT_TRUE(tasks.ok());
  for (const auto& t : *tasks) from_cache += t.worker == "cache";
  EXPECT_EQ(from_cache, 2);
  // Everything is in the cache now: a third store of either study computes nothing.
  const RunSummary again = run(a, fresh("cache-a2.sqlite"), reg, cache, 1);
  EXPECT_EQ(again.ran, 0);
  EXPECT_EQ(again.reused, 4);
  // Resume is unchanged: the store already holds every task.
  const RunSummary resumed = run(b, bstore, reg, cache);
  EXPECT_EQ(resumed.ran + resumed.reused, 0);
}

TEST(StudyCache, AnotherKindVersionOrSeedIsNotReused) {
  const TaskRegistry reg = default_registry();
  const std::string cache = cache_file("cache-versions.sqlite");
  const Study a = parse(kStudyA, reg);
  EXPECT_EQ(run(a, fresh("cache-v1.sqlite"), reg, cache).ran, 4);
  // The same kind at version 2 (its results may differ): computed again, not reused.
  TaskRegistry bumped = default_registry();
  TaskKind k = *bumped.find("koch-signature");
  k.version += 1;
  bumped.add(k);
  const Study a2 = parse(kStudyA, bumped);
  const RunSummary r2 = run(a2, fresh("cache-v2.sqlite"), bumped, cache);
  EXPECT_EQ(r2.reused, 0);
  EXPECT_EQ(r2.ran, 4);
  EXPECT_NE(content_address("koch-signature", 1, a.tasks[0].params, false, 0),
            content_address("koch-signature", 2, a.tasks[0].params, false, 0));
  // A kind that uses its seed: another study seed gives other results, so nothing is shared;
  // the same seed and parameters in another study (other name, other part) are.
  const char* wm = R"(
[study]
name = "wm-%s"
seed = %d
[[part]]
name = "%s"
kind = "wm-pair-statistics"
seed_from = ["pair"]
[part.parameters]
dimension = [1.3]
n_max = [2]
pair = { count = 2 }
)";
  auto wm_study = [&](const char* name, int seed, const char* part) {
    char buf[512];
    std::snprintf(buf, sizeof buf, wm, name, seed, part);
    return parse(buf, reg);
  };
  EXPECT_EQ(run(wm_study("one", 1, "wm"), fresh("cache-wm1.sqlite"), reg, cache).ran, 2);
  const RunSummary other_seed = run(wm_study("two", 2, "wm"), fresh("cache-wm2.sqlite"), reg, cache);
  EXPECT_EQ(other_seed.reused, 0);
  EXPECT_EQ(other_seed.ran, 2);
  const std::string same = fresh("cache-wm3.sqlite");
  const RunSummary same_seed = run(wm_study("three", 1, "pairs"), same, reg, cache);
  EXPECT_EQ(same_seed.reused, 2);
  EXPECT_EQ(same_seed.ran, 0);
  const std::string ref = fresh("cache-wm3-ref.sqlite");
  run(wm_study("three", 1, "pairs"), ref, reg, "");
  EXPECT_EQ(dump(same), dump(ref));
}

TEST(StudyCache, AnUnusableCacheIsANoteNotAFailure) {
  const TaskRegistry reg = default_registry();
  const Study a = parse(kStudyA, reg);
  const RunSummary r = run(a, fresh("cache-none.sqlite"), reg, ::testing::TempDir());  // a directory
  EXPECT_EQ(r.ran, 4);
  EXPECT_EQ(r.reused, 0);
  EXPECT_NE(r.cache_note.find("result cache not used"), std::string::npos) << r.cache_note;
  EXPECT_EQ(default_cache_path("out/studies/fig06.sqlite"), "out/studies/results-cache.sqlite");
  EXPECT_EQ(default_cache_path("fig06.sqlite"), "results-cache.sqlite");
}

TEST(StudySchedule, KindCostModelsRankTheExpensiveTasksFirst) {
  // Independent expectations from the physics of each kind, not the models' own numbers: a tilt
  // runs until the tilt reaches the friction angle (n alpha for K_n, plus atan mu_a), and K3 has
  // more contacts than K1; WM pairs cost more with more scales (n_max).
  const TaskRegistry reg = default_registry();
  const auto& tilt = reg.find("tilt")->cost;
  ASSERT_TRUE(tilt);
  auto koch = [](std::int64_t n, double alpha, double mu_a) {
    return Params{{"iterations", n}, {"alpha", alpha}, {"atomic_friction", mu_a}};
  };
  EXPECT_GT(tilt(koch(3, 25, 0)), tilt(koch(3, 10, 0)));
  EXPECT_GT(tilt(koch(3, 20, 0)), tilt(koch(1, 20, 0)));
  EXPECT_GT(tilt(koch(1, 20, 0.5)), tilt(koch(1, 20, 0)));
  const auto& wm = reg.find("wm-pair-statistics")->cost;
  ASSERT_TRUE(wm);
  EXPECT_GT(wm(Params{{"n_max", std::int64_t{10}}}), 10 * wm(Params{{"n_max", std::int64_t{2}}}));
  // Random phases come from the seed; the Koch kinds and the tilt are deterministic.
  EXPECT_TRUE(reg.find("wm-pair-statistics")->uses_seed);
  for (const char* k : {"tilt", "koch-signature", "divider"}) EXPECT_FALSE(reg.find(k)->uses_seed) << k;
}
