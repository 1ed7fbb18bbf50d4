// The tilt test's settings table (tilt.hpp, settings.hpp): each user-facing TiltConfig member
// once, with its unit, range and help; defaults are TiltConfig's own initialisers.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include <fmt/core.h>

#include "frictal/hold.hpp"
#include "frictal/tilt.hpp"
#include "settings/binding.hpp"

namespace frictal {
namespace {

using settings_detail::bind;
using settings_detail::bind_choice;
using settings_detail::Binding;

constexpr double kInf = std::numeric_limits<double>::infinity();

using settings_detail::F;
using settings_detail::Lo;

using B = Binding<TiltConfig>;
#define FRICTAL_MEMBER(expr) \
  [](TiltConfig & c) -> auto& { return c.expr; }

const std::vector<B>& table() {
  static const auto t = settings_detail::with_defaults<TiltConfig>(
      {
          // Contact law (Table II).
          bind<TiltConfig>(F("normal_stiffness", "N/m", 0, Lo::Open, kInf, "Normal contact stiffness k_n"),
                           FRICTAL_MEMBER(contact.normal_stiffness)),
          bind<TiltConfig>(F("tangential_stiffness", "N/m", 0, Lo::Closed, kInf, "Tangential contact stiffness k_t"),
                           FRICTAL_MEMBER(contact.tangential_stiffness)),
          bind<TiltConfig>(F("normal_damping", "1/s", 0, Lo::Closed, kInf, "Normal damping gamma_n"),
                           FRICTAL_MEMBER(contact.normal_damping)),
          bind<TiltConfig>(F("tangential_damping", "1/s", 0, Lo::Closed, kInf,
                             "Tangential damping gamma_t (constant-rate protocol; off in quasi-static)"),
                           FRICTAL_MEMBER(contact.tangential_damping)),
          bind<TiltConfig>(settings_detail::shared("atomic_friction"), FRICTAL_MEMBER(contact.atomic_friction)),
          bind_choice<TiltConfig>(
              F("contact_rule", "", 0, Lo::Closed, 0,
                "Which touching vertex-edge pairs push: pairs (every one, the paper's), closest (one force per "
                "contact of the rigid rounded blocks: none from concave corners, one pair per contact, a "
                "concave corner's flanks by inclusion-exclusion), or auto (pairs with constant-rate, closest "
                "with quasi-static)"),
              FRICTAL_MEMBER(contact_rule),
              std::vector<std::pair<std::string, TiltContactRule>>{{"auto", TiltContactRule::Auto},
                                                                   {"pairs", TiltContactRule::Pairs},
                                                                   {"closest", TiltContactRule::Closest}}),
          bind_choice<TiltConfig>(
              F("contact_law", "", 0, Lo::Closed, 0,
                "Normal force law: linear (f_n = k_n overlap, Eq. 8, stiff enough for rigid blocks) or hertz "
                "((4/3) E* sqrt(R) overlap^1.5 with R the local radius of curvature at the contact; needs "
                "block_modulus)"),
              FRICTAL_MEMBER(contact.law),
              std::vector<std::pair<std::string, dem::ContactLaw>>{{"linear", dem::ContactLaw::Linear},
                                                                   {"hertz", dem::ContactLaw::Hertz}}),
          bind<TiltConfig>(F("block_modulus", "Pa", 0, Lo::Closed, kInf,
                             "Young's modulus E of the blocks (contact_law hertz; > 0 there)"),
                           FRICTAL_MEMBER(modulus)),
          bind<TiltConfig>(
              F("block_poisson", "", -1, Lo::Open, 0.5, "Poisson's ratio nu of the blocks (contact_law hertz)"),
              FRICTAL_MEMBER(poisson)),
          bind<TiltConfig>(F("elastic_blocks", "", 1, Lo::Closed, 2,
                             "Contact law hertz: 1 (one elastic block on a rigid one, E* = E/(1-nu^2)) or 2 "
                             "(both of that material, E* = E/(2(1-nu^2)))"),
                           FRICTAL_MEMBER(elastic_blocks)),
          bind<TiltConfig>(F("damping_ratio", "", 0, Lo::Closed, kInf,
                             "Damping ratio zeta of the Hertz dashpot 2 zeta sqrt(m k) (contact_law hertz)"),
                           FRICTAL_MEMBER(contact.damping_ratio)),
          bind<TiltConfig>(F("restitution", "", 0, Lo::Closed, 1,
                             "Restitution eps of Eq. 12 on the upper block's mass; > 0 replaces normal_damping"),
                           FRICTAL_MEMBER(restitution)),
          // Blocks (Table I, II).
          bind<TiltConfig>(F("block_height", "m", 0, Lo::Open, kInf, "Block height h below the surface minimum"),
                           FRICTAL_MEMBER(block_height)),
          // The signature's table takes this field too (shared_field): absent there, the faces are
          // rigid profiles. The CLI also reads the retired `--radius` (hidden, options.cpp).
          bind<TiltConfig>(settings_detail::shared("spheroradius"), FRICTAL_MEMBER(radius)),
          bind<TiltConfig>(F("density", "kg/m^2", 0, Lo::Open, kInf, "Areal density rho of both blocks"),
                           FRICTAL_MEMBER(density)),
          bind<TiltConfig>(F("gravity", "m/s^2", 0, Lo::Closed, kInf, "Gravitational acceleration g"),
                           FRICTAL_MEMBER(gravity)),
          bind_choice<TiltConfig>(
              F("face", "", 0, Lo::Closed, 0, "Block face of a folded surface: the full curve or its upper envelope"),
              FRICTAL_MEMBER(face),
              std::vector<std::pair<std::string, TiltFace>>{{"curve", TiltFace::Curve},
                                                            {"envelope", TiltFace::Envelope}}),
          bind<TiltConfig>(
              F("initial_offset", "m", -kInf, Lo::Closed, kInf,
                "Shift of the upper block along x from the left ends aligned; auto: the offset of least lift from "
                "the signature (files: the middle of the stated test's drop range)"),
              FRICTAL_MEMBER(initial_offset)),
          bind<TiltConfig>(F("placement_gap", "m", 0, Lo::Closed, kInf, "Clearance between the blocks when placed"),
                           FRICTAL_MEMBER(placement_gap)),
          bind<TiltConfig>(settings_detail::shared("period"), FRICTAL_MEMBER(period)),
          bind<TiltConfig>(
              F("predict", "", 0, Lo::Closed, 1, "Compute the signature prediction theta_max + atan(mu_a)"),
              FRICTAL_MEMBER(predict)),
          // Protocol and detection (docs/dem.md).
          bind<TiltConfig>(F("tilt_rate", "rad/s", 0, Lo::Open, kInf,
                             "Angular velocity of the lower block (constant-rate protocol)"),
                           FRICTAL_MEMBER(tilt_rate)),
          bind<TiltConfig>(F("reverse", "", 0, Lo::Closed, 1, "Tilt the other way: the upper block slides towards -x"),
                           FRICTAL_MEMBER(reverse)),
          bind<TiltConfig>(
              F("settle_time", "s", 0, Lo::Closed, kInf,
                "Free settling before the tilt starts (constant-rate protocol; quasi-static: a relaxation)"),
              FRICTAL_MEMBER(settle_time)),
          bind_choice<TiltConfig>(
              F("settling", "", 0, Lo::Closed, 0,
                "Constant-rate protocol: how the block comes to rest before the tilt starts: free (the paper's, "
                "settle_time of free motion) or relax (FIRE at zero tilt, as quasi-static, at most relax_time)"),
              FRICTAL_MEMBER(settling),
              std::vector<std::pair<std::string, TiltSettling>>{{"free", TiltSettling::Free},
                                                                {"relax", TiltSettling::Relax}}),
          bind_choice<TiltConfig>(
              F("turn", "", 0, Lo::Closed, 0,
                "Constant-rate protocol: what turns at tilt_rate: block (the lower block about its centroid, the "
                "paper's; it kicks a resting block at the start) or gravity (in the lower block's frame, as "
                "quasi-static)"),
              FRICTAL_MEMBER(turn),
              std::vector<std::pair<std::string, TiltTurn>>{{"block", TiltTurn::Block},
                                                            {"gravity", TiltTurn::Gravity}}),
          bind<TiltConfig>(
              F("max_tilt", "rad", 0, Lo::Open, std::numbers::pi / 2, "Give up (no slide) beyond this tilt", true),
              FRICTAL_MEMBER(max_tilt)),
          bind<TiltConfig>(settings_detail::shared("runaway_distance"), FRICTAL_MEMBER(runaway_distance)),
          bind<TiltConfig>(
              F("stick_speed", "m/s", 0, Lo::Open, kInf, "Relative speed counted as stuck (constant-rate protocol)"),
              FRICTAL_MEMBER(stick_speed)),
          bind<TiltConfig>(F("stick_duration", "s", 0, Lo::Closed, kInf, "Shortest stick (constant-rate protocol)"),
                           FRICTAL_MEMBER(stick_duration)),
          bind_choice<TiltConfig>(
              F("protocol", "", 0, Lo::Closed, 0,
                "How the tilt grows: constant-rate (the paper's, tilt_rate) or quasi-static (tilt_increment, "
                "each relaxed to rest by FIRE)"),
              FRICTAL_MEMBER(protocol),
              std::vector<std::pair<std::string, TiltProtocol>>{{"constant-rate", TiltProtocol::ConstantRate},
                                                                {"quasi-static", TiltProtocol::QuasiStatic}}),
          bind<TiltConfig>(
              F("tilt_increment", "rad", 0, Lo::Open, std::numbers::pi / 2,
                "Quasi-static: tilt added per increment (the angle reads at most one increment low)", true),
              FRICTAL_MEMBER(tilt_increment)),
          bind<TiltConfig>(F("relax_time", "s", 0, Lo::Open, kInf,
                             "Quasi-static: longest relaxation per increment (and of the settling, also with "
                             "settling = relax); beyond it the run warns (unrelaxed)"),
                           FRICTAL_MEMBER(relax_time)),
          bind<TiltConfig>(F("relax_force", "", 0, Lo::Open, kInf,
                             "Quasi-static: at rest below this unbalanced force on the upper block averaged over "
                             "relax_duration, as a fraction of its weight"),
                           FRICTAL_MEMBER(relax_force)),
          bind<TiltConfig>(F("relax_speed", "m/s", 0, Lo::Open, kInf, "Quasi-static: at rest below this speed"),
                           FRICTAL_MEMBER(relax_speed)),
          bind<TiltConfig>(F("relax_duration", "s", 0, Lo::Closed, kInf,
                             "Quasi-static: the speed stays below relax_speed this long without a break (the force "
                             "is averaged over it)"),
                           FRICTAL_MEMBER(relax_duration)),
          bind<TiltConfig>(F("check_stiffness", "", 0, Lo::Closed, 1,
                             "Run again at 10 normal_stiffness and tangential_stiffness; warn (stiffness) when the "
                             "angle moves by more than warn_stiffness_angle"),
                           FRICTAL_MEMBER(check_stiffness)),
          // Numerics.
          bind<TiltConfig>(F("time_step", "s", 0, Lo::Open, kInf,
                             "Largest time step with the adaptive step, else the fixed step (docs/dem.md)"),
                           FRICTAL_MEMBER(time_step)),
          bind<TiltConfig>(
              F("adaptive_time_step", "", 0, Lo::Closed, 1,
                "Choose each step from the stability limit of the contacts present; false: fixed time_step"),
              FRICTAL_MEMBER(adaptive_time_step)),
          bind<TiltConfig>(
              F("time_step_safety", "", 0, Lo::Open, 1, "Adaptive step: the fraction of the stability limit taken"),
              FRICTAL_MEMBER(time_step_safety)),
          bind<TiltConfig>(F("implicit_damping", "", 0, Lo::Closed, 1,
                             "Integrate the normal dashpots implicitly (backward Euler); false: explicit"),
                           FRICTAL_MEMBER(implicit_damping)),
          bind<TiltConfig>(F("skin", "m", 0, Lo::Closed, kInf, "Neighbour-list skin"), FRICTAL_MEMBER(skin)),
          bind<TiltConfig>(F("max_steps_beyond_limit", "", 0, Lo::Closed, 2147483647,
                             "Stop after this many steps (in total) beyond the explicit stability limit"),
                           FRICTAL_MEMBER(max_steps_beyond_limit)),
          bind<TiltConfig>(F("hold_rotation", "", 0, Lo::Closed, 1,
                             "Hold the upper block's rotation relative to the lower block (it still translates)"),
                           FRICTAL_MEMBER(hold_rotation)),
          // Model warnings (docs/dem.md sec. 6).
          bind<TiltConfig>(F("warn_overlap_fraction", "", 0, Lo::Open, kInf,
                             "Warn (core-overlap) when the resting overlap W/k_n exceeds this fraction of r"),
                           FRICTAL_MEMBER(warn_overlap_fraction)),
          bind<TiltConfig>(F("warn_prediction_tolerance", "rad", 0, Lo::Open, kInf,
                             "Warn (rounding) when the spheropolygon and rigid predictions differ by more"),
                           FRICTAL_MEMBER(warn_prediction_tolerance)),
          bind<TiltConfig>(F("warn_rotation", "rad", 0, Lo::Open, kInf,
                             "Warn (rotation) when the upper block turns against the lower one by more before the "
                             "slide"),
                           FRICTAL_MEMBER(warn_rotation)),
          bind<TiltConfig>(F("warn_time_step_fraction", "", 0, Lo::Open, kInf,
                             "Warn (time-step) when a fixed time step exceeds this fraction of one contact's "
                             "period"),
                           FRICTAL_MEMBER(warn_time_step_fraction)),
          bind<TiltConfig>(F("warn_creep_slip", "m", 0, Lo::Open, kInf,
                             "Creep event: a slip at least this long that sticks again within a tenth of the "
                             "smallest feature"),
                           FRICTAL_MEMBER(warn_creep_slip)),
          bind<TiltConfig>(F("warn_creep_angle", "rad", 0, Lo::Open, kInf,
                             "Warn (creep) when the first creep event began more than this below the friction "
                             "angle"),
                           FRICTAL_MEMBER(warn_creep_angle)),
          bind<TiltConfig>(F("warn_stiffness_angle", "rad", 0, Lo::Open, kInf,
                             "Warn (stiffness) when check_stiffness moves the friction angle by more"),
                           FRICTAL_MEMBER(warn_stiffness_angle)),
          // Output.
          bind<TiltConfig>(
              F("series_interval", "s", 0, Lo::Closed, kInf, "Time between rows of the time series; 0: none"),
              FRICTAL_MEMBER(series_interval)),
          bind<TiltConfig>(F("frame_interval", "s", 0, Lo::Closed, kInf, "Time between frames; 0: none", false,
                             "0.01 when frames are written (CLI --frames), else 0"),
                           FRICTAL_MEMBER(frame_interval)),
      },
      TiltConfig{});
  return t;
}

#undef FRICTAL_MEMBER

}  // namespace

const std::vector<Field>& tilt_settings() {
  static const std::vector<Field> f = settings_detail::fields_of(table());
  return f;
}

TiltConfig tilt_config_for_surface(double period, double scale) {
  TiltConfig c = default_tilt_config();
  c.period = period;
  if (scale > 0) c.runaway_distance = scale;
  return c;
}

namespace {

// Median spacing of the distinct x of a curve, in order of x (unit: m); 0 without two.
double median_spacing(const Curve& c) {
  std::vector<double> x(c.x);
  std::sort(x.begin(), x.end());
  std::vector<double> d;
  for (std::size_t i = 1; i < x.size(); ++i)
    if (x[i] > x[i - 1]) d.push_back(x[i] - x[i - 1]);
  if (d.empty()) return 0;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

}  // namespace

Result<TiltScaling> scale_tilt_defaults(const Curve& lower, const Curve& upper, const TiltConfig& base) {
  TiltScaling sc;
  double len[2], dx[2];
  const Curve* c[2] = {&lower, &upper};
  for (int i = 0; i < 2; ++i) {
    const char* what = i ? "upper surface" : "lower surface";
    for (std::size_t k = 0; k < c[i]->x.size(); ++k)
      if (!std::isfinite(c[i]->x[k]) || (k < c[i]->z.size() && !std::isfinite(c[i]->z[k])))
        return make_error(fmt::format("{}: point {} is not finite", what, k));
    dx[i] = median_spacing(*c[i]);
    if (!(dx[i] > 0)) return make_error(fmt::format("{}: expected at least two points with distinct x", what));
    const auto [lo, hi] = std::minmax_element(c[i]->x.begin(), c[i]->x.end());
    len[i] = *hi - *lo;
    if (!c[i]->z.empty()) {
      const auto [zlo, zhi] = std::minmax_element(c[i]->z.begin(), c[i]->z.end());
      sc.height_range = std::max(sc.height_range, *zhi - *zlo);
    }
  }
  sc.length = std::min(len[0], len[1]);
  sc.point_spacing = std::min(dx[0], dx[1]);
  // A file written at the reference length keeps the defaults bit for bit: a length within
  // rounding of 0.2 m (1e-9 relative: e.g. a scan rescaled to 0.2 m in floating point) is 0.2 m.
  double s = sc.length / kTiltReferenceLength;
  if (std::fabs(s - 1) <= 1e-9) s = 1;
  sc.length_factor = s;
  TiltConfig& t = sc.config;
  t = base;
  const double sr = s * base.radius;
  const double r = std::min(sr, sc.point_spacing);
  const double q = r < sr ? r / sr : 1.0;
  sc.radius_factor = q;
  const double contact_time = std::sqrt(s * q), gravity_time = std::sqrt(s);
  // In table order (tilt_settings()); each entry: name, member, factor.
  auto set = [&](const char* name, double& v, double factor) {
    const double from = v;
    v *= factor;
    if (v != from) sc.settings.push_back({name, from, v});
  };
  set("normal_stiffness", t.contact.normal_stiffness, s / q);
  set("tangential_stiffness", t.contact.tangential_stiffness, s / q);
  set("normal_damping", t.contact.normal_damping, 1 / contact_time);
  set("tangential_damping", t.contact.tangential_damping, 1 / contact_time);
  set("block_height", t.block_height, s);
  {
    const double from = t.radius;
    t.radius = r;
    if (t.radius != from) sc.settings.push_back({"spheroradius", from, r});
  }
  set("placement_gap", t.placement_gap, s * q);
  if (t.period > 0) set("period", t.period, s);  // a length like the others (<= 0: none)
  set("tilt_rate", t.tilt_rate, 1 / gravity_time);
  set("settle_time", t.settle_time, gravity_time);
  set("runaway_distance", t.runaway_distance, s);
  set("stick_speed", t.stick_speed, gravity_time);
  set("stick_duration", t.stick_duration, gravity_time);
  set("relax_time", t.relax_time, gravity_time);
  set("relax_speed", t.relax_speed, gravity_time);
  set("relax_duration", t.relax_duration, gravity_time);
  set("time_step", t.time_step, contact_time);
  set("skin", t.skin, s);
  set("warn_creep_slip", t.warn_creep_slip, s);
  set("series_interval", t.series_interval, gravity_time);
  set("frame_interval", t.frame_interval, gravity_time);
  return sc;
}

namespace {

// The stated test of a measured pair (hold.hpp's, as predict() states it): the block cut from the
// upper profile, d, the drops. A folded curve (not a profile) states none: its whole block stays.
Result<TiltStatedTest> measured_test(const Curve& lower, const Curve& upper, const ValueSet& given, double block_length,
                                     Curve& block, StatedDrops& drops) {
  TiltStatedTest t;
  auto lp = as_profile(lower, "lower surface");
  auto up = as_profile(upper, "upper surface");
  if (!lp.ok() || !up.ok() || lp->x.size() < 2 || up->x.size() < 2) {
    if (block_length != 0)
      return make_error(fmt::format(
          "tilt: block length {:.6g} m: a folded curve (not a profile) states no test; its whole block slides "
          "(leave the block length unset)",
          block_length));
    return t;
  }
  const double d_given = given.count("runaway_distance") ? as_real(given.at("runaway_distance")) : 0.0;
  const double upper_len = up->x.back() - up->x.front(), lower_len = lp->x.back() - lp->x.front();
  auto fit = stated_test(*lp, upper_len, d_given, block_length);
  if (!fit) return with_prefix("tilt: ", fit.error());
  t.runaway_distance = fit->runaway_distance;
  t.rule = fit->rule;
  t.warnings = std::move(fit->warnings);
  if (fit->whole) {
    t.block = "whole";
    t.block_length = upper_len;
    t.drop = given.count("initial_offset") ? "given" : "the offset of least lift";
    return t;
  }
  Profile piece = stated_block(*up, fit->block_length);
  t.block = "stated";
  t.block_length = piece.x.back() - piece.x.front();
  drops = stated_drops(lower_len, t.block_length, t.runaway_distance);
  t.drop_min = drops.drop_min;
  t.drop_max = drops.drop_max;
  t.drop = given.count("initial_offset") ? "given" : "the middle of the drop range";
  block = as_curve(piece);
  return t;
}

}  // namespace

Result<TiltScaling> tilt_setup(const Curve& lower, const Curve& upper, const ValueSet& given, double period,
                               double scale, double block_length) {
  const bool measured = !(period > 0) && !(scale > 0);
  if (!std::isfinite(block_length))
    return make_error(fmt::format("tilt: block length {} m: expected a length > 0 (or the whole block)", block_length));
  if (!measured && block_length != 0)
    return make_error(fmt::format(
        "tilt: block length {:.6g} m: a generated surface slides its whole block (the paper's Table I blocks); leave "
        "the block length unset, or give the surface as a measured profile",
        block_length));
  Curve block = upper;
  TiltStatedTest test;
  StatedDrops drops;
  if (measured) {
    auto t = measured_test(lower, upper, given, block_length, block, drops);
    if (!t) return t.error();
    test = std::move(*t);
  }
  const TiltConfig own = tilt_config_for_surface(period, scale);
  auto sc = scale_tilt_defaults(lower, block, own);
  if (!sc) return sc.error();
  if (!test.block.empty()) {
    // The stated d is at the surfaces' own scale (slope correlation lengths), not scaled.
    std::erase_if(sc->settings, [](const TiltScaledSetting& t) { return t.name == "runaway_distance"; });
    sc->config.runaway_distance = test.runaway_distance;
    if (test.block == "stated") {
      sc->config.spread_offset_max = drops.offset_max;
      sc->config.spread_drop_min = drops.drop_min;
      sc->config.spread_drop_max = drops.drop_max;
      sc->config.initial_offset = 0.5 * (drops.drop_min + drops.drop_max);
    }
  }
  sc->test = std::move(test);
  sc->upper = std::move(block);
  // A surface's own period and run-away distance (its wavelength) are already at its scale.
  if (period > 0) {
    std::erase_if(sc->settings, [](const TiltScaledSetting& t) { return t.name == "period"; });
    sc->config.period = own.period;
  }
  if (scale > 0) {
    std::erase_if(sc->settings, [](const TiltScaledSetting& t) { return t.name == "runaway_distance"; });
    sc->config.runaway_distance = own.runaway_distance;
  }
  // A measured scan: the quasi-static protocol with the rotation held, where not given. On every
  // profile of tests/data the paper's protocol (the lower block turning at tilt_rate, the upper
  // block free to turn) reads no friction angle of the surfaces: the block turns against the
  // lower one (warning rotation) or is still moving when the tilt starts and slides below the
  // rigid model's bracket; loaded quasi-statically with its rotation held, each reads inside it
  // (docs/dem.md sec. 5, "The protocol on measured surfaces").
  if (!(period > 0) && !(scale > 0)) {
    std::string note;
    if (!given.count("protocol")) {
      sc->config.protocol = TiltProtocol::QuasiStatic;
      note = "protocol = quasi-static";
    }
    if (!given.count("hold_rotation")) {
      sc->config.hold_rotation = true;
      note += std::string(note.empty() ? "" : ", ") + "hold_rotation = true";
    }
    sc->measured_defaults = note;
  }
  auto cfg = make_tilt_config(given, sc->config);
  if (!cfg) return cfg.error();
  // What the caller set is kept and not reported as scaled.
  std::erase_if(sc->settings, [&](const TiltScaledSetting& t) { return given.count(t.name) > 0; });
  // Scaled from the length, the test assumes a surface whose relief is below its length (the
  // Table I blocks: 1e-2 m of relief or less on 0.2 m); a taller one (typically z in other units
  // than x) would turn its blocks' ends far faster than the length scale allows.
  if (sc->height_range > sc->length)
    return make_error(
        fmt::format("tilt: the surfaces' height range {:.4g} m exceeds their length {:.4g} m (expected a height "
                    "range in [0, {:.4g}] m): are z and x in the same unit? (frictal info FILE; give the unit in the "
                    "file's header)",
                    sc->height_range, sc->length, sc->length));
  const double r_max = kTiltMaxRadiusOverSpacing * sc->point_spacing;
  if (cfg->radius > r_max)
    return make_error(fmt::format(
        "tilt: spheroradius {:.3g} m cannot resolve this surface: expected a value in (0, {:.3g}] m, {} times its "
        "point spacing {:.3g} m (the default here: {:.3g} m; beyond it one rounded contact spans more than {} points "
        "of each face)",
        cfg->radius, r_max, kTiltMaxRadiusOverSpacing, sc->point_spacing, sc->config.radius,
        2 * kTiltMaxRadiusOverSpacing));
  sc->config = std::move(*cfg);
  return sc;
}

Result<TiltConfig> make_tilt_config(const ValueSet& si_values, const TiltConfig& base) {
  return settings_detail::apply(table(), base, si_values, "tilt");
}

ValueSet tilt_values(const TiltConfig& config) { return settings_detail::values_of(table(), config); }

}  // namespace frictal
