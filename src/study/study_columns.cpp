// The output tables of studies (frictal/outputs.hpp): the keys of `frictal study status --json`
// and of Python's study_status(), study_run(), study_run_many() and study_rows() dicts.
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "frictal/study.hpp"

namespace frictal::study {

const Columns<StoreCounts>& study_tasks_columns() {
  using T = StoreCounts;
  static const Columns<T> cols = {
      column<T>("total", "count", "tasks in the study", [](const T& c) { return double(c.total); }),
      column<T>("done", "count", "tasks done", [](const T& c) { return double(c.done); }),
      column<T>("failed", "count", "tasks failed", [](const T& c) { return double(c.failed); }),
      column<T>("pending", "count", "tasks not yet run", [](const T& c) { return double(c.pending); }),
  };
  return cols;
}

const Columns<StoreStatus::PartStatus>& study_part_columns() {
  using T = StoreStatus::PartStatus;
  static const Columns<T> cols = {
      column<T>("part", "text", "the part's name", [](const T& p) { return p.part; }),
      column<T>("kind", "text", "its task kind", [](const T& p) { return p.kind; }),
      column<T>("done", "count", "tasks done", [](const T& p) { return double(p.done); }),
      column<T>("failed", "count", "tasks failed", [](const T& p) { return double(p.failed); }),
      column<T>("pending", "count", "tasks pending", [](const T& p) { return double(p.pending); }),
      column<T>("available", "flag", "this build can run the kind", [](const T& p) { return p.available; }),
      column<T>("kind_version", "count", "this build's version of the kind (0: unknown kind)",
                [](const T& p) { return double(p.kind_version); }),
      // Keyed by version (data, not names).
      data_map_column<T>("done_by_kind_version", "tasks done by each kind version (0: not recorded)",
                         [](const T& p) {
                           std::vector<MapEntry> e;
                           for (const auto& [v, n] : p.done_by_kind_version)
                             e.push_back({std::to_string(v), "count", double(n)});
                           return e;
                         }),
      data_map_column<T>("done_by_frictal_version", "tasks done by each frictal version (empty: not recorded)",
                         [](const T& p) {
                           std::vector<MapEntry> e;
                           for (const auto& [v, n] : p.done_by_frictal_version) e.push_back({v, "count", double(n)});
                           return e;
                         }),
      column<T>("version_note", "text", "what a version change means for the stored results",
                [](const T& p) { return p.version_note; }),
  };
  return cols;
}

const Columns<StudyStatusReport>& study_status_columns() {
  using T = StudyStatusReport;
  static const Columns<T> cols = {
      column<T>("store", "text", "the store", [](const T& r) { return r.store; }),
      column<T>("study", "text", "the study's name", [](const T& r) { return r.status.study; }),
      column<T>("scale", "text", "full or quick", [](const T& r) { return r.status.scale; }),
      column<T>("study_hash", "text", "hash of the study file", [](const T& r) { return r.status.study_hash; }),
      column<T>("schema_version", "count", "the store's schema version",
                [](const T& r) { return double(r.status.schema_version); }),
      column<T>("frictal_version", "text", "frictal's version that created the store",
                [](const T& r) { return r.status.frictal_version; }),
      column<T>("claimed", "count", "tasks claimed by a running process (or by one that died)",
                [](const T& r) { return double(r.status.claimed); }),
      object_column<T, StoreCounts>("tasks", "study_tasks", "task counts", study_tasks_columns(),
                                    [](const T& r) { return std::optional(r.status.tasks); }),
      list_column<T, StoreStatus::PartStatus>("parts", "study_part", "one entry per part", study_part_columns(),
                                              [](const T& r) { return std::optional(r.status.parts); }),
  };
  return cols;
}

const Columns<StudyRunReport>& study_run_columns() {
  using T = StudyRunReport;
  auto given = [](std::string python, std::string help, std::optional<std::string> T::*field) {
    return only_if(column<T>(
                       "", "text", std::move(help), [field](const T& r) { return *(r.*field); }, std::move(python)),
                   [field](const T& r) { return (r.*field).has_value(); });
  };
  auto count = [](std::string python, std::string help, std::int64_t RunSummary::*field) {
    return column<T>(
        "", "count", std::move(help), [field](const T& r) { return double(r.summary.*field); }, std::move(python));
  };
  static const Columns<T> cols = {
      given("study", "the study (runs of several studies)", &T::study),
      given("store", "the store (runs of several studies)", &T::store),
      count("ran", "tasks run", &RunSummary::ran),
      count("failed", "tasks failed", &RunSummary::failed),
      count("retries", "failed attempts queued again", &RunSummary::retries),
      count("reused", "tasks taken from the result cache", &RunSummary::reused),
      column<T>(
          "", "text", "why the result cache was not used or not fully written (empty: it was)",
          [](const T& r) { return r.summary.cache_note; }, "cache_note"),
      count("skipped_unavailable", "tasks skipped: their kind is not in this build", &RunSummary::skipped_unavailable),
      column<T>(
          "", "count", "compute threads used", [](const T& r) { return double(r.summary.threads); }, "threads"),
      column<T>(
          "", "s", "wall time of the run", [](const T& r) { return r.summary.wall_s; }, "wall_time"),
      object_column<T, StoreCounts>(
          "", "study_tasks", "the store's task counts after the run", study_tasks_columns(),
          [](const T& r) { return std::optional(r.tasks); }, "tasks"),
  };
  return cols;
}

const Columns<TaskRow>& study_row_columns() {
  using T = TaskRow;
  // A parameter's value as it was given: an integer, a number (the study's units, as its name
  // says), a text or a flag.
  auto param = [](const std::string& name, const Value& v) {
    struct V {
      const std::string& name;
      MapEntry operator()(std::int64_t i) const { return {name, "count", double(i)}; }
      MapEntry operator()(double d) const { return {name, "1", d}; }
      MapEntry operator()(const std::string& t) const { return {name, "text", t}; }
      MapEntry operator()(bool b) const { return {name, "flag", b}; }
    };
    return std::visit(V{name}, v);
  };
  static const Columns<T> cols = {
      column<T>(
          "", "count", "the task's id", [](const T& r) { return double(r.id); }, "task_id"),
      column<T>(
          "", "text", "its part", [](const T& r) { return r.part; }, "part"),
      column<T>(
          "", "text", "its kind", [](const T& r) { return r.kind; }, "kind"),
      data_map_column<T>(
          "", "its parameters (the kind's settings, in the study's units)",
          [param](const T& r) {
            std::vector<MapEntry> e;
            for (const auto& [k, v] : r.params) e.push_back(param(k, v));
            return e;
          },
          "params"),
      data_map_column<T>(
          "", "its scalar outputs (frictal study kinds lists them with units)",
          [](const T& r) {
            std::vector<MapEntry> e;
            for (const auto& [k, v] : r.output.scalars) e.push_back({k, "1", v});
            return e;
          },
          "scalars"),
      data_map_column<T>(
          "", "its array outputs (numpy arrays)",
          [](const T& r) {
            std::vector<MapEntry> e;
            for (const auto& [k, v] : r.output.arrays) e.push_back({k, "1", v});
            return e;
          },
          "arrays"),
  };
  return cols;
}

}  // namespace frictal::study
