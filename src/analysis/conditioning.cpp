// Conditioning of measured surfaces (frictal/conditioning.hpp): crop, spike removal, form removal,
// in that order, with a record of each step. Rules and why: docs/analysis.md, "Conditioning".
#include "frictal/conditioning.hpp"
#include "frictal/units.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include <fmt/core.h>

namespace frictal {

namespace {

// At most this many passes of the spike rule (each pass re-fits the form and Sq without the
// points already removed); a surface that still has spikes after them keeps them, and the
// record says how many passes ran.
constexpr int kMaxSpikePasses = 32;

double median_of(std::vector<double>& v) {
  const std::size_t k = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  double m = v[k];
  if (v.size() % 2 == 0) m = 0.5 * (m + *std::max_element(v.begin(), v.begin() + std::ptrdiff_t(k)));
  return m;
}

// rms of the finite values about their mean (equal weights), as the plausibility checks compute it.
double rms_about_mean(const std::vector<double>& z) {
  double s = 0;
  std::size_t n = 0;
  for (double v : z)
    if (std::isfinite(v)) s += v, ++n;
  if (n == 0) return 0;
  const double mean = s / double(n);
  double s2 = 0;
  for (double v : z)
    if (std::isfinite(v)) s2 += (v - mean) * (v - mean);
  return std::sqrt(s2 / double(n));
}

// One number of a crop window: a finite number, optionally followed by m, mm, um, µm, nm.
bool parse_length(std::string t, double& out) {
  while (!t.empty() && t.front() == ' ') t.erase(0, 1);
  while (!t.empty() && t.back() == ' ') t.pop_back();
  if (t.empty()) return false;
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  if (end == t.c_str()) return false;
  std::string unit(end);
  while (!unit.empty() && unit.front() == ' ') unit.erase(0, 1);
  const auto scale = units::length_scale(unit);
  if (!scale) return false;
  out = v * *scale;
  return std::isfinite(out);
}

std::string range_text(double a, double b) { return fmt::format("[{:.6g}, {:.6g}] m", a, b); }

std::string window_text(const CropWindow& w) {
  std::string s = "x " + range_text(w.x_min, w.x_max);
  if (w.has_y) s += ", y " + range_text(w.y_min, w.y_max);
  return s;
}

Status check_window(const CropWindow& w, const std::string& source) {
  if (!std::isfinite(w.x_min) || !std::isfinite(w.x_max) || !(w.x_min < w.x_max))
    return make_error(
        fmt::format("{}: x window [{:.6g}, {:.6g}] m; expected finite x0 < x1", source, w.x_min, w.x_max));
  if (w.has_y && (!std::isfinite(w.y_min) || !std::isfinite(w.y_max) || !(w.y_min < w.y_max)))
    return make_error(
        fmt::format("{}: y window [{:.6g}, {:.6g}] m; expected finite y0 < y1", source, w.y_min, w.y_max));
  return Ok{};
}

Status check_threshold(const Conditioning& c) {
  if (c.remove_spikes && !(std::isfinite(c.spike_threshold) && c.spike_threshold > 0))
    return make_error(fmt::format("spike threshold {}: expected a finite number > 0 (multiples of the rms height Sq)",
                                  c.spike_threshold));
  return Ok{};
}

// The grid indices [lo, hi] whose coordinate origin + i * step lies in [a, b] (to 1e-9 step),
// clamped to [0, n - 1]; count 0 when none.
std::pair<std::size_t, std::size_t> grid_range(double origin, double step, std::size_t n, double a, double b,
                                               std::size_t& count) {
  const double lo = std::ceil((a - origin) / step - 1e-9);
  const double hi = std::floor((b - origin) / step + 1e-9);
  const double l = std::max(lo, 0.0), h = std::min(hi, double(n) - 1);
  if (!(h >= l)) {
    count = 0;
    return {0, 0};
  }
  count = std::size_t(h - l) + 1;
  return {std::size_t(l), std::size_t(h)};
}

}  // namespace

std::string detrend_name(const Detrend& d, bool is_map) {
  switch (d.kind) {
    case DetrendKind::None: return "none";
    case DetrendKind::Mean: return "mean";
    case DetrendKind::Line: return is_map ? "plane" : "line";
    case DetrendKind::Polynomial: return fmt::format("poly:{}", d.degree);
  }
  return "none";
}

Result<CropWindow> parse_crop(const std::string& text, const std::string& option) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    parts.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  const std::string expected =
      "expected x0,x1 or x0,x1,y0,y1 (m, or with a unit m, mm, um, nm: e.g. 0.1mm,0.9mm), with x0 < x1 and y0 < y1";
  if (parts.size() != 2 && parts.size() != 4)
    return make_error(fmt::format("{} '{}': {} number(s); {}", option, text, parts.size(), expected));
  double v[4] = {0, 0, 0, 0};
  for (std::size_t k = 0; k < parts.size(); ++k)
    if (!parse_length(parts[k], v[k]))
      return make_error(fmt::format("{} '{}': '{}' is not a length; {}", option, text, parts[k], expected));
  CropWindow w;
  w.x_min = v[0], w.x_max = v[1];
  if (parts.size() == 4) w.has_y = true, w.y_min = v[2], w.y_max = v[3];
  if (!(w.x_min < w.x_max) || (w.has_y && !(w.y_min < w.y_max)))
    return make_error(fmt::format("{} '{}': {}", option, text, expected));
  return w;
}

std::string ConditioningRecord::text() const {
  std::vector<std::string> steps;
  if (cropped) {
    if (is_map)
      steps.push_back(fmt::format("crop {}: kept {} x {} of {} x {} points", window_text(window), nx_after, ny_after,
                                  nx_before, ny_before));
    else
      steps.push_back(fmt::format("crop {}: kept {} of {} points", window_text(window), nx_after, nx_before));
  }
  if (spikes_checked) {
    const auto points = [](std::size_t n) { return fmt::format("{} point{}", n, n == 1 ? "" : "s"); };
    std::string what;
    if (spikes_removed == 0)
      what = "none found";
    else if (is_map)
      what = points(spikes_removed) + " masked";
    else if (spikes_dropped == 0)
      what = points(spikes_removed) + " removed (replaced by linear interpolation)";
    else if (spikes_dropped == spikes_removed)
      what = points(spikes_removed) + " removed (dropped at the ends)";
    else
      what = fmt::format("{} removed ({} replaced by linear interpolation, {} dropped at the ends)",
                         points(spikes_removed), spikes_removed - spikes_dropped, spikes_dropped);
    if (spikes_left) what += fmt::format(" (stopped after {} passes with spikes left)", spike_passes);
    steps.push_back(fmt::format("spikes (k = {:g} Sq): {}", spike_threshold, what));
  }
  steps.push_back("form: " + detrend_name(form, is_map));
  std::string s;
  for (const std::string& x : steps) s += (s.empty() ? "" : "; ") + x;
  return s;
}

std::string conditioning_text(const std::vector<ConditioningRecord>& records) {
  if (records.empty()) return "";
  const std::string first = records[0].text();
  bool same = true;
  for (const ConditioningRecord& r : records) same = same && r.text() == first;
  if (same) return first;
  std::string s;
  for (std::size_t k = 0; k < records.size(); ++k)
    s += (k ? " | " : "") +
         (k == 0   ? std::string("lower")
          : k == 1 ? std::string("upper")
                   : fmt::format("surface {}", k + 1)) +
         ": " + records[k].text();
  return s;
}

SpikeSearch find_spikes(const Profile& p, double k) {
  SpikeSearch s;
  s.rms = rms_about_mean(p.z);
  const std::size_t n = p.z.size();
  if (!(s.rms > 0) || n < 5) return s;
  std::vector<double> w;
  w.reserve(4);
  const double* z = p.z.data();
  for (std::size_t i = 0; i < n; ++i) {
    double med;
    if (i >= 2 && i + 2 < n) {
      // Four neighbours: the median is the mean of the middle two, which are the larger of the
      // two pairs' minima and the smaller of their maxima (the same sum as median_of's, whose
      // order of the two terms does not change a rounded sum); no sort, no branch to mispredict.
      const double a = z[i - 2], b = z[i - 1], c = z[i + 1], d = z[i + 2];
      const double lo = std::max(std::min(a, b), std::min(c, d)), hi = std::min(std::max(a, b), std::max(c, d));
      med = 0.5 * (hi + lo);
    } else {
      // The points up to two places away on each side (at the ends, those that exist: 2 or 3).
      w.clear();
      for (std::size_t j = i >= 2 ? i - 2 : 0; j <= i + 2 && j < n; ++j)
        if (j != i) w.push_back(z[j]);
      med = median_of(w);
    }
    const double dev = std::abs(z[i] - med) / s.rms;
    if (dev > k) s.points.push_back(i), s.worst = std::max(s.worst, dev);
  }
  return s;
}

SpikeSearch find_spikes(const Map& mp, double k) {
  SpikeSearch s;
  s.rms = rms_about_mean(mp.heights);
  if (!(s.rms > 0)) return s;
  std::vector<double> w;
  w.reserve(8);
  for (std::size_t j = 0; j < mp.ny; ++j)
    for (std::size_t i = 0; i < mp.nx; ++i) {
      const double z = mp.at(i, j);
      if (!std::isfinite(z)) continue;
      w.clear();
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          if (!di && !dj) continue;
          const long ii = long(i) + di, jj = long(j) + dj;
          if (ii < 0 || jj < 0 || ii >= long(mp.nx) || jj >= long(mp.ny)) continue;
          const double v = mp.at(std::size_t(ii), std::size_t(jj));
          if (std::isfinite(v)) w.push_back(v);
        }
      if (w.size() < 3) continue;
      const double dev = std::abs(z - median_of(w)) / s.rms;
      if (dev > k) s.points.push_back(j * mp.nx + i), s.worst = std::max(s.worst, dev);
    }
  return s;
}

namespace {

// condition() of p; with `take` (p itself) p's points move into the result where no crop copies
// a window of them.
Result<ConditionedProfile> condition_impl(const Profile& p, Profile* take, const Conditioning& c,
                                          const std::string& name) {
  if (auto st = check_threshold(c); !st) return st.error();
  ConditionedProfile out;
  ConditioningRecord& r = out.record;
  r.is_map = false;
  r.form = c.form;
  r.nx_before = r.nx_after = p.size();
  r.ny_before = r.ny_after = 1;
  Profile cur;
  if (c.crop) {
    const CropWindow& w = *c.crop;
    if (auto st = check_window(w, c.crop_source); !st) return st.error();
    if (w.has_y)
      return make_error(fmt::format("{}: a window along y ({}), but {} is a line profile; expected x0,x1",
                                    c.crop_source, window_text(w), name));
    if (p.size() < 2) return make_error(fmt::format("{}: {} has fewer than 2 points", c.crop_source, name));
    const double tol = 1e-9 * p.length() / double(p.size() - 1);
    const auto a = std::lower_bound(p.x.begin(), p.x.end(), w.x_min - tol) - p.x.begin();
    const auto b = std::upper_bound(p.x.begin(), p.x.end(), w.x_max + tol) - p.x.begin();
    const std::size_t kept = b > a ? std::size_t(b - a) : 0;
    if (kept < 2 || !(p.x[std::size_t(b - 1)] > p.x[std::size_t(a)]))
      return make_error(fmt::format(
          "{}: the window x {} keeps {} of the {} points of {}, whose x spans {}; expected a "
          "window inside that extent that keeps at least 2 points",
          c.crop_source, range_text(w.x_min, w.x_max), kept, p.size(), name, range_text(p.x_min(), p.x_max())));
    cur.x.assign(p.x.begin() + a, p.x.begin() + b);
    cur.z.assign(p.z.begin() + a, p.z.begin() + b);
    if (kept == p.size()) cur.period = p.period;  // a crop that keeps everything keeps the period
    r.cropped = true;
    r.window = w;
    r.nx_after = kept;
  } else if (take) {
    cur = std::move(*take);
  } else {
    cur = p;
  }
  std::optional<Profile> formed;
  if (c.remove_spikes) {
    r.spikes_checked = true;
    r.spike_threshold = c.spike_threshold;
    while (r.spike_passes < kMaxSpikePasses) {
      auto f = detrend(cur, c.form);
      if (!f) return f.error();
      const SpikeSearch s = find_spikes(*f, c.spike_threshold);
      ++r.spike_passes;
      if (s.points.empty()) {
        formed = std::move(f).value();
        break;
      }
      // Remove the spikes from the polyline: each one between kept points is replaced by the
      // straight line between its nearest kept neighbours (the sampling grid stays), those with no
      // kept point on one side (at an end) are dropped. Both give the profile without them.
      std::vector<char> spike(cur.size(), 0);
      for (std::size_t i : s.points) spike[i] = 1;
      std::size_t first = 0, last = cur.size() - 1;
      while (first < cur.size() && spike[first]) ++first;
      while (last > first && spike[last]) --last;
      if (last <= first || cur.x[last] <= cur.x[first])
        return make_error(
            fmt::format("{}: the spike filter (k = {:g}) flags all but {} of the {} points; expected a "
                        "threshold that leaves the surface",
                        name, c.spike_threshold, last >= first ? last - first + 1 : 0, cur.size()));
      for (std::size_t i = first + 1; i < last; ++i) {
        if (!spike[i]) continue;
        std::size_t l = i - 1, h = i + 1;
        while (spike[l]) --l;
        while (spike[h]) ++h;
        const double dx = cur.x[h] - cur.x[l];
        const double t = dx > 0 ? (cur.x[i] - cur.x[l]) / dx : 0.5;
        cur.z[i] = cur.z[l] + t * (cur.z[h] - cur.z[l]);
      }
      // The neighbours read above were never spikes of this pass, so the order does not matter.
      if (first > 0 || last + 1 < cur.size()) {
        r.spikes_dropped += first + (cur.size() - 1 - last);
        cur.x = std::vector<double>(cur.x.begin() + std::ptrdiff_t(first), cur.x.begin() + std::ptrdiff_t(last + 1));
        cur.z = std::vector<double>(cur.z.begin() + std::ptrdiff_t(first), cur.z.begin() + std::ptrdiff_t(last + 1));
        cur.period.reset();  // shorter than the periods it covered
      }
      r.spikes_removed += s.points.size();
    }
  }
  r.spikes_left = c.remove_spikes && !formed;
  if (!formed) {
    auto f = detrend(std::move(cur), c.form);
    if (!f) return f.error();
    formed = std::move(f).value();
  }
  out.profile = std::move(*formed);
  return out;
}

}  // namespace

Result<ConditionedProfile> condition(const Profile& p, const Conditioning& c, const std::string& name) {
  return condition_impl(p, nullptr, c, name);
}

Result<ConditionedProfile> condition(Profile&& p, const Conditioning& c, const std::string& name) {
  return condition_impl(p, &p, c, name);
}

Result<ConditionedMap> condition(const Map& m, const Conditioning& c, const std::string& name) {
  if (auto st = check_threshold(c); !st) return st.error();
  ConditionedMap out;
  ConditioningRecord& r = out.record;
  r.is_map = true;
  r.form = c.form;
  r.nx_before = r.nx_after = m.nx;
  r.ny_before = r.ny_after = m.ny;
  Map cur;
  if (c.crop) {
    const CropWindow& w = *c.crop;
    if (auto st = check_window(w, c.crop_source); !st) return st.error();
    std::size_t nx = 0, ny = m.ny;
    const auto [i0, i1] = grid_range(m.x0, m.dx, m.nx, w.x_min, w.x_max, nx);
    std::pair<std::size_t, std::size_t> jr{0, m.ny ? m.ny - 1 : 0};
    if (w.has_y) jr = grid_range(m.y0, m.dy, m.ny, w.y_min, w.y_max, ny);
    const std::string extent = fmt::format("whose x spans {} and y {}", range_text(m.x0, m.x0 + m.width()),
                                           range_text(m.y0, m.y0 + m.height()));
    if (nx < std::min<std::size_t>(2, m.nx) || ny < std::min<std::size_t>(2, m.ny))
      return make_error(
          fmt::format("{}: the window {} keeps {} x {} of the {} x {} points of {}, {}; expected a window "
                      "inside that extent that keeps at least 2 points along each side",
                      c.crop_source, window_text(w), nx, ny, m.nx, m.ny, name, extent));
    cur.nx = nx, cur.ny = ny, cur.dx = m.dx, cur.dy = m.dy;
    cur.x0 = m.x0 + double(i0) * m.dx;
    cur.y0 = m.y0 + double(jr.first) * m.dy;
    cur.heights.resize(nx * ny);
    for (std::size_t j = 0; j < ny; ++j)
      std::copy_n(m.heights.begin() + std::ptrdiff_t((jr.first + j) * m.nx + i0), nx,
                  cur.heights.begin() + std::ptrdiff_t(j * nx));
    (void)i1;
    if (cur.valid_count() == 0)
      return make_error(fmt::format("{}: the window {} keeps no valid point of {} ({} x {} points, all masked); {}",
                                    c.crop_source, window_text(w), name, nx, ny, extent));
    r.cropped = true;
    r.window = w;
    r.nx_after = nx, r.ny_after = ny;
  } else {
    cur = m;
  }
  std::optional<Map> formed;
  if (c.remove_spikes) {
    r.spikes_checked = true;
    r.spike_threshold = c.spike_threshold;
    while (r.spike_passes < kMaxSpikePasses) {
      auto f = detrend(cur, c.form);
      if (!f) return f.error();
      const SpikeSearch s = find_spikes(*f, c.spike_threshold);
      ++r.spike_passes;
      if (s.points.empty()) {
        formed = std::move(f).value();
        break;
      }
      for (std::size_t k : s.points) cur.heights[k] = std::numeric_limits<double>::quiet_NaN();
      r.spikes_removed += s.points.size();
    }
  }
  r.spikes_left = c.remove_spikes && !formed;
  if (!formed) {
    auto f = detrend(cur, c.form);
    if (!f) return f.error();
    formed = std::move(f).value();
  }
  out.map = std::move(*formed);
  return out;
}

}  // namespace frictal
