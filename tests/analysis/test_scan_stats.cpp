// Scan quantities against closed forms derived by hand (docs/analysis.md, "Scan quantities").
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "frictal/scan_stats.hpp"

namespace {
constexpr double kPi = std::numbers::pi;

// z(i, j) = A sin(2 pi i / Nx) + C j dy: a sine along x over exactly one period, a plane along y.
frictal::Map sine_plane(std::size_t nx, std::size_t ny, double dx, double dy, double A, double C) {
  frictal::Map m;
  m.nx = nx;
  m.ny = ny;
  m.dx = dx;
  m.dy = dy;
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i)
      m.heights.push_back(A * std::sin(2 * kPi * double(i) / double(nx)) + C * double(j) * dy);
  return m;
}
}  // namespace

TEST(ScanStats, MapSizesBandwidthAndPerProfileValues) {
  const std::size_t nx = 32, ny = 10;
  const double dx = 0.5e-6, dy = 0.25e-6, A = 2e-8, C = 0.03;
  auto s = frictal::map_scan_stats(sine_plane(nx, ny, dx, dy, A, C));
  EXPECT_DOUBLE_EQ(s.physical_size_x, 16e-6);
  EXPECT_DOUBLE_EQ(s.physical_size_y, 2.5e-6);
  EXPECT_DOUBLE_EQ(s.bandwidth_short, 0.375e-6);
  EXPECT_DOUBLE_EQ(s.bandwidth_long, 9.25e-6);
  EXPECT_DOUBLE_EQ(s.nyquist_wavelength, 1e-6);
  // Rows: a whole period of A sin (the plane is the row's mean): Rq_x = A / sqrt 2.
  EXPECT_NEAR(s.Rq_x, A / std::sqrt(2.0), 1e-12 * A);
  // Forward differences of the sine, k = 2 pi / Nx: sum_{i=0}^{N-2} (sin k(i+1) - sin ki)^2
  //   = 4 sin^2(k/2) (N/2 - cos^2(k/2)), over N - 1 differences.
  const double k = 2 * kPi / double(nx);
  const double sum = 4 * std::pow(std::sin(k / 2), 2) * (double(nx) / 2 - std::pow(std::cos(k / 2), 2));
  const double rdq_x = A / dx * std::sqrt(sum / double(nx - 1));
  EXPECT_NEAR(s.Rdq_x, rdq_x, 1e-12 * rdq_x);
  // Columns: C j dy about its mean: Rq_y = C dy sqrt((Ny^2 - 1) / 12); every slope is C.
  EXPECT_NEAR(s.Rq_y, C * dy * std::sqrt((double(ny * ny) - 1) / 12), 1e-12 * C * dy);
  EXPECT_NEAR(s.Rdq_y, C, 1e-12 * C);
  // Common grid: the x differences of rows 0..ny-2 (the same i range) plus C^2.
  EXPECT_NEAR(s.rms_gradient_fd, std::sqrt(rdq_x * rdq_x + C * C), 1e-12);
}

TEST(ScanStats, InvalidPointsAreSkipped) {
  // A plane of slope 0.1 along x with a hole: slopes stay 0.1, Rdq_x = 0.1.
  frictal::Map m = sine_plane(8, 8, 1e-6, 1e-6, 0, 0);
  for (std::size_t j = 0; j < 8; ++j)
    for (std::size_t i = 0; i < 8; ++i) m.at(i, j) = 0.1e-6 * double(i);
  m.at(3, 3) = NAN;
  auto s = frictal::map_scan_stats(m);
  EXPECT_NEAR(s.Rdq_x, 0.1, 1e-12);
  EXPECT_NEAR(s.Rdq_y, 0.0, 1e-12);
  EXPECT_NEAR(s.rms_gradient_fd, 0.1, 1e-12);
}

TEST(ScanStats, ProfileSizes) {
  frictal::Profile p;
  for (int k = 0; k < 11; ++k) {
    p.x.push_back(2e-6 + 0.5e-6 * k);
    p.z.push_back(0);
  }
  auto s = frictal::profile_scan_stats(p);
  EXPECT_DOUBLE_EQ(s.sampling_interval, 0.5e-6);
  EXPECT_DOUBLE_EQ(s.physical_length, 5.5e-6);  // 11 x 0.5 um (the (n-1) dx extent is 5 um)
  EXPECT_DOUBLE_EQ(s.bandwidth_long, 5.5e-6);
  EXPECT_DOUBLE_EQ(s.nyquist_wavelength, 1e-6);
}

TEST(ScanStats, TipRadiusCutoffOfATriangleWave) {
  // SurfaceTopography's definition (docs/analysis.md): the stencil length 2h at which the most
  // negative curvature (z(x+h) - 2 z(x) + z(x-h)) / h^2 reaches -1/(2R). A triangle wave of slope
  // +-s with its kinks on the samples (period 64 dx, peaks at i = 32 mod 64) has -2 s / h at
  // every peak for h up to half a period, and nothing more negative anywhere; linear
  // interpolation between samples is exact on it. So 2 s / h = 1 / (2R) at h = 4 s R: the cutoff
  // is 8 s R, also between samples.
  const double dx = 1e-7, s = 0.1;
  auto tri = [&](int i) { return s * dx * (16 - std::abs(i % 64 - 32)); };
  frictal::Profile p;
  for (int i = 0; i < 512; ++i) {
    p.x.push_back(i * dx);
    p.z.push_back(tri(i));
  }
  const double R = 5.3 * dx / (4 * s);  // h = 5.3 dx: cutoff 10.6 dx
  auto c = frictal::short_reliability_cutoff(p, R);
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_NEAR(*c, 8 * s * R, 1e-9 * 8 * s * R);
  EXPECT_NEAR(*c, 10.6 * dx, 1e-9 * dx);
  // A blunter tip: 4 R gives h = 21.2 dx, still inside half a period.
  auto blunt = frictal::short_reliability_cutoff(p, 4 * R);
  ASSERT_TRUE(blunt.ok());
  EXPECT_NEAR(*blunt, 32 * s * R, 1e-9 * 32 * s * R);
  // A tip sharper than the peaks at h = dx (4 s R < dx) follows everything: 0.
  auto sharp = frictal::short_reliability_cutoff(p, 0.2 * dx / (4 * s));
  ASSERT_TRUE(sharp.ok());
  EXPECT_EQ(*sharp, 0.0);
  // Only peaks count: V-shaped valleys (the upside-down wave shifted by half a period has them
  // too, so use a single V) never make the scan unreliable, however sharp.
  frictal::Profile v;
  for (int i = 0; i < 512; ++i) {
    v.x.push_back(i * dx);
    v.z.push_back(s * dx * std::abs(i - 256));
  }
  auto cv = frictal::short_reliability_cutoff(v, 1.0);
  ASSERT_TRUE(cv.ok());
  EXPECT_EQ(*cv, 0.0);
  // A single tent: its apex stays sharp up to a quarter of the length (h = 128 dx) for a tip
  // with 2 s / (128 dx) > 1 / (2R): unreliable at every scale, NaN.
  frictal::Profile tent = v;
  for (double& z : tent.z) z = -z;
  auto ct = frictal::short_reliability_cutoff(tent, 1.0);
  ASSERT_TRUE(ct.ok());
  EXPECT_TRUE(std::isnan(*ct));
  EXPECT_NEAR(*frictal::short_reliability_cutoff(tent, R), 10.6 * dx, 1e-9 * dx);
  // The same wave along y in a map (the larger of the two directions; along x it is flat).
  frictal::Map m;
  m.nx = 4;
  m.ny = 512;
  m.dx = m.dy = dx;
  for (int j = 0; j < 512; ++j)
    for (int i = 0; i < 4; ++i) m.heights.push_back(tri(j));
  auto cm = frictal::short_reliability_cutoff(m, R);
  ASSERT_TRUE(cm.ok()) << cm.error().message;
  EXPECT_NEAR(*cm, 10.6 * dx, 1e-9 * dx);
  EXPECT_FALSE(frictal::short_reliability_cutoff(p, -1).ok());
}
