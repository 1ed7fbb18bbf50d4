// Canonical parameter text, hashing and seeds: the identity of a task.
#include <charconv>
#include <cmath>
#include <cstdio>

#include <fmt/core.h>

#include "frictal/study.hpp"
#include "util/json_text.hpp"

namespace frictal::study {

using util::json_real;
using util::json_string;

std::string canonical(const Value& v) {
  struct V {
    std::string operator()(std::int64_t i) const { return std::to_string(i); }
    std::string operator()(double d) const { return json_real(d, true); }
    std::string operator()(const std::string& s) const { return json_string(s); }
    std::string operator()(bool b) const { return b ? "true" : "false"; }
  };
  return std::visit(V{}, v);
}

std::string canonical(const Params& p) {
  std::string s = "{";
  bool first = true;
  for (const auto& [k, v] : p) {  // std::map: sorted by name
    if (!first) s += ',';
    first = false;
    s += json_string(k);
    s += ':';
    s += canonical(v);
  }
  return s + "}";
}

namespace {
std::uint64_t splitmix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
std::uint64_t fnv1a(const std::string& text, std::uint64_t basis) {
  std::uint64_t h = basis;
  for (unsigned char c : text) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}
}  // namespace

std::uint64_t hash64(const std::string& text) { return splitmix(fnv1a(text, 0xcbf29ce484222325ULL)); }

std::string digest(const std::string& text) {
  return fmt::format("{:016x}{:016x}", hash64(text), splitmix(fnv1a(text, 0x84222325cbf29ce4ULL) ^ 0x5bd1e995ULL));
}

std::string content_address(const std::string& kind, int kind_version, const Params& params, bool uses_seed,
                            std::uint64_t seed) {
  // {"kind":"tilt","kind_version":2,"params":{...},"seed":null}: canonical JSON, one line.
  return digest(fmt::format(R"({{"kind":{},"kind_version":{},"params":{},"seed":{}}})", json_string(kind), kind_version,
                            canonical(params), uses_seed ? json_string(std::to_string(seed)) : std::string("null")));
}

std::uint64_t task_seed(std::uint64_t study_seed, const Params& seed_params) {
  return hash64(std::to_string(study_seed) + ":" + canonical(seed_params));
}

std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t stream) {
  return splitmix(seed ^ splitmix(stream + 0x632be59bd9b4e019ULL));
}

Result<double> get_real(const Params& p, const std::string& name) {
  auto it = p.find(name);
  if (it == p.end()) return make_error(fmt::format("parameter '{}' is required", name));
  if (auto* d = std::get_if<double>(&it->second)) return *d;
  if (auto* i = std::get_if<std::int64_t>(&it->second)) return static_cast<double>(*i);
  return make_error(fmt::format("parameter '{}': expected a number, got {}", name, canonical(it->second)));
}
Result<double> get_real(const Params& p, const std::string& name, double fallback) {
  if (!p.count(name)) return fallback;
  return get_real(p, name);
}
Result<std::int64_t> get_int(const Params& p, const std::string& name) {
  auto it = p.find(name);
  if (it == p.end()) return make_error(fmt::format("parameter '{}' is required", name));
  if (auto* i = std::get_if<std::int64_t>(&it->second)) return *i;
  if (auto* d = std::get_if<double>(&it->second); d && std::floor(*d) == *d && std::abs(*d) < 9e15)
    return static_cast<std::int64_t>(*d);
  return make_error(fmt::format("parameter '{}': expected an integer, got {}", name, canonical(it->second)));
}
Result<std::int64_t> get_int(const Params& p, const std::string& name, std::int64_t fallback) {
  if (!p.count(name)) return fallback;
  return get_int(p, name);
}
Result<std::string> get_string(const Params& p, const std::string& name, const std::string& fallback) {
  auto it = p.find(name);
  if (it == p.end()) return fallback;
  if (auto* s = std::get_if<std::string>(&it->second)) return *s;
  return make_error(fmt::format("parameter '{}': expected a string, got {}", name, canonical(it->second)));
}

}  // namespace frictal::study
