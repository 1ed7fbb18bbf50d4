// Study definitions: TOML parsing, grid expansion, seeds and the definition hash.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include "frictal/io.hpp"
#include "frictal/study.hpp"
#include "util/json_text.hpp"

namespace frictal::study {

using util::json_real;
using util::json_string;

namespace {

constexpr int kDefinitionFormat = 1;
constexpr std::int64_t kMaxTasks = 10'000'000;

std::string where(const std::string& origin, const toml::node& n) {
  const auto& s = n.source();
  if (s.begin.line) return fmt::format("{}:{}", origin, s.begin.line);
  return origin;
}

/// Reals in ranges are rounded to 12 significant digits so that 1.0 + 3 * 0.1 is 1.3, the
/// number a person would write (and the one the canonical text and seed see).
double tidy(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.12g", x);
  double y = std::strtod(buf, nullptr);
  return y == 0.0 ? 0.0 : y;
}

Result<Value> scalar_value(const toml::node& n, const std::string& ctx) {
  if (auto v = n.value_exact<std::int64_t>()) return Value{*v};
  if (auto v = n.value_exact<double>()) {
    if (!std::isfinite(*v)) return make_error(fmt::format("{}: expected a finite number", ctx));
    return Value{*v};
  }
  if (auto v = n.value_exact<std::string>()) return Value{*v};
  if (auto v = n.value_exact<bool>()) return Value{*v};
  return make_error(fmt::format("{}: expected a number, string, boolean, list or range table", ctx));
}

/// An axis: a scalar (one value), a list, or a range table {from, to, step|count} / {count}.
Result<std::vector<Value>> axis_values(const toml::node& n, const std::string& ctx, std::int64_t max_tasks) {
  std::vector<Value> out;
  if (const toml::array* a = n.as_array()) {
    if (a->empty()) return make_error(fmt::format("{}: the list is empty", ctx));
    for (const auto& e : *a) {
      auto v = scalar_value(e, ctx);
      if (!v) return v.error();
      out.push_back(*v);
    }
  } else if (const toml::table* t = n.as_table()) {
    for (auto&& [k, v] : *t) {
      const std::string key(k.str());
      if (key != "from" && key != "to" && key != "step" && key != "count")
        return make_error(fmt::format("{}: unknown range key '{}' (expected from, to, step, count)", ctx, key));
      if (!v.is_number()) return make_error(fmt::format("{}: range key '{}' must be a number", ctx, key));
    }
    const bool has_from = t->contains("from"), has_to = t->contains("to"), has_step = t->contains("step"),
               has_count = t->contains("count");
    auto is_int = [&](const char* k) { return !t->contains(k) || (*t)[k].is_integer(); };
    auto num = [&](const char* k) { return (*t)[k].value<double>().value_or(0.0); };
    if (!has_from && !has_to && has_count && !has_step) {  // replicates 0 .. count-1
      if (!is_int("count") || num("count") < 1)
        return make_error(fmt::format("{}: count must be an integer >= 1", ctx));
      const auto c = (*t)["count"].value<std::int64_t>().value();
      if (c > max_tasks) return make_error(fmt::format("{}: count {} is too large", ctx, c));
      for (std::int64_t i = 0; i < c; ++i) out.push_back(Value{i});
      return out;
    }
    if (!has_from || !has_to || (has_step && has_count))
      return make_error(fmt::format("{}: a range needs from and to, and either step or count (or only count)", ctx));
    const double from = num("from"), to = num("to");
    if (!(to >= from)) return make_error(fmt::format("{}: expected from <= to", ctx));
    if (is_int("from") && is_int("to") && is_int("step") && !has_count) {
      const auto f = (*t)["from"].value<std::int64_t>().value(), e = (*t)["to"].value<std::int64_t>().value();
      const std::int64_t s = has_step ? (*t)["step"].value<std::int64_t>().value() : 1;
      if (s < 1) return make_error(fmt::format("{}: step must be >= 1", ctx));
      if ((e - f) / s + 1 > max_tasks) return make_error(fmt::format("{}: too many values", ctx));
      for (std::int64_t i = f; i <= e; i += s) out.push_back(Value{i});
      return out;
    }
    std::int64_t count = 0;
    double step = 0;
    if (has_count) {
      if (!is_int("count") || num("count") < 1)
        return make_error(fmt::format("{}: count must be an integer >= 1", ctx));
      count = (*t)["count"].value<std::int64_t>().value();
      step = count > 1 ? (to - from) / static_cast<double>(count - 1) : 0.0;
    } else {
      step = has_step ? num("step") : 1.0;
      if (!(step > 0)) return make_error(fmt::format("{}: step must be > 0", ctx));
      // Compared as a double first: (to - from) / step can exceed any integer (e.g. 4e123), and
      // its conversion would be undefined.
      const double n = std::floor((to - from) / step + 1e-9) + 1;
      if (!(n <= static_cast<double>(max_tasks))) return make_error(fmt::format("{}: too many values", ctx));
      count = static_cast<std::int64_t>(n);
    }
    if (count > max_tasks) return make_error(fmt::format("{}: too many values", ctx));
    for (std::int64_t i = 0; i < count; ++i) out.push_back(Value{tidy(from + step * static_cast<double>(i))});
  } else {
    auto v = scalar_value(n, ctx);
    if (!v) return v.error();
    out.push_back(*v);
  }
  return out;
}

std::string definition_text(const Study& s, const TaskRegistry& reg) {
  std::string d = fmt::format("{{\"format\":{},\"name\":{},\"seed\":{},\"scale\":\"{}\",\"parts\":[", kDefinitionFormat,
                              json_string(s.name), s.seed, s.quick ? "quick" : "full");
  for (std::size_t i = 0; i < s.parts.size(); ++i) {
    const Part& p = s.parts[i];
    if (i) d += ',';
    d += fmt::format("{{\"name\":{},\"kind\":{},\"kind_version\":{},\"seed_from\":[", json_string(p.name),
                     json_string(p.kind), reg.version(p.kind));
    for (std::size_t j = 0; j < p.seed_from.size(); ++j) {
      if (j) d += ',';
      d += json_string(p.seed_from[j]);
    }
    d += "],\"axes\":[";
    for (std::size_t j = 0; j < p.axes.size(); ++j) {
      if (j) d += ',';
      d += '[';
      d += json_string(p.axes[j].first);
      d += ",[";
      for (std::size_t m = 0; m < p.axes[j].second.size(); ++m) {
        if (m) d += ',';
        d += canonical(p.axes[j].second[m]);
      }
      d += "]]";
    }
    d += "]}";
  }
  return d + "]}";
}

}  // namespace

Result<Study> parse_study(const std::string& text, const std::string& origin, bool quick, const TaskRegistry& reg) {
  return parse_study(text, origin, quick, reg, kMaxTasks);
}

Result<Study> parse_study(const std::string& text, const std::string& origin, bool quick, const TaskRegistry& reg,
                          std::int64_t max_tasks) {
  toml::table doc;
  try {
    doc = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    return make_error(fmt::format("{}:{}:{}: {}", origin, e.source().begin.line, e.source().begin.column,
                                  std::string(e.description())));
  }
  Study s;
  s.quick = quick;
  const toml::table* head = doc["study"].as_table();
  if (!head) return make_error(fmt::format("{}: missing [study] table (name, description, seed)", origin));
  for (auto&& [k, v] : *head) {
    const std::string key(k.str());
    if (key != "name" && key != "description" && key != "seed")
      return make_error(
          fmt::format("{}: [study] has unknown key '{}' (expected name, description, seed)", where(origin, v), key));
  }
  auto name = (*head)["name"].value<std::string>();
  if (!name || name->empty()) return make_error(fmt::format("{}: [study] needs a non-empty name", origin));
  s.name = *name;
  s.description = (*head)["description"].value_or(std::string{});
  auto seed = (*head)["seed"].value<std::int64_t>();
  if (!seed || *seed < 0) return make_error(fmt::format("{}: [study] needs an integer seed >= 0", origin));
  s.seed = static_cast<std::uint64_t>(*seed);
  for (auto&& [k, v] : doc) {
    const std::string key(k.str());
    if (key != "study" && key != "part" && key != "figure")
      return make_error(fmt::format("{}: unknown top-level entry '{}' (expected [study], [[part]] and [[figure]])",
                                    where(origin, v), key));
  }
  // [[figure]]: what scripts/plot_studies.py draws from the store (docs/studies.md). Not part of
  // the definition (a figure changes no result); only its shape is checked here.
  if (const toml::node* figs = doc.get("figure")) {
    const toml::array* a = figs->as_array();
    if (!a)
      return make_error(fmt::format("{}: 'figure' must be an array of tables ([[figure]])", where(origin, *figs)));
    for (const auto& f : *a) {
      const toml::table* t = f.as_table();
      if (!t || !(*t)["file"].value<std::string>())
        return make_error(fmt::format("{}: every [[figure]] needs a file name (file = \"fig06\")", where(origin, f)));
      if (!t->contains("views") && !t->contains("panel"))
        return make_error(fmt::format("{}: [[figure]] '{}' needs views = [...] or [[figure.panel]] entries",
                                      where(origin, f), *(*t)["file"].value<std::string>()));
    }
  }
  const toml::array* parts = doc["part"].as_array();
  if (!parts || parts->empty()) return make_error(fmt::format("{}: expected at least one [[part]]", origin));
  std::set<std::string> part_names;
  for (const auto& pn : *parts) {
    const toml::table* pt = pn.as_table();
    if (!pt) return make_error(fmt::format("{}: [[part]] must be a table", where(origin, pn)));
    Part part;
    for (auto&& [k, v] : *pt) {
      const std::string key(k.str());
      if (key != "name" && key != "kind" && key != "description" && key != "seed_from" && key != "parameters" &&
          key != "quick")
        return make_error(
            fmt::format("{}: [[part]] has unknown key '{}' (expected name, kind, description, seed_from, "
                        "parameters, quick)",
                        where(origin, v), key));
    }
    part.name = (*pt)["name"].value_or(std::string{});
    part.kind = (*pt)["kind"].value_or(std::string{});
    part.description = (*pt)["description"].value_or(std::string{});
    if (part.name.empty() || part.kind.empty())
      return make_error(fmt::format("{}: every [[part]] needs a name and a kind", where(origin, pn)));
    // Part names become file names (PART.csv of the export): letters, digits, '-', '_', '.'.
    if (part.name.size() > 100 || part.name.front() == '.' ||
        part.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.") !=
            std::string::npos)
      return make_error(
          fmt::format("{}: part name '{}': expected at most 100 letters, digits, '-', '_' or '.' (not "
                      "first), as it names the part's files in an export",
                      where(origin, pn), part.name));
    if (!part_names.insert(part.name).second)
      return make_error(fmt::format("{}: part name '{}' is used twice", where(origin, pn), part.name));
    if (!reg.find(part.kind) && reg.unavailable_reason(part.kind).empty())
      return make_error(fmt::format("{}: part '{}': unknown task kind '{}' (known: {})", where(origin, pn), part.name,
                                    part.kind, fmt::format("{}", fmt::join(reg.names(), ", "))));
    const toml::table* params = (*pt)["parameters"].as_table();
    if (!params || params->empty())
      return make_error(fmt::format("{}: part '{}' needs a [part.parameters] table", where(origin, pn), part.name));
    std::map<std::string, const toml::node*> chosen;
    for (auto&& [k, v] : *params) chosen[std::string(k.str())] = &v;
    if (quick) {
      if (const toml::table* q = (*pt)["quick"].as_table()) {
        for (auto&& [k, v] : *q) {
          const std::string key(k.str());
          if (!chosen.count(key))
            return make_error(fmt::format("{}: part '{}': quick overrides '{}', which is not in [part.parameters]",
                                          where(origin, v), part.name, key));
          chosen[key] = &v;
        }
      }
    }
    for (const auto& [key, node] : chosen) {
      if (key == "part")
        return make_error(fmt::format("{}: 'part' is a reserved parameter name", where(origin, *node)));
      auto vals = axis_values(*node, fmt::format("{}: part '{}' parameter '{}'", where(origin, *node), part.name, key),
                              max_tasks);
      if (!vals) return vals.error();
      part.axes.emplace_back(key, std::move(*vals));
    }
    if (const toml::array* sf = (*pt)["seed_from"].as_array()) {
      for (const auto& e : *sf) {
        auto nm = e.value<std::string>();
        if (!nm || !chosen.count(*nm))
          return make_error(fmt::format("{}: part '{}': seed_from must list parameter names of the part",
                                        where(origin, e), part.name));
        part.seed_from.push_back(*nm);
      }
    }
    s.parts.push_back(std::move(part));
  }
  // Expand: parts in file order, axes sorted by name, the last axis varying fastest.
  std::int64_t id = 0;
  std::set<std::string> task_keys;  // a repeated list value would give two tasks with one key
  for (const Part& part : s.parts) {
    std::int64_t n = 1;
    for (const auto& ax : part.axes) {
      n *= static_cast<std::int64_t>(ax.second.size());
      if (n > max_tasks)
        return make_error(fmt::format("{}: part '{}' has more than {} tasks", origin, part.name, max_tasks));
    }
    if (id + n > max_tasks) return make_error(fmt::format("{}: more than {} tasks", origin, max_tasks));
    std::vector<std::size_t> idx(part.axes.size(), 0);
    for (std::int64_t t = 0; t < n; ++t) {
      Task task;
      task.id = id++;
      task.part = part.name;
      task.kind = part.kind;
      task.kind_version = reg.version(part.kind);
      for (std::size_t a = 0; a < part.axes.size(); ++a) task.params[part.axes[a].first] = part.axes[a].second[idx[a]];
      Params keyed = task.params;
      keyed["part"] = part.name;
      task.key = canonical(keyed);
      if (!task_keys.insert(task.key).second)
        return make_error(fmt::format("{}: part '{}': the task {} appears twice (a parameter list repeats a value)",
                                      origin, part.name, task.key));
      Params seed_params;
      if (part.seed_from.empty()) {
        seed_params = task.params;
      } else {
        for (const auto& nm : part.seed_from) seed_params[nm] = task.params.at(nm);
      }
      task.seed = task_seed(s.seed, seed_params);
      s.tasks.push_back(std::move(task));
      for (std::size_t a = part.axes.size(); a-- > 0;) {
        if (++idx[a] < part.axes[a].second.size()) break;
        idx[a] = 0;
      }
    }
  }
  s.definition = definition_text(s, reg);
  s.hash = digest(s.definition);
  return s;
}

Result<Study> load_study(const std::string& path, bool quick, const TaskRegistry& reg) {
  // A directory, FIFO or device is named as such (and a FIFO is never opened: it would block).
  if (auto st = check_input_file(path, "a study file (TOML)"); !st && st.error().code != ErrorCode::Io)
    return st.error();
  std::ifstream f(path, std::ios::binary);
  if (!f) return make_error(ErrorCode::Io, fmt::format("{}: cannot open the study file", path));
  std::stringstream ss;
  ss << f.rdbuf();
  return parse_study(ss.str(), path, quick, reg);
}

}  // namespace frictal::study
