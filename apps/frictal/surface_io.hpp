// frictal CLI — options shared by the commands that read measured surfaces (any format):
// --format, --unit, --x-column/--z-column; warnings go to stderr.
#pragma once

#include <memory>
#include <string>

#include "common.hpp"
#include "frictal/io.hpp"

namespace frictal::cli {

struct InputOptions {
  std::string format = "auto";
  std::string unit;
  int x_column = -1, z_column = -1;
};

inline void add_input_options(CLI::App& app, InputOptions& o) {
  app.add_option("--format", o.format, "Input format: auto, csv, dektak, gwyddion, x3p (default: detect from content)");
  app.add_option("--unit", o.unit, "Unit of text columns that name none: m, mm, um, nm (default m, with a warning)");
  app.add_option("--x-column", o.x_column, "0-based column of x in delimited text (default: automatic)");
  app.add_option("--z-column", o.z_column, "0-based column of z in delimited text (default: the one after x)");
}

inline SurfaceData load_surface(const std::string& path, const InputOptions& o) {
  ReadOptions r;
  r.format = unwrap(parse_format(o.format));
  r.default_unit = o.unit;
  r.x_column = o.x_column;
  r.z_column = o.z_column;
  SurfaceData s = unwrap(read_surface(input_path(path), r));
  for (const auto& w : s.warnings) fmt::print(stderr, "frictal: warning: {}\n", w);
  return s;
}

/// The surface as a single-valued profile (error naming the file for maps or folded curves).
inline Profile surface_profile(const SurfaceData& s, const std::string& path) {
  if (s.is_map)
    throw UsageError(fmt::format("{}: an areal map ({} x {}); this command needs a line profile", path, s.map.nx, s.map.ny));
  return unwrap(as_profile(s.curve, path));
}

}  // namespace frictal::cli
