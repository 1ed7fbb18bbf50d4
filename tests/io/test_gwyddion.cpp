// Gwyddion backend. Files are written through Gwyddion's own file modules from a map whose
// heights are known (an analytic surface), read back through frictal (native reader where
// frictal has one, else the Gwyddion backend), and compared; where both read a file (X3P,
// SDF text, SPIP ASCII) the two paths must give the same sizes and heights. Skipped, with the
// reason, where Gwyddion's libraries or file modules are not installed.
#include <gtest/gtest.h>

#include <dlfcn.h>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "frictal/io.hpp"

namespace {

const std::string kData = FRICTAL_TEST_DATA;

#define REQUIRE_GWYDDION()                                           \
  do {                                                               \
    std::string why;                                                 \
    if (!frictal::gwyddion_available("", &why)) GTEST_SKIP() << why; \
  } while (0)

// z(i, j) = 1e-9 (3 i - 2 j + 0.5 i j), 7 x 5 points, dx = 0.5 um, dy = 0.25 um.
frictal::Map analytic_map(std::size_t nx = 7, std::size_t ny = 5) {
  frictal::Map m;
  m.nx = nx;
  m.ny = ny;
  m.dx = 0.5e-6;
  m.dy = 0.25e-6;
  m.x0 = 1e-6;
  m.y0 = 2e-6;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) m.heights.push_back(1e-9 * (3.0 * i - 2.0 * j + 0.5 * i * j));
  return m;
}

void expect_same_grid(const frictal::Map& a, const frictal::Map& b, double rel, const std::string& what) {
  ASSERT_EQ(a.nx, b.nx) << what;
  ASSERT_EQ(a.ny, b.ny) << what;
  EXPECT_NEAR(a.dx, b.dx, 1e-9 * a.dx) << what;
  EXPECT_NEAR(a.dy, b.dy, 1e-9 * a.dy) << what;
  double lo = INFINITY, hi = -INFINITY;
  for (double v : a.heights)
    if (!std::isnan(v)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(std::isnan(a.heights[k]), std::isnan(b.heights[k])) << what << " point " << k;
    if (!std::isnan(a.heights[k])) {
      EXPECT_NEAR(a.heights[k], b.heights[k], rel * (hi - lo)) << what << " point " << k;
    }
  }
}

}  // namespace

TEST(Gwyddion, HeadlessInitAndFormatList) {
  REQUIRE_GWYDDION();
  auto f = frictal::gwyddion_formats();
  EXPECT_GT(f.size(), 100u);  // Gwyddion 2.62 on Debian 12: 159 loaders
  bool sur = false, opengps = false;
  for (const auto& x : f) {
    sur |= x.name == "surffile";
    opengps |= x.name == "opengps";
  }
  EXPECT_TRUE(sur);
  EXPECT_TRUE(opengps);
  EXPECT_GT(frictal::readable_formats().size(), f.size());
}

TEST(Gwyddion, WrittenByGwyddionReadBackByFrictal) {
  REQUIRE_GWYDDION();
  // extension, relative height tolerance (of the range), reader expected
  struct Case {
    const char* ext;
    double rel;
    const char* reader;
  };
  const Case cases[] = {
      {".gwy", 1e-15, "gwyddion:gwyfile"}, {".gsf", 1e-6, "gwyddion:gsffile"},   {".sur", 1e-6, "gwyddion:surffile"},
      {".ibw", 1e-6, "gwyddion:igorfile"}, {".nrrd", 1e-6, "gwyddion:nrrdfile"}, {".sdf", 1e-5, "native"},
      {".asc", 1e-12, "native"},           {".tom", 1e-6, "gwyddion:wsxmfile"},  {".afm", 1e-4, "gwyddion:assing-afm"},
      {".spm", 1e-6, "gwyddion:iso28600"},
  };
  for (const auto& c : cases) {
    const std::string path = ::testing::TempDir() + "frictal_gwy" + c.ext;
    // NRRD as Gwyddion writes it keeps one pixel size for both axes: square pixels there;
    // Assing AFM files are square images with square pixels.
    const bool afm = std::string(c.ext) == ".afm";
    frictal::Map m = afm ? analytic_map(6, 6) : analytic_map();
    if (afm || std::string(c.ext) == ".nrrd") m.dy = m.dx;
    auto w = frictal::write_gwyddion(path, m);
    ASSERT_TRUE(w.ok()) << c.ext << ": " << w.error().message;
    auto s = frictal::read_surface(path);
    ASSERT_TRUE(s.ok()) << c.ext << ": " << s.error().message;
    ASSERT_TRUE(s->is_map) << c.ext;
    EXPECT_EQ(s->reader, c.reader) << c.ext;
    if (afm) {
      // The Assing format stores heights about their mid-range: compare about the means.
      auto centred = [](frictal::Map x) {
        double mean = 0;
        for (double v : x.heights) mean += v / double(x.size());
        for (double& v : x.heights) v -= mean;
        return x;
      };
      expect_same_grid(centred(m), centred(s->map), c.rel, c.ext);
    } else {
      expect_same_grid(m, s->map, c.rel, c.ext);
    }
    if (std::string(c.ext) == ".gwy") {
      EXPECT_DOUBLE_EQ(s->map.x0, m.x0);
      EXPECT_DOUBLE_EQ(s->map.y0, m.y0);
      ASSERT_EQ(s->channels.size(), 1u);
      EXPECT_EQ(s->channels[0].name, "Height");
      EXPECT_EQ(s->channels[0].xy_unit, "m");
    }
    // Where frictal reads natively, the Gwyddion path gives the same.
    if (std::string(c.reader) == "native") {
      frictal::ReadOptions o;
      o.format = frictal::ProfileFormat::GwyddionLib;
      auto g = frictal::read_surface(path, o);
      ASSERT_TRUE(g.ok()) << c.ext << ": " << g.error().message;
      expect_same_grid(s->map, g->map, 1e-12, std::string(c.ext) + " native vs Gwyddion");
    }
  }
}

TEST(Gwyddion, MaskIsInvalidPoints) {
  REQUIRE_GWYDDION();
  frictal::Map m = analytic_map();
  m.at(2, 3) = NAN;
  m.at(6, 0) = NAN;
  const std::string path = ::testing::TempDir() + "frictal_gwy_mask.gwy";
  ASSERT_TRUE(frictal::write_gwyddion(path, m).ok());
  auto s = frictal::read_surface(path);
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(s->map.valid_count(), m.size() - 2);
  expect_same_grid(m, s->map, 1e-15, "mask");
}

TEST(Gwyddion, NativeAndGwyddionReadTheSameX3p) {
  REQUIRE_GWYDDION();
  for (const char* f :
       {"/x3p/pyramid.x3p", "/x3p/x3p-2.x3p", "/x3p/ISO5436-sample1_bin.x3p", "/x3p/ISO5436-sample4_bin.x3p"}) {
    auto n = frictal::read_surface(kData + f);
    ASSERT_TRUE(n.ok()) << f << n.error().message;
    frictal::ReadOptions o;
    o.format = frictal::ProfileFormat::GwyddionLib;
    auto g = frictal::read_surface(kData + f, o);
    ASSERT_TRUE(g.ok()) << f << ": " << g.error().message;
    EXPECT_EQ(g->reader, "gwyddion:opengps") << f;
    ASSERT_TRUE(g->is_map) << f;
    expect_same_grid(n->map, g->map, 1e-12, f);
  }
}

TEST(Gwyddion, NativeReadsX3pThatGwyddionRefuses) {
  REQUIRE_GWYDDION();
  // sample-land.x3p keeps main.xml in a sub-folder: Gwyddion 2.62's opengps module does not
  // take it (another module claims it and finds no data); the native reader does.
  frictal::ReadOptions o;
  o.format = frictal::ProfileFormat::GwyddionLib;
  EXPECT_FALSE(frictal::read_surface(kData + "/x3p/sample-land.x3p", o).ok());
  EXPECT_TRUE(frictal::read_surface(kData + "/x3p/sample-land.x3p").ok());
}

TEST(Gwyddion, ChannelSelectionAndErrors) {
  REQUIRE_GWYDDION();
  const std::string path = ::testing::TempDir() + "frictal_gwy_ch.gwy";
  ASSERT_TRUE(frictal::write_gwyddion(path, analytic_map()).ok());
  frictal::ReadOptions o;
  o.channel = "height";
  EXPECT_TRUE(frictal::read_surface(path, o).ok());
  o.channel = "3";
  auto e = frictal::read_surface(path, o);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().message.find("channel 3"), std::string::npos) << e.error().message;
  o.channel = "Phase";
  EXPECT_FALSE(frictal::read_surface(path, o).ok());
  // A binary file no module recognises.
  const std::string junk = ::testing::TempDir() + "frictal_junk.bin";
  {
    std::FILE* fp = std::fopen(junk.c_str(), "wb");
    const char b[] = {'\x01', '\x00', '\x02', '\x7f', '\x00', '\x00', '\x10'};
    std::fwrite(b, 1, sizeof b, fp);
    std::fclose(fp);
  }
  auto j = frictal::read_surface(junk);
  ASSERT_FALSE(j.ok());
  EXPECT_NE(j.error().message.find("recognise"), std::string::npos) << j.error().message;
}

TEST(Gwyddion, MissingModulesNameThePackages) {
  std::string why;
  EXPECT_FALSE(frictal::gwyddion_available("/nonexistent/gwyddion/modules", &why));
  EXPECT_NE(why.find("wyddion"), std::string::npos) << why;
  frictal::ReadOptions o;
  o.gwyddion_module_dir = "/nonexistent/gwyddion/modules";
  o.format = frictal::ProfileFormat::GwyddionLib;
  auto s = frictal::read_surface(kData + "/x3p/pyramid.x3p", o);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("Gwyddion"), std::string::npos) << s.error().message;
  if (why.find("built without") == std::string::npos) {
    EXPECT_NE(s.error().message.find("libgwyddion2-0"), std::string::npos) << s.error().message;
  }
}

TEST(Gwyddion, GraphCurvesAreProfiles) {
  REQUIRE_GWYDDION();
  // Build a .gwy holding a graph (two curves, x in m, y in m) and an image, through Gwyddion's
  // own functions (already loaded process-wide by the backend), then read it with frictal.
  auto sym = [](const char* n) {
    void* p = dlsym(RTLD_DEFAULT, n);
    EXPECT_NE(p, nullptr) << n;
    return p;
  };
  using Obj = void*;
  auto graph_new = reinterpret_cast<Obj (*)()>(sym("gwy_graph_model_new"));
  auto curve_new = reinterpret_cast<Obj (*)()>(sym("gwy_graph_curve_model_new"));
  auto set_data =
      reinterpret_cast<void (*)(Obj, const double*, const double*, int)>(sym("gwy_graph_curve_model_set_data"));
  auto add_curve = reinterpret_cast<int (*)(Obj, Obj)>(sym("gwy_graph_model_add_curve"));
  auto obj_set = reinterpret_cast<void (*)(Obj, const char*, ...)>(sym("g_object_set"));
  auto unit_new = reinterpret_cast<Obj (*)(const char*)>(sym("gwy_si_unit_new"));
  auto cont_new = reinterpret_cast<Obj (*)()>(sym("gwy_container_new"));
  auto quark = reinterpret_cast<std::uint32_t (*)(const char*)>(sym("g_quark_from_string"));
  auto set_obj = reinterpret_cast<void (*)(Obj, std::uint32_t, Obj)>(sym("gwy_container_set_object"));
  auto save = reinterpret_cast<int (*)(Obj, const char*, int, const char**, void**)>(sym("gwy_file_save_with_func"));
  ASSERT_FALSE(::testing::Test::HasFailure());
  Obj g = graph_new();
  obj_set(g, "si-unit-x", unit_new("m"), "si-unit-y", unit_new("m"), "title", "Profile", nullptr);
  const double x[] = {0, 1e-6, 2e-6, 3e-6}, y1[] = {5e-9, 6e-9, NAN, 8e-9}, y2[] = {1, 2, 3, 4};
  Obj c1 = curve_new(), c2 = curve_new();
  obj_set(c1, "description", "height", nullptr);
  obj_set(c2, "description", "other", nullptr);
  set_data(c1, x, y1, 4);
  set_data(c2, x, y2, 4);
  add_curve(g, c1);
  add_curve(g, c2);
  Obj c = cont_new();
  set_obj(c, quark("/0/graph/graph/1"), g);
  const std::string path = ::testing::TempDir() + "frictal_gwy_graph.gwy";
  void* err = nullptr;
  const char* module = nullptr;
  ASSERT_NE(save(c, path.c_str(), 1, &module, &err), 0);
  auto s = frictal::read_surface(path);
  ASSERT_TRUE(s.ok()) << s.error().message;
  ASSERT_FALSE(s->is_map);
  ASSERT_EQ(s->channels.size(), 2u);
  EXPECT_EQ(s->channels[0].name, "Profile: height");
  ASSERT_EQ(s->curve.size(), 3u);  // the NaN point is dropped, with a warning
  EXPECT_DOUBLE_EQ(s->curve.x[2], 3e-6);
  EXPECT_DOUBLE_EQ(s->curve.z[2], 8e-9);
  EXPECT_EQ(s->warnings.size(), 1u);
  frictal::ReadOptions o;
  o.channel = "1";
  auto t = frictal::read_surface(path, o);
  ASSERT_TRUE(t.ok()) << t.error().message;
  ASSERT_EQ(t->curve.size(), 4u);
  EXPECT_DOUBLE_EQ(t->curve.z[3], 4);
}

TEST(Gwyddion, BadTextKeepsTheNativeMessage) {
  REQUIRE_GWYDDION();
  const std::string path = ::testing::TempDir() + "frictal_bad.csv";
  {
    std::FILE* fp = std::fopen(path.c_str(), "wb");
    const std::string t = "x (um),z (um)\n0,1\n1,2\nnot a number here\n3,4\n";
    std::fwrite(t.data(), 1, t.size(), fp);
    std::fclose(fp);
  }
  auto s = frictal::read_surface(path);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find(path + ":4:"), std::string::npos) << s.error().message;
}

TEST(Gwyddion, BinarySdfWrittenFromTheLayoutOfIso25178_71) {
  // Gwyddion 2.62 reads binary SDF (sdfile-bin) but writes only the text form, and no public
  // binary sample was found (docs/io.md). So the bytes are laid out here as ISO 25178-71 / the
  // Surfstand SDF define them: "bISO-1.0", ManufacID[10], CreateDate[12], ModDate[12],
  // NumPoints u16, NumProfiles u16, Xscale, Yscale, Zscale, Zresolution (float64), Compression,
  // DataType, CheckType (u8), 81 bytes, then the points little-endian. DataType 5 = int16, whose
  // invalid value is -32768; DataType 7 = float64, whose invalid value is NaN.
  REQUIRE_GWYDDION();
  auto put = [](std::string& s, const void* p, std::size_t n) { s.append(static_cast<const char*>(p), n); };
  auto sdf = [&](int type, const std::vector<double>& z) {
    std::string b = "bISO-1.0";
    b += "frictal   ";
    b += "231120261200";
    b += "231120261200";
    const std::uint16_t nx = 5, ny = 3;
    const double xs = 1e-6, ys = 2e-6, zs = 1e-9, zr = 1e-9;
    put(b, &nx, 2);
    put(b, &ny, 2);
    for (double v : {xs, ys, zs, zr}) put(b, &v, 8);
    b += '\0';
    b += char(type);
    b += '\0';
    EXPECT_EQ(b.size(), 81u);
    for (double v : z) {
      if (type == 5) {
        const std::int16_t w = std::int16_t(v);
        put(b, &w, 2);
      } else {
        put(b, &v, 8);
      }
    }
    return b;
  };
  std::vector<double> z;  // z(i, j) = 10 (i + 1) + 100 j - 150 in units of Zscale
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 5; ++i) z.push_back(10.0 * (i + 1) + 100.0 * j - 150);
  for (int type : {5, 7}) {
    std::vector<double> zz = z;
    zz[7] = type == 5 ? -32768.0 : std::nan("");  // (i, j) = (2, 1): invalid
    const std::string path = ::testing::TempDir() + "frictal_bin" + std::to_string(type) + ".sdf";
    {
      std::ofstream f(path, std::ios::binary);
      f << sdf(type, zz);
    }
    auto s = frictal::read_surface(path);
    ASSERT_TRUE(s.ok()) << s.error().message;
    EXPECT_EQ(s->reader, "gwyddion:sdfile-bin");
    ASSERT_TRUE(s->is_map);
    const frictal::Map& m = s->map;
    ASSERT_EQ(m.nx, 5u);
    ASSERT_EQ(m.ny, 3u);
    EXPECT_NEAR(m.dx, 1e-6, 1e-21);
    EXPECT_NEAR(m.dy, 2e-6, 1e-21);
    EXPECT_EQ(m.valid_count(), 14u);
    for (std::size_t k = 0; k < 15; ++k) {
      if (k == 7) {
        EXPECT_TRUE(std::isnan(m.heights[k])) << type;
      } else {
        EXPECT_NEAR(m.heights[k], z[k] * 1e-9, 1e-24) << type << " point " << k;
      }
    }
  }
}

TEST(Gwyddion, ItsLogMessagesBecomeWarningsNotStderr) {
  // gwyfile-test.gwy (tests/data/README.md) holds a GwySelectionPoint, a type Gwyddion 2.62 no
  // longer knows: its gwyfile module says so with g_warning(). The library never prints: the
  // message is one of the read's warnings, and nothing reaches stderr.
  REQUIRE_GWYDDION();
  ::testing::internal::CaptureStderr();
  auto s = frictal::read_surface(kData + "/instruments/gwyfile-test.gwy");
  const std::string err = ::testing::internal::GetCapturedStderr();
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(err, "");
  bool found = false;
  for (const auto& w : s->warnings) found |= w.message.find("GwySelectionPoint") != std::string::npos;
  EXPECT_TRUE(found);
}
