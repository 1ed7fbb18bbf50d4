#include "io/text_util.hpp"

#include <fmt/core.h>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

namespace frictal::io_detail {

namespace {
bool is_space(unsigned char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v' || c == 0;
}
}  // namespace

std::string_view trim(std::string_view s) {
  if (s.size() >= 3 && (unsigned char)s[0] == 0xEF && (unsigned char)s[1] == 0xBB && (unsigned char)s[2] == 0xBF)
    s.remove_prefix(3);
  while (!s.empty() && is_space((unsigned char)s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space((unsigned char)s.back())) s.remove_suffix(1);
  return s;
}

std::string lower_ascii(std::string_view s) {
  std::string r(s);
  for (char& c : r)
    if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
  return r;
}

int last_digit_exponent(std::string_view s, bool decimal_comma) {
  s = trim(s);
  const char point = decimal_comma ? ',' : '.';
  std::size_t k = 0;
  if (k < s.size() && (s[k] == '+' || s[k] == '-')) ++k;
  bool digit = false, after_point = false;
  int fraction = 0;
  for (; k < s.size(); ++k) {
    const char c = s[k];
    if (c >= '0' && c <= '9') {
      digit = true;
      fraction += after_point;
    } else if (c == point && !after_point) {
      after_point = true;
    } else {
      break;
    }
  }
  if (!digit) return kNoPrintedDigit;
  long exponent = 0;
  if (k < s.size() && (s[k] == 'e' || s[k] == 'E')) {
    std::size_t j = k + 1;
    bool negative = false;
    if (j < s.size() && (s[j] == '+' || s[j] == '-')) negative = s[j++] == '-';
    if (j >= s.size()) return kNoPrintedDigit;
    for (; j < s.size() && s[j] >= '0' && s[j] <= '9'; ++j) exponent = std::min(exponent * 10 + (s[j] - '0'), 1000L);
    if (j != s.size()) return kNoPrintedDigit;
    if (negative) exponent = -exponent;
  } else if (k != s.size()) {
    return kNoPrintedDigit;
  }
  return static_cast<int>(std::clamp(exponent - fraction, -126L, 126L));
}

bool parse_double(std::string_view s, double& out, bool decimal_comma) {
  s = trim(s);
  if (s.empty()) return false;
  if (s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  // Fast path for plain numbers (a digit or '.' after an optional '-'): none of the special
  // spellings below starts so except "1.#inf" and the like, which from_chars does not take whole.
  {
    const std::size_t k = s.front() == '-' ? 1 : 0;
    if (k < s.size() && ((s[k] >= '0' && s[k] <= '9') || s[k] == '.') &&
        !(decimal_comma && s.find(',') != std::string_view::npos)) {
      double v = 0;
      auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
      if (ec == std::errc() && p == s.data() + s.size()) {
        out = v;
        return true;
      }
    }
  }
  std::string low = lower_ascii(s);
  // Old MSVC printf pads its spellings with zeros ("1.#INF00", "-1.#IND00", "1.#QNAN0"); newer
  // MSVC and C99 strtod's form carry a payload in parentheses ("-nan(ind)", "nan(0x8)").
  if (low.find('#') != std::string::npos)
    while (low.size() > 3 && low.back() == '0') low.pop_back();
  if (const auto open = low.find('(');
      open != std::string::npos && low.back() == ')' && (low.rfind("nan(", 0) == 0 || low.rfind("-nan(", 0) == 0))
    low.resize(open);
  if (low == "nan" || low == "-nan" || low == "+nan" || low == "1.#qnan" || low == "-1.#qnan" || low == "1.#snan" ||
      low == "-1.#snan" || low == "-1.#ind" || low == "1.#ind") {
    out = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  if (low == "inf" || low == "infinity" || low == "1.#inf" || low == "-inf" || low == "-infinity" || low == "-1.#inf") {
    out = low.front() == '-' ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
    return true;
  }
  std::string tmp;
  if (decimal_comma && s.find(',') != std::string_view::npos) {
    tmp.assign(s);
    for (char& c : tmp)
      if (c == ',') c = '.';
    s = tmp;
  }
  double v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size()) {
    // from_chars rejects values that over/underflow; treat underflow as 0 and overflow as failure.
    if (ec == std::errc::result_out_of_range && p == s.data() + s.size()) {
      std::string t(s);
      double w = std::strtod(t.c_str(), nullptr);
      if (std::isfinite(w)) {
        out = w;
        return true;
      }
    }
    return false;
  }
  out = v;
  return true;
}

bool parse_int64(std::string_view s, long long& out) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return false;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && p == s.data() + s.size();
}

std::optional<double> unit_scale(std::string_view word) {
  std::string w = lower_ascii(trim(word));
  // Strip surrounding punctuation.
  while (!w.empty() && (w.front() == '(' || w.front() == '[' || w.front() == '_' || w.front() == '"')) w.erase(0, 1);
  while (!w.empty() && (w.back() == ')' || w.back() == ']' || w.back() == '_' || w.back() == '"' || w.back() == ':' ||
                        w.back() == '.'))
    w.pop_back();
  if (w == "m" || w == "meter" || w == "meters" || w == "metre" || w == "metres") return 1.0;
  if (w == "mm" || w == "millimeter" || w == "millimeters" || w == "millimetre" || w == "millimetres") return 1e-3;
  // micro sign U+00B5 = C2 B5, greek mu U+03BC = CE BC
  if (w == "um" || w == "\xC2\xB5m" || w == "\xCE\xBCm" || w == "micron" || w == "microns" || w == "micrometer" ||
      w == "micrometers" || w == "micrometre" || w == "micrometres")
    return 1e-6;
  if (w == "nm" || w == "nanometer" || w == "nanometers" || w == "nanometre" || w == "nanometres") return 1e-9;
  if (w == "a" || w == "\xC3\x85" || w == "\xC3\xA5" || w == "angstrom" || w == "angstroms" ||
      w == "\xC3\xA5ngstr\xC3\xB6m")
    return 1e-10;
  if (w == "pm" || w == "picometer" || w == "picometers") return 1e-12;
  return std::nullopt;
}

std::optional<double> unit_in_header(std::string_view header) {
  std::string h(trim(header));
  // Units in brackets or parentheses first: "X_(microns)", "height [nm]".
  for (auto [open, close] : {std::pair{'(', ')'}, std::pair{'[', ']'}}) {
    auto a = h.rfind(open);
    if (a != std::string::npos) {
      auto b = h.find(close, a);
      if (b != std::string::npos)
        if (auto s = unit_scale(std::string_view(h).substr(a + 1, b - a - 1))) return s;
    }
  }
  // Otherwise the last word that is a unit ("x in µm", "Lateral um", "Raw Micrometer").
  std::vector<std::string> words;
  std::string cur;
  for (char c : h) {
    if (c == ' ' || c == '_' || c == '/' || c == '\t' || c == '(' || c == ')' || c == '[' || c == ']') {
      if (!cur.empty()) words.push_back(cur);
      cur.clear();
    } else {
      cur.push_back(c);
    }
  }
  if (!cur.empty()) words.push_back(cur);
  // A single word that is only a unit is a unit column ("µm"); for longer headers skip the
  // first word so that a column named "m" or "a" is not a unit.
  for (std::size_t k = words.size(); k-- > 0;) {
    if (words.size() > 1 && k == 0) break;
    if (auto s = unit_scale(words[k])) return s;
  }
  return std::nullopt;
}

std::optional<double> length_value(std::string_view s) {
  s = trim(s);
  std::size_t k = 0;
  while (k < s.size() && s[k] != ' ' && s[k] != '\t') ++k;
  double v = 0;
  if (!parse_double(s.substr(0, k), v) || !std::isfinite(v)) return std::nullopt;
  auto unit = trim(s.substr(k));
  if (unit.empty()) return std::nullopt;
  auto scale = unit_scale(unit);
  if (!scale) return std::nullopt;
  return v * *scale;
}

std::vector<Line> split_lines(std::string_view text) {
  std::vector<Line> lines;
  std::size_t start = 0, number = 1;
  for (std::size_t i = 0; i < text.size(); ++i) {
    char c = text[i];
    if (c == '\n' || c == '\r') {
      lines.push_back({text.substr(start, i - start), number++});
      if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      start = i + 1;
    }
  }
  if (start < text.size()) lines.push_back({text.substr(start), number});
  return lines;
}

std::size_t InvalidCount::total() const { return nan + pos_inf + neg_inf; }

void InvalidCount::add(double v) {
  if (std::isnan(v))
    ++nan;
  else if (v > 0)
    ++pos_inf;
  else
    ++neg_inf;
}

std::size_t mask_invalid(std::vector<double>& z, InvalidCount& count) {
  std::size_t n = 0;
  for (double& v : z)
    if (!std::isfinite(v)) {
      count.add(v);
      v = std::numeric_limits<double>::quiet_NaN();
      ++n;
    }
  return n;
}

std::string invalid_warning(const std::string& name, const InvalidCount& c, bool map) {
  std::string parts;
  auto part = [&](std::size_t n, const char* what) {
    if (!n) return;
    parts += fmt::format("{}{} {}", parts.empty() ? "" : ", ", n, what);
  };
  part(c.nan, "NaN");
  part(c.pos_inf, "+inf");
  part(c.neg_inf, "-inf");
  return fmt::format("{}: {} invalid point{} ({}) {}", name, c.total(), c.total() == 1 ? "" : "s", parts,
                     map ? "masked" : "dropped from the profile");
}

}  // namespace frictal::io_detail
