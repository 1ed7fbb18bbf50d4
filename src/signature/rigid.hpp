// Private: evaluation of the rigid lift h0(s) of two profiles at arbitrary offsets, with the same
// prepared faces and contact rules as signature() (used by the spheropolygon signature).
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include "frictal/signature.hpp"

namespace frictal::detail {

class RigidLift {
 public:
  struct Point {
    double lift = 0;                             ///< h0(s), the upper reference height (unit: m)
    double left = 0;                             ///< atan(h0'(s-)); +pi/2 when h0 jumps down to the left (unit: rad)
    double right = 0;                            ///< atan(h0'(s+)); -pi/2 when h0 jumps down to the right (unit: rad)
    double contact_x = 0;                        ///< abscissa of the leftmost contact in the lower frame (unit: m)
    ContactType type = ContactType::VertexEdge;  ///< the leftmost contact's type
  };
  /// Prepares `lower` against `upper` (already rotated; the frame puts offset 0 at the left ends
  /// aligned, as signature() does). Options used: tolerance.
  static Result<RigidLift> make(const Profile& lower, const Profile& upper, const SignatureOptions& o);
  /// Exact h0 and one-sided slopes at offset s (unit: m); lift is NaN where the blocks do not overlap.
  Point at(double s) const;
  /// Height of the lower surface at abscissa x of the lower frame (unit: m).
  double lower_height(double x) const;

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;
};

/// The lift at offsets beyond a signature's own (signature_with_lift).
struct LiftPoints {
  std::vector<double> offset;  ///< increasing (unit: m)
  std::vector<double> lift;    ///< h(s) (unit: m)
  std::vector<double> left;    ///< atan(h'(s-)) (unit: rad)
  std::vector<double> right;   ///< atan(h'(s+)) (unit: rad)
};
/// The offsets W that signature() lists over a wider range [lo, hi]: those the signature R does
/// not hold, evaluated, and the indices of R's offsets that are not in W (its range ends where
/// they are no events of the wider range). W = (R without `dropped`) merged with `points`.
struct LiftExtension {
  LiftPoints points;
  std::vector<std::size_t> dropped;
  bool exact = true;            ///< W holds every event of [lo, hi] (else a sampled grid)
  std::size_t events = 0;       ///< |W|
  std::vector<double> skipped;  ///< offsets of W left out by a LiftPruneRequest (increasing)
};
/// Stretches of a wider range whose lift cannot change the hold analysis: beyond
/// `fwd_from` a stretch whose forward slopes h' are all at most `fwd_max`, before `bwd_to` one
/// whose backward slopes -h' are all at most `bwd_max`. Such a stretch holds no record of any
/// chain that gets there (hold.cpp, LiftPruneRequest's use) and lies beyond every inertial window.
struct LiftPrune {
  double fwd_from = std::numeric_limits<double>::infinity(), fwd_max = 0;
  double bwd_to = -std::numeric_limits<double>::infinity(), bwd_max = 0;
};
/// Exact mode on an aligned lattice only: the offsets to evaluate inside [inner_lo, inner_hi]
/// are evaluated first; decide(offsets, lifts, count, dropped) then gives the stretches
/// (LiftPrune) from those points (increasing offsets) and the signature's points. Outside, a block of 65 consecutive
/// lattice offsets k0 .. k0 + 64 (k0 a multiple of 64; the whole block beyond fwd_from or before bwd_to) whose slopes
/// are bounded below the stretch's limit, by the steepest edge of both faces at every candidate contact of its offsets
/// (the batch frontier of the first one's contact), is evaluated at its two ends only: the first end's right slope is
/// NaN (the lift curve joins the two by a chord, no steeper than the lift between them), the 63 offsets between are
/// listed in `skipped`.
struct LiftPruneRequest {
  double inner_lo = 0, inner_hi = 0;
  std::function<LiftPrune(const double* offset, const double* lift, std::size_t count,
                          const std::vector<std::size_t>& dropped)>
      decide;
};
/// extend(lo, hi, have, prune): as above; offsets listed in `have` (increasing; may be null), or
/// within xtol of one, are neither evaluated nor returned (they were, by an earlier call); `prune` (may be null) leaves
/// out the offsets that cannot matter, in LiftExtension::skipped.
using LiftExtender = std::function<Result<LiftExtension>(double lo, double hi, const std::vector<double>* have,
                                                         const LiftPruneRequest* prune)>;
using WithLift = std::function<Status(const SignatureResult& partial, const LiftExtender& extend)>;
/// signature(), calling `with_lift` once the offsets are evaluated (R holds offset, lift, theta,
/// theta_min, theta_left/right and contacts, not yet the extremes and the distribution) while
/// the prepared faces still live, so that `extend` evaluates the lift over wider ranges with
/// them. Rigid faces only (spheroradius 0). take_lower/take_upper as signature(Profile&&).
/// `after_faces` (if given) is called next, with R as with_lift saw it, once the faces are let go
/// and before the extremes and the slope distribution are computed (their memory is not yet
/// taken).
using AfterFaces = std::function<Status(const SignatureResult& partial)>;
Result<SignatureResult> signature_with_lift(const Profile& lower, const Profile& upper, const SignatureOptions& o,
                                            Profile* take_lower, Profile* take_upper, const WithLift& with_lift,
                                            const AfterFaces& after_faces = {});

/// The signature of spheropolygon blocks (o.spheroradius > 0), see signature.hpp.
Result<SignatureResult> sphero_signature(const Profile& lower, const Profile& upper, const SignatureOptions& o);

}  // namespace frictal::detail
