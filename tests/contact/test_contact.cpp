// Elastic normal contact (frictal/contact.hpp) against analytic solutions: Hertz's sphere (maps)
// and cylinder (profiles, plane strain) on a flat, Westergaard's and Johnson's wavy surface
// (partial and full contact), the hardness cap, and the errors and warnings of bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>
#include <vector>

#include "contact/kernel.hpp"
#include "frictal/contact.hpp"

using namespace frictal;

namespace {

constexpr double kPi = std::numbers::pi;

bool has_warning(const ContactResult& r, const std::string& code) {
  return std::any_of(r.warnings.begin(), r.warnings.end(), [&](const Warning& w) { return w.code == code; });
}

/// A paraboloid z = -r^2 / (2 R) on an n x n grid, centred on node (n/2, n/2).
Map sphere(std::size_t n, double dx, double R) {
  Map m;
  m.nx = m.ny = n;
  m.dx = m.dy = dx;
  m.heights.resize(n * n);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      const double x = (double(i) - double(n / 2)) * dx, y = (double(j) - double(n / 2)) * dx;
      m.heights[j * n + i] = -(x * x + y * y) / (2 * R);
    }
  return m;
}

/// A parabolic cylinder z = -x^2 / (2 R) on n points, centred on point n/2.
Profile cylinder(std::size_t n, double dx, double R) {
  Profile p;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = (double(i) - double(n / 2)) * dx;
    p.x.push_back(x);
    p.z.push_back(-x * x / (2 * R));
  }
  return p;
}

/// One period of z = amplitude cos(2 pi x / wavelength) on n points.
Profile wave(std::size_t n, double wavelength, double amplitude) {
  Profile p;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = double(i) * wavelength / double(n);
    p.x.push_back(x);
    p.z.push_back(amplitude * std::cos(2 * kPi * x / wavelength));
  }
  p.period = wavelength;
  return p;
}

}  // namespace

TEST(ContactModulus, OneBodyAndTwo) {
  EXPECT_NEAR(*contact_modulus({200e9, 0.3}), 200e9 / (1 - 0.09), 1e-3);
  // Two equal bodies: half the one body's E*.
  EXPECT_NEAR(*contact_modulus({70e9, 0.25}, {70e9, 0.25}), 0.5 * 70e9 / (1 - 0.0625), 1e-3);
  // Steel on a rubber: the rubber's E* (the steel is nearly rigid against it).
  EXPECT_NEAR(*contact_modulus({210e9, 0.3}, {10e6, 0.5}) / (10e6 / 0.75), 1.0, 1e-4);
}

TEST(ContactModulus, BadMaterialsNameTheParameter) {
  for (const ElasticMaterial m : {ElasticMaterial{0, 0.3}, ElasticMaterial{-1e9, 0.3}, ElasticMaterial{NAN, 0.3}}) {
    auto r = contact_modulus(m);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("Young's modulus"), std::string::npos) << r.error().message;
  }
  for (const double nu : {-1.0, 0.51, 0.7, double(NAN)}) {
    auto r = contact_modulus({1e9, nu});
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("Poisson's ratio"), std::string::npos) << r.error().message;
  }
  EXPECT_TRUE(contact_modulus({1e9, 0.5}));
  auto second = contact_modulus({1e9, 0.3}, {1e9, 0.6});
  ASSERT_FALSE(second);
  EXPECT_NE(second.error().message.find("second body"), std::string::npos);
}

// Hertz, sphere on a flat: a = (3 F R / (4 E*))^(1/3), p0 = 3 F / (2 pi a^2), approach a^2 / R,
// stiffness dF/d(delta) = 2 E* a. The contact radius is 40 grid spacings on a 200 x 200 map (not
// periodic: padded to 400 x 400).
TEST(Contact, HertzSphereOnAFlat) {
  const double Es = 1e9, R = 0.01, dx = 1e-6, a_target = 40 * dx;
  const double F = 4 * Es * a_target * a_target * a_target / (3 * R);
  ContactOptions o;
  o.contact_modulus = Es;
  const Map m = sphere(200, dx, R);
  auto r = solve_contact(m, {ContactLoadKind::Force, F}, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->converged);
  const double a = std::cbrt(3 * F * R / (4 * Es));
  const double p0 = 3 * F / (2 * kPi * a * a);
  const double a_num = std::sqrt(r->contact_area / kPi);
  EXPECT_NEAR(a_num / a, 1.0, 0.01) << "contact radius " << a_num << " m, Hertz " << a << " m";
  EXPECT_NEAR(r->max_pressure / p0, 1.0, 0.01) << "peak pressure " << r->max_pressure << " Pa, Hertz " << p0;
  EXPECT_NEAR(r->approach / (a * a / R), 1.0, 0.01) << "approach " << r->approach;
  EXPECT_NEAR(r->stiffness / (2 * Es * a), 1.0, 0.02) << "stiffness " << r->stiffness;
  EXPECT_NEAR(r->force, F, 1e-12 * F);
  EXPECT_NEAR(r->nominal_pressure, F / (200 * 200 * dx * dx), 1e-9 * F / (200 * 200 * dx * dx));
  EXPECT_FALSE(has_warning(*r, "contact-at-edge"));
  EXPECT_FALSE(has_warning(*r, "small-slope"));
  // The gap closes in the contact and opens outside it as Hertz's: at r = 2a,
  // gap = (a^2 / (pi R)) [(2 - r^2/a^2) asin(a/r) + sqrt(r^2/a^2 - 1)] - ... (Johnson eq. 3.42b):
  // uz = (a^2/(2R)) [(2 - r^2/a^2) asin(a/r) + (r/a) sqrt(1 - a^2/r^2)] / (pi/2), gap = r^2/(2R) - delta + uz.
  const std::size_t n = 200, i = n / 2 + 80, j = n / 2;
  const double rr = 80 * dx;
  const double uz =
      (a * a / (kPi * R)) * ((2 - rr * rr / (a * a)) * std::asin(a / rr) + (rr / a) * std::sqrt(1 - a * a / (rr * rr)));
  const double gap = rr * rr / (2 * R) - a * a / R + uz;
  EXPECT_NEAR(r->gap[j * n + i] / gap, 1.0, 0.02) << "gap at r = 2a";
  EXPECT_EQ(r->pressure[j * n + i], 0.0);
}

// Hertz, cylinder on a flat in plane strain: a = sqrt(4 F' R / (pi E*)), p0 = 2 F' / (pi a); the
// half-width is 500 spacings of a 4096-point profile.
TEST(Contact, HertzCylinderPlaneStrain) {
  const double Es = *contact_modulus({2e9, 0.35}), R = 0.02, dx = 1e-6, a_target = 500 * dx;
  const double Fp = kPi * Es * a_target * a_target / (4 * R);
  ContactOptions o;
  o.contact_modulus = Es;
  auto r = solve_contact(cylinder(4096, dx, R), {ContactLoadKind::Force, Fp}, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->converged);
  const double a = std::sqrt(4 * Fp * R / (kPi * Es));
  const double p0 = 2 * Fp / (kPi * a);
  EXPECT_NEAR(r->contact_length / 2 / a, 1.0, 0.01) << "half-width " << r->contact_length / 2;
  EXPECT_NEAR(r->max_pressure / p0, 1.0, 0.01) << "peak pressure " << r->max_pressure << " Pa, Hertz " << p0;
  EXPECT_TRUE(std::isnan(r->approach));  // the half-plane has no reference for it
  EXPECT_TRUE(std::isnan(r->stiffness));
  EXPECT_TRUE(std::isnan(r->contact_area));
}

// Johnson's wavy surface z = D cos(2 pi x / L) in plane strain: full contact from the nominal
// pressure p* = pi E* D / L on, where p(x) = pbar + p* cos(2 pi x / L) and the gap is zero
// everywhere; below it (Westergaard) the contact half-width a has pbar = p* sin^2(pi a / L) and the
// peak pressure is 2 sqrt(pbar p*).
TEST(Contact, WavySurfaceFullAndPartialContact) {
  const double Es = 1e9, L = 1e-3, D = 1e-6;
  const double pstar = kPi * Es * D / L;
  ContactOptions o;
  o.contact_modulus = Es;
  const std::size_t n = 1024;
  const Profile w = wave(n, L, D);
  auto full = solve_contact(w, {ContactLoadKind::Pressure, 2 * pstar}, o);
  ASSERT_TRUE(full) << full.error().message;
  EXPECT_DOUBLE_EQ(full->contact_fraction, 1.0);
  EXPECT_TRUE(has_warning(*full, "contact-full"));
  EXPECT_NEAR(full->mean_separation, 0.0, 1e-6 * D);
  double worst = 0;
  for (std::size_t i = 0; i < n; ++i)
    worst =
        std::max(worst, std::abs(full->pressure[i] - (2 * pstar + pstar * std::cos(2 * kPi * double(i) / double(n)))));
  EXPECT_LT(worst, 1e-6 * pstar);
  EXPECT_TRUE(std::isinf(full->stiffness));

  auto part = solve_contact(w, {ContactLoadKind::Pressure, 0.5 * pstar}, o);
  ASSERT_TRUE(part) << part.error().message;
  EXPECT_TRUE(part->converged);
  EXPECT_FALSE(has_warning(*part, "contact-full"));
  const double fraction = 2 / kPi * std::asin(std::sqrt(0.5));  // 2a / L
  EXPECT_NEAR(part->contact_fraction, fraction, 0.01 * fraction);
  EXPECT_NEAR(part->max_pressure / (2 * std::sqrt(0.5 * pstar * pstar)), 1.0, 0.01);
  EXPECT_GT(part->mean_separation, 0.0);
  EXPECT_LT(part->mean_separation, D);
  EXPECT_GT(part->stiffness, 0.0);
}

// A load curve starts each load from the previous one; its numbers are those of separate solves.
TEST(Contact, CurveEqualsSeparateSolves) {
  const double Es = 1e9, R = 0.01, dx = 1e-6;
  ContactOptions o;
  o.contact_modulus = Es;
  o.periodic = true;
  const Map m = sphere(64, dx, R);
  std::vector<ContactLoad> loads;
  for (double p : {2e5, 1e6, 5e6}) loads.push_back({ContactLoadKind::Pressure, p});
  auto curve = solve_contact_curve(m, loads, o);
  ASSERT_TRUE(curve) << curve.error().message;
  ASSERT_EQ(curve->size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    auto one = solve_contact(m, loads[k], o);
    ASSERT_TRUE(one);
    EXPECT_NEAR((*curve)[k].contact_fraction, one->contact_fraction, 1e-12);
    EXPECT_NEAR((*curve)[k].max_pressure / one->max_pressure, 1.0, 1e-5);
    EXPECT_NEAR((*curve)[k].mean_separation / one->mean_separation, 1.0, 1e-5);
  }
  EXPECT_LT((*curve)[0].contact_fraction, (*curve)[1].contact_fraction);
  EXPECT_LT((*curve)[1].contact_fraction, (*curve)[2].contact_fraction);
  EXPECT_GT((*curve)[0].mean_separation, (*curve)[2].mean_separation);
}

// The hardness cap: no pressure above H, so the contact area is at least F / H; for H far below
// Hertz's peak pressure nearly all the load is carried at H (the rigid-plastic limit, area F / H).
TEST(Contact, HardnessCapsThePressure) {
  const double Es = 1e9, R = 0.01, dx = 1e-6, a_target = 20 * dx;
  const double F = 4 * Es * a_target * a_target * a_target / (3 * R);
  const double p0 = 3 * F / (2 * kPi * a_target * a_target);
  ContactOptions o;
  o.contact_modulus = Es;
  o.hardness = p0 / 10;
  auto r = solve_contact(sphere(160, dx, R), {ContactLoadKind::Force, F}, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->converged);
  EXPECT_LE(r->max_pressure, o.hardness * (1 + 1e-12));
  EXPECT_NEAR(r->max_pressure, o.hardness, 1e-9 * o.hardness);
  EXPECT_GT(r->plastic_fraction, 0.0);
  EXPECT_GE(r->contact_area, F / o.hardness * (1 - 1e-9));
  EXPECT_LT(r->contact_area, 1.15 * F / o.hardness);
  double total = 0;
  for (double p : r->pressure) total += p * dx * dx;
  EXPECT_NEAR(total / F, 1.0, 1e-9);
}

TEST(Contact, BadLoadsAndWarnings) {
  ContactOptions o;
  o.contact_modulus = 1e9;
  const Map m = sphere(32, 1e-6, 0.01);
  for (const double v : {0.0, -1.0, double(NAN), double(INFINITY)}) {
    auto r = solve_contact(m, {ContactLoadKind::Force, v}, o);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find("load"), std::string::npos) << r.error().message;
  }
  ContactOptions bad = o;
  bad.contact_modulus = -1;
  EXPECT_FALSE(solve_contact(m, {ContactLoadKind::Pressure, 1e6}, bad));
  ContactOptions soft = o;
  soft.hardness = 1e6;
  auto beyond = solve_contact(m, {ContactLoadKind::Pressure, 2e6}, soft);
  ASSERT_FALSE(beyond);
  EXPECT_NE(beyond.error().message.find("hardness"), std::string::npos);
  // Slopes of 2 pi D / L / sqrt(2) = 0.44 rms: the small-slope warning.
  auto steep = solve_contact(wave(128, 1e-4, 1e-5), {ContactLoadKind::Pressure, 1e6}, o);
  ASSERT_TRUE(steep);
  EXPECT_TRUE(has_warning(*steep, "small-slope"));
  EXPECT_NEAR(steep->rms_slope, 2 * kPi * 1e-5 / 1e-4 / std::sqrt(2.0), 0.01);
  Profile uneven = wave(64, 1e-3, 1e-6);
  uneven.x[10] += 1e-6;
  auto not_uniform = solve_contact(uneven, {ContactLoadKind::Pressure, 1e6}, o);
  ASSERT_FALSE(not_uniform);
  EXPECT_NE(not_uniform.error().message.find("equally spaced"), std::string::npos);
}

// Two surfaces as one: the upper face turned over about the y axis adds its mirrored heights; in
// place it is subtracted (the gap between the faces); grids must match.
TEST(Contact, CompositeTopography) {
  Map lower, upper;
  lower.nx = upper.nx = 3;
  lower.ny = upper.ny = 2;
  lower.dx = upper.dx = lower.dy = upper.dy = 1e-6;
  lower.heights = {1, 2, 3, 4, 5, 6};
  upper.heights = {10, 20, 30, 40, 50, 60};
  auto turned = composite_topography(lower, upper, true);
  ASSERT_TRUE(turned);
  EXPECT_EQ(turned->heights, (std::vector<double>{31, 22, 13, 64, 55, 46}));
  auto in_place = composite_topography(lower, upper, false);
  ASSERT_TRUE(in_place);
  EXPECT_EQ(in_place->heights, (std::vector<double>{-9, -18, -27, -36, -45, -54}));
  upper.dx = 2e-6;
  auto mismatch = composite_topography(lower, upper, true, "a.x3p", "b.x3p");
  ASSERT_FALSE(mismatch);
  EXPECT_NE(mismatch.error().message.find("b.x3p"), std::string::npos);
  Profile a = cylinder(8, 1e-6, 0.01), b = cylinder(8, 1e-6, 0.01);
  for (std::size_t i = 0; i < 8; ++i) b.z[i] = double(i);
  auto p = composite_topography(a, b, true);
  ASSERT_TRUE(p);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_DOUBLE_EQ(p->z[i], a.z[i] + double(7 - i));
}

// A contact that reaches the edge of a non-periodic map is flagged; the same map periodic is not.
// A profile whose points are not equally spaced is resampled, with a warning that says so.
TEST(Contact, EdgeAndResampleWarnings) {
  ContactOptions o;
  o.contact_modulus = 1e9;
  Map flat;
  flat.nx = flat.ny = 16;
  flat.dx = flat.dy = 1e-6;
  flat.heights.assign(256, 0.0);
  flat.heights[0] = 1e-9;  // a corner touches first
  auto edge = solve_contact(flat, {ContactLoadKind::Pressure, 1e3}, o);
  ASSERT_TRUE(edge) << edge.error().message;
  EXPECT_TRUE(has_warning(*edge, "contact-at-edge"));
  o.periodic = true;
  auto periodic = solve_contact(flat, {ContactLoadKind::Pressure, 1e3}, o);
  ASSERT_TRUE(periodic);
  EXPECT_FALSE(has_warning(*periodic, "contact-at-edge"));
  Profile uneven = wave(64, 1e-3, 1e-6);
  uneven.x[10] += 3e-6;
  uneven.period.reset();  // a measured scan: no period
  std::vector<Warning> w;
  auto even = equally_spaced(uneven, "scan.csv", w);
  ASSERT_TRUE(even) << even.error().message;
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].code, "contact-resampled");
  EXPECT_NE(w[0].message.find("scan.csv"), std::string::npos);
  EXPECT_TRUE(is_uniform(*even, 1e-9));
  EXPECT_EQ(even->size(), uneven.size());
}

// A flat surface (rms height 0) on a rigid flat: full contact at once, converged, with the load.
TEST(Contact, FlatSurfaceConverges) {
  ContactOptions o;
  o.contact_modulus = 1e9;
  Map flat;
  flat.nx = flat.ny = 32;
  flat.dx = flat.dy = 1e-6;
  flat.heights.assign(32 * 32, 0.0);
  auto r = solve_contact(flat, {ContactLoadKind::Pressure, 1e6}, o);
  ASSERT_TRUE(r) << r.error().message;
  EXPECT_TRUE(r->converged);
  EXPECT_DOUBLE_EQ(r->contact_fraction, 1.0);
  EXPECT_TRUE(has_warning(*r, "contact-full"));
  // A flat punch: the pressure is least at the centre and grows towards the edges.
  EXPECT_LT(r->pressure[16 * 32 + 16], r->pressure[16 * 32 + 0]);
  EXPECT_NEAR(r->force, 1e6 * 32 * 32 * 1e-12, 1e-9 * r->force);
}

// The padded (non-periodic) operator against the direct sum of the influence coefficients: the
// displacement of a pressure on one cell at offset (x, y) is (1 / (pi E*)) times the integral of
// 1/r over the cell (Johnson, Contact Mechanics, eq. 3.25), here by the corner sum of
// x asinh(y/|x|) + y asinh(x/|y|); in plane strain -(2 / (pi E*)) times the integral of ln|x - s|
// over the cell. The padded transforms are 2N - 1 long (8: 15, 11: 21, 13: 25, 25: 49, 32: 63)
// or longer (100001 points: the next product of 2, 3, 5, 7 above 2N - 1), where a wrap-around
// onto the N points or a row left out of the pruned transform would show at once.
TEST(ContactOperator, PaddedEqualsTheDirectSum) {
  using frictal::contact_detail::ElasticOperator;
  const double E = 2e9;
  const auto rect = [](double x, double y) {
    double f = 0;
    if (x != 0) f += x * std::asinh(y / std::abs(x));
    if (y != 0) f += y * std::asinh(x / std::abs(y));
    return f;
  };
  std::uint64_t state = 12345;
  const auto uniform = [&] {  // a fixed pseudo-random pressure in [0, 1) MPa
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(state >> 11) * 0x1.0p-53 * 1e6;
  };
  for (auto [nx, ny] : {std::pair<std::size_t, std::size_t>{13, 8}, {11, 25}, {32, 13}}) {
    const double dx = 1e-6, dy = 1.5e-6, a = dx / 2, b = dy / 2;
    auto op = ElasticOperator::create(nx, ny, dx, dy, false, E, 1);
    ASSERT_TRUE(op) << op.error().message;
    std::vector<double> p(nx * ny), u(nx * ny);
    for (double& v : p) v = uniform();
    (*op)->apply(p.data(), u.data());
    double worst = 0, scale = 0;
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        double direct = 0;
        for (std::size_t l = 0; l < ny; ++l)
          for (std::size_t k = 0; k < nx; ++k) {
            const double x = (double(i) - double(k)) * dx, y = (double(j) - double(l)) * dy;
            direct += p[l * nx + k] / (kPi * E) *
                      (rect(x + a, y + b) - rect(x - a, y + b) - rect(x + a, y - b) + rect(x - a, y - b));
          }
        worst = std::max(worst, std::abs(u[j * nx + i] - direct));
        scale = std::max(scale, std::abs(direct));
      }
    EXPECT_LT(worst, 1e-12 * scale) << nx << " x " << ny;
  }
  for (std::size_t n : {8, 13, 25, 100001}) {
    const double dx = 1e-7, a = dx / 2;
    auto op = ElasticOperator::create(n, 1, dx, 0, false, E, 1);
    ASSERT_TRUE(op) << op.error().message;
    // A few loaded points (the direct sum of 10^5 points stays cheap), at both ends.
    std::vector<double> p(n, 0.0), u(n);
    const std::vector<std::size_t> loaded = {0, 1, n / 2, n - 2, n - 1};
    for (std::size_t k : loaded) p[k] = uniform();
    (*op)->apply(p.data(), u.data());
    const auto G = [](double t) { return t == 0 ? 0.0 : t * std::log(std::abs(t)) - t; };  // of ln|t|
    double worst = 0, scale = 0;
    for (std::size_t i = 0; i < n; i += (n > 1000 ? 997 : 1)) {
      double direct = 0;
      for (std::size_t k : loaded) {
        const double x = (double(i) - double(k)) * dx;
        // ln|t / dx| rather than ln|t|: the half-plane's displacement is defined up to a
        // constant times the load; the operator takes its reference at one spacing.
        direct += p[k] * -2 / (kPi * E) * (G(x + a) - G(x - a) - dx * std::log(dx));
      }
      worst = std::max(worst, std::abs(u[i] - direct));
      scale = std::max(scale, std::abs(direct));
    }
    EXPECT_LT(worst, 1e-10 * scale) << n << " points";  // rounding of the 2 x 10^5-point transform: ~1e-11
  }
}

// Two threads split the transforms and the solver's passes (from 2^16 points on) and add their
// partial sums in a fixed order: Hertz's sphere on a 256 x 256 map (the contact radius 30
// spacings; padded, 511 -> 512 points a side) holds Hertz's radius and peak pressure as the
// single-threaded solve does, and the two solves agree to the solver's tolerance.
TEST(Contact, TwoThreadsSolveHertzAsOne) {
  const double Es = 1e9, R = 0.01, dx = 1e-6, a = 30 * dx;
  const double F = 4 * Es * a * a * a / (3 * R);
  ContactOptions o;
  o.contact_modulus = Es;
  const Map m = sphere(256, dx, R);
  auto one = solve_contact(m, {ContactLoadKind::Force, F}, o);
  o.threads = 2;
  auto two = solve_contact(m, {ContactLoadKind::Force, F}, o);
  ASSERT_TRUE(one && two);
  ASSERT_TRUE(one->converged && two->converged);
  EXPECT_NEAR(std::sqrt(two->contact_area / kPi) / a, 1.0, 0.015);
  EXPECT_NEAR(two->max_pressure / (3 * F / (2 * kPi * a * a)), 1.0, 0.01);
  EXPECT_EQ(two->contact_area, one->contact_area);
  EXPECT_NEAR(two->max_pressure, one->max_pressure, 1e-6 * one->max_pressure);
  EXPECT_NEAR(two->approach, one->approach, 1e-6 * one->approach);
  EXPECT_NEAR(two->stiffness, one->stiffness, 1e-5 * one->stiffness);
}
