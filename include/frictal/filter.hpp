// frictal — low-pass filtering of profiles: the Gaussian profile filter of ISO 16610-21, used to
// ask how the signature depends on the resolution of a measured surface (the measured analogue
// of the paper's Fig. 14: theta_max against the shortest wavelength kept). Definitions:
// docs/report.md ("Resolution").
#pragma once

#include "frictal/geometry.hpp"

namespace frictal {

/// alpha of the ISO 16610-21 Gaussian weighting function, sqrt(ln 2 / pi) (unitless): the
/// filter transmits 50 % of a sine whose wavelength equals the cutoff.
inline constexpr double kGaussianFilterAlpha = 0.46971863934982566;

/// Amplitude transmission of the Gaussian low-pass filter for a sine of wavelength `wavelength`
/// (unit: m) and cutoff `cutoff` (unit: m): exp(-pi (alpha cutoff / wavelength)^2) (unitless).
double gaussian_transmission(double wavelength, double cutoff);

/// Gaussian low-pass (ISO 16610-21 mean line) with cutoff wavelength `cutoff` (unit: m):
///   w(x) = exp(-pi (x / (alpha cutoff))^2) / (alpha cutoff),  truncated at |x| <= cutoff,
/// z_f(x_i) = sum_j w(x_i - x_j) z_j / sum_j w(x_i - x_j) over the samples inside the profile:
/// near the ends the weights are renormalised (no padding, no end ringing). Uniformly spaced
/// profiles are filtered as sampled; others are first resampled linearly on as many equally
/// spaced points. The result has the same abscissae (or the resampled ones) and keeps `period`
/// only if it is unset (a periodic profile is filtered as one non-periodic stretch).
/// Errors: cutoff not finite or <= 0, an invalid profile. Direct sums when short, FFT otherwise
/// (the two agree to rounding; tested).
Result<Profile> gaussian_lowpass(const Profile& p, double cutoff);

}  // namespace frictal
