// The coordinator of a study run (see coordinator.hpp): planning, executing one task, and the
// claim -> compute -> record cycle with its retry policy and progress, for both transports.
#include "study/coordinator.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include <fmt/core.h>

#include "study/cache.hpp"

namespace frictal::study {

Result<std::vector<std::int64_t>> plan(const Study& study, Store& store, const TaskRegistry& registry,
                                       const RunOptions& options, std::int64_t* skipped_unavailable) {
  std::set<std::string> wanted(options.parts.begin(), options.parts.end());
  for (const auto& w : wanted) {
    if (std::none_of(study.parts.begin(), study.parts.end(), [&](const Part& p) { return p.name == w; })) {
      std::string list;
      for (const auto& p : study.parts) list += (list.empty() ? "" : ", ") + p.name;
      return make_error(fmt::format("--part {}: study '{}' has no such part (parts: {})", w, study.name, list));
    }
  }
  for (const Part& p : study.parts) {
    if (!wanted.empty() && !wanted.count(p.name)) continue;
    const std::string why = registry.unavailable_reason(p.kind);
    if (!why.empty() && !options.skip_unavailable)
      return make_error(
          ErrorCode::NotAvailable,
          fmt::format("part '{}' of study '{}': {}; run the other parts with --skip-unavailable{}", p.name, study.name,
                      why, study.parts.size() > 1 ? " or choose parts with --part" : ""));
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
    r.code = ErrorCode::NotAvailable;
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
        r.code = out.error().code;
      }
    } catch (const std::exception& e) {  // e.g. std::bad_alloc: a failure of this task only
      r.status = TaskStatus::Failed;
      r.error = fmt::format("exception: {}", e.what());
      r.code = ErrorCode::Internal;
    }
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

bool retryable(ErrorCode code) { return code == ErrorCode::Io || code == ErrorCode::Internal; }

namespace {
/// The kind's cost model of a task (unit: s); 1 without a model or for a model that gives no
/// positive finite number (e.g. parameters the kind will refuse).
double model_cost(const Task& t, const TaskRegistry& registry) {
  const TaskKind* k = registry.find(t.kind);
  if (!k || !k->cost) return 1.0;
  double c = 1.0;
  try {
    c = k->cost(t.params);
  } catch (const std::exception&) {
    return 1.0;
  }
  return std::isfinite(c) && c > 0 ? c : 1.0;
}
}  // namespace

std::vector<PlannedTask> estimate_costs(const Study& study, Store& store, const TaskRegistry& registry,
                                        const std::vector<std::int64_t>& ids, ResultCache* cache) {
  const auto task = [&](std::int64_t id) -> const Task& { return study.tasks[static_cast<std::size_t>(id)]; };
  // Recorded times: the cache's (by kind and canonical parameters, any kind version) and this
  // store's (done tasks; a result taken from the cache has no time of its own, and a failure may
  // have stopped early).
  std::map<std::pair<std::string, std::string>, double> measured;
  if (cache)
    if (auto t = cache->timings(); t)
      for (const auto& e : *t) measured[{e.kind, e.params}] = e.wall_s;
  std::map<std::string, std::vector<double>> ratios;  // kind -> recorded time / model
  std::map<std::pair<std::string, std::string>, std::int64_t> by_params;
  for (const Task& t : study.tasks) by_params[{t.kind, canonical(t.params)}] = t.id;
  if (auto infos = store.tasks(); infos) {
    for (const auto& i : *infos) {
      if (i.status != TaskStatus::Done || !(i.wall_s > 0) || i.worker == "cache") continue;
      if (i.id < 0 || i.id >= static_cast<std::int64_t>(study.tasks.size())) continue;
      const Task& t = task(i.id);
      ratios[t.kind].push_back(i.wall_s / model_cost(t, registry));
    }
  }
  for (const auto& [key, wall] : measured)
    if (auto it = by_params.find(key); it != by_params.end())
      ratios[key.first].push_back(wall / model_cost(task(it->second), registry));
  std::map<std::string, double> scale;
  for (auto& [kind, r] : ratios) {
    std::sort(r.begin(), r.end());
    const std::size_t n = r.size();
    scale[kind] = n % 2 ? r[n / 2] : 0.5 * (r[n / 2 - 1] + r[n / 2]);
  }
  std::vector<PlannedTask> cost;
  cost.reserve(ids.size());
  for (const std::int64_t id : ids) {
    const Task& t = task(id);
    PlannedTask p;
    p.id = id;
    if (auto it = measured.find({t.kind, canonical(t.params)}); it != measured.end()) {
      p.estimated_s = it->second;
      p.measured = true;
    } else {
      const auto s = scale.find(t.kind);
      p.estimated_s = model_cost(t, registry) * (s == scale.end() ? 1.0 : s->second);
    }
    cost.push_back(p);
  }
  return cost;
}

void longest_first(std::vector<PlannedTask>& tasks) {
  std::stable_sort(tasks.begin(), tasks.end(),
                   [](const PlannedTask& a, const PlannedTask& b) { return a.estimated_s > b.estimated_s; });
}

Result<std::vector<PlannedTask>> schedule(const Study& study, Store& store, const TaskRegistry& registry,
                                          const RunOptions& options) {
  auto todo = plan(study, store, registry, options, nullptr);
  if (!todo) return todo.error();
  std::unique_ptr<ResultCache> cache;
  if (!options.cache.empty())
    if (auto c = ResultCache::open(options.cache); c) cache = std::move(*c);
  std::vector<PlannedTask> cached;
  std::vector<std::int64_t> left;
  for (const std::int64_t id : *todo) {
    const Task& t = study.tasks[static_cast<std::size_t>(id)];
    auto f = cache ? cache->find(content_address(t, registry), t)
                   : Result<std::optional<TaskOutput>>(std::optional<TaskOutput>{});
    if (f && f->has_value()) {
      PlannedTask p;
      p.id = id;
      p.cached = true;
      cached.push_back(p);
    } else {
      left.push_back(id);
    }
  }
  std::vector<PlannedTask> out = estimate_costs(study, store, registry, left, cache.get());
  if (options.longest_first) longest_first(out);
  cached.insert(cached.end(), out.begin(), out.end());
  return cached;
}

Coordinator::Coordinator(const Study& study, Store& store, const TaskRegistry& registry, const RunOptions& options,
                         std::vector<std::int64_t> todo, int sites)
    : study_(study),
      store_(store),
      registry_(registry),
      options_(options),
      sites_(std::max(1, sites)),
      start_(std::chrono::steady_clock::now()),
      to_run_(todo.size()),
      fail_first_(options.fail_first_attempt.begin(), options.fail_first_attempt.end()),
      queue_(todo.begin(), todo.end()) {}

Coordinator::~Coordinator() = default;

Status Coordinator::start() {
  if (options_.max_page_count > 0)
    if (auto s = store_.limit_pages(options_.max_page_count); !s) return s.error();
  last_heartbeat_ = std::chrono::steady_clock::now();
  auto c0 = store_.counts();
  if (!c0) return c0.error();
  progress_.total = c0->total;
  progress_.done = c0->done;
  progress_.to_run = static_cast<std::int64_t>(to_run_);
  if (!options_.cache.empty()) {
    if (auto c = ResultCache::open(options_.cache); c)
      cache_ = std::move(*c);
    else
      cache_note_ = fmt::format("result cache not used: {}", c.error().message);
  }
  // Tasks whose result the cache holds: recorded from it (worker "cache"), not computed.
  std::deque<std::int64_t> left;
  for (const std::int64_t id : queue_) {
    const Task& t = study_.tasks[static_cast<std::size_t>(id)];
    std::optional<TaskOutput> hit;
    if (cache_) {
      auto f = cache_->find(content_address(t, registry_), t);
      if (!f) {
        if (cache_note_.empty()) cache_note_ = fmt::format("result cache not read: {}", f.error().message);
      } else {
        hit = std::move(*f);
      }
    }
    if (!hit) {
      left.push_back(id);
      continue;
    }
    TaskRecord r;
    r.id = id;
    r.status = TaskStatus::Done;
    r.worker = "cache";
    r.output = std::move(*hit);
    if (auto s = store_.record(r); !s) return s.error();
    ++reused_;
    ++progress_.done;
    ++progress_.this_run;
    ++progress_.reused;
  }
  queue_ = std::move(left);
  if (options_.longest_first && !queue_.empty()) {
    std::vector<PlannedTask> order = estimate_costs(
        study_, store_, registry_, std::vector<std::int64_t>(queue_.begin(), queue_.end()), cache_.get());
    longest_first(order);
    queue_.clear();
    for (const PlannedTask& p : order) {
      queue_.push_back(p.id);
      cost_[p.id] = p.estimated_s;  // for next_cost (multi-study runs)
    }
  }
  progress_.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (options_.progress) options_.progress(progress_);
  return Ok{};
}

void Coordinator::poll_stop_locked() {
  if (!closing_ && options_.stop && options_.stop->load()) {
    closing_ = true;
    queue_.clear();
    busy_.clear();
    cv_.notify_all();
  }
}

void Coordinator::fail_store_locked(Error e) {
  if (!claim_failed_) {
    claim_failed_ = true;
    claim_error_ = std::move(e);
  }
  closing_ = true;
  queue_.clear();
  busy_.clear();
  cv_.notify_all();
}

std::int64_t Coordinator::take_locked(int site) {
  for (auto it = queue_.begin(); it != queue_.end(); ++it) {
    auto f = failed_on_.find(*it);
    // Not again on a site it failed on while another site has not failed it.
    if (f != failed_on_.end() && f->second.count(site) && static_cast<int>(f->second.size()) < sites_) continue;
    const std::int64_t id = *it;
    queue_.erase(it);
    ++in_flight_;
    return id;
  }
  return -1;
}

bool Coordinator::over_locked() const {
  return (closing_ || (queue_.empty() && busy_.empty() && waiting_ == 0)) && in_flight_ == 0 && finished_.empty();
}

std::int64_t Coordinator::claim(int site, bool wait) {
  std::unique_lock lk(mu_);
  for (;;) {
    poll_stop_locked();
    if (closing_) return -1;
    // Tasks held by other runs: look again once the queue is empty, every 250 ms.
    if (queue_.empty() && !busy_.empty() && std::chrono::steady_clock::now() >= recheck_) {
      queue_.insert(queue_.end(), busy_.begin(), busy_.end());
      busy_.clear();
      recheck_ = std::chrono::steady_clock::now() + std::chrono::milliseconds(250);
    }
    if (const std::int64_t id = take_locked(site); id >= 0) {
      if (attempts_.count(id)) return id;  // a retry: this run holds the claim already
      lk.unlock();
      auto c = store_.claim(id, options_.lease_s);
      lk.lock();
      if (!c) {
        --in_flight_;
        fail_store_locked(c.error());
        return -1;
      }
      if (*c == Store::Claim::Claimed || *c == Store::Claim::TakenOver) {
        if (*c == Store::Claim::TakenOver) ++taken_over_;
        if (resolve_claimed(id, lk)) return id;
        // Reused or waiting for another study's result. In a multi-study run the caller chooses
        // the next study again (the costliest head); else take the next task here.
        if (shared_ && !wait) return kClaimAgain;
        continue;
      }
      --in_flight_;
      if (*c == Store::Claim::Finished)
        ++done_elsewhere_;
      else
        busy_.push_back(id);
      cv_.notify_all();
      continue;
    }
    if (!wait || (queue_.empty() && in_flight_ == 0 && busy_.empty() && waiting_ == 0)) return -1;
    // Woken by finish() (a retry may be queued) or after a while to look at the stop flag.
    cv_.wait_for(lk, std::chrono::milliseconds(50));
  }
}

void Coordinator::finish(TaskRecord r, int site) {
  std::unique_lock lk(mu_);
  --in_flight_;
  const int attempt = ++attempts_[r.id];
  // Testing hooks (RunOptions): fault injection decided here, whichever worker computed.
  const bool inject = site == options_.inject_failure_rank || (attempt == 1 && fail_first_.count(r.id));
  if (inject) {
    r.status = TaskStatus::Failed;
    r.code = ErrorCode::Internal;
    r.error = fmt::format("fault injected on {} (attempt {})", r.worker, attempt);
    r.output = {};
  }
  if (r.status == TaskStatus::Failed) {
    failed_on_[r.id].insert(site);
    if (!closing_ && retryable(r.code) && attempt < kMaxAttempts) {
      queue_.push_back(r.id);
      ++retries_;
      cv_.notify_all();
      return;
    }
    if (attempt > 1) r.error += fmt::format(" (after {} attempts)", attempt);
  }
  r.attempts = attempt;
  // The final outcome of a task other studies may wait for: hand it to them (outside mu_).
  std::string address;
  TaskRecord copy;
  if (auto p = producing_.find(r.id); p != producing_.end()) {
    address = std::move(p->second);
    producing_.erase(p);
    copy = r;
  }
  finished_.push_back(std::move(r));
  cv_.notify_all();
  lk.unlock();
  if (!address.empty()) shared_->complete(address, copy);
}

bool Coordinator::resolve_claimed(std::int64_t id, std::unique_lock<std::mutex>& lk) {
  if (!cache_ && !shared_) return true;
  const Task& t = study_.tasks[static_cast<std::size_t>(id)];
  const std::string address = content_address(t, registry_);
  lk.unlock();
  // The cache again: another run or study may have added the result since start().
  std::optional<TaskOutput> hit;
  if (cache_) {
    std::lock_guard ck(cache_mu_);
    if (auto f = cache_->find(address, t); f)
      hit = std::move(*f);
    else if (cache_note_.empty())
      cache_note_ = fmt::format("result cache not read: {}", f.error().message);
  }
  SharedResults::Take take = SharedResults::Take::Compute;
  if (!hit && shared_) {
    TaskOutput out;
    take = shared_->take(address, this, id, &out);
    if (take == SharedResults::Take::Reuse) hit = std::move(out);
  }
  // Another process (a run of another study on this folder) may compute the address now: claim
  // it in the cache; while its owner lives, set the task aside and look again later.
  bool elsewhere = false;
  if (!hit && take == SharedResults::Take::Compute && cache_) {
    std::lock_guard ck(cache_mu_);
    auto c = cache_->claim(address, options_.lease_s);
    if (!c) {
      if (cache_note_.empty()) cache_note_ = fmt::format("result cache not claimed: {}", c.error().message);
    } else if (*c == ResultCache::Claim::Stored) {
      if (auto f = cache_->find(address, t); f && *f) hit = std::move(*f);  // else: compute it here
    } else if (*c == ResultCache::Claim::Busy) {
      elsewhere = true;
    }
  }
  if (elsewhere && shared_) {
    // Not computed here now: the studies of this run waiting on it take it up again.
    TaskRecord none;
    none.id = id;
    none.status = TaskStatus::Failed;
    shared_->complete(address, none);
  }
  lk.lock();
  if (elsewhere) {
    --in_flight_;
    busy_.push_back(id);
    cv_.notify_all();
    return false;
  }
  if (hit) {
    --in_flight_;
    TaskRecord r;
    r.id = id;
    r.status = TaskStatus::Done;
    r.worker = "cache";
    r.output = std::move(*hit);
    finished_.push_back(std::move(r));
    cv_.notify_all();
    return false;
  }
  if (take == SharedResults::Take::Wait) {
    --in_flight_;
    ++waiting_;
    cv_.notify_all();
    return false;
  }
  if (shared_) producing_[id] = address;
  return true;
}

double Coordinator::next_cost() {
  std::lock_guard lk(mu_);
  poll_stop_locked();
  if (closing_) return -1;
  if (queue_.empty()) return busy_.empty() ? -1.0 : 0.0;
  if (!options_.longest_first) return 0;
  const auto it = cost_.find(queue_.front());
  return it == cost_.end() ? 0.0 : it->second;
}

bool Coordinator::exhausted() {
  std::lock_guard lk(mu_);
  poll_stop_locked();
  return closing_ || (queue_.empty() && busy_.empty() && in_flight_ == 0 && waiting_ == 0);
}

void Coordinator::deliver(std::int64_t id, const TaskOutput& output) {
  std::lock_guard lk(mu_);
  --waiting_;
  TaskRecord r;
  r.id = id;
  r.status = TaskStatus::Done;
  r.worker = "cache";
  r.output = output;
  finished_.push_back(std::move(r));
  cv_.notify_all();
}

void Coordinator::requeue(std::int64_t id) {
  std::lock_guard lk(mu_);
  --waiting_;
  if (!closing_) queue_.push_front(id);
  cv_.notify_all();
}

SharedResults::Take SharedResults::take(const std::string& address, Coordinator* co, std::int64_t id, TaskOutput* out) {
  std::lock_guard lk(mu_);
  auto [it, fresh] = entries_.try_emplace(address);
  if (fresh) return Take::Compute;
  if (it->second.done) {
    *out = it->second.output;
    return Take::Reuse;
  }
  it->second.waiters.emplace_back(co, id);
  return Take::Wait;
}

void SharedResults::complete(const std::string& address, const TaskRecord& r) {
  std::vector<std::pair<Coordinator*, std::int64_t>> waiters;
  const bool done = r.status == TaskStatus::Done;
  {
    std::lock_guard lk(mu_);
    auto it = entries_.find(address);
    if (it == entries_.end()) return;
    waiters.swap(it->second.waiters);
    if (done) {
      it->second.done = true;
      it->second.output = r.output;
    } else {
      entries_.erase(it);  // the next take computes it again
    }
  }
  for (const auto& [co, id] : waiters) {
    if (done)
      co->deliver(id, r.output);
    else
      co->requeue(id);
  }
}

std::size_t Coordinator::record_finished(bool wait) {
  std::deque<TaskRecord> batch;
  {
    std::unique_lock lk(mu_);
    poll_stop_locked();
    if (wait && finished_.empty() && !over_locked())
      cv_.wait_for(lk, std::chrono::milliseconds(50), [&] { return !finished_.empty() || over_locked(); });
    batch.swap(finished_);
  }
  if (const auto now = std::chrono::steady_clock::now();
      now - last_heartbeat_ > std::chrono::duration<double>(options_.lease_s / 4)) {
    last_heartbeat_ = now;
    (void)store_.heartbeat();  // a store that cannot be written fails the next record or claim
    if (cache_) {
      std::lock_guard ck(cache_mu_);
      (void)cache_->heartbeat();
    }
  }
  std::size_t n = 0;
  {
    std::lock_guard lk(mu_);
    progress_.to_run = static_cast<std::int64_t>(to_run_) - done_elsewhere_;
  }
  for (TaskRecord& r : batch) {
    if (store_failed_) break;
    if (auto s = store_.record(r); !s) {
      store_failed_ = true;
      store_error_ = s.error();
      std::lock_guard lk(mu_);
      closing_ = true;
      queue_.clear();
      cv_.notify_all();
      break;
    }
    const bool reused = r.worker == "cache";  // found in the cache or computed by another study of this run
    if (reused) {
      ++reused_;
      ++progress_.reused;
    } else {
      ++ran_;
    }
    if (cache_ && !reused) {
      // A result for the cache; a failure gives up the claim (another run may try it).
      const Task& t = study_.tasks[static_cast<std::size_t>(r.id)];
      const TaskKind* k = registry_.find(t.kind);
      const std::string address = content_address(t, registry_);
      std::lock_guard ck(cache_mu_);
      if (auto s = r.status == TaskStatus::Done ? cache_->put(address, t, k ? k->uses_seed : true, r, study_.name)
                                                : cache_->release(address);
          !s && cache_note_.empty())
        cache_note_ = fmt::format("result cache not written: {}", s.error().message);
    }
    ++n;
    ++progress_.this_run;
    if (r.status == TaskStatus::Done)
      ++progress_.done;
    else
      ++failed_, ++progress_.failed;
    progress_.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (options_.progress) options_.progress(progress_);
  }
  if (n) {
    std::lock_guard lk(mu_);
    poll_stop_locked();  // the progress callback may have asked to stop
  }
  return n;
}

bool Coordinator::over() {
  std::lock_guard lk(mu_);
  poll_stop_locked();
  return over_locked();
}

bool Coordinator::closing() {
  std::lock_guard lk(mu_);
  return closing_;
}

Result<RunSummary> Coordinator::summary(RunSummary base) {
  (void)store_.release_claims();  // tasks left unrecorded (interrupted) are free for others at once
  if (cache_) {
    std::lock_guard ck(cache_mu_);
    (void)cache_->release_claims();
  }
  if (store_failed_) return store_error_;
  std::lock_guard lk(mu_);
  if (claim_failed_) return claim_error_;
  base.ran = ran_;
  base.failed = failed_;
  base.retries = retries_;
  base.done_elsewhere = done_elsewhere_;
  base.taken_over = taken_over_;
  base.reused = reused_;
  {
    std::lock_guard ck(cache_mu_);
    base.cache_note = cache_note_;
  }
  base.interrupted = ran_ + done_elsewhere_ + reused_ < static_cast<std::int64_t>(to_run_);
  base.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  return base;
}

}  // namespace frictal::study
