// Private: evaluation of the rigid lift h0(s) of two profiles at arbitrary offsets, with the same
// prepared faces and contact rules as signature() (used by the spheropolygon signature).
#pragma once

#include <memory>

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

/// The signature of spheropolygon blocks (o.spheroradius > 0), see signature.hpp.
Result<SignatureResult> sphero_signature(const Profile& lower, const Profile& upper, const SignatureOptions& o);

}  // namespace frictal::detail
