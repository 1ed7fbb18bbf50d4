// frictal study run/status/export/report through the CLI: SIGKILL at random points and resume,
// MPI ranks against threads, user errors.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <thread>

#include "cli/cli_runner.hpp"
#include "frictal/study.hpp"
#include "study/study_helpers.hpp"

using namespace frictal::study;

namespace {

using study_test::dump;
using study_test::fresh;

// About 30 tasks of a few to some tens of milliseconds: long enough to be killed mid-run.
const char* kStudy = R"(
[study]
name = "kill-test"
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

// One file per test: ctest runs tests in parallel processes that share the temp directory.
std::string study_file(const std::string& tag) {
  const std::string p = temp_path("kill-test-" + tag + ".toml");
  write_file(p, kStudy);
  return p;
}

/// Starts `frictal study run` as a child (stdout/stderr to /dev/null) and returns its pid.
pid_t spawn_run(const std::string& study, const std::string& store, const std::string& threads) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
    ::execl(FRICTAL_CLI_PATH, FRICTAL_CLI_PATH, "study", "run", study.c_str(), "--store", store.c_str(), "--threads",
            threads.c_str(), "--cache", "none", "--progress", "none", static_cast<char*>(nullptr));
    std::_Exit(127);
  }
  return pid;
}

}  // namespace

TEST(StudyCli, KilledWithSigkillAtRandomPointsAndResumedGivesTheUninterruptedRows) {
  const std::string study = study_file("kill");
  const std::string ref = fresh("kill-ref.sqlite");
  const auto t0 = std::chrono::steady_clock::now();
  auto r = run_cli("study run " + study + " --store " + ref + " --threads 1 --cache none --progress none");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string expected = dump(ref);
  // Kill points within the first 60 % of an uninterrupted run's time on this machine now: a fixed
  // 0..250 ms let a fast machine finish the first run before its kill, and every later run then
  // found nothing to do (no kill at all).
  const auto ref_ms =
      std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - t0).count();

  std::mt19937 rng(std::random_device{}());
  std::uniform_int_distribution<int> delay_ms(0, std::max(1, static_cast<int>(0.6 * static_cast<double>(ref_ms))));
  for (int trial = 0; trial < 2; ++trial) {
    const std::string store = fresh("kill-" + std::to_string(trial) + ".sqlite");
    int kills = 0;
    std::string delays;
    for (int attempt = 0; attempt < 6; ++attempt) {
      const int d = delay_ms(rng);
      delays += std::to_string(d) + " ";
      const pid_t pid = spawn_run(study, store, attempt % 2 ? "2" : "1");
      ASSERT_GT(pid, 0);
      std::this_thread::sleep_for(std::chrono::milliseconds(d));
      int status = 0;
      if (::waitpid(pid, &status, WNOHANG) == 0) {
        ::kill(pid, SIGKILL);
        ::waitpid(pid, &status, 0);
        if (WIFSIGNALED(status)) ++kills;
      }
    }
    // Resume to completion and compare every row with the uninterrupted run.
    r = run_cli("study run " + study + " --store " + store + " --threads 2 --cache none --progress none");
    ASSERT_EQ(r.code, 0) << r.err << " (kill delays ms: " << delays << ")";
    EXPECT_EQ(dump(store), expected) << "kill delays ms: " << delays;
    EXPECT_GT(kills, 0) << "no run was killed (delays ms: " << delays << ")";
    r = run_cli("study status " + store + " --json");
    EXPECT_NE(r.out.find("\"done\": 30"), std::string::npos) << r.out;
  }
}

TEST(StudyCli, CtrlCStopsCleanlyAndResumes) {
  const std::string study = study_file("sigint");
  const std::string store = fresh("sigint.sqlite");
  const pid_t pid = spawn_run(study, store, "1");
  EXPECT_TRUE(study_test::wait_for_file(store)) << "the run never created its store";
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  ::kill(pid, SIGINT);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_TRUE(WEXITSTATUS(status) == 130 || WEXITSTATUS(status) == 0) << WEXITSTATUS(status);
  auto r = run_cli("study run " + study + " --store " + store + " --threads 2 --cache none --progress lines");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("30/30 done"), std::string::npos) << r.err;  // plain progress lines off a terminal
}

TEST(StudyCli, MpiRanksGiveTheSameRowsAsThreads) {
  if (!mpi_available()) GTEST_SKIP() << "built without FRICTAL_MPI";
  if (std::system("command -v mpirun >/dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun not found";
  const std::string study = study_file("mpi");
  const std::string a = fresh("mpi-threads.sqlite"), b = fresh("mpi-ranks.sqlite");
  auto r = run_cli("study run " + study + " --store " + a + " --threads 2 --cache none --progress none");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string mpirun = study_test::mpirun_prefix(2);
  const std::string cmd = mpirun + FRICTAL_CLI_PATH + " study run " + study + " --store " + b +
                          " --cache none --progress none >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  EXPECT_EQ(dump(a), dump(b));
  // Both ranks computed (rank 1 took at least one task from rank 0's queue).
  auto st = Store::open_existing(b);
  std::string workers;
  const auto tasks = (*st)->tasks();
  ASSERT_TRUE(tasks.ok());
  for (const auto& t : *tasks) workers += t.worker.substr(0, 6) + "\n";
  EXPECT_NE(workers.find("rank 1"), std::string::npos) << workers;

  // Fault injection: rank 0's compute thread fails every task it takes (it surely takes the
  // first one); each is reassigned to rank 1 and the
  // store is still exactly the threads run, with the extra attempts recorded.
  const std::string c = fresh("mpi-fault.sqlite");
  const std::string cmd2 = mpirun + FRICTAL_CLI_PATH + " study run " + study + " --store " + c +
                           " --cache none --progress none --inject-failure-rank 0 >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd2.c_str()), 0) << cmd2;
  EXPECT_EQ(dump(a), dump(c));
  auto sc = Store::open_existing(c);
  int on_rank0 = 0, max_attempts = 0;
  const auto fault_tasks = (*sc)->tasks();
  ASSERT_TRUE(fault_tasks.ok());
  for (const auto& t : *fault_tasks) {
    on_rank0 += t.worker.rfind("rank 0", 0) == 0;
    max_attempts = std::max(max_attempts, t.attempts);
  }
  EXPECT_EQ(on_rank0, 0);
  EXPECT_NE(max_attempts, 1);
}

TEST(StudyCli, UserErrorsAndExport) {
  const std::string study = study_file("cli");
  const std::string store = fresh("cli.sqlite");
  auto r = run_cli("study run " + study + " --store " + store + " --threads 2 --cache none --progress none");
  ASSERT_EQ(r.code, 0) << r.err;
  // Same store, other definition (quick scale has other tasks here? no quick table: same grid,
  // but the scale is part of the definition).
  r = run_cli("study run " + study + " --store " + store + " --quick --cache none --progress none");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("another study definition"), std::string::npos) << r.err;
  r = run_cli("study run /nonexistent.toml --store " + fresh("x.sqlite"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("/nonexistent.toml"), std::string::npos);
  r = run_cli("study status " + fresh("none.sqlite"));
  EXPECT_EQ(r.code, 2);
  const std::string bogus = temp_path("bogus.toml");
  write_file(
      bogus,
      "[study]\nname='t'\nseed=1\n[[part]]\nname='sim'\nkind='no-such-kind'\n[part.parameters]\nalpha_deg=[5.0]\n");
  r = run_cli("study run " + bogus + " --store " + fresh("bogus.sqlite"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("unknown task kind 'no-such-kind'"), std::string::npos) << r.err;

  const std::string dir = temp_path("export");
  r = run_cli("study export " + store + " --csv " + dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string wide = read_file(dir + "/wm.csv");
  EXPECT_EQ(wide.rfind("task_id,dimension,n_max,pair,", 0), 0u) << wide.substr(0, 200);
  EXPECT_NE(wide.find("contact_slope_max_deg"), std::string::npos);
  std::size_t lines = 0;
  for (char c : wide) lines += c == '\n';
  EXPECT_EQ(lines, 31u);
  EXPECT_NE(read_file(dir + "/wm-arrays.csv").find("contact_slope_pdf_density_per_deg"), std::string::npos);
  EXPECT_FALSE(read_file(dir + "/report.md").empty());
}

TEST(StudyCli, ATaskRetriedOnceGivesTheSameStoreOnThreadsAndMpiRanks) {
  // The coordinator's fault-injection hook (--inject-failure-task): the first attempt of tasks 3
  // and 17 is reported failed, whichever worker computed it; both are retried and the store
  // holds exactly what an undisturbed run holds, with two attempts recorded for those tasks.
  const std::string study = study_file("retry");
  const std::string ref = fresh("retry-ref.sqlite"), thr = fresh("retry-threads.sqlite");
  auto r = run_cli("study run " + study + " --store " + ref + " --threads 2 --cache none --progress none");
  ASSERT_EQ(r.code, 0) << r.err;
  r = run_cli("study run " + study + " --store " + thr +
              " --threads 2 --cache none --progress none --inject-failure-task 3 --inject-failure-task 17");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string expected = dump(ref);
  EXPECT_EQ(dump(thr), expected);
  auto attempts = [](const std::string& path) {
    std::map<std::int64_t, int> a;
    auto st = Store::open_existing(path);
    EXPECT_TRUE(st.ok());
    if (!st.ok()) return a;
    const auto tasks = (*st)->tasks();
    EXPECT_TRUE(tasks.ok());
    if (tasks.ok())
      for (const auto& t : *tasks) a[t.id] = t.attempts;
    return a;
  };
  auto a = attempts(thr);
  EXPECT_EQ(a[3], 2);
  EXPECT_EQ(a[17], 2);
  EXPECT_EQ(a[4], 1);

  if (!mpi_available()) GTEST_SKIP() << "built without FRICTAL_MPI";
  if (std::system("command -v mpirun >/dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun not found";
  const std::string mpi = fresh("retry-mpi.sqlite");
  const std::string cmd =
      study_test::mpirun_prefix(2) + FRICTAL_CLI_PATH + " study run " + study + " --store " + mpi +
      " --cache none --progress none --inject-failure-task 3 --inject-failure-task 17 >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  EXPECT_EQ(dump(mpi), expected);
  a = attempts(mpi);
  EXPECT_EQ(a[3], 2);
  EXPECT_EQ(a[17], 2);
  EXPECT_EQ(a[4], 1);
}
