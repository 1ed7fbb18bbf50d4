// Exit codes come from one table (apps/frictal/command.hpp, docs/ARCHITECTURE.md): invalid input
// and I/O errors exit 2 in every command, an unstable simulation 1.
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>

#include <gtest/gtest.h>

#include "cli/cli_runner.hpp"

TEST(CliExitCodes, TiltInputErrorsExitTwoAndAnUnstableRunExitsOne) {
  // A library error on invalid input (the block's density) is an input error like any other.
  auto r = run_cli("tilt koch -n 0 --alpha 20 --length 0.02 --density -1 --no-predict");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("density"), std::string::npos) << r.err;
  // gamma_n = 2e5 1/s puts the explicit stability limit (2 / damping rate) below a fixed explicit
  // step of 1e-5 s; with no step allowed beyond it the engine's guard stops the run.
  r = run_cli(
      "tilt koch -n 0 --alpha 20 --length 0.02 --normal-damping 2e5 --max-steps-beyond-limit 0 --no-predict "
      "--no-adaptive-time-step --no-implicit-damping --time-step 1e-5");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("stability"), std::string::npos) << r.err;
  // A missing file (I/O) exits 2, as in every command.
  r = run_cli("stats /nonexistent/frictal-profile.csv");
  EXPECT_EQ(r.code, 2) << r.err;
}

// Inputs that are no regular file: each command says what the path is and exits 2; a FIFO with
// no writer never blocks (checked with stat before anything opens it; `timeout` would exit 124).
TEST(CliExitCodes, DevNullADirectoryAndAFifoAreNamedAndExitTwo) {
  const std::string dir = temp_path("cli_input_dir");
  std::filesystem::create_directories(dir);
  const std::string fifo = temp_path("cli_input_fifo");
  ::unlink(fifo.c_str());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  struct Case {
    std::string args, what;
  };
  const Case cases[] = {
      {"stats /dev/null", "/dev/null: is a character device (/dev/null, which holds no data), expected a surface file"},
      {"info /dev/null", "/dev/null: is a character device"},
      {"stats " + dir, dir + ": is a directory, expected a surface file"},
      {"info " + dir, dir + ": is a directory, expected a surface file"},
      {"stats " + fifo, fifo + ": is a FIFO (named pipe), expected a surface file"},
      {"stats --format dektak " + fifo, fifo + ": is a FIFO (named pipe), expected a surface file"},
      {"info " + fifo, fifo + ": is a FIFO (named pipe), expected a surface file"},
      {"study run " + fifo + " --store " + temp_path("cli_kinds.sqlite"),
       fifo + ": is a FIFO (named pipe), expected a study file (TOML)"},
      {"study run " + dir + " --store " + temp_path("cli_kinds.sqlite"),
       dir + ": is a directory, expected a study file (TOML)"},
      {"study status " + fifo, fifo + ": is a FIFO (named pipe), expected a study store (SQLite file)"},
      {"study status " + dir, dir + ": is a directory, expected a study store (SQLite file)"},
      {"study status /dev/null", "/dev/null: is a character device"},
  };
  for (const Case& c : cases) {
    auto r = run_cli(c.args, 60);
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.what), std::string::npos) << c.args << "\n" << r.err;
  }
  ::unlink(fifo.c_str());
  std::filesystem::remove_all(dir);
}
