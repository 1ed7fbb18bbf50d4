// Study reports: summary tables and the paper's findings checked against stored results.
#include <fmt/core.h>

#include "frictal/study.hpp"

namespace frictal::study {

Result<Report> report(Store& store) {
  auto m = store.meta();
  if (!m) return m.error();
  Report r;
  r.title = fmt::format("Study '{}' ({} scale)", (*m)["study_name"], (*m)["scale"]);
  return r;
}

}  // namespace frictal::study
