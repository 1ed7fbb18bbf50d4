// The page of `frictal report`: report_data() computes every section's results (data.cpp), the
// section writers format them (sections.cpp); this file puts the page together.
#include <fmt/core.h>

#include "frictal/report.hpp"
#include "report/sections.hpp"

namespace frictal::report {

Result<std::string> report_page(const ReportInput& in, const ReportData& data) {
  struct Written {
    const detail::PageSection* section;
    std::string title, html;
  };
  std::vector<Written> sections;
  for (const detail::PageSection& s : detail::page_sections()) {
    if (!s.shown(data)) continue;
    auto html = s.write(in, data);
    if (!html) return html.error();
    sections.push_back({&s, s.title(in, data), std::move(*html)});
  }
  const std::string title = detail::page_title(in, data);
  std::string page;
  page += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  page += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  page += fmt::format("<title>{}</title>\n", escape_html(title));
  page += R"(<style>
body { font-family: "DejaVu Sans", Arial, sans-serif; max-width: 1100px; margin: 1.5em auto; padding: 0 1em; color: #222; line-height: 1.4; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; border-bottom: 1px solid #ccc; padding-bottom: .2em; margin-top: 1.6em; }
figure { margin: 1em 0; } figcaption { font-size: .9em; color: #444; max-width: 700px; }
svg.plot { max-width: 100%; height: auto; }
.pair { display: flex; flex-wrap: wrap; gap: 0 1.5em; align-items: flex-start; } .pair > * { flex: 1 1 460px; min-width: 0; }
table { border-collapse: collapse; margin: .8em 0; font-size: .92em; } caption { text-align: left; font-weight: bold; padding: .3em 0; }
th, td { border: 1px solid #ddd; padding: .25em .6em; text-align: left; } td.note { color: #666; font-size: .9em; }
table.resolution td, table.friction td { font-variant-numeric: tabular-nums; }
#directions-table td { white-space: nowrap; }
tr.below-tip td { color: #999; }
tr.unfiltered td { font-weight: bold; }
.verdict { background: #f3f7ee; border-left: 4px solid #5a9a2a; padding: .5em .8em; }
.verdict.doubtful { background: #fdf0e8; border-left-color: #d62728; }
.warnings { background: #fff4e5; border-left: 4px solid #e08a00; padding: .4em .8em; margin: .6em 0; }
.bounds { color: #444; font-size: .95em; }
.assumptions { background: #f7f7f7; padding: .6em 1.4em; border-radius: 4px; }
nav a { margin-right: 1em; } footer { margin-top: 2em; font-size: .85em; color: #666; }
</style>
</head>
<body>
)";
  page += fmt::format("<h1>{}</h1>\n", escape_html(title));
  page += detail::headline(in, data);
  page += "<nav>";
  for (const auto& s : sections) page += fmt::format("<a href=\"#{}\">{}</a>", s.section->id, escape_html(s.title));
  page += "<a href=\"#assumptions\">What was assumed</a></nav>\n";
  for (const auto& s : sections)
    page +=
        fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n{}</section>\n", s.section->id, escape_html(s.title), s.html);
  page += "<section id=\"assumptions\">\n<h2>What was assumed</h2>\n<ul class=\"assumptions\">\n";
  for (const auto& a : detail::assumptions(in, data)) page += fmt::format("<li>{}</li>\n", a);
  page += "</ul>\n</section>\n";
  page += fmt::format(
      "<footer>Method: F. Alonso-Marroquín et al., “Static friction between rigid fractal surfaces”, Phys. Rev. E 92, "
      "032405 (2015). Every number on this page was computed by frictal from the input file(s). {}</footer>\n",
      escape_html(in.generated_by));
  page += "</body>\n</html>\n";
  return page;
}

Result<std::string> surface_report(const ReportInput& in) {
  auto data = report_data(in);
  if (!data) return data.error();
  return report_page(in, *data);
}

}  // namespace frictal::report
