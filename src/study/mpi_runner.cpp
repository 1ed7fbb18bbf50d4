// Running a study over MPI ranks (compiled only with FRICTAL_MPI). Rank 0 owns the store and
// hands out task ids one at a time as ranks ask for work (dynamic load balancing); it also runs
// `threads` local compute threads. Only rank 0's main thread calls MPI (MPI_THREAD_FUNNELED).
//
// Failures: a task that fails on a rank (error or exception, e.g. out of memory there) goes back
// into the queue and is reassigned to a rank it has not failed on, up to kMaxAttempts attempts
// (or until every rank has failed it), before it is recorded as failed. A rank
// that dies outright makes mpirun abort the job (standard MPI has no recovery from process
// loss); the store keeps every finished task and rerunning the command resumes the rest.
#ifdef FRICTAL_MPI
#include <mpi.h>

#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <deque>
#include <map>
#include <mutex>
#include <set>
#include <algorithm>
#include <thread>

#include <fmt/core.h>

#include "frictal/study.hpp"

namespace frictal::study {
namespace {
constexpr int kTagReady = 1, kTagResult = 2, kTagTask = 3, kTagStop = 4;
constexpr int kMaxAttempts = 3;

std::string recv_bytes(int source, int tag, MPI_Status* st) {
  MPI_Status probe;
  MPI_Probe(source, tag, MPI_COMM_WORLD, &probe);
  int n = 0;
  MPI_Get_count(&probe, MPI_BYTE, &n);
  std::string buf(static_cast<std::size_t>(n), '\0');
  MPI_Recv(buf.data(), n, MPI_BYTE, probe.MPI_SOURCE, probe.MPI_TAG, MPI_COMM_WORLD, st);
  return buf;
}
}  // namespace

static TaskRecord injected_failure(std::int64_t id, const std::string& worker) {
  TaskRecord r;
  r.id = id;
  r.status = TaskStatus::Failed;
  r.error = fmt::format("fault injected on {}", worker);
  r.worker = worker;
  return r;
}

bool mpi_available() { return true; }

bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(v)) return true;
  return false;
}

Status mpi_init(int* rank, int* size) {
  int provided = 0;
  if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    return make_error("MPI_Init_thread failed");
  if (provided < MPI_THREAD_FUNNELED) return make_error("the MPI library does not provide MPI_THREAD_FUNNELED");
  MPI_Comm_rank(MPI_COMM_WORLD, rank);
  MPI_Comm_size(MPI_COMM_WORLD, size);
  return Ok{};
}

void mpi_finalize() {
  int fin = 0;
  MPI_Finalized(&fin);
  if (!fin) MPI_Finalize();
}

Result<RunSummary> run_mpi(const Study& study, Store* store, const TaskRegistry& registry, const RunOptions& options) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const auto start = std::chrono::steady_clock::now();
  RunSummary sum;

  if (rank != 0) {  // worker: ask, compute, answer, until told to stop
    const std::string me = fmt::format("rank {}", rank);
    MPI_Send(nullptr, 0, MPI_BYTE, 0, kTagReady, MPI_COMM_WORLD);
    for (;;) {
      MPI_Status st;
      MPI_Probe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &st);
      if (st.MPI_TAG == kTagStop) {
        MPI_Recv(nullptr, 0, MPI_BYTE, 0, kTagStop, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        break;
      }
      long long id = -1;
      MPI_Recv(&id, 1, MPI_LONG_LONG, 0, kTagTask, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      TaskRecord r;
      if (id < 0 || id >= static_cast<long long>(study.tasks.size())) {
        r.id = id;
        r.status = TaskStatus::Failed;
        r.error = fmt::format("{}: task id {} is not in this rank's study (different study file?)", me, id);
      } else if (options.inject_failure_rank == rank) {
        r = injected_failure(id, me);
      } else {
        r = execute(study.tasks[static_cast<std::size_t>(id)], registry, me);
      }
      const std::string bytes = serialize(r);
      MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, 0, kTagResult, MPI_COMM_WORLD);
      ++sum.ran;
    }
    sum.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return sum;
  }

  // Rank 0. On a planning error, still release the workers before returning.
  auto release_all = [&](std::set<int>& stopped) {
    for (int r = 1; r < size; ++r) {
      if (stopped.count(r)) continue;
      // Each worker sends READY or RESULT before waiting; answer its last message with STOP.
      MPI_Status st;
      std::string b = recv_bytes(r, MPI_ANY_TAG, &st);
      (void)b;
      MPI_Send(nullptr, 0, MPI_BYTE, r, kTagStop, MPI_COMM_WORLD);
      stopped.insert(r);
    }
  };
  std::set<int> stopped;
  if (!store) {
    release_all(stopped);
    return make_error("run_mpi: rank 0 needs the store");
  }
  auto todo = plan(study, *store, registry, options, &sum.skipped_unavailable);
  auto c0 = todo ? store->counts() : Result<StoreCounts>(make_error(""));
  if (!todo || !c0) {
    release_all(stopped);
    return todo ? c0.error() : todo.error();
  }

  std::mutex mu;
  std::condition_variable cv;
  std::deque<std::int64_t> queue(todo->begin(), todo->end());
  std::deque<TaskRecord> local_done;
  std::map<std::int64_t, int> attempts;
  std::map<std::int64_t, std::set<int>> failed_on;  // task -> ranks it failed on
  // Takes the first queued task that has not failed on `who` (caller holds mu); -1 if none.
  auto take_for = [&](int who) -> std::int64_t {
    for (auto it = queue.begin(); it != queue.end(); ++it) {
      auto f = failed_on.find(*it);
      if (f != failed_on.end() && f->second.count(who)) continue;
      const std::int64_t id = *it;
      queue.erase(it);
      return id;
    }
    return -1;
  };
  auto has_for = [&](int who) {
    return std::any_of(queue.begin(), queue.end(), [&](std::int64_t id) {
      auto f = failed_on.find(id);
      return f == failed_on.end() || !f->second.count(who);
    });
  };
  bool closing = false;  // no more dispatch (interrupted or store error)
  int local_busy = 0;
  const unsigned T = options.threads ? options.threads : 1;
  std::vector<std::thread> pool;
  for (unsigned w = 0; w < T; ++w) {
    pool.emplace_back([&, w] {
      const std::string me = fmt::format("rank 0 thread {}", w);
      for (;;) {
        std::int64_t id;
        {
          std::unique_lock lk(mu);
          cv.wait(lk, [&] { return closing || has_for(0); });
          if (closing) return;
          id = take_for(0);
          ++local_busy;
        }
        TaskRecord r = options.inject_failure_rank == 0
                           ? injected_failure(id, me)
                           : execute(study.tasks[static_cast<std::size_t>(id)], registry, me);
        std::lock_guard lk(mu);
        local_done.push_back(std::move(r));
        --local_busy;
      }
    });
  }

  Progress pr;
  pr.total = c0->total;
  pr.done = c0->done;
  pr.to_run = static_cast<std::int64_t>(todo->size());
  if (options.progress) options.progress(pr);
  std::set<int> idle;             // workers waiting for a task
  std::map<int, std::int64_t> inflight;  // worker -> task
  Error store_error;
  bool failed_store = false;

  // Records a final outcome, or puts a failed task back for another rank.
  auto handle = [&](TaskRecord r, int on_rank) {
    if (r.status == TaskStatus::Failed && !failed_store) {
      std::lock_guard lk(mu);
      auto& ranks = failed_on[r.id];
      ranks.insert(on_rank);
      if (!closing && ++attempts[r.id] < kMaxAttempts && static_cast<int>(ranks.size()) < size) {
        queue.push_back(r.id);
        cv.notify_all();
        return;
      }
    }
    if (failed_store) return;
    {
      std::lock_guard lk(mu);
      auto f = failed_on.find(r.id);
      r.attempts = 1 + (f == failed_on.end() ? 0 : static_cast<int>(f->second.size()) - (r.status == TaskStatus::Failed));
      if (r.status == TaskStatus::Failed && f != failed_on.end())
        r.error += fmt::format(" (failed on {} rank(s))", f->second.size());
    }
    if (auto s = store->record(r); !s) {
      store_error = s.error();
      failed_store = true;
      std::lock_guard lk(mu);
      closing = true;
      cv.notify_all();
      return;
    }
    ++sum.ran;
    ++pr.this_run;
    if (r.status == TaskStatus::Done) ++pr.done;
    else ++sum.failed, ++pr.failed;
    pr.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (options.progress) options.progress(pr);
  };

  for (;;) {
    bool busy = false;
    if (options.stop && options.stop->load()) {
      std::lock_guard lk(mu);
      if (!closing) {
        closing = true;
        queue.clear();
        cv.notify_all();
      }
    }
    // Local results.
    std::deque<TaskRecord> mine;
    {
      std::lock_guard lk(mu);
      mine.swap(local_done);
    }
    for (auto& r : mine) {
      busy = true;
      handle(std::move(r), 0);
    }
    // Remote messages.
    int flag = 0;
    MPI_Status st;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
    if (flag) {
      busy = true;
      const int src = st.MPI_SOURCE;
      std::string bytes = recv_bytes(src, st.MPI_TAG, &st);
      if (st.MPI_TAG == kTagResult) {
        inflight.erase(src);
        auto r = deserialize(bytes);
        if (r) handle(std::move(*r), src);
      }
      idle.insert(src);
    }
    // Dispatch to idle workers (a worker stays idle if every queued task failed on it).
    for (auto it = idle.begin(); it != idle.end();) {
      const int w = *it;
      std::int64_t id;
      {
        std::lock_guard lk(mu);
        if (closing) break;
        id = take_for(w);
      }
      if (id < 0) {
        ++it;
        continue;
      }
      it = idle.erase(it);
      long long v = id;
      MPI_Send(&v, 1, MPI_LONG_LONG, w, kTagTask, MPI_COMM_WORLD);
      inflight[w] = id;
      busy = true;
    }
    bool finished;
    {
      std::lock_guard lk(mu);
      finished = (closing || queue.empty()) && local_busy == 0 && local_done.empty() && inflight.empty();
      if (finished) {
        closing = true;  // lets local threads exit
        cv.notify_all();
      }
    }
    if (finished) break;
    if (!busy) std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  for (auto& t : pool) t.join();
  {  // results that raced with the end (none expected, but never drop one)
    std::deque<TaskRecord> mine;
    mine.swap(local_done);
    for (auto& r : mine) handle(std::move(r), 0);
  }
  // Stop every worker: idle ones now, the others after their next message.
  for (int w : idle) {
    MPI_Send(nullptr, 0, MPI_BYTE, w, kTagStop, MPI_COMM_WORLD);
    stopped.insert(w);
  }
  release_all(stopped);
  if (failed_store) return store_error;
  sum.interrupted = pr.this_run < static_cast<std::int64_t>(todo->size());
  sum.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sum;
}

}  // namespace frictal::study
#endif  // FRICTAL_MPI
