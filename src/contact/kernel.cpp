// The elastic convolution on FFTW (kernel.hpp). The transfer function of the periodic operator is
// the continuous one, 2 / (E* |q|) with the mean (q = 0) term zero; the padded operator's is the
// transform of the real-space influence coefficients of uniform pressure on one cell (Love's
// rectangle for maps, the logarithmic half-plane for profiles) on the padded grid (at least 2N - 1
// points a side, the next product of 2, 3, 5, 7), whose wrap-around
// never meets the N points (the discrete convolution theorem on the padded grid).
#include "kernel.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <numbers>

#include <fftw3.h>

namespace frictal::contact_detail {

namespace {

// FFTW's planner is not thread-safe: every plan is made and destroyed under this lock.
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

#ifdef FRICTAL_FFTW_THREADS
void init_threads_once() {
  static std::once_flag once;
  std::call_once(once, [] { fftw_init_threads(); });
}
#endif

/// The integral of 1 / r over the rectangle [x1, x2] x [y1, y2] as the corner sum of
/// F(x, y) = x asinh(y / |x|) + y asinh(x / |y|) (the x ln|x| + y ln|y| terms of the primitive
/// cancel in the corner sum); F is 0 where x or y is 0 (its limit).
double love_primitive(double x, double y) {
  double f = 0;
  if (x != 0) f += x * std::asinh(y / std::abs(x));
  if (y != 0) f += y * std::asinh(x / std::abs(y));
  return f;
}

/// The transform length of a padded direction of n points: the smallest product of 2, 3, 5 and 7
/// that is at least 2 n - 1, the length whose wrap-around never brings one of the n points onto
/// another's offset (a length with a large prime factor, 2 n of n = 100001 = 11 x 9091, makes
/// FFTW's transform several times slower).
std::size_t padded_size(std::size_t n) {
  const std::size_t want = 2 * n - 1;
  for (std::size_t m = want;; ++m) {
    std::size_t r = m;
    for (std::size_t f : {2, 3, 5, 7})
      while (r % f == 0) r /= f;
    if (r == 1) return m;
  }
}

}  // namespace

Result<std::unique_ptr<ElasticOperator>> ElasticOperator::create(std::size_t nx, std::size_t ny, double dx, double dy,
                                                                 bool periodic, double e_star, unsigned threads) {
  std::unique_ptr<ElasticOperator> op(new ElasticOperator());
  op->nx_ = nx;
  op->ny_ = ny;
  op->padded_ = !periodic;
  op->Nx_ = periodic ? nx : padded_size(nx);
  op->Ny_ = (periodic || ny == 1) ? ny : padded_size(ny);
  op->pruned_ = !periodic && ny > 1;
  const std::size_t Nx = op->Nx_, Ny = op->Ny_, Nh = Nx / 2 + 1;
  const std::size_t total = Nx * Ny, spectral = Ny * Nh;
  op->spec_ = fftw_alloc_complex(spectral);
  op->real_ = reinterpret_cast<double*>(op->spec_);
  op->rs_ = 2 * Nh;
  const std::size_t rs = op->rs_;
  if (!op->spec_)
    return make_error(ErrorCode::Internal,
                      "contact: out of memory for the FFT buffers (" + std::to_string(total) + " points)");
  auto* spec = static_cast<fftw_complex*>(op->spec_);
  {
    std::lock_guard<std::mutex> lock(planner_mutex());
#ifdef FRICTAL_FFTW_THREADS
    init_threads_once();
    fftw_plan_with_nthreads(int(threads < 1 ? 1 : threads));
#else
    (void)threads;
#endif
    // Measured plans for maps from 2^19 points on: they cut a 1024 x 1024 transform pair's time
    // by a third to a half for 0.2-0.6 s of CPU planning (bench/results/contact.md), which the
    // hundred-odd iterations of one solve repay; FFTW keeps what it measured for later plans of
    // the same size in the process. Profiles and smaller grids take estimated plans at once:
    // measuring a 1D transform of 10^6 points or more takes FFTW 30-60 s. The planner's
    // measurements may pick a different algorithm from run to run: results agree to rounding,
    // not to the bit.
    const unsigned flags = (ny > 1 && total >= (std::size_t(1) << 19)) ? FFTW_MEASURE : FFTW_ESTIMATE;
    if (ny == 1) {
      op->forward_ = fftw_plan_dft_r2c_1d(int(Nx), op->real_, spec, flags);
      op->backward_ = fftw_plan_dft_c2r_1d(int(Nx), spec, op->real_, flags);
    } else if (!op->pruned_) {
      op->forward_ = fftw_plan_dft_r2c_2d(int(Ny), int(Nx), op->real_, spec, flags);
      op->backward_ = fftw_plan_dft_c2r_2d(int(Ny), int(Nx), spec, op->real_, flags);
    } else {
      // Rows: ny real transforms of length Nx, in place (row stride 2 Nh reals, Nh complex numbers).
      // Columns: Nh complex transforms of length Ny, in place (element stride Nh).
      const int n_row[1] = {int(Nx)}, n_col[1] = {int(Ny)};
      op->forward_ =
          fftw_plan_many_dft_r2c(1, n_row, int(ny), op->real_, nullptr, 1, int(rs), spec, nullptr, 1, int(Nh), flags);
      op->backward_ =
          fftw_plan_many_dft_c2r(1, n_row, int(ny), spec, nullptr, 1, int(Nh), op->real_, nullptr, 1, int(rs), flags);
      op->columns_forward_ = fftw_plan_many_dft(1, n_col, int(Nh), spec, nullptr, int(Nh), 1, spec, nullptr, int(Nh), 1,
                                                FFTW_FORWARD, flags);
      op->columns_backward_ = fftw_plan_many_dft(1, n_col, int(Nh), spec, nullptr, int(Nh), 1, spec, nullptr, int(Nh),
                                                 1, FFTW_BACKWARD, flags);
      if (!op->columns_forward_ || !op->columns_backward_)
        return make_error(ErrorCode::Internal, "contact: FFTW could not plan");
    }
  }
  if (!op->forward_ || !op->backward_) return make_error(ErrorCode::Internal, "contact: FFTW could not plan");
  op->kernel_.assign(spectral, 0.0);
  const double norm = 1.0 / double(total);
  if (periodic) {
    const double lx = double(Nx) * dx, ly = ny == 1 ? 1.0 : double(Ny) * dy;
    for (std::size_t j = 0; j < Ny; ++j) {
      const double fy = ny == 1 ? 0.0 : double(j <= Ny / 2 ? double(j) : double(j) - double(Ny)) / ly;
      for (std::size_t i = 0; i < Nh; ++i) {
        const double fx = double(i) / lx;
        const double q = 2 * std::numbers::pi * std::hypot(fx, fy);
        op->kernel_[j * Nh + i] = q > 0 ? 2.0 / (e_star * q) * norm : 0.0;
      }
    }
    return op;
  }
  // Influence coefficients at the wrapped offsets of the padded grid: 0 .. (N - 1)/2 at indices
  // 0 .. (N - 1)/2, the negative ones above (N >= 2 n - 1 holds the offsets -(n - 1) .. n - 1).
  auto wrapped = [](std::size_t k, std::size_t n) { return k <= (n - 1) / 2 ? double(k) : double(k) - double(n); };
  if (ny == 1) {
    const double a = dx / 2, c = -2.0 / (std::numbers::pi * e_star);
    // G(t) = t ln|t / dx| - t, whose difference over [x - a, x + a] integrates ln|x - s|.
    auto G = [dx](double t) { return t == 0 ? 0.0 : t * std::log(std::abs(t) / dx) - t; };
    for (std::size_t i = 0; i < Nx; ++i) {
      const double x = wrapped(i, Nx) * dx;
      op->real_[i] = c * (G(x + a) - G(x - a));
    }
    fftw_execute(static_cast<fftw_plan>(op->forward_));
  } else {
    // All Ny rows of coefficients, the rows' transforms in place by an estimated plan of their
    // own (used once; it leaves the arrays alone while planning), then the columns' transform.
    const double a = dx / 2, b = dy / 2, c = 1.0 / (std::numbers::pi * e_star);
    for (std::size_t j = 0; j < Ny; ++j) {
      const double y = wrapped(j, Ny) * dy;
      double* row = op->real_ + j * rs;
      // Even in x: the offsets -x (i > Nx/2) repeat the coefficients of +x.
      for (std::size_t i = 0; i <= Nx / 2; ++i) {
        const double x = wrapped(i, Nx) * dx;
        row[i] = c * (love_primitive(x + a, y + b) - love_primitive(x - a, y + b) - love_primitive(x + a, y - b) +
                      love_primitive(x - a, y - b));
      }
      for (std::size_t i = Nx / 2 + 1; i < Nx; ++i) row[i] = row[Nx - i];
    }
    fftw_plan rows = nullptr;
    {
      std::lock_guard<std::mutex> lock(planner_mutex());
      const int n_row[1] = {int(Nx)};
      rows = fftw_plan_many_dft_r2c(1, n_row, int(Ny), op->real_, nullptr, 1, int(rs), spec, nullptr, 1, int(Nh),
                                    FFTW_ESTIMATE);
    }
    if (!rows) return make_error(ErrorCode::Internal, "contact: FFTW could not plan");
    fftw_execute(rows);
    {
      std::lock_guard<std::mutex> lock(planner_mutex());
      fftw_destroy_plan(rows);
    }
    fftw_execute(static_cast<fftw_plan>(op->columns_forward_));
  }
  for (std::size_t k = 0; k < spectral; ++k) op->kernel_[k] = spec[k][0] * norm;  // even: real
  return op;
}

ElasticOperator::~ElasticOperator() {
  {
    std::lock_guard<std::mutex> lock(planner_mutex());
    if (forward_) fftw_destroy_plan(static_cast<fftw_plan>(forward_));
    if (backward_) fftw_destroy_plan(static_cast<fftw_plan>(backward_));
    if (columns_forward_) fftw_destroy_plan(static_cast<fftw_plan>(columns_forward_));
    if (columns_backward_) fftw_destroy_plan(static_cast<fftw_plan>(columns_backward_));
  }
  fftw_free(spec_);
}

template <class Body>
void ElasticOperator::chunks(std::size_t n, const Body& body) {
  const unsigned members = team_ ? team_->members() : 1;
  if (members <= 1) {
    body(std::size_t(0), n);
    return;
  }
  struct Context {
    const Body* body;
    std::size_t n;
    unsigned members;
  } context{&body, n, members};
  team_->run(
      members,
      [](void* c, unsigned m) {
        const auto* x = static_cast<const Context*>(c);
        (*x->body)(x->n * m / x->members, x->n * (m + 1) / x->members);
      },
      &context);
}

void ElasticOperator::apply(const double* in, double* out) {
  const std::size_t Nh = Nx_ / 2 + 1;
  auto* spec = static_cast<fftw_complex*>(spec_);
  const std::size_t spectral = Ny_ * Nh;
  const auto multiply = [&](std::size_t b, std::size_t e) {
    for (std::size_t k = b; k < e; ++k) {
      spec[k][0] *= kernel_[k];
      spec[k][1] *= kernel_[k];
    }
  };
  // The ny data rows into the in-place buffer, each padded with zeros to Nx where padded (the
  // last two doubles of a row are the spectrum's, not read by the real transform).
  const auto copy_in = [&](std::size_t b, std::size_t e) {
    for (std::size_t j = b; j < e; ++j) {
      std::memcpy(real_ + j * rs_, in + j * nx_, sizeof(double) * nx_);
      if (padded_) std::memset(real_ + j * rs_ + nx_, 0, sizeof(double) * (Nx_ - nx_));
    }
  };
  const auto copy_out = [&](std::size_t b, std::size_t e) {
    for (std::size_t j = b; j < e; ++j) std::memcpy(out + j * nx_, real_ + j * rs_, sizeof(double) * nx_);
  };
  if (ny_ == 1) {
    copy_in(0, 1);
    fftw_execute(static_cast<fftw_plan>(forward_));
    chunks(spectral, multiply);
    fftw_execute(static_cast<fftw_plan>(backward_));
    copy_out(0, 1);
    return;
  }
  chunks(ny_, copy_in);
  fftw_execute(static_cast<fftw_plan>(forward_));
  if (pruned_) {
    // The rows' transforms filled the first ny rows of the spectrum; the other Ny - ny rows (the
    // padding) are zero.
    chunks(Ny_ - ny_, [&](std::size_t b, std::size_t e) {
      std::memset(spec + (ny_ + b) * Nh, 0, sizeof(fftw_complex) * (e - b) * Nh);
    });
    fftw_execute(static_cast<fftw_plan>(columns_forward_));
    chunks(spectral, multiply);
    fftw_execute(static_cast<fftw_plan>(columns_backward_));
  } else {
    chunks(spectral, multiply);
  }
  fftw_execute(static_cast<fftw_plan>(backward_));  // pruned: the first ny rows only, the ones asked for
  chunks(ny_, copy_out);
}

}  // namespace frictal::contact_detail
