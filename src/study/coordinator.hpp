// The study runner's coordinator: one place for claim -> compute -> record, the retry policy and
// progress, shared by both transports (threads: runner.cpp; MPI ranks: mpi_runner.cpp).
//
// Workers are grouped in *sites* (site 0: this process; under MPI site r is rank r). Any thread
// may claim a task for a site and hand back its outcome; the thread that owns the store (the
// caller of run_threads / rank 0's main thread) records final outcomes and reports progress.
//
// Retry policy: an attempt that fails with a transient error (ErrorCode::Io or Internal: out of
// memory, a lost file system, an injected fault) goes back into the queue, up to kMaxAttempts
// attempts; a retry is not given to a site the task already failed on while another site has not
// failed it. Deterministic failures (invalid input, unstable, not available) are recorded at once:
// the same task would fail the same way again.
//
// Shared stores: before a task is computed for the first time the coordinator claims it in the
// store (Store::claim). A task another live run holds is set aside and looked at again every
// 250 ms once the queue is empty, until that run records it (then it is skipped) or dies or its
// lease expires (then this run takes it over); so concurrent runs on one store share the work
// and each ends only when every task it set out to do is recorded by someone.
//
// Result cache, per task: besides start()'s bulk lookup, a task is looked up in the cache again
// right after it is claimed (claim()), so that a result another run or study added since this run
// started is reused rather than computed (recorded as reused, worker "cache"). Before computing,
// its content address is claimed in the cache (ResultCache::claim): an address another live
// process computes now is set aside like a task another run holds, and later found in the cache.
//
// Several studies, one pool (run_threads over StudyRun, SharedResults): one coordinator per study
// and store; the workers take the task with the largest estimate among the coordinators' queue
// heads (next_cost), and tasks of different studies with one content address are computed once:
// the first claim computes it, later claims wait (set aside, the worker takes another task) and
// are recorded as reused when it finishes.
//
// Order (start()): with RunOptions::longest_first the queue is sorted by decreasing estimated cost
// (TaskKind::cost, refined by recorded times: see estimate_costs), so that the longest tasks do
// not run last and alone. Result cache (RunOptions::cache): start() records every queued task
// whose content address the cache holds from the cache, and the owner adds every result it
// records. Neither changes any stored result: seeds come from the task, not the order.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <vector>

#include "frictal/study.hpp"

namespace frictal::study {

inline constexpr int kMaxAttempts = 3;

class ResultCache;

/// Estimated cost (unit: s) of each of `ids`: a time recorded in `cache` for the same kind and
/// parameters (any kind version) if there is one; else the kind's model (TaskKind::cost, 1 s
/// without one) times the kind's calibration, the median ratio of recorded time to model over
/// the tasks of that kind with a recorded time (done in `store`, or in the cache with
/// the parameters of a task of this study); 1 without any.
std::vector<PlannedTask> estimate_costs(const Study& study, Store& store, const TaskRegistry& registry,
                                        const std::vector<std::int64_t>& ids, ResultCache* cache);
/// Sorts by decreasing estimate, ties in the given order (stable).
void longest_first(std::vector<PlannedTask>& tasks);

/// True if a failure with this code may pass on another attempt.
bool retryable(ErrorCode code);

class Coordinator;

/// The in-process results of a multi-study run, by content address: which coordinator computes
/// an address now, and the outputs computed so far, so that no address is computed twice.
class SharedResults {
 public:
  enum class Take {
    Compute,  ///< nobody has it: the caller computes it (and calls complete() with its final outcome)
    Wait,     ///< another task computes it now: the caller is told through deliver() or requeue()
    Reuse,    ///< computed already: `*out` holds the output
  };
  Take take(const std::string& address, Coordinator* co, std::int64_t id, TaskOutput* out);
  /// The final outcome of a task take() said to compute: a done one is delivered to every waiter
  /// (and kept for later takes); after a failure the waiters compute it themselves (requeue).
  void complete(const std::string& address, const TaskRecord& r);

 private:
  struct Entry {
    bool done = false;
    TaskOutput output;
    std::vector<std::pair<Coordinator*, std::int64_t>> waiters;
  };
  std::mutex mu_;
  std::map<std::string, Entry> entries_;
};

class Coordinator {
 public:
  /// `todo`: the tasks to run, from plan(); `sites`: 1 for threads, the number of ranks under MPI.
  Coordinator(const Study& study, Store& store, const TaskRegistry& registry, const RunOptions& options,
              std::vector<std::int64_t> todo, int sites);
  ~Coordinator();

  /// Multi-study runs: the shared in-process results (before start(); null: none).
  void set_shared(SharedResults* shared) { shared_ = shared; }

  /// Owner: reads the store's counts, records the tasks the result cache holds, orders the queue
  /// and reports the initial progress.
  Status start();

  /// What claim() returns in a multi-study run (set_shared, without `wait`) when the task it
  /// took needed no computing (reused, or waiting for another study's result): ask again.
  static constexpr std::int64_t kClaimAgain = -2;
  /// Any thread: a task for `site`, or -1 (or kClaimAgain). With `wait`, blocks until one is available and returns
  /// -1 only when the run is over (or stopping); without, returns -1 when none is available now.
  std::int64_t claim(int site, bool wait);
  /// Any thread: the outcome of an attempt at a claimed task, computed on `site`. A retryable
  /// failure is queued again; anything else waits for the owner to record it.
  void finish(TaskRecord r, int site);

  /// Owner: records the outcomes handed back so far (waiting briefly for one if `wait`) and
  /// reports progress; returns how many were recorded.
  std::size_t record_finished(bool wait);
  /// True when nothing is queued (or the run is stopping), nothing is computing and every
  /// outcome is recorded.
  bool over();
  /// True once the run stops dispatching (interrupted or a store error).
  bool closing();

  /// Multi-study runs. The estimated cost (unit: s) of the task claim() would try next: 0 when only
  /// tasks held by other runs remain (without longest_first: 0 for any), -1 when none is queued.
  double next_cost();
  /// True when this coordinator can give no more work: nothing queued, held elsewhere, computing
  /// or waiting for another study's result (or the run is stopping).
  bool exhausted();
  /// A result another coordinator computed for task `id`, which waits for it (SharedResults).
  void deliver(std::int64_t id, const TaskOutput& output);
  /// The task another coordinator failed to compute: this run computes it itself.
  void requeue(std::int64_t id);

  /// The summary of the run, or the store's error if recording failed.
  Result<RunSummary> summary(RunSummary base);

 private:
  std::int64_t take_locked(int site);
  /// After the store claim: the result cache's and the shared results' answer for a claimed task.
  /// True if the task needs computing by the caller; false if it was handled (reused or waiting).
  bool resolve_claimed(std::int64_t id, std::unique_lock<std::mutex>& lk);
  bool over_locked() const;
  void poll_stop_locked();
  void fail_store_locked(Error e);

  const Study& study_;
  Store& store_;
  const TaskRegistry& registry_;
  const RunOptions& options_;
  const int sites_;
  const std::chrono::steady_clock::time_point start_;
  const std::size_t to_run_;
  std::set<std::int64_t> fail_first_;

  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<std::int64_t> queue_;
  std::deque<TaskRecord> finished_;
  std::map<std::int64_t, int> attempts_;
  std::map<std::int64_t, std::set<int>> failed_on_;
  std::int64_t in_flight_ = 0;
  bool closing_ = false;
  // Shared stores (under mu_): tasks another live run holds, when to look at them again, and
  // what the claims found.
  std::vector<std::int64_t> busy_;
  std::chrono::steady_clock::time_point recheck_{};
  std::int64_t done_elsewhere_ = 0, taken_over_ = 0;
  bool claim_failed_ = false;
  Error claim_error_;
  // Multi-study runs (under mu_): tasks waiting for another study's result, the addresses this
  // run computes for SharedResults, and the estimated costs of the queued tasks.
  SharedResults* shared_ = nullptr;
  std::int64_t waiting_ = 0;
  std::map<std::int64_t, std::string> producing_;
  std::map<std::int64_t, double> cost_;

  // The result cache: opened by start(); used by the owner (put) and by claim() (find).
  std::mutex cache_mu_;

  std::unique_ptr<ResultCache> cache_;
  // Owner only.
  std::string cache_note_;
  std::int64_t reused_ = 0;
  Progress progress_;
  std::int64_t ran_ = 0, failed_ = 0, retries_ = 0;
  bool store_failed_ = false;
  Error store_error_;
  std::chrono::steady_clock::time_point last_heartbeat_{};
};

}  // namespace frictal::study
