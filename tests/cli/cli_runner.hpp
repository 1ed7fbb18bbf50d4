// Runs the frictal executable for CLI tests.
#pragma once

#include <sys/wait.h>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

struct CliRun {
  int code = -1;
  std::string out, err;
};

// A file of the current test: ctest runs the tests side by side as separate processes, and a
// helper that writes a fixed name for several tests would rewrite a file another test is reading
// (a reader that maps the file then sees it truncated).
inline std::string temp_path(const std::string& name) {
  const auto* t = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string tag = t ? std::string(t->test_suite_name()) + "." + t->name() + "_" : std::string();
  for (char& c : tag)
    if (c == '/') c = '_';  // parameterised tests' names
  return ::testing::TempDir() + "frictal_" + tag + name;
}

inline void write_file(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
}

inline std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

/// Runs `frictal ARGS`, capturing stdout and stderr; with `timeout_s` > 0 under coreutils'
/// `timeout` (exit 124 when the command ran past it, e.g. blocked on a FIFO).
/// `env`: assignments put before the command (e.g. "PATH=/nonexistent").
inline CliRun run_cli(const std::string& args, int timeout_s = 0, const std::string& env = "") {
  static int counter = 0;
  const std::string err_path = temp_path("stderr_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
  const std::string cmd = (env.empty() ? std::string() : "env " + env + " ") +
                          (timeout_s > 0 ? "timeout -k 5 " + std::to_string(timeout_s) + " " : std::string()) +
                          std::string(FRICTAL_CLI_PATH) + " " + args + " 2>" + err_path;
  CliRun r;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int status = ::pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.err = read_file(err_path);
  std::remove(err_path.c_str());
  return r;
}
