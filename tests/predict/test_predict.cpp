// The prediction (frictal/predict.hpp): what a tilt test reads, against hand-derived answers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>
#include <random>

#include "frictal/generators.hpp"
#include "frictal/hold.hpp"
#include "frictal/predict.hpp"
#include "frictal/warnings.hpp"

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180;

frictal::PredictSurface profile_surface(frictal::Profile p, const std::string& name = "profile") {
  frictal::PredictSurface s;
  s.profile = std::move(p);
  s.name = name;
  return s;
}

bool has_code(const std::vector<frictal::Warning>& w, const std::string& code) {
  for (const auto& x : w)
    if (x.code == code) return true;
  return false;
}

frictal::PredictOptions no_form_removal() {
  frictal::PredictOptions o;
  o.detrend = frictal::Detrend{frictal::DetrendKind::None, 0};
  return o;
}

}  // namespace

TEST(Predict, SawtoothAgainstItselfHoldsAtItsFlanks) {
  // A sawtooth rising at 25 deg over 0.7 of its wavelength, against itself turned over: the
  // teeth mate, every drop rests in the mated seat, and the block slides forward when the tilt
  // passes the rising flank (25 deg) and backward when it passes the falling one,
  // atan(tan 25 deg * 0.7 / 0.3) (both by hand). Rigid: the upper bound is the same flank.
  frictal::SawtoothParams sp;
  sp.rise_angle = 25 * kDeg;
  sp.rise_fraction = 0.7;
  const auto saw = profile_surface(frictal::sawtooth_profile(sp).value(), "saw");
  const double back = std::atan(std::tan(25 * kDeg) * 0.7 / 0.3);
  for (const double mu : {0.0, 0.1}) {
    frictal::PredictOptions o = no_form_removal();
    o.atomic_friction = mu;
    auto f = frictal::predict(saw, nullptr, o);
    ASSERT_TRUE(f.ok()) << f.error().message;
    const double want = 25 * kDeg + std::atan(mu);
    EXPECT_EQ(f->model, "profile-quasi-static-hold");
    EXPECT_EQ(f->conditioning, "form: none");
    EXPECT_EQ(f->form, "none");
    EXPECT_NEAR(f->friction_angle.q05, want, 1e-9);
    EXPECT_NEAR(f->friction_angle.q50, want, 1e-9);
    EXPECT_NEAR(f->friction_angle.q95, want, 1e-9);
    EXPECT_NEAR(f->friction_coefficient, std::tan(want), 1e-9);
    EXPECT_NEAR(f->upper_bound_friction_angle, want, 1e-9);
    EXPECT_NEAR(f->runaway_distance, sp.wavelength, 1e-15);  // one period for a periodic pair
    // The contact slopes are the two flanks, so sigma is large: Eq. 18's low end would be negative
    // and is reported as 0 with its code; nothing else is warned of on a clean sawtooth.
    EXPECT_GE(f->eq18_range[0], 0.0);
    for (const auto& w : f->warnings) EXPECT_EQ(w.code, "eq18-low-clamped") << w.message;
    EXPECT_EQ(has_code(f->warnings, "eq18-low-clamped"), f->theta_max - f->contact_slope_std + std::atan(mu) < 0);
    o.direction = kPi;
    auto b = frictal::predict(saw, nullptr, o);
    ASSERT_TRUE(b.ok()) << b.error().message;
    EXPECT_NEAR(b->friction_angle.q50, back + std::atan(mu), 1e-9);
    EXPECT_NEAR(b->upper_bound_friction_angle, back + std::atan(mu), 1e-9);
  }
}

TEST(Predict, KochK1ReadsItsAlphaAsThePaperFinds) {
  // Alonso-Marroquin et al. (2015), Fig. 4 and 6: K1 surfaces reach a contact slope of alpha,
  // and the tilt test reads alpha (K0 and K1 identical); so does every drop here.
  frictal::KochParams kp;
  kp.iterations = 1;
  kp.alpha = 20 * kDeg;
  const auto k1 = profile_surface(frictal::koch_profile(kp).value(), "k1");
  auto p = frictal::predict(k1, nullptr, no_form_removal());
  ASSERT_TRUE(p.ok()) << p.error().message;
  EXPECT_NEAR(p->upper_bound_friction_angle, 20 * kDeg, 1e-9);
  EXPECT_NEAR(p->friction_angle.q50, 20 * kDeg, 1e-9);
}

TEST(Predict, TheDefaultConditioningIsALineForProfilesAndIsListed) {
  // A sawtooth on a ramp of slope 0.05: with the line removed (the default) the flanks are back
  // at 25 deg to within the fit's residual slope; without it the ramp adds atan 0.05 to the
  // rising flank (the rigid bound, by hand: atan(tan 25 + 0.05)).
  frictal::SawtoothParams sp;
  sp.rise_angle = 25 * kDeg;
  sp.rise_fraction = 0.7;
  frictal::Profile p = frictal::sawtooth_profile(sp).value();
  p.period.reset();
  for (std::size_t i = 0; i < p.x.size(); ++i) p.z[i] += 0.05 * p.x[i];
  const auto s = profile_surface(p, "ramp");
  auto d = frictal::predict(s, nullptr, {});
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_EQ(d->conditioning, "form: line");
  EXPECT_EQ(d->form, "line");
  EXPECT_NEAR(d->upper_bound_friction_angle, 25 * kDeg, 0.05 * kDeg);
  auto n = frictal::predict(s, nullptr, no_form_removal());
  ASSERT_TRUE(n.ok()) << n.error().message;
  EXPECT_NEAR(n->upper_bound_friction_angle, std::atan(std::tan(25 * kDeg) + 0.05), 1e-9);
}

TEST(Predict, OneDropRestsInItsSeat) {
  frictal::SawtoothParams sp;
  sp.rise_angle = 25 * kDeg;
  sp.rise_fraction = 0.7;
  const auto saw = profile_surface(frictal::sawtooth_profile(sp).value(), "saw");
  frictal::PredictOptions o = no_form_removal();
  o.start_offset = {0.003, 0};
  auto p = frictal::predict(saw, nullptr, o);
  ASSERT_TRUE(p.ok()) << p.error().message;
  EXPECT_TRUE(p->single_drop);
  EXPECT_EQ(p->drops, 1u);
  EXPECT_NEAR(p->friction_angle.q50, 25 * kDeg, 1e-9);
  // The mated seats: the upper face is the sawtooth turned over, g(x) = -f(L - x) with L a whole
  // number of wavelengths, so at offset s it lies on f where f(s - x) = -f(x) + c for all x: the
  // gentle falling stretch of f(s - x), x in [s - 0.7 lambda, s], must be that of -f(x), [0, 0.7
  // lambda], i.e. s = 0.7 lambda modulo lambda (by hand).
  const double r = std::remainder(p->rest_offset[0] - 0.7 * sp.wavelength, sp.wavelength);
  EXPECT_NEAR(r, 0, 1e-12);
}

TEST(Predict, BadInputIsRefusedNamingTheValue) {
  frictal::SawtoothParams sp;
  const auto saw = profile_surface(frictal::sawtooth_profile(sp).value(), "saw.csv");
  frictal::PredictOptions o;
  o.direction = 90 * kDeg;
  auto e = frictal::predict(saw, nullptr, o);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().message.find("90 deg"), std::string::npos) << e.error().message;
  o = {};
  o.atomic_friction = -0.2;
  e = frictal::predict(saw, nullptr, o);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().message.find("-0.2"), std::string::npos) << e.error().message;
  frictal::PredictSurface map;
  map.is_map = true;
  map.name = "map.x3p";
  map.map.nx = map.map.ny = 3;
  map.map.heights.assign(9, 0.0);
  e = frictal::predict(saw, &map, {});
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().message.find("map.x3p is an areal map"), std::string::npos) << e.error().message;
}

TEST(Predict, GroovesMapHoldsAtTheSteepestSegmentFromEveryDrop) {
  // Grooves across x (heights A sin(2 pi i / m) along x, the same in every row) against
  // themselves turned over: they mate, the block is free to move along the grooves without
  // effect, and it climbs the steepest segment of the piecewise-linear grooves, slope
  // A sin(2 pi / m) / a (by hand), from every drop; the locked block reads the same.
  const std::size_t n = 16;
  const int m = 8;
  const double a = 1e-3 / double(n - 1), A = 2.4e-5;
  frictal::PredictSurface s;
  s.is_map = true;
  s.name = "grooves";
  s.map.nx = s.map.ny = n;
  s.map.dx = s.map.dy = a;
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < n; ++i) s.map.heights.push_back(A * std::sin(2 * kPi * double(i) / m));
  // The upper block: an 8 x 8 window of the same grooves (a smaller block, the same contact).
  frictal::PredictSurface u;
  u.is_map = true;
  u.name = "window";
  u.map.nx = u.map.ny = 8;
  u.map.dx = u.map.dy = a;
  for (std::size_t j = 0; j < 8; ++j)
    for (std::size_t i = 0; i < 8; ++i) u.map.heights.push_back(s.map.at(i + 4, j + 4));
  frictal::PredictOptions o = no_form_removal();
  o.map_drops = 3;
  o.map_locked = true;
  auto p = frictal::predict(s, &u, o);
  ASSERT_TRUE(p.ok()) << p.error().message;
  const double want = std::atan(A * std::sin(2 * kPi / m) / a);
  EXPECT_EQ(p->model, "map-continuous-free");
  EXPECT_EQ(p->drops, 9u);
  EXPECT_GE(p->friction_angle.min, want - 1e-9);
  EXPECT_LE(p->friction_angle.max, want + 2e-4);
  ASSERT_TRUE(p->has_locked);
  EXPECT_GE(p->locked_friction_angle.min, want - 1e-9);
  EXPECT_LE(p->locked_friction_angle.max, want + 2e-4);
  EXPECT_FALSE(has_code(p->warnings, "held-to-max-tilt"));
}

TEST(Predict, MapDropsKeepTheBlocksSpheresWhollyOverTheLowerMapWithRoomD) {
  // Lower 41 x 21 nodes, upper 9 x 5, both at 5 um: node extents Lf = 200 um, Wf = 100 um,
  // Lg = 40 um, Wg = 20 um. The block's footprint is its nodes widened by the sphere radius r
  // (default a fifth of the lower spacing, 1 um); D is stated, 10 um. By hand
  // the drop range is +-((Lf - Lg) / 2 - r - D) = +-69 um along x and +-((Wf - Wg) / 2 - r - D) =
  // +-29 um across, and the 2 x 2 drops are its corners: at each, the footprint's nearest side
  // lies exactly D from the lower map's edge (no sphere starts on the edge).
  const double a = 5e-6;
  auto grid = [&](std::size_t nx, std::size_t ny, double k) {
    frictal::PredictSurface m;
    m.is_map = true;
    m.name = "waves";
    m.map.nx = nx;
    m.map.ny = ny;
    m.map.dx = m.map.dy = a;
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i)
        m.map.heights.push_back(2e-7 * std::sin(k * double(i)) * std::cos(0.7 * k * double(j)));
    return m;
  };
  const auto lower = grid(41, 21, 0.9), upper = grid(9, 5, 1.3);
  const double Lf = 200e-6, Wf = 100e-6, Lg = 40e-6, Wg = 20e-6;
  frictal::PredictOptions o = no_form_removal();
  o.map_drops = 2;
  o.runaway_distance = 10e-6;
  for (const double r : {0.0, 3e-6}) {
    o.sphere_radius = r;
    const double rr = r > 0 ? r : 0.2 * a, D = 10e-6;
    auto p = frictal::predict(lower, &upper, o);
    ASSERT_TRUE(p.ok()) << p.error().message;
    EXPECT_NEAR(p->runaway_distance, D, 1e-18);
    const double u = 0.5 * (Lf - Lg) - rr - D, v = 0.5 * (Wf - Wg) - rr - D;
    EXPECT_NEAR(p->drop_range[0], -u, 1e-15);
    EXPECT_NEAR(p->drop_range[1], u, 1e-15);
    EXPECT_NEAR(p->drop_range[2], -v, 1e-15);
    EXPECT_NEAR(p->drop_range[3], v, 1e-15);
    ASSERT_EQ(p->drop_offsets.size(), 4u);
    double gap[4] = {1, 1, 1, 1};  // least room from the footprint to the lower map's -x, +x, -y, +y edges
    for (const auto& q : p->drop_offsets) {
      gap[0] = std::min(gap[0], (q[0] - Lg / 2 - rr) + Lf / 2);
      gap[1] = std::min(gap[1], Lf / 2 - (q[0] + Lg / 2 + rr));
      gap[2] = std::min(gap[2], (q[1] - Wg / 2 - rr) + Wf / 2);
      gap[3] = std::min(gap[3], Wf / 2 - (q[1] + Wg / 2 + rr));
    }
    for (const double g : gap) EXPECT_NEAR(g, D, 1e-15);
  }
}

TEST(Warnings, UnitsSpikesScaleAndFillValuesAreNamed) {
  // A clean sawtooth gives none.
  frictal::SawtoothParams sp;
  const frictal::Profile saw = frictal::sawtooth_profile(sp).value();
  EXPECT_TRUE(frictal::check_profile(saw, "saw").empty());
  // x in micrometres read as metres with z in metres: x 10^6 too small, slopes 10^6 too steep.
  frictal::Profile um = saw;
  for (double& x : um.x) x *= 1e-6;
  auto w = frictal::check_profile(um, "um.csv");
  EXPECT_TRUE(has_code(w, "units-suspect"));
  EXPECT_TRUE(has_code(w, "heights-exceed-length"));
  EXPECT_NE(w.front().message.find("um.csv"), std::string::npos);
  // Heights of femtometres.
  frictal::Profile fm = saw;
  for (double& z : fm.z) z *= 1e-12;
  EXPECT_TRUE(has_code(frictal::check_profile(fm, "fm"), "heights-tiny"));
  // One spike 50 rms high on a sine.
  frictal::SineParams sn;
  frictal::Profile sine = frictal::sine_profile(sn).value();
  EXPECT_TRUE(frictal::check_profile(sine, "sine").empty());
  sine.z[sine.z.size() / 2] += 50 * sn.amplitude / std::sqrt(2.0);
  EXPECT_TRUE(has_code(frictal::check_profile(sine, "spiky"), "spikes"));
  // A map with a fill value over 20 % of it.
  frictal::Map mp;
  mp.nx = mp.ny = 20;
  mp.dx = mp.dy = 1e-6;
  for (std::size_t k = 0; k < 400; ++k) mp.heights.push_back(k < 80 ? -1e-6 : 1e-8 * std::sin(0.7 * double(k)));
  EXPECT_TRUE(has_code(frictal::check_map(mp, "filled"), "fill-value"));
  // Points not measured (NaN) are no fill value, and a map of holes is checked in finite time
  // (NaN equals nothing: a run of NaN once never ended).
  for (std::size_t k = 0; k < 80; ++k) mp.heights[k] = std::nan("");
  EXPECT_FALSE(has_code(frictal::check_map(mp, "holes"), "fill-value"));
  // Two scans 20000x apart in length.
  EXPECT_TRUE(has_code(frictal::check_pair_scales(1.0, 1e-3, 5e-5, 1e-7, "a", "b"), "scale-mismatch"));
  EXPECT_TRUE(frictal::check_pair_scales(1e-3, 1e-6, 2e-3, 2e-6, "a", "b").empty());
  // Every code used is in the table.
  for (const char* code : {"units-suspect", "heights-exceed-length", "heights-tiny", "spikes", "fill-value",
                           "scale-mismatch", "eq18-low-clamped", "reader"}) {
    bool found = false;
    for (const auto& c : frictal::warning_codes()) found |= c.code == code;
    EXPECT_TRUE(found) << code;
  }
}

TEST(Warnings, ASurfaceThatIsItsFormIsNotOneOfTinyHeights) {
  // The heights 1..12 m of a 4 x 3 map lie on the plane z = 1 + i + 4 j exactly (a whitespace
  // matrix file of that kind): the plane removed, nothing is left, but the heights as read vary by
  // metres, so the fix is not a scale factor (heights-tiny) but a look at the file or the form kept.
  frictal::Map plane;
  plane.nx = 4, plane.ny = 3;
  plane.dx = plane.dy = 2.5e-6;
  for (int k = 0; k < 12; ++k) plane.heights.push_back(1.0 + k);
  frictal::Map flat = plane;
  for (double& z : flat.heights) z = 0;
  const double as_read = frictal::rms_height_as_read(plane.heights);
  EXPECT_NEAR(as_read, std::sqrt(143.0 / 12.0), 1e-12);  // 1..12: variance (n^2 - 1) / 12
  auto w = frictal::check_map(flat, "plane.txt", {}, as_read);
  EXPECT_TRUE(has_code(w, "form-only"));
  EXPECT_FALSE(has_code(w, "heights-tiny"));
  // Heights that are tiny as read stay heights-tiny; unknown heights as read (NaN) too.
  EXPECT_TRUE(has_code(frictal::check_map(flat, "zeros.txt", {}, 0.0), "heights-tiny"));
  EXPECT_TRUE(has_code(frictal::check_map(flat, "zeros.txt"), "heights-tiny"));
  // A line profile likewise, and the prediction says so in its warnings (its default form: a line).
  frictal::Profile line;
  for (int i = 0; i < 50; ++i) line.x.push_back(1e-6 * i), line.z.push_back(2e-7 * i);
  frictal::PredictSurface s;
  s.profile = line;
  s.name = "line.csv";
  const auto p = frictal::predict(s, nullptr, frictal::PredictOptions{});
  ASSERT_TRUE(p.ok()) << p.error().message;
  EXPECT_TRUE(has_code(p->warnings, "form-only"));
  EXPECT_FALSE(has_code(p->warnings, "heights-tiny"));
  bool listed = false;
  for (const auto& c : frictal::warning_codes()) listed |= c.code == "form-only";
  EXPECT_TRUE(listed);
}

TEST(Warnings, SpikesAloneDoNotMakeTheUnitsSuspect) {
  // A sawtooth of 2 points a wavelength rising at 20 deg (rms slope about 0.36) with three spikes
  // of 20 rms heights: the spikes' edges are steeper than any instrument measures (rms slope over
  // the whole profile about 30), but the surface between them is not: the warning is the spikes',
  // whose fix is their removal, not another unit for the heights.
  frictal::SawtoothParams sp;
  sp.length = 2.0;  // 200 wavelengths, 400 points
  frictal::Profile saw = frictal::sawtooth_profile(sp).value();
  saw.period.reset();
  double rq = 0;
  for (double z : saw.z) rq += z * z;
  rq = std::sqrt(rq / double(saw.size()));
  for (std::size_t k : {100u, 201u, 333u}) saw.z[k] += 20 * rq;
  const auto w = frictal::check_profile(saw, "spiky");
  EXPECT_TRUE(has_code(w, "spikes"));
  EXPECT_FALSE(has_code(w, "units-suspect"));
  // The same with heights 10^6 too large (micrometres read as metres): the units still are.
  for (double& z : saw.z) z *= 1e6;
  EXPECT_TRUE(has_code(frictal::check_profile(saw, "spiky-um"), "units-suspect"));
}

TEST(Predict, TakingTheSurfacesOverGivesTheSamePrediction) {
  // The overload that takes the surfaces (their points moved through the conditioning into the
  // signature) against the one that reads them where they are: the same prediction to the bit
  // (its whole JSON) on a random non-uniform pair with a spike (default form, spike removal), a
  // profile against itself, one drop, the backward direction, and a map pair.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> step(0.5e-6, 1.5e-6), height(-1e-7, 1e-7);
  auto random_profile = [&](std::size_t n, double ramp) {
    frictal::Profile p;
    double x = 0, z = 0;
    for (std::size_t i = 0; i < n; ++i) {
      p.x.push_back(x);
      p.z.push_back(z + ramp * x);
      x += step(rng);
      z += height(rng);
    }
    p.z[n / 3] += 5e-6;  // a spike
    return p;
  };
  const frictal::Profile lo = random_profile(400, 0.02), up = random_profile(250, -0.01);
  frictal::PredictOptions spikes;
  spikes.remove_spikes = true;
  frictal::PredictOptions one = no_form_removal();
  one.start_offset = {6e-5, 0};
  frictal::PredictOptions backward;
  backward.direction = kPi;
  int compared = 0;
  for (const frictal::PredictOptions& o : {frictal::PredictOptions{}, spikes, one, backward})
    for (const bool pair : {true, false}) {
      const auto l = profile_surface(lo, "lower"), u = profile_surface(up, "upper");
      auto kept = frictal::predict(l, pair ? &u : nullptr, o);
      ASSERT_TRUE(kept.ok()) << kept.error().message;
      std::optional<frictal::PredictSurface> taken_upper;
      if (pair) taken_upper = profile_surface(up, "upper");
      auto taken = frictal::predict(profile_surface(lo, "lower"), std::move(taken_upper), o);
      ASSERT_TRUE(taken.ok()) << taken.error().message;
      EXPECT_EQ(frictal::prediction_json(*taken), frictal::prediction_json(*kept));
      EXPECT_GT(kept->drops, 0u);
      ++compared;
    }
  EXPECT_EQ(compared, 8);
  // Maps: read where they are by both.
  frictal::PredictSurface m;
  m.is_map = true;
  m.name = "map";
  m.map.nx = m.map.ny = 12;
  m.map.dx = m.map.dy = 1e-6;
  for (std::size_t k = 0; k < 144; ++k) m.map.heights.push_back(height(rng) * 3);
  frictal::PredictOptions mo = no_form_removal();
  mo.map_drops = 2;
  auto mk = frictal::predict(m, nullptr, mo);
  ASSERT_TRUE(mk.ok()) << mk.error().message;
  auto mt = frictal::predict(frictal::PredictSurface(m), std::nullopt, mo);
  ASSERT_TRUE(mt.ok()) << mt.error().message;
  EXPECT_EQ(frictal::prediction_json(*mt), frictal::prediction_json(*mk));
  // The checks come first on both: a profile against a map is refused naming both.
  std::optional<frictal::PredictSurface> map_upper = m;
  auto mixed = frictal::predict(profile_surface(lo, "lower"), std::move(map_upper), {});
  ASSERT_FALSE(mixed.ok());
  EXPECT_NE(mixed.error().message.find("a pair is two profiles or two maps"), std::string::npos);
}

TEST(PredictColumns, EveryColumnHasAUnitAndTheJsonCarriesEveryKey) {
  frictal::SawtoothParams sp;
  const auto saw = profile_surface(frictal::sawtooth_profile(sp).value(), "saw");
  auto p = frictal::predict(saw, nullptr, no_form_removal());
  ASSERT_TRUE(p.ok());
  const std::string json = frictal::prediction_json(*p);
  for (const auto& c : frictal::prediction_columns()) {
    EXPECT_FALSE(c.unit.empty()) << c.key;
    EXPECT_NE(json.find("\"" + c.key + "\""), std::string::npos) << c.key;
    if (c.unit == "deg") {
      EXPECT_TRUE(c.key.ends_with("_deg")) << c.key;
    }
    if (c.unit == "m") {
      EXPECT_TRUE(c.key.ends_with("_m")) << c.key;
    }
  }
  EXPECT_NE(json.find("\"warnings\": ["), std::string::npos);
  // The interface unit: degrees for "deg" columns.
  for (const auto& c : frictal::prediction_columns())
    if (c.key == "friction_angle_deg") {
      EXPECT_NEAR(std::get<double>(frictal::interface_value(c, *p)), 20.0, 1e-9);
    }
}

TEST(Warnings, DimensionOutsideOneToTwoOrAPoorFit) {
  EXPECT_TRUE(frictal::check_dimension_fit(1.4, 0.99, "psd").empty());
  const auto w = frictal::check_dimension_fit(0.78, 0.99, "psd");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].code, "dimension-out-of-range");
  EXPECT_NE(w[0].message.find("0.78"), std::string::npos);
  EXPECT_TRUE(has_code(frictal::check_dimension_fit(2.3, 0.99, "box"), "dimension-out-of-range"));
  EXPECT_TRUE(has_code(frictal::check_dimension_fit(1.5, 0.6, "divider"), "poor-fit"));
}

TEST(Warnings, ABoundBelowZeroIsNegativeFriction) {
  // mu = tan(phi) < 0 exactly when phi < 0; none at 0, above or for NaN.
  EXPECT_TRUE(frictal::check_friction_bound(0.1, "x").empty());
  EXPECT_TRUE(frictal::check_friction_bound(0.0, "x").empty());
  EXPECT_TRUE(frictal::check_friction_bound(std::nan(""), "x").empty());
  const auto w = frictal::check_friction_bound(-0.1, "areal");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].code, "bound-negative");
  EXPECT_NE(w[0].message.find("areal: "), std::string::npos) << w[0].message;
  EXPECT_NE(w[0].message.find("-5.7296 deg"), std::string::npos) << w[0].message;  // -0.1 rad
  bool listed = false;
  for (const auto& c : frictal::warning_codes()) listed |= c.code == "bound-negative";
  EXPECT_TRUE(listed);
}

// --- The stated test: d and L_b are lengths of the surface, not fractions of the scan ---------

namespace {

// A sine z = A sin(2 pi x / lambda) over `waves` wavelengths, `per` points a wavelength, not
// marked periodic (as a measured scan).
frictal::Profile sine(double lambda, int waves, int per) {
  frictal::Profile p;
  const int n = waves * per;
  for (int i = 0; i <= n; ++i) {
    const double x = lambda * double(i) / per;
    p.x.push_back(x);
    p.z.push_back(1e-6 * std::sin(2 * kPi * x / lambda));
  }
  return p;
}

// The piece [a, b] of a uniformly sampled profile (its own samples, x from 0).
frictal::Profile window(const frictal::Profile& p, double a, double b) {
  frictal::Profile w;
  for (std::size_t i = 0; i < p.x.size(); ++i)
    if (p.x[i] >= a - 1e-15 && p.x[i] <= b + 1e-15) w.x.push_back(p.x[i] - a), w.z.push_back(p.z[i]);
  return w;
}

// A stationary random self-affine scan (Fourier-filtered, H = 0.8, rolloff 1 cm, 16384 points
// over 1.6 m), its period dropped: a measured scan much longer than its slope correlation length.
frictal::Profile long_scan() {
  frictal::FourierSelfAffineParams fp;
  fp.points = 16384;
  fp.length = 1.6;
  fp.rolloff_wavelength = 0.01;
  fp.short_cutoff_wavelength = 0.001;
  fp.seed = 7;
  frictal::Profile p = frictal::fourier_self_affine_profile(fp).value();
  p.period.reset();
  return p;
}

}  // namespace

TEST(PredictStatedTest, SlopeCorrelationLengthOfASineAndASawtooth) {
  // A sine's slope is a cosine, whose autocorrelation cos(2 pi tau / lambda) falls to 1/e at
  // tau = lambda acos(1/e) / (2 pi) = 0.19204 lambda. A sawtooth's slope is a two-level wave
  // with duty p; its normalised autocorrelation falls linearly, 1 - tau / (lambda p (1 - p)),
  // to 1/e at tau = (1 - 1/e) p (1 - p) lambda (0.13276 lambda for p = 0.7): both by hand.
  const double lambda = 0.01;
  EXPECT_NEAR(frictal::slope_correlation_length(sine(lambda, 20, 64)), lambda * std::acos(std::exp(-1.0)) / (2 * kPi),
              2e-3 * lambda);
  frictal::SawtoothParams sp;
  sp.rise_angle = 25 * kDeg;
  sp.rise_fraction = 0.7;
  frictal::Profile saw = frictal::sawtooth_profile(sp).value();  // 2 vertices a wavelength
  saw.period.reset();
  EXPECT_NEAR(frictal::slope_correlation_length(saw), (1 - std::exp(-1.0)) * 0.7 * 0.3 * sp.wavelength,
              3e-3 * sp.wavelength);
  // No slope variation: no length (the default then counts sampling intervals).
  frictal::Profile flat{{0, 1e-3, 2e-3, 3e-3}, {0, 0, 0, 0}, {}};
  EXPECT_EQ(frictal::slope_correlation_length(flat), 0.0);
}

TEST(PredictStatedTest, TheDefaultsOfTwoCropsOfOneSurfaceAreTheSame) {
  // The old default d was L_b / 20 of the scan: a half crop had half the d. The stated test's
  // defaults are a local statistic of the surface: the whole 1.6 m scan and two 0.4 m crops of
  // it give the same d and L_b within 15 % (the estimate's scatter), and medians that lie in
  // each other's 5-95 % range.
  const frictal::Profile p = long_scan();
  const frictal::Profile a = window(p, 0.0, 0.4), b = window(p, 0.8, 1.2);
  const double d_all = frictal::default_test_lengths(p).runaway_distance;
  for (const frictal::Profile* c : {&a, &b}) {
    const frictal::StatedTest t = frictal::default_test_lengths(*c);
    EXPECT_NEAR(t.runaway_distance / d_all, 1.0, 0.15);
    EXPECT_NEAR(t.block_length, frictal::kBlockPerRunaway * t.runaway_distance, 1e-15);
  }
  auto pa = frictal::predict(profile_surface(a, "a"), nullptr, {});
  auto pb = frictal::predict(profile_surface(b, "b"), nullptr, {});
  ASSERT_TRUE(pa.ok()) << pa.error().message;
  ASSERT_TRUE(pb.ok()) << pb.error().message;
  EXPECT_FALSE(has_code(pa->warnings, "scan-too-short"));
  EXPECT_FALSE(has_code(pb->warnings, "scan-too-short"));
  EXPECT_NEAR(pa->runaway_distance / pb->runaway_distance, 1.0, 0.15);
  EXPECT_GE(pa->friction_angle.q50, pb->friction_angle.q05);
  EXPECT_LE(pa->friction_angle.q50, pb->friction_angle.q95);
  EXPECT_GE(pb->friction_angle.q50, pa->friction_angle.q05);
  EXPECT_LE(pb->friction_angle.q50, pa->friction_angle.q95);
}

TEST(PredictStatedTest, AScanTooShortIsWarnedAndAnsweredForTheLargestTestOfTheSameShape) {
  // A 5 cm piece of the scan cannot hold the default test (L_b = 20 d plus 8 d of room, about
  // 0.14 m here): the answer is for the test of the same shape that just fits (L = L_b + 8 d
  // with L_b = 20 d, so d = L / 28), and says so.
  const frictal::Profile p = long_scan();
  const frictal::Profile s = window(p, 0.3, 0.35);
  const double len = s.x.back() - s.x.front();
  auto r = frictal::predict(profile_surface(s, "piece"), nullptr, {});
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_TRUE(has_code(r->warnings, "scan-too-short"));
  EXPECT_NEAR(r->runaway_distance, len / (frictal::kBlockPerRunaway + frictal::kRoomPerRunaway), 1e-9 * len);
  // The block is L_b to the nearest samples of the scan (each end within half a sampling interval).
  const double dx = len / double(s.size() - 1);
  EXPECT_NEAR(r->block_length, frictal::kBlockPerRunaway * r->runaway_distance, dx * (1 + 1e-9));
  // A stated d keeps: the defaulted block gives way (to the upper scan here), warned.
  frictal::PredictOptions o;
  o.runaway_distance = 0.005;  // the default block: 20 d = 0.1 m
  const frictal::PredictSurface lower = profile_surface(window(p, 0.0, 0.6), "lower");
  auto q = frictal::predict(lower, nullptr, o);
  ASSERT_TRUE(q.ok()) << q.error().message;
  EXPECT_FALSE(has_code(q->warnings, "scan-too-short"));
  EXPECT_NEAR(q->block_length, 0.1, 1e-9);
  const frictal::PredictSurface upper = profile_surface(window(p, 0.6, 0.66), "upper");
  auto u = frictal::predict(lower, &upper, o);
  ASSERT_TRUE(u.ok()) << u.error().message;
  EXPECT_TRUE(has_code(u->warnings, "scan-too-short"));
  EXPECT_NEAR(u->block_length, upper.profile.x.back() - upper.profile.x.front(), 1e-12);  // all of it
  EXPECT_EQ(u->runaway_distance, 0.005);
  // A stated test that the scans cannot hold is refused, naming what it needs.
  o.block_length = 0.2;
  auto e = frictal::predict(lower, &upper, o);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().message.find("needs a lower scan of 0.24 m"), std::string::npos) << e.error().message;
}

TEST(PredictStatedTest, TheSweepOverDHoldsTheHeadlineAtD) {
  const frictal::Profile p = window(long_scan(), 0.0, 0.4);
  frictal::PredictOptions o;
  o.runaway_distance = 0.004;
  auto r = frictal::predict(profile_surface(p, "scan"), nullptr, o);
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_EQ(r->d_sweep_distance.size(), 5u);
  const double want[5] = {0.001, 0.002, 0.004, 0.008, 0.016};
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(r->d_sweep_distance[i], want[i], 1e-15);
  EXPECT_EQ(r->d_sweep_q50[2], r->friction_angle.q50);
  EXPECT_EQ(r->d_sweep_q05[2], r->friction_angle.q05);
  EXPECT_EQ(r->d_sweep_q95[2], r->friction_angle.q95);
  // L_b = 20 d, d given, to the nearest samples (one sampling interval of 1.6 m / 16384 at most).
  EXPECT_NEAR(r->block_length, frictal::kBlockPerRunaway * 0.004, 1.6 / 16384 * (1 + 1e-9));
  for (std::size_t i = 0; i < 5; ++i) EXPECT_LE(r->d_sweep_q05[i], r->d_sweep_q50[i]);
}

TEST(PredictStatedTest, TheWholeBlockIsTheHoldAnalysisOfTheWholePair) {
  // --block-length whole: the whole upper profile over the first half of the lower one, the
  // hold analysis of `frictal signature` (analyse_hold over its own range), to rounding.
  const frictal::Profile p = window(long_scan(), 0.0, 0.2);
  frictal::PredictOptions o = no_form_removal();
  o.block_length = -1;
  o.runaway_distance = 0.01;
  auto r = frictal::predict(profile_surface(p, "scan"), nullptr, o);
  ASSERT_TRUE(r.ok()) << r.error().message;
  frictal::HoldOptions ho;
  ho.runaway_distance = 0.01;
  auto h = frictal::analyse_hold(p, frictal::rotate180(p), {}, ho);
  ASSERT_TRUE(h.ok()) << h.error().message;
  EXPECT_NEAR(r->friction_angle.q50, h->distribution.forward.hold.q50, 1e-12);
  EXPECT_NEAR(r->friction_angle.q95, h->distribution.forward.hold.q95, 1e-12);
  EXPECT_NEAR(r->block_length, 0.2, 1e-12);
}

TEST(PredictStatedTest, BadBlockLengthsAreRefusedNamingTheValue) {
  frictal::KochParams kp;
  kp.iterations = 1;
  auto k = profile_surface(frictal::koch_profile(kp).value(), "k1");
  frictal::PredictOptions o;
  o.block_length = 0.05;
  auto r = frictal::predict(k, nullptr, o);  // periodic: the whole profile slides
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("periodic"), std::string::npos) << r.error().message;
  o.block_length = std::numeric_limits<double>::quiet_NaN();
  auto n = frictal::predict(profile_surface(sine(0.01, 20, 64)), nullptr, o);
  ASSERT_FALSE(n.ok());
  EXPECT_NE(n.error().message.find("block length"), std::string::npos) << n.error().message;
}

TEST(PredictStatedTest, TheMapDefaultIsTheSlopeCorrelationLengthAlongTheDirection) {
  // Rows z = A sin(2 pi x / lambda), the same along y: along x the slope correlation length is
  // 0.19204 lambda (above), so d = 12.5 of it; along y the rows are flat and d counts spacings.
  frictal::Map m;
  m.nx = 64 * 40 + 1;
  m.ny = 8;
  m.dx = m.dy = 0.01 / 64;
  m.heights.resize(m.nx * m.ny);
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) m.at(i, j) = 1e-6 * std::sin(2 * kPi * double(i) / 64);
  const double xi = 0.01 * std::acos(std::exp(-1.0)) / (2 * kPi);
  EXPECT_NEAR(frictal::default_map_runaway_distance(m, 0).distance, frictal::kRunawayPerSlopeCorrelation * xi,
              frictal::kRunawayPerSlopeCorrelation * 2e-3 * 0.01);
  EXPECT_NEAR(frictal::default_map_runaway_distance(m, kPi / 2).distance, frictal::kRunawayPerSlopeCorrelation * m.dy,
              1e-15);
}

TEST(Predict, EightDigitXColumnAsPrintedGivesAnAnswer) {
  // instruments/opdx-3.txt, a profilometer's text export: x with 8 significant digits, so its
  // steps of 1.6655563e-08 m wobble in the last digit and the lift's events come within ulps of
  // each other. Taken as printed (not through the reader, which reads it as its uniform grid), the
  // prediction ended in "hold: lift curve offsets must increase"; now it gives the answer of the
  // uniform grid x = k * 1.6655563e-08 m to within the x column's rounding.
  std::ifstream f(std::string(FRICTAL_TEST_DATA) + "/instruments/opdx-3.txt");
  frictal::Profile printed, grid;
  for (double x, z; f >> x >> z;) {
    grid.x.push_back(double(printed.x.size()) * 1.6655563e-08);
    printed.x.push_back(x);
    printed.z.push_back(z);
    grid.z.push_back(z);
  }
  ASSERT_EQ(printed.x.size(), 3001u);
  auto a = frictal::predict(profile_surface(printed, "printed"), nullptr);
  ASSERT_TRUE(a.ok()) << a.error().message;
  auto b = frictal::predict(profile_surface(grid, "grid"), nullptr);
  ASSERT_TRUE(b.ok()) << b.error().message;
  EXPECT_NEAR(a->friction_angle.q50, b->friction_angle.q50, 0.05 * kDeg);
  EXPECT_NEAR(a->upper_bound_friction_angle, b->upper_bound_friction_angle, 0.05 * kDeg);
}

TEST(Predict, AShortUpperScanOnALongLowerOneGivesAnAnswer) {
  // profiles/xy-2.txt (29 um long as read) on profiles/xy-1.txt (187 m): the stated test shrinks
  // to the short scan (scan-too-short), the lift's own range then ends nearer the overlap's end
  // than the hold analysis's sliver, and the widening asked the signature for a range that lay
  // partly inside its own: "extension ... outside the overlap or inside the range", an internal
  // failure on two valid files. The answer exists and keeps the rigid order of things: every
  // drop between atan(mu_a) = 0 and the bound, both overloads to the bit.
  const std::string dir = std::string(FRICTAL_TEST_DATA) + "/profiles/";
  auto lower = frictal::read_profile(dir + "xy-1.txt");
  auto upper = frictal::read_profile(dir + "xy-2.txt");
  ASSERT_TRUE(lower.ok() && upper.ok());
  const auto lo = profile_surface(*lower, "xy-1"), up = profile_surface(*upper, "xy-2");
  auto a = frictal::predict(lo, &up);
  ASSERT_TRUE(a.ok()) << a.error().message;
  EXPECT_GE(a->friction_angle.min, 0.0);
  EXPECT_LE(a->friction_angle.max, a->upper_bound_friction_angle + 1e-12);
  auto b = frictal::predict(profile_surface(*lower, "xy-1"), std::optional(profile_surface(*upper, "xy-2")));
  ASSERT_TRUE(b.ok()) << b.error().message;
  EXPECT_EQ(a->friction_angle.q50, b->friction_angle.q50);
}

TEST(Predict, TheWholeShortUpperScanOnALongLowerOneShortensTheDefaultDWithAWarning) {
  // xy-2.txt (29 um as read) whole on xy-1.txt (187 m): d from the lower scan's slopes (tens of
  // metres) does not fit the 29 um block; it gave "runaway_distance ... expected a length shorter
  // than the blocks' overlap", an error for a default the caller never chose. The default gives
  // way to the default's shape, d = L_b / kBlockPerRunaway over the blocks' overlap, warned; a
  // stated d is never changed.
  const std::string dir = std::string(FRICTAL_TEST_DATA) + "/profiles/";
  auto lower = frictal::read_profile(dir + "xy-1.txt");
  auto upper = frictal::read_profile(dir + "xy-2.txt");
  ASSERT_TRUE(lower.ok() && upper.ok());
  const auto lo = profile_surface(*lower, "xy-1"), up = profile_surface(*upper, "xy-2");
  frictal::PredictOptions o;
  o.block_length = -1;
  auto a = frictal::predict(lo, &up, o);
  ASSERT_TRUE(a.ok()) << a.error().message;
  const double overlap = std::min(lower->x.back() - lower->x.front(), upper->x.back() - upper->x.front());
  EXPECT_NEAR(a->runaway_distance, overlap / frictal::kBlockPerRunaway, 1e-12 * overlap);
  bool warned = false;
  for (const auto& w : a->warnings) warned = warned || w.code == "scan-too-short";
  EXPECT_TRUE(warned);
  // The whole block's run-aways read stops beyond the signature's range (the first half of the
  // short scan); the bound is the steepest contact slope the test reached, so at least each drop.
  EXPECT_LE(a->friction_angle.max, a->upper_bound_friction_angle + 1e-12);
  EXPECT_GE(a->theta_max + std::atan(o.atomic_friction), a->friction_angle.max - 1e-12);
  o.runaway_distance = 1.0;  // stated: longer than the overlap, refused, not shortened
  EXPECT_FALSE(frictal::predict(lo, &up, o).ok());
}

TEST(Warnings, ABoundAt90ThatNoDropNearsIsNoReasonToDoubtTheAnswer) {
  // instruments/sdf-1.sdf, a 7 x 4 map whose steepest facet rises 1.95 deg: against itself, drops
  // near its side slide sideways until the block hangs on the lower map's rim, a seat with a
  // vertical contact, so the rigid upper bound (the steepest seat) is 90 deg, while every drop
  // holds at most at the facets' slopes. That is bound-at-90 (the bound is no estimate), not
  // friction-angle-at-90 with a units fix: the answer is not doubtful.
  auto m = frictal::read_map(std::string(FRICTAL_TEST_DATA) + "/instruments/sdf-1.sdf");
  ASSERT_TRUE(m.ok()) << m.error().message;
  frictal::PredictSurface s;
  s.is_map = true;
  s.map = *m;
  s.name = "sdf-1.sdf";
  const auto p = frictal::predict(s, nullptr);
  ASSERT_TRUE(p.ok()) << p.error().message;
  EXPECT_LT(p->friction_angle.max, 2.0 * std::numbers::pi / 180);
  EXPECT_GE(p->upper_bound_friction_angle, 89.5 * std::numbers::pi / 180);
  EXPECT_TRUE(has_code(p->warnings, "bound-at-90"));
  EXPECT_FALSE(has_code(p->warnings, "friction-angle-at-90"));
  EXPECT_EQ(p->trust, "ok");
  bool listed = false;
  for (const auto& c : frictal::warning_codes()) listed |= c.code == "bound-at-90" && !c.doubtful;
  EXPECT_TRUE(listed);
}

TEST(PredictSettings, EachFieldFillsItsMemberAndTheDefaultsAreTheStructs) {
  using frictal::find_field;
  using frictal::PredictOptions;
  const PredictOptions d;
  // The table's defaults are PredictOptions{}'s (0 lengths read as automatic: NaN).
  const auto& t = frictal::predict_settings();
  EXPECT_EQ(find_field(t, "drops")->default_value, d.map_drops);
  EXPECT_EQ(find_field(t, "map_work_limit")->default_value, d.map_work_limit);
  EXPECT_EQ(find_field(t, "in_place")->default_value, d.turn_over_upper ? 0 : 1);
  for (const char* automatic : {"runaway_distance", "block_length", "sphere_radius"})
    EXPECT_TRUE(std::isnan(find_field(t, automatic)->default_value)) << automatic;
  EXPECT_EQ(find_field(frictal::conditioning_settings(), "spike_threshold")->default_value,
            frictal::kDefaultSpikeThreshold);
  // Each name reaches its member (values in SI), the conditioning's beside the prediction's.
  const frictal::ValueSet v = {{"direction", 3.0},
                               {"atomic_friction", 0.25},
                               {"runaway_distance", 2e-4},
                               {"block_length", std::string("whole")},
                               {"period", 1e-3},
                               {"drops", std::int64_t{7}},
                               {"locked", true},
                               {"in_place", true},
                               {"sphere_radius", 1e-6},
                               {"map_work_limit", 10.0},
                               {"crop", std::string("1mm,2mm")},
                               {"remove_spikes", true},
                               {"spike_threshold", 6.0},
                               {"detrend", std::string("poly:2")}};
  auto o = frictal::make_predict_options(v);
  ASSERT_TRUE(o) << o.error().message;
  EXPECT_EQ(o->direction, 3.0);
  EXPECT_EQ(o->atomic_friction, 0.25);
  EXPECT_EQ(o->runaway_distance, 2e-4);
  EXPECT_EQ(o->block_length, -1);  // predict.hpp: < 0 is the whole upper profile
  EXPECT_EQ(o->period, 1e-3);
  EXPECT_EQ(o->map_drops, 7);
  EXPECT_TRUE(o->map_locked);
  EXPECT_FALSE(o->turn_over_upper);
  EXPECT_EQ(o->sphere_radius, 1e-6);
  EXPECT_EQ(o->map_work_limit, 10.0);
  ASSERT_TRUE(o->crop.has_value());
  EXPECT_DOUBLE_EQ(o->crop->x_min, 1e-3);
  EXPECT_DOUBLE_EQ(o->crop->x_max, 2e-3);
  EXPECT_TRUE(o->remove_spikes);
  EXPECT_EQ(o->spike_threshold, 6.0);
  ASSERT_TRUE(o->detrend.has_value());
  EXPECT_EQ(o->detrend->kind, frictal::DetrendKind::Polynomial);
  EXPECT_EQ(o->detrend->degree, 2);
  // Nothing given: the struct's defaults (a NaN automatic length is 0, "the default", in the struct).
  auto none = frictal::make_predict_options({{"runaway_distance", std::nan("")}});
  ASSERT_TRUE(none);
  EXPECT_EQ(none->runaway_distance, 0);
  EXPECT_EQ(none->map_drops, d.map_drops);
  EXPECT_FALSE(none->detrend.has_value());
  // Errors name the field and the valid values, or the nearest name.
  auto bad = frictal::make_predict_options({{"drops", std::int64_t{1}}});
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("drops: expected a whole number in 2..64, got 1"), std::string::npos)
      << bad.error().message;
  auto typo = frictal::make_predict_options({{"runaway_distanse", 1e-3}});
  ASSERT_FALSE(typo);
  EXPECT_NE(typo.error().message.find("did you mean 'runaway_distance'"), std::string::npos) << typo.error().message;
  auto form = frictal::make_predict_options({{"detrend", std::string("cubic")}});
  ASSERT_FALSE(form);
  EXPECT_NE(form.error().message.find("none, mean, line, plane or poly:N"), std::string::npos) << form.error().message;
  auto whole = frictal::make_predict_options({{"block_length", -1.0}});  // the word's value is no length
  EXPECT_FALSE(whole);
}
