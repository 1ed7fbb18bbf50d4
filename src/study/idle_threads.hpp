// Private: the cores a study run leaves idle, lent to its running tasks (borrow_idle_threads in
// frictal/study.hpp). A runner makes one pool per run, installs it on each compute thread, and
// counts a compute thread idle while it waits for a task; a task on a compute thread borrows from
// that thread's pool. Results never depend on it: a borrower (the tilt kinds) only splits work
// whose result does not depend on the thread count.
#pragma once

#include <atomic>

namespace frictal::study::detail {

struct IdlePool {
  /// Idle cores not lent; may go negative for a while when a compute thread that had been
  /// counted idle gets a task (a retry) while its core is lent: the borrower keeps it until its
  /// task ends.
  std::atomic<int> idle{0};
  /// A compute thread waits for work (its core is idle) / has work again.
  void lend() { idle.fetch_add(1); }
  void reclaim() { idle.fetch_sub(1); }
};

/// Installs `pool` (nullptr: none) for the tasks that the calling thread runs.
void set_idle_pool(IdlePool* pool);

}  // namespace frictal::study::detail
