// frictal — spheropolygon rigid-body dynamics (paper Sec. IV A, Eq. 7-12).
//
// A body is a simple polygon (convex or not) swept by a disk of radius r, its spheroradius
// (Pournin & Liebling; Alonso-Marroquin). Two bodies interact through vertex-edge pairs: a vertex
// of one body closer than r1 + r2 to an edge of the other carries a contact with overlap
// r1 + r2 - distance and normal along the shortest segment. The force of each pair is Eq. 7-11:
//   normal:     f_n = k_n * overlap - m * gamma_n * v_n                       (Eq. 8, 10)
//   tangential: f_t = -k_t * xi - m * gamma_t * v_t, |k_t xi| <= mu_a k_n overlap  (Eq. 9, 11)
// with xi the tangential spring elongation kept per pair (keyed by vertex and edge ids) across
// steps and cut back to the Coulomb limit, and m the reduced mass m1 m2 / (m1 + m2) (the dynamic
// body's mass when the other body is kinematic). The normal force is not clipped at zero, so a
// single contact behaves as the linear damped oscillator behind Eq. 12.
//
// Layout (MuJoCo-like): make_model() validates definitions into a constant Model (shapes, mass
// properties, parameters, flat arrays); make_state() creates the mutable State (poses,
// velocities, neighbour list with the per-pair springs, counters, timings, and an opaque private
// workspace); step(model, state) advances one time step (fixed, or adaptive from the stability
// limit of the current contacts). A sweep copies only State.
// Nothing here allocates in the contact loop, prints, throws on numerical trouble, or keeps
// global state; the result is bitwise deterministic for a given build (-ffp-contract=off, fixed
// evaluation order). Sources, one subsystem each (src/dem/): model.cpp (definitions, mass
// properties), neighbor_list.cpp, contact_geometry.cpp (hot list, distance passes),
// force_law.cpp (Eq. 7-11, sums per body), stability.cpp (explicit limit), integrator.cpp
// (step, guards).
//
// Integration: velocity Verlet in kick-drift-kick form (second order for position-dependent
// forces, exact for constant forces such as free fall). The dashpots use the half-step velocity
// v(t + dt/2), the usual DEM choice (e.g. LAMMPS granular), which makes the damping terms first
// order in dt.
//
// Candidate pairs come from a Verlet neighbour list: every vertex-edge pair within
// r1 + r2 + skin, found through a uniform grid over the region where the two bodies' bounding
// boxes overlap, and rebuilt only when the relative motion of two bodies may have closed the skin
// since the last build. Only the rebuild touches every vertex. Within the list, a hot list of the
// pairs within r1 + r2 + hot_skin is evaluated until the bodies have moved by hot_skin / 2; a step
// costs O(hot pairs), with a full pass over the list when the hot list is refreshed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "frictal/result.hpp"

namespace frictal::dem {

struct Vec2 {
  double x = 0;
  double y = 0;
};

enum class BodyType : std::uint8_t {
  Dynamic,    ///< moved by forces and gravity
  Kinematic,  ///< prescribed motion (KinematicMotion); infinite mass for contacts
};

/// Prescribed motion of a kinematic body: at rest until `start_time`, then a rotation about the
/// fixed `pivot` at constant `angular_velocity` (e.g. the tilting lower block).
struct KinematicMotion {
  Vec2 pivot;                   ///< fixed point of the rotation, world frame (unit: m)
  double angular_velocity = 0;  ///< counter-clockwise positive (unit: rad/s)
  double start_time = 0;        ///< the body is at rest before this time (unit: s)
};

struct BodyDef {
  /// Polygon vertices in world coordinates at t = 0 (unit: m). A simple polygon, convex or not,
  /// either orientation, without a repeated closing point; at least 3 vertices.
  std::vector<double> x;
  std::vector<double> y;
  double radius = 5e-5;  ///< spheroradius r > 0 (unit: m)
  double density = 50;   ///< areal density of the core polygon (unit: kg/m^2)
  BodyType type = BodyType::Dynamic;
  Vec2 velocity;                ///< initial centroid velocity, dynamic bodies (unit: m/s)
  double angular_velocity = 0;  ///< initial angular velocity, dynamic bodies (unit: rad/s)
  KinematicMotion motion;       ///< used by kinematic bodies only
  /// Dynamic bodies: -1 (default) for a free rotation; else the index of a kinematic body whose
  /// angle and angular velocity this body takes at every step (its rotation is held relative to
  /// that body, torques are ignored; its translation stays free). Both start at angle 0.
  int rotation_follows = -1;
};
BodyDef default_body_def();

/// Which touching vertex-edge pairs carry a force (docs/dem.md sec. 1, "Contact rule").
enum class ContactRule : std::uint8_t {
  /// Every vertex-edge pair within r1 + r2 (the paper's SPOLY rule): near a corner a vertex may
  /// feel the same surface through two pairs, with normals the rigid contact does not have.
  Pairs,
  /// One force per contact: a touching pair is dropped when a deeper pair describes the same
  /// contact (features the same or meeting at a vertex on both bodies, contact points within
  /// r1 + r2 of each other); a vertex touching two edges inside (a vertex in a valley, on both
  /// flanks) keeps both. The rigid limit is the same as Pairs; at finite stiffness the force
  /// keeps the normal of the rigid contact.
  Closest,
};

/// The normal force of a touching pair (docs/dem.md sec. 1, "Hertzian contacts").
enum class ContactLaw : std::uint8_t {
  /// Eq. 8: f_n = k_n overlap - m gamma_n v_n (the paper's; stiff enough for rigid blocks).
  Linear,
  /// Hertz: f_n = (4/3) E* sqrt(R) overlap^(3/2) - 2 zeta sqrt(m k) v_n with R the composite radius
  /// of curvature at the contact (Model::curvature_radius; 1/R = 1/R_vertex, plus 1/R of the
  /// edge's end vertex when the closest point is that end) and k = 2 E* sqrt(R overlap) the
  /// tangent stiffness. The dashpot keeps the damping ratio zeta of the linearised contact at
  /// every overlap (the restitution is then independent of the impact speed: Tsuji et al. 1992);
  /// the tangential spring is tangential_ratio x k. The stability limit of the time step uses k.
  Hertz,
};

/// Contact law of Eq. 7-11, shared by every pair. Defaults: paper Table II.
struct ContactParams {
  double normal_stiffness = 6e5;          ///< k_n > 0 (unit: N/m); linear law
  double tangential_stiffness = 6e4;      ///< k_t >= 0 (unit: N/m); linear law
  double normal_damping = 929.5;          ///< gamma_n >= 0 (unit: 1/s); linear law
  double tangential_damping = 4;          ///< gamma_t >= 0 (unit: 1/s)
  double atomic_friction = 0;             ///< mu_a >= 0, Coulomb limit of the tangential spring (unitless)
  ContactRule rule = ContactRule::Pairs;  ///< which touching pairs carry a force
  ContactLaw law = ContactLaw::Linear;    ///< the normal force law
  /// Hertz law: the contact modulus E* > 0, E / (1 - nu^2) of one elastic body on a rigid one or
  /// the composite 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 of two (unit: Pa).
  double contact_modulus = 0;
  /// Hertz law: damping ratio zeta >= 0 of the normal dashpot 2 zeta sqrt(m k) (unitless; 0.2, the
  /// ratio of Table II's gamma_n on a Table I block: restitution 0.53 for the linear law, 0.49
  /// for Hertz, hertz_restitution).
  double damping_ratio = 0.2;
  /// Hertz law: tangential over normal tangent stiffness, >= 0 (unitless): Mindlin's
  /// 2 (1 - nu) / (2 - nu) for two bodies of the same nu, 0.82 at nu = 0.3.
  double tangential_ratio = 2 * (1 - 0.3) / (2 - 0.3);
};
ContactParams default_contact_params();

struct WorldDef {
  Vec2 gravity{0, -9.81};  ///< (unit: m/s^2)
  /// The fixed time step dt > 0, or with `adaptive_time_step` the largest step (unit: s).
  double time_step = 1e-5;
  /// Adaptive time step: after each step the next one is the smallest of `time_step`,
  /// `time_step_safety` x the stability limit of each dynamic body (the smaller of
  /// State::step_limit, from the contacts present now, and the limit of one new contact, which
  /// the step must also resolve: 2 / sqrt(k_n max(1/m, extent^2 / I)), or 2 / gamma_n with
  /// explicit dashpots), and the step in which a body moves skin / 4.
  /// It follows the run: it shrinks when contacts pile up and grows again when they go.
  /// Default off: a fixed step (State::time == steps x time_step exactly).
  bool adaptive_time_step = false;
  /// Fraction of the stability limit taken by the adaptive step, in (0, 1] (unitless).
  double time_step_safety = 0.5;
  /// Integrate the normal dashpots (gamma_n) implicitly: each kick of length h solves, per dynamic
  /// body, (M + 2 h gamma_n G_m) dv = h (F + m g) with G_m = sum over its contacts of
  /// m_red J J^T, J = (n_x, n_y, r x n), instead of dv = h M^-1 (F + m g). The damping of many
  /// contacts acting together (rate ~ contacts x gamma_n) then no longer limits the step; it widens
  /// the limit instead (State::step_limit). First order in dt like the
  /// explicit dashpots; the tangential dashpots stay explicit (gamma_t << gamma_n). Default off.
  bool implicit_damping = false;
  double skin = 5e-5;  ///< Verlet skin added to r1 + r2 for the neighbour list (unit: m)
  /// Skin of the hot list inside the neighbour list: only pairs within r1 + r2 + hot_skin at the
  /// last full pass are evaluated until the bodies have moved by hot_skin / 2 (speed only; the
  /// results do not depend on it) (unit: m).
  double hot_skin = 5e-6;
  ContactParams contact;
  /// Stability guard: stop with an error when an overlap exceeds this fraction of r1 + r2
  /// (cores about to interpenetrate) (unitless).
  double max_overlap_ratio = 1.0;
  /// Stability guard: stop when a dynamic body's speed (centroid speed + |omega| * its size)
  /// exceeds this (unit: m/s).
  double max_speed = 100;
  /// Stability guard: stop when dt has exceeded a body's explicit stability limit
  /// (State::step_limit) in more than this many steps in total. Isolated steps beyond it while the
  /// contact count peaks are harmless (K3 at dt = 1e-5 s: 316 such steps out of 2.1 M, same
  /// friction angle as at dt/2 to 1e-4 degree); a run that lives beyond it is not (K3 at 2e-5 s:
  /// 31 370 steps, wrong answer). Counted in State::steps_beyond_limit; with
  /// `adaptive_time_step` only counted (the next step is below the limit again) (unitless).
  int max_steps_beyond_limit = 1000;
  bool timings = true;  ///< time each stage into State::timings (costs ~4 clock reads/step)
};
WorldDef default_world_def();

/// Constant part of a simulation: shapes, mass properties, parameters. Flat arrays indexed by
/// body and global vertex ids; vertices are stored counter-clockwise relative to the centroid
/// at the initial orientation.
struct Model {
  WorldDef def;
  std::vector<std::uint32_t> vertex_begin;  ///< body b owns vertices [begin[b], begin[b+1])
  std::vector<double> local_x;              ///< vertex x relative to the centroid (unit: m)
  std::vector<double> local_y;              ///< (unit: m)
  std::vector<std::uint32_t> vertex_body;   ///< owning body of each global vertex
  std::vector<std::uint32_t> next_vertex;   ///< edge of vertex i runs from i to next_vertex[i]
  /// 1 where the core polygon turns left (or goes straight) at vertex i: a convex corner, seen
  /// from outside the (counter-clockwise) polygon; 0 at a concave one
  std::vector<unsigned char> convex_vertex;
  std::vector<double> edge_inv_length2;  ///< 1 / |edge i|^2, invariant under rigid motion (unit: 1/m^2)
  /// Hertz law only (empty for the linear law): radius of curvature of the rounded body at vertex
  /// i: the radius of the circle through it and its two neighbours (the discrete curvature of
  /// the core polygon), at least the body's spheroradius r (the swept disk rounds every corner
  /// to r, so no contact there is sharper) and at most the body's extent (a straight or nearly
  /// straight run, or a concave corner, acts as a sphere of the body's size: its flank pairs
  /// carry the contact) (unit: m).
  std::vector<double> curvature_radius;
  /// Hertz law: (4/3) E* sqrt(min over the body's vertices of curvature_radius): the softest
  /// contact coefficient of each body (unit: N/m^1.5); and the stiffest, with the largest radius.
  std::vector<double> hertz_coeff_min, hertz_coeff_max;
  std::vector<double> radius;   ///< spheroradius per body (unit: m)
  std::vector<double> mass;     ///< (unit: kg)
  std::vector<double> inertia;  ///< about the centroid (unit: kg m^2)
  std::vector<double> area;     ///< core polygon area (unit: m^2)
  std::vector<double> extent;   ///< max vertex distance from the centroid (unit: m)
  std::vector<BodyType> type;
  std::vector<KinematicMotion> motion;
  std::vector<int> rotation_follows;             ///< BodyDef::rotation_follows per body
  std::vector<Vec2> initial_position;            ///< centroid at t = 0 (unit: m)
  std::vector<Vec2> initial_velocity;            ///< (unit: m/s)
  std::vector<double> initial_angular_velocity;  ///< (unit: rad/s)
  std::size_t body_count() const { return mass.size(); }
  std::size_t vertex_count(std::size_t b) const { return vertex_begin[b + 1] - vertex_begin[b]; }
};

/// One candidate pair of the neighbour list: vertex `vertex` of body `vbody` against the edge
/// (edge0, edge1) of body `ebody`. Global vertex ids. `elongation` is the tangential spring xi,
/// the one piece of contact history (carried across list rebuilds by `key`).
struct NeighborPair {
  std::uint64_t key = 0;  ///< (vertex << 32) | edge0, sorted ascending
  std::uint32_t vertex = 0;
  std::uint32_t edge0 = 0;
  std::uint32_t edge1 = 0;
  std::uint32_t vbody = 0;
  std::uint32_t ebody = 0;
  double reduced_mass = 0;  ///< m1 m2 / (m1 + m2), or the dynamic body's mass (unit: kg)
  double elongation = 0;    ///< xi (unit: m)
  double overlap = 0;       ///< last overlap, <= 0 when apart (unit: m)
};

/// Cumulative wall time per stage of step() (unit: s) and counters.
struct StepTimings {
  double neighbor_list = 0;  ///< rebuild test + rebuilds
  double contacts = 0;       ///< pair forces
  double integration = 0;    ///< kicks, drift, kinematic motion, guards
  std::uint64_t list_builds = 0;
  std::uint64_t pairs_visited = 0;    ///< sum over steps of the list length
  std::uint64_t pairs_evaluated = 0;  ///< sum over steps of the pairs actually evaluated (hot list or full list)
  std::uint64_t hot_refreshes = 0;    ///< full passes over the list that rebuilt the hot list
  std::uint64_t split_steps = 0;      ///< steps whose contact passes were split over threads (set_thread_count)
};

namespace detail {
struct Workspace;  // src/dem/workspace.hpp
}

/// Private working memory of step(): cached rotations, the poses of the last list build and of
/// the last full contact pass, the hot list, and the scratch buffers of the list builder and the
/// contact passes (src/dem/workspace.hpp). Opaque; owned by its State and copied with it (a copy
/// continues bitwise like the original).
class StateWorkspace {
 public:
  StateWorkspace();
  ~StateWorkspace();
  StateWorkspace(const StateWorkspace& other);
  StateWorkspace& operator=(const StateWorkspace& other);
  StateWorkspace(StateWorkspace&& other) noexcept;
  StateWorkspace& operator=(StateWorkspace&& other) noexcept;
  detail::Workspace& get() { return *p_; }
  const detail::Workspace& get() const { return *p_; }

 private:
  std::unique_ptr<detail::Workspace> p_;
};

/// Mutable part of a simulation.
struct State {
  double time = 0;  ///< (unit: s)
  std::uint64_t steps = 0;
  /// Step that the next call of step() takes: WorldDef::time_step when fixed, else chosen after
  /// each step (WorldDef::adaptive_time_step) (unit: s).
  double time_step = 0;
  std::vector<Vec2> position;            ///< centroid (unit: m)
  std::vector<double> angle;             ///< rotation from the initial orientation (unit: rad)
  std::vector<Vec2> velocity;            ///< centroid velocity (unit: m/s)
  std::vector<double> angular_velocity;  ///< (unit: rad/s)
  std::vector<Vec2> force;               ///< contact force on each body at `time`, gravity excluded (unit: N)
  std::vector<double> torque;            ///< contact torque about the centroid (unit: N m)
  std::vector<NeighborPair> pairs;       ///< neighbour list with the per-pair springs
  int contact_count = 0;                 ///< pairs with positive overlap at `time`
  std::vector<int> body_contacts;        ///< pairs with positive overlap per body at `time`
  /// Explicit stability limit of each dynamic body at `time` from its contact modes: with
  /// G = sum over its contacts of J J^T, J = (n_x, n_y, r x n), and M = diag(m, m, I),
  /// min(2 / sqrt(lambda_max(k_n M^-1/2 G M^-1/2)), 2 / lambda_max(gamma_n M^-1/2 G_m M^-1/2))
  /// (G_m weighted by the reduced masses); tangential terms (k_t = k_n/10, gamma_t << gamma_n)
  /// are neglected. With WorldDef::implicit_damping: (c + sqrt(c^2 + 4 omega^2)) / omega^2, the
  /// limit of the implicit-dashpot scheme, with c = gamma_n m_red,min omega^2 / k_n (>= 2 / omega;
  /// damping now widens the limit). Infinite without contacts (unit: s).
  std::vector<double> step_limit;
  std::uint64_t steps_beyond_limit = 0;  ///< steps with dt above some body's stability limit (warnings)
  int consecutive_beyond_limit = 0;      ///< current run of such steps
  double max_overlap = 0;                ///< largest overlap at `time` (unit: m)
  double elastic_energy = 0;             ///< sum of k_n overlap^2/2 + k_t xi^2/2 at `time` (unit: J)
  StepTimings timings;
  StateWorkspace workspace;  ///< private (src/dem/workspace.hpp)
};

/// Validates the definitions and computes mass properties. Errors name the body and field.
Result<Model> make_model(const WorldDef& world, const std::vector<BodyDef>& bodies);
/// Initial state at t = 0 with the neighbour list built and the contact forces evaluated.
State make_state(const Model& model);
/// Advances one time step. On a stability-guard failure the state is left at the failing step
/// and the error gives the time, the cause and a suggested time step.
Status step(const Model& model, State& state);
/// Splits the contact passes of each step() of `state` over `threads` threads (>= 1; 1, the
/// default: none). A team of threads - 1 workers, owned by the state (not copied with it), starts
/// at the first step that uses it and is joined with the state. A step is split only when its hot
/// list holds at least `min_hot_pairs_per_thread` (default 64: a share must outweigh the team's
/// start and join, ~1 us) pairs per thread used and no full pass over the list is due. With
/// `tune` (default) the steps that can be split also time their contact passes now and then,
/// serial and split (64 steps each, twice, every 16384 such steps, backing off to every ~10^6
/// while it does not pay), and split only while that is clearly (5 %, both times) faster: on a
/// loaded machine, where a split step waits for a descheduled worker, they stay serial. Results
/// do not depend on `threads`, bit for bit: each thread takes a fixed contiguous share of the hot
/// list (its exact tests and forces), and the sums run on the calling thread in list order
/// (docs/dem.md sec. 7).
void set_thread_count(State& state, unsigned threads, unsigned min_hot_pairs_per_thread = 64, bool tune = true);
/// The thread count of set_thread_count (1 if never set; a copied State keeps it).
unsigned thread_count(const State& state);
/// Advances `steps` steps (stops at the first error).
Status advance(const Model& model, State& state, std::uint64_t steps);

/// One touching vertex-edge pair and its force (Eq. 7-11) at the state's time.
struct ContactForce {
  std::uint32_t vertex_body = 0, edge_body = 0;
  Vec2 point;               ///< contact point, the middle of the overlap (unit: m)
  Vec2 normal;              ///< unit normal, from the edge towards the vertex
  double overlap = 0;       ///< (unit: m)
  double normal_force = 0;  ///< f_n (linear or Hertz law), on the vertex body along `normal` (unit: N)
  /// Hertz law: the composite radius of curvature R of the pair; 0 for the linear law (unit: m).
  double curvature_radius = 0;
  double tangential_force = 0;  ///< f_t on the vertex body along t = normal turned by +90 deg (unit: N)
};
/// The touching pairs of `state` with their forces, recomputed from the poses, velocities and
/// springs (the same formulas as step(); sums equal State::force up to rounding). For output.
std::vector<ContactForce> contact_forces(const Model& model, const State& state);

/// World position of global vertex `v` (unit: m).
Vec2 world_vertex(const Model& model, const State& state, std::uint32_t v);
/// Translational + rotational kinetic energy of body b (unit: J).
double kinetic_energy(const Model& model, const State& state, std::size_t b);
/// Worst-case explicit stability limit of body b's time step with `contacts` contacts all acting
/// in the same direction (unit: s): min(2 / (contacts gamma_n), 2 / omega) with
/// omega^2 = contacts k_n max(1/m, extent^2/I). The guard uses the sharper State::step_limit. The dashpot term is what
/// binds for many contacts: 150 contacts with gamma_n = 929.5 1/s need dt < 1.4e-5 s. Infinite for 0 contacts.
double stability_limit(const Model& model, std::size_t b, int contacts);
/// Half the smallest stability_limit over the dynamic bodies (unit: s).
double suggested_time_step(const Model& model, int contacts);

/// Hertz law: the tangent stiffness of a contact of `body` when it carries its weight alone on
/// its softest vertex (hertz_coeff_min; gravity from the model), or at the overlap
/// `overlap` if larger, on its stiffest vertex: the stiffness the time step and the cost estimate
/// assume for one contact (unit: N/m). The linear law: k_n.
double contact_stiffness(const Model& model, std::size_t body, double overlap = 0);
/// Hertz: overlap of a sphere of radius R (m) pressed by force W (N) on a flat of contact modulus
/// E* (Pa): (3 W / (4 E* sqrt(R)))^(2/3) (unit: m).
double hertz_overlap(double force, double contact_modulus, double radius);
/// Restitution of one Hertz contact with the dashpot of ContactLaw::Hertz at damping ratio zeta
/// (unitless, >= 0): independent of the mass, modulus, radius and impact speed; from the
/// dimensionless equation of motion integrated to the separation (unitless).
double hertz_restitution(double zeta);
/// The damping ratio zeta that gives restitution eps in (0, 1] to one Hertz contact (unitless).
Result<double> hertz_damping_ratio(double eps);

/// Eq. 12 solved for gamma_n: damping that gives restitution `eps` in (0, 1] for one contact of
/// stiffness k_n (N/m) on mass m (kg). Result in 1/s.
Result<double> damping_from_restitution(double eps, double k_n, double m);
/// Eq. 12: restitution of one contact (gamma_n in 1/s, k_n in N/m, m in kg); 0 if overdamped.
double restitution_from_damping(double gamma_n, double k_n, double m);

}  // namespace frictal::dem
