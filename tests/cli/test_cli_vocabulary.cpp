// CLI vocabulary: one name per quantity across every command's --help, the options and JSON keys
// are exactly the library tables' names, mistyped words get an answer naming them, and "-"
// composes commands in pipes. Expected names come from the tables as `frictal settings --json`
// prints them and from the list of retired second names below, not from the help being tested.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"

namespace {

struct HelpPage {
  std::string path;                            ///< "tilt koch"
  std::map<std::string, std::string> options;  ///< long option -> description
  std::vector<std::string> subcommands;
};

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(' ');
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(' ') - a + 1);
}

/// Parses CLI11's help: option lines "  -n,--iterations INT   Description" (the description may
/// start on the next line when the name column is full) and the "Subcommands:" section.
HelpPage parse_help(const std::string& path, const std::string& text) {
  HelpPage page{path, {}, {}};
  std::istringstream in(text);
  std::string line, section;
  std::vector<std::string> lines;
  while (std::getline(in, line)) lines.push_back(line);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& l = lines[i];
    if (!l.empty() && l[0] != ' ') {
      section = l;
      continue;
    }
    const std::string t = trim(l);
    if (t.empty()) continue;
    if (section.rfind("Subcommands", 0) == 0) {
      page.subcommands.push_back(t.substr(0, t.find(' ')));
      continue;
    }
    if (t[0] != '-') continue;
    const auto gap = t.find("  ");
    std::string names = t.substr(0, gap), desc = gap == std::string::npos ? "" : trim(t.substr(gap));
    if (desc.empty() && i + 1 < lines.size()) desc = trim(lines[i + 1]);
    std::istringstream ns(names);
    std::string tok;
    while (std::getline(ns, tok, ',')) {
      tok = trim(tok);
      tok = tok.substr(0, tok.find(' '));
      if (tok.rfind("--", 0) == 0) page.options[tok] = desc;
    }
  }
  return page;
}

/// Every help page: the top level, each command and, recursively, each subcommand.
std::vector<HelpPage> all_help_pages() {
  std::vector<HelpPage> pages;
  std::vector<std::string> todo{""};
  while (!todo.empty()) {
    const std::string path = todo.back();
    todo.pop_back();
    const CliRun r = run_cli(path + " --help");
    EXPECT_EQ(r.code, 0) << path;
    HelpPage p = parse_help(path, r.out);
    for (const std::string& s : p.subcommands) todo.push_back(path.empty() ? s : path + " " + s);
    pages.push_back(std::move(p));
  }
  return pages;
}

nlohmann::json tables() {
  const CliRun r = run_cli("settings --json");
  EXPECT_EQ(r.code, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

const char* kCommandsWithGenerators[] = {"surface", "signature", "tilt", "dimension"};

}  // namespace

TEST(CliVocabulary, NoQuantityHasTwoNames) {
  const auto pages = all_help_pages();
  ASSERT_GT(pages.size(), 20u);
  // Second names retired for one quantity (old -> the one name); none may come back.
  const std::map<std::string, std::string> retired = {{"--mu-a", "--atomic-friction"},
                                                      {"--koch-alpha", "--alpha"},
                                                      {"--kn", "--normal-stiffness"},
                                                      {"--kt", "--tangential-stiffness"},
                                                      {"--gamma-n", "--normal-damping"},
                                                      {"--gamma-t", "--tangential-damping"},
                                                      {"--dt", "--time-step"},
                                                      {"--settle", "--settle-time"},
                                                      {"--height", "--block-height"},
                                                      {"--runaway", "--runaway-distance"},
                                                      {"--offset", "--initial-offset"},
                                                      {"--rms", "--rms-height"},
                                                      {"--deterministic", "--no-stochastic"},
                                                      {"--surface", "(generator subcommand)"},
                                                      {"--radius", "--spheroradius"},
                                                      {"--alpha-deg", "--alpha"}};
  for (const HelpPage& p : pages)
    for (const auto& [name, desc] : p.options) {
      auto it = retired.find(name);
      EXPECT_TRUE(it == retired.end()) << "frictal " << p.path << " offers " << name << ", a second name of "
                                       << it->second;
    }
  // A table field's description belongs to its one option: the same description under another
  // option name would be a second name for the quantity; and the option reads the same
  // (description with unit, default, range) in every command.
  std::map<std::string, std::set<std::string>> names_by_desc;
  std::map<std::string, std::set<std::string>> descs_by_name;
  for (const HelpPage& p : pages)
    for (const auto& [name, desc] : p.options) {
      names_by_desc[desc].insert(name);
      descs_by_name[name].insert(desc);
    }
  const auto t = tables();
  std::vector<nlohmann::json> fields(t["tilt"].begin(), t["tilt"].end());
  for (const auto& [gen, g] : t["generators"].items())
    for (const auto& f : g["fields"]) fields.push_back(f);
  for (const auto& f : fields) {
    const std::string option = f["option"];
    for (const auto& [desc, names] : names_by_desc) {
      if (desc.rfind(f["help"].get<std::string>() + " ", 0) == 0 || desc == f["help"].get<std::string>()) {
        for (const std::string& n : names) {
          EXPECT_TRUE(n == option || n == "--no-" + option.substr(2)) << f["name"] << " is also offered as " << n;
        }
      }
    }
  }
  // Options named like a table field read the same in every command.
  for (const auto& f : t["tilt"]) EXPECT_LE(descs_by_name[f["option"].get<std::string>()].size(), 1u) << f["option"];
  // The sawtooth's angle is --rise-angle everywhere, Koch's is --alpha.
  for (const HelpPage& p : pages) {
    if (p.path.size() >= 9 && p.path.substr(p.path.size() - 9) == " sawtooth") {
      EXPECT_TRUE(p.options.count("--rise-angle")) << p.path;
      EXPECT_FALSE(p.options.count("--alpha")) << p.path;
    }
    if (p.path.size() >= 5 && p.path.substr(p.path.size() - 5) == " koch") {
      EXPECT_TRUE(p.options.count("--alpha")) << p.path;
      EXPECT_FALSE(p.options.count("--rise-angle")) << p.path;
    }
  }
}

TEST(CliVocabulary, GeneratorCommandsOfferExactlyTheTablesOptions) {
  const auto t = tables();
  std::vector<std::string> gens;
  for (const auto& [gen, g] : t["generators"].items()) gens.push_back(gen);
  ASSERT_EQ(gens.size(), 6u);
  for (const char* cmd : kCommandsWithGenerators) {
    const HelpPage top = parse_help(cmd, run_cli(std::string(cmd) + " --help").out);
    for (const auto& [gen, g] : t["generators"].items()) {
      EXPECT_NE(std::find(top.subcommands.begin(), top.subcommands.end(), gen), top.subcommands.end())
          << cmd << " " << gen;
      const HelpPage p = parse_help(gen, run_cli(std::string(cmd) + " " + gen + " --help").out);
      std::set<std::string> expected{"--help"}, offered;
      for (const auto& f : g["fields"]) {
        expected.insert(f["option"].get<std::string>());
        if (f["type"] == "boolean") expected.insert("--no-" + f["option"].get<std::string>().substr(2));
      }
      for (const auto& [name, desc] : p.options)
        // The generator's own (an option of the parent command with the same name, e.g. the
        // readers' --spacing beside wm's --spacing, is the generator's when its help differs).
        if (!top.options.count(name) || top.options.at(name) != desc || name == "--help") offered.insert(name);
      EXPECT_EQ(offered, expected) << cmd << " " << gen;
    }
  }
  // tilt offers every tilt setting.
  const HelpPage tilt = parse_help("tilt", run_cli("tilt --help").out);
  for (const auto& f : t["tilt"]) EXPECT_TRUE(tilt.options.count(f["option"].get<std::string>())) << f["name"];
}

TEST(CliVocabulary, TiltJsonPrintsExactlyTheTablesNames) {
  const auto t = tables();
  // K0 at 5 deg on two wavelengths, stopped at 1 deg of tilt: fast, and the settings given in
  // degrees come back in degrees.
  const CliRun r = run_cli("tilt koch --alpha 5 --length 0.02 --max-tilt 1 --atomic-friction 0.25 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  std::set<std::string> expected, printed;
  for (const auto& f : t["tilt"]) expected.insert(f["name"].get<std::string>());
  for (const auto& [k, v] : j["settings"].items()) printed.insert(k);
  EXPECT_EQ(printed, expected);
  EXPECT_DOUBLE_EQ(j["settings"]["max_tilt"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(j["settings"]["atomic_friction"].get<double>(), 0.25);
  // The generated surface sets the period and the run-away distance: one wavelength.
  EXPECT_DOUBLE_EQ(j["settings"]["period"].get<double>(), 0.01);
  EXPECT_DOUBLE_EQ(j["settings"]["runaway_distance"].get<double>(), 0.01);
  std::set<std::string> surface{"generator"}, koch;
  for (const auto& f : t["generators"]["koch"]["fields"]) surface.insert(f["name"].get<std::string>());
  for (const auto& [k, v] : j["surface"].items()) koch.insert(k);
  EXPECT_EQ(koch, surface);
  EXPECT_DOUBLE_EQ(j["surface"]["alpha"].get<double>(), 5.0);
  // theta_max of K0 is alpha (Sec. III); with mu_a: alpha + atan(0.25).
  EXPECT_NEAR(j["predicted_friction_angle_deg"].get<double>(), 5.0 + std::atan(0.25) * 180 / M_PI, 1e-9);
}

TEST(CliVocabulary, TiltTakesEveryGeneratorWithoutFiles) {
  for (const std::string g : {"koch --length 0.02", "sawtooth --length 0.02", "sine --length 0.02",
                              "wm --length 0.02 --longest-wavelength 0.01 --rms-height 1e-3 --n-max 3",
                              "self-affine --length 0.02 --rms-height 5e-4 --points 200",
                              "fourier --length 0.02 --rolloff-wavelength 0.005 --short-cutoff-wavelength 0.001 "
                              "--rms-height 5e-4 --points 256"}) {
    const CliRun r = run_cli("tilt " + g + " --max-tilt 2 --json");
    ASSERT_EQ(r.code, 0) << g << ": " << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["surface"]["generator"], g.substr(0, g.find(' '))) << g;
  }
  // Sawtooth at 30 deg: the prediction is the rise angle (theta_max of a sawtooth on itself).
  const CliRun s = run_cli("tilt sawtooth --rise-angle 30 --length 0.02 --max-tilt 1 --json");
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_NEAR(nlohmann::json::parse(s.out)["predicted_theta_max_deg"].get<double>(), 30.0, 1e-9);
}

TEST(CliVocabulary, SettingsDocIsCurrent) {
  const CliRun r = run_cli("settings --markdown");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, read_file(std::string(FRICTAL_TEST_DATA) + "/../../docs/settings.md"))
      << "docs/settings.md is out of date: run `frictal settings --markdown > docs/settings.md`";
}

TEST(CliVocabulary, MistypedWordsAreNamedWithTheNearest) {
  auto r = run_cli("stat x.csv");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("unknown command 'stat'; did you mean 'stats'?"), std::string::npos) << r.err;
  r = run_cli("xyzzy");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("unknown command 'xyzzy'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Commands: predict, surface, signature"), std::string::npos) << r.err;
  r = run_cli("surface kohc -o x.csv");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("unknown subcommand 'kohc' for 'frictal surface'; did you mean 'koch'?"), std::string::npos)
      << r.err;
  r = run_cli("surface koch --alph 20 -o x.csv");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("unknown option '--alph' for 'frictal surface koch'; did you mean '--alpha'?"),
            std::string::npos)
      << r.err;
  r = run_cli("tilt koch --time-stpe 1e-5");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("did you mean '--time-step'?"), std::string::npos) << r.err;
  r = run_cli("tilt sawtooth --alpha 10");  // the sawtooth's angle is --rise-angle
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("unknown option '--alpha'"), std::string::npos) << r.err;
  // Values out of the table's range name the option, the range and the unit.
  r = run_cli("surface koch --alpha 75 -o x.csv");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--alpha: expected a number in (0, 60] deg, got 75"), std::string::npos) << r.err;
  r = run_cli("surface wm --exponent comon -o x.csv");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("did you mean 'common'?"), std::string::npos) << r.err;
}

TEST(CliVocabulary, DashComposesCommandsInPipes) {
  const std::string cli = FRICTAL_CLI_PATH;
  // K2 at alpha = 20 deg: theta_max = 2 alpha = 40 deg (Sec. III).
  const CliRun r = run_cli("surface koch -n 2 --alpha 20 --length 0.02 -o - | " + cli + " signature - --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["theta_max_forward_deg"].get<double>(), 40.0, 1e-9);
  EXPECT_EQ(j["lower"], "-");
  // stdout carries only the CSV; the status line goes to stderr.
  const CliRun csv = run_cli("surface sine --length 0.01 --points-per-wavelength 4 -o -");
  ASSERT_EQ(csv.code, 0) << csv.err;
  EXPECT_EQ(csv.out.substr(0, 8), "x_m,z_m\n");
  EXPECT_EQ(std::count(csv.out.begin(), csv.out.end(), '\n'), 6);  // header + 5 points
  EXPECT_NE(csv.err.find("wrote sine profile"), std::string::npos);
  // signature -o - writes the CSV on stdout and the summary on stderr.
  const CliRun sig = run_cli("signature sawtooth --length 0.02 -o -");
  ASSERT_EQ(sig.code, 0) << sig.err;
  EXPECT_EQ(sig.out.rfind("offset_m,lift_m,theta_deg", 0), 0u);
  EXPECT_NE(sig.err.find("theta_max forward"), std::string::npos);
  EXPECT_EQ(run_cli("signature sawtooth --length 0.02 -o - --json").code, 2);
  // Errors about standard input name it "-".
  const CliRun bad = run_cli("stats - < /dev/null");
  EXPECT_EQ(bad.code, 2);
  EXPECT_EQ(bad.err.find("frictal-"), std::string::npos) << bad.err;
}

TEST(CliVocabulary, AModulusSettingTakesItsUnitAsFrictalContactDoes) {
  // `frictal contact --modulus 70GPa` and `predict --load ... --modulus 70GPa` take a unit; a
  // settings table's field in Pa (tilt's block_modulus) takes the same words: 70GPa is 7e10 Pa
  // to the bit, 70000MPa and 7e7kPa too, and a unit that is no pressure is refused naming the
  // units it takes.
  const std::string base = "tilt koch --alpha 5 --length 0.02 --max-tilt 1 --contact-law hertz --json --block-modulus ";
  double pa[4] = {0, 0, 0, 0};
  const std::string words[4] = {"7e10", "70GPa", "70000MPa", "7e7kPa"};
  for (int i = 0; i < 4; ++i) {
    const CliRun r = run_cli(base + words[i]);
    ASSERT_EQ(r.code, 0) << words[i] << ": " << r.err;
    pa[i] = nlohmann::json::parse(r.out)["settings"]["block_modulus"].get<double>();
  }
  EXPECT_EQ(pa[0], 7e10);
  for (int i = 1; i < 4; ++i) EXPECT_EQ(pa[i], pa[0]) << words[i];
  const CliRun bad = run_cli(base + "70GN");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--block-modulus"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("Pa, kPa, MPa, GPa"), std::string::npos) << bad.err;
}
