// The library's thread pool helper (see parallel.hpp): the only place that starts threads.
#include "util/parallel.hpp"

#include <algorithm>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace frictal::util {

using Thread = std::thread;

unsigned thread_count(unsigned requested, std::size_t items) {
  unsigned t = requested ? requested : std::max(1u, Thread::hardware_concurrency());
  if (items > 0 && t > items) t = static_cast<unsigned>(items);
  return std::max(1u, t);
}

void run_workers(unsigned workers, const std::function<void(unsigned)>& worker, const std::function<void()>& main) {
  std::mutex mu;
  std::exception_ptr first;
  auto guarded = [&](const std::function<void()>& f) {
    try {
      f();
    } catch (...) {
      std::lock_guard lk(mu);
      if (!first) first = std::current_exception();
    }
  };
  std::vector<Thread> pool;
  pool.reserve(workers);
  for (unsigned w = 0; w < workers; ++w) pool.emplace_back([&, w] { guarded([&] { worker(w); }); });
  if (main) guarded(main);
  for (auto& t : pool) t.join();
  if (first) std::rethrow_exception(first);
}

void parallel_chunks(std::size_t n, unsigned chunks,
                     const std::function<void(unsigned, std::size_t, std::size_t)>& body) {
  const unsigned C = std::max(1u, chunks);
  auto range = [&](unsigned c) { body(c, n * c / C, n * (c + 1) / C); };
  if (C == 1) {
    range(0);
    return;
  }
  run_workers(
      C - 1, [&](unsigned w) { range(w + 1); }, [&] { range(0); });
}

}  // namespace frictal::util
