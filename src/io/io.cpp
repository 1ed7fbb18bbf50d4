// Entry points: file access with size limits, format detection, simple writers.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/core.h>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>

#include <sys/mman.h>

#include "frictal/io.hpp"
#include "io/readers.hpp"
#include "io/text_util.hpp"

namespace frictal {

const char* format_name(ProfileFormat f) {
  switch (f) {
    case ProfileFormat::Auto: return "auto";
    case ProfileFormat::Csv: return "csv";
    case ProfileFormat::Dektak: return "dektak";
    case ProfileFormat::Gwyddion: return "gwyddion";
    case ProfileFormat::X3p: return "x3p";
    case ProfileFormat::Matrix: return "matrix";
    case ProfileFormat::Xyz: return "xyz";
    case ProfileFormat::Sdf: return "sdf";
    case ProfileFormat::Npy: return "npy";
    case ProfileFormat::GwyddionLib: return "gwyddion-lib";
  }
  return "?";
}

Result<ProfileFormat> parse_format(const std::string& name) {
  std::string n = io_detail::lower_ascii(name);
  for (auto f :
       {ProfileFormat::Auto, ProfileFormat::Csv, ProfileFormat::Dektak, ProfileFormat::Gwyddion, ProfileFormat::X3p,
        ProfileFormat::Matrix, ProfileFormat::Xyz, ProfileFormat::Sdf, ProfileFormat::Npy, ProfileFormat::GwyddionLib})
    if (n == format_name(f)) return f;
  if (n == "txt" || n == "tsv" || n == "text") return ProfileFormat::Csv;
  if (n == "gwy" || n == "gwyddionlib" || n == "libgwyddion") return ProfileFormat::GwyddionLib;
  return make_error(fmt::format(
      "unknown format '{}' (expected auto, csv, dektak, gwyddion, x3p, matrix, xyz, sdf, npy or gwyddion-lib)", name));
}

namespace {

/// What a file that is no regular file is, for messages ("a directory", ...).
const char* file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

Error not_a_file(const std::string& path, mode_t mode, const std::string& expected) {
  std::string kind = file_kind(mode);
  if (S_ISCHR(mode) && path == "/dev/null") kind += " (/dev/null, which holds no data)";
  return make_error(ErrorCode::InvalidInput, fmt::format("{}: is {}, expected {}", path, kind, expected));
}

/// Reads a whole regular file. Opened with O_NONBLOCK and checked with fstat before any read, so
/// that a FIFO (even one put in place after a check) never blocks the caller.
Result<std::string> read_file_bytes(const std::string& path, std::uint64_t max_bytes) {
  if (auto st = check_input_file(path, "a surface file"); !st) return st.error();
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0)
    return make_error(ErrorCode::Io, fmt::format("{}: cannot open for reading: {}", path, std::strerror(errno)));
  struct FdCloser {
    int fd;
    ~FdCloser() { ::close(fd); }
  } closer{fd};
  struct stat sb {};
  if (::fstat(fd, &sb) != 0)
    return make_error(ErrorCode::Io, fmt::format("{}: cannot read its size: {}", path, std::strerror(errno)));
  if (!S_ISREG(sb.st_mode)) return not_a_file(path, sb.st_mode, "a surface file");
  const auto size = static_cast<std::uint64_t>(sb.st_size);
  if (size > max_bytes)
    return make_error(fmt::format("{}: {} bytes, above the limit of {} bytes", path, size, max_bytes));
  std::string bytes(std::size_t(size), '\0');
  std::size_t got = 0;
  while (got < bytes.size()) {
    const ssize_t n = ::read(fd, bytes.data() + got, bytes.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return make_error(ErrorCode::Io, fmt::format("{}: read error: {}", path, std::strerror(errno)));
    if (n == 0) break;
    got += std::size_t(n);
  }
  if (got != size)
    return make_error(ErrorCode::Io, fmt::format("{}: read {} of its {} bytes (did it shrink?)", path, got, size));
  return bytes;
}

}  // namespace

Status check_input_file(const std::string& path, const std::string& expected) {
  if (path.empty()) return make_error(fmt::format("empty file name, expected {}", expected));
  struct stat sb {};
  if (::stat(path.c_str(), &sb) != 0) {
    const int e = errno;
    if (e == ENOENT)
      return make_error(ErrorCode::Io, fmt::format("{}: cannot open: no such file, expected {}", path, expected));
    return make_error(ErrorCode::Io, fmt::format("{}: cannot open: {}", path, std::strerror(e)));
  }
  if (!S_ISREG(sb.st_mode)) return not_a_file(path, sb.st_mode, expected);
  return Ok{};
}

namespace {

Result<SurfaceData> parse_text(std::string_view text, const std::string& name, const ReadOptions& options,
                               const io_detail::ReleaseBehind* release = nullptr);

Result<SurfaceData> read_native_bytes(const std::string& bytes, const std::string& name, const ReadOptions& options,
                                      int depth) {
  ProfileFormat f = options.format;
  if (f == ProfileFormat::GwyddionLib)
    return make_error(fmt::format("{}: the Gwyddion backend reads files, not bytes in memory", name));
  if (io_detail::looks_like_gzip(bytes)) {
    if (depth > 0) return make_error(fmt::format("{}: gzip inside gzip is not read", name));
    auto inner = io_detail::gunzip(bytes, name, options.max_bytes);
    if (!inner) return inner.error();
    auto r = read_native_bytes(*inner, name, options, depth + 1);
    if (r) r->reader = fmt::format("{} (gzip)", r->reader);
    return r;
  }
  bool zip = bytes.size() >= 4 && bytes.compare(0, 4, "PK\x03\x04") == 0;
  if (f == ProfileFormat::X3p || (f == ProfileFormat::Auto && zip)) {
    if (!zip) return make_error(fmt::format("{}: not an X3P file (no ZIP signature)", name));
    return io_detail::read_x3p_bytes(bytes, name, options);
  }
  if (zip) return make_error(fmt::format("{}: a ZIP archive cannot be read as {}", name, format_name(f)));
  if (f == ProfileFormat::Npy || (f == ProfileFormat::Auto && io_detail::looks_like_npy(bytes))) {
    if (!io_detail::looks_like_npy(bytes))
      return make_error(fmt::format("{}: not a .npy file (no \\x93NUMPY signature)", name));
    return io_detail::read_npy_bytes(bytes, name, options);
  }
  std::string decoded;
  const std::string_view text = io_detail::decode_text_view(bytes, decoded);
  if (text.find('\0') != std::string_view::npos)
    return make_error(fmt::format("{}: binary data of no format frictal reads natively (text, X3P, .npy, gzip)", name));
  return parse_text(text, name, options);
}

}  // namespace

namespace {

// Text already decoded to UTF-8: the format from its content (or options) and its parser.
Result<SurfaceData> parse_text(std::string_view text, const std::string& name, const ReadOptions& options,
                               const io_detail::ReleaseBehind* release) {
  ProfileFormat f = options.format;
  if (f == ProfileFormat::Auto) {
    if (io_detail::looks_like_sdf_text(text))
      f = ProfileFormat::Sdf;
    else if (io_detail::looks_like_dektak(text))
      f = ProfileFormat::Dektak;
    else if (io_detail::looks_like_gwyddion(text))
      f = ProfileFormat::Gwyddion;
    else
      f = ProfileFormat::Csv;
  }
  switch (f) {
    case ProfileFormat::Sdf: return io_detail::parse_sdf_text(text, name, options);
    case ProfileFormat::Dektak: return io_detail::parse_dektak(text, name, options);
    case ProfileFormat::Gwyddion: return io_detail::parse_gwyddion(text, name, options);
    default: return io_detail::parse_delimited(text, name, options, release);
  }
}

std::string lower_ascii_copy(const std::string& s) { return io_detail::lower_ascii(s); }

/// The one channel a native file holds, for `frictal info`.
void describe_native(SurfaceData& s) {
  s.reader = fmt::format("native{}", s.reader);
  ChannelInfo c;
  c.name = format_name(s.format);
  c.is_map = s.is_map;
  if (s.is_map) {
    c.nx = s.map.nx;
    c.ny = s.map.ny;
    c.size_x = double(s.map.nx) * s.map.dx;
    c.size_y = double(s.map.ny) * s.map.dy;
  } else {
    c.nx = s.curve.size();
    c.ny = 1;
    c.size_x = s.curve.size() ? s.curve.x.back() - s.curve.x.front() : 0;
  }
  c.xy_unit.push_back('m');  // (not = "m": GCC 12 -Wrestrict false positive, PR 105329)
  c.z_unit = c.xy_unit;
  s.channels = {c};
  s.channel = 0;
}

/// A map's spacing below the smallest normal double (e.g. "# Width: 3e-320 m") has lost its
/// precision, and every size and slope computed from it with it: an error, not a wrong number.
Result<SurfaceData> checked_spacing(Result<SurfaceData> r, const std::string& name) {
  if (r && r->is_map &&
      (r->map.dx < std::numeric_limits<double>::min() || r->map.dy < std::numeric_limits<double>::min()))
    return make_error(
        fmt::format("{}: grid spacing dx = {} m, dy = {} m is below the smallest normal double ({} m) and has lost "
                    "precision; give the lateral sizes in a larger unit",
                    name, r->map.dx, r->map.dy, std::numeric_limits<double>::min()));
  return r;
}

/// A profile whose x decreases down the file (an instrument that exports from its far end) is the
/// same profile: its rows are read in reverse order, with a note. Only a column that never
/// increases is turned; one that goes back and forth stays as read (a folded curve, or an error
/// later where a profile is needed).
Result<SurfaceData> increasing_x(Result<SurfaceData> r, const std::string& name) {
  if (!r || r->is_map || r->curve.x.size() < 2) return r;
  std::vector<double>& x = r->curve.x;
  if (!(x.back() < x.front())) return r;
  for (std::size_t i = 1; i < x.size(); ++i)
    if (x[i] > x[i - 1]) return r;
  std::reverse(x.begin(), x.end());
  std::reverse(r->curve.z.begin(), r->curve.z.end());
  r->warnings.emplace_back("reader", fmt::format("{}: x decreases down the file ({:.6g} to {:.6g} m); the rows are "
                                                 "read in reverse order, the same profile with x increasing",
                                                 name, x.back(), x.front()));
  return r;
}

/// The name of a unit scale (metres per unit) for messages: "m", "mm", "um", "nm", "pm", or "1e-05 m".
std::string unit_word(double scale) {
  for (const auto& [s, w] : {std::pair{1.0, "m"}, {1e-3, "mm"}, {1e-6, "um"}, {1e-9, "nm"}, {1e-12, "pm"}})
    if (std::abs(scale - s) <= 1e-9 * s) return w;
  return fmt::format("{:g} m", scale);
}

/// ReadOptions::x_unit / z_unit: the values read rescaled from the unit the reader applied to the
/// unit given, with a warning where that changes them.
Result<SurfaceData> with_units(Result<SurfaceData> r, const ReadOptions& o, const std::string& name) {
  if (!r) return r;
  for (const bool lateral : {true, false}) {
    const std::string& unit = lateral ? o.x_unit : o.z_unit;
    if (unit.empty()) continue;
    const std::optional<double> s = io_detail::unit_scale(unit);
    if (!s)
      return make_error(
          fmt::format("{}: unknown unit '{}' (expected m, mm, um, nm)", lateral ? "x_unit" : "z_unit", unit));
    double& applied = lateral ? r->x_unit_scale : r->z_unit_scale;
    if (!(applied > 0) || std::abs(*s - applied) <= 1e-12 * *s) {
      applied = *s;
      continue;
    }
    const double f = *s / applied;
    if (lateral) {
      if (r->is_map) {
        r->map.dx *= f, r->map.dy *= f, r->map.x0 *= f, r->map.y0 *= f;
      } else {
        for (double& x : r->curve.x) x *= f;
      }
    } else {
      for (double& z : r->is_map ? r->map.heights : r->curve.z) z *= f;
    }
    r->warnings.emplace_back(
        "reader", fmt::format("{}: {} are read in {}, the {} given, not in {} as the file gives or implies", name,
                              lateral ? "the lateral lengths" : "the heights", unit_word(*s),
                              lateral ? "x unit" : "z unit", unit_word(applied)));
    applied = *s;
  }
  return r;
}

}  // namespace

Result<SurfaceData> read_surface_bytes(const std::string& bytes, const std::string& name, const ReadOptions& options) {
  auto r = read_native_bytes(bytes, name, options, 0);
  if (r) describe_native(*r);
  return increasing_x(checked_spacing(with_units(std::move(r), options, name), name), name);
}

static Status check_native_channel(const SurfaceData& s, const std::string& path, const ReadOptions& options) {
  if (options.channel.empty() || options.channel == "0" || lower_ascii_copy(options.channel) == s.channels[0].name)
    return Ok{};
  return make_error(fmt::format("{}: channel '{}' requested but this {} file has one channel (0)", path,
                                options.channel, format_name(s.format)));
}

namespace {

// A text or .npy file parsed straight from a read-only mapping of the file: no copy of its bytes
// (a 10^7-point CSV is about 460 MB). Only a successful parse of UTF-8 text or of a .npy array
// is returned; anything else (other formats, decoding, errors, Gwyddion's fallback) goes the
// usual way (nullopt), which reads the file again and gives the same result or message.
std::optional<SurfaceData> read_text_mapped(const std::string& path, const ReadOptions& options) {
  if (options.format == ProfileFormat::X3p) return std::nullopt;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || size < 4 || size > options.max_bytes) return std::nullopt;
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  void* map = ::mmap(nullptr, std::size_t(size), PROT_READ, MAP_PRIVATE, fd, 0);
  ::close(fd);
  if (map == MAP_FAILED) return std::nullopt;
  ::madvise(map, std::size_t(size), MADV_SEQUENTIAL);
  struct Unmap {
    void* p;
    std::size_t n;
    ~Unmap() { ::munmap(p, n); }
  } unmap{map, std::size_t(size)};
  std::string_view bytes(static_cast<const char*>(map), std::size_t(size));
  const bool zip = bytes.compare(0, 4, "PK\x03\x04") == 0;
  const bool npy = bytes.compare(0, 6, "\x93NUMPY") == 0;
  if (!npy && options.format == ProfileFormat::Npy) return std::nullopt;
  const bool gz = (unsigned char)bytes[0] == 0x1f && (unsigned char)bytes[1] == 0x8b && bytes[2] == 8;
  if (npy && bytes.size() >= 10 && (options.format == ProfileFormat::Auto || options.format == ProfileFormat::Npy)) {
    // .npy: the array is converted straight from the mapping (read at the speed of the disk).
    auto r = io_detail::read_npy_bytes(bytes, path, options);
    if (!r) return std::nullopt;
    describe_native(*r);
    if (auto st = check_native_channel(*r, path, options); !st) return std::nullopt;
    return std::move(*r);
  }
  if (zip || npy || gz || io_detail::utf16_text(bytes)) return std::nullopt;
  const bool bom8 =
      (unsigned char)bytes[0] == 0xEF && (unsigned char)bytes[1] == 0xBB && (unsigned char)bytes[2] == 0xBF;
  if (bom8) bytes.remove_prefix(3);
  // Pages already read are given back as the reading goes (MADV_DONTNEED on a read-only private
  // mapping: a later read of them, e.g. a header line, faults them in again from the file).
  const char* const base = static_cast<const char*>(map);
  const io_detail::ReleaseBehind release = [base](const char* upto) {
    const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
    const std::size_t n = static_cast<std::size_t>(upto - base) / page * page;
    if (n > 0) ::madvise(const_cast<char*>(base), n, MADV_DONTNEED);
  };
  // UTF-8 (unless the file says so by its BOM) without NUL bytes, else the usual way decodes it:
  // checked 32 MB at a time, each piece's pages given back, so that the whole file is never
  // resident at once. A piece ends before a byte that starts a character.
  constexpr std::size_t kPiece = std::size_t{32} << 20;
  for (std::size_t at = 0; at < bytes.size();) {
    std::size_t end = std::min(bytes.size(), at + kPiece);
    while (end < bytes.size() && ((unsigned char)bytes[end] & 0xC0) == 0x80) ++end;
    const std::string_view piece = bytes.substr(at, end - at);
    if ((!bom8 && !io_detail::valid_utf8(piece)) || piece.find('\0') != std::string_view::npos) return std::nullopt;
    release(piece.data() + piece.size());
    at = end;
  }
  auto r = parse_text(bytes, path, options, &release);
  if (!r) return std::nullopt;
  describe_native(*r);
  if (auto st = check_native_channel(*r, path, options); !st) return std::nullopt;
  return std::move(*r);
}

}  // namespace

static Result<SurfaceData> read_surface_unchecked(const std::string& path, const ReadOptions& options);

Result<SurfaceData> read_surface(const std::string& path, const ReadOptions& options) {
  return increasing_x(checked_spacing(with_units(read_surface_unchecked(path, options), options, path), path), path);
}

static Result<SurfaceData> read_surface_unchecked(const std::string& path, const ReadOptions& options) {
  if (options.format == ProfileFormat::GwyddionLib) {
    if (auto st = check_input_file(path, "a surface file"); !st) return st.error();
    return io_detail::read_gwyddion(path, options);
  }
  if (auto m = read_text_mapped(path, options)) return std::move(*m);
  auto bytes = read_file_bytes(path, options.max_bytes);
  if (!bytes) return bytes.error();
  auto r = read_native_bytes(*bytes, path, options, 0);
  if (r) {
    describe_native(*r);
    if (auto st = check_native_channel(*r, path, options); !st) return st.error();
    return r;
  }
  if (options.format != ProfileFormat::Auto) return r;
  // No native reader took it (and it is no X3P, .npy or gzip file): Gwyddion's file modules may.
  const std::string& b = *bytes;
  if ((b.size() >= 4 && b.compare(0, 4, "PK\x03\x04") == 0) || io_detail::looks_like_npy(b) ||
      io_detail::looks_like_gzip(b))
    return r;
  const bool binary = decode_text(b).find('\0') != std::string::npos;
  std::string why;
  if (gwyddion_available(options.gwyddion_module_dir, &why)) {
    if (io_detail::gwyddion_detects(path, options.gwyddion_module_dir)) {
      auto g = io_detail::read_gwyddion(path, options);
      // Text that a Gwyddion module claims but cannot load: the native message (with its line
      // number) says more.
      if (g || binary) return g;
      return r;
    }
    if (binary)
      return make_error(
          fmt::format("{}: binary data that neither frictal's readers nor Gwyddion's file modules recognise "
                      "(see `frictal formats`)",
                      path));
    return r;
  }
  if (binary)
    return make_error(
        fmt::format("{}: binary data of no format frictal reads natively (text, X3P, .npy, gzip); Gwyddion's "
                    "file modules may read it, but {}",
                    path, why));
  return r;
}

std::vector<FormatInfo> readable_formats(const std::string& gwyddion_module_dir) {
  std::vector<FormatInfo> f = {
      {"csv", "delimited text profiles: CSV, TSV, whitespace, ';' with decimal commas (.csv, .txt, .dat, .asc, ...)",
       "native", true},
      {"dektak", "Bruker Dektak CSV export (.csv)", "native", false},
      {"gwyddion", "Gwyddion text export of a map, '# Width:' headers (.txt)", "native", true},
      {"matrix",
       "text matrix of heights, optionally with a 'w= h=' / 'nx= ny=' / SPIP 'x-pixels =' header (.txt, .asc)",
       "native", false},
      {"xyz", "text x, y, z point list on a regular grid (.xyz, .txt, .csv)", "native", false},
      {"sdf", "ISO 25178-71 / BCR surface data file, ASCII (.sdf)", "native", false},
      {"x3p", "ISO 25178-72 XML 3D surface profile, X3P (.x3p): SUR, PRF, PCL on a grid", "native", true},
      {"npy", "NumPy array (.npy): 1-D profile, 2-D map; f4, f8, i1-i8, u1-u4", "native", false},
      {"gzip", "any of the above compressed with gzip (.txt.gz, .csv.gz, ...)", "native", false},
  };
  for (auto& g : gwyddion_formats(gwyddion_module_dir)) f.push_back(std::move(g));
  return f;
}

Result<Curve> read_curve(const std::string& path, const ReadOptions& options) {
  auto s = read_surface(path, options);
  if (!s) return s.error();
  if (s->is_map)
    return make_error(fmt::format("{}: an areal map ({} x {}), not a line profile; extract a line first", path,
                                  s->map.nx, s->map.ny));
  return std::move(s->curve);
}

Result<Profile> read_profile(const std::string& path, const ReadOptions& options) {
  auto c = read_curve(path, options);
  if (!c) return c.error();
  for (std::size_t k = 1; k < c->x.size(); ++k)
    if (c->x[k] < c->x[k - 1])
      return make_error(fmt::format("{}: x decreases at point {} ({} after {}); a profile needs non-decreasing x", path,
                                    k + 1, c->x[k], c->x[k - 1]));
  return as_profile(std::move(*c), path);
}

Result<Map> read_map(const std::string& path, const ReadOptions& options) {
  auto s = read_surface(path, options);
  if (!s) return s.error();
  if (!s->is_map) return make_error(fmt::format("{}: a line profile, not an areal map", path));
  return std::move(s->map);
}

Result<Curve> parse_curve_text(const std::string& text, const std::string& name) {
  auto s = io_detail::parse_delimited(decode_text(text), name, ReadOptions{});
  if (!s) return s.error();
  return std::move(s->curve);
}

Status write_profile_csv(const std::string& path, const Curve& c) {
  if (c.x.size() != c.z.size()) return make_error(fmt::format("{}: x and z sizes differ", path));
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return make_error(ErrorCode::Io, fmt::format("{}: cannot open for writing", path));
  std::string buf = "x_m,z_m\n";
  for (std::size_t k = 0; k < c.x.size(); ++k) buf += fmt::format("{:.17g},{:.17g}\n", c.x[k], c.z[k]);
  bool ok = std::fwrite(buf.data(), 1, buf.size(), f) == buf.size();
  ok = std::fclose(f) == 0 && ok;
  if (!ok) return make_error(ErrorCode::Io, fmt::format("{}: write error", path));
  return Ok{};
}

Status write_profile_csv(const std::string& path, const Profile& p) {
  Curve c;
  c.x = p.x;
  c.z = p.z;
  return write_profile_csv(path, c);
}

Status write_map_text(const std::string& path, const Map& m) {
  if (auto s = validate(m, path); !s) return s;
  std::string buf = fmt::format("# Channel: frictal\n# Width: {:.17g} m\n# Height: {:.17g} m\n# Value units: m\n",
                                m.dx * double(m.nx), m.dy * double(m.ny));
  for (std::size_t j = 0; j < m.ny; ++j) {
    for (std::size_t i = 0; i < m.nx; ++i) {
      double v = m.at(i, j);
      buf += std::isnan(v) ? std::string("NaN") : fmt::format("{:.17g}", v);
      buf += i + 1 < m.nx ? ' ' : '\n';
    }
  }
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return make_error(ErrorCode::Io, fmt::format("{}: cannot open for writing", path));
  bool ok = std::fwrite(buf.data(), 1, buf.size(), f) == buf.size();
  ok = std::fclose(f) == 0 && ok;
  if (!ok) return make_error(ErrorCode::Io, fmt::format("{}: write error", path));
  return Ok{};
}

}  // namespace frictal
