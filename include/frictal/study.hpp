// frictal — studies: the paper's parameter sweeps as resumable, parallel runs.
//
// A study (TOML file under studies/) names one or more *parts*; each part has a task *kind*
// (an analysis or experiment registered in a TaskRegistry) and a grid of parameters (ranges,
// lists, replicate counts) at two scales, full (the paper's) and quick (CI). Expanding the grid
// gives tasks; each task's random seed is a hash of the study seed and the canonical text of
// (a chosen subset of) its parameters, so results do not depend on threads, ranks, order or
// restarts. Results go into one SQLite store (schema in docs/studies.md) written in one
// transaction per task, so an interrupted run resumes where it stopped.
//
// The library never prints: progress is reported through a callback the front end provides.
#pragma once

#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "frictal/outputs.hpp"
#include "frictal/result.hpp"

namespace frictal::study {

/// Version of the store layout (meta key "schema_version"). Bump on incompatible change.
/// Version 2 adds per-task kind_version, frictal_version and study_hash and the `claims` table
/// (concurrent runs); a version-1 store is upgraded in place when a run opens it.
inline constexpr int kSchemaVersion = 2;

/// One parameter value. Integers and reals are distinct (2 and 2.0 differ in canonical text).
using Value = std::variant<std::int64_t, double, std::string, bool>;
/// Parameters by name, sorted by name (the canonical order).
using Params = std::map<std::string, Value>;

/// Canonical text of a value / of parameters: compact JSON with sorted keys and shortest
/// round-trip reals (e.g. {"dimension":1.3,"n_max":10,"pair":4}). The seed and the store key
/// derive from it.
std::string canonical(const Value& v);
std::string canonical(const Params& p);
/// 64-bit FNV-1a of text, mixed by splitmix64 (stable across platforms and builds).
std::uint64_t hash64(const std::string& text);
/// Hex digest (32 hex digits) of text from two independent 64-bit hashes.
std::string digest(const std::string& text);
/// Content address of a task's result: digest of the kind, the kind version, canonical(params)
/// and, for a kind that uses its seed, the seed (the part and the study are not in it). Two tasks
/// with one address compute the same result; the result cache (RunOptions::cache) is keyed by it.
std::string content_address(const std::string& kind, int kind_version, const Params& params, bool uses_seed,
                            std::uint64_t seed);
/// Seed of a task: hash of the study seed and the canonical text of `seed_params`.
std::uint64_t task_seed(std::uint64_t study_seed, const Params& seed_params);
/// A derived stream, e.g. stream 1 and 2 for the lower and upper surface of a pair.
std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t stream);

/// Accessors with errors that name the parameter.
Result<double> get_real(const Params& p, const std::string& name);
Result<double> get_real(const Params& p, const std::string& name, double fallback);
Result<std::int64_t> get_int(const Params& p, const std::string& name);
Result<std::int64_t> get_int(const Params& p, const std::string& name, std::int64_t fallback);
Result<std::string> get_string(const Params& p, const std::string& name, const std::string& fallback);
/// A parameter as a number (integers converted); NaN for text and booleans.
double as_number(const Value& v);
/// A parameter as an int (reals truncated); -1 for text, booleans and numbers outside int's
/// range or not finite (a store may hold anything).
int as_int(const Value& v);

/// What a task returns: named scalars and named arrays (flat vectors of reals).
struct TaskOutput {
  std::map<std::string, double> scalars;
  std::map<std::string, std::vector<double>> arrays;
};

/// One done task as read back from a store: its parameters and outputs.
struct TaskRow {
  std::int64_t id = 0;
  std::string part, kind, params_json, status;
  Params params;
  TaskOutput output;
};
struct Report;

/// An output a kind writes: a named scalar or array, its unit and meaning, and, for an output
/// taken from an output table (outputs_of), which column of which table it is.
struct OutputColumn {
  OutputColumn() = default;
  OutputColumn(std::string name_, std::string unit_, std::string description_, bool array_ = false)
      : name(std::move(name_)), unit(std::move(unit_)), description(std::move(description_)), array(array_) {}
  std::string name;
  std::string unit;  ///< e.g. "deg", "m", "s", "1" (unitless)
  std::string description;
  bool array = false;  ///< an array (one value per index) rather than a scalar
  std::string table;   ///< the output table (frictal columns) it is a column of; "" = declared by the kind
  std::string column;  ///< that column's key (the table's declaration: its unit and, ending the description, help)
};

/// One column of an output table that a kind stores: the table's `column` under the study key
/// `name` (nullptr: the same key), its help after `context` + ": " (nullptr: the help alone), e.g.
/// {"hold_angle_deg", "sphero_hold_angle_deg", "the rounded blocks"}. A plain key converts. A
/// column without a JSON key is named by its Python key (e.g. the signature's "events").
struct ColumnOutput {
  constexpr ColumnOutput(const char* column_) : column(column_) {}  // NOLINT: a key converts
  constexpr ColumnOutput(const char* column_, const char* name_, const char* context_ = nullptr)
      : column(column_), name(name_), context(context_) {}
  const char* column;
  const char* name = nullptr;
  const char* context = nullptr;
  std::string key() const { return name ? name : column; }
  /// Whether `c` is the column named.
  bool names(const ColumnInfo& c) const { return c.key.empty() ? c.python == column : c.key == column; }
};

/// The study outputs of the columns `keys` of the output table `table` (its name in frictal
/// columns; `cols` its typed columns, frictal/outputs.hpp): the study key, the interface unit ("1"
/// for a count or a flag: a store holds numbers), the table's meaning and where it comes from, so
/// that a quantity that a kind stores and a command prints is declared once (the output key test
/// checks each against the table). A key not in the table is left out (the key test then names
/// the output that the kind stores undeclared).
template <class T>
std::vector<OutputColumn> outputs_of(const std::string& table, const Columns<T>& cols,
                                     std::initializer_list<ColumnOutput> keys) {
  std::vector<OutputColumn> out;
  for (const ColumnOutput& k : keys)
    for (const Column<T>& c : cols)
      if (k.names(c)) {
        const bool number = c.unit == "count" || c.unit == "flag";
        OutputColumn o(k.key(), number ? "1" : c.unit, k.context ? std::string(k.context) + ": " + c.help : c.help);
        o.table = table;
        o.column = k.column;
        out.push_back(std::move(o));
      }
  return out;
}

/// The generic study writer of an output table: the columns `keys` of `value` as scalars of `out`
/// under their study keys, in the interface unit (degrees for "deg"), a flag as 1 or 0; text and
/// list columns are not stored.
template <class T>
void put_outputs(TaskOutput& out, const Columns<T>& cols, const T& value, std::initializer_list<ColumnOutput> keys) {
  for (const ColumnOutput& k : keys)
    for (const Column<T>& c : cols) {
      if (!k.names(c) || !c.si || (c.present && !c.present(value))) continue;
      const OutputValue v = to_interface(c.unit, c.si(value));
      if (const double* d = std::get_if<double>(&v)) out.scalars[k.key()] = *d;
      if (const bool* b = std::get_if<bool>(&v)) out.scalars[k.key()] = *b ? 1 : 0;
    }
}

/// One axis of a plot view. `column` names a parameter, a scalar or (for both axes of a view
/// together) an array of the task.
struct PlotAxis {
  PlotAxis() = default;
  PlotAxis(std::string column_, std::string label_, std::string divide_by_ = {}, bool log_ = false)
      : column(std::move(column_)), label(std::move(label_)), divide_by(std::move(divide_by_)), log(log_) {}
  std::string column;
  std::string label;            ///< axis label, with its unit
  std::string divide_by;        ///< optional parameter the values are divided by (e.g. "wavelength")
  bool log = false;             ///< logarithmic axis
  double min = NAN, max = NAN;  ///< axis limits (NaN: automatic)
};

/// What the tasks of a part of this kind contribute to a figure: data, rendered by
/// scripts/plot_studies.py (a study file's [[figure]] entries name views by id; parts of other
/// kinds with a view of the same id are drawn in the same panel).
struct PlotView {
  std::string id;  ///< e.g. "friction-vs-alpha"
  PlotAxis x, y;
  std::string series;        ///< parameter whose values make one series each; "task": one per task
  std::string label;         ///< legend, "{name}" or "{name:.4f}" replaced by a parameter or scalar
  std::string marker;        ///< matplotlib marker ("o", "s") or empty for none
  double marker_size = 0;    ///< points; 0: matplotlib's default
  double line_width = 0;     ///< points; 0: matplotlib's default
  bool line = true;          ///< join the points
  bool open = false;         ///< hollow markers
  std::string color;         ///< fixed colour; empty: "C<series value>" for integer series, else cycle
  std::string average_over;  ///< parameter averaged over (mean of y per series and x)
  /// A column missing from a task is taken from a task of another part with the same values of
  /// these parameters (e.g. the Eq. 13 dimension of the same alpha).
  std::vector<std::string> match;
  /// Optional reference line: "identity" (y = x, labelled `reference_label`), or
  /// "power:<column>" (through the last series' point at the largest x, with exponent
  /// 1 - <column> of that task: the divider law L ~ eps^(1-D)).
  std::string reference;
  std::string reference_label;

  // Builders for the common cases; they only fill the fields above.
  /// A view with its id and axes.
  static PlotView of(std::string id_, PlotAxis x_, PlotAxis y_) {
    PlotView v;
    v.id = std::move(id_);
    v.x = std::move(x_);
    v.y = std::move(y_);
    return v;
  }
  /// One series per value of `series_` ("task": one per task), legend `label_`.
  PlotView& by(std::string series_, std::string label_) {
    series = std::move(series_);
    label = std::move(label_);
    return *this;
  }
  /// The legend of a single series.
  PlotView& named(std::string label_) {
    label = std::move(label_);
    return *this;
  }
  /// Markers (`size_` and `width_` in points, 0: matplotlib's default).
  PlotView& markers(std::string marker_, double size_ = 0, double width_ = 0) {
    marker = std::move(marker_);
    marker_size = size_;
    line_width = width_;
    return *this;
  }
  /// Simulation results: hollow circles, not joined.
  PlotView& simulated() {
    marker = "o";
    open = true;
    line = false;
    return *this;
  }
  /// The mean of y over the values of `parameter` (per series and x).
  PlotView& averaged_over(std::string parameter) {
    average_over = std::move(parameter);
    return *this;
  }
};

/// A kind's section of a study report: summary lines and the paper's findings, from the done
/// tasks of one part.
using ReportSection = std::function<void(const std::string& part, const std::vector<TaskRow>& rows, Report& report)>;

/// A task kind: everything about one analysis or experiment in one unit (one source file):
/// the compute function, its outputs, its report section and its plots. Registered in one list
/// (default_registry, src/study/registry.cpp); docs/studies.md says how to add one.
/// `run` must be thread-safe and deterministic (same inputs, bit-identical output); it runs
/// single-threaded.
struct TaskKind {
  using Run = std::function<Result<TaskOutput>(const Params&, std::uint64_t seed)>;
  TaskKind() = default;
  TaskKind(std::string name_, std::string description_, int version_, Run run_)
      : name(std::move(name_)), description(std::move(description_)), version(version_), run(std::move(run_)) {}
  std::string name;
  std::string description;
  int version = 1;  ///< bump when results change; part of the study hash
  Run run;
  /// Estimated cost of one task with these parameters (unit: s of one core; only ratios between
  /// tasks matter, and the store's recorded times refine it): the runner starts the costliest
  /// tasks first. Empty: every task costs 1 s.
  using Cost = std::function<double(const Params&)>;
  Cost cost;
  /// Whether `run` reads its seed. A kind whose result depends on its parameters only (seed
  /// ignored) shares results with every study that has the same parameters, whatever its study
  /// seed (the seed is then left out of the task's content address).
  bool uses_seed = true;
  std::vector<OutputColumn> outputs;  ///< every scalar and array `run` may return
  ReportSection report;               ///< empty: the report lists the part's counts
  std::vector<PlotView> plots;
};

class TaskRegistry {
 public:
  void add(TaskKind kind);
  /// Declares a kind known to the project whose engine is not part of this build, with the
  /// version its engine will have, so that a store begun without the engine can be resumed by
  /// a build that has it.
  void add_unavailable(std::string name, std::string reason, int version = 1);
  /// Version of an available or declared kind (0 if unknown).
  int version(const std::string& name) const;
  const TaskKind* find(const std::string& name) const;
  /// Empty if available; else "task kind 'NAME' is not available in this build (...)".
  std::string unavailable_reason(const std::string& name) const;
  /// Names of the available kinds, and of the declared unavailable ones.
  std::vector<std::string> names() const;
  std::vector<std::string> unavailable_names() const;

 private:
  std::map<std::string, TaskKind> kinds_;
  std::map<std::string, std::string> unavailable_;
  std::map<std::string, int> unavailable_version_;
};
/// The kinds of this build: the one list in src/study/registry.cpp.
TaskRegistry default_registry();
/// The registry as JSON (`frictal study kinds --json`): per kind its name, description,
/// version, availability, outputs (name, unit, description, array) and plot views (the fields
/// of PlotView). scripts/plot_studies.py renders the views from it.
std::string kinds_json(const TaskRegistry& registry);

// ---------------------------------------------------------------- study definition and grid

struct Task {
  std::int64_t id = 0;   ///< index in grid order, stable for a given definition
  std::string part;      ///< part name
  std::string kind;      ///< task kind
  int kind_version = 0;  ///< the registry's version of the kind (stored with the task's result)
  Params params;         ///< every parameter of the task (constants included)
  std::string key;       ///< canonical(params) with "part" added: unique in the study
  std::uint64_t seed = 0;
};

struct Part {
  std::string name;
  std::string kind;
  std::string description;
  /// Parameter names the seed derives from (empty: all parameters).
  std::vector<std::string> seed_from;
  /// Axes in expansion order (first varies slowest) and their values at the chosen scale.
  std::vector<std::pair<std::string, std::vector<Value>>> axes;
};

struct Study {
  std::string name;
  std::string description;
  std::uint64_t seed = 0;
  bool quick = false;
  std::vector<Part> parts;
  std::vector<Task> tasks;  ///< the expanded grid
  /// Canonical text of the resolved definition (name, seed, scale, parts, axes, kind versions).
  std::string definition;
  std::string hash;  ///< digest(definition)
};

/// Parses a study from TOML text; `origin` names the file in messages. `registry` supplies the
/// kind versions that enter the hash (unknown kinds are an error; unavailable ones are not).
Result<Study> parse_study(const std::string& toml_text, const std::string& origin, bool quick,
                          const TaskRegistry& registry);
/// Same, with a limit on the study's size: at most `max_tasks` tasks over all parts, and as many
/// values per axis (unitless; the overload above allows 10^7). A larger grid is an error before
/// any task is built (fuzz_study uses 10^4, so that no input spends its time building tasks).
Result<Study> parse_study(const std::string& toml_text, const std::string& origin, bool quick,
                          const TaskRegistry& registry, std::int64_t max_tasks);
Result<Study> load_study(const std::string& path, bool quick, const TaskRegistry& registry);

// ---------------------------------------------------------------- store

enum class TaskStatus { Pending, Done, Failed };

struct TaskRecord {
  std::int64_t id = 0;
  TaskStatus status = TaskStatus::Pending;
  std::string error;
  ErrorCode code = ErrorCode::InvalidInput;  ///< of a failure: decides whether it is retried
  double wall_s = 0;
  std::string worker;  ///< e.g. "thread 1", "rank 2"
  int attempts = 1;    ///< attempts this record stands for (retried failures + 1)
  TaskOutput output;
};

struct StoreCounts {
  std::int64_t total = 0, done = 0, failed = 0, pending = 0;
};

/// The SQLite store of one study (WAL journal, one transaction per finished task).
class Store {
 public:
  /// Opens or creates `path` for `study`. A store created for another definition (other file,
  /// scale or kind version) is refused with an error naming both.
  static Result<std::unique_ptr<Store>> open(const std::string& path, const Study& study);
  /// Opens an existing store without a study (status, export, report).
  static Result<std::unique_ptr<Store>> open_existing(const std::string& path);
  ~Store();
  Store(const Store&) = delete;
  Store& operator=(const Store&) = delete;

  /// Ids of tasks not yet done (pending or failed), in id order.
  Result<std::vector<std::int64_t>> unfinished();
  /// Writes one task's outcome atomically.
  Status record(const TaskRecord& r);
  Result<StoreCounts> counts();
  Result<std::map<std::string, std::string>> meta();
  /// Counts by (part, kind, status).
  struct PartCount {
    std::string part, kind;
    std::int64_t done = 0, failed = 0, pending = 0;
  };
  Result<std::vector<PartCount>> part_counts();
  /// Every done task of a part: params (canonical JSON), scalars and arrays.
  using Row = TaskRow;
  Result<std::vector<Row>> rows(const std::string& part = "", bool with_arrays = true);
  /// Bookkeeping of every task (any status), in id order.
  struct TaskInfo {
    std::int64_t id = 0;
    std::string part, kind;
    TaskStatus status = TaskStatus::Pending;
    int attempts = 0;
    std::string error, worker;  ///< empty when none
    double wall_s = 0;          ///< NaN while pending
  };
  Result<std::vector<TaskInfo>> tasks();
  /// The `tasks` table as CSV (task_id, part, kind, params, seed, status, attempts, error,
  /// worker, started_at, finished_at, wall_s): the tasks.csv of export_csv.
  Result<std::string> tasks_csv();
  /// The failed tasks as CSV (task_id, part, params, error).
  Result<std::string> failures_csv();
  /// Claims (concurrent runs on one store): before computing a task a run claims it in the
  /// store (table `claims`: owner, host, pid, heartbeat), in one transaction, so that two runs
  /// never compute the same task while both are alive. A claim held by another run is taken
  /// over when that run's process is gone (same host: its pid no longer exists) or when its
  /// heartbeat is older than `lease_s` seconds (any host).
  enum class Claim {
    Claimed,    ///< this run holds the claim (new, or already its own)
    TakenOver,  ///< claimed from a run that died or whose lease expired
    Finished,   ///< another run recorded the task since this run listed it: skip it
    Busy,       ///< another live run holds it: look again later
  };
  Result<Claim> claim(std::int64_t id, double lease_s);
  /// Refreshes the heartbeat of every claim of this run.
  Status heartbeat();
  /// Drops every claim of this run (at the end of a run, interrupted or not).
  Status release_claims();
  /// This run's claim owner: "host:pid:n".
  const std::string& owner() const;
  /// Testing: caps the store file at `pages` pages (PRAGMA max_page_count), so that writing
  /// beyond it fails as on a full disk (SQLITE_FULL).
  Status limit_pages(std::int64_t pages);
  /// Done tasks by (part, kind version, frictal version) as recorded with each result; kind
  /// version 0 and an empty frictal version: not recorded (a schema-1 store).
  struct VersionCount {
    std::string part;
    int kind_version = 0;
    std::string frictal_version;
    std::int64_t done = 0;
  };
  Result<std::vector<VersionCount>> version_counts();
  /// Tasks claimed now (by live runs or by runs that died).
  Result<std::int64_t> claimed();

  /// Every stored value that does not depend on the run (no timings, worker, attempts or
  /// creation time) as text: two stores of one definition with the same results give the same
  /// text whatever threads or ranks computed them (used to compare runs).
  Result<std::string> content();

  struct Impl;  // opaque (SQLite handle)

 private:
  Store() = default;
  std::unique_ptr<Impl> impl_;
};

// ---------------------------------------------------------------- running

struct Progress {
  std::int64_t total = 0;     ///< tasks in the study
  std::int64_t done = 0;      ///< done (including earlier runs)
  std::int64_t failed = 0;    ///< failed in this run
  std::int64_t this_run = 0;  ///< finished in this run
  std::int64_t to_run = 0;    ///< tasks this run set out to do
  std::int64_t reused = 0;    ///< of this_run: results taken from the result cache, not computed
  double elapsed_s = 0;       ///< since this run started
};

/// The result cache of the stores in the folder of `store_path`: `results-cache.sqlite` beside it.
std::string default_cache_path(const std::string& store_path);

struct RunOptions {
  unsigned threads = 1;           ///< compute threads (0 = hardware concurrency)
  bool skip_unavailable = false;  ///< leave tasks of unavailable kinds pending
  /// Pin compute thread i to CPU i mod (CPUs allowed), as mpirun binds ranks to cores. Results do
  /// not change; on a busy machine it can help the scheduler (docs/performance.md, "Studies and the reproduction").
  bool pin_threads = false;
  std::vector<std::string> parts;                 ///< run only these parts (empty: all)
  std::function<void(const Progress&)> progress;  ///< called after each finished task
  const std::atomic<bool>* stop = nullptr;        ///< set to stop dispatching; in-flight tasks finish
  /// Testing: every attempt computed on this site (rank under MPI; 0 = this process on threads)
  /// is reported failed (a transient, retryable failure), to exercise the retry policy. -1: off.
  int inject_failure_rank = -1;
  /// Testing: the first attempt of each of these task ids is reported failed (transient), so
  /// the task is retried; the same under threads and MPI (decided by the coordinator).
  std::vector<std::int64_t> fail_first_attempt;
  /// Seconds after its last heartbeat that another run's claim on a task is taken over (claims
  /// of a process gone from this host are taken over at once). Heartbeats every lease_s / 4.
  double lease_s = 60;
  /// Testing: caps the store at this many pages (0: no cap), to simulate a full disk.
  std::int64_t max_page_count = 0;
  /// Start tasks in decreasing estimated cost (TaskKind::cost, refined by recorded task times:
  /// docs/studies.md, "Scheduling"); false: in grid (id) order. Results never depend on it.
  bool longest_first = true;
  /// Result cache file shared by the stores of one folder (see default_cache_path; empty: none).
  /// A task whose content address (content_address) the cache holds is recorded from it instead
  /// of being computed (byte-identical: the cache keeps the exact output); every result this run
  /// computes is added. The cache is read for every queued task when the run starts and again
  /// for each task just before it would be computed, so a result another run (another process,
  /// or another study) added meanwhile is reused too. Several runs may share one cache at once.
  std::string cache;
  /// Testing: called once on the calling thread after the run has started (the cache's bulk
  /// lookup done, the queue ordered) and before the first task is claimed (threads only).
  std::function<void()> started;
};

struct RunSummary {
  std::int64_t ran = 0, failed = 0, skipped_unavailable = 0;
  std::int64_t retries = 0;         ///< failed attempts that were queued again
  std::int64_t done_elsewhere = 0;  ///< planned tasks that another run (same store) recorded
  std::int64_t taken_over = 0;      ///< claims taken over from a dead run or an expired lease
  std::int64_t reused = 0;          ///< tasks recorded from the result cache (not computed, not in `ran`)
  /// Why the result cache was not used or not fully written (the run goes on without it); empty if fine.
  std::string cache_note;
  unsigned threads = 0;  ///< compute threads (on rank 0 under MPI)
  bool interrupted = false;
  double wall_s = 0;
};

/// Runs every unfinished task of `study` on threads and records it in `store`. One coordinator
/// (claim -> compute -> record, retry policy, progress) serves this and run_mpi: a failure with a
/// transient code (ErrorCode::Io, Internal) is retried up to 3 attempts, on another rank under
/// MPI when one has not failed it; other failures are recorded at once.
Result<RunSummary> run_threads(const Study& study, Store& store, const TaskRegistry& registry,
                               const RunOptions& options);

/// One study of a multi-study run (run_threads below).
struct StudyRun {
  const Study* study = nullptr;
  Store* store = nullptr;                         ///< this study's store
  std::string cache;                              ///< this study's result cache (RunOptions::cache; empty: none)
  std::function<void(const Progress&)> progress;  ///< this study's progress (RunOptions::progress)
};
/// Runs several studies on one pool of threads (`frictal study run A.toml B.toml --store-dir DIR`).
/// Every unfinished task of every study is in one queue, costliest first across studies (with
/// options.longest_first); each study has its own store, cache and progress (as if run alone), and
/// tasks of different studies with one content address are computed once: the first computes it,
/// the others are recorded from its result (counted as reused). Each store ends with the same
/// content (Store::content) as a run of its study alone. `options` applies to every study except
/// its cache and progress (taken from `runs`); options.parts must be empty with several studies.
/// The summaries are in the order of `runs`; an error (a store that cannot be written) names the
/// study and stops the whole run.
Result<std::vector<RunSummary>> run_threads(const std::vector<StudyRun>& runs, const TaskRegistry& registry,
                                            const RunOptions& options);

/// Tasks of the study that this run will compute (unfinished, selected parts, available kinds),
/// or an error naming an unavailable kind if skip_unavailable is false.
Result<std::vector<std::int64_t>> plan(const Study& study, Store& store, const TaskRegistry& registry,
                                       const RunOptions& options, std::int64_t* skipped_unavailable);

/// A task a run would compute, in the order it would start it (see RunOptions::longest_first).
struct PlannedTask {
  std::int64_t id = 0;
  double estimated_s = 0;  ///< estimated cost (unit: s): a recorded time, or the kind's calibrated model
  bool measured = false;   ///< the estimate is a time recorded for the same kind and parameters
  bool cached = false;     ///< the result cache holds it: it would be reused, not computed
};
/// What run_threads / run_mpi would do with `options` (plan(), the cache lookups and the order),
/// without computing or recording anything: `frictal study run --dry-run`.
Result<std::vector<PlannedTask>> schedule(const Study& study, Store& store, const TaskRegistry& registry,
                                          const RunOptions& options);

/// Cores a run on threads (run_threads) leaves idle, lent to its tasks: once fewer tasks than
/// compute threads remain, a task may borrow the cores of the compute threads that wait for work
/// (the tilt kinds split the contact passes of a long tilt over them). Called from TaskKind::run:
/// borrows up to `want` idle cores and returns how many it got (0 outside run_threads, under MPI,
/// or when none is idle); the task gives them back with return_idle_threads before it returns.
/// Results must not depend on it (it is not a parameter: not in the seed, the store or the
/// content address).
unsigned borrow_idle_threads(unsigned want);
void return_idle_threads(unsigned n);

/// Runs one task (timed, exceptions turned into failures). Used by every runner.
TaskRecord execute(const Task& task, const TaskRegistry& registry, const std::string& worker);

/// Binary (de)serialisation of a record for message passing (MPI). Lossless.
std::string serialize(const TaskRecord& r);
Result<TaskRecord> deserialize(const std::string& bytes);

/// MPI (only when built with FRICTAL_MPI): true if this process was started by mpirun/srun.
bool mpi_available();
bool launched_by_mpi();
/// Under MPI: rank 0 owns the store and runs `options.threads` compute threads besides the
/// message loop; other ranks compute one task at a time. Tasks are handed out dynamically; the
/// retry policy is run_threads' (a transient failure on a rank is retried on another rank). `store` is only used (and
/// must be non-null) on rank 0. The caller owns MPI_Init/Finalize (see mpi_init / mpi_finalize).
Result<RunSummary> run_mpi(const Study& study, Store* store, const TaskRegistry& registry, const RunOptions& options);
/// Initialises MPI (thread level funneled); returns rank and size.
Status mpi_init(int* rank, int* size);
void mpi_finalize();
/// Under MPI: rank 0's `value`, on every rank (every rank must call it, in the same order); keeps
/// the ranks in step between the studies of one run. Without MPI: `value`.
bool mpi_broadcast(bool value);

// ---------------------------------------------------------------- analysis of stored results

/// A claim that the studies check: a claim of the paper, or one of frictal's own findings (what
/// frictal found where the paper's claim does not hold, or a question the paper does not ask).
/// The catalogue (claims()) names each once; a kind's report section checks it on the parts it
/// applies to (Finding::claim_id), and conclude() gives it one verdict over all of them.
struct Claim {
  std::string id;            ///< e.g. "koch-theta-max" (stable: the page links to it)
  bool paper = true;         ///< a claim of the paper; false: frictal's own finding
  std::string statement;     ///< the claim in one sentence
  std::string where;         ///< the paper's section, equation, figures; for frictal's: the docs page and section
  std::vector<int> figures;  ///< the paper's figures it speaks to
  std::string applies_to;    ///< which parts check it (one line)
  std::vector<std::string>
      superseded_by;  ///< frictal's findings (ids) that replace it where the data do not support it
};
/// The catalogue, paper's claims first (src/study/claims.cpp).
const std::vector<Claim>& claims();
/// The claim of that id; nullptr if the catalogue has none.
const Claim* find_claim(const std::string& id);

/// A claim checked on one part of a store: whether the data support it, and the numbers behind it
/// (plain text lines).
struct Finding {
  std::string claim_id;  ///< the claim checked (claims())
  std::string part;      ///< the part (or variant, e.g. "wm [slopes=spline]") it was checked on
  std::string claim;     ///< as the report states it, naming the part
  bool supported = false;
  std::vector<std::string> evidence;  ///< the first line is the criterion and the measured value
  /// A finding that is not supported: the cause the data measure and name (one line, e.g. which
  /// runs a model warning flags, or what a test reads instead), or empty when they name none.
  std::string cause;
};
struct Report {
  std::string study;  ///< the study's name
  std::string title;
  std::vector<std::string> lines;  ///< summary tables
  std::vector<Finding> findings;
};

/// A claim's verdict over every part that checks it: supported (by every part); superseded (not
/// supported, and every one of its superseding findings is supported); not supported (with the
/// measured causes).
enum class Verdict { Supported, NotSupported, Superseded };
/// "supported", "not supported", "superseded".
const char* verdict_name(Verdict v);
struct Conclusion {
  Claim claim;
  Verdict verdict = Verdict::NotSupported;
  struct Check {
    std::string study, part;
    bool supported = false;
    std::string cause;
  };
  std::vector<Check> checks;  ///< every part that checked it, in report order
  /// Not supported or superseded: the measured causes, "study/part: cause" joined by "; " (the
  /// parts without one are named in uncaused).
  std::string cause;
  std::vector<std::string> uncaused;  ///< "study/part" of the parts not supported that measure no cause
};
/// One conclusion per claim that the reports check, in the catalogue's order (claims checked by
/// none are left out). Error: a finding names a claim that the catalogue does not have.
Result<std::vector<Conclusion>> conclude(const std::vector<Report>& reports);

/// A probability density pooled over replicates: every done task of `part` whose parameters
/// equal `params` except `pair`, rebinned onto common edges (assuming uniform density inside
/// each source bin) and averaged with equal weights (paper Fig. 16 pools the 20 pairs).
struct PooledPdf {
  std::string part;
  Params params;                ///< the group's parameters (without pair)
  std::string name;             ///< array prefix, e.g. "contact_slope_pdf"
  int members = 0;              ///< tasks pooled
  std::vector<double> edges;    ///< common bin edges (unit of the source edges)
  std::vector<double> density;  ///< pooled density (integrates to 1)
};
/// Pools every array pair "<prefix>_edges_<unit>" / "<prefix>_density_per_<unit>" of a part.
Result<std::vector<PooledPdf>> pooled_pdfs(Store& store, const std::string& part);

/// Summarises a store: per part, the report section of its kind (tables and the paper's
/// findings with supporting numbers); parts of kinds without a section, their counts.
Result<Report> report(Store& store, const TaskRegistry& registry);
inline Result<Report> report(Store& store) { return report(store, default_registry()); }
/// The report as Markdown (what `frictal study report` prints).
std::string render_markdown(const Report& report);
/// Reports as one JSON object (what `frictal study report --json` prints): per report its study,
/// title and findings (claim id, source, statement, figures, part, claim, criterion, numbers,
/// verdict, cause), and the conclusions over all of them (conclude()). Error: as conclude().
Result<std::string> render_json(const std::vector<Report>& reports);

/// How far a store is: what `frictal study status` shows.
struct StoreStatus {
  std::string study, description, scale, study_hash;
  std::string frictal_version;  ///< of the build that created the store
  int schema_version = 0;
  std::int64_t claimed = 0;  ///< tasks claimed by a run now (or by one that died)
  StoreCounts tasks;
  struct PartStatus {
    std::string part, kind;
    std::int64_t done = 0, failed = 0, pending = 0;
    bool available = false;          ///< this build has the part's kind
    std::string unavailable_reason;  ///< empty if available
    int kind_version = 0;            ///< this build's version of the kind (0: unknown kind)
    /// Done tasks by the kind version and frictal version they were computed with (0 / "": not
    /// recorded, a store of schema 1).
    std::map<int, std::int64_t> done_by_kind_version;
    std::map<std::string, std::int64_t> done_by_frictal_version;
    /// A line when some done tasks were computed by another version of the kind than this
    /// build's (their results may differ from what this build computes); empty otherwise.
    std::string version_note;
  };
  std::vector<PartStatus> parts;
};
Result<StoreStatus> store_status(Store& store, const TaskRegistry& registry);
/// Which versions computed a part's done tasks, as `frictal study status` prints it: per kind
/// version "N by vK" (K = 0: "N by unrecorded version"), then per frictal version "N by frictal V"
/// (V empty: "?"), joined by ", "; empty when no task is done.
std::string done_versions_text(const StoreStatus::PartStatus& part);

/// Writes the store as CSV files under `dir` (created if missing): tasks.csv, per part
/// PART.csv (wide: parameters then scalars), PART-arrays.csv (long), PART-pooled-pdfs.csv (when
/// the part has PDFs) and report.md. Returns the file names written.
Result<std::vector<std::string>> export_csv(Store& store, const std::string& dir, const TaskRegistry& registry);
inline Result<std::vector<std::string>> export_csv(Store& store, const std::string& dir) {
  return export_csv(store, dir, default_registry());
}

/// A store's status as the front ends report it: the store's path and its status.
struct StudyStatusReport {
  const std::string& store;
  const StoreStatus& status;
};
/// A run of a study as the front ends report it: its summary, the store's task counts after it
/// and, for one study of several, which study and store.
struct StudyRunReport {
  const RunSummary& summary;
  StoreCounts tasks;
  std::optional<std::string> study = std::nullopt;  ///< the study's name (runs of several studies)
  std::optional<std::string> store = std::nullopt;  ///< the store's path (runs of several studies)
};

/// The output tables of studies (frictal/outputs.hpp; src/study/study_columns.cpp): `frictal
/// study status --json` and Python study_status() ("study_status", its "tasks" and "parts"), and
/// Python study_run() and study_run_many() ("study_run").
const Columns<StoreCounts>& study_tasks_columns();
const Columns<StoreStatus::PartStatus>& study_part_columns();
const Columns<StudyStatusReport>& study_status_columns();
const Columns<StudyRunReport>& study_run_columns();
/// Python's study_rows(): one done task ("study_row"): its id, part, kind, and its parameters,
/// scalar and array outputs as data maps keyed by name.
const Columns<TaskRow>& study_row_columns();

}  // namespace frictal::study
