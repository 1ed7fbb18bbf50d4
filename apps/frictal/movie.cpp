// frictal CLI — the tilt movie (movie.hpp): a small software rasteriser (filled polygons,
// lines, a 5 x 7 pixel font) writing raw RGB frames into ffmpeg's standard input.
#include "movie.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "command.hpp"

extern char** environ;

namespace frictal::cli {

std::string find_on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    std::size_t end = dirs.find(':', start);
    if (end == std::string::npos) end = dirs.size();
    std::string dir = dirs.substr(start, end - start);
    if (dir.empty()) dir = ".";
    const std::string candidate = dir + "/" + program;
    struct stat st {};
    if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(candidate.c_str(), X_OK) == 0)
      return candidate;
    start = end + 1;
  }
  return {};
}

void check_movie_tool(const std::string& path) {
  const bool gif = path.size() > 4 && path.compare(path.size() - 4, 4, ".gif") == 0;
  const bool mp4 = path.size() > 4 && path.compare(path.size() - 4, 4, ".mp4") == 0;
  if (!gif && !mp4) throw UsageError(fmt::format("--movie {}: expected a file name ending in .mp4 or .gif", path));
  if (find_on_path("ffmpeg").empty())
    throw UsageError(fmt::format("--movie {}: ffmpeg was not found on PATH; it renders the movie (Debian: "
                                 "apt-get install ffmpeg; scripts/install-deps installs it)",
                                 path),
                     ErrorCode::NotAvailable);
}

namespace {

struct Rgb {
  std::uint8_t r, g, b;
};

struct Image {
  int w, h;
  std::vector<std::uint8_t> px;
  Image(int w_, int h_) : w(w_), h(h_), px(static_cast<std::size_t>(w_) * h_ * 3, 255) {}
  void set(int x, int y, Rgb c) {
    if (x < 0 || y < 0 || x >= w || y >= h) return;
    std::uint8_t* p = &px[(static_cast<std::size_t>(y) * w + x) * 3];
    p[0] = c.r, p[1] = c.g, p[2] = c.b;
  }
  void fill(Rgb c) {
    for (std::size_t i = 0; i < px.size(); i += 3) px[i] = c.r, px[i + 1] = c.g, px[i + 2] = c.b;
  }
};

// Even-odd scanline fill of a polygon in pixel coordinates.
void fill_polygon(Image& im, const std::vector<double>& x, const std::vector<double>& y, Rgb c) {
  const std::size_t n = x.size();
  const auto [ylo, yhi] = std::minmax_element(y.begin(), y.end());
  const int y0 = std::max(0, static_cast<int>(std::floor(*ylo))), y1 = std::min(im.h - 1, static_cast<int>(*yhi));
  std::vector<double> xs;
  for (int row = y0; row <= y1; ++row) {
    const double yc = row + 0.5;
    xs.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t j = (i + 1) % n;
      if ((y[i] <= yc) != (y[j] <= yc)) xs.push_back(x[i] + (yc - y[i]) * (x[j] - x[i]) / (y[j] - y[i]));
    }
    std::sort(xs.begin(), xs.end());
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2)
      for (int col = std::max(0, static_cast<int>(std::ceil(xs[k] - 0.5)));
           col <= std::min(im.w - 1, static_cast<int>(std::floor(xs[k + 1] - 0.5))); ++col)
        im.set(col, row, c);
  }
}

void line(Image& im, double x0, double y0, double x1, double y1, Rgb c, int thick = 1) {
  const int steps = static_cast<int>(std::max(std::fabs(x1 - x0), std::fabs(y1 - y0))) + 1;
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    const int x = static_cast<int>(std::lround(x0 + t * (x1 - x0))),
              y = static_cast<int>(std::lround(y0 + t * (y1 - y0)));
    for (int dx = -(thick / 2); dx <= thick / 2; ++dx)
      for (int dy = -(thick / 2); dy <= thick / 2; ++dy) im.set(x + dx, y + dy, c);
  }
}

// 5 x 7 glyphs, one string of 7 rows of 5 characters per glyph ('#' = ink).
const std::map<char, const char*>& font() {
  static const std::map<char, const char*> f = {
      {'0', " ### #   ##  ### # ###  ##   # ### "},   {'1', "  #   ##    #    #    #    #   ### "},
      {'2', " ### #   #    #  ##  #    #    #####"},  {'3', "#####   #   #    ##     ##   # ### "},
      {'4', "   #   ##  # # #  # #####   #    # "},   {'5', "######    ####     #    ##   # ### "},
      {'6', "  ## #    #    #### #   ##   # ### "},   {'7', "#####    #   #   #   #    #    #   "},
      {'8', " ### #   ##   # ### #   ##   # ### "},   {'9', " ### #   ##   # ####    #   #  ##  "},
      {'.', "                         ##   ##   "},   {'-', "               ###               "},
      {'=', "          #####     #####          "},   {'(', "   #   #   #    #    #     #     # "},
      {')', " #     #     #    #    #   #   #   "},   {'/', "    #    #   #   #   #   #    #    "},
      {' ', "                                   "},   {'a', "           ###     # #####   # ####"},
      {'c', "           ### #    #    #   # ### "},   {'d', "    #    # ## ##  ##   ##   # ####"},
      {'e', "           ### #   #######     ### "},   {'F', "######    #    #### #    #    #    "},
      {'g', "      #####   ##   # ####    # ### "},   {'i', "  #         ##    #    #    #   ###"},
      {'l', " ##    #    #    #    #    #   ### "},   {'n', "          # ## ##  ##   ##   ##   #"},
      {'o', "           ### #   ##   ##   # ### "},   {'r', "          # ## ##  ##    #    #    "},
      {'s', "           #####     ###     ##### "},   {'t', "  #    #  #####  #    #    #  #  ## "},
      {'u', "          #   ##   ##   ##  ## ## #"},   {'m', "          ## # # # ## # ##   ##   #"},
      {'p', "          #### #   ######  #    #    "}, {'h', "#    #    # ## ##  ##   ##   ##   #"},
  };
  return f;
}

void text(Image& im, int x, int y, const std::string& s, int scale, Rgb c) {
  for (char ch : s) {
    auto it = font().find(ch);
    if (it != font().end()) {
      const std::string g = it->second;
      for (int row = 0; row < 7; ++row)
        for (int col = 0; col < 5; ++col) {
          const std::size_t k = static_cast<std::size_t>(row * 5 + col);
          if (k < g.size() && g[k] == '#')
            for (int a = 0; a < scale; ++a)
              for (int b = 0; b < scale; ++b) im.set(x + col * scale + a, y + row * scale + b, c);
        }
    }
    x += 6 * scale;
  }
}

}  // namespace

void write_tilt_movie(const std::string& path, const TiltResult& r, double radius, int fps) {
  if (r.frames.empty()) throw UsageError("--movie: the run has no frames");
  const bool gif = path.size() > 4 && path.substr(path.size() - 4) == ".gif";
  const bool mp4 = path.size() > 4 && path.substr(path.size() - 4) == ".mp4";
  if (!gif && !mp4) throw UsageError(fmt::format("--movie {}: expected a file name ending in .mp4 or .gif", path));
  const int W = gif ? 640 : 1280, H = gif ? 360 : 720;
  // One fixed view over every frame: bounding box of both blocks.
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  std::vector<double> x, y, ox, oy;
  for (const TiltFrame& f : r.frames)
    for (int b = 0; b < 2; ++b) {
      tilt_frame_polygon(r, f, b, x, y);
      x0 = std::min(x0, *std::min_element(x.begin(), x.end()));
      x1 = std::max(x1, *std::max_element(x.begin(), x.end()));
      y0 = std::min(y0, *std::min_element(y.begin(), y.end()));
      y1 = std::max(y1, *std::max_element(y.begin(), y.end()));
    }
  const double margin = 0.05 * std::max(x1 - x0, y1 - y0);
  x0 -= margin, x1 += margin, y0 -= margin, y1 += margin;
  const double top = 60;  // text band (pixels)
  const double scale = std::min(W / (x1 - x0), (H - top) / (y1 - y0));
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  auto px = [&](double wx) { return 0.5 * W + (wx - cx) * scale; };
  auto py = [&](double wy) { return top + 0.5 * (H - top) - (wy - cy) * scale; };
  // Force arrows (normal red, tangential green, on the upper block): the mean contact force is 4 % of H.
  double fsum = 0;
  std::size_t fn = 0;
  for (const TiltFrame& f : r.frames)
    for (const auto& c : f.contacts) fsum += std::hypot(c.normal_force, c.tangential_force), ++fn;
  const double fscale = fsum > 0 ? 0.04 * H / (fsum / static_cast<double>(fn)) : 0;  // mean force: 4 % of H

  // ffmpeg gets its arguments as a vector (no shell: any file name is safe) and the frames on a pipe.
  std::vector<std::string> args = {"ffmpeg",
                                   "-hide_banner",
                                   "-loglevel",
                                   "error",
                                   "-y",
                                   "-f",
                                   "rawvideo",
                                   "-pix_fmt",
                                   "rgb24",
                                   "-s",
                                   fmt::format("{}x{}", W, H),
                                   "-r",
                                   std::to_string(fps),
                                   "-i",
                                   "-"};
  if (gif) {
    args.insert(args.end(), {"-vf", "split[a][b];[a]palettegen[p];[b][p]paletteuse"});
  } else {
    args.insert(args.end(), {"-c:v", "libx264", "-pix_fmt", "yuv420p", "-crf", "20"});
  }
  args.push_back(path);
  const std::string ffmpeg = find_on_path("ffmpeg");
  if (ffmpeg.empty()) check_movie_tool(path);  // throws with the message that says what to install
  int fds[2];
  if (::pipe(fds) != 0) throw UsageError(fmt::format("--movie: pipe: {}", std::strerror(errno)), ErrorCode::Io);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, fds[0], STDIN_FILENO);
  posix_spawn_file_actions_addclose(&fa, fds[1]);
  posix_spawn_file_actions_addclose(&fa, fds[0]);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int sp = posix_spawn(&pid, ffmpeg.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  ::close(fds[0]);
  if (sp != 0) {
    ::close(fds[1]);
    throw UsageError(fmt::format("--movie: cannot start {}: {}", ffmpeg, std::strerror(sp)), ErrorCode::Io);
  }
  // A dying ffmpeg must not kill frictal with SIGPIPE: the write fails with EPIPE and is reported.
  struct sigaction ignore {
  }, previous{};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGPIPE, &ignore, &previous);
  std::FILE* pipe = ::fdopen(fds[1], "w");
  if (!pipe) {
    ::close(fds[1]);
    ::waitpid(pid, nullptr, 0);
    ::sigaction(SIGPIPE, &previous, nullptr);
    throw UsageError(fmt::format("--movie: fdopen: {}", std::strerror(errno)), ErrorCode::Io);
  }
  const Rgb lower_c{150, 150, 160}, upper_c{90, 140, 200}, rim_c{40, 40, 40}, contact_c{220, 30, 30},
      tang_c{30, 160, 60}, text_c{0, 0, 0};
  Image im(W, H);
  const double deg = 180 / std::numbers::pi;
  bool write_failed = false;
  for (const TiltFrame& f : r.frames) {
    im.fill({255, 255, 255});
    for (int b = 0; b < 2; ++b) {
      tilt_frame_polygon(r, f, b, x, y);
      rounded_outline(x, y, radius, 10 / deg, ox, oy);
      for (auto& v : ox) v = px(v);
      for (auto& v : oy) v = py(v);
      fill_polygon(im, ox, oy, rim_c);  // the rim shows where the rounded outline extends the core
      for (auto& v : x) v = px(v);
      for (auto& v : y) v = py(v);
      fill_polygon(im, x, y, b == 0 ? lower_c : upper_c);
    }
    for (const auto& c : f.contacts) {
      const double sx = px(c.point.x), sy = py(c.point.y);
      // Force on the upper block: the vertex body's force, reversed when the vertex is the lower's.
      const double sgn = c.vertex_body == 1 ? 1.0 : -1.0;
      const double fnx = sgn * c.normal_force * c.normal.x, fny = sgn * c.normal_force * c.normal.y;
      const double ftx = sgn * -c.tangential_force * c.normal.y, fty = sgn * c.tangential_force * c.normal.x;
      line(im, sx, sy, sx + fnx * fscale, sy - fny * fscale, contact_c, 2);
      line(im, sx, sy, sx + ftx * fscale, sy - fty * fscale, tang_c, 2);
      for (int a = -3; a <= 3; ++a)
        for (int b = -3; b <= 3; ++b)
          if (a * a + b * b <= 9) im.set(static_cast<int>(sx) + a, static_cast<int>(sy) + b, contact_c);
    }
    const int ts = gif ? 2 : 3;
    text(im, 10, 8, fmt::format("t = {:.3f} s   tilt = {:.3f} deg", f.time, f.tilt * deg), ts, text_c);
    text(im, 10, 8 + 9 * ts,
         fmt::format("atan(Ft/Fn) = {:.3f} deg   contacts {}", std::atan2(f.tangential_force, f.normal_force) * deg,
                     f.contacts.size()),
         ts, text_c);
    if (std::fwrite(im.px.data(), 1, im.px.size(), pipe) != im.px.size()) {
      write_failed = true;
      break;
    }
  }
  if (std::fclose(pipe) != 0) write_failed = true;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  ::sigaction(SIGPIPE, &previous, nullptr);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw UsageError(
        fmt::format("--movie {}: ffmpeg failed ({} {}){}", path, WIFEXITED(status) ? "exit status" : "signal",
                    WIFEXITED(status) ? WEXITSTATUS(status) : WTERMSIG(status),
                    write_failed ? "; the frames could not all be written" : ""),
        ErrorCode::Io);
  if (write_failed)
    throw UsageError(fmt::format("--movie {}: the frames could not all be written to ffmpeg", path), ErrorCode::Io);
}

}  // namespace frictal::cli
