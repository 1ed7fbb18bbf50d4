// Helpers shared by the study tests: fresh store paths and a store's run-independent content.
#pragma once

#include <cstdio>
#include <string>

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

}  // namespace study_test
