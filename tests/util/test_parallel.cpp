// The library's parallel-for: fixed contiguous chunks, every item once, exceptions propagated.
#include <gtest/gtest.h>

#include <atomic>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "util/parallel.hpp"

using frictal::util::parallel_chunks;
using frictal::util::run_workers;
using frictal::util::thread_count;

TEST(Parallel, ChunksAreContiguousFixedAndCoverEveryItemOnce) {
  for (std::size_t n : {0u, 1u, 7u, 64u, 1000u}) {
    for (unsigned C = 1; C <= 8; ++C) {
      std::vector<int> hits(n, 0);
      std::vector<std::pair<std::size_t, std::size_t>> ranges(C);
      parallel_chunks(n, C, [&](unsigned c, std::size_t b, std::size_t e) {
        ranges[c] = {b, e};
        for (std::size_t i = b; i < e; ++i) ++hits[i];  // chunks are disjoint: no race
      });
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(hits[i], 1) << "n " << n << " chunks " << C;
      // Chunk c is [n c / C, n (c + 1) / C): the split depends on n and C only.
      for (unsigned c = 0; c < C; ++c) {
        EXPECT_EQ(ranges[c].first, n * c / C);
        EXPECT_EQ(ranges[c].second, n * (c + 1) / C);
      }
    }
  }
}

TEST(Parallel, ResultsCombinedInOrderDoNotDependOnThreads) {
  // A sum of terms whose floating-point result depends on the order: per-chunk partial sums
  // combined in chunk order equal the serial sum when the chunks are the same; written per item
  // and summed in item order they equal it for any number of threads.
  const std::size_t n = 10007;
  std::vector<double> ref(n);
  for (std::size_t i = 0; i < n; ++i) ref[i] = 1.0 / static_cast<double>(i + 1);
  double serial = 0;
  for (double v : ref) serial += v;
  for (unsigned T = 1; T <= 6; ++T) {
    std::vector<double> out(n);
    parallel_chunks(n, T, [&](unsigned, std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) out[i] = 1.0 / static_cast<double>(i + 1);
    });
    double s = 0;
    for (double v : out) s += v;
    EXPECT_EQ(s, serial) << T << " threads";
  }
}

TEST(Parallel, WorkersRunBesideTheCallerAndExceptionsPropagate) {
  std::atomic<int> ran{0};
  bool main_ran = false;
  run_workers(
      3, [&](unsigned) { ++ran; }, [&] { main_ran = true; });
  EXPECT_EQ(ran.load(), 3);
  EXPECT_TRUE(main_ran);
  EXPECT_THROW(parallel_chunks(100, 4,
                               [](unsigned c, std::size_t, std::size_t) {
                                 if (c == 2) throw std::runtime_error("chunk 2");
                               }),
               std::runtime_error);
  EXPECT_EQ(thread_count(3, 2), 2u);  // never more threads than items
  EXPECT_EQ(thread_count(3), 3u);
  EXPECT_GE(thread_count(0), 1u);
}
