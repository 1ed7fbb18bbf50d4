// Surface generators: Koch (Sec. III), Weierstrass-Mandelbrot (Eq. 14-17), sawtooth, sine,
// random self-affine (midpoint displacement), periodic self-affine by Fourier filtering.
#include "frictal/generators.hpp"

#include <fmt/core.h>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "frictal/stats.hpp"
#include "util/fft.hpp"
#include "util/random.hpp"

namespace frictal {
namespace {

constexpr double kPi = std::numbers::pi;

// Number of whole periods of `wavelength` in `length`, or an error naming the parameters.
Result<long> whole_periods(double length, double wavelength, const char* what) {
  if (!(wavelength > 0) || !std::isfinite(wavelength))
    return make_error(fmt::format("{}: wavelength must be a positive length in metres, got {}", what, wavelength));
  if (!(length > 0) || !std::isfinite(length))
    return make_error(fmt::format("{}: length must be a positive length in metres, got {}", what, length));
  double n = length / wavelength;
  double r = std::round(n);
  if (r < 1 || std::abs(n - r) > 1e-9 * std::max(1.0, r))
    return make_error(fmt::format("{}: length ({} m) must be a whole number of wavelengths ({} m); ratio is {}", what,
                                  length, wavelength, n));
  if (r > 1e7) return make_error(fmt::format("{}: {} periods is too many (limit 1e7)", what, r));
  return static_cast<long>(r);
}

}  // namespace

KochParams default_koch_params() { return KochParams{}; }
WmParams default_wm_params() { return WmParams{}; }

Result<Curve> koch_curve(const KochParams& p) {
  if (p.iterations < 0 || p.iterations > 10)
    return make_error(fmt::format("koch: iterations must be in 0..10, got {}", p.iterations));
  if (!(p.alpha > 0) || !(p.alpha <= kPi / 3 + 1e-12))
    return make_error(fmt::format("koch: alpha must be in (0, 60] degrees, got {} degrees", p.alpha * 180 / kPi));
  auto periods = whole_periods(p.length, p.wavelength, "koch");
  if (!periods) return periods.error();
  const double per_period_points = 2.0 * std::pow(4.0, p.iterations) * static_cast<double>(*periods) + 1;
  if (per_period_points > 5e7)
    return make_error(fmt::format("koch: {} iterations over {} periods would need {:.3g} points (limit 5e7)",
                                  p.iterations, *periods, per_period_points));
  // One period, then repeated.
  std::vector<double> x{0.0, p.wavelength / 2, p.wavelength};
  std::vector<double> z{0.0, p.wavelength / 2 * std::tan(p.alpha), 0.0};
  const double t = std::tan(p.alpha);
  for (int it = 0; it < p.iterations; ++it) {
    std::vector<double> nx, nz;
    nx.reserve(4 * x.size());
    nz.reserve(4 * x.size());
    for (std::size_t i = 0; i + 1 < x.size(); ++i) {
      const double dx = x[i + 1] - x[i], dz = z[i + 1] - z[i];
      const double ax = x[i] + dx / 3, az = z[i] + dz / 3;
      const double bx = x[i] + 2 * dx / 3, bz = z[i] + 2 * dz / 3;
      // Apex over the middle third, on the outward (left of the walking direction) side:
      // left normal of (dx, dz) is (-dz, dx); its length is |d|, the middle third is |d|/3,
      // so the apex is at half of it times tan(alpha) along the unit normal.
      const double h = t / 6.0;  // (|d|/3)/2 * tan(alpha) / |d|
      const double cx = (ax + bx) / 2 - h * dz, cz = (az + bz) / 2 + h * dx;
      nx.insert(nx.end(), {x[i], ax, cx, bx});
      nz.insert(nz.end(), {z[i], az, cz, bz});
    }
    nx.push_back(x.back());
    nz.push_back(z.back());
    x.swap(nx);
    z.swap(nz);
  }
  Curve c;
  const std::size_t m = x.size() - 1;  // points per period without the closing one
  c.x.reserve(m * static_cast<std::size_t>(*periods) + 1);
  c.z.reserve(c.x.capacity());
  for (long k = 0; k < *periods; ++k) {
    const double off = static_cast<double>(k) * p.wavelength;
    for (std::size_t i = 0; i < m; ++i) {
      c.x.push_back(off + x[i]);
      c.z.push_back(z[i]);
    }
  }
  c.x.push_back(static_cast<double>(*periods) * p.wavelength);
  c.z.push_back(0.0);
  return c;
}

Result<Profile> koch_profile(const KochParams& p) {
  auto c = koch_curve(p);
  if (!c) return c.error();
  auto env = upper_envelope(*c);
  if (!env) return env.error();
  env->period = p.wavelength;
  return env;
}

Result<std::size_t> wm_point_count(const WmParams& p) {
  if (!(p.dimension >= 1.0 && p.dimension <= 2.0))
    return make_error(fmt::format("wm: dimension D must be in [1, 2], got {}", p.dimension));
  if (!(p.gamma > 1.0) || !std::isfinite(p.gamma))
    return make_error(fmt::format("wm: gamma must be > 1, got {}", p.gamma));
  if (p.n_max < 0 || p.n_max > 60) return make_error(fmt::format("wm: n_max must be in 0..60, got {}", p.n_max));
  if (!(p.longest_wavelength > 0) || !std::isfinite(p.longest_wavelength))
    return make_error(fmt::format("wm: longest wavelength L must be positive (m), got {}", p.longest_wavelength));
  if (!(p.length > 0) || !std::isfinite(p.length))
    return make_error(fmt::format("wm: length L_b must be positive (m), got {}", p.length));
  double dx = p.spacing;
  if (!(dx > 0)) {
    // Eq. 16: L_s = L / gamma^n_max; dx = L_s / 10; n_max = 0 uses the n_max = 1 spacing.
    const int n = std::max(p.n_max, 1);
    dx = p.longest_wavelength / std::pow(p.gamma, n) / 10.0;
  }
  const double count = std::floor(p.length / dx * (1 + 1e-12)) + 1;
  if (!(count >= 2) || count > 2e8)
    return make_error(
        fmt::format("wm: {:.4g} points (length {} m, spacing {} m) is outside 2..2e8", count, p.length, dx));
  return static_cast<std::size_t>(count);
}

Result<Profile> wm_profile(const WmParams& p) {
  auto count = wm_point_count(p);
  if (!count) return count.error();
  const std::size_t n = *count;
  double dx = p.spacing;
  if (!(dx > 0)) dx = p.longest_wavelength / std::pow(p.gamma, std::max(p.n_max, 1)) / 10.0;
  const double k = (p.exponent == WmExponent::Printed) ? 2.0 : 1.0;
  std::vector<double> phase(static_cast<std::size_t>(p.n_max) + 1, 0.0);
  if (p.stochastic) {
    util::Rng rng(p.seed);
    for (auto& ph : phase) ph = 2 * kPi * rng.uniform();
  }
  Profile out;
  out.x.resize(n);
  out.z.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) out.x[i] = dx * static_cast<double>(i);
  for (int m = 0; m <= p.n_max; ++m) {
    const double amp = std::pow(p.gamma, k * (p.dimension - 2.0) * m);
    const double q = 2 * kPi * std::pow(p.gamma, m) / p.longest_wavelength;
    const double c0 = std::cos(phase[static_cast<std::size_t>(m)]);
    const double ph = phase[static_cast<std::size_t>(m)];
    for (std::size_t i = 0; i < n; ++i) out.z[i] += amp * (c0 - std::cos(q * out.x[i] + ph));
  }
  if (p.rms_height > 0) {
    const double rms = profile_stats(out).rms_height;
    if (!(rms > 0))
      return make_error("wm: the generated profile is flat (zero rms); cannot scale it to the requested rms height");
    const double G = p.rms_height / rms;
    for (auto& v : out.z) v *= G;
  }
  return out;
}

Result<Profile> sawtooth_profile(const SawtoothParams& p) {
  if (!(p.rise_angle > 0 && p.rise_angle < kPi / 2))
    return make_error(fmt::format("sawtooth: rise angle must be in (0, 90) degrees, got {}", p.rise_angle * 180 / kPi));
  if (!(p.rise_fraction > 0 && p.rise_fraction < 1))
    return make_error(fmt::format("sawtooth: rise fraction must be in (0, 1), got {}", p.rise_fraction));
  auto periods = whole_periods(p.length, p.wavelength, "sawtooth");
  if (!periods) return periods.error();
  Profile out;
  const double top = p.rise_fraction * p.wavelength * std::tan(p.rise_angle);
  for (long k = 0; k < *periods; ++k) {
    const double off = static_cast<double>(k) * p.wavelength;
    out.x.push_back(off);
    out.z.push_back(0.0);
    out.x.push_back(off + p.rise_fraction * p.wavelength);
    out.z.push_back(top);
  }
  out.x.push_back(static_cast<double>(*periods) * p.wavelength);
  out.z.push_back(0.0);
  out.period = p.wavelength;
  return out;
}

Result<Profile> sine_profile(const SineParams& p) {
  if (!std::isfinite(p.amplitude) || !(p.amplitude >= 0))
    return make_error(fmt::format("sine: amplitude must be a non-negative length (m), got {}", p.amplitude));
  if (p.points_per_wavelength < 4 || p.points_per_wavelength > 10'000'000)
    return make_error(fmt::format("sine: points per wavelength must be in 4..1e7, got {}", p.points_per_wavelength));
  auto periods = whole_periods(p.length, p.wavelength, "sine");
  if (!periods) return periods.error();
  const std::size_t m = static_cast<std::size_t>(p.points_per_wavelength);
  const std::size_t n = m * static_cast<std::size_t>(*periods) + 1;
  if (n > 2e8) return make_error(fmt::format("sine: {} points is too many (limit 2e8)", n));
  Profile out;
  out.x.resize(n);
  out.z.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = i % m;  // phase index: exact periodicity
    out.x[i] = p.wavelength * (static_cast<double>(i / m) + static_cast<double>(j) / static_cast<double>(m));
    out.z[i] = p.amplitude * std::sin(2 * kPi * static_cast<double>(j) / static_cast<double>(m));
  }
  out.period = p.wavelength;
  return out;
}

Result<Profile> self_affine_profile(const SelfAffineParams& p) {
  if (p.points < 16 || p.points > 500'000'000)
    return make_error(fmt::format("self-affine: points must be in 16..5e8, got {}", p.points));
  if (!(p.length > 0) || !std::isfinite(p.length))
    return make_error(fmt::format("self-affine: length must be positive (m), got {}", p.length));
  if (!(p.hurst > 0 && p.hurst <= 1))
    return make_error(fmt::format("self-affine: Hurst exponent must be in (0, 1], got {}", p.hurst));
  // Random midpoint displacement (Fournier, Fussell & Carpenter 1982) on 2^k + 1 points,
  // then linear resampling onto `points` points: variance of the displacement at level l is
  // proportional to 2^{-2 H l}, giving a profile with Hurst exponent H.
  std::size_t k = 1;
  while ((std::size_t{1} << k) + 1 < p.points) ++k;
  const std::size_t N = (std::size_t{1} << k);
  std::vector<double> h(N + 1, 0.0);
  util::Rng rng(p.seed);
  h[0] = 0.0;
  h[N] = rng.normal();
  // Displacement of the midpoint of an interval of relative length r: sd ~ r^H.
  for (std::size_t step = N; step > 1; step /= 2) {
    const double sd = std::pow(static_cast<double>(step) / static_cast<double>(N), p.hurst);
    for (std::size_t i = step / 2; i < N; i += step)
      h[i] = 0.5 * (h[i - step / 2] + h[i + step / 2]) + sd * rng.normal();
  }
  Profile out;
  out.x.resize(p.points);
  out.z.resize(p.points);
  for (std::size_t i = 0; i < p.points; ++i) {
    const double u = static_cast<double>(i) * static_cast<double>(N) / static_cast<double>(p.points - 1);
    std::size_t j = std::min(static_cast<std::size_t>(u), N - 1);
    const double t = u - static_cast<double>(j);
    out.x[i] = p.length * static_cast<double>(i) / static_cast<double>(p.points - 1);
    out.z[i] = h[j] + t * (h[j + 1] - h[j]);
  }
  const double rms = profile_stats(out).rms_height;
  if (rms > 0 && p.rms_height > 0)
    for (auto& v : out.z) v *= p.rms_height / rms;
  return out;
}

Status validate(const FourierSelfAffineParams& p) {
  const char* what = "fourier";
  if (p.points < 8 || p.points > (std::size_t{1} << 26))
    return make_error(fmt::format("{}: points must be in 8..2^26 (67108864), got {}", what, p.points));
  if (!(p.length > 0) || !std::isfinite(p.length))
    return make_error(fmt::format("{}: length must be a positive length in metres, got {}", what, p.length));
  if (!(p.hurst > 0 && p.hurst <= 1))
    return make_error(fmt::format("{}: hurst (Hurst exponent H) must be in (0, 1], got {}", what, p.hurst));
  if (!(p.rolloff_wavelength > 0) || !std::isfinite(p.rolloff_wavelength))
    return make_error(
        fmt::format("{}: rolloff_wavelength must be a positive length in metres, got {}", what, p.rolloff_wavelength));
  if (!(p.short_cutoff_wavelength > 0) || !std::isfinite(p.short_cutoff_wavelength))
    return make_error(fmt::format("{}: short_cutoff_wavelength must be a positive length in metres, got {}", what,
                                  p.short_cutoff_wavelength));
  if (!(p.rms_height > 0) || !std::isfinite(p.rms_height))
    return make_error(fmt::format("{}: rms_height must be a positive length in metres, got {}", what, p.rms_height));
  if (p.short_cutoff_wavelength > p.rolloff_wavelength)
    return make_error(fmt::format("{}: short_cutoff_wavelength ({} m) must not exceed rolloff_wavelength ({} m)", what,
                                  p.short_cutoff_wavelength, p.rolloff_wavelength));
  if (p.short_cutoff_wavelength > p.length)
    return make_error(fmt::format(
        "{}: short_cutoff_wavelength ({} m) must not exceed length ({} m): no wavenumber would carry height", what,
        p.short_cutoff_wavelength, p.length));
  const double dx = p.length / static_cast<double>(p.points);
  if (!(p.short_cutoff_wavelength > 2 * dx))
    return make_error(
        fmt::format("{}: short_cutoff_wavelength ({} m) must be longer than the Nyquist wavelength 2 length / points "
                    "({} m); raise points or the cutoff (8 samples per cutoff wavelength keep the power law clean)",
                    what, p.short_cutoff_wavelength, 2 * dx));
  return Ok{};
}

Result<Profile> fourier_self_affine_profile(const FourierSelfAffineParams& p) {
  const char* what = "fourier";
  if (Status st = validate(p); !st) return st.error();
  const std::size_t N = p.points;
  // Wavenumber indices: q_k = 2 pi k / L. k_s is the last k with q_k <= q_s (k_s < N / 2 by the
  // Nyquist check, with a relative margin for lengths that are a whole number of cutoffs).
  const double ks_real = p.length / p.short_cutoff_wavelength;
  std::size_t ks = static_cast<std::size_t>(std::floor(ks_real * (1 + 1e-12)));
  ks = std::min(ks, (N - 1) / 2);
  const double kr = p.length / p.rolloff_wavelength;
  std::vector<std::complex<double>> a(N, 0.0);
  util::Rng rng(p.seed);
  for (std::size_t k = 1; k <= ks; ++k) {
    const double kk = static_cast<double>(k);
    const double c = kk < kr ? 1.0 : std::pow(kk / kr, -(1 + 2 * p.hurst));  // C(q_k) / C0
    std::complex<double> z;
    if (p.amplitudes == FourierAmplitudes::Gaussian) {
      const double re = rng.normal(), im = rng.normal();
      z = std::sqrt(c / 2) * std::complex<double>(re, im);
    } else {
      const double phase = 2 * kPi * rng.uniform();
      z = std::sqrt(c) * std::complex<double>(std::cos(phase), std::sin(phase));
    }
    a[k] = z;
    a[N - k] = std::conj(z);
  }
  util::dft(a, true);  // z_j = sum_k a_k exp(+2 pi i j k / N), real by the Hermitian symmetry
  Profile out;
  out.x.resize(N + 1);
  out.z.resize(N + 1);
  for (std::size_t j = 0; j <= N; ++j) {
    out.x[j] = p.length * static_cast<double>(j) / static_cast<double>(N);
    out.z[j] = a[j % N].real();
  }
  out.period = p.length;
  const double rms = profile_stats(out).rms_height;
  if (!(rms > 0))
    return make_error(
        fmt::format("{}: the generated heights are all equal (no wavenumber between 2 pi / length and "
                    "2 pi / short_cutoff_wavelength carries height)",
                    what));
  const double scale = p.rms_height / rms;
  for (auto& v : out.z) v *= scale;
  return out;
}

}  // namespace frictal
