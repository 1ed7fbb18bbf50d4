// frictal convert IN OUT — converts between surface formats. The output format follows OUT's
// extension: .x3p (ISO 25178-71), .csv (profiles: x_m,z_m), .txt (maps: Gwyddion-style text),
// and, through Gwyddion's file modules when installed, .gwy .gsf .sdf .sur .asc .ibw .nrrd .tom
// .afm .spm.
#include <limits>

#include "common.hpp"
#include "frictal/analysis.hpp"
#include "surface_io.hpp"

namespace frictal::cli {
namespace {

struct Args {
  std::string in, out;
  std::string type = "D";
  bool xml = false;
  double line_angle = std::numeric_limits<double>::quiet_NaN();
  double line_offset = 0;
  InputOptions input;
};

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<Args>();
  app.add_option("input", a->in, "Input surface (any readable format)")->required();
  app.add_option("output", a->out,
                 "Output file: .x3p, .csv (profiles) or .txt (maps); with Gwyddion: .gwy .gsf .sdf .sur .asc .ibw "
                 ".nrrd .tom .afm .spm")
      ->required();
  app.add_option("--x3p-type", a->type, "X3P height type: I (int16), L (int32), F (float32), D (float64)");
  app.add_flag("--x3p-xml", a->xml, "Store X3P heights as an XML data list instead of bindata/data.bin");
  app.add_option("--line-angle", a->line_angle,
                 "Extract the line profile of a map along this direction (deg from +x towards +y), bilinear");
  app.add_option("--line-offset", a->line_offset, "Perpendicular distance of that line from the map centre (m)");
  add_input_options(app, a->input);
  return [a]() {
    X3pWriteOptions o;
    if (a->type == "I")
      o.type = X3pDataType::I;
    else if (a->type == "L")
      o.type = X3pDataType::L;
    else if (a->type == "F")
      o.type = X3pDataType::F;
    else if (a->type == "D")
      o.type = X3pDataType::D;
    else
      throw UsageError(fmt::format("--x3p-type '{}' not understood (expected I, L, F or D)", a->type));
    o.binary = !a->xml;
    SurfaceData s = load_surface(a->in, a->input);
    if (!std::isnan(a->line_angle)) {
      if (!s.is_map) throw UsageError(fmt::format("{}: --line-angle needs an areal map", a->in));
      require(std::isfinite(a->line_angle) && std::isfinite(a->line_offset),
              "--line-angle/--line-offset must be finite");
      const Map& m = s.map;
      const double ang = a->line_angle * kDeg;
      const double cx = m.x0 + 0.5 * m.width() - a->line_offset * std::sin(ang);
      const double cy = m.y0 + 0.5 * m.height() + a->line_offset * std::cos(ang);
      auto runs = map_line(m, cx, cy, ang, 0, 2);
      if (runs.empty())
        throw UsageError(fmt::format("{}: no valid line at {} deg, offset {} m (off the map or all invalid)", a->in,
                                     a->line_angle, a->line_offset));
      std::size_t best = 0;
      for (std::size_t k = 1; k < runs.size(); ++k)
        if (runs[k].size() > runs[best].size()) best = k;
      if (runs.size() > 1)
        fmt::print(stderr,
                   "frictal: warning: the line crosses invalid points; kept the longest of {} runs ({} points)\n",
                   runs.size(), runs[best].size());
      s.is_map = false;
      s.curve = as_curve(runs[best]);
    }
    if (has_extension(a->out, ".x3p")) {
      if (s.is_map)
        unwrap(write_x3p(a->out, s.map, o));
      else
        unwrap(write_x3p(a->out, surface_profile(s, a->in), o));
    } else if (has_extension(a->out, ".csv")) {
      if (s.is_map)
        throw UsageError(fmt::format("{}: a map cannot be written as a CSV profile; use .txt or .x3p", a->in));
      unwrap(write_profile_csv(a->out, s.curve));
    } else if (has_extension(a->out, ".txt")) {
      if (!s.is_map)
        unwrap(write_profile_csv(a->out, s.curve));
      else
        unwrap(write_map_text(a->out, s.map));
    } else if (has_extension(a->out, ".gwy") || has_extension(a->out, ".gsf") || has_extension(a->out, ".sdf") ||
               has_extension(a->out, ".sur") || has_extension(a->out, ".asc") || has_extension(a->out, ".ibw") ||
               has_extension(a->out, ".nrrd") || has_extension(a->out, ".tom") || has_extension(a->out, ".afm") ||
               has_extension(a->out, ".spm")) {
      if (!s.is_map) throw UsageError(fmt::format("{}: only maps are written through Gwyddion", a->in));
      unwrap(write_gwyddion(a->out, s.map));
    } else {
      throw UsageError(
          fmt::format("{}: unknown output extension (expected .x3p, .csv, .txt; through Gwyddion: .gwy, .gsf, .sdf, "
                      ".sur, .asc, .ibw, .nrrd)",
                      a->out));
    }
    return 0;
  };
}

FRICTAL_COMMAND({"convert", "Convert a surface between formats (CSV, Gwyddion text, X3P; Gwyddion-written formats)",
                 setup, 60});

}  // namespace
}  // namespace frictal::cli
