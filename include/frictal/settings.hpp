// frictal — settings tables: each group of settings (a surface generator's parameters, the tilt
// test's configuration) is declared once as a table of fields (name, unit, default, valid range,
// help). The CLI options, the study TOML keys, the Python keywords, the JSON keys and the
// reference table in docs/settings.md are all derived from these tables, so a quantity has one
// name everywhere:
//   TOML key, Python keyword, JSON key:  the field's name (snake_case), e.g. rise_angle
//   CLI option:                          "--" + the name with '_' -> '-', e.g. --rise-angle
// Units: the library and Python use SI (angles in radians). The text interfaces (CLI options,
// TOML files, JSON printed by the CLI) give angles in degrees; to_text_unit()/from_text_unit()
// are the one place where that conversion happens, driven by the field's unit.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "frictal/outputs.hpp"
#include "frictal/result.hpp"

namespace frictal {

enum class FieldType {
  Real,     ///< a number
  Integer,  ///< a whole number
  Boolean,  ///< true/false (CLI: --name / --no-name)
  Choice,   ///< one word of `choices` (or of their forms: Field::check_word)
};

/// One setting.
struct Field {
  std::string name;  ///< the one name: TOML/Python/JSON key; CLI option "--" + kebab-case
  FieldType type = FieldType::Real;
  std::string unit;  ///< SI unit of the library value: "m", "rad", "s", "N/m", "1/s", ... ("" unitless)
  /// Default in SI (Boolean: 0/1; Choice: index into `choices`). NaN: "automatic", see `help`.
  double default_value = 0;
  double min = -std::numeric_limits<double>::infinity();  ///< smallest valid value (SI)
  double max = std::numeric_limits<double>::infinity();   ///< largest valid value (SI)
  bool min_open = false;                                  ///< min itself is invalid
  bool max_open = false;                                  ///< max itself is invalid
  std::vector<std::string> choices;                       ///< words of a Choice
  std::string help;                                       ///< one line, without the unit (derived from `unit`)
  char short_name = 0;                                    ///< optional one-letter CLI form (-n), the same option
  /// The default at the text interfaces (CLI, TOML) when it comes from the surface rather than
  /// from `default_value` (e.g. "the surface's period"); "" when `default_value` applies.
  std::string text_default;
  /// A Choice whose words follow a form rather than a fixed list (a crop window "X0,X1", a form
  /// "poly:N"): checks a word, the error naming `prefix`; `choices` then name the forms (help and
  /// range). Empty: a word must be one of `choices`.
  std::function<Status(const std::string& word, const std::string& prefix)> check_word;
  /// Real: words that stand for a value outside the range (block_length "whole" = -1): the word
  /// is accepted (and stays a word in a ValueSet: word_value_of gives its value); the value
  /// itself, given as a number, is not.
  std::vector<std::pair<std::string, double>> words;
};

/// A value as given: in SI in a ValueSet, in text units (degrees) at the text interfaces.
using FieldValue = std::variant<double, std::int64_t, bool, std::string>;
/// Values by field name. Absent fields take their default.
using ValueSet = std::map<std::string, FieldValue>;

/// "--rise-angle" for "rise_angle".
std::string cli_option_name(const Field& f);
/// Unit at the text interfaces (CLI, TOML, JSON): "deg" for "rad", otherwise `unit`.
std::string text_unit(const Field& f);
/// The one angle conversion: SI value -> text unit (rad -> deg); other units unchanged.
double to_text_unit(const Field& f, double si);
/// The one angle conversion: text unit -> SI value (deg -> rad); other units unchanged.
double from_text_unit(const Field& f, double text);

/// The default as text in text units ("5", "printed", "true", "auto"; `text_default` if set).
std::string default_text(const Field& f);
/// The valid range as text in text units ("(0, 60] deg", "0..10", "printed or common").
std::string range_text(const Field& f);

/// A settings field as every front end lists it (table "settings_field": `frictal settings --json`,
/// `frictal commands --json`, Python's tilt_settings() and the generators' fields): name, CLI
/// option, type (number, integer, boolean or word), the text unit and the SI unit, the default
/// and the valid range in text units, the meaning; Python's dicts hold the unit, the default, min
/// and max in SI (the default as the field's type: float, int, bool or str; None = automatic) and
/// the choices.
const Columns<Field>& settings_field_columns();

/// Checks a value given in SI (type and range); integers are accepted for Real fields and
/// whole reals for Integer fields, and the result is normalised to the field's type. Errors
/// name the field: "rise_angle: expected a value in (0, 1.5708) rad, got 2".
Result<FieldValue> check_si_value(const Field& f, const FieldValue& v);
/// The same for a value given at a text interface (angles in degrees): converts to SI and
/// checks; errors speak in text units. `prefix` names where the value came from
/// (e.g. "--alpha" or "parameter 'alpha'").
Result<FieldValue> si_from_text(const Field& f, const FieldValue& text_value, const std::string& prefix);
/// Parses a word typed at the CLI for the field (number, integer, true/false, choice) into a
/// text-unit value; errors name `prefix`.
Result<FieldValue> parse_text_word(const Field& f, const std::string& word, const std::string& prefix);
/// The quantities that several settings tables share (the tilt test's, the 3D tilt test's, the
/// prediction's, the areal signature's): one name, unit, range and help wherever they are taken
/// ("atomic_friction", "runaway_distance", "period", "spheroradius", "direction", "in_place"); each table fills
/// the default from its own struct. nullptr for another name.
const Field* shared_field(std::string_view name);

/// SI value -> text-unit value (angles to degrees), for printing JSON.
FieldValue text_from_si(const Field& f, const FieldValue& si);

/// The field of that name, or nullptr.
const Field* find_field(const std::vector<Field>& fields, std::string_view name);
/// Levenshtein edit distance (for "did you mean" answers).
std::size_t edit_distance(std::string_view a, std::string_view b);
/// The candidate nearest to `word` if it is close (distance <= max(2, |word|/3)), else "".
std::string nearest_word(std::string_view word, const std::vector<std::string>& candidates);

/// A value as a double (Real/Integer/Boolean), for code that reads a ValueSet.
double as_real(const FieldValue& v);
/// The same for a value of `f`, one of its words (Field::words) read as its value.
double word_value_of(const Field& f, const FieldValue& v);

}  // namespace frictal
