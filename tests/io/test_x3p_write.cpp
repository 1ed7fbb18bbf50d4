// X3P write -> read round trips for profiles (PRF) and maps (SUR), every data type, binary and
// XML data lists, with invalid points.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "frictal/io.hpp"

namespace {

std::string tmp_path(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / "frictal-test-x3p";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

const char* tname(frictal::X3pDataType t) {
  switch (t) {
    case frictal::X3pDataType::I: return "I";
    case frictal::X3pDataType::L: return "L";
    case frictal::X3pDataType::F: return "F";
    default: return "D";
  }
}

// Heights that every type stores exactly: z = offset + increment * k for small integers k
// (also exact in float32 for the chosen k, increment = 2^-20 m, offset = 2^-10 m).
frictal::Map grid_map(std::size_t nx, std::size_t ny, bool holes) {
  frictal::Map m;
  m.nx = nx;
  m.ny = ny;
  m.dx = 1.5e-6;
  m.dy = 2.5e-6;
  m.x0 = 1e-5;
  m.y0 = -3e-5;
  const double inc = std::ldexp(1.0, -20), off = std::ldexp(1.0, -10);
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      long k = long((i * 7 + j * 13) % 61) - 30;
      m.heights.push_back(off + inc * double(k));
    }
  if (holes) {
    m.heights[1] = NAN;
    m.heights[nx * ny - 1] = NAN;
  }
  return m;
}

}  // namespace

TEST(X3pWrite, MapRoundTripEveryTypeBinaryAndXml) {
  for (auto t : {frictal::X3pDataType::I, frictal::X3pDataType::L, frictal::X3pDataType::F, frictal::X3pDataType::D})
    for (bool binary : {true, false})
      for (bool holes : {false, true}) {
        frictal::Map m = grid_map(13, 7, holes);
        frictal::X3pWriteOptions o;
        o.type = t;
        o.binary = binary;
        o.z_increment = std::ldexp(1.0, -20);
        o.z_offset = std::ldexp(1.0, -10);
        std::string path =
            tmp_path(std::string("map-") + tname(t) + (binary ? "-bin" : "-xml") + (holes ? "-holes" : "") + ".x3p");
        auto w = frictal::write_x3p(path, m, o);
        ASSERT_TRUE(w.ok()) << w.error().message;
        auto s = frictal::read_surface(path);
        ASSERT_TRUE(s.ok()) << s.error().message;
        EXPECT_TRUE(s->warnings.empty()) << s->warnings[0].message;  // our own checksums verify
        ASSERT_TRUE(s->is_map);
        const auto& r = s->map;
        ASSERT_EQ(r.nx, m.nx);
        ASSERT_EQ(r.ny, m.ny);
        EXPECT_EQ(r.dx, m.dx);
        EXPECT_EQ(r.dy, m.dy);
        EXPECT_EQ(r.x0, m.x0);
        EXPECT_EQ(r.y0, m.y0);
        for (std::size_t k = 0; k < m.size(); ++k) {
          if (std::isnan(m.heights[k]))
            EXPECT_TRUE(std::isnan(r.heights[k])) << path << " " << k;
          else
            EXPECT_EQ(r.heights[k], m.heights[k]) << path << " " << k;
        }
      }
}

TEST(X3pWrite, DoubleKeepsArbitraryValuesExactly) {
  frictal::Map m;
  m.nx = 5;
  m.ny = 3;
  m.dx = m.dy = 1e-7 / 3;
  for (int k = 0; k < 15; ++k) m.heights.push_back(std::sin(k * 1.234567) * 1e-7 / 7);
  for (bool binary : {true, false}) {
    std::string path = tmp_path(binary ? "d-bin.x3p" : "d-xml.x3p");
    frictal::X3pWriteOptions o;
    o.binary = binary;
    ASSERT_TRUE(frictal::write_x3p(path, m, o).ok());
    auto r = frictal::read_map(path);
    ASSERT_TRUE(r.ok()) << r.error().message;
    EXPECT_EQ(r->heights, m.heights);  // 17 significant digits in XML, raw bytes in binary
    EXPECT_EQ(r->dx, m.dx);
  }
}

TEST(X3pWrite, AutoIncrementQuantisesWithinHalfAStep) {
  frictal::Map m;
  m.nx = 4;
  m.ny = 4;
  m.dx = m.dy = 1e-6;
  for (int k = 0; k < 16; ++k) m.heights.push_back(std::cos(k * 0.7) * 3e-6);
  frictal::X3pWriteOptions o;
  o.type = frictal::X3pDataType::I;
  std::string path = tmp_path("auto-int16.x3p");
  ASSERT_TRUE(frictal::write_x3p(path, m, o).ok());
  auto r = frictal::read_map(path);
  ASSERT_TRUE(r.ok());
  // Range 6e-6 m over 2 * 32766 steps: error <= half a step.
  for (int k = 0; k < 16; ++k) EXPECT_NEAR(r->heights[k], m.heights[k], 0.5 * 6e-6 / 65532 * 1.0001);
}

TEST(X3pWrite, ProfileRoundTripEveryType) {
  for (auto t : {frictal::X3pDataType::I, frictal::X3pDataType::L, frictal::X3pDataType::F, frictal::X3pDataType::D})
    for (bool binary : {true, false}) {
      frictal::Profile p;
      const double inc = std::ldexp(1.0, -24);
      for (int k = 0; k < 50; ++k) {
        p.x.push_back(2e-6 + 0.25e-6 * k);
        p.z.push_back(inc * ((k * 17) % 23 - 11));
      }
      frictal::X3pWriteOptions o;
      o.type = t;
      o.binary = binary;
      o.z_increment = inc;
      std::string path = tmp_path(std::string("prf-") + tname(t) + (binary ? "-bin" : "-xml") + ".x3p");
      auto w = frictal::write_x3p(path, p, o);
      ASSERT_TRUE(w.ok()) << w.error().message;
      auto r = frictal::read_profile(path);
      ASSERT_TRUE(r.ok()) << r.error().message;
      ASSERT_EQ(r->size(), p.size());
      for (std::size_t k = 0; k < p.size(); ++k) {
        EXPECT_EQ(r->z[k], p.z[k]) << path;
        EXPECT_NEAR(r->x[k], p.x[k], 1e-18) << path;  // x = x0 + k * dx recomputed
      }
    }
}

TEST(X3pWrite, RefusesNonUniformProfileAndOverflow) {
  frictal::Profile p;
  p.x = {0, 1, 3};
  p.z = {0, 0, 0};
  EXPECT_FALSE(frictal::write_x3p(tmp_path("bad.x3p"), p).ok());
  frictal::Map m;
  m.nx = 2;
  m.ny = 1;
  m.heights = {0, 1};
  frictal::X3pWriteOptions o;
  o.type = frictal::X3pDataType::I;
  o.z_increment = 1e-9;  // 1 m / 1 nm does not fit in int16
  EXPECT_FALSE(frictal::write_x3p(tmp_path("overflow.x3p"), m, o).ok());
}

TEST(X3pWrite, RewriteOfSharedMapKeepsValues) {
  auto m = frictal::read_map(std::string(FRICTAL_TEST_DATA) + "/x3p/sample-land.x3p");
  ASSERT_TRUE(m.ok());
  std::string path = tmp_path("land.x3p");
  ASSERT_TRUE(frictal::write_x3p(path, *m).ok());
  auto r = frictal::read_map(path);
  ASSERT_TRUE(r.ok());
  ASSERT_EQ(r->size(), m->size());
  for (std::size_t k = 0; k < m->size(); ++k) {
    if (std::isnan(m->heights[k]))
      ASSERT_TRUE(std::isnan(r->heights[k]));
    else
      ASSERT_EQ(r->heights[k], m->heights[k]);
  }
}

TEST(X3pWrite, FixedDateGivesIdenticalFiles) {
  frictal::Map m;
  m.nx = 3;
  m.ny = 2;
  m.heights = {1e-9, 2e-9, 3e-9, 4e-9, NAN, 6e-9};
  frictal::X3pWriteOptions o;
  o.date = "2026-11-21T00:00:00+00:00";
  o.comment = "a < b & c";
  const std::string a = tmp_path("fixed-a.x3p"), b = tmp_path("fixed-b.x3p");
  ASSERT_TRUE(frictal::write_x3p(a, m, o).ok());
  ASSERT_TRUE(frictal::write_x3p(b, m, o).ok());
  auto slurp = [](const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  // With a fixed date the member times are fixed too: byte-identical archives.
  EXPECT_EQ(slurp(a), slurp(b));
  auto ra = frictal::read_surface(a);
  ASSERT_TRUE(ra.ok()) << ra.error().message;  // the escaped comment keeps main.xml valid
  EXPECT_TRUE(ra->warnings.empty());
}
