// frictal study run|status|export|report|kinds — the paper's parameter sweeps as resumable,
// parallel runs with results in one SQLite store (docs/studies.md).
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <thread>

#include <fmt/ranges.h>

#include "common.hpp"
#include "frictal/study.hpp"

namespace frictal::cli {
namespace {

namespace fs = std::filesystem;
using namespace frictal::study;

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int sig) {
  g_stop = true;
  std::signal(sig, SIG_DFL);  // a second Ctrl-C ends the process at once
}

std::string hms(double s) {
  if (!std::isfinite(s) || s < 0) return "--:--";
  const long t = static_cast<long>(s + 0.5);
  return t >= 3600 ? fmt::format("{}:{:02}:{:02}", t / 3600, t / 60 % 60, t % 60) : fmt::format("{}:{:02}", t / 60, t % 60);
}

/// Progress: a bar redrawn in place on a terminal, else a plain line every `every` seconds.
struct ProgressPrinter {
  bool bar = false;
  bool quiet = false;
  double every = 10;
  double last = -1e9;
  void operator()(const Progress& p) {
    if (quiet) return;
    const double rate = p.elapsed_s > 0 ? p.this_run / p.elapsed_s : 0;
    const double eta = rate > 0 ? (p.to_run - p.this_run) / rate : NAN;
    const bool end = p.this_run == p.to_run;
    if (bar) {
      if (!end && p.elapsed_s - last < 0.1) return;
      last = p.elapsed_s;
      const int W = 30;
      const double f = p.total ? static_cast<double>(p.done) / static_cast<double>(p.total) : 1.0;
      const int k = static_cast<int>(f * W);
      fmt::print(stderr, "\r[{}{}] {}/{} {:5.1f}% {:.1f} tasks/s ETA {}{}   ", std::string(k, '#'), std::string(W - k, '-'),
                 p.done, p.total, 100 * f, rate, hms(eta), p.failed ? fmt::format(" failed {}", p.failed) : "");
      if (end) fmt::print(stderr, "\n");
    } else {
      if (!end && p.this_run != 0 && p.elapsed_s - last < every) return;
      last = p.elapsed_s;
      fmt::print(stderr, "study: {}/{} done, {} of {} this run, {:.1f} tasks/s, elapsed {}, ETA {}{}\n", p.done, p.total,
                 p.this_run, p.to_run, rate, hms(p.elapsed_s), hms(eta), p.failed ? fmt::format(", failed {}", p.failed) : "");
    }
    std::fflush(stderr);
  }
};

struct RunArgs {
  std::string study, store, progress = "auto";
  unsigned threads = 0;
  int inject_failure_rank = -1;
  bool quick = false, skip_unavailable = false, threads_set = false, pin = false;
  std::vector<std::string> parts;
};

int run(const RunArgs& a) {
  TaskRegistry reg = default_registry();
  if (!mpi_available()) {
    // Several copies of a build without MPI would each run the whole study on the same store.
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
      if (const char* n = std::getenv(v); n && std::atoi(n) > 1)
        throw UsageError("this frictal was built without MPI (FRICTAL_MPI=OFF) but runs under mpirun with several "
                         "ranks; run it without mpirun (use --threads) or rebuild with MPI");
  }
  const bool mpi = mpi_available() && launched_by_mpi();
  int rank = 0, size = 1;
  if (mpi) unwrap(mpi_init(&rank, &size));
  struct Fin {
    bool on;
    ~Fin() {
      if (on) mpi_finalize();
    }
  } fin{mpi};
  Study study = unwrap(load_study(a.study, a.quick, reg));
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  RunOptions o;
  o.threads = a.threads_set ? a.threads : (mpi ? 1 : 0);
  o.skip_unavailable = a.skip_unavailable;
  o.parts = a.parts;
  o.stop = &g_stop;
  o.inject_failure_rank = a.inject_failure_rank;
  o.pin_threads = a.pin;
  ProgressPrinter pp;
  pp.bar = a.progress == "bar" || (a.progress == "auto" && ::isatty(2));
  pp.quiet = a.progress == "none" || rank != 0;
  o.progress = std::ref(pp);
  std::unique_ptr<Store> store;
  RunSummary sum;
  if (mpi) {
    Result<std::unique_ptr<Store>> st = rank == 0 ? Store::open(a.store, study) : Result<std::unique_ptr<Store>>(nullptr);
    if (!st) {
      // Release the workers before failing: run_mpi with no store stops them.
      (void)run_mpi(study, nullptr, reg, o);
      throw UsageError(st.error().message);
    }
    store = std::move(*st);
    sum = unwrap(run_mpi(study, store.get(), reg, o));
    if (rank != 0) return 0;
  } else {
    store = unwrap(Store::open(a.store, study));
    sum = unwrap(run_threads(study, *store, reg, o));
  }
  const StoreCounts c = unwrap(store->counts());
  fmt::print("study '{}' ({} scale, {} tasks): {} done, {} failed, {} pending; this run: {} tasks in {:.2f} s on {}\n",
             study.name, study.quick ? "quick" : "full", c.total, c.done, c.failed, c.pending, sum.ran, sum.wall_s,
             mpi ? fmt::format("{} ranks", size) : fmt::format("{} threads", o.threads ? o.threads : std::thread::hardware_concurrency()));
  if (sum.skipped_unavailable)
    fmt::print("  {} tasks left pending: their task kind is not available in this build\n", sum.skipped_unavailable);
  if (sum.interrupted || g_stop) {
    fmt::print(stderr, "frictal: interrupted; finished tasks are kept in {}; run the same command again to resume\n", a.store);
    return 130;
  }
  if (c.failed) {
    fmt::print(stderr, "frictal: {} tasks failed; see `frictal study status {} --failed`\n", c.failed, a.store);
    return 1;
  }
  return 0;
}

int status(const std::string& path, bool json, bool failed) {
  auto store = unwrap(Store::open_existing(path));
  auto meta = unwrap(store->meta());
  auto c = unwrap(store->counts());
  auto parts = unwrap(store->part_counts());
  TaskRegistry reg = default_registry();
  if (json) {
    nlohmann::json j;
    j["store"] = path;
    j["study"] = meta["study_name"];
    j["scale"] = meta["scale"];
    j["study_hash"] = meta["study_hash"];
    j["schema_version"] = std::stoi(meta["schema_version"]);
    j["tasks"] = {{"total", c.total}, {"done", c.done}, {"failed", c.failed}, {"pending", c.pending}};
    for (const auto& p : parts)
      j["parts"].push_back({{"part", p.part}, {"kind", p.kind}, {"done", p.done}, {"failed", p.failed}, {"pending", p.pending},
                            {"available", reg.find(p.kind) != nullptr}});
    print_json(j);
    return 0;
  }
  fmt::print("{}: study '{}' ({} scale), schema {}, definition {}\n", path, meta["study_name"], meta["scale"],
             meta["schema_version"], meta["study_hash"]);
  fmt::print("  {} tasks: {} done, {} failed, {} pending ({:.1f}% complete)\n", c.total, c.done, c.failed, c.pending,
             c.total ? 100.0 * c.done / c.total : 100.0);
  for (const auto& p : parts) {
    const std::string why = reg.unavailable_reason(p.kind);
    fmt::print("  part {:<14} kind {:<20} done {:>6} failed {:>4} pending {:>6}{}\n", p.part, p.kind, p.done, p.failed,
               p.pending, why.empty() ? "" : "  (" + why + ")");
  }
  if (failed) {
    std::string csv = unwrap(store->query_csv("SELECT task_id, part, params, error FROM tasks WHERE status = 'failed' ORDER BY task_id"));
    fmt::print("{}", csv);
  }
  return 0;
}

std::string render(const Report& r) {
  std::string s = fmt::format("# {}\n\n", r.title);
  for (const auto& l : r.lines) s += l + "\n";
  if (!r.findings.empty()) {
    s += "\n## Findings of the paper checked against this store\n\n";
    for (const auto& f : r.findings) {
      s += fmt::format("- [{}] {}\n", f.supported ? "SUPPORTED" : "NOT SUPPORTED", f.claim);
      for (const auto& e : f.evidence) s += "    " + e + "\n";
    }
  }
  return s;
}

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::binary);
  if (!f) throw UsageError(fmt::format("{}: cannot open for writing", p.string()));
  f << text;
  if (!f) throw UsageError(fmt::format("{}: write failed", p.string()));
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

int export_csv(const std::string& path, const std::string& dir) {
  auto store = unwrap(Store::open_existing(path));
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw UsageError(fmt::format("--csv {}: cannot create the directory: {}", dir, ec.message()));
  write_text(fs::path(dir) / "tasks.csv",
             unwrap(store->query_csv("SELECT task_id, part, kind, params, seed, status, attempts, error, worker, started_at, "
                                     "finished_at, wall_s FROM tasks ORDER BY task_id")));
  std::vector<std::string> files = {"tasks.csv"};
  for (const auto& pc : unwrap(store->part_counts())) {
    auto rows = unwrap(store->rows(pc.part, true));
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
        wide.append(",").append(it != r.output.scalars.end() && std::isfinite(it->second) ? fmt::format("{}", it->second)
                                                                                           : std::string{});
      }
      wide += "\n";
      for (const auto& [name, v] : r.output.arrays)
        for (std::size_t i = 0; i < v.size(); ++i)
          longf += fmt::format("{},{},{},{}\n", r.id, csv_field(name), i, std::isfinite(v[i]) ? fmt::format("{}", v[i]) : "");
    }
    write_text(fs::path(dir) / (pc.part + ".csv"), wide);
    write_text(fs::path(dir) / (pc.part + "-arrays.csv"), longf);
    files.push_back(pc.part + ".csv");
    files.push_back(pc.part + "-arrays.csv");
    // PDFs pooled over replicates (pair), e.g. Fig. 16.
    auto pooled = unwrap(pooled_pdfs(*store, pc.part));
    if (!pooled.empty()) {
      std::string csv = "group";
      for (const auto& k : pn)
        if (k != "pair") csv.append(",").append(csv_field(k));
      csv += ",pdf,members,lo,hi,density\n";
      for (std::size_t g = 0; g < pooled.size(); ++g) {
        const PooledPdf& pp = pooled[g];
        std::string prefix = std::to_string(g);
        for (const auto& k : pn)
          if (k != "pair") prefix.append(",").append(pp.params.count(k) ? value_text(pp.params.at(k)) : std::string{});
        for (std::size_t i = 0; i < pp.density.size(); ++i)
          csv += fmt::format("{},{},{},{},{},{}\n", prefix, pp.name, pp.members, pp.edges[i], pp.edges[i + 1], pp.density[i]);
      }
      write_text(fs::path(dir) / (pc.part + "-pooled-pdfs.csv"), csv);
      files.push_back(pc.part + "-pooled-pdfs.csv");
    }
  }
  write_text(fs::path(dir) / "report.md", render(unwrap(report(*store))));
  files.push_back("report.md");
  fmt::print("exported {} to {}: {}\n", path, dir, fmt::format("{}", fmt::join(files, ", ")));
  return 0;
}

std::function<int()> setup(CLI::App& app) {
  app.require_subcommand(1);
  auto ra = std::make_shared<RunArgs>();
  auto* run_cmd = app.add_subcommand("run", "Run (or resume) a study; results go into an SQLite store");
  run_cmd->add_option("study", ra->study, "Study definition (TOML), e.g. studies/fig14-18-wm-statistics.toml")->required();
  run_cmd->add_option("--store", ra->store, "SQLite store file (created if missing, resumed if it exists)")->required();
  run_cmd->add_option("--threads", ra->threads, "Compute threads (0 = all cores; under MPI: threads on rank 0, default 1)")
      ->each([ra](const std::string&) { ra->threads_set = true; });
  run_cmd->add_flag("--pin", ra->pin, "Pin compute thread i to CPU i (as mpirun binds ranks); results do not change");
  run_cmd->add_flag("--quick", ra->quick, "Use the study's quick (CI) scale instead of the paper's full scale");
  run_cmd->add_option("--part", ra->parts, "Run only this part (repeatable)");
  run_cmd->add_flag("--skip-unavailable", ra->skip_unavailable,
                    "Run the parts whose task kind this build has; leave the others pending");
  run_cmd->add_option("--inject-failure-rank", ra->inject_failure_rank,
                      "Testing under MPI: this rank fails every task it gets (its tasks must be reassigned)")
      ->group("");  // hidden
  run_cmd->add_option("--progress", ra->progress, "auto (bar on a terminal, lines otherwise), bar, lines, none")
      ->check(CLI::IsMember({"auto", "bar", "lines", "none"}))->capture_default_str();

  auto store_path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto failed = std::make_shared<bool>(false);
  auto* status_cmd = app.add_subcommand("status", "Show how far a store is");
  status_cmd->add_option("store", *store_path, "SQLite store file")->required();
  status_cmd->add_flag("--json", *json, "Print one JSON object");
  status_cmd->add_flag("--failed", *failed, "List the failed tasks and their errors");

  auto export_store = std::make_shared<std::string>();
  auto export_dir = std::make_shared<std::string>();
  auto* export_cmd = app.add_subcommand("export", "Write a store as CSV files (one wide table and one arrays table per part)");
  export_cmd->add_option("store", *export_store, "SQLite store file")->required();
  export_cmd->add_option("--csv", *export_dir, "Output directory")->required();

  auto report_store = std::make_shared<std::string>();
  auto report_out = std::make_shared<std::string>();
  auto* report_cmd = app.add_subcommand("report", "Summarise a store and check the paper's findings against it");
  report_cmd->add_option("store", *report_store, "SQLite store file")->required();
  report_cmd->add_option("-o,--output", *report_out, "Also write the report (Markdown) to this file");

  auto* kinds_cmd = app.add_subcommand("kinds", "List the task kinds of this build");

  return [=]() -> int {
    if (run_cmd->parsed()) return run(*ra);
    if (status_cmd->parsed()) return status(*store_path, *json, *failed);
    if (export_cmd->parsed()) return export_csv(*export_store, *export_dir);
    if (report_cmd->parsed()) {
      auto store = unwrap(Store::open_existing(*report_store));
      const Report r = unwrap(report(*store));
      const std::string text = render(r);
      fmt::print("{}", text);
      if (!report_out->empty()) write_text(*report_out, text);
      return 0;
    }
    if (kinds_cmd->parsed()) {
      TaskRegistry reg = default_registry();
      for (const auto& n : reg.names()) fmt::print("{:<20} {}\n", n, reg.find(n)->description);
      for (const char* n : {"tilt", "divider"})
        if (!reg.find(n)) fmt::print("{:<20} {}\n", n, reg.unavailable_reason(n));
      return 0;
    }
    return 2;
  };
}

}  // namespace

FRICTAL_COMMAND({"study", "Run the paper's parameter sweeps (resumable, threads or MPI) and inspect their stores", setup, 50});

}  // namespace frictal::cli
