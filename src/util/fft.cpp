#include "util/fft.hpp"

#include <cmath>
#include <numbers>

namespace frictal::util {

namespace {

using cd = std::complex<double>;

void fft_pow2(std::vector<cd>& a, bool inverse) {
  const std::size_t n = a.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const double ang = 2 * std::numbers::pi / double(len) * (inverse ? 1 : -1);
    // Twiddles computed directly (no recurrence) to keep the error at O(eps log n).
    std::vector<cd> w(len / 2);
    for (std::size_t k = 0; k < len / 2; ++k) w[k] = cd(std::cos(ang * double(k)), std::sin(ang * double(k)));
    for (std::size_t i = 0; i < n; i += len)
      for (std::size_t k = 0; k < len / 2; ++k) {
        cd u = a[i + k], v = a[i + k + len / 2] * w[k];
        a[i + k] = u + v;
        a[i + k + len / 2] = u - v;
      }
  }
}

}  // namespace

void dft(std::vector<cd>& a, bool inverse) {
  const std::size_t n = a.size();
  if (n <= 1) return;
  if ((n & (n - 1)) == 0) {
    fft_pow2(a, inverse);
    return;
  }
  // Bluestein: x_n w_n convolved with conj chirp, w_n = exp(-i pi n^2 / N).
  std::size_t m = 1;
  while (m < 2 * n - 1) m <<= 1;
  const double s = inverse ? 1 : -1;
  std::vector<cd> w(n);
  for (std::size_t k = 0; k < n; ++k) {
    // n^2 mod 2N keeps the angle small and exact.
    unsigned long long kk = (unsigned long long)k * k % (2ull * n);
    double ang = std::numbers::pi * double(kk) / double(n) * s;
    w[k] = cd(std::cos(ang), std::sin(ang));
  }
  std::vector<cd> A(m, 0.0), B(m, 0.0);
  for (std::size_t k = 0; k < n; ++k) A[k] = a[k] * w[k];
  B[0] = std::conj(w[0]);
  for (std::size_t k = 1; k < n; ++k) B[k] = B[m - k] = std::conj(w[k]);
  fft_pow2(A, false);
  fft_pow2(B, false);
  for (std::size_t k = 0; k < m; ++k) A[k] *= B[k];
  fft_pow2(A, true);
  for (std::size_t k = 0; k < n; ++k) a[k] = A[k] / double(m) * w[k];
}

}  // namespace frictal::util
