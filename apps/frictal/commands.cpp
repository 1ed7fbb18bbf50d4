// frictal commands --json — every command, subcommand and option of this CLI as one JSON object,
// walked from the command tree that main() built out of the command registry, with each option
// that comes from a settings table tied to its field (unit, default, range). The documentation
// site's CLI reference is generated from it (scripts/docs/gen_reference.py), so no option's text
// is ever copied by hand.
#include <memory>
#include <string>
#include <vector>

#include "frictal/tilt.hpp"
#include "options.hpp"

namespace frictal::cli {
namespace {

/// Every table field a CLI option can come from, with the help line the option carries.
struct KnownField {
  const Field* field;
  std::string help_line;
};

std::vector<KnownField> known_fields() {
  std::vector<KnownField> out;
  for (const GeneratorInfo& g : surface_generators())
    for (const Field& f : g.fields) out.push_back({&f, field_help(f)});
  for (const Field& f : tilt_settings()) out.push_back({&f, field_help(f)});
  return out;
}

nlohmann::json option_json(const CLI::Option& o, const std::vector<KnownField>& fields) {
  nlohmann::json names = nlohmann::json::array();
  for (const std::string& s : o.get_snames()) names.push_back("-" + s);
  for (const std::string& l : o.get_lnames()) names.push_back("--" + l);
  nlohmann::json j = {{"name", o.get_name()},
                      {"names", names},
                      {"positional", o.get_positional()},
                      {"flag", o.get_items_expected_max() == 0},
                      {"required", o.get_required()},
                      {"value", o.get_type_name()},
                      {"default", o.get_default_str()},
                      {"description", o.get_description()},
                      {"group", o.get_group()},
                      {"field", nullptr}};
  if (o.get_positional()) j["names"] = nlohmann::json::array({o.get_name()});
  for (const KnownField& k : fields) {
    if (k.help_line != o.get_description()) continue;
    const Field& f = *k.field;
    j["field"] = {{"name", f.name},         {"unit", text_unit(f)}, {"si_unit", f.unit}, {"default", default_text(f)},
                  {"range", range_text(f)}, {"help", f.help}};
    break;
  }
  return j;
}

nlohmann::json command_json(CLI::App& app, const std::string& path, const std::vector<KnownField>& fields) {
  nlohmann::json options = nlohmann::json::array();
  const CLI::Option* help = app.get_help_ptr();
  for (const CLI::Option* o : app.get_options()) {
    // Hidden options (retired names still read, group "") and -h/--help are not documented.
    if (o == help || o->get_group().empty()) continue;
    options.push_back(option_json(*o, fields));
  }
  nlohmann::json subs = nlohmann::json::array();
  for (CLI::App* s : app.get_subcommands([](CLI::App*) { return true; })) {
    if (s->get_group().empty()) continue;
    subs.push_back(command_json(*s, path + " " + s->get_name(), fields));
  }
  return {{"name", app.get_name()},
          {"path", path},
          {"description", app.get_description()},
          {"options", options},
          {"fallthrough", app.get_fallthrough()},
          {"needs_subcommand", app.get_require_subcommand_min() > 0},
          {"help", app.help()},
          {"subcommands", subs}};
}

std::function<int()> setup(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  app.add_flag("--json", *json, "Print every command, subcommand and option as one JSON object (the docs' reference)");
  return [&app, json]() {
    CLI::App* root = &app;
    while (root->get_parent()) root = root->get_parent();
    const std::vector<KnownField> fields = known_fields();
    if (*json) {
      nlohmann::json commands = nlohmann::json::array();
      for (CLI::App* s : root->get_subcommands([](CLI::App*) { return true; }))
        commands.push_back(command_json(*s, "frictal " + s->get_name(), fields));
      print_json({{"program", "frictal"}, {"description", root->get_description()}, {"commands", commands}});
    } else {
      for (CLI::App* s : root->get_subcommands([](CLI::App*) { return true; }))
        fmt::print("  {:<12} {}\n", s->get_name(), s->get_description());
    }
    return 0;
  };
}

FRICTAL_COMMAND({"commands", "Every command and option (--json: the reference the documentation is generated from)",
                 setup, 95});

}  // namespace
}  // namespace frictal::cli
