// frictal columns [--json|--markdown] — the output table of the prediction: every key of
// `frictal predict --json` (and of Python's Prediction.to_dict()) with its unit and meaning.
#include "common.hpp"
#include "frictal/predict.hpp"

namespace frictal::cli {
namespace {

std::function<int()> setup(CLI::App& app) {
  auto json = std::make_shared<bool>(false);
  auto markdown = std::make_shared<bool>(false);
  app.add_flag("--json", *json, "Print the table as JSON: [{key, unit, help}]");
  app.add_flag("--markdown", *markdown, "Print the table as Markdown (the docs' outputs reference)");
  return [json, markdown]() {
    require(!(*json && *markdown), "give one of --json and --markdown");
    if (*json) {
      nlohmann::json j = nlohmann::json::array();
      for (const OutputColumn& c : prediction_columns())
        j.push_back({{"key", c.key}, {"unit", c.unit}, {"help", c.help}});
      j.push_back({{"key", "warnings"}, {"unit", "list"}, {"help", "[{code, message}]: see frictal warnings"}});
      print_json(j);
    } else if (*markdown) {
      fmt::print("| key | unit | meaning |\n|---|---|---|\n");
      for (const OutputColumn& c : prediction_columns()) fmt::print("| `{}` | {} | {} |\n", c.key, c.unit, c.help);
      fmt::print("| `warnings` | list | `[{{code, message}}]`: see `frictal warnings` |\n");
    } else {
      for (const OutputColumn& c : prediction_columns()) fmt::print("{:34} {:6} {}\n", c.key, c.unit, c.help);
      fmt::print("{:34} {:6} {}\n", "warnings", "list", "[{code, message}]: see frictal warnings");
    }
    return 0;
  };
}

FRICTAL_COMMAND({"columns", "The prediction's output keys (frictal predict --json, Python to_dict) with units", setup,
                 94});

}  // namespace
}  // namespace frictal::cli
