// The loaded lift of a map pair (frictal/load.hpp, "Maps"): the composite of the overlap at each
// offset pressed by the load onto the elastic half-space (contact.hpp's solver), the block's
// approach and elastic energy, and the minimum potential energy per unit load.
#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include <fmt/core.h>

#include "frictal/contact.hpp"
#include "frictal/load.hpp"
#include "util/parallel.hpp"

namespace frictal {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A contact fraction above this is "approaching full contact" (MapLoadedDiagnostics::full_share).
constexpr double kFullContact = 0.5;

// The composite c(p) of the overlap for an upper map moved by (sx, sy), at the lower map's nodes:
// the turn-over and the centring of areal_lift (areal.hpp).
class Composite {
 public:
  Composite(const Map& f, const Map& g, double angle, bool turn) : f_(f), g_(g), turn_(turn) {
    const double c = std::cos(angle), s = std::sin(angle);
    dx_ = c, dy_ = s;
    cfx_ = f.x0 + 0.5 * f.width(), cfy_ = f.y0 + 0.5 * f.height();
    cgx_ = g.x0 + 0.5 * g.width(), cgy_ = g.y0 + 0.5 * g.height();
    r11_ = 1 - 2 * c * c, r12_ = -2 * c * s, r22_ = 1 - 2 * s * s;
  }
  // (sx, sy) of the offset u along d, v across it (m).
  void shift(double u, double v, double& sx, double& sy) const { sx = u * dx_ - v * dy_, sy = u * dy_ + v * dx_; }
  double at(std::size_t i, std::size_t j, double sx, double sy) const {
    const double fz = f_.at(i, j);
    if (std::isnan(fz)) return kNaN;
    const double px = f_.x0 + double(i) * f_.dx, py = f_.y0 + double(j) * f_.dy;
    if (!turn_) return fz - interpolate(g_, px - sx, py - sy);
    const double ax = px - sx - cfx_, ay = py - sy - cfy_;
    return fz + interpolate(g_, cgx_ + r11_ * ax + r12_ * ay, cgy_ + r12_ * ax + r22_ * ay);
  }
  const Map& lower() const { return f_; }

 private:
  const Map& f_;
  const Map& g_;
  bool turn_;
  double dx_ = 1, dy_ = 0, cfx_ = 0, cfy_ = 0, cgx_ = 0, cgy_ = 0, r11_ = 1, r12_ = 0, r22_ = 1;
};

// The overlap at one offset: its bounding box on the lower grid and the composite there (NaN where
// the maps do not overlap), as a Map in the lower map's coordinates.
struct Window {
  std::size_t i0 = 0, j0 = 0;
  Map surface;
  double hmax = -std::numeric_limits<double>::infinity();
  std::size_t top = 0;  // the highest node, on the lower grid (j * nx + i)
  std::size_t valid = 0;
};

Window window_at(const Composite& comp, double sx, double sy) {
  const Map& f = comp.lower();
  std::vector<double> c(f.nx * f.ny);
  std::size_t i0 = f.nx, i1 = 0, j0 = f.ny, j1 = 0;
  Window w;
  for (std::size_t j = 0; j < f.ny; ++j)
    for (std::size_t i = 0; i < f.nx; ++i) {
      const double v = comp.at(i, j, sx, sy);
      c[j * f.nx + i] = v;
      if (std::isfinite(v)) {
        i0 = std::min(i0, i), i1 = std::max(i1, i), j0 = std::min(j0, j), j1 = std::max(j1, j);
        if (v > w.hmax) w.hmax = v, w.top = j * f.nx + i;
        ++w.valid;
      }
    }
  if (w.valid == 0 || i1 == i0 || j1 == j0) {
    w.valid = 0;
    return w;
  }
  w.i0 = i0, w.j0 = j0;
  Map& m = w.surface;
  m.nx = i1 - i0 + 1, m.ny = j1 - j0 + 1, m.dx = f.dx, m.dy = f.dy;
  m.x0 = f.x0 + double(i0) * f.dx, m.y0 = f.y0 + double(j0) * f.dy;
  m.heights.resize(m.nx * m.ny);
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) m.heights[j * m.nx + i] = c[(j + j0) * f.nx + (i + i0)];
  return w;
}

// The solves of every load at one offset, each started from `starts[l]` (the lower grid's pressure
// of the previous offset at load l; empty: cold), which they update. States in load order; none
// where the maps overlap by fewer than 2 x 2 nodes.
Result<std::vector<MapLoadedState>> solve_offset(const Composite& comp, double u, double v,
                                                 const MapLoadedLiftOptions& o,
                                                 std::vector<std::vector<double>>& starts) {
  const Map& f = comp.lower();
  double sx = 0, sy = 0;
  comp.shift(u, v, sx, sy);
  const Window w = window_at(comp, sx, sy);
  if (w.valid < 4) return std::vector<MapLoadedState>{};
  const Map& m = w.surface;
  ContactOptions co;
  co.contact_modulus = o.contact_modulus;
  co.periodic = false;
  co.tolerance = o.tolerance;
  co.threads = 1;
  co.stiffness = false;
  co.keep_fields = true;
  std::vector<ContactLoad> loads;
  std::vector<std::vector<double>> seeds(o.loads.size());
  for (std::size_t l = 0; l < o.loads.size(); ++l) {
    loads.push_back({ContactLoadKind::Force, o.loads[l]});
    if (starts[l].empty()) continue;
    seeds[l].assign(m.nx * m.ny, 0.0);
    for (std::size_t j = 0; j < m.ny; ++j)
      for (std::size_t i = 0; i < m.nx; ++i) seeds[l][j * m.nx + i] = starts[l][(j + w.j0) * f.nx + (i + w.i0)];
  }
  auto res = solve_contact_curve(m, loads, co, seeds);
  if (!res) return res.error();
  // dc/du at the contact points: central differences of the composite over +-eps along d (the
  // bilinear upper face is linear in u within a cell, so this is its derivative there).
  const double eps = 1e-4 * std::min(f.dx, f.dy);
  double sxp = 0, syp = 0, sxm = 0, sym = 0;
  comp.shift(u + eps, v, sxp, syp);
  comp.shift(u - eps, v, sxm, sym);
  const double cell = m.dx * m.dy;
  std::vector<MapLoadedState> out;
  std::vector<char> seen;
  std::vector<std::size_t> stack;
  for (std::size_t l = 0; l < o.loads.size(); ++l) {
    const ContactResult& r = (*res)[l];
    MapLoadedState st;
    st.along = u, st.across = v, st.load = o.loads[l];
    st.rigid_lift = w.hmax;
    st.highest_node = w.top;
    st.approach = r.approach;
    st.converged = r.converged;
    st.iterations = r.iterations;
    const double z = w.hmax - r.approach;
    double energy = 0, force = 0, slope = 0, grad2 = 0;
    auto h_at = [&](std::size_t i, std::size_t j) { return m.heights[j * m.nx + i]; };
    // One-sided at the window's edge and next to NaN nodes.
    auto derivative = [&](std::size_t i, std::size_t j, bool along_x) {
      const std::size_t n = along_x ? m.nx : m.ny;
      const std::size_t k = along_x ? i : j;
      const double step = along_x ? m.dx : m.dy;
      auto val = [&](std::size_t q) { return along_x ? h_at(q, j) : h_at(i, q); };
      const double c0 = val(k);
      const double cm = k > 0 ? val(k - 1) : kNaN, cp = k + 1 < n ? val(k + 1) : kNaN;
      if (std::isfinite(cm) && std::isfinite(cp)) return (cp - cm) / (2 * step);
      if (std::isfinite(cp)) return (cp - c0) / step;
      if (std::isfinite(cm)) return (c0 - cm) / step;
      return 0.0;
    };
    for (std::size_t j = 0; j < m.ny; ++j)
      for (std::size_t i = 0; i < m.nx; ++i) {
        const double p = r.pressure[j * m.nx + i];
        if (!(p > 0)) continue;
        const double F = p * cell;
        const std::size_t fi = i + w.i0, fj = j + w.j0;
        force += F;
        energy += 0.5 * F * (h_at(i, j) - z);
        const double dcdu = (comp.at(fi, fj, sxp, syp) - comp.at(fi, fj, sxm, sym)) / (2 * eps);
        if (std::isfinite(dcdu)) slope += F * dcdu;
        const double gx = derivative(i, j, true), gy = derivative(i, j, false);
        grad2 += F * (gx * gx + gy * gy);
        ++st.contact_points;
      }
    st.energy = energy;
    // h plus the elastic correction (which vanishes with the load).
    st.loaded_lift = w.hmax + (energy / o.loads[l] - r.approach);
    st.effective_slope = force > 0 ? slope / force : 0.0;
    st.contact_slope_rms = force > 0 ? std::sqrt(grad2 / force) : 0.0;
    st.contact_fraction = double(st.contact_points) / double(w.valid);
    // Patches: 4-connected components of the points in contact.
    seen.assign(m.nx * m.ny, 0);
    for (std::size_t k = 0; k < m.nx * m.ny; ++k) {
      if (seen[k] || !(r.pressure[k] > 0)) continue;
      ++st.patches;
      stack.assign(1, k);
      seen[k] = 1;
      while (!stack.empty()) {
        const std::size_t q = stack.back();
        stack.pop_back();
        const std::size_t i = q % m.nx, j = q / m.nx;
        auto visit = [&](std::size_t n) {
          if (!seen[n] && r.pressure[n] > 0) seen[n] = 1, stack.push_back(n);
        };
        if (i > 0) visit(q - 1);
        if (i + 1 < m.nx) visit(q + 1);
        if (j > 0) visit(q - m.nx);
        if (j + 1 < m.ny) visit(q + m.nx);
      }
    }
    // The next offset starts from this pressure, on the lower grid.
    starts[l].assign(f.nx * f.ny, 0.0);
    for (std::size_t j = 0; j < m.ny; ++j)
      for (std::size_t i = 0; i < m.nx; ++i) starts[l][(j + w.j0) * f.nx + (i + w.i0)] = r.pressure[j * m.nx + i];
    out.push_back(st);
  }
  return out;
}

Status check_options(const Map& lower, const Map& upper, const MapLoadedLiftOptions& o) {
  if (!std::isfinite(o.contact_modulus) || !(o.contact_modulus > 0))
    return make_error(
        fmt::format("contact modulus E* {} Pa: expected a finite value > 0 (unit: Pa)", o.contact_modulus));
  if (o.loads.empty()) return make_error("load: no load given");
  for (double w : o.loads)
    if (!std::isfinite(w) || !(w > 0)) return make_error(fmt::format("load {} N: expected a finite force > 0", w));
  if (!std::isfinite(o.angle)) return make_error("direction: expected a finite angle");
  if (!std::isfinite(o.step) || o.step < 0)
    return make_error(fmt::format("offset step {} m: expected a finite length >= 0 (0: the spacing)", o.step));
  if (!std::isfinite(o.refine_slope) || o.refine_slope < 0)
    return make_error(
        fmt::format("refinement slope {}: expected a finite slope >= 0 (0: no refinement)", o.refine_slope));
  if (!std::isfinite(o.min_step) || o.min_step < 0)
    return make_error(
        fmt::format("shortest offset step {} m: expected a finite length >= 0 (0: the spacing / 16)", o.min_step));
  if (lower.nx < 2 || lower.ny < 2 || upper.nx < 2 || upper.ny < 2)
    return make_error("the loaded map lift needs maps of at least 2 x 2 points");
  if (auto st = validate(lower, "lower map"); !st) return st;
  if (auto st = validate(upper, "upper map"); !st) return st;
  return Ok{};
}

}  // namespace

Result<MapLoadedState> map_loaded_state(const Map& lower, const Map& upper, double along, double across, double load,
                                        const MapLoadedLiftOptions& options) {
  MapLoadedLiftOptions o = options;
  o.loads = {load};
  if (auto st = check_options(lower, upper, o); !st) return st.error();
  if (!std::isfinite(along) || !std::isfinite(across))
    return make_error(fmt::format("offset ({}, {}) m: expected finite offsets", along, across));
  const Composite comp(lower, upper, o.angle, o.turn_over_upper);
  std::vector<std::vector<double>> starts(1);
  auto r = solve_offset(comp, along, across, o, starts);
  if (!r) return r.error();
  if (r->empty())
    return make_error(
        fmt::format("offset ({:.6g}, {:.6g}) m along and across the direction: the maps overlap by "
                    "fewer than 2 x 2 nodes there",
                    along, across));
  return r->front();
}

Result<MapLoadedLift> map_loaded_lift(const Map& lower, const Map& upper, const std::vector<double>& across,
                                      double along_min, double along_max, const MapLoadedLiftOptions& options) {
  const MapLoadedLiftOptions& o = options;
  if (auto st = check_options(lower, upper, o); !st) return st.error();
  if (across.empty()) return make_error("the loaded map lift: no line across the direction given");
  if (!std::isfinite(along_min) || !std::isfinite(along_max) || !(along_max > along_min))
    return make_error(fmt::format("offsets along the direction [{}, {}] m: expected a finite range, min < max",
                                  along_min, along_max));
  const double step = o.step > 0 ? o.step : std::min(lower.dx, lower.dy);
  const double min_step = o.min_step > 0 ? o.min_step : std::min(lower.dx, lower.dy) / 16;
  const std::size_t n = std::size_t(std::floor((along_max - along_min) / step + 1e-9)) + 1;
  if (n < 2 || n > 100000)
    return make_error(
        fmt::format("offsets along the direction: {} at a step of {:.6g} m; expected 2 to 100000", n, step));
  const Composite comp(lower, upper, o.angle, o.turn_over_upper);
  const std::size_t nl = o.loads.size();
  MapLoadedLift out;
  out.loads = o.loads;
  out.lines.resize(across.size());
  // Per line and load: the states at its offsets (for the diagnostics).
  std::vector<std::vector<std::vector<MapLoadedState>>> states(across.size());
  std::vector<std::vector<char>> first_pass(across.size());  // per line and offset: of the first pass
  std::vector<std::string> errors(across.size());
  std::mutex next_lock;
  std::size_t next = 0;
  const unsigned workers = util::thread_count(o.threads, across.size());
  util::run_workers(workers, [&](unsigned) {
    for (;;) {
      std::size_t li = 0;
      {
        std::lock_guard<std::mutex> lock(next_lock);
        if (next >= across.size()) return;
        li = next++;
      }
      MapLoadedLine& line = out.lines[li];
      line.across = across[li];
      line.curves.assign(nl, {});
      line.slopes.assign(nl, {});
      states[li].assign(nl, {});
      std::vector<std::vector<double>> starts(nl);
      // The line's solves in increasing u: the first pass's, with the midpoints refinement adds
      // before each of them.
      std::vector<std::vector<MapLoadedState>> solved;
      std::vector<char>& first = first_pass[li];
      // Halves [a, b] down to min_step: a solve at its middle, kept; both halves again where the
      // rigid contact moved to another node of the lower map between a and b (the correction has
      // a narrow feature there, where the load passes from one asperity to the next, that a solve
      // at the middle can miss), or where the elastic correction c = H_W - h at the middle misses
      // the line between a's and b's by more than refine_slope times half the interval at some
      // load (the interpolation's slope off by about that). The midpoints are appended in order
      // (b by the caller).
      auto refine = [&](auto& self, const std::vector<MapLoadedState>& a,
                        const std::vector<MapLoadedState>& b) -> Status {
        const double ua = a.front().along, ub = b.front().along, half = 0.5 * (ub - ua);
        if (half < min_step * (1 - 1e-9)) return Ok{};
        auto r = solve_offset(comp, ua + half, across[li], o, starts);
        if (!r) return r.error();
        if (r->empty()) return Ok{};  // (not inside the overlap's contiguous run)
        const std::vector<MapLoadedState> mid = std::move(*r);
        auto c = [](const MapLoadedState& s) { return s.loaded_lift - s.rigid_lift; };
        bool miss = a.front().highest_node != b.front().highest_node;
        for (std::size_t l = 0; l < nl; ++l)
          miss = miss || std::abs(c(mid[l]) - 0.5 * (c(a[l]) + c(b[l]))) > o.refine_slope * half;
        if (!miss) {
          solved.push_back(mid), first.push_back(0);
          return Ok{};
        }
        if (auto st = self(self, a, mid); !st) return st;
        solved.push_back(mid), first.push_back(0);
        return self(self, mid, b);
      };
      for (std::size_t k = 0; k < n; ++k) {
        const double u = along_min + double(k) * step;
        auto r = solve_offset(comp, u, across[li], o, starts);
        if (!r) {
          errors[li] = r.error().message;
          break;
        }
        if (r->empty()) {
          if (!solved.empty()) break;  // the overlap ends: the line's contiguous run is over
          continue;                    // not yet overlapping
        }
        std::vector<MapLoadedState> here = std::move(*r);
        if (!solved.empty() && o.refine_slope > 0) {
          const std::vector<MapLoadedState> prev = solved.back();
          if (auto st = refine(refine, prev, here); !st) {
            errors[li] = st.error().message;
            break;
          }
        }
        solved.push_back(std::move(here)), first.push_back(1);
      }
      for (const std::vector<MapLoadedState>& at : solved) {
        line.rigid.offset.push_back(at.front().along);
        line.rigid.lift.push_back(at.front().rigid_lift);
        for (std::size_t l = 0; l < nl; ++l) {
          const MapLoadedState& s = at[l];
          line.curves[l].offset.push_back(s.along);
          line.curves[l].lift.push_back(s.loaded_lift);
          line.slopes[l].push_back(s.effective_slope);
          states[li][l].push_back(s);
        }
      }
      if (errors[li].empty() && line.rigid.offset.size() < 2)
        errors[li] = fmt::format(
            "the line {:.6g} m across the direction: the maps overlap at fewer than 2 of its "
            "offsets in [{:.6g}, {:.6g}] m",
            across[li], along_min, along_max);
    }
  });
  for (const std::string& e : errors)
    if (!e.empty()) return make_error(e);
  out.diagnostics.resize(nl);
  for (std::size_t l = 0; l < nl; ++l) {
    MapLoadedDiagnostics& d = out.diagnostics[l];
    d.load = o.loads[l];
    // The means are over the first pass's offsets (evenly spaced; with the default step, on the
    // lower map's grid), as without refinement: its solves gather where the contact changes, and
    // off the grid the bilinear upper face's kinks inflate the contact slope. Every solve counts
    // for the largest contact fraction and the unconverged ones.
    double patches = 0, approach = 0, g2 = 0, fw = 0, full = 0, count = 0;
    for (std::size_t li = 0; li < states.size(); ++li)
      for (std::size_t k = 0; k < states[li][l].size(); ++k) {
        const MapLoadedState& s = states[li][l][k];
        d.max_contact_fraction = std::max(d.max_contact_fraction, s.contact_fraction);
        if (!s.converged) ++d.unconverged;
        ++out.solves;
        out.iterations += s.iterations;
        if (!first_pass[li][k]) continue;
        patches += double(s.patches), approach += s.approach, count += 1;
        g2 += s.load * s.contact_slope_rms * s.contact_slope_rms, fw += s.load;
        if (s.contact_fraction > kFullContact) full += 1;
      }
    d.mean_patches = count > 0 ? patches / count : 0;
    d.mean_approach = count > 0 ? approach / count : 0;
    d.rms_contact_slope = fw > 0 ? std::sqrt(g2 / fw) : 0;
    d.full_share = count > 0 ? full / count : 0;
  }
  return out;
}

}  // namespace frictal
