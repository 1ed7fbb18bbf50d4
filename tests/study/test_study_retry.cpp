// The coordinator's retry policy (the same for threads and MPI), error codes, and the task kinds
// as units (declared outputs, report sections, plot views).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <mutex>
#include <numbers>
#include <set>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "frictal/areal_tilt.hpp"
#include "frictal/generators.hpp"
#include "frictal/io.hpp"
#include "frictal/study.hpp"
#include "frictal/tilt.hpp"

using namespace frictal;
using namespace frictal::study;

namespace {

std::string tmp(const std::string& name) {
  const std::string p = ::testing::TempDir() + "frictal_retry_" + name;
  for (const char* suffix : {"", "-wal", "-shm"}) std::remove((p + suffix).c_str());
  return p;
}

/// y = 3 x + 1 from the parameter x; `fail` decides, per x and attempt, how an attempt fails.
struct Calc {
  std::mutex mu;
  std::map<std::int64_t, int> calls;  // x -> attempts seen (owned by the test: no global state)
  std::function<Result<TaskOutput>(std::int64_t x, int attempt)> fail;
  TaskRegistry registry() {
    TaskRegistry r;
    r.add({"calc", "test kind", 1, [this](const Params& p, std::uint64_t) -> Result<TaskOutput> {
             const std::int64_t x = std::get<std::int64_t>(p.at("x"));
             int attempt;
             {
               std::lock_guard lk(mu);
               attempt = ++calls[x];
             }
             if (fail) {
               auto f = fail(x, attempt);
               if (!f) return f;
             }
             TaskOutput t;
             t.scalars["y"] = 3.0 * static_cast<double>(x) + 1;
             t.arrays["v"] = {static_cast<double>(x), 0.5};
             return t;
           }});
    return r;
  }
};

const char* kCalcStudy =
    "[study]\nname='retry'\nseed=1\n[[part]]\nname='p'\nkind='calc'\n[part.parameters]\nx={from=0,to=5}\n";

Result<TaskOutput> pass() { return TaskOutput{}; }

struct Outcome {
  std::string content;
  RunSummary summary;
  std::vector<Store::TaskInfo> tasks;
};

Outcome run(Calc& calc, const std::string& name, unsigned threads, RunOptions o = {}) {
  const TaskRegistry reg = calc.registry();
  auto s = parse_study(kCalcStudy, "retry.toml", false, reg);
  EXPECT_TRUE(s.ok());
  auto st = Store::open(tmp(name), *s);
  EXPECT_TRUE(st.ok());
  o.threads = threads;
  auto sum = run_threads(*s, **st, reg, o);
  EXPECT_TRUE(sum.ok()) << (sum.ok() ? "" : sum.error().message);
  return {*(*st)->content(), *sum, *(*st)->tasks()};
}

}  // namespace

TEST(StudyRetry, ATransientFailureIsRetriedAndGivesTheSameStore) {
  Calc clean;
  const Outcome ref = run(clean, "ref.sqlite", 1);
  EXPECT_EQ(ref.summary.retries, 0);
  // The first attempt at x = 2 fails as out of memory would (internal: may pass again).
  Calc flaky;
  flaky.fail = [](std::int64_t x, int attempt) -> Result<TaskOutput> {
    if (x == 2 && attempt == 1) return make_error("simulated out of memory", ErrorCode::Internal);
    return pass();
  };
  for (unsigned threads : {1u, 2u}) {
    flaky.calls.clear();
    const Outcome r = run(flaky, "flaky" + std::to_string(threads) + ".sqlite", threads);
    EXPECT_EQ(r.content, ref.content) << threads << " threads";
    EXPECT_EQ(r.summary.failed, 0);
    EXPECT_EQ(r.summary.ran, 6);
    EXPECT_EQ(r.summary.retries, 1);
    EXPECT_EQ(flaky.calls[2], 2);
    for (const auto& t : r.tasks) EXPECT_EQ(t.attempts, t.id == 2 ? 2 : 1) << "task " << t.id;
  }
}

TEST(StudyRetry, DeterministicFailuresAreRecordedAtOnce) {
  Calc bad;
  bad.fail = [](std::int64_t x, int) -> Result<TaskOutput> {
    if (x == 4) return make_error("parameter 'x': expected anything but 4");
    return pass();
  };
  const Outcome r = run(bad, "bad.sqlite", 2);
  EXPECT_EQ(r.summary.failed, 1);
  EXPECT_EQ(r.summary.retries, 0);
  EXPECT_EQ(bad.calls[4], 1);
  EXPECT_EQ(r.tasks[4].status, TaskStatus::Failed);
  EXPECT_EQ(r.tasks[4].error, "parameter 'x': expected anything but 4");
  EXPECT_EQ(r.tasks[4].attempts, 1);
}

TEST(StudyRetry, ExceptionsAreRetriedUpToThreeAttempts) {
  Calc broken;
  broken.fail = [](std::int64_t x, int) -> Result<TaskOutput> {
    if (x == 1) throw std::runtime_error("boom");
    return pass();
  };
  const Outcome r = run(broken, "broken.sqlite", 2);
  EXPECT_EQ(broken.calls[1], 3);
  EXPECT_EQ(r.summary.failed, 1);
  EXPECT_EQ(r.summary.retries, 2);
  EXPECT_EQ(r.tasks[1].status, TaskStatus::Failed);
  EXPECT_EQ(r.tasks[1].attempts, 3);
  EXPECT_EQ(r.tasks[1].error, "exception: boom (after 3 attempts)");
}

TEST(StudyRetry, FaultInjectionHookOfRunOptions) {
  Calc clean;
  const Outcome ref = run(clean, "hook-ref.sqlite", 1);
  Calc c;
  RunOptions o;
  o.fail_first_attempt = {0, 5};
  const Outcome r = run(c, "hook.sqlite", 2, o);
  EXPECT_EQ(r.content, ref.content);
  EXPECT_EQ(r.summary.retries, 2);
  EXPECT_EQ(c.calls[0], 2);  // the first attempt was computed, then reported failed
  EXPECT_EQ(r.tasks[0].attempts, 2);
  EXPECT_EQ(r.tasks[5].attempts, 2);
  EXPECT_EQ(r.tasks[3].attempts, 1);
  // Every attempt on site 0 failing: each task is tried kMaxAttempts = 3 times, then failed.
  Calc d;
  RunOptions all;
  all.inject_failure_rank = 0;
  const Outcome f = run(d, "hook-all.sqlite", 2, all);
  EXPECT_EQ(f.summary.failed, 6);
  for (const auto& t : f.tasks) EXPECT_EQ(t.attempts, 3);
}

TEST(ErrorCodes, DefaultsIoAndUnstable) {
  EXPECT_EQ(make_error("x").code, ErrorCode::InvalidInput);
  EXPECT_EQ(with_prefix("a: ", make_error("b", ErrorCode::Io)).code, ErrorCode::Io);
  EXPECT_EQ(with_prefix("a: ", make_error("b", ErrorCode::Io)).message, "a: b");
  auto missing = read_profile("/nonexistent/frictal/profile.csv");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().code, ErrorCode::Io);
  auto store = Store::open_existing(tmp("no-such-store.sqlite"));
  ASSERT_FALSE(store.ok());
  EXPECT_EQ(store.error().code, ErrorCode::Io);
  // The engine's stability guard: a normal dashpot of 2e5 1/s gives a bounce-mode limit of
  // 2 / (2 * 2e5) = 5e-6 s, below a fixed explicit step of 1e-5 s; the strict guard stops at once.
  // (The adaptive step with implicit dashpots, the tilt test's default, never meets the guard.)
  TiltConfig c = default_tilt_config();
  c.adaptive_time_step = false;
  c.implicit_damping = false;
  c.time_step = 1e-5;
  c.contact.normal_damping = 2e5;
  c.max_steps_beyond_limit = 0;
  c.predict = false;
  auto k0 = koch_curve(KochParams{0, 20 * std::numbers::pi / 180, 0.01, 0.02});
  ASSERT_TRUE(k0.ok());
  auto r = run_tilt(*k0, *k0, c);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::Unstable) << r.error().message;
}

TEST(StudyKindsUnit, EveryKindDeclaresWhatItReturnsAndItsViews) {
  const TaskRegistry reg = default_registry();
  // Cheap parameters per kind (K_n tiny, few rulers, short blocks).
  const std::map<std::string, Params> sample = {
      {"koch-signature", {{"iterations", std::int64_t{1}}, {"alpha", 10.0}, {"length", 0.01}}},
      {"wm-pair-statistics", {{"dimension", 1.5}, {"n_max", std::int64_t{2}}, {"pair", std::int64_t{0}}}},
      {"divider", {{"iterations", std::int64_t{1}}, {"alpha", 30.0}, {"rulers", std::int64_t{5}}}},
      {"tilt", {{"iterations", std::int64_t{0}}, {"alpha", 20.0}, {"length", 0.02}, {"record_series", true}}},
      {"wm-tilt",
       {{"dimension", 1.5},
        {"n_max", std::int64_t{2}},
        {"longest_wavelength", 0.01},
        {"length", 0.02},
        {"rms_height", 1e-5},
        {"spheroradius", 2e-5},
        {"pair", std::int64_t{0}}}},
      {"areal-tilt",
       {{"pair", std::string("grooves")},
        {"nodes", std::int64_t{16}},
        {"upper_nodes", std::int64_t{4}},
        {"groove_period", std::int64_t{6}}}},
  };
  // areal-tilt is available only in a build with MuJoCo.
  ASSERT_EQ(reg.names().size(), sample.size() - (frictal::mujoco_available() ? 0 : 1));
  const auto kinds = nlohmann::json::parse(kinds_json(reg))["kinds"];
  for (const auto& name : reg.names()) {
    const TaskKind& k = *reg.find(name);
    ASSERT_TRUE(sample.count(name)) << name;
    auto out = k.run(sample.at(name), 7);
    ASSERT_TRUE(out.ok()) << name << ": " << out.error().message;
    std::set<std::string> scalars, arrays;
    for (const auto& c : k.outputs) (c.array ? arrays : scalars).insert(c.name);
    for (const auto& [s, v] : out->scalars) EXPECT_TRUE(scalars.count(s)) << name << " returns undeclared scalar " << s;
    for (const auto& [a, v] : out->arrays) EXPECT_TRUE(arrays.count(a)) << name << " returns undeclared array " << a;
    for (const auto& s : scalars)
      EXPECT_TRUE(out->scalars.count(s)) << name << " declares scalar " << s << " it never returns";
    for (const auto& a : arrays)
      EXPECT_TRUE(out->arrays.count(a)) << name << " declares array " << a << " it never returns";
    EXPECT_TRUE(bool(k.report)) << name;
    // Every plot view's y column is a declared output; x is an output or a parameter.
    for (const auto& v : k.plots) {
      EXPECT_TRUE(scalars.count(v.y.column) || arrays.count(v.y.column)) << name << " view " << v.id;
      EXPECT_TRUE(scalars.count(v.x.column) || arrays.count(v.x.column) || sample.at(name).count(v.x.column) ||
                  v.x.column == "alpha" || v.x.column == "n_max" || v.x.column == "dimension" || !v.match.empty())
          << name << " view " << v.id << " x " << v.x.column;
    }
    // kinds_json carries the same.
    bool found = false;
    for (const auto& j : kinds)
      if (j["name"] == name) {
        found = true;
        EXPECT_EQ(j["outputs"].size(), k.outputs.size());
        EXPECT_EQ(j["plots"].size(), k.plots.size());
        EXPECT_EQ(j["version"], k.version);
      }
    EXPECT_TRUE(found) << name;
  }
}

TEST(StudyArealTilt, TakesTheModelSettingsAndRefusesThoseItSets) {
  // The areal-tilt kind takes every setting of areal_tilt_settings() (docs/settings.md) beside its
  // own pair parameters; `lateral` and `angle` it sets itself. Refused before any simulation, so
  // this runs in a build without MuJoCo too.
  const frictal::study::TaskRegistry reg = frictal::study::default_registry();
  const frictal::study::TaskKind* k = reg.find("areal-tilt");
  if (!k) GTEST_SKIP() << "built without MuJoCo";
  frictal::study::Params p = {{"pair", std::string("grooves")}, {"lateral", std::string("locked")}};
  auto r = k->run(p, 1);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("'lateral'"), std::string::npos) << r.error().message;
  p = {{"pair", std::string("grooves")}, {"local_damping", 1.5}};
  r = k->run(p, 1);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("local_damping"), std::string::npos) << r.error().message;
  p = {{"pair", std::string("grooves")}, {"local_dampng", 0.5}};
  r = k->run(p, 1);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("local_dampng"), std::string::npos) << r.error().message;
}
