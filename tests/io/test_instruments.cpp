// Real instrument files (tests/data/instruments/, provenance in tests/data/README.md) read into
// the numbers that a peer project states for them. The expected values are copied from the test
// suite of SurfaceTopography (ContactEngineering/SurfaceTopography, MIT licence, commit
// 119cb66ade8917a0a62a878c82d459f959566760, files test/IO/test_*.py and test/test_topography.py;
// each value cites its file and test). They are independent of frictal: SurfaceTopography has
// its own reader for every format. Definitions used to compare (SurfaceTopography's, in
// SurfaceTopography/Uniform/ScalarParameters.py):
//   rms_height_from_area         = Sq about the mean of all points     -> map_stats().Sq
//   rms_height_from_profile      = Rq pooled over the profiles along x -> map_scan_stats().Rq_x
//   transpose().rms_height_...   = the same along y                    -> map_scan_stats().Rq_y
//   rms_gradient                 = forward differences on the common (nx-1)(ny-1) grid
//                                                                      -> map_scan_stats().rms_gradient_fd
//   physical_sizes               = n dx (pixel convention)             -> nx dx, ny dy
// Files in a format only Gwyddion reads are skipped (GTEST_SKIP with the reason) where Gwyddion's
// libraries or file modules are not installed.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "frictal/analysis.hpp"
#include "frictal/io.hpp"
#include "frictal/scan_stats.hpp"

namespace {

const std::string kDir = std::string(FRICTAL_TEST_DATA) + "/instruments/";

bool native_format(const std::string& file) {
  for (const char* ext : {".txt", ".txt.gz", ".npy", ".sdf", ".hfm"})
    if (file.size() >= std::string(ext).size() &&
        file.compare(file.size() - std::string(ext).size(), std::string::npos, ext) == 0)
      return true;
  return false;
}

#define SKIP_WITHOUT_GWYDDION(file)                                                               \
  do {                                                                                            \
    std::string why;                                                                              \
    if (!native_format(file) && !frictal::gwyddion_available("", &why))                           \
      GTEST_SKIP() << file << " is read through Gwyddion's file modules, not available: " << why; \
  } while (0)

frictal::SurfaceData read_ok(const std::string& file, const frictal::ReadOptions& o = {}) {
  auto r = frictal::read_surface(kDir + file, o);
  EXPECT_TRUE(r.ok()) << file << ": " << (r ? std::string() : r.error().message);
  return r ? *r : frictal::SurfaceData{};
}

// One file: grid, physical sizes (n dx) and the rms values SurfaceTopography's tests state.
// 0 = not stated there. Lengths in metres (converted from the unit of the cited test).
struct Expect {
  const char* file;
  const char* channel;  // "" = frictal's default channel
  std::size_t nx, ny;
  double sx, sy, size_rtol;
  double Sq, Rq_x, Rq_y, rms_gradient, rms_rtol;
  const char* source;  // SurfaceTopography test that states the values
};

const Expect kMaps[] = {
    // Alicona .al3d (Gwyddion alicona): test/IO/test_al3d.py::test_al3d_metadata, rtol 1e-6.
    {"al3d-1.al3d", "", 200, 296, 8.76054e-05, 0.000129655992, 1e-6, 7.688266102603082e-06, 3.915731160953795e-06,
     6.620846789152015e-06, 0, 1e-6, "test_al3d.py::test_al3d_metadata"},
    // BCR binary .bcrf (Gwyddion bcrfile), lengths in nm there: test/IO/test_bcr.py::test_bcr_metadata.
    {"bcrf-1.bcrf", "", 960, 600, 1777404e-9, 1110878e-9, 1e-6, 24.560207201442292e-9, 24.009754961959388e-9,
     24.134045799796326e-9, 0, 1e-6, "test_bcr.py::test_bcr_metadata"},
    // Bruker Nanoscope .di (Gwyddion nanoscope), nm there, assertAlmostEqual (7 places in nm):
    // test/test_topography.py::diSurfaceTest::test_read: di-1 channels 0 and 1 (both "Height"),
    // di-3 channels 0 (ZSensor) and 3 (Height).
    {"di-1.di", "", 512, 512, 500e-9, 500e-9, 1e-12, 9.9459868005603909e-9, 0, 0, 0, 1e-9,
     "test_topography.py::diSurfaceTest::test_read"},
    {"di-1.di", "1", 512, 512, 500e-9, 500e-9, 1e-12, 114.01328027385664e-9, 0, 0, 0, 1e-9,
     "test_topography.py::diSurfaceTest::test_read"},
    {"di-3.di", "", 256, 256, 10000e-9, 10000e-9, 1e-12, 226.42539668457405e-9, 0, 0, 0, 1e-9,
     "test_topography.py::diSurfaceTest::test_read"},
    {"di-3.di", "Height", 256, 256, 10000e-9, 10000e-9, 1e-12, 264.00285276203158e-9, 0, 0, 0, 1e-9,
     "test_topography.py::diSurfaceTest::test_read"},
    // Park Systems TIFF (Gwyddion psia), µm there: test/IO/test_ps.py::test_ps_metadata.
    {"example_ps.tiff", "", 512, 512, 1e-6, 1e-6, 1e-6, 0.003933333499668988e-6, 0, 0, 0, 1e-6,
     "test_ps.py::test_ps_metadata"},
    // Zygo MetroPro .dat (Gwyddion metropro): test/IO/test_metropro.py::test_metropro_metadata.
    {"metropro-1.dat", "", 640, 480, 0.0007028812979115173, 0.000527160973433638, 1e-6, 7.528822204734589e-08,
     7.524071e-08, 0, 0, 1e-6, "test_metropro.py::test_metropro_metadata"},
    // Agilent/Molecular Imaging .mi (Gwyddion mifile): test/IO/test_mi.py::test_read_header.
    {"mi-1.mi", "", 256, 256, 2e-05, 2e-05, 1e-12, 0, 0, 0, 0, 0, "test_mi.py::test_read_header"},
    // Nanosurf .nid (Gwyddion ezdfile): test/IO/test_ezd.py::test_ezd_metadata, rtol 1e-6.
    // SurfaceTopography's channel 0 'Scan forward (Z-Axis)' is Gwyddion's 'Z-Axis forward' (its
    // channel 1; Gwyddion lists the deflection first), channel 1 'Scan forward (Z-AxisSensor)'.
    {"nid-1.nid", "", 256, 256, 2e-5, 2e-5, 1e-6, 2.395896706764167e-07, 2.294702406191355e-07, 6.891854644154332e-08,
     0, 1e-6, "test_ezd.py::test_ezd_metadata"},
    {"nid-1.nid", "Z-AxisSensor forward", 256, 256, 2e-5, 2e-5, 1e-6, 3.026701737129839e-07, 0, 0, 0, 1e-6,
     "test_ezd.py::test_ezd_metadata"},
    // Wyko .opd (Gwyddion wyko), mm there, pytest.approx (rel 1e-6): test/IO/test_opd.py::test_read_opd.
    {"opd-1.opd", "", 640, 480, 0.125909140e-3, 0.094431855e-3, 1e-6, 0, 0, 0, 0, 0, "test_opd.py::test_read_opd"},
    // Sensofar .plu (Gwyddion sensofar), µm there: test/IO/test_plu.py::test_plu_metadata, rtol 1e-6.
    {"plu-1.plu", "", 768, 576, 1274.880066e-6, 956.160049e-6, 1e-6, 2.834391e-6, 2.833895e-6, 0, 0, 1e-6,
     "test_plu.py::test_plu_metadata"},
    // WSxM .stp/.top (Gwyddion wsxmfile), nm there: test/IO/test_wsxm.py. The .stp value is
    // stated to 7 digits (1.654156 nm); Gwyddion's reading gives 1.6541585 nm, 1.5e-6 relative
    // away (SurfaceTopography's own rtol is 1e-6): tolerance 3e-6 here, see docs/io.md.
    {"stp-1.stp", "", 256, 256, 600e-9, 600e-9, 1e-12, 1.654156e-9, 0, 0, 0, 3e-6, "test_wsxm.py::test_stp_metadata"},
    {"top-1.top", "", 256, 256, 600e-9, 600e-9, 1e-12, 3.153099e-9, 0, 0, 0, 1e-6, "test_wsxm.py::test_top_metadata"},
    // Digital Surf .sur (Gwyddion surffile): test/IO/test_sur.py::test_sur3_metadata, rtol 1e-6.
    {"sur-3.sur", "", 512, 512, 0.151319552, 0.151319552, 1e-6, 0.0019200491394179297, 0, 0, 0, 1e-6,
     "test_sur.py::test_sur3_metadata"},
    // Igor .ibw (Gwyddion igorfile): test/IO/test_ibw.py::test_ibw_kpfm_file states 2e-5 m for
    // every channel with abs 0.01 (m!); the file's 256 pixels of 20 um / 255 give 2.00784e-5 m,
    // the convention of its ibw-1 test (50 nm x 512/511). Tolerance 0.5 % here.
    {"spot_1-1000nm.ibw", "", 256, 256, 2e-5, 2e-5, 5e-3, 0, 0, 0, 0, 0, "test_ibw.py::test_ibw_kpfm_file"},
    // Wyko ASCII matrix ("h= w=", "pixel size", "height conversion factor (-> m)"), gzip-compressed
    // (native): test/IO/test_asc.py::test_example4 (assert_allclose, rtol 1e-7).
    {"matrix-4.txt.gz", "", 75, 305, 2.773965e-05, 0.00011280791, 1e-6, 1.1745891510991089e-07, 7.198047e-08, 0,
     0.06776316911544318, 1e-6, "test_asc.py::test_example4"},
    // Gwyddion text export of an AFM scan (native): test/IO/test_asc.py::test_example3, rtol 1e-7.
    {"matrix-3.txt", "", 256, 256, 10e-6, 10e-6, 1e-7, 3.5222918750198742e-08, 0, 0, 0.19235602282848963, 1e-7,
     "test_asc.py::test_example3"},
    // ISO 25178-71 SDF, ASCII (native): test/IO/test_sdf.py::test_sdf_ascii_metadata (7 x 4 um, rtol 1e-3).
    {"sdf-1.sdf", "", 7, 4, 7e-6, 4e-6, 1e-3, 0, 0, 0, 0, 0, "test_sdf.py::test_sdf_ascii_metadata"},
};

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

void check_map(const Expect& e) {
  SCOPED_TRACE(std::string(e.file) + " channel '" + e.channel + "' (" + e.source + ")");
  frictal::ReadOptions o;
  o.channel = e.channel;
  frictal::SurfaceData s = read_ok(e.file, o);
  ASSERT_TRUE(s.is_map);
  const frictal::Map& m = s.map;
  EXPECT_EQ(m.nx, e.nx);
  EXPECT_EQ(m.ny, e.ny);
  EXPECT_LE(rel(double(m.nx) * m.dx, e.sx), e.size_rtol) << double(m.nx) * m.dx;
  EXPECT_LE(rel(double(m.ny) * m.dy, e.sy), e.size_rtol) << double(m.ny) * m.dy;
  const frictal::MapStats st = frictal::map_stats(m);
  const frictal::MapScanStats sc = frictal::map_scan_stats(m);
  if (e.Sq > 0) {
    EXPECT_LE(rel(st.Sq, e.Sq), e.rms_rtol) << "Sq " << st.Sq;
  }
  if (e.Rq_x > 0) {
    EXPECT_LE(rel(sc.Rq_x, e.Rq_x), e.rms_rtol) << "Rq_x " << sc.Rq_x;
  }
  if (e.Rq_y > 0) {
    EXPECT_LE(rel(sc.Rq_y, e.Rq_y), e.rms_rtol) << "Rq_y " << sc.Rq_y;
  }
  if (e.rms_gradient > 0) {
    EXPECT_LE(rel(sc.rms_gradient_fd, e.rms_gradient), e.rms_rtol) << "rms gradient " << sc.rms_gradient_fd;
  }
}

}  // namespace

TEST(Instruments, NativeMapsMatchSurfaceTopography) {
  int n = 0;
  for (const Expect& e : kMaps)
    if (native_format(e.file)) {
      check_map(e);
      ++n;
    }
  EXPECT_EQ(n, 3);
}

TEST(Instruments, GwyddionMapsMatchSurfaceTopography) {
  std::string why;
  if (!frictal::gwyddion_available("", &why))
    GTEST_SKIP() << "al3d, bcrf, di, tiff, MetroPro, mi, nid, opd, plu, stp/top, sur, ibw files are read through "
                    "Gwyddion's file modules, not available: "
                 << why;
  for (const Expect& e : kMaps)
    if (!native_format(e.file)) check_map(e);
}

// Orientation: test/test_topography.py::test_di_orientation states the corners of di-1.di's
// heights() (first index x, second y) to 1e-3 nm: [0, 0] = 6.060, [0, -1] = 2.843, [-1, 0] =
// -9.740, [-1, -1] = -30.306 nm. frictal's map.at(i, j) is x = i dx, y = j dy: the same corners.
TEST(Instruments, NanoscopeOrientation) {
  SKIP_WITHOUT_GWYDDION(std::string("di-1.di"));
  frictal::SurfaceData s = read_ok("di-1.di");
  ASSERT_TRUE(s.is_map);
  const frictal::Map& m = s.map;
  ASSERT_EQ(m.nx, 512u);
  EXPECT_NEAR(m.at(0, 0), 6.060e-9, 1e-12);
  EXPECT_NEAR(m.at(0, m.ny - 1), 2.843e-9, 1e-12);
  EXPECT_NEAR(m.at(m.nx - 1, 0), -9.740e-9, 1e-12);
  EXPECT_NEAR(m.at(m.nx - 1, m.ny - 1), -30.306e-9, 1e-12);
}

// Agilent .mi: SurfaceTopography's test_mi.py::test_topography states heights[0, 0] =
// -0.4986900329589844 um (rtol 1e-6): the first point of the first row, x = y = 0.
TEST(Instruments, AgilentMiFirstHeight) {
  SKIP_WITHOUT_GWYDDION(std::string("mi-1.mi"));
  frictal::SurfaceData s = read_ok("mi-1.mi");
  ASSERT_TRUE(s.is_map);
  EXPECT_LE(rel(s.map.at(0, 0), -0.4986900329589844e-6), 1e-6);
  EXPECT_EQ(s.channels.size(), 4u);  // "Like in Gwyddion, there should be 4 channels in total"
  EXPECT_EQ(s.channels[0].name, "Topography");
}

// MicroProf .frt (Gwyddion microprof): test/IO/test_frt.py::test_frt2_metadata states 150 x 300
// points, 0.03 x 0.06 m, rms_height_from_area 1.853335e-05 m and rms_height_from_profile
// 1.439208e-05 m (rtol 1e-6), and that the file has undefined data. The raw value 1 marks an
// undefined point in both readers, but SurfaceTopography computes those rms values on its masked
// array with the mean and the count taken over ALL nx ny points (Sq'^2 = sum over valid points
// of (z - sum(z)/N)^2 / N, N = nx ny; Rq' likewise per row with the row's nx), so the stated
// numbers are reproduced with that formula here. frictal's own Sq is over the valid points
// only: 8.826763181113766e-06 m, from a decoding of the file by a second method (Python
// struct: block 0x66 gives 150 x 300 x 16 bit, block 0x6c the scale 9.765923032319103e-09 m,
// block 0x0b the uint16 data; 32686 valid points).
TEST(Instruments, MicroProfFrtMatchesWithItsMaskedConvention) {
  SKIP_WITHOUT_GWYDDION(std::string("frt-2.frt"));
  frictal::SurfaceData s = read_ok("frt-2.frt");
  ASSERT_TRUE(s.is_map);
  const frictal::Map& m = s.map;
  ASSERT_EQ(m.nx, 150u);
  ASSERT_EQ(m.ny, 300u);
  EXPECT_LE(rel(double(m.nx) * m.dx, 0.03), 1e-6);
  EXPECT_LE(rel(double(m.ny) * m.dy, 0.06), 1e-6);
  EXPECT_EQ(m.valid_count(), 32686u);
  const double N = double(m.nx * m.ny);
  double sum = 0;
  for (double v : m.heights)
    if (!std::isnan(v)) sum += v;
  const double mean_all = sum / N;
  double s2 = 0, r2 = 0;
  for (std::size_t j = 0; j < m.ny; ++j) {
    double rs = 0;
    for (std::size_t i = 0; i < m.nx; ++i)
      if (!std::isnan(m.at(i, j))) rs += m.at(i, j);
    const double row_mean = rs / double(m.nx);
    for (std::size_t i = 0; i < m.nx; ++i)
      if (!std::isnan(m.at(i, j))) {
        s2 += (m.at(i, j) - mean_all) * (m.at(i, j) - mean_all);
        r2 += (m.at(i, j) - row_mean) * (m.at(i, j) - row_mean);
      }
  }
  EXPECT_LE(rel(std::sqrt(s2 / N), 1.853335e-05), 1e-6);
  EXPECT_LE(rel(std::sqrt(r2 / N), 1.439208e-05), 1e-6);
  EXPECT_LE(rel(frictal::map_stats(m).Sq, 8.826763181113766e-06), 1e-9);
}

// Bruker Vision64 .opdx line scan (Gwyddion dektakvca) against its text export opdx-3.txt (x, z
// in metres, native reader): test/IO/test_opdx.py::test_opdx3 states heights == z of the text
// file (assert_allclose, rtol 1e-7). Both paths must give the same points.
TEST(Instruments, OpdxProfileEqualsItsTextExport) {
  SKIP_WITHOUT_GWYDDION(std::string("opdx-3.opdx"));
  frictal::SurfaceData a = read_ok("opdx-3.opdx");
  frictal::SurfaceData b = read_ok("opdx-3.txt");
  ASSERT_FALSE(a.is_map);
  ASSERT_FALSE(b.is_map);
  ASSERT_EQ(a.curve.size(), 3001u);
  ASSERT_EQ(b.curve.size(), 3001u);
  double lo = INFINITY, hi = -INFINITY;
  for (double z : b.curve.z) {
    lo = std::min(lo, z);
    hi = std::max(hi, z);
  }
  const double length = b.curve.x.back() - b.curve.x.front();
  for (std::size_t k = 0; k < a.curve.size(); ++k) {
    // The text export prints 8 significant digits.
    EXPECT_NEAR(a.curve.z[k], b.curve.z[k], 1e-7 * std::abs(b.curve.z[k]) + 1e-12 * (hi - lo)) << k;
    EXPECT_NEAR(a.curve.x[k] - a.curve.x.front(), b.curve.x[k] - b.curve.x.front(), 1e-7 * length) << k;
  }
}

// HFM (X;Y;valid semicolon text from a stylus instrument, native): test/IO/test_xyz.py::
// test_hfm_metadata states 9600 points, physical size 4.8 mm (n dx) and rms_height_from_profile
// 0.000906 mm (rtol 1e-3; Rq about the mean of the points).
TEST(Instruments, HfmProfile) {
  frictal::SurfaceData s = read_ok("hfm-1.hfm");
  ASSERT_FALSE(s.is_map);
  ASSERT_EQ(s.curve.size(), 9600u);
  const double dx = (s.curve.x.back() - s.curve.x.front()) / double(s.curve.size() - 1);
  EXPECT_LE(rel(dx * double(s.curve.size()), 4.8e-3), 1e-6);
  double mean = 0;
  for (double z : s.curve.z) mean += z / double(s.curve.size());
  double q = 0;
  for (double z : s.curve.z) q += (z - mean) * (z - mean);
  EXPECT_LE(rel(std::sqrt(q / double(s.curve.size())), 0.000906e-3), 1e-3);
}

// x, y, z point lists on a 4 x 4 grid, in any order (native): test/IO/test_xyz.py::test_read_2d
// states shape (4, 4) and, for xyz-1, z = 2 at (x, y) = (1, 1), (1, 2) and 1 elsewhere.
TEST(Instruments, XyzGrids) {
  for (const char* f : {"xyz-1.txt", "xyz-1-different-order.txt", "xyz-2.txt"}) {
    SCOPED_TRACE(f);
    frictal::SurfaceData s = read_ok(f);
    ASSERT_TRUE(s.is_map);
    ASSERT_EQ(s.map.nx, 4u);
    ASSERT_EQ(s.map.ny, 4u);
    if (std::string(f).rfind("xyz-1", 0) != 0) continue;
    for (std::size_t j = 0; j < 4; ++j)
      for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(s.map.at(i, j), (i == 1 && (j == 1 || j == 2)) ? 2.0 : 1.0) << i << "," << j;
      }
  }
}

// A single column of heights (native, needs the spacing): test/IO/test_asc.py::
// test_single_column reads 9 points with physical size 2.3 and heights 1..9.
TEST(Instruments, SingleColumn) {
  frictal::ReadOptions o;
  o.spacing = 2.3 / 9;
  frictal::SurfaceData s = read_ok("single_column.txt", o);
  ASSERT_FALSE(s.is_map);
  ASSERT_EQ(s.curve.size(), 9u);
  for (std::size_t k = 0; k < 9; ++k) EXPECT_DOUBLE_EQ(s.curve.z[k], double(k + 1));
  EXPECT_NEAR(double(s.curve.size()) * (s.curve.x[1] - s.curve.x[0]), 2.3, 1e-12);
}

// NumPy .npy (native): test/IO/test_npy.py reads example-2d.npy with physical_sizes (1, 1). The
// array, decoded by a second method (Python struct; '<f8', C order, shape (2, 2)), is
// [[0.1, 1.0], [4.0, 7.0]]; a[j, i] is x = i dx, y = j dy.
TEST(Instruments, NumpyArray) {
  frictal::ReadOptions o;
  o.spacing = 0.5;
  frictal::SurfaceData s = read_ok("example-2d.npy", o);
  ASSERT_TRUE(s.is_map);
  ASSERT_EQ(s.map.nx, 2u);
  ASSERT_EQ(s.map.ny, 2u);
  EXPECT_DOUBLE_EQ(s.map.at(0, 0), 0.1);
  EXPECT_DOUBLE_EQ(s.map.at(1, 0), 1.0);
  EXPECT_DOUBLE_EQ(s.map.at(0, 1), 4.0);
  EXPECT_DOUBLE_EQ(s.map.at(1, 1), 7.0);
  EXPECT_DOUBLE_EQ(double(s.map.nx) * s.map.dx, 1.0);
}

// Where both read a file, the native reader and Gwyddion's give the same grid and heights:
// sdf-1.sdf (native SDF reader / Gwyddion sdfile).
TEST(Instruments, SdfNativeEqualsGwyddion) {
  std::string why;
  if (!frictal::gwyddion_available("", &why)) GTEST_SKIP() << "Gwyddion not available: " << why;
  frictal::SurfaceData a = read_ok("sdf-1.sdf");
  frictal::ReadOptions o;
  o.format = frictal::ProfileFormat::GwyddionLib;
  frictal::SurfaceData b = read_ok("sdf-1.sdf", o);
  ASSERT_EQ(a.reader, "native");
  ASSERT_TRUE(b.reader.rfind("gwyddion:", 0) == 0) << b.reader;
  ASSERT_EQ(a.map.nx, b.map.nx);
  ASSERT_EQ(a.map.ny, b.map.ny);
  EXPECT_NEAR(a.map.dx, b.map.dx, 1e-12 * a.map.dx);
  EXPECT_NEAR(a.map.dy, b.map.dy, 1e-12 * a.map.dy);
  for (std::size_t k = 0; k < a.map.size(); ++k) EXPECT_NEAR(a.map.heights[k], b.map.heights[k], 1e-15) << k;
}

// The Wyko/Vision ASCII matrix header (matrix-2/-4 of SurfaceTopography's corpus): "h=" and "w="
// are the numbers of rows and columns, "pixel size" the spacing, and each value times the
// "height conversion factor (-> UNIT)" is a height in UNIT. Built by hand: 3 columns, 2 rows.
TEST(Instruments, WykoAsciiHeader) {
  const std::string text =
      "h=2 w=3\npixel size=2.5e-007 m\ndata unit=rad\nheight conversion factor (-> um)=0.5\n"
      "1 2 3\n4 5 6\n";
  auto r = frictal::read_surface_bytes(text, "wyko.txt");
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_TRUE(r->is_map);
  EXPECT_EQ(r->map.nx, 3u);
  EXPECT_EQ(r->map.ny, 2u);
  EXPECT_DOUBLE_EQ(r->map.dx, 2.5e-7);
  EXPECT_DOUBLE_EQ(r->map.dy, 2.5e-7);
  EXPECT_DOUBLE_EQ(r->map.at(0, 0), 0.5e-6);
  EXPECT_DOUBLE_EQ(r->map.at(2, 1), 3.0e-6);
  EXPECT_TRUE(r->warnings.empty()) << r->warnings.front().message;
  // "w" with a length unit stays the physical width (pixel convention); the pixel size is then
  // only a fallback: dx = 3 um / 3 columns.
  auto sized = frictal::read_surface_bytes("w=3um h=2um\npixel size=2.5e-007 m\nunit: nm\n1 2 3\n4 5 6\n", "w.txt");
  ASSERT_TRUE(sized.ok()) << sized.error().message;
  EXPECT_DOUBLE_EQ(sized->map.dx, 1e-6);
  EXPECT_DOUBLE_EQ(sized->map.dy, 1e-6);
  // A column count that disagrees with the data is an error naming the key.
  auto bad = frictal::read_surface_bytes("h=2 w=4\npixel size=2.5e-007 m\n1 2 3\n4 5 6\n", "wyko.txt");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("w = 4"), std::string::npos) << bad.error().message;
  // A conversion factor without a length unit is refused.
  auto unit = frictal::read_surface_bytes(
      "h=2 w=3\npixel size=1e-6 m\nheight conversion factor (-> V)=2\n1 2 3\n4 5 6\n", "wyko.txt");
  ASSERT_FALSE(unit.ok());
  EXPECT_NE(unit.error().message.find("height conversion factor"), std::string::npos) << unit.error().message;
}

// JPK QI image (.jpk-qi-image, Gwyddion jpkscan), from AFMReader (AFM-SPM/AFMReader, LGPL-3.0,
// commit 062b98453fb6abae9b7a9312f164ac82f771c6a4): tests/test_jpk.py::test_load_jpk states a
// (100, 100) image of 4.999999999999986 nm pixels whose heights sum to 31593146.16051172 nm
// (channel height_trace) and 32181137.138706185 nm (measuredHeight_trace), pytest.approx (rel
// 1e-6). Gwyddion names them "Height" and "Height (measured)" (channel 2; channel 0 is the
// retrace of the same name).
TEST(Instruments, JpkQiImage) {
  SKIP_WITHOUT_GWYDDION(std::string("sample_0.jpk-qi-image"));
  for (const auto& [channel, sum_nm] : {std::pair<const char*, double>{"Height", 31593146.16051172},
                                        std::pair<const char*, double>{"2", 32181137.138706185}}) {
    SCOPED_TRACE(channel);
    frictal::ReadOptions o;
    o.channel = channel;
    frictal::SurfaceData s = read_ok("sample_0.jpk-qi-image", o);
    ASSERT_TRUE(s.is_map);
    ASSERT_EQ(s.map.nx, 100u);
    ASSERT_EQ(s.map.ny, 100u);
    EXPECT_LE(rel(s.map.dx, 4.999999999999986e-9), 1e-9);
    EXPECT_LE(rel(s.map.dy, 4.999999999999986e-9), 1e-9);
    double sum = 0;
    for (double v : s.map.heights) sum += v;
    EXPECT_LE(rel(sum * 1e9, sum_nm), 1e-6);
  }
}

// A "valid" column (hfm-1.hfm's `X;Y;valid` with the unit line `[mm];[mm];[1/0]`) flags points:
// 0 drops the point (one warning), anything but 0 or 1 is an error naming the line.
TEST(Instruments, ValidColumnFlagsPoints) {
  // (x = 0, 1, 2, 3 would look like an index column were it not for the "valid" column)
  const std::string text = "X;Y;valid\n[mm];[mm];[1/0]\n0;1;1\n1;2;0\n2;3;1\n3;4;1\n";
  auto r = frictal::read_surface_bytes(text, "v.hfm");
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_FALSE(r->is_map);
  ASSERT_EQ(r->curve.size(), 3u);
  EXPECT_DOUBLE_EQ(r->curve.x[1], 2e-3);
  EXPECT_DOUBLE_EQ(r->curve.z[1], 3e-3);
  ASSERT_EQ(r->warnings.size(), 1u);
  EXPECT_NE(r->warnings[0].message.find("1 points flagged invalid"), std::string::npos) << r->warnings[0].message;
  auto bad = frictal::read_surface_bytes("X;Y;valid\n[mm];[mm];[1/0]\n0;1;1\n1;2;2\n2;3;1\n", "v.hfm");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("v.hfm:4:"), std::string::npos) << bad.error().message;
  // The real file: 9,600 points, all flagged valid, no column warning.
  auto hfm = frictal::read_surface(kDir + "hfm-1.hfm");
  ASSERT_TRUE(hfm.ok());
  EXPECT_TRUE(hfm->warnings.empty()) << hfm->warnings.front().message;
}

// An Igor file whose one channel has no name and no units: test/IO/test_ibw.py::
// test_ibw_file_with_one_channel_without_name states one channel, two-dimensional, 10 x 10
// points. Without units it reads like a text column without one: metres with a warning, or the
// unit given (ReadOptions::default_unit, --unit) for sizes and heights alike.
TEST(Instruments, IgorChannelWithoutUnits) {
  SKIP_WITHOUT_GWYDDION(std::string("10x10-one_channel_without_name.ibw"));
  frictal::SurfaceData m = read_ok("10x10-one_channel_without_name.ibw");
  ASSERT_TRUE(m.is_map);
  EXPECT_EQ(m.channels.size(), 1u);
  EXPECT_EQ(m.map.nx, 10u);
  EXPECT_EQ(m.map.ny, 10u);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].message.find("carries no units"), std::string::npos) << m.warnings[0].message;
  frictal::ReadOptions o;
  o.default_unit = "nm";
  frictal::SurfaceData n = read_ok("10x10-one_channel_without_name.ibw", o);
  EXPECT_TRUE(n.warnings.empty());
  EXPECT_DOUBLE_EQ(n.map.dx, 1e-9 * m.map.dx);
  for (std::size_t k = 0; k < m.map.size(); ++k) EXPECT_DOUBLE_EQ(n.map.heights[k], 1e-9 * m.map.heights[k]) << k;
}

// Wyko .opd undefined points: test/test_derivatives.py::test_derivative_with_undefined_data and
// test/test_scale_dependent_statistics.py::test_missing_data state that opd-1.opd has undefined
// data (and that some but not all heights are finite): Gwyddion's mask becomes invalid points,
// which never enter a statistic.
TEST(Instruments, WykoOpdHasUndefinedPoints) {
  SKIP_WITHOUT_GWYDDION(std::string("opd-1.opd"));
  frictal::SurfaceData s = read_ok("opd-1.opd");
  ASSERT_TRUE(s.is_map);
  const std::size_t valid = s.map.valid_count();
  EXPECT_LT(valid, s.map.size());
  EXPECT_GT(valid, s.map.size() / 2);
  const frictal::MapStats st = frictal::map_stats(s.map);
  EXPECT_EQ(st.valid, valid);
  EXPECT_TRUE(std::isfinite(st.Sq));
}

// A plain 10 x 10 matrix of heights without any header whose first column (2 2 2 2 2 0 0 0 0 0)
// is monotonic but no abscissa: test/IO/test_asc.py::test_example5 states a 10 x 10 topography
// with rms_height_from_area 1.0 (rows of 2 above rows of 0). Read as a 10-column CSV profile
// before (column 0 taken as x).
TEST(Instruments, PlainMatrixWhoseFirstColumnStaysPut) {
  frictal::ReadOptions o;
  o.spacing = 0.1;  // test_example5 gives physical sizes (1, 2); frictal's spacing is one value
  frictal::SurfaceData s = read_ok("matrix-5.txt", o);
  ASSERT_TRUE(s.is_map);
  EXPECT_EQ(s.format, frictal::ProfileFormat::Matrix);
  EXPECT_EQ(s.map.nx, 10u);
  EXPECT_EQ(s.map.ny, 10u);
  EXPECT_NEAR(frictal::map_stats(s.map).Sq, 1.0, 1e-15);
  EXPECT_NEAR(double(s.map.nx) * s.map.dx, 1.0, 1e-15);
}
