// The SVG/PNG building blocks of frictal report and the report page itself. Expected values come
// from RFC/PNG specifications (base64 vectors, the IEND CRC), from the data drawn, or from the
// sawtooth's analytic signature (theta_max = the rise angle, phi = theta_max + atan(mu_a)).
#include <fmt/core.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <regex>
#include <string>

#include <zlib.h>

#include "frictal/areal.hpp"
#include "frictal/generators.hpp"
#include "frictal/report.hpp"
#include "report/sections.hpp"

namespace {

namespace rp = frictal::report;
constexpr double kDeg = std::numbers::pi / 180;

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (auto p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

std::uint32_t be32(const std::string& s, std::size_t at) {
  return (std::uint32_t(std::uint8_t(s[at])) << 24) | (std::uint32_t(std::uint8_t(s[at + 1])) << 16) |
         (std::uint32_t(std::uint8_t(s[at + 2])) << 8) | std::uint8_t(s[at + 3]);
}

std::string fmt_like(double deg) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f\u00b0", deg);
  return b;
}

/// No network: nothing on the page may point at http(s) (the SVG namespace URI is an identifier).
void expect_self_contained(const std::string& page) {
  std::string s = page;
  const std::string ns = "xmlns=\"http://www.w3.org/2000/svg\"";
  for (auto p = s.find(ns); p != std::string::npos; p = s.find(ns)) s.erase(p, ns.size());
  EXPECT_EQ(s.find("http:"), std::string::npos);
  EXPECT_EQ(s.find("https:"), std::string::npos);
  EXPECT_EQ(count(s, "src=\""), count(s, "src=\"data:"));
  EXPECT_EQ(count(s, "href=\""), count(s, "href=\"data:") + count(s, "href=\"#"));
}

}  // namespace

TEST(Report, Base64MatchesRfc4648Vectors) {
  EXPECT_EQ(rp::base64(""), "");
  EXPECT_EQ(rp::base64("f"), "Zg==");
  EXPECT_EQ(rp::base64("fo"), "Zm8=");
  EXPECT_EQ(rp::base64("foo"), "Zm9v");
  EXPECT_EQ(rp::base64("foob"), "Zm9vYg==");
  EXPECT_EQ(rp::base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(rp::base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(rp::base64(std::string("\xff\xfe", 2)), "//4=");
}

/// The pixels of an 8-bit RGB PNG, decoded as the PNG specification says: every chunk's CRC-32
/// checked, the IDAT data inflated with zlib's uncompress and each scanline unfiltered (any of the
/// five filter types). Fails the test (and returns nothing) on anything else.
static std::vector<std::uint8_t> decode_rgb_png(const std::string& s, std::size_t& w, std::size_t& h) {
  EXPECT_EQ(s.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  std::string idat;
  bool end = false;
  for (std::size_t at = 8; at + 12 <= s.size() && !end;) {
    const std::size_t len = be32(s, at);
    if (at + 12 + len > s.size()) break;
    const std::string type = s.substr(at + 4, 4);
    const std::uint32_t crc =
        std::uint32_t(crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(s.data() + at + 4), uInt(4 + len)));
    EXPECT_EQ(be32(s, at + 8 + len), crc) << type;
    if (type == "IHDR") {
      w = be32(s, at + 8);
      h = be32(s, at + 12);
      EXPECT_EQ(int(std::uint8_t(s[at + 16])), 8);  // bit depth
      EXPECT_EQ(int(std::uint8_t(s[at + 17])), 2);  // RGB
    }
    if (type == "IDAT") idat += s.substr(at + 8, len);
    end = type == "IEND";
    at += 12 + len;
  }
  EXPECT_TRUE(end);
  const std::size_t stride = 3 * w;
  std::string raw(h * (1 + stride), '\0');
  uLongf raw_size = uLongf(raw.size());
  EXPECT_EQ(uncompress(reinterpret_cast<Bytef*>(raw.data()), &raw_size, reinterpret_cast<const Bytef*>(idat.data()),
                       uLong(idat.size())),
            Z_OK);
  EXPECT_EQ(raw_size, raw.size());
  std::vector<std::uint8_t> px(h * stride);
  for (std::size_t r = 0; r < h; ++r) {
    const int filter = std::uint8_t(raw[r * (1 + stride)]);
    EXPECT_LE(filter, 4);
    for (std::size_t i = 0; i < stride; ++i) {
      const int x = std::uint8_t(raw[r * (1 + stride) + 1 + i]);
      const int a = i >= 3 ? px[r * stride + i - 3] : 0, b = r > 0 ? px[(r - 1) * stride + i] : 0,
                c = i >= 3 && r > 0 ? px[(r - 1) * stride + i - 3] : 0;
      const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
      const int pred = filter == 1   ? a
                       : filter == 2 ? b
                       : filter == 3 ? (a + b) / 2
                       : filter == 4 ? (pa <= pb && pa <= pc ? a
                                        : pb <= pc           ? b
                                                             : c)
                                     : 0;
      px[r * stride + i] = std::uint8_t(x + pred);
    }
  }
  return px;
}

TEST(Report, PngDecodesWithZlibToThePixelsPutIn) {
  // 3 x 2 pixels: red, green, blue / white, black, grey.
  const std::vector<std::uint8_t> rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255, 0, 0, 0, 128, 128, 128};
  auto png = rp::encode_png(3, 2, rgb);
  ASSERT_TRUE(png);
  const std::string& s = *png;
  EXPECT_EQ(be32(s, 8), 13u);
  EXPECT_EQ(s.substr(12, 4), "IHDR");
  // IEND is always 00000000 "IEND" AE426082 (PNG specification).
  EXPECT_EQ(s.substr(s.size() - 12), std::string("\0\0\0\0IEND\xae\x42\x60\x82", 12));
  std::size_t w = 0, h = 0;
  EXPECT_EQ(decode_rgb_png(s, w, h), rgb);
  EXPECT_EQ(w, 3u);
  EXPECT_EQ(h, 2u);
  // A larger image: pseudo-random bytes (every byte value, rows that differ) and a smooth ramp.
  const std::size_t W = 67, H = 41;
  std::vector<std::uint8_t> noise(W * H * 3), ramp(W * H * 3);
  std::uint32_t state = 12345;
  for (std::size_t i = 0; i < noise.size(); ++i) {
    state = state * 1664525u + 1013904223u;
    noise[i] = std::uint8_t(state >> 24);
    ramp[i] = std::uint8_t((i / 3 % W) * 3 + (i / 3 / W) * 2 + i % 3);
  }
  for (const auto* img : {&noise, &ramp}) {
    auto p = rp::encode_png(W, H, *img);
    ASSERT_TRUE(p);
    EXPECT_EQ(decode_rgb_png(*p, w, h), *img);
    EXPECT_EQ(w, W);
    EXPECT_EQ(h, H);
  }
  // Compressed: the ramp's file is far smaller than its pixels (stored blocks would be larger).
  EXPECT_LT(rp::encode_png(W, H, ramp)->size(), ramp.size() / 4);
  EXPECT_FALSE(rp::encode_png(3, 3, rgb));
}

TEST(Report, ViridisIsMatplotlibs) {
  // matplotlib's published viridis values: viridis(0) #440154, viridis(0.5) #21918c, viridis(1)
  // #fde725; and entries 32 (#472d7b), 224 (#addc30) of its 256 (matplotlib.colormaps['viridis'](k / 255)).
  const auto hex = [](double t) {
    std::uint8_t c[3];
    rp::viridis(t, c);
    return fmt::format("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
  };
  EXPECT_EQ(hex(0), "#440154");
  EXPECT_EQ(hex(0.5), "#21918c");
  EXPECT_EQ(hex(1), "#fde725");
  EXPECT_EQ(hex(32.0 / 255), "#472d7b");
  EXPECT_EQ(hex(224.0 / 255), "#addc30");
  EXPECT_EQ(hex(-1), "#440154");  // clamped
  EXPECT_EQ(hex(2), "#fde725");
  EXPECT_EQ(hex(std::nan("")), "#440154");
}

TEST(Report, NiceTicksAndUnits) {
  EXPECT_EQ(rp::nice_ticks(0, 1, 5), (std::vector<double>{0, 0.2, 0.4, 0.6000000000000001, 0.8, 1}));
  const auto t = rp::nice_ticks(-3.7, 12.2, 6);
  ASSERT_FALSE(t.empty());
  EXPECT_GE(t.front(), -3.7);
  EXPECT_LE(t.back(), 12.2);
  EXPECT_DOUBLE_EQ(t[1] - t[0], 5);                    // span 15.9 / 6 = 2.65 per tick: the next nice step is 5
  EXPECT_DOUBLE_EQ(rp::nice_ticks(0, 10, 4)[1], 2.5);  // 2.5 per tick exactly
  EXPECT_EQ(rp::length_unit(2.4e-3).name, "mm");
  EXPECT_EQ(rp::length_unit(650e-6).name, "\u00b5m");
  EXPECT_EQ(rp::length_unit(3e-9).name, "nm");
  EXPECT_DOUBLE_EQ(rp::length_unit(3e-9).scale, 1e-9);
}

TEST(Report, PlotDrawsEverySeriesWithLabelsAndRefusesEmptyPlots) {
  rp::Plot p;
  p.title = "t & <x>";
  p.x_label = "x (\u00b5m)";
  p.y_label = "z (nm)";
  p.series.push_back({{0, 1, 2, 3}, {0, 1, 0, 1}, "line", "", rp::SeriesStyle::Line});
  p.series.push_back({{0, 1, 2}, {0.5, 0.25}, "hist", "", rp::SeriesStyle::Step});
  p.series.push_back({{0.5, 1.5}, {0.2, 0.8}, "", "", rp::SeriesStyle::Points});
  auto svg = rp::plot_svg(p);
  ASSERT_TRUE(svg) << svg.error().message;
  EXPECT_EQ(count(*svg, "<polyline"), 2u);
  EXPECT_EQ(count(*svg, "<circle"), 2u);
  EXPECT_NE(svg->find("t &amp; &lt;x&gt;"), std::string::npos);
  EXPECT_NE(svg->find("x (\u00b5m)"), std::string::npos);
  EXPECT_NE(svg->find("z (nm)"), std::string::npos);
  EXPECT_FALSE(std::regex_search(*svg, std::regex("[^a-z]nan[^a-z]|inf")));
  rp::Plot empty;
  empty.title = "nothing";
  EXPECT_FALSE(rp::plot_svg(empty));
  empty.series.push_back({{0, 1}, {NAN, NAN}, "", "", rp::SeriesStyle::Line});
  auto e = rp::plot_svg(empty);
  ASSERT_FALSE(e);
  EXPECT_NE(e.error().message.find("nothing"), std::string::npos);
  rp::Plot bad;
  bad.series.push_back({{0, 1, 2}, {0, 1}, "bad", "", rp::SeriesStyle::Line});
  EXPECT_FALSE(rp::plot_svg(bad));
}

TEST(Report, LogAxisTicksAreLabelledWithTheValues) {
  rp::Plot p;
  p.x_log = true;
  p.series.push_back({{1e-3, 1e-2, 1e-1}, {1, 2, 3}, "", "", rp::SeriesStyle::Line});
  auto svg = rp::plot_svg(p);
  ASSERT_TRUE(svg);
  for (const char* t : {">0.001<", ">0.01<", ">0.1<"}) EXPECT_NE(svg->find(t), std::string::npos) << t;
  // less than a decade: ticks of x itself (3, 3.5, 4, 4.5)
  p.series[0].x = {3, 4, 4.5};
  auto narrow = rp::plot_svg(p);
  ASSERT_TRUE(narrow);
  EXPECT_NE(narrow->find(">3.5<"), std::string::npos);
  EXPECT_NE(narrow->find(">4.5<"), std::string::npos);
  p.series[0].x = {-1, 0, -2};  // nothing positive on a log axis
  EXPECT_FALSE(rp::plot_svg(p));
}

TEST(Report, PolarPlotClosesAFullCircle) {
  rp::PolarPlot p;
  p.title = "polar";
  rp::Series s;
  for (int k = 0; k < 36; ++k) {
    s.x.push_back(k * 10 * kDeg);
    s.y.push_back(20 + 5 * std::cos(2 * k * 10 * kDeg));
  }
  p.series.push_back(s);
  auto svg = rp::polar_svg(p);
  ASSERT_TRUE(svg) << svg.error().message;
  EXPECT_EQ(count(*svg, "<polygon"), 1u);
  EXPECT_NE(svg->find("90\u00b0"), std::string::npos);
}

TEST(Report, MapImageEmbedsAPngOfTheDownsampledMap) {
  frictal::Map m;
  m.nx = 700;
  m.ny = 100;
  m.dx = m.dy = 1e-6;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) m.heights.push_back(1e-8 * double(i) + (i == 5 ? NAN : 0.0));
  rp::MapImage o;
  o.max_pixels = 100;
  auto svg = rp::map_svg(m, o);
  ASSERT_TRUE(svg) << svg.error().message;
  // two images (map, colour bar); the map's PNG is ceil(700/7) x ceil(100/7) = 100 x 15 pixels
  EXPECT_EQ(count(*svg, "href=\"data:image/png;base64,"), 2u);
  const auto p = svg->find("base64,") + 7;
  const std::string b64 = svg->substr(p, 32);
  EXPECT_EQ(b64.substr(0, 8), rp::base64("\x89PNG\r\n").substr(0, 8));
  EXPECT_NE(svg->find("x (\u00b5m)"), std::string::npos);
  EXPECT_NE(svg->find("height z (\u00b5m)"), std::string::npos);  // 7 um of relief
}

TEST(Report, SawtoothPageStatesTheAnalyticPrediction) {
  frictal::SawtoothParams sp;
  sp.rise_angle = 20 * kDeg;
  sp.rise_fraction = 0.7;
  auto saw = frictal::sawtooth_profile(sp);
  ASSERT_TRUE(saw);
  rp::ReportInput in;
  in.lower = *saw;
  in.lower_name = "saw.csv";
  in.detrend = "none";
  in.atomic_friction = 0.2;
  in.resolution_steps = 4;
  in.threads = 2;
  auto page = rp::surface_report(in);
  ASSERT_TRUE(page) << page.error().message;
  // Sawtooth against itself turned over: theta_max forward = the rising flank (20 deg), backward the
  // falling one, atan(tan 20 * 0.7 / 0.3); phi = 20 deg + atan 0.2, mu = tan phi.
  const double back = std::atan(std::tan(20 * kDeg) * 0.7 / 0.3) / kDeg;
  const double phi = 20 + std::atan(0.2) / kDeg;
  EXPECT_NE(page->find("20.000\u00b0"), std::string::npos);
  EXPECT_NE(page->find(fmt_like(back)), std::string::npos);
  EXPECT_NE(page->find(fmt_like(phi)), std::string::npos);
  char mu[32];
  std::snprintf(mu, sizeof mu, "%.4f", std::tan(phi * kDeg));
  EXPECT_NE(page->find(std::string("<b>") + mu + "</b>"), std::string::npos);
  EXPECT_NE(page->find("turned over"), std::string::npos);
  EXPECT_NE(page->find("Conditioning applied"), std::string::npos);
  EXPECT_GE(count(*page, "<svg"), 4u);  // surface, signature, slopes, resolution
  expect_self_contained(*page);
}

TEST(Report, MapPageHasImagePolarPlotAndCentralLine) {
  // Ridges along y: a symmetric 20-degree sawtooth in x, flat in y.
  frictal::Map m;
  m.nx = 64;
  m.ny = 16;
  m.dx = m.dy = 1e-6;
  const double period = 16e-6;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) {
      const double u = std::fmod(double(i) * m.dx, period) / period;
      m.heights.push_back(std::tan(20 * kDeg) * period * (u < 0.5 ? u : 1 - u));
    }
  rp::ReportInput in;
  in.is_map = true;
  in.map = m;
  in.lower_name = "ridges.x3p";
  in.detrend = "none";
  in.directions = 2;  // across the ridges both ways (along them a block tilts to the model's largest tilt, slowly)
  in.map_drops = 2;
  in.resolution_steps = 3;
  in.threads = 2;
  auto page = rp::surface_report(in);
  ASSERT_TRUE(page) << page.error().message;
  EXPECT_NE(page->find("The map over sliding directions"), std::string::npos);
  // the hold angle's median, 5 % and 95 %; the hold model's bound and the signature's
  EXPECT_EQ(count(*page, "<polygon"), 5u);
  EXPECT_NE(page->find("central line along x"), std::string::npos);
  // The polar plot's rows: the map against itself turned over. Across the ridges (0 and 180
  // degrees) its areal signature climbs the flanks, theta_max = 20 degrees both ways.
  auto row = [&](const char* dir) {
    const auto at = page->find(std::string("<tr><td>") + dir + "\u00b0</td>");
    return at == std::string::npos ? std::string() : page->substr(at, page->find("</tr>", at) - at);
  };
  EXPECT_NE(row("0.0").find("<td>20.0000\u00b0 / 20.0000\u00b0</td>"), std::string::npos) << row("0.0");
  EXPECT_NE(row("180.0").find("<td>20.0000\u00b0 / 20.0000\u00b0</td>"), std::string::npos) << row("180.0");
  EXPECT_GE(count(*page, "data:image/png;base64,"), 2u);
  expect_self_contained(*page);
  in.upper = frictal::Profile{};
  EXPECT_FALSE(rp::surface_report(in));
}

TEST(Report, TwoMapsShowThePredictionsHoldAnglesOnTheLift) {
  // Grooves across x (A sin(2 pi i / m) along x, the same in every row) and a 12 x 12 window of
  // them turned over: they mate, the block gains nothing by moving along the grooves, and from
  // every drop it climbs the steepest segment of the piecewise-linear grooves, slope
  // A sin(2 pi / m) / a (by hand; as tests/predict's grooves). The section shows the prediction's
  // model (no grid model): its drops and the block dropped at s = 0 hold there.
  const std::size_t nx = 32, ny = 24;
  const int m = 8;
  const double a = 1e-6, A = 2.4e-8 * 15;
  frictal::Map g;
  g.nx = nx;
  g.ny = ny;
  g.dx = g.dy = a;
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) g.heights.push_back(A * std::sin(2 * std::numbers::pi * double(i) / m));
  frictal::Map u;
  u.nx = u.ny = 12;
  u.dx = u.dy = a;
  for (std::size_t j = 0; j < 12; ++j)
    for (std::size_t i = 0; i < 12; ++i) u.heights.push_back(g.at(i + 4, j + 4));
  rp::ReportInput in;
  in.is_map = true;
  in.map = g;
  in.upper_map = u;
  in.lower_name = "lower.x3p";
  in.upper_name = "upper.x3p";
  in.detrend = "none";
  in.directions = 2;  // +x and -x: along the grooves a block tilts to the model's largest tilt, slowly
  in.resolution_steps = 0;
  const double want = std::atan(A * std::sin(2 * std::numbers::pi / m) / a);
  auto d = rp::report_data(in);
  ASSERT_TRUE(d) << d.error().message;
  ASSERT_TRUE(d->areal_hold);
  const rp::ReportArealHold& h = *d->areal_hold;
  ASSERT_TRUE(h.failure.empty()) << h.failure;
  EXPECT_EQ(h.prediction.model, "map-continuous-free");
  EXPECT_EQ(h.prediction.drops, 25u);
  EXPECT_GE(h.prediction.friction_angle.min, want - 1e-9);
  EXPECT_LE(h.prediction.friction_angle.max, want + 2e-4);  // bisected to 1e-4 rad
  EXPECT_TRUE(h.from_zero.ran_away);
  EXPECT_GE(h.from_zero.hold_angle, want - 1e-9);
  EXPECT_LE(h.from_zero.hold_angle, want + 2e-4);
  // The prediction is predict()'s on the same maps (no form removed again) ...
  frictal::PredictSurface pl, pu;
  pl.is_map = pu.is_map = true;
  pl.map = g;
  pu.map = u;
  frictal::PredictOptions po;
  po.detrend = frictal::Detrend{frictal::DetrendKind::None, 0};
  auto p = frictal::predict(pl, &pu, po);
  ASSERT_TRUE(p) << p.error().message;
  EXPECT_EQ(h.prediction.drop_angles, p->drop_angles);
  // The polar plot is the pair's: along +x its hold angles are the same prediction's, and its
  // bound the hold model's.
  ASSERT_TRUE(d->directions);
  ASSERT_TRUE(d->directions->pair);
  ASSERT_TRUE(d->directions->failure.empty()) << d->directions->failure;
  ASSERT_TRUE(d->directions->hold_failure.empty()) << d->directions->hold_failure;
  ASSERT_EQ(d->directions->pair_table.size(), 2u);
  const frictal::AnisotropyRow& plus_x = d->directions->pair_table[0];
  EXPECT_EQ(plus_x.direction, 0.0);
  ASSERT_TRUE(plus_x.hold_angle);
  EXPECT_EQ(plus_x.hold_angle->q50, p->friction_angle.q50);
  EXPECT_EQ(plus_x.hold_angle->q95, p->friction_angle.q95);
  EXPECT_EQ(plus_x.upper_bound_friction_angle, p->upper_bound_friction_angle);
  EXPECT_TRUE(plus_x.signature_bound_friction_angle);
  // ... and a prediction given with the input (the CLI's headline) is the one the section shows.
  in.prediction = *p;
  in.prediction->friction_angle.q50 = 0.5;  // marked: the section must take it, not recompute
  auto page = rp::surface_report(in);
  ASSERT_TRUE(page) << page.error().message;
  EXPECT_NE(page->find("Areal blocks that may move sideways"), std::string::npos);
  EXPECT_NE(page->find("Lift h with the prediction"), std::string::npos);
  EXPECT_GE(count(*page, "<polyline points="), 2u);  // the block's path (white under red)
  EXPECT_NE(page->find(">rest</text>"), std::string::npos);
  EXPECT_NE(page->find("median " + fmt_like(0.5 / kDeg)), std::string::npos);
  EXPECT_NE(page->find(fmt::format("over {} drops", p->drops)), std::string::npos);
  // No grid model on the page: no locked column without the prediction's locked drops.
  EXPECT_EQ(page->find("locked (1D rule)"), std::string::npos);
  EXPECT_EQ(page->find("a diagnostic)</th>"), std::string::npos);
  expect_self_contained(*page);
}

TEST(Report, TipRadiusCutoffIsDrawnOnTheResolutionPlot) {
  // A triangle wave of slope +-s with its kinks on the samples (period 64 dx): at a peak the
  // stencil curvature is -2 s / h for every h up to half a period (linear interpolation is exact
  // there), so the cutoff -- the stencil length 2h where it reaches -1/(2R) -- is 8 s R
  // (docs/analysis.md). R = 500 nm / (8 s) puts it at 500 nm. The resolution study's 6 cutoffs
  // run from L/2 = 25.6 um down to 4 dx = 0.4 um geometrically: only the last one lies below.
  const double dx = 1e-7, s = 0.1, R = 500e-9 / (8 * s);
  rp::ReportInput in;
  for (int i = 0; i < 512; ++i) {
    in.lower.x.push_back(i * dx);
    in.lower.z.push_back(s * dx * (16 - std::abs(i % 64 - 32)));
  }
  in.lower_name = "triangle.csv";
  in.detrend = "none";
  in.resolution_steps = 6;
  in.threads = 2;
  in.tip_radius = R;
  auto page = rp::surface_report(in);
  ASSERT_TRUE(page) << page.error().message;
  const auto at = page->find("short reliability cutoff for a tip of radius");
  ASSERT_NE(at, std::string::npos);
  EXPECT_NE(page->substr(at, 120).find(": 500 nm (below it"), std::string::npos) << page->substr(at, 120);
  EXPECT_NE(page->find("reliable above"), std::string::npos);  // the vertical line's label
  EXPECT_EQ(count(*page, "(below tip cutoff)"), 1u);
  EXPECT_EQ(count(*page, "class=\"below-tip\""), 1u);
  // A tip 100 times sharper follows every scale: no line, no marked row.
  in.tip_radius = R / 100;
  auto sharp = rp::surface_report(in);
  ASSERT_TRUE(sharp) << sharp.error().message;
  EXPECT_NE(sharp->find("down to the sampling interval"), std::string::npos);
  EXPECT_EQ(count(*sharp, "(below tip cutoff)"), 0u);
  EXPECT_EQ(sharp->find("reliable above"), std::string::npos);
  // Without a tip radius the page says nothing about it; a negative one is refused.
  in.tip_radius = 0;
  auto none = rp::surface_report(in);
  ASSERT_TRUE(none);
  EXPECT_EQ(none->find("tip of radius"), std::string::npos);
  EXPECT_EQ(none->find("reliable above"), std::string::npos);
  in.tip_radius = -1e-9;
  EXPECT_FALSE(rp::surface_report(in));
}

// --- the analyses and the section writers apart (src/report/data.cpp, sections.cpp) ---------------

TEST(Report, DataIsTheLibrarysAnalysesAndThePageIsWrittenFromIt) {
  frictal::SawtoothParams sp;
  sp.rise_angle = 20 * kDeg;
  sp.rise_fraction = 0.7;
  auto saw = frictal::sawtooth_profile(sp);
  ASSERT_TRUE(saw);
  rp::ReportInput in;
  in.lower = *saw;
  in.lower_name = "saw.csv";
  in.atomic_friction = 0.2;
  in.resolution_steps = 3;
  in.threads = 2;
  auto d = rp::report_data(in);
  ASSERT_TRUE(d) << d.error().message;
  // The signature and Eq. 6 are the library's calls on the same pair.
  frictal::SignatureOptions so;
  so.keep_contacts = false;
  so.bins = in.bins;
  auto sig = frictal::signature(*saw, frictal::rotate180(*saw), so);
  ASSERT_TRUE(sig);
  EXPECT_EQ(d->signature.theta_max_forward, sig->theta_max_forward);
  EXPECT_EQ(d->signature.theta_max_backward, sig->theta_max_backward);
  auto fwd = frictal::predict_friction(0.2, sig->theta_max_forward, sig->contact_slope_std);
  ASSERT_TRUE(fwd);
  EXPECT_EQ(d->forward.friction_angle, fwd->friction_angle);
  EXPECT_NEAR(d->forward.friction_angle, 20 * kDeg + std::atan(0.2), 1e-9);
  // Sections present as computed: a profile has no directions and no areal section.
  EXPECT_FALSE(d->directions);
  EXPECT_FALSE(d->areal_hold);
  ASSERT_TRUE(d->resolution);
  EXPECT_EQ(d->resolution->rows.size(), 3u);
  // The slope densities integrate to the share of the length inside the range.
  double area = 0;
  for (std::size_t i = 0; i < d->slopes.lower.density.size(); ++i)
    area += d->slopes.lower.density[i] * (d->slopes.lower.edges[i + 1] - d->slopes.lower.edges[i]);
  EXPECT_NEAR(area, 1 - d->slopes.outside_length / d->slopes.total_length, 1e-9);
  // The page is the page of these results.
  auto page = rp::report_page(in, *d);
  ASSERT_TRUE(page) << page.error().message;
  auto whole = rp::surface_report(in);
  ASSERT_TRUE(whole);
  EXPECT_EQ(*page, *whole);
  // Refused inputs are refused by the analysis step.
  in.bins = 1;
  EXPECT_FALSE(rp::report_data(in));
}

TEST(Report, FrictionSectionWritesTheResultsItIsGiven) {
  // Hand-made results: the writer formats them and computes nothing.
  rp::ReportInput in;
  in.atomic_friction = 0.25;
  rp::ReportData d;
  d.signature.theta_max_forward = 12.5 * kDeg;
  d.signature.theta_max_backward = 7.25 * kDeg;
  d.signature.contact_slope_std = 3 * kDeg;
  d.forward.atomic_angle = d.backward.atomic_angle = 14 * kDeg;
  d.forward.friction_angle = 26.5 * kDeg;
  d.forward.friction_angle_low = 23.5 * kDeg;
  d.forward.friction_coefficient = 0.5;
  d.forward.friction_coefficient_low = 0.4321;
  d.backward.friction_angle = 21.25 * kDeg;
  d.backward.friction_angle_low = 18.25 * kDeg;
  d.backward.friction_coefficient = 0.375;
  d.backward.friction_coefficient_low = 0.3;
  auto html = rp::detail::friction_section(in, d);
  ASSERT_TRUE(html) << html.error().message;
  EXPECT_NE(html->find("<td>12.500\u00b0</td><td>7.250\u00b0</td>"), std::string::npos) << *html;
  EXPECT_NE(html->find("<td>0.25, 14.000\u00b0</td>"), std::string::npos);
  EXPECT_NE(html->find("<td>23.500\u00b0 \u2026 26.500\u00b0</td><td>18.250\u00b0 \u2026 21.250\u00b0</td>"),
            std::string::npos);
  EXPECT_NE(html->find("\u03bc \u2264 0.5000 sliding towards +x (Eq. 18's range below it 0.4321 \u2026 0.5000"),
            std::string::npos)
      << *html;
  EXPECT_NE(html->find("\u03bc \u2264 0.3750 towards \u2212x, with \u03bc_a = 0.25"), std::string::npos);
  d.forward.friction_coefficient = std::numeric_limits<double>::infinity();
  html = rp::detail::friction_section(in, d);
  ASSERT_TRUE(html);
  EXPECT_NE(html->find("\u221e (interlocked)"), std::string::npos);
}

TEST(Report, ResolutionSectionMarksTheRowsBelowTheTipAndSaysWhenTooShort) {
  rp::ReportInput in;
  in.tip_radius = 1e-6;
  rp::ReportData d;
  d.surfaces.lower.x = {0, 1e-4};
  d.surfaces.lower.z = {0, 0};
  d.surfaces.upper = d.surfaces.lower;
  d.signature.theta_max_forward = 10 * kDeg;
  rp::ReportResolution res;
  res.cutoff_min = 4e-7;
  res.cutoff_max = 5e-5;
  res.offsets = 1000;
  res.tip_cutoff = 2e-6;
  for (double c : {5e-5, 5e-6, 5e-7}) {
    rp::ReportResolutionRow row;
    row.cutoff = c;
    row.theta_max_forward = (c > 1e-6 ? 4 : 8) * kDeg;
    row.friction_coefficient = c > 1e-6 ? 0.0699 : -0.1;
    row.below_tip = c < *res.tip_cutoff;
    res.rows.push_back(row);
  }
  d.resolution = res;
  auto html = rp::detail::resolution_section(in, d);
  ASSERT_TRUE(html) << html.error().message;
  EXPECT_EQ(count(*html, "class=\"below-tip\""), 1u);
  EXPECT_NE(html->find("<td>0.5 \u00b5m (below tip cutoff)</td><td>8.000\u00b0</td>"), std::string::npos) << *html;
  EXPECT_NE(html->find("0 (\u03b8_a + \u03b8_max &lt; 0)"), std::string::npos);
  EXPECT_NE(html->find("at 3 cutoffs"), std::string::npos);
  EXPECT_NE(html->find("goes from 4.000\u00b0 to 8.000\u00b0 (unfiltered: 10.000\u00b0)"), std::string::npos);
  EXPECT_NE(html->find(": 2 \u00b5m (below it"), std::string::npos);
  EXPECT_NE(html->find("reliable above"), std::string::npos);
  // No rows: the range was too short for a study.
  d.resolution->rows.clear();
  html = rp::detail::resolution_section(in, d);
  ASSERT_TRUE(html);
  EXPECT_NE(html->find("Too few points for a resolution study"), std::string::npos);
  EXPECT_EQ(html->find("<svg"), std::string::npos);
}

TEST(Report, TwoMapsAreNamedAsAPairInTitleHeadlineAndAssumptions) {
  // The headline's prediction of two maps is the pair's (bug: it said "this surface against itself").
  rp::ReportInput in;
  in.is_map = true;
  in.map.nx = in.map.ny = 4;
  in.map.dx = in.map.dy = 1e-6;
  in.map.heights.assign(16, 0.0);
  in.upper_map = in.map;
  in.lower_name = "dir/lower.x3p";
  in.upper_name = "dir/upper.x3p";
  frictal::Prediction p;
  p.is_map = true;
  p.model = "map-continuous-free";
  in.prediction = p;
  rp::ReportData d;
  d.surfaces.lower_name = in.lower_name;
  d.surfaces.upper_name = in.lower_name;  // the central line against itself
  d.surfaces.lower.x = {0, 1e-6, 2e-6};
  d.surfaces.lower.z = {0, 0, 0};
  d.surfaces.upper = d.surfaces.lower;
  d.signature.offset = {0, 1e-6};
  EXPECT_EQ(rp::detail::page_title(in, d), "frictal report: lower.x3p on upper.x3p");
  EXPECT_NE(rp::detail::headline(in, d).find("A tilt test of these surfaces reads"), std::string::npos);
  const auto a = rp::detail::assumptions(in, d);
  ASSERT_FALSE(a.empty());
  EXPECT_NE(a[0].find("the upper block's face is dir/upper.x3p as measured"), std::string::npos) << a[0];
  // One map: the surface against itself.
  in.upper_map.reset();
  EXPECT_EQ(rp::detail::page_title(in, d), "frictal report: lower.x3p");
  EXPECT_NE(rp::detail::headline(in, d).find("this surface against itself"), std::string::npos);
  EXPECT_NE(rp::detail::assumptions(in, d)[0].find("slides on a copy of itself"), std::string::npos);
}
