// Findings as data: one conclusion per claim over every part that checks it,
// with a verdict from the allowed set; `frictal study report --json` writes them; a claim is not
// checked on the parts it does not apply to (Eq. 18 only on the paper's test, the bracket
// [phi_in, phi_qs] only on a test from rest). The verdicts are derived again here from the
// exported CSV (a second path: `frictal study export`, no report code).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/cli_runner.hpp"
#include "frictal/study.hpp"
#include "study/study_helpers.hpp"

using namespace frictal::study;

namespace {

Finding finding(const std::string& claim_id, const std::string& part, bool supported, const std::string& cause = "") {
  Finding f;
  f.claim_id = claim_id;
  f.part = part;
  f.claim = "Part '" + part + "': " + claim_id;
  f.supported = supported;
  f.evidence.push_back("criterion: made up");
  f.cause = cause;
  return f;
}

const Conclusion* of(const std::vector<Conclusion>& cs, const std::string& id) {
  for (const auto& c : cs)
    if (c.claim.id == id) return &c;
  return nullptr;
}

// CSV rows of an exported part (header -> value), split on commas (the exported fields quoted
// here have none).
std::vector<std::map<std::string, std::string>> read_csv(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> head;
  std::vector<std::map<std::string, std::string>> rows;
  auto split = [](const std::string& s) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string f;
    while (std::getline(ss, f, ',')) out.push_back(f);
    if (!s.empty() && s.back() == ',') out.emplace_back();
    return out;
  };
  if (std::getline(in, line)) head = split(line);
  while (std::getline(in, line)) {
    const auto v = split(line);
    std::map<std::string, std::string> r;
    for (std::size_t i = 0; i < head.size() && i < v.size(); ++i) r[head[i]] = v[i];
    rows.push_back(std::move(r));
  }
  return rows;
}

}  // namespace

TEST(StudyFindings, CatalogueIdsAreUniqueAndSupersedingClaimsAreFrictalsOwn) {
  std::set<std::string> ids;
  for (const auto& c : claims()) {
    EXPECT_TRUE(ids.insert(c.id).second) << c.id;
    EXPECT_FALSE(c.statement.empty()) << c.id;
    EXPECT_FALSE(c.applies_to.empty()) << c.id;
    for (const auto& s : c.superseded_by) {
      const Claim* r = find_claim(s);
      ASSERT_NE(r, nullptr) << c.id << " -> " << s;
      EXPECT_FALSE(r->paper) << c.id << " is superseded by frictal's own findings only, not by " << s;
      EXPECT_TRUE(c.paper) << c.id;
    }
  }
  EXPECT_EQ(find_claim("no-such-claim"), nullptr);
}

TEST(StudyFindings, OneConclusionPerClaimOverEveryPart) {
  Report a, b;
  a.study = "s1";
  b.study = "s2";
  a.findings = {finding("koch-theta-max", "theory", true), finding("eq18-range", "wm", false, "reads phi_qs"),
                finding("dynamic-hold-bracket", "wm-rest", true)};
  b.findings = {finding("koch-theta-max", "signature", true), finding("eq6-simulation", "sim", false),
                finding("eq18-range", "fourier", false, "reads phi_qs too"),
                finding("tilt-hold-angle", "sim", false, "a wall")};
  auto cs = conclude({a, b});
  ASSERT_TRUE(cs.ok()) << cs.error().message;
  // One per claim checked, in the catalogue's order, none for claims nobody checked.
  ASSERT_EQ(cs->size(), 5u);
  std::set<std::string> seen;
  for (const auto& c : *cs) EXPECT_TRUE(seen.insert(c.claim.id).second);
  EXPECT_EQ(of(*cs, "wm-contact-below-surface"), nullptr);
  const Conclusion* k = of(*cs, "koch-theta-max");
  ASSERT_NE(k, nullptr);
  EXPECT_EQ(k->verdict, Verdict::Supported);
  ASSERT_EQ(k->checks.size(), 2u);
  EXPECT_EQ(k->checks[0].study, "s1");
  EXPECT_EQ(k->checks[1].part, "signature");
  // Not supported in two parts, superseded: its superseding finding holds.
  const Conclusion* e = of(*cs, "eq18-range");
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->verdict, Verdict::Superseded);
  EXPECT_EQ(e->cause, "s1/wm: reads phi_qs; s2/fourier: reads phi_qs too");
  EXPECT_TRUE(e->uncaused.empty());
  // Not supported, and what would supersede it does not hold either: not supported; the part
  // without a cause is named.
  const Conclusion* s = of(*cs, "eq6-simulation");
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(s->verdict, Verdict::NotSupported);
  EXPECT_EQ(s->uncaused, std::vector<std::string>{"s2/sim"});
  EXPECT_STREQ(verdict_name(Verdict::Superseded), "superseded");
  EXPECT_STREQ(verdict_name(Verdict::NotSupported), "not supported");
  // A finding that names no claim of the catalogue is an error, not a silent extra verdict.
  b.findings.push_back(finding("made-up", "sim", true));
  auto bad = conclude({a, b});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("made-up"), std::string::npos);
}

TEST(StudyFindings, ReportJsonHasOneVerdictPerClaimAndSkipsPartsAClaimDoesNotApplyTo) {
  // The paper's test (constant rate, free settling) and a test from rest on the same pair.
  const std::string toml = temp_path("findings_tiny.toml");
  write_file(toml, R"([study]
name = "findings-tiny"
seed = 3
[[part]]
name = "wm"
kind = "wm-tilt"
seed_from = ["pair"]
[part.parameters]
generator = "wm"
dimension = 1.5
pair = { count = 1 }
n_max = 4
longest_wavelength = 0.01
length = 0.04
rms_height = 1e-5
spheroradius = 2e-5
[[part]]
name = "wm-rest"
kind = "wm-tilt"
seed_from = ["pair"]
[part.parameters]
generator = "wm"
dimension = 1.5
pair = { count = 1 }
n_max = 4
longest_wavelength = 0.01
length = 0.04
rms_height = 1e-5
spheroradius = 2e-5
settling = "relax"
turn = "gravity"
hold_rotation = true
)");
  const std::string store = study_test::fresh("findings_tiny.sqlite");
  const CliRun run = run_cli("study run " + toml + " --store " + store + " --threads 2");
  ASSERT_EQ(run.code, 0) << run.err << run.out;
  const CliRun rep = run_cli("study report --json " + store);
  ASSERT_EQ(rep.code, 0) << rep.err;
  const auto j = nlohmann::json::parse(rep.out);
  const std::set<std::string> allowed = {"supported", "not supported", "superseded"};
  std::set<std::string> catalogue;
  for (const auto& c : j.at("claims")) catalogue.insert(c.at("id").get<std::string>());
  EXPECT_EQ(catalogue.size(), claims().size());

  // Which claims each part was checked on, from the findings.
  std::map<std::string, std::set<std::string>> parts_of;
  ASSERT_EQ(j.at("reports").size(), 1u);
  EXPECT_EQ(j["reports"][0].at("study"), "findings-tiny");
  std::map<std::string, std::string> verdict_on;  // claim_id/part -> verdict
  for (const auto& f : j["reports"][0].at("findings")) {
    const std::string id = f.at("claim_id"), part = f.at("part");
    EXPECT_TRUE(catalogue.count(id)) << id;
    EXPECT_TRUE(f.at("verdict") == "supported" || f.at("verdict") == "not supported") << f.dump();
    EXPECT_FALSE(f.at("criterion").get<std::string>().empty()) << f.dump();
    EXPECT_TRUE(f.at("source") == "paper" || f.at("source") == "frictal");
    parts_of[id].insert(part);
    verdict_on[id + "/" + part] = f.at("verdict");
  }
  // The paper's Eq. 18 and the run-away and prediction questions on the paper's test only; the bracket only on
  // the test from rest.
  EXPECT_EQ(parts_of["eq18-range"], std::set<std::string>{"wm"});
  EXPECT_EQ(parts_of["eq18-over-drops"], std::set<std::string>{"wm"});
  EXPECT_EQ(parts_of["runaway-independent"], std::set<std::string>{"wm"});
  EXPECT_EQ(parts_of["sphero-closer-than-rigid"], std::set<std::string>{"wm"});
  EXPECT_EQ(parts_of["dynamic-hold-bracket"], std::set<std::string>{"wm-rest"});
  EXPECT_EQ(parts_of.count("quasi-static-hold"), 0u);

  // One conclusion per claim checked, each with an allowed verdict.
  std::map<std::string, std::string> verdict;
  for (const auto& c : j.at("conclusions")) {
    const std::string id = c.at("id");
    EXPECT_TRUE(verdict.emplace(id, c.at("verdict")).second) << "two conclusions for " << id;
    EXPECT_TRUE(allowed.count(c.at("verdict"))) << c.dump();
    EXPECT_EQ(c.at("checks").size(), parts_of[id].size()) << id;
  }
  EXPECT_EQ(verdict.size(), parts_of.size());

  // The verdicts again, from the exported scalars. Eq. 18 on the paper's test: every block slid
  // and at least 90 % of the angles inside the range.
  const std::string dir = temp_path("findings_tiny_csv");
  ASSERT_EQ(run_cli("study export " + store + " --csv " + dir).code, 0);
  const auto wm = read_csv(dir + "/wm.csv"), rest = read_csv(dir + "/wm-rest.csv");
  ASSERT_EQ(wm.size(), 1u);
  ASSERT_EQ(rest.size(), 1u);
  const bool slid = std::stod(wm[0].at("slid")) > 0, inside = std::stod(wm[0].at("inside_eq18")) > 0;
  EXPECT_EQ(verdict_on["eq18-range/wm"], slid && inside ? "supported" : "not supported");
  // The bracket on the test from rest: the one pair inside [phi_in - 0.1, phi_qs + 0.1] unless a
  // warning flags it (then nothing is judged: not supported).
  const auto& r = rest[0];
  bool flagged = false;
  for (const char* w : {"warning_rotation", "warning_unsettled", "warning_core_overlap", "warning_time_step",
                        "warning_unrelaxed", "warning_stiffness"})
    flagged = flagged || (r.count(w) && !r.at(w).empty() && std::stod(r.at(w)) > 0);
  const double phi = std::stod(r.at("friction_angle_deg")), in = std::stod(r.at("sphero_inertial_hold_angle_deg")),
               qs = std::stod(r.at("sphero_hold_angle_deg"));
  const bool rest_slid = std::stod(r.at("slid")) > 0;
  ASSERT_TRUE(rest_slid) << "the block from rest did not slide: nothing to judge";
  const bool bracket = !flagged && phi >= std::min(in, qs) - 0.1 && phi <= qs + 0.1;
  EXPECT_EQ(verdict_on["dynamic-hold-bracket/wm-rest"], bracket ? "supported" : "not supported")
      << "phi " << phi << ", phi_in " << in << ", phi_qs " << qs << ", flagged " << flagged;
  // The conclusion on Eq. 18: superseded exactly when it fails and the bracket holds.
  const std::string want = slid && inside ? "supported" : (bracket ? "superseded" : "not supported");
  EXPECT_EQ(verdict["eq18-range"], want);
  std::remove(toml.c_str());
}
