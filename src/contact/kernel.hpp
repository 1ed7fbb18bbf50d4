// Private: the elastic half-space (maps) or half-plane (profiles) as a convolution on FFTW's real
// transforms: u = K p, the surface displacement of the pressure p on a grid of points.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "frictal/result.hpp"

namespace frictal::contact_detail {

/// The operator of one grid. ny = 1 and dy = 0 for a profile. Not copyable; one apply at a time.
class ElasticOperator {
 public:
  /// nx, ny points at spacings dx, dy (unit: m); periodic, or padded to 2 nx (x 2 ny); E* (unit:
  /// Pa); FFTW threads (>= 1). Internal error when FFTW cannot plan (memory).
  static Result<std::unique_ptr<ElasticOperator>> create(std::size_t nx, std::size_t ny, double dx, double dy,
                                                         bool periodic, double contact_modulus, unsigned threads);
  ~ElasticOperator();
  ElasticOperator(const ElasticOperator&) = delete;
  ElasticOperator& operator=(const ElasticOperator&) = delete;

  /// out = K in: the displacement (unit: m, positive into the body) of the pressures `in` (unit:
  /// Pa) at the nx ny points (x fastest). `in` and `out` may be the same array.
  void apply(const double* in, double* out);

 private:
  ElasticOperator() = default;
  std::size_t nx_ = 0, ny_ = 0, Nx_ = 0, Ny_ = 0;
  bool padded_ = false;
  double* real_ = nullptr;      // Nx Ny reals
  void* spec_ = nullptr;        // Ny (Nx/2 + 1) complex numbers
  std::vector<double> kernel_;  // the transfer function, normalised (1 / (Nx Ny) folded in)
  void* forward_ = nullptr;
  void* backward_ = nullptr;
};

}  // namespace frictal::contact_detail
