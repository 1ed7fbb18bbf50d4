// Gaussian low-pass profile filter (ISO 16610-21) with renormalised weights at the ends.
#include <fmt/core.h>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "analysis/filter_detail.hpp"
#include "frictal/filter.hpp"
#include "util/fft.hpp"

namespace frictal {

namespace analysis_detail {

std::vector<double> gaussian_smooth(const std::vector<double>& z, double dx, double cutoff, ConvolutionMethod method) {
  const std::size_t n = z.size();
  const double a = kGaussianFilterAlpha * cutoff;
  // Half-width of the truncated kernel in samples (|x| <= cutoff), at most the profile.
  const std::size_t half = std::min<std::size_t>(n - 1, std::size_t(std::floor(cutoff / dx)));
  std::vector<double> w(half + 1);
  for (std::size_t k = 0; k <= half; ++k) {
    const double x = double(k) * dx / a;
    w[k] = std::exp(-std::numbers::pi * x * x);
  }
  if (method == ConvolutionMethod::Auto)
    method = (double(n) * double(2 * half + 1) <= 4e7) ? ConvolutionMethod::Direct : ConvolutionMethod::Fft;
  std::vector<double> out(n);
  if (method == ConvolutionMethod::Direct) {
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t lo = i >= half ? i - half : 0, hi = std::min(n - 1, i + half);
      double num = 0, den = 0;
      for (std::size_t j = lo; j <= hi; ++j) {
        const double wj = w[i > j ? i - j : j - i];
        num += wj * z[j];
        den += wj;
      }
      out[i] = num / den;
    }
    return out;
  }
  // FFT: linear (zero-padded) convolutions of z and of the all-ones mask with the kernel.
  std::size_t m = 1;
  while (m < n + 2 * half + 1) m <<= 1;
  using cd = std::complex<double>;
  std::vector<cd> zz(m), kk(m);
  // real part: z scaled to order 1 (so that rounding is relative to z, not to the mask), imaginary: the mask
  double scale = 0;
  for (double v : z) scale = std::max(scale, std::abs(v));
  if (!(scale > 0) || !std::isfinite(scale)) scale = 1;
  for (std::size_t i = 0; i < n; ++i) zz[i] = cd(z[i] / scale, 1.0);
  for (std::size_t k = 0; k <= half; ++k) {
    kk[k] = w[k];
    if (k > 0) kk[m - k] = w[k];
  }
  util::dft(zz);
  util::dft(kk);
  for (std::size_t i = 0; i < m; ++i) zz[i] *= kk[i];  // the kernel is real and even: its DFT is real
  util::dft(zz, true);
  for (std::size_t i = 0; i < n; ++i) out[i] = scale * zz[i].real() / zz[i].imag();
  return out;
}

}  // namespace analysis_detail

double gaussian_transmission(double wavelength, double cutoff) {
  const double r = kGaussianFilterAlpha * cutoff / wavelength;
  return std::exp(-std::numbers::pi * r * r);
}

Result<Profile> gaussian_lowpass(const Profile& p, double cutoff) {
  if (!(std::isfinite(cutoff) && cutoff > 0))
    return make_error(fmt::format("gaussian_lowpass: cutoff must be a positive length in m, got {}", cutoff));
  if (auto s = validate(p, "gaussian_lowpass profile"); !s) return s.error();
  Profile u;
  if (is_uniform(p, 1e-6)) {
    u.x = p.x;
    u.z = p.z;
  } else {
    auto r = resample(p, p.size());
    if (!r) return r.error();
    u = std::move(*r);
    u.period.reset();
  }
  const double dx = u.length() / double(u.size() - 1);
  u.z = analysis_detail::gaussian_smooth(u.z, dx, cutoff);
  return u;
}

}  // namespace frictal
