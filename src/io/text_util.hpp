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

/// Parses a whole field as a double (leading '+'; ',' as decimal separator if decimal_comma).
/// "nan", "inf", "-inf", "infinity" (any case, also MSVC's "1.#INF"/"1.#QNAN") give NaN or
/// +-infinity: callers decide (heights: invalid points; coordinates and headers: errors).
/// Empty or partly numeric fields fail; numbers beyond the double range fail.
bool parse_double(std::string_view s, double& out, bool decimal_comma = false);
bool parse_int64(std::string_view s, long long& out);
/// The decimal exponent of the last digit a number was printed with: "0.2" -> -1, "1500" -> 0,
/// "1.6655563e-08" -> -15, "2,50" with decimal_comma -> -2 (clamped to [-126, 126]);
/// kNoPrintedDigit for text without one (nan, inf).
inline constexpr int kNoPrintedDigit = 127;
int last_digit_exponent(std::string_view s, bool decimal_comma = false);

/// Metres per unit for a unit word ("m", "mm", "um", "µm", "micron", "micrometer", "nm",
/// "angstrom", "pm", ...); nullopt if the word is not a length unit.
std::optional<double> unit_scale(std::string_view word);
/// Finds a length unit inside a column header such as "X_(microns)", "x in µm",
/// "Lateral um", "height [nm]"; nullopt if none.
std::optional<double> unit_in_header(std::string_view header);
/// Parses "12.34 µm" (number then unit); nullopt on failure.
std::optional<double> length_value(std::string_view s);

/// Invalid heights met by a reader (NaN, +inf, -inf): one rule for every format -- dropped
/// from a profile, masked (NaN) in a map, reported in one warning.
struct InvalidCount {
  std::size_t nan = 0, pos_inf = 0, neg_inf = 0;
  std::size_t total() const;
  void add(double v);  ///< counts one non-finite value
};
/// Sets every non-finite value of z to NaN, counting them; returns how many.
std::size_t mask_invalid(std::vector<double>& z, InvalidCount& count);
/// "name: 3 invalid points (2 NaN, 1 +inf) masked" (map) or "... dropped from the profile".
std::string invalid_warning(const std::string& name, const InvalidCount& c, bool map);

/// decode_text(b) without a copy when b is already UTF-8 (the common case): a view of b, or
/// of `storage` holding the decoded text.
std::string_view decode_text_view(const std::string& b, std::string& storage);
/// True if decode_text(b) would change b other than by dropping a UTF-8 BOM (UTF-16, Latin-1).
bool text_needs_decoding(std::string_view b);
/// Whether b is valid UTF-8 (ASCII runs are checked 8 bytes at a time).
bool valid_utf8(std::string_view b);
/// Whether b is UTF-16 text: by its BOM, or BOM-less ASCII as UTF-16 (first 512 bytes).
bool utf16_text(std::string_view b);

struct Line {
  std::string_view text;
  std::size_t number;  ///< 1-based line number
};
/// Splits on \n, \r\n, \r (each terminator ends one line; "\r\r\n" gives an empty line).
std::vector<Line> split_lines(std::string_view text);

}  // namespace frictal::io_detail
