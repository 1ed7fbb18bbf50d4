// Running a study on threads: plan, execute, record. One writer (the calling thread) owns the
// store; compute threads hand finished records over through a queue.
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <mutex>
#include <set>
#include <thread>

#ifdef __linux__
#include <pthread.h>
#include <sched.h>
#endif

#include <fmt/core.h>

#include "frictal/study.hpp"

namespace frictal::study {

Result<std::vector<std::int64_t>> plan(const Study& study, Store& store, const TaskRegistry& registry,
                                       const RunOptions& options, std::int64_t* skipped_unavailable) {
  std::set<std::string> wanted(options.parts.begin(), options.parts.end());
  for (const auto& w : wanted) {
    if (std::none_of(study.parts.begin(), study.parts.end(), [&](const Part& p) { return p.name == w; })) {
      std::vector<std::string> names;
      for (const auto& p : study.parts) names.push_back(p.name);
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
      return make_error(fmt::format("--part {}: study '{}' has no such part (parts: {})", w, study.name, list));
    }
  }
  for (const Part& p : study.parts) {
    if (!wanted.empty() && !wanted.count(p.name)) continue;
    const std::string why = registry.unavailable_reason(p.kind);
    if (!why.empty() && !options.skip_unavailable)
      return make_error(fmt::format("part '{}' of study '{}': {}; run the other parts with --skip-unavailable{}", p.name,
                                    study.name, why, study.parts.size() > 1 ? " or choose parts with --part" : ""));
  }
  auto ids = store.unfinished();
  if (!ids) return ids.error();
  std::vector<std::int64_t> todo;
  std::int64_t skipped = 0;
  for (auto id : *ids) {
    if (id < 0 || id >= static_cast<std::int64_t>(study.tasks.size()))
      return make_error(fmt::format("store has task {} which the study does not define", id));
    const Task& t = study.tasks[static_cast<std::size_t>(id)];
    if (!wanted.empty() && !wanted.count(t.part)) continue;
    if (!registry.find(t.kind)) {
      ++skipped;
      continue;
    }
    todo.push_back(id);
  }
  if (skipped_unavailable) *skipped_unavailable = skipped;
  return todo;
}

TaskRecord execute(const Task& task, const TaskRegistry& registry, const std::string& worker) {
  TaskRecord r;
  r.id = task.id;
  r.worker = worker;
  const auto t0 = std::chrono::steady_clock::now();
  const TaskKind* k = registry.find(task.kind);
  if (!k) {
    r.status = TaskStatus::Failed;
    r.error = registry.unavailable_reason(task.kind);
    if (r.error.empty()) r.error = fmt::format("unknown task kind '{}'", task.kind);
  } else {
    try {
      auto out = k->run(task.params, task.seed);
      if (out) {
        r.status = TaskStatus::Done;
        r.output = std::move(*out);
      } else {
        r.status = TaskStatus::Failed;
        r.error = out.error().message;
      }
    } catch (const std::exception& e) {  // e.g. std::bad_alloc: a failure of this task only
      r.status = TaskStatus::Failed;
      r.error = fmt::format("exception: {}", e.what());
    }
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

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

Result<RunSummary> run_threads(const Study& study, Store& store, const TaskRegistry& registry, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  RunSummary sum;
  auto todo = plan(study, store, registry, options, &sum.skipped_unavailable);
  if (!todo) return todo.error();
  auto c0 = store.counts();
  if (!c0) return c0.error();
  const unsigned T = std::max(1u, std::min<unsigned>(options.threads ? options.threads : std::thread::hardware_concurrency(),
                                                     static_cast<unsigned>(std::max<std::size_t>(1, todo->size()))));
  std::mutex mu;
  std::condition_variable cv;
  std::deque<TaskRecord> finished;
  std::atomic<std::size_t> next{0};
  std::atomic<bool> abort{false};
  unsigned running = T;
  std::vector<std::thread> pool;
  for (unsigned w = 0; w < T; ++w) {
    pool.emplace_back([&, w] {
      const std::string name = fmt::format("thread {}", w);
      if (options.pin_threads) pin_to_cpu(w);
      for (;;) {
        if (abort || (options.stop && options.stop->load())) break;
        const std::size_t i = next++;
        if (i >= todo->size()) break;
        TaskRecord r = execute(study.tasks[static_cast<std::size_t>((*todo)[i])], registry, name);
        std::lock_guard lk(mu);
        finished.push_back(std::move(r));
        cv.notify_one();
      }
      std::lock_guard lk(mu);
      --running;
      cv.notify_one();
    });
  }
  Progress pr;
  pr.total = c0->total;
  pr.done = c0->done;
  pr.to_run = static_cast<std::int64_t>(todo->size());
  if (options.progress) options.progress(pr);
  Error store_error;
  bool failed_store = false;
  for (;;) {
    std::unique_lock lk(mu);
    cv.wait(lk, [&] { return !finished.empty() || running == 0; });
    if (finished.empty() && running == 0) break;
    TaskRecord r = std::move(finished.front());
    finished.pop_front();
    lk.unlock();
    if (failed_store) continue;
    if (auto s = store.record(r); !s) {
      store_error = s.error();
      failed_store = true;
      abort = true;
      continue;
    }
    ++sum.ran;
    ++pr.this_run;
    if (r.status == TaskStatus::Done) ++pr.done;
    else ++sum.failed, ++pr.failed;
    pr.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (options.progress) options.progress(pr);
  }
  for (auto& t : pool) t.join();
  if (failed_store) return store_error;
  sum.interrupted = sum.ran < static_cast<std::int64_t>(todo->size());
  sum.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sum;
}

// ---------------------------------------------------------------- serialisation (for MPI)

namespace {
constexpr std::uint32_t kMagic = 0x46545231;  // "FTR1"
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
#endif

}  // namespace frictal::study
