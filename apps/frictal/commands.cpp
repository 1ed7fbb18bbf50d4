// frictal commands --json — every command, subcommand and option of this CLI as one JSON object,
// walked from the command tree that main() built out of the command registry, with each option
// that comes from a settings table tied to its field (unit, default, range). The documentation
// site's CLI reference is generated from it (scripts/docs/gen_reference.py), so no option's text
// is ever copied by hand.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "frictal/areal.hpp"
#include "frictal/conditioning.hpp"
#include "frictal/predict.hpp"
#include "frictal/signature.hpp"
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
  // After the tilt test's: a quantity both tables share (shared_field) lists the tilt test's field.
  for (const Field& f : predict_settings()) out.push_back({&f, field_help(f)});
  for (const Field& f : conditioning_settings()) out.push_back({&f, field_help(f)});
  for (const Field& f : signature_settings()) out.push_back({&f, field_help(f)});
  for (const Field& f : areal_signature_settings()) out.push_back({&f, field_help(f)});
  for (const Field& f : anisotropy_settings()) out.push_back({&f, field_help(f)});
  return out;
}

/// One option as the listing gives it.
struct OptionListing {
  std::string name;
  std::vector<std::string> names;  ///< every name it is given by ("-o", "--output"); a positional: its name
  bool positional = false, flag = false, required = false;
  std::string value, default_text, description, group;
  const Field* field = nullptr;  ///< the settings field it comes from, if any
};
/// One command (or subcommand) as the listing gives it.
struct CommandListing {
  std::string name, path, description, help;
  std::vector<OptionListing> options;
  bool fallthrough = false, needs_subcommand = false;
  std::vector<CommandListing> subcommands;
};
/// The whole CLI.
struct ProgramListing {
  std::string program, description;
  std::vector<CommandListing> commands;
};

// The listing's own output tables: `frictal commands --json` is written from them.
const Columns<Field>& option_field_columns() {
  // The settings field's columns that an option lists (its option and type are the option's own).
  static const Columns<Field> cols = [] {
    Columns<Field> c;
    for (const Column<Field>& f : settings_field_columns())
      if (f.key != "option" && f.key != "type") c.push_back(f);
    return c;
  }();
  return cols;
}

const Columns<OptionListing>& option_listing_columns() {
  using T = OptionListing;
  static const Columns<T> cols = {
      column<T>(
          "name", "text", "the option's name", [](const T& o) { return o.name; }, "-"),
      column<T>(
          "names", "text", "every name it is given by (a positional: its name)", [](const T& o) { return o.names; },
          "-"),
      column<T>(
          "positional", "flag", "a positional argument", [](const T& o) { return o.positional; }, "-"),
      column<T>(
          "flag", "flag", "takes no value", [](const T& o) { return o.flag; }, "-"),
      column<T>(
          "required", "flag", "must be given", [](const T& o) { return o.required; }, "-"),
      column<T>(
          "value", "text", "the kind of value it takes (NUMBER, TEXT, ...)", [](const T& o) { return o.value; }, "-"),
      column<T>(
          "default", "text", "the default as the help shows it", [](const T& o) { return o.default_text; }, "-"),
      column<T>(
          "description", "text", "its help line", [](const T& o) { return o.description; }, "-"),
      column<T>(
          "group", "text", "its group in the help", [](const T& o) { return o.group; }, "-"),
      only_if(object_column<T>(
                  "field", "settings_field", "the settings field it comes from (null: none)", option_field_columns(),
                  [](const T& o) { return o.field ? std::optional<Field>(*o.field) : std::nullopt; }, "-"),
              [](const T&) { return true; }),
  };
  return cols;
}

const Columns<CommandListing>& command_listing_columns() {
  using T = CommandListing;
  static const Columns<T> cols = {
      column<T>(
          "name", "text", "the command's name", [](const T& c) { return c.name; }, "-"),
      column<T>(
          "path", "text", "how it is called (frictal ...)", [](const T& c) { return c.path; }, "-"),
      column<T>(
          "description", "text", "one line", [](const T& c) { return c.description; }, "-"),
      list_column<T>(
          "options", "command_option", "its options", option_listing_columns(),
          [](const T& c) { return std::optional(c.options); }, "-"),
      column<T>(
          "fallthrough", "flag", "options of its parent are read after it", [](const T& c) { return c.fallthrough; },
          "-"),
      column<T>(
          "needs_subcommand", "flag", "a subcommand must be given", [](const T& c) { return c.needs_subcommand; }, "-"),
      column<T>(
          "help", "text", "its help page", [](const T& c) { return c.help; }, "-"),
      list_column<T>(
          "subcommands", "command_listing", "its subcommands, each listed as a command", cols,
          [](const T& c) { return std::optional(c.subcommands); }, "-"),
  };
  return cols;
}

const Columns<ProgramListing>& program_listing_columns() {
  using T = ProgramListing;
  static const Columns<T> cols = {
      column<T>(
          "program", "text", "the program's name", [](const T& p) { return p.program; }, "-"),
      column<T>(
          "description", "text", "what it does", [](const T& p) { return p.description; }, "-"),
      list_column<T>(
          "commands", "command_listing", "every command", command_listing_columns(),
          [](const T& p) { return std::optional(p.commands); }, "-"),
  };
  return cols;
}

OptionListing option_listing(const CLI::Option& o, const std::vector<KnownField>& fields) {
  OptionListing l;
  l.name = o.get_name();
  if (o.get_positional()) {
    l.names = {o.get_name()};
  } else {
    for (const std::string& s : o.get_snames()) l.names.push_back("-" + s);
    for (const std::string& n : o.get_lnames()) l.names.push_back("--" + n);
  }
  l.positional = o.get_positional();
  l.flag = o.get_items_expected_max() == 0;
  l.required = o.get_required();
  l.value = o.get_type_name();
  l.default_text = o.get_default_str();
  l.description = o.get_description();
  l.group = o.get_group();
  for (const KnownField& k : fields)
    if (k.help_line == o.get_description()) {
      l.field = k.field;
      break;
    }
  return l;
}

CommandListing command_listing(CLI::App& app, const std::string& path, const std::vector<KnownField>& fields) {
  CommandListing c;
  c.name = app.get_name();
  c.path = path;
  c.description = app.get_description();
  const CLI::Option* help = app.get_help_ptr();
  for (const CLI::Option* o : app.get_options()) {
    // Hidden options (retired names still read, group "") and -h/--help are not documented.
    if (o == help || o->get_group().empty()) continue;
    c.options.push_back(option_listing(*o, fields));
  }
  c.fallthrough = app.get_fallthrough();
  c.needs_subcommand = app.get_require_subcommand_min() > 0;
  c.help = app.help();
  for (CLI::App* s : app.get_subcommands([](CLI::App*) { return true; })) {
    if (s->get_group().empty()) continue;
    c.subcommands.push_back(command_listing(*s, path + " " + s->get_name(), fields));
  }
  return c;
}

std::function<int()> setup(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  app.add_flag("--json", *json, "Print every command, subcommand and option as one JSON object (the docs' reference)");
  return [&app, json]() {
    CLI::App* root = &app;
    while (root->get_parent()) root = root->get_parent();
    const std::vector<KnownField> fields = known_fields();
    if (*json) {
      ProgramListing p{"frictal", root->get_description(), {}};
      for (CLI::App* s : root->get_subcommands([](CLI::App*) { return true; }))
        p.commands.push_back(command_listing(*s, "frictal " + s->get_name(), fields));
      print_json(object_of(program_listing_columns(), p));
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
