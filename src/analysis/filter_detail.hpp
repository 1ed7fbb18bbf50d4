// Private: the Gaussian smoothing kernel of gaussian_lowpass on uniform samples, by direct sums
// or by FFT (exposed so that tests can compare the two methods).
#pragma once

#include <vector>

namespace frictal::analysis_detail {

enum class ConvolutionMethod { Auto, Direct, Fft };

/// Renormalised Gaussian mean line of uniformly spaced samples z (spacing dx, cutoff, both in m).
std::vector<double> gaussian_smooth(const std::vector<double>& z, double dx, double cutoff,
                                    ConvolutionMethod method = ConvolutionMethod::Auto);

}  // namespace frictal::analysis_detail
