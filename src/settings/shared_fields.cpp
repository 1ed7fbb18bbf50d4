// The quantities that several settings tables share (settings.hpp, shared_field): declared once
// here, so that `--atomic-friction`, `--runaway-distance` and `--period` read the same in the
// tilt test, the 3D tilt test and the prediction, `--spheroradius` the same in the tilt test and
// the signature, and `--direction` and `--in-place` the same in
// the prediction and the areal signature (each table fills the default from its struct).
#include <limits>

#include "frictal/settings.hpp"
#include "settings/binding.hpp"

namespace frictal {
namespace {

using settings_detail::F;
using settings_detail::Lo;

constexpr double kInf = std::numeric_limits<double>::infinity();

const std::vector<Field>& shared_fields() {
  static const std::vector<Field> fields = {
      F("atomic_friction", "", 0, Lo::Closed, kInf, "Atomic (Coulomb) friction coefficient mu_a"),
      F("runaway_distance", "m", 0, Lo::Open, kInf, "Sliding for good: growth of the displacement since the last stick",
        false,
        "predict and areal-tilt: 12.5 slope correlation lengths of the lower surface along the direction "
        "(periodic profiles: one period); tilt: the surface's wavelength (generated), files: predict's, the "
        "stated test's"),
      F("period", "m", -kInf, Lo::Closed, kInf,
        "Period of both surfaces (<= 0: not periodic; the offsets then span half the length)", false,
        "the surface's (generated), none (files)"),
      F("spheroradius", "m", 0, Lo::Open, kInf, "Spheroradius r of both blocks", false,
        "none: rigid profiles (signature); 5e-05 (tilt)"),
      F("direction", "rad", -kInf, Lo::Open, kInf,
        "Sliding direction, from +x towards +y (profiles: along +x or -x only)", true),
      [] {
        Field f = F("in_place", "", 0, Lo::Closed, 1,
                    "The upper surface is the upper face already in place in the lower one's coordinates (not "
                    "turned over); a drop's offsets count from that place. Maps only, except in contact");
        f.type = FieldType::Boolean;
        return f;
      }(),
  };
  return fields;
}

}  // namespace

const Field* shared_field(std::string_view name) { return find_field(shared_fields(), name); }

}  // namespace frictal
