// SVG plots (Cartesian, polar, height-map images), PNG encoding (zlib) and base64 for self-contained pages.
#include <fmt/core.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include <zlib.h>

#include "frictal/report.hpp"
#include "viridis_data.hpp"

namespace frictal::report {

namespace {

constexpr std::array<const char*, 8> kPalette = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                                 "#9467bd", "#8c564b", "#e377c2", "#17becf"};
constexpr double kFont = 12;        // tick and legend font size (px)
constexpr double kCharWidth = 6.8;  // estimated advance of a 12 px sans-serif digit (px)

bool finite(double v) { return std::isfinite(v); }

/// FNV-1a hash: deterministic element ids derived from the content (no global counter).
std::uint64_t fnv1a(const std::string& s) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

/// Tick label: as many decimals as the tick step needs, no trailing noise, "−" for minus.
std::string tick_label(double v, double step) {
  if (std::abs(v) < step * 1e-9) v = 0;
  std::string s;
  const double mag = std::max(std::abs(v), step);
  if (mag >= 1e6 || step < 1e-5) {
    s = fmt::format("{:.3g}", v);
  } else {
    int dec = std::max(0, int(std::ceil(-std::log10(step) - 1e-9)));
    // steps of 2.5 x 10^k need one more decimal
    const double scaled = step * std::pow(10.0, dec);
    if (std::abs(scaled - std::round(scaled)) > 1e-6) ++dec;
    s = fmt::format("{:.{}f}", v, dec);
  }
  if (!s.empty() && s[0] == '-') s = "\u2212" + s.substr(1);
  return s;
}

std::size_t text_chars(const std::string& s) {
  std::size_t n = 0;
  for (unsigned char c : s) n += (c & 0xC0) != 0x80 ? 1 : 0;  // UTF-8 code points
  return n;
}

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!finite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool empty() const { return !(lo <= hi); }
};

/// Extends a degenerate range and adds a margin (fraction of the span) on both sides.
void widen(double& lo, double& hi, double margin) {
  if (hi - lo <= 0) {
    const double d = lo != 0 ? std::abs(lo) * 0.1 : 1.0;
    lo -= d;
    hi += d;
    return;
  }
  const double m = (hi - lo) * margin;
  lo -= m;
  hi += m;
}

/// Min/max decimation of a polyline for a plot `pixels` wide: at most 4 points per pixel column,
/// keeping each column's first, extreme and last points so that peaks survive.
void decimate(const std::vector<double>& x, const std::vector<double>& y, double x0, double x1, double pixels,
              std::vector<double>& ox, std::vector<double>& oy) {
  const std::size_t n = x.size();
  if (double(n) <= 4 * pixels || !(x1 > x0)) {
    ox = x;
    oy = y;
    return;
  }
  long col = std::numeric_limits<long>::min();
  std::size_t first = 0, imin = 0, imax = 0, last = 0;
  auto flush = [&]() {
    if (col == std::numeric_limits<long>::min()) return;
    std::array<std::size_t, 4> idx = {first, imin, imax, last};
    std::sort(idx.begin(), idx.end());
    std::size_t prev = std::size_t(-1);
    for (auto k : idx)
      if (k != prev) {
        ox.push_back(x[k]);
        oy.push_back(y[k]);
        prev = k;
      }
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!finite(x[i]) || !finite(y[i])) {
      flush();
      col = std::numeric_limits<long>::min();
      ox.push_back(std::numeric_limits<double>::quiet_NaN());
      oy.push_back(std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    const long c = long(std::floor((x[i] - x0) / (x1 - x0) * pixels));
    if (c != col) {
      flush();
      col = c;
      first = imin = imax = last = i;
    } else {
      last = i;
      if (y[i] < y[imin]) imin = i;
      if (y[i] > y[imax]) imax = i;
    }
  }
  flush();
}

std::string stroke_attrs(const Series& s, const std::string& color) {
  return fmt::format("fill=\"none\" stroke=\"{}\" stroke-width=\"{:.2f}\"{} stroke-linejoin=\"round\"", color,
                     s.line_width, s.dashed ? " stroke-dasharray=\"6 4\"" : "");
}

std::string legend_svg(const std::vector<Series>& series, const std::vector<std::string>& colors, double right,
                       double top) {
  std::vector<std::size_t> shown;
  std::size_t longest = 0;
  for (std::size_t i = 0; i < series.size(); ++i)
    if (!series[i].label.empty()) {
      shown.push_back(i);
      longest = std::max(longest, text_chars(series[i].label));
    }
  if (shown.empty()) return {};
  const double w = 40 + double(longest) * 7.4, h = 8 + 16 * double(shown.size());
  const double x = right - w - 6, y = top + 6;
  std::string s = fmt::format(
      "<g class=\"legend\"><rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"white\" "
      "fill-opacity=\"0.85\" stroke=\"#ccc\"/>",
      x, y, w, h);
  for (std::size_t k = 0; k < shown.size(); ++k) {
    const Series& se = series[shown[k]];
    const double yy = y + 12 + 16 * double(k);
    if (se.style == SeriesStyle::Points)
      s += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"3\" fill=\"{}\"/>", x + 15, yy, colors[shown[k]]);
    else
      s += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" {}/>", x + 6, yy, x + 24, yy,
                       stroke_attrs(se, colors[shown[k]]));
    s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"{}\" dominant-baseline=\"middle\">{}</text>", x + 30,
                     yy + 0.5, kFont, escape_html(se.label));
  }
  return s + "</g>";
}

std::string svg_open(double w, double h, const std::string& title) {
  return fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot\" width=\"{0:.0f}\" height=\"{1:.0f}\" "
      "viewBox=\"0 0 {0:.0f} {1:.0f}\" font-family=\"DejaVu Sans, Arial, sans-serif\" role=\"img\" "
      "aria-label=\"{2}\"><rect width=\"100%\" height=\"100%\" fill=\"white\"/>",
      w, h, escape_html(title));
}

std::vector<std::string> series_colors(const std::vector<Series>& series) {
  std::vector<std::string> c;
  std::size_t next = 0;
  for (const auto& s : series) c.push_back(s.color.empty() ? kPalette[next++ % kPalette.size()] : s.color);
  return c;
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target) {
  std::vector<double> t;
  if (!(finite(lo) && finite(hi)) || target < 1) return t;
  if (hi < lo) std::swap(lo, hi);
  if (hi == lo) return {lo};
  const double raw = (hi - lo) / target;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10 * p;
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * p >= raw * 0.999) {
      step = m * p;
      break;
    }
  const double first = std::ceil(lo / step - 1e-9) * step;
  for (int k = 0;; ++k) {
    const double v = first + k * step;
    if (v > hi + step * 1e-9) break;
    t.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
    if (k > 1000) break;
  }
  return t;
}

LengthUnit length_unit(double magnitude) {
  magnitude = std::abs(magnitude);
  if (!(magnitude > 0) || !finite(magnitude)) return {1, "m"};
  if (magnitude >= 1) return {1, "m"};
  if (magnitude >= 1e-3) return {1e-3, "mm"};
  if (magnitude >= 1e-6) return {1e-6, "\u00b5m"};
  if (magnitude >= 1e-9) return {1e-9, "nm"};
  return {1e-12, "pm"};
}

std::string escape_html(const std::string& text) {
  std::string o;
  o.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\'': o += "&#39;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string base64(const std::string& bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string o;
  o.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = (std::uint32_t(std::uint8_t(bytes[i])) << 16) |
                            (std::uint32_t(std::uint8_t(bytes[i + 1])) << 8) | std::uint8_t(bytes[i + 2]);
    o += kAlphabet[(v >> 18) & 63];
    o += kAlphabet[(v >> 12) & 63];
    o += kAlphabet[(v >> 6) & 63];
    o += kAlphabet[v & 63];
  }
  if (i < bytes.size()) {
    std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) v |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    o += kAlphabet[(v >> 18) & 63];
    o += kAlphabet[(v >> 12) & 63];
    o += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    o += '=';
  }
  return o;
}

namespace {

void put32(std::string& s, std::uint32_t v) {
  s += char((v >> 24) & 255);
  s += char((v >> 16) & 255);
  s += char((v >> 8) & 255);
  s += char(v & 255);
}

/// A PNG chunk: length, type, data and the CRC-32 (zlib's) of type and data.
void chunk(std::string& png, const char* type, const std::string& data) {
  put32(png, std::uint32_t(data.size()));
  const std::size_t start = png.size();
  png += type;
  png += data;
  put32(png, std::uint32_t(::crc32(::crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(png.data() + start),
                                   uInt(png.size() - start))));
}

}  // namespace

Result<std::string> encode_png(std::size_t width, std::size_t height, const std::vector<std::uint8_t>& rgb) {
  if (width == 0 || height == 0 || width > 100000 || height > 100000 || rgb.size() != width * height * 3)
    return make_error(fmt::format("encode_png: expected {} x {} x 3 bytes, got {}", width, height, rgb.size()));
  // Scanlines, each with filter byte 0 (None): a height map's image has few distinct colours (at
  // most the colour map's 256), which deflate's repeated strings catch best unfiltered (for a
  // 512^2 map's 256^2 image: 72 kB; filters Up, Paeth or per-row adaptive: 83-86 kB).
  const std::size_t stride = 3 * width;
  std::string raw;
  raw.reserve(height * (1 + stride));
  for (std::size_t r = 0; r < height; ++r) {
    raw += char(0);
    raw.append(reinterpret_cast<const char*>(rgb.data() + r * stride), stride);
  }
  // The zlib stream (deflate, Adler-32) of the scanlines.
  uLongf size = compressBound(uLong(raw.size()));
  std::string z(size, '\0');
  const int rc = compress2(reinterpret_cast<Bytef*>(z.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
                           uLong(raw.size()), Z_BEST_COMPRESSION);
  if (rc != Z_OK) return make_error(ErrorCode::Internal, fmt::format("encode_png: zlib compress2 failed ({})", rc));
  z.resize(size);
  std::string png("\x89PNG\r\n\x1a\n", 8);
  std::string ihdr;
  put32(ihdr, std::uint32_t(width));
  put32(ihdr, std::uint32_t(height));
  ihdr += char(8);               // bit depth
  ihdr += char(2);               // colour type: RGB
  ihdr += std::string(3, '\0');  // compression, filter, interlace
  chunk(png, "IHDR", ihdr);
  chunk(png, "IDAT", z);
  chunk(png, "IEND", "");
  return png;
}

void viridis(double t, std::uint8_t rgb[3]) {
  // matplotlib's viridis (viridis_data.hpp, its 256 entries) looked up as matplotlib does: entry
  // floor(256 t), the last one for t = 1; each channel rounded to the nearest byte.
  if (!finite(t)) t = 0;
  const int k = std::min(255, int(std::clamp(t, 0.0, 1.0) * 256));
  for (int c = 0; c < 3; ++c) rgb[c] = std::uint8_t(std::lround(detail::kViridis[k][c] * 255));
}

Result<std::string> plot_svg(const Plot& input) {
  Plot plot = input;
  if (plot.x_log) {  // draw log10(x) on a linear axis, ticks labelled with x
    auto lg = [](double v) { return v > 0 ? std::log10(v) : std::numeric_limits<double>::quiet_NaN(); };
    for (auto& se : plot.series)
      for (auto& v : se.x) v = lg(v);
    for (auto& l : plot.lines)
      if (!l.horizontal) l.value = lg(l.value);
    if (plot.x_min) plot.x_min = lg(*plot.x_min);
    if (plot.x_max) plot.x_max = lg(*plot.x_max);
  }
  Range xr, yr;
  for (const auto& s : plot.series) {
    const bool step = s.style == SeriesStyle::Step;
    if (step ? s.x.size() != s.y.size() + 1 : s.x.size() != s.y.size())
      return make_error(
          fmt::format("plot '{}': series '{}' has {} x and {} y values", plot.title, s.label, s.x.size(), s.y.size()));
    for (std::size_t i = 0; i < s.y.size(); ++i) {
      const double x0 = s.x[i], x1 = step ? s.x[i + 1] : s.x[i];
      if (finite(x0) && finite(x1) && finite(s.y[i])) {
        xr.add(x0);
        xr.add(x1);
        yr.add(s.y[i]);
        if (step) yr.add(0);
      }
    }
  }
  if (xr.empty() || yr.empty()) return make_error(fmt::format("plot '{}': no finite data to draw", plot.title));
  for (const auto& l : plot.lines) (l.horizontal ? yr : xr).add(l.value);
  for (const auto& b : plot.bands) {
    if (!(finite(b.lo) && finite(b.hi) && b.hi >= b.lo))
      return make_error(fmt::format("plot '{}': band '{}' needs finite lo <= hi", plot.title, b.label));
    (b.horizontal ? yr : xr).add(b.lo);
    (b.horizontal ? yr : xr).add(b.hi);
  }
  double x0 = xr.lo, x1 = xr.hi, y0 = yr.lo, y1 = yr.hi;
  bool points_only = true;
  for (const auto& s : plot.series) points_only = points_only && s.style == SeriesStyle::Points;
  widen(x0, x1, points_only ? 0.04 : 0.0);
  widen(y0, y1, 0.06);
  if (plot.x_min) x0 = *plot.x_min;
  if (plot.x_max) x1 = *plot.x_max;
  if (plot.y_min) y0 = *plot.y_min;
  if (plot.y_max) y1 = *plot.y_max;
  if (!(x1 > x0) || !(y1 > y0)) return make_error(fmt::format("plot '{}': empty axis range", plot.title));

  std::vector<double> xt;
  std::vector<std::string> xlabels;
  if (plot.x_log) {
    const bool fine = x1 - x0 < 2.5;
    for (int k = int(std::floor(x0)); k <= int(std::ceil(x1)); ++k)
      for (double m : {1.0, 2.0, 5.0}) {
        if (m != 1.0 && !fine) continue;
        const double v = k + std::log10(m);
        if (v < x0 - 1e-9 || v > x1 + 1e-9) continue;
        xt.push_back(v);
        xlabels.push_back(fmt::format("{:g}", m * std::pow(10.0, k)));
      }
    if (xt.size() < 2) {  // less than a decade without a 1-2-5 mark inside: linear ticks of x itself
      xt.clear();
      xlabels.clear();
      const auto lin = nice_ticks(std::pow(10.0, x0), std::pow(10.0, x1), 3);
      const double step = lin.size() > 1 ? lin[1] - lin[0] : std::pow(10.0, x0);
      for (double v : lin)
        if (v > 0) {
          xt.push_back(std::log10(v));
          xlabels.push_back(tick_label(v, step));
        }
    }
  } else {
    xt = nice_ticks(x0, x1, std::max(3, int(plot.width / 110)));
  }
  const auto yt = nice_ticks(y0, y1, std::max(3, int(plot.height / 60)));
  const double xstep = xt.size() > 1 ? xt[1] - xt[0] : (x1 - x0);
  const double ystep = yt.size() > 1 ? yt[1] - yt[0] : (y1 - y0);
  std::size_t ylab = 1;
  for (double v : yt) ylab = std::max(ylab, text_chars(tick_label(v, ystep)));
  const double ml = 30 + 10 + double(ylab) * kCharWidth, mr = 18, mt = plot.title.empty() ? 14 : 34, mb = 50;
  const double pw = plot.width - ml - mr, ph = plot.height - mt - mb;
  if (pw < 40 || ph < 40) return make_error(fmt::format("plot '{}': figure too small", plot.title));
  auto X = [&](double v) { return ml + (v - x0) / (x1 - x0) * pw; };
  auto Y = [&](double v) { return mt + (y1 - v) / (y1 - y0) * ph; };

  std::string body;
  // grid and ticks
  for (std::size_t ti = 0; ti < xt.size(); ++ti) {
    const double v = xt[ti];
    body += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\" stroke=\"#e6e6e6\"/>", X(v),
                        mt, mt + ph);
    body += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\" stroke=\"#333\"/>", X(v),
                        mt + ph, mt + ph + 5);
    body += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"{}\" text-anchor=\"middle\">{}</text>", X(v),
                        mt + ph + 18, kFont, plot.x_log ? xlabels[ti] : tick_label(v, xstep));
  }
  for (double v : yt) {
    body += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\" stroke=\"#e6e6e6\"/>", ml,
                        Y(v), ml + pw);
    body += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\" stroke=\"#333\"/>", ml - 5,
                        Y(v), ml);
    body += fmt::format(
        "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"{}\" text-anchor=\"end\" dominant-baseline=\"middle\">{}</text>",
        ml - 8, Y(v), kFont, tick_label(v, ystep));
  }
  // data, clipped to the plot area
  const std::string clip_placeholder = "@CLIP@";
  body += fmt::format("<g clip-path=\"url(#{})\">", clip_placeholder);
  const auto colors = series_colors(plot.series);
  for (const auto& b : plot.bands) {
    if (b.horizontal)
      body += fmt::format(
          "<rect x=\"{:.1f}\" y=\"{:.2f}\" width=\"{:.1f}\" height=\"{:.2f}\" fill=\"{}\" "
          "fill-opacity=\"{:.3g}\"/>",
          ml, Y(b.hi), pw, std::max(0.5, Y(b.lo) - Y(b.hi)), b.color, b.opacity);
    else
      body += fmt::format(
          "<rect x=\"{:.2f}\" y=\"{:.1f}\" width=\"{:.2f}\" height=\"{:.1f}\" fill=\"{}\" "
          "fill-opacity=\"{:.3g}\"/>",
          X(b.lo), mt, std::max(0.5, X(b.hi) - X(b.lo)), ph, b.color, b.opacity);
  }
  for (const auto& l : plot.lines) {
    if (l.horizontal)
      body += fmt::format(
          "<line x1=\"{:.1f}\" y1=\"{:.2f}\" x2=\"{:.1f}\" y2=\"{:.2f}\" stroke=\"{}\" "
          "stroke-dasharray=\"3 3\"/>",
          ml, Y(l.value), ml + pw, Y(l.value), l.color);
    else
      body += fmt::format(
          "<line x1=\"{:.2f}\" y1=\"{:.1f}\" x2=\"{:.2f}\" y2=\"{:.1f}\" stroke=\"{}\" "
          "stroke-dasharray=\"3 3\"/>",
          X(l.value), mt, X(l.value), mt + ph, l.color);
  }
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const Series& s = plot.series[k];
    if (s.style == SeriesStyle::Points) {
      body += fmt::format("<g fill=\"{}\">", colors[k]);
      for (std::size_t i = 0; i < s.x.size(); ++i)
        if (finite(s.x[i]) && finite(s.y[i]))
          body += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"2.6\"/>", X(s.x[i]), Y(s.y[i]));
      body += "</g>";
      continue;
    }
    std::vector<double> px, py;
    if (s.style == SeriesStyle::Step) {
      for (std::size_t i = 0; i < s.y.size(); ++i) {
        px.insert(px.end(), {s.x[i], s.x[i + 1]});
        py.insert(py.end(), {s.y[i], s.y[i]});
      }
    } else {
      decimate(s.x, s.y, x0, x1, pw, px, py);
    }
    std::string pts;
    auto emit = [&]() {
      if (!pts.empty()) body += fmt::format("<polyline points=\"{}\" {}/>", pts, stroke_attrs(s, colors[k]));
      pts.clear();
    };
    for (std::size_t i = 0; i < px.size(); ++i) {
      if (!finite(px[i]) || !finite(py[i])) {
        emit();
        continue;
      }
      // keep far-off points finite for the renderer
      const double yy = std::clamp(Y(py[i]), -1e4, 1e4), xx = std::clamp(X(px[i]), -1e4, 1e4);
      pts += fmt::format("{}{:.2f},{:.2f}", pts.empty() ? "" : " ", xx, yy);
    }
    emit();
  }
  body += "</g>";
  for (const auto& b : plot.bands)
    if (!b.label.empty())
      body += fmt::format(
          "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"11\" fill=\"#555\" stroke=\"#fff\" stroke-width=\"3\" "
          "paint-order=\"stroke\">{}</text>",
          b.horizontal ? ml + 4 : X(b.lo) + 3, b.horizontal ? Y(b.hi) + 13 : mt + 0.5 * ph, escape_html(b.label));
  for (const auto& l : plot.lines)
    if (!l.label.empty()) {
      if (l.horizontal)
        body += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"11\" fill=\"{}\">{}</text>", ml + 4,
                            Y(l.value) - 4, l.color, escape_html(l.label));
      else
        // Along the line, reading upwards from the bottom, with a white halo over the data.
        body += fmt::format(
            "<text x=\"{0:.1f}\" y=\"{1:.1f}\" transform=\"rotate(-90 {0:.1f} {1:.1f})\" font-size=\"11\" "
            "fill=\"{2}\" stroke=\"#fff\" stroke-width=\"3\" paint-order=\"stroke\">{3}</text>",
            X(l.value) + 12, mt + ph - 4, l.color, escape_html(l.label));
    }
  body += fmt::format(
      "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"none\" "
      "stroke=\"#333\"/>",
      ml, mt, pw, ph);
  body += legend_svg(plot.series, colors, ml + pw, mt);
  body += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"13\" text-anchor=\"middle\">{}</text>", ml + pw / 2,
                      plot.height - 12, escape_html(plot.x_label));
  body += fmt::format(
      "<text transform=\"translate(16 {:.1f}) rotate(-90)\" font-size=\"13\" "
      "text-anchor=\"middle\">{}</text>",
      mt + ph / 2, escape_html(plot.y_label));
  if (!plot.title.empty())
    body += fmt::format(
        "<text x=\"{:.1f}\" y=\"21\" font-size=\"14\" font-weight=\"bold\" "
        "text-anchor=\"middle\">{}</text>",
        plot.width / 2, escape_html(plot.title));
  const std::string id = fmt::format("clip{:016x}", fnv1a(body));
  body.replace(body.find(clip_placeholder), clip_placeholder.size(), id);
  return svg_open(plot.width, plot.height, plot.title) +
         fmt::format(
             "<defs><clipPath id=\"{}\"><rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\"/>"
             "</clipPath></defs>",
             id, ml, mt, pw, ph) +
         body + "</svg>";
}

Result<std::string> polar_svg(const PolarPlot& plot) {
  Range rr;
  for (const auto& s : plot.series) {
    if (s.x.size() != s.y.size() || s.style == SeriesStyle::Step)
      return make_error(fmt::format("polar plot '{}': series '{}' must be lines or points with as many angles as radii",
                                    plot.title, s.label));
    for (std::size_t i = 0; i < s.y.size(); ++i)
      if (finite(s.x[i]) && finite(s.y[i])) rr.add(s.y[i]);
  }
  if (rr.empty()) return make_error(fmt::format("polar plot '{}': no finite data to draw", plot.title));
  double rmax = plot.r_max ? *plot.r_max : rr.hi;
  if (!(rmax > 0)) rmax = 1;
  auto rings = nice_ticks(0, rmax, 4);
  if (!plot.r_max && !rings.empty() && rings.back() < rmax)
    rings.push_back(rings.back() + (rings.size() > 1 ? rings[1] - rings[0] : rmax));
  if (!plot.r_max && !rings.empty()) rmax = rings.back();
  const double rstep = rings.size() > 1 ? rings[1] - rings[0] : rmax;
  const double w = plot.size, top = plot.title.empty() ? 10 : 36;
  std::size_t nlabels = 0;
  for (const auto& s : plot.series) nlabels += s.label.empty() ? 0 : 1;
  const double bottom = 28 + 16 * double(nlabels);
  const double R = std::min(w / 2 - 44, (w - top - bottom) / 2 - 22);
  const double h = top + 2 * R + 44 + bottom;
  const double cx = w / 2, cy = top + 22 + R;
  auto P = [&](double ang, double r) {
    const double rr2 = std::clamp(r / rmax, 0.0, 1.05) * R;
    return std::pair<double, double>{cx + rr2 * std::cos(ang), cy - rr2 * std::sin(ang)};
  };
  std::string s = svg_open(w, h, plot.title);
  for (double r : rings) {
    if (r <= 0) continue;
    s += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"{:.1f}\" fill=\"none\" stroke=\"{}\"/>", cx, cy,
                     r / rmax * R, r >= rmax * (1 - 1e-9) ? "#333" : "#ddd");
  }
  for (int d = 0; d < 360; d += 30) {
    const double a = d * std::numbers::pi / 180;
    auto [x, y] = P(a, rmax);
    s += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"#ddd\"/>", cx, cy, x, y);
    const double lx = cx + (R + 18) * std::cos(a), ly = cy - (R + 18) * std::sin(a);
    s += fmt::format(
        "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"{}\" text-anchor=\"middle\" "
        "dominant-baseline=\"middle\">{}\u00b0</text>",
        lx, ly, kFont, d);
  }
  for (double r : rings) {
    if (r <= 0) continue;
    // ring labels along the 75-degree spoke, clear of the data's usual extremes
    auto [x, y] = P(75 * std::numbers::pi / 180, r);
    s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"11\" fill=\"#555\">{}</text>", x + 3, y - 2,
                     tick_label(r, rstep));
  }
  const auto colors = series_colors(plot.series);
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const Series& se = plot.series[k];
    if (se.style == SeriesStyle::Points) {
      for (std::size_t i = 0; i < se.x.size(); ++i) {
        if (!finite(se.x[i]) || !finite(se.y[i])) continue;
        auto [x, y] = P(se.x[i], se.y[i]);
        s += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"2.6\" fill=\"{}\"/>", x, y, colors[k]);
      }
      continue;
    }
    std::string pts;
    for (std::size_t i = 0; i < se.x.size(); ++i) {
      if (!finite(se.x[i]) || !finite(se.y[i])) continue;
      auto [x, y] = P(se.x[i], se.y[i]);
      pts += fmt::format("{}{:.2f},{:.2f}", pts.empty() ? "" : " ", x, y);
    }
    Range ar;
    for (double a : se.x) ar.add(a);
    const bool closed = !ar.empty() && ar.hi - ar.lo >= 2 * std::numbers::pi * (1 - 1.5 / double(se.x.size()));
    if (!pts.empty())
      s += fmt::format("<{} points=\"{}\" {}/>", closed ? "polygon" : "polyline", pts, stroke_attrs(se, colors[k]));
  }
  // legend below the circle
  double ly = cy + R + 40;
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    if (plot.series[k].label.empty()) continue;
    s += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" {}/>", 20.0, ly, 40.0, ly,
                     stroke_attrs(plot.series[k], colors[k]));
    s += fmt::format("<text x=\"46\" y=\"{:.1f}\" font-size=\"{}\" dominant-baseline=\"middle\">{}</text>", ly + 0.5,
                     kFont, escape_html(plot.series[k].label));
    ly += 16;
  }
  s += fmt::format(
      "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"12\" text-anchor=\"end\" fill=\"#555\">radius: {}</text>", w - 8,
      ly + 6, escape_html(plot.radius_label));
  if (!plot.title.empty())
    s += fmt::format(
        "<text x=\"{:.1f}\" y=\"21\" font-size=\"14\" font-weight=\"bold\" text-anchor=\"middle\">{}</text>", w / 2,
        escape_html(plot.title));
  return s + "</svg>";
}

Result<std::string> map_svg(const Map& m, const MapImage& o) {
  if (auto st = validate(m, "map_svg map"); !st) return st.error();
  if (o.max_pixels < 2) return make_error("map_svg: max_pixels must be >= 2");
  // Block-average to at most max_pixels along the longer side.
  const std::size_t f = std::max<std::size_t>(1, (std::max(m.nx, m.ny) + o.max_pixels - 1) / o.max_pixels);
  const std::size_t w = (m.nx + f - 1) / f, hgt = (m.ny + f - 1) / f;
  std::vector<double> img(w * hgt, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t bj = 0; bj < hgt; ++bj)
    for (std::size_t bi = 0; bi < w; ++bi) {
      double sum = 0;
      std::size_t n = 0;
      for (std::size_t j = bj * f; j < std::min(m.ny, bj * f + f); ++j)
        for (std::size_t i = bi * f; i < std::min(m.nx, bi * f + f); ++i)
          if (finite(m.at(i, j))) {
            sum += m.at(i, j);
            ++n;
          }
      if (n) img[bj * w + bi] = sum / double(n);
    }
  std::vector<double> valid;
  for (double v : m.heights)
    if (finite(v)) valid.push_back(v);
  std::sort(valid.begin(), valid.end());
  auto quantile = [&](double q) {
    return valid[std::size_t(std::lround(std::clamp(q, 0.0, 1.0) * double(valid.size() - 1)))];
  };
  double zlo = quantile(o.low_quantile), zhi = quantile(o.high_quantile);
  if (!(zhi > zlo)) {
    zlo = valid.front();
    zhi = valid.back();
  }
  if (!(zhi > zlo)) {
    zlo -= 1e-9;
    zhi += 1e-9;
  }
  std::vector<std::uint8_t> rgb(w * hgt * 3);
  for (std::size_t r = 0; r < hgt; ++r)
    for (std::size_t i = 0; i < w; ++i) {
      const double v = img[(hgt - 1 - r) * w + i];  // row ny-1 (largest y) at the top
      std::uint8_t* px = &rgb[(r * w + i) * 3];
      if (!finite(v)) {
        px[0] = px[1] = px[2] = 190;
      } else {
        viridis((v - zlo) / (zhi - zlo), px);
      }
    }
  auto png = encode_png(w, hgt, rgb);
  if (!png) return png.error();
  std::vector<std::uint8_t> bar(1 * 128 * 3);
  for (std::size_t r = 0; r < 128; ++r) viridis(1.0 - double(r) / 127.0, &bar[r * 3]);
  auto bar_png = encode_png(1, 128, bar);
  if (!bar_png) return bar_png.error();

  // Layout: the image keeps the map's physical aspect ratio.
  const double W = std::max(m.width(), m.dx), H = std::max(m.height(), m.dy);
  const LengthUnit lu = length_unit(std::max(W, H));
  const LengthUnit zu = length_unit(std::max(std::abs(zlo), std::abs(zhi)) > 0 ? (zhi - zlo) : 1e-9);
  const double ty0 = o.absolute_axes ? m.y0 : 0;
  auto ytl = nice_ticks(ty0 / lu.scale, (ty0 + H) / lu.scale, 5);
  std::size_t ylab = 1;
  const double ystep = ytl.size() > 1 ? ytl[1] - ytl[0] : 1;
  for (double v : ytl) ylab = std::max(ylab, text_chars(tick_label(v, ystep)));
  const double ml = 40 + double(ylab) * kCharWidth, mt = o.title.empty() ? 14 : 36, mb = 50;
  const double bar_w = 18, bar_gap = 16;
  std::size_t zlab = 1;
  {
    const auto zt = nice_ticks(zlo / zu.scale, zhi / zu.scale, 5);
    const double zs = zt.size() > 1 ? zt[1] - zt[0] : 1;
    for (double v : zt) zlab = std::max(zlab, text_chars(tick_label(v, zs)));
  }
  const double bar_labels = double(zlab) * kCharWidth + 36;
  double iw = o.width - ml - bar_gap - bar_w - bar_labels - 10;
  double ih = iw * H / W;
  const double max_h = 460;
  if (ih > max_h) {
    ih = max_h;
    iw = ih * W / H;
  }
  if (ih < 60) ih = 60;  // very elongated maps: stretch a little rather than vanish
  const double total_w = ml + iw + bar_gap + bar_w + bar_labels + 10, total_h = mt + ih + mb;
  std::string s = svg_open(total_w, total_h, o.title);
  s += fmt::format(
      "<image x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" preserveAspectRatio=\"none\" "
      "style=\"image-rendering:pixelated\" href=\"data:image/png;base64,{}\"/>",
      ml, mt, iw, ih, base64(*png));
  s += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"none\" stroke=\"#333\"/>",
                   ml, mt, iw, ih);
  auto px_of = [&](double x) { return ml + (x - m.x0) / W * iw; };
  auto py_of = [&](double y) { return mt + ih - (y - m.y0) / H * ih; };
  if (o.path_x.size() >= 2 && o.path_x.size() == o.path_y.size()) {
    std::string pts;
    for (std::size_t k = 0; k < o.path_x.size(); ++k)
      pts += fmt::format("{:.1f},{:.1f} ", px_of(o.path_x[k]), py_of(o.path_y[k]));
    s += fmt::format(
        "<polyline points=\"{0}\" fill=\"none\" stroke=\"white\" stroke-width=\"4\"/>"
        "<polyline points=\"{0}\" fill=\"none\" stroke=\"#d62728\" stroke-width=\"2\"/>",
        pts);
    if (!o.path_label.empty())
      s += fmt::format(
          "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"11\" fill=\"white\" stroke=\"black\" "
          "stroke-width=\"2.5\" paint-order=\"stroke\">{}</text>",
          px_of(o.path_x.back()) + 6, py_of(o.path_y.back()) + 4, escape_html(o.path_label));
  }
  for (const auto& mk : o.marks) {
    const double x = px_of(mk.x), y = py_of(mk.y);
    s += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"5\" fill=\"{}\" stroke=\"white\" stroke-width=\"2\"/>", x,
                     y, mk.color);
    if (!mk.label.empty())
      s += fmt::format(
          "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"11\" fill=\"white\" stroke=\"black\" "
          "stroke-width=\"2.5\" paint-order=\"stroke\">{}</text>",
          x + 7, y - 6, escape_html(mk.label));
  }
  if (o.line_y) {
    const double y = mt + ih - (*o.line_y - m.y0) / H * ih;
    const double xa = ml + (o.line_x0 - m.x0) / W * iw, xb = ml + (o.line_x1 - m.x0) / W * iw;
    s += fmt::format(
        "<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\" stroke=\"white\" "
        "stroke-width=\"3\"/><line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\" "
        "stroke=\"#d62728\" stroke-width=\"1.5\" stroke-dasharray=\"6 4\"/>",
        xa, y, xb, y);
    if (!o.line_label.empty())
      s += fmt::format(
          "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"11\" fill=\"white\" stroke=\"black\" "
          "stroke-width=\"2.5\" paint-order=\"stroke\">{}</text>",
          xa + 4, y - 5, escape_html(o.line_label));
  }
  // lateral axes (from the map's first node, or at its coordinates)
  const double ax0 = o.absolute_axes ? m.x0 : 0, ay0 = o.absolute_axes ? m.y0 : 0;
  auto xtl = nice_ticks(ax0 / lu.scale, (ax0 + W) / lu.scale, std::max(3, int(iw / 90)));
  const double xstep = xtl.size() > 1 ? xtl[1] - xtl[0] : 1;
  for (double v : xtl) {
    const double x = ml + (v * lu.scale - ax0) / W * iw;
    s += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{0:.1f}\" y2=\"{2:.1f}\" stroke=\"#333\"/>", x, mt + ih,
                     mt + ih + 5);
    s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"{}\" text-anchor=\"middle\">{}</text>", x,
                     mt + ih + 18, kFont, tick_label(v, xstep));
  }
  for (double v : ytl) {
    const double y = mt + ih - (v * lu.scale - ay0) / H * ih;
    s += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\" stroke=\"#333\"/>", ml - 5, y,
                     ml);
    s += fmt::format(
        "<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"{}\" text-anchor=\"end\" "
        "dominant-baseline=\"middle\">{}</text>",
        ml - 8, y, kFont, tick_label(v, ystep));
  }
  s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"13\" text-anchor=\"middle\">{} ({})</text>",
                   ml + iw / 2, total_h - 12, escape_html(o.x_label), lu.name);
  s += fmt::format(
      "<text transform=\"translate(16 {:.1f}) rotate(-90)\" font-size=\"13\" "
      "text-anchor=\"middle\">{} ({})</text>",
      mt + ih / 2, escape_html(o.y_label), lu.name);
  // scale bar: a round length near a fifth of the width, bottom left inside the image
  {
    const double target = W / 5;
    const double p = std::pow(10.0, std::floor(std::log10(target)));
    double len = p;
    for (double k : {1.0, 2.0, 5.0})
      if (k * p <= target) len = k * p;
    const LengthUnit bu = length_unit(len);
    const double px_len = len / W * iw, x = ml + 10, y = mt + ih - 12;
    s += fmt::format(
        "<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"22\" fill=\"white\" "
        "fill-opacity=\"0.8\"/>",
        x - 5, y - 16, std::max(px_len, 50.0) + 10);
    s += fmt::format(
        "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"black\" "
        "stroke-width=\"3\"/>",
        x, y, x + px_len, y);
    s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"11\">{:g} {}</text>", x, y - 5, len / bu.scale,
                     bu.name);
  }
  // colour bar
  const double bx = ml + iw + bar_gap;
  s += fmt::format(
      "<image x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" preserveAspectRatio=\"none\" "
      "href=\"data:image/png;base64,{}\"/>",
      bx, mt, bar_w, ih, base64(*bar_png));
  s += fmt::format("<rect x=\"{:.1f}\" y=\"{:.1f}\" width=\"{:.1f}\" height=\"{:.1f}\" fill=\"none\" stroke=\"#333\"/>",
                   bx, mt, bar_w, ih);
  auto ztl = nice_ticks(zlo / zu.scale, zhi / zu.scale, 5);
  const double zstep = ztl.size() > 1 ? ztl[1] - ztl[0] : 1;
  for (double v : ztl) {
    const double y = mt + ih - (v * zu.scale - zlo) / (zhi - zlo) * ih;
    s += fmt::format("<line x1=\"{0:.1f}\" y1=\"{1:.1f}\" x2=\"{2:.1f}\" y2=\"{1:.1f}\" stroke=\"#333\"/>", bx + bar_w,
                     y, bx + bar_w + 4);
    s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"{}\" dominant-baseline=\"middle\">{}</text>",
                     bx + bar_w + 7, y, kFont, tick_label(v, zstep));
  }
  s += fmt::format(
      "<text transform=\"translate({:.1f} {:.1f}) rotate(90)\" font-size=\"13\" "
      "text-anchor=\"middle\">{} ({})</text>",
      std::min(total_w - 6, bx + bar_w + bar_labels - 4), mt + ih / 2, escape_html(o.z_label), zu.name);
  if (!o.title.empty())
    s += fmt::format(
        "<text x=\"{:.1f}\" y=\"21\" font-size=\"14\" font-weight=\"bold\" text-anchor=\"middle\">{}</text>",
        total_w / 2, escape_html(o.title));
  return s + "</svg>";
}

}  // namespace frictal::report
