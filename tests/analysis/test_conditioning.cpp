// Conditioning (frictal/conditioning.hpp): crop, spike removal and form removal, each against
// values derived by hand from the constructed surfaces; masks kept through every step; the
// spike filter and the `spikes` warning read the same rule; predict conditions as asked.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <set>

#include "frictal/conditioning.hpp"
#include "frictal/predict.hpp"
#include "frictal/warnings.hpp"

namespace {

constexpr double kPi = std::numbers::pi;

// z = A sin(2 pi x / L) on x = i h, i = 0..n-1.
frictal::Profile sine(std::size_t n, double h, double A, double L) {
  frictal::Profile p;
  for (std::size_t i = 0; i < n; ++i) {
    p.x.push_back(double(i) * h);
    p.z.push_back(A * std::sin(2 * kPi * double(i) * h / L));
  }
  return p;
}

bool has_code(const std::vector<frictal::Warning>& w, const std::string& code) {
  for (const auto& x : w)
    if (x.code == code) return true;
  return false;
}

frictal::Conditioning spikes_only(double k = frictal::kDefaultSpikeThreshold) {
  frictal::Conditioning c;
  c.remove_spikes = true;
  c.spike_threshold = k;
  return c;
}

}  // namespace

TEST(Conditioning, TheSpikeFilterRemovesExactlyTheInjectedSpikesAndNothingOfACleanSine) {
  // 1001 points, h = 1 um, A = 1 um, wavelength 0.2 mm: neighbouring heights differ by at most
  // A 2 pi h / L = 0.031 um, far below 10 Sq (Sq = A / sqrt 2 = 0.71 um), so nothing is flagged.
  const frictal::Profile clean = sine(1001, 1e-6, 1e-6, 2e-4);
  EXPECT_TRUE(frictal::find_spikes(clean, 10).points.empty());
  auto c0 = frictal::condition(clean, spikes_only(), "clean");
  ASSERT_TRUE(c0.ok()) << c0.error().message;
  EXPECT_EQ(c0->record.spikes_removed, 0u);
  EXPECT_EQ(c0->profile.z, clean.z);  // form none: untouched
  EXPECT_NE(c0->record.text().find("none found"), std::string::npos) << c0->record.text();
  // Three spikes of +-20 um: Sq grows to sqrt(0.5 + 3 * 400 / 1001) um = 1.31 um, and each lies
  // about 15 Sq from the median of its neighbours (> 10).
  frictal::Profile spiky = clean;
  const std::size_t at[3] = {250, 500, 753};
  spiky.z[250] += 2e-5;
  spiky.z[500] -= 2e-5;
  spiky.z[753] += 2e-5;
  const frictal::SpikeSearch s = frictal::find_spikes(spiky, 10);
  EXPECT_EQ(s.points, (std::vector<std::size_t>{250, 500, 753}));
  auto c = frictal::condition(spiky, spikes_only(), "spiky");
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->record.spikes_removed, 3u);
  EXPECT_EQ(c->record.spikes_dropped, 0u);
  EXPECT_EQ(c->record.spike_passes, 2);  // one pass finds them, the second finds none
  ASSERT_EQ(c->profile.size(), 1001u);   // the grid stays
  // Each spike is replaced by the mean of its two neighbours of the clean sine (the midpoint of a
  // uniform grid): A (sin(a - b) + sin(a + b)) / 2 = A sin(a) cos(b), b = 2 pi h / L.
  const double b = 2 * kPi * 1e-6 / 2e-4;
  for (std::size_t i : at)
    EXPECT_NEAR(c->profile.z[i], 1e-6 * std::sin(2 * kPi * double(i) * 1e-6 / 2e-4) * std::cos(b), 1e-20) << i;
  for (std::size_t i = 0; i < 1001; ++i)
    if (i != 250 && i != 500 && i != 753) {
      EXPECT_EQ(c->profile.z[i], clean.z[i]) << i;
    }
  EXPECT_EQ(c->record.text(), "spikes (k = 10 Sq): 3 points removed (replaced by linear interpolation); form: none");
}

TEST(Conditioning, ASpikeAtAnEndIsDroppedAndTheThresholdIsTheOneAsked) {
  frictal::Profile p = sine(1001, 1e-6, 1e-6, 2e-4);
  p.z[0] += 2e-5;  // its neighbours are points 1 and 2 only
  auto c = frictal::condition(p, spikes_only(), "end");
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->record.spikes_removed, 1u);
  EXPECT_EQ(c->record.spikes_dropped, 1u);
  ASSERT_EQ(c->profile.size(), 1000u);
  EXPECT_EQ(c->profile.x.front(), 1e-6);
  // A spike of 5 um is about 7 Sq from its neighbours' median: kept at k = 10, removed at k = 5.
  frictal::Profile q = sine(1001, 1e-6, 1e-6, 2e-4);
  q.z[400] += 5e-6;
  EXPECT_EQ(frictal::condition(q, spikes_only(10), "q")->record.spikes_removed, 0u);
  EXPECT_EQ(frictal::condition(q, spikes_only(5), "q")->record.spikes_removed, 1u);
  for (double bad : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    auto e = frictal::condition(q, spikes_only(bad), "q");
    ASSERT_FALSE(e.ok()) << bad;
    EXPECT_NE(e.error().message.find("spike threshold"), std::string::npos) << e.error().message;
  }
}

TEST(Conditioning, TheFilterAndTheSpikesWarningReadOneRule) {
  // Before: the warning reports the 2 spikes; after the filter at the warning's threshold it has
  // nothing left to report, on profiles and on maps.
  frictal::Profile p = sine(1001, 1e-6, 1e-6, 2e-4);
  p.z[100] += 3e-5;
  p.z[600] -= 3e-5;
  EXPECT_TRUE(has_code(frictal::check_profile(p, "p"), "spikes"));
  auto c = frictal::condition(p, spikes_only(frictal::PlausibilityLimits{}.spike_sq), "p");
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->record.spikes_removed, 2u);
  EXPECT_FALSE(has_code(frictal::check_profile(c->profile, "p"), "spikes"));
  bool suggests = false;
  for (const auto& w : frictal::check_profile(p, "p"))
    suggests = suggests || (w.code == "spikes" && w.message.find("--remove-spikes") != std::string::npos);
  EXPECT_TRUE(suggests);
}

TEST(Conditioning, ACropKeepsTheWindowsPointsExactly) {
  const frictal::Profile p = sine(1001, 1e-6, 1e-6, 2e-4);  // x = 0, 1, ..., 1000 um
  auto w = frictal::parse_crop("0.1mm,0.9mm");
  ASSERT_TRUE(w.ok()) << w.error().message;
  EXPECT_DOUBLE_EQ(w->x_min, 1e-4);
  EXPECT_DOUBLE_EQ(w->x_max, 9e-4);
  EXPECT_FALSE(w->has_y);
  frictal::Conditioning cond;
  cond.crop = *w;
  auto c = frictal::condition(p, cond, "p");
  ASSERT_TRUE(c.ok()) << c.error().message;
  ASSERT_EQ(c->profile.size(), 801u);  // x = 100 .. 900 um, both ends kept
  EXPECT_EQ(c->profile.x.front(), p.x[100]);
  EXPECT_EQ(c->profile.x.back(), p.x[900]);
  EXPECT_EQ(c->profile.z[0], p.z[100]);
  EXPECT_EQ(c->record.text(), "crop x [0.0001, 0.0009] m: kept 801 of 1001 points; form: none");
  // A window between grid points: x in [105.5, 205.5] um holds x = 106 .. 205, 100 points.
  cond.crop = frictal::CropWindow{105.5e-6, 205.5e-6};
  c = frictal::condition(p, cond, "p");
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->profile.size(), 100u);
  EXPECT_EQ(c->profile.x.front(), p.x[106]);
  // A periodic profile cropped to part of it is no longer periodic.
  frictal::Profile per = p;
  per.period = 2e-4;
  EXPECT_FALSE(frictal::condition(per, cond, "per")->profile.period.has_value());
}

TEST(Conditioning, BadWindowsAreErrorsNamingTheWindowAndTheExtent) {
  const frictal::Profile p = sine(1001, 1e-6, 1e-6, 2e-4);
  frictal::Conditioning cond;
  cond.crop_source = "--crop '5mm,6mm'";
  cond.crop = frictal::CropWindow{5e-3, 6e-3};
  auto e = frictal::condition(p, cond, "p.csv");
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().message.find("--crop '5mm,6mm'"), std::string::npos) << e.error().message;
  EXPECT_NE(e.error().message.find("[0, 0.001] m"), std::string::npos) << e.error().message;  // the extent
  EXPECT_NE(e.error().message.find("keeps 0 of the 1001 points"), std::string::npos) << e.error().message;
  cond.crop = frictal::CropWindow{0, 0.5e-6};  // one point: x = 0
  EXPECT_FALSE(frictal::condition(p, cond, "p").ok());
  cond.crop = frictal::CropWindow{0, 1e-4, true, 0, 1e-4};  // a window along y for a profile
  e = frictal::condition(p, cond, "p");
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().message.find("line profile"), std::string::npos) << e.error().message;
  for (const char* bad : {"1", "1,2,3", "2,1", "a,b", "1,2,4,3", "1mm,2parsec", "1,nan", ""}) {
    auto r = frictal::parse_crop(bad, "--crop");
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_NE(r.error().message.find("--crop"), std::string::npos) << r.error().message;
  }
  auto four = frictal::parse_crop("1um, 2um, 3nm, 4nm");
  ASSERT_TRUE(four.ok()) << four.error().message;
  EXPECT_TRUE(four->has_y);
  EXPECT_DOUBLE_EQ(four->y_max, 4e-9);
}

TEST(Conditioning, PolyTwoLeavesNoResidualOnAParabola) {
  frictal::Profile p;
  for (int i = 0; i <= 500; ++i) {
    const double x = 1e-3 + i * 2e-6;
    p.x.push_back(x);
    p.z.push_back(3e-6 - 0.02 * x + 40 * x * x);
  }
  frictal::Conditioning cond;
  cond.form = frictal::Detrend{frictal::DetrendKind::Polynomial, 2};
  auto c = frictal::condition(p, cond, "parabola");
  ASSERT_TRUE(c.ok()) << c.error().message;
  for (double z : c->profile.z) EXPECT_NEAR(z, 0, 1e-17);
  EXPECT_EQ(c->record.text(), "form: poly:2");
  // A map: every polynomial of total degree 2 in (x, y).
  frictal::Map m;
  m.nx = 30, m.ny = 20, m.dx = 1e-6, m.dy = 2e-6, m.x0 = 5e-6, m.y0 = -3e-6;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) {
      const double x = m.x0 + double(i) * m.dx, y = m.y0 + double(j) * m.dy;
      m.heights.push_back(1e-6 + 0.01 * x - 0.03 * y + 200 * x * x + 300 * x * y - 100 * y * y);
    }
  m.heights[17] = NAN;
  auto cm = frictal::condition(m, cond, "map");
  ASSERT_TRUE(cm.ok()) << cm.error().message;
  EXPECT_TRUE(std::isnan(cm->map.heights[17]));
  for (std::size_t k = 0; k < cm->map.size(); ++k)
    if (k != 17) {
      EXPECT_NEAR(cm->map.heights[k], 0, 1e-17) << k;
    }
}

TEST(Conditioning, AMaskedMapKeepsItsMaskThroughCropSpikesAndForm) {
  // 40 x 30 nodes: a tilted plane with a ripple along x (amplitude 0.1 um, wavelength 8 nodes:
  // a node differs from its 8 neighbours' median by at most 0.1 um 2 sin(pi / 8) = 0.077 um,
  // about one Sq of the ripple), reader-masked points (NaN) and one spike of 20 um.
  frictal::Map m;
  m.nx = 40, m.ny = 30, m.dx = 1e-6, m.dy = 1e-6;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i)
      m.heights.push_back(2e-3 * double(i) * m.dx - 1e-3 * double(j) * m.dy + 1e-7 * std::sin(2 * kPi * double(i) / 8));
  const std::set<std::pair<std::size_t, std::size_t>> masked = {{12, 10}, {13, 10}, {12, 11}, {13, 11},
                                                                {20, 15}, {2, 2},   {30, 25}};
  for (auto [i, j] : masked) m.at(i, j) = NAN;
  m.at(25, 12) += 2e-5;
  frictal::Conditioning cond;
  cond.crop = frictal::CropWindow{10e-6, 35.5e-6, true, 5e-6, 20e-6};  // columns 10..35, rows 5..20
  cond.remove_spikes = true;
  cond.form = frictal::Detrend{frictal::DetrendKind::Line, 1};
  auto c = frictal::condition(m, cond, "masked");
  ASSERT_TRUE(c.ok()) << c.error().message;
  const frictal::Map& o = c->map;
  ASSERT_EQ(o.nx, 26u);
  ASSERT_EQ(o.ny, 16u);
  EXPECT_DOUBLE_EQ(o.x0, 10e-6);
  EXPECT_DOUBLE_EQ(o.y0, 5e-6);
  EXPECT_EQ(c->record.spikes_removed, 1u);
  // Inside the window: (12..13, 10..11) and (20,15) masked by the reader, (25,12) by the filter.
  std::size_t nan = 0;
  for (std::size_t j = 0; j < o.ny; ++j)
    for (std::size_t i = 0; i < o.nx; ++i) {
      const std::size_t I = i + 10, J = j + 5;
      const bool want = masked.count({I, J}) || (I == 25 && J == 12);
      EXPECT_EQ(std::isnan(o.at(i, j)), want) << I << "," << J;
      nan += std::isnan(o.at(i, j));
    }
  EXPECT_EQ(nan, 6u);
  EXPECT_EQ(o.valid_count(), 26u * 16u - 6u);
  EXPECT_EQ(c->record.text(),
            "crop x [1e-05, 3.55e-05] m, y [5e-06, 2e-05] m: kept 26 x 16 of 40 x 30 points; spikes (k = 10 Sq): 1 "
            "point masked; form: plane");
  // The plane is gone: what is left is the ripple (and its part the plane fit takes), within
  // +-0.1 um plus a little.
  for (double z : o.heights)
    if (std::isfinite(z)) {
      EXPECT_LT(std::abs(z), 1.5e-7);
    }
  // A window of masked points only is an error naming the window.
  frictal::Conditioning c2;
  c2.crop = frictal::CropWindow{12e-6, 13e-6, true, 10e-6, 11e-6};
  auto none = frictal::condition(m, c2, "masked");
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.error().message.find("no valid point"), std::string::npos) << none.error().message;
  c2.crop = frictal::CropWindow{100e-6, 200e-6};
  auto e = frictal::condition(m, c2, "masked");
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().message.find("x spans [0, 3.9e-05] m"), std::string::npos) << e.error().message;
}

TEST(Conditioning, PredictWithSpikesRemovedReadsTheCleanProfile) {
  // 2001 points, h = 10 um, a sine of 1 um and wavelength 0.5 mm (slopes below 0.72 deg). One
  // spike of 10 um at point 1000 (about 13 Sq from its neighbours): its flanks rise 10 um over
  // 10 um. Against itself turned over, the spike meets its copy at offset 0 and the drops lie at
  // offsets >= 0, so sliding backward (-x) the contact climbs the copy's 45-degree flank: the rigid
  // bound reads about 45 deg with it. The clean reference is the profile the filter must give:
  // the spike's point on the straight line between its neighbours.
  const frictal::Profile base = sine(2001, 1e-5, 1e-6, 5e-4);
  frictal::Profile clean = base;
  clean.z[1000] = 0.5 * (base.z[999] + base.z[1001]);
  frictal::Profile spiky = clean;
  spiky.z[1000] += 1e-5;
  frictal::PredictSurface s_clean, s_spiky;
  s_clean.profile = clean, s_clean.name = "clean";
  s_spiky.profile = spiky, s_spiky.name = "spiky";
  frictal::PredictOptions back;
  back.direction = kPi;
  auto pc = frictal::predict(s_clean, nullptr, back);
  ASSERT_TRUE(pc.ok()) << pc.error().message;
  EXPECT_FALSE(has_code(pc->warnings, "spikes"));
  EXPECT_LT(pc->theta_max, 1.0 * kPi / 180);
  auto ps = frictal::predict(s_spiky, nullptr, back);
  ASSERT_TRUE(ps.ok()) << ps.error().message;
  EXPECT_TRUE(has_code(ps->warnings, "spikes"));
  EXPECT_GT(ps->theta_max, 40 * kPi / 180);  // the spike sets it
  frictal::PredictOptions o = back;
  o.remove_spikes = true;
  auto pr = frictal::predict(s_spiky, nullptr, o);
  ASSERT_TRUE(pr.ok()) << pr.error().message;
  EXPECT_FALSE(has_code(pr->warnings, "spikes"));
  EXPECT_EQ(pr->spikes_removed, 1u);
  EXPECT_EQ(pr->conditioning, "spikes (k = 10 Sq): 1 point removed (replaced by linear interpolation); form: line");
  EXPECT_NEAR(pr->theta_max, pc->theta_max, 1e-12);
  EXPECT_NEAR(pr->friction_angle.q50, pc->friction_angle.q50, 1e-12);
  EXPECT_NEAR(pr->friction_angle.q05, pc->friction_angle.q05, 1e-12);
  EXPECT_NEAR(pr->friction_angle.q95, pc->friction_angle.q95, 1e-12);
  EXPECT_EQ(pr->drops, pc->drops);
  // A crop through predict: listed, and its window's extent sets the drop range's end.
  o.crop = frictal::CropWindow{2e-3, 1.2e-2};
  auto pw = frictal::predict(s_spiky, nullptr, o);
  ASSERT_TRUE(pw.ok()) << pw.error().message;
  EXPECT_EQ(pw->conditioning.rfind("crop x [0.002, 0.012] m: kept 1001 of 2001 points; spikes", 0), 0u)
      << pw->conditioning;
  o.crop = frictal::CropWindow{1, 2};
  auto bad = frictal::predict(s_spiky, nullptr, o);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("spiky"), std::string::npos) << bad.error().message;
}

// find_spikes against the rule written out: the median of the (up to) four neighbours by a full
// sort, on rough heights with ties (heights on a coarse grid) and with spikes, at every threshold
// from 0: every flagged point and the worst deviation bit for bit.
TEST(Conditioning, FindSpikesIsTheSortedMedianRuleToTheBit) {
  std::uint64_t state = 12345;
  auto next = [&] {  // xorshift64: a fixed stream on every platform
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return state;
  };
  frictal::Profile p;
  for (std::size_t i = 0; i < 2000; ++i) {
    p.x.push_back(double(i) * 1e-6);
    double z = double(next() % 64) * 1e-7;                  // ties: 64 levels
    if (next() % 97 == 0) z += double(next() % 50) * 1e-6;  // spikes
    p.z.push_back(z);
  }
  double mean = 0;
  for (double z : p.z) mean += z;
  mean /= double(p.z.size());
  double s2 = 0;
  for (double z : p.z) s2 += (z - mean) * (z - mean);
  const double rms = std::sqrt(s2 / double(p.z.size()));
  for (double k : {0.0, 0.5, 2.0, 5.0}) {
    std::vector<std::size_t> want;
    double worst = 0;
    for (std::size_t i = 0; i < p.z.size(); ++i) {
      std::vector<double> w;
      for (std::size_t j = i >= 2 ? i - 2 : 0; j <= i + 2 && j < p.z.size(); ++j)
        if (j != i) w.push_back(p.z[j]);
      std::sort(w.begin(), w.end());
      const std::size_t h = w.size() / 2;
      const double med = w.size() % 2 ? w[h] : 0.5 * (w[h] + w[h - 1]);
      const double dev = std::abs(p.z[i] - med) / rms;
      if (dev > k) want.push_back(i), worst = std::max(worst, dev);
    }
    const frictal::SpikeSearch got = frictal::find_spikes(p, k);
    EXPECT_EQ(got.points, want) << "k = " << k;
    EXPECT_EQ(got.worst, worst) << "k = " << k;
  }
}

// condition(Profile&&) gives condition(const Profile&)'s result to the bit, with and without a
// crop, spikes removed and a form taken off (it only avoids copying the points).
TEST(Conditioning, TakingTheProfileOverGivesTheSameResult) {
  frictal::Profile p = sine(3000, 1e-6, 1e-6, 5e-4);
  p.z[1234] += 1e-4;  // a spike
  for (const bool crop : {false, true})
    for (const bool spikes : {false, true}) {
      frictal::Conditioning c = spikes ? spikes_only() : frictal::Conditioning{};
      c.form.kind = frictal::DetrendKind::Polynomial;
      c.form.degree = 2;
      if (crop) {
        frictal::CropWindow w;
        w.x_min = 1e-4;
        w.x_max = 2e-3;
        c.crop = w;
      }
      auto a = frictal::condition(p, c, "p");
      frictal::Profile q = p;
      auto b = frictal::condition(std::move(q), c, "p");
      ASSERT_TRUE(a && b);
      EXPECT_EQ(a->profile.x, b->profile.x) << crop << spikes;
      EXPECT_EQ(a->profile.z, b->profile.z) << crop << spikes;
      EXPECT_EQ(a->record.spikes_removed, b->record.spikes_removed);
      EXPECT_EQ(a->record.nx_after, b->record.nx_after);
    }
}
