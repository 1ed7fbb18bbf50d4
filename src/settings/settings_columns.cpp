// The output table of a settings field (frictal/settings.hpp): how every front end lists the
// inputs that a settings table declares.
#include <cmath>

#include "frictal/settings.hpp"

namespace frictal {
namespace {

const char* type_word(FieldType t) {
  switch (t) {
    case FieldType::Real: return "number";
    case FieldType::Integer: return "integer";
    case FieldType::Boolean: return "boolean";
    case FieldType::Choice: return "word";
  }
  return "";
}

/// The default in SI as the field's type: a number (NaN = automatic), a flag or a word. An
/// Integer field's default is the "count" column's.
OutputValue si_default(const Field& f) {
  if (f.type == FieldType::Boolean) return OutputValue(f.default_value != 0);
  if (f.type == FieldType::Choice)
    return std::isnan(f.default_value) ? OutputValue(f.default_value)
                                       : OutputValue(f.choices.at(static_cast<std::size_t>(f.default_value)));
  return OutputValue(f.default_value);
}

}  // namespace

const Columns<Field>& settings_field_columns() {
  using T = Field;
  static const Columns<T> cols = {
      column<T>("name", "text", "the field's name: the study TOML key, the Python keyword, the JSON key",
                [](const T& f) { return f.name; }),
      column<T>("option", "text", "its CLI option", [](const T& f) { return cli_option_name(f); }),
      column<T>("type", "text", "number, integer, boolean or word",
                [](const T& f) { return std::string(type_word(f.type)); }),
      column<T>(
          "unit", "text", "the unit of the CLI, TOML files and JSON (angles in degrees)",
          [](const T& f) { return text_unit(f); }, "-"),
      column<T>(
          "si_unit", "text", "the unit of the library and Python (SI)", [](const T& f) { return f.unit; }, "unit"),
      column<T>(
          "default", "text", "the default, in the text unit", [](const T& f) { return default_text(f); }, "-"),
      only_if(
          column<T>(
              "", "count", "the default of an integer field", [](const T& f) { return f.default_value; }, "default"),
          [](const T& f) { return f.type == FieldType::Integer; }),
      only_if(column<T>(
                  "", "value", "the default in SI: a number (None: automatic, see help), a flag or a word",
                  [](const T& f) { return si_default(f); }, "default"),
              [](const T& f) { return f.type != FieldType::Integer; }),
      column<T>(
          "range", "text", "the valid values", [](const T& f) { return range_text(f); }, "-"),
      column<T>(
          "", "value", "the smallest valid value, in SI (-inf: none)", [](const T& f) { return f.min; }, "min"),
      column<T>(
          "", "value", "the largest valid value, in SI (inf: none)", [](const T& f) { return f.max; }, "max"),
      column<T>(
          "", "text", "the words of a word field", [](const T& f) { return f.choices; }, "choices"),
      column<T>("help", "text", "what it is", [](const T& f) { return f.help; }),
  };
  return cols;
}

}  // namespace frictal
