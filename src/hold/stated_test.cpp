// The stated test of a profile pair (hold.hpp): its default lengths, their fit to the scans, the
// block cut from the upper scan, its offsets and drops, and the lift cut to them. predict() and
// the tilt test's setup both read it, so that `frictal predict` and `frictal tilt` state one test.
#include <algorithm>
#include <cmath>

#include <fmt/core.h>

#include "frictal/analysis.hpp"
#include "frictal/hold.hpp"

namespace frictal {

StatedTest default_test_lengths(const Profile& lower) {
  StatedTest t;
  const double xi = slope_correlation_length(lower);
  const double dx = lower.x.size() > 1 ? (lower.x.back() - lower.x.front()) / double(lower.x.size() - 1) : 0;
  if (xi > 0) {
    // The scan resolves no slope structure finer than its sampling interval (a rounded x column
    // makes neighbouring slopes alternate, which the cells would read as a shorter length).
    const double l = std::max(xi, dx);
    t.runaway_distance = kRunawayPerSlopeCorrelation * l;
    t.rule = fmt::format("{:g} slope correlation lengths of the lower scan ({:.4g} m{})", kRunawayPerSlopeCorrelation,
                         l, xi < dx ? ", its sampling interval" : "");
  } else {
    t.runaway_distance = kRunawayPerSlopeCorrelation * dx;
    t.rule = fmt::format("{:g} sampling intervals of the lower scan ({:.4g} m; its slopes have no correlation length)",
                         kRunawayPerSlopeCorrelation, dx);
  }
  t.block_length = kBlockPerRunaway * t.runaway_distance;
  return t;
}

Result<StatedTestFit> stated_test(const Profile& lower, double upper_len, double runaway_distance,
                                  double block_length) {
  if (lower.x.size() < 2) return make_error("the stated test: expected a lower profile of at least two points");
  if (!std::isfinite(runaway_distance) || runaway_distance < 0)
    return make_error(
        fmt::format("run-away distance {:.6g} m: expected a length > 0 (0: the default)", runaway_distance));
  if (!std::isfinite(block_length))
    return make_error(
        fmt::format("block length {:.6g} m: expected a length > 0 (0: the default; < 0: the whole upper "
                    "profile)",
                    block_length));
  StatedTestFit f;
  const double lower_len = lower.x.back() - lower.x.front();
  const bool given_d = runaway_distance > 0, given_lb = block_length > 0;
  double d = runaway_distance, lb = block_length;
  std::string d_rule = "given";
  if (!given_d) {
    const StatedTest def = default_test_lengths(lower);
    d = def.runaway_distance;
    d_rule = def.rule;
  }
  if (lb < 0) {
    // The whole upper profile over the first half of the lower one (the blocks of `frictal
    // signature`'s hold analysis): the signature's own drop range, no piece cut.
    f.rule = "d: " + d_rule + "; block: the whole upper profile, dropped over the first half of the lower one";
    f.whole = true;
    lb = upper_len;
    // A defaulted d longer than the default's shape allows on these blocks (a short upper scan on
    // a long lower one: d from the lower scan's slopes, the block the whole short scan) gives way
    // to the largest of that shape, L_b / kBlockPerRunaway over the blocks' overlap, with the
    // warning; a stated d never changes.
    const double d_fit = std::min(lower_len, upper_len) / kBlockPerRunaway;
    if (!given_d && d > d_fit) {
      f.warnings.push_back(
          {"scan-too-short",
           fmt::format("the default run-away distance d = {:.4g} m ({}) does not fit the whole upper profile "
                       "({:.4g} m on a lower one of {:.4g} m): the answer is for d = {:.4g} m, the "
                       "blocks' overlap over {:g} (a shorter test reads other angles; d_sweep shows how "
                       "much); measure longer scans or state d (--runaway-distance)",
                       d, d_rule, upper_len, lower_len, d_fit, kBlockPerRunaway)});
      d = d_fit;
      f.rule += fmt::format("; d shortened to the blocks' overlap over {:g}", kBlockPerRunaway);
    }
    f.runaway_distance = d;
    f.block_length = lb;
    return f;
  }
  if (!given_lb) lb = kBlockPerRunaway * d;
  f.rule = fmt::format("d: {}; block: {}", d_rule, given_lb ? "given" : fmt::format("{:g} d", kBlockPerRunaway));
  // The test fits where the block lies within the upper scan and the lower one leaves sliding room
  // L - L_b of at least kRoomPerRunaway d (drops over all but kEndRoomPerRunaway d at each end).
  // Where it does not, a length that was defaulted gives way (warned, with the test answered); a
  // length the caller stated never changes: with no room left, a refusal.
  const double need = lb + kRoomPerRunaway * d;
  if (upper_len < lb || lower_len < need) {
    const std::string stated = fmt::format(
        "the test (a block of {:.4g} m{}, d = {:.4g} m{}) needs a lower scan of {:.4g} m (the block and {:g} d of "
        "sliding room) and an upper scan of {:.4g} m; the scans are {:.4g} m and {:.4g} m",
        lb, given_lb ? " as given" : "", d, given_d ? " as given" : "", need, kRoomPerRunaway, lb, lower_len,
        upper_len);
    const std::string fix =
        "measure longer scans, state a shorter test (--block-length, --runaway-distance), or slide the whole "
        "upper profile over the first half of the lower one (--block-length whole)";
    double lb_new = lb, d_new = d;
    if (!given_d && !given_lb) {  // the largest test of the default's shape
      const double s = std::min(upper_len / lb, lower_len / need);
      lb_new = s * lb, d_new = s * d;
    } else if (given_d && !given_lb) {  // the block shortened, down to 2 d
      lb_new = std::min({lb, upper_len, lower_len - kRoomPerRunaway * d});
      if (!(lb_new >= 2 * d))
        return make_error(fmt::format("{}: no block of at least 2 d fits with d = {:.4g} m; {}", stated, d, fix));
    } else if (!given_d && given_lb) {  // d shortened, down to a hundredth of the default
      d_new = std::min(d, (lower_len - lb) / kRoomPerRunaway);
      if (!(lb <= upper_len) || !(d_new >= 0.01 * d))
        return make_error(fmt::format("{}: the block of {:.4g} m leaves no room on these scans; {}", stated, lb, fix));
    } else {
      return make_error(fmt::format("{}; {}", stated, fix));
    }
    f.warnings.push_back({"scan-too-short", fmt::format("{}: the answer is for the test they hold, a block of {:.4g} m "
                                                        "and d = {:.4g} m (a shorter test reads other angles; d_sweep "
                                                        "shows how much); {}",
                                                        stated, lb_new, d_new, fix)});
    lb = lb_new;
    d = d_new;
  }
  f.runaway_distance = d;
  f.block_length = lb;
  return f;
}

Profile stated_block(const Profile& p, double block_length) {
  const double mid = 0.5 * (p.x.front() + p.x.back());
  double x0 = std::max(mid - 0.5 * block_length, p.x.front());
  double x1 = std::min(mid + 0.5 * block_length, p.x.back());
  // Each end snapped to the nearest sample (a tie outward, so that a mirrored scan gives the
  // mirrored piece): the block keeps the scan's own samples. Ends interpolated between samples
  // would put the turned-over block off the lower scan's grid, and the signature's aligned-lattice
  // search would give way to the general one (a 10^6-point pair: 4.7 s against 1.7 s). A piece
  // of fewer than 8 samples (a block shorter than the scan's spacing allows, e.g. scans of very
  // different scales) keeps its stated ends, interpolated.
  auto nearest = [&](double x, bool tie_left) {
    const auto it = std::lower_bound(p.x.begin(), p.x.end(), x);
    if (it == p.x.begin()) return p.x.front();
    if (it == p.x.end()) return p.x.back();
    const double hi = *it, lo = *(it - 1);
    if (x - lo < hi - x) return lo;
    if (hi - x < x - lo) return hi;
    return tie_left ? lo : hi;
  };
  const double spacing = (p.x.back() - p.x.front()) / double(p.x.size() - 1);
  Profile out;
  if (x1 - x0 >= 8 * spacing) {
    const double s0 = nearest(x0, true), s1 = nearest(x1, false);
    // A vertical jump at an end keeps its side inside the piece: the last sample at s0 (the right
    // limit) and the first at s1 (the left limit).
    for (std::size_t i = 0; i < p.x.size(); ++i) {
      if (p.x[i] < s0 || p.x[i] > s1) continue;
      if (p.x[i] == s0 && i + 1 < p.x.size() && p.x[i + 1] == s0) continue;
      if (p.x[i] == s1 && !out.x.empty() && out.x.back() == s1) continue;
      out.x.push_back(p.x[i]), out.z.push_back(p.z[i]);
    }
    if (out.size() >= 2 && out.x.back() > out.x.front()) return out;
    out = Profile{};
  }
  auto at = [&](double x) {
    const auto it = std::upper_bound(p.x.begin(), p.x.end(), x);
    const std::size_t k = std::clamp<std::size_t>(std::size_t(it - p.x.begin()), 1, p.x.size() - 1);
    const double w = p.x[k] - p.x[k - 1];
    if (!(w > 0)) return p.z[k];
    const double t = (x - p.x[k - 1]) / w;
    return p.z[k - 1] + t * (p.z[k] - p.z[k - 1]);
  };
  const double tol = 1e-9 * (p.x.back() - p.x.front());
  out.x.push_back(x0);
  out.z.push_back(at(x0));
  for (std::size_t i = 0; i < p.x.size(); ++i)
    if (p.x[i] > x0 + tol && p.x[i] < x1 - tol) out.x.push_back(p.x[i]), out.z.push_back(p.z[i]);
  out.x.push_back(x1);
  out.z.push_back(at(x1));
  return out;
}

StatedDrops stated_drops(double lower_len, double lb, double d) {
  StatedDrops s;
  s.offset_min = 0;
  s.offset_max = std::max(lower_len - lb, 1e-9 * lower_len);
  const double room = kEndRoomPerRunaway * d;
  s.drop_min = s.offset_min + room;
  s.drop_max = std::max(s.offset_max - room, s.drop_min + 1e-9 * lower_len);
  return s;
}

LiftCurve cut_lift_curve(const LiftCurve& c, double a, double b) {
  LiftCurve out;
  auto at = [&](double s) {
    const auto it = std::upper_bound(c.offset.begin(), c.offset.end(), s);
    const std::size_t k = std::clamp<std::size_t>(std::size_t(it - c.offset.begin()), 1, c.offset.size() - 1);
    const double t = (s - c.offset[k - 1]) / (c.offset[k] - c.offset[k - 1]);
    return c.lift[k - 1] + t * (c.lift[k] - c.lift[k - 1]);
  };
  a = std::max(a, c.offset.front());
  b = std::min(b, c.offset.back());
  out.offset.push_back(a);
  out.lift.push_back(at(a));
  for (std::size_t i = 0; i < c.offset.size(); ++i)
    if (c.offset[i] > a && c.offset[i] < b) out.offset.push_back(c.offset[i]), out.lift.push_back(c.lift[i]);
  out.offset.push_back(b);
  out.lift.push_back(at(b));
  return out;
}

}  // namespace frictal
