// CLI: frictal report writes one self-contained page (file or stdout); usage errors exit 2.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"
#include "frictal/io.hpp"

namespace {
const std::string kData = FRICTAL_TEST_DATA;

/// The page's text (tags dropped, entities kept), sentence by sentence.
std::vector<std::string> sentences(const std::string& page) {
  std::string text;
  bool tag = false;
  for (char c : page) {
    if (c == '<') tag = true;
    if (!tag) text += c;
    if (c == '>') tag = false, text += ' ';
  }
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t k = 0; k < text.size(); ++k)
    if ((text[k] == '.' && k + 1 < text.size() && text[k + 1] == ' ') || text[k] == '\n') {
      out.push_back(text.substr(start, k - start));
      start = k + 1;
    }
  out.push_back(text.substr(start));
  return out;
}

/// No friction number on the page is called predicted unless it is the headline's: a sentence
/// that says "predict" and gives an angle or a coefficient must be in the headline paragraph.
void expect_no_unnamed_bound(const std::string& page) {
  const auto at = page.find("id=\"headline\"");
  const std::string rest = at == std::string::npos ? page : page.substr(0, at) + page.substr(page.find("</p>", at));
  for (const std::string& s : sentences(rest)) {
    std::string low = s;
    for (char& c : low) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (low.find("predicted") == std::string::npos) continue;
    const bool number = s.find("\u00b0") != std::string::npos || s.find("\u03bc =") != std::string::npos ||
                        s.find("\u03bc \u2264") != std::string::npos;
    EXPECT_FALSE(number) << "a friction number called predicted outside the headline: " << s;
  }
}
/// The text of `html` with its tags dropped.
std::string text_of(const std::string& html) {
  std::string t;
  bool tag = false;
  for (char c : html) {
    if (c == '<') tag = true;
    if (!tag) t += c;
    if (c == '>') tag = false, t += ' ';
  }
  return t;
}

/// The elements <tag ...>...</tag> of `html` (not nested in themselves) as [begin, end) ranges.
std::vector<std::pair<std::size_t, std::size_t>> elements(const std::string& html, const std::string& tag) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  const std::string open = "<" + tag, close = "</" + tag + ">";
  for (std::size_t k = html.find(open); k != std::string::npos; k = html.find(open, k + 1)) {
    const char next = k + open.size() < html.size() ? html[k + open.size()] : '\0';
    if (next != ' ' && next != '>') continue;  // <table> but not <tablex>
    const std::size_t e = html.find(close, k);
    if (e == std::string::npos) break;
    out.emplace_back(k, e + close.size());
  }
  return out;
}

bool has_any(const std::string& text, std::initializer_list<const char*> words) {
  for (const char* w : words)
    if (text.find(w) != std::string::npos) return true;
  return false;
}

/// An angle in degrees ("1.785°") or a coefficient after μ ("μ = 0.03", "μ ≤ 0.3").
bool has_friction_value(const std::string& t) {
  for (std::size_t k = t.find("\u00b0"); k != std::string::npos; k = t.find("\u00b0", k + 1))
    if (k > 0 && std::isdigit(static_cast<unsigned char>(t[k - 1]))) return true;
  for (const char* op : {"\u03bc = ", "\u03bc \u2264 "})
    for (std::size_t k = t.find(op); k != std::string::npos; k = t.find(op, k + 1)) {
      const char c = k + std::strlen(op) < t.size() ? t[k + std::strlen(op)] : ' ';
      if (std::isdigit(static_cast<unsigned char>(c)) || c == '-') return true;
    }
  return false;
}

/// Every friction number on the page is the headline's or named as a bound or a diagnostic. The
/// page is cut into blocks (paragraphs, list items, table rows, captions, plot labels); a block that
/// gives an angle or a coefficient of friction (beside φ, μ, "friction", "hold angle" or
/// θ_a + θ_max, in itself or in its table's or figure's caption and header) must be the headline
/// paragraph or name its role ("headline", "bound", "diagnostic") in itself, in that caption or
/// header, or in its section's heading.
void expect_every_friction_number_named(const std::string& page_html) {
  std::string page = page_html;
  for (const char* drop : {"script", "style"})
    for (auto r = elements(page, drop); !r.empty(); r = elements(page, drop))
      page.erase(r.front().first, r.front().second - r.front().first);
  std::vector<std::pair<std::size_t, std::size_t>> parts = elements(page, "section");
  parts.insert(parts.begin(), {0, parts.empty() ? page.size() : parts.front().first});  // the headline's part
  std::size_t checked = 0;
  for (const auto& [pb, pe] : parts) {
    const std::string part = page.substr(pb, pe - pb);
    const auto h2 = elements(part, "h2");
    const std::string heading = h2.empty() ? "" : text_of(part.substr(h2[0].first, h2[0].second - h2[0].first));
    // The labels of the containers: a table's caption and first row, a figure's caption, a summary.
    struct Container {
      std::size_t b, e;
      std::string label;
    };
    std::vector<Container> containers;
    for (const auto& [b, e] : elements(part, "table")) {
      const std::string t = part.substr(b, e - b);
      std::string label;
      for (const char* tag : {"caption", "tr"})
        if (const auto r = elements(t, tag); !r.empty())
          label += text_of(t.substr(r[0].first, r[0].second - r[0].first));
      containers.push_back({b, e, label});
    }
    for (const char* kind : {"figure", "details"})
      for (const auto& [b, e] : elements(part, kind)) {
        const std::string t = part.substr(b, e - b);
        const auto r = elements(t, std::string(kind) == "figure" ? "figcaption" : "summary");
        containers.push_back({b, e, r.empty() ? "" : text_of(t.substr(r[0].first, r[0].second - r[0].first))});
      }
    for (const char* tag : {"p", "li", "tr", "figcaption", "caption", "text"})
      for (const auto& [b, e] : elements(part, tag)) {
        const std::string raw = part.substr(b, e - b);
        if (raw.find("id=\"headline\"") != std::string::npos) continue;  // the headline itself
        const std::string t = text_of(raw);
        if (!has_friction_value(t)) continue;
        std::string label;
        for (const Container& c : containers)
          if (c.b <= b && e <= c.e) label += " " + c.label;
        const auto friction = {
            "\u03c6", "\u03bc", "friction", "hold angle", "\u03b8_a + \u03b8_max", "\u03b8_max + \u03b8_a"};
        if (!has_any(t, friction) && !has_any(label, friction)) continue;
        ++checked;
        const auto roles = {"headline", "bound", "diagnostic"};
        EXPECT_TRUE(has_any(t, roles) || has_any(label, roles) || has_any(heading, roles))
            << "a friction number named neither the headline nor a bound nor a diagnostic, in section '" << heading
            << "': " << t;
      }
  }
  EXPECT_GT(checked, 0u) << "the scan found no friction number at all";
}
}  // namespace

// Pages of a section that names its role and of one that does not, the same table in both.
std::string page_with_section(const std::string& heading) {
  return "<p class=\"verdict\" id=\"headline\">A tilt test reads <b>\u03c6 = 3.000\u00b0</b></p>\n"
         "<section id=\"s\">\n<h2>" +
         heading +
         "</h2>\n<table><tr><th></th><th>towards +x</th></tr>\n"
         "<tr><th>quasi-static hold angle over drops</th><td>4.000\u00b0</td></tr></table>\n"
         "<p>Steepest edge 30.000\u00b0.</p></section>\n";
}

TEST(CliReport, TheFrictionNumberScanFindsAnUnnamedNumber) {
  expect_every_friction_number_named(page_with_section("The hold angle of the whole scans (a diagnostic)"));
  EXPECT_NONFATAL_FAILURE(expect_every_friction_number_named(page_with_section("The hold angle of the whole scans")),
                          "quasi-static hold angle over drops");
}

TEST(CliReport, MeasuredMapAndProfilePairPages) {
  const std::string map_html = temp_path("report_map.html");
  auto r = run_cli("report " + kData + "/x3p/sample-land.x3p -o " + map_html +
                   " --atomic-friction 0.2 --directions 4 --drops 3 --resolution-steps 4 --threads 2");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string page = read_file(map_html);
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(page.find("sample-land.x3p"), std::string::npos);
  EXPECT_NE(page.find("<b>form: plane</b>"), std::string::npos);  // the default detrending for maps, stated
  EXPECT_NE(page.find("Reader warning: "), std::string::npos);    // the reader's warnings are on the page
  EXPECT_NE(page.find("The map over sliding directions"), std::string::npos);
  // The polar plot is `frictal anisotropy`'s table of the map against itself turned over.
  EXPECT_NE(
      page.find("frictal anisotropy sample-land.x3p --areal --hold --directions 4 --drops 3 --atomic-friction 0.2"),
      std::string::npos);
  expect_no_unnamed_bound(page);
  expect_every_friction_number_named(page);

  const std::string wm1 = temp_path("rep_wm1.csv"), wm2 = temp_path("rep_wm2.csv");
  ASSERT_EQ(run_cli("surface wm --dimension 1.5 --n-max 8 --seed 1 -o " + wm1).code, 0);
  ASSERT_EQ(run_cli("surface wm --dimension 1.5 --n-max 8 --seed 2 -o " + wm2).code, 0);
  auto s = run_cli("report " + wm1 + " " + wm2 + " -o - --resolution-steps 3 --threads 2");
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_EQ(s.out.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(s.out.find("surface slopes: upper"), std::string::npos);
  EXPECT_NE(s.out.find("<b>form: line</b>"), std::string::npos);  // the default detrending for profiles
  expect_no_unnamed_bound(s.out);
  expect_every_friction_number_named(s.out);
}

TEST(CliReport, AMeasuredProfilesPageCallsNoBoundPredicted) {
  auto r = run_cli("report " + kData + "/profiles/dektak-1.csv -o - --resolution-steps 0 -q");
  ASSERT_EQ(r.code, 0) << r.err;
  expect_no_unnamed_bound(r.out);
  expect_every_friction_number_named(r.out);
  EXPECT_NE(r.out.find("Rigid upper bound of the friction coefficient"), std::string::npos);
}

TEST(CliReport, TwoMapsSectionIsThePredictionOfFrictalPredict) {
  // Grooves across x (A sin(2 pi i / m), every row alike) and a 12 x 12 window of them, turned
  // over: they mate, and from every drop the block climbs the steepest segment of the
  // piecewise-linear grooves, slope A sin(2 pi / m) / a (by hand). The page's two-map section
  // shows the headline's prediction, the object of `frictal predict --json` on the same input.
  const double a = 1e-6, A = 3.6e-7, kPi = std::numbers::pi;
  const int m = 8;
  frictal::Map g, u;
  g.nx = 32;
  g.ny = 24;
  g.dx = g.dy = a;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) g.heights.push_back(A * std::sin(2 * kPi * double(i) / m));
  u.nx = u.ny = 12;
  u.dx = u.dy = a;
  for (std::size_t j = 0; j < 12; ++j)
    for (std::size_t i = 0; i < 12; ++i) u.heights.push_back(g.at(i + 4, j + 4));
  const std::string lower = temp_path("rep-grooves.x3p"), upper = temp_path("rep-window.x3p");
  ASSERT_TRUE(frictal::write_x3p(lower, g).ok());
  ASSERT_TRUE(frictal::write_x3p(upper, u).ok());
  auto pr = run_cli("predict " + lower + " " + upper + " --detrend none --drops 3 --json");
  ASSERT_EQ(pr.code, 0) << pr.err;
  const nlohmann::json p = nlohmann::json::parse(pr.out);
  const double want = std::atan(A * std::sin(2 * kPi / m) / a) * 180 / kPi;
  EXPECT_GE(p["friction_angle_deg"].get<double>(), want - 1e-7);
  EXPECT_LE(p["friction_angle_deg"].get<double>(), want + 0.012);  // bisected to 1e-4 rad
  const std::string page_file = temp_path("rep-grooves.html");
  auto r = run_cli("report " + lower + " " + upper + " -o " + page_file +
                   " --detrend none --drops 3 --resolution-steps 0 --directions 2 -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string page = read_file(page_file);
  const std::string open = "<script type=\"application/json\" id=\"prediction\">";
  const auto at = page.find(open);
  ASSERT_NE(at, std::string::npos);
  const nlohmann::json q =
      nlohmann::json::parse(page.substr(at + open.size(), page.find("</script>", at) - at - open.size()));
  EXPECT_EQ(q["friction_angle_deg"], p["friction_angle_deg"]);
  EXPECT_EQ(q["drop_friction_angles_deg"], p["drop_friction_angles_deg"]);
  EXPECT_EQ(q["lower"], lower);  // the pair named, as `frictal predict --json` names it
  EXPECT_EQ(q["upper"], upper);
  // Both maps and both maps' statistics are on the page: the upper one is 12 x 12 points.
  const std::string lname = lower.substr(lower.rfind('/') + 1), uname = upper.substr(upper.rfind('/') + 1);
  EXPECT_NE(page.find("Height map: lower, " + lname), std::string::npos);
  EXPECT_NE(page.find("Height map: upper, " + uname), std::string::npos);
  EXPECT_NE(page.find("Areal statistics of the upper map, " + uname), std::string::npos);
  EXPECT_NE(page.find("12 \u00d7 12 points"), std::string::npos);
  // The resolution study's lines are the pair's: the upper map's central line is the upper face.
  EXPECT_NE(page.find("the central line along x of the upper map, " + uname), std::string::npos);
  expect_no_unnamed_bound(page);
  expect_every_friction_number_named(page);
  // The section: its table's median and drops are the prediction's; no grid hold angle.
  const auto sec = page.find("Areal blocks that may move sideways: the headline&#39;s drops</h2>");
  ASSERT_NE(sec, std::string::npos);
  const std::string section = page.substr(sec, page.find("<h2", sec + 10) - sec);
  char median[64];
  std::snprintf(median, sizeof median, "median %.3f\u00b0", p["friction_angle_deg"].get<double>());
  EXPECT_NE(section.find(median), std::string::npos) << median;
  EXPECT_NE(section.find("hold angle over 9 drops"), std::string::npos);
  EXPECT_EQ(section.find("locked (1D rule)"), std::string::npos);
  EXPECT_EQ(section.find("hold angle from s = 0"), std::string::npos);
}

namespace {
/// The page's polar-plot table (id directions-table) holds the rows of `frictal anisotropy --json`
/// (the hold angle over drops per direction and the bounds), row by row to the digits it prints.
void expect_directions_table_is(const std::string& page, const nlohmann::json& t) {
  const auto tb = page.find("id=\"directions-table\"");
  ASSERT_NE(tb, std::string::npos);
  const std::string table = page.substr(tb, page.find("</table>", tb) - tb);
  std::size_t at = table.find("</tr>");  // past the header
  for (const auto& row : t["directions"]) {
    const auto b = table.find("<tr>", at), e = table.find("</tr>", b);
    ASSERT_NE(e, std::string::npos);
    const std::string tr = table.substr(b, e - b);
    at = e;
    auto d = [&](const char* key) { return row[key].get<double>(); };
    char want[200];
    std::snprintf(want, sizeof want,
                  "<tr><td>%.1f\u00b0</td><td>%.4f\u00b0</td><td>%.4f\u00b0 \u2026 %.4f\u00b0</td><td>%.4f\u00b0</td>"
                  "<td>%.4f\u00b0</td><td>%.4f\u00b0 / %.4f\u00b0</td><td>%.4f\u00b0</td>",
                  d("direction_deg"), d("hold_angle_q50_deg"), d("hold_angle_q05_deg"), d("hold_angle_q95_deg"),
                  d("upper_bound_friction_angle_deg"), d("signature_bound_friction_angle_deg"), d("theta_forward_deg"),
                  d("theta_backward_deg"), d("sigma_deg"));
    EXPECT_EQ(tr, std::string(want));
  }
  EXPECT_EQ(table.find("<tr>", at), std::string::npos);  // no row more than the command's
}
}  // namespace

TEST(CliReport, AMapsPolarPlotIsAnisotropyOfTheMapAgainstItself) {
  // One rough map (oblique sines): the polar plot's rows are `frictal anisotropy MAP --areal --hold`'s,
  // the map against itself turned over, with the page's directions and drops; along +x the median
  // hold angle is the headline's (`frictal predict MAP`).
  const double a = 1e-6, A = 2e-7, kPi = std::numbers::pi;
  frictal::Map m;
  m.nx = 12, m.ny = 10;  // small: a map against itself mates, and its drops tilt far
  m.dx = m.dy = a;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i)
      m.heights.push_back(
          A * (std::sin(2 * kPi * double(i) / 6 + 0.7 * double(j)) + 0.5 * std::sin(2 * kPi * double(j) / 5)));
  const std::string file = temp_path("one-map.x3p");
  ASSERT_TRUE(frictal::write_x3p(file, m).ok());
  // (mu_a = 0: a map mated with itself takes the map model many times longer to tilt with mu_a > 0)
  const std::string opts = " --detrend none --drops 3 --threads 2 -q";
  const std::string page_file = temp_path("one-map.html");
  auto r = run_cli("report " + file + " -o " + page_file + opts + " --directions 4 --resolution-steps 0");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string page = read_file(page_file);
  auto an = run_cli("anisotropy " + file + " --areal --hold --directions 4" + opts + " --json");
  ASSERT_EQ(an.code, 0) << an.err;
  const nlohmann::json t = nlohmann::json::parse(an.out);
  ASSERT_EQ(t["directions"].size(), 4u);
  expect_directions_table_is(page, t);
  auto pr = run_cli("predict " + file + opts + " --json");
  ASSERT_EQ(pr.code, 0) << pr.err;
  const nlohmann::json p = nlohmann::json::parse(pr.out);
  char head[64], first[64];
  std::snprintf(head, sizeof head, "%.4f", p["friction_angle_deg"].get<double>());
  std::snprintf(first, sizeof first, "%.4f", t["directions"][0]["hold_angle_q50_deg"].get<double>());
  EXPECT_EQ(std::string(head), std::string(first));
  const std::string name = file.substr(file.rfind('/') + 1);
  EXPECT_NE(page.find("frictal anisotropy " + name + " --areal --hold --directions 4 --drops 3"), std::string::npos);
  EXPECT_NE(page.find("Hold angle over drops by direction"), std::string::npos);

  // The areal signature section is `frictal areal`'s along the headline's direction (+x): its
  // theta_max both ways, sigma, the grid's bound and its mu, to the digits the page prints.
  auto ar = run_cli("areal " + file + " --detrend none --threads 2 --json");
  ASSERT_EQ(ar.code, 0) << ar.err;
  const nlohmann::json g = nlohmann::json::parse(ar.out);
  const auto sec = page.find("<section id=\"areal-signature\">");
  ASSERT_NE(sec, std::string::npos);
  const std::string section = page.substr(sec, page.find("</section>", sec) - sec);
  auto cells = [&](const char* name, const std::string& a, const std::string& b) {
    return "<tr><th>" + std::string(name) + "</th><td>" + a + "</td><td>" + b + "</td></tr>";
  };
  auto degs = [](double v) {
    char t[32];
    std::snprintf(t, sizeof t, "%.3f\u00b0", v);
    return std::string(t);
  };
  const double tf = g["theta_max_forward_deg"].get<double>(), tb = g["theta_max_backward_deg"].get<double>();
  EXPECT_GT(tf, 0.5);  // a rough map: the rows below say something
  EXPECT_NE(section.find(cells("\u03b8_max (steepest contact of the grid)", degs(tf), degs(tb))), std::string::npos)
      << section;
  const std::string sd = degs(g["contact_slope_std_deg"].get<double>());
  EXPECT_NE(section.find(cells("\u03c3 (std of the contact slopes)", sd, sd)), std::string::npos);
  // The grid's bound atan(mu_a) + theta_max (Eq. 6) with mu_a = 0, from `areal`'s theta_max both ways.
  const double ta = 0;
  EXPECT_NE(section.find(cells("the grid's bound \u03b8_a + \u03b8_max (Eq. 6)", degs(ta + tf), degs(ta + tb))),
            std::string::npos);
  EXPECT_NE(section.find(degs(g["upper_bound_friction_angle_deg"].get<double>())), std::string::npos);
  char mu[32];
  std::snprintf(mu, sizeof mu, "<td>%.4f</td>", g["upper_bound_friction_coefficient"].get<double>());
  EXPECT_NE(section.find(mu), std::string::npos) << mu;
  EXPECT_NE(section.find("frictal areal " + name + " --angle 0</code>"), std::string::npos);
  // A map's page has no line signature, line slopes, line bound or line hold angle: only the
  // resolution study (here none) is of the central line.
  for (const char* id : {"id=\"signature\"", "id=\"slopes\"", "id=\"friction\"", "id=\"hold\""})
    EXPECT_EQ(page.find(id), std::string::npos) << id;
  EXPECT_NE(page.find("<section id=\"areal-slopes\">"), std::string::npos);
  expect_no_unnamed_bound(page);
  expect_every_friction_number_named(page);
}

TEST(CliReport, AMapPairsPageNamesBothMapsAndItsNumbersAreTheCommands) {
  // Two different rough maps of one spacing (sums of oblique sines), the upper one smaller.
  const double a = 1e-6, A = 2e-7, kPi = std::numbers::pi;
  frictal::Map lo, up;
  lo.nx = 24, lo.ny = 20, up.nx = up.ny = 14;
  lo.dx = lo.dy = up.dx = up.dy = a;
  for (std::size_t j = 0; j < lo.ny; ++j)
    for (std::size_t i = 0; i < lo.nx; ++i)
      lo.heights.push_back(
          A * (std::sin(2 * kPi * double(i) / 6 + 0.7 * double(j)) + 0.5 * std::sin(2 * kPi * double(j) / 5)));
  for (std::size_t j = 0; j < up.ny; ++j)
    for (std::size_t i = 0; i < up.nx; ++i)
      up.heights.push_back(A * (std::sin(2 * kPi * double(i) / 5 - 0.4 * double(j)) +
                                0.4 * std::cos(2 * kPi * double(j) / 7 + double(i))));
  const std::string lower = temp_path("pair-lower.x3p"), upper = temp_path("pair-upper.x3p");
  ASSERT_TRUE(frictal::write_x3p(lower, lo).ok());
  ASSERT_TRUE(frictal::write_x3p(upper, up).ok());
  const std::string opts = " --detrend none --drops 3 --threads 2 -q";
  const std::string page_file = temp_path("pair.html");
  auto r =
      run_cli("report " + lower + " " + upper + " -o " + page_file + opts + " --directions 4 --resolution-steps 0");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string page = read_file(page_file);
  const std::string lname = lower.substr(lower.rfind('/') + 1), uname = upper.substr(upper.rfind('/') + 1);

  // Both maps, named by their block and file, each with its statistics: the point counts and Sq,
  // the rms height about the mean, computed here from the heights written.
  EXPECT_NE(page.find("Height map: lower, " + lname), std::string::npos);
  EXPECT_NE(page.find("Height map: upper, " + uname), std::string::npos);
  for (const auto* m : {&lo, &up}) {
    const std::string name = m == &lo ? "the lower map, " + lname : "the upper map, " + uname;
    const auto at = page.find("Areal statistics of " + name);
    ASSERT_NE(at, std::string::npos) << name;
    const std::string table = page.substr(at, page.find("</table>", at) - at);
    double mean = 0, sq = 0;
    for (double z : m->heights) mean += z / double(m->heights.size());
    for (double z : m->heights) sq += (z - mean) * (z - mean) / double(m->heights.size());
    char want[64];
    std::snprintf(want, sizeof want, "<td>%.4g nm</td>", std::sqrt(sq) * 1e9);
    EXPECT_NE(table.find(want), std::string::npos) << name << ": " << want;
    const std::string n = std::to_string(m->heights.size());
    EXPECT_NE(table.find("<td>" + n + " (" + n + ")</td>"), std::string::npos) << name;
  }

  // The headline is `frictal predict`'s on the same pair.
  auto pr = run_cli("predict " + lower + " " + upper + opts + " --json");
  ASSERT_EQ(pr.code, 0) << pr.err;
  const nlohmann::json p = nlohmann::json::parse(pr.out);
  char phi[64];
  std::snprintf(phi, sizeof phi, "<b>\u03c6 = %.3f\u00b0</b>", p["friction_angle_deg"].get<double>());
  EXPECT_NE(page.find(phi), std::string::npos) << phi;

  // The polar plot's table is `frictal anisotropy`'s on the pair.
  auto an = run_cli("anisotropy " + lower + " --upper " + upper + " --areal --hold --directions 4" + opts + " --json");
  ASSERT_EQ(an.code, 0) << an.err;
  const nlohmann::json t = nlohmann::json::parse(an.out);
  ASSERT_EQ(t["directions"].size(), 4u);
  expect_directions_table_is(page, t);
  // Along +x the polar plot's median is the headline's.
  char head[64];
  std::snprintf(head, sizeof head, "%.4f", p["friction_angle_deg"].get<double>());
  char first[64];
  std::snprintf(first, sizeof first, "%.4f", t["directions"][0]["hold_angle_q50_deg"].get<double>());
  EXPECT_EQ(std::string(head), std::string(first));
  EXPECT_NE(page.find("frictal anisotropy " + lname + " --upper " + uname + " --areal --hold --directions 4 --drops 3"),
            std::string::npos);
  EXPECT_EQ(page.find("lower map alone"), std::string::npos);
  expect_no_unnamed_bound(page);
  expect_every_friction_number_named(page);
}

TEST(CliReport, UsageErrorsExitTwoAndNameTheProblem) {
  auto a = run_cli("report " + kData + "/profiles/missing.csv -o " + temp_path("x.html"));
  EXPECT_EQ(a.code, 2);
  EXPECT_NE(a.err.find("missing.csv"), std::string::npos);
  auto b =
      run_cli("report " + kData + "/x3p/sample-land.x3p " + kData + "/profiles/xy-1.txt -o " + temp_path("x.html"));
  EXPECT_EQ(b.code, 2);
  EXPECT_NE(b.err.find("UPPER must be a map too"), std::string::npos);
  auto c = run_cli("report " + kData + "/profiles/xy-1.txt -o " + temp_path("x.html") + " --atomic-friction -1");
  EXPECT_EQ(c.code, 2);
  EXPECT_NE(c.err.find("--atomic-friction"), std::string::npos);
  auto d = run_cli("report " + kData + "/profiles/xy-1.txt -o /nonexistent-dir/x.html --resolution-steps 0");
  EXPECT_EQ(d.code, 2);
  EXPECT_NE(d.err.find("/nonexistent-dir/x.html"), std::string::npos);
  EXPECT_EQ(run_cli("report " + kData + "/profiles/xy-1.txt -o " + temp_path("x.html") + " --detrend cubic").code, 2);
}
