// Readers never crash on damaged input: random byte flips, truncations and insertions into the
// measured test files and into crafted X3P archives (mutated before zipping, so that the XML and binary
// parsers see the damage rather than the CRC check). Each read must return a value or an error.
// Run under the sanitize preset to catch memory errors.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "frictal/io.hpp"
#include "io/zip_builder.hpp"

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string mutate(std::string s, std::mt19937& rng) {
  std::uniform_int_distribution<int> kind(0, 3), byte(0, 255);
  if (s.empty()) return s;
  std::uniform_int_distribution<std::size_t> pos(0, s.size() - 1);
  switch (kind(rng)) {
    case 0:  // flip a few bytes
      for (int k = 0; k < 4; ++k) s[pos(rng)] = char(byte(rng));
      break;
    case 1:  // truncate
      s.resize(pos(rng));
      break;
    case 2:  // insert garbage
      s.insert(pos(rng), std::string(1 + pos(rng) % 16, char(byte(rng))));
      break;
    default: {  // replace a digit run by a huge or odd number
      const char* odd[] = {"1e400", "-0", "nan", "99999999999999999999", "", ";", "1;2;3;4", "-32769"};
      std::size_t p = pos(rng);
      s.replace(p, std::min<std::size_t>(3, s.size() - p), odd[pos(rng) % 8]);
    }
  }
  return s;
}

const char* kXml =
    "<?xml version=\"1.0\"?><p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\"><Record1>"
    "<FeatureType>SUR</FeatureType><Axes>"
    "<CX><AxisType>I</AxisType><DataType>D</DataType><Increment>1e-6</Increment><Offset>0</Offset></CX>"
    "<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>2e-6</Increment><Offset>0</Offset></CY>"
    "<CZ><AxisType>A</AxisType><DataType>I</DataType><Increment>1e-9</Increment><Offset>0</Offset></CZ>"
    "</Axes></Record1><Record3><MatrixDimension><SizeX>3</SizeX><SizeY>2</SizeY><SizeZ>1</SizeZ></MatrixDimension>"
    "<DataLink><PointDataLink>bindata/data.bin</PointDataLink><ValidPointsLink>bindata/valid.bin</ValidPointsLink>"
    "</DataLink></Record3></p:ISO5436_2>";
const char* kXmlList =
    "<?xml version=\"1.0\"?><ISO5436_2><Record1><FeatureType>PCL</FeatureType><Axes>"
    "<CX><AxisType>A</AxisType><DataType>D</DataType></CX><CY><AxisType>A</AxisType><DataType>L</DataType></CY>"
    "<CZ><AxisType>A</AxisType><DataType>F</DataType></CZ></Axes></Record1><Record3><ListDimension>4</ListDimension>"
    "<DataList><Datum>0;0;1</Datum><Datum>1;0;2</Datum><Datum>0;1;3</Datum><Datum>1;1;</Datum></DataList>"
    "</Record3></ISO5436_2>";

}  // namespace

TEST(Fuzz, SharedFilesSurviveMutation) {
  std::mt19937 rng(12345);
  const std::string base = FRICTAL_TEST_DATA;
  for (const char* f : {"/profiles/csv-1.csv", "/profiles/csv-2.csv", "/profiles/xy-2.txt", "/profiles/nonuniform.asc",
                        "/maps/gwyddion-export-german.txt", "/maps/matrix-6.txt", "/x3p/ISO5436-sample1.x3p",
                        "/x3p/ISO5436-sample4_bin.x3p", "/x3p/pyramid.x3p"}) {
    const std::string bytes = slurp(base + f);
    for (int k = 0; k < 300; ++k) {
      auto r = frictal::read_surface_bytes(mutate(bytes, rng), f);
      if (!r) {
        EXPECT_FALSE(r.error().message.empty());
      }
    }
  }
  const std::string dektak = slurp(base + "/profiles/dektak-1.csv");
  for (int k = 0; k < 20; ++k) (void)frictal::read_surface_bytes(mutate(dektak, rng), "dektak");
}

TEST(Fuzz, CraftedX3pSurviveMutation) {
  std::mt19937 rng(777);
  const std::string data(3 * 2 * 2, '\x01'), valid("\x3f", 1);
  int ok = 0;
  for (int k = 0; k < 2000; ++k) {
    std::string xml = mutate(k % 2 ? kXml : kXmlList, rng);
    std::string bin = k % 3 ? data : mutate(data, rng);
    std::string zip =
        frictal::test::zip_stored({{"main.xml", xml}, {"bindata/data.bin", bin}, {"bindata/valid.bin", valid}});
    auto r = frictal::read_surface_bytes(zip, "fuzz.x3p");
    if (r) {
      ++ok;
      if (r->is_map) {
        EXPECT_EQ(r->map.heights.size(), r->map.nx * r->map.ny);
      }
    } else {
      EXPECT_NE(r.error().message.find("fuzz.x3p"), std::string::npos) << r.error().message;
    }
  }
  EXPECT_GT(ok, 0);
  // The unmutated archives read.
  EXPECT_TRUE(
      frictal::read_surface_bytes(
          frictal::test::zip_stored({{"main.xml", kXml}, {"bindata/data.bin", data}, {"bindata/valid.bin", valid}}),
          "a.x3p")
          .ok());
  EXPECT_TRUE(frictal::read_surface_bytes(frictal::test::zip_stored({{"main.xml", kXmlList}}), "b.x3p").ok());
}
