// Private helpers shared by the text and X3P readers.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace frictal::io_detail {

/// Strips ASCII whitespace (and a UTF-8 BOM / NUL padding) from both ends.
std::string_view trim(std::string_view s);
std::string lower_ascii(std::string_view s);

/// Parses a whole field as a double (leading '+', "nan"/"NaN" accepted; ',' as decimal
/// separator if decimal_comma). Empty or partly numeric fields fail.
bool parse_double(std::string_view s, double& out, bool decimal_comma = false);
bool parse_int64(std::string_view s, long long& out);

/// Metres per unit for a unit word ("m", "mm", "um", "µm", "micron", "micrometer", "nm",
/// "angstrom", "pm", ...); nullopt if the word is not a length unit.
std::optional<double> unit_scale(std::string_view word);
/// Finds a length unit inside a column header such as "X_(microns)", "x in µm",
/// "Lateral um", "height [nm]"; nullopt if none.
std::optional<double> unit_in_header(std::string_view header);
/// Parses "12.34 µm" (number then unit); nullopt on failure.
std::optional<double> length_value(std::string_view s);

struct Line {
  std::string_view text;
  std::size_t number;  ///< 1-based line number
};
/// Splits on \n, \r\n, \r (each terminator ends one line; "\r\r\n" gives an empty line).
std::vector<Line> split_lines(std::string_view text);

}  // namespace frictal::io_detail
