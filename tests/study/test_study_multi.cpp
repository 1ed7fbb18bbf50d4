// The result cache read per task (a result added after a run started is reused) and several
// studies in one run on one pool of threads (run_threads over StudyRun): one queue costliest
// first across studies, tasks with one content address computed once, stores identical to
// separate runs.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "frictal/study.hpp"
#include "study/cache.hpp"
#include "study_helpers.hpp"

using namespace frictal::study;
using study_test::dump;
using study_test::fresh;

namespace {

std::mutex g_mu;
std::vector<std::int64_t> g_ran;         // order of the computations: w + tag
std::map<std::int64_t, int> g_computed;  // how often each w + tag was computed
std::atomic<bool>* g_stop = nullptr;     // set when w + tag == g_stop_at is computed
std::int64_t g_stop_at = -1;
std::atomic<int> g_delay_ms{0};  // how long each computation takes (unit: ms)

/// A deterministic kind (seed ignored: shared by every study with the same w) that records its
/// computations; its cost model is w (unit: s); its output is w squared, an independent value.
TaskKind counting_kind(const std::string& name, std::int64_t tag) {
  TaskKind k{name, "counts its computations", 1, [tag](const Params& p, std::uint64_t) -> frictal::Result<TaskOutput> {
               const std::int64_t w = std::get<std::int64_t>(p.at("w"));
               {
                 std::lock_guard lk(g_mu);
                 g_ran.push_back(w + tag);
                 ++g_computed[w + tag];
                 if (g_stop && w + tag == g_stop_at) *g_stop = true;  // as if Ctrl-C came now
               }
               if (g_delay_ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(g_delay_ms.load()));
               TaskOutput t;
               t.scalars["w_squared"] = static_cast<double>(w * w);
               t.arrays["w_and_tag"] = {static_cast<double>(w), static_cast<double>(tag)};
               // Some kilobytes per task, so that a store capped at its size cannot take one more.
               t.arrays["payload"].assign(static_cast<std::size_t>(200 * w), static_cast<double>(w) / 3.0);
               return t;
             }};
  k.cost = [](const Params& p) { return static_cast<double>(std::get<std::int64_t>(p.at("w"))); };
  k.uses_seed = false;
  return k;
}

TaskRegistry counting_registry() {
  TaskRegistry reg;
  reg.add(counting_kind("count-a", 0));
  reg.add(counting_kind("count-b", 100));
  return reg;
}

void reset() {
  std::lock_guard lk(g_mu);
  g_ran.clear();
  g_computed.clear();
}

Study parse(const std::string& text, const TaskRegistry& reg) {
  auto s = parse_study(text, "test.toml", false, reg);
  EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().message);
  return *s;
}

// Two studies (other names, seeds, part names) sharing the count-a tasks w = 4, 5, 6.
const char* kA = R"(
[study]
name = "multi-a"
seed = 1
[[part]]
name = "x"
kind = "count-a"
[part.parameters]
w = [1, 2, 3, 4, 5, 6]
)";
const char* kB = R"(
[study]
name = "multi-b"
seed = 2
[[part]]
name = "y"
kind = "count-a"
[part.parameters]
w = [4, 5, 6, 7, 8, 9]
[[part]]
name = "z"
kind = "count-b"
[part.parameters]
w = [10, 2]
)";

RunSummary run_one(const Study& s, const std::string& store, const TaskRegistry& reg, const std::string& cache,
                   unsigned threads, std::function<void()> started = {}) {
  auto st = Store::open(store, s);
  EXPECT_TRUE(st.ok()) << (st.ok() ? "" : st.error().message);
  if (!st.ok()) return {};
  RunOptions o;
  o.threads = threads;
  o.cache = cache;
  o.started = std::move(started);
  auto sum = run_threads(s, **st, reg, o);
  EXPECT_TRUE(sum.ok()) << (sum.ok() ? "" : sum.error().message);
  return sum.ok() ? *sum : RunSummary{};
}

struct Multi {
  std::vector<std::unique_ptr<Store>> stores;
  std::vector<StudyRun> runs;
};
Multi open_multi(const std::vector<const Study*>& studies, const std::vector<std::string>& paths,
                 const std::string& cache) {
  Multi m;
  for (std::size_t i = 0; i < studies.size(); ++i) {
    auto st = Store::open(paths[i], *studies[i]);
    EXPECT_TRUE(st.ok()) << (st.ok() ? "" : st.error().message);
    m.stores.push_back(std::move(*st));
    StudyRun r;
    r.study = studies[i];
    r.store = m.stores.back().get();
    r.cache = cache;
    m.runs.push_back(std::move(r));
  }
  return m;
}

}  // namespace

TEST(StudyCachePerTask, AResultAddedAfterTheRunStartedIsReusedByteIdentically) {
  // Study B starts with an empty cache (nothing to take at start); then, before B claims its
  // first task, a run of study A (another store, the same cache) computes the shared tasks.
  // B must take those three from the cache when it claims them, not compute them again.
  const TaskRegistry reg = counting_registry();
  const Study a = parse(kA, reg), b = parse(kB, reg);
  const std::string cache = fresh("multi-percache.sqlite");
  const std::string bstore = fresh("multi-percache-b.sqlite");
  reset();
  RunSummary ra;
  const RunSummary rb =
      run_one(b, bstore, reg, cache, 2, [&] { ra = run_one(a, fresh("multi-percache-a.sqlite"), reg, cache, 1); });
  EXPECT_EQ(ra.ran, 6);
  EXPECT_EQ(rb.reused, 3);  // w = 4, 5, 6 of part y
  EXPECT_EQ(rb.ran, 5);     // w = 7, 8, 9 and part z
  EXPECT_FALSE(rb.interrupted);
  EXPECT_TRUE(rb.cache_note.empty()) << rb.cache_note;
  for (const std::int64_t w : {4, 5, 6}) EXPECT_EQ(g_computed[w], 1) << "w = " << w;
  // The same store as B computed alone, without a cache.
  const std::string ref = fresh("multi-percache-bref.sqlite");
  EXPECT_EQ(run_one(b, ref, reg, "", 1).ran, 8);
  EXPECT_EQ(dump(bstore), dump(ref));
  EXPECT_NE(dump(bstore).find("w_and_tag"), std::string::npos);  // arrays compared too
}

// Claims on content addresses in the result cache, as two runs (two objects: two owners) and a
// run that died see them.
TEST(StudyCacheClaims, AnAddressIsComputedByOneRunAtATime) {
  const std::string path = fresh("cache-claims.sqlite");
  auto a = ResultCache::open(path), b = ResultCache::open(path);
  ASSERT_TRUE(a.ok() && b.ok());
  using C = ResultCache::Claim;
  EXPECT_EQ(*(*a)->claim("x", 60), C::Claimed);
  EXPECT_EQ(*(*a)->claim("x", 60), C::Claimed);  // its own claim
  EXPECT_EQ(*(*b)->claim("x", 60), C::Busy);     // held by a live run
  EXPECT_EQ(*(*b)->claim("x", -1), C::Claimed);  // unless its heartbeat is older than the lease
  EXPECT_EQ(*(*a)->claim("x", 60), C::Busy);
  // A stored result ends the claim; a released claim is free.
  const TaskRegistry reg = counting_registry();
  const Study st = parse(kA, reg);
  const Task& t = st.tasks[0];
  TaskRecord r = execute(t, reg, "test");
  ASSERT_EQ(r.status, TaskStatus::Done);
  ASSERT_TRUE((*b)->put("x", t, false, r, "multi-a").ok());
  EXPECT_EQ(*(*a)->claim("x", 60), C::Stored);
  EXPECT_EQ(*(*a)->claim("y", 60), C::Claimed);
  ASSERT_TRUE((*a)->release("y").ok());
  EXPECT_EQ(*(*b)->claim("y", 60), C::Claimed);
  ASSERT_TRUE((*b)->release_claims().ok());
  // A run killed while it holds a claim: taken over at once (same host, its process is gone).
  const pid_t child = ::fork();
  if (child == 0) {
    auto c = ResultCache::open(path);
    if (!c.ok() || !(*c)->claim("z", 3600).ok()) std::_Exit(1);
    ::kill(::getpid(), SIGKILL);
    std::_Exit(2);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "child exit " << WEXITSTATUS(status);
  EXPECT_EQ(*(*a)->claim("z", 3600), C::Claimed);
}

TEST(StudyCacheClaims, TwoRunsOfStudiesThatShareTasksComputeEachOnceWhenStartedTogether) {
  // Two studies (two stores, one cache) whose costliest tasks are the same three addresses, run
  // at the same moment by two runs (each with its own cache connection, as two processes): each
  // shared task is computed by one of them and taken from the cache by the other.
  const TaskRegistry reg = counting_registry();
  const char* kC = R"(
[study]
name = "claims-c"
seed = 3
[[part]]
name = "p"
kind = "count-a"
[part.parameters]
w = [4, 5, 6]
)";
  const char* kD = R"(
[study]
name = "claims-d"
seed = 4
[[part]]
name = "q"
kind = "count-a"
[part.parameters]
w = [1, 4, 5, 6]
)";
  const Study c = parse(kC, reg), d = parse(kD, reg);
  const std::string cache = fresh("claims-cache.sqlite");
  const std::string cs = fresh("claims-c.sqlite"), ds = fresh("claims-d.sqlite");
  reset();
  g_delay_ms = 60;
  RunSummary rc, rd;
  std::thread tc([&] { rc = run_one(c, cs, reg, cache, 1); });
  std::thread td([&] { rd = run_one(d, ds, reg, cache, 1); });
  tc.join();
  td.join();
  g_delay_ms = 0;
  for (const std::int64_t w : {1, 4, 5, 6}) EXPECT_EQ(g_computed[w], 1) << "w = " << w;
  EXPECT_EQ(rc.ran + rd.ran, 4);
  EXPECT_EQ(rc.reused + rd.reused, 3);
  EXPECT_FALSE(rc.interrupted || rd.interrupted);
  EXPECT_TRUE(rc.cache_note.empty() && rd.cache_note.empty()) << rc.cache_note << rd.cache_note;
  // Each store as its study run alone, without a cache.
  const std::string cref = fresh("claims-cref.sqlite"), dref = fresh("claims-dref.sqlite");
  run_one(c, cref, reg, "", 1);
  run_one(d, dref, reg, "", 1);
  EXPECT_EQ(dump(cs), dump(cref));
  EXPECT_EQ(dump(ds), dump(dref));
  // Every address is stored, none is left claimed.
  auto again = ResultCache::open(cache);
  ASSERT_TRUE(again.ok());
  for (const Task& t : d.tasks) EXPECT_EQ(*(*again)->claim(content_address(t, reg), 3600), ResultCache::Claim::Stored);
}

TEST(StudyMulti, OnePoolComputesEverySharedTaskOnceAndGivesTheStoresOfSeparateRuns) {
  const TaskRegistry reg = counting_registry();
  const Study a = parse(kA, reg), b = parse(kB, reg);
  // Separate runs without a cache: the reference stores.
  const std::string aref = fresh("multi-aref.sqlite"), bref = fresh("multi-bref.sqlite");
  EXPECT_EQ(run_one(a, aref, reg, "", 1).ran, 6);
  EXPECT_EQ(run_one(b, bref, reg, "", 1).ran, 8);
  for (const unsigned threads : {1u, 2u, 4u}) {
    for (const bool with_cache : {false, true}) {
      SCOPED_TRACE(testing::Message() << threads << " threads, cache " << with_cache);
      reset();
      const std::string tag = std::to_string(threads) + (with_cache ? "c" : "");
      const std::vector<std::string> paths = {fresh("multi-a" + tag + ".sqlite"), fresh("multi-b" + tag + ".sqlite")};
      Multi m = open_multi({&a, &b}, paths, with_cache ? fresh("multi-cache" + tag + ".sqlite") : "");
      RunOptions o;
      o.threads = threads;
      auto sums = run_threads(m.runs, reg, o);
      ASSERT_TRUE(sums.ok()) << sums.error().message;
      ASSERT_EQ(sums->size(), 2u);
      const RunSummary &sa = (*sums)[0], &sb = (*sums)[1];
      // 11 distinct tasks: 6 of A, w = 7..9 and 2 of z in B; the 3 shared ones once.
      EXPECT_EQ(sa.ran + sb.ran, 11);
      EXPECT_EQ(sa.reused + sb.reused, 3);
      EXPECT_EQ(sa.ran + sa.reused, 6);
      EXPECT_EQ(sb.ran + sb.reused, 8);
      EXPECT_FALSE(sa.interrupted || sb.interrupted);
      EXPECT_EQ(g_ran.size(), 11u);
      for (const auto& [w, n] : g_computed) EXPECT_EQ(n, 1) << "w + tag = " << w;
      EXPECT_EQ(dump(paths[0]), dump(aref));
      EXPECT_EQ(dump(paths[1]), dump(bref));
    }
  }
}

TEST(StudyMulti, OneThreadTakesTheCostliestTaskOfAllStudiesFirst) {
  const TaskRegistry reg = counting_registry();
  const Study a = parse(kA, reg), b = parse(kB, reg);
  reset();
  Multi m = open_multi({&a, &b}, {fresh("multi-order-a.sqlite"), fresh("multi-order-b.sqlite")}, "");
  RunOptions o;
  o.threads = 1;
  auto sums = run_threads(m.runs, reg, o);
  ASSERT_TRUE(sums.ok()) << sums.error().message;
  // Costs are w: B's z w = 10 (110), B's 9, 8, 7, then the shared 6, 5, 4 (A first: the earlier
  // study wins ties; B's copies are reused), A's 3, B's z w = 2 (102) before A's 2 (a tie: but B's
  // z task is tagged 100; the tie goes to the earlier study, A), then 1.
  EXPECT_EQ(g_ran, (std::vector<std::int64_t>{110, 9, 8, 7, 6, 5, 4, 3, 2, 102, 1}));
  // Grid order: study by study, in id order.
  reset();
  Multi g = open_multi({&a, &b}, {fresh("multi-grid-a.sqlite"), fresh("multi-grid-b.sqlite")}, "");
  o.longest_first = false;
  ASSERT_TRUE(run_threads(g.runs, reg, o).ok());
  EXPECT_EQ(g_ran, (std::vector<std::int64_t>{1, 2, 3, 4, 5, 6, 7, 8, 9, 110, 102}));
}

TEST(StudyMulti, InterruptedRunResumesPerStore) {
  const TaskRegistry reg = counting_registry();
  const Study a = parse(kA, reg), b = parse(kB, reg);
  const std::string aref = fresh("multi-int-aref.sqlite"), bref = fresh("multi-int-bref.sqlite");
  run_one(a, aref, reg, "", 1);
  run_one(b, bref, reg, "", 1);
  const std::vector<std::string> paths = {fresh("multi-int-a.sqlite"), fresh("multi-int-b.sqlite")};
  std::atomic<bool> stop{false};
  {
    Multi m = open_multi({&a, &b}, paths, "");
    RunOptions o;
    o.threads = 1;
    o.stop = &stop;
    reset();
    g_stop = &stop;
    g_stop_at = 7;  // the 4th task of the costliest-first order (B's 10, 9, 8, 7)
    auto sums = run_threads(m.runs, reg, o);
    g_stop = nullptr;
    ASSERT_TRUE(sums.ok()) << sums.error().message;
    EXPECT_TRUE((*sums)[0].interrupted);
    EXPECT_TRUE((*sums)[1].interrupted);
    EXPECT_EQ((*sums)[0].ran, 0);
    EXPECT_EQ((*sums)[1].ran, 4);  // the task running when the stop came is recorded
  }
  // Resume: every store completes and equals its separate run.
  Multi m = open_multi({&a, &b}, paths, "");
  RunOptions o;
  o.threads = 2;
  auto sums = run_threads(m.runs, reg, o);
  ASSERT_TRUE(sums.ok()) << sums.error().message;
  EXPECT_FALSE((*sums)[0].interrupted || (*sums)[1].interrupted);
  EXPECT_EQ(dump(paths[0]), dump(aref));
  EXPECT_EQ(dump(paths[1]), dump(bref));
}

TEST(StudyMulti, PartsCannotBeChosenForSeveralStudies) {
  const TaskRegistry reg = counting_registry();
  const Study a = parse(kA, reg), b = parse(kB, reg);
  Multi m = open_multi({&a, &b}, {fresh("multi-parts-a.sqlite"), fresh("multi-parts-b.sqlite")}, "");
  RunOptions o;
  o.parts = {"x"};
  auto sums = run_threads(m.runs, reg, o);
  ASSERT_FALSE(sums.ok());
  EXPECT_NE(sums.error().message.find("part 'x'"), std::string::npos) << sums.error().message;
}

namespace {
std::string shipped(const std::string& name) {
  return (std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() / "studies" / (name + ".toml"))
      .string();
}
/// Runs each shipped study `names` alone at quick scale into sep/<name>.sqlite (no cache): the
/// reference stores; `files` gets their study files, space-separated.
void run_separately(const std::vector<std::string>& names, const std::string& sep, std::string& files) {
  std::filesystem::remove_all(sep);
  std::filesystem::create_directories(sep);
  for (const auto& n : names) {
    auto r = run_cli("study run " + shipped(n) + " --store " + sep + "/" + n +
                     ".sqlite --quick --threads 2 --cache none --progress none");
    ASSERT_EQ(r.code, 0) << r.err;
    files += " " + shipped(n);
  }
}
}  // namespace

TEST(StudyMultiCli, ShippedDemStudiesInOneRunGiveTheStoresOfSeparateRuns) {
  // The quick scale of Figs. 6, 8 and 10 (they share tilt and theory tasks) in one run with
  // --store-dir, against one run per study with --store and no cache: every store holds the same
  // run-independent content, and the shared tasks are computed once (reused in the later study).
  const std::vector<std::string> names = {"fig06-koch-friction", "fig08-atomic-friction", "fig10-mu-vs-dimension"};
  const std::string sep = temp_path("multi-cli-separate"), one = temp_path("multi-cli-one");
  std::filesystem::remove_all(one);
  std::string files;
  ASSERT_NO_FATAL_FAILURE(run_separately(names, sep, files));
  auto r = run_cli("study run" + files + " --store-dir " + one + " --quick --threads 2 --progress lines");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("tasks reused"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("study fig10-mu-vs-dimension: "), std::string::npos) << r.err;  // progress names the study
  std::int64_t reused = 0;
  for (const auto& n : names) {
    SCOPED_TRACE(n);
    EXPECT_EQ(dump(one + "/" + n + ".sqlite"), dump(sep + "/" + n + ".sqlite"));
    auto st = Store::open_existing(one + "/" + n + ".sqlite");
    ASSERT_TRUE(st.ok());
    auto tasks = (*st)->tasks();
    ASSERT_TRUE(tasks.ok());
    for (const auto& t : *tasks) reused += t.worker == "cache";
  }
  EXPECT_GT(reused, 0);
  EXPECT_TRUE(std::filesystem::exists(one + "/results-cache.sqlite"));
  // Resume: nothing left to do, nothing changes.
  r = run_cli("study run" + files + " --store-dir " + one + " --quick --threads 2 --progress none");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(dump(one + "/" + names[0] + ".sqlite"), dump(sep + "/" + names[0] + ".sqlite"));
}

TEST(StudyMultiCli, UnderMpiEveryStudyRunsOverTheRanksAndGivesTheStoresOfSeparateRuns) {
  if (!mpi_available()) GTEST_SKIP() << "built without FRICTAL_MPI";
  if (std::system("command -v mpirun >/dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun not found";
  // Under mpirun, --store-dir runs the studies one after another, each over both ranks; the
  // later ones reuse the shared tilt and theory tasks through the result cache in the folder.
  const std::vector<std::string> names = {"fig06-koch-friction", "fig10-mu-vs-dimension"};
  const std::string sep = temp_path("multi-mpi-separate"), one = temp_path("multi-mpi-one");
  std::filesystem::remove_all(one);
  std::string files;
  ASSERT_NO_FATAL_FAILURE(run_separately(names, sep, files));
  const std::string mpirun = study_test::mpirun_prefix(2);
  const std::string log = temp_path("multi-mpi.log");
  const std::string cmd = mpirun + FRICTAL_CLI_PATH + std::string(" study run") + files + " --store-dir " + one +
                          " --quick --progress none >" + log + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd << "\n" << read_file(log);
  const std::string out = read_file(log);
  EXPECT_NE(out.find("on 2 ranks"), std::string::npos) << out;
  EXPECT_NE(out.find("tasks reused: taken from the result cache"), std::string::npos) << out;
  std::string workers;
  for (const auto& n : names) {
    SCOPED_TRACE(n);
    EXPECT_EQ(dump(one + "/" + n + ".sqlite"), dump(sep + "/" + n + ".sqlite"));
    auto st = Store::open_existing(one + "/" + n + ".sqlite");
    ASSERT_TRUE(st.ok());
    auto tasks = (*st)->tasks();
    ASSERT_TRUE(tasks.ok());
    for (const auto& t : *tasks) workers += t.worker.substr(0, 6) + "\n";
  }
  EXPECT_NE(workers.find("rank 1"), std::string::npos) << workers;  // the second rank took tasks
  EXPECT_NE(workers.find("cache"), std::string::npos) << workers;   // fig10 reused fig06's tilts

  // A folder that cannot be made: one message, exit 2, no rank left waiting.
  const std::string bad = mpirun + FRICTAL_CLI_PATH + std::string(" study run") + files +
                          " --store-dir /proc/frictal-no/dir --quick --progress none >" + log + " 2>&1";
  const int rc = std::system(bad.c_str());
  EXPECT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) != 0) << read_file(log);
  EXPECT_NE(read_file(log).find("--store-dir /proc/frictal-no/dir: cannot create the folder"), std::string::npos)
      << read_file(log);
}

TEST(StudyMultiCli, AmbiguousStoreOptionsAreRefused) {
  const std::string a = shipped("fig06-koch-friction"), b = shipped("fig10-mu-vs-dimension");
  const std::string dir = temp_path("multi-cli-refused");
  struct Case {
    std::string args, says;
  };
  for (const Case& c : std::vector<Case>{
           {a + " " + b + " --store " + fresh("multi-x.sqlite"), "give --store-dir DIR for several studies"},
           {a + " --store " + fresh("multi-y.sqlite") + " --store-dir " + dir, "give one"},
           {a + " " + b, "give --store FILE (one study) or --store-dir DIR"},
           {a + " " + b + " --store-dir " + dir + " --part theory", "--part: not with several studies"},
           {a + " " + b + " --store-dir " + dir + " --dry-run", "--dry-run: give one study"},
           {a + " " + a + " --store-dir " + dir, "two studies have the file name 'fig06-koch-friction'"},
       }) {
    auto r = run_cli("study run " + c.args + " --quick --progress none");
    EXPECT_EQ(r.code, 2) << c.args;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << ": " << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir));  // refused before anything was written
}

TEST(StudyMultiCli, CtrlCStopsEveryStudyAndTheSameCommandResumesEach) {
  // Two studies of about 30 WM tasks each (tens of ms each): interrupted early, resumed.
  const char* kWm = R"(
[study]
name = "NAME"
seed = 99
[[part]]
name = "wm"
kind = "wm-pair-statistics"
seed_from = ["pair"]
[part.parameters]
dimension = [1.3, 1.7]
n_max = [6, 8, 9]
pair = { count = 5 }
)";
  std::vector<std::string> files;
  for (const std::string n : {"sigint-a", "sigint-b"}) {
    std::string text = kWm;
    text.replace(text.find("NAME"), 4, "multi-" + n);
    files.push_back(temp_path("multi-" + n + ".toml"));
    write_file(files.back(), text);
  }
  const std::string dir = temp_path("multi-sigint");
  std::filesystem::remove_all(dir);
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
    ::execl(FRICTAL_CLI_PATH, FRICTAL_CLI_PATH, "study", "run", files[0].c_str(), files[1].c_str(), "--store-dir",
            dir.c_str(), "--threads", "1", "--cache", "none", "--progress", "none", static_cast<char*>(nullptr));
    std::_Exit(127);
  }
  EXPECT_TRUE(study_test::wait_for_file(dir + "/" + std::filesystem::path(files[0]).stem().string() + ".sqlite"))
      << "the run never created its stores";
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_TRUE(WEXITSTATUS(status) == 130 || WEXITSTATUS(status) == 0) << WEXITSTATUS(status);
  auto r = run_cli("study run " + files[0] + " " + files[1] + " --store-dir " + dir +
                   " --threads 2 --cache none --progress lines");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("study multi-sigint-b: 30/30 done"), std::string::npos) << r.err;
  // Each store equals its study run alone.
  for (std::size_t i = 0; i < 2; ++i) {
    const std::string ref = fresh("multi-sigint-ref" + std::to_string(i) + ".sqlite");
    r = run_cli("study run " + files[i] + " --store " + ref + " --threads 2 --cache none --progress none");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(dump(dir + "/" + std::filesystem::path(files[i]).stem().string() + ".sqlite"), dump(ref));
  }
}

TEST(StudyMulti, AStoreThatCannotBeWrittenStopsTheRunAndResumeCompletesEveryStore) {
  const TaskRegistry reg = counting_registry();
  const Study a = parse(kA, reg), b = parse(kB, reg);
  const std::string aref = fresh("multi-full-aref.sqlite"), bref = fresh("multi-full-bref.sqlite");
  run_one(a, aref, reg, "", 1);
  run_one(b, bref, reg, "", 1);
  const std::vector<std::string> paths = {fresh("multi-full-a.sqlite"), fresh("multi-full-b.sqlite")};
  {
    Multi m = open_multi({&a, &b}, paths, "");
    RunOptions o;
    o.threads = 2;
    o.max_page_count = 1;  // every store capped at its current size: the first result fills it
    auto sums = run_threads(m.runs, reg, o);
    ASSERT_FALSE(sums.ok());
    EXPECT_EQ(sums.error().code, frictal::ErrorCode::Io);
    EXPECT_NE(sums.error().message.find("study 'multi-"), std::string::npos) << sums.error().message;
    EXPECT_NE(sums.error().message.find("disk is full"), std::string::npos) << sums.error().message;
  }
  Multi m = open_multi({&a, &b}, paths, "");
  RunOptions o;
  o.threads = 2;
  auto sums = run_threads(m.runs, reg, o);
  ASSERT_TRUE(sums.ok()) << sums.error().message;
  EXPECT_EQ(dump(paths[0]), dump(aref));
  EXPECT_EQ(dump(paths[1]), dump(bref));
}
