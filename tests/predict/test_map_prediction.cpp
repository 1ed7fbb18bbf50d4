// The map prediction (predict() on two maps, the continuous model of areal_tilt.hpp): its upper
// bound against its own drops on every map the project ships, the known answer of a flat pair,
// and the resolution of its hold angles; the cost of nearly flat pairs, in the model's own count of
// its work.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "frictal/areal_tilt.hpp"
#include "frictal/conditioning.hpp"
#include "frictal/io.hpp"
#include "frictal/predict.hpp"

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180;

frictal::PredictSurface map_surface(frictal::Map m, const std::string& name) {
  frictal::PredictSurface s;
  s.is_map = true;
  s.map = std::move(m);
  s.name = name;
  return s;
}

frictal::Map constant_map(std::size_t nx, std::size_t ny, double a, double z) {
  frictal::Map m;
  m.nx = nx;
  m.ny = ny;
  m.dx = m.dy = a;
  m.heights.assign(nx * ny, z);
  return m;
}

}  // namespace

TEST(MapPrediction, TheUpperBoundLiesAboveEveryDropOnEveryMapOfTheTestData) {
  // Every file of tests/data/{maps,x3p,instruments} that reads as a map, against itself turned
  // over (a window of at most 24 x 24 nodes, by the conditioning's crop, and 3 x 3 drops: the
  // test's cost), with and without atomic friction: the rigid upper bound comes from the seats
  // the drops rested in (the hold angles' own model) and lies above every drop. Before, it was
  // the grid areal signature's and lay below the median on 8 of 14 instrument maps (metropro-1:
  // bound 0.078 deg, median 3.99 deg).
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  for (const char* dir : {"maps", "x3p", "instruments"})
    for (const auto& e : fs::directory_iterator(fs::path(FRICTAL_TEST_DATA) / dir))
      if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  int maps = 0;
  for (const fs::path& path : files) {
    auto data = frictal::read_surface(path.string());
    if (!data.ok() || !data->is_map) continue;
    const frictal::Map& m = data->map;
    if (m.nx < 3 || m.ny < 3 || m.valid_count() < 9) continue;
    ++maps;
    frictal::PredictOptions o;
    o.map_drops = 3;
    const std::size_t n = 24;
    if (m.nx > n || m.ny > n) {
      frictal::CropWindow w;
      w.x_min = m.x0;
      w.x_max = m.x0 + double(std::min(m.nx, n) - 1) * m.dx;
      w.has_y = true;
      w.y_min = m.y0;
      w.y_max = m.y0 + double(std::min(m.ny, n) - 1) * m.dy;
      o.crop = w;
    }
    const frictal::PredictSurface s = map_surface(m, path.filename().string());
    // With friction on two maps only (the test's cost).
    const std::string name = path.filename().string();
    for (const double mu : {0.0, 0.2}) {
      if (mu > 0 && name != "x3p-2.x3p" && name != "metropro-1.dat") continue;
      o.atomic_friction = mu;
      auto p = frictal::predict(s, nullptr, o);
      ASSERT_TRUE(p.ok()) << path << ": " << p.error().message;
      ASSERT_EQ(p->drop_angles.size(), 9u) << path;
      for (std::size_t k = 0; k < p->drop_angles.size(); ++k)
        EXPECT_LE(p->drop_angles[k], p->upper_bound_friction_angle) << path << " mu_a " << mu << " drop " << k;
      // With friction the bound holds the cone's whole rim: at least theta_max + atan(mu_a) where
      // the steepest seat slope lies along the direction, and never below atan(mu_a) itself.
      EXPECT_GE(p->upper_bound_friction_angle, std::atan(mu) - 1e-12) << path;
      EXPECT_LE(p->eq18_range[0], p->eq18_range[1]) << path;
      EXPECT_EQ(p->eq18_range[1], p->upper_bound_friction_angle) << path;
    }
  }
  EXPECT_GE(maps, 20);  // the files the project ships that read as maps (most of them)
}

TEST(MapPrediction, AFlatPairHoldsAtAtanMuAExactlyInSeconds) {
  // Two flat faces: every contact is horizontal, so the block is held exactly while the load lies in
  // the contacts' friction cones, up to atan(mu_a) (0 without friction), and slides without end
  // beyond it (by hand). Along the axes the model's cone samples hold that direction exactly. A
  // 300 x 300 pair: before, each drop's descents evaluated every sphere (all tie for the max) at
  // each of thousands of steps (200 x 200: 13 of 25 drops in 240 s).
  const auto lower = map_surface(constant_map(300, 300, 1e-6, 2e-6), "flat");
  const auto upper = map_surface(constant_map(120, 90, 1e-6, -5e-7), "flat upper");
  for (const double mu : {0.0, 0.1, 0.35})
    for (const double dir : {0.0, 90.0}) {
      frictal::PredictOptions o;
      o.atomic_friction = mu;
      o.direction = dir * kDeg;
      o.map_drops = 4;
      o.map_locked = true;
      auto p = frictal::predict(lower, &upper, o);
      ASSERT_TRUE(p.ok()) << p.error().message;
      for (const double a : p->drop_angles) EXPECT_NEAR(a, std::atan(mu), 1e-12) << mu << " " << dir;
      for (const double a : p->drop_angles_locked) EXPECT_NEAR(a, std::atan(mu), 1e-12) << mu << " " << dir;
      EXPECT_NEAR(p->upper_bound_friction_angle, std::atan(mu), 1e-12);
      EXPECT_EQ(p->theta_max, 0.0);
    }
}

TEST(MapPrediction, HoldAnglesAreResolvedToATenThousandthOfADegree) {
  // Shallow grooves across x (A sin(2 pi i / m), the same in every row) against themselves turned
  // over: the block climbs the steepest segment of the piecewise-linear grooves, slope
  // A sin(2 pi / m) / a (by hand), 0.37 deg here: every drop reads it to 1e-4 deg (the bracket of
  // tilt_step once took 5 halvings: multiples of 0.003125 deg).
  const std::size_t n = 16;
  const int m = 8;
  const double a = 1e-3 / double(n - 1), A = 6e-7;
  frictal::Map g;
  g.nx = g.ny = n;
  g.dx = g.dy = a;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) g.heights.push_back(A * std::sin(2 * kPi * double(i) / m));
  frictal::Map w;
  w.nx = w.ny = 8;
  w.dx = w.dy = a;
  for (std::size_t j = 0; j < 8; ++j)
    for (std::size_t i = 0; i < 8; ++i) w.heights.push_back(g.at(i + 4, j + 4));
  frictal::PredictOptions o;
  o.detrend = frictal::Detrend{frictal::DetrendKind::None, 0};
  o.map_drops = 3;
  const frictal::PredictSurface window = map_surface(w, "window");
  auto p = frictal::predict(map_surface(g, "grooves"), &window, o);
  ASSERT_TRUE(p.ok()) << p.error().message;
  const double want = std::atan(A * std::sin(2 * kPi / m) / a);
  ASSERT_GT(want, 0.3 * kDeg);
  for (const double h : p->drop_angles) EXPECT_NEAR(h, want, 1e-4 * kDeg);
  EXPECT_GE(p->upper_bound_friction_angle, p->friction_angle.max);
}

namespace {

// The map turned by a quarter turn counterclockwise in its plane about the origin, written out
// here from its definition (the node at (x, y) moves to (-y, x)).
frictal::Map turn_quarter(const frictal::Map& m) {
  frictal::Map r;
  r.nx = m.ny;
  r.ny = m.nx;
  r.dx = m.dy;
  r.dy = m.dx;
  r.x0 = -(m.y0 + double(m.ny - 1) * m.dy);
  r.y0 = m.x0;
  for (std::size_t j = 0; j < r.ny; ++j)
    for (std::size_t i = 0; i < r.nx; ++i) r.heights.push_back(m.at(j, m.ny - 1 - i));
  return r;
}

// An anisotropic random surface: a sum of waves, long along y and short along x.
frictal::Map anisotropic(std::size_t nx, std::size_t ny, double a, unsigned seed) {
  frictal::Map m;
  m.nx = nx;
  m.ny = ny;
  m.dx = m.dy = a;
  double phase[12];
  for (int k = 0; k < 12; ++k) phase[k] = std::fmod(1.618033988749895 * (k + 1) * (seed + 3), 1.0) * 2 * kPi;
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      double z = 0;
      for (int k = 0; k < 12; ++k) {
        const double kx = 2 * kPi * (1 + k % 4) / 9.0, ky = 2 * kPi * (1 + k / 4) / 40.0;
        z += std::sin(kx * double(i) + ky * double(j) * (k % 2 ? 1 : -1) + phase[k]) / (1 + k % 4);
      }
      m.heights.push_back(0.15 * a * z);
    }
  return m;
}

}  // namespace

TEST(MapPrediction, TurningTheWholeExperimentChangesNothing) {
  // Both maps of an anisotropic pair turned by 90, 180 and 270 deg in their plane, the sliding
  // direction turned with them: the same experiment, so the same hold angle from every drop (the
  // drops lie at the same offsets along and across the direction). Before, the height field's
  // cells were split along one diagonal of the grid whatever the direction, and a quarter turn of
  // the maps split them along the other: other triangles, another answer (a random anisotropic
  // pair: median 18.10 deg against 16.91). Checked at 0 and 30 deg, free and locked.
  const frictal::Map lo = anisotropic(30, 26, 1e-6, 1), up = anisotropic(14, 12, 1e-6, 2);
  for (const double dir : {0.0, 30.0}) {
    frictal::PredictOptions o;
    o.map_drops = 3;
    o.map_locked = true;
    o.direction = dir * kDeg;
    const auto a = map_surface(lo, "lower"), b = map_surface(up, "upper");
    auto p0 = frictal::predict(a, &b, o);
    ASSERT_TRUE(p0.ok()) << p0.error().message;
    frictal::Map tl = lo, tu = up;
    for (int q = 1; q < 4; ++q) {
      tl = turn_quarter(tl);
      tu = turn_quarter(tu);
      const auto ta = map_surface(tl, "lower"), tb = map_surface(tu, "upper");
      o.direction = (dir + 90.0 * q) * kDeg;
      auto p = frictal::predict(ta, &tb, o);
      ASSERT_TRUE(p.ok()) << p.error().message;
      ASSERT_EQ(p->drop_angles.size(), p0->drop_angles.size());
      for (std::size_t k = 0; k < p->drop_angles.size(); ++k) {
        EXPECT_NEAR(p->drop_angles[k], p0->drop_angles[k], 1e-6 * kDeg) << dir << " deg, " << q << " turns, drop " << k;
        EXPECT_NEAR(p->drop_angles_locked[k], p0->drop_angles_locked[k], 1e-6 * kDeg) << dir << " " << q << " " << k;
      }
      EXPECT_NEAR(p->upper_bound_friction_angle, p0->upper_bound_friction_angle, 1e-6 * kDeg);
    }
  }
}

TEST(MapPrediction, RemovingSpikesFromANearlyFlatMapCostsAtMostABoundedMultipleOfTheSpikyMap) {
  // A nearly flat map (1 nm rms white noise on a 1 um grid, 160 x 144 nodes) with 6 spikes of
  // 1 um, against itself turned over, as predict() runs it (its model options, 9 drops over the
  // middle): with the spikes the block rests on them; with them masked by the spike filter and
  // filled (the model's small holes), the two faces are nearly flat and every sphere lies within a
  // few nm of the top. The model's work (ArealTiltHold::work: tiles and spheres read for the
  // candidate lists, spheres and cells evaluated; no clock), filled against spiky: 9.2 times
  // with the lists of before (cell-top bounds, every list from a scan of every tile), 6.1 times
  // with the tight bound and outer lists about the block, 5.1 times with outer lists wider and
  // ahead of the block on its way (fewer scans), of which 2.0 is the descents' own evaluations
  // (the block settles on noise instead of three spikes). The aim, removal never costlier, is not
  // met yet (bench/results/map-predict.md, "Nearly flat maps"); the bound keeps what was gained
  // (the outer lists about the block fail it).
  frictal::Map m;
  m.nx = 160;
  m.ny = 144;
  m.dx = m.dy = 1e-6;
  m.heights.resize(m.nx * m.ny);
  std::uint64_t state = 12345;
  auto uniform = [&] {  // a fixed generator (the same heights on every platform)
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double(state >> 11) + 0.5) / 9007199254740992.0;
  };
  for (double& z : m.heights)
    z = 1e-9 * std::sqrt(-2 * std::log(uniform())) * std::cos(2 * kPi * uniform());  // Box-Muller
  const std::size_t spikes[][2] = {{11, 9}, {123, 24}, {60, 80}, {140, 120}, {37, 118}, {95, 57}};
  for (const auto& sp : spikes) m.heights[sp[1] * m.nx + sp[0]] += 1e-6;
  frictal::Conditioning c;
  c.remove_spikes = true;
  auto cleaned = frictal::condition(m, c);
  ASSERT_TRUE(cleaned.ok()) << cleaned.error().message;
  ASSERT_EQ(cleaned->record.spikes_removed, std::size(spikes));
  auto work = [](const frictal::Map& map) {
    const frictal::MapHoldOptions t = frictal::map_model_options(map, frictal::PredictOptions{});
    std::vector<frictal::ArealTiltDrop> drops;
    for (const double u : {0.0, 8e-6, 16e-6})
      for (const double v : {-8e-6, 0.0, 8e-6}) drops.push_back({{u, v}, false});
    auto holds = frictal::areal_tilt_hold_drops(map, map, t, drops, 2);
    EXPECT_TRUE(holds.ok()) << holds.error().message;
    long total = 0;
    if (holds)
      for (const frictal::ArealTiltHold& h : *holds) total += h.work;
    return total;
  };
  const long spiky = work(m), removed = work(cleaned->map);
  EXPECT_GT(spiky, 0);
  EXPECT_LE(double(removed), 5.5 * double(spiky)) << "spiky " << spiky << ", spikes removed " << removed;
}

TEST(MapPrediction, ProgressFollowsTheDropsUnderWayAndTheDropsDone) {
  // The progress of a run of drops: every drop once finished (done counts 1..n, in order, each
  // once), and between, the tilt of the drops under way, which rises within a drop from zero
  // through its increments (at most the largest tilt; never negative). Two threads: the calls
  // come one at a time from either. The answers are those without progress.
  const frictal::Map lo = anisotropic(30, 26, 1e-6, 1);
  frictal::PredictOptions o;
  o.map_drops = 3;
  o.threads = 2;
  const frictal::Prediction quiet = *frictal::predict(map_surface(lo, "lo"), nullptr, o);
  std::vector<frictal::DropProgress> calls;
  o.progress = [&](const frictal::DropProgress& p) { calls.push_back(p); };
  auto p = frictal::predict(map_surface(lo, "lo"), nullptr, o);
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ(p->friction_angle.q50, quiet.friction_angle.q50);
  EXPECT_EQ(p->friction_angle.q95, quiet.friction_angle.q95);
  ASSERT_FALSE(calls.empty());
  std::size_t done = 0, with_tilt = 0;
  double highest = 0;
  for (const frictal::DropProgress& c : calls) {
    EXPECT_EQ(c.total, 9u);
    EXPECT_TRUE(c.done == done || c.done == done + 1) << c.done << " after " << done;
    done = c.done;
    EXPECT_LE(c.running, 2u);
    EXPECT_EQ(std::isnan(c.tilt), c.running == 0);
    if (c.running > 0) {
      EXPECT_GE(c.tilt, 0);
      EXPECT_LE(c.tilt, kPi / 2);
      highest = std::max(highest, c.tilt);
      ++with_tilt;
    }
  }
  EXPECT_EQ(done, 9u);
  EXPECT_EQ(calls.back().running, 0u);
  // More calls than drops: the increments of the drops under way are seen, up to the hold angles.
  EXPECT_GT(with_tilt, 9u * 3);
  EXPECT_GT(highest, 0.5 * p->friction_angle.q05);
}
