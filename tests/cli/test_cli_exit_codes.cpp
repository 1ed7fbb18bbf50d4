// Exit codes come from one table (apps/frictal/command.hpp, docs/ARCHITECTURE.md): invalid input
// and I/O errors exit 2 in every command, an unstable simulation 1.
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
