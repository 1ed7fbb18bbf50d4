// A persistent team of worker threads for short, frequent parallel sections (the contact passes
// of one DEM step: a few microseconds each, millions of times per run), where starting threads
// per section (parallel.hpp) would cost more than the work. The caller runs member 0 itself;
// the workers wait for the next section spinning for up to 100 microseconds, then blocked (futex
// via std::atomic::wait), so an idle or oversubscribed team does not burn its cores for long.
//
// Determinism is the caller's business, as with parallel.hpp: give each member a fixed share of
// the work and combine the shares in member order.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

namespace frictal::util {

class Team {
 public:
  /// A team of `members` (>= 1): the calling thread of run() and members - 1 workers, started
  /// here. Throws std::system_error if a thread cannot be started (Team::make catches it).
  explicit Team(unsigned members);
  /// Stops and joins the workers.
  ~Team();
  Team(const Team&) = delete;
  Team& operator=(const Team&) = delete;
  /// A team of `members`, or nullptr if the threads cannot be started (the caller then runs
  /// serially).
  static std::unique_ptr<Team> make(unsigned members) noexcept;

  unsigned members() const { return static_cast<unsigned>(workers_.size()) + 1; }
  /// Runs job(context, j) for j = 0 .. n - 1 (n <= members()): j = 0 on the calling thread,
  /// the others on the workers; returns when all have returned. The job must not throw.
  void run(unsigned n, void (*job)(void* context, unsigned member), void* context);

 private:
  void work(unsigned member);

  std::vector<std::thread> workers_;
  // Section: written by run() before `generation_` is bumped (release), read after (acquire).
  unsigned n_ = 0;
  void (*job_)(void*, unsigned) = nullptr;
  void* context_ = nullptr;
  alignas(64) std::atomic<std::uint32_t> generation_{0};  ///< bumped to start a section
  alignas(64) std::atomic<std::uint32_t> pending_{0};     ///< workers yet to acknowledge this section
  alignas(64) std::atomic<std::uint32_t> sleepers_{0};    ///< workers blocked on generation_
  std::atomic<bool> caller_blocked_{false};               ///< run() blocked on pending_
  std::atomic<bool> stop_{false};
};

}  // namespace frictal::util
