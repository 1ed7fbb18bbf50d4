// frictal formats — every format frictal reads: its native readers, then every format a
// Gwyddion file module loads when Gwyddion's libraries and modules are installed.
#include "common.hpp"
#include "surface_io.hpp"

namespace frictal::cli {
namespace {

struct Args {
  bool json = false;
};

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  app.add_flag("--json", a->json, "Print one JSON object");
  return [a]() {
    const auto formats = readable_formats();
    std::string why;
    const bool gwy = gwyddion_available("", &why);
    if (a->json) {
      print_json(object_of(format_list_columns(), FormatList{formats, gwy, why}));
      return 0;
    }
    std::size_t native = 0;
    for (const auto& f : formats) native += f.reader == "native";
    fmt::print("Native readers ({}), detected by content:\n", native);
    for (const auto& f : formats)
      if (f.reader == "native")
        fmt::print("  {:<10} {}{}\n", f.name, f.description, f.can_write ? " [write: convert]" : "");
    if (gwy) {
      fmt::print("Through Gwyddion's file modules ({}):\n", formats.size() - native);
      for (const auto& f : formats)
        if (f.reader != "native") fmt::print("  {:<18} {}\n", f.name, f.description);
    } else {
      fmt::print("Gwyddion-backed formats: not available ({})\n", why);
    }
    return 0;
  };
}

FRICTAL_COMMAND({"formats", "List every readable surface format (native and Gwyddion-backed)", setup, 26});

}  // namespace
}  // namespace frictal::cli
