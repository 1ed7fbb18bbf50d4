// frictal CLI — options derived from the settings tables (options.hpp).
#include "options.hpp"

#include <algorithm>
#include <map>

#include "frictal/tilt.hpp"

namespace frictal::cli {

std::string field_help(const Field& f) {
  std::string s = f.help;
  const std::string u = text_unit(f);
  if (!u.empty()) s += " [" + u + "]";
  // A number without bounds has no valid range worth a word (its unit is in the brackets).
  const std::string range = range_text(f);
  if (range.rfind("any", 0) == 0) return s + " (default " + default_text(f) + ")";
  return s + " (default " + default_text(f) + "; valid " + range + ")";
}

namespace {
/// The value's forms of a word field that follows forms (Field::check_word): "X0,X1|X0,X1,Y0,Y1".
std::string choice_forms(const Field& f) {
  std::string s;
  for (const std::string& c : f.choices) s += (s.empty() ? "" : "|") + c;
  return s.empty() ? "WORD" : s;
}
/// First names shown in the help and in errors: the name every command gives the quantity
/// (`predict --direction`) where the settings table keeps its own (`angle`, the key of study
/// files and the field's option, still accepted).
const std::map<std::string, std::string> kFirstNames = {{"angle", "--direction"}};
}  // namespace

std::string shown_option_name(const Field& f) {
  auto it = kFirstNames.find(f.name);
  return it != kFirstNames.end() ? it->second : cli_option_name(f);
}

void add_field_options(CLI::App& app, const std::vector<Field>& fields, FieldWords& words,
                       const std::vector<std::string>& skip) {
  for (const Field& f : fields) {
    if (std::find(skip.begin(), skip.end(), f.name) != skip.end()) continue;
    const std::string name = cli_option_name(f);
    std::string flags = f.short_name ? fmt::format("-{},{}", f.short_name, name) : name;
    if (auto it = kFirstNames.find(f.name); it != kFirstNames.end()) flags = it->second + "," + flags;
    const std::string key = f.name;
    if (f.type == FieldType::Boolean) {
      const std::string no = "--no-" + name.substr(2);
      app.add_flag_callback(
          flags, [&words, key] { words.words[key] = "true"; }, field_help(f));
      app.add_flag_callback(
          no, [&words, key] { words.words[key] = "false"; }, "Opposite of " + name);
    } else {
      app.add_option_function<std::string>(
             flags, [&words, key](const std::string& w) { words.words[key] = w; }, field_help(f))
          ->type_name(f.type == FieldType::Choice ? (f.check_word ? choice_forms(f) : std::string("WORD"))
                                                  : (f.type == FieldType::Integer ? "INT" : "NUMBER"));
    }
    // Retired option names still read on the command line (scripts written before the rename),
    // hidden from the help so that each quantity shows one name.
    static const std::map<std::string, std::string> retired = {{"spheroradius", "--radius"}};
    if (auto it = retired.find(f.name); it != retired.end())
      app.add_option_function<std::string>(
             it->second, [&words, key](const std::string& w) { words.words[key] = w; }, "Retired name of " + name)
          ->group("");
  }
}

std::vector<std::string> all_but(const std::vector<Field>& fields, const std::string& keep) {
  std::vector<std::string> n;
  for (const Field& f : fields)
    if (f.name != keep) n.push_back(f.name);
  return n;
}

ValueSet si_values(const std::vector<Field>& fields, const FieldWords& words) {
  ValueSet v;
  for (const auto& [name, word] : words.words) {
    const Field* f = find_field(fields, name);
    if (!f) continue;
    const std::string option = shown_option_name(*f);
    FieldValue text = unwrap(parse_text_word(*f, word, option));
    v[name] = unwrap(si_from_text(*f, text, option));
  }
  return v;
}

std::optional<SurfaceSpec> GeneratorOptions::spec() const {
  for (const auto& [name, sub] : subcommands) {
    if (!sub->parsed()) continue;
    const GeneratorInfo* g = find_generator(name);
    return unwrap(make_surface_spec(name, si_values(g->fields, *words.at(name))));
  }
  return std::nullopt;
}

void add_generator_subcommands(CLI::App& app, GeneratorOptions& g, bool fallthrough, const std::string& what) {
  for (const GeneratorInfo& info : surface_generators()) {
    CLI::App* sub = app.add_subcommand(info.name, info.description + what);
    auto w = std::make_shared<FieldWords>();
    add_field_options(*sub, info.fields, *w);
    if (fallthrough) sub->fallthrough();
    g.subcommands[info.name] = sub;
    g.words[info.name] = w;
  }
}

void add_atomic_friction_option(CLI::App& app, double& mu_a) {
  const Field* f = find_field(tilt_settings(), "atomic_friction");
  app.add_option(cli_option_name(*f), mu_a, field_help(*f))->type_name("NUMBER");  // as the tables' numbers
}

/// "X,Y" in metres.
std::array<double, 2> parse_offset(const std::string& text, const std::string& option) {
  const auto comma = text.find(',');
  std::array<double, 2> v{};
  bool ok = comma != std::string::npos;
  for (int k = 0; ok && k < 2; ++k) {
    const std::string part = k == 0 ? text.substr(0, comma) : text.substr(comma + 1);
    std::size_t used = 0;
    try {
      v[k] = std::stod(part, &used);
    } catch (const std::exception&) {
      ok = false;
    }
    ok = ok && used == part.size() && std::isfinite(v[k]);
  }
  require(ok, fmt::format("{} '{}': expected X,Y, two finite numbers of metres", option, text));
  return v;
}

}  // namespace frictal::cli
