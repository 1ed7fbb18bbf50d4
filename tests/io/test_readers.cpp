// Reading every measured file in tests/data (provenance in tests/data/README.md). Expected values come from the files'
// own numbers, parsed here with a deliberately trivial method (replace separators by spaces, istringstream), times the
// unit the file states (µm = 1e-6 m, nm = 1e-9 m), or from the values written in the X3P XML / computed with python3
// struct from the binary members (stated where used).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "frictal/io.hpp"
#include "frictal/warnings.hpp"
#include "io/zip_builder.hpp"

namespace {

const std::string kData = FRICTAL_TEST_DATA;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Rows of >= `cols` numbers; lines where the first `cols` fields are not all numbers are skipped.
std::vector<std::vector<double>> numeric_rows(const std::string& text, int cols) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    for (char& c : line)
      if (c == ',' || c == '\t' || c == '\r' || c == ';') c = ' ';
    std::istringstream ls(line);
    std::vector<double> r(cols);
    bool ok = true;
    for (int k = 0; k < cols && ok; ++k) ok = bool(ls >> r[k]);
    std::string rest;
    if (ok && !(ls >> rest)) rows.push_back(r);
  }
  return rows;
}

// Trapezoid (piecewise-linear) mean and rms about the mean, computed from points directly.
std::pair<double, double> pl_mean_rms(const std::vector<double>& x, const std::vector<double>& z) {
  double L = x.back() - x.front(), m = 0;
  for (std::size_t k = 1; k < x.size(); ++k) m += 0.5 * (z[k] + z[k - 1]) * (x[k] - x[k - 1]);
  m /= L;
  double s = 0;
  for (std::size_t k = 1; k < x.size(); ++k) {
    double a = z[k - 1] - m, b = z[k] - m;
    s += (a * a + a * b + b * b) / 3 * (x[k] - x[k - 1]);
  }
  return {m, std::sqrt(s / L)};
}

void expect_points(const frictal::Curve& c, const std::vector<std::vector<double>>& rows, int xc, int zc, double xs,
                   double zs) {
  ASSERT_EQ(c.x.size(), rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_DOUBLE_EQ(c.x[k], rows[k][xc] * xs) << "point " << k;
    EXPECT_DOUBLE_EQ(c.z[k], rows[k][zc] * zs) << "point " << k;
  }
}

// An x column that is uniform within its printed digits is read as the uniform grid from its first
// to its last value (docs/io.md): each x within `half_unit` (the printing's half unit, in the
// file's unit) of the value printed, the steps all equal; z as printed.
void expect_grid_points(const frictal::Curve& c, const std::vector<std::vector<double>>& rows, int xc, int zc,
                        double xs, double zs, double half_unit) {
  ASSERT_EQ(c.x.size(), rows.size());
  const std::size_t n = rows.size();
  const double dx = (rows[n - 1][xc] - rows[0][xc]) * xs / double(n - 1);
  for (std::size_t k = 0; k < n; ++k) {
    EXPECT_NEAR(c.x[k], rows[0][xc] * xs + double(k) * dx, 1e-9 * std::abs(dx)) << "point " << k;
    EXPECT_LE(std::abs(c.x[k] - rows[k][xc] * xs), 2 * half_unit * xs) << "point " << k;
    EXPECT_DOUBLE_EQ(c.z[k], rows[k][zc] * zs) << "point " << k;
  }
}

}  // namespace

TEST(ReadText, Csv1MicronsHeader) {
  std::string path = kData + "/profiles/csv-1.csv";
  auto s = frictal::read_surface(path);
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(s->format, frictal::ProfileFormat::Csv);
  EXPECT_FALSE(s->is_map);
  // Header "X_(microns),y1": x in µm; z has no unit, read as metres with a warning.
  auto rows = numeric_rows(slurp(path), 2);
  ASSERT_EQ(rows.size(), 8u);
  // x printed with 4 decimals (0.0386, 0.0772, ... 0.2703: steps of 0.0386 and 0.0387 um):
  // within its digits a uniform grid, read as one, with a note.
  expect_grid_points(s->curve, rows, 0, 1, 1e-6, 1.0, 0.5e-4);
  EXPECT_FALSE(s->warnings.empty());
  bool grid_note = false;
  for (const auto& w : s->warnings) grid_note = grid_note || w.message.find("uniform grid") != std::string::npos;
  EXPECT_TRUE(grid_note);
  // With an explicit unit for unlabeled columns the z column follows it.
  frictal::ReadOptions o;
  o.default_unit = "um";
  auto p = frictal::read_profile(path, o);
  ASSERT_TRUE(p.ok());
  EXPECT_DOUBLE_EQ(p->z[0], 2.10425e-6);
}

TEST(ReadText, Csv2Utf16IndexColumnUnits) {
  std::string path = kData + "/profiles/csv-2.csv";
  std::string raw = slurp(path), ascii;
  // UTF-16LE with BOM: for ASCII characters the text is every even byte after the BOM.
  for (std::size_t k = 2; k < raw.size(); k += 2)
    if ((unsigned char)raw[k] < 0x80 && raw[k + 1] == 0) ascii += raw[k];
  auto rows = numeric_rows(ascii, 3);
  ASSERT_EQ(rows.size(), 8u);
  auto s = frictal::read_surface(path);
  ASSERT_TRUE(s.ok()) << s.error().message;
  // Header "index,x in µm,y in µm": column 0 is an index; x and z are in µm.
  expect_points(s->curve, rows, 1, 2, 1e-6, 1e-6);
  EXPECT_NEAR(s->curve.x[0], -99.958333333333333e-6, 1e-18);
}

TEST(ReadText, DektakLatin1ScanData) {
  std::string path = kData + "/profiles/dektak-1.csv";
  std::string raw = slurp(path);
  auto pos = raw.find("Scan Data");
  ASSERT_NE(pos, std::string::npos);
  auto rows = numeric_rows(raw.substr(pos), 2);
  ASSERT_EQ(rows.size(), 9600u);  // README: 9,600 points over 1,500 um
  auto s = frictal::read_surface(path);
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(s->format, frictal::ProfileFormat::Dektak);
  // "Lateral um,Raw Micrometer": both columns in micrometres; x printed with one decimal, steps
  // alternating 0.1 and 0.2 um: the uniform grid of 1499.8 / 9599 um.
  expect_grid_points(s->curve, rows, 0, 1, 1e-6, 1e-6, 0.05);
  EXPECT_NEAR(s->curve.x.back() - s->curve.x.front(), 1499.8e-6, 1e-12);
  std::vector<double> x, z;
  for (auto& r : rows) {
    x.push_back(r[0] * 1e-6);
    z.push_back(r[1] * 1e-6);
  }
  auto [m, rms] = pl_mean_rms(x, z);
  EXPECT_GT(rms, 1e-6);  // strong tilt/form: several micrometres
  (void)m;
}

TEST(ReadText, XyWhitespaceNoUnit) {
  for (const char* f : {"/profiles/xy-1.txt", "/profiles/nonuniform.asc"}) {
    std::string path = kData + f;
    auto rows = numeric_rows(slurp(path), 2);
    auto s = frictal::read_surface(path);
    ASSERT_TRUE(s.ok()) << s.error().message;
    expect_points(s->curve, rows, 0, 1, 1.0, 1.0);
    EXPECT_FALSE(s->warnings.empty()) << "no unit: a warning says metres were assumed";
  }
  EXPECT_EQ(numeric_rows(slurp(kData + "/profiles/xy-1.txt"), 2).size(), 132u);
}

TEST(ReadText, Xy2UnitLineAndCountLine) {
  std::string path = kData + "/profiles/xy-2.txt";
  auto rows = numeric_rows(slurp(path), 2);
  ASSERT_EQ(rows.size(), 24u);
  auto s = frictal::read_surface(path);
  ASSERT_TRUE(s.ok()) << s.error().message;
  expect_points(s->curve, rows, 0, 1, 1e-6, 1e-6);  // unit line "µm µm"
  ASSERT_FALSE(s->warnings.empty());                // count line says 23, 24 rows follow
  EXPECT_NE(s->warnings[0].message.find("23"), std::string::npos);
  // The reader gives its own warnings their code, one that `frictal warnings` lists.
  EXPECT_EQ(s->warnings[0].code, "reader");
  EXPECT_NE(frictal::find_warning_code(s->warnings[0].code), nullptr);
}

TEST(ReadText, GwyddionEnglishGerman) {
  for (const char* f : {"/maps/gwyddion-export-english.txt", "/maps/gwyddion-export-german.txt"}) {
    auto s = frictal::read_surface(kData + f);
    ASSERT_TRUE(s.ok()) << s.error().message;
    ASSERT_TRUE(s->is_map);
    const auto& m = s->map;
    ASSERT_EQ(m.nx, 3u);
    ASSERT_EQ(m.ny, 4u);
    // Width 12.34 µm over 3 columns, Height 5678.9 nm over 4 rows (Gwyddion: real size = n * d).
    EXPECT_DOUBLE_EQ(m.dx, 12.34e-6 / 3);
    EXPECT_DOUBLE_EQ(m.dy, 5678.9e-9 / 4);
    const double expect[] = {1, 1.5, 3, -2, -3, -6, 0, 0, 0, 9, 9, 9};  // Value units: m
    for (int k = 0; k < 12; ++k) EXPECT_EQ(m.heights[k], expect[k]);
  }
}

TEST(ReadText, Matrix6) {
  auto m = frictal::read_map(kData + "/maps/matrix-6.txt");
  ASSERT_TRUE(m.ok()) << m.error().message;
  ASSERT_EQ(m->nx, 4u);
  ASSERT_EQ(m->ny, 3u);
  EXPECT_DOUBLE_EQ(m->dx, 10e-6 / 4);
  EXPECT_DOUBLE_EQ(m->dy, 10e-6 / 3);
  for (int k = 0; k < 12; ++k) EXPECT_EQ(m->heights[k], k + 1.0);
}

namespace {
// The 16 values written in ISO5436-sample1.x3p's DataList (x fastest); index 7 is <Datum/>.
const double kSample1[16] = {
    4.86219120804151E-0001, 3.46341436648013E-0003, -8.08368571682830E-0001, -5.79793099037002E-0001,
    8.57622027393310E-0001, 1.04759602566142E+0000, 1.01879225277798E+0000,  NAN,
    8.23683772970184E-0001, 7.97872489327661E-0001, -5.57459388341694E-0001, -2.33247858849220E-0001,
    6.75397146760858E-0001, 4.20737549074718E-0001, 6.42069248110950E-0001,  -2.15696638464903E-0001};
}  // namespace

TEST(ReadX3p, Sample1XmlAndBinary) {
  for (const char* f : {"/x3p/ISO5436-sample1.x3p", "/x3p/ISO5436-sample1_bin.x3p"}) {
    auto s = frictal::read_surface(kData + f);
    ASSERT_TRUE(s.ok()) << s.error().message;
    EXPECT_TRUE(s->warnings.empty()) << s->warnings[0].message;  // checksums are correct in these files
    ASSERT_TRUE(s->is_map);
    const auto& m = s->map;
    ASSERT_EQ(m.nx, 4u);
    ASSERT_EQ(m.ny, 4u);
    EXPECT_DOUBLE_EQ(m.dx, 1.6016e-2);
    EXPECT_DOUBLE_EQ(m.dy, 1.6016e-2);
    for (int k = 0; k < 16; ++k) {
      if (std::isnan(kSample1[k]))
        EXPECT_TRUE(std::isnan(m.heights[k])) << f;  // empty Datum / valid.bin bit 7 = 0
      else
        EXPECT_DOUBLE_EQ(m.heights[k], kSample1[k]) << f << " " << k;
    }
  }
}

TEST(ReadX3p, Sample2PointListOnGrid) {
  // PCL, ListDimension 16, absolute x;y;z. CX Offset 0.1, CY Offset 2, CZ Offset 2 (value =
  // Offset + Increment * raw, Increment 1): x = 0.1 + {0..3}e-6, y = 2 + {0..3}e-6, z = 2 + listed.
  auto m = frictal::read_map(kData + "/x3p/ISO5436-sample2.x3p");
  ASSERT_TRUE(m.ok()) << m.error().message;
  ASSERT_EQ(m->nx, 4u);
  ASSERT_EQ(m->ny, 4u);
  EXPECT_NEAR(m->dx, 1e-6, 1e-15);
  EXPECT_NEAR(m->dy, 1e-6, 1e-15);
  EXPECT_DOUBLE_EQ(m->x0, 0.1);
  EXPECT_DOUBLE_EQ(m->y0, 2.0);
  EXPECT_DOUBLE_EQ(m->heights[0], 2 + 4.86219120804151E-0001);
  EXPECT_DOUBLE_EQ(m->heights[7], 2 + 3.46341436648013E-0003);
  EXPECT_DOUBLE_EQ(m->heights[15], 2 + -2.15696638464903E-0001);
}

TEST(ReadX3p, Sample3AbsoluteY) {
  // CY absolute, int: y = 1 + 2 * {1,2,3,4} = 3..9, so y0 = 3 and dy = 2; z = 2 + listed.
  auto m = frictal::read_map(kData + "/x3p/ISO5436-sample3.x3p");
  ASSERT_TRUE(m.ok()) << m.error().message;
  EXPECT_DOUBLE_EQ(m->y0, 3.0);
  EXPECT_DOUBLE_EQ(m->dy, 2.0);
  EXPECT_DOUBLE_EQ(m->x0, 0.1);
  EXPECT_DOUBLE_EQ(m->dx, 1.6016e-2);
  for (int k = 0; k < 16; ++k) {
    if (std::isnan(kSample1[k]))
      EXPECT_TRUE(std::isnan(m->heights[k]));
    else
      EXPECT_DOUBLE_EQ(m->heights[k], 2 + kSample1[k]);
  }
}

TEST(ReadX3p, Sample4Int16IncrementOffset) {
  // CZ int16, Increment 0.001, Offset -0.5: z = -0.5 + 0.001 * raw; raw from the DataList.
  const int raw[16] = {986, 503, -308, -80, 1358, 1548, 1519, 0, 1324, 1298, -57, 267, 1175, 921, 1142, 284};
  for (const char* f : {"/x3p/ISO5436-sample4.x3p", "/x3p/ISO5436-sample4_bin.x3p"}) {
    auto m = frictal::read_map(kData + f);
    ASSERT_TRUE(m.ok()) << m.error().message;
    for (int k = 0; k < 16; ++k) {
      if (k == 7)
        EXPECT_TRUE(std::isnan(m->heights[k])) << f;
      else
        EXPECT_DOUBLE_EQ(m->heights[k], -0.5 + 0.001 * raw[k]) << f << " " << k;
    }
  }
}

TEST(ReadX3p, PyramidFloat32) {
  // data.bin decoded with python3 struct.unpack('<25f'): a 5 x 5 pyramid of 2, 6, 10.
  auto m = frictal::read_map(kData + "/x3p/pyramid.x3p");
  ASSERT_TRUE(m.ok()) << m.error().message;
  ASSERT_EQ(m->nx, 5u);
  const double e[25] = {2, 2, 2, 2, 2, 2, 6, 6, 6, 2, 2, 6, 10, 6, 2, 2, 6, 6, 6, 2, 2, 2, 2, 2, 2};
  for (int k = 0; k < 25; ++k) EXPECT_EQ(m->heights[k], e[k]);
}

TEST(ReadX3p, SampleLandSubfolderNoNamespaceNaN) {
  // Values from python3: struct.unpack('<235008d') of sample-land/bindata/data.bin; mean and
  // population rms about the mean over the non-NaN points.
  auto s = frictal::read_surface(kData + "/x3p/sample-land.x3p");
  ASSERT_TRUE(s.ok()) << s.error().message;
  const auto& m = s->map;
  ASSERT_EQ(m.nx, 918u);
  ASSERT_EQ(m.ny, 256u);
  EXPECT_DOUBLE_EQ(m.dx, 2.58e-6);
  EXPECT_EQ(m.valid_count(), 209716u);
  double sum = 0, n = 0;
  for (double v : m.heights)
    if (!std::isnan(v)) {
      sum += v;
      ++n;
    }
  double mean = sum / n, ss = 0;
  for (double v : m.heights)
    if (!std::isnan(v)) ss += (v - mean) * (v - mean);
  EXPECT_NEAR(mean, -5.3520683475475706e-07, 1e-18);
  EXPECT_NEAR(std::sqrt(ss / n), 3.4334274890691285e-05, 1e-15);
  EXPECT_DOUBLE_EQ(m.heights[0], -5.421108289738186e-05);
  bool subfolder = false, ns = false;
  for (auto& w : s->warnings) {
    subfolder |= w.message.find("sub-folder") != std::string::npos;
    ns |= w.message.find("namespace") != std::string::npos;
  }
  EXPECT_TRUE(subfolder);
  EXPECT_TRUE(ns);
}

TEST(ReadX3p, MountainsMap650UpperCaseMd5) {
  auto s = frictal::read_surface(kData + "/x3p/x3p-2.x3p");
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_TRUE(s->warnings.empty()) << s->warnings[0].message;  // upper-case MD5 hex still matches
  const auto& m = s->map;
  ASSERT_EQ(m.nx, 650u);
  ASSERT_EQ(m.ny, 650u);
  EXPECT_DOUBLE_EQ(m.dx, 1.27656509837346e-007);
  EXPECT_DOUBLE_EQ(m.dy, 3.14582113527746e-007);
  EXPECT_DOUBLE_EQ(m.x0, 7.65614218798151e-005);
  // python3 struct.unpack of data.bin: first, second and last values.
  EXPECT_EQ(m.heights[0], 6.5797813412232884e-08);
  EXPECT_EQ(m.heights[1], 7.4191213412232881e-08);
  EXPECT_EQ(m.heights.back(), -3.2769186587767108e-08);
}

// ---- crafted archives: quirks and damage -------------------------------------------------

namespace {

std::string tiny_xml(const std::string& root_open, const std::string& root_close, const std::string& record3,
                     const std::string& cz = "<AxisType>A</AxisType><DataType>D</DataType>") {
  return "<?xml version=\"1.0\"?>" + root_open +
         "<Record1><Revision>ISO5436 - 2000</Revision><FeatureType>SUR</FeatureType><Axes>"
         "<CX><AxisType>I</AxisType><DataType>D</DataType><Increment>1e-6</Increment><Offset></Offset></CX>"
         "<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>2e-6</Increment><Offset/></CY>"
         "<CZ>" +
         cz + "</CZ></Axes></Record1><Record3>" + record3 +
         "</Record3><Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4>" + root_close;
}
const std::string kNsOpen = "<p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\">";
const std::string kNsClose = "</p:ISO5436_2>";
const std::string kList2x2 =
    "<MatrixDimension><SizeX>2</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ></MatrixDimension>"
    "<DataList><Datum>1</Datum><Datum>2</Datum><Datum>3</Datum><Datum>4</Datum></DataList>";

bool has_warning(const frictal::SurfaceData& s, const char* what) {
  for (auto& w : s.warnings)
    if (w.message.find(what) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST(ReadX3p, StaleChecksumIsAWarning) {
  std::string xml = tiny_xml(kNsOpen, kNsClose, kList2x2);
  std::string zip = frictal::test::zip_stored(
      {{"main.xml", xml}, {"md5checksum.hex", "0123456789abcdef0123456789abcdef *main.xml\n"}});
  auto s = frictal::read_surface_bytes(zip, "stale.x3p");
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_TRUE(has_warning(*s, "MD5"));
  EXPECT_EQ(s->map.heights[3], 4.0);
  EXPECT_DOUBLE_EQ(s->map.dy, 2e-6);
  EXPECT_EQ(s->map.x0, 0.0);  // empty Offset
}

TEST(ReadX3p, MissingChecksumAndSubfolder) {
  std::string xml = tiny_xml("<ISO5436_2>", "</ISO5436_2>", kList2x2);
  auto s = frictal::read_surface_bytes(frictal::test::zip_stored({{"scan/main.xml", xml}}), "sub.x3p");
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_TRUE(has_warning(*s, "sub-folder"));
  EXPECT_TRUE(has_warning(*s, "checksum"));
}

TEST(ReadX3p, DamagedInputsAreErrors) {
  auto err = [](const std::string& bytes) {
    auto s = frictal::read_surface_bytes(bytes, "bad.x3p");
    EXPECT_FALSE(s.ok());
    return s.ok() ? std::string() : s.error().message;
  };
  std::string good = frictal::test::zip_stored({{"main.xml", tiny_xml(kNsOpen, kNsClose, kList2x2)}});
  // Truncated archive.
  EXPECT_NE(err(good.substr(0, good.size() / 2)).find("bad.x3p"), std::string::npos);
  // Binary data with the wrong size.
  std::string link =
      "<MatrixDimension><SizeX>2</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ></MatrixDimension>"
      "<DataLink><PointDataLink>bindata/data.bin</PointDataLink></DataLink>";
  auto m = err(frictal::test::zip_stored(
      {{"main.xml", tiny_xml(kNsOpen, kNsClose, link)}, {"bindata/data.bin", std::string(31, '\0')}}));
  EXPECT_NE(m.find("32"), std::string::npos) << m;
  // Absurd dimensions: refused before allocating.
  std::string huge =
      "<MatrixDimension><SizeX>100000000</SizeX><SizeY>100000000</SizeY><SizeZ>1</SizeZ></MatrixDimension>"
      "<DataLink><PointDataLink>bindata/data.bin</PointDataLink></DataLink>";
  m = err(frictal::test::zip_stored({{"main.xml", tiny_xml(kNsOpen, kNsClose, huge)}}));
  EXPECT_NE(m.find("limit"), std::string::npos) << m;
  // Bad number, too few points, missing main.xml, not a zip, bad XML.
  std::string bad =
      "<MatrixDimension><SizeX>2</SizeX><SizeY>1</SizeY><SizeZ>1</SizeZ></MatrixDimension>"
      "<DataList><Datum>1.5x</Datum><Datum>2</Datum></DataList>";
  EXPECT_NE(err(frictal::test::zip_stored({{"main.xml", tiny_xml(kNsOpen, kNsClose, bad)}})).find("1.5x"),
            std::string::npos);
  std::string few =
      "<MatrixDimension><SizeX>2</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ></MatrixDimension>"
      "<DataList><Datum>1</Datum></DataList>";
  EXPECT_NE(err(frictal::test::zip_stored({{"main.xml", tiny_xml(kNsOpen, kNsClose, few)}})).find("declared"),
            std::string::npos);
  EXPECT_NE(err(frictal::test::zip_stored({{"other.xml", "x"}})).find("main.xml"), std::string::npos);
  EXPECT_NE(err(frictal::test::zip_stored({{"main.xml", "<a><b></a>"}})).find("XML"), std::string::npos);
  frictal::ReadOptions o;
  o.format = frictal::ProfileFormat::X3p;
  EXPECT_FALSE(frictal::read_surface_bytes("hello", "t.txt", o).ok());
}

TEST(ReadText, BadInputsAreErrors) {
  auto msg = [](const std::string& text) {
    auto s = frictal::read_surface_bytes(text, "t.csv");
    EXPECT_FALSE(s.ok()) << text;
    return s.ok() ? std::string() : s.error().message;
  };
  EXPECT_NE(msg("x,z\n1,2\n2,3\nfoo,bar\n3,4\n").find(":4:"), std::string::npos);
  EXPECT_NE(msg("x,z\n1,2\n2,3,4\n").find(":3:"), std::string::npos);
  EXPECT_NE(msg("hello\nworld\n").find("no numeric"), std::string::npos);
  EXPECT_NE(msg("1\n2\n3\n").find("two columns"), std::string::npos);
  EXPECT_FALSE(frictal::read_surface("/nonexistent/file.csv").ok());
  // Latin-1 µm in a header, semicolons with decimal commas, TSV with nm.
  auto a = frictal::read_surface_bytes("x (\xb5m);z (nm)\n0,5;1,5\n1,0;2,5\n", "latin.csv");
  ASSERT_TRUE(a.ok()) << a.error().message;
  EXPECT_DOUBLE_EQ(a->curve.x[0], 0.5e-6);
  EXPECT_DOUBLE_EQ(a->curve.z[1], 2.5e-9);
  auto b = frictal::read_surface_bytes("# comment\nx [mm]\tz [mm]\n0\t1\n2\t3\n", "t.tsv");
  ASSERT_TRUE(b.ok()) << b.error().message;
  EXPECT_DOUBLE_EQ(b->curve.x[1], 2e-3);
  EXPECT_DOUBLE_EQ(b->curve.z[1], 3e-3);
  EXPECT_TRUE(b->warnings.empty());
}

TEST(ReadText, CommentedProfileIsNotAMapAndFrenchGwyddionIs) {
  auto p = frictal::read_surface_bytes("# Length: 10 um\n# Resolution: 1 um\n0 1\n1 2\n2 3\n", "p.txt");
  ASSERT_TRUE(p.ok()) << p.error().message;
  EXPECT_FALSE(p->is_map);
  // Gwyddion in French: Largeur/Hauteur; 2 x 2 nodes -> dx = 4 um / 2, dy = 6 nm / 2.
  auto m = frictal::read_surface_bytes(
      "# Canal: a\n# Largeur: 4 \xc2\xb5m\n# Hauteur: 6 nm\n# Value units: nm\n1 2\n3 NaN\n", "fr.txt");
  ASSERT_TRUE(m.ok()) << m.error().message;
  ASSERT_TRUE(m->is_map);
  EXPECT_DOUBLE_EQ(m->map.dx, 2e-6);
  EXPECT_DOUBLE_EQ(m->map.dy, 3e-9);
  EXPECT_DOUBLE_EQ(m->map.heights[2], 3e-9);
  EXPECT_TRUE(std::isnan(m->map.heights[3]));
}

TEST(ReadText, Utf16BigEndianAndBomlessLittleEndian) {
  const std::string ascii = "x (nm),z (nm)\n1,2\n3,4\n";
  std::string be = "\xFE\xFF", le;
  for (char c : ascii) {
    be += '\0';
    be += c;
    le += c;
    le += '\0';
  }
  for (const auto& bytes : {be, le}) {
    auto s = frictal::read_surface_bytes(bytes, "u16.csv");
    ASSERT_TRUE(s.ok()) << s.error().message;
    EXPECT_DOUBLE_EQ(s->curve.x[1], 3e-9);
    EXPECT_DOUBLE_EQ(s->curve.z[1], 4e-9);
  }
}

TEST(ReadText, LimitsAndForcedFormats) {
  frictal::ReadOptions o;
  o.max_points = 2;
  auto s = frictal::read_surface_bytes("0 0\n1 1\n2 2\n", "big.txt", o);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("max_points"), std::string::npos);
  o = {};
  o.max_bytes = 100;
  auto f = frictal::read_surface(std::string(FRICTAL_TEST_DATA) + "/profiles/xy-1.txt", o);
  ASSERT_FALSE(f.ok());
  EXPECT_NE(f.error().message.find("limit"), std::string::npos);
  // Forcing Gwyddion on a two-column profile reads it as a 2-column map; forcing Dektak on a
  // file without "Scan Data" is an error naming the section.
  o = {};
  o.format = frictal::ProfileFormat::Gwyddion;
  auto g = frictal::read_surface_bytes("0 1\n2 3\n", "m.txt", o);
  ASSERT_TRUE(g.ok());
  EXPECT_TRUE(g->is_map);
  o.format = frictal::ProfileFormat::Dektak;
  auto d = frictal::read_surface_bytes("0 1\n2 3\n", "d.csv", o);
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.error().message.find("Scan Data"), std::string::npos);
  EXPECT_FALSE(frictal::parse_format("bmp").ok());
  EXPECT_EQ(*frictal::parse_format("X3P"), frictal::ProfileFormat::X3p);
}

TEST(ReadX3p, ProfileWithMaskDropsInvalidPoints) {
  // PRF, 5 points, int32 z = 1e-9 * raw, valid.bin 0b11011 (point 2 invalid).
  std::string xml =
      "<?xml version=\"1.0\"?><p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\"><Record1>"
      "<FeatureType>PRF</FeatureType><Axes>"
      "<CX><AxisType>I</AxisType><DataType>D</DataType><Increment>0.5e-6</Increment><Offset>1e-6</Offset></CX>"
      "<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>1</Increment><Offset>0</Offset></CY>"
      "<CZ><AxisType>A</AxisType><DataType>L</DataType><Increment>1e-9</Increment><Offset>0</Offset></CZ>"
      "</Axes></Record1><Record3><MatrixDimension><SizeX>5</SizeX><SizeY>1</SizeY><SizeZ>1</SizeZ></MatrixDimension>"
      "<DataLink><PointDataLink>bindata/data.bin</PointDataLink><ValidPointsLink>bindata/valid.bin</ValidPointsLink>"
      "</DataLink></Record3></p:ISO5436_2>";
  std::string data;
  for (std::int32_t v : {10, -20, 30, -40, 50})
    for (int b = 0; b < 4; ++b) data += char((std::uint32_t(v) >> (8 * b)) & 0xFF);
  auto s = frictal::read_surface_bytes(
      frictal::test::zip_stored({{"main.xml", xml}, {"bindata/data.bin", data}, {"bindata/valid.bin", "\x1b"}}),
      "prf.x3p");
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_FALSE(s->is_map);
  ASSERT_EQ(s->curve.size(), 4u);
  const double ex[] = {1e-6, 1.5e-6, 2.5e-6, 3e-6}, ez[] = {10e-9, -20e-9, -40e-9, 50e-9};
  for (int k = 0; k < 4; ++k) {
    EXPECT_DOUBLE_EQ(s->curve.x[k], ex[k]);
    EXPECT_DOUBLE_EQ(s->curve.z[k], ez[k]);
  }
}

TEST(ReadX3p, HugeDeclaredMemberSizeIsRefusedWithoutAllocating) {
  std::string link =
      "<MatrixDimension><SizeX>2</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ></MatrixDimension>"
      "<DataLink><PointDataLink>bindata/data.bin</PointDataLink></DataLink>";
  std::string zip = frictal::test::zip_stored(
      {{"main.xml", tiny_xml(kNsOpen, kNsClose, link)}, {"bindata/data.bin", std::string(32, '\0')}});
  // Patch the uncompressed size of data.bin (local header +22, central directory +24) to 1 GiB.
  auto patch = [&](std::size_t at) {
    zip[at] = 0;
    zip[at + 1] = 0;
    zip[at + 2] = 0;
    zip[at + 3] = 0x40;
  };
  std::size_t local = zip.find("PK\x03\x04", 1), central = zip.find("PK\x01\x02");
  central = zip.find("PK\x01\x02", central + 4);
  ASSERT_NE(local, std::string::npos);
  ASSERT_NE(central, std::string::npos);
  patch(local + 22);
  patch(central + 24);
  auto s = frictal::read_surface_bytes(zip, "bomb.x3p");
  ASSERT_FALSE(s.ok());
  // Refused from the declared size, before reading: "1073741824 bytes, but 4 points of 8 bytes need 32".
  EXPECT_NE(s.error().message.find("1073741824 bytes"), std::string::npos) << s.error().message;
}

// Large text files are parsed from a memory mapping, lines one at a time, and the
// delimiter is found from a tail of the file. A file of 6,000 rows separated by ';' with
// decimal commas, whose last 3,000 lines are comments and blank lines (so the tail holding 200
// data lines is longer than the first one looked at), CRLF line ends and a UTF-8 BOM: every
// value must come back as written (x = k/1000 mm, z = (k mod 7) - 3.5 um, units in the header).
TEST(ReadersLarge, MappedTextWithLongCommentTailReadsEveryRow) {
  const std::string path = ::testing::TempDir() + "frictal_large_mapped.csv";
  {
    std::ofstream out(path, std::ios::binary);
    out << "\xEF\xBB\xBFx [mm];z [um]\r\n";
    auto comma = [](double v, const char* fmt) {
      char buf[32];
      std::snprintf(buf, sizeof buf, fmt, v);
      std::string t(buf);
      for (char& ch : t)
        if (ch == '.') ch = ',';
      return t;
    };
    for (int k = 0; k < 6000; ++k) out << comma(k / 1000.0, "%.3f") << ";" << comma(k % 7 - 3.5, "%.1f") << "\r\n";
    for (int k = 0; k < 3000; ++k) out << (k % 2 ? "# note\r\n" : "\r\n");
  }
  auto c = frictal::read_curve(path);
  ASSERT_TRUE(c.ok()) << c.error().message;
  ASSERT_EQ(c->x.size(), 6000u);
  for (int k = 0; k < 6000; k += 397) {
    EXPECT_NEAR(c->x[k], k / 1000.0 * 1e-3, 1e-15) << k;
    EXPECT_NEAR(c->z[k], (k % 7 - 3.5) * 1e-6, 1e-18) << k;
  }
  std::remove(path.c_str());
}

#include "io/text_util.hpp"

namespace {
// A second, plain check of UTF-8: one character at a time, by its lead byte.
bool plain_utf8(const std::string& s) {
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    int more = c < 0x80 ? 0 : (c & 0xE0) == 0xC0 ? 1 : (c & 0xF0) == 0xE0 ? 2 : (c & 0xF8) == 0xF0 ? 3 : -1;
    if (more < 0) return false;                                                    // not a lead byte
    if (more > 0 && i + static_cast<std::size_t>(more) >= s.size()) return false;  // cut short
    for (int k = 1; k <= more; ++k)
      if ((static_cast<unsigned char>(s[i + static_cast<std::size_t>(k)]) & 0xC0) != 0x80) return false;
    i += static_cast<std::size_t>(more) + 1;
  }
  return true;
}
}  // namespace

// The UTF-8 check reads runs of ASCII 8 bytes at a time: every position of a multi-byte
// character, a stray continuation byte or a truncated sequence inside or after such runs must
// give what a one-character-at-a-time check gives.
TEST(TextDecoding, ValidUtf8AgreesWithAPlainCheckAtEveryPosition) {
  const std::vector<std::string> inserts = {"\xC2\xB5",     "\xE2\x82\xAC", "\xF0\x9F\x98\x80",
                                            "\xB5",         "\xC2",         "\xE2\x82",
                                            "\xC2\xB5\xB5", "\xFF",         "\xF0\x9F\x98"};
  int valid = 0, invalid = 0;
  for (std::size_t len = 0; len <= 24; ++len)
    for (std::size_t at = 0; at <= len; ++at)
      for (const std::string& ins : inserts) {
        std::string s(len, 'a');
        s.insert(at, ins);
        const bool want = plain_utf8(s);
        EXPECT_EQ(frictal::io_detail::valid_utf8(s), want) << "length " << len << ", at " << at;
        (want ? valid : invalid)++;
      }
  EXPECT_GT(valid, 0);
  EXPECT_GT(invalid, 0);
  EXPECT_TRUE(frictal::io_detail::valid_utf8(std::string(1000, 'x')));
  EXPECT_FALSE(frictal::io_detail::valid_utf8(std::string(999, 'x') + "\x80"));
}

// A mapped CSV is checked for UTF-8 32 MiB at a time: a file of 34 MB whose one multi-byte
// character (in a comment) straddles the 32 MiB mark reads every row, with the values written.
TEST(ReadersLarge, MappedTextCheckedInPiecesReadsACharacterAcrossTheirBoundary) {
  const std::string path = ::testing::TempDir() + "frictal_pieces.csv";
  constexpr std::size_t kMark = std::size_t{32} << 20;
  std::size_t rows = 0;
  {
    std::ofstream out(path, std::ios::binary);
    std::string text = "x_m,z_m\n";
    text.reserve(kMark + 4096);
    char buf[64];
    while (text.size() < kMark - 64) {
      const int n = std::snprintf(buf, sizeof buf, "%zu,%zu\n", rows, rows % 1000);
      text.append(buf, static_cast<std::size_t>(n));
      ++rows;
    }
    text += "# ";
    text.append(kMark - 1 - text.size(), 'c');  // "\xC2" ends at byte kMark - 1, "\xB5" starts the next piece
    text += "\xC2\xB5m\n# end\n";
    ASSERT_EQ(static_cast<unsigned char>(text[kMark]), 0xB5);
    out << text;
  }
  auto c = frictal::read_curve(path);
  ASSERT_TRUE(c.ok()) << c.error().message;
  ASSERT_EQ(c->x.size(), rows);
  for (std::size_t k = 0; k < rows; k += 99991) {
    EXPECT_EQ(c->x[k], static_cast<double>(k)) << k;
    EXPECT_EQ(c->z[k], static_cast<double>(k % 1000)) << k;
  }
  std::remove(path.c_str());
}
