// What front ends show of a store: its status, the report as Markdown, and the CSV export
// (docs/studies.md). The CLI and the Python package call these; the SQL stays in store.cpp.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "frictal/study.hpp"

namespace frictal::study {
namespace {

namespace fs = std::filesystem;

Status write_text(const fs::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary);
  if (!f) return make_error(ErrorCode::Io, fmt::format("{}: cannot open for writing", p.string()));
  f << text;
  if (!f) return make_error(ErrorCode::Io, fmt::format("{}: write failed", p.string()));
  return Ok{};
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string o = "\"";
  for (char c : s) o += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return o + "\"";
}

std::string value_text(const Value& v) {
  if (auto* s = std::get_if<std::string>(&v)) return csv_field(*s);
  return canonical(v);
}

}  // namespace

Result<StoreStatus> store_status(Store& store, const TaskRegistry& registry) {
  auto meta = store.meta();
  if (!meta) return meta.error();
  auto c = store.counts();
  if (!c) return c.error();
  auto parts = store.part_counts();
  if (!parts) return parts.error();
  StoreStatus s;
  auto& m = *meta;
  s.study = m["study_name"];
  s.description = m["study_description"];
  s.scale = m["scale"];
  s.study_hash = m["study_hash"];
  s.schema_version = std::atoi(m["schema_version"].c_str());
  s.frictal_version = m["frictal_version"];
  s.tasks = *c;
  auto claimed = store.claimed();
  if (!claimed) return claimed.error();
  s.claimed = *claimed;
  auto versions = store.version_counts();
  if (!versions) return versions.error();
  for (const auto& p : *parts) {
    StoreStatus::PartStatus ps;
    ps.part = p.part;
    ps.kind = p.kind;
    ps.done = p.done;
    ps.failed = p.failed;
    ps.pending = p.pending;
    ps.available = registry.find(p.kind) != nullptr;
    ps.unavailable_reason = registry.unavailable_reason(p.kind);
    ps.kind_version = registry.version(p.kind);
    for (const auto& v : *versions) {
      if (v.part != p.part) continue;
      ps.done_by_kind_version[v.kind_version] += v.done;
      ps.done_by_frictal_version[v.frictal_version] += v.done;
    }
    std::string other;
    for (const auto& [kv, n] : ps.done_by_kind_version) {
      if (kv == ps.kind_version) continue;
      other +=
          fmt::format("{}{} tasks by {}", other.empty() ? "" : ", ", n,
                      kv == 0 ? std::string("an unrecorded version (schema-1 store)") : fmt::format("version {}", kv));
    }
    if (!other.empty())
      ps.version_note = fmt::format(
          "part '{}': {} of kind '{}', but this build has version {}; their results may "
          "differ from what this build computes (a new store recomputes them)",
          p.part, other, p.kind, ps.kind_version);
    s.parts.push_back(std::move(ps));
  }
  return s;
}

std::string done_versions_text(const StoreStatus::PartStatus& part) {
  std::string by;
  for (const auto& [v, n] : part.done_by_kind_version)
    by += fmt::format("{}{} by {}", by.empty() ? "" : ", ", n,
                      v ? fmt::format("v{}", v) : std::string("unrecorded version"));
  for (const auto& [v, n] : part.done_by_frictal_version)
    by += fmt::format("{}{} by frictal {}", by.empty() ? "" : ", ", n, v.empty() ? std::string("?") : v);
  return by;
}

std::string render_markdown(const Report& r) {
  std::string s = fmt::format("# {}\n\n", r.title);
  for (const auto& l : r.lines) s += l + "\n";
  if (!r.findings.empty()) {
    s += "\n## Findings of the paper checked against this store\n\n";
    for (const auto& f : r.findings) {
      s += fmt::format("- [{}] {}\n", f.supported ? "SUPPORTED" : "NOT SUPPORTED", f.claim);
      for (std::size_t i = 0; i < f.evidence.size(); ++i) {
        s += "    " + f.evidence[i] + "\n";
        if (i == 0 && !f.supported && !f.cause.empty()) s += "    cause: " + f.cause + "\n";
      }
      if (f.evidence.empty() && !f.supported && !f.cause.empty()) s += "    cause: " + f.cause + "\n";
    }
  }
  return s;
}

namespace {

nlohmann::json claim_json(const Claim& c) {
  return {{"id", c.id},
          {"source", c.paper ? "paper" : "frictal"},
          {"statement", c.statement},
          {"where", c.where},
          {"figures", c.figures},
          {"applies_to", c.applies_to},
          {"superseded_by", c.superseded_by}};
}

}  // namespace

Result<std::string> render_json(const std::vector<Report>& reports) {
  auto conclusions = conclude(reports);
  if (!conclusions) return conclusions.error();
  nlohmann::json j;
  j["reports"] = nlohmann::json::array();
  for (const auto& r : reports) {
    nlohmann::json jr = {{"study", r.study}, {"title", r.title}, {"findings", nlohmann::json::array()}};
    for (const auto& f : r.findings) {
      const Claim* c = find_claim(f.claim_id);  // conclude() checked every id
      // The first evidence line is the criterion with the measured value, the others the numbers.
      std::string criterion = f.evidence.empty() ? std::string() : f.evidence.front();
      if (criterion.rfind("criterion: ", 0) == 0) criterion.erase(0, 11);
      nlohmann::json numbers = nlohmann::json::array();
      for (std::size_t i = 1; i < f.evidence.size(); ++i) numbers.push_back(f.evidence[i]);
      jr["findings"].push_back({{"claim_id", f.claim_id},
                                {"source", c->paper ? "paper" : "frictal"},
                                {"figures", c->figures},
                                {"part", f.part},
                                {"claim", f.claim},
                                {"criterion", criterion},
                                {"numbers", numbers},
                                {"verdict", f.supported ? "supported" : "not supported"},
                                {"cause", f.cause}});
    }
    j["reports"].push_back(std::move(jr));
  }
  j["conclusions"] = nlohmann::json::array();
  for (const auto& k : *conclusions) {
    nlohmann::json jc = claim_json(k.claim);
    jc["verdict"] = verdict_name(k.verdict);
    jc["cause"] = k.cause;
    jc["uncaused"] = k.uncaused;
    jc["checks"] = nlohmann::json::array();
    for (const auto& ch : k.checks)
      jc["checks"].push_back({{"study", ch.study},
                              {"part", ch.part},
                              {"verdict", ch.supported ? "supported" : "not supported"},
                              {"cause", ch.cause}});
    j["conclusions"].push_back(std::move(jc));
  }
  j["claims"] = nlohmann::json::array();
  for (const auto& c : claims()) j["claims"].push_back(claim_json(c));
  return j.dump(1);
}

Result<std::vector<std::string>> export_csv(Store& store, const std::string& dir, const TaskRegistry& registry) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return make_error(ErrorCode::Io, fmt::format("{}: cannot create the directory: {}", dir, ec.message()));
  std::vector<std::string> files;
  auto put = [&](const std::string& name, const std::string& text) -> Status {
    if (auto s = write_text(fs::path(dir) / name, text); !s) return s;
    files.push_back(name);
    return Ok{};
  };
  auto tasks = store.tasks_csv();
  if (!tasks) return tasks.error();
  if (auto s = put("tasks.csv", *tasks); !s) return s.error();
  auto parts = store.part_counts();
  if (!parts) return parts.error();
  for (const auto& pc : *parts) {
    // The store may come from anywhere: a part name must not lead out of `dir`.
    if (pc.part.empty() || pc.part.size() > 100 || pc.part.front() == '.' ||
        pc.part.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.") !=
            std::string::npos)
      return make_error(
          fmt::format("{}: part name '{}' cannot name a file (expected letters, digits, '-', '_', '.'); "
                      "the store was not written by frictal",
                      dir, pc.part));
    auto rows_r = store.rows(pc.part, true);
    if (!rows_r) return rows_r.error();
    const auto& rows = *rows_r;
    std::set<std::string> pn, sn;
    for (const auto& r : rows) {
      for (const auto& [k, v] : r.params) pn.insert(k);
      for (const auto& [k, v] : r.output.scalars) sn.insert(k);
    }
    std::string wide = "task_id";
    for (const auto& k : pn) wide.append(",").append(csv_field(k));
    for (const auto& k : sn) wide.append(",").append(csv_field(k));
    wide += "\n";
    std::string longf = "task_id,name,index,value\n";
    for (const auto& r : rows) {
      wide += std::to_string(r.id);
      for (const auto& k : pn) wide.append(",").append(r.params.count(k) ? value_text(r.params.at(k)) : std::string{});
      for (const auto& k : sn) {
        auto it = r.output.scalars.find(k);
        wide.append(",").append(
            it != r.output.scalars.end() && std::isfinite(it->second) ? fmt::format("{}", it->second) : std::string{});
      }
      wide += "\n";
      for (const auto& [name, v] : r.output.arrays)
        for (std::size_t i = 0; i < v.size(); ++i)
          longf += fmt::format("{},{},{},{}\n", r.id, csv_field(name), i,
                               std::isfinite(v[i]) ? fmt::format("{}", v[i]) : "");
    }
    if (auto s = put(pc.part + ".csv", wide); !s) return s.error();
    if (auto s = put(pc.part + "-arrays.csv", longf); !s) return s.error();
    // PDFs pooled over replicates (pair), e.g. Fig. 16.
    auto pooled = pooled_pdfs(store, pc.part);
    if (!pooled) return pooled.error();
    if (!pooled->empty()) {
      std::string csv = "group";
      for (const auto& k : pn)
        if (k != "pair") csv.append(",").append(csv_field(k));
      csv += ",pdf,members,lo,hi,density\n";
      for (std::size_t g = 0; g < pooled->size(); ++g) {
        const PooledPdf& pp = (*pooled)[g];
        std::string prefix = std::to_string(g);
        for (const auto& k : pn)
          if (k != "pair") prefix.append(",").append(pp.params.count(k) ? value_text(pp.params.at(k)) : std::string{});
        for (std::size_t i = 0; i < pp.density.size(); ++i)
          csv += fmt::format("{},{},{},{},{},{}\n", prefix, pp.name, pp.members, pp.edges[i], pp.edges[i + 1],
                             pp.density[i]);
      }
      if (auto s = put(pc.part + "-pooled-pdfs.csv", csv); !s) return s.error();
    }
  }
  auto rep = report(store, registry);
  if (!rep) return rep.error();
  if (auto s = put("report.md", render_markdown(*rep)); !s) return s.error();
  return files;
}

}  // namespace frictal::study
