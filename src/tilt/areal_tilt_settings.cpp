// The 3D tilt test's settings table (areal_tilt.hpp, settings.hpp): each user-facing
// ArealTiltOptions member once, with its unit, range and help; defaults are the struct's own
// initialisers. The model's times are in scaled units (lengths divided by the lower map's larger
// extent, gravity 9.81 m/s^2; docs/mujoco.md): their unit is written "scaled s".
#include <limits>
#include <numbers>
#include <utility>

#include "frictal/areal_tilt.hpp"
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

// A quantity that the tilt test has too keeps its one name and reads the same in every command
// (the tilt table's field: help, unit, range, default text).
Field from_tilt(const std::string& name) {
  for (const Field& f : tilt_settings())
    if (f.name == name) return f;
  return F(name, "", 0, Lo::Closed, kInf, name);  // not reached: the names below are the tilt table's
}

using B = Binding<ArealTiltOptions>;
#define FRICTAL_MEMBER(expr) \
  [](ArealTiltOptions & c) -> auto& { return c.expr; }

const std::vector<B>& table() {
  static const auto t = settings_detail::with_defaults<ArealTiltOptions>(
      {
          // The test.
          bind<ArealTiltOptions>(
              F("angle", "rad", -kInf, Lo::Open, kInf, "Sliding direction d, from +x towards +y", true),
              FRICTAL_MEMBER(angle)),
          // As in the tilt test (from_tilt): mu_a at every contact; D along d since the last stop
          // (the front ends' default: default_map_runaway_distance, a length of the lower map's surface).
          bind<ArealTiltOptions>(from_tilt("atomic_friction"), FRICTAL_MEMBER(atomic_friction)),
          bind<ArealTiltOptions>(from_tilt("runaway_distance"), FRICTAL_MEMBER(runaway_distance)),
          bind_choice<ArealTiltOptions>(
              F("lateral", "", 0, Lo::Closed, 0,
                "free: the block may move sideways (slide joints along x, y, z); locked: along d (and z) only"),
              FRICTAL_MEMBER(lock_lateral),
              std::vector<std::pair<std::string, bool>>{{"free", false}, {"locked", true}}),
          bind<ArealTiltOptions>(
              F("tilt_step", "rad", 0, Lo::Open, 10 * std::numbers::pi / 180,
                "Tilt increment near the run-away (the angle reads at most one increment low)", true),
              FRICTAL_MEMBER(tilt_step)),
          bind<ArealTiltOptions>(
              F("coarse_tilt_step", "rad", 0, Lo::Open, std::numbers::pi / 4,
                "Tilt increment up to the first run-away (then tilt_step from the state before)", true),
              FRICTAL_MEMBER(coarse_tilt_step)),
          // The contact model.
          bind<ArealTiltOptions>(F("sphere_radius", "m", 0, Lo::Closed, kInf,
                                   "Radius r of the spheres on the upper face's nodes; 0: a fifth of the lower map's "
                                   "smaller spacing"),
                                 FRICTAL_MEMBER(sphere_radius)),
          bind<ArealTiltOptions>(
              F("hfield_refine", "", 1, Lo::Closed, 16,
                "Sample the lower map's bilinear surface this many times finer for the height field"),
              FRICTAL_MEMBER(hfield_refine)),
          bind_choice<ArealTiltOptions>(
              F("collision", "", 0, Lo::Closed, 0,
                "Sphere-height field contacts: exact (the nearest point of each triangle) or native (MuJoCo's MPR "
                "on prisms, whose internal edges catch a sliding sphere)"),
              FRICTAL_MEMBER(exact_contacts),
              std::vector<std::pair<std::string, bool>>{{"exact", true}, {"native", false}}),
          bind<ArealTiltOptions>(F("mujoco_time_step", "scaled s", 0, Lo::Open, kInf, "MuJoCo time step"),
                                 FRICTAL_MEMBER(time_step)),
          bind<ArealTiltOptions>(F("mujoco_contact_time", "scaled s", 0, Lo::Open, kInf,
                                   "Contact softness: solref time constant, at least 2 time steps"),
                                 FRICTAL_MEMBER(contact_time)),
          // The quasi-static protocol.
          bind<ArealTiltOptions>(F("damping", "1/scaled s", 0, Lo::Closed, kInf, "Viscous joint damping per unit mass"),
                                 FRICTAL_MEMBER(damping)),
          bind<ArealTiltOptions>(F("local_damping", "", 0, Lo::Closed, 1,
                                   "Local non-viscous (Cundall) damping: a force against each joint's velocity, this "
                                   "fraction of its unbalanced force",
                                   true),
                                 FRICTAL_MEMBER(local_damping)),
          bind<ArealTiltOptions>(
              F("settle_damping", "1/scaled s", 0, Lo::Closed, kInf,
                "Viscous damping per unit mass in place of the local damping while the dropped block settles at "
                "zero tilt (an overdamped descent; the prediction's steepest descent as it grows); 0: the drop "
                "relaxes as the increments (relaxation)"),
              FRICTAL_MEMBER(settle_damping)),
          bind<ArealTiltOptions>(
              F("tilt_damping", "1/scaled s", 0, Lo::Closed, kInf,
                "Viscous damping per unit mass in place of the local damping during the tilt increments (an "
                "overdamped slip; each increment waits until the block could creep two lower-map cells at one "
                "tilt step's drive); 0: the relaxation (local or quench)"),
              FRICTAL_MEMBER(tilt_damping)),
          bind_choice<ArealTiltOptions>(
              F("relaxation", "", 0, Lo::Closed, 0,
                "How the block relaxes after the drop and each tilt increment (unless settle_damping or "
                "tilt_damping): local (Cundall's local damping) or quench (quenched dynamics: the velocity zeroed "
                "whenever the unbalanced force does negative work, the speed capped at quench_speed; no creep, no "
                "momentum past a seat)"),
              FRICTAL_MEMBER(quench), std::vector<std::pair<std::string, bool>>{{"local", false}, {"quench", true}}),
          bind<ArealTiltOptions>(
              F("quench_speed", "scaled m/s", 0, Lo::Open, kInf,
                "With relaxation quench: the block's largest speed (it turns with the force within speed^2 / "
                "force; the steepest descent as it shrinks)"),
              FRICTAL_MEMBER(quench_speed)),
          bind<ArealTiltOptions>(
              F("relax_chunk", "scaled s", 0, Lo::Open, kInf,
                "Longest relaxation per rest test; an increment waits for up to 40 of them before it counts as "
                "unsettled"),
              FRICTAL_MEMBER(relax_time)),
          bind<ArealTiltOptions>(F("force_tolerance", "", 0, Lo::Open, kInf,
                                   "At rest: unbalanced force below this fraction of the weight"),
                                 FRICTAL_MEMBER(force_tolerance)),
          bind<ArealTiltOptions>(F("speed_tolerance", "scaled m/s", 0, Lo::Open, kInf, "At rest: speed below this"),
                                 FRICTAL_MEMBER(speed_tolerance)),
          bind<ArealTiltOptions>(
              F("rest_steps", "", 1, Lo::Closed, 1e9, "At rest: balanced and still for this many steps in a row"),
              FRICTAL_MEMBER(rest_steps)),
      },
      ArealTiltOptions{});
  return t;
}

#undef FRICTAL_MEMBER

}  // namespace

const std::vector<Field>& areal_tilt_settings() {
  static const std::vector<Field> f = settings_detail::fields_of(table());
  return f;
}

Result<ArealTiltOptions> make_areal_tilt_options(const ValueSet& si_values, const ArealTiltOptions& base) {
  auto o = settings_detail::apply(table(), base, si_values, "areal-tilt");
  if (!o) return o;
  if (o->contact_time < 2 * o->time_step)
    return make_error(fmt::format(
        "areal-tilt mujoco_contact_time = {} scaled s: expected at least 2 time steps (2 x mujoco_time_step = {})",
        o->contact_time, 2 * o->time_step));
  return o;
}

ValueSet areal_tilt_values(const ArealTiltOptions& options) { return settings_detail::values_of(table(), options); }

}  // namespace frictal
