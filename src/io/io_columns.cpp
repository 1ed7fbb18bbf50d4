// The output tables of what a surface file holds (frictal/outputs.hpp): the keys of `frictal info
// --json` and of Python's read_surface() dict.
#include "frictal/io.hpp"

namespace frictal {

const Columns<ChannelInfo>& channel_info_columns() {
  using T = ChannelInfo;
  static const Columns<T> cols = {
      column<T>(
          "name", "text", "the channel's name", [](const T& c) { return c.name; }, "-"),
      column<T>(
          "kind", "text", "map or profile", [](const T& c) { return std::string(c.is_map ? "map" : "profile"); }, "-"),
      column<T>(
          "nx", "count", "nodes along x", [](const T& c) { return double(c.nx); }, "-"),
      column<T>(
          "ny", "count", "nodes along y", [](const T& c) { return double(c.ny); }, "-"),
      column<T>(
          "size_x", "1", "extent along x, in xy_unit", [](const T& c) { return c.size_x; }, "-"),
      column<T>(
          "size_y", "1", "extent along y, in xy_unit", [](const T& c) { return c.size_y; }, "-"),
      column<T>(
          "xy_unit", "text", "the file's lateral unit", [](const T& c) { return c.xy_unit; }, "-"),
      column<T>(
          "z_unit", "text", "the file's height unit", [](const T& c) { return c.z_unit; }, "-"),
      column<T>(
          "readable", "flag", "frictal reads this channel", [](const T& c) { return c.readable; }, "-"),
  };
  return cols;
}

const Columns<SurfaceData>& surface_data_columns() {
  using T = SurfaceData;
  auto map = [](const T& s) { return s.is_map; };
  auto profile = [](const T& s) { return !s.is_map; };
  static const Columns<T> cols = {
      column<T>("reader", "text", "the reader that read it: native or gwyddion", [](const T& s) { return s.reader; }),
      column<T>(
          "channel", "count", "the channel read (0-based)", [](const T& s) { return double(s.channel); }, "-"),
      list_column<T>(
          "channels", "info_channel", "every channel of the file", channel_info_columns(),
          [](const T& s) { return std::optional(s.channels); }, "-"),
      only_if(column<T>("x0_m", "m", "x of the first node", [](const T& s) { return s.map.x0; }), map),
      only_if(column<T>("y0_m", "m", "y of the first node", [](const T& s) { return s.map.y0; }), map),
      only_if(column<T>(
                  "points", "count", "points of the profile", [](const T& s) { return double(s.curve.size()); }, "-"),
              profile),
      only_if(column<T>(
                  "valid_points", "count", "nodes with a measured height",
                  [](const T& s) { return double(s.map.valid_count()); }, "-"),
              map),
      only_if(column<T>(
                  "", "m", "the profile's abscissae", [](const T& s) { return s.curve.x; }, "x"),
              profile),
      only_if(column<T>(
                  "", "m", "the profile's heights", [](const T& s) { return s.curve.z; }, "z"),
              profile),
      column<T>(
          "", "1", "metres per unit of the file's lateral numbers as read (0: none in the file, the spacing given)",
          [](const T& s) { return s.x_unit_scale; }, "x_unit_scale"),
      column<T>(
          "", "1", "metres per unit of the file's heights as read", [](const T& s) { return s.z_unit_scale; },
          "z_unit_scale"),
      column<T>(
          "warnings", "text", "what the reader said that did not stop it: the messages, as the text output gives them",
          [](const T& s) {
            std::vector<std::string> messages;
            for (const Warning& w : s.warnings) messages.push_back(w.message);
            return messages;
          },
          "-"),
  };
  return cols;
}

const Columns<FormatInfo>& format_info_columns() {
  using T = FormatInfo;
  static const Columns<T> cols = {
      column<T>(
          "name", "text", "the format's name (--format)", [](const T& f) { return f.name; }, "-"),
      column<T>(
          "description", "text", "what it is, with the usual extensions", [](const T& f) { return f.description; },
          "-"),
      column<T>(
          "reader", "text", "native or gwyddion", [](const T& f) { return f.reader; }, "-"),
      column<T>(
          "can_write", "flag", "frictal writes it (native) / Gwyddion's module saves it",
          [](const T& f) { return f.can_write; }, "-"),
  };
  return cols;
}

const Columns<FormatList>& format_list_columns() {
  using T = FormatList;
  static const Columns<T> cols = {
      list_column<T>(
          "formats", "format", "every readable format: the native readers, then Gwyddion's", format_info_columns(),
          [](const T& l) { return std::optional(l.formats); }, "-"),
      column<T>(
          "gwyddion", "flag", "the Gwyddion backend is available", [](const T& l) { return l.gwyddion; }, "-"),
      only_if(column<T>(
                  "gwyddion_missing", "text", "why the Gwyddion backend is not available",
                  [](const T& l) { return l.gwyddion_missing; }, "-"),
              [](const T& l) { return !l.gwyddion; }),
  };
  return cols;
}

}  // namespace frictal
