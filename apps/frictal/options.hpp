// frictal CLI — options derived from the library's settings tables (frictal/settings.hpp):
// one option per field, named "--" + the field's name in kebab-case, with the field's unit,
// default, range and help; and the generator subcommands (koch, wm, sawtooth, sine,
// self-affine) that every command building a surface takes, from frictal/surface_spec.hpp.
#pragma once

#include <array>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common.hpp"
#include "frictal/settings.hpp"
#include "frictal/surface_spec.hpp"

namespace frictal::cli {

/// The help line of a field: help, unit, default and valid range (identical in every command).
std::string field_help(const Field& f);

/// The option name a field shows in the help, in errors and in docs/settings.md: its own
/// (`cli_option_name`) but where every command calls the quantity otherwise (`angle`:
/// `--direction`, as `predict`); the field's own name is then read as well.
std::string shown_option_name(const Field& f);

/// Words typed for the fields of one table, by field name (converted after parsing).
struct FieldWords {
  std::map<std::string, std::string> words;
};

/// Adds one option per field to `app` ("--name VALUE"; Boolean: "--name" / "--no-name"),
/// recording what was typed in `words`. `skip` names fields not offered here.
void add_field_options(CLI::App& app, const std::vector<Field>& fields, FieldWords& words,
                       const std::vector<std::string>& skip = {});

/// The names of every field but `keep` (for offering one field of a table).
std::vector<std::string> all_but(const std::vector<Field>& fields, const std::string& keep);

/// The typed values, converted to SI (degrees -> radians through the table's unit) and checked;
/// a bad value is a UsageError naming the option.
ValueSet si_values(const std::vector<Field>& fields, const FieldWords& words);

/// The generator subcommands of a command.
struct GeneratorOptions {
  std::map<std::string, CLI::App*> subcommands;              ///< by generator name
  std::map<std::string, std::shared_ptr<FieldWords>> words;  ///< by generator name
  /// The specification of the generator subcommand given, if any (UsageError on bad values).
  std::optional<SurfaceSpec> spec() const;
};

/// Adds one subcommand per generator to `app`, each with the generator's options. With
/// `fallthrough`, options of `app` itself are still accepted after the generator's name
/// (`frictal tilt koch --alpha 20 --json`). `what` completes the subcommands' descriptions.
void add_generator_subcommands(CLI::App& app, GeneratorOptions& g, bool fallthrough, const std::string& what);

/// `--atomic-friction`, the field of the tilt settings table, for the commands that predict
/// friction without the tilt test (signature, areal, anisotropy).
void add_atomic_friction_option(CLI::App& app, double& mu_a);

/// "X,Y" in metres; a bad text is a UsageError naming `option`.
std::array<double, 2> parse_offset(const std::string& text, const std::string& option);

}  // namespace frictal::cli
