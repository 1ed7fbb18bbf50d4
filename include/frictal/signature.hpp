// frictal — the signature function theta(x_ofs) (paper Sec. II A, Eq. 1-3) and the friction
// prediction (Eq. 6 and 18).
//
// Geometry: `lower` is the lower block's face f(x) as measured (material below). `upper` is the
// upper block's face g(y) already rotated into place (material above, same frame direction), i.e.
// rotate180() of a measured surface. At offset s the upper block's reference is lifted by
//   h(s) = max_{x in overlap} [ f(x) - g(x - s) ]
// so that the two touch; contacts are the maximisers. h is piecewise linear and its maximum is
// attained at a vertex of f or of g, so evaluation needs only vertices; it changes its linear
// piece only at "events" (offsets where a vertex of f is aligned with a vertex of g), between
// which h is convex. Hence the exact extreme slopes are the one-sided slopes at events.
#pragma once

#include <cstdint>
#include <vector>

#include "frictal/geometry.hpp"
#include "frictal/outputs.hpp"
#include "frictal/settings.hpp"
#include "frictal/stats.hpp"

namespace frictal {

enum class SlopeMethod {
  Exact,   ///< polyline slopes with the paper's contact rules (edge-edge, vertex-edge, vertex-vertex)
  Spline,  ///< natural cubic-spline slopes of both surfaces at the contact, averaged (Sec. V B)
};

enum class ContactType : std::uint8_t {
  VertexEdge,    ///< a vertex of the lower surface on an edge of the upper: the upper edge's slope
  EdgeVertex,    ///< a vertex of the upper surface on an edge of the lower: the lower edge's slope
  VertexVertex,  ///< vertices of both: mean of the two vertex slopes (vertex = mean of its edges)
  EdgeEdge,      ///< collinear overlapping edges: their common slope (x is the segment's middle)
};

/// "vertex-edge", "edge-vertex", "vertex-vertex" or "edge-edge" (CSV/JSON/Python output).
const char* contact_type_name(ContactType t);

struct Contact {
  double x = 0;      ///< contact abscissa in the lower block's frame (unit: m)
  double z = 0;      ///< contact height on the lower surface (unit: m)
  double slope = 0;  ///< contact slope angle by the type's rule (unit: rad)
  ContactType type = ContactType::VertexEdge;
};

struct SignatureOptions {
  SlopeMethod slopes = SlopeMethod::Exact;
  /// 0: exact — every event offset in the range. If there are more than max_events (grids
  /// that do not align, as measured data often have), offsets are sampled at the finer vertex
  /// spacing instead (SignatureResult::exact = false), or an error if require_exact is set.
  /// N > 0: N equally spaced offsets over [offset_min, offset_max] (end included), each still
  /// evaluated exactly, with exact one-sided slopes at each; on aligned grids where N is at least
  /// a quarter of the exact events, every event instead (SignatureResult::grid_replaced).
  std::size_t offsets = 0;
  /// offsets = N: evaluate exactly that grid even where every event would cost less (a grid
  /// shared with another tool; tests of the off-lattice search).
  bool keep_grid = false;
  std::size_t max_events = 20'000'000;
  bool require_exact = false;
  /// Aligned grids: bound the search with each block's tilted upper line (its chord raised over
  /// its points) as well as its maximum, so that profiles with long-wavelength trends (many
  /// scales) cost no more per offset than others. Speed only: the result is identical either
  /// way (tests and benchmarks compare the two).
  bool tilted_bounds = true;
  /// Offset range (unit: m). If offset_max <= offset_min: one period of the lower profile if it
  /// is periodic, else [0, half the shorter block length].
  double offset_min = 0;
  double offset_max = 0;
  /// Worker threads (0 = hardware concurrency). The result does not depend on this.
  unsigned threads = 0;
  /// Keep every contact of every offset (memory: a few per offset).
  bool keep_contacts = true;
  /// Contacts are candidates within tolerance * (height range of both surfaces) of the maximum.
  double tolerance = 1e-9;
  /// Bins of the contact-slope PDF.
  int bins = 90;
  /// Spheroradius r of both blocks (unit: m), as in the DEM's spheropolygons: each face is a
  /// polygon core swept by a disk of radius r. 0: rigid polylines (the paper's signature). r > 0:
  /// the lift is that of the upper core against the lower core dilated by a disk of radius 2r,
  /// i.e. the rigid lift h0 dilated: h(s) = max over s' of h0(s') + sqrt((2r)^2 - (s - s')^2).
  /// Offset lines of h0's pieces and arcs at its ridges form h; contacts on an arc have the
  /// arc's tangent slope, so theta varies continuously there. Breakpoints of h (changes of the
  /// active primitive) are exact and theta_max is exact (analytic on arcs); `offsets` = 0 lists
  /// the breakpoints plus up to 8 points inside each arc (one per degree it turns). Contacts are
  /// the touching points of the two rounded faces (on the lower face's rounded outline), typed by
  /// the rigid contact they round.
  /// Spline slopes are not available with r > 0.
  double spheroradius = 0;
};

/// The signature's settings table (settings.hpp; src/signature/signature_settings.cpp): the
/// SignatureOptions a user states (slopes, offsets, keep_grid, exact = require_exact, offset_range
/// = [offset_min, offset_max] as the word "MIN MAX" of lengths, bins, spheroradius), each with its
/// SI unit, range and help: the options of `frictal signature`, the keywords of Python's
/// signature(), a table of `frictal settings`. Defaults are SignatureOptions' initialisers.
const std::vector<Field>& signature_settings();
/// `base` with the values `si` of signature_settings() applied (SI, checked against the table);
/// errors name the field and its range. Also refused: spheroradius > 0 with spline slopes.
Result<SignatureOptions> make_signature_options(const ValueSet& si, SignatureOptions base = {});

struct SignatureResult {
  std::vector<double> offset;                ///< evaluated offsets s (unit: m)
  std::vector<double> lift;                  ///< h(s), the upper block reference height (unit: m)
  std::vector<double> theta;                 ///< Eq. 3: max contact slope at s (unit: rad)
  std::vector<double> theta_min;             ///< min contact slope at s (unit: rad)
  std::vector<double> theta_left;            ///< slope of h just before s, atan(h'(s-)) (unit: rad)
  std::vector<double> theta_right;           ///< slope of h just after s, atan(h'(s+)) (unit: rad)
  std::vector<std::uint32_t> contact_begin;  ///< offsets' contacts: [begin[i], begin[i+1])
  std::vector<Contact> contacts;

  double theta_max_forward = 0;   ///< max theta: resists sliding towards +x (unit: rad)
  double theta_max_backward = 0;  ///< max of -theta: resists sliding towards -x (unit: rad)
  double offset_at_forward = 0;   ///< where theta_max_forward is reached (unit: m)
  double offset_at_backward = 0;  ///< (unit: m)
  /// Contact-slope distribution, one value per offset (weighted by the offset length it
  /// represents when offsets are not equally spaced).
  std::vector<double> slope_samples;  ///< (unit: rad)
  std::vector<double> slope_weights;  ///< (unit: m)
  double contact_slope_mean = 0;      ///< (unit: rad)
  double contact_slope_std = 0;       ///< sigma of Eq. 18 (unit: rad)
  Histogram contact_slope_pdf;        ///< (unit: 1/rad over rad)
  bool exact = true;                  ///< true if every event offset was evaluated
  /// `offsets` = N asked for at least a quarter as many offsets as the exact path has events on
  /// aligned grids, where an off-lattice offset costs about 3.3 lattice events: every event was
  /// evaluated instead (exact, denser and cheaper than the grid).
  bool grid_replaced = false;
  std::size_t events = 0;   ///< number of distinct event offsets in the range (r > 0: breakpoints of h)
  double spheroradius = 0;  ///< the spheroradius r used (unit: m)
};

/// Computes the signature of `lower` against `upper` (already rotated, see above).
Result<SignatureResult> signature(const Profile& lower, const Profile& upper, const SignatureOptions& options = {});
/// The same, taking both profiles over: their storage becomes the evaluator's (no copy; at
/// 10^7 points each copy is 160 MB). Both are left empty (non-periodic) or unchanged (periodic).
Result<SignatureResult> signature(Profile&& lower, Profile&& upper, const SignatureOptions& options = {});

/// Signature of a surface against itself turned over: upper = rotate180(surface).
Result<SignatureResult> self_signature(const Profile& surface, const SignatureOptions& options = {});

/// The natural cubic spline through a profile's points: the curve whose slopes SlopeMethod::Spline
/// takes at the contacts (Sec. V B, Fig. 13), sampled.
struct SplineSamples {
  std::vector<double> x;      ///< abscissae (unit: m)
  std::vector<double> z;      ///< the spline's height (unit: m)
  std::vector<double> slope;  ///< its slope dz/dx (unit: 1)
};
/// `per_interval` evenly spaced samples in each interval between two points (the interval's start
/// included), and the last point. Error: fewer than 2 points, x not strictly increasing, or
/// per_interval outside 1..10000.
Result<SplineSamples> sample_spline(const Profile& profile, int per_interval);

/// Plain reference evaluation of h(s) at one offset: scans every vertex of both profiles.
/// O(N + M); used by tests and benchmarks as the second method.
double lift_direct(const Profile& lower, const Profile& upper, double offset);

/// Friction prediction (Eq. 6, 18).
struct FrictionPrediction {
  double atomic_friction = 0;           ///< mu_a (unitless)
  double atomic_angle = 0;              ///< theta_a = atan(mu_a) (unit: rad)
  double theta_max = 0;                 ///< (unit: rad)
  double friction_angle = 0;            ///< phi = theta_a + theta_max, capped at pi/2 (unit: rad)
  double friction_coefficient = 0;      ///< mu = tan(phi); +inf when phi reaches pi/2 (unitless)
  double friction_angle_low = 0;        ///< Eq. 18 lower end: max(0, theta_a + theta_max - sigma) (unit: rad)
  double friction_coefficient_low = 0;  ///< tan of the above (unitless)
  bool low_clamped = false;  ///< theta_a + theta_max - sigma was below 0: the low end is 0 (warning eq18-low-clamped)
};
/// mu_a >= 0; theta_max and sigma in radians.
Result<FrictionPrediction> predict_friction(double atomic_friction, double theta_max, double sigma);

/// Every contact at every offset of a signature (SignatureOptions::keep_contacts), one element
/// per contact: the offset (unit: m), where it is in the lower block's frame (x, z; unit: m), its
/// slope (unit: rad) and type (contact_type_name). Table "contacts".
struct ContactList {
  std::vector<double> offset, x, z, slope;
  std::vector<std::string> type;
};
/// The contacts that `r` kept, in offset order (empty without keep_contacts).
ContactList contact_list(const SignatureResult& r);
/// The output table of a ContactList (src/signature/signature_columns.cpp).
const Columns<ContactList>& contact_list_columns();

/// The signature's output table (frictal/outputs.hpp): `frictal signature --json` and Python's
/// signature() dict (src/signature/signature_columns.cpp).
const Columns<SignatureResult>& signature_columns();
/// The rigid bound and the Eq. 18 low end (forward): `signature --json`, Python predict_friction().
const Columns<FrictionPrediction>& friction_columns();
/// The backward rigid bound: `signature --json` (upper_bound_friction_angle_backward_deg, ...).
const Columns<FrictionPrediction>& friction_backward_columns();

}  // namespace frictal
