// Private: the elastic half-space (maps) or half-plane (profiles) as a convolution on FFTW's real
// transforms: u = K p, the surface displacement of the pressure p on a grid of points.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "frictal/result.hpp"
#include "util/team.hpp"

namespace frictal::contact_detail {

/// The operator of one grid. ny = 1 and dy = 0 for a profile. Not copyable; one apply at a time.
class ElasticOperator {
 public:
  /// nx, ny points at spacings dx, dy (unit: m); periodic, or padded to 2 nx - 1 (x 2 ny - 1)
  /// rounded up to a product of 2, 3, 5, 7; E* (unit: Pa); FFTW threads (>= 1). Internal error when FFTW cannot plan
  /// (memory). Maps from 2^19 transform points take measured plans (planning about 0.2-0.6 s at 1024^2); profiles take
  /// estimated plans (measuring a 10^6-point 1D transform takes FFTW half a minute).
  static Result<std::unique_ptr<ElasticOperator>> create(std::size_t nx, std::size_t ny, double dx, double dy,
                                                         bool periodic, double contact_modulus, unsigned threads);
  ~ElasticOperator();
  ElasticOperator(const ElasticOperator&) = delete;
  ElasticOperator& operator=(const ElasticOperator&) = delete;

  /// out = K in: the displacement (unit: m, positive into the body) of the pressures `in` (unit:
  /// Pa) at the nx ny points (x fastest). `in` and `out` may be the same array.
  void apply(const double* in, double* out);
  /// The team that shares apply's copies and the spectrum's product with FFTW's threads (nullptr:
  /// the calling thread alone); it must outlive the operator's use.
  void set_team(util::Team* team) { team_ = team; }

 private:
  /// Runs body(begin, end) over [0, n) in one contiguous chunk per member of the team.
  template <class Body>
  void chunks(std::size_t n, const Body& body);
  util::Team* team_ = nullptr;
  ElasticOperator() = default;
  std::size_t nx_ = 0, ny_ = 0, Nx_ = 0, Ny_ = 0;
  bool padded_ = false;
  /// A padded map's transform is pruned: the rows' real transforms run over the ny rows that hold
  /// data only (the other Ny - ny rows are zero on the way in and not needed on the way out), the
  /// columns' complex transforms over the whole padded height.
  bool pruned_ = false;
  // The transforms are in place: the reals are the spectrum's buffer seen as rows of 2 (Nx/2 + 1)
  // doubles (row stride rs_), Nx of them used.
  double* real_ = nullptr;
  std::size_t rs_ = 0;
  void* spec_ = nullptr;              // Ny (Nx/2 + 1) complex numbers
  std::vector<double> kernel_;        // the transfer function, normalised (1 / (Nx Ny) folded in)
  void* forward_ = nullptr;           // the whole r2c transform (pruned: the rows' r2c transforms)
  void* backward_ = nullptr;          // the whole c2r transform (pruned: the rows' c2r transforms)
  void* columns_forward_ = nullptr;   // pruned only: the columns' forward complex transforms
  void* columns_backward_ = nullptr;  // pruned only: the columns' backward complex transforms
};

}  // namespace frictal::contact_detail
