// Stores shared and interrupted: claims between runs on one store (library and three concurrent
// CLI runs killed at random), a read-only store, a full disk, MPI ranks killed, and the versions
// recorded per task.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <linux/fs.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <dirent.h>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <regex>
#include <thread>

#include <sqlite3.h>

#include "cli/cli_runner.hpp"
#include "frictal/study.hpp"
#include "frictal/version.hpp"
#include "study/study_helpers.hpp"

using namespace frictal::study;

namespace {

using study_test::dump;
using study_test::fresh;

// 30 tasks of a few to some tens of milliseconds in two parts (the second part alone is the
// "already stored" data of the read-only and full-disk tests).
const char* kStudy = R"(
[study]
name = "shared-test"
seed = 7
[[part]]
name = "a"
kind = "wm-pair-statistics"
seed_from = ["pair"]
[part.parameters]
dimension = [1.3, 1.7]
n_max = [6, 8, 9]
pair = { count = 3 }
[[part]]
name = "b"
kind = "wm-pair-statistics"
seed_from = ["pair"]
[part.parameters]
dimension = [1.5]
n_max = [7, 9]
pair = { count = 6 }
)";
constexpr int kTasks = 30;

std::string study_file(const std::string& tag) {
  const std::string p = temp_path("shared-test-" + tag + ".toml");
  write_file(p, kStudy);
  return p;
}

Study load(const std::string& file) {
  auto s = load_study(file, false, default_registry());
  EXPECT_TRUE(s.ok()) << (s.ok() ? "" : s.error().message);
  return *s;
}

/// `frictal study run` as a child with stdout and stderr to `log`; returns its pid.
pid_t spawn_run(const std::string& study, const std::string& store, const std::string& log) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::freopen(log.c_str(), "w", stdout);
    std::freopen(log.c_str(), "a", stderr);
    ::execl(FRICTAL_CLI_PATH, FRICTAL_CLI_PATH, "study", "run", study.c_str(), "--store", store.c_str(), "--threads",
            "1", "--cache", "none", "--progress", "none", static_cast<char*>(nullptr));
    std::_Exit(127);
  }
  return pid;
}

/// Tasks a run says it recorded ("this run: N tasks").
int ran_in(const std::string& log) {
  std::smatch m;
  const std::string text = read_file(log);
  static const std::regex re("this run: ([0-9]+) tasks");
  return std::regex_search(text, m, re) ? std::stoi(m[1]) : -1;
}

std::int64_t claimed(const std::string& path) {
  auto st = Store::open_existing(path);
  if (!st.ok()) return -1;
  auto c = (*st)->claimed();
  return c.ok() ? *c : -1;
}

/// Makes a file read-only in a way that holds for root too: the immutable attribute (needs
/// CAP_LINUX_IMMUTABLE and a file system that has it); for other users, mode 0444.
bool make_read_only(const std::string& path, bool on) {
  if (::getuid() != 0) return ::chmod(path.c_str(), on ? 0444 : 0644) == 0;
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return false;
  int flags = 0;
  bool ok = ::ioctl(fd, FS_IOC_GETFLAGS, &flags) == 0;
  if (ok) {
    flags = on ? (flags | FS_IMMUTABLE_FL) : (flags & ~FS_IMMUTABLE_FL);
    ok = ::ioctl(fd, FS_IOC_SETFLAGS, &flags) == 0;
  }
  ::close(fd);
  return ok;
}

}  // namespace

TEST(StudyShared, ClaimsAreExclusiveWhileTheOwnerLivesAndTakenOverWhenItDies) {
  const Study study = load(study_file("claims"));
  const std::string path = fresh("claims.sqlite");
  auto a = Store::open(path, study);
  ASSERT_TRUE(a.ok()) << a.error().message;
  auto b = Store::open(path, study);
  ASSERT_TRUE(b.ok()) << b.error().message;
  ASSERT_TRUE((*a)->unfinished().ok());
  ASSERT_TRUE((*b)->unfinished().ok());
  EXPECT_NE((*a)->owner(), (*b)->owner());

  EXPECT_EQ(*(*a)->claim(0, 60), Store::Claim::Claimed);
  EXPECT_EQ(*(*a)->claim(0, 60), Store::Claim::Claimed);  // its own claim
  EXPECT_EQ(*(*b)->claim(0, 60), Store::Claim::Busy);     // owner alive, lease fresh
  EXPECT_EQ(*(*b)->claim(1, 60), Store::Claim::Claimed);
  // A lease that has run out (here: a negative lease) is taken over although the owner lives.
  EXPECT_EQ(*(*b)->claim(0, -1), Store::Claim::TakenOver);
  EXPECT_EQ(*(*a)->claim(0, 60), Store::Claim::Busy);

  // Once recorded by one run, the task is finished for the other.
  TaskRecord r = execute(study.tasks[1], default_registry(), "test");
  ASSERT_EQ(r.status, TaskStatus::Done) << r.error;
  ASSERT_TRUE((*b)->record(r).ok());
  EXPECT_EQ(*(*a)->claim(1, 60), Store::Claim::Finished);
  // A second record of the same task by the other run changes nothing.
  TaskRecord late = r;
  late.output.scalars["points"] = -1;
  ASSERT_TRUE((*a)->record(late).ok());
  auto rows = (*a)->rows("a", false);
  ASSERT_TRUE(rows.ok());
  for (const auto& row : *rows)
    if (row.id == 1) {
      EXPECT_NE(row.output.scalars.at("points"), -1);
    }

  // A claim left by a process that died (SIGKILL, no clean-up) is taken over at once.
  const pid_t child = ::fork();
  if (child == 0) {
    auto c = Store::open(path, study);
    if (!c.ok() || !(*c)->unfinished().ok() || !(*c)->claim(5, 3600).ok()) std::_Exit(1);
    ::kill(::getpid(), SIGKILL);
    std::_Exit(2);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "child exit " << WEXITSTATUS(status);
  EXPECT_EQ(claimed(path), 2);  // task 0 by b, task 5 by the dead child
  EXPECT_EQ(*(*a)->claim(5, 3600), Store::Claim::TakenOver);
  ASSERT_TRUE((*a)->release_claims().ok());
  ASSERT_TRUE((*b)->release_claims().ok());
  EXPECT_EQ(claimed(path), 0);
}

// Switching a new file to WAL needs an exclusive lock, and SQLite fails it at once (SQLITE_BUSY,
// no busy handler) while another connection holds a write lock on the file: three runs started
// together on one new store would stop with "database is locked".
// Store::open must wait for the other connection instead.
TEST(StudyShared, OpeningANewStoreWaitsForAnotherConnectionsLock) {
  const Study study = load(study_file("busy"));
  const std::string path = fresh("busy.sqlite");
  sqlite3* other = nullptr;
  ASSERT_EQ(sqlite3_open_v2(path.c_str(), &other, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr), SQLITE_OK);
  // A write transaction holds a RESERVED lock on the (still rollback-journal) file.
  ASSERT_EQ(sqlite3_exec(other, "BEGIN IMMEDIATE;", nullptr, nullptr, nullptr), SQLITE_OK);
  const auto t0 = std::chrono::steady_clock::now();  // the lock is held for >= 0.3 s after this
  std::thread release([other] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    sqlite3_exec(other, "COMMIT", nullptr, nullptr, nullptr);
  });
  auto st = Store::open(path, study);
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  release.join();
  sqlite3_close(other);
  ASSERT_TRUE(st.ok()) << st.error().message;
  EXPECT_GE(waited, 0.29);  // it waited for the writer, and then made the store
  EXPECT_TRUE((*st)->unfinished().ok());
}

TEST(StudyShared, ThreeConcurrentRunsShareTheWorkAndSurviveRandomKills) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string study = study_file("concurrent");
  const std::string ref = fresh("concurrent-ref.sqlite");
  auto r = run_cli("study run " + study + " --store " + ref + " --threads 1 --cache none --progress none");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string expected = dump(ref);

  // Three runs at once, none killed: every task computed exactly once, by one of them.
  {
    const std::string store = fresh("concurrent-0.sqlite");
    pid_t pids[3];
    std::string logs[3];
    for (int i = 0; i < 3; ++i) {
      logs[i] = temp_path("concurrent-0-" + std::to_string(i) + ".log");
      pids[i] = spawn_run(study, store, logs[i]);
    }
    int total = 0, busy = 0;
    for (int i = 0; i < 3; ++i) {
      int status = 0;
      ::waitpid(pids[i], &status, 0);
      ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << read_file(logs[i]);
      const int n = ran_in(logs[i]);
      ASSERT_GE(n, 0) << read_file(logs[i]);
      total += n;
      busy += n > 0;
    }
    EXPECT_EQ(total, kTasks);  // no task computed twice, none lost
    EXPECT_GE(busy, 2) << "the runs did not share the work";
    EXPECT_EQ(dump(store), expected);
    EXPECT_EQ(claimed(store), 0);
  }

  // Three runs at once, any of them killed with SIGKILL at random times, then a final run.
  std::mt19937 rng(20261123);
  std::uniform_int_distribution<int> delay_ms(20, 400);
  int kills = 0;
  for (int trial = 0; trial < 3; ++trial) {
    const std::string store = fresh("concurrent-k" + std::to_string(trial) + ".sqlite");
    pid_t pids[3];
    std::string delays, logs[3];
    for (int i = 0; i < 3; ++i) {
      logs[i] = temp_path("concurrent-k" + std::to_string(trial) + "-" + std::to_string(i) + ".log");
      pids[i] = spawn_run(study, store, logs[i]);
    }
    // Kill one or two of the three (which ones and when: from the seeded generator).
    const int victims = 1 + trial % 2;
    for (int v = 0; v < victims; ++v) {
      const int d = delay_ms(rng);
      delays += std::to_string(d) + "ms ";
      std::this_thread::sleep_for(std::chrono::milliseconds(d));
      const int who = static_cast<int>(rng() % 3);
      if (::kill(pids[who], SIGKILL) == 0) ++kills;
    }
    for (int i = 0; i < 3; ++i) {
      int status = 0;
      ::waitpid(pids[i], &status, 0);
      if (WIFEXITED(status)) {
        EXPECT_EQ(WEXITSTATUS(status), 0) << "trial " << trial << ", run " << i << ":\n" << read_file(logs[i]);
      }
    }
    r = run_cli("study run " + study + " --store " + store + " --threads 2 --cache none --progress none");
    ASSERT_EQ(r.code, 0) << r.err << " (kill delays " << delays << ")";
    EXPECT_EQ(dump(store), expected) << "kill delays " << delays;
    EXPECT_EQ(claimed(store), 0);
  }
  EXPECT_GT(kills, 0);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("[ timing ] three concurrent runs, 4 scenarios (1 clean + 3 with kills): %.2f s\n", s);
}

TEST(StudyShared, ReadOnlyStoreIsAClearErrorAndKeepsWhatIsStored) {
  const std::string study = study_file("ro");
  const std::string store = fresh("ro.sqlite");
  auto r = run_cli("study run " + study + " --store " + store + " --part b --threads 2 --cache none --progress none");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string before = dump(store);
  if (!make_read_only(store, true)) GTEST_SKIP() << "cannot make a file read-only here";
  r = run_cli("study run " + study + " --store " + store + " --threads 2 --cache none --progress none");
  EXPECT_EQ(r.code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find(store), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("read-only"), std::string::npos) << r.err;
  // status and export still read it.
  const auto st = run_cli("study status " + store);
  EXPECT_EQ(st.code, 0) << st.err;
  EXPECT_NE(st.out.find("12 done"), std::string::npos) << st.out;
  ASSERT_TRUE(make_read_only(store, false));
  EXPECT_EQ(dump(store), before);
  r = run_cli("study run " + study + " --store " + store + " --threads 2 --cache none --progress none");
  EXPECT_EQ(r.code, 0) << r.err;
}

TEST(StudyShared, FullDiskIsAClearErrorAndKeepsWhatIsStored) {
  const std::string file = study_file("full");
  const Study study = load(file);
  const auto& reg = default_registry();
  const std::string path = fresh("full.sqlite"), ref = fresh("full-ref.sqlite");
  {
    auto s = Store::open(ref, study);
    ASSERT_TRUE(s.ok());
    RunOptions o;
    o.threads = 2;
    ASSERT_TRUE(run_threads(study, **s, reg, o).ok());
  }
  std::string before;
  {
    auto s = Store::open(path, study);
    ASSERT_TRUE(s.ok());
    RunOptions o;
    o.threads = 2;
    o.parts = {"b"};
    ASSERT_TRUE(run_threads(study, **s, reg, o).ok());
    auto c = (*s)->content();
    ASSERT_TRUE(c.ok());
    before = *c;
  }
  {
    // The disk "fills": the store may not grow by a page.
    auto s = Store::open(path, study);
    ASSERT_TRUE(s.ok());
    RunOptions o;
    o.threads = 2;
    o.max_page_count = 1;  // below the current size: capped at the current size
    auto sum = run_threads(study, **s, reg, o);
    ASSERT_FALSE(sum.ok());
    EXPECT_EQ(sum.error().code, frictal::ErrorCode::Io);
    EXPECT_NE(sum.error().message.find(path), std::string::npos) << sum.error().message;
    EXPECT_NE(sum.error().message.find("disk is full"), std::string::npos) << sum.error().message;
    auto rows = (*s)->rows("b", true);
    ASSERT_TRUE(rows.ok());
    EXPECT_EQ(rows->size(), 12u);
  }
  // Part b as it was; resuming completes the study exactly as an undisturbed run.
  {
    auto s = Store::open(path, study);
    ASSERT_TRUE(s.ok());
    auto c = (*s)->content();
    ASSERT_TRUE(c.ok());
    // Every line of the earlier content that is about part b is still there.
    auto rows = (*s)->rows("b", true);
    ASSERT_TRUE(rows.ok());
    EXPECT_EQ(rows->size(), 12u);
    RunOptions o;
    o.threads = 2;
    ASSERT_TRUE(run_threads(study, **s, reg, o).ok());
  }
  EXPECT_EQ(dump(path), dump(ref));
  (void)before;
}

TEST(StudyShared, FileSizeLimitAsAFullDiskThroughTheCli) {
  // A real write failure (EFBIG/short write from RLIMIT_FSIZE holds for root too): exit 2, the
  // message names the store, and the tasks stored before are kept.
  const std::string study = study_file("fsize");
  const std::string store = fresh("fsize.sqlite");
  auto r = run_cli("study run " + study + " --store " + store + " --part b --threads 2 --cache none --progress none");
  ASSERT_EQ(r.code, 0) << r.err;
  struct stat sb {};
  ::stat(store.c_str(), &sb);
  const std::string log = temp_path("fsize.log");
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::freopen(log.c_str(), "w", stdout);
    std::freopen(log.c_str(), "a", stderr);
    ::signal(SIGXFSZ, SIG_IGN);  // the write fails with EFBIG instead of killing the process
    struct rlimit lim {
      static_cast<rlim_t>(sb.st_size), static_cast<rlim_t>(sb.st_size)
    };
    ::setrlimit(RLIMIT_FSIZE, &lim);
    ::execl(FRICTAL_CLI_PATH, FRICTAL_CLI_PATH, "study", "run", study.c_str(), "--store", store.c_str(), "--threads",
            "2", "--cache", "none", "--progress", "none", static_cast<char*>(nullptr));
    std::_Exit(127);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  const std::string out = read_file(log);
  ASSERT_TRUE(WIFEXITED(status)) << out;
  EXPECT_EQ(WEXITSTATUS(status), 2) << out;
  EXPECT_NE(out.find(store), std::string::npos) << out;
  EXPECT_NE(out.find("disk is full"), std::string::npos) << out;
  EXPECT_NE(out.find("kept"), std::string::npos) << out;
  auto st = Store::open_existing(store);
  ASSERT_TRUE(st.ok());
  auto rows = (*st)->rows("b", false);
  ASSERT_TRUE(rows.ok());
  EXPECT_EQ(rows->size(), 12u);
  r = run_cli("study run " + study + " --store " + store + " --threads 2 --cache none --progress none");
  EXPECT_EQ(r.code, 0) << r.err;
}

TEST(StudyShared, EachResultKeepsTheFrictalAndKindVersion) {
  const std::string study = study_file("versions");
  const std::string store = fresh("versions.sqlite");
  auto r = run_cli("study run " + study + " --store " + store + " --part b --threads 2 --cache none --progress none");
  ASSERT_EQ(r.code, 0) << r.err;
  auto st = Store::open_existing(store);
  ASSERT_TRUE(st.ok());
  auto m = (*st)->meta();
  ASSERT_TRUE(m.ok());
  EXPECT_EQ((*m)["frictal_version"], std::string(frictal::version()));
  auto v = (*st)->version_counts();
  ASSERT_TRUE(v.ok());
  ASSERT_EQ(v->size(), 1u);
  EXPECT_EQ((*v)[0].part, "b");
  EXPECT_EQ((*v)[0].kind_version, default_registry().version("wm-pair-statistics"));
  EXPECT_EQ((*v)[0].frictal_version, std::string(frictal::version()));
  EXPECT_EQ((*v)[0].done, 12);

  // A registry whose wm kind is a version ahead sees these results as from an older version.
  TaskRegistry newer;
  TaskRegistry base = default_registry();
  for (const auto& n : base.names()) {
    TaskKind k = *base.find(n);
    if (n == "wm-pair-statistics") ++k.version;
    newer.add(std::move(k));
  }
  auto s = store_status(**st, newer);
  ASSERT_TRUE(s.ok());
  ASSERT_EQ(s->parts.size(), 2u);
  const auto& b = s->parts[1];
  EXPECT_EQ(b.part, "b");
  EXPECT_EQ(b.done_by_kind_version.at(base.version("wm-pair-statistics")), 12);
  const int v0 = base.version("wm-pair-statistics");
  EXPECT_NE(b.version_note.find("12 tasks by version " + std::to_string(v0)), std::string::npos) << b.version_note;
  EXPECT_NE(b.version_note.find("this build has version " + std::to_string(v0 + 1)), std::string::npos)
      << b.version_note;
  EXPECT_TRUE(s->parts[0].version_note.empty());  // nothing done there
  auto rep = report(**st, newer);
  ASSERT_TRUE(rep.ok());
  const std::string md = render_markdown(*rep);
  EXPECT_NE(md.find("**Warning:** part 'b'"), std::string::npos) << md;
  // The CLI's status lists the versions.
  r = run_cli("study status " + store);
  EXPECT_NE(r.out.find("12 by v" + std::to_string(v0)), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;  // this build's version: no warning
}

namespace {
/// Pid of the process whose command line contains `needle` and whose environment has
/// `env_entry` (e.g. "OMPI_COMM_WORLD_RANK=2"), or -1.
pid_t find_process(const std::string& needle, const std::string& env_entry) {
  DIR* d = ::opendir("/proc");
  if (!d) return -1;
  pid_t found = -1;
  while (dirent* e = ::readdir(d)) {
    const std::string name = e->d_name;
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    const std::string cmd = read_file("/proc/" + name + "/cmdline");
    if (cmd.find(needle) == std::string::npos) continue;
    std::string env = read_file("/proc/" + name + "/environ");
    for (char& c : env)
      if (c == '\0') c = '\n';
    if (("\n" + env).find("\n" + env_entry + "\n") == std::string::npos) continue;
    found = static_cast<pid_t>(std::stol(name));
    break;
  }
  ::closedir(d);
  return found;
}
}  // namespace

TEST(StudyShared, MpiRankKilledLeavesTheStoreConsistentAndARerunCompletes) {
  if (!mpi_available()) GTEST_SKIP() << "built without FRICTAL_MPI";
  if (std::system("command -v mpirun >/dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun not found";
  const std::string study = study_file("mpi-kill");
  const std::string ref = fresh("mpi-kill-ref.sqlite");
  auto r = run_cli("study run " + study + " --store " + ref + " --threads 2 --cache none --progress none");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string expected = dump(ref);
  const std::string mpirun = study_test::mpirun_prefix(3);
  std::mt19937 rng(31337);
  for (int trial = 0; trial < 2; ++trial) {
    const std::string store = fresh("mpi-kill-" + std::to_string(trial) + ".sqlite");
    const std::string log = temp_path("mpi-kill-" + std::to_string(trial) + ".log");
    const std::string cmd = mpirun + FRICTAL_CLI_PATH + " study run " + study + " --store " + store +
                            " --cache none --progress none >" + log + " 2>&1";
    const pid_t launcher = ::fork();
    if (launcher == 0) {
      ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      std::_Exit(127);
    }
    // Kill rank 1 or 2 (a worker) with SIGKILL a random moment after it started.
    const std::string victim = "OMPI_COMM_WORLD_RANK=" + std::to_string(1 + trial % 2);
    pid_t rank = -1;
    for (int i = 0; i < 400 && rank < 0; ++i) {
      rank = find_process(store, victim);
      if (rank < 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ASSERT_GT(rank, 0) << "rank process not found";
    // Mid-run: once a few tasks are recorded, then a random moment later.
    for (int i = 0; i < 1000; ++i) {
      if (::access(store.c_str(), F_OK) == 0) {
        auto st = Store::open_existing(store);
        auto c = st.ok() ? (*st)->counts() : frictal::Result<StoreCounts>(frictal::make_error("no store"));
        if (c.ok() && c->done >= 3) break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(rng() % 150));
    const bool killed = ::kill(rank, SIGKILL) == 0;
    int status = 0;
    ::waitpid(launcher, &status, 0);
    const std::string out = read_file(log);
    if (killed && WIFEXITED(status) && WEXITSTATUS(status) != 0) {
      // The job ends; rank 0 says what to do (unless mpirun killed it before it could).
      EXPECT_TRUE(out.find("run the same command again") != std::string::npos ||
                  out.find("signal 9") != std::string::npos)
          << out;
    }
    // The store is consistent: it opens, every done task has its results, nothing half-written.
    {
      auto st = Store::open_existing(store);
      ASSERT_TRUE(st.ok()) << st.error().message;
      auto rows = (*st)->rows("", true);
      ASSERT_TRUE(rows.ok());
      for (const auto& row : *rows) EXPECT_FALSE(row.output.scalars.empty()) << "task " << row.id;
      std::printf("[ mpi-kill ] trial %d: rank killed %d, mpirun exit %d, %zu of %d tasks stored before the rerun\n",
                  trial, killed ? 1 : 0, WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), rows->size(),
                  kTasks);
    }
    // Running the same command again completes it, with exactly the undisturbed results.
    ASSERT_EQ(std::system((mpirun + FRICTAL_CLI_PATH + " study run " + study + " --store " + store +
                           " --cache none --progress none >/dev/null 2>&1")
                              .c_str()),
              0);
    EXPECT_EQ(dump(store), expected) << out;
    EXPECT_EQ(claimed(store), 0);
  }
}
