// The idle cores of a study run (idle_threads.hpp): borrowed by its tasks, given back when they end.
#include "study/idle_threads.hpp"

#include <algorithm>

#include "frictal/study.hpp"

namespace frictal::study {

namespace {
thread_local detail::IdlePool* tl_pool = nullptr;
}

void detail::set_idle_pool(IdlePool* pool) { tl_pool = pool; }

unsigned borrow_idle_threads(unsigned want) {
  if (!tl_pool || want == 0) return 0;
  int cur = tl_pool->idle.load();
  while (cur > 0) {
    const int take = std::min(cur, static_cast<int>(std::min(want, 1024u)));
    if (tl_pool->idle.compare_exchange_weak(cur, cur - take)) return static_cast<unsigned>(take);
  }
  return 0;
}

void return_idle_threads(unsigned n) {
  if (tl_pool && n > 0) tl_pool->idle.fetch_add(static_cast<int>(n));
}

}  // namespace frictal::study
