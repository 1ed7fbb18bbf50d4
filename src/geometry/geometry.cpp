// Curves, profiles, exact envelopes, rotation, evaluation.
#include "frictal/geometry.hpp"

#include <fmt/core.h>
#include <algorithm>
#include <cmath>
#include <limits>

namespace frictal {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Status check_arrays(const std::vector<double>& x, const std::vector<double>& z, const std::string& what) {
  if (x.size() != z.size())
    return make_error(fmt::format("{}: x has {} values but z has {}", what, x.size(), z.size()));
  if (x.size() < 2) return make_error(fmt::format("{}: needs at least 2 points, got {}", what, x.size()));
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(z[i]))
      return make_error(fmt::format("{}: point {} is not finite (x = {}, z = {})", what, i + 1, x[i], z[i]));
  }
  return Ok{};
}

// One vertical group of an envelope under construction: value approached from the left, value
// at x (the envelope's extreme), value approached from the right; NaN outside the domain.
struct Group {
  double x, l, m, r;
};
using Env = std::vector<Group>;

// Keeps the better of two possibly-NaN values.
inline double pick(double a, double b, bool upper) {
  if (std::isnan(a)) return b;
  if (std::isnan(b)) return a;
  return upper ? std::max(a, b) : std::min(a, b);
}

// Values (l, m, r) of envelope e at x, using cursor k (advanced monotonically).
struct Probe {
  const Env* e;
  std::size_t k = 0;  // first group with x >= query
  Group at(double x) {
    const Env& g = *e;
    while (k < g.size() && g[k].x < x) ++k;
    if (k < g.size() && g[k].x == x) return g[k];
    if (k == 0 || k == g.size()) return {x, kNaN, kNaN, kNaN};
    const Group& a = g[k - 1];
    const Group& b = g[k];
    if (std::isnan(a.r) || std::isnan(b.l)) return {x, kNaN, kNaN, kNaN};
    double t = (x - a.x) / (b.x - a.x);
    double v = a.r + t * (b.l - a.r);
    return {x, v, v, v};
  }
};

Env merge(const Env& A, const Env& B, bool upper) {
  std::vector<double> xs;
  xs.reserve(A.size() + B.size());
  std::size_t i = 0, j = 0;
  while (i < A.size() || j < B.size()) {
    double v;
    if (j == B.size() || (i < A.size() && A[i].x <= B[j].x)) {
      v = A[i++].x;
    } else {
      v = B[j++].x;
    }
    if (xs.empty() || xs.back() != v) xs.push_back(v);
  }
  Env out;
  out.reserve(xs.size() + 8);
  Probe pa{&A}, pb{&B};
  Group prevA{}, prevB{};
  for (std::size_t n = 0; n < xs.size(); ++n) {
    Group ga = pa.at(xs[n]);
    Group gb = pb.at(xs[n]);
    if (n > 0) {
      // Both linear on (xs[n-1], xs[n]); insert their crossing if the order flips.
      double a0 = prevA.r, b0 = prevB.r, a1 = ga.l, b1 = gb.l;
      if (!std::isnan(a0) && !std::isnan(b0) && !std::isnan(a1) && !std::isnan(b1)) {
        double d0 = a0 - b0, d1 = a1 - b1;
        if ((d0 < 0 && d1 > 0) || (d0 > 0 && d1 < 0)) {
          double t = d0 / (d0 - d1);
          double x0 = xs[n - 1], x1 = xs[n];
          double xc = x0 + t * (x1 - x0);
          if (xc > x0 && xc < x1) {
            double v = a0 + t * (a1 - a0);
            out.push_back({xc, v, v, v});
          }
        }
      }
    }
    out.push_back({xs[n], pick(ga.l, gb.l, upper), pick(ga.m, gb.m, upper), pick(ga.r, gb.r, upper)});
    prevA = ga;
    prevB = gb;
  }
  return out;
}

Env edge_env(double x0, double z0, double x1, double z1, bool upper) {
  if (x0 == x1) {
    double v = upper ? std::max(z0, z1) : std::min(z0, z1);
    return {{x0, kNaN, v, kNaN}};
  }
  if (x1 < x0) {
    std::swap(x0, x1);
    std::swap(z0, z1);
  }
  return {{x0, kNaN, z0, z0}, {x1, z1, z1, kNaN}};
}

Env envelope_rec(const Curve& c, std::size_t e0, std::size_t e1, bool upper) {
  if (e1 - e0 == 1) return edge_env(c.x[e0], c.z[e0], c.x[e0 + 1], c.z[e0 + 1], upper);
  std::size_t mid = e0 + (e1 - e0) / 2;
  return merge(envelope_rec(c, e0, mid, upper), envelope_rec(c, mid, e1, upper), upper);
}

Profile env_to_profile(const Env& env, double zscale) {
  const double tol = 1e-12 * zscale;
  Profile p;
  auto push = [&](double x, double z) {
    if (!p.x.empty() && p.x.back() == x && std::abs(p.z.back() - z) <= tol) return;
    p.x.push_back(x);
    p.z.push_back(z);
  };
  for (const Group& g : env) {
    if (!std::isnan(g.l)) push(g.x, g.l);
    push(g.x, g.m);
    if (!std::isnan(g.r)) push(g.x, g.r);
  }
  // Drop vertices that lie on the straight line through their neighbours (hidden-edge
  // breakpoints left by the merge); they would only create spurious events.
  Profile q;
  q.x.reserve(p.x.size());
  q.z.reserve(p.z.size());
  for (std::size_t i = 0; i < p.x.size(); ++i) {
    if (!q.x.empty() && i + 1 < p.x.size()) {
      double xa = q.x.back(), za = q.z.back(), xb = p.x[i], zb = p.z[i], xc = p.x[i + 1], zc = p.z[i + 1];
      if (xa < xb && xb < xc) {
        double zl = za + (zc - za) * (xb - xa) / (xc - xa);
        if (std::abs(zl - zb) <= tol) continue;
      }
    }
    q.x.push_back(p.x[i]);
    q.z.push_back(p.z[i]);
  }
  return q;
}

Result<Profile> envelope(const Curve& c, bool upper) {
  if (auto st = validate(c, "curve"); !st) return st.error();
  double zmin = *std::min_element(c.z.begin(), c.z.end());
  double zmax = *std::max_element(c.z.begin(), c.z.end());
  double xmin = *std::min_element(c.x.begin(), c.x.end());
  double xmax = *std::max_element(c.x.begin(), c.x.end());
  if (!(xmax > xmin)) return make_error("curve: all points have the same x; an envelope needs a positive width");
  double zscale = std::max({std::abs(zmax - zmin), std::abs(zmax), std::abs(zmin), xmax - xmin});
  Env env = envelope_rec(c, 0, c.size() - 1, upper);
  return env_to_profile(env, zscale);
}

}  // namespace

Status validate(const Curve& c, const std::string& what) { return check_arrays(c.x, c.z, what); }

Status validate(const Profile& p, const std::string& what) {
  if (auto st = check_arrays(p.x, p.z, what); !st) return st;
  int run = 1;
  for (std::size_t i = 1; i < p.x.size(); ++i) {
    if (p.x[i] < p.x[i - 1]) {
      const bool backwards = std::is_sorted(p.x.rbegin(), p.x.rend());
      return make_error(fmt::format("{}: x must be non-decreasing, but point {} (x = {}) comes after x = {}{}", what,
                                    i + 1, p.x[i], p.x[i - 1],
                                    backwards ? "; x decreases throughout: give the points in reverse order" : ""));
    }
    run = (p.x[i] == p.x[i - 1]) ? run + 1 : 1;
    if (run > 3)
      return make_error(fmt::format("{}: more than 3 points share x = {} (point {}); a vertical jump needs at most 3",
                                    what, p.x[i], i + 1));
  }
  if (!(p.x.back() > p.x.front())) return make_error(fmt::format("{}: has zero length (all x equal)", what));
  if (p.x.back() - p.x.front() < std::numeric_limits<double>::min())
    return make_error(
        fmt::format("{}: x spans {} to {}, a length of {} m below the smallest normal double ({} m) that has lost "
                    "precision; rescale x (e.g. to another unit)",
                    what, p.x.front(), p.x.back(), p.x.back() - p.x.front(), std::numeric_limits<double>::min()));
  if (!std::isfinite(p.x.back() - p.x.front()))
    return make_error(
        fmt::format("{}: x spans {} to {}, a length beyond the range of double; rescale x (e.g. to "
                    "another unit)",
                    what, p.x.front(), p.x.back()));
  if (p.period) {
    double P = *p.period;
    if (!(P > 0) || !std::isfinite(P)) return make_error(fmt::format("{}: period must be positive, got {}", what, P));
    if (P > p.length() * (1 + 1e-12))
      return make_error(fmt::format("{}: period {} m is longer than the profile ({} m)", what, P, p.length()));
  }
  return Ok{};
}

Result<Profile> as_profile(const Curve& c, const std::string& what) {
  Profile p{c.x, c.z, std::nullopt};
  if (auto st = validate(p, what); !st) return st.error();
  return p;
}

Result<Profile> as_profile(Curve&& c, const std::string& what) {
  Profile p{std::move(c.x), std::move(c.z), std::nullopt};
  if (auto st = validate(p, what); !st) return st.error();
  return p;
}

Curve as_curve(const Profile& p) { return Curve{p.x, p.z}; }

Result<Profile> upper_envelope(const Curve& c) { return envelope(c, true); }
Result<Profile> lower_envelope(const Curve& c) { return envelope(c, false); }

Profile rotate180(const Profile& p) {
  Profile r;
  const std::size_t n = p.size();
  r.x.resize(n);
  r.z.resize(n);
  const double a = p.x.front(), b = p.x.back();
  for (std::size_t i = 0; i < n; ++i) {
    r.x[i] = (a + b) - p.x[n - 1 - i];
    r.z[i] = -p.z[n - 1 - i];
  }
  r.x.front() = a;  // exact ends despite rounding
  r.x.back() = b;
  r.period = p.period;
  return r;
}

Profile rotate180(Profile&& p) {
  Profile r = std::move(p);
  const std::size_t n = r.size();
  if (n == 0) return r;
  const double a = r.x.front(), b = r.x.back();
  // The same expression as the copy's on the same values: x'[i] = (a + b) - x[n - 1 - i].
  std::reverse(r.x.begin(), r.x.end());
  std::reverse(r.z.begin(), r.z.end());
  for (std::size_t i = 0; i < n; ++i) {
    r.x[i] = (a + b) - r.x[i];
    r.z[i] = -r.z[i];
  }
  r.x.front() = a;  // exact ends despite rounding
  r.x.back() = b;
  return r;
}

Curve rotate180(const Curve& c) {
  Curve r;
  const std::size_t n = c.size();
  r.x.resize(n);
  r.z.resize(n);
  if (n == 0) return r;
  const double a = *std::min_element(c.x.begin(), c.x.end());
  const double b = *std::max_element(c.x.begin(), c.x.end());
  for (std::size_t i = 0; i < n; ++i) {
    r.x[i] = (a + b) - c.x[n - 1 - i];
    r.z[i] = -c.z[n - 1 - i];
  }
  return r;
}

double evaluate(const Profile& p, double x, JumpValue at_jump) {
  if (p.period) {
    double P = *p.period;
    double t = std::fmod(x - p.x.front(), P);
    if (t < 0) t += P;
    x = p.x.front() + t;
  }
  auto it = std::lower_bound(p.x.begin(), p.x.end(), x);
  std::size_t k = static_cast<std::size_t>(it - p.x.begin());
  if (k < p.size() && p.x[k] == x) {
    double v = p.z[k];
    for (std::size_t j = k + 1; j < p.size() && p.x[j] == x; ++j)
      v = (at_jump == JumpValue::Upper) ? std::max(v, p.z[j]) : std::min(v, p.z[j]);
    return v;
  }
  if (k == 0) return p.z.front();
  if (k == p.size()) return p.z.back();
  double t = (x - p.x[k - 1]) / (p.x[k] - p.x[k - 1]);
  return p.z[k - 1] + t * (p.z[k] - p.z[k - 1]);
}

Result<Profile> resample(const Profile& p, std::size_t n) {
  if (auto st = validate(p); !st) return st.error();
  if (n < 2) return make_error(fmt::format("resample: needs at least 2 points, got {}", n));
  Profile r;
  r.x.resize(n);
  r.z.resize(n);
  const double a = p.x.front(), L = p.length();
  for (std::size_t i = 0; i < n; ++i) {
    double x = (i + 1 == n) ? p.x.back() : a + L * static_cast<double>(i) / static_cast<double>(n - 1);
    r.x[i] = x;
    r.z[i] = evaluate(p, x, JumpValue::Upper);
  }
  r.period = p.period;
  return r;
}

bool is_uniform(const Profile& p, double rel_tol) {
  if (p.size() < 2) return false;
  const double dx = (p.x.back() - p.x.front()) / static_cast<double>(p.size() - 1);
  if (!(dx > 0)) return false;
  for (std::size_t i = 1; i < p.size(); ++i) {
    double expect = p.x.front() + dx * static_cast<double>(i);
    if (std::abs(p.x[i] - expect) > rel_tol * (p.x.back() - p.x.front())) return false;
  }
  return true;
}

}  // namespace frictal
