// Portable deterministic random numbers: the same stream on every platform and standard
// library (std:: distributions are implementation-defined, so we map the raw bits ourselves).
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace frictal::util {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : eng_(seed) {}
  /// Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(eng_() >> 11) * 0x1.0p-53; }
  /// Standard normal (Box-Muller, both values used).
  double normal() {
    if (have_spare_) {
      have_spare_ = false;
      return spare_;
    }
    double u1 = uniform();
    while (u1 <= 0.0) u1 = uniform();
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2 * std::numbers::pi * u2);
    have_spare_ = true;
    return r * std::cos(2 * std::numbers::pi * u2);
  }

 private:
  std::mt19937_64 eng_;
  double spare_ = 0;
  bool have_spare_ = false;
};

}  // namespace frictal::util
