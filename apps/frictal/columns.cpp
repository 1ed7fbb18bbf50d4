// frictal columns [TABLE] [--json|--markdown] — the output tables (frictal/outputs.hpp): every key
// that a command's --json and Python's dicts print, with its unit and meaning, table by table.
#include <optional>

#include "common.hpp"
#include "frictal/outputs.hpp"
#include "frictal/settings.hpp"

namespace frictal::cli {
namespace {

std::string python_text(const ColumnInfo& c) {
  if (c.python.empty()) return "";
  return c.python + (c.unit == "deg" ? " (rad)" : "");
}

// The listing's own record types as output tables: `frictal columns --json` is written from them.
const Columns<ColumnInfo>& column_info_columns() {
  using T = ColumnInfo;
  static const Columns<T> cols = {
      column<T>(
          "key", "text", "the CLI's JSON key (\"\": Python only)", [](const T& c) { return c.key; }, "-"),
      column<T>(
          "unit", "text", "the interface unit", [](const T& c) { return c.unit; }, "-"),
      column<T>(
          "help", "text", "what it means", [](const T& c) { return c.help; }, "-"),
      column<T>(
          "python", "text", "the key in Python's dicts (SI; \"\": not in Python's dicts)",
          [](const T& c) { return c.python; }, "-"),
  };
  return cols;
}

const Columns<OutputTable>& output_table_columns() {
  using T = OutputTable;
  static const Columns<T> cols = {
      column<T>(
          "name", "text", "the table's name", [](const T& t) { return t.name; }, "-"),
      column<T>(
          "help", "text", "which outputs carry it", [](const T& t) { return t.help; }, "-"),
      list_column<T>(
          "columns", "column_info", "its columns", column_info_columns(),
          [](const T& t) { return std::optional(t.columns); }, "-"),
  };
  return cols;
}

std::function<int()> setup(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  auto markdown = std::make_shared<bool>(false);
  auto table = std::make_shared<std::string>();
  app.add_option("table", *table, "Only this table (e.g. prediction, signature, hold, stats, tilt); default: all");
  app.add_flag("--json", *json, "Print the tables as JSON: [{name, help, columns: [{key, unit, help, python}]}]");
  app.add_flag("--markdown", *markdown, "Print the tables as Markdown (the docs' outputs reference)");
  return [json, markdown, table]() {
    require(!(*json && *markdown), "give one of --json and --markdown");
    std::vector<const OutputTable*> tables;
    if (table->empty()) {
      for (const OutputTable& t : output_tables()) tables.push_back(&t);
    } else {
      const OutputTable* t = find_output_table(*table);
      if (!t) {
        std::vector<std::string> names;
        for (const OutputTable& x : output_tables()) names.push_back(x.name);
        std::string hint = nearest_word(*table, names);
        throw UsageError("columns: no output table '" + *table + "'" +
                         (hint.empty() ? "" : "; did you mean '" + hint + "'?") + " (frictal columns lists them)");
      }
      tables.push_back(t);
    }
    if (*json) {
      nlohmann::json j = nlohmann::json::array();
      for (const OutputTable* t : tables) j.push_back(object_of(output_table_columns(), *t));
      print_json(j);
    } else if (*markdown) {
      for (const OutputTable* t : tables) {
        fmt::print("## `{}`\n\n{}\n\n| key | unit | Python key (SI) | meaning |\n|---|---|---|---|\n", t->name,
                   t->help);
        for (const ColumnInfo& c : t->columns)
          fmt::print("| {} | {} | {} | {} |\n", c.key.empty() ? "" : "`" + c.key + "`", c.unit,
                     c.python.empty() ? "" : "`" + python_text(c) + "`", c.help);
        fmt::print("\n");
      }
    } else {
      for (const OutputTable* t : tables) {
        fmt::print("{}: {}\n", t->name, t->help);
        for (const ColumnInfo& c : t->columns)
          fmt::print("  {:38} {:24} {:30} {}\n", c.key.empty() ? "-" : c.key, c.unit,
                     c.python.empty() ? "-" : python_text(c), c.help);
        fmt::print("\n");
      }
    }
    return 0;
  };
}

FRICTAL_COMMAND({"columns",
                 "The output tables: every key of each command's --json and of Python's dicts, with unit and meaning",
                 setup, 94});

}  // namespace
}  // namespace frictal::cli
