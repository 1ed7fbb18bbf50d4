// Gaussian low-pass filter (ISO 16610-21): analytic transmission of sines, the two convolution
// methods against each other, exact preservation of constants, and input checks.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "analysis/filter_detail.hpp"
#include "frictal/filter.hpp"

namespace {

using frictal::Profile;
constexpr double kPi = std::numbers::pi;

Profile sampled(double length, double dx, double (*f)(double)) {
  Profile p;
  const auto n = std::size_t(std::llround(length / dx)) + 1;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = double(i) * dx;
    p.x.push_back(x);
    p.z.push_back(f(x));
  }
  return p;
}

constexpr double kL1 = 500e-6, kA1 = 1e-6, kL2 = 10e-6, kA2 = 0.5e-6;
double two_sines(double x) { return kA1 * std::sin(2 * kPi * x / kL1) + kA2 * std::sin(2 * kPi * x / kL2); }

}  // namespace

TEST(Filter, AlphaIsHalfTransmissionAtCutoff) {
  // ISO 16610-21: alpha = sqrt(ln 2 / pi), so that a sine of the cutoff wavelength keeps half its amplitude.
  EXPECT_NEAR(frictal::kGaussianFilterAlpha, std::sqrt(std::log(2.0) / kPi), 1e-16);
  EXPECT_NEAR(frictal::gaussian_transmission(1e-4, 1e-4), 0.5, 1e-15);
}

TEST(Filter, TwoSinesFilteredBetweenThemKeepOnlyTheLongOne) {
  // lambda1 = 500 um (kept), lambda2 = 10 um (removed), cutoff 80 um between them.
  const double cutoff = 80e-6;
  const Profile p = sampled(2e-3, 1e-6, two_sines);
  auto f = frictal::gaussian_lowpass(p, cutoff);
  ASSERT_TRUE(f) << f.error().message;
  ASSERT_EQ(f->size(), p.size());
  // Continuous Gaussian: T(lambda) = exp(-pi (alpha lambda_c / lambda)^2).
  const double a = std::sqrt(std::log(2.0) / kPi);
  const double t1 = std::exp(-kPi * std::pow(a * cutoff / kL1, 2));
  ASSERT_GT(t1, 0.98);
  ASSERT_LT(std::exp(-kPi * std::pow(a * cutoff / kL2, 2)), 1e-18);
  double worst = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double x = p.x[i];
    if (x < cutoff || x > p.x.back() - cutoff) continue;  // away from the ends (renormalised weights)
    EXPECT_DOUBLE_EQ(f->x[i], x);
    worst = std::max(worst, std::abs(f->z[i] - t1 * kA1 * std::sin(2 * kPi * x / kL1)));
  }
  EXPECT_LT(worst, 2e-5 * kA1);
}

TEST(Filter, SineAtTheCutoffKeepsHalfItsAmplitude) {
  const double cutoff = 100e-6;
  const Profile p = sampled(3e-3, 0.5e-6, [](double x) { return std::sin(2 * kPi * x / 100e-6); });
  auto f = frictal::gaussian_lowpass(p, cutoff);
  ASSERT_TRUE(f);
  double amp = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.x[i] > 1e-3 && p.x[i] < 2e-3) amp = std::max(amp, std::abs(f->z[i]));
  EXPECT_NEAR(amp, 0.5, 1e-4);
}

TEST(Filter, ConstantsArePreservedUpToTheEndsAndLinesInside) {
  const Profile c = sampled(1e-3, 1e-6, [](double) { return 3e-6; });
  auto f = frictal::gaussian_lowpass(c, 200e-6);
  ASSERT_TRUE(f);
  for (double z : f->z) EXPECT_NEAR(z, 3e-6, 1e-20);
  // A line is reproduced where the (even) kernel fits inside the profile.
  const Profile l = sampled(1e-3, 1e-6, [](double x) { return 0.1 * x; });
  auto g = frictal::gaussian_lowpass(l, 100e-6);
  ASSERT_TRUE(g);
  for (std::size_t i = 100; i + 100 < l.size(); ++i) EXPECT_NEAR(g->z[i], l.z[i], 1e-17);
}

TEST(Filter, DirectSumsAndFftAgree) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n(0, 1e-6);
  std::vector<double> z(3001);
  for (auto& v : z) v = n(rng);
  using frictal::analysis_detail::ConvolutionMethod;
  for (double cutoff : {5e-6, 80e-6, 2e-3, 1.0}) {  // kernel shorter than, comparable to, longer than the profile
    auto d = frictal::analysis_detail::gaussian_smooth(z, 1e-6, cutoff, ConvolutionMethod::Direct);
    auto f = frictal::analysis_detail::gaussian_smooth(z, 1e-6, cutoff, ConvolutionMethod::Fft);
    ASSERT_EQ(d.size(), z.size());
    for (std::size_t i = 0; i < z.size(); ++i) EXPECT_NEAR(d[i], f[i], 1e-18) << cutoff << " " << i;
  }
}

TEST(Filter, NonUniformProfilesAreResampledAndBadInputRefused) {
  Profile p;
  for (int i = 0; i < 200; ++i) {
    const double x = 1e-6 * (i + 0.3 * (i % 2));
    p.x.push_back(x);
    p.z.push_back(2e-6);
  }
  auto f = frictal::gaussian_lowpass(p, 20e-6);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->size(), p.size());
  EXPECT_TRUE(frictal::is_uniform(*f, 1e-9));
  for (double z : f->z) EXPECT_NEAR(z, 2e-6, 1e-18);
  for (double bad : {0.0, -1e-6, std::nan("")}) {
    auto e = frictal::gaussian_lowpass(p, bad);
    ASSERT_FALSE(e);
    EXPECT_NE(e.error().message.find("cutoff"), std::string::npos);
  }
}
