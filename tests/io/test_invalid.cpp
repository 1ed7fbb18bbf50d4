// Invalid points, one rule for every format: NaN, +inf and -inf heights are dropped from a
// profile and masked (NaN) in a map, with one warning giving how many; they never stop a read
// and never enter a statistic. Expected values: the finite numbers written in each test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "frictal/analysis.hpp"
#include "frictal/io.hpp"
#include "io/zip_builder.hpp"

namespace {

std::size_t count_containing(const std::vector<frictal::Warning>& w, const std::string& what) {
  std::size_t n = 0;
  for (const auto& s : w) n += s.message.find(what) != std::string::npos;
  return n;
}

// A 3 x 2 SUR X3P whose data.bin holds `z` as float32 (F) or float64 (D), little-endian.
std::string x3p_sur(char type, const std::vector<double>& z, const std::string& valid = "") {
  std::string xml =
      "<?xml version=\"1.0\"?><p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\"><Record1>"
      "<FeatureType>SUR</FeatureType><Axes>"
      "<CX><AxisType>I</AxisType><DataType>D</DataType><Increment>1e-6</Increment><Offset>0</Offset></CX>"
      "<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>2e-6</Increment><Offset>0</Offset></CY>"
      "<CZ><AxisType>A</AxisType><DataType>" +
      std::string(1, type) +
      "</DataType></CZ></Axes></Record1><Record3><MatrixDimension><SizeX>3</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ>"
      "</MatrixDimension><DataLink><PointDataLink>bindata/data.bin</PointDataLink>" +
      (valid.empty() ? "" : "<ValidPointsLink>bindata/valid.bin</ValidPointsLink>") +
      "</DataLink></Record3></p:ISO5436_2>";
  std::string data;
  for (double v : z) {
    unsigned char b[8];
    std::size_t n = type == 'F' ? 4 : 8;
    if (type == 'F') {
      float f = float(v);
      std::memcpy(b, &f, 4);
    } else
      std::memcpy(b, &v, 8);
    for (std::size_t k = 0; k < n; ++k) data += char(b[k]);  // the test machine is little-endian (x86-64)
  }
  std::vector<std::pair<std::string, std::string>> members = {{"main.xml", xml}, {"bindata/data.bin", data}};
  if (!valid.empty()) members.push_back({"bindata/valid.bin", valid});
  return frictal::test::zip_stored(members);
}

const double kInf = std::numeric_limits<double>::infinity();
const double kNan = std::numeric_limits<double>::quiet_NaN();

}  // namespace

TEST(InvalidPoints, TextProfileEverySpellingIsDroppedWithOneWarning) {
  // z column: 1, inf, 2, -inf, NaN, nan, +Inf, Infinity, -INF, 3 (um); 7 invalid.
  const std::string text = "x (um),z (um)\n0,1\n1,inf\n2,2\n3,-inf\n4,NaN\n5,nan\n6,+Inf\n7,Infinity\n8,-INF\n9,3\n";
  auto s = frictal::read_surface_bytes(text, "inf.csv");
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_FALSE(s->is_map);
  ASSERT_EQ(s->curve.size(), 3u);
  const double ex[] = {0, 2e-6, 9e-6}, ez[] = {1e-6, 2e-6, 3e-6};
  for (int k = 0; k < 3; ++k) {
    EXPECT_DOUBLE_EQ(s->curve.x[k], ex[k]);
    EXPECT_DOUBLE_EQ(s->curve.z[k], ez[k]);
  }
  ASSERT_EQ(count_containing(s->warnings, "invalid point"), 1u);
  const std::string& w = s->warnings[0].message;
  EXPECT_NE(w.find("7 invalid points"), std::string::npos) << w;
  EXPECT_NE(w.find("2 NaN"), std::string::npos) << w;
  EXPECT_NE(w.find("3 +inf"), std::string::npos) << w;
  EXPECT_NE(w.find("2 -inf"), std::string::npos) << w;
  // The spellings other programs print: MSVC (old: padded with zeros; new: "-nan(ind)"), C99
  // strtod's payload form, signs on NaN. Each one invalid point, none an error.
  for (const char* v : {"1.#INF", "-1.#INF", "1.#INF00", "-1.#IND", "-1.#IND00", "1.#QNAN", "1.#QNAN0", "-1.#QNAN",
                        "1.#SNAN", "-nan(ind)", "nan(ind)", "NaN(0x8)", "-nan", "+nan", "-Infinity", "+INFINITY"}) {
    auto r = frictal::read_surface_bytes(std::string("x,z\n0,1\n1,") + v + "\n2,2\n3,4\n", "v.csv", [] {
      frictal::ReadOptions o;
      o.default_unit = "m";
      return o;
    }());
    ASSERT_TRUE(r.ok()) << v << ": " << r.error().message;
    EXPECT_EQ(r->curve.size(), 3u) << v;
    EXPECT_EQ(count_containing(r->warnings, "1 invalid point"), 1u) << v;
  }
  // Whitespace and semicolon files, too.
  for (const char* t : {"0 1\n1 inf\n2 2\n", "0;1\n1;-Inf\n2;2\n", "0\t1\n1\tNaN\n2\t2\n"}) {
    auto r = frictal::read_surface_bytes(t, "t.txt", [] {
      frictal::ReadOptions o;
      o.default_unit = "m";
      return o;
    }());
    ASSERT_TRUE(r.ok()) << t << r.error().message;
    EXPECT_EQ(r->curve.size(), 2u) << t;
    EXPECT_EQ(count_containing(r->warnings, "1 invalid point"), 1u) << t;
  }
}

TEST(InvalidPoints, InfiniteXIsAnErrorNamingTheLine) {
  auto s = frictal::read_surface_bytes("0,1\n1,2\ninf,3\n", "x.csv");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("x.csv:3"), std::string::npos) << s.error().message;
}

TEST(InvalidPoints, GwyddionTextMapMasksAndStatisticsIgnoreThem) {
  // 3 x 2 matrix in nm: 1 inf 3 / -inf 5 NaN -> valid 1, 3, 5 nm.
  auto s =
      frictal::read_surface_bytes("# Width: 3 um\n# Height: 2 um\n# Value units: nm\n1 inf 3\n-inf 5 NaN\n", "m.txt");
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_TRUE(s->is_map);
  const auto& m = s->map;
  ASSERT_EQ(m.size(), 6u);
  EXPECT_DOUBLE_EQ(m.heights[0], 1e-9);
  EXPECT_TRUE(std::isnan(m.heights[1]));
  EXPECT_TRUE(std::isnan(m.heights[3]));
  EXPECT_TRUE(std::isnan(m.heights[5]));
  EXPECT_EQ(m.valid_count(), 3u);
  ASSERT_EQ(count_containing(s->warnings, "invalid point"), 1u);
  EXPECT_EQ(count_containing(s->warnings, "3 invalid points (1 NaN, 1 +inf, 1 -inf) masked"), 1u)
      << s->warnings[0].message;
  // Statistics over 1, 3, 5 nm only: mean 3 nm, Sq = sqrt((4 + 0 + 4) / 3) nm, Sz = 4 nm.
  auto st = frictal::map_stats(m);
  EXPECT_EQ(st.valid, 3u);
  EXPECT_NEAR(st.mean, 3e-9, 1e-24);
  EXPECT_NEAR(st.Sq, std::sqrt(8.0 / 3.0) * 1e-9, 1e-24);
  EXPECT_NEAR(st.Sz, 4e-9, 1e-24);
  EXPECT_TRUE(frictal::validate(m).ok());
}

TEST(InvalidPoints, X3pFloatAndDoubleWithInfinitiesAreMasked) {
  const std::vector<double> z = {1e-6, kInf, -kInf, 2e-6, kNan, 3e-6};
  for (char type : {'F', 'D'}) {
    auto s = frictal::read_surface_bytes(x3p_sur(type, z), std::string("inf-") + type + ".x3p");
    ASSERT_TRUE(s.ok()) << type << ": " << s.error().message;
    ASSERT_TRUE(s->is_map);
    const auto& m = s->map;
    EXPECT_EQ(m.valid_count(), 3u);
    EXPECT_DOUBLE_EQ(m.heights[0], type == 'F' ? double(float(1e-6)) : 1e-6);
    EXPECT_DOUBLE_EQ(m.heights[3], type == 'F' ? double(float(2e-6)) : 2e-6);
    for (int k : {1, 2, 4}) EXPECT_TRUE(std::isnan(m.heights[k])) << k;
    EXPECT_EQ(count_containing(s->warnings, "3 invalid points (1 NaN, 1 +inf, 1 -inf) masked"), 1u) << type;
    EXPECT_TRUE(frictal::validate(m).ok());
  }
  // A valid.bin that already flags the +inf point: only the other two are counted; flagged
  // points are the format's own "not measured" (no warning for them).
  auto s = frictal::read_surface_bytes(x3p_sur('D', z, std::string(1, char(0b111101))), "mask.x3p");
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(s->map.valid_count(), 3u);
  EXPECT_EQ(count_containing(s->warnings, "2 invalid points (1 NaN, 1 -inf) masked"), 1u);
}

TEST(InvalidPoints, X3pXmlListWithInfinityIsMasked) {
  std::string xml =
      "<?xml version=\"1.0\"?><p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\"><Record1>"
      "<FeatureType>SUR</FeatureType><Axes>"
      "<CX><AxisType>I</AxisType><DataType>D</DataType><Increment>1e-6</Increment></CX>"
      "<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>1e-6</Increment></CY>"
      "<CZ><AxisType>A</AxisType><DataType>D</DataType></CZ></Axes></Record1><Record3><MatrixDimension>"
      "<SizeX>2</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ></MatrixDimension><DataList><Datum>1e-6</Datum>"
      "<Datum>+INF</Datum><Datum/><Datum>4e-6</Datum></DataList></Record3></p:ISO5436_2>";
  auto s = frictal::read_surface_bytes(frictal::test::zip_stored({{"main.xml", xml}}), "list.x3p");
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(s->map.valid_count(), 2u);
  EXPECT_DOUBLE_EQ(s->map.heights[3], 4e-6);
  EXPECT_EQ(count_containing(s->warnings, "1 invalid point (1 +inf) masked"), 1u);
}

TEST(InvalidPoints, X3pProfileDropsInfinities) {
  std::string xml =
      "<?xml version=\"1.0\"?><p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\"><Record1>"
      "<FeatureType>PRF</FeatureType><Axes>"
      "<CX><AxisType>I</AxisType><DataType>D</DataType><Increment>1e-6</Increment></CX>"
      "<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>1e-6</Increment></CY>"
      "<CZ><AxisType>A</AxisType><DataType>D</DataType></CZ></Axes></Record1><Record3><MatrixDimension>"
      "<SizeX>4</SizeX><SizeY>1</SizeY><SizeZ>1</SizeZ></MatrixDimension><DataList><Datum>1e-6</Datum>"
      "<Datum>-inf</Datum><Datum>3e-6</Datum><Datum>4e-6</Datum></DataList></Record3></p:ISO5436_2>";
  auto s = frictal::read_surface_bytes(frictal::test::zip_stored({{"main.xml", xml}}), "prf.x3p");
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_FALSE(s->is_map);
  ASSERT_EQ(s->curve.size(), 3u);
  EXPECT_DOUBLE_EQ(s->curve.x[1], 2e-6);
  EXPECT_DOUBLE_EQ(s->curve.z[1], 3e-6);
  EXPECT_EQ(count_containing(s->warnings, "1 invalid point (1 -inf) dropped"), 1u);
}

TEST(InvalidPoints, AllInvalidIsAnError) {
  EXPECT_FALSE(frictal::read_surface_bytes("# Width: 2 um\n# Height: 2 um\ninf NaN\n-inf nan\n", "all.txt").ok());
  EXPECT_FALSE(frictal::read_surface_bytes("0,inf\n1,nan\n2,-inf\n", "all.csv").ok());
}
