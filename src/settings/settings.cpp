// Settings tables: names, the one unit conversion, value checks and parsing (settings.hpp).
#include "frictal/settings.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>

#include <fmt/core.h>

#include "frictal/units.hpp"

namespace frictal {
namespace {

constexpr double kDeg = units::kRadPerDeg;

bool is_angle(const Field& f) { return f.unit == "rad"; }

/// A number for people: 10 significant digits, so that 5 deg stored in radians prints as 5.
std::string num(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{:.10g}", v);
}

std::string with_unit(const std::string& s, const std::string& unit) { return unit.empty() ? s : s + " " + unit; }

}  // namespace

std::string cli_option_name(const Field& f) {
  std::string s = "--" + f.name;
  std::replace(s.begin(), s.end(), '_', '-');
  return s;
}

std::string text_unit(const Field& f) { return is_angle(f) ? "deg" : f.unit; }

double to_text_unit(const Field& f, double si) { return is_angle(f) ? si / kDeg : si; }

double from_text_unit(const Field& f, double text) { return is_angle(f) ? text * kDeg : text; }

std::string default_text(const Field& f) {
  if (!f.text_default.empty()) return f.text_default;
  switch (f.type) {
    case FieldType::Boolean: return f.default_value != 0 ? "true" : "false";
    case FieldType::Choice: {
      if (std::isnan(f.default_value)) return "auto";
      const auto i = static_cast<std::size_t>(f.default_value);
      return i < f.choices.size() ? f.choices[i] : "";
    }
    case FieldType::Integer:
    case FieldType::Real:
      if (std::isnan(f.default_value)) return "auto";
      return num(to_text_unit(f, f.default_value));
  }
  return "";
}

namespace {

/// The valid range in text units (`text`) or in SI.
std::string range_in(const Field& f, bool text) {
  switch (f.type) {
    case FieldType::Boolean: return "true or false";
    case FieldType::Choice: {
      std::string s;
      for (std::size_t i = 0; i < f.choices.size(); ++i)
        s += (i == 0 ? "" : (i + 1 == f.choices.size() ? " or " : ", ")) + f.choices[i];
      return s;
    }
    case FieldType::Integer: {
      const bool lo = std::isfinite(f.min), hi = std::isfinite(f.max);
      if (lo && hi) return num(f.min) + ".." + num(f.max);
      if (lo) return ">= " + num(f.min);
      if (hi) return "<= " + num(f.max);
      return "any whole number";
    }
    case FieldType::Real: {
      std::string words;
      for (const auto& [w, value] : f.words) words += " or " + w;
      const bool lo = std::isfinite(f.min), hi = std::isfinite(f.max);
      const std::string u = text ? text_unit(f) : f.unit;
      if (!words.empty()) {
        Field plain = f;
        plain.words.clear();
        return range_in(plain, text) + words;
      }
      const std::string a = num(text ? to_text_unit(f, f.min) : f.min), b = num(text ? to_text_unit(f, f.max) : f.max);
      if (lo && hi)
        return with_unit(fmt::format("{}{}, {}{}", f.min_open ? "(" : "[", a, b, f.max_open ? ")" : "]"), u);
      if (lo) return with_unit(fmt::format("{} {}", f.min_open ? ">" : ">=", a), u);
      if (hi) return with_unit(fmt::format("{} {}", f.max_open ? "<" : "<=", b), u);
      return u.empty() ? "any" : "any, in " + u;
    }
  }
  return "";
}

}  // namespace

std::string range_text(const Field& f) { return range_in(f, true); }

double as_real(const FieldValue& v) {
  if (const double* d = std::get_if<double>(&v)) return *d;
  if (const std::int64_t* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  if (const bool* b = std::get_if<bool>(&v)) return *b ? 1.0 : 0.0;
  return std::nan("");
}

namespace {

/// The value of a Real field's word (block_length "whole"), if `word` is one.
const double* word_value(const Field& f, const std::string& word) {
  for (const auto& [w, value] : f.words)
    if (w == word) return &value;
  return nullptr;
}

}  // namespace

double word_value_of(const Field& f, const FieldValue& v) {
  if (const std::string* w = std::get_if<std::string>(&v))
    if (const double* x = word_value(f, *w)) return *x;
  return as_real(v);
}

namespace {

std::string shown(const FieldValue& v, double scale_to_text, bool angle) {
  struct V {
    double s;
    bool angle;
    std::string operator()(double d) const { return num(angle ? d * s : d); }
    std::string operator()(std::int64_t i) const { return std::to_string(i); }
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(const std::string& t) const { return "\"" + t + "\""; }
  };
  return std::visit(V{scale_to_text, angle}, v);
}

/// Type and range check of a value in SI; `text` selects the units of the message.
Result<FieldValue> check(const Field& f, const FieldValue& v, const std::string& prefix, bool text) {
  const bool angle = is_angle(f) && text;
  const std::string got = shown(v, 1 / kDeg, angle);
  auto expected = [&](const std::string& what) {
    return make_error(fmt::format("{}: expected {}, got {}", prefix, what, got));
  };
  std::string range = range_in(f, text);
  // Unbounded: "a finite number, in deg" rather than "a number any, in deg".
  const bool unbounded = range.rfind("any", 0) == 0 && f.type == FieldType::Real;
  if (unbounded) range = range.size() > 3 ? range.substr(3) : std::string();
  // "a number in (0, 60] deg", "a number > 0 s"
  const std::string in =
      (!range.empty() && (range[0] == '(' || range[0] == '[' || std::isdigit(static_cast<unsigned char>(range[0]))))
          ? "in "
          : "";
  switch (f.type) {
    case FieldType::Boolean:
      if (const bool* b = std::get_if<bool>(&v)) return FieldValue{*b};
      return expected("true or false");
    case FieldType::Choice:
      if (const std::string* s = std::get_if<std::string>(&v)) {
        if (f.check_word) {
          if (Status st = f.check_word(*s, prefix); !st) return st.error();
          return FieldValue{*s};
        }
        if (std::find(f.choices.begin(), f.choices.end(), *s) != f.choices.end()) return FieldValue{*s};
        std::string hint;
        if (std::string n = nearest_word(*s, f.choices); !n.empty()) hint = fmt::format(" (did you mean '{}'?)", n);
        return make_error(fmt::format("{}: expected {}, got \"{}\"{}", prefix, range, *s, hint));
      }
      return expected(range);
    case FieldType::Integer: {
      std::int64_t i = 0;
      if (const std::int64_t* p = std::get_if<std::int64_t>(&v))
        i = *p;
      else if (const double* d = std::get_if<double>(&v);
               d && std::isfinite(*d) && std::floor(*d) == *d && std::abs(*d) < 9e15)
        i = static_cast<std::int64_t>(*d);
      else
        return expected("a whole number " + in + range);
      const double x = static_cast<double>(i);
      if (x < f.min || x > f.max) return expected("a whole number " + in + range);
      return FieldValue{i};
    }
    case FieldType::Real: {
      double x = 0;
      if (const double* d = std::get_if<double>(&v))
        x = *d;
      else if (const std::int64_t* p = std::get_if<std::int64_t>(&v))
        x = static_cast<double>(*p);
      else if (const std::string* w = std::get_if<std::string>(&v); w && word_value(f, *w))
        return FieldValue{*w};  // the word (word_value_of gives its value, outside the range)
      else
        return expected((unbounded ? "a finite number" : "a number " + in) + range);
      if (std::isnan(x) && std::isnan(f.default_value)) return FieldValue{x};  // "automatic"
      if (!std::isfinite(x) || x < f.min || x > f.max || (f.min_open && x == f.min) || (f.max_open && x == f.max))
        return expected((unbounded ? "a finite number" : "a number " + in) + range);
      return FieldValue{x};
    }
  }
  return expected(range);
}

}  // namespace

Result<FieldValue> check_si_value(const Field& f, const FieldValue& v) { return check(f, v, f.name, false); }

Result<FieldValue> si_from_text(const Field& f, const FieldValue& text_value, const std::string& prefix) {
  FieldValue v = text_value;
  if (is_angle(f)) {
    if (const double* d = std::get_if<double>(&v))
      v = from_text_unit(f, *d);
    else if (const std::int64_t* i = std::get_if<std::int64_t>(&v))
      v = from_text_unit(f, static_cast<double>(*i));
  }
  return check(f, v, prefix, true);
}

FieldValue text_from_si(const Field& f, const FieldValue& si) {
  if (const double* d = std::get_if<double>(&si)) return to_text_unit(f, *d);
  return si;
}

Result<FieldValue> parse_text_word(const Field& f, const std::string& word, const std::string& prefix) {
  switch (f.type) {
    case FieldType::Boolean:
      if (word == "true" || word == "1" || word == "yes" || word == "on") return FieldValue{true};
      if (word == "false" || word == "0" || word == "no" || word == "off") return FieldValue{false};
      return make_error(fmt::format("{}: expected true or false, got '{}'", prefix, word));
    case FieldType::Choice: return FieldValue{word};
    case FieldType::Integer: {
      std::int64_t i = 0;
      const char* end = word.data() + word.size();
      auto [p, ec] = std::from_chars(word.data(), end, i);
      if (ec == std::errc() && p == end) return FieldValue{i};
      return make_error(fmt::format("{}: expected a whole number in {}, got '{}'", prefix, range_text(f), word));
    }
    case FieldType::Real: {
      if (word_value(f, word)) return FieldValue{word};  // kept as the word (word_value_of)
      double d = 0;
      const char* end = word.data() + word.size();
      auto [p, ec] = std::from_chars(word.data(), end, d);
      if (ec == std::errc() && p == end) return FieldValue{d};
      // A length may name its unit: 10um, 0.1mm, 5e-6 m (units::length_scale); a pressure or
      // modulus too: 70GPa, 200 MPa (units::pressure_scale).
      if (ec == std::errc() && (f.unit == "m" || f.unit == "Pa")) {
        std::string_view unit(p, std::size_t(end - p));
        while (!unit.empty() && unit.front() == ' ') unit.remove_prefix(1);
        const auto scale = f.unit == "m" ? units::length_scale(unit) : units::pressure_scale(unit);
        if (scale && std::isfinite(d * *scale)) return FieldValue{d * *scale};
      }
      std::string range = range_text(f);
      const bool interval = !range.empty() && (range[0] == '(' || range[0] == '[');
      // Unbounded: "a finite number, in deg" rather than "a number any, in deg" (as check() says).
      const bool unbounded = range.rfind("any", 0) == 0;
      if (unbounded) range = range.substr(3);
      return make_error(fmt::format("{}: expected {}{}{}{}, got '{}'", prefix,
                                    unbounded ? "a finite number" : "a number ", interval ? "in " : "", range,
                                    f.unit == "m"    ? " (a unit may follow: m, mm, um, nm)"
                                    : f.unit == "Pa" ? " (a unit may follow: Pa, kPa, MPa, GPa)"
                                                     : "",
                                    word));
    }
  }
  return make_error(prefix + ": cannot parse '" + word + "'");
}

const Field* find_field(const std::vector<Field>& fields, std::string_view name) {
  for (const Field& f : fields)
    if (f.name == name) return &f;
  return nullptr;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string nearest_word(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_d = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const std::string& c : candidates) {
    std::size_t d = edit_distance(word, c);
    // A prefix of a candidate ("stat" for "stats") or a candidate with a suffix ("alpha_deg" for
    // "alpha") counts as close.
    if (c.size() > word.size() && word.size() >= 3 && c.compare(0, word.size(), word) == 0)
      d = std::min<std::size_t>(d, 1);
    if (word.size() > c.size() && c.size() >= 3 && word.compare(0, c.size(), c) == 0) d = std::min<std::size_t>(d, 2);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

}  // namespace frictal
