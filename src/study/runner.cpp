// Running a study on threads: the threads transport of the coordinator (coordinator.hpp). The
// calling thread owns the store and records; compute threads claim, compute and hand back.
// Also the binary record format that the MPI transport sends between ranks.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <optional>
#include <thread>

#ifdef __linux__
#include <pthread.h>
#include <sched.h>
#endif

#include <fmt/core.h>

#include "frictal/study.hpp"
#include "study/coordinator.hpp"
#include "study/idle_threads.hpp"
#include "util/parallel.hpp"

namespace frictal::study {

namespace {
/// Pins the calling thread to the k-th CPU it may run on (Linux; a no-op elsewhere or on error).
void pin_to_cpu(unsigned k) {
#ifdef __linux__
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) return;
  const int n = CPU_COUNT(&allowed);
  if (n <= 1) return;
  int want = static_cast<int>(k % static_cast<unsigned>(n));
  for (int c = 0; c < CPU_SETSIZE; ++c) {
    if (!CPU_ISSET(c, &allowed)) continue;
    if (want-- == 0) {
      cpu_set_t one;
      CPU_ZERO(&one);
      CPU_SET(c, &one);
      pthread_setaffinity_np(pthread_self(), sizeof one, &one);
      return;
    }
  }
#else
  (void)k;
#endif
}
}  // namespace

Result<RunSummary> run_threads(const Study& study, Store& store, const TaskRegistry& registry,
                               const RunOptions& options) {
  RunSummary sum;
  auto todo = plan(study, store, registry, options, &sum.skipped_unavailable);
  if (!todo) return todo.error();
  const unsigned T = util::thread_count(options.threads, std::max<std::size_t>(1, todo->size()));
  sum.threads = util::thread_count(options.threads);
  Coordinator co(study, store, registry, options, std::move(*todo), 1);
  if (auto s = co.start(); !s) return s.error();
  if (options.started) options.started();
  // Cores without a compute thread (fewer tasks than threads), and later those of compute threads
  // waiting for work, are lent to the running tasks (borrow_idle_threads).
  detail::IdlePool idle;
  idle.idle = static_cast<int>(sum.threads) - static_cast<int>(T);
  // T compute threads claim, compute and hand back; this thread owns the store and records.
  util::run_workers(
      T,
      [&](unsigned w) {
        const std::string name = fmt::format("thread {}", w);
        if (options.pin_threads) pin_to_cpu(w);
        detail::set_idle_pool(&idle);
        for (;;) {
          std::int64_t id = co.claim(0, false);
          if (id < 0) {  // nothing queued: this core is idle (lent to running tasks) while it waits
            idle.lend();
            id = co.claim(0, true);
            idle.reclaim();
          }
          if (id < 0) break;
          co.finish(execute(study.tasks[static_cast<std::size_t>(id)], registry, name), 0);
        }
        detail::set_idle_pool(nullptr);
      },
      [&] {
        while (!co.over()) co.record_finished(true);
      });
  co.record_finished(false);
  return co.summary(sum);
}

Result<std::vector<RunSummary>> run_threads(const std::vector<StudyRun>& runs, const TaskRegistry& registry,
                                            const RunOptions& options) {
  if (runs.empty()) return std::vector<RunSummary>{};
  if (runs.size() > 1 && !options.parts.empty())
    return make_error(
        fmt::format("part '{}': parts cannot be chosen when running several studies (part names "
                    "belong to one study)",
                    options.parts.front()));
  for (const StudyRun& r : runs)
    if (!r.study || !r.store)
      return make_error(ErrorCode::InvalidInput, "run_threads: a StudyRun without study or store");
  // One stop flag for every study: set by the caller's, or when one study's store fails.
  std::atomic<bool> stop_all{options.stop && options.stop->load()};
  const std::size_t n = runs.size();
  std::vector<RunOptions> opts(n, options);
  std::vector<RunSummary> sums(n);
  std::vector<std::unique_ptr<Coordinator>> cos;
  SharedResults shared;
  std::size_t total = 0;
  for (std::size_t i = 0; i < n; ++i) {
    opts[i].cache = runs[i].cache;
    opts[i].progress = runs[i].progress;
    opts[i].stop = &stop_all;
    opts[i].started = nullptr;
    auto todo = plan(*runs[i].study, *runs[i].store, registry, opts[i], &sums[i].skipped_unavailable);
    if (!todo) return with_prefix(fmt::format("study '{}': ", runs[i].study->name), todo.error());
    total += todo->size();
    cos.push_back(
        std::make_unique<Coordinator>(*runs[i].study, *runs[i].store, registry, opts[i], std::move(*todo), 1));
    cos.back()->set_shared(&shared);
  }
  for (std::size_t i = 0; i < n; ++i)
    if (auto s = cos[i]->start(); !s) return with_prefix(fmt::format("study '{}': ", runs[i].study->name), s.error());
  if (options.started) options.started();
  const unsigned T = util::thread_count(options.threads, std::max<std::size_t>(1, total));
  // Idle cores lent to running tasks, as in the single-study run.
  detail::IdlePool idle;
  idle.idle = static_cast<int>(util::thread_count(options.threads)) - static_cast<int>(T);
  util::run_workers(
      T,
      [&](unsigned w) {
        const std::string name = fmt::format("thread {}", w);
        if (options.pin_threads) pin_to_cpu(w);
        detail::set_idle_pool(&idle);
        std::vector<std::pair<double, std::size_t>> heads;
        for (;;) {
          if (options.stop && options.stop->load()) stop_all = true;  // dispatch nothing more
          // The costliest queue head of all studies first (ties: the earlier study).
          heads.clear();
          for (std::size_t i = 0; i < n; ++i)
            if (const double c = cos[i]->next_cost(); c >= 0) heads.emplace_back(c, i);
          std::stable_sort(heads.begin(), heads.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
          bool took = false;
          for (const auto& [c, i] : heads) {
            const std::int64_t id = cos[i]->claim(0, false);
            if (id == Coordinator::kClaimAgain) {  // reused or set aside: choose the study again
              took = true;
              break;
            }
            if (id < 0) continue;
            cos[i]->finish(execute(runs[i].study->tasks[static_cast<std::size_t>(id)], registry, name), 0);
            took = true;
            break;
          }
          if (took) continue;
          if (std::all_of(cos.begin(), cos.end(), [](const auto& co) { return co->exhausted(); })) break;
          // Nothing to take now: tasks computing (a retry may come back), waiting for another
          // study's result, or held by another run on a shared store. The core is lent meanwhile.
          idle.lend();
          std::this_thread::sleep_for(std::chrono::milliseconds(20));
          idle.reclaim();
        }
        detail::set_idle_pool(nullptr);
      },
      [&] {
        for (;;) {
          if (options.stop && options.stop->load()) stop_all = true;
          bool all_over = true;
          std::size_t recorded = 0;
          for (auto& co : cos) {
            recorded += co->record_finished(false);
            if (co->closing()) stop_all = true;  // interrupted, or a store failed: stop every study
            if (!co->over()) all_over = false;
          }
          if (all_over) break;
          if (!recorded) std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
      });
  for (auto& co : cos) co->record_finished(false);
  // Every study's summary (each releases its store's claims), then the first error if any.
  std::optional<Error> first_error;
  for (std::size_t i = 0; i < n; ++i) {
    sums[i].threads = util::thread_count(options.threads);
    auto s = cos[i]->summary(sums[i]);
    if (s)
      sums[i] = *s;
    else if (!first_error)
      first_error = with_prefix(fmt::format("study '{}': ", runs[i].study->name), s.error());
  }
  if (first_error) return *first_error;
  return sums;
}

// ---------------------------------------------------------------- serialisation (for MPI)

namespace {
constexpr std::uint32_t kMagic = 0x46545232;  // "FTR2"
void put_u64(std::string& s, std::uint64_t v) { s.append(reinterpret_cast<const char*>(&v), 8); }
void put_f64(std::string& s, double v) { s.append(reinterpret_cast<const char*>(&v), 8); }
void put_str(std::string& s, const std::string& v) {
  put_u64(s, v.size());
  s += v;
}
struct Reader {
  const std::string& s;
  std::size_t at = 0;
  bool ok = true;
  std::uint64_t u64() {
    std::uint64_t v = 0;
    if (at + 8 > s.size()) return ok = false, 0;
    std::memcpy(&v, s.data() + at, 8);
    at += 8;
    return v;
  }
  double f64() {
    double v = 0;
    if (at + 8 > s.size()) return ok = false, 0.0;
    std::memcpy(&v, s.data() + at, 8);
    at += 8;
    return v;
  }
  std::string str() {
    const auto n = u64();
    if (!ok || n > s.size() - at) return ok = false, std::string{};
    std::string v = s.substr(at, n);
    at += n;
    return v;
  }
};
}  // namespace

std::string serialize(const TaskRecord& r) {
  std::string s;
  put_u64(s, kMagic);
  put_u64(s, static_cast<std::uint64_t>(r.id));
  put_u64(s, static_cast<std::uint64_t>(r.status));
  put_str(s, r.error);
  put_u64(s, static_cast<std::uint64_t>(r.code));
  put_f64(s, r.wall_s);
  put_str(s, r.worker);
  put_u64(s, r.output.scalars.size());
  for (const auto& [k, v] : r.output.scalars) {
    put_str(s, k);
    put_f64(s, v);
  }
  put_u64(s, r.output.arrays.size());
  for (const auto& [k, v] : r.output.arrays) {
    put_str(s, k);
    put_u64(s, v.size());
    s.append(reinterpret_cast<const char*>(v.data()), v.size() * 8);
  }
  return s;
}

Result<TaskRecord> deserialize(const std::string& bytes) {
  Reader in{bytes};
  TaskRecord r;
  if (in.u64() != kMagic) return make_error("task record: bad header");
  r.id = static_cast<std::int64_t>(in.u64());
  const auto st = in.u64();
  if (st > 2) return make_error("task record: bad status");
  r.status = static_cast<TaskStatus>(st);
  r.error = in.str();
  const auto code = in.u64();
  if (code > static_cast<std::uint64_t>(ErrorCode::Internal)) return make_error("task record: bad error code");
  r.code = static_cast<ErrorCode>(code);
  r.wall_s = in.f64();
  r.worker = in.str();
  const auto ns = in.u64();
  for (std::uint64_t i = 0; in.ok && i < ns; ++i) {
    std::string k = in.str();
    r.output.scalars[k] = in.f64();
  }
  const auto na = in.u64();
  for (std::uint64_t i = 0; in.ok && i < na; ++i) {
    std::string k = in.str();
    const auto n = in.u64();
    if (!in.ok || n > (bytes.size() - in.at) / 8) return make_error("task record: truncated array");
    std::vector<double> v(n);
    std::memcpy(v.data(), bytes.data() + in.at, n * 8);
    in.at += n * 8;
    r.output.arrays[k] = std::move(v);
  }
  if (!in.ok || in.at != bytes.size()) return make_error("task record: truncated or trailing bytes");
  return r;
}

#ifndef FRICTAL_MPI
bool mpi_available() { return false; }
bool launched_by_mpi() { return false; }
Result<RunSummary> run_mpi(const Study&, Store*, const TaskRegistry&, const RunOptions&) {
  return make_error("this build has no MPI support (configure with FRICTAL_MPI=ON and an MPI library)");
}
Status mpi_init(int*, int*) { return make_error("this build has no MPI support"); }
void mpi_finalize() {}
bool mpi_broadcast(bool value) { return value; }
#endif

}  // namespace frictal::study
