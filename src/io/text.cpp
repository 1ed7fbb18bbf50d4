// Text formats: delimited two-column profiles, the Bruker Dektak CSV export, Gwyddion text
// matrices. Text arrives here decoded to UTF-8 (decode_text).
#include <fmt/core.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>

#include "io/readers.hpp"
#include "io/text_util.hpp"

namespace frictal {

namespace {

void append_utf8(std::string& out, unsigned cp) {
  if (cp < 0x80) {
    out.push_back(char(cp));
  } else if (cp < 0x800) {
    out.push_back(char(0xC0 | (cp >> 6)));
    out.push_back(char(0x80 | (cp & 0x3F)));
  } else if (cp < 0x10000) {
    out.push_back(char(0xE0 | (cp >> 12)));
    out.push_back(char(0x80 | ((cp >> 6) & 0x3F)));
    out.push_back(char(0x80 | (cp & 0x3F)));
  } else {
    out.push_back(char(0xF0 | (cp >> 18)));
    out.push_back(char(0x80 | ((cp >> 12) & 0x3F)));
    out.push_back(char(0x80 | ((cp >> 6) & 0x3F)));
    out.push_back(char(0x80 | (cp & 0x3F)));
  }
}

std::string decode_utf16(const std::string& b, std::size_t start, bool little) {
  std::string out;
  out.reserve(b.size() / 2);
  for (std::size_t i = start; i + 1 < b.size(); i += 2) {
    unsigned u = little ? (unsigned char)b[i] | ((unsigned char)b[i + 1] << 8)
                        : ((unsigned char)b[i] << 8) | (unsigned char)b[i + 1];
    if (u >= 0xD800 && u < 0xDC00 && i + 3 < b.size()) {
      unsigned v = little ? (unsigned char)b[i + 2] | ((unsigned char)b[i + 3] << 8)
                          : ((unsigned char)b[i + 2] << 8) | (unsigned char)b[i + 3];
      if (v >= 0xDC00 && v < 0xE000) {
        append_utf8(out, 0x10000 + ((u - 0xD800) << 10) + (v - 0xDC00));
        i += 2;
        continue;
      }
    }
    if (u >= 0xD800 && u < 0xE000) u = 0xFFFD;
    append_utf8(out, u);
  }
  return out;
}

bool has_utf8_bom(std::string_view b) {
  return b.size() >= 3 && (unsigned char)b[0] == 0xEF && (unsigned char)b[1] == 0xBB && (unsigned char)b[2] == 0xBF;
}

/// UTF-16 text: by its BOM, or without one when the first 512 bytes have a NUL in every other
/// byte and none in the others (ASCII characters as UTF-16). `No` for anything else.
enum class Utf16 { No, BomLittle, BomBig, Little, Big };
Utf16 utf16_kind(std::string_view b) {
  auto u = [&](std::size_t i) { return (unsigned char)b[i]; };
  if (has_utf8_bom(b)) return Utf16::No;
  if (b.size() >= 2 && u(0) == 0xFF && u(1) == 0xFE) return Utf16::BomLittle;
  if (b.size() >= 2 && u(0) == 0xFE && u(1) == 0xFF) return Utf16::BomBig;
  if (b.size() >= 4) {
    std::size_t n = std::min<std::size_t>(b.size() & ~std::size_t(1), 512), even0 = 0, odd0 = 0;
    for (std::size_t i = 0; i < n; ++i) (i % 2 ? odd0 : even0) += b[i] == 0;
    if (odd0 > n / 4 && even0 == 0) return Utf16::Little;
    if (even0 > n / 4 && odd0 == 0) return Utf16::Big;
  }
  return Utf16::No;
}

}  // namespace

namespace io_detail {

bool valid_utf8(std::string_view s) {
  std::size_t i = 0, n = s.size();
  while (i < n) {
    // Runs of ASCII (the whole of a CSV, typically) 8 bytes at a time.
    for (std::uint64_t w; i + 8 <= n; i += 8) {
      std::memcpy(&w, s.data() + i, 8);
      if (w & 0x8080808080808080ULL) break;
    }
    if (i >= n) break;
    unsigned char c = s[i];
    std::size_t len = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
    if (len == 0 || i + len > n) return false;
    for (std::size_t k = 1; k < len; ++k)
      if (((unsigned char)s[i + k] >> 6) != 2) return false;
    i += len;
  }
  return true;
}

bool utf16_text(std::string_view b) { return utf16_kind(b) != Utf16::No; }

bool text_needs_decoding(std::string_view b) { return !has_utf8_bom(b) && (utf16_text(b) || !valid_utf8(b)); }

std::string_view decode_text_view(const std::string& b, std::string& storage) {
  // The same cases as decode_text, which returns valid UTF-8 unchanged: no copy then.
  if (has_utf8_bom(b)) return std::string_view(b).substr(3);
  if (!utf16_text(b) && valid_utf8(b)) return b;
  storage = decode_text(b);
  return storage;
}

}  // namespace io_detail

std::string decode_text(const std::string& b) {
  if (has_utf8_bom(b)) return b.substr(3);
  switch (utf16_kind(b)) {
    case Utf16::BomLittle: return decode_utf16(b, 2, true);
    case Utf16::BomBig: return decode_utf16(b, 2, false);
    case Utf16::Little: return decode_utf16(b, 0, true);
    case Utf16::Big: return decode_utf16(b, 0, false);
    case Utf16::No: break;
  }
  if (io_detail::valid_utf8(b)) return b;
  std::string out;  // Latin-1: every byte is its code point
  out.reserve(b.size() + b.size() / 8);
  for (char c : b) append_utf8(out, (unsigned char)c);
  return out;
}

namespace io_detail {

namespace {

bool is_comment(std::string_view t) {
  return !t.empty() && (t.front() == '#' || t.front() == '%' || t.substr(0, 2) == "//");
}

void split_fields_into(std::string_view line, char delim, std::vector<std::string_view>& f) {
  f.clear();
  if (delim == ' ') {
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i >= line.size()) break;
      std::size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
      f.push_back(line.substr(i, j - i));
      i = j;
    }
  } else {
    std::size_t i = 0;
    while (true) {
      std::size_t j = line.find(delim, i);
      f.push_back(trim(line.substr(i, j == std::string_view::npos ? std::string_view::npos : j - i)));
      if (j == std::string_view::npos) break;
      i = j + 1;
    }
    while (!f.empty() && f.back().empty()) f.pop_back();  // "0.0,-0.00933,," (Dektak)
  }
}

std::vector<std::string_view> split_fields(std::string_view line, char delim) {
  std::vector<std::string_view> f;
  split_fields_into(line, delim, f);
  return f;
}

bool numeric_fields(const std::vector<std::string_view>& f, bool decimal_comma, std::vector<double>* out) {
  if (f.empty()) return false;
  if (out) out->clear();
  for (auto s : f) {
    double v;
    if (!parse_double(s, v, decimal_comma)) return false;
    if (out) out->push_back(v);
  }
  return true;
}

struct Delim {
  char c = ' ';
  bool decimal_comma = false;
};

Delim detect_delimiter(const std::vector<Line>& lines) {
  const Delim cands[] = {{'\t', false}, {';', false}, {';', true}, {',', false}, {' ', false}, {' ', true}};
  Delim best{' ', false};
  std::size_t best_count = 0;
  for (const Delim& d : cands) {
    std::size_t count = 0, seen = 0;
    // Sample up to 200 lines from the end (data is at the end of every format we read).
    for (std::size_t k = lines.size(); k-- > 0 && seen < 200;) {
      auto t = trim(lines[k].text);
      if (t.empty() || is_comment(t)) continue;
      ++seen;
      auto f = split_fields(t, d.c);
      if (f.size() >= 2 && numeric_fields(f, d.decimal_comma, nullptr)) ++count;
    }
    if (count > best_count) {
      best_count = count;
      best = d;
    }
  }
  return best;
}

bool is_index_name(std::string_view s) {
  std::string l = lower_ascii(trim(s));
  return l == "index" || l == "#" || l == "n" || l == "i" || l == "no" || l == "no." || l == "idx" || l == "point" ||
         l == "nr" || l == "nr.";
}

/// "key = value" / "key: value" pairs of the header lines ("# w = 10 um", "x-pixels = 256",
/// "Width: 12 µm"). Keys are lower-cased with spaces, '-' and '_' removed.
struct HeaderPairs {
  std::vector<std::pair<std::string, std::string>> kv;
  const std::string* get(std::initializer_list<const char*> keys) const {
    for (const char* k : keys)
      for (auto it = kv.rbegin(); it != kv.rend(); ++it)
        if (it->first == k) return &it->second;
    return nullptr;
  }
};

HeaderPairs header_pairs(const std::vector<std::string_view>& lines) {
  HeaderPairs h;
  auto norm = [](std::string_view k) {
    std::string r;
    for (char c : lower_ascii(trim(k)))
      if (c != ' ' && c != '-' && c != '_' && c != '\t' && c != '.') r += c;
    return r;
  };
  for (auto l : lines) {
    l = trim(l);
    while (!l.empty() && (l.front() == '#' || l.front() == '%' || l.front() == '/')) l.remove_prefix(1);
    const char sep = l.find('=') != std::string_view::npos ? '=' : ':';
    std::vector<std::string_view> segs;
    std::size_t start = 0;
    for (std::size_t i = 0; i <= l.size(); ++i)
      if (i == l.size() || l[i] == sep) {
        segs.push_back(l.substr(start, i - start));
        start = i + 1;
      }
    if (segs.size() < 2) continue;
    std::string_view key = segs[0];
    for (std::size_t i = 1; i < segs.size(); ++i) {
      std::string_view value = segs[i], next;
      if (i + 1 < segs.size()) {  // "w=10um h=5um": the next key is the last word
        auto v = trim(value);
        auto cut = v.find_last_of(" \t,;");
        if (cut == std::string_view::npos) break;
        next = v.substr(cut + 1);
        value = v.substr(0, cut);
      }
      value = trim(value);
      while (!value.empty() && (value.back() == ',' || value.back() == ';')) value.remove_suffix(1);
      h.kv.emplace_back(norm(key), std::string(trim(value)));
      key = next;
    }
  }
  return h;
}

/// "10 um", "10um", "1e-6" (no unit: nullopt scale).
bool number_with_unit(std::string_view s, double& v, std::optional<double>& scale) {
  s = trim(s);
  std::size_t k = 0;
  while (k < s.size() && (std::isdigit((unsigned char)s[k]) || s[k] == '.' || s[k] == '-' || s[k] == '+' ||
                          ((s[k] == 'e' || s[k] == 'E') && k > 0 && k + 1 < s.size() &&
                           (std::isdigit((unsigned char)s[k + 1]) || s[k + 1] == '-' || s[k + 1] == '+'))))
    ++k;
  if (!parse_double(s.substr(0, k), v) || !std::isfinite(v)) return false;
  auto unit = trim(s.substr(k));
  scale.reset();
  if (unit.empty()) return true;
  scale = unit_scale(unit);
  return scale.has_value();
}

/// Whether a column can be an abscissa: monotonic, and changing at more than half of its steps
/// (a column that stays put, like the first column "2 2 2 2 2 0 0 0 0 0" of a height matrix, is
/// no x axis).
bool monotonic(const double* col, std::size_t stride, std::size_t n) {
  if (n < 2) return true;
  bool up = true, down = true;
  std::size_t flat = 0;
  for (std::size_t k = 1; k < n; ++k) {
    up = up && col[k * stride] >= col[(k - 1) * stride];
    down = down && col[k * stride] <= col[(k - 1) * stride];
    flat += col[k * stride] == col[(k - 1) * stride];
  }
  return (up || down) && 2 * flat < n - 1;
}

/// Whether the steps of a column all lie within 1 % of their mean (an evenly sampled axis, as
/// printed with a few significant digits).
bool evenly_spaced(const double* col, std::size_t stride, std::size_t n) {
  if (n < 3) return true;
  const double mean = (col[(n - 1) * stride] - col[0]) / double(n - 1);
  if (!(std::abs(mean) > 0)) return false;
  for (std::size_t k = 1; k < n; ++k)
    if (!(std::abs(col[k * stride] - col[(k - 1) * stride] - mean) <= 0.01 * std::abs(mean))) return false;
  return true;
}

/// Sorted distinct values of v, with the spacing a + b k if they are regular (within 1e-3 b).
std::optional<std::pair<double, double>> regular_axis(std::vector<double> v, std::size_t& n) {
  std::sort(v.begin(), v.end());
  std::vector<double> u;
  const double span = v.back() - v.front();
  for (double a : v)
    if (u.empty() || a - u.back() > 1e-9 * std::max(span, std::abs(a))) u.push_back(a);
  n = u.size();
  if (u.size() < 2) return std::nullopt;
  double a = u.front(), b = (u.back() - u.front()) / double(u.size() - 1);
  for (std::size_t k = 0; k < u.size(); ++k)
    if (std::abs(u[k] - (a + b * double(k))) > 1e-3 * b) return std::nullopt;
  return std::pair{a, b};
}

/// An x column that is a uniform grid as far as its printed digits tell: x_k = x0 + k dx.
struct PrintedGrid {
  double x0 = 0, dx = 0;
  double min_step = 0, max_step = 0;  // the steps as printed
  double unit = 0;                    // the coarsest last printed digit (10^e)
  bool changed = false;               // some printed x differs from the grid by more than float rounding
  bool from_header = false;           // dx is the header's stated spacing
};

/// Whether the printed x column `x` (last printed digits at 10^e[k]) is a uniform grid within its
/// printing: every x_k lies within half a unit of its printing precision of the grid x0 + k dx,
/// where the grid's ends are the printed first and last values (each off by up to half its unit:
/// the line through them is off by at most the larger half unit anywhere), plus a few ulps of
/// float slack. The printing precision of a value is the writer's format, read from the whole
/// column: a fixed number of decimals (the most any value has) or of significant digits (the most
/// any value has); of the two, the coarser at that value, and never coarser than the value's own
/// last digit. (A writer that drops trailing zeros prints 0.5 for 0.50000000: its other values
/// show how many digits it keeps; a shortest round-trip writer keeps 17, and nothing is changed.)
/// The spacing is the header's (`header_dx`, in the column's unit) when the grid with it fits the
/// same bound, else the whole column's (x_last - x_0) / (n - 1). A column that is not uniform
/// within its printing (a non-uniform sampling, a column printed with all its digits) gives
/// nullopt.
std::optional<PrintedGrid> printed_uniform_grid(const std::vector<double>& x, const std::vector<signed char>& e,
                                                std::optional<double> header_dx) {
  const std::size_t n = x.size();
  if (n < 3 || e.size() != n) return std::nullopt;
  double scale = 0;
  int finest = kNoPrintedDigit, significant = 0;  // the most decimals, the most significant digits
  std::vector<int> lead(n, kNoPrintedDigit);      // exponent of each value's leading digit
  for (std::size_t k = 0; k < n; ++k) {
    if (e[k] == kNoPrintedDigit || !std::isfinite(x[k])) return std::nullopt;
    scale = std::max(scale, std::abs(x[k]));
    finest = std::min(finest, int(e[k]));
    if (x[k] != 0) {
      lead[k] = int(std::floor(std::log10(std::abs(x[k]))));
      significant = std::max(significant, lead[k] - e[k] + 1);
    }
  }
  std::vector<double> halfs(n);
  double unit = 0;
  for (std::size_t k = 0; k < n; ++k) {
    double u = std::pow(10.0, finest);
    if (lead[k] != kNoPrintedDigit && significant > 0) u = std::max(u, std::pow(10.0, lead[k] - significant + 1));
    u = std::min(u, std::pow(10.0, e[k]));
    halfs[k] = 0.5 * u;
    unit = std::max(unit, u);
  }
  const double slack = 8 * std::numeric_limits<double>::epsilon() * scale;
  auto half = [&](std::size_t k) { return halfs[k]; };
  // The largest residual beyond its bound (<= 0: every point fits), and the largest residual.
  auto misfit = [&](double x0, double dx, double end_error, double& largest) {
    double worst = -INFINITY;
    largest = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const double r = std::abs(x[k] - (x0 + double(k) * dx));
      largest = std::max(largest, r);
      worst = std::max(worst, r - (half(k) + end_error + slack));
    }
    return worst;
  };
  PrintedGrid g;
  g.x0 = x[0];
  g.dx = (x[n - 1] - x[0]) / double(n - 1);
  if (!(std::abs(g.dx) > 0) || !std::isfinite(g.dx)) return std::nullopt;
  double largest = 0;
  if (misfit(g.x0, g.dx, std::max(half(0), half(n - 1)), largest) > 0) return std::nullopt;
  g.changed = largest > slack;
  g.unit = unit;
  g.min_step = INFINITY, g.max_step = -INFINITY;
  for (std::size_t k = 1; k < n; ++k) {
    g.min_step = std::min(g.min_step, x[k] - x[k - 1]);
    g.max_step = std::max(g.max_step, x[k] - x[k - 1]);
  }
  // Rounding keeps the order: the printed column of a grid never steps against the grid's
  // direction (x going back and forth is a folded curve, not a rounded grid).
  if (g.dx > 0 ? g.min_step < 0 : g.max_step > 0) return std::nullopt;
  if (header_dx && *header_dx > 0) {
    const double hdx = g.dx < 0 ? -*header_dx : *header_dx;
    double l = 0;
    if (misfit(g.x0, hdx, half(0), l) <= 0) {
      g.dx = hdx;
      g.from_header = true;
      g.changed = l > slack;
    }
  }
  return g;
}

}  // namespace

// Lines of a text one at a time, as split_lines() cuts them (no vector of every line: a 10^7
// line file would need 240 MB for it).
class LineCursor {
 public:
  explicit LineCursor(std::string_view text) : text_(text) {}
  bool next(Line& out) {
    if (pos_ >= text_.size()) return false;
    const char* b = text_.data() + pos_;
    const std::size_t rest = text_.size() - pos_;
    std::size_t i = 0;
    while (i < rest && b[i] != '\n' && b[i] != '\r') ++i;
    out = {text_.substr(pos_, i), number_++};
    std::size_t next = pos_ + i + 1;
    if (i < rest && b[i] == '\r' && next < text_.size() && text_[next] == '\n') ++next;
    pos_ = next;
    return true;
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0, number_ = 1;
};

// The delimiter from the last 200 data lines, as detect_delimiter(split_lines(text)) finds it,
// splitting only a tail of the text that holds them.
Delim detect_delimiter_tail(std::string_view text) {
  std::size_t want = 2048;
  while (true) {
    // Start of the tail: just after the want-th line terminator from the end.
    std::size_t start = 0, count = 0;
    for (std::size_t i = text.size(); i-- > 0;) {
      if (text[i] == '\n' || text[i] == '\r') {
        if (++count >= want) {
          start = i + 1;
          if (text[i] == '\r' && start < text.size() && text[start] == '\n') ++start;  // "\r\n" ends one line
          break;
        }
      }
    }
    auto lines = split_lines(text.substr(start));
    std::size_t data = 0;
    for (const Line& l : lines) {
      auto t = trim(l.text);
      if (!t.empty() && !is_comment(t)) ++data;
    }
    if (start == 0 || data >= 200) return detect_delimiter(lines);
    want *= 4;
  }
}

// Line numbers of the data rows: consecutive runs stored as (first row, first line).
class RowLines {
 public:
  void push_back(std::size_t line) {
    if (runs_.empty() || runs_.back().second + (n_ - runs_.back().first) != line) runs_.push_back({n_, line});
    ++n_;
  }
  void push_front(std::size_t line) {
    std::vector<std::size_t> all;
    all.reserve(n_ + 1);
    all.push_back(line);
    for (std::size_t k = 0; k < n_; ++k) all.push_back((*this)[k]);
    runs_.clear();
    n_ = 0;
    for (auto l : all) push_back(l);
  }
  std::size_t operator[](std::size_t k) const {
    auto it = std::upper_bound(runs_.begin(), runs_.end(), k,
                               [](std::size_t v, const std::pair<std::size_t, std::size_t>& r) { return v < r.first; });
    --it;
    return it->second + (k - it->first);
  }
  std::size_t front() const { return (*this)[0]; }

 private:
  std::vector<std::pair<std::size_t, std::size_t>> runs_;  // (row index, line number)
  std::size_t n_ = 0;
};

Result<SurfaceData> parse_delimited(std::string_view text, const std::string& name, const ReadOptions& options,
                                    const ReleaseBehind* release) {
  Delim delim = detect_delimiter_tail(text);
  std::vector<std::vector<std::string_view>> headers;  // non-numeric lines before the data
  std::vector<std::string_view> raw_headers;           // the same lines, whole
  // Data rows stored flat (ncols values per row): no per-row allocation for large files.
  struct Rows {
    std::vector<double> v;
    std::size_t ncols = 0;
    bool empty() const { return v.empty(); }
    std::size_t size() const { return ncols ? v.size() / ncols : 0; }
    const double* operator[](std::size_t k) const { return v.data() + k * ncols; }
    void push_back(const std::vector<double>& r) { v.insert(v.end(), r.begin(), r.end()); }
    // The last printed digit (last_digit_exponent) of the first `dcols` columns of each row, the
    // columns x can be in: whether x is a rounded uniform grid (printed_uniform_grid).
    std::vector<signed char> digits;
    std::size_t dcols = 0;
  } rows;
  RowLines row_line;
  std::vector<double> vals;
  std::vector<std::string_view> f;
  std::size_t ncols = 0, trailer_line = 0;
  std::string_view trailer_text;
  long long count_line_value = -1;
  std::size_t count_line_number = 0;
  LineCursor cursor(text);
  constexpr std::size_t kReleaseStep = std::size_t{32} << 20;  // bytes between release calls
  const char* next_release = text.data() + kReleaseStep;
  bool reserved = false;
  for (Line ln; cursor.next(ln);) {
    if (release && ln.text.data() >= next_release) {
      (*release)(ln.text.data());
      next_release = ln.text.data() + kReleaseStep;
    }
    auto t = trim(ln.text);
    if (t.empty()) continue;
    if (is_comment(t)) {
      if (rows.empty()) {
        headers.push_back(split_fields(t.substr(1), delim.c));
        raw_headers.push_back(t);
      }
      continue;
    }
    split_fields_into(t, delim.c, f);
    if (numeric_fields(f, delim.decimal_comma, &vals)) {
      if (trailer_line)
        return make_error(fmt::format("{}:{}: expected numbers, found text '{}' inside the data", name, trailer_line,
                                      std::string(trim(trailer_text)).substr(0, 60)));
      if (rows.empty() && vals.size() == 1 && count_line_number == 0) {
        // A count line ("23") before the data, or the first of a single column of heights
        // (decided below).
        long long n;
        if (parse_int64(f[0], n)) {
          count_line_value = n;
          count_line_number = ln.number;
          continue;
        }
      }
      if (rows.empty()) {
        ncols = rows.ncols = vals.size();
        rows.dcols = std::min<std::size_t>(ncols, std::size_t(std::max(2, options.x_column + 1)));
      } else if (vals.size() != ncols) {
        return make_error(fmt::format("{}:{}: expected {} columns like line {}, found {}", name, ln.number, ncols,
                                      row_line.front(), vals.size()));
      }
      if (rows.size() >= options.max_points)
        return make_error(fmt::format("{}: more than {} points (limit max_points)", name, options.max_points));
      rows.push_back(vals);
      for (std::size_t c = 0; c < rows.dcols; ++c)
        rows.digits.push_back(static_cast<signed char>(last_digit_exponent(f[c], delim.decimal_comma)));
      row_line.push_back(ln.number);
      if (!reserved && rows.size() == 4096) {
        // Room for the rest at the bytes per row so far (+10 %), so that a large file's rows are
        // not copied by repeated doubling (untouched capacity costs address space, not memory).
        reserved = true;
        const auto used = static_cast<double>(ln.text.data() + ln.text.size() - text.data());
        const double estimate = 1.1 * static_cast<double>(rows.size()) * static_cast<double>(text.size()) / used;
        const double cap = static_cast<double>(options.max_points) + 1;
        rows.v.reserve(static_cast<std::size_t>(std::min(estimate, cap)) * ncols);
        rows.digits.reserve(static_cast<std::size_t>(std::min(estimate, cap)) * rows.dcols);
      }
    } else if (rows.empty()) {
      headers.push_back(f);
      raw_headers.push_back(t);
      // A unit line written with spaces in a comma file ("µm µm").
      if (f.size() == 1 && delim.c != ' ') headers.push_back(split_fields(t, ' '));
    } else if (!trailer_line) {
      trailer_line = ln.number;
      trailer_text = ln.text;
    }
  }
  if (trailer_line && rows.size() < 2)
    return make_error(fmt::format("{}:{}: expected numbers, found '{}'", name, trailer_line,
                                  std::string(trim(trailer_text)).substr(0, 60)));
  // A single column whose first line is not its count: that line is the first height.
  if (ncols == 1 && count_line_number && (std::size_t(count_line_value) != rows.size() || rows.size() < 2)) {
    rows.v.insert(rows.v.begin(), double(count_line_value));
    rows.digits.insert(rows.digits.begin(), 0);
    row_line.push_front(count_line_number);
    count_line_value = -1;
  }
  if (rows.empty()) {
    if (trim(text).empty()) return make_error(fmt::format("{}: file is empty", name));
    if (count_line_number)
      return make_error(
          fmt::format("{}:{}: only one number; expected two columns (x and z), a column of heights or a matrix", name,
                      count_line_number));
    return make_error(fmt::format("{}: no numeric data rows found (expected lines of x and z values)", name));
  }
  if (rows.size() < 2)
    return make_error(fmt::format("{}:{}: only one data row; a profile needs at least 2 points", name, row_line[0]));

  SurfaceData out;
  out.format = ProfileFormat::Csv;
  const HeaderPairs hp = header_pairs(raw_headers);
  double fallback_unit = 1.0;
  if (!options.default_unit.empty()) {
    auto s = unit_scale(options.default_unit);
    if (!s) return make_error(fmt::format("unknown unit '{}' (expected m, mm, um, nm)", options.default_unit));
    fallback_unit = *s;
  }
  // A length from the header ("w = 10 um"; a bare number is in `bare_scale`); the unit of the
  // last one read is the lateral unit the reader applied (SurfaceData::x_unit_scale).
  std::optional<double> lateral_unit_seen;
  auto header_length = [&](std::initializer_list<const char*> keys,
                           double bare_scale) -> Result<std::optional<double>> {
    const std::string* v = hp.get(keys);
    if (!v) return std::optional<double>{};
    double x;
    std::optional<double> sc;
    if (!number_with_unit(*v, x, sc) || !(x > 0))
      return make_error(fmt::format("{}: header value '{}' for '{}' is not a positive length (number and unit)", name,
                                    *v, *keys.begin()));
    lateral_unit_seen = sc.value_or(bare_scale);
    return std::optional<double>{x * sc.value_or(bare_scale)};
  };
  // Height unit named in the header ("# unit: nm", "Value units: um", "z unit = nm").
  std::optional<double> z_unit_header;
  if (const std::string* u =
          hp.get({"zunit", "zunits", "valueunits", "valueunit", "heightunit", "heightunits", "unit", "units"})) {
    z_unit_header = unit_scale(*u);
    if (!z_unit_header)
      return make_error(
          fmt::format("{}: height unit '{}' in the header is not a length unit (expected m, mm, um, nm)", name, *u));
  }
  const bool spip = hp.get({"bit2nm"}) != nullptr;  // SPIP ASCII: lengths in nm, z = value * Bit2nm nm
  const double lateral_bare = spip ? 1e-9 : fallback_unit;

  // One column of heights: a profile at a constant spacing (option, or header "spacing", "dx").
  if (ncols == 1) {
    auto dx_h = header_length({"spacing", "dx", "xspacing", "step", "xstep", "sampling", "samplinginterval", "interval",
                               "increment", "xincrement", "resolution", "xresolution"},
                              fallback_unit);
    if (!dx_h) return dx_h.error();
    double dx = options.spacing > 0 ? options.spacing : dx_h->value_or(0.0);
    if (!(dx > 0))
      return make_error(fmt::format(
          "{}: one column of {} heights and no spacing: expected two columns (x and z), or give the sampling interval "
          "(--spacing, ReadOptions::spacing, or a '# spacing: 0.5 um' header)",
          name, rows.size()));
    std::optional<double> zu = z_unit_header;
    for (auto it = raw_headers.rbegin(); it != raw_headers.rend() && !zu; ++it)
      if (!is_comment(*it) && it->find_first_of("=:") == std::string_view::npos)
        zu = unit_in_header(*it);  // "height [nm]"
    if (!zu && options.default_unit.empty())
      out.warnings.emplace_back(
          "reader",
          fmt::format("{}: no length unit found for the heights; read as metres (give a unit to override)", name));
    const double zs = zu.value_or(fallback_unit);
    out.z_unit_scale = zs;
    out.x_unit_scale = options.spacing > 0 ? 0.0 : lateral_unit_seen.value_or(fallback_unit);
    InvalidCount invalid;
    for (std::size_t k = 0; k < rows.size(); ++k) {
      double z = rows[k][0];
      if (!std::isfinite(z)) {
        invalid.add(z);
        continue;
      }
      out.curve.x.push_back(double(k) * dx);
      out.curve.z.push_back(z * zs);
    }
    if (invalid.total()) out.warnings.emplace_back("reader", invalid_warning(name, invalid, false));
    if (out.curve.x.size() < 2) return make_error(fmt::format("{}: fewer than 2 points with finite values", name));
    return out;
  }

  const bool forced = options.x_column >= 0 || options.z_column >= 0;
  // Header keys that make a matrix: sizes and counts. A two-column file needs a count key (a
  // profile with a "# dx = 0.1 um" comment stays a profile).
  const bool count_key =
      hp.get({"nx", "ny", "xpixels", "ypixels", "xres", "yres", "ncols", "nrows", "cols", "rows"}) != nullptr;
  const bool size_key = hp.get({"w", "h", "width", "height", "xlength", "ylength", "xreal", "yreal", "xsize", "ysize",
                                "dx", "dy", "bit2nm"}) != nullptr;
  const bool matrix_header = count_key || (ncols >= 3 && size_key);
  const std::vector<std::string_view>* named_row = nullptr;
  for (auto it = headers.rbegin(); it != headers.rend(); ++it)
    if (it->size() == ncols) {
      named_row = &*it;
      break;
    }

  // x, y, z point lists that lie on a regular grid: a map.
  if (!forced && ncols == 3 && !matrix_header && rows.size() >= 4) {
    std::vector<double> xs(rows.size()), ys(rows.size());
    bool finite = true;
    for (std::size_t k = 0; k < rows.size(); ++k) {
      xs[k] = rows[k][0];
      ys[k] = rows[k][1];
      finite = finite && std::isfinite(xs[k]) && std::isfinite(ys[k]);
    }
    std::size_t nx = 0, ny = 0;
    auto gx = finite ? regular_axis(xs, nx) : std::nullopt;
    auto gy = finite && gx ? regular_axis(ys, ny) : std::nullopt;
    if (gx && gy && nx * ny <= 2 * rows.size() && nx * ny >= rows.size()) {
      auto unit_of = [&](std::size_t col) -> std::optional<double> {
        for (auto it = headers.rbegin(); it != headers.rend(); ++it)
          if (it->size() == 3)
            if (auto u = unit_in_header((*it)[col])) return u;
        return std::nullopt;
      };
      auto xu = unit_of(0), yu = unit_of(1), zu = unit_of(2);
      if (!zu) zu = z_unit_header;
      if ((!xu || !yu || !zu) && options.default_unit.empty())
        out.warnings.emplace_back(
            "reader", fmt::format("{}: no length unit found for some of the x, y, z columns; read as metres", name));
      Map& m = out.map;
      m.nx = nx;
      m.ny = ny;
      m.x0 = gx->first * xu.value_or(fallback_unit);
      m.dx = gx->second * xu.value_or(fallback_unit);
      m.y0 = gy->first * yu.value_or(fallback_unit);
      m.dy = gy->second * yu.value_or(fallback_unit);
      out.x_unit_scale = xu.value_or(fallback_unit);
      out.z_unit_scale = zu.value_or(fallback_unit);
      m.heights.assign(nx * ny, std::numeric_limits<double>::quiet_NaN());
      std::vector<char> seen(nx * ny, 0);
      InvalidCount invalid;
      for (std::size_t k = 0; k < rows.size(); ++k) {
        auto i = std::size_t(std::llround((xs[k] - gx->first) / gx->second));
        auto j = std::size_t(std::llround((ys[k] - gy->first) / gy->second));
        std::size_t at = j * nx + i;
        if (seen[at])
          return make_error(fmt::format("{}:{}: grid node ({}, {}) appears twice in the x, y, z list", name,
                                        row_line[k], xs[k], ys[k]));
        seen[at] = 1;
        double z = rows[k][2];
        if (!std::isfinite(z)) {
          invalid.add(z);
          continue;
        }
        m.heights[at] = z * zu.value_or(fallback_unit);
      }
      if (invalid.total()) out.warnings.emplace_back("reader", invalid_warning(name, invalid, true));
      if (nx * ny > rows.size())
        out.warnings.emplace_back(
            "reader", fmt::format("{}: {} of the {} x {} grid nodes are missing from the list (invalid points)", name,
                                  nx * ny - rows.size(), nx, ny));
      if (m.valid_count() == 0) return make_error(fmt::format("{}: no valid point", name));
      out.is_map = true;
      out.format = ProfileFormat::Xyz;
      return out;
    }
  }

  // A matrix of heights: a header with sizes ("w= h=", "x-pixels", "nx"), or three or more
  // unnamed columns whose first is no abscissa (not monotonic). With ten or more unnamed
  // columns a monotonic first column must also be evenly spaced (within 1 % of its mean step)
  // to be an abscissa: the left edge of a tilted height matrix rises, but not in equal steps.
  const bool abscissa =
      monotonic(rows[0], ncols, rows.size()) && (ncols < 10 || evenly_spaced(rows[0], ncols, rows.size()));
  if (!forced && (matrix_header || (ncols >= 3 && !named_row && !abscissa))) {
    Map& m = out.map;
    m.nx = ncols;
    m.ny = rows.size();
    auto check_count = [&](const std::string* v, const char* key, std::size_t want, const char* what) -> Status {
      long long n;
      if (v && (!parse_int64(*v, n) || n != (long long)want))
        return make_error(fmt::format("{}: header says {} = {} but the matrix has {} {}", name, key, *v, want, what));
      return Ok{};
    };
    if (auto st = check_count(hp.get({"nx", "xpixels", "xres", "cols", "ncols"}), "nx", m.nx, "columns"); !st)
      return st.error();
    if (auto st = check_count(hp.get({"ny", "ypixels", "yres", "rows", "nrows"}), "ny", m.ny, "rows"); !st)
      return st.error();
    // Wyko/Vision ASCII export ("h=305 w=75", "pixel size=3.69862e-007 m", "height conversion
    // factor (-> m)=2.91818e-008"): w and h are the counts of columns and rows there, the
    // spacing is the pixel size and every value times the factor is a height in that unit.
    // (A pixel size beside a "w = 10 um" with a unit is only the fallback spacing.)
    auto pixel = header_length({"pixelsize"}, lateral_bare);
    if (!pixel) return pixel.error();
    auto bare_count = [&](const char* key) {
      const std::string* v = hp.get({key});
      long long n;
      return !v || parse_int64(*v, n);
    };
    const bool wyko = *pixel && bare_count("w") && bare_count("h");
    if (wyko) {
      if (auto st = check_count(hp.get({"w"}), "w", m.nx, "columns"); !st) return st.error();
      if (auto st = check_count(hp.get({"h"}), "h", m.ny, "rows"); !st) return st.error();
    }
    auto w = wyko ? Result<std::optional<double>>(std::optional<double>{})
                  : header_length({"w", "width", "xlength", "xreal", "xsize"}, lateral_bare);
    if (!w) return w.error();
    auto h = wyko ? Result<std::optional<double>>(std::optional<double>{})
                  : header_length({"h", "height", "ylength", "yreal", "ysize"}, lateral_bare);
    if (!h) return h.error();
    auto dxh = header_length({"dx", "xspacing", "spacing", "xstep", "step"}, lateral_bare);
    if (!dxh) return dxh.error();
    auto dyh = header_length({"dy", "yspacing", "ystep"}, lateral_bare);
    if (!dyh) return dyh.error();
    // Gwyddion's pixel convention: the real width is nx pixels of size dx.
    std::optional<double> dx = wyko ? *pixel : *w ? std::optional<double>(**w / double(m.nx)) : *dxh ? *dxh : *pixel;
    std::optional<double> dy = *h ? std::optional<double>(**h / double(m.ny)) : *dyh ? *dyh : dx;
    if (!dx && options.spacing > 0) dx = options.spacing;
    if (!dy && options.spacing > 0) dy = options.spacing;
    if (!dx || !dy)
      out.warnings.emplace_back(
          "reader",
          fmt::format("{}: a {} x {} matrix of heights without sizes; grid spacing set to 1 {} (give --spacing)", name,
                      m.nx, m.ny, options.default_unit.empty() ? "m" : options.default_unit));
    m.dx = dx.value_or(fallback_unit);
    m.dy = dy.value_or(fallback_unit);
    std::optional<double> zu = z_unit_header;
    if (spip) {
      double b2n = 1;
      std::optional<double> sc;
      if (!number_with_unit(*hp.get({"bit2nm"}), b2n, sc))
        return make_error(fmt::format("{}: Bit2nm '{}' is not a number", name, *hp.get({"bit2nm"})));
      zu = b2n * 1e-9;
    }
    for (const auto& [key, value] : hp.kv)
      if (key.rfind("heightconversionfactor", 0) == 0) {  // "height conversion factor (-> m)"
        const auto open = key.find("(>"), close = key.rfind(')');
        std::optional<double> unit = open != std::string::npos && close > open
                                         ? unit_scale(key.substr(open + 2, close - open - 2))
                                         : std::nullopt;
        double factor = 0;
        if (!unit || !parse_double(trim(value), factor) || !std::isfinite(factor))
          return make_error(fmt::format(
              "{}: height conversion factor '{}' (key '{}'): expected a number and a length unit in '(-> m)'", name,
              value, key));
        zu = factor * *unit;
      }
    if (!zu && options.default_unit.empty())
      out.warnings.emplace_back(
          "reader", fmt::format("{}: no unit for the heights; read as metres (give a unit to override)", name));
    m.heights = std::move(rows.v);
    InvalidCount invalid;
    mask_invalid(m.heights, invalid);
    const double zs = zu.value_or(fallback_unit);
    out.z_unit_scale = zs;
    // 0: no lateral numbers in the file (the spacing given, in metres, is the one lateral length).
    out.x_unit_scale = dx && !dxh->has_value() && !w->has_value() && !pixel->has_value() && options.spacing > 0
                           ? 0.0
                           : lateral_unit_seen.value_or(fallback_unit);
    for (double& v : m.heights) v *= zs;
    if (invalid.total()) out.warnings.emplace_back("reader", invalid_warning(name, invalid, true));
    if (m.valid_count() == 0) return make_error(fmt::format("{}: no valid point", name));
    out.is_map = true;
    out.format = ProfileFormat::Matrix;
    return out;
  }

  if (count_line_value >= 0 && std::size_t(count_line_value) != rows.size())
    out.warnings.emplace_back(
        "reader", fmt::format("{}: line {} gives a count of {} but {} data rows follow; all rows were read", name,
                              count_line_number, count_line_value, rows.size()));

  // Columns.
  int xc = options.x_column, zc = options.z_column;
  const std::vector<std::string_view>* named = nullptr;
  for (auto it = headers.rbegin(); it != headers.rend(); ++it)
    if (it->size() == ncols) {
      named = &*it;
      break;
    }
  // A column named "valid" (HFM-style `X;Y;valid` with a `[1/0]` unit line) flags the points: 0 =
  // invalid (dropped), 1 = valid.
  int vc = -1;
  for (const auto& h : headers)
    if (h.size() == ncols)
      for (std::size_t c = 0; c < ncols; ++c)
        if (lower_ascii(trim(h[c])) == "valid") vc = int(c);
  if (xc < 0 || zc < 0) {
    bool index_col = false;
    if (ncols - (vc >= 0 ? 1 : 0) >= 3) {  // an index column before x and z (not counting "valid")
      if (named && is_index_name((*named)[0])) index_col = true;
      bool consecutive = true;
      for (std::size_t k = 0; k < rows.size() && consecutive; ++k)
        consecutive = rows[k][0] == rows[0][0] + double(k) && (rows[0][0] == 0 || rows[0][0] == 1);
      index_col = index_col || consecutive;
    }
    if (xc < 0) xc = index_col ? 1 : 0;
    if (zc < 0) zc = xc + 1;
    const std::size_t used = std::size_t(std::max(xc, zc)) + 1 + (vc == std::max(xc, zc) + 1 ? 1 : 0);
    if (ncols > used || (index_col && ncols > 3))
      out.warnings.emplace_back(
          "reader",
          fmt::format("{}: {} columns; using column {} as x and column {} as z (0-based)", name, ncols, xc, zc));
  }
  if (std::size_t(std::max(xc, zc)) >= ncols || xc == zc)
    return make_error(
        fmt::format("{}: columns x={} and z={} requested but the data has {} columns", name, xc, zc, ncols));

  // Units: the last header line (or comment) naming a unit for the column.
  auto find_unit = [&](int col) -> std::optional<double> {
    for (auto it = headers.rbegin(); it != headers.rend(); ++it) {
      const auto& h = *it;
      std::size_t idx = col;
      if (h.size() != ncols) {
        if (h.size() == 2 && ncols == 3 && (col == xc || col == zc))
          idx = col == xc ? 0 : 1;  // unit line for x, z
        else
          continue;
      }
      if (auto s = unit_in_header(h[idx])) return s;
    }
    return std::nullopt;
  };
  double fallback = 1.0;
  if (!options.default_unit.empty()) {
    auto s = unit_scale(options.default_unit);
    if (!s) return make_error(fmt::format("unknown unit '{}' (expected m, mm, um, nm)", options.default_unit));
    fallback = *s;
  }
  // A column without a unit takes the override given for its axis, else default_unit, else metres
  // (with a warning); a column with one is rescaled by the override later (read_surface).
  auto axis_fallback = [&](const std::string& unit) -> Result<std::optional<double>> {
    if (unit.empty()) return std::optional<double>{};
    auto s = unit_scale(unit);
    if (!s) return make_error(fmt::format("unknown unit '{}' (expected m, mm, um, nm)", unit));
    return std::optional<double>{*s};
  };
  auto xo = axis_fallback(options.x_unit), zo = axis_fallback(options.z_unit);
  if (!xo) return xo.error();
  if (!zo) return zo.error();
  auto xu = find_unit(xc), zu = find_unit(zc);
  // A unit the header states by key when the columns name none: the heights' is the one read
  // above (z_unit_header: "# z unit: nm", or "# units: um" for the whole file); x takes its own
  // ("# x unit: um") or the whole file's, and a word that is no length unit is an error naming it.
  if (!xu && !*xo)
    if (const std::string* u = hp.get({"xunit", "xunits", "lateralunit", "lateralunits", "unit", "units"})) {
      xu = unit_scale(*u);
      if (!xu)
        return make_error(
            fmt::format("{}: x unit '{}' in the header is not a length unit (expected m, mm, um, nm)", name, *u));
    }
  if (!zu && !*zo) zu = z_unit_header;
  const bool x_none = !xu && !*xo, z_none = !zu && !*zo;
  if ((x_none || z_none) && options.default_unit.empty())
    out.warnings.emplace_back(
        "reader",
        fmt::format("{}: no length unit found for the {} column; values read as metres (give a unit to override)", name,
                    x_none && z_none ? "x and z"
                    : x_none         ? "x"
                                     : "z"));
  double xs = xu.value_or(xo->value_or(fallback)), zs = zu.value_or(zo->value_or(fallback));
  out.x_unit_scale = xs;
  out.z_unit_scale = zs;

  // An x column that is uniform within the digits it is printed with (an exporter that rounds
  // x, e.g. steps alternating 0.1 and 0.2 um for 0.15625 um) is read as the uniform grid: the
  // rounding's alternating steps are slopes that the surface does not have.
  std::optional<PrintedGrid> grid;
  if (std::size_t(xc) < rows.dcols) {
    std::vector<double> xcol(rows.size());
    std::vector<signed char> xdig(rows.size());
    for (std::size_t k = 0; k < rows.size(); ++k) {
      xcol[k] = rows[k][xc];
      xdig[k] = rows.digits[k * rows.dcols + std::size_t(xc)];
    }
    // A spacing the header states ("# spacing: 0.5 um", Dektak's "Resolution"), in the x unit.
    std::optional<double> header_dx;
    if (const std::string* v = hp.get({"spacing", "dx", "xspacing", "step", "xstep", "sampling", "samplinginterval",
                                       "interval", "increment", "xincrement", "resolution", "xresolution"})) {
      double d = 0;
      std::optional<double> sc;
      if (number_with_unit(*v, d, sc) && d > 0) header_dx = d * sc.value_or(xs) / xs;
    }
    grid = printed_uniform_grid(xcol, xdig, header_dx);
    if (grid && grid->changed) {
      std::string stated;
      if (const std::string* v = hp.get({"spacing", "dx", "xspacing", "step", "xstep", "sampling", "samplinginterval",
                                         "interval", "increment", "xincrement", "resolution", "xresolution"}))
        stated = grid->from_header ? fmt::format("the header's stated spacing '{}'", *v)
                                   : fmt::format(
                                         "the whole column's (x_last - x_0) / (n - 1); the header's '{}' "
                                         "does not fit the column within its digits",
                                         *v);
      else
        stated = "the whole column's (x_last - x_0) / (n - 1)";
      out.warnings.emplace_back(
          "reader", fmt::format("{}: the x column is a uniform grid within the precision it is printed with (steps "
                                "{:.6g} to {:.6g} m, last "
                                "printed digit {:.3g} m); read as the uniform grid of spacing {:.10g} m: {}",
                                name, grid->min_step * xs, grid->max_step * xs, grid->unit * xs,
                                std::abs(grid->dx) * xs, stated));
    }
  }

  if (vc == xc || vc == zc) vc = -1;
  InvalidCount invalid;
  std::size_t flagged = 0;
  out.curve.x.reserve(rows.size());
  out.curve.z.reserve(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    double x = rows[k][xc], z = rows[k][zc];
    if (vc >= 0) {
      const double v = rows[k][vc];
      if (v != 0 && v != 1)
        return make_error(
            fmt::format("{}:{}: 'valid' column holds {} (expected 1 = valid or 0 = invalid)", name, row_line[k], v));
      if (v == 0) {
        ++flagged;
        continue;
      }
    }
    if (!std::isfinite(x))
      return make_error(
          fmt::format("{}:{}: x is {} (expected a finite number; only heights may be invalid)", name, row_line[k], x));
    if (!std::isfinite(z)) {
      invalid.add(z);
      continue;
    }
    if (grid && grid->changed) x = grid->x0 + double(k) * grid->dx;
    out.curve.x.push_back(x * xs);
    out.curve.z.push_back(z * zs);
  }
  if (invalid.total()) out.warnings.emplace_back("reader", invalid_warning(name, invalid, false));
  if (flagged)
    out.warnings.emplace_back(
        "reader", fmt::format("{}: {} points flagged invalid (0) in the 'valid' column dropped", name, flagged));
  if (out.curve.x.size() < 2) return make_error(fmt::format("{}: fewer than 2 points with finite values", name));
  return out;
}

bool looks_like_dektak(std::string_view text) {
  auto lines = split_lines(text.substr(0, std::min<std::size_t>(text.size(), 1 << 16)));
  bool scan_data = false, lateral = false;
  for (const auto& l : lines) {
    auto t = lower_ascii(trim(l.text));
    if (t == "scan data" || t == "scan data,") scan_data = true;
    if (t.rfind("lateral", 0) == 0) lateral = true;
  }
  return scan_data && lateral;
}

Result<SurfaceData> parse_dektak(std::string_view text, const std::string& name, const ReadOptions& options) {
  auto lines = split_lines(text);
  std::size_t k = 0;
  while (k < lines.size() && lower_ascii(trim(lines[k].text)).rfind("scan data", 0) != 0) ++k;
  if (k == lines.size()) return make_error(fmt::format("{}: Dektak export without a 'Scan Data' section", name));
  // The section runs from the column header to the first blank line after the data.
  std::size_t first = k + 1;
  while (first < lines.size() && trim(lines[first].text).empty()) ++first;
  if (first >= lines.size())
    return make_error(fmt::format("{}:{}: 'Scan Data' section is empty", name, lines[k].number));
  std::size_t last = first + 1;
  bool data_seen = false;
  for (; last < lines.size(); ++last) {
    auto t = trim(lines[last].text);
    if (t.empty()) {
      if (data_seen) break;
      continue;
    }
    data_seen = true;
  }
  const char* b = lines[first].text.data();
  const char* e = last < lines.size() ? lines[last].text.data() : text.data() + text.size();
  // Keep the file's line numbers in messages: prefix as many newlines as lines skipped.
  std::string section(lines[first].number - 1, '\n');
  // The stated resolution ("Resolution,0.156 um/sample") as a header line of the section, where
  // the x column's reading compares it with the column (printed_uniform_grid).
  for (std::size_t j = 0; j < k && !section.empty(); ++j) {
    auto t = trim(lines[j].text);
    if (lower_ascii(t).rfind("resolution,", 0) != 0) continue;
    std::string value(trim(t.substr(11)));
    if (auto slash = value.find('/'); slash != std::string::npos) value.resize(slash);
    section = fmt::format("# resolution = {}{}", trim(value), section);
    break;
  }
  section.append(b, e);
  auto r = parse_delimited(section, name, options);
  if (!r) return r;
  r->format = ProfileFormat::Dektak;
  return r;
}

namespace {

bool header_key(std::string_view line, std::string& key, std::string& value) {
  auto t = trim(line);
  if (t.empty() || t.front() != '#') return false;
  t.remove_prefix(1);
  auto c = t.find(':');
  if (c == std::string_view::npos) return false;
  key = lower_ascii(trim(t.substr(0, c)));
  value = std::string(trim(t.substr(c + 1)));
  return true;
}

bool is_width_key(const std::string& k) {
  for (const char* w : {"width", "breite", "largeur", "ancho", "anchura", "larghezza", "largura",
                        "szeroko\xc5\x9b\xc4\x87", "\xc5\xa1\xc3\xad\xc5\x99ka", "x size", "x-size", "x range"})
    if (k == w) return true;
  return false;
}
bool is_height_key(const std::string& k) {
  for (const char* w : {"height", "h\xc3\xb6he", "hoehe", "hauteur", "alto", "altura", "altezza",
                        "wysoko\xc5\x9b\xc4\x87", "v\xc3\xbd\xc5\xa1ka", "y size", "y-size", "y range"})
    if (k == w) return true;
  return false;
}

}  // namespace

bool looks_like_gwyddion(std::string_view text) {
  auto lines = split_lines(text.substr(0, std::min<std::size_t>(text.size(), 1 << 14)));
  int lengths = 0;
  bool width = false;
  std::size_t first_row_fields = 0;
  std::string k, v;
  for (const auto& l : lines) {
    auto t = trim(l.text);
    if (!t.empty() && t.front() != '#' && first_row_fields == 0) first_row_fields = split_fields(t, ' ').size();
    if (!header_key(l.text, k, v)) continue;
    if (is_width_key(k) || is_height_key(k)) width = true;
    if (length_value(v)) ++lengths;
  }
  // Width/Height keys, or (other languages) two length-valued keys above a matrix of >= 3
  // columns; a commented two-column profile ("# Length: 10 um") stays a profile.
  return width || (lengths >= 2 && first_row_fields >= 3);
}

Result<SurfaceData> parse_gwyddion(std::string_view text, const std::string& name, const ReadOptions& options) {
  auto lines = split_lines(text);
  std::optional<double> width, height, zscale, width_scale;
  std::vector<double> positional;  // length-valued header entries in order (fallback for unknown languages)
  std::vector<double> values;
  std::size_t nx = 0, ny = 0, first_line = 0;
  std::string k, v;
  std::vector<double> row;
  for (const Line& ln : lines) {
    auto t = trim(ln.text);
    if (t.empty()) continue;
    if (t.front() == '#') {
      if (!header_key(t, k, v)) continue;
      auto len = length_value(v);
      if (is_width_key(k) && len) {
        width = len;
        double number = 0;
        std::optional<double> unit;
        if (number_with_unit(v, number, unit) && unit) width_scale = unit;
      } else if (is_height_key(k) && len)
        height = len;
      else if (len)
        positional.push_back(*len);
      if (k.find("value unit") != std::string::npos || k.find("z unit") != std::string::npos || k == "einheit" ||
          k.find("werteinheit") != std::string::npos) {
        auto s = unit_scale(v);
        if (!s)
          return make_error(
              fmt::format("{}:{}: value unit '{}' is not a length unit (expected m, mm, um, nm)", name, ln.number, v));
        zscale = s;
      }
      continue;
    }
    auto f = split_fields(t, ' ');
    if (!numeric_fields(f, false, &row)) {
      bool comma = numeric_fields(f, true, &row);
      if (!comma)
        return make_error(
            fmt::format("{}:{}: expected a row of numbers, found '{}'", name, ln.number, std::string(t.substr(0, 60))));
    }
    if (ny == 0) {
      nx = row.size();
      first_line = ln.number;
    } else if (row.size() != nx) {
      return make_error(
          fmt::format("{}:{}: expected {} values like line {}, found {}", name, ln.number, nx, first_line, row.size()));
    }
    if (values.size() + row.size() > options.max_points)
      return make_error(fmt::format("{}: more than {} points (limit max_points)", name, options.max_points));
    values.insert(values.end(), row.begin(), row.end());
    ++ny;
  }
  if (ny == 0 || nx == 0) return make_error(fmt::format("{}: no rows of numbers found", name));
  SurfaceData out;
  out.format = ProfileFormat::Gwyddion;
  out.is_map = true;
  if (!width && !positional.empty()) width = positional[0];
  if (!height && positional.size() >= 2) height = positional[1];
  double fallback = 1.0;
  if (!options.default_unit.empty()) {
    auto s = unit_scale(options.default_unit);
    if (!s) return make_error(fmt::format("unknown unit '{}' (expected m, mm, um, nm)", options.default_unit));
    fallback = *s;
  }
  if (!width || !height)
    out.warnings.emplace_back("reader", fmt::format("{}: no Width/Height header; grid spacing set to 1 {}", name,
                                                    options.default_unit.empty() ? "m" : options.default_unit));
  if (!zscale && options.default_unit.empty())
    out.warnings.emplace_back("reader", fmt::format("{}: no 'Value units' header; heights read as metres", name));
  Map& m = out.map;
  m.nx = nx;
  m.ny = ny;
  // Gwyddion: the real width is nx pixels of size dx (pixel-centred samples).
  m.dx = width ? *width / double(nx) : fallback;
  m.dy = height ? *height / double(ny) : fallback;
  if (!(m.dx > 0) || !(m.dy > 0) || !std::isfinite(m.dx) || !std::isfinite(m.dy))
    return make_error(fmt::format("{}: Width and Height must be positive", name));
  double zs = zscale.value_or(fallback);
  out.z_unit_scale = zs;
  if (!width || !height) out.x_unit_scale = fallback;
  if (width_scale) out.x_unit_scale = *width_scale;
  m.heights = std::move(values);
  InvalidCount invalid;
  mask_invalid(m.heights, invalid);
  for (double& h : m.heights) h *= zs;
  if (invalid.total()) out.warnings.emplace_back("reader", invalid_warning(name, invalid, true));
  if (invalid.total() == m.heights.size())
    return make_error(fmt::format("{}: no valid point (every height is NaN or infinite)", name));
  return out;
}

}  // namespace io_detail
}  // namespace frictal
