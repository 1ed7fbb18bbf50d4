// Native readers added for what users have and Gwyddion lacks or reads only with dialogs:
// NumPy .npy arrays, gzip-compressed files (any readable format inside), and the ASCII form of
// the ISO 25178-71 / BCR surface data file (SDF). All work on bytes in memory.
#include <fmt/core.h>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>

#include <zlib.h>

#include "io/readers.hpp"
#include "io/text_util.hpp"

namespace frictal::io_detail {

// ---------------------------------------------------------------------------------------------
// NumPy .npy (format versions 1, 2, 3): "\x93NUMPY", major, minor, header length (uint16 LE
// in v1, uint32 LE in v2/3), a Python dict literal {'descr': '<f8', 'fortran_order': False,
// 'shape': (ny, nx), }, then the raw array.

bool looks_like_npy(const std::string& bytes) { return bytes.size() >= 10 && bytes.compare(0, 6, "\x93NUMPY") == 0; }

namespace {

std::optional<std::string> dict_value(std::string_view header, std::string_view key) {
  auto k = header.find(fmt::format("'{}'", key));
  if (k == std::string_view::npos) k = header.find(fmt::format("\"{}\"", key));
  if (k == std::string_view::npos) return std::nullopt;
  auto colon = header.find(':', k);
  if (colon == std::string_view::npos) return std::nullopt;
  auto v = trim(header.substr(colon + 1));
  if (v.empty()) return std::nullopt;
  std::size_t end;
  if (v.front() == '(')
    end = v.find(')') + 1;
  else if (v.front() == '\'' || v.front() == '"')
    end = v.find(v.front(), 1) + 1;
  else
    end = v.find_first_of(",}");
  if (end == 0 || end == std::string_view::npos + 1 || end > v.size()) return std::nullopt;
  return std::string(v.substr(0, end));
}

}  // namespace

Result<SurfaceData> read_npy_bytes(std::string_view bytes, const std::string& name, const ReadOptions& options) {
  const auto u8 = [&](std::size_t i) { return (unsigned char)bytes[i]; };
  const int major = u8(6);
  if (major < 1 || major > 3)
    return make_error(fmt::format("{}: .npy format version {}.{} (expected 1.0, 2.0 or 3.0)", name, major, u8(7)));
  std::size_t hlen, start;
  if (major == 1) {
    hlen = std::size_t(u8(8)) | std::size_t(u8(9)) << 8;
    start = 10;
  } else {
    if (bytes.size() < 12) return make_error(fmt::format("{}: .npy header truncated", name));
    hlen = std::size_t(u8(8)) | std::size_t(u8(9)) << 8 | std::size_t(u8(10)) << 16 | std::size_t(u8(11)) << 24;
    start = 12;
  }
  if (hlen > bytes.size() - start)
    return make_error(fmt::format("{}: .npy header of {} bytes but the file has {} after the preamble", name, hlen,
                                  bytes.size() - start));
  const std::string_view header(bytes.data() + start, hlen);
  auto descr = dict_value(header, "descr"), order = dict_value(header, "fortran_order"),
       shape = dict_value(header, "shape");
  if (!descr || !order || !shape)
    return make_error(fmt::format("{}: .npy header '{}' lacks descr, fortran_order or shape", name,
                                  std::string(trim(header)).substr(0, 120)));
  // descr: '<f8', '>i4', '|u1', ...
  std::string d = descr->substr(1, descr->size() - 2);
  if (d.size() < 3) return make_error(fmt::format("{}: .npy dtype {} not understood", name, *descr));
  const char endian = d[0], kind = d[1];
  int size = 0;
  for (char c : d.substr(2)) {
    if (c < '0' || c > '9' || size > 1000) {  // no item size has 4 digits (and no overflow)
      size = -1;
      break;
    }
    size = size * 10 + (c - '0');
  }
  const bool ok_kind = (kind == 'f' && (size == 4 || size == 8)) ||
                       (kind == 'i' && (size == 1 || size == 2 || size == 4 || size == 8)) ||
                       (kind == 'u' && (size == 1 || size == 2 || size == 4));
  if (!ok_kind || (endian != '<' && endian != '>' && endian != '|' && endian != '='))
    return make_error(fmt::format(
        "{}: .npy dtype {} is not supported (expected float32/64 or int8..int64, uint8..uint32)", name, *descr));
  const bool big = endian == '>' || (endian == '=' && std::endian::native == std::endian::big);
  const bool fortran = trim(*order) == "True";
  if (!fortran && trim(*order) != "False")
    return make_error(fmt::format("{}: .npy fortran_order '{}' (expected True or False)", name, *order));
  // shape: (n,) or (ny, nx)
  std::vector<std::uint64_t> dims;
  {
    std::string_view sv(*shape);
    sv = trim(sv.substr(1, sv.size() - 2));
    std::size_t i = 0;
    while (i < sv.size()) {
      auto j = sv.find(',', i);
      auto f = trim(sv.substr(i, j == std::string_view::npos ? std::string_view::npos : j - i));
      if (!f.empty()) {
        if (!f.empty() && (f.back() == 'L')) f.remove_suffix(1);
        long long v;
        if (!parse_int64(f, v) || v < 0)
          return make_error(fmt::format("{}: .npy shape {} not understood", name, *shape));
        dims.push_back(std::uint64_t(v));
      }
      if (j == std::string_view::npos) break;
      i = j + 1;
    }
  }
  if (dims.empty() || dims.size() > 2)
    return make_error(
        fmt::format("{}: .npy array of shape {} (expected 1-D heights or a 2-D (ny, nx) map)", name, *shape));
  std::uint64_t count = 1;
  for (auto v : dims) {
    if (v == 0) return make_error(fmt::format("{}: .npy array of shape {} is empty", name, *shape));
    if (v > options.max_points || count > options.max_points / v)
      return make_error(
          fmt::format("{}: .npy shape {} exceeds the limit of {} points", name, *shape, options.max_points));
    count *= v;
  }
  const std::uint64_t data_start = start + hlen, need = count * std::uint64_t(size);
  if (bytes.size() - data_start != need)
    return make_error(fmt::format("{}: .npy data is {} bytes, but shape {} of {} needs {}", name,
                                  bytes.size() - data_start, *shape, *descr, need));
  std::vector<double> v(count);
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + data_start);
  const bool native_f8 = kind == 'f' && size == 8 && big == (std::endian::native == std::endian::big);
  if (native_f8) std::memcpy(v.data(), p, count * 8);  // the common case at memory speed
  for (std::uint64_t k = 0; k < count && !native_f8; ++k, p += size) {
    unsigned char b[8];
    std::memcpy(b, p, std::size_t(size));
    if (big != (std::endian::native == std::endian::big)) std::reverse(b, b + size);
    double x;
    if (kind == 'f') {
      if (size == 4) {
        float f;
        std::memcpy(&f, b, 4);
        x = f;
      } else
        std::memcpy(&x, b, 8);
    } else if (kind == 'i') {
      if (size == 1) {
        std::int8_t i;
        std::memcpy(&i, b, 1);
        x = i;
      } else if (size == 2) {
        std::int16_t i;
        std::memcpy(&i, b, 2);
        x = i;
      } else if (size == 4) {
        std::int32_t i;
        std::memcpy(&i, b, 4);
        x = i;
      } else {
        std::int64_t i;
        std::memcpy(&i, b, 8);
        x = double(i);
      }
    } else {
      if (size == 1)
        x = b[0];
      else if (size == 2) {
        std::uint16_t i;
        std::memcpy(&i, b, 2);
        x = i;
      } else {
        std::uint32_t i;
        std::memcpy(&i, b, 4);
        x = i;
      }
    }
    v[k] = x;
  }
  SurfaceData out;
  out.format = ProfileFormat::Npy;
  double zs = 1;
  if (!options.default_unit.empty()) {
    auto s = unit_scale(options.default_unit);
    if (!s) return make_error(fmt::format("unknown unit '{}' (expected m, mm, um, nm)", options.default_unit));
    zs = *s;
  } else {
    out.warnings.emplace_back(
        "reader", fmt::format("{}: .npy arrays carry no unit; heights read as metres (give a unit to override)", name));
  }
  out.z_unit_scale = zs;
  out.x_unit_scale = 0;  // no lateral numbers: the spacing, given in metres, is the one lateral length
  InvalidCount invalid;
  const bool profile = dims.size() == 1 || dims[0] == 1 || dims[1] == 1;
  if (profile) {
    if (!(options.spacing > 0))
      return make_error(
          fmt::format("{}: a 1-D .npy array of {} heights needs the sampling interval (--spacing, "
                      "ReadOptions::spacing)",
                      name, count));
    out.curve.x.reserve(count);
    out.curve.z.reserve(count);
    for (std::uint64_t k = 0; k < count; ++k) {
      if (!std::isfinite(v[k])) {
        invalid.add(v[k]);
        continue;
      }
      out.curve.x.push_back(double(k) * options.spacing);
      out.curve.z.push_back(v[k] * zs);
    }
    if (invalid.total()) out.warnings.emplace_back("reader", invalid_warning(name, invalid, false));
    if (out.curve.x.size() < 2) return make_error(fmt::format("{}: fewer than 2 points with finite values", name));
    return out;
  }
  Map& m = out.map;
  m.ny = std::size_t(dims[0]);
  m.nx = std::size_t(dims[1]);
  m.heights.resize(count);
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) m.heights[j * m.nx + i] = v[fortran ? i * m.ny + j : j * m.nx + i];
  mask_invalid(m.heights, invalid);
  for (double& h : m.heights) h *= zs;
  if (options.spacing > 0) {
    m.dx = m.dy = options.spacing;
  } else {
    m.dx = m.dy = 1;
    out.warnings.emplace_back("reader",
                              fmt::format("{}: .npy arrays carry no grid spacing; set to 1 m (give --spacing)", name));
  }
  if (invalid.total()) out.warnings.emplace_back("reader", invalid_warning(name, invalid, true));
  if (m.valid_count() == 0) return make_error(fmt::format("{}: no valid point", name));
  out.is_map = true;
  return out;
}

// ---------------------------------------------------------------------------------------------
// gzip (RFC 1952), through zlib; the inflated size is limited by max_bytes.

bool looks_like_gzip(const std::string& bytes) {
  return bytes.size() >= 18 && (unsigned char)bytes[0] == 0x1f && (unsigned char)bytes[1] == 0x8b && bytes[2] == 8;
}

Result<std::string> gunzip(const std::string& bytes, const std::string& name, std::uint64_t max_bytes) {
  z_stream zs{};
  if (inflateInit2(&zs, 16 + MAX_WBITS) != Z_OK)
    return make_error(fmt::format("{}: cannot start gzip decompression", name));
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  zs.avail_in = uInt(std::min<std::size_t>(bytes.size(), std::numeric_limits<uInt>::max()));
  std::string out;
  char buf[1 << 16];
  int rc = Z_OK;
  while (rc != Z_STREAM_END) {
    zs.next_out = reinterpret_cast<Bytef*>(buf);
    zs.avail_out = sizeof buf;
    rc = inflate(&zs, Z_NO_FLUSH);
    if (rc != Z_OK && rc != Z_STREAM_END) {
      std::string why = zs.msg ? zs.msg : rc == Z_BUF_ERROR ? "truncated" : "corrupt data";
      inflateEnd(&zs);
      return make_error(fmt::format("{}: gzip data is corrupt or truncated ({})", name, why));
    }
    out.append(buf, sizeof buf - zs.avail_out);
    if (out.size() > max_bytes) {
      inflateEnd(&zs);
      return make_error(fmt::format("{}: more than {} bytes uncompressed, above the limit", name, max_bytes));
    }
  }
  inflateEnd(&zs);
  return out;
}

// ---------------------------------------------------------------------------------------------
// SDF ASCII (ISO 25178-71 / BCR): first line "aISO-1.0" or "aBCR-x.y", "Key = value" lines up
// to a line "*", then NumProfiles rows of NumPoints heights (x fastest), then "*" and an
// optional trailer. z = value * Zscale, spacings Xscale and Yscale, all in metres.

bool looks_like_sdf_text(std::string_view text) {
  auto t = trim(text.substr(0, 16));
  return t.size() >= 5 && (t.substr(0, 4) == "aISO" || t.substr(0, 4) == "aBCR") && t[4] == '-';
}

Result<SurfaceData> parse_sdf_text(std::string_view text, const std::string& name, const ReadOptions& options) {
  auto lines = split_lines(text);
  std::optional<long long> nx, ny;
  std::optional<double> xs, ys, zs;
  std::size_t k = 1;
  for (; k < lines.size(); ++k) {
    auto t = trim(lines[k].text);
    if (t == "*") break;
    auto eq = t.find('=');
    if (t.empty() || eq == std::string_view::npos) continue;
    std::string key = lower_ascii(trim(t.substr(0, eq)));
    auto value = trim(t.substr(eq + 1));
    auto number = [&](auto& dst) -> Status {
      double v;
      if (!parse_double(value, v) || !std::isfinite(v))
        return make_error(
            fmt::format("{}:{}: {} = '{}' is not a number", name, lines[k].number, key, std::string(value)));
      if constexpr (std::is_same_v<std::decay_t<decltype(dst)>, std::optional<long long>>) {
        // 2^62: far above any limit on points, and a double below it converts to long long exactly.
        if (v != std::floor(v) || v < 1 || v > 4.611686018427387904e18)
          return make_error(fmt::format("{}:{}: {} = '{}' is not a positive integer", name, lines[k].number, key,
                                        std::string(value)));
        dst = (long long)v;
      } else {
        dst = v;
      }
      return Ok{};
    };
    Status st = Ok{};
    if (key == "numpoints")
      st = number(nx);
    else if (key == "numprofiles")
      st = number(ny);
    else if (key == "xscale")
      st = number(xs);
    else if (key == "yscale")
      st = number(ys);
    else if (key == "zscale")
      st = number(zs);
    else if (key == "compression" && value != "0")
      return make_error(
          fmt::format("{}:{}: SDF Compression = {} (only 0 is defined)", name, lines[k].number, std::string(value)));
    if (!st) return st.error();
  }
  if (k >= lines.size()) return make_error(fmt::format("{}: SDF header without the '*' line that ends it", name));
  if (!nx || !ny || !xs || !ys || !zs)
    return make_error(fmt::format("{}: SDF header lacks NumPoints, NumProfiles, Xscale, Yscale or Zscale", name));
  if (!(*xs > 0) || !(*ys > 0))
    return make_error(fmt::format("{}: SDF Xscale and Yscale must be positive (found {} and {})", name, *xs, *ys));
  if (std::uint64_t(*nx) > options.max_points / std::uint64_t(*ny))
    return make_error(fmt::format("{}: SDF {} x {} points exceed the limit of {}", name, *nx, *ny, options.max_points));
  const std::size_t count = std::size_t(*nx * *ny);
  std::vector<double> v;
  v.reserve(count);
  for (++k; k < lines.size() && v.size() <= count; ++k) {
    auto t = trim(lines[k].text);
    if (t == "*") break;
    std::size_t i = 0;
    while (i < t.size()) {
      while (i < t.size() && (t[i] == ' ' || t[i] == '\t')) ++i;
      std::size_t j = i;
      while (j < t.size() && t[j] != ' ' && t[j] != '\t') ++j;
      if (j > i) {
        auto f = t.substr(i, j - i);
        double z;
        if (lower_ascii(f) == "bad")
          z = std::numeric_limits<double>::quiet_NaN();
        else if (!parse_double(f, z))
          return make_error(
              fmt::format("{}:{}: '{}' is not a height", name, lines[k].number, std::string(f.substr(0, 40))));
        v.push_back(z);
      }
      i = j;
    }
  }
  if (v.size() != count)
    return make_error(fmt::format("{}: SDF data has {} values but NumPoints x NumProfiles = {} x {} = {}", name,
                                  v.size(), *nx, *ny, count));
  SurfaceData out;
  out.format = ProfileFormat::Sdf;
  InvalidCount invalid;
  mask_invalid(v, invalid);
  for (double& z : v) z *= *zs;
  if (invalid.total()) out.warnings.emplace_back("reader", invalid_warning(name, invalid, *nx > 1 && *ny > 1));
  if (*ny == 1 || *nx == 1) {
    const double d = *ny == 1 ? *xs : *ys;
    for (std::size_t i = 0; i < count; ++i)
      if (!std::isnan(v[i])) {
        out.curve.x.push_back(double(i) * d);
        out.curve.z.push_back(v[i]);
      }
    if (out.curve.x.size() < 2) return make_error(fmt::format("{}: profile with fewer than two valid points", name));
    return out;
  }
  out.is_map = true;
  out.map.nx = std::size_t(*nx);
  out.map.ny = std::size_t(*ny);
  out.map.dx = *xs;
  out.map.dy = *ys;
  out.map.heights = std::move(v);
  if (out.map.valid_count() == 0) return make_error(fmt::format("{}: no valid point", name));
  return out;
}

}  // namespace frictal::io_detail
