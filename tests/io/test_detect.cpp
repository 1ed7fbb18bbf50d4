// Detection by content, no format hint: a single column of heights, matrices with or without a
// small size header, x,y,z lists on a grid, ISO 25178-71 SDF (ASCII), NumPy .npy and
// gzip-compressed files. Every file is written here from known numbers; expected values are
// those numbers times the units written.
#include <fmt/core.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "frictal/io.hpp"
#include "io/zip_builder.hpp"  // crc32

namespace {

frictal::ReadOptions with_spacing(double dx) {
  frictal::ReadOptions o;
  o.spacing = dx;
  return o;
}

bool has_warning(const frictal::SurfaceData& s, const std::string& what) {
  for (const auto& w : s.warnings)
    if (w.message.find(what) != std::string::npos) return true;
  return false;
}

// .npy v1.0 file: header dict padded with spaces to a multiple of 64 bytes, ending in '\n'.
std::string npy(const std::string& descr, bool fortran, const std::string& shape, const std::string& data) {
  std::string dict =
      "{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") + ", 'shape': " + shape + ", }";
  std::size_t total = 10 + dict.size() + 1;
  dict += std::string((64 - total % 64) % 64, ' ') + "\n";
  std::string out = "\x93NUMPY";
  out += char(1);
  out += char(0);
  out += char(dict.size() & 0xFF);
  out += char(dict.size() >> 8);
  return out + dict + data;
}

template <class T>
std::string raw(const std::vector<T>& v, bool big) {
  std::string out;
  for (T x : v) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &x, sizeof(T));  // the test machine is little-endian (x86-64)
    for (std::size_t k = 0; k < sizeof(T); ++k) out += char(b[big ? sizeof(T) - 1 - k : k]);
  }
  return out;
}

// gzip member with one stored (uncompressed) deflate block, written from RFC 1951/1952 alone.
std::string gzip_stored(const std::string& data) {
  std::string g = "\x1f\x8b\x08";
  g += std::string(6, '\0');
  g += '\xff';
  g += '\x01';  // BFINAL = 1, BTYPE = 00 (stored)
  const unsigned len = unsigned(data.size()), nlen = ~len & 0xFFFF;
  g += char(len & 0xFF);
  g += char(len >> 8);
  g += char(nlen & 0xFF);
  g += char(nlen >> 8);
  g += data;
  auto u32 = [&](std::uint32_t v) {
    for (int k = 0; k < 4; ++k) g += char((v >> (8 * k)) & 0xFF);
  };
  u32(frictal::test::crc32(data));
  u32(std::uint32_t(data.size()));
  return g;
}

}  // namespace

TEST(DetectText, SingleColumnWithSpacingHeaderIsAProfile) {
  auto s = frictal::read_surface_bytes("# spacing: 0.5 um\n# unit: nm\n1.5\n-2\n3\nNaN\n4\n", "col.txt");
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_FALSE(s->is_map);
  ASSERT_EQ(s->curve.size(), 4u);
  const double ex[] = {0, 0.5e-6, 1e-6, 2e-6}, ez[] = {1.5e-9, -2e-9, 3e-9, 4e-9};
  for (int k = 0; k < 4; ++k) {
    EXPECT_DOUBLE_EQ(s->curve.x[k], ex[k]);
    EXPECT_DOUBLE_EQ(s->curve.z[k], ez[k]);
  }
  EXPECT_TRUE(has_warning(*s, "1 invalid point (1 NaN)"));
  // A column header naming the unit: "height [um]", dx = 2e-6 from the option.
  auto h = frictal::read_surface_bytes("height [um]\n1\n2\n", "h.csv", with_spacing(2e-6));
  ASSERT_TRUE(h.ok()) << h.error().message;
  EXPECT_DOUBLE_EQ(h->curve.x[1], 2e-6);
  EXPECT_DOUBLE_EQ(h->curve.z[1], 2e-6);
  EXPECT_TRUE(h->warnings.empty()) << h->warnings[0].message;
}

TEST(DetectText, SingleColumnWithoutSpacingIsAClearError) {
  auto s = frictal::read_surface_bytes("1.5\n2.5\n3.5\n", "col.txt");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("--spacing"), std::string::npos) << s.error().message;
  EXPECT_NE(s.error().message.find("3 heights"), std::string::npos) << s.error().message;
}

TEST(DetectText, SingleColumnCountLine) {
  // "3" followed by 3 heights: a count line. "5" followed by 2: the first of 3 heights.
  auto a = frictal::read_surface_bytes("3\n7\n8\n9\n", "a.txt", with_spacing(1));
  ASSERT_TRUE(a.ok()) << a.error().message;
  ASSERT_EQ(a->curve.size(), 3u);
  EXPECT_DOUBLE_EQ(a->curve.z[0], 7);
  auto b = frictal::read_surface_bytes("5\n7\n8\n", "b.txt", with_spacing(1));
  ASSERT_TRUE(b.ok()) << b.error().message;
  ASSERT_EQ(b->curve.size(), 3u);
  EXPECT_DOUBLE_EQ(b->curve.z[0], 5);
  EXPECT_DOUBLE_EQ(b->curve.z[2], 8);
}

TEST(DetectText, MatrixWithoutHeader) {
  // 4 columns, 3 rows, first column 5, 1, 3 (no abscissa): a map with a spacing warning.
  const std::string text = "5 6 7 8\n1 2 3 4\n3 1 4 1\n";
  auto s = frictal::read_surface_bytes(text, "m.txt");
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_TRUE(s->is_map);
  EXPECT_EQ(s->format, frictal::ProfileFormat::Matrix);
  EXPECT_EQ(s->map.nx, 4u);
  EXPECT_EQ(s->map.ny, 3u);
  EXPECT_DOUBLE_EQ(s->map.at(2, 2), 4);
  EXPECT_DOUBLE_EQ(s->map.at(3, 0), 8);
  EXPECT_TRUE(has_warning(*s, "spacing"));
  auto t = frictal::read_surface_bytes(text, "m.txt", with_spacing(0.25e-6));
  ASSERT_TRUE(t.ok());
  EXPECT_DOUBLE_EQ(t->map.dx, 0.25e-6);
  EXPECT_DOUBLE_EQ(t->map.dy, 0.25e-6);
}

TEST(DetectText, TiltedMatrixWithoutHeaderIsAMatrix) {
  // 12 x 6 heights z(i, j) = 10 j + e(i, j) with |e| < 3: the first column rises (a map tilted
  // along y), but in unequal steps (10 + e differences), so it is no abscissa: a map. The same
  // 12 columns whose first column rises in equal steps (0.25, 0.75, 1.25, ...) stay a table: a
  // profile from columns 0 and 1 with a warning naming them.
  auto e = [](int i, int j) { return double((i * 7 + j * 13) % 5) - 2.0; };  // -2 .. 2
  std::string tilted, table;
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i < 12; ++i) {
      tilted += fmt::format("{}{}", i ? " " : "", 10.0 * j + e(i, j));
      table += fmt::format("{}{}", i ? " " : "", i == 0 ? 0.5 * j + 0.25 : e(i, j));
    }
    tilted += "\n";
    table += "\n";
  }
  auto s = frictal::read_surface_bytes(tilted, "tilted.txt", with_spacing(1e-6));
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_TRUE(s->is_map);
  EXPECT_EQ(s->format, frictal::ProfileFormat::Matrix);
  EXPECT_EQ(s->map.nx, 12u);
  EXPECT_EQ(s->map.ny, 6u);
  EXPECT_DOUBLE_EQ(s->map.at(3, 4), 40.0 + e(3, 4));
  auto t = frictal::read_surface_bytes(table, "table.txt", with_spacing(1e-6));
  ASSERT_TRUE(t.ok()) << t.error().message;
  EXPECT_FALSE(t->is_map);
  EXPECT_TRUE(has_warning(*t, "using column 0 as x"));
}

TEST(DetectText, MatrixWithSmallHeaders) {
  // "w= h=" on one line, lengths with units; heights unit nm.
  auto a = frictal::read_surface_bytes("# w=4um h=3um unit=nm\n1 2 3 4\n5 6 7 8\n9 10 11 12\n", "wh.txt");
  ASSERT_TRUE(a.ok()) << a.error().message;
  ASSERT_TRUE(a->is_map);
  EXPECT_EQ(a->map.nx, 4u);
  EXPECT_EQ(a->map.ny, 3u);
  EXPECT_DOUBLE_EQ(a->map.dx, 1e-6);  // 4 um / 4 columns
  EXPECT_DOUBLE_EQ(a->map.dy, 1e-6);  // 3 um / 3 rows
  EXPECT_DOUBLE_EQ(a->map.at(1, 2), 10e-9);
  EXPECT_TRUE(a->warnings.empty()) << a->warnings[0].message;
  // Two columns are a matrix when the header gives sizes; nx/ny are checked.
  auto b = frictal::read_surface_bytes("nx = 2, ny = 2\ndx = 0.5 um\n1 2\n3 4\n", "nxny.txt", [] {
    frictal::ReadOptions o;
    o.default_unit = "um";
    return o;
  }());
  ASSERT_TRUE(b.ok()) << b.error().message;
  ASSERT_TRUE(b->is_map);
  EXPECT_DOUBLE_EQ(b->map.dx, 0.5e-6);
  EXPECT_DOUBLE_EQ(b->map.dy, 0.5e-6);
  EXPECT_DOUBLE_EQ(b->map.at(1, 1), 4e-6);
  // A two-column profile with a spacing comment stays a profile.
  auto p = frictal::read_surface_bytes("# dx = 0.1 um\n0 1\n1 2\n2 3\n", "prof.txt");
  ASSERT_TRUE(p.ok()) << p.error().message;
  EXPECT_FALSE(p->is_map);
  auto c = frictal::read_surface_bytes("nx = 3\n1 2\n3 4\n", "bad.txt");
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error().message.find("nx"), std::string::npos) << c.error().message;
  // SPIP ASCII (as Gwyddion exports it): lengths in nm, z = value * Bit2nm nm.
  auto d = frictal::read_surface_bytes(
      "# File Format = ASCII\n# x-pixels = 3\n# y-pixels = 2\n# x-length = 3000\n# y-length = 2000\n"
      "# x-offset = 0\n# y-offset = 0\n# Bit2nm = 2.0\n# Start of Data:\n0\t1\t2\n3\t4\t5\n",
      "spip.asc");
  ASSERT_TRUE(d.ok()) << d.error().message;
  ASSERT_TRUE(d->is_map);
  EXPECT_DOUBLE_EQ(d->map.dx, 1e-6);
  EXPECT_DOUBLE_EQ(d->map.dy, 1e-6);
  EXPECT_DOUBLE_EQ(d->map.at(2, 1), 10e-9);
}

TEST(DetectText, XyzListOnAGridIsAMap) {
  // 3 x 2 grid, x = 10, 12, 14 um, y = 5, 6 um, listed out of order; z in nm = 10 i + j.
  const std::string text = "x (um)\ty (um)\tz (nm)\n12\t5\t10\n10\t5\t0\n14\t6\t21\n10\t6\t1\n12\t6\t11\n14\t5\t20\n";
  auto s = frictal::read_surface_bytes(text, "grid.xyz");
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_TRUE(s->is_map);
  EXPECT_EQ(s->format, frictal::ProfileFormat::Xyz);
  const auto& m = s->map;
  ASSERT_EQ(m.nx, 3u);
  ASSERT_EQ(m.ny, 2u);
  EXPECT_DOUBLE_EQ(m.x0, 10e-6);
  EXPECT_DOUBLE_EQ(m.dx, 2e-6);
  EXPECT_DOUBLE_EQ(m.y0, 5e-6);
  EXPECT_DOUBLE_EQ(m.dy, 1e-6);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 2; ++j) EXPECT_DOUBLE_EQ(m.at(i, j), (10 * i + j) * 1e-9);
  EXPECT_TRUE(s->warnings.empty()) << s->warnings[0].message;
  // A missing node is an invalid point, with a warning.
  auto t = frictal::read_surface_bytes("0 0 1\n1 0 2\n2 0 3\n0 1 4\n1 1 5\n", "holes.xyz");
  ASSERT_TRUE(t.ok()) << t.error().message;
  ASSERT_TRUE(t->is_map);
  EXPECT_EQ(t->format, frictal::ProfileFormat::Xyz);
  EXPECT_DOUBLE_EQ(t->map.at(1, 1), 5);
  EXPECT_TRUE(std::isnan(t->map.at(2, 1)));
  EXPECT_TRUE(has_warning(*t, "missing"));
}

TEST(DetectText, IsoSdfAscii) {
  const std::string text =
      "aISO-1.0\nManufacID   = test\nCreateDate  = 231120261200\nModDate     = 231120261200\nNumPoints   = 3\n"
      "NumProfiles = 2\nXscale      = 1.0e-6\nYscale      = 2.0e-6\nZscale      = 1.0e-9\nZresolution = -1\n"
      "Compression = 0\nDataType    = 7\nCheckType   = 0\nNumDataSet  = 1\nNanPresent  = 0\n*\n"
      "1 2 3\n4 5 6\n*\nsome trailer\n";
  auto s = frictal::read_surface_bytes(text, "t.sdf");
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_TRUE(s->is_map);
  EXPECT_EQ(s->format, frictal::ProfileFormat::Sdf);
  EXPECT_EQ(s->map.nx, 3u);
  EXPECT_EQ(s->map.ny, 2u);
  EXPECT_DOUBLE_EQ(s->map.dx, 1e-6);
  EXPECT_DOUBLE_EQ(s->map.dy, 2e-6);
  EXPECT_DOUBLE_EQ(s->map.at(2, 1), 6e-9);
  EXPECT_DOUBLE_EQ(s->map.at(0, 1), 4e-9);
  auto bad = frictal::read_surface_bytes(
      "aBCR-1.0\nNumPoints = 3\nNumProfiles = 2\nXscale = 1\nYscale = 1\nZscale = 1\n*\n1 2 3\n", "short.sdf");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("3 values"), std::string::npos) << bad.error().message;
}

TEST(DetectNpy, EveryTypeOrderAndEndianness) {
  // heights[j][i] = 10 j + i, shape (2, 3).
  const std::vector<double> c_order = {0, 1, 2, 10, 11, 12}, f_order = {0, 10, 1, 11, 2, 12};
  struct Case {
    std::string bytes;
    const char* what;
  };
  std::vector<Case> cases = {
      {npy("<f8", false, "(2, 3)", raw(c_order, false)), "<f8 C"},
      {npy(">f8", false, "(2, 3)", raw(c_order, true)), ">f8 C"},
      {npy("<f4", true, "(2, 3)", raw(std::vector<float>(f_order.begin(), f_order.end()), false)), "<f4 F"},
      {npy(">f4", false, "(2, 3)", raw(std::vector<float>(c_order.begin(), c_order.end()), true)), ">f4 C"},
      {npy("<i2", true, "(2, 3)", raw(std::vector<std::int16_t>(f_order.begin(), f_order.end()), false)), "<i2 F"},
      {npy(">i2", false, "(2, 3)", raw(std::vector<std::int16_t>(c_order.begin(), c_order.end()), true)), ">i2 C"},
      {npy("<i4", false, "(2, 3)", raw(std::vector<std::int32_t>(c_order.begin(), c_order.end()), false)), "<i4 C"},
      {npy(">i4", true, "(2, 3)", raw(std::vector<std::int32_t>(f_order.begin(), f_order.end()), true)), ">i4 F"},
  };
  frictal::ReadOptions o;
  o.default_unit = "nm";
  o.spacing = 1e-6;
  for (const auto& c : cases) {
    auto s = frictal::read_surface_bytes(c.bytes, "a.npy", o);
    ASSERT_TRUE(s.ok()) << c.what << ": " << s.error().message;
    ASSERT_TRUE(s->is_map) << c.what;
    EXPECT_EQ(s->format, frictal::ProfileFormat::Npy);
    ASSERT_EQ(s->map.nx, 3u) << c.what;
    ASSERT_EQ(s->map.ny, 2u) << c.what;
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(s->map.at(i, j), (10 * j + i) * 1e-9) << c.what;
    EXPECT_DOUBLE_EQ(s->map.dx, 1e-6);
  }
}

TEST(DetectNpy, OneDimensionalIsAProfileAndSizesAreChecked) {
  auto bytes = npy("<f8", false, "(4,)", raw(std::vector<double>{1, 2, NAN, 4}, false));
  auto s = frictal::read_surface_bytes(bytes, "p.npy", with_spacing(0.5));
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_FALSE(s->is_map);
  ASSERT_EQ(s->curve.size(), 3u);
  EXPECT_DOUBLE_EQ(s->curve.x[2], 1.5);
  EXPECT_DOUBLE_EQ(s->curve.z[2], 4);
  auto nospacing = frictal::read_surface_bytes(bytes, "p.npy");
  ASSERT_FALSE(nospacing.ok());
  EXPECT_NE(nospacing.error().message.find("spacing"), std::string::npos);
  // One value short: the size check names both sizes.
  auto shortf =
      frictal::read_surface_bytes(npy("<f8", false, "(2, 3)", raw(std::vector<double>(5, 1.0), false)), "s.npy");
  ASSERT_FALSE(shortf.ok());
  EXPECT_NE(shortf.error().message.find("40 bytes"), std::string::npos) << shortf.error().message;
  EXPECT_NE(shortf.error().message.find("48"), std::string::npos) << shortf.error().message;
  auto cplx = frictal::read_surface_bytes(npy("<c16", false, "(1,)", std::string(16, '\0')), "c.npy");
  ASSERT_FALSE(cplx.ok());
  EXPECT_NE(cplx.error().message.find("not supported"), std::string::npos);
  auto huge = frictal::read_surface_bytes(npy("<f8", false, "(100000, 100000)", ""), "h.npy");
  ASSERT_FALSE(huge.ok());
  EXPECT_NE(huge.error().message.find("limit"), std::string::npos);
}

TEST(DetectGzip, CompressedTextReadsAsItsContent) {
  const std::string csv = "x (um),z (nm)\n0,1\n1,2\n2,-3\n";
  const std::string path = ::testing::TempDir() + "frictal_detect.csv.gz";
  {
    std::ofstream f(path, std::ios::binary);
    f << gzip_stored(csv);
  }
  auto s = frictal::read_surface(path);
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_FALSE(s->is_map);
  ASSERT_EQ(s->curve.size(), 3u);
  EXPECT_DOUBLE_EQ(s->curve.x[2], 2e-6);
  EXPECT_DOUBLE_EQ(s->curve.z[2], -3e-9);
  EXPECT_EQ(s->reader, "native (gzip)");
  // A gzip-compressed Gwyddion text matrix.
  auto m =
      frictal::read_surface_bytes(gzip_stored("# Width: 2 um\n# Height: 1 um\n# Value units: nm\n1 2\n"), "m.txt.gz");
  ASSERT_TRUE(m.ok()) << m.error().message;
  ASSERT_TRUE(m->is_map);
  EXPECT_DOUBLE_EQ(m->map.at(1, 0), 2e-9);
  // Truncated: an error, not a crash or a partial read.
  std::string g = gzip_stored(csv);
  auto t = frictal::read_surface_bytes(g.substr(0, g.size() - 20), "t.csv.gz");
  ASSERT_FALSE(t.ok());
  EXPECT_NE(t.error().message.find("gzip"), std::string::npos) << t.error().message;
  // The uncompressed size is limited.
  frictal::ReadOptions o;
  o.max_bytes = 10;
  EXPECT_FALSE(frictal::read_surface_bytes(g, "big.csv.gz", o).ok());
}

TEST(DetectText, TwoColumnsTakeTheHeadersUnits) {
  // Each axis its own unit by key; one unit for the whole file; a word that is no length unit is
  // an error naming it (not metres).
  auto a = frictal::read_surface_bytes("# x unit: um\n# z unit: nm\n0 1.5\n2 -3\n4 2\n", "a.txt");
  ASSERT_TRUE(a.ok()) << a.error().message;
  ASSERT_FALSE(a->is_map);
  EXPECT_DOUBLE_EQ(a->curve.x[1], 2e-6);
  EXPECT_DOUBLE_EQ(a->curve.z[1], -3e-9);
  EXPECT_FALSE(has_warning(*a, "no length unit"));
  auto b = frictal::read_surface_bytes("# Units: mm\n0 1.5\n2 -3\n4 2\n", "b.txt");
  ASSERT_TRUE(b.ok()) << b.error().message;
  EXPECT_DOUBLE_EQ(b->curve.x[2], 4e-3);
  EXPECT_DOUBLE_EQ(b->curve.z[0], 1.5e-3);
  auto c = frictal::read_surface_bytes("# Units: counts\n0 1.5\n2 -3\n4 2\n", "c.txt");
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error().message.find("'counts' in the header is not a length unit"), std::string::npos)
      << c.error().message;
}

TEST(DetectText, AProfileWithXDecreasingIsReadInReverseOrder) {
  auto s = frictal::read_surface_bytes("x [um],z [nm]\n4,2\n2,-3\n0,1.5\n", "back.csv");
  ASSERT_TRUE(s.ok()) << s.error().message;
  const double ex[] = {0, 2e-6, 4e-6}, ez[] = {1.5e-9, -3e-9, 2e-9};
  for (int k = 0; k < 3; ++k) {
    EXPECT_DOUBLE_EQ(s->curve.x[k], ex[k]);
    EXPECT_DOUBLE_EQ(s->curve.z[k], ez[k]);
  }
  EXPECT_TRUE(has_warning(*s, "read in reverse order"));
  // x that goes back and forth is neither a reversed profile nor a rounded grid: kept as read (a
  // folded curve).
  auto f = frictal::read_surface_bytes("x,z\n0,0\n2,1\n1,2\n3,0\n", "fold.csv");
  ASSERT_TRUE(f.ok()) << f.error().message;
  EXPECT_DOUBLE_EQ(f->curve.x[2], 1);
  EXPECT_FALSE(has_warning(*f, "reverse order"));
}
