// frictal — surface generators. Every length in metres, every angle in radians. The tables of
// their parameters (names, units, ranges, help) are in frictal/surface_spec.hpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <numbers>

#include "frictal/geometry.hpp"

namespace frictal {

/// Triadic Koch surface K_n (paper Sec. III, Fig. 3). The generator K_0 is a row of isosceles
/// triangles of base `wavelength` and base angle `alpha`, pointing outward (+z, away from the
/// material). Each iteration splits every segment in three equal parts and replaces the middle
/// one by the two sides of an outward isosceles triangle of base angle alpha, so the steepest
/// edge of K_n is (n+1) alpha. For alpha above 45 (K1), 30 (K2), 22.5 (K3) degrees the curve
/// folds over, hence the result is a Curve; take upper_envelope() to get a profile.
struct KochParams {
  int iterations = 0;                         ///< n >= 0 (unitless); n <= 10 to bound memory
  double alpha = 5 * std::numbers::pi / 180;  ///< base angle of the triangles, in (0, pi/3], 5 deg (unit: rad)
  double wavelength = 0.01;                   ///< base of the K_0 triangles, lambda (unit: m)
  double length = 0.2;                        ///< block length L_b, a whole number of wavelengths (unit: m)
};
KochParams default_koch_params();
Result<Curve> koch_curve(const KochParams& p);
/// The upper envelope of koch_curve(p), marked periodic with period `wavelength`.
Result<Profile> koch_profile(const KochParams& p);

/// Which exponent Eq. 14 uses: the paper's printed gamma^{2(D-2)n} or the common profile form
/// gamma^{(D-2)n} (e.g. Yan & Komvopoulos 1998 for profiles).
enum class WmExponent { Printed, Common };

/// Ausloos-Berman Weierstrass-Mandelbrot profile (Eq. 14-17):
///   z(x) = G sum_{n=0}^{n_max} gamma^{k(D-2)n} [cos phi_n - cos(2 pi gamma^n x / L + phi_n)]
/// with k = 2 (Printed) or 1 (Common), phi_n uniform in [0, 2 pi) from `seed` (stochastic) or
/// phi_n = 0 (deterministic, Eq. 17). Sampled with dx = L_s / 10, L_s = L / gamma^{n_max}
/// (Eq. 16), n_max = 0 using the n_max = 1 spacing. G is chosen so that the rms height about
/// the mean of the piecewise-linear profile equals `rms_height`.
struct WmParams {
  double dimension = 1.5;                     ///< D in [1, 2] (unitless)
  double gamma = 1.5;                         ///< wavelength density gamma > 1 (unitless)
  int n_max = 10;                             ///< highest wavelength index, 0..60 (unitless)
  double longest_wavelength = 1e-6;           ///< L (unit: m)
  double length = 20e-6;                      ///< profile length L_b (unit: m)
  double rms_height = 1e-9;                   ///< target rms height about the mean; <= 0 keeps G = 1 m (unit: m)
  bool stochastic = true;                     ///< random phases (Eq. 14) or zero phases (Eq. 17)
  std::uint64_t seed = 1;                     ///< seed of the phases (unitless)
  WmExponent exponent = WmExponent::Printed;  ///< form of the exponent of Eq. 14
  double spacing = 0.0;                       ///< override dx if > 0 (unit: m)
};
WmParams default_wm_params();
Result<Profile> wm_profile(const WmParams& p);
/// Number of points wm_profile(p) would produce (for checking sizes before allocating).
Result<std::size_t> wm_point_count(const WmParams& p);

/// Asymmetric sawtooth: each period rises at angle `rise_angle` over `rise_fraction` of the
/// wavelength, then falls back over the rest. Periodic.
struct SawtoothParams {
  double rise_angle =
      20 * std::numbers::pi / 180;  ///< slope angle of the rising flank, in (0, pi/2), 20 deg (unit: rad)
  double rise_fraction = 0.5;       ///< fraction of the wavelength that rises, in (0, 1) (unitless)
  double wavelength = 0.01;         ///< (unit: m)
  double length = 0.2;              ///< a whole number of wavelengths (unit: m)
};
Result<Profile> sawtooth_profile(const SawtoothParams& p);

/// Sinusoid z = A sin(2 pi x / lambda), sampled with `points_per_wavelength` points. Periodic.
struct SineParams {
  double amplitude = 1e-3;         ///< A (unit: m)
  double wavelength = 0.01;        ///< lambda (unit: m)
  double length = 0.2;             ///< a whole number of wavelengths (unit: m)
  int points_per_wavelength = 64;  ///< >= 4 (unitless)
};
Result<Profile> sine_profile(const SineParams& p);

/// Random self-affine profile by random midpoint displacement (Fournier, Fussell & Carpenter
/// 1982), a real-space construction whose spectrum is only approximately ~ q^{-(1+2H)} (it is
/// not periodic and not spectral synthesis; see fourier_self_affine_profile for that), resampled
/// onto `points` uniform points over `length`, rms height `rms_height` (<= 0: unscaled). Used
/// for large benchmarks and tests.
struct SelfAffineParams {
  std::size_t points = 1024;  ///< number of points >= 16 (unitless)
  double length = 1e-3;       ///< (unit: m)
  double hurst = 0.8;         ///< Hurst exponent H in (0, 1] (unitless)
  double rms_height = 1e-6;   ///< rms height about the mean; <= 0: unscaled (unit: m)
  std::uint64_t seed = 1;     ///< seed of the random heights (unitless)
};
Result<Profile> self_affine_profile(const SelfAffineParams& p);

/// How fourier_self_affine_profile draws the Fourier amplitudes.
enum class FourierAmplitudes {
  Gaussian,  ///< complex Gaussian coefficients (filtered white noise): a Gaussian random process
             ///< whose periodogram follows the target spectrum on average, exponentially distributed
             ///< about it at each wavenumber
  Fixed      ///< |coefficient| = sqrt of the target, only the phases random: the periodogram of
             ///< every realisation is the target spectrum exactly
};

/// Periodic random self-affine profile by Fourier filtering, the way contact mechanics makes
/// rough surfaces (Hu & Tonder 1992; e.g. SurfaceTopography's fourier_synthesis, Tamaas's
/// SurfaceGeneratorFilter). With q_k = 2 pi k / L (k = 1 .. N/2 - 1), q_r = 2 pi / rolloff_wavelength
/// and q_s = 2 pi / short_cutoff_wavelength, the target power spectrum is
///   C(q) = C0                          for q < q_r   (rolloff: flat),
///   C(q) = C0 (q / q_r)^{-(1 + 2H)}    for q_r <= q <= q_s,
///   C(q) = 0                           for q > q_s   (and at q = 0: zero mean),
/// in the convention of power_spectrum (analysis.hpp): C(q_k) = L |Z_k|^2 for the discrete Fourier
/// coefficients Z_k of the N samples z_j = sum_k Z_k exp(i q_k x_j). The coefficients are drawn for
/// k = 1, 2, ... in order from `seed` (Gaussian: real and imaginary parts normal with variance
/// C/(2L); Fixed: modulus sqrt(C/L), phase uniform in [0, 2 pi)); the samples come from one inverse
/// DFT, and C0 is fixed by scaling the profile so that the rms height about the mean of the
/// piecewise-linear profile (profile_stats) is exactly `rms_height` — for Gaussian amplitudes this
/// scale factor is random, common to all wavenumbers. The piecewise-linear interpolation between
/// samples multiplies the continuous spectrum by sinc^4(q dx / 2) (>= 0.90 up to a quarter of the
/// Nyquist wavenumber); keep short_cutoff_wavelength >= 8 dx for a clean power law.
/// Output: points + 1 uniform samples x_j = j L / points, j = 0 .. points (the last repeats the
/// first), period = length.
struct FourierSelfAffineParams {
  std::size_t points = 2048;  ///< samples per period N, 8 .. 2^26 (unitless)
  double length = 0.2;        ///< period L of the profile (unit: m)
  double hurst = 0.8;         ///< Hurst exponent H in (0, 1] (unitless)
  /// 2 pi / q_r: C(q) is flat at longer wavelengths; >= length: no flat part (unit: m)
  double rolloff_wavelength = 0.01;
  /// 2 pi / q_s: C(q) = 0 at shorter wavelengths; > 2 L / points, <= rolloff_wavelength and
  /// <= length (unit: m)
  double short_cutoff_wavelength = 0.001;
  double rms_height = 1e-5;  ///< rms height about the mean, > 0, exact (unit: m)
  /// Gaussian (a random process) or Fixed (the exact spectrum, random phases)
  FourierAmplitudes amplitudes = FourierAmplitudes::Gaussian;
  std::uint64_t seed = 1;  ///< seed of the amplitudes and phases (unitless)
};
/// Checks the parameters (ranges and the order rolloff >= cutoff > Nyquist wavelength) without
/// generating; the error names the parameter.
Status validate(const FourierSelfAffineParams& p);
Result<Profile> fourier_self_affine_profile(const FourierSelfAffineParams& p);

}  // namespace frictal
