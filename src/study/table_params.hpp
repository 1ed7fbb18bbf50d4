// Private: a task's parameters read through a library settings table (frictal/settings.hpp):
// the TOML keys are the table's names, angles in degrees, converted and checked by the table.
#pragma once

#include <algorithm>
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

/// Refuses a parameter that is neither a field of `tables` nor one of `extra`, naming the nearest
/// known name (a renamed or mistyped key would otherwise be silently ignored).
inline Status only_known_parameters(const Params& p, const std::vector<const std::vector<Field>*>& tables,
                                    const std::vector<std::string>& extra, const std::string& kind) {
  std::vector<std::string> known = extra;
  for (const auto* t : tables)
    for (const Field& f : *t) known.push_back(f.name);
  for (const auto& [name, value] : p) {
    if (std::find(known.begin(), known.end(), name) != known.end()) continue;
    std::string hint;
    if (std::string n = nearest_word(name, known); !n.empty()) hint = "; did you mean '" + n + "'?";
    return make_error("parameter '" + name + "' is not a parameter of task kind '" + kind + "'" + hint +
                      " (names: docs/settings.md, docs/studies.md)");
  }
  return Ok{};
}

}  // namespace frictal::study
