// ISO 25178-71 X3P: a ZIP archive with main.xml (ISO5436_2), md5checksum.hex, and optionally
// bindata/data.bin (little-endian, x fastest) and bindata/valid.bin (bit mask, LSB first).
// Members are read into memory with size limits, never extracted to disk.
#include <fmt/core.h>
#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <limits>
#include <map>
#include <memory>

#include <openssl/evp.h>
#include <zip.h>
#include <pugixml.hpp>

#include "frictal/version.hpp"
#include "io/readers.hpp"
#include "io/text_util.hpp"

namespace frictal {
namespace io_detail {

namespace {

std::string md5_hex(const std::string& data) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_md5(), nullptr) != 1 ||
      EVP_DigestUpdate(ctx.get(), data.data(), data.size()) != 1 || EVP_DigestFinal_ex(ctx.get(), digest, &len) != 1)
    return {};
  std::string hex;
  for (unsigned i = 0; i < len; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

struct ZipCloser {
  void operator()(zip_t* z) const { zip_discard(z); }
};

class Archive {
 public:
  // Opens the archive from memory. `bytes` must outlive the Archive.
  Status open(const std::string& bytes, const std::string& name) {
    name_ = name;
    zip_error_t err;
    zip_error_init(&err);
    zip_source_t* src = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &err);
    if (!src) {
      zip_error_fini(&err);
      return make_error(fmt::format("{}: cannot read the ZIP archive", name));
    }
    zip_t* z = zip_open_from_source(src, ZIP_RDONLY | ZIP_CHECKCONS, &err);
    if (!z) {
      std::string why = zip_error_strerror(&err);
      zip_source_free(src);
      zip_error_fini(&err);
      return make_error(fmt::format("{}: not a valid X3P (ZIP) archive: {}", name, why));
    }
    zip_error_fini(&err);
    zip_.reset(z);
    return Ok{};
  }
  std::vector<std::string> names() const {
    std::vector<std::string> n;
    zip_int64_t count = zip_get_num_entries(zip_.get(), 0);
    for (zip_int64_t i = 0; i < count; ++i) {
      const char* s = zip_get_name(zip_.get(), zip_uint64_t(i), 0);
      n.emplace_back(s ? s : "");
    }
    return n;
  }
  /// Uncompressed size of a member as the archive declares it.
  Result<std::uint64_t> size(const std::string& member) const {
    zip_int64_t idx = zip_name_locate(zip_.get(), member.c_str(), 0);
    if (idx < 0) return make_error(fmt::format("{}: archive member '{}' not found", name_, member));
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat_index(zip_.get(), zip_uint64_t(idx), 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE))
      return make_error(fmt::format("{}: member '{}': cannot read its size", name_, member));
    return std::uint64_t(st.size);
  }
  /// Reads one member into memory, at most max_bytes (checked before allocating).
  Result<std::string> read(const std::string& member, std::uint64_t max_bytes) const {
    zip_int64_t idx = zip_name_locate(zip_.get(), member.c_str(), 0);
    if (idx < 0) return make_error(fmt::format("{}: archive member '{}' not found", name_, member));
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat_index(zip_.get(), zip_uint64_t(idx), 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE))
      return make_error(fmt::format("{}: member '{}': cannot read its size", name_, member));
    if (st.size > max_bytes)
      return make_error(fmt::format("{}: member '{}' is {} bytes uncompressed, above the limit of {} bytes", name_,
                                    member, st.size, max_bytes));
    zip_file_t* f = zip_fopen_index(zip_.get(), zip_uint64_t(idx), 0);
    if (!f) return make_error(fmt::format("{}: member '{}': {}", name_, member, zip_strerror(zip_.get())));
    std::string data(std::size_t(st.size), '\0');
    std::uint64_t got = 0;
    while (got < st.size) {
      zip_int64_t n = zip_fread(f, data.data() + got, st.size - got);
      if (n <= 0) break;
      got += std::uint64_t(n);
    }
    std::string why = got < st.size ? zip_file_strerror(f) : "";
    zip_fclose(f);  // also verifies the CRC
    if (got < st.size)
      return make_error(fmt::format("{}: member '{}' is truncated or corrupt: read {} of {} bytes ({})", name_, member,
                                    got, st.size, why));
    return data;
  }

 private:
  std::unique_ptr<zip_t, ZipCloser> zip_;
  std::string name_;
};

std::string_view local_name(const char* n) {
  std::string_view s(n);
  auto c = s.find(':');
  return c == std::string_view::npos ? s : s.substr(c + 1);
}

pugi::xml_node child(pugi::xml_node node, std::string_view local) {
  for (pugi::xml_node c = node.first_child(); c; c = c.next_sibling())
    if (c.type() == pugi::node_element && local_name(c.name()) == local) return c;
  return {};
}

std::string text_of(pugi::xml_node n) { return std::string(trim(n.child_value())); }

struct Axis {
  bool incremental = true;
  char type = 'D';
  double increment = 1;
  double offset = 0;
};

Result<Axis> parse_axis(pugi::xml_node axes, const char* which, const std::string& name) {
  Axis a;
  pugi::xml_node n = child(axes, which);
  if (!n) return make_error(fmt::format("{}: main.xml: Record1/Axes/{} is missing", name, which));
  std::string at = text_of(child(n, "AxisType"));
  if (at == "A")
    a.incremental = false;
  else if (at == "I" || at.empty())
    a.incremental = true;
  else
    return make_error(fmt::format("{}: main.xml: {}/AxisType is '{}' (expected I or A)", name, which, at));
  std::string dt = text_of(child(n, "DataType"));
  if (dt.empty()) dt.push_back('D');  // (not dt = "D": GCC 12 -Wrestrict false positive, PR 105329)
  if (dt != "I" && dt != "L" && dt != "F" && dt != "D")
    return make_error(fmt::format("{}: main.xml: {}/DataType is '{}' (expected I, L, F or D)", name, which, dt));
  a.type = dt[0];
  std::string inc = text_of(child(n, "Increment")), off = text_of(child(n, "Offset"));
  if (!inc.empty() && (!parse_double(inc, a.increment) || !std::isfinite(a.increment) || a.increment == 0))
    return make_error(fmt::format("{}: main.xml: {}/Increment '{}' is not a non-zero number", name, which, inc));
  if (!off.empty() && (!parse_double(off, a.offset) || !std::isfinite(a.offset)))
    return make_error(fmt::format("{}: main.xml: {}/Offset '{}' is not a number", name, which, off));
  return a;
}

Result<std::uint64_t> parse_size(pugi::xml_node parent, const char* which, const std::string& name) {
  std::string s = text_of(child(parent, which));
  long long v;
  if (!parse_int64(s, v) || v < 1 || v > (1LL << 40))
    return make_error(fmt::format("{}: main.xml: {} is '{}' (expected a positive integer)", name, which, s));
  return std::uint64_t(v);
}

std::size_t type_size(char t) { return t == 'I' ? 2 : t == 'L' ? 4 : t == 'F' ? 4 : 8; }

double decode_raw(const unsigned char* p, char t) {
  unsigned char b[8];
  std::size_t n = type_size(t);
  std::memcpy(b, p, n);
  if constexpr (std::endian::native == std::endian::big) std::reverse(b, b + n);
  switch (t) {
    case 'I': {
      std::int16_t v;
      std::memcpy(&v, b, 2);
      return v;
    }
    case 'L': {
      std::int32_t v;
      std::memcpy(&v, b, 4);
      return v;
    }
    case 'F': {
      float v;
      std::memcpy(&v, b, 4);
      return v;
    }
    default: {
      double v;
      std::memcpy(&v, b, 8);
      return v;
    }
  }
}

bool same_hex(std::string a, std::string b) {
  a = lower_ascii(trim(a));
  b = lower_ascii(trim(b));
  return !a.empty() && a == b;
}

/// Fits v[k] = a + b * k (k = 0..n-1) and checks it is linear within tolerance; returns b.
std::optional<std::pair<double, double>> regular(const std::vector<double>& v) {
  if (v.size() == 1) return std::pair{v[0], 0.0};
  double a = v.front(), b = (v.back() - v.front()) / double(v.size() - 1);
  if (!(b > 0)) return std::nullopt;
  for (std::size_t k = 0; k < v.size(); ++k)
    if (std::abs(v[k] - (a + b * double(k))) > 1e-6 * std::abs(b)) return std::nullopt;
  return std::pair{a, b};
}

}  // namespace

Result<SurfaceData> read_x3p_bytes(const std::string& bytes, const std::string& name, const ReadOptions& options) {
  Archive ar;
  if (auto s = ar.open(bytes, name); !s) return s.error();
  SurfaceData out;
  out.format = ProfileFormat::X3p;
  auto& warn = out.warnings;
  InvalidCount invalid;  // NaN / +-inf heights stored as values (not flagged by valid.bin or <Datum/>)

  // main.xml at the root, or in one sub-folder (archives zipped from a folder); skip macOS forks.
  std::string base, main_name;
  for (const auto& n : ar.names()) {
    if (n.rfind("__MACOSX/", 0) == 0) continue;
    if (n == "main.xml" || (n.size() > 9 && n.compare(n.size() - 9, 9, "/main.xml") == 0)) {
      if (main_name.empty() || n.size() < main_name.size()) main_name = n;
    }
  }
  if (main_name.empty()) return make_error(fmt::format("{}: X3P archive without main.xml", name));
  base = main_name.substr(0, main_name.size() - 8);
  if (!base.empty()) warn.emplace_back("reader", fmt::format("{}: main.xml is in the sub-folder '{}'", name, base));
  // main.xml holds metadata (and at most an XML data list): 1 KiB per point of max_points is
  // plenty, capped at 256 MiB.
  auto xml =
      ar.read(main_name, std::min<std::uint64_t>({options.max_bytes, 256u << 20, 4096 + options.max_points * 1024}));
  if (!xml) return xml.error();

  pugi::xml_document doc;
  pugi::xml_parse_result pr = doc.load_buffer(xml->data(), xml->size());
  if (!pr)
    return make_error(fmt::format("{}: {}: XML error at byte {}: {}", name, main_name, pr.offset, pr.description()));
  pugi::xml_node root;
  for (pugi::xml_node c = doc.first_child(); c; c = c.next_sibling())
    if (c.type() == pugi::node_element) {
      root = c;
      break;
    }
  if (!root || (local_name(root.name()) != "ISO5436_2" && local_name(root.name()) != "ISO5436"))
    return make_error(
        fmt::format("{}: {}: root element is '{}' (expected ISO5436_2)", name, main_name, root ? root.name() : ""));
  if (std::string_view(root.name()).find(':') == std::string_view::npos && !root.attribute("xmlns"))
    warn.emplace_back("reader", fmt::format("{}: root element '{}' has no namespace", name, root.name()));

  // Checksum of main.xml (a mismatch is a warning: real files often carry stale ones).
  {
    std::string cname = text_of(child(child(root, "Record4"), "ChecksumFile"));
    if (cname.empty()) cname = "md5checksum.hex";
    auto sum = ar.read(base + cname, 4096);
    if (!sum) {
      warn.emplace_back("reader", fmt::format("{}: no checksum file '{}'; main.xml not verified", name, cname));
    } else {
      std::string expect = std::string(trim(*sum)).substr(0, 32);
      if (!same_hex(expect, md5_hex(*xml)))
        warn.emplace_back(
            "reader", fmt::format("{}: MD5 checksum of main.xml does not match {} (file says {}, content is {})", name,
                                  cname, expect, md5_hex(*xml)));
    }
  }

  pugi::xml_node r1 = child(root, "Record1"), r3 = child(root, "Record3");
  if (!r1 || !r3) return make_error(fmt::format("{}: main.xml: Record1 or Record3 missing", name));
  std::string feature = text_of(child(r1, "FeatureType"));
  if (feature != "SUR" && feature != "PRF" && feature != "PCL")
    return make_error(fmt::format("{}: main.xml: FeatureType '{}' (expected SUR, PRF or PCL)", name, feature));
  pugi::xml_node axes = child(r1, "Axes");
  auto cx = parse_axis(axes, "CX", name);
  if (!cx) return cx.error();
  auto cy = parse_axis(axes, "CY", name);
  if (!cy) return cy.error();
  auto cz = parse_axis(axes, "CZ", name);
  if (!cz) return cz.error();
  if (cz->incremental) return make_error(fmt::format("{}: main.xml: CZ must be an absolute axis (AxisType A)", name));

  // Dimensions.
  std::uint64_t nx = 0, ny = 0, count = 0;
  bool matrix = false;
  if (pugi::xml_node md = child(r3, "MatrixDimension")) {
    auto sx = parse_size(md, "SizeX", name);
    if (!sx) return sx.error();
    auto sy = parse_size(md, "SizeY", name);
    if (!sy) return sy.error();
    std::string szs = text_of(child(md, "SizeZ"));
    if (!szs.empty() && szs != "1")
      return make_error(fmt::format("{}: main.xml: SizeZ is {} (only one layer is supported)", name, szs));
    nx = *sx;
    ny = *sy;
    if (nx > options.max_points / ny)
      return make_error(
          fmt::format("{}: main.xml: {} x {} points exceed the limit of {}", name, nx, ny, options.max_points));
    count = nx * ny;
    matrix = true;
  } else if (pugi::xml_node ld = child(r3, "ListDimension")) {
    long long v;
    if (!parse_int64(text_of(ld), v) || v < 1)
      return make_error(fmt::format("{}: main.xml: ListDimension '{}' is not a positive integer", name, text_of(ld)));
    if (std::uint64_t(v) > options.max_points)
      return make_error(fmt::format("{}: main.xml: {} points exceed the limit of {}", name, v, options.max_points));
    count = std::uint64_t(v);
  } else {
    return make_error(fmt::format("{}: main.xml: Record3 has neither MatrixDimension nor ListDimension", name));
  }

  // Which coordinates each point stores: the absolute axes, in x, y, z order.
  std::vector<char> stored;
  if (!cx->incremental) stored.push_back('x');
  if (!cy->incremental) stored.push_back('y');
  stored.push_back('z');
  const Axis* ax[3] = {&*cx, &*cy, &*cz};
  auto axis_of = [&](char c) { return c == 'x' ? ax[0] : c == 'y' ? ax[1] : ax[2]; };
  std::vector<double> px, py, pz(count, std::numeric_limits<double>::quiet_NaN());
  if (!cx->incremental) px.assign(count, std::numeric_limits<double>::quiet_NaN());
  if (!cy->incremental) py.assign(count, std::numeric_limits<double>::quiet_NaN());
  auto column = [&](char c) -> std::vector<double>& { return c == 'x' ? px : c == 'y' ? py : pz; };

  pugi::xml_node link = child(r3, "DataLink");
  if (link) {
    std::string dname = text_of(child(link, "PointDataLink"));
    if (dname.empty()) return make_error(fmt::format("{}: main.xml: DataLink without PointDataLink", name));
    std::size_t rec = 0;
    for (char c : stored) rec += type_size(axis_of(c)->type);
    std::uint64_t expect = count * rec;
    // The declared size must match before anything is allocated (no trust in a huge header).
    auto declared = ar.size(base + dname);
    if (!declared) return declared.error();
    if (*declared != expect)
      return make_error(fmt::format("{}: {}: {} bytes, but {} points of {} bytes need {}", name, dname, *declared,
                                    count, rec, expect));
    auto data = ar.read(base + dname, std::min<std::uint64_t>(options.max_bytes, expect));
    if (!data) return data.error();
    if (data->size() != expect)
      return make_error(fmt::format("{}: {}: {} bytes, but {} points of {} bytes need {}", name, dname, data->size(),
                                    count, rec, expect));
    std::string sum = text_of(child(link, "MD5ChecksumPointData"));
    if (!sum.empty() && !same_hex(sum, md5_hex(*data)))
      warn.emplace_back("reader", fmt::format("{}: MD5 checksum of {} does not match main.xml", name, dname));
    const auto* p = reinterpret_cast<const unsigned char*>(data->data());
    for (std::uint64_t k = 0; k < count; ++k)
      for (char c : stored) {
        char t = axis_of(c)->type;
        column(c)[k] = decode_raw(p, t);
        p += type_size(t);
      }
    std::string valid_bits;  // empty: every point valid
    std::string vname = text_of(child(link, "ValidPointsLink"));
    if (!vname.empty()) {
      auto vdeclared = ar.size(base + vname);
      if (!vdeclared) return vdeclared.error();
      if (*vdeclared > (count + 7) / 8 + 4096)
        return make_error(fmt::format("{}: {}: {} bytes, far more than the {} bytes of mask {} points need", name,
                                      vname, *vdeclared, (count + 7) / 8, count));
      auto valid = ar.read(base + vname, options.max_bytes);
      if (!valid) return valid.error();
      if (valid->size() < (count + 7) / 8)
        return make_error(fmt::format("{}: {}: {} bytes, but {} points need {} bytes of mask", name, vname,
                                      valid->size(), count, (count + 7) / 8));
      std::string vs = text_of(child(link, "MD5ChecksumValidPoints"));
      if (!vs.empty() && !same_hex(vs, md5_hex(*valid)))
        warn.emplace_back("reader", fmt::format("{}: MD5 checksum of {} does not match main.xml", name, vname));
      valid_bits = std::move(*valid);
    }
    // Heights stored as NaN or +-inf on points the mask calls valid: invalid points (one rule
    // for every format); points the mask flags are the format's own "not measured".
    for (std::uint64_t k = 0; k < count; ++k) {
      const bool flagged = !valid_bits.empty() && !(((unsigned char)valid_bits[k / 8] >> (k % 8)) & 1u);
      if (flagged)
        pz[k] = std::numeric_limits<double>::quiet_NaN();
      else if (!std::isfinite(pz[k]))
        invalid.add(pz[k]);
    }
  } else if (pugi::xml_node list = child(r3, "DataList")) {
    std::uint64_t k = 0;
    for (pugi::xml_node d = list.first_child(); d; d = d.next_sibling()) {
      if (d.type() != pugi::node_element || local_name(d.name()) != "Datum") continue;
      if (k >= count)
        return make_error(fmt::format("{}: main.xml: DataList has more than the {} points declared", name, count));
      std::string_view t = trim(d.child_value());
      if (!t.empty()) {
        std::size_t field = 0, start = 0;
        while (true) {
          std::size_t semi = t.find(';', start);
          std::string_view f = t.substr(start, semi == std::string_view::npos ? std::string_view::npos : semi - start);
          if (field >= stored.size())
            return make_error(fmt::format("{}: main.xml: Datum {} '{}' has more than {} values", name, k + 1,
                                          std::string(t.substr(0, 60)), stored.size()));
          double v;
          if (!trim(f).empty()) {
            if (!parse_double(f, v))
              return make_error(fmt::format("{}: main.xml: Datum {}: '{}' is not a number", name, k + 1,
                                            std::string(f.substr(0, 40))));
            const char type = axis_of(stored[field])->type;
            if (type == 'F') v = double(float(v));  // the value is a float32
            if ((type == 'I' || type == 'L') &&
                (v != std::floor(v) || std::abs(v) > (type == 'I' ? 32768.0 : 2147483648.0)))
              return make_error(fmt::format("{}: main.xml: Datum {}: '{}' is not a {} integer", name, k + 1,
                                            std::string(f.substr(0, 40)), type == 'I' ? "16-bit" : "32-bit"));
            if (stored[field] == 'z' && !std::isfinite(v)) invalid.add(v);
            column(stored[field])[k] = v;
          }
          ++field;
          if (semi == std::string_view::npos) break;
          start = semi + 1;
        }
        if (field != stored.size())
          return make_error(fmt::format("{}: main.xml: Datum {} has {} values (expected {}: {})", name, k + 1, field,
                                        stored.size(), std::string(stored.begin(), stored.end())));
      }
      ++k;
    }
    if (k != count)
      return make_error(fmt::format("{}: main.xml: DataList has {} points but {} are declared", name, k, count));
  } else {
    return make_error(fmt::format("{}: main.xml: Record3 has neither DataLink nor DataList", name));
  }

  // Scale: value = Offset + Increment * raw, for every stored axis.
  for (char c : stored) {
    const Axis* a = axis_of(c);
    for (double& v : column(c))
      if (!std::isnan(v)) v = a->offset + a->increment * v;
  }
  for (double& v : pz)
    if (std::isinf(v)) v = std::numeric_limits<double>::quiet_NaN();  // counted above
  for (const auto* col : {&px, &py})
    for (std::uint64_t k = 0; k < col->size(); ++k)
      if (std::isinf((*col)[k]))
        return make_error(
            fmt::format("{}: point {} has an infinite {} coordinate", name, k + 1, col == &px ? 'x' : 'y'));

  Map m;
  if (matrix) {
    m.nx = nx;
    m.ny = ny;
    if (cx->incremental) {
      m.dx = cx->increment;
      m.x0 = cx->offset;
    }
    if (cy->incremental) {
      m.dy = cy->increment;
      m.y0 = cy->offset;
    }
    // Absolute x or y in a matrix: accept if they lie on a regular grid.
    if (!cx->incremental) {
      std::vector<double> xs(px.begin(), px.begin() + nx);
      auto g = regular(xs);
      if (!g || nx < 2) return make_error(fmt::format("{}: absolute x axis is not a regular grid", name));
      m.x0 = g->first;
      m.dx = g->second;
    }
    if (!cy->incremental) {
      std::vector<double> ys(ny);
      for (std::uint64_t j = 0; j < ny; ++j) ys[j] = py[j * nx];
      auto g = regular(ys);
      if (!g || ny < 2) return make_error(fmt::format("{}: absolute y axis is not a regular grid", name));
      m.y0 = g->first;
      m.dy = g->second;
    }
    m.heights = std::move(pz);
  } else {
    // A point list: accepted when its points fill a regular grid.
    if (px.empty() || py.empty()) return make_error(fmt::format("{}: list data needs absolute x and y axes", name));
    std::vector<double> ux, uy;
    for (std::uint64_t k = 0; k < count; ++k) {
      if (std::isnan(px[k]) || std::isnan(py[k]))
        return make_error(fmt::format("{}: point {} has no x or y", name, k + 1));
      ux.push_back(px[k]);
      uy.push_back(py[k]);
    }
    auto uniq = [](std::vector<double>& v) {
      std::sort(v.begin(), v.end());
      std::vector<double> r;
      for (double a : v)
        if (r.empty() || std::abs(a - r.back()) > 1e-9 * std::max(1.0, std::abs(a))) r.push_back(a);
      v = r;
    };
    uniq(ux);
    uniq(uy);
    auto gx = regular(ux), gy = regular(uy);
    if (!gx || !gy || ux.size() * uy.size() != count || ux.size() < 2)
      return make_error(
          fmt::format("{}: point list ({} points) does not fill a regular x-y grid (not supported)", name, count));
    m.nx = ux.size();
    m.ny = uy.size();
    m.x0 = gx->first;
    m.dx = gx->second;
    m.y0 = gy->first;
    m.dy = gy->second > 0 ? gy->second : gx->second;
    m.heights.assign(count, std::numeric_limits<double>::quiet_NaN());
    for (std::uint64_t k = 0; k < count; ++k) {
      auto i = std::size_t(std::llround((px[k] - m.x0) / m.dx)), j = std::size_t(std::llround((py[k] - m.y0) / m.dy));
      if (i >= m.nx || j >= m.ny) return make_error(fmt::format("{}: point {} off the grid", name, k + 1));
      m.heights[j * m.nx + i] = pz[k];
    }
  }
  if (!(m.dx > 0) || !(m.dy > 0))
    return make_error(fmt::format("{}: grid spacings must be positive (CX/CY Increment)", name));

  if (feature == "PRF" || m.nx == 1 || m.ny == 1) {
    if (m.nx > 1 && m.ny > 1)
      return make_error(fmt::format("{}: FeatureType PRF but the matrix is {} x {}", name, m.nx, m.ny));
    bool along_y = m.nx == 1 && m.ny > 1;
    std::size_t n = along_y ? m.ny : m.nx;
    std::size_t dropped = 0;
    for (std::size_t k = 0; k < n; ++k) {
      double z = m.heights[k];
      if (std::isnan(z)) {
        ++dropped;
        continue;
      }
      out.curve.x.push_back(along_y ? m.y0 + double(k) * m.dy : m.x0 + double(k) * m.dx);
      out.curve.z.push_back(z);
    }
    if (invalid.total()) warn.emplace_back("reader", invalid_warning(name, invalid, false));
    if (dropped > invalid.total())
      warn.emplace_back("reader",
                        fmt::format("{}: {} points flagged invalid were dropped", name, dropped - invalid.total()));
    if (out.curve.x.size() < 2) return make_error(fmt::format("{}: profile with fewer than two valid points", name));
    out.is_map = false;
  } else {
    out.is_map = true;
    out.map = std::move(m);
    if (invalid.total()) warn.emplace_back("reader", invalid_warning(name, invalid, true));
    if (out.map.valid_count() == 0) return make_error(fmt::format("{}: no valid points", name));
  }
  return out;
}

}  // namespace io_detail

namespace {

const char* type_letter(X3pDataType t) {
  switch (t) {
    case X3pDataType::I: return "I";
    case X3pDataType::L: return "L";
    case X3pDataType::F: return "F";
    default: return "D";
  }
}

std::string utc_now() {
  std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S+00:00", &tm);
  return buf;
}

Status write_x3p_grid(const std::string& path, const Map& m, bool profile, const X3pWriteOptions& o) {
  if (auto s = validate(m, path); !s && !profile) return s;
  const std::size_t n = m.heights.size();
  bool any_invalid = false;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : m.heights) {
    if (std::isnan(v)) {
      any_invalid = true;
      continue;
    }
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (!(lo <= hi)) return make_error(fmt::format("{}: nothing to write: no valid point", path));
  const bool integer = o.type == X3pDataType::I || o.type == X3pDataType::L;
  double inc = 1, off = 0;
  if (integer) {
    const double maxraw = o.type == X3pDataType::I ? 32767.0 : 2147483647.0;
    if (o.z_increment > 0) {
      inc = o.z_increment;
      off = o.z_offset;
    } else {
      off = 0.5 * (lo + hi);
      inc = hi > lo ? (hi - lo) / (2 * (maxraw - 1)) : 1e-12;
    }
    if (std::abs((lo - off) / inc) > maxraw + 0.5 || std::abs((hi - off) / inc) > maxraw + 0.5)
      return make_error(fmt::format("{}: heights [{}, {}] m do not fit in {} with increment {} and offset {}", path, lo,
                                    hi, type_letter(o.type), inc, off));
  }
  // Data.
  std::string data, valid;
  std::string list;
  std::size_t tsize = o.type == X3pDataType::I ? 2 : (o.type == X3pDataType::D ? 8 : 4);
  if (o.binary) data.resize(n * tsize);
  if (any_invalid) valid.assign((n + 7) / 8, '\0');
  for (std::size_t k = 0; k < n; ++k) {
    double v = m.heights[k];
    bool ok = !std::isnan(v);
    if (ok && any_invalid) valid[k / 8] = char((unsigned char)valid[k / 8] | (1u << (k % 8)));
    unsigned char b[8] = {0};
    std::string txt;
    switch (o.type) {
      case X3pDataType::I: {
        std::int16_t r = ok ? std::int16_t(std::llround((v - off) / inc)) : 0;
        std::memcpy(b, &r, 2);
        txt = fmt::format("{}", r);
        break;
      }
      case X3pDataType::L: {
        std::int32_t r = ok ? std::int32_t(std::llround((v - off) / inc)) : 0;
        std::memcpy(b, &r, 4);
        txt = fmt::format("{}", r);
        break;
      }
      case X3pDataType::F: {
        float r = float(v);
        std::memcpy(b, &r, 4);
        txt = fmt::format("{:.9g}", r);
        break;
      }
      case X3pDataType::D: {
        std::memcpy(b, &v, 8);
        txt = fmt::format("{:.17g}", v);
        break;
      }
    }
    if constexpr (std::endian::native == std::endian::big) std::reverse(b, b + tsize);
    if (o.binary)
      std::memcpy(data.data() + k * tsize, b, tsize);
    else
      list += ok ? fmt::format("      <Datum>{}</Datum>\n", txt) : "      <Datum/>\n";
  }

  auto esc = [](const std::string& t) {
    std::string r;
    for (char c : t) {
      if (c == '<')
        r += "&lt;";
      else if (c == '>')
        r += "&gt;";
      else if (c == '&')
        r += "&amp;";
      else
        r += c;
    }
    return r;
  };
  const std::string date = o.date.empty() ? utc_now() : esc(o.date);
  std::string xml;
  xml += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  xml +=
      "<p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\" "
      "xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
      "xsi:schemaLocation=\"http://www.opengps.eu/2008/ISO5436_2 "
      "http://www.opengps.eu/2008/ISO5436_2/ISO5436_2.xsd\">\n";
  xml += "  <Record1>\n    <Revision>ISO5436 - 2000</Revision>\n";
  xml += fmt::format("    <FeatureType>{}</FeatureType>\n    <Axes>\n", profile ? "PRF" : "SUR");
  xml += fmt::format(
      "      <CX>\n        <AxisType>I</AxisType>\n        <DataType>D</DataType>\n"
      "        <Increment>{:.17g}</Increment>\n        <Offset>{:.17g}</Offset>\n      </CX>\n",
      m.dx, m.x0);
  xml += fmt::format(
      "      <CY>\n        <AxisType>I</AxisType>\n        <DataType>D</DataType>\n"
      "        <Increment>{:.17g}</Increment>\n        <Offset>{:.17g}</Offset>\n      </CY>\n",
      m.dy, m.y0);
  xml +=
      fmt::format("      <CZ>\n        <AxisType>A</AxisType>\n        <DataType>{}</DataType>\n", type_letter(o.type));
  if (integer)
    xml += fmt::format("        <Increment>{:.17g}</Increment>\n        <Offset>{:.17g}</Offset>\n", inc, off);
  xml += "      </CZ>\n    </Axes>\n  </Record1>\n";
  xml += fmt::format(
      "  <Record2>\n    <Date>{}</Date>\n    <Creator>{}</Creator>\n    <Instrument>\n"
      "      <Manufacturer>frictal</Manufacturer>\n      <Model>frictal</Model>\n"
      "      <Serial>not available</Serial>\n      <Version>{}</Version>\n    </Instrument>\n"
      "    <CalibrationDate>{}</CalibrationDate>\n    <ProbingSystem>\n      <Type>Software</Type>\n"
      "      <Identification>frictal</Identification>\n    </ProbingSystem>\n"
      "    <Comment>{}</Comment>\n  </Record2>\n",
      date, esc(o.creator), frictal::version(), date, esc(o.comment));
  xml += fmt::format(
      "  <Record3>\n    <MatrixDimension>\n      <SizeX>{}</SizeX>\n      <SizeY>{}</SizeY>\n"
      "      <SizeZ>1</SizeZ>\n    </MatrixDimension>\n",
      m.nx, m.ny);
  if (o.binary) {
    xml += "    <DataLink>\n      <PointDataLink>bindata/data.bin</PointDataLink>\n";
    xml += fmt::format("      <MD5ChecksumPointData>{}</MD5ChecksumPointData>\n", io_detail::md5_hex(data));
    if (any_invalid)
      xml += fmt::format(
          "      <ValidPointsLink>bindata/valid.bin</ValidPointsLink>\n"
          "      <MD5ChecksumValidPoints>{}</MD5ChecksumValidPoints>\n",
          io_detail::md5_hex(valid));
    xml += "    </DataLink>\n";
  } else {
    xml += "    <DataList>\n" + list + "    </DataList>\n";
  }
  xml += "  </Record3>\n  <Record4>\n    <ChecksumFile>md5checksum.hex</ChecksumFile>\n  </Record4>\n</p:ISO5436_2>\n";
  std::string md5 = io_detail::md5_hex(xml) + " *main.xml\n";

  int err = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  if (!z) {
    zip_error_t ze;
    zip_error_init_with_code(&ze, err);
    std::string why = zip_error_strerror(&ze);
    zip_error_fini(&ze);
    return make_error(ErrorCode::Io, fmt::format("{}: cannot create: {}", path, why));
  }
  auto add = [&](const char* member, const std::string& content) -> bool {
    zip_source_t* s = zip_source_buffer(z, content.data(), content.size(), 0);
    if (!s) return false;
    zip_int64_t idx = zip_file_add(z, member, s, ZIP_FL_OVERWRITE | ZIP_FL_ENC_UTF_8);
    if (idx < 0) {
      zip_source_free(s);
      return false;
    }
    zip_set_file_compression(z, zip_uint64_t(idx), ZIP_CM_DEFLATE, 1);            // fast; height data compresses poorly
    if (!o.date.empty()) zip_file_set_mtime(z, zip_uint64_t(idx), 315532800, 0);  // 1980-01-01: reproducible bytes
    return true;
  };
  bool ok = add("main.xml", xml) && add("md5checksum.hex", md5);
  if (ok && o.binary) {
    zip_int64_t dir = zip_dir_add(z, "bindata", ZIP_FL_ENC_UTF_8);
    ok = dir >= 0;
    if (ok && !o.date.empty()) zip_file_set_mtime(z, zip_uint64_t(dir), 315532800, 0);
    ok = ok && add("bindata/data.bin", data);
  }
  if (ok && o.binary && any_invalid) ok = add("bindata/valid.bin", valid);
  if (!ok) {
    std::string why = zip_strerror(z);
    zip_discard(z);
    return make_error(ErrorCode::Io, fmt::format("{}: cannot write the archive: {}", path, why));
  }
  if (zip_close(z) != 0) {
    std::string why = zip_strerror(z);
    zip_discard(z);
    return make_error(ErrorCode::Io, fmt::format("{}: cannot write the archive: {}", path, why));
  }
  return Ok{};
}

}  // namespace

Status write_x3p(const std::string& path, const Map& m, const X3pWriteOptions& options) {
  return write_x3p_grid(path, m, false, options);
}

Status write_x3p(const std::string& path, const Profile& p, const X3pWriteOptions& options) {
  if (p.size() < 2) return make_error(fmt::format("{}: a profile needs at least two points", path));
  double dx = (p.x.back() - p.x.front()) / double(p.size() - 1);
  for (std::size_t k = 0; k < p.size(); ++k)
    if (!(dx > 0) || std::abs(p.x[k] - (p.x.front() + dx * double(k))) > 0.01 * dx)
      return make_error(fmt::format(
          "{}: X3P profiles need uniformly spaced x (point {} is off the grid); resample first", path, k + 1));
  Map m;
  m.nx = p.size();
  m.ny = 1;
  m.dx = dx;
  m.dy = dx;
  m.x0 = p.x.front();
  m.heights = p.z;
  return write_x3p_grid(path, m, true, options);
}

}  // namespace frictal
