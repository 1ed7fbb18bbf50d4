// Helpers shared by the study tests: fresh store paths and a store's run-independent content.
#pragma once

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "cli/cli_runner.hpp"
#include "frictal/study.hpp"

namespace study_test {

/// A temporary store path with no store (nor SQLite journal files) left at it.
inline std::string fresh(const std::string& name) {
  const std::string p = temp_path(name);
  for (const char* suffix : {"", "-wal", "-shm"}) std::remove((p + suffix).c_str());
  return p;
}

/// Stored content that does not depend on the run: no timings, worker or attempt counts.
inline std::string dump(const std::string& path) {
  auto st = frictal::study::Store::open_existing(path);
  EXPECT_TRUE(st.ok()) << (st.ok() ? "" : st.error().message);
  if (!st.ok()) return {};
  auto d = (*st)->content();
  EXPECT_TRUE(d.ok());
  return d.ok() ? *d : std::string{};
}

/// Waits (at most timeout_s, s) until `path` exists: a child `frictal study run` has set up its
/// signal handlers before it creates its store, so a test that interrupts it at a fixed delay
/// after this does not race the start-up of a loaded machine. False when it never appeared.
inline bool wait_for_file(const std::string& path, double timeout_s = 30) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  struct stat sb {};
  while (::stat(path.c_str(), &sb) != 0) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

/// The start of a command line that runs the CLI on `ranks` MPI ranks (append the CLI's path and
/// arguments). Open MPI leaks at exit by design: under the sanitizer preset ASan keeps its memory
/// checks but not LeakSanitizer (the leaks are all inside libmpi and its plugins).
inline std::string mpirun_prefix(int ranks) {
  return "ASAN_OPTIONS=detect_leaks=0 mpirun -x ASAN_OPTIONS -n " + std::to_string(ranks) + " --oversubscribe" +
         (::getuid() == 0 ? " --allow-run-as-root " : " ");
}

}  // namespace study_test
