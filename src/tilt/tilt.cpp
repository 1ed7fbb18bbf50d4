// frictal — tilting-block friction test (paper Sec. IV) on the spheropolygon engine.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

#include <fmt/core.h>

#include "frictal/hold.hpp"
#include "frictal/signature.hpp"
#include "frictal/tilt.hpp"
#include "util/parallel.hpp"

namespace frictal {

namespace {

// Whether the upper block relaxes to rest (FIRE) before the loading starts: always with the
// quasi-static protocol, with the constant-rate one when settling = relax.
bool relaxed_settling(const TiltConfig& cfg) {
  return cfg.protocol == TiltProtocol::QuasiStatic || cfg.settling == TiltSettling::Relax;
}

using dem::Vec2;

struct Poly {
  std::vector<double> x, z;
};

// Copy without consecutive duplicate points; oriented left to right (first x < last x).
Result<Poly> clean_face(const Curve& c, const std::string& what) {
  if (c.x.size() != c.z.size() || c.x.size() < 2)
    return make_error(fmt::format("{}: expected at least two points with as many x as z", what));
  Poly p;
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (!std::isfinite(c.x[i]) || !std::isfinite(c.z[i]))
      return make_error(fmt::format("{}: point {} is not finite", what, i));
    if (!p.x.empty() && p.x.back() == c.x[i] && p.z.back() == c.z[i]) continue;
    p.x.push_back(c.x[i]);
    p.z.push_back(c.z[i]);
  }
  if (p.x.size() < 2 || p.x.front() == p.x.back())
    return make_error(fmt::format("{}: the surface must span a positive length in x", what));
  if (p.x.front() > p.x.back()) {
    std::reverse(p.x.begin(), p.x.end());
    std::reverse(p.z.begin(), p.z.end());
  }
  return p;
}

// Edges of a polyline sorted by their smallest x, for range queries along x.
struct EdgeIndex {
  std::vector<std::size_t> order;  // edge i runs from point i to i+1
  std::vector<double> xmin;        // sorted
  double max_width = 0;
  explicit EdgeIndex(const Poly& p) {
    const std::size_t n = p.x.size() - 1;
    order.resize(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = i;
    auto lo = [&](std::size_t i) { return std::min(p.x[i], p.x[i + 1]); };
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return lo(a) < lo(b) || (lo(a) == lo(b) && a < b); });
    xmin.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      xmin[k] = lo(order[k]);
      max_width = std::max(max_width, std::fabs(p.x[order[k] + 1] - p.x[order[k]]));
    }
  }
  // Calls f(edge) for every edge whose x-range may meet [x0, x1].
  template <class F>
  void query(double x0, double x1, F&& f) const {
    auto it = std::lower_bound(xmin.begin(), xmin.end(), x0 - max_width);
    for (std::size_t k = static_cast<std::size_t>(it - xmin.begin()); k < xmin.size() && xmin[k] <= x1; ++k)
      f(order[k]);
  }
};

// Smallest lift of `upper` (added to its z) so that along every vertical line each point of the
// upper face is at or above each point of the lower face: the first contact under a vertical
// drop. The extreme is reached at a vertex of one face over an edge of the other.
double vertical_contact_lift(const Poly& lower, const EdgeIndex& li, const Poly& upper, const EdgeIndex& ui) {
  double lift = -std::numeric_limits<double>::infinity();
  auto scan = [&](const Poly& pts, const Poly& other, const EdgeIndex& oi, double sign) {
    for (std::size_t v = 0; v < pts.x.size(); ++v) {
      const double x = pts.x[v];
      oi.query(x, x, [&](std::size_t e) {
        const double x0 = other.x[e], x1 = other.x[e + 1];
        if (x0 == x1 || x < std::min(x0, x1) || x > std::max(x0, x1)) return;
        const double z = other.z[e] + (other.z[e + 1] - other.z[e]) * ((x - x0) / (x1 - x0));
        // sign +1: pts are lower vertices, z on an upper edge; -1: the reverse.
        lift = std::max(lift, sign > 0 ? pts.z[v] - z : z - pts.z[v]);
      });
    }
  };
  scan(lower, upper, ui, +1);
  scan(upper, lower, li, -1);
  return lift;
}

// True if every vertex-edge distance between the faces (upper lifted by `lift`) is >= `clear`.
// Valid when the faces do not cross (lift >= the vertical contact lift).
bool faces_clear(const Poly& lower, const EdgeIndex& li, const Poly& upper, const EdgeIndex& ui, double lift,
                 double clear) {
  const double c2 = clear * clear;
  bool ok = true;
  auto scan = [&](const Poly& pts, double pz, const Poly& other, const EdgeIndex& oi, double oz) {
    for (std::size_t v = 0; v < pts.x.size() && ok; ++v) {
      const double px = pts.x[v], py = pts.z[v] + pz;
      oi.query(px - clear, px + clear, [&](std::size_t e) {
        const double ax = other.x[e], ay = other.z[e] + oz;
        const double dx = other.x[e + 1] - ax, dy = other.z[e + 1] + oz - ay;
        const double l2 = dx * dx + dy * dy;
        double t = l2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / l2 : 0.0;
        t = std::clamp(t, 0.0, 1.0);
        const double qx = px - ax - t * dx, qy = py - ay - t * dy;
        if (qx * qx + qy * qy < c2) ok = false;
      });
    }
  };
  scan(lower, 0.0, upper, ui, lift);
  scan(upper, lift, lower, li, 0.0);
  return ok;
}

// Shortest edge of a face (unit: m).
double shortest_edge(const Poly& p) {
  double s = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < p.x.size(); ++i)
    s = std::min(s, std::hypot(p.x[i + 1] - p.x[i], p.z[i + 1] - p.z[i]));
  return s;
}

// Shortest run of a face between neighbouring local extrema of z (path length, unit: m), the
// flank of the smallest feature, and the smallest height difference of such a run (unit: m;
// not reported: flat steps of generated faces make it unreliable).
// Flat edges continue a run; the partial runs at the two ends count only if there is no
// complete one.
std::pair<double, double> smallest_feature(const Poly& p) {
  const double inf = std::numeric_limits<double>::infinity();
  double best = inf, best_h = inf, run = 0, first = -1, first_h = 0, z0 = p.z.front();
  int dir = 0;  // sign of dz of the current run
  const auto [zlo, zhi] = std::minmax_element(p.z.begin(), p.z.end());
  const double flat = 1e-9 * (*zhi - *zlo);  // rounding of generated faces is flat
  for (std::size_t i = 0; i + 1 < p.x.size(); ++i) {
    const double dz = p.z[i + 1] - p.z[i];
    const int d = dz > flat ? 1 : (dz < -flat ? -1 : 0);
    if (d != 0 && dir != 0 && d != dir) {  // an extremum at vertex i
      const double h = std::fabs(p.z[i] - z0);
      if (first < 0) {
        first = run;
        first_h = h;
      } else {
        best = std::min(best, run);
        best_h = std::min(best_h, h);
      }
      run = 0;
      z0 = p.z[i];
    }
    if (d != 0) dir = d;
    run += std::hypot(p.x[i + 1] - p.x[i], dz);
  }
  if (std::isfinite(best)) return {best, best_h};
  const double last_h = std::fabs(p.z.back() - z0);
  if (first < 0) return {run, last_h};
  return {std::min(first, run), std::min(first_h, last_h)};
}

Status check_config(const TiltConfig& c) {
  auto pos = [](double v) { return std::isfinite(v) && v > 0; };
  if (!pos(c.block_height)) return make_error(fmt::format("tilt block_height = {} m: expected > 0", c.block_height));
  if (!pos(c.radius)) return make_error(fmt::format("tilt radius = {} m: expected > 0", c.radius));
  if (!pos(c.density)) return make_error(fmt::format("tilt density = {} kg/m^2: expected > 0", c.density));
  if (!(std::isfinite(c.gravity) && c.gravity >= 0)) return make_error("tilt gravity: expected >= 0 m/s^2");
  if (!pos(c.tilt_rate)) return make_error(fmt::format("tilt tilt_rate = {} rad/s: expected > 0", c.tilt_rate));
  if (!pos(c.time_step)) return make_error(fmt::format("tilt time_step = {} s: expected > 0", c.time_step));
  if (!(c.time_step_safety > 0 && c.time_step_safety <= 1))
    return make_error(fmt::format("tilt time_step_safety = {}: expected a value in (0, 1]", c.time_step_safety));
  if (!(std::isfinite(c.settle_time) && c.settle_time >= 0)) return make_error("tilt settle_time: expected >= 0 s");
  if (!(c.max_tilt > 0 && c.max_tilt < 1.5707963267948966))
    return make_error("tilt max_tilt: expected in (0, 90) degrees");
  if (!pos(c.runaway_distance))
    return make_error(fmt::format("tilt runaway_distance = {} m: expected > 0", c.runaway_distance));
  for (double d : c.runaway_checkpoints)
    if (!(std::isfinite(d) && d > 0 && d <= c.runaway_distance))
      return make_error(
          fmt::format("tilt runaway_checkpoints: {} m: expected a distance in (0, runaway_distance = {} m]", d,
                      c.runaway_distance));
  if (c.contact.law == dem::ContactLaw::Hertz) {
    if (!pos(c.modulus))
      return make_error(
          fmt::format("tilt block_modulus = {} Pa: expected Young's modulus > 0 with contact_law hertz "
                      "(e.g. --block-modulus 7e10 for 70 GPa)",
                      c.modulus));
    if (!(c.poisson > -1 && c.poisson <= 0.5))
      return make_error(fmt::format("tilt block_poisson = {}: expected a Poisson ratio in (-1, 0.5]", c.poisson));
    if (c.elastic_blocks != 1 && c.elastic_blocks != 2)
      return make_error(fmt::format("tilt elastic_blocks = {}: expected 1 or 2", c.elastic_blocks));
  }
  if (!(std::isfinite(c.restitution) && c.restitution <= 1))
    return make_error(fmt::format("tilt restitution = {}: expected <= 1 (0 or less: use gamma_n)", c.restitution));
  if (!pos(c.stick_speed)) return make_error(fmt::format("tilt stick_speed = {} m/s: expected > 0", c.stick_speed));
  if (!(std::isfinite(c.stick_duration) && c.stick_duration >= 0))
    return make_error("tilt stick_duration: expected >= 0 s");
  if (!(std::isfinite(c.placement_gap) && c.placement_gap >= 0))
    return make_error("tilt placement_gap: expected >= 0 m");
  if (c.protocol == TiltProtocol::QuasiStatic && !(pos(c.tilt_increment) && c.tilt_increment < c.max_tilt))
    return make_error(fmt::format("tilt tilt_increment = {} rad: expected > 0 and below max_tilt = {} rad",
                                  c.tilt_increment, c.max_tilt));
  if (c.protocol == TiltProtocol::QuasiStatic || c.settling == TiltSettling::Relax) {
    if (!pos(c.relax_time)) return make_error(fmt::format("tilt relax_time = {} s: expected > 0", c.relax_time));
    if (!pos(c.relax_force)) return make_error(fmt::format("tilt relax_force = {}: expected > 0", c.relax_force));
    if (!pos(c.relax_speed)) return make_error(fmt::format("tilt relax_speed = {} m/s: expected > 0", c.relax_speed));
    if (!(std::isfinite(c.relax_duration) && c.relax_duration >= 0 && c.relax_duration < c.relax_time))
      return make_error(fmt::format("tilt relax_duration = {} s: expected >= 0 and below relax_time = {} s",
                                    c.relax_duration, c.relax_time));
  }
  if (!std::isnan(c.initial_offset) && !std::isfinite(c.initial_offset))
    return make_error("tilt initial_offset: expected a finite value or NaN (auto)");
  return Ok{};
}

}  // namespace

TiltConfig default_tilt_config() { return TiltConfig{}; }

namespace {

// ---- Phase 1: the faces (tilt.hpp header comment).
struct Faces {
  Poly lower;         // lower face as measured
  Poly upper;         // upper face rotated by 180 degrees, before the offset
  Profile lower_env;  // envelopes (for the signature and face = envelope)
  Profile upper_env;
  bool has_env = false;
  // The stated test (TiltConfig::spread_offset_max > 0) on profiles: the surfaces as given, which
  // the model's spread over drops reads as predict() reads them (the envelopes may drop points).
  std::optional<Profile> lower_profile, upper_profile;
};

Result<Faces> build_faces(const Curve& lower_surface, const Curve& upper_surface, const TiltConfig& cfg) {
  Faces f;
  // Faces: the full curves, or their upper envelopes.
  Curve lower_c = lower_surface, upper_c = upper_surface;
  f.has_env = cfg.face == TiltFace::Envelope || cfg.predict;
  if (f.has_env) {
    auto le = upper_envelope(lower_surface);
    if (!le.ok()) return with_prefix("lower surface: ", le.error());
    auto ue = upper_envelope(upper_surface);
    if (!ue.ok()) return with_prefix("upper surface: ", ue.error());
    f.lower_env = std::move(*le);
    f.upper_env = std::move(*ue);
    if (cfg.face == TiltFace::Envelope) {
      lower_c = as_curve(f.lower_env);
      upper_c = as_curve(f.upper_env);
    }
  }
  auto lower_r = clean_face(lower_c, "lower surface");
  if (!lower_r.ok()) return lower_r.error();
  auto upper_r = clean_face(rotate180(upper_c), "upper surface");
  if (!upper_r.ok()) return upper_r.error();
  f.lower = std::move(*lower_r);
  f.upper = std::move(*upper_r);
  if (cfg.spread_offset_max > 0 && cfg.predict) {
    auto lp = as_profile(lower_surface, "lower surface");
    auto up = as_profile(upper_surface, "upper surface");
    if (lp.ok() && up.ok()) f.lower_profile = std::move(*lp), f.upper_profile = std::move(*up);
  }
  // Offsets count as the signature counts them, from the left ends aligned: a block whose x starts
  // elsewhere than the lower surface's (a piece cut from the middle of a scan, a second file) is
  // moved there (no move where both start together, as a surface on itself).
  const double shift =
      *std::min_element(f.lower.x.begin(), f.lower.x.end()) - *std::min_element(f.upper.x.begin(), f.upper.x.end());
  if (shift != 0)
    for (double& x : f.upper.x) x += shift;
  return f;
}

// ---- Phase 2: the predictions before the run (theta_max of the rigid and the rounded
// blocks) and the initial offset (least lift unless given). Returns the offset.
Result<double> predict_theta_max(Faces& f, const TiltConfig& cfg, unsigned threads, TiltResult& res) {
  double offset = std::isnan(cfg.initial_offset) ? 0.0 : cfg.initial_offset;
  if (!cfg.predict) return offset;
  SignatureOptions opt;
  opt.keep_contacts = false;
  opt.threads = 1;
  if (cfg.period > 0) {
    opt.offset_min = 0;
    opt.offset_max = cfg.period;
    f.lower_env.period.reset();
  }
  // The stated test: the offsets at which the block lies wholly over the lower surface.
  if (cfg.spread_offset_max > 0) {
    opt.offset_min = 0;
    opt.offset_max = cfg.spread_offset_max;
  }
  // The simulated blocks: one core against the other dilated by 2r (docs/dem.md sec. 6).
  SignatureOptions so = opt;
  so.spheroradius = cfg.radius;
  // With several threads the two predictions run side by side, each on half of them (the
  // signature does not depend on its thread count).
  const Profile upper_face = rotate180(f.upper_env);
  std::optional<Result<SignatureResult>> sig_r, sph_r;
  if (threads >= 2) {
    opt.threads = threads / 2;
    so.threads = threads - threads / 2;
    util::run_workers(
        1, [&](unsigned) { sph_r.emplace(signature(f.lower_env, upper_face, so)); },
        [&] { sig_r.emplace(signature(f.lower_env, upper_face, opt)); });
  } else {
    sig_r.emplace(signature(f.lower_env, upper_face, opt));
    if (*sig_r) sph_r.emplace(signature(f.lower_env, upper_face, so));
  }
  const Result<SignatureResult>& sig = *sig_r;
  if (!sig.ok()) return with_prefix("signature for the prediction: ", sig.error());
  res.predicted_theta_max = cfg.reverse ? sig->theta_max_backward : sig->theta_max_forward;
  res.predicted_friction_angle =
      std::min(res.predicted_theta_max + std::atan(cfg.contact.atomic_friction), 1.5707963267948966);
  const Result<SignatureResult>& sph = *sph_r;
  if (!sph.ok()) return with_prefix("spheropolygon signature for the prediction: ", sph.error());
  res.predicted_sphero_theta_max = cfg.reverse ? sph->theta_max_backward : sph->theta_max_forward;
  res.predicted_sphero_friction_angle =
      std::min(res.predicted_sphero_theta_max + std::atan(cfg.contact.atomic_friction), 1.5707963267948966);
  if (std::isnan(cfg.initial_offset) && !sig->lift.empty()) {
    const auto it = std::min_element(sig->lift.begin(), sig->lift.end());
    offset = sig->offset[static_cast<std::size_t>(it - sig->lift.begin())];
  }
  return offset;
}

// ---- Phase 6: the hold-angle predictions (hold.hpp) from where the block rests when the loading
// starts: the exact lift of the finite blocks from d behind the rest to the end of their overlap
// in the sliding direction (hold_lift_range), rigid profiles
// and the run's spheroradius, in the sliding direction. A failure leaves NaN and says why.
// These model this run (the bracket of tilt_validity), so they read the lift as far as the
// simulated blocks overlap: a run dropped inside the stated test's drop range can still be
// carried past the offsets where the block lies wholly over the lower surface before it runs
// away, and the simulation then feels the partial overlap. The spread over drops below is the
// stated test's (the lift cut to those offsets), as predict() reads it.
void predict_hold_angles(const Faces& f, const TiltConfig& cfg, TiltResult& res) {
  if (!cfg.predict || !f.has_env) return;
  const double s = res.rest_offset, d = cfg.runaway_distance;
  Profile lower = f.lower_env;
  lower.period.reset();  // the simulated blocks are finite
  const Profile upper_face = rotate180(f.upper_env);
  // The chain of short slips may carry the block well past rest + d before the run-away (the
  // measured Dektak pair: its holding stop lies 9.3 mm ahead of the rest with d = 1 cm): the lift
  // runs from d behind the rest to 2d ahead, and twice as far again while the run-away leaves a
  // stop less than d before the cut end (or the rest lies that close), up to the end of the
  // blocks' overlap. (A K3 block's lift over the whole overlap cost 8 s; most runs need 3d.)
  const OffsetRange full =
      hold_lift_range(s, s, lower.length() + upper_face.length(), lower.length(), upper_face.length());
  HoldOptions ho;
  ho.runaway_distance = d;
  ho.atomic_friction = cfg.contact.atomic_friction;
  auto hold = [&](double radius) -> Result<HoldAngle> {
    SignatureOptions so;
    so.keep_contacts = false;
    so.threads = 1;
    so.spheroradius = radius;
    for (double margin = 2 * d;; margin *= 2) {
      OffsetRange range = full;
      if (cfg.reverse) {
        range.max = std::min(full.max, s + d);
        range.min = std::max(full.min, s - margin);
      } else {
        range.min = std::max(full.min, s - d);
        range.max = std::min(full.max, s + margin);
      }
      so.offset_min = range.min;
      so.offset_max = range.max;
      auto sig = signature(lower, upper_face, so);
      if (!sig.ok()) return with_prefix("signature: ", sig.error());
      auto curve = lift_curve(*sig);
      if (!curve.ok()) return with_prefix("lift curve: ", curve.error());
      auto h = hold_angle(*curve, s, ho);
      if (!h.ok()) return h.error();
      const HoldAngle a = cfg.reverse ? h->backward : h->forward;
      const bool cut = cfg.reverse ? range.min > full.min : range.max < full.max;
      const double room = cfg.reverse ? a.hold_offset - range.min : range.max - a.hold_offset;
      const double rest_room = cfg.reverse ? a.rest_offset - range.min : range.max - a.rest_offset;
      if (!cut || ((!a.ran_off_end || room >= d) && rest_room >= d)) return a;
    }
  };
  auto rigid = hold(0);
  if (!rigid.ok()) {
    res.hold_error = "rigid profiles: " + rigid.error().message;
    return;
  }
  res.predicted_hold_angle = rigid->hold_angle;
  res.predicted_hold_offset = rigid->hold_offset;
  res.predicted_inertial_hold_angle = rigid->inertial_hold_angle;
  // The rigid model over drops for this test: where a single run's drop lies in it. The stated
  // test (spread_offset_max > 0): the lift where the block lies wholly over the lower surface, cut
  // there, and the stated drops over it, as predict() reads them.
  {
    SignatureOptions so;
    so.keep_contacts = false;
    so.threads = 1;
    const bool stated = cfg.spread_offset_max > 0;
    if (stated) {
      so.offset_min = 0;
      so.offset_max = cfg.spread_offset_max;
    }
    Result<HoldDistributions> dist = make_error("no lift");
    if (stated && f.lower_profile) {
      // As predict(): one signature_with_hold pass over the profiles, the lift cut to the offsets.
      auto both = signature_with_hold(*f.lower_profile, rotate180(*f.upper_profile), so, ho);
      if (both.ok()) {
        HoldOptions hk = ho;
        hk.drop_min = cfg.spread_drop_min;
        hk.drop_max = cfg.spread_drop_max;
        dist = hold_distribution(cut_lift_curve(both->hold.curve, so.offset_min, so.offset_max), hk);
      } else {
        dist = both.error();
      }
    } else {
      auto spread = analyse_hold(lower, upper_face, so, ho);
      if (spread.ok() && stated) {
        HoldOptions hk = ho;
        hk.drop_min = cfg.spread_drop_min;
        hk.drop_max = cfg.spread_drop_max;
        dist = hold_distribution(cut_lift_curve(spread->curve, so.offset_min, so.offset_max), hk);
      } else if (spread.ok()) {
        dist = spread->distribution;
      } else {
        dist = spread.error();
      }
    }
    if (dist.ok()) {
      const HoldStatistics& q = (cfg.reverse ? dist->backward : dist->forward).hold;
      res.predicted_spread_q05 = q.q05;
      res.predicted_spread_q50 = q.q50;
      res.predicted_spread_q95 = q.q95;
    } else {
      res.spread_error = dist.error().message;
    }
  }
  auto sphero = hold(cfg.radius);
  if (!sphero.ok()) {
    res.hold_error = "spheropolygons: " + sphero.error().message;
    return;
  }
  res.predicted_sphero_hold_angle = sphero->hold_angle;
}

// ---- Phase 3: placement. Shifts the upper face by `offset`, lowers it to `placement_gap`
// above contact, builds both blocks and the model, and fills the result's masses, polygons and
// scales.
Result<dem::Model> place_blocks(const Poly& lower, Poly upper, double offset, const TiltConfig& cfg, TiltResult& res) {
  res.initial_offset = offset;
  for (double& x : upper.x) x += offset;

  // Vertical placement: first contact under a vertical drop, then raised (bisection) until the
  // two spheropolygons are `placement_gap` apart.
  const EdgeIndex li(lower), ui(upper);
  const double lift0 = vertical_contact_lift(lower, li, upper, ui);
  const double clear = 2 * cfg.radius + cfg.placement_gap;
  double lo = lift0, hi = lift0 + clear;
  while (!faces_clear(lower, li, upper, ui, hi, clear)) hi = lo + 2 * (hi - lo);
  for (int i = 0; i < 60 && hi - lo > 1e-3 * clear; ++i) {
    const double mid = 0.5 * (lo + hi);
    (faces_clear(lower, li, upper, ui, mid, clear) ? hi : lo) = mid;
  }
  for (double& z : upper.z) z += hi;

  // Block polygons.
  const double lmin = *std::min_element(lower.z.begin(), lower.z.end());
  const double umax = *std::max_element(upper.z.begin(), upper.z.end());
  dem::BodyDef lb, ub;
  lb.x = lower.x;
  lb.y = lower.z;
  lb.x.push_back(lower.x.back());
  lb.y.push_back(lmin - cfg.block_height);
  lb.x.push_back(lower.x.front());
  lb.y.push_back(lmin - cfg.block_height);
  ub.x = upper.x;
  ub.y = upper.z;
  ub.x.push_back(upper.x.back());
  ub.y.push_back(umax + cfg.block_height);
  ub.x.push_back(upper.x.front());
  ub.y.push_back(umax + cfg.block_height);
  for (dem::BodyDef* b : {&lb, &ub}) {
    b->radius = cfg.radius;
    b->density = cfg.density;
  }
  lb.type = dem::BodyType::Kinematic;
  if (cfg.hold_rotation) ub.rotation_follows = 0;
  // The quasi-static protocol keeps the lower block still and turns gravity instead.
  if (cfg.protocol == TiltProtocol::ConstantRate && cfg.turn == TiltTurn::Block)
    lb.motion.angular_velocity = cfg.reverse ? cfg.tilt_rate : -cfg.tilt_rate;
  // With a relaxed settling the lower block starts turning when the relaxation ends (set then).
  lb.motion.start_time = relaxed_settling(cfg) ? std::numeric_limits<double>::max() : cfg.settle_time;
  dem::WorldDef wd;
  wd.gravity = {0, -cfg.gravity};
  wd.time_step = cfg.time_step;
  wd.adaptive_time_step = cfg.adaptive_time_step;
  wd.time_step_safety = cfg.time_step_safety;
  wd.implicit_damping = cfg.implicit_damping;
  wd.skin = cfg.skin;
  wd.max_steps_beyond_limit = cfg.max_steps_beyond_limit;
  wd.contact = cfg.contact;
  wd.contact.rule = tilt_contact_rule(cfg);
  if (cfg.contact.law == dem::ContactLaw::Hertz) {
    wd.contact.contact_modulus = cfg.modulus / ((1 - cfg.poisson * cfg.poisson) * cfg.elastic_blocks);
    wd.contact.tangential_ratio = 2 * (1 - cfg.poisson) / (2 - cfg.poisson);
    res.contact_modulus = wd.contact.contact_modulus;
  }
  res.contact_rule = wd.contact.rule;
  auto model_r = dem::make_model(wd, {lb, ub});
  if (!model_r.ok()) {
    std::string msg = model_r.error().message;
    if (msg.rfind("body 0", 0) == 0)
      msg = "lower block " + msg.substr(7);
    else if (msg.rfind("body 1", 0) == 0)
      msg = "upper block " + msg.substr(7);
    return make_error(
        model_r.error().code,
        "tilt: " + msg + (cfg.face == TiltFace::Curve ? " (a folded surface may need face = envelope)" : ""));
  }
  dem::Model model = std::move(*model_r);
  // Quasi-static: FIRE dissipates; the tangential dashpot (-m gamma_t v_t per contact, not
  // capped by mu_a) would turn every slip into a creep at a / (N_c gamma_t) ~ 1e-3 m/s and does
  // not change where a block comes to rest (docs/dem.md sec. 4).
  if (cfg.protocol == TiltProtocol::QuasiStatic) model.def.contact.tangential_damping = 0;
  model.motion[0].pivot = model.initial_position[0];  // turn about the lower block's centroid
  if (cfg.restitution > 0 && cfg.contact.law == dem::ContactLaw::Hertz) {
    auto z = dem::hertz_damping_ratio(cfg.restitution);
    if (!z.ok()) return with_prefix("tilt restitution: ", z.error());
    model.def.contact.damping_ratio = *z;
  } else if (cfg.restitution > 0) {
    auto g = dem::damping_from_restitution(cfg.restitution, cfg.contact.normal_stiffness, model.mass[1]);
    if (!g.ok()) return with_prefix("tilt restitution: ", g.error());
    model.def.contact.normal_damping = *g;
  }
  res.normal_damping = model.def.contact.normal_damping;
  res.lower_mass = model.mass[0];
  res.upper_mass = model.mass[1];
  res.lower_vertices = model.vertex_count(0);
  res.upper_vertices = model.vertex_count(1);
  res.lower_polygon_x.assign(model.local_x.begin(), model.local_x.begin() + model.vertex_begin[1]);
  res.lower_polygon_y.assign(model.local_y.begin(), model.local_y.begin() + model.vertex_begin[1]);
  res.upper_polygon_x.assign(model.local_x.begin() + model.vertex_begin[1], model.local_x.end());
  res.upper_polygon_y.assign(model.local_y.begin() + model.vertex_begin[1], model.local_y.end());
  // Scales (the warnings they give come from tilt_scale_warnings).
  TiltScales& sc = res.scales;
  sc.resting_overlap = model.mass[1] * cfg.gravity / cfg.contact.normal_stiffness;
  double k_rest = cfg.contact.normal_stiffness;
  if (cfg.contact.law == dem::ContactLaw::Hertz) {
    const double r_min = *std::min_element(model.curvature_radius.begin(), model.curvature_radius.end());
    sc.resting_overlap = dem::hertz_overlap(model.mass[1] * cfg.gravity, model.def.contact.contact_modulus, r_min);
    k_rest = dem::contact_stiffness(model, 1);
  }
  sc.spheroradius = cfg.radius;
  sc.shortest_edge[0] = shortest_edge(lower);
  sc.shortest_edge[1] = shortest_edge(upper);
  sc.smallest_feature[0] = smallest_feature(lower).first;
  sc.smallest_feature[1] = smallest_feature(upper).first;
  sc.time_step = cfg.time_step;
  sc.contact_period = 2 * std::numbers::pi * std::sqrt(model.mass[1] / k_rest);
  return model;
}

// FIRE constants (Bitzek et al. 2006, Table I of the paper; LAMMPS min_style fire): the mixing
// parameter starts at alpha_start and shrinks by f_alpha per step after N_min steps of P > 0.
// The step is the engine's own (adaptive, at the stability limit): FIRE's step growth is not used.
constexpr double kFireAlphaStart = 0.1;
constexpr double kFireAlphaShrink = 0.99;
constexpr int kFireMinSteps = 5;

// ---- The run: the state and the measurements, output and bookkeeping that every phase
// shares; one member function per phase (settling, each loading protocol with its detection).
// The stick/run-away rule of both protocols: with the block at displacement d and its last stop
// (or stick) at `from` (tilt, time, rotation so far), each checkpoint distance reached for the
// first time records that stop, and a slip of runaway_distance sets the friction angle. Returns
// whether the run ran away.
bool mark_runaway(TiltResult& res, std::size_t& checkpoints_left, double d, double from, double tilt, double time,
                  double rotation, double runaway_distance) {
  if (checkpoints_left)
    for (TiltCheckpoint& k : res.checkpoints)
      if (!k.reached && d - from >= k.distance) {
        k.reached = true;
        k.friction_angle = tilt;
        k.slide_time = time;
        k.slide_start_displacement = from;
        --checkpoints_left;
      }
  if (d - from < runaway_distance) return false;
  res.slid = true;
  res.rotation_before_slide = rotation;
  res.friction_angle = tilt;
  res.slide_time = time;
  res.slide_start_displacement = from;
  return true;
}

class TiltRun {
 public:
  TiltRun(const TiltConfig& cfg, dem::Model& model, TiltResult& res, unsigned threads)
      : run_start_(std::chrono::steady_clock::now()),
        cfg_(cfg),
        model_(model),
        res_(res),
        st_(dem::make_state(model)),
        step_threads_(threads),
        dt_(cfg.time_step),
        adaptive_(cfg.adaptive_time_step),
        sgn_(cfg.reverse ? -1.0 : 1.0),
        quasi_(cfg.protocol == TiltProtocol::QuasiStatic),
        gravity_turns_(quasi_ || cfg.turn == TiltTurn::Gravity) {
    dem::set_thread_count(st_, step_threads_);
    budget();
    progress_every_ = std::max<std::uint64_t>(1, cfg.progress_interval);
    // Fixed step: the schedule in steps. Adaptive step: in time (the same instants up to one step).
    settle_steps_ = static_cast<std::uint64_t>(std::ceil(cfg.settle_time / dt_ - 1e-9));
    series_every_ =
        cfg.series_interval > 0
            ? std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(cfg.series_interval / dt_)))
            : 0;
    frame_every_ = cfg.frame_interval > 0
                       ? std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(cfg.frame_interval / dt_)))
                       : 0;
    max_steps_ = settle_steps_ + static_cast<std::uint64_t>(std::ceil(cfg.max_tilt / cfg.tilt_rate / dt_)) + 1;
    eps_t_ = 1e-9 * dt_;
    max_time_ = cfg.settle_time + cfg.max_tilt / cfg.tilt_rate + dt_;
    next_series_ = cfg.series_interval;
    next_frame_ = cfg.frame_interval;
    // Displacements during settling are relative to the initial placement.
    d_ref_ = measure().d;
    if (frame_every_) frame();
  }

  Status settle();
  Status load_constant_rate();
  Status load_quasi_static();
  /// Relative displacement along x during settling (unit: m), signed in the sliding direction.
  double settle_displacement() const { return settle_d_; }
  void finish();
  /// Pairs in the neighbour list now (the cost of a step).
  std::size_t list_pairs() const { return st_.pairs.size(); }

 private:
  struct Measure {
    double d, v, fn, ft, tilt;
  };
  enum class Relax { Rest, Runaway, OutOfTime };

  // Threads of the contact passes (results do not depend on them): cfg.threads, or what the
  // budget grants, asked again every 4096 steps.
  void budget() {
    if (!cfg_.thread_budget) return;
    step_threads_ = std::max(1u, cfg_.thread_budget(step_threads_));
    dem::set_thread_count(st_, step_threads_);
  }
  bool series_due() {
    if (!series_every_) return false;
    if (!adaptive_) return st_.steps % series_every_ == 0;
    if (st_.time + eps_t_ < next_series_) return false;
    while (next_series_ <= st_.time + eps_t_) next_series_ += cfg_.series_interval;
    return true;
  }
  bool frame_due() {
    if (!frame_every_) return false;
    if (!adaptive_) return st_.steps % frame_every_ == 0;
    if (st_.time + eps_t_ < next_frame_) return false;
    while (next_frame_ <= st_.time + eps_t_) next_frame_ += cfg_.frame_interval;
    return true;
  }
  bool settling(std::uint64_t i) const { return adaptive_ ? st_.time + eps_t_ < cfg_.settle_time : i < settle_steps_; }
  bool running() const { return adaptive_ ? st_.time < max_time_ : st_.steps < max_steps_; }

  // d: relative displacement along the lower block's x axis in its frame, signed in the sliding
  // direction; v its rate; F_n, F_t the contact force on the upper block in that frame; the tilt.
  Measure measure() const {
    Measure m;
    const double a = st_.angle[0];
    const double ex = std::cos(a), ey = std::sin(a);  // lower block's x axis
    const double rx = st_.position[1].x - st_.position[0].x, ry = st_.position[1].y - st_.position[0].y;
    const double w = st_.angular_velocity[0];
    const double vx = st_.velocity[1].x - st_.velocity[0].x, vy = st_.velocity[1].y - st_.velocity[0].y;
    m.d = sgn_ * (rx * ex + ry * ey) - d_ref_;
    m.v = sgn_ * ((vx * ex + vy * ey) + w * (-rx * ey + ry * ex));
    const dem::Vec2 f = st_.force[1];
    m.ft = -sgn_ * (f.x * ex + f.y * ey);
    m.fn = -f.x * ey + f.y * ex;
    m.tilt = gravity_turns_ ? tilt_ : std::fabs(a);
    return m;
  }
  void record() {
    const Measure m = measure();
    TiltSeries& s = res_.series;
    s.time.push_back(st_.time);
    s.tilt.push_back(m.tilt);
    s.normal_force.push_back(m.fn);
    s.tangential_force.push_back(m.ft);
    s.force_angle.push_back(std::atan2(m.ft, m.fn));
    s.displacement.push_back(m.d);
    s.velocity.push_back(m.v);
    s.contacts.push_back(st_.contact_count);
  }
  void frame() {
    TiltFrame f;
    f.time = st_.time;
    f.tilt = std::fabs(st_.angle[0]);
    for (int b = 0; b < 2; ++b) {
      f.position[b] = st_.position[b];
      f.angle[b] = st_.angle[b];
    }
    const Measure m = measure();
    f.normal_force = m.fn;
    f.tangential_force = m.ft;
    f.contacts = dem::contact_forces(model_, st_);
    if (gravity_turns_) {  // show the lower block turned by the tilt about its pivot (gravity turned instead)
      f.tilt = tilt_;
      const double a = -sgn_ * tilt_, c = std::cos(a), s = std::sin(a);
      const dem::Vec2 p = model_.motion[0].pivot;
      auto turn = [&](dem::Vec2 q) {
        return dem::Vec2{p.x + c * (q.x - p.x) - s * (q.y - p.y), p.y + s * (q.x - p.x) + c * (q.y - p.y)};
      };
      for (int b = 0; b < 2; ++b) {
        f.position[b] = turn(f.position[b]);
        f.angle[b] += a;
      }
      for (dem::ContactForce& k : f.contacts) {
        k.point = turn(k.point);
        k.normal = {c * k.normal.x - s * k.normal.y, s * k.normal.x + c * k.normal.y};
      }
    }
    res_.frames.push_back(std::move(f));
  }
  Status advance_one() {
    if (cfg_.thread_budget && (st_.steps & 4095u) == 4095u) budget();
    last_dt_ = adaptive_ ? st_.time_step : dt_;  // the step that dem::step takes
    Status s = dem::step(model_, st_);
    min_dt_ = std::min(min_dt_, last_dt_);
    max_dt_ = std::max(max_dt_, last_dt_);
    if (cfg_.progress && st_.steps % progress_every_ == 0) report_progress();
    return s;
  }
  void report_progress() {
    const Measure m = measure();
    TiltProgress p;
    p.steps = st_.steps;
    p.time = st_.time;
    p.tilt = m.tilt;
    p.displacement = m.d;
    p.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start_).count();
    p.estimate = &res_.estimate;
    cfg_.progress(p);
  }
  // Sliding speed of the upper block along the lower block's x axis, from the translational
  // velocities only; taken at the start of the last settling step, before the lower block's
  // rotation (which begins at settle_time) reaches the upper block through the contacts.
  double sliding_speed() const {
    const double a = st_.angle[0];
    return std::fabs((st_.velocity[1].x - st_.velocity[0].x) * std::cos(a) +
                     (st_.velocity[1].y - st_.velocity[0].y) * std::sin(a));
  }
  void set_tilt(double tilt) {  // gravity turned by the tilt in the lower block's frame
    tilt_ = tilt;
    model_.def.gravity = {sgn_ * cfg_.gravity * std::sin(tilt), -cfg_.gravity * std::cos(tilt)};
  }
  Result<Relax> relax(double budget, bool watch_runaway);
  void record_runaway(double d);

  const std::chrono::steady_clock::time_point run_start_;
  const TiltConfig& cfg_;
  dem::Model& model_;
  TiltResult& res_;
  dem::State st_;
  unsigned step_threads_;
  const double dt_;  // fixed step, or the largest adaptive step
  const bool adaptive_;
  const double sgn_;
  const bool quasi_;
  const bool gravity_turns_;  // quasi-static, or constant rate with turn = gravity
  std::uint64_t settle_steps_ = 0, series_every_ = 0, frame_every_ = 0, max_steps_ = 0;
  std::uint64_t progress_every_ = 4096;
  double min_dt_ = std::numeric_limits<double>::infinity(), max_dt_ = 0, last_dt_ = 0;  // steps taken
  double eps_t_ = 0;  // time comparisons of the adaptive schedule
  double max_time_ = 0, next_series_ = 0, next_frame_ = 0;
  double d_ref_ = 0, settle_d_ = 0;
  double tilt_ = 0;  // quasi-static: the tilt of the current increment
  // Quasi-static: the last relaxed stop (displacement, tilt, time) and the rotation until then.
  double stop_d_ = 0, stop_tilt_ = 0, stop_time_ = 0, max_rot_ = 0, rot0_ = 0, rot_at_stop_ = 0;
  std::size_t checkpoints_left_ = 0;
};

// ---- Phase 4: settling. Constant rate: free settling for settle_time (settling = free, the
// paper's). Quasi-static, or settling = relax: a relaxation at zero tilt (at most relax_time);
// the constant-rate tilt then starts at once.
Status TiltRun::settle() {
  if (relaxed_settling(cfg_)) {
    if (quasi_) set_tilt(0);
    auto r = relax(cfg_.relax_time, false);
    if (!r.ok()) return with_prefix("tilt (settling): ", r.error());
    res_.settled_speed = std::fabs(st_.velocity[1].x - st_.velocity[0].x);
    if (*r != Relax::Rest)
      res_.warnings.push_back(
          {"unsettled",
           fmt::format("the upper block did not relax to rest at zero tilt within relax_time = {:.3g} s (speed "
                       "{:.3g} m/s, thresholds relax_force = {:.3g} of its weight, relax_speed = {:.3g} m/s): it is "
                       "not at rest where the prediction starts; raise relax_time",
                       cfg_.relax_time, res_.settled_speed, cfg_.relax_force, cfg_.relax_speed)});
    if (!quasi_) {  // the lower block turns from now on; the budget of the tilt counts from here
      model_.motion[0].start_time = st_.time;
      max_time_ = st_.time + cfg_.max_tilt / cfg_.tilt_rate + dt_;
      max_steps_ = st_.steps + static_cast<std::uint64_t>(std::ceil(cfg_.max_tilt / cfg_.tilt_rate / dt_)) + 1;
    }
  } else {
    for (std::uint64_t i = 0; settling(i); ++i) {
      res_.settled_speed = sliding_speed();
      if (Status s = advance_one(); !s.ok()) return with_prefix("tilt (settling): ", s.error());
      if (series_due()) record();
      if (frame_due()) frame();
    }
  }
  res_.settled_overlap = st_.max_overlap;
  res_.settled_contacts = st_.contact_count;
  if (model_.def.contact.law == dem::ContactLaw::Hertz) {
    double sum = 0;
    int n = 0;
    for (const dem::ContactForce& c : dem::contact_forces(model_, st_)) {
      sum += c.overlap / c.curvature_radius;
      ++n;
    }
    res_.settled_interference_ratio = n > 0 ? sum / n : std::numeric_limits<double>::quiet_NaN();
  }
  // From here on, relative to the settled position.
  settle_d_ = measure().d;
  d_ref_ += settle_d_;
  // The prediction starts from rest at the chosen offset; a block still moving when the tilt
  // starts (e.g. gliding after the drop on a nearly flat pair) starts elsewhere, with kinetic
  // energy, and its stick detection sees reversals (docs/dem.md sec. 6).
  if (!quasi_ && res_.settled_speed > cfg_.stick_speed)
    res_.warnings.push_back(
        {"unsettled",
         fmt::format("the upper block still moves at {:.3g} m/s against the lower one when the tilt starts "
                     "(warning above stick_speed = {:.3g} m/s, after settle_time = {:.3g} s): it is not at rest "
                     "where the prediction starts; raise settle_time",
                     res_.settled_speed, cfg_.stick_speed, cfg_.settle_time)});
  return Ok{};
}

// ---- Phase 5a: the constant-rate protocol and its detection. A stick is an interval of at
// least stick_duration with v <= stick_speed; the slide starts at the end of the last stick
// (short dips of v during a slide, e.g. bounces, do not count).
Status TiltRun::load_constant_rate() {
  TiltResult& res = res_;
  const TiltConfig& cfg = cfg_;
  double stick_time = st_.time, stick_tilt = 0, stick_d = 0;
  double low_since = st_.time;  // start of the current interval with v <= stick_speed (NaN: none)
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Rotation of the upper block against the lower one since the end of settling.
  const double rot0 = st_.angle[1] - st_.angle[0];
  double max_rot = 0, rot_at_stick = 0;
  // Creep: a slip between two sticks shorter than a tenth of the smallest feature of the faces
  // (it reaches no other feature: K3 at 20 deg slips 1 um at 60.04 deg and holds until 60.32 deg).
  const double creep_max = 0.1 * std::min(res.scales.smallest_feature[0], res.scales.smallest_feature[1]);
  bool sticking = false;  // a slip counts between two sticks (not the settling before the first)
  double leave_tilt = 0, leave_d = std::numeric_limits<double>::quiet_NaN();
  for (double dist : cfg.runaway_checkpoints) res.checkpoints.push_back({dist, false, nan, nan, nan});
  std::size_t checkpoints_left = res.checkpoints.size();
  double d_now = 0;
  const double t0 = st_.time;  // turn = gravity: the tilt grows from here
  while (running()) {
    if (gravity_turns_) set_tilt(cfg.tilt_rate * (st_.time - t0));
    if (Status s = advance_one(); !s.ok()) return with_prefix("tilt: ", s.error());
    const bool rec = series_due();
    if (rec) record();
    if (frame_due()) frame();
    const Measure m = measure();
    const double d = m.d, v = m.v, tilt = m.tilt;
    max_rot = std::max(max_rot, std::fabs(st_.angle[1] - st_.angle[0] - rot0));
    if (v <= cfg.stick_speed) {
      if (std::isnan(low_since)) low_since = st_.time;
      if (st_.time - low_since >= cfg.stick_duration - 0.5 * last_dt_) {
        if (!sticking) {                               // a new stick after a slip
          const double slip = std::fabs(d - leave_d);  // NaN before the first stick: no event
          if (std::isnan(res.first_creep_tilt) && slip >= cfg.warn_creep_slip && slip < creep_max) {
            res.first_creep_tilt = leave_tilt;
            res.first_creep_slip = slip;
          }
          sticking = true;
        }
        stick_time = st_.time;
        stick_tilt = tilt;
        stick_d = d;
        rot_at_stick = max_rot;
      }
    } else {
      low_since = nan;
      if (sticking) {  // leaving a stick: where and at which tilt
        sticking = false;
        leave_tilt = stick_tilt;
        leave_d = stick_d;
      }
    }
    d_now = d;
    // The same test as the stop below, for each shorter distance: the first run-away that reaches
    // it (later sticks may reset the stick point before a longer distance is reached).
    if (mark_runaway(res, checkpoints_left, d, stick_d, stick_tilt, stick_time, rot_at_stick, cfg.runaway_distance)) {
      if (!rec && series_every_) record();
      break;
    }
  }
  if (frame_every_ && (res.frames.empty() || res.frames.back().time != st_.time)) frame();
  if (!res.slid) res.rotation_before_slide = max_rot;
  res.final_displacement = d_now;
  return Ok{};
}

// Quasi-static: the run-away (and the checkpoints) from the displacement since the last stop.
void TiltRun::record_runaway(double d) {
  mark_runaway(res_, checkpoints_left_, d, stop_d_, stop_tilt_, stop_time_, rot_at_stop_, cfg_.runaway_distance);
}

// One FIRE relaxation of the upper block (Bitzek et al. 2006) for at most `budget` seconds:
// after each step of the engine, with F the unbalanced force (contacts and gravity) and torque
// and v the velocity in mass-weighted coordinates (sqrt(m) v, sqrt(I) omega; F / sqrt(m),
// tau / sqrt(I); rotation only when it is free), P = F . v; P > 0: v <- (1 - alpha) v + alpha
// |v| F/|F| (alpha shrinks after kFireMinSteps such steps); P <= 0: v <- 0, alpha reset. At rest
// when |v| < relax_speed (and, turning freely, |omega| R < relax_speed, R the block's extent) at
// every step of relax_duration (a block passing an unstable balance, e.g. tip on tip, is slow
// only for a moment) and F (and tau / R) averaged over that stretch is below relax_force W. The
// lower block is at rest.
Result<TiltRun::Relax> TiltRun::relax(double budget, bool watch_runaway) {
  const double t_end = st_.time + budget;
  const double m = model_.mass[1], inertia = model_.inertia[1], weight = m * cfg_.gravity;
  const double extent = model_.extent[1];
  const bool turns = !cfg_.hold_rotation;
  const double sm = std::sqrt(m), si = std::sqrt(inertia);
  double alpha = kFireAlphaStart;
  int positive = 0;
  double rest_since = std::numeric_limits<double>::quiet_NaN();  // start of the current at-rest stretch
  double sfx = 0, sfy = 0, stau = 0, span = 0;                   // impulse of the unbalanced force and torque over it
  while (st_.time < t_end) {
    if (Status s = advance_one(); !s.ok()) return s.error();
    if (series_due()) record();
    if (frame_due()) frame();
    max_rot_ = std::max(max_rot_, std::fabs(st_.angle[1] - st_.angle[0] - rot0_));
    if (watch_runaway) {
      record_runaway(measure().d);
      if (res_.slid) return Relax::Runaway;
    }
    const dem::Vec2 g = model_.def.gravity;
    const double fx = st_.force[1].x + m * g.x, fy = st_.force[1].y + m * g.y, tau = turns ? st_.torque[1] : 0.0;
    dem::Vec2& v = st_.velocity[1];
    double& w = st_.angular_velocity[1];
    const double wt = turns ? w : 0.0;
    // At rest: still (speed below relax_speed at every step) for relax_duration, with the
    // unbalanced force averaged over that stretch below relax_force W. The average, not the
    // instantaneous force: a block held where two contact pieces cross (a kink of the contact
    // energy) chatters across the kink with a force that flips between the two normals and
    // balances only on average; it does not move.
    if (std::hypot(v.x, v.y) < cfg_.relax_speed && std::fabs(wt) * extent < cfg_.relax_speed) {
      if (std::isnan(rest_since)) {
        rest_since = st_.time;
        sfx = sfy = stau = span = 0;
      }
      sfx += fx * last_dt_, sfy += fy * last_dt_, stau += tau * last_dt_, span += last_dt_;
      if (st_.time - rest_since >= cfg_.relax_duration - 0.5 * last_dt_) {
        if (std::hypot(sfx, sfy) < cfg_.relax_force * weight * span &&
            std::fabs(stau) < cfg_.relax_force * weight * extent * span)
          return Relax::Rest;
        rest_since = std::numeric_limits<double>::quiet_NaN();  // not balanced: a new stretch
      }
    } else {
      rest_since = std::numeric_limits<double>::quiet_NaN();
    }
    // FIRE in mass-weighted coordinates on the sliding coordinate x (the lower block's x axis:
    // gravity turns, the lower block does not) and the rotation when it is free; the normal
    // coordinate y is left to the contacts' normal dashpots (docs/dem.md sec. 4).
    const double ux = sm * v.x, uw = si * wt;
    const double gx = fx / sm, gw = tau / si;
    const double p = ux * gx + uw * gw;
    if (p > 0) {
      const double un = std::sqrt(ux * ux + uw * uw), gn = std::sqrt(gx * gx + gw * gw);
      const double k = gn > 0 ? alpha * un / gn : 0.0;
      v.x = ((1 - alpha) * ux + k * gx) / sm;
      if (turns) w = ((1 - alpha) * uw + k * gw) / si;
      if (++positive > kFireMinSteps) alpha *= kFireAlphaShrink;
    } else {
      v.x = 0;
      if (turns) w = 0;
      alpha = kFireAlphaStart;
      positive = 0;
    }
  }
  return Relax::OutOfTime;
}

// ---- Phase 5b: the quasi-static protocol and its detection. Increment k sets the tilt to
// k tilt_increment and relaxes; a relaxed increment is the new stop; the run-away is the first
// increment during whose relaxation (or after which) the block has moved runaway_distance from
// the last stop, and the friction angle is that stop's tilt.
Status TiltRun::load_quasi_static() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double dist : cfg_.runaway_checkpoints) res_.checkpoints.push_back({dist, false, nan, nan, nan});
  checkpoints_left_ = res_.checkpoints.size();
  rot0_ = st_.angle[1] - st_.angle[0];
  max_rot_ = 0;
  stop_d_ = 0;
  stop_tilt_ = 0;
  stop_time_ = st_.time;
  for (int k = 1;; ++k) {
    const double tilt = k * cfg_.tilt_increment;
    if (tilt > cfg_.max_tilt) break;
    set_tilt(tilt);
    ++res_.increments;
    auto r = relax(cfg_.relax_time, true);
    if (!r.ok()) return with_prefix("tilt: ", r.error());
    if (*r == Relax::Runaway) break;
    if (*r == Relax::OutOfTime) {
      ++res_.unrelaxed_increments;
      continue;
    }
    stop_d_ = measure().d;
    stop_tilt_ = tilt;
    stop_time_ = st_.time;
    rot_at_stop_ = max_rot_;
  }
  if (series_every_ && (res_.series.time.empty() || res_.series.time.back() != st_.time)) record();
  if (frame_every_ && (res_.frames.empty() || res_.frames.back().time != st_.time)) frame();
  if (!res_.slid) res_.rotation_before_slide = max_rot_;
  res_.final_displacement = measure().d;
  if (res_.unrelaxed_increments > 0)
    res_.warnings.push_back(
        {"unrelaxed",
         fmt::format("{} of {} tilt increments did not relax to rest within relax_time = {:.3g} s (rest: unbalanced "
                     "force below relax_force = {:.3g} of the weight and speed below relax_speed = {:.3g} m/s); the "
                     "friction angle {:.4f} deg is the last increment that did: raise relax_time",
                     res_.unrelaxed_increments, res_.increments, cfg_.relax_time, cfg_.relax_force, cfg_.relax_speed,
                     res_.friction_angle * 180 / std::numbers::pi)});
  return Ok{};
}

void TiltRun::finish() {
  res_.simulated_time = st_.time;
  res_.steps = st_.steps;
  res_.timings = st_.timings;
  res_.steps_beyond_limit = st_.steps_beyond_limit;
  res_.min_time_step = min_dt_;
  res_.max_time_step = max_dt_;
  res_.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start_).count();
}

// ---- The cost estimate before the first step (TiltEstimate, docs/dem.md sec. 7).
TiltEstimate estimate_cost(const dem::Model& model, const TiltConfig& cfg, const TiltResult& res,
                           std::size_t list_pairs, double expected_end) {
  TiltEstimate e;
  double dt = cfg.time_step;
  if (cfg.adaptive_time_step) {
    // The engine's rule for one more contact (stability.cpp, choose_time_step): one contact at
    // the upper block's extent against the kinematic lower block.
    const double m = model.mass[1], inertia = model.inertia[1], ext = model.extent[1];
    const double w2 = dem::contact_stiffness(model, 1) * std::max(1.0 / m, ext * ext / inertia);
    double one = 2.0 / std::sqrt(w2);
    if (model.def.contact.law == dem::ContactLaw::Hertz) {
      if (!cfg.implicit_damping && model.def.contact.damping_ratio > 0)
        one = std::min(one, 1.0 / (model.def.contact.damping_ratio * std::sqrt(w2)));
    } else if (!cfg.implicit_damping && model.def.contact.normal_damping > 0) {
      one = std::min(one, 2.0 / model.def.contact.normal_damping);
    }
    dt = std::min(dt, cfg.time_step_safety * one);
  }
  e.time_step = dt;
  const double end = std::isfinite(expected_end) ? expected_end : res.predicted_sphero_friction_angle;
  const double phi = cfg.predict && std::isfinite(end) ? std::min(end, cfg.max_tilt) : cfg.max_tilt;
  if (cfg.protocol == TiltProtocol::QuasiStatic) {
    const double bound_increments = std::floor(cfg.max_tilt / cfg.tilt_increment);
    const double expected_increments = std::ceil(phi / cfg.tilt_increment) + 1;
    e.simulated_time_bound = cfg.relax_time * (1 + bound_increments);
    e.simulated_time_expected = std::min(
        e.simulated_time_bound,
        cfg.relax_time * (kTiltRelaxFixed + kTiltRelaxShare * std::min(expected_increments, bound_increments)));
  } else {
    const double settle = relaxed_settling(cfg) ? cfg.relax_time : cfg.settle_time;
    e.simulated_time_bound = settle + cfg.max_tilt / cfg.tilt_rate;
    e.simulated_time_expected = settle + phi / cfg.tilt_rate;
  }
  e.steps_bound = std::ceil(e.simulated_time_bound / dt);
  e.steps_expected = std::ceil(e.simulated_time_expected / dt);
  e.list_pairs = static_cast<double>(list_pairs);
  e.seconds_per_step = kTiltStepSeconds0 + kTiltStepSecondsPerPair * e.list_pairs;
  e.seconds_bound = e.steps_bound * e.seconds_per_step;
  e.seconds_expected = e.steps_expected * e.seconds_per_step;
  return e;
}

// ---- Phase 6: the warnings from the run.
void run_warnings(const TiltConfig& cfg, TiltResult& res) {
  if (res.rotation_before_slide > cfg.warn_rotation)
    res.warnings.push_back(
        {"rotation",
         fmt::format("the upper block turned by {:.4g} deg against the lower one before the slide (warning above "
                     "{:.4g} deg): the signature assumes it does not rotate; hold_rotation (--hold-rotation) holds it",
                     res.rotation_before_slide * 180 / std::numbers::pi, cfg.warn_rotation * 180 / std::numbers::pi)});
  if (res.slid && !std::isnan(res.first_creep_tilt) &&
      res.friction_angle - res.first_creep_tilt > cfg.warn_creep_angle) {
    const double creep_max = 0.1 * std::min(res.scales.smallest_feature[0], res.scales.smallest_feature[1]);
    res.warnings.push_back(
        {"creep",
         fmt::format("the upper block slipped {:.3g} m at a tilt of {:.4f} deg and was held again (a slip "
                     "shorter than a tenth of the smallest feature, {:.3g} m): sliding began {:.3f} deg "
                     "below the reported friction angle {:.4f} deg (the stick rule reports the last stick; "
                     "warning above {:.3g} deg)",
                     res.first_creep_slip, res.first_creep_tilt * 180 / std::numbers::pi, creep_max,
                     (res.friction_angle - res.first_creep_tilt) * 180 / std::numbers::pi,
                     res.friction_angle * 180 / std::numbers::pi, cfg.warn_creep_angle * 180 / std::numbers::pi)});
  }
}

}  // namespace

dem::ContactRule tilt_contact_rule(const TiltConfig& cfg) {
  switch (cfg.contact_rule) {
    case TiltContactRule::Pairs: return dem::ContactRule::Pairs;
    case TiltContactRule::Closest: return dem::ContactRule::Closest;
    case TiltContactRule::Auto: break;
  }
  return cfg.protocol == TiltProtocol::QuasiStatic ? dem::ContactRule::Closest : dem::ContactRule::Pairs;
}

Result<TiltResult> run_tilt(const Curve& lower_surface, const Curve& upper_surface, const TiltConfig& cfg) {
  using Clock = std::chrono::steady_clock;
  const auto setup_start = Clock::now();
  if (Status s = check_config(cfg); !s.ok()) return s.error();
  TiltResult res;
  auto faces = build_faces(lower_surface, upper_surface, cfg);
  if (!faces.ok()) return faces.error();
  const unsigned threads = util::thread_count(static_cast<unsigned>(std::max(0, cfg.threads)));
  auto offset = predict_theta_max(*faces, cfg, threads, res);
  if (!offset.ok()) return offset.error();
  auto model = place_blocks(faces->lower, faces->upper, *offset, cfg, res);
  if (!model.ok()) return model.error();
  res.warnings = tilt_scale_warnings(res.scales, res, cfg);

  TiltRun run(cfg, *model, res, threads);
  // The angle the run is expected to end at: the quasi-static hold angle of the block from where it
  // is put down (the rest is not known yet), else the rounded blocks' bound.
  double expected_end = std::numeric_limits<double>::quiet_NaN();
  if (cfg.predict) {
    TiltResult from_start;
    from_start.rest_offset = res.initial_offset;
    predict_hold_angles(*faces, cfg, from_start);
    expected_end = std::max(from_start.predicted_hold_angle, from_start.predicted_sphero_hold_angle);
  }
  res.estimate = estimate_cost(*model, cfg, res, run.list_pairs(), expected_end);
  res.setup_time = std::chrono::duration<double>(Clock::now() - setup_start).count();
  if (cfg.before_run)
    if (Status s = cfg.before_run(res.estimate); !s.ok()) return s.error();
  if (Status s = run.settle(); !s.ok()) return s.error();
  res.rest_offset = res.initial_offset + (cfg.reverse ? -1.0 : 1.0) * run.settle_displacement();
  if (Status s = cfg.protocol == TiltProtocol::QuasiStatic ? run.load_quasi_static() : run.load_constant_rate();
      !s.ok())
    return s.error();
  run_warnings(cfg, res);
  run.finish();
  const auto hold_start = Clock::now();
  predict_hold_angles(*faces, cfg, res);
  res.setup_time += std::chrono::duration<double>(Clock::now() - hold_start).count();
  // A reading outside the model's 5-95 % over drops for this test says why (tilt_spread_note).
  if (const std::string note = tilt_spread_note(res, cfg); note.rfind("outside ", 0) == 0)
    res.warnings.push_back({"outside-spread", "the friction angle lies " + note});
  if (cfg.check_stiffness) {
    // The same test from the same offset at 10 k_n (and k_t): in the rigid limit the angle stays.
    TiltConfig stiff = cfg;
    stiff.contact.normal_stiffness *= 10;
    stiff.contact.tangential_stiffness *= 10;
    stiff.modulus *= 10;  // the Hertz law's stiffness
    stiff.check_stiffness = false;
    stiff.predict = false;
    stiff.initial_offset = res.initial_offset;
    stiff.series_interval = 0;
    stiff.frame_interval = 0;
    stiff.runaway_checkpoints.clear();
    stiff.before_run = nullptr;  // the rerun is part of this run: one estimate, one progress
    stiff.progress = nullptr;
    auto r = run_tilt(lower_surface, upper_surface, stiff);
    if (!r.ok()) return with_prefix("tilt (stiffness check at 10 k_n): ", r.error());
    const double deg = 180 / std::numbers::pi;
    if (r->slid) res.stiff_friction_angle = r->friction_angle;
    if (r->slid != res.slid ||
        (res.slid && std::fabs(r->friction_angle - res.friction_angle) > cfg.warn_stiffness_angle))
      res.warnings.push_back(
          {"stiffness",
           cfg.contact.law == dem::ContactLaw::Hertz
               ? fmt::format("the angle depends on the contacts' compliance: at 10 E = {:.3g} Pa the friction angle "
                             "is {} against {} at E = {:.3g} Pa (warning above a change of {:.3g} deg); a "
                             "load-dependent angle, or overlaps beyond the spheroradius (core-overlap)",
                             stiff.modulus,
                             r->slid ? fmt::format("{:.4f} deg", r->friction_angle * deg) : std::string("no slide"),
                             res.slid ? fmt::format("{:.4f} deg", res.friction_angle * deg) : std::string("no slide"),
                             cfg.modulus, cfg.warn_stiffness_angle * deg)
               : fmt::format("not in the rigid limit: at 10 k_n = {:.3g} N/m the friction angle is {} against {} at "
                             "k_n = {:.3g} N/m (warning above a change of {:.3g} deg); raise normal_stiffness",
                             stiff.contact.normal_stiffness,
                             r->slid ? fmt::format("{:.4f} deg", r->friction_angle * deg) : std::string("no slide"),
                             res.slid ? fmt::format("{:.4f} deg", res.friction_angle * deg) : std::string("no slide"),
                             cfg.contact.normal_stiffness, cfg.warn_stiffness_angle * deg)});
  }
  return res;
}

std::vector<Warning> tilt_scale_warnings(const TiltScales& sc, const TiltResult& r, const TiltConfig& cfg) {
  std::vector<Warning> w;
  const double deg = 180 / std::numbers::pi;
  const bool hertz = cfg.contact.law == dem::ContactLaw::Hertz;
  if (sc.resting_overlap > cfg.warn_overlap_fraction * sc.spheroradius)
    w.push_back({"core-overlap",
                 fmt::format("the resting overlap {} = {:.3g} m is {:.3g} r (warning above {:.3g} r, r = {:.3g} m): a "
                             "contact carrying the block sinks far into the rounded rims and the cores can "
                             "interpenetrate (2r = {:.3g} m); raise the spheroradius or {}",
                             hertz ? "of one Hertz contact on the sharpest vertex" : "W/k_n", sc.resting_overlap,
                             sc.resting_overlap / sc.spheroradius, cfg.warn_overlap_fraction, sc.spheroradius,
                             2 * sc.spheroradius, hertz ? "block_modulus" : "normal_stiffness")});
  if (cfg.predict &&
      std::fabs(r.predicted_sphero_friction_angle - r.predicted_friction_angle) > cfg.warn_prediction_tolerance)
    w.push_back(
        {"rounding",
         fmt::format("the spheroradius r = {:.3g} m rounds away features that carry the friction: predicted {:.4f} "
                     "deg for the rounded blocks against {:.4f} deg for rigid profiles (tolerance {:.3g} deg); "
                     "smallest feature {:.3g} / {:.3g} m, shortest edge {:.3g} / {:.3g} m (lower / upper face); the "
                     "simulation follows the rounded blocks: lower r for the rigid profiles",
                     sc.spheroradius, r.predicted_sphero_friction_angle * deg, r.predicted_friction_angle * deg,
                     cfg.warn_prediction_tolerance * deg, sc.smallest_feature[0], sc.smallest_feature[1],
                     sc.shortest_edge[0], sc.shortest_edge[1])});
  // The adaptive step follows the stability limit of the contacts present (a larger cap changes
  // nothing, docs/dem.md sec. 6): only a fixed step is compared with the contact period.
  if (!cfg.adaptive_time_step && sc.time_step > cfg.warn_time_step_fraction * sc.contact_period)
    w.push_back({"time-step", fmt::format("the fixed time step {:.3g} s is {:.3g} of one contact's period 2 pi "
                                          "sqrt(m/k_n) = {:.3g} s (warning above {:.3g}); many contacts need "
                                          "less: use the adaptive step",
                                          sc.time_step, sc.time_step / sc.contact_period, sc.contact_period,
                                          cfg.warn_time_step_fraction)});
  return w;
}

Status write_tilt_series_csv(const std::string& path, const TiltSeries& s) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!f) return make_error(ErrorCode::Io, fmt::format("{}: cannot open for writing", path));
  fmt::print(f.get(), "time_s,tilt_deg,fn_N,ft_N,force_angle_deg,displacement_m,velocity_m_s,contacts\n");
  for (std::size_t i = 0; i < s.time.size(); ++i)
    fmt::print(f.get(), "{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{}\n", s.time[i], units::to_deg(s.tilt[i]),
               s.normal_force[i], s.tangential_force[i], units::to_deg(s.force_angle[i]), s.displacement[i],
               s.velocity[i], s.contacts[i]);
  if (std::ferror(f.get())) return make_error(ErrorCode::Io, fmt::format("{}: write failed", path));
  return Ok{};
}

Status write_tilt_frames(const std::string& path, const TiltResult& r) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!f) return make_error(ErrorCode::Io, fmt::format("{}: cannot open for writing", path));
  fmt::print(f.get(), "frictal-dem-frames 1\n");
  const std::vector<double>* px[2] = {&r.lower_polygon_x, &r.upper_polygon_x};
  const std::vector<double>* py[2] = {&r.lower_polygon_y, &r.upper_polygon_y};
  for (int b = 0; b < 2; ++b) {
    fmt::print(f.get(), "body {} {} {}\n", b, b == 0 ? "lower" : "upper", px[b]->size());
    for (std::size_t i = 0; i < px[b]->size(); ++i) fmt::print(f.get(), "{:.17g} {:.17g}\n", (*px[b])[i], (*py[b])[i]);
  }
  for (const TiltFrame& fr : r.frames) {
    fmt::print(f.get(), "frame {:.9g} {:.9g}\n", fr.time, fr.tilt);
    for (int b = 0; b < 2; ++b)
      fmt::print(f.get(), "{} {:.17g} {:.17g} {:.17g}\n", b, fr.position[b].x, fr.position[b].y, fr.angle[b]);
  }
  if (std::ferror(f.get())) return make_error(ErrorCode::Io, fmt::format("{}: write failed", path));
  return Ok{};
}

namespace {

// The whitespace-separated numbers of `line`; false where a field is not a finite number or the
// count differs from `n`.
bool frame_numbers(const std::string& line, std::size_t n, std::vector<double>& out) {
  out.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i == line.size()) break;
    std::size_t j = i;
    while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
    const std::string field = line.substr(i, j - i);
    char* end = nullptr;
    const double v = std::strtod(field.c_str(), &end);
    if (end != field.c_str() + field.size() || !std::isfinite(v)) return false;
    out.push_back(v);
    i = j;
  }
  return out.size() == n;
}

}  // namespace

Result<TiltFramesFile> read_tilt_frames(const std::string& path) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "r"), &std::fclose);
  if (!f) return make_error(ErrorCode::Io, fmt::format("{}: cannot open for reading", path));
  std::vector<std::string> lines;
  std::string cur;
  for (int c; (c = std::fgetc(f.get())) != EOF;) {
    if (c == '\n') {
      lines.push_back(std::move(cur));
      cur.clear();
    } else if (c != '\r') {
      cur.push_back(static_cast<char>(c));
    }
  }
  if (!cur.empty()) lines.push_back(std::move(cur));
  auto bad = [&](std::size_t i, const std::string& what) {
    return make_error(ErrorCode::InvalidInput, fmt::format("{}: line {}: {}", path, i + 1, what));
  };
  if (lines.empty() || lines[0].rfind("frictal-dem-frames 1", 0) != 0)
    return bad(0, "expected the header 'frictal-dem-frames 1' (a file written by frictal tilt --frames)");
  TiltFramesFile out;
  std::vector<double>* px[2] = {&out.lower_polygon_x, &out.upper_polygon_x};
  std::vector<double>* py[2] = {&out.lower_polygon_y, &out.upper_polygon_y};
  bool have[2] = {false, false};
  std::vector<double> v;
  for (std::size_t i = 1; i < lines.size();) {
    const std::string& line = lines[i];
    if (line.find_first_not_of(" \t") == std::string::npos) {
      ++i;
      continue;
    }
    if (line.rfind("body ", 0) == 0) {
      int b = -1;
      unsigned long n = 0;
      char name[16] = {0};
      if (std::sscanf(line.c_str(), "body %d %15s %lu", &b, name, &n) != 3 || (b != 0 && b != 1))
        return bad(i, "expected 'body <0|1> <lower|upper> <vertex count>'");
      if (have[b]) return bad(i, fmt::format("body {} is given twice", b));
      if (!out.frames.empty()) return bad(i, "a body after the first frame");
      if (n < 3 || n > lines.size() - i - 1)
        return bad(i, fmt::format("{} vertices: expected at least 3 and as many lines of 'x y' after it", n));
      for (std::size_t k = 0; k < n; ++k) {
        if (!frame_numbers(lines[i + 1 + k], 2, v)) return bad(i + 1 + k, "expected two numbers 'x y' (m)");
        px[b]->push_back(v[0]);
        py[b]->push_back(v[1]);
      }
      have[b] = true;
      i += 1 + n;
    } else if (line.rfind("frame ", 0) == 0) {
      if (!have[0] || !have[1]) return bad(i, "a frame before both bodies ('body 0 ...', 'body 1 ...')");
      TiltFrame fr;
      if (!frame_numbers(line.substr(6), 2, v)) return bad(i, "expected 'frame <time_s> <tilt_rad>'");
      fr.time = v[0], fr.tilt = v[1];
      for (int b = 0; b < 2; ++b) {
        const std::size_t k = i + 1 + static_cast<std::size_t>(b);
        if (k >= lines.size() || !frame_numbers(lines[k], 4, v) || v[0] != b)
          return bad(k, fmt::format("expected the pose of body {}: '{} <cx> <cy> <angle_rad>'", b, b));
        fr.position[b] = {v[1], v[2]};
        fr.angle[b] = v[3];
      }
      out.frames.push_back(std::move(fr));
      i += 3;
    } else {
      return bad(i, fmt::format("expected 'body ...' or 'frame ...', found '{}'", line.substr(0, 40)));
    }
  }
  if (!have[0] || !have[1]) return bad(lines.size() - 1, "the file ends before both bodies are given");
  return out;
}

}  // namespace frictal
