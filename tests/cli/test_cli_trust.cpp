// The same surface, the same answer, however the file presents it: a rounded x column read as the
// uniform grid it is, units given on the command line over the file's, and a prediction that a
// warning calls doubtful says so first and names the option that fixes it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_runner.hpp"
#include "frictal/areal.hpp"
#include "frictal/conditioning.hpp"
#include "frictal/predict.hpp"
#include "frictal/signature.hpp"
#include "frictal/tilt.hpp"
#include "frictal/units.hpp"

using json = nlohmann::json;

namespace {

std::string data(const std::string& rel) { return std::string(FRICTAL_TEST_DATA) + "/" + rel; }

json predict_json(const std::string& args) {
  auto r = run_cli("predict " + args + " --json -q");
  EXPECT_EQ(r.code, 0) << args << "\n" << r.err;
  return r.code == 0 ? json::parse(r.out) : json::object();
}

std::set<std::string> codes_of(const json& j) {
  std::set<std::string> c;
  for (const auto& w : j["warnings"]) c.insert(w["code"].get<std::string>());
  return c;
}

// The x, z columns of the data rows of a text file (rows of two numbers after any header).
std::vector<std::pair<double, double>> two_columns(const std::string& path, char delim) {
  std::ifstream f(path);
  std::vector<std::pair<double, double>> rows;
  for (std::string line; std::getline(f, line);) {
    for (char& c : line)
      if (c == delim) c = ' ';
    std::istringstream ls(line);
    double x, z;
    if (ls >> x >> z) rows.push_back({x, z});
  }
  return rows;
}

// A clean self-affine profile of 2000 points over 1 mm (rms height 0.5 um), as the generator
// writes it: x and z in m, full precision.
std::vector<std::pair<double, double>> clean_profile() {
  const std::string f = temp_path("trust-clean-src.csv");
  EXPECT_EQ(run_cli("surface self-affine --points 2000 --length 1e-3 --rms-height 5e-7 --seed 7 -o " + f).code, 0);
  return two_columns(f, ',');
}

// Writes rows as "x_m,z_m" CSV, x times xs and z times zs, with 17 significant digits.
std::string write_rows(const std::string& name, const std::vector<std::pair<double, double>>& rows, double xs,
                       double zs, const std::set<std::size_t>& spikes = {}, double spike = 0) {
  const std::string path = temp_path(name);
  std::ofstream f(path);
  f << "x_m,z_m\n";
  char buf[96];
  for (std::size_t k = 0; k < rows.size(); ++k) {
    std::snprintf(buf, sizeof buf, "%.17g,%.17g\n", rows[k].first * xs,
                  (rows[k].second + (spikes.count(k) ? spike : 0.0)) * zs);
    f << buf;
  }
  return path;
}

// The option a doubtful prediction's fix names for `option` ("--z-unit um" -> "um").
std::string fix_value(const json& j, const std::string& option) {
  std::smatch m;
  const std::string fix = j["trust_fix"].get<std::string>();
  if (std::regex_search(fix, m, std::regex(option + " ([a-z]+)"))) return m[1];
  return "";
}

}  // namespace

TEST(CliTrust, RoundedDektakGridPredictsAsItsUniformGrid) {
  // dektak-1.csv prints x with one decimal: steps alternate 0.1 and 0.2 um for a sampling of
  // 1499.8 um / 9599. Second presentation: the same heights on the uniform grid of the header's
  // nominal sampling (1500 um / 9600 = 0.15625 um), x written with 17 digits.
  const auto rows = two_columns(data("profiles/dektak-1.csv"), ',');
  ASSERT_EQ(rows.size(), 9600u);
  std::vector<std::pair<double, double>> uniform;
  for (std::size_t k = 0; k < rows.size(); ++k) uniform.push_back({double(k) * 0.15625e-6, rows[k].second * 1e-6});
  const std::string u = write_rows("trust-dektak-uniform.csv", uniform, 1, 1);
  const json a = predict_json(data("profiles/dektak-1.csv"));
  const json b = predict_json(u);
  EXPECT_NEAR(a["friction_angle_deg"].get<double>(), b["friction_angle_deg"].get<double>(), 0.1);
  EXPECT_NEAR(a["upper_bound_friction_angle_deg"].get<double>(), b["upper_bound_friction_angle_deg"].get<double>(),
              0.1);
  EXPECT_EQ(a["trust"], "ok") << a.dump();
  bool note = false;
  for (const auto& w : a["warnings"])
    note = note || w["message"].get<std::string>().find("uniform grid") != std::string::npos;
  EXPECT_TRUE(note) << a.dump();
}

TEST(CliTrust, EightDigitExportGivesTheAnswerOfItsUniformGrid) {
  // opdx-3.txt: a profilometer's text export, x with 8 significant digits (spacing
  // 1.6655563e-08 m); predict, signature and report exited 2 on it ("lift curve offsets must
  // increase"). Second presentation: its heights on x = k * 1.6655563e-08 m at full precision.
  const auto rows = two_columns(data("instruments/opdx-3.txt"), ' ');
  ASSERT_EQ(rows.size(), 3001u);
  std::vector<std::pair<double, double>> uniform;
  for (std::size_t k = 0; k < rows.size(); ++k) uniform.push_back({double(k) * 1.6655563e-08, rows[k].second});
  const json a = predict_json(data("instruments/opdx-3.txt"));
  const json b = predict_json(write_rows("trust-opdx-uniform.csv", uniform, 1, 1));
  EXPECT_NEAR(a["friction_angle_deg"].get<double>(), b["friction_angle_deg"].get<double>(), 0.01);
  auto s = run_cli("signature " + data("instruments/opdx-3.txt") + " --json");
  EXPECT_EQ(s.code, 0) << s.err;
}

TEST(CliTrust, HeightsInMicrometresLabelledMetresAreDoubtfulAndTheNamedFixGivesTheCleanAnswer) {
  const auto rows = clean_profile();
  const json clean = predict_json(write_rows("trust-clean.csv", rows, 1, 1));
  EXPECT_EQ(clean["trust"], "ok") << clean.dump();
  const std::string wrong = write_rows("trust-z-um-as-m.csv", rows, 1, 1e6);
  const json d = predict_json(wrong);
  EXPECT_EQ(d["trust"], "doubtful");
  EXPECT_NE(d["trust_codes"].get<std::string>().find("units-suspect"), std::string::npos) << d.dump();
  const std::string unit = fix_value(d, "--z-unit");
  EXPECT_EQ(unit, "um") << d["trust_fix"];
  auto t = run_cli("predict " + wrong + " -q");
  EXPECT_EQ(t.out.rfind("DOUBTFUL", 0), 0u) << t.out;  // the text says it first
  EXPECT_NE(t.out.find("--z-unit um"), std::string::npos) << t.out;
  const json fixed = predict_json(wrong + " --z-unit " + unit);
  EXPECT_EQ(fixed["trust"], "ok") << fixed.dump();
  // The same surface: the clean file's answer (the heights scaled by 10^6 and back).
  EXPECT_NEAR(fixed["friction_angle_deg"].get<double>(), clean["friction_angle_deg"].get<double>(), 1e-6);
  EXPECT_TRUE(codes_of(fixed).count("reader"));  // the override is said
}

TEST(CliTrust, ThreeSpikesAreDoubtfulAndRemovingThemGivesTheCleanAnswerWithinItsSpread) {
  const auto rows = clean_profile();
  const json clean = predict_json(write_rows("trust-clean2.csv", rows, 1, 1));
  // Three points raised by 10 um (about 14 rms heights) in 2000.
  const std::string spiky = write_rows("trust-spikes.csv", rows, 1, 1, {400, 1100, 1700}, 1e-5);
  const json d = predict_json(spiky);
  EXPECT_EQ(d["trust"], "doubtful");
  EXPECT_NE(d["trust_codes"].get<std::string>().find("spikes"), std::string::npos) << d.dump();
  EXPECT_NE(d["trust_fix"].get<std::string>().find("--remove-spikes"), std::string::npos) << d.dump();
  const json fixed = predict_json(spiky + " --remove-spikes");
  EXPECT_EQ(fixed["trust"], "ok") << fixed.dump();
  EXPECT_EQ(fixed["spikes_removed"].get<double>(), 3);
  const double phi = fixed["friction_angle_deg"].get<double>();
  EXPECT_GE(phi, clean["friction_angle_q05_deg"].get<double>());
  EXPECT_LE(phi, clean["friction_angle_q95_deg"].get<double>());
}

TEST(CliTrust, LateralLengthsInMillimetresLabelledMetresAreWarnedAndTheFixGivesTheCleanAnswer) {
  const auto rows = clean_profile();
  const json clean = predict_json(write_rows("trust-clean3.csv", rows, 1, 1));
  const std::string wrong = write_rows("trust-x-mm-as-m.csv", rows, 1e3, 1);
  const json d = predict_json(wrong);
  EXPECT_TRUE(codes_of(d).count("lateral-suspect")) << d.dump();
  EXPECT_EQ(d["trust"], "doubtful");
  const std::string unit = fix_value(d, "--x-unit");
  EXPECT_EQ(unit, "mm") << d["trust_fix"];
  const json fixed = predict_json(wrong + " --x-unit " + unit);
  EXPECT_EQ(fixed["trust"], "ok") << fixed.dump();
  EXPECT_NEAR(fixed["friction_angle_deg"].get<double>(), clean["friction_angle_deg"].get<double>(), 1e-6);
}

TEST(CliTrust, UnitOptionsOverrideTheFilesUnitsWithANote) {
  // csv-2.csv names its columns "x in µm", "y in µm": --unit nm reads both in nm, 1000x smaller,
  // --z-unit alone the heights only.
  const std::string f = data("profiles/csv-2.csv");
  auto stats = [&](const std::string& opt) {
    auto r = run_cli("stats " + f + " --json " + opt);
    EXPECT_EQ(r.code, 0) << r.err;
    return r.code == 0 ? json::parse(r.out) : json::object();
  };
  const json a = stats(""), b = stats("--unit nm"), c = stats("--x-unit nm");
  EXPECT_NEAR(b["length_m"].get<double>(), a["length_m"].get<double>() * 1e-3, 1e-12 * a["length_m"].get<double>());
  EXPECT_NEAR(c["length_m"].get<double>(), a["length_m"].get<double>() * 1e-3, 1e-12 * a["length_m"].get<double>());
  bool note = false;
  for (const auto& w : b["warnings"])
    note = note || w["message"].get<std::string>().find("the z unit given") != std::string::npos;
  EXPECT_TRUE(note) << b.dump();
  auto bad = run_cli("predict " + f + " --z-unit furlong");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--z-unit"), std::string::npos) << bad.err;
}

TEST(CliTrust, EveryOptionAWarningNamesIsARealOption) {
  // The options the warnings table names (in a code's meaning and its fix) exist: the fixes of the
  // codes a prediction can carry are options of `frictal predict`, the others of some command.
  auto c = run_cli("commands --json");
  ASSERT_EQ(c.code, 0) << c.err;
  std::set<std::string> options, predict_options;
  std::function<void(const json&)> walk = [&](const json& cmd) {
    for (const auto& o : cmd["options"])
      for (const auto& n : o["names"]) {
        options.insert(n.get<std::string>());
        if (cmd["name"] == "predict") predict_options.insert(n.get<std::string>());
      }
    if (cmd.contains("subcommands"))
      for (const auto& sub : cmd["subcommands"]) walk(sub);
  };
  const json commands = json::parse(c.out);
  for (const auto& cmd : commands["commands"]) walk(cmd);
  ASSERT_TRUE(predict_options.count("--remove-spikes"));
  const json table = json::parse(run_cli("warnings --json").out);
  for (const auto& code : table) {
    const std::string fix = code["fix"].get<std::string>();
    const std::regex opt("--[a-z][a-z-]*[a-z]");
    for (auto it = std::sregex_iterator(fix.begin(), fix.end(), opt); it != std::sregex_iterator(); ++it)
      EXPECT_TRUE(predict_options.count(it->str())) << code["code"] << "'s fix names " << it->str();
  }
  auto w = run_cli("warnings --json");
  ASSERT_EQ(w.code, 0) << w.err;
  const std::regex option("--[a-z][a-z-]*[a-z]");
  std::size_t named = 0;
  for (const auto& code : json::parse(w.out)) {
    const std::string text = code["meaning"].get<std::string>() + " " + code["fix"].get<std::string>();
    for (auto it = std::sregex_iterator(text.begin(), text.end(), option); it != std::sregex_iterator(); ++it) {
      ++named;
      EXPECT_TRUE(options.count(it->str())) << code["code"] << " names " << it->str() << ", which no command has";
    }
    if (code["doubtful"].get<bool>()) {
      EXPECT_FALSE(code["fix"].get<std::string>().empty()) << code["code"];
    }
  }
  EXPECT_GE(named, 5u);
}

TEST(CliTrust, TheSharedInputsHaveOneHelpText) {
  // An input that several commands take is one option: the same description wherever it appears
  // (`frictal commands --json`), so that a user reads one meaning, one default, one unit.
  auto c = run_cli("commands --json");
  ASSERT_EQ(c.code, 0) << c.err;
  std::map<std::string, std::map<std::string, std::vector<std::string>>> texts;  // option -> text -> commands
  std::function<void(const json&, const std::string&)> walk = [&](const json& cmd, const std::string& path) {
    const std::string here = path + " " + cmd["name"].get<std::string>();
    for (const auto& o : cmd["options"]) texts[o["name"].get<std::string>()][o["description"]].push_back(here);
    if (cmd.contains("subcommands"))
      for (const auto& sub : cmd["subcommands"]) walk(sub, here);
  };
  const json listing = json::parse(c.out);
  for (const auto& cmd : listing["commands"]) walk(cmd, "frictal");
  for (const char* name : {"--detrend", "--crop", "--remove-spikes", "--spike-threshold", "--atomic-friction",
                           "--runaway-distance", "--period", "--unit", "--drops", "--locked", "--block-length",
                           "--in-place", "--contact-slope", "--spheroradius"}) {
    ASSERT_TRUE(texts.count(name)) << name;
    std::size_t commands = 0;
    for (const auto& [text, where] : texts[name]) commands += where.size();
    EXPECT_GE(commands, 2u) << name;
    EXPECT_EQ(texts[name].size(), 1u) << name << " has " << texts[name].size() << " descriptions, e.g. in "
                                      << texts[name].begin()->second.front() << " and "
                                      << texts[name].rbegin()->second.front();
  }
}

TEST(CliTrust, PredictsOptionsAreItsSettingsTablesPlusAStatedList) {
  // `frictal predict` offers the fields of predict_settings() and conditioning_settings(), each
  // option named after its field and described by the table (help, unit, default, range), and
  // besides them only the options that are no setting of the prediction: the one drop (a point),
  // friction under load (forces with their unit, lists, "rigid"), the reading of the files and
  // the run options.
  const std::set<std::string> cli_only = {"--start-offset",  "--quiet",        "--threads", "--json",     "--format",
                                          "--unit",          "--x-unit",       "--z-unit",  "--x-column", "--z-column",
                                          "--spacing",       "--channel",      "--load",    "--modulus",  "--poisson",
                                          "--upper-modulus", "--upper-poisson"};
  auto c = run_cli("commands --json");
  ASSERT_EQ(c.code, 0) << c.err;
  std::map<std::string, std::string> options;  // option -> description
  const json listing = json::parse(c.out);
  for (const auto& cmd : listing["commands"])
    if (cmd["name"] == "predict")
      for (const auto& o : cmd["options"])
        if (!o["positional"].get<bool>()) options[o["name"].get<std::string>()] = o["description"];
  ASSERT_FALSE(options.empty());
  std::set<std::string> expected = cli_only;
  std::vector<frictal::Field> fields = frictal::predict_settings();
  for (const frictal::Field& f : frictal::conditioning_settings()) fields.push_back(f);
  EXPECT_EQ(fields.size(), 14u);
  for (const frictal::Field& f : fields) {
    std::string option = "--" + f.name;
    std::replace(option.begin(), option.end(), '_', '-');
    // The table's line: help [unit] (default D; valid R), angles in degrees at the CLI; a number
    // without bounds states no range.
    const std::string unit = f.unit == "rad" ? "deg" : f.unit;
    const std::string range = frictal::range_text(f);
    const std::string help = f.help + (unit.empty() ? "" : " [" + unit + "]") + " (default " +
                             frictal::default_text(f) + (range.rfind("any", 0) == 0 ? "" : "; valid " + range) + ")";
    ASSERT_TRUE(options.count(option)) << option;
    EXPECT_EQ(options[option], help) << option;
    expected.insert(option);
    if (f.type == frictal::FieldType::Boolean) {
      expected.insert("--no-" + option.substr(2));
      EXPECT_EQ(options["--no-" + option.substr(2)], "Opposite of " + option);
    }
  }
  std::set<std::string> listed;
  for (const auto& [name, text] : options) listed.insert(name);
  EXPECT_EQ(listed, expected);
}

TEST(CliTrust, ABadPredictSettingNamesTheOptionAndItsRange) {
  const std::string f = data("profiles/csv-2.csv");
  struct Case {
    std::string args, says;
  };
  const Case cases[] = {
      {"--drops 1", "--drops: expected a whole number in 2..64, got 1"},
      {"--drops 2.5", "--drops: expected a whole number in 2..64, got '2.5'"},
      {"--block-length -1mm", "--block-length: expected a number > 0 m or whole, got -0.001"},
      {"--block-length part", "--block-length: expected a number > 0 m or whole (a unit may follow"},
      {"--direction east", "--direction: expected a finite number, in deg, got 'east'"},
      {"--runaway-distance 0", "--runaway-distance: expected a number > 0 m, got 0"},
      {"--atomic-friction -0.1", "--atomic-friction: expected a number >= 0, got -0.1"},
      {"--map-work-limit -1", "--map-work-limit: expected a number >= 0 s, got -1"},
  };
  for (const Case& c : cases) {
    const CliRun r = run_cli("predict " + f + " -q " + c.args);
    EXPECT_EQ(r.code, 2) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << ": " << r.err;
  }
}

namespace {

// The options of one command in `frictal commands --json` (option -> description), positionals left out.
std::map<std::string, std::string> options_of(const std::string& command) {
  auto c = run_cli("commands --json");
  EXPECT_EQ(c.code, 0) << c.err;
  std::map<std::string, std::string> options;
  const json listing = json::parse(c.out);
  for (const auto& cmd : listing["commands"])
    if (cmd["name"] == command)
      for (const auto& o : cmd["options"])
        if (!o["positional"].get<bool>()) options[o["name"].get<std::string>()] = o["description"];
  return options;
}

// A command's options are the fields of `fields` (each named after its field, described by the
// table: help [unit] (default D; valid R), angles in degrees; a Boolean with its --no- form) and
// `cli_only`, nothing else.
void expect_options_are_fields(const std::string& command, const std::vector<frictal::Field>& fields,
                               const std::set<std::string>& cli_only) {
  std::map<std::string, std::string> options = options_of(command);
  ASSERT_FALSE(options.empty()) << command;
  std::set<std::string> expected = cli_only;
  for (const frictal::Field& f : fields) {
    std::string option = "--" + f.name;
    std::replace(option.begin(), option.end(), '_', '-');
    const std::string unit = f.unit == "rad" ? "deg" : f.unit;
    const std::string range = frictal::range_text(f);
    const std::string help = f.help + (unit.empty() ? "" : " [" + unit + "]") + " (default " +
                             frictal::default_text(f) + (range.rfind("any", 0) == 0 ? "" : "; valid " + range) + ")";
    ASSERT_TRUE(options.count(option)) << command << " " << option;
    EXPECT_EQ(options[option], help) << command << " " << option;
    expected.insert(option);
    if (f.type == frictal::FieldType::Boolean) {
      expected.insert("--no-" + option.substr(2));
      EXPECT_EQ(options["--no-" + option.substr(2)], "Opposite of " + option) << command;
    }
  }
  std::set<std::string> listed;
  for (const auto& [name, text] : options) listed.insert(name);
  EXPECT_EQ(listed, expected) << command;
}

// The fields `names` of a table.
std::vector<frictal::Field> fields_named(const std::vector<frictal::Field>& table, const std::set<std::string>& names) {
  std::vector<frictal::Field> out;
  for (const frictal::Field& f : table)
    if (names.count(f.name)) out.push_back(f);
  EXPECT_EQ(out.size(), names.size());
  return out;
}

const std::set<std::string> kReading = {"--format",   "--unit",     "--x-unit",  "--z-unit",
                                        "--x-column", "--z-column", "--spacing", "--channel"};

std::set<std::string> with_reading(std::set<std::string> s) {
  s.insert(kReading.begin(), kReading.end());
  return s;
}

void expect_refused(const std::string& args, const std::string& says) {
  const CliRun r = run_cli(args);
  EXPECT_EQ(r.code, 2) << args << ": " << r.err;
  EXPECT_NE(r.err.find(says), std::string::npos) << args << ": " << r.err;
}

}  // namespace

TEST(CliTrust, SignaturesOptionsAreItsSettingsTablePlusAStatedList) {
  // `frictal signature` offers signature_settings() and conditioning_settings(); the hold analysis
  // it runs on the same lift takes the quantities shared with the tilt test and the prediction
  // (atomic friction, run-away distance, period: one field each); besides them only the one drop,
  // the outputs, the reading of the files and the run options.
  std::vector<frictal::Field> fields = frictal::signature_settings();
  for (const frictal::Field& f : frictal::conditioning_settings()) fields.push_back(f);
  for (const frictal::Field& f :
       fields_named(frictal::tilt_settings(), {"atomic_friction", "runaway_distance", "period"}))
    fields.push_back(f);
  EXPECT_EQ(frictal::signature_settings().size(), 7u);
  expect_options_are_fields(
      "signature", fields,
      with_reading({"--start-offset", "--no-hold", "--threads", "--json", "--output", "--contacts", "--pdf"}));
}

TEST(CliTrust, ArealAndAnisotropysOptionsAreTheirSettingsTablesPlusAStatedList) {
  // `frictal areal`: areal_signature_settings(), the conditioning, and for the hold angle beside
  // the signature the prediction's drops and the shared run-away distance, its mode (--lateral)
  // and one drop (--start-offset); `frictal anisotropy`: anisotropy_settings(), the conditioning,
  // and for the hold angle per direction the prediction's drops and locked, the run-away distance.
  std::vector<frictal::Field> areal = frictal::areal_signature_settings();
  std::vector<frictal::Field> aniso = frictal::anisotropy_settings();
  for (const frictal::Field& f : frictal::conditioning_settings()) areal.push_back(f), aniso.push_back(f);
  areal.push_back(*frictal::find_field(frictal::predict_settings(), "drops"));
  areal.push_back(*frictal::shared_field("runaway_distance"));
  for (const frictal::Field& f : fields_named(frictal::predict_settings(), {"drops", "locked"})) aniso.push_back(f);
  aniso.push_back(*frictal::shared_field("runaway_distance"));
  expect_options_are_fields(
      "areal", areal, with_reading({"--lateral", "--start-offset", "--output", "--threads", "--quiet", "--json"}));
  expect_options_are_fields("anisotropy", aniso, with_reading({"--upper", "--hold", "--threads", "--quiet", "--json"}));
  // The quantities the prediction shares are its fields: one text in predict and areal.
  const auto predict = options_of("predict"), areal_options = options_of("areal");
  for (const char* o : {"--direction", "--in-place", "--atomic-friction"})
    EXPECT_EQ(areal_options.at(o), predict.at(o)) << o;
}

TEST(CliTrust, ABadSignatureArealOrAnisotropySettingNamesTheOptionAndItsRange) {
  const std::string f = data("profiles/csv-2.csv");
  const std::string m = data("x3p/pyramid.x3p");
  expect_refused("signature " + f + " --bins 0", "--bins: expected a whole number in 1..100000, got 0");
  expect_refused("signature " + f + " --offsets -1", "--offsets: expected a whole number in 0..100000000, got -1");
  expect_refused("signature " + f + " --slopes splin", "--slopes: expected exact or spline, got \"splin\"");
  expect_refused("signature " + f + " --spheroradius -1um", "--spheroradius: expected a number > 0 m, got -1e-06");
  expect_refused("signature " + f + " --offset-range 1 0", "--offset-range '1 0': expected MIN MAX");
  expect_refused("signature " + f + " --offset-range 0 far", "--offset-range '0 far': 'far' is not a length");
  expect_refused("signature " + f + " --spheroradius 1um --slopes spline", "use --slopes exact");
  expect_refused("areal " + m + " --step 0", "--step: expected a number > 0 m, got 0");
  expect_refused("areal " + m + " --max-offset -1", "--max-offset: expected a number > 0 m, got -1");
  expect_refused("areal " + m + " --contact-slope max", "--contact-slope: expected lower or mean, got \"max\"");
  expect_refused("areal " + m + " --atomic-friction -0.1", "--atomic-friction: expected a number >= 0, got -0.1");
  expect_refused("areal " + m + " --direction inf", "--direction: expected a finite number, in deg, got inf");
  expect_refused("areal " + m + " --lateral free --step 1e-6", "--step: the hold angle");
  expect_refused("anisotropy " + m + " --directions 0", "--directions: expected a whole number in 1..3600, got 0");
  expect_refused("anisotropy " + m + " --lines 0", "--lines: expected a whole number in 1..100000, got 0");
  expect_refused("anisotropy " + m + " --contact-slope mean", "--contact-slope: the contact slope of the grid");
  // Stated values reach the signature: N offsets from MIN to MAX (a length with its unit), that grid
  // kept (--keep-grid) where the aligned grids' every event would cost less.
  auto r = run_cli("signature " + f + " --offsets 5 --keep-grid --offset-range 0 0.1um --no-hold --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["offsets"].get<double>(), 5) << j.dump();
  EXPECT_FALSE(j["grid_replaced"].get<bool>()) << j.dump();
  EXPECT_EQ(j["offset_range_m"][0].get<double>(), 0.0) << j.dump();
  EXPECT_DOUBLE_EQ(j["offset_range_m"][1].get<double>(), 1e-7) << j.dump();
}

TEST(CliTrust, ArealsDirectionKeepsEveryBitOfTheDegreesItAlwaysRead) {
  // `frictal areal --direction DEG` has always read DEG as CLI11 reads a number (strtold, then
  // rounded to double) and sent DEG * pi/180 to the signature. The table's own reading (from_chars,
  // rounded once) differs from it in the last bit for about 1 in 10^4 random angles of 1 to 20
  // digits, such as these; the radians the signature gets (its direction_deg, converted back) are
  // the old ones.
  const std::string m = data("x3p/pyramid.x3p");
  for (const char* deg : {"-409.214118662093", "-341.22738923", "423.8517967489", "706.276187934088"}) {
    const double old_rad = static_cast<double>(std::strtold(deg, nullptr)) * frictal::units::kRadPerDeg;
    const double once_rad = std::strtod(deg, nullptr) * frictal::units::kRadPerDeg;
    // A case where the two readings differ, in the radians and in the degrees the JSON shows.
    EXPECT_NE(old_rad, once_rad) << deg;
    EXPECT_NE(frictal::units::to_deg(old_rad), frictal::units::to_deg(once_rad)) << deg;
    auto r = run_cli(std::string("areal ") + m + " --direction " + deg + " --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const double shown = json::parse(r.out)["direction_deg"].get<double>();
    EXPECT_EQ(shown, frictal::units::to_deg(old_rad)) << deg;
  }
}
