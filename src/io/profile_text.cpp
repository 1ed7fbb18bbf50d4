// Delimited-text line profiles (CSV/TSV/whitespace) and the CSV writer.
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fmt/core.h>
#include <fstream>
#include <sstream>

#include "frictal/io.hpp"

namespace frictal {
namespace {

constexpr std::size_t kMaxFileBytes = std::size_t{2} << 30;  // 2 GiB: beyond that, refuse

bool parse_double(const std::string& tok, double& out) {
  if (tok.empty()) return false;
  const char* b = tok.c_str();
  char* e = nullptr;
  errno = 0;
  out = std::strtod(b, &e);
  if (e == b || errno == ERANGE) return false;
  while (*e == ' ' || *e == '\t' || *e == '\r') ++e;
  return *e == '\0';
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> f;
  char delim = 0;
  for (char c : {',', ';', '\t'})
    if (line.find(c) != std::string::npos) {
      delim = c;
      break;
    }
  if (delim) {
    std::string cur;
    for (char c : line) {
      if (c == delim) {
        f.push_back(cur);
        cur.clear();
      } else if (c != '\r') {
        cur += c;
      }
    }
    f.push_back(cur);
    for (auto& s : f) {
      std::size_t a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
      s = (a == std::string::npos) ? std::string() : s.substr(a, b - a + 1);
    }
  } else {
    std::istringstream is(line);
    std::string t;
    while (is >> t) f.push_back(t);
  }
  return f;
}

}  // namespace

Result<Curve> parse_curve_text(const std::string& text, const std::string& name) {
  Curve c;
  std::istringstream in(text);
  std::string line;
  std::size_t lineno = 0;
  bool seen_data = false;
  while (std::getline(in, line)) {
    ++lineno;
    std::size_t a = line.find_first_not_of(" \t\r");
    if (a == std::string::npos || line[a] == '#') continue;
    auto fields = split_fields(line);
    if (fields.size() < 2)
      return make_error(fmt::format("{}:{}: expected two columns (x, z), found {}", name, lineno, fields.size()));
    double x, z;
    const bool okx = parse_double(fields[0], x), okz = parse_double(fields[1], z);
    if (!okx || !okz) {
      if (!seen_data && !okx) continue;  // header line
      return make_error(fmt::format("{}:{}: '{}' is not a number", name, lineno, okx ? fields[1] : fields[0]));
    }
    if (!std::isfinite(x) || !std::isfinite(z))
      return make_error(fmt::format("{}:{}: values must be finite numbers, got x = {}, z = {}", name, lineno, fields[0], fields[1]));
    c.x.push_back(x);
    c.z.push_back(z);
    seen_data = true;
  }
  if (c.size() < 2)
    return make_error(fmt::format("{}: a profile needs at least 2 data points, found {}", name, c.size()));
  return c;
}

Result<Curve> read_curve(const std::string& path, const ReadOptions&) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return make_error(fmt::format("{}: cannot open file", path));
  f.seekg(0, std::ios::end);
  const auto size = static_cast<std::size_t>(f.tellg());
  if (size > kMaxFileBytes) return make_error(fmt::format("{}: file is too large ({} bytes)", path, size));
  f.seekg(0);
  std::string text(size, '\0');
  f.read(text.data(), static_cast<std::streamsize>(size));
  if (!f) return make_error(fmt::format("{}: read error", path));
  if (size == 0) return make_error(fmt::format("{}: file is empty", path));
  return parse_curve_text(text, path);
}

Result<Profile> read_profile(const std::string& path, const ReadOptions& options) {
  auto c = read_curve(path, options);
  if (!c) return c.error();
  return as_profile(*c, path);
}

Status write_profile_csv(const std::string& path, const Curve& c) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) return make_error(fmt::format("{}: cannot open for writing", path));
  std::string buf = "x_m,z_m\n";
  for (std::size_t i = 0; i < c.size(); ++i) buf += fmt::format("{:.17g},{:.17g}\n", c.x[i], c.z[i]);
  const bool ok = std::fwrite(buf.data(), 1, buf.size(), f) == buf.size();
  if (std::fclose(f) != 0 || !ok) return make_error(fmt::format("{}: write failed", path));
  return Ok{};
}

Status write_profile_csv(const std::string& path, const Profile& p) { return write_profile_csv(path, as_curve(p)); }

}  // namespace frictal
