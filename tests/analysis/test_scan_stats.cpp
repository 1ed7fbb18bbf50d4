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

TEST(ScanStats, TipRadiusCutoffOfASinusoid) {
  // z = a sin(2 pi x / L0), L0 = 64 dx, sampled through its valleys. The stencil curvature at a
  // valley is a 2 (1 - cos(k0 h)) / h^2, decreasing in h: a tip of radius R follows the
  // surface from the h where it equals 1/R. Choose R so that this happens at h = 5 dx.
  const double dx = 1e-7, L0 = 64 * dx, a = 5e-8, k0 = 2 * kPi / L0, h5 = 5 * dx;
  const double R = h5 * h5 / (a * 2 * (1 - std::cos(k0 * h5)));
  frictal::Profile p;
  for (int i = 0; i < 512; ++i) {
    p.x.push_back(i * dx);
    p.z.push_back(a * std::sin(k0 * i * dx));
  }
  auto c = frictal::short_reliability_cutoff(p, R);
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_NEAR(*c, h5, 1e-6 * h5);
  // A much blunter tip fails at more scales; a sharp tip follows everything.
  auto blunt = frictal::short_reliability_cutoff(p, 4 * R);
  ASSERT_TRUE(blunt.ok());
  EXPECT_GT(*blunt, h5);
  auto sharp = frictal::short_reliability_cutoff(p, R / 100);
  ASSERT_TRUE(sharp.ok());
  EXPECT_EQ(*sharp, 0.0);
  // The same along y in a map (the larger of the two directions).
  frictal::Map m;
  m.nx = 4;
  m.ny = 512;
  m.dx = m.dy = dx;
  for (int j = 0; j < 512; ++j)
    for (int i = 0; i < 4; ++i) m.heights.push_back(a * std::sin(k0 * j * dx));
  auto cm = frictal::short_reliability_cutoff(m, R);
  ASSERT_TRUE(cm.ok()) << cm.error().message;
  EXPECT_NEAR(*cm, h5, 1e-6 * h5);
  EXPECT_FALSE(frictal::short_reliability_cutoff(p, -1).ok());
}
