// frictal study run|status|export|report|kinds — the paper's parameter sweeps as resumable,
// parallel runs with results in one SQLite store (docs/studies.md). A shell over the library
// (frictal/study.hpp): options, signals, MPI start-up, progress and printing; nothing here
// names a task kind or holds SQL.
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>

#include <fmt/ranges.h>

#include "common.hpp"
#include "frictal/study.hpp"

namespace frictal::cli {
namespace {

using namespace frictal::study;

std::atomic<bool> g_stop{false};
// Written (async-signal-safe) when a signal arrives under MPI, where mpirun may end rank 0 with
// SIGKILL before it prints anything else (e.g. after another rank died).
char g_signal_note[1024];
std::size_t g_signal_note_len = 0;
extern "C" void on_signal(int sig) {
  if (g_signal_note_len && !g_stop) (void)!::write(2, g_signal_note, g_signal_note_len);
  g_stop = true;
  std::signal(sig, SIG_DFL);  // a second Ctrl-C ends the process at once
}

/// Under MPI, what rank 0 writes when signalled: where the finished tasks are kept.
void set_signal_note(const std::string& where) {
  const std::string note = fmt::format(
      "frictal: rank 0 was signalled (interrupted, or another rank died and mpirun ends the job); every finished "
      "task is kept in {}; run the same command again to resume\n",
      where);
  g_signal_note_len = std::min(note.size(), sizeof g_signal_note);
  std::memcpy(g_signal_note, note.data(), g_signal_note_len);
}

std::string hms(double s) {
  if (!std::isfinite(s) || s < 0) return "--:--";
  const long t = std::lround(s);
  return t >= 3600 ? fmt::format("{}:{:02}:{:02}", t / 3600, t / 60 % 60, t % 60)
                   : fmt::format("{}:{:02}", t / 60, t % 60);
}

/// Progress: a bar redrawn in place on a terminal, else a plain line every `every` seconds.
struct ProgressPrinter {
  std::string name;  ///< the study's name, printed when several studies run at once
  bool bar = false;
  bool quiet = false;
  double every = 10;
  double last = -1e9;
  void operator()(const Progress& p) {
    if (quiet) return;
    // Rate and ETA from the computed tasks (results taken from the cache cost nothing).
    const double rate = p.elapsed_s > 0 ? (p.this_run - p.reused) / p.elapsed_s : 0;
    const double eta = rate > 0 ? (p.to_run - p.this_run) / rate : NAN;
    const bool end = p.this_run == p.to_run;
    if (bar) {
      if (!end && p.elapsed_s - last < 0.1) return;
      last = p.elapsed_s;
      const int W = 30;
      const double f = p.total ? static_cast<double>(p.done) / static_cast<double>(p.total) : 1.0;
      const int k = static_cast<int>(f * W);
      fmt::print(stderr, "\r[{}{}] {}/{} {:5.1f}% {:.1f} tasks/s ETA {}{}{}   ", std::string(k, '#'),
                 std::string(W - k, '-'), p.done, p.total, 100 * f, rate, hms(eta),
                 p.reused ? fmt::format(" reused {}", p.reused) : "",
                 p.failed ? fmt::format(" failed {}", p.failed) : "");
      if (end) fmt::print(stderr, "\n");
    } else {
      if (!end && p.this_run != 0 && p.elapsed_s - last < every) return;
      last = p.elapsed_s;
      fmt::print(stderr, "study{}: {}/{} done, {} of {} this run{}, {:.1f} tasks/s, elapsed {}, ETA {}{}\n",
                 name.empty() ? "" : " " + name, p.done, p.total, p.this_run, p.to_run,
                 !p.reused      ? std::string()
                 : name.empty() ? fmt::format(" ({} reused from the cache)", p.reused)
                                : fmt::format(" ({} reused, not computed)", p.reused),
                 rate, hms(p.elapsed_s), hms(eta), p.failed ? fmt::format(", failed {}", p.failed) : "");
    }
    std::fflush(stderr);
  }
};

struct RunArgs {
  std::vector<std::string> studies;
  std::string store, store_dir, progress = "auto", cache = "auto", schedule = "longest";
  unsigned threads = 0;
  int inject_failure_rank = -1;
  std::vector<std::int64_t> fail_first_attempt;
  bool quick = false, skip_unavailable = false, threads_set = false, pin = false, dry_run = false;
  std::vector<std::string> parts;
};

/// The file name of a study without folder and extension: its store's name under --store-dir.
std::string stem(const std::string& path) {
  std::string f = path.substr(path.rfind('/') == std::string::npos ? 0 : path.rfind('/') + 1);
  if (const auto dot = f.rfind('.'); dot != std::string::npos && dot > 0) f.resize(dot);
  return f;
}

/// MPI_Finalize at scope exit when MPI was initialised.
struct MpiFinalizer {
  bool on;
  ~MpiFinalizer() {
    if (on) mpi_finalize();
  }
};

/// The summary of one study of a `--store-dir` run (threads or MPI ranks alike).
void print_study_result(const Study& study, const std::string& store_path, Store& store, const RunSummary& sum,
                        const std::string& cache, const std::string& on, bool one_pool) {
  const StoreCounts c = unwrap(store.counts());
  fmt::print(
      "study '{}' ({} scale, {} tasks) in {}: {} done, {} failed, {} pending; this run: {} tasks in {:.2f} s on {}\n",
      study.name, study.quick ? "quick" : "full", c.total, store_path, c.done, c.failed, c.pending, sum.ran, sum.wall_s,
      on);
  if (sum.reused) {
    std::string from = cache.empty() ? "" : fmt::format("taken from the result cache {}", cache);
    if (one_pool) from += (from.empty() ? "" : " or ") + std::string("computed once for another study of this run");
    fmt::print("  {} tasks reused: {}\n", sum.reused, from);
  }
  if (!sum.cache_note.empty()) fmt::print(stderr, "frictal: warning: {}: {}\n", study.name, sum.cache_note);
  if (sum.done_elsewhere || sum.taken_over)
    fmt::print("  shared store: {} tasks recorded by other runs, {} claims taken over from runs that died\n",
               sum.done_elsewhere, sum.taken_over);
  if (sum.skipped_unavailable)
    fmt::print("  {} tasks left pending: their task kind is not available in this build\n", sum.skipped_unavailable);
}

/// Several studies in one run (`--store-dir DIR`): DIR/<stem>.sqlite each. With threads, one pool
/// and one queue for all studies; under MPI (mpirun), one study after another, each over every
/// rank as `--store` would run it (later studies reuse earlier ones' results through the cache).
int run_many(const RunArgs& a) {
  TaskRegistry reg = default_registry();
  const bool mpi = mpi_available() && launched_by_mpi();
  int rank = 0, size = 1;
  if (mpi) unwrap(mpi_init(&rank, &size));
  MpiFinalizer fin{mpi};
  std::vector<Study> studies;
  std::vector<std::string> stores;
  std::set<std::string> seen;
  for (const auto& f : a.studies) {
    const std::string s = stem(f);
    if (!seen.insert(s).second)
      throw UsageError(
          fmt::format("--store-dir: two studies have the file name '{}' (their stores would both be "
                      "{}/{}.sqlite); run them separately with --store",
                      s, a.store_dir, s));
    studies.push_back(unwrap(load_study(f, a.quick, reg)));
    stores.push_back(a.store_dir + "/" + s + ".sqlite");
  }
  // The folder is rank 0's (the other ranks never open a store); every rank learns whether it is there.
  std::string folder_error;
  if (rank == 0 && ::mkdir(a.store_dir.c_str(), 0777) != 0 && errno != EEXIST)
    folder_error = fmt::format("--store-dir {}: cannot create the folder: {}", a.store_dir, std::strerror(errno));
  if (mpi && !mpi_broadcast(folder_error.empty()) && rank != 0) return 0;  // rank 0 says why
  if (!folder_error.empty()) throw UsageError(folder_error, ErrorCode::Io);
  if (mpi && rank == 0) set_signal_note("the stores under " + a.store_dir);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  RunOptions o;
  o.threads = a.threads_set ? a.threads : (mpi ? 1 : 0);
  o.skip_unavailable = a.skip_unavailable;
  o.stop = &g_stop;
  o.inject_failure_rank = a.inject_failure_rank;
  o.fail_first_attempt = a.fail_first_attempt;
  o.pin_threads = a.pin;
  o.longest_first = a.schedule == "longest";
  const bool several = studies.size() > 1;
  std::vector<ProgressPrinter> printers(studies.size());
  std::vector<std::string> caches;
  for (std::size_t i = 0; i < studies.size(); ++i) {
    ProgressPrinter& pp = printers[i];
    pp.name = several ? studies[i].name : "";
    // One bar cannot show several studies: lines unless asked for bars.
    pp.bar = a.progress == "bar" || (a.progress == "auto" && !several && ::isatty(2));
    pp.quiet = a.progress == "none" || rank != 0;
    caches.push_back(a.cache == "none" ? std::string() : a.cache == "auto" ? default_cache_path(stores[i]) : a.cache);
  }
  std::vector<std::unique_ptr<Store>> owned;
  std::vector<RunSummary> sums;
  if (mpi) {
    // Every rank runs study i, then learns from rank 0 whether to go on (not after Ctrl-C or an
    // error on rank 0), so that the ranks stay in step.
    for (std::size_t i = 0; i < studies.size(); ++i) {
      if (rank != 0) {
        (void)run_mpi(studies[i], nullptr, reg, o);  // a worker: computes what rank 0 hands out
        if (!mpi_broadcast(false)) return 0;
        continue;
      }
      auto st = Store::open(stores[i], studies[i]);
      if (!st) {
        (void)run_mpi(studies[i], nullptr, reg, o);  // releases the workers
        mpi_broadcast(false);
        fail(st.error());
      }
      RunOptions oi = o;
      oi.cache = caches[i];
      oi.progress = std::ref(printers[i]);
      auto sum = run_mpi(studies[i], st->get(), reg, oi);
      const bool go = sum.ok() && !sum->interrupted && !g_stop && i + 1 < studies.size();
      mpi_broadcast(go);
      if (!sum) fail(with_prefix(fmt::format("study {}: ", studies[i].name), sum.error()));
      owned.push_back(std::move(*st));
      sums.push_back(*sum);
      if (!go) break;
    }
  } else {
    std::vector<StudyRun> runs;
    for (std::size_t i = 0; i < studies.size(); ++i) {
      owned.push_back(unwrap(Store::open(stores[i], studies[i])));
      StudyRun r;
      r.study = &studies[i];
      r.store = owned.back().get();
      r.cache = caches[i];
      r.progress = std::ref(printers[i]);
      runs.push_back(std::move(r));
    }
    sums = unwrap(run_threads(runs, reg, o));
  }
  bool interrupted = g_stop.load();
  std::int64_t failed = 0;
  for (std::size_t i = 0; i < sums.size(); ++i) {
    print_study_result(studies[i], stores[i], *owned[i], sums[i], caches[i],
                       mpi ? fmt::format("{} ranks", size) : fmt::format("{} threads", sums[i].threads), !mpi);
    interrupted = interrupted || sums[i].interrupted;
    failed += unwrap(owned[i]->counts()).failed;
  }
  if (interrupted) {
    fmt::print(stderr,
               "frictal: interrupted; finished tasks are kept in the stores under {}; run the same command again to "
               "resume\n",
               a.store_dir);
    return 130;
  }
  if (failed) {
    fmt::print(stderr, "frictal: {} tasks failed; see `frictal study status {}/<study>.sqlite --failed`\n", failed,
               a.store_dir);
    return 1;
  }
  return 0;
}

int run(const RunArgs& a) {
  if (!mpi_available()) {
    // Several copies of a build without MPI would each run the whole study on the same store.
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
      if (const char* n = std::getenv(v); n && std::atoi(n) > 1)
        throw UsageError(
            "this frictal was built without MPI (FRICTAL_MPI=OFF) but runs under mpirun with several "
            "ranks; run it without mpirun (use --threads) or rebuild with MPI");
  }
  // --store FILE: one study, its store; --store-dir DIR: one or more studies, DIR/<stem>.sqlite each.
  if (!a.store.empty() && !a.store_dir.empty())
    throw UsageError(
        "--store and --store-dir: give one (--store FILE for one study, --store-dir DIR for one store "
        "per study file, DIR/<file name>.sqlite)");
  if (a.store.empty() && a.store_dir.empty())
    throw UsageError(
        "give --store FILE (one study) or --store-dir DIR (one or more studies, DIR/<file name>.sqlite "
        "each)");
  if (!a.store.empty() && a.studies.size() > 1)
    throw UsageError(
        fmt::format("{} studies but one --store: give --store-dir DIR for several studies (their stores "
                    "are DIR/<file name>.sqlite)",
                    a.studies.size()));
  if (!a.store_dir.empty()) {
    if (a.studies.size() > 1 && !a.parts.empty())
      throw UsageError("--part: not with several studies (part names belong to one study)");
    if (a.dry_run) throw UsageError("--dry-run: give one study and its --store");
    return run_many(a);
  }
  TaskRegistry reg = default_registry();
  const bool mpi = mpi_available() && launched_by_mpi();
  int rank = 0, size = 1;
  if (mpi) unwrap(mpi_init(&rank, &size));
  MpiFinalizer fin{mpi};
  Study study = unwrap(load_study(a.studies.front(), a.quick, reg));
  if (mpi && rank == 0) set_signal_note(a.store);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  RunOptions o;
  o.threads = a.threads_set ? a.threads : (mpi ? 1 : 0);
  o.skip_unavailable = a.skip_unavailable;
  o.parts = a.parts;
  o.stop = &g_stop;
  o.inject_failure_rank = a.inject_failure_rank;
  o.fail_first_attempt = a.fail_first_attempt;
  o.pin_threads = a.pin;
  o.cache = a.cache == "none" ? std::string() : a.cache == "auto" ? default_cache_path(a.store) : a.cache;
  o.longest_first = a.schedule == "longest";
  ProgressPrinter pp;
  pp.bar = a.progress == "bar" || (a.progress == "auto" && ::isatty(2));
  pp.quiet = a.progress == "none" || rank != 0;
  o.progress = std::ref(pp);
  std::unique_ptr<Store> store;
  RunSummary sum;
  if (a.dry_run) {  // the order a run would take, with the estimates; nothing computed
    if (mpi) throw UsageError("--dry-run: run it without mpirun");
    store = unwrap(Store::open(a.store, study));
    const auto order = unwrap(schedule(study, *store, reg, o));
    fmt::print("order,task_id,part,estimated_s,estimate\n");
    int k = 0;
    for (const PlannedTask& p : order)
      fmt::print("{},{},{},{:.6g},{}\n", k++, p.id, study.tasks[static_cast<std::size_t>(p.id)].part, p.estimated_s,
                 p.cached     ? "cached"
                 : p.measured ? "recorded"
                              : "model");
    return 0;
  }
  if (mpi) {
    Result<std::unique_ptr<Store>> st =
        rank == 0 ? Store::open(a.store, study) : Result<std::unique_ptr<Store>>(nullptr);
    if (!st) {
      // Release the workers before failing: run_mpi with no store stops them.
      (void)run_mpi(study, nullptr, reg, o);
      fail(st.error());
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
             mpi ? fmt::format("{} ranks", size) : fmt::format("{} threads", sum.threads));
  if (sum.reused)
    fmt::print("  {} tasks reused from the result cache {} (computed before by this or another study)\n", sum.reused,
               o.cache);
  if (!sum.cache_note.empty()) fmt::print(stderr, "frictal: warning: {}\n", sum.cache_note);
  if (sum.done_elsewhere || sum.taken_over)
    fmt::print("  shared store: {} tasks recorded by other runs, {} claims taken over from runs that died\n",
               sum.done_elsewhere, sum.taken_over);
  if (sum.skipped_unavailable)
    fmt::print("  {} tasks left pending: their task kind is not available in this build\n", sum.skipped_unavailable);
  if (sum.interrupted || g_stop) {
    fmt::print(stderr, "frictal: interrupted; finished tasks are kept in {}; run the same command again to resume\n",
               a.store);
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
  const StoreStatus st = unwrap(store_status(*store, default_registry()));
  if (json) {
    print_json(object_of(study_status_columns(), StudyStatusReport{path, st}));
    return 0;
  }
  fmt::print("{}: study '{}' ({} scale), schema {}, definition {}, created by frictal {}\n", path, st.study, st.scale,
             st.schema_version, st.study_hash, st.frictal_version.empty() ? "?" : st.frictal_version);
  const StoreCounts& c = st.tasks;
  fmt::print("  {} tasks: {} done, {} failed, {} pending ({:.1f}% complete)\n", c.total, c.done, c.failed, c.pending,
             c.total ? 100.0 * c.done / c.total : 100.0);
  for (const auto& p : st.parts)
    fmt::print("  part {:<14} kind {:<20} done {:>6} failed {:>4} pending {:>6}{}\n", p.part, p.kind, p.done, p.failed,
               p.pending, p.unavailable_reason.empty() ? "" : "  (" + p.unavailable_reason + ")");
  if (st.claimed)
    fmt::print("  {} tasks claimed by a run now (or by one that died: the next run takes them over)\n", st.claimed);
  for (const auto& p : st.parts)
    if (const std::string by = done_versions_text(p); !by.empty())
      fmt::print("  part {:<14} done tasks: {}\n", p.part, by);
  for (const auto& p : st.parts)
    if (!p.version_note.empty()) fmt::print(stderr, "frictal: warning: {}\n", p.version_note);
  if (failed) fmt::print("{}", unwrap(store->failures_csv()));
  return 0;
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  if (!f) throw UsageError(fmt::format("{}: cannot open for writing", path), ErrorCode::Io);
  f << text;
  if (!f) throw UsageError(fmt::format("{}: write failed", path), ErrorCode::Io);
}

std::function<int()> setup(CLI::App& app) {
  app.require_subcommand(1);
  auto ra = std::make_shared<RunArgs>();
  auto* run_cmd = app.add_subcommand("run", "Run (or resume) a study; results go into an SQLite store");
  run_cmd
      ->add_option("study", ra->studies,
                   "Study definition (TOML), e.g. studies/fig14-18-wm-statistics.toml; several with --store-dir")
      ->required();
  run_cmd->add_option("--store", ra->store,
                      "SQLite store file of the one study (created if missing, resumed if it exists)");
  run_cmd->add_option("--store-dir", ra->store_dir,
                      "Run one or more studies in one pool of threads, costliest tasks first across studies, tasks "
                      "they share computed once; the store of STUDY.toml is DIR/STUDY.sqlite (created or resumed)");
  run_cmd
      ->add_option("--threads", ra->threads, "Compute threads (0 = all cores; under MPI: threads on rank 0, default 1)")
      ->each([ra](const std::string&) { ra->threads_set = true; });
  run_cmd->add_flag("--pin", ra->pin, "Pin compute thread i to CPU i (as mpirun binds ranks); results do not change");
  run_cmd->add_flag("--quick", ra->quick, "Use the study's quick (CI) scale instead of the paper's full scale");
  run_cmd->add_option("--part", ra->parts, "Run only this part (repeatable)");
  run_cmd->add_flag("--skip-unavailable", ra->skip_unavailable,
                    "Run the parts whose task kind this build has; leave the others pending");
  run_cmd
      ->add_option("--inject-failure-rank", ra->inject_failure_rank,
                   "Testing: every attempt computed on this rank (0 without MPI) is reported failed")
      ->group("");  // hidden
  run_cmd
      ->add_option("--inject-failure-task", ra->fail_first_attempt,
                   "Testing: the first attempt of this task id is reported failed, so it is retried (repeatable)")
      ->group("");  // hidden
  run_cmd
      ->add_option("--cache", ra->cache,
                   "Result cache shared by the studies of a folder: auto (results-cache.sqlite beside the store), "
                   "none, or a file; a task already computed (same kind, kind version and parameters) is reused")
      ->capture_default_str();
  run_cmd
      ->add_option("--schedule", ra->schedule,
                   "Task order: longest (estimated costliest first) or grid (id order); results do not change")
      ->check(CLI::IsMember({"longest", "grid"}))
      ->capture_default_str();
  run_cmd->add_flag("--dry-run", ra->dry_run,
                    "Print the tasks this run would compute, in the order it would start them, with their estimated "
                    "cost (CSV: order, task_id, part, estimated_s, estimate = cached|recorded|model); compute nothing");
  run_cmd->add_option("--progress", ra->progress, "auto (bar on a terminal, lines otherwise), bar, lines, none")
      ->check(CLI::IsMember({"auto", "bar", "lines", "none"}))
      ->capture_default_str();

  auto store_path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  auto failed = std::make_shared<bool>(false);
  auto* status_cmd = app.add_subcommand("status", "Show how far a store is");
  status_cmd->add_option("store", *store_path, "SQLite store file")->required();
  status_cmd->add_flag("--json", *json, "Print one JSON object");
  status_cmd->add_flag("--failed", *failed, "List the failed tasks and their errors");

  auto export_store = std::make_shared<std::string>();
  auto export_dir = std::make_shared<std::string>();
  auto* export_cmd =
      app.add_subcommand("export", "Write a store as CSV files (one wide table and one arrays table per part)");
  export_cmd->add_option("store", *export_store, "SQLite store file")->required();
  export_cmd->add_option("--csv", *export_dir, "Output directory")->required();

  auto report_stores = std::make_shared<std::vector<std::string>>();
  auto report_out = std::make_shared<std::string>();
  auto report_json = std::make_shared<bool>(false);
  auto* report_cmd = app.add_subcommand("report", "Summarise stores and check the paper's findings against them");
  report_cmd->add_option("stores", *report_stores, "SQLite store files (Markdown: one report after the other)")
      ->required();
  report_cmd->add_option("-o,--output", *report_out,
                         "Also write the report (Markdown, or JSON with --json) to this file");
  report_cmd->add_flag("--json", *report_json,
                       "Print the findings as data: per store its findings (claim, figures, part, criterion, numbers, "
                       "verdict, cause), and one conclusion per claim over all stores (docs/studies.md)");

  auto kinds_json_flag = std::make_shared<bool>(false);
  auto* kinds_cmd = app.add_subcommand("kinds", "List the task kinds of this build");
  kinds_cmd->add_flag(
      "--json", *kinds_json_flag,
      "Print every kind with its outputs (name, unit) and plot views, as JSON (scripts/plot_studies.py)");

  return [=]() -> int {
    if (run_cmd->parsed()) return run(*ra);
    if (status_cmd->parsed()) return status(*store_path, *json, *failed);
    if (export_cmd->parsed()) {
      auto store = unwrap(Store::open_existing(*export_store));
      const auto files = unwrap(export_csv(*store, *export_dir));
      fmt::print("exported {} to {}: {}\n", *export_store, *export_dir, fmt::format("{}", fmt::join(files, ", ")));
      return 0;
    }
    if (report_cmd->parsed()) {
      std::vector<Report> reports;
      for (const auto& path : *report_stores) {
        auto store = unwrap(Store::open_existing(path));
        reports.push_back(unwrap(report(*store)));
      }
      std::string text;
      if (*report_json)
        text = unwrap(render_json(reports)) + "\n";
      else
        for (const auto& r : reports) text += (text.empty() ? "" : "\n") + render_markdown(r);
      fmt::print("{}", text);
      if (!report_out->empty()) write_text(*report_out, text);
      return 0;
    }
    if (kinds_cmd->parsed()) {
      const TaskRegistry reg = default_registry();
      if (*kinds_json_flag) {
        fmt::print("{}\n", kinds_json(reg));
        return 0;
      }
      for (const auto& n : reg.names()) fmt::print("{:<20} {}\n", n, reg.find(n)->description);
      for (const auto& n : reg.unavailable_names()) fmt::print("{:<20} {}\n", n, reg.unavailable_reason(n));
      return 0;
    }
    return 2;
  };
}

}  // namespace

FRICTAL_COMMAND({"study", "Run the paper's parameter sweeps (resumable, threads or MPI) and inspect their stores",
                 setup, 50});

}  // namespace frictal::cli
