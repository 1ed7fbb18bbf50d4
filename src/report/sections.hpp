// The parts of the page of `frictal report` (private to src/report/): each section one writer
// that takes the results of report_data() and writes its HTML; nothing here computes an analysis.
// A new section is one member of ReportData (computed in data.cpp) and one writer in the list
// of page_sections().
#pragma once

#include <string>
#include <vector>

#include "frictal/report.hpp"

namespace frictal::report::detail {

/// A section's HTML (the body under its heading) from the page's inputs and results.
using SectionWriter = Result<std::string> (*)(const ReportInput& input, const ReportData& data);

struct PageSection {
  const char* id;  ///< the HTML id (the navigation's anchor)
  /// Its heading (and the navigation's entry) for the page's inputs and results.
  std::string (*title)(const ReportInput& input, const ReportData& data);
  bool (*shown)(const ReportData& data);  ///< whether the page has it (its results were computed)
  SectionWriter write;
};

/// The sections in the order of the page.
const std::vector<PageSection>& page_sections();

Result<std::string> surface_section(const ReportInput& input, const ReportData& data);
Result<std::string> signature_section(const ReportInput& input, const ReportData& data);
Result<std::string> slopes_section(const ReportInput& input, const ReportData& data);
/// Maps: the areal signature along the headline's direction, its grid bounds; the facets' and contacts' slopes.
Result<std::string> areal_signature_section(const ReportInput& input, const ReportData& data);
Result<std::string> areal_slopes_section(const ReportInput& input, const ReportData& data);
Result<std::string> friction_section(const ReportInput& input, const ReportData& data);
Result<std::string> hold_section(const ReportInput& input, const ReportData& data);
/// Needs data.areal_hold; a failure of its analysis or its figures is written as "Not computed".
Result<std::string> areal_hold_section(const ReportInput& input, const ReportData& data);
/// Needs data.directions.
Result<std::string> directions_section(const ReportInput& input, const ReportData& data);
/// Needs data.resolution.
Result<std::string> resolution_section(const ReportInput& input, const ReportData& data);

/// The page's title: the surface, or the pair.
std::string page_title(const ReportInput& input, const ReportData& data);
/// The paragraphs under the title: the prediction (input.prediction) with its warnings and JSON,
/// else the rigid upper bound.
std::string headline(const ReportInput& input, const ReportData& data);
/// The items of "What was assumed" (HTML).
std::vector<std::string> assumptions(const ReportInput& input, const ReportData& data);

}  // namespace frictal::report::detail
