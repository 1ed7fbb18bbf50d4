// Elastic normal contact (frictal/contact.hpp): Polonsky & Keer's constrained conjugate gradient
// on the FFT convolution of kernel.hpp, with the hardness cap as a box constraint 0 <= p <= H.
#include "frictal/contact.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <thread>

#include <fmt/core.h>

#include "kernel.hpp"
#include "util/team.hpp"

namespace frictal {

using contact_detail::ElasticOperator;

namespace {

Status check_material(const ElasticMaterial& m, const char* which) {
  if (!std::isfinite(m.modulus) || !(m.modulus > 0))
    return make_error(
        fmt::format("{}Young's modulus {} Pa: expected a finite modulus > 0 (unit: Pa)", which, m.modulus));
  if (!std::isfinite(m.poisson) || !(m.poisson > -1) || !(m.poisson <= 0.5))
    return make_error(fmt::format("{}Poisson's ratio {}: expected a value in (-1, 0.5]", which, m.poisson));
  return Ok{};
}

/// The grid the solver works on: heights (NaN: masked), spacing, the pixel's area.
struct Grid {
  bool is_map = false;
  std::size_t nx = 0, ny = 1;
  double dx = 0, dy = 0;
  bool periodic = false;
  const double* heights = nullptr;
  double cell() const { return is_map ? dx * dy : dx; }
  std::size_t size() const { return nx * ny; }
};

/// The rms slope of the heights (central differences; one-sided at the ends of a non-periodic
/// surface; masked points skipped).
double rms_slope(const Grid& g) {
  const auto h = [&](std::size_t i, std::size_t j) { return g.heights[j * g.nx + i]; };
  double s = 0;
  std::size_t n = 0;
  auto slope_along = [&](std::size_t i, std::size_t j, bool along_x) -> double {
    const std::size_t len = along_x ? g.nx : g.ny;
    const std::size_t k = along_x ? i : j;
    const double step = along_x ? g.dx : g.dy;
    std::size_t lo = k, hi = k;
    if (g.periodic) {
      lo = (k + len - 1) % len;
      hi = (k + 1) % len;
    } else {
      lo = k > 0 ? k - 1 : k;
      hi = k + 1 < len ? k + 1 : k;
    }
    const double span = double(g.periodic ? 2 : hi - lo) * step;
    const double a = along_x ? h(lo, j) : h(i, lo), b = along_x ? h(hi, j) : h(i, hi);
    return (b - a) / span;
  };
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      double q = slope_along(i, j, true);
      q *= q;
      if (g.is_map && g.ny > 1) {
        const double r = slope_along(i, j, false);
        q += r * r;
      }
      if (std::isfinite(q)) s += q, ++n;
    }
  return n ? std::sqrt(s / double(n)) : 0.0;
}

/// The solver of one surface: its operator and work arrays, kept across the loads of a curve.
class Solver {
 public:
  Solver(const Grid& g, const ContactOptions& o, std::unique_ptr<ElasticOperator> op, unsigned threads)
      : g_(g), o_(o), op_(std::move(op)) {
    const std::size_t n = g.size();
    // The passes over the points on `threads` threads from 2^16 points on (below, a pass takes
    // microseconds and the team's hand-over would cost more than it saves).
    if (threads > 1 && n >= (std::size_t(1) << 16)) team_ = util::Team::make(threads);
    members_ = team_ ? team_->members() : 1;
    op_->set_team(team_.get());
    partial_.assign(members_, {0, 0, 0, 0});
    h_ = g.heights;
    active_.assign(n, 0);
    hmax_ = -INFINITY;
    double mean = 0;
    for (std::size_t k = 0; k < n; ++k)
      if (std::isfinite(g.heights[k])) {
        active_[k] = 1, ++n_active_, hmax_ = std::max(hmax_, g.heights[k]), mean += g.heights[k];
      }
    mean /= double(n_active_);
    double s2 = 0;
    for (std::size_t k = 0; k < n; ++k)
      if (active_[k]) {
        s2 += (g.heights[k] - mean) * (g.heights[k] - mean);
      }
    h_rms_ = std::sqrt(s2 / double(n_active_));

    p_.assign(n, 0.0);
    g_field_.assign(n, 0.0);
    t_.assign(n, 0.0);
    r_.assign(n, 0.0);
  }
  std::size_t active_points() const { return n_active_; }
  /// The pressure a solve starts from (solve(force, true)): `start` where positive and finite.
  void seed(const std::vector<double>& start) {
    const double H = cap();
    for (std::size_t k = 0; k < p_.size(); ++k)
      p_[k] = active_[k] && std::isfinite(start[k]) && start[k] > 0 ? std::min(H, start[k]) : 0.0;
  }
  double cap() const { return o_.hardness > 0 ? o_.hardness : INFINITY; }

  /// Scales the pressure so that it carries `sum` (the force over the cell): p <- min(lambda p, H)
  /// with the one lambda > 0 that gives the sum (Newton's steps on the piecewise-linear sum,
  /// kept inside a bracket).
  void enforce_load(double sum) {
    const double H = cap();
    const std::size_t n = p_.size();
    double total = 0;
    std::size_t positive = 0;
    for (std::size_t k = 0; k < n; ++k)
      if (active_[k] && p_[k] > 0) total += p_[k], ++positive;
    if (!(total > 0) || (std::isfinite(H) && H * double(positive) < sum)) {
      // Too few loaded points to carry the load below H: every valid point takes a share.
      for (std::size_t k = 0; k < n; ++k)
        if (active_[k]) p_[k] = std::max(p_[k], 1e-3 * sum / double(n_active_));
      total = 0;
      for (std::size_t k = 0; k < n; ++k)
        if (active_[k]) total += p_[k];
    }
    if (!std::isfinite(H)) {
      const double f = sum / total;
      for (double& v : p_) v *= f;
      return;
    }
    // The capped points keep H; the free ones are scaled to carry the rest (those that pass H
    // are capped in turn). Only when the capped points alone carry more than the load do they
    // come down with the rest (the common lambda below).
    for (int round = 0; round < 50; ++round) {
      double free_sum = 0, capped = 0;
      for (std::size_t k = 0; k < n; ++k) {
        if (!active_[k] || p_[k] <= 0) continue;
        if (p_[k] >= H)
          capped += H;
        else
          free_sum += p_[k];
      }
      const double want = sum - capped;
      if (!(want > 0) || !(free_sum > 0)) break;
      const double f = want / free_sum;
      bool clipped = false;
      for (std::size_t k = 0; k < n; ++k)
        if (active_[k] && p_[k] > 0 && p_[k] < H) {
          p_[k] *= f;
          if (p_[k] >= H) p_[k] = H, clipped = true;
        }
      if (!clipped) return;
    }
    auto value = [&](double lambda, double* slope) {
      double s = 0, d = 0;
      for (std::size_t k = 0; k < n; ++k) {
        if (!active_[k] || p_[k] <= 0) continue;
        const double v = lambda * p_[k];
        if (v >= H)
          s += H;
        else
          s += v, d += p_[k];
      }
      if (slope) *slope = d;
      return s - sum;
    };
    double lo = 0, hi = 1;
    while (value(hi, nullptr) < 0 && hi < 1e300) lo = hi, hi *= 2;
    double lambda = 1, slope = 0;
    for (int it = 0; it < 200; ++it) {
      const double v = value(lambda, &slope);
      if (std::abs(v) <= 1e-14 * sum) break;
      if (v < 0)
        lo = lambda;
      else
        hi = lambda;
      double next = slope > 0 ? lambda - v / slope : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      lambda = next;
    }
    for (std::size_t k = 0; k < n; ++k)
      if (active_[k]) p_[k] = std::min(H, lambda * p_[k]);
  }

  /// The solution at force `force` (N or N/m); warm: start from the current pressure.
  ContactResult solve(double force, bool warm) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::size_t n = g_.size();
    const double cell = g_.cell(), H = cap();
    const double sum = force / cell;  // the pressure sum the load asks for (Pa)
    double pool = 0;
    for (std::size_t k = 0; k < n; ++k) pool += p_[k];
    if (!warm || !(pool > 0)) {
      for (std::size_t k = 0; k < n; ++k) p_[k] = active_[k] ? std::min(H, sum / double(n_active_)) : 0.0;
    }
    enforce_load(sum);
    const int max_it = o_.max_iterations > 0 ? o_.max_iterations : int(20 * std::sqrt(double(n_active_))) + 1000;
    const double tol = o_.tolerance;
    // The scale of the residual: the rms height; for a flat surface (rms 0) the displacement
    // that the mean pressure makes over one spacing (a flat punch's scale).
    const double scale = std::max(h_rms_, sum / double(n_active_) * g_.dx / o_.contact_modulus);
    double g_old = 1;
    bool conjugate = false;
    std::fill(t_.begin(), t_.end(), 0.0);
    ContactResult res;
    double shift = 0, residual = INFINITY;
    int it = 0;
    // The passes over the points run in `members_` fixed contiguous chunks whose partial sums
    // are added in chunk order (the same numbers for a given thread count).
    for (;; ++it) {
      op_->apply(p_.data(), g_field_.data());  // u, made the gap in place below
      // gap up to a constant: u - h; the constant makes its mean over the free contact zero.
      chunks([&](unsigned m, std::size_t b, std::size_t e) {
        double gsum = 0, nc = 0;
        for (std::size_t k = b; k < e; ++k) {
          g_field_[k] -= h_[k];
          if (active_[k] && p_[k] > 0 && p_[k] < H) gsum += g_field_[k], ++nc;
        }
        partial_[m] = {gsum, nc, 0, 0};
      });
      double gsum = 0;
      std::size_t nc = 0;
      for (unsigned m = 0; m < members_; ++m) gsum += partial_[m][0], nc += std::size_t(partial_[m][1]);
      shift = nc ? gsum / double(nc) : 0.0;
      chunks([&](unsigned m, std::size_t b, std::size_t e) {
        double G = 0, worst = 0;
        for (std::size_t k = b; k < e; ++k) {
          g_field_[k] -= shift;
          if (!active_[k]) continue;
          if (p_[k] > 0 && p_[k] < H)
            G += g_field_[k] * g_field_[k];
          else if (p_[k] <= 0)
            worst = std::max(worst, -g_field_[k]);  // interpenetration outside the contact
          else
            worst = std::max(worst, g_field_[k]);  // a capped point whose gap opens
        }
        partial_[m] = {G, worst, 0, 0};
      });
      double G = 0, worst = 0;
      for (unsigned m = 0; m < members_; ++m) G += partial_[m][0], worst = std::max(worst, partial_[m][1]);
      residual = std::max(nc ? std::sqrt(G / double(nc)) : 0.0, worst) / scale;
      if (residual < tol || it >= max_it) break;
      // The conjugate direction on the free contact set.
      const double beta = conjugate ? G / g_old : 0.0;
      chunks([&](unsigned, std::size_t b, std::size_t e) {
        for (std::size_t k = b; k < e; ++k)
          t_[k] = (active_[k] && p_[k] > 0 && p_[k] < H) ? g_field_[k] + beta * t_[k] : 0.0;
      });
      g_old = G;
      op_->apply(t_.data(), r_.data());
      // One pass (t is zero outside the free contact): the mean of r over the free contact
      // rbar, and sum (r - rbar) t = sum r t - rbar sum t.
      chunks([&](unsigned m, std::size_t b, std::size_t e) {
        double rsum = 0, rt = 0, tsum = 0, num = 0;
        for (std::size_t k = b; k < e; ++k)
          if (active_[k] && p_[k] > 0 && p_[k] < H) {
            rsum += r_[k];
            rt += r_[k] * t_[k];
            tsum += t_[k];
            num += g_field_[k] * t_[k];
          }
        partial_[m] = {rsum, rt, tsum, num};
      });
      double rsum = 0, rt = 0, tsum = 0, num = 0;
      for (unsigned m = 0; m < members_; ++m)
        rsum += partial_[m][0], rt += partial_[m][1], tsum += partial_[m][2], num += partial_[m][3];
      const double rbar = nc ? rsum / double(nc) : 0.0;
      const double den = rt - rbar * tsum;
      double tau = (den > 0 && nc) ? num / den : 0.0;
      // No step on the free contact (one point, or its gap already uniform) while points outside
      // it interpenetrate: the step above would change nothing, and the iteration would stall
      // there (a start whose contact lies elsewhere: a warm start from a neighbouring problem).
      // Those points enter with the pressure that about closes their overlap over one spacing,
      // p = E* |g| / dx.
      if (!(tau > 0) && worst > 0) tau = o_.contact_modulus / g_.dx;
      chunks([&](unsigned m, std::size_t b, std::size_t e) {
        double entered = 0, total = 0, reset = 0;
        for (std::size_t k = b; k < e; ++k) {
          if (!active_[k]) continue;
          const bool free_point = p_[k] > 0 && p_[k] < H;
          if (free_point) {
            p_[k] = std::clamp(p_[k] - tau * t_[k], 0.0, H);
          } else if (p_[k] <= 0 && g_field_[k] < 0) {
            // Polonsky & Keer's overlap set: points that interpenetrate take pressure.
            p_[k] = std::min(H, -tau * g_field_[k]);
            ++entered;
          } else if (p_[k] >= H && g_field_[k] > 0) {
            p_[k] = std::max(0.0, H - tau * g_field_[k]);  // a capped point whose gap opens unloads
            reset = 1;
          }
          total += p_[k];
        }
        partial_[m] = {entered, total, reset, 0};
      });
      bool reset = false;
      std::size_t entered = 0;
      double total = 0;
      for (unsigned m = 0; m < members_; ++m)
        entered += std::size_t(partial_[m][0]), total += partial_[m][1], reset = reset || partial_[m][2] > 0;
      // Polonsky & Keer restart the conjugate directions whenever a point enters the contact;
      // on rough surfaces a few points enter at almost every step while the contact set settles,
      // which leaves steepest descent (3-4 times the iterations at 1024 x 1024). The directions
      // are restarted only when more than 1 % of the contact set enters at once (the same
      // solutions to the tolerance; bench/results/contact.md).
      if (double(entered) > 0.01 * double(nc)) reset = true;
      conjugate = !reset;
      if (!std::isfinite(H) && total > 0) {
        const double f = sum / total;  // the load (enforce_load without a cap, its sum known)
        chunks([&](unsigned, std::size_t b, std::size_t e) {
          for (std::size_t k = b; k < e; ++k) p_[k] *= f;
        });
      } else {
        enforce_load(sum);
      }
    }
    res.iterations = it;
    res.residual = residual;
    res.converged = residual < tol;
    // The solution's numbers (u and the gap are those of the current p).
    res.is_map = g_.is_map;
    res.nx = g_.nx;
    res.ny = g_.ny;
    res.dx = g_.dx;
    res.dy = g_.is_map ? g_.dy : 0.0;
    res.periodic = g_.periodic;
    res.contact_modulus = o_.contact_modulus;
    res.hardness = o_.hardness;
    res.force = force;
    res.nominal_area = double(n) * cell;
    res.nominal_pressure = force / res.nominal_area;
    std::size_t in_contact = 0, capped = 0;
    double gap_sum = 0, pmax = 0;
    bool at_edge = false;
    for (std::size_t k = 0; k < n; ++k) {
      if (!active_[k]) continue;
      if (p_[k] > 0) {
        ++in_contact;
        pmax = std::max(pmax, p_[k]);
        if (p_[k] >= H) ++capped;
        const std::size_t i = k % g_.nx, j = k / g_.nx;
        if (i == 0 || i + 1 == g_.nx || (g_.is_map && (j == 0 || j + 1 == g_.ny))) at_edge = true;
      }
      gap_sum += std::max(0.0, g_field_[k]);
    }
    res.contact_fraction = double(in_contact) / double(n_active_);
    res.plastic_fraction = double(capped) / double(n_active_);
    const double contact = double(in_contact) * cell;
    if (g_.is_map)
      res.contact_area = contact;
    else
      res.contact_length = contact;
    res.max_pressure = pmax;
    res.mean_contact_pressure = contact > 0 ? force / contact : 0.0;
    res.mean_separation = gap_sum / double(n_active_);
    // The flat at max(h) - approach: gap = (hmax - approach) - (h - u), and the solver's gap is
    // u - h - shift, so approach = hmax + shift.
    if (g_.is_map || g_.periodic) res.approach = hmax_ + shift;
    if (o_.keep_fields) {
      res.pressure.assign(n, 0.0);
      res.gap.assign(n, std::numeric_limits<double>::quiet_NaN());
      for (std::size_t k = 0; k < n; ++k)
        if (active_[k]) res.pressure[k] = p_[k], res.gap[k] = std::max(0.0, g_field_[k]);
    }
    if (o_.stiffness && (g_.is_map || g_.periodic)) stiffness(res);
    if (!res.converged)
      res.warnings.push_back(
          {"contact-not-converged",
           fmt::format("the contact solution did not converge in {} iterations: residual {:.3g} of the rms height "
                       "(tolerance {:.3g}); its numbers are approximate",
                       res.iterations, res.residual, tol)});
    if (in_contact == n_active_)
      res.warnings.push_back(
          {"contact-full",
           fmt::format("full contact at nominal pressure {:.6g} Pa: every point touches; a larger load only "
                       "compresses the half-space (the contact area is the nominal area)",
                       res.nominal_pressure)});
    else if (at_edge && !g_.periodic)
      res.warnings.push_back(
          {"contact-at-edge",
           "the contact reaches the edge of the non-periodic surface: the surface beyond the scan, taken as never "
           "touching, would carry load there; give a larger surface, or --periodic for a surface that repeats"});
    res.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return res;
  }

 private:
  /// dF/d(approach) at fixed contact set: K dp = 1 on the free contact points (dp = 0 elsewhere),
  /// by conjugate gradients; the stiffness is the cell times the sum of dp.
  void stiffness(ContactResult& res) {
    const std::size_t n = g_.size();
    const double H = cap();
    std::vector<char> set(n, 0);
    std::size_t m = 0;
    for (std::size_t k = 0; k < n; ++k)
      if (active_[k] && p_[k] > 0 && p_[k] < H) set[k] = 1, ++m;
    if (m == 0) {
      res.stiffness = 0;
      return;
    }
    if (g_.periodic && m == n_active_ && n_active_ == n) {
      res.stiffness = INFINITY;  // the mean mode costs nothing to compress: no finite force moves it
      return;
    }
    // CG on the set: x = dp, residual rr = 1 - K x on the set. The gap field is free once the
    // result has its numbers (the next solve makes it anew): it holds K d.
    std::vector<double>& x = t_;
    std::vector<double>& d = r_;
    std::vector<double>& kd = g_field_;
    std::vector<double> rr(n, 0.0);
    std::fill(x.begin(), x.end(), 0.0);
    for (std::size_t k = 0; k < n; ++k) rr[k] = set[k] ? 1.0 : 0.0;
    d = rr;
    double rho = double(m);
    const double stop = 1e-6 * std::sqrt(double(m));
    const int max_it = int(20 * std::sqrt(double(m))) + 500;
    int it = 0;
    for (; it < max_it && std::sqrt(rho) > stop; ++it) {
      op_->apply(d.data(), kd.data());
      chunks([&](unsigned c, std::size_t b, std::size_t e) {
        double dkd = 0;
        for (std::size_t k = b; k < e; ++k)
          if (set[k]) dkd += d[k] * kd[k];
        partial_[c] = {dkd, 0, 0, 0};
      });
      double dkd = 0;
      for (unsigned c = 0; c < members_; ++c) dkd += partial_[c][0];
      if (!(dkd > 0)) break;
      const double alpha = rho / dkd;
      chunks([&](unsigned c, std::size_t b, std::size_t e) {
        double rho_new = 0;
        for (std::size_t k = b; k < e; ++k)
          if (set[k]) {
            x[k] += alpha * d[k];
            rr[k] -= alpha * kd[k];
            rho_new += rr[k] * rr[k];
          }
        partial_[c] = {rho_new, 0, 0, 0};
      });
      double rho_new = 0;
      for (unsigned c = 0; c < members_; ++c) rho_new += partial_[c][0];
      const double beta = rho_new / rho;
      rho = rho_new;
      chunks([&](unsigned, std::size_t b, std::size_t e) {
        for (std::size_t k = b; k < e; ++k) d[k] = set[k] ? rr[k] + beta * d[k] : 0.0;
      });
    }
    double s = 0;
    for (std::size_t k = 0; k < n; ++k)
      if (set[k]) s += x[k];
    res.stiffness = s * g_.cell();
    res.stiffness_iterations = it;
  }

  /// Runs body(member, begin, end) on the members_ contiguous chunks of [0, points), chunk m
  /// [n m / M, n (m + 1) / M), chunk 0 on the calling thread.
  template <class Body>
  void chunks(const Body& body) {
    const std::size_t n = g_.size();
    if (members_ <= 1) {
      body(0u, std::size_t(0), n);
      return;
    }
    struct Context {
      const Body* body;
      std::size_t n;
      unsigned members;
    } context{&body, n, members_};
    team_->run(
        members_,
        [](void* c, unsigned m) {
          const auto* x = static_cast<const Context*>(c);
          (*x->body)(m, x->n * m / x->members, x->n * (m + 1) / x->members);
        },
        &context);
  }

  Grid g_;
  ContactOptions o_;
  std::unique_ptr<ElasticOperator> op_;
  std::unique_ptr<util::Team> team_;
  unsigned members_ = 1;
  std::vector<std::array<double, 4>> partial_;  // one chunk's partial sums per member
  std::vector<char> active_;
  std::size_t n_active_ = 0;
  /// The heights, the caller's (NaN where masked: the gap is NaN there, and every pass skips the
  /// masked points).
  const double* h_ = nullptr;
  std::vector<double> p_, g_field_, t_, r_;
  double hmax_ = 0, h_rms_ = 1;
};

unsigned thread_count(unsigned t) {
  if (t == 0) t = std::max(1u, std::thread::hardware_concurrency());
  return t;
}

Result<std::vector<ContactResult>> solve_grid(const Grid& g, const std::vector<ContactLoad>& loads,
                                              const ContactOptions& o,
                                              const std::vector<std::vector<double>>* starts = nullptr) {
  if (!std::isfinite(o.contact_modulus) || !(o.contact_modulus > 0))
    return make_error(
        fmt::format("contact modulus E* {} Pa: expected a finite value > 0 (unit: Pa)", o.contact_modulus));
  if (!std::isfinite(o.hardness) || o.hardness < 0)
    return make_error(fmt::format("hardness {} Pa: expected a finite value > 0 (unit: Pa), or 0 for none", o.hardness));
  if (!std::isfinite(o.tolerance) || !(o.tolerance > 0) || o.tolerance >= 1)
    return make_error(fmt::format("contact tolerance {}: expected a value in (0, 1)", o.tolerance));
  if (o.max_iterations < 0)
    return make_error(fmt::format("contact max_iterations {}: expected >= 0 (0: the default)", o.max_iterations));
  if (loads.empty()) return make_error("contact: no load given");
  if (starts && !starts->empty()) {
    if (starts->size() != loads.size())
      return make_error(fmt::format("contact: {} start pressures for {} loads", starts->size(), loads.size()));
    for (const auto& st : *starts)
      if (!st.empty() && st.size() != g.size())
        return make_error(
            fmt::format("contact: a start pressure of {} points for a surface of {}", st.size(), g.size()));
  }
  const std::size_t min_points = g.is_map ? 2 : 4;
  if (g.nx < min_points || (g.is_map && g.ny < 2))
    return make_error(fmt::format("contact: the surface has {} x {} points; expected at least {} x {}", g.nx, g.ny,
                                  min_points, g.is_map ? 2 : 1));
  if (!(g.dx > 0) || !std::isfinite(g.dx) || (g.is_map && (!(g.dy > 0) || !std::isfinite(g.dy))))
    return make_error(fmt::format("contact: grid spacing {} x {} m: expected finite spacings > 0", g.dx, g.dy));
  std::size_t valid = 0;
  for (std::size_t k = 0; k < g.size(); ++k) valid += std::isfinite(g.heights[k]) ? 1 : 0;
  if (valid < 4) return make_error(fmt::format("contact: {} valid heights; expected at least 4", valid));
  const double nominal = double(g.size()) * g.cell();
  std::vector<double> forces;
  for (const ContactLoad& l : loads) {
    const char* unit = l.kind == ContactLoadKind::Pressure ? "Pa" : (g.is_map ? "N" : "N/m");
    if (!std::isfinite(l.value) || !(l.value > 0))
      return make_error(fmt::format("contact load {} {}: expected a finite load > 0", l.value, unit));
    const double f = l.kind == ContactLoadKind::Pressure ? l.value * nominal : l.value;
    if (o.hardness > 0 && f > o.hardness * double(valid) * g.cell())
      return make_error(fmt::format(
          "contact load {} {}: above the hardness {} Pa times the area of the valid points ({} {}): no pressure "
          "p <= H carries it",
          l.value, unit, o.hardness, double(valid) * g.cell(), g.is_map ? "m^2" : "m"));
    forces.push_back(f);
  }
  auto op = ElasticOperator::create(g.nx, g.ny, g.dx, g.is_map ? g.dy : 0.0, g.periodic, o.contact_modulus,
                                    thread_count(o.threads));
  if (!op) return op.error();
  Solver solver(g, o, std::move(*op), thread_count(o.threads));
  const double slope = rms_slope(g);
  std::vector<ContactResult> out;
  out.reserve(loads.size());
  for (std::size_t k = 0; k < forces.size(); ++k) {
    const bool seeded = starts && !starts->empty() && !(*starts)[k].empty();
    if (seeded) solver.seed((*starts)[k]);
    ContactResult r = solver.solve(forces[k], k > 0 || seeded);
    r.rms_slope = slope;
    if (slope > o.max_rms_slope)
      r.warnings.insert(
          r.warnings.begin(),
          {"small-slope", fmt::format("the composite topography's rms slope is {:.3g}, above {:.3g}: the half-space "
                                      "solution assumes small slopes; its contact area and pressures are approximate",
                                      slope, o.max_rms_slope)});
    out.push_back(std::move(r));
  }
  return out;
}

Grid map_grid(const Map& m, bool periodic) {
  Grid g;
  g.is_map = true;
  g.nx = m.nx;
  g.ny = m.ny;
  g.dx = m.dx;
  g.dy = m.dy;
  g.periodic = periodic;
  g.heights = m.heights.data();
  return g;
}

Result<Grid> profile_grid(const Profile& p, bool periodic) {
  if (p.x.size() != p.z.size() || p.x.size() < 4)
    return make_error(fmt::format("contact: a profile of {} points; expected at least 4", p.x.size()));
  if (!is_uniform(p, 1e-6))
    return make_error("contact: the profile is not equally spaced; resample it first (the FFT solver needs a grid)");
  Grid g;
  g.nx = p.x.size();
  g.dx = (p.x.back() - p.x.front()) / double(g.nx - 1);
  g.periodic = periodic || p.period.has_value();
  g.heights = p.z.data();
  if (!p.period && periodic) {
    // Periodic without a stored period: a last point that repeats the first (the same height)
    // closes the period and is left out; otherwise the period is nx dx.
    double lo = p.z.front(), hi = p.z.front();
    for (double z : p.z) lo = std::min(lo, z), hi = std::max(hi, z);
    if (std::abs(p.z.back() - p.z.front()) <= 1e-9 * (hi - lo)) --g.nx;
  }
  if (p.period) {
    // One or more whole periods: the grid's period is nx dx; a last point one period after the
    // first repeats it and is left out.
    const double span = double(g.nx) * g.dx;
    const double whole = *p.period * std::round(span / *p.period);
    if (std::abs(p.length() - whole) < 0.5 * g.dx && g.nx > 4) {
      --g.nx;
    } else if (!(std::abs(span - whole) < 0.5 * g.dx)) {
      return make_error(fmt::format("contact: the profile's period {:g} m does not divide its {} points at {:g} m",
                                    *p.period, p.x.size(), g.dx));
    }
  }
  return g;
}

}  // namespace

Result<double> contact_modulus(const ElasticMaterial& body) {
  if (Status s = check_material(body, ""); !s) return s.error();
  return body.modulus / (1 - body.poisson * body.poisson);
}

Result<double> contact_modulus(const ElasticMaterial& first, const ElasticMaterial& second) {
  if (Status s = check_material(first, "first body: "); !s) return s.error();
  if (Status s = check_material(second, "second body: "); !s) return s.error();
  return 1.0 /
         ((1 - first.poisson * first.poisson) / first.modulus + (1 - second.poisson * second.poisson) / second.modulus);
}

Result<Profile> equally_spaced(const Profile& p, const std::string& name, std::vector<Warning>& warnings) {
  if (p.size() < 2) return make_error(fmt::format("contact: {}: {} points; expected at least 4", name, p.size()));
  if (is_uniform(p, 1e-6)) return p;
  double lo = INFINITY, hi = 0;
  for (std::size_t i = 1; i < p.size(); ++i)
    lo = std::min(lo, p.x[i] - p.x[i - 1]), hi = std::max(hi, p.x[i] - p.x[i - 1]);
  auto r = resample(p, p.size());
  if (!r) return with_prefix("contact: " + name + ": ", r.error());
  warnings.push_back({"contact-resampled",
                      fmt::format("{}: the points are not equally spaced (spacing {:.4g} to {:.4g} m); resampled on {} "
                                  "equally spaced points by linear interpolation for the FFT solver",
                                  name, lo, hi, p.size())});
  return r;
}

Result<Map> composite_topography(const Map& lower, const Map& upper, bool turn_over_upper,
                                 const std::string& lower_name, const std::string& upper_name) {
  const auto rel = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(std::abs(a), std::abs(b)); };
  if (lower.nx != upper.nx || lower.ny != upper.ny || !rel(lower.dx, upper.dx) || !rel(lower.dy, upper.dy))
    return make_error(fmt::format(
        "contact: {} ({} x {} points at {:g} x {:g} m) and {} ({} x {} at {:g} x {:g} m) must share one grid",
        lower_name, lower.nx, lower.ny, lower.dx, lower.dy, upper_name, upper.nx, upper.ny, upper.dx, upper.dy));
  Map c = lower;
  for (std::size_t j = 0; j < lower.ny; ++j)
    for (std::size_t i = 0; i < lower.nx; ++i) {
      const std::size_t k = j * lower.nx + i;
      c.heights[k] = turn_over_upper ? lower.heights[k] + upper.heights[j * lower.nx + (lower.nx - 1 - i)]
                                     : lower.heights[k] - upper.heights[k];
    }
  return c;
}

Result<Profile> composite_topography(const Profile& lower, const Profile& upper, bool turn_over_upper,
                                     const std::string& lower_name, const std::string& upper_name) {
  if (!is_uniform(lower, 1e-6) || !is_uniform(upper, 1e-6))
    return make_error(fmt::format("contact: {} and {} must be equally spaced", lower_name, upper_name));
  const double dl = lower.length() / double(lower.size() - 1), du = upper.length() / double(upper.size() - 1);
  if (lower.size() != upper.size() || std::abs(dl - du) > 1e-9 * std::max(dl, du))
    return make_error(fmt::format("contact: {} ({} points at {:g} m) and {} ({} points at {:g} m) must share one grid",
                                  lower_name, lower.size(), dl, upper_name, upper.size(), du));
  Profile c = lower;
  const std::size_t n = lower.size();
  for (std::size_t i = 0; i < n; ++i)
    c.z[i] = turn_over_upper ? lower.z[i] + upper.z[n - 1 - i] : lower.z[i] - upper.z[i];
  if (lower.period != upper.period) c.period.reset();
  return c;
}

Result<std::vector<ContactResult>> solve_contact_curve(const Map& surface, const std::vector<ContactLoad>& loads,
                                                       const ContactOptions& options) {
  if (surface.heights.size() != surface.nx * surface.ny)
    return make_error(fmt::format("contact: the map has {} heights for {} x {} points", surface.heights.size(),
                                  surface.nx, surface.ny));
  return solve_grid(map_grid(surface, options.periodic), loads, options);
}

Result<std::vector<ContactResult>> solve_contact_curve(const Map& surface, const std::vector<ContactLoad>& loads,
                                                       const ContactOptions& options,
                                                       const std::vector<std::vector<double>>& starts) {
  if (surface.heights.size() != surface.nx * surface.ny)
    return make_error(fmt::format("contact: the map has {} heights for {} x {} points", surface.heights.size(),
                                  surface.nx, surface.ny));
  return solve_grid(map_grid(surface, options.periodic), loads, options, &starts);
}

Result<std::vector<ContactResult>> solve_contact_curve(const Profile& surface, const std::vector<ContactLoad>& loads,
                                                       const ContactOptions& options) {
  auto g = profile_grid(surface, options.periodic);
  if (!g) return g.error();
  return solve_grid(*g, loads, options);
}

Result<ContactResult> solve_contact(const Map& surface, const ContactLoad& load, const ContactOptions& options) {
  auto r = solve_contact_curve(surface, {load}, options);
  if (!r) return r.error();
  return std::move(r->front());
}

Result<ContactResult> solve_contact(const Profile& surface, const ContactLoad& load, const ContactOptions& options) {
  auto r = solve_contact_curve(surface, {load}, options);
  if (!r) return r.error();
  return std::move(r->front());
}

}  // namespace frictal
