// frictal CLI — the tilt movie (movie.hpp): each frame drawn with cairo (antialiased polygons,
// lines and text) on an image surface, written as raw RGB into ffmpeg's standard input.
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
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <cairo.h>
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
  double r, g, b;  // 0..1
};

void set_colour(cairo_t* cr, Rgb c) { cairo_set_source_rgb(cr, c.r, c.g, c.b); }

void polygon_path(cairo_t* cr, const std::vector<double>& x, const std::vector<double>& y) {
  cairo_new_path(cr);
  for (std::size_t i = 0; i < x.size(); ++i) cairo_line_to(cr, x[i], y[i]);
  cairo_close_path(cr);
}

void line(cairo_t* cr, double x0, double y0, double x1, double y1, Rgb c, double width) {
  set_colour(cr, c);
  cairo_set_line_width(cr, width);
  cairo_move_to(cr, x0, y0);
  cairo_line_to(cr, x1, y1);
  cairo_stroke(cr);
}

/// Text with its baseline at y, left edge at x; returns the x after it.
double text(cairo_t* cr, double x, double y, const std::string& s, Rgb c) {
  set_colour(cr, c);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, s.c_str());
  double cx = 0, cy = 0;
  cairo_get_current_point(cr, &cx, &cy);
  return cx;
}

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};

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
  // Text band at the top: two lines of labels and a legend; the font scales with the frame.
  const double font = gif ? 15 : 26, top = 3.6 * font;
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

  // The frame: a cairo image surface (32-bit xRGB), turned into the rgb24 rows ffmpeg reads.
  std::unique_ptr<cairo_surface_t, SurfaceDeleter> surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, W, H));
  std::unique_ptr<cairo_t, ContextDeleter> context(cairo_create(surface.get()));
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS ||
      cairo_status(context.get()) != CAIRO_STATUS_SUCCESS)
    throw UsageError(fmt::format("--movie: cairo cannot make a {} x {} image: {}", W, H,
                                 cairo_status_to_string(cairo_status(context.get()))),
                     ErrorCode::Internal);
  cairo_t* cr = context.get();
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, font);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(W) * H * 3);

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
  const Rgb lower_c{150 / 255.0, 150 / 255.0, 160 / 255.0}, upper_c{90 / 255.0, 140 / 255.0, 200 / 255.0},
      rim_c{40 / 255.0, 40 / 255.0, 40 / 255.0}, contact_c{220 / 255.0, 30 / 255.0, 30 / 255.0},
      tang_c{30 / 255.0, 160 / 255.0, 60 / 255.0}, text_c{0, 0, 0};
  const double deg = 180 / std::numbers::pi;
  const double line_width = gif ? 2 : 3;
  bool write_failed = false;
  for (const TiltFrame& f : r.frames) {
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    for (int b = 0; b < 2; ++b) {
      tilt_frame_polygon(r, f, b, x, y);
      rounded_outline(x, y, radius, 10 / deg, ox, oy);
      for (auto& v : ox) v = px(v);
      for (auto& v : oy) v = py(v);
      polygon_path(cr, ox, oy);
      set_colour(cr, rim_c);  // the rim shows where the rounded outline extends the core
      cairo_fill(cr);
      for (auto& v : x) v = px(v);
      for (auto& v : y) v = py(v);
      polygon_path(cr, x, y);
      set_colour(cr, b == 0 ? lower_c : upper_c);
      cairo_fill(cr);
    }
    for (const auto& c : f.contacts) {
      const double sx = px(c.point.x), sy = py(c.point.y);
      // Force on the upper block: the vertex body's force, reversed when the vertex is the lower's.
      const double sgn = c.vertex_body == 1 ? 1.0 : -1.0;
      const double fnx = sgn * c.normal_force * c.normal.x, fny = sgn * c.normal_force * c.normal.y;
      const double ftx = sgn * -c.tangential_force * c.normal.y, fty = sgn * c.tangential_force * c.normal.x;
      line(cr, sx, sy, sx + fnx * fscale, sy - fny * fscale, contact_c, line_width);
      line(cr, sx, sy, sx + ftx * fscale, sy - fty * fscale, tang_c, line_width);
      set_colour(cr, contact_c);
      cairo_new_path(cr);
      cairo_arc(cr, sx, sy, 1.5 * line_width, 0, 2 * std::numbers::pi);
      cairo_fill(cr);
    }
    // Labels: time, tilt and the force ratio with their units; the legend of the arrows.
    const double pad = 0.6 * font, line1 = pad + font, line2 = line1 + 1.4 * font;
    text(cr, pad, line1, fmt::format("t = {:.3f} s     tilt = {:.3f}\u00b0", f.time, f.tilt * deg), text_c);
    text(cr, pad, line2,
         fmt::format("atan(F\u209c / F\u2099) = {:.3f}\u00b0     contacts: {}",
                     std::atan2(f.tangential_force, f.normal_force) * deg, f.contacts.size()),
         text_c);
    cairo_text_extents_t ext{};
    const std::string normal_label = "normal force", tangential_label = "tangential force";
    cairo_text_extents(cr, tangential_label.c_str(), &ext);
    const double key = 1.6 * font, legend_x = W - pad - ext.x_advance - key - 0.4 * font;
    line(cr, legend_x, line1 - 0.35 * font, legend_x + key, line1 - 0.35 * font, contact_c, line_width);
    text(cr, legend_x + key + 0.4 * font, line1, normal_label, text_c);
    line(cr, legend_x, line2 - 0.35 * font, legend_x + key, line2 - 0.35 * font, tang_c, line_width);
    text(cr, legend_x + key + 0.4 * font, line2, tangential_label, text_c);
    cairo_surface_flush(surface.get());
    const unsigned char* data = cairo_image_surface_get_data(surface.get());
    const int stride = cairo_image_surface_get_stride(surface.get());
    for (int row = 0; row < H; ++row) {
      const auto* p = reinterpret_cast<const std::uint32_t*>(data + static_cast<std::size_t>(row) * stride);
      std::uint8_t* out = &rgb[static_cast<std::size_t>(row) * W * 3];
      for (int col = 0; col < W; ++col) {  // CAIRO_FORMAT_RGB24: 0xXXRRGGBB in native byte order
        out[3 * col] = static_cast<std::uint8_t>(p[col] >> 16);
        out[3 * col + 1] = static_cast<std::uint8_t>(p[col] >> 8);
        out[3 * col + 2] = static_cast<std::uint8_t>(p[col]);
      }
    }
    if (std::fwrite(rgb.data(), 1, rgb.size(), pipe) != rgb.size()) {
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
