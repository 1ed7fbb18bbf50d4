// Minimal JSON text writers with shortest round-trip reals, so stored text is bit-stable.
#pragma once

#include <charconv>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/core.h>

namespace frictal::util {

/// Shortest text that reads back to the same double; "null" for NaN/inf (JSON has none).
/// With `mark_real`, integral values get ".0" so that reals and integers stay distinct.
inline std::string json_real(double d, bool mark_real = false) {
  if (!std::isfinite(d)) return "null";
  char buf[64];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, d);
  std::string s(buf, end);
  if (mark_real && s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

inline std::string json_string(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    switch (c) {
      case '"': o += "\\\""; break;
      case '\\': o += "\\\\"; break;
      case '\n': o += "\\n"; break;
      case '\t': o += "\\t"; break;
      case '\r': o += "\\r"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20)
          o += fmt::format("\\u{:04x}", c);
        else
          o += c;
    }
  }
  return o + "\"";
}

inline std::string json_array(const std::vector<double>& v) {
  std::string s = "[";
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i) s += ',';
    s += json_real(v[i]);
  }
  return s + "]";
}

}  // namespace frictal::util
