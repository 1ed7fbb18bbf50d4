// The library's one way to run work on several threads. Deterministic in the number of
// threads: work is split into fixed contiguous chunks [n*c/C, n*(c+1)/C) whose results the caller
// writes per item (or per chunk) and combines in order, so results never depend on how many
// threads ran or how they were scheduled.
#pragma once

#include <cstddef>
#include <functional>

namespace frictal::util {

/// Threads to use for `requested` (0 = every hardware thread), at least 1 and at most `items`
/// (when `items` > 0).
unsigned thread_count(unsigned requested, std::size_t items = 0);

/// Runs `worker(w)` for w = 0..workers-1, each on its own thread, while the calling thread runs
/// `main` (if given); returns when all have returned. An exception thrown by any of them is
/// rethrown here (the first one) after every thread has finished.
void run_workers(unsigned workers, const std::function<void(unsigned)>& worker, const std::function<void()>& main = {});

/// Splits [0, n) into `chunks` contiguous chunks (chunk c is [n*c/chunks, n*(c+1)/chunks)) and
/// runs `body(c, begin, end)` for each, one chunk per thread (chunk 0 on the calling thread).
/// With chunks <= 1 everything runs on the calling thread.
void parallel_chunks(std::size_t n, unsigned chunks,
                     const std::function<void(unsigned chunk, std::size_t begin, std::size_t end)>& body);

}  // namespace frictal::util
