// Detrending, spectra, autocorrelation, distributions, areal statistics and map lines.
#include <fmt/core.h>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

#include "analysis/edge_scale.hpp"
#include "frictal/analysis.hpp"
#include "util/fft.hpp"

namespace frictal {

namespace {

using cd = std::complex<double>;

/// Legendre polynomials P_0..P_deg at t.
void legendre(double t, int deg, double* out) {
  out[0] = 1;
  if (deg >= 1) out[1] = t;
  for (int k = 1; k < deg; ++k) out[k + 1] = ((2 * k + 1) * t * out[k] - k * out[k - 1]) / (k + 1);
}

/// Solves G a = b (G symmetric positive semi-definite, small) by Gaussian elimination with
/// partial pivoting. False if singular.
bool solve(std::vector<double> G, std::vector<double> b, std::vector<double>& a) {
  const std::size_t n = b.size();
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t piv = c;
    for (std::size_t r = c + 1; r < n; ++r)
      if (std::abs(G[r * n + c]) > std::abs(G[piv * n + c])) piv = r;
    if (!(std::abs(G[piv * n + c]) > 1e-300)) return false;
    if (piv != c) {
      for (std::size_t k = 0; k < n; ++k) std::swap(G[c * n + k], G[piv * n + k]);
      std::swap(b[c], b[piv]);
    }
    for (std::size_t r = c + 1; r < n; ++r) {
      double f = G[r * n + c] / G[c * n + c];
      for (std::size_t k = c; k < n; ++k) G[r * n + k] -= f * G[c * n + k];
      b[r] -= f * b[c];
    }
  }
  a.assign(n, 0);
  for (std::size_t c = n; c-- > 0;) {
    double s = b[c];
    for (std::size_t k = c + 1; k < n; ++k) s -= G[c * n + k] * a[k];
    a[c] = s / G[c * n + c];
  }
  return true;
}

std::vector<double> trapezoid_weights(const Profile& p) {
  std::vector<double> w(p.size(), 0.0);
  for (std::size_t k = 1; k < p.size(); ++k) {
    double h = p.x[k] - p.x[k - 1];
    w[k - 1] += 0.5 * h;
    w[k] += 0.5 * h;
  }
  return w;
}

double pl_mean(const Profile& p) {
  double s = 0;
  for (std::size_t k = 1; k < p.size(); ++k) s += 0.5 * (p.z[k] + p.z[k - 1]) * (p.x[k] - p.x[k - 1]);
  return s / p.length();
}

/// Integrals over one segment of length h of the two linear hat functions times exp(-i q t):
/// A = int (1 - t/h) e^{-iqt} dt, B = int (t/h) e^{-iqt} dt, t in [0, h].
void hat_integrals(double q, double h, cd& A, cd& B) {
  const double u = q * h;
  cd S0, S1;
  if (std::abs(u) < 0.1) {  // series: cancellation-free for small u
    cd term = 1.0, s0 = 0.0, s1 = 0.0;
    double fact = 1;  // m!
    for (int m = 0; m <= 12; ++m) {
      if (m > 0) {
        term *= cd(0, -u);
        fact *= m;
      }
      s0 += term / (double(m + 1) * fact);
      s1 += term / (double(m + 2) * fact);
    }
    S0 = h * s0;
    S1 = h * h * s1;
  } else {
    cd E(std::cos(u), -std::sin(u));
    S0 = (1.0 - E) / cd(0, q);
    S1 = E * cd(1 / (q * q), h / q) - 1 / (q * q);
  }
  B = S1 / h;
  A = S0 - B;
}

}  // namespace

Result<Detrend> parse_detrend(const std::string& text) {
  Detrend d;
  if (text == "none" || text.empty()) return d;
  if (text == "mean") {
    d.kind = DetrendKind::Mean;
    return d;
  }
  if (text == "line" || text == "plane") {
    d.kind = DetrendKind::Line;
    d.degree = 1;
    return d;
  }
  if (text.rfind("poly:", 0) == 0) {
    std::string n = text.substr(5);
    char* end = nullptr;
    long v = std::strtol(n.c_str(), &end, 10);
    if (!n.empty() && end && *end == '\0' && v >= 0 && v <= 10) {
      d.kind = DetrendKind::Polynomial;
      d.degree = int(v);
      return d;
    }
  }
  return make_error(
      fmt::format("detrend '{}' not understood (expected none, mean, line or poly:N with N in 0..10)", text));
}

static int degree_of(const Detrend& d) {
  return d.kind == DetrendKind::Mean ? 0 : d.kind == DetrendKind::Line ? 1 : d.degree;
}

Result<Profile> detrend(Profile&& p, const Detrend& d) {
  if (auto s = validate(p, "profile"); !s) return s.error();
  if (d.kind == DetrendKind::None) return std::move(p);
  const int deg = degree_of(d);
  if (deg < 0 || deg > 10) return make_error(fmt::format("detrend degree {} out of range 0..10", deg));
  if (std::size_t(deg) + 1 > p.size())
    return make_error(
        fmt::format("detrend degree {} needs at least {} points, the profile has {}", deg, deg + 1, p.size()));
  const std::size_t n = std::size_t(deg) + 1;
  auto w = trapezoid_weights(p);
  const double mid = 0.5 * (p.x_min() + p.x_max()), half = 0.5 * p.length();
  std::vector<double> G(n * n, 0.0), b(n, 0.0), P(n), a;
  for (std::size_t i = 0; i < p.size(); ++i) {
    legendre((p.x[i] - mid) / half, deg, P.data());
    for (std::size_t r = 0; r < n; ++r) {
      b[r] += w[i] * P[r] * p.z[i];
      for (std::size_t c = 0; c < n; ++c) G[r * n + c] += w[i] * P[r] * P[c];
    }
  }
  if (!solve(G, b, a)) return make_error("detrend: the least-squares system is singular (too few distinct x)");
  for (std::size_t i = 0; i < p.size(); ++i) {
    legendre((p.x[i] - mid) / half, deg, P.data());
    double f = 0;
    for (std::size_t r = 0; r < n; ++r) f += a[r] * P[r];
    p.z[i] -= f;
  }
  return std::move(p);
}

Result<Profile> detrend(const Profile& p, const Detrend& d) { return detrend(Profile(p), d); }

Result<Map> detrend(const Map& m, const Detrend& d) {
  if (auto s = validate(m, "map"); !s) return s.error();
  if (d.kind == DetrendKind::None) return m;
  const int deg = degree_of(d);
  if (deg < 0 || deg > 10) return make_error(fmt::format("detrend degree {} out of range 0..10", deg));
  std::vector<std::pair<int, int>> terms;
  for (int t = 0; t <= deg; ++t)
    for (int a = t; a >= 0; --a) terms.emplace_back(a, t - a);
  const std::size_t n = terms.size();
  if (m.valid_count() < n)
    return make_error(fmt::format("detrend of degree {} needs at least {} valid points", deg, n));
  const double hx = m.nx > 1 ? 0.5 * m.width() : 1, hy = m.ny > 1 ? 0.5 * m.height() : 1;
  auto coords = [&](std::size_t i, std::size_t j, double* Pu, double* Pv) {
    legendre(m.nx > 1 ? (double(i) * m.dx - 0.5 * m.width()) / hx : 0, deg, Pu);
    legendre(m.ny > 1 ? (double(j) * m.dy - 0.5 * m.height()) / hy : 0, deg, Pv);
  };
  std::vector<double> G(n * n, 0.0), b(n, 0.0), a, Pu(deg + 1), Pv(deg + 1), B(n);
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) {
      double z = m.at(i, j);
      if (std::isnan(z)) continue;
      coords(i, j, Pu.data(), Pv.data());
      for (std::size_t r = 0; r < n; ++r) B[r] = Pu[terms[r].first] * Pv[terms[r].second];
      for (std::size_t r = 0; r < n; ++r) {
        b[r] += B[r] * z;
        for (std::size_t c = 0; c < n; ++c) G[r * n + c] += B[r] * B[c];
      }
    }
  if (!solve(G, b, a))
    return make_error("detrend: the least-squares system is singular (valid points do not span the polynomial)");
  Map out = m;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) {
      double& z = out.at(i, j);
      if (std::isnan(z)) continue;
      coords(i, j, Pu.data(), Pv.data());
      double f = 0;
      for (std::size_t r = 0; r < n; ++r) f += a[r] * Pu[terms[r].first] * Pv[terms[r].second];
      z -= f;
    }
  return out;
}

Result<Spectrum> power_spectrum(const Profile& p, std::size_t max_k) {
  if (auto s = validate(p, "profile"); !s) return s.error();
  const std::size_t n = p.size();
  const double L = p.length(), mean = pl_mean(p);
  const bool uniform = is_uniform(p, 1e-9);
  std::size_t K = max_k ? max_k : std::max<std::size_t>(1, n / 2);
  if (!uniform && !max_k) K = std::min<std::size_t>({K, 4096, std::max<std::size_t>(16, std::size_t(5e8 / double(n)))});
  if (!uniform && double(K) * double(n) > 2e9)
    return make_error(
        fmt::format("power_spectrum: {} wavenumbers x {} points of a non-uniform profile is too much "
                    "work (direct sums); resample it uniformly first",
                    K, n));
  if (K > (std::size_t(1) << 26)) return make_error("power_spectrum: too many wavenumbers requested");
  Spectrum out;
  out.q.resize(K);
  out.psd.resize(K);
  if (uniform) {
    const std::size_t M = n - 1;
    const double h = L / double(M);
    std::vector<cd> a(M), b(M);
    for (std::size_t i = 0; i < M; ++i) {
      a[i] = p.z[i] - mean;
      b[i] = p.z[i + 1] - mean;
    }
    util::dft(a);
    util::dft(b);
    for (std::size_t k = 1; k <= K; ++k) {
      const double q = 2 * std::numbers::pi * double(k) / L;
      cd A, B;
      hat_integrals(q, h, A, B);
      cd I = A * a[k % M] + B * b[k % M];
      out.q[k - 1] = q;
      out.psd[k - 1] = std::norm(I) / L;
    }
  } else {
    for (std::size_t k = 1; k <= K; ++k) {
      const double q = 2 * std::numbers::pi * double(k) / L;
      cd I = 0;
      for (std::size_t i = 0; i + 1 < n; ++i) {
        const double h = p.x[i + 1] - p.x[i];
        if (h <= 0) continue;
        cd A, B;
        hat_integrals(q, h, A, B);
        const double ph = q * (p.x[i] - p.x[0]);
        I += cd(std::cos(ph), -std::sin(ph)) * (A * (p.z[i] - mean) + B * (p.z[i + 1] - mean));
      }
      out.q[k - 1] = q;
      out.psd[k - 1] = std::norm(I) / L;
    }
  }
  return out;
}

Result<Autocorrelation> autocorrelation(const Profile& p, std::size_t max_lag) {
  if (auto s = validate(p, "profile"); !s) return s.error();
  Profile u = p;
  if (!is_uniform(p, 1e-9)) {
    auto r = resample(p, p.size());
    if (!r) return r.error();
    u = std::move(*r);
  }
  const std::size_t n = u.size();
  const double h = u.length() / double(n - 1);
  if (max_lag == 0 || max_lag >= n) max_lag = n / 2;
  double mean = 0;
  for (double z : u.z) mean += z;
  mean /= double(n);
  std::size_t m = 1;
  while (m < 2 * n) m <<= 1;
  std::vector<cd> a(m, 0.0);
  for (std::size_t i = 0; i < n; ++i) a[i] = u.z[i] - mean;
  util::dft(a);
  for (auto& v : a) v = std::norm(v);
  util::dft(a, true);
  Autocorrelation out;
  const double r0 = a[0].real() / double(m) / double(n);
  for (std::size_t k = 0; k <= max_lag; ++k) {
    double r = a[k].real() / double(m) / double(n - k);
    out.lag.push_back(double(k) * h);
    out.acf.push_back(r0 > 0 ? r / r0 : (k == 0 ? 1.0 : 0.0));
  }
  for (std::size_t k = 1; k < out.acf.size(); ++k)
    if (out.acf[k] < std::exp(-1.0)) {
      // Linear interpolation between the two lags around 1/e.
      double a0 = out.acf[k - 1], a1 = out.acf[k], t = (a0 - std::exp(-1.0)) / (a0 - a1);
      out.correlation_length = out.lag[k - 1] + t * h;
      break;
    }
  return out;
}

Histogram height_distribution(const Profile& p, int bins) { return histogram(p.z, trapezoid_weights(p), bins); }

namespace {
/// map_stats in the map's own units; `max_gradient` gets max |dz/dx| (before the arctangent).
MapStats map_stats_unscaled(const Map& m, double& max_gradient) {
  MapStats s;
  s.points = m.size();
  s.width = m.width();
  s.height = m.height();
  double sum = 0, lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : m.heights)
    if (!std::isnan(v)) {
      ++s.valid;
      sum += v;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  if (s.valid == 0) return s;
  s.mean = sum / double(s.valid);
  double a = 0, q2 = 0, q3 = 0, q4 = 0;
  for (double v : m.heights)
    if (!std::isnan(v)) {
      double d = v - s.mean, d2 = d * d;
      a += std::abs(d);
      q2 += d2;
      q3 += d2 * d;
      q4 += d2 * d2;
    }
  const double nv = double(s.valid);
  s.Sa = a / nv;
  s.Sq = std::sqrt(q2 / nv);
  s.Sp = hi - s.mean;
  s.Sv = s.mean - lo;
  s.Sz = hi - lo;
  if (s.Sq > 0) {
    s.Ssk = q3 / nv / (s.Sq * s.Sq * s.Sq);
    s.Sku = q4 / nv / (s.Sq * s.Sq * s.Sq * s.Sq);
  }
  double gx = 0, gy = 0, mx = 0;
  std::size_t nx = 0, ny = 0;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) {
      double z = m.at(i, j);
      if (std::isnan(z)) continue;
      if (i + 1 < m.nx && !std::isnan(m.at(i + 1, j))) {
        double g = (m.at(i + 1, j) - z) / m.dx;
        gx += g * g;
        ++nx;
        mx = std::max(mx, std::abs(g));
      }
      if (j + 1 < m.ny && !std::isnan(m.at(i, j + 1))) {
        double g = (m.at(i, j + 1) - z) / m.dy;
        gy += g * g;
        ++ny;
        mx = std::max(mx, std::abs(g));
      }
    }
  s.Sdq = std::sqrt((nx ? gx / double(nx) : 0) + (ny ? gy / double(ny) : 0));
  s.max_slope = std::atan(mx);
  max_gradient = mx;
  return s;
}
}  // namespace

MapStats map_stats(const Map& m) {
  double mx = 0;
  const auto sc = analysis_detail::edge_scale(m);
  if (!sc) return map_stats_unscaled(m, mx);
  // Heights or spacings near the limits of double: computed at a power-of-two scale.
  MapStats s = map_stats_unscaled(analysis_detail::scaled(m, *sc), mx);
  s.width = m.width();
  s.height = m.height();
  for (double* h : {&s.mean, &s.Sa, &s.Sq, &s.Sp, &s.Sv, &s.Sz}) *h = sc->height(*h);
  s.Sdq = sc->slope(s.Sdq);
  s.max_slope = std::atan(sc->slope(mx));
  return s;
}

std::vector<Profile> map_line(const Map& m, double x, double y, double angle, double step, std::size_t min_points) {
  std::vector<Profile> out;
  if (m.nx < 2 && m.ny < 2) return out;
  if (step <= 0) step = std::min(m.dx, m.dy);
  const double c = std::cos(angle), s = std::sin(angle);
  const double xa = m.x0, xb = m.x0 + m.width(), ya = m.y0, yb = m.y0 + m.height();
  double t0 = -std::numeric_limits<double>::infinity(), t1 = -t0;
  auto slab = [&](double p, double d, double lo, double hi) {
    if (std::abs(d) < 1e-15) {
      if (p < lo - 1e-12 * (hi - lo + 1) || p > hi + 1e-12 * (hi - lo + 1)) t0 = 1, t1 = 0;
      return;
    }
    double a = (lo - p) / d, b = (hi - p) / d;
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  };
  slab(x, c, xa, xb);
  slab(y, s, ya, yb);
  if (!(t1 - t0 >= step * (1 - 1e-9))) return out;
  // Samples that rounding puts a hair outside the grid are clamped back onto its edge.
  const std::size_t count = std::size_t(std::floor((t1 - t0) / step + 1e-9)) + 1;
  Profile cur;
  auto flush = [&] {
    if (cur.size() >= std::max<std::size_t>(min_points, 2)) out.push_back(std::move(cur));
    cur = Profile{};
  };
  for (std::size_t k = 0; k < count; ++k) {
    const double t = t0 + double(k) * step;
    double px = x + t * c, py = y + t * s;
    px = std::clamp(px, xa, xb);
    py = std::clamp(py, ya, yb);
    double z = interpolate(m, px, py);
    if (std::isnan(z)) {
      flush();
      continue;
    }
    cur.x.push_back(double(k) * step);
    cur.z.push_back(z);
  }
  flush();
  return out;
}

std::vector<Profile> map_lines(const Map& m, double angle, double spacing, double step, std::size_t min_points) {
  std::vector<Profile> out;
  if (spacing <= 0) spacing = std::min(m.dx, m.dy);
  const double c = std::cos(angle), s = std::sin(angle), nxv = -s, nyv = c;
  const double cx = m.x0 + 0.5 * m.width(), cy = m.y0 + 0.5 * m.height();
  const double half = 0.5 * (std::abs(nxv) * m.width() + std::abs(nyv) * m.height());
  const long K = long(std::floor(half / spacing));
  for (long k = -K; k <= K; ++k) {
    double off = double(k) * spacing;
    auto lines = map_line(m, cx + off * nxv, cy + off * nyv, angle, step, min_points);
    for (auto& l : lines) out.push_back(std::move(l));
  }
  return out;
}

double slope_correlation_length(const Profile& p) {
  const std::size_t n = p.x.size();
  const double len = n > 1 ? p.x.back() - p.x.front() : 0;
  if (!(len > 0)) return 0;
  // The slope averaged over M equal cells (exact for cells inside one segment), its mean removed.
  const std::size_t m = std::clamp<std::size_t>(8 * (n - 1), 4096, std::size_t(1) << 20);
  const double h = len / double(m);
  std::vector<double> zc(m + 1);
  std::size_t k = 1;
  for (std::size_t i = 0; i <= m; ++i) {
    const double x = i == m ? p.x.back() : p.x.front() + double(i) * h;
    while (k + 1 < n && p.x[k] <= x) ++k;
    const double w = p.x[k] - p.x[k - 1];
    zc[i] = w > 0 ? p.z[k - 1] + (x - p.x[k - 1]) / w * (p.z[k] - p.z[k - 1]) : p.z[k];
  }
  std::vector<double> s(m);
  double mean = 0;
  for (std::size_t i = 0; i < m; ++i) mean += (s[i] = (zc[i + 1] - zc[i]) / h);
  mean /= double(m);
  std::size_t size = 1;
  while (size < 2 * m) size <<= 1;
  std::vector<std::complex<double>> a(size, 0.0);
  for (std::size_t i = 0; i < m; ++i) a[i] = s[i] - mean;
  util::dft(a);
  for (auto& v : a) v = std::norm(v);
  util::dft(a, true);
  const double r0 = a[0].real() / double(m);
  if (!(r0 > 0)) return 0;  // no slope variation: a flat profile
  const double target = std::exp(-1.0);
  double prev = 1;
  for (std::size_t lag = 1; lag < m / 2; ++lag) {
    const double r = a[lag].real() / double(m - lag) / r0;
    if (r < target) return (double(lag) - 1 + (prev - target) / (prev - r)) * h;
    prev = r;
  }
  return 0;  // the slopes stay correlated over half the scan: no local length to read
}

}  // namespace frictal
