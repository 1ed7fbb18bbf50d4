// Private: discrete Fourier transform of any length (radix-2, Bluestein for other lengths).
#pragma once

#include <complex>
#include <vector>

namespace frictal::util {

/// In place: X_k = sum_n x_n exp(-2 pi i k n / N) (forward) or exp(+...) (inverse, unscaled).
void dft(std::vector<std::complex<double>>& a, bool inverse = false);

}  // namespace frictal::util
