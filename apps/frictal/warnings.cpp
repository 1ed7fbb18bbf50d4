// frictal warnings [--json|--markdown] — every warning code the library issues and what it means.
#include "frictal/warnings.hpp"
#include "common.hpp"

namespace frictal::cli {
namespace {

std::function<int()> setup(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  auto markdown = std::make_shared<bool>(false);
  app.add_flag("--json", *json, "Print the codes as JSON: [{code, meaning, doubtful, fix}]");
  app.add_flag("--markdown", *markdown, "Print the codes as a Markdown table");
  return [json, markdown]() {
    require(!(*json && *markdown), "give one of --json and --markdown");
    if (*json) {
      nlohmann::json j = nlohmann::json::array();
      for (const WarningCode& c : warning_codes()) j.push_back(object_of(warning_code_columns(), c));
      print_json(j);
    } else if (*markdown) {
      fmt::print("| code | meaning | prediction | fix |\n|---|---|---|---|\n");
      for (const WarningCode& c : warning_codes())
        fmt::print("| `{}` | {} | {} | {} |\n", c.code, c.meaning, c.doubtful ? "doubtful" : "ok", c.fix);
    } else {
      for (const WarningCode& c : warning_codes())
        fmt::print("{:24} {}{}\n", c.code, c.meaning,
                   c.doubtful ? fmt::format(" [the prediction is doubtful; fix: {}]", c.fix) : "");
    }
    return 0;
  };
}

FRICTAL_COMMAND({"warnings", "Every warning code (units, spikes, scale, ...) and what it means", setup, 95});

}  // namespace
}  // namespace frictal::cli
