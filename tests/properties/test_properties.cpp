// Property tests: thousands of random cases with fixed seeds, each checked against a brute-force
// evaluation written here from the definitions (not the library's own reference functions).
//  - the exact signature's lift h(s) = max_x [f(x) - g(x - s)] (paper Eq. 1-2 with the upper face
//    already turned over) at every reported offset and at random offsets in between;
//  - h is continuous where no vertical wall is reported: over a tiny step d it moves by at most
//    (steepest edge slope) * d;
//  - envelopes of random folded curves equal the pointwise max/min over the curve's segments;
//  - X3P write -> read is the identity for random maps of every data type, with masks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "frictal/geometry.hpp"
#include "frictal/io.hpp"
#include "frictal/map.hpp"
#include "frictal/signature.hpp"

namespace {

using frictal::Curve;
using frictal::Profile;

constexpr double kInf = std::numeric_limits<double>::infinity();

// Value of a profile (possibly with vertical jumps) at x: linear between neighbours; at an x held
// by several points, the largest (take_max) or smallest of their values. Periodic profiles wrap.
double value_at(const Profile& p, double x, bool take_max) {
  if (p.period) {
    const double P = *p.period, x0 = p.x.front();
    x = x0 + std::fmod(std::fmod(x - x0, P) + P, P);
  }
  double best = take_max ? -kInf : kInf;
  bool on_vertex = false;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.x[i] == x) {
      on_vertex = true;
      best = take_max ? std::max(best, p.z[i]) : std::min(best, p.z[i]);
    }
  if (p.period && x == p.x.front()) {  // the period's end is the same point
    const double zend = p.z.back();
    best = take_max ? std::max(best, zend) : std::min(best, zend);
  }
  if (on_vertex) return best;
  for (std::size_t i = 0; i + 1 < p.size(); ++i)
    if (p.x[i] < x && x < p.x[i + 1]) {
      const double t = (x - p.x[i]) / (p.x[i + 1] - p.x[i]);
      return p.z[i] + t * (p.z[i + 1] - p.z[i]);
    }
  return take_max ? -kInf : kInf;  // outside
}

// Brute-force lift: the sup of f(x) - g(x - s) over the overlap is attained at a vertex of f, a
// vertex of g (shifted) or an end of the overlap, so those candidates suffice. Each candidate is a
// pair (x on f, y on g) with x - y = s; a vertex keeps its own abscissa exactly (x - s would round
// away from a jump of g, and miss it).
double brute_lift(const Profile& f, const Profile& g, double s) {
  std::vector<std::pair<double, double>> xy;
  if (f.period && g.period) {
    const double P = *f.period;
    for (double x : f.x) xy.emplace_back(x, x - s);
    for (double y : g.x)
      for (int k = -2; k <= 2; ++k) {
        const double x = y + s + k * P;
        if (x >= f.x.front() && x <= f.x.front() + P) xy.emplace_back(x, y);
      }
  } else {
    const double a = std::max(f.x.front(), g.x.front() + s), b = std::min(f.x.back(), g.x.back() + s);
    xy = {{a, a - s}, {b, b - s}};
    for (double x : f.x)
      if (x >= a && x <= b) xy.emplace_back(x, x - s);
    for (double y : g.x)
      if (y + s >= a && y + s <= b) xy.emplace_back(y + s, y);
  }
  // A vertex of f aligned with a vertex of g (to rounding: s itself is a rounded x_f - x_g) is
  // one contact point of both: both vertices' extreme values count there.
  const double tol = 1e-12 * std::max(f.x.back() - f.x.front(), g.x.back() - g.x.front());
  const double P = (f.period && g.period) ? *f.period : 0;
  for (double x : f.x)
    for (double y : g.x)
      for (int k = (P > 0 ? -2 : 0); k <= (P > 0 ? 2 : 0); ++k)
        if (std::abs(x - (y + s + k * P)) <= tol) xy.emplace_back(x, y);
  double best = -kInf;
  for (auto [x, y] : xy) best = std::max(best, value_at(f, x, true) - value_at(g, y, false));
  return best;
}

double steepest(const Profile& p) {
  double m = 0;
  for (std::size_t i = 0; i + 1 < p.size(); ++i)
    if (p.x[i + 1] > p.x[i]) m = std::max(m, std::abs((p.z[i + 1] - p.z[i]) / (p.x[i + 1] - p.x[i])));
  return m;
}

// A random profile on [0, L]: uniform grid or random spacing, optional vertical jumps (2 or 3
// points at one x), optional periodicity (last height = first, period = L).
Profile random_profile(std::mt19937_64& rng, bool uniform, bool jumps, bool periodic, double L) {
  std::uniform_int_distribution<int> npts(4, 24);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int n = npts(rng);
  std::vector<double> x(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) x[static_cast<std::size_t>(i)] = L * i / (n - 1);
  if (!uniform)
    for (int i = 1; i + 1 < n; ++i) x[static_cast<std::size_t>(i)] = L * (i + 0.8 * (u(rng) - 0.5)) / (n - 1);
  Profile p;
  for (int i = 0; i < n; ++i) {
    const double xi = x[static_cast<std::size_t>(i)];
    const double z = L * 0.2 * (u(rng) - 0.5);
    p.x.push_back(xi);
    p.z.push_back(z);
    if (jumps && i > 0 && i + 1 < n && u(rng) < 0.2) {  // a vertical jump: left limit, (extreme), right limit
      if (u(rng) < 0.5) {
        p.x.push_back(xi);
        p.z.push_back(z + L * 0.3 * (u(rng) - 0.5) * 2);
      }
      p.x.push_back(xi);
      p.z.push_back(L * 0.2 * (u(rng) - 0.5));
    }
  }
  if (periodic) {
    p.z.back() = p.z.front();
    p.period = L;
  }
  return p;
}

std::string dump(const Profile& p) {
  std::string out;
  char buf[96];
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::snprintf(buf, sizeof buf, "(%.17g, %.17g) ", p.x[i], p.z[i]);
    out += buf;
  }
  return out;
}

struct Case {
  bool uniform, jumps, periodic;
};

class SignatureProperty : public ::testing::TestWithParam<Case> {};

TEST_P(SignatureProperty, LiftEqualsBruteForceAndIsContinuousAwayFromWalls) {
  const Case c = GetParam();
  std::mt19937_64 rng(20261123 + 7 * c.uniform + 13 * c.jumps + 29 * c.periodic);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int cases = 1500;
  long checked = 0, continuity_checked = 0;
  for (int k = 0; k < cases; ++k) {
    const double L = 1.0;
    const Profile f = random_profile(rng, c.uniform, c.jumps, c.periodic, L);
    const Profile g = random_profile(rng, c.uniform, c.jumps, c.periodic, L);
    ASSERT_TRUE(frictal::validate(f, "f").ok()) << "case " << k;
    ASSERT_TRUE(frictal::validate(g, "g").ok()) << "case " << k;
    frictal::SignatureOptions o;
    o.threads = 1;
    o.keep_contacts = false;
    auto sig = frictal::signature(f, g, o);
    ASSERT_TRUE(sig.ok()) << "case " << k << ": " << sig.error().message;
    ASSERT_TRUE(sig->exact);
    const double scale = 0.6 * L;  // heights are within +-0.3 L
    const double maxslope = std::max(steepest(f), steepest(g));
    const auto& s = sig->offset;
    for (std::size_t i = 0; i < s.size(); ++i) {
      ASSERT_NEAR(sig->lift[i], brute_lift(f, g, s[i]), 1e-12 * scale)
          << "case " << k << " offset " << s[i] << " (uniform " << c.uniform << ", jumps " << c.jumps << ", periodic "
          << c.periodic << ")\nf: " << dump(f) << "\ng: " << dump(g);
      ++checked;
      if (i + 1 < s.size()) {
        // Between events: h at a random point is the brute-force value too (the engine reports
        // only events; this checks the event list is complete enough for the lift there).
        const double mid = s[i] + u(rng) * (s[i + 1] - s[i]);
        const double hm = brute_lift(f, g, mid);
        // h is convex between events: it lies below the chord of its end values.
        const double t = (mid - s[i]) / (s[i + 1] - s[i]);
        const double chord = sig->lift[i] + t * (sig->lift[i + 1] - sig->lift[i]);
        const bool wall_here = std::abs(sig->theta_right[i]) > 1.5707 || std::abs(sig->theta_left[i + 1]) > 1.5707;
        if (!wall_here) {
          EXPECT_LE(hm, chord + 1e-12 * scale) << "case " << k << ": h not convex between events " << s[i];
          // Continuity: a tiny step moves h by at most the steepest slope times the step.
          const double d = 1e-9 * (s[i + 1] - s[i]);
          const double h1 = brute_lift(f, g, s[i] + d);
          EXPECT_LE(std::abs(h1 - sig->lift[i]), maxslope * d * (1 + 1e-6) + 1e-12 * scale)
              << "case " << k << ": h jumps at offset " << s[i] << " with no wall reported; theta_right "
              << sig->theta_right[i] << " next offset " << s[i + 1] << " h(s) " << sig->lift[i] << " h(s+d) " << h1
              << "\nf: " << dump(f) << "\ng: " << dump(g);
          ++continuity_checked;
        }
      }
    }
  }
  EXPECT_GT(checked, cases * 10);
  EXPECT_GT(continuity_checked, cases * 5);
}

INSTANTIATE_TEST_SUITE_P(Random, SignatureProperty,
                         ::testing::Values(Case{true, false, false}, Case{false, false, false},
                                           Case{false, true, false}, Case{true, false, true}, Case{false, false, true}),
                         [](const auto& info) {
                           const Case c = info.param;
                           return std::string(c.uniform ? "Uniform" : "NonUniform") + (c.jumps ? "Jumps" : "") +
                                  (c.periodic ? "Periodic" : "Open");
                         });

// Pointwise upper (lower) envelope of a curve: max (min) over every segment spanning x of its
// value there; vertical segments count at their x with both ends.
double brute_envelope(const Curve& c, double x, bool upper) {
  double best = upper ? -kInf : kInf;
  for (std::size_t i = 0; i + 1 < c.size(); ++i) {
    const double a = c.x[i], b = c.x[i + 1];
    const double lo = std::min(a, b), hi = std::max(a, b);
    if (x < lo || x > hi) continue;
    double v;
    if (a == b) {
      v = upper ? std::max(c.z[i], c.z[i + 1]) : std::min(c.z[i], c.z[i + 1]);
    } else {
      const double t = (x - a) / (b - a);
      v = c.z[i] + t * (c.z[i + 1] - c.z[i]);
    }
    best = upper ? std::max(best, v) : std::min(best, v);
  }
  return best;
}

TEST(EnvelopeProperty, RandomFoldedCurvesMatchThePointwiseExtreme) {
  std::mt19937_64 rng(4242);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  long checked = 0;
  for (int k = 0; k < 3000; ++k) {
    // A random walk that goes back and forth in x (folds), starting at 0 and ending at 1.
    Curve c;
    const int n = 3 + static_cast<int>(u(rng) * 20);
    c.x.push_back(0);
    c.z.push_back(u(rng));
    for (int i = 1; i < n; ++i) {
      c.x.push_back(u(rng) < 0.1 ? c.x.back() : std::clamp(c.x.back() + (u(rng) - 0.35) * 0.3, 0.0, 1.0));
      c.z.push_back(u(rng));
    }
    c.x.push_back(1);
    c.z.push_back(u(rng));
    for (bool upper : {true, false}) {
      auto env = upper ? frictal::upper_envelope(c) : frictal::lower_envelope(c);
      ASSERT_TRUE(env.ok()) << env.error().message;
      ASSERT_TRUE(frictal::validate(*env, "envelope").ok());
      for (int t = 0; t < 40; ++t) {
        const double x = u(rng);
        // Away from the envelope's breakpoints the envelope is single-valued there.
        const double want = brute_envelope(c, x, upper);
        const double got = value_at(*env, x, upper);
        ASSERT_NEAR(got, want, 1e-12) << "case " << k << (upper ? " upper" : " lower") << " at x = " << x;
        ++checked;
      }
      // At every vertex of the curve the envelope's extreme value is the curve's extreme there.
      for (double x : c.x) {
        ASSERT_NEAR(value_at(*env, x, upper), brute_envelope(c, x, upper), 1e-12) << "case " << k << " at vertex " << x;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 200000);
}

TEST(X3pProperty, WriteThenReadIsTheIdentityForRandomMapsOfEveryType) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto dir = std::filesystem::temp_directory_path() / ("frictal-x3p-prop-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  int files = 0;
  for (int k = 0; k < 400; ++k) {
    frictal::Map m;
    m.nx = 2 + static_cast<std::size_t>(u(rng) * 17);  // a map (ny = 1 reads back as a line profile)
    m.ny = 2 + static_cast<std::size_t>(u(rng) * 13);
    m.dx = std::pow(10.0, -3 - 6 * u(rng));
    m.dy = std::pow(10.0, -3 - 6 * u(rng));
    const auto type = static_cast<frictal::X3pDataType>(k % 4);
    frictal::X3pWriteOptions o;
    o.type = type;
    o.binary = (k / 4) % 2 == 0;
    o.date = "2026-11-23T00:00:00Z";
    const bool integer = type == frictal::X3pDataType::I || type == frictal::X3pDataType::L;
    const double inc = 1e-9 * (1 + std::floor(u(rng) * 5)), off = 1e-6 * std::floor(u(rng) * 100 - 50);
    if (integer) {
      o.z_increment = inc;
      o.z_offset = off;
    }
    const long range = type == frictal::X3pDataType::I ? 30000 : 2000000000;
    m.heights.resize(m.nx * m.ny);
    for (auto& h : m.heights) {
      if (integer) {
        const long raw = static_cast<long>(std::floor((u(rng) - 0.5) * 2 * range));
        h = off + inc * static_cast<double>(raw);
      } else if (type == frictal::X3pDataType::F) {
        h = static_cast<double>(static_cast<float>((u(rng) - 0.5) * 1e-5));
      } else {
        h = (u(rng) - 0.5) * std::pow(10.0, -9 + 6 * u(rng));
      }
    }
    // A random mask (keep at least one valid point).
    for (std::size_t i = 1; i < m.heights.size(); ++i)
      if (u(rng) < 0.15) m.heights[i] = std::nan("");
    const std::string path = (dir / ("m" + std::to_string(k) + ".x3p")).string();
    ASSERT_TRUE(frictal::write_x3p(path, m, o).ok()) << "map " << k;
    auto r = frictal::read_map(path);
    ASSERT_TRUE(r.ok()) << "map " << k << ": " << r.error().message;
    ASSERT_EQ(r->nx, m.nx);
    ASSERT_EQ(r->ny, m.ny);
    EXPECT_DOUBLE_EQ(r->dx, m.dx);
    EXPECT_DOUBLE_EQ(r->dy, m.dy);
    for (std::size_t i = 0; i < m.heights.size(); ++i) {
      if (std::isnan(m.heights[i])) {
        ASSERT_TRUE(std::isnan(r->heights[i])) << "map " << k << " point " << i << " should be invalid";
      } else if (integer) {
        // z = offset + increment * raw: the same arithmetic on the same raw integer.
        ASSERT_NEAR(r->heights[i], m.heights[i], 1e-15 + 1e-15 * std::abs(m.heights[i]))
            << "map " << k << " point " << i;
      } else {
        ASSERT_EQ(r->heights[i], m.heights[i]) << "map " << k << " point " << i;
      }
    }
    std::filesystem::remove(path);
    ++files;
  }
  std::filesystem::remove_all(dir);
  EXPECT_EQ(files, 400);
}

}  // namespace
