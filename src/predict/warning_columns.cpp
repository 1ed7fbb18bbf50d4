// The output table of the warning codes (frictal/warnings.hpp): `frictal warnings --json`, one
// row per code of warning_codes().
#include "frictal/outputs.hpp"
#include "frictal/warnings.hpp"

namespace frictal {

const Columns<WarningCode>& warning_code_columns() {
  using T = WarningCode;
  static const Columns<T> cols = {
      column<T>(
          "code", "text", "the code", [](const T& c) { return c.code; }, "-"),
      column<T>(
          "meaning", "text", "what it means", [](const T& c) { return c.meaning; }, "-"),
      column<T>(
          "doubtful", "flag",
          "the input was probably read wrong, or the model does not hold: a prediction with the code is doubtful",
          [](const T& c) { return c.doubtful; }, "-"),
      column<T>(
          "fix", "text", "the fix that exists: the options to add (Python keywords in parentheses)",
          [](const T& c) { return c.fix; }, "-"),
  };
  return cols;
}

}  // namespace frictal
