// frictal info FILE — what a surface file holds: its format, the reader that took it, every
// channel (name, kind, points, physical size, units) and which one frictal reads.
#include "common.hpp"
#include "frictal/scan_stats.hpp"
#include "surface_io.hpp"

namespace frictal::cli {
namespace {

struct Args {
  std::string file;
  bool json = false;
  InputOptions input;
};

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  app.add_option("file", a->file, "Surface file (any readable format; see 'frictal formats')")->required();
  app.add_flag("--json", a->json, "Print one JSON object");
  add_input_options(app, a->input);
  return [a]() {
    const SurfaceData s = load_surface(a->file, a->input);
    if (a->json) {
      RunRecord in;
      in.file = a->file;
      in.format = format_name(s.format);
      in.kind = s.is_map ? "map" : "profile";
      nlohmann::json j = object_of(surface_data_columns(), s);
      if (s.is_map) put_columns(j, map_grid_columns(), s.map);
      put_columns(j, run_record_columns(), in);
      print_json(j);
      return 0;
    }
    fmt::print("{}\n  format {}, read by {}\n  {} channel{}:\n", a->file, format_name(s.format), s.reader,
               s.channels.size(), s.channels.size() == 1 ? "" : "s");
    for (std::size_t k = 0; k < s.channels.size(); ++k) {
      const auto& c = s.channels[k];
      fmt::print("  {} {:>3}  {:<24} {:<7} {} x {} points, {:.6g} x {:.6g} {}, values in {}{}\n",
                 k == s.channel ? '*' : ' ', k, c.name, c.is_map ? "map" : "profile", c.nx, c.ny, c.size_x, c.size_y,
                 c.xy_unit, c.z_unit.empty() ? "(none)" : c.z_unit,
                 !c.readable                             ? "  (not lengths: not readable)"
                 : c.xy_unit.empty() && c.z_unit.empty() ? "  (no units: read as metres or --unit)"
                                                         : "");
    }
    if (s.is_map)
      fmt::print("  read: {} x {} map, dx {:.6g} m, dy {:.6g} m, origin ({:.6g}, {:.6g}) m, {} valid of {} points\n",
                 s.map.nx, s.map.ny, s.map.dx, s.map.dy, s.map.x0, s.map.y0, s.map.valid_count(), s.map.size());
    else
      fmt::print("  read: profile of {} points\n", s.curve.size());
    return 0;
  };
}

FRICTAL_COMMAND({"info", "What a surface file holds: format, reader, channels, sizes and units", setup, 25});

}  // namespace
}  // namespace frictal::cli
