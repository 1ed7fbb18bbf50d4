// Study reports: the report of a store is, per part, the report section of its task kind
// (each kind's unit owns its tables and the paper's findings it checks), and pooled PDFs.
#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/core.h>

#include "frictal/study.hpp"

namespace frictal::study {

double as_number(const Value& v) {
  if (auto* d = std::get_if<double>(&v)) return *d;
  if (auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  return std::nan("");
}

int as_int(const Value& v) {
  const double x = as_number(v);
  if (!std::isfinite(x) || x < -2147483648.0 || x > 2147483647.0) return -1;
  return static_cast<int>(x);
}

Result<std::vector<PooledPdf>> pooled_pdfs(Store& store, const std::string& part) {
  auto rows = store.rows(part, true);
  if (!rows) return rows.error();
  // Group key: part + canonical params without pair; then array prefix.
  struct Acc {
    Params params;
    std::vector<const Store::Row*> rows;
  };
  std::map<std::string, Acc> groups;
  for (const auto& r : *rows) {
    Params p = r.params;
    p.erase("pair");
    auto& g = groups[canonical(p)];
    g.params = p;
    g.rows.push_back(&r);
  }
  std::vector<PooledPdf> out;
  for (const auto& [key, g] : groups) {
    // Prefixes present in the first member.
    std::vector<std::pair<std::string, std::string>> pdfs;  // prefix, unit
    for (const auto& [name, v] : g.rows.front()->output.arrays) {
      const auto at = name.find("_edges_");
      if (at == std::string::npos) continue;
      const std::string prefix = name.substr(0, at), unit = name.substr(at + 7);
      if (g.rows.front()->output.arrays.count(prefix + "_density_per_" + unit)) pdfs.emplace_back(prefix, unit);
    }
    for (const auto& [prefix, unit] : pdfs) {
      const std::string en = prefix + "_edges_" + unit, dn = prefix + "_density_per_" + unit;
      double lo = INFINITY, hi = -INFINITY;
      std::size_t bins = 0;
      for (const auto* r : g.rows) {
        auto e = r->output.arrays.find(en);
        auto d = r->output.arrays.find(dn);
        if (e == r->output.arrays.end() || d == r->output.arrays.end() || e->second.size() != d->second.size() + 1 ||
            e->second.size() < 2)
          continue;
        lo = std::min(lo, e->second.front());
        hi = std::max(hi, e->second.back());
        bins = std::max(bins, d->second.size());
      }
      if (!(hi > lo) || bins == 0) continue;
      PooledPdf pp;
      pp.part = part;
      pp.params = g.params;
      pp.name = prefix;
      pp.edges.resize(bins + 1);
      for (std::size_t i = 0; i <= bins; ++i)
        pp.edges[i] = lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(bins);
      std::vector<double> mass(bins, 0.0);
      const double w = (hi - lo) / static_cast<double>(bins);
      for (const auto* r : g.rows) {
        auto e = r->output.arrays.find(en);
        auto d = r->output.arrays.find(dn);
        if (e == r->output.arrays.end() || d == r->output.arrays.end() || e->second.size() != d->second.size() + 1)
          continue;
        const auto& E = e->second;
        const auto& Dn = d->second;
        double total = 0;
        for (std::size_t k = 0; k < Dn.size(); ++k) total += Dn[k] * (E[k + 1] - E[k]);
        if (!(total > 0)) continue;
        ++pp.members;
        for (std::size_t k = 0; k < Dn.size(); ++k) {
          const double a = E[k], b = E[k + 1], m = Dn[k] * (b - a) / total;
          if (m <= 0) continue;
          if (!(b > a)) {  // degenerate bin: all its mass at a point
            const auto j = std::min(bins - 1, static_cast<std::size_t>(std::max(0.0, std::floor((a - lo) / w))));
            mass[j] += m;
            continue;
          }
          const auto j0 = static_cast<std::size_t>(std::max(0.0, std::floor((a - lo) / w)));
          for (std::size_t j = std::min(j0, bins - 1); j < bins && pp.edges[j] < b; ++j) {
            const double ov = std::min(b, pp.edges[j + 1]) - std::max(a, pp.edges[j]);
            if (ov > 0) mass[j] += m * ov / (b - a);
          }
        }
      }
      if (pp.members == 0) continue;
      pp.density.resize(bins);
      for (std::size_t j = 0; j < bins; ++j) pp.density[j] = mass[j] / (pp.members * w);
      out.push_back(std::move(pp));
    }
  }
  return out;
}

Result<Report> report(Store& store, const TaskRegistry& registry) {
  auto m = store.meta();
  if (!m) return m.error();
  Report r;
  r.study = (*m)["study_name"];
  r.title = fmt::format("Study '{}' ({} scale)", (*m)["study_name"], (*m)["scale"]);
  auto c = store.counts();
  if (!c) return c.error();
  r.lines.push_back(fmt::format("{}\n\nTasks: {} total, {} done, {} failed, {} pending. Definition hash {}.",
                                (*m)["study_description"], c->total, c->done, c->failed, c->pending,
                                (*m)["study_hash"]));
  // Which versions computed the results; a warning for results of another kind version.
  auto st = store_status(store, registry);
  if (!st) return st.error();
  std::string versions;
  for (const auto& p : st->parts) {
    for (const auto& [kv, n] : p.done_by_kind_version)
      versions += fmt::format("{}part '{}': {} tasks by {} {}", versions.empty() ? "" : "; ", p.part, n, p.kind,
                              kv ? fmt::format("version {}", kv) : std::string("(version not recorded)"));
  }
  std::map<std::string, std::int64_t> by_frictal;
  for (const auto& p : st->parts)
    for (const auto& [fv, n] : p.done_by_frictal_version) by_frictal[fv.empty() ? "(not recorded)" : fv] += n;
  std::string fvs;
  for (const auto& [fv, n] : by_frictal) fvs += fmt::format("{}{} ({} tasks)", fvs.empty() ? "" : ", ", fv, n);
  if (!versions.empty()) r.lines.push_back(fmt::format("Computed by frictal {}; {}.", fvs, versions));
  for (const auto& p : st->parts)
    if (!p.version_note.empty()) r.lines.push_back("\n**Warning:** " + p.version_note + ".");
  auto parts = store.part_counts();
  if (!parts) return parts.error();
  for (const auto& p : *parts) {
    const TaskKind* kind = registry.find(p.kind);
    if (!kind || !kind->report) {
      r.lines.push_back(fmt::format("\n## Part '{}' ({}): {} done, {} pending", p.part, p.kind, p.done, p.pending));
      continue;
    }
    auto rows = store.rows(p.part, false);
    if (!rows) return rows.error();
    // A kind's section reads the scalars it declares: rows without them (a store that frictal
    // did not write, or a damaged one) are left out and counted.
    std::vector<TaskRow> complete;
    std::int64_t incomplete = 0;
    for (auto& row : *rows) {
      bool ok = true;
      for (const auto& o : kind->outputs)
        if (!o.array && !row.output.scalars.count(o.name)) ok = false;
      if (ok)
        complete.push_back(std::move(row));
      else
        ++incomplete;
    }
    if (incomplete)
      r.lines.push_back(
          fmt::format("\n**Warning:** part '{}': {} done tasks lack some of the scalars of kind '{}' "
                      "and are left out of its report.",
                      p.part, incomplete, p.kind));
    try {
      kind->report(p.part, complete, r);
    } catch (const std::exception& e) {
      return make_error(
          fmt::format("part '{}': the stored results do not fit kind '{}' ({})", p.part, p.kind, e.what()));
    }
  }
  return r;
}

}  // namespace frictal::study
