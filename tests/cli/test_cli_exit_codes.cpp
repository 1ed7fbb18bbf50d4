// Exit codes come from one table (apps/frictal/command.hpp, docs/ARCHITECTURE.md): invalid input
// and I/O errors exit 2 in every command, an unstable simulation 1.
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "cli/cli_runner.hpp"

namespace {
std::string fmt_double(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}
}  // namespace

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

// Numbers at the edges through `frictal stats`: each case gives the correct answer or exits 2
// with a message. Expected values by hand (see each comment).
TEST(CliExitCodes, EdgeProfilesAndMapsGiveTheRightNumberOrExitTwo) {
  auto file = [](const std::string& name, const std::string& text) {
    const std::string p = temp_path(name);
    write_file(p, text);
    return p;
  };
  auto json_number = [](const std::string& out, const std::string& key) {
    const auto at = out.find("\"" + key + "\":");
    return at == std::string::npos ? std::nan("") : std::stod(out.substr(at + key.size() + 3));
  };
  // Constant profile: rms height and slope 0, mean 3 m (the heights as read: --detrend none).
  auto r = run_cli("stats --json --detrend none --unit m " + file("edge_const.csv", "x,z\n0,3\n1,3\n2,3\n"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(json_number(r.out, "rms_height_m"), 0.0);
  EXPECT_EQ(json_number(r.out, "rms_slope"), 0.0);
  EXPECT_EQ(json_number(r.out, "mean_height_m"), 3.0);
  // Two points (0, 0), (2, 1): one edge of slope 1/2; rms about the mean of a linear ramp of
  // rise 1 is 1/sqrt(12).
  r = run_cli("stats --json --detrend none --unit m " + file("edge_two.csv", "x,z\n0,0\n2,1\n"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NEAR(json_number(r.out, "rms_height_m"), 1 / std::sqrt(12.0), 1e-12);
  EXPECT_NEAR(json_number(r.out, "rms_slope"), 0.5, 1e-12);
  // One point: no profile.
  r = run_cli("stats --unit m " + file("edge_one.csv", "x,z\n0,0\n"));
  EXPECT_EQ(r.code, 2) << r.out;
  // One repeated x: zero length.
  r = run_cli("stats --unit m " + file("edge_samex.csv", "x,z\n1,0\n1,1\n1,2\n"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.err.find("zero length (all x equal)"), std::string::npos) << r.err;
  // x underflowing to subnormal metres (2e-310 nm = 2e-319 m): an error, not 1.99998e-319 m.
  r = run_cli("stats " + file("edge_under.csv", "x (nm),z (nm)\n0,0\n1e-310,1\n2e-310,0\n"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.err.find("below the smallest normal double"), std::string::npos) << r.err;
  // x spanning beyond double: an error naming the range.
  r = run_cli("stats --unit m " + file("edge_over.csv", "x,z\n-1e308,0\n1e308,1\n"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.err.find("beyond the range of double"), std::string::npos) << r.err;
  // A spacing that overflows x (3 heights at 1e308 m: x = 2e308) or underflows.
  const std::string col = file("edge_col.csv", "z\n1\n2\n1\n");
  r = run_cli("stats --unit m --spacing 1e308 " + col);
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.err.find("not finite"), std::string::npos) << r.err;
  r = run_cli("stats --unit m --spacing 1e-320 " + col);
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.err.find("--spacing '1e-320' is beyond the range of double"), std::string::npos) << r.err;
  r = run_cli("stats --unit m --spacing 1e-305nm " + col);
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.err.find("beyond the range of double"), std::string::npos) << r.err;
  // Maps: a checkerboard +-1e300 on a 1 m grid has Sq = 1e300 and Sdq = 2 sqrt(2) 1e300
  // (StatsEdges in tests/stats derives them); +-1e-300 likewise, never inf or 0.
  for (double A : {1e300, 1e-300}) {
    const std::string a = fmt_double(A), b = fmt_double(-A);
    r = run_cli("stats --json --detrend none " +
                file("edge_map.txt", "# Width: 3 m\n# Height: 2 m\n# Value units: m\n" + a + " " + b + " " + a + "\n" +
                                         b + " " + a + " " + b + "\n"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NEAR(json_number(r.out, "Sq_m") / A, 1.0, 1e-12) << r.out;
    EXPECT_NEAR(json_number(r.out, "Sdq") / (2 * std::sqrt(2.0) * A), 1.0, 1e-12) << r.out;
    EXPECT_NEAR(json_number(r.out, "Sku"), 1.0, 1e-12) << r.out;
  }
  // A map whose spacing is subnormal (Width 3e-320 m over 3 columns).
  r = run_cli("stats " +
              file("edge_tiny.txt", "# Width: 3e-320 m\n# Height: 2e-320 m\n# Value units: m\n1 2 3\n4 5 6\n"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.err.find("below the smallest normal double"), std::string::npos) << r.err;
}

// tilt --movie: the name and ffmpeg are checked before the run (so that a missing ffmpeg cannot end
// the process with SIGPIPE after the whole simulation); with ffmpeg the GIF holds every frame.
TEST(CliExitCodes, TiltMovieNeedsAKnownExtensionAndFfmpegAndHoldsEveryFrame) {
  const std::string gif = temp_path("movie_k0.gif");
  std::remove(gif.c_str());
  auto r = run_cli("tilt koch -n 0 --alpha 5 --movie " + temp_path("movie.avi"));
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(".mp4 or .gif"), std::string::npos) << r.err;
  r = run_cli("tilt koch -n 0 --alpha 5 --movie " + gif, 0, "PATH=/nonexistent");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("ffmpeg was not found on PATH"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(gif));
  if (::access("/usr/bin/ffmpeg", X_OK) != 0 || ::access("/usr/bin/ffprobe", X_OK) != 0)
    GTEST_SKIP() << "ffmpeg/ffprobe not installed (scripts/install-deps installs them)";
  r = run_cli("tilt koch -n 0 --alpha 5 --movie " + gif);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string head = read_file(gif).substr(0, 6);
  EXPECT_EQ(head, "GIF89a");
  // The frame count the CLI reports against the count ffprobe decodes from the file.
  const auto at = r.err.find("frames)");
  ASSERT_NE(at, std::string::npos) << r.err;
  const auto open = r.err.rfind('(', at);
  const long reported = std::stol(r.err.substr(open + 1, at - open - 1));
  EXPECT_GT(reported, 10);
  const std::string count_path = temp_path("movie_frames.txt");
  const std::string probe =
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
      "-of csv=p=0 " +
      gif + " > " + count_path;
  ASSERT_EQ(std::system(probe.c_str()), 0);
  EXPECT_EQ(std::stol(read_file(count_path)), reported);
  // The first frame as ffmpeg decodes it (640 x 360 RGB): the labels (dark antialiased text) in
  // the band at the top, the blocks (grey lower, blue upper) below it, white around.
  const std::string raw_path = temp_path("movie_frame0.rgb");
  ASSERT_EQ(
      std::system(("ffmpeg -v error -y -i " + gif + " -vframes 1 -f rawvideo -pix_fmt rgb24 " + raw_path).c_str()), 0);
  const std::string px = read_file(raw_path);
  ASSERT_EQ(px.size(), 640u * 360u * 3u);
  auto near = [&](std::size_t i, int r, int g, int b) {
    return std::abs(std::uint8_t(px[3 * i]) - r) < 30 && std::abs(std::uint8_t(px[3 * i + 1]) - g) < 30 &&
           std::abs(std::uint8_t(px[3 * i + 2]) - b) < 30;
  };
  std::size_t text_dark = 0, text_white = 0, lower = 0, upper = 0;
  for (std::size_t i = 0; i < 640u * 360u; ++i) {
    const bool band = i / 640 < 50;  // the two label lines (font 15 px)
    if (band && near(i, 0, 0, 0)) ++text_dark;
    if (band && near(i, 255, 255, 255)) ++text_white;
    if (!band && near(i, 150, 150, 160)) ++lower;
    if (!band && near(i, 90, 140, 200)) ++upper;
  }
  EXPECT_GT(text_dark, 500u);             // "t = 0.000 s  tilt = ...", "atan(...) = ...", legend
  EXPECT_GT(text_white, 640u * 50u / 2);  // text, not a filled band
  EXPECT_GT(lower, 2000u);
  EXPECT_GT(upper, 2000u);
}
