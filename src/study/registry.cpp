// The task-kind registry and the one list of this build's kinds.
//
// Each kind is one unit (one source file defining `TaskKind NAME_kind()`: compute function,
// outputs, report section, plot views). Adding a kind touches that file and the list below
// (docs/studies.md, "How to add a task kind"); nothing else names a kind.
#include <cmath>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "frictal/areal_tilt.hpp"
#include "frictal/study.hpp"

namespace frictal::study {

// ---------------------------------------------------------------- the list

TaskKind koch_signature_kind();      // kind_koch_signature.cpp
TaskKind wm_pair_statistics_kind();  // kind_wm_pair_statistics.cpp
TaskKind tilt_kind();                // kind_tilt.cpp
TaskKind divider_kind();             // kind_divider.cpp
TaskKind wm_tilt_kind();             // kind_wm_tilt.cpp
TaskKind areal_tilt_kind();          // kind_areal_tilt.cpp (needs MuJoCo)

TaskRegistry default_registry() {
  TaskRegistry r;
  for (TaskKind (*make)() : {koch_signature_kind, wm_pair_statistics_kind, tilt_kind, divider_kind, wm_tilt_kind})
    r.add(make());
  if (mujoco_available())
    r.add(areal_tilt_kind());
  else
    r.add_unavailable("areal-tilt", "it needs MuJoCo: install libmujoco-dev and rebuild");
  return r;
}

// ---------------------------------------------------------------- the registry

void TaskRegistry::add(TaskKind kind) {
  unavailable_.erase(kind.name);
  kinds_[kind.name] = std::move(kind);
}
void TaskRegistry::add_unavailable(std::string name, std::string reason, int version) {
  if (kinds_.count(name)) return;
  unavailable_version_[name] = version;
  unavailable_[std::move(name)] = std::move(reason);
}
int TaskRegistry::version(const std::string& name) const {
  if (const TaskKind* k = find(name)) return k->version;
  auto it = unavailable_version_.find(name);
  return it == unavailable_version_.end() ? 0 : it->second;
}
const TaskKind* TaskRegistry::find(const std::string& name) const {
  auto it = kinds_.find(name);
  return it == kinds_.end() ? nullptr : &it->second;
}
std::string TaskRegistry::unavailable_reason(const std::string& name) const {
  auto it = unavailable_.find(name);
  if (it == unavailable_.end()) return {};
  return fmt::format("task kind '{}' is not available in this build ({})", name, it->second);
}
std::vector<std::string> TaskRegistry::names() const {
  std::vector<std::string> n;
  for (const auto& [k, v] : kinds_) n.push_back(k);
  return n;
}
std::vector<std::string> TaskRegistry::unavailable_names() const {
  std::vector<std::string> n;
  for (const auto& [k, v] : unavailable_) n.push_back(k);
  return n;
}

namespace {
nlohmann::json axis_json(const PlotAxis& a) {
  nlohmann::json j = {{"column", a.column}, {"label", a.label}, {"divide_by", a.divide_by}, {"log", a.log}};
  j["min"] = std::isnan(a.min) ? nlohmann::json(nullptr) : nlohmann::json(a.min);
  j["max"] = std::isnan(a.max) ? nlohmann::json(nullptr) : nlohmann::json(a.max);
  return j;
}
}  // namespace

std::string kinds_json(const TaskRegistry& registry) {
  nlohmann::json kinds = nlohmann::json::array();
  for (const auto& name : registry.names()) {
    const TaskKind& k = *registry.find(name);
    nlohmann::json j = {{"name", k.name},       {"description", k.description},
                        {"version", k.version}, {"available", true},
                        {"reason", ""},         {"report_section", bool(k.report)}};
    j["outputs"] = nlohmann::json::array();
    for (const auto& c : k.outputs)
      j["outputs"].push_back({{"name", c.name},
                              {"unit", c.unit},
                              {"description", c.description},
                              {"array", c.array},
                              {"table", c.table},
                              {"column", c.column}});
    j["plots"] = nlohmann::json::array();
    for (const auto& v : k.plots)
      j["plots"].push_back({{"id", v.id},
                            {"x", axis_json(v.x)},
                            {"y", axis_json(v.y)},
                            {"series", v.series},
                            {"label", v.label},
                            {"marker", v.marker},
                            {"marker_size", v.marker_size},
                            {"line_width", v.line_width},
                            {"line", v.line},
                            {"open", v.open},
                            {"color", v.color},
                            {"average_over", v.average_over},
                            {"match", v.match},
                            {"reference", v.reference},
                            {"reference_label", v.reference_label}});
    kinds.push_back(std::move(j));
  }
  for (const auto& name : registry.unavailable_names())
    kinds.push_back({{"name", name},
                     {"description", ""},
                     {"version", registry.version(name)},
                     {"available", false},
                     {"reason", registry.unavailable_reason(name)},
                     {"report_section", false},
                     {"outputs", nlohmann::json::array()},
                     {"plots", nlohmann::json::array()}});
  return nlohmann::json{{"kinds", kinds}}.dump(2);
}

}  // namespace frictal::study
