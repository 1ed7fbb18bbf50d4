// Metamorphic tests of the map prediction: one pair of maps presented in different ways must give
// the same answer. Where the presentation is an exact symmetry of the tilt test (other units, the
// experiment seen in a mirror, a re-export that keeps every height) the drops must agree to
// rounding; where it removes information (a crop) the answer must stay within its own spread
// (the 5-95 % range over drops). The turn of the whole experiment in its plane is
// MapPrediction.TurningTheWholeExperimentChangesNothing.
//
// Why each is the same test (lower map f, upper face g = the upper map turned over, the block's
// lift h(s) = max over the face of f - g at offset s):
//  - units: every length (x, y, z, the run-away distance, the spheres' radius) times k scales h
//    and s alike, so every slope dh/ds and every angle is unchanged;
//  - mirror: x -> -x of both maps, with the sliding direction reflected (theta -> 180 - theta),
//    is the experiment seen in a mirror normal to x at the nodes; between the nodes it is not: each
//    grid cell is split into two triangles along a diagonal (chosen relative to the direction), and
//    a mirror swaps the diagonals, so the mirrored maps are other surfaces through the same nodes.
//    Held within the spread;
//  - crop: the stated test (d, the spheres) is a local statistic of the map, so a crop keeps the
//    test where the cropped map still holds it and loses drops. Held within the spread.
//  - re-export: a map written to X3P as doubles and read back holds the same heights on the same
//    grid; written as 32-bit integers (an instrument's raw counts) its heights are rounded to
//    2^-32 of their range.
// Rounding alone can still move a drop that starts on the boundary between two basins (a tie
// between two seats broken the other way): the exact symmetries are held to a hundredth of the
// spread and most drops to 1e-3 deg, not every drop to rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>

#include "frictal/io.hpp"
#include "frictal/predict.hpp"

namespace {

constexpr double kDeg = std::numbers::pi / 180;

frictal::PredictSurface map_surface(frictal::Map m, const std::string& name) {
  frictal::PredictSurface s;
  s.is_map = true;
  s.map = std::move(m);
  s.name = name;
  return s;
}

// A random rough map: a sum of oblique waves of decreasing amplitude (no symmetry of its own).
frictal::Map waves(std::size_t nx, std::size_t ny, double a, unsigned seed) {
  frictal::Map m;
  m.nx = nx;
  m.ny = ny;
  m.dx = m.dy = a;
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      double z = 0;
      for (int k = 0; k < 10; ++k) {
        const double u = std::fmod(0.7548776662466927 * (k + 1) * (seed + 2), 1.0);
        const double v = std::fmod(0.5698402909980532 * (k + 1) * (seed + 5), 1.0);
        const double kx = 2 * std::numbers::pi * (0.6 + 2.5 * u) / 10.0,
                     ky = 2 * std::numbers::pi * (0.6 + 2.5 * v) / 10.0;
        z += std::sin(kx * double(i) + (k % 2 ? 1 : -1) * ky * double(j) + 6.283 * u * v) / (1 + 0.5 * k);
      }
      m.heights.push_back(0.25 * a * z);
    }
  return m;
}

frictal::Map scaled(frictal::Map m, double k) {
  m.dx *= k;
  m.dy *= k;
  m.x0 *= k;
  m.y0 *= k;
  for (double& z : m.heights) z *= k;
  return m;
}

// x -> -x: the node at (x, y) moves to (-x, y) (the map seen in a mirror normal to x).
frictal::Map mirrored_x(const frictal::Map& m) {
  frictal::Map r = m;
  r.x0 = -(m.x0 + double(m.nx - 1) * m.dx);
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) r.heights[j * m.nx + i] = m.at(m.nx - 1 - i, j);
  return r;
}

frictal::Prediction run(const frictal::Map& lo, const frictal::Map& up, double direction_deg, int drops = 9) {
  frictal::PredictOptions o;
  o.map_drops = drops;
  o.direction = direction_deg * kDeg;
  const auto a = map_surface(lo, "lower"), b = map_surface(up, "upper");
  auto p = frictal::predict(a, &b, o);
  EXPECT_TRUE(p.ok()) << (p ? "" : p.error().message);
  return p ? *p : frictal::Prediction{};
}

// The quantiles of b within a hundredth of a's 5-95 % spread, and at least `share` of the drops
// within 1e-3 deg of a's.
void expect_same_to_ties(const frictal::Prediction& a, const frictal::Prediction& b, double share,
                         const std::string& what) {
  const double tol = 0.01 * (a.friction_angle.q95 - a.friction_angle.q05);
  EXPECT_NEAR(b.friction_angle.q50, a.friction_angle.q50, tol) << what;
  EXPECT_NEAR(b.friction_angle.q05, a.friction_angle.q05, tol) << what;
  EXPECT_NEAR(b.friction_angle.q95, a.friction_angle.q95, tol) << what;
  ASSERT_EQ(a.drop_angles.size(), b.drop_angles.size()) << what;
  std::size_t same = 0;
  for (std::size_t k = 0; k < a.drop_angles.size(); ++k)
    same += std::abs(a.drop_angles[k] - b.drop_angles[k]) <= 1e-3 * kDeg ? 1 : 0;
  EXPECT_GE(double(same), share * double(a.drop_angles.size()))
      << what << ": " << same << " of " << a.drop_angles.size() << " drops within 1e-3 deg";
}

// Each median within the other's 5-95 % range over drops.
void expect_within_spreads(const frictal::Prediction& a, const frictal::Prediction& b, const std::string& what) {
  EXPECT_GE(b.friction_angle.q50, a.friction_angle.q05) << what;
  EXPECT_LE(b.friction_angle.q50, a.friction_angle.q95) << what;
  EXPECT_GE(a.friction_angle.q50, b.friction_angle.q05) << what;
  EXPECT_LE(a.friction_angle.q50, b.friction_angle.q95) << what;
}

}  // namespace

TEST(MapMetamorphic, OtherUnitsGiveTheSameAnswer) {
  // The pair in mm, in inches and in micrometres of micrometres against metres: the same stated
  // test scaled, every angle the same (along a grid axis and obliquely).
  const frictal::Map lo = waves(28, 26, 1e-6, 1), up = waves(16, 14, 1e-6, 2);
  for (const double dir : {0.0, 30.0}) {
    const auto p0 = run(lo, up, dir);
    for (const double k : {1e3, 25.4e-3, 1e-6}) {
      const auto p = run(scaled(lo, k), scaled(up, k), dir);
      EXPECT_NEAR(p.runaway_distance, k * p0.runaway_distance, 1e-9 * k * p0.runaway_distance);
      expect_same_to_ties(p0, p, 0.9, "lengths x " + std::to_string(k) + " at " + std::to_string(dir) + " deg");
    }
  }
}

TEST(MapMetamorphic, TheExperimentInAMirrorIsWithinTheSpread) {
  const frictal::Map lo = waves(28, 26, 1e-6, 1), up = waves(16, 14, 1e-6, 2);
  for (const double dir : {0.0, 30.0}) {
    const auto p0 = run(lo, up, dir);
    const auto pm = run(mirrored_x(lo), mirrored_x(up), 180 - dir);
    expect_within_spreads(p0, pm, "mirrored at " + std::to_string(dir) + " deg");
  }
}

TEST(MapMetamorphic, AReExportedMapGivesTheSameAnswer) {
  const frictal::Map lo = waves(28, 26, 1e-6, 1), up = waves(16, 14, 1e-6, 2);
  const auto p0 = run(lo, up, 30);
  const auto dir = std::filesystem::temp_directory_path() /
                   ("frictal-metamorphic-maps-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::create_directories(dir);
  for (const auto type : {frictal::X3pDataType::D, frictal::X3pDataType::L}) {
    frictal::X3pWriteOptions w;
    w.type = type;
    w.date = "2026-01-01T00:00:00Z";
    const std::string a = (dir / "lower.x3p").string(), b = (dir / "upper.x3p").string();
    ASSERT_TRUE(frictal::write_x3p(a, lo, w).ok());
    ASSERT_TRUE(frictal::write_x3p(b, up, w).ok());
    auto ra = frictal::read_map(a), rb = frictal::read_map(b);
    ASSERT_TRUE(ra.ok()) << ra.error().message;
    ASSERT_TRUE(rb.ok()) << rb.error().message;
    const auto p = run(*ra, *rb, 30);
    if (type == frictal::X3pDataType::D) {
      ASSERT_EQ(p.drop_angles.size(), p0.drop_angles.size());
      for (std::size_t k = 0; k < p.drop_angles.size(); ++k) EXPECT_EQ(p.drop_angles[k], p0.drop_angles[k]) << k;
    } else {
      expect_same_to_ties(p0, p, 0.9, "written as int32 counts");
    }
  }
  std::filesystem::remove_all(dir);
}

TEST(MapMetamorphic, ACropKeepsTheAnswerWithinItsSpread) {
  // A measured AFM map (tests/data/instruments/di-3.di, 10 um, 256 x 256) and its central 8 um:
  // the same surface, fewer drops.
  auto full = frictal::read_map(std::string(FRICTAL_TEST_DATA) + "/instruments/di-3.di");
  ASSERT_TRUE(full.ok()) << full.error().message;
  const frictal::Map& m = *full;
  const std::size_t c0 = m.nx / 10, c1 = m.nx - m.nx / 10;
  frictal::Map crop = m;
  crop.nx = crop.ny = c1 - c0;
  crop.x0 = m.x0 + double(c0) * m.dx;
  crop.y0 = m.y0 + double(c0) * m.dy;
  crop.heights.clear();
  for (std::size_t j = c0; j < c1; ++j)
    for (std::size_t i = c0; i < c1; ++i) crop.heights.push_back(m.at(i, j));
  frictal::PredictOptions o;
  auto a = frictal::predict(map_surface(m, "full"), nullptr, o);
  auto b = frictal::predict(map_surface(crop, "crop"), nullptr, o);
  ASSERT_TRUE(a.ok()) << a.error().message;
  ASSERT_TRUE(b.ok()) << b.error().message;
  expect_within_spreads(*a, *b, "the central 8 um of di-3");
}
