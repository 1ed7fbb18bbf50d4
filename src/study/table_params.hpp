// Private: a task's parameters read through a library settings table (frictal/settings.hpp):
// the TOML keys are the table's names, angles in degrees, converted and checked by the table.
#pragma once

#include <string>
#include <vector>

#include "frictal/settings.hpp"
#include "frictal/study.hpp"

namespace frictal::study {

/// The parameters of `p` that `fields` names, converted to SI (degrees -> radians through the
/// field's unit) and checked against the field's type and range; errors name the parameter.
inline Result<ValueSet> table_values(const std::vector<Field>& fields, const Params& p) {
  ValueSet out;
  for (const Field& f : fields) {
    auto it = p.find(f.name);
    if (it == p.end()) continue;
    const FieldValue text = std::visit([](const auto& v) { return FieldValue{v}; }, it->second);
    auto si = si_from_text(f, text, "parameter '" + f.name + "'");
    if (!si) return si.error();
    out[f.name] = *si;
  }
  return out;
}

}  // namespace frictal::study
