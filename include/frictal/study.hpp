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
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "frictal/result.hpp"

namespace frictal::study {

/// Version of the store layout (meta key "schema_version"). Bump on incompatible change.
inline constexpr int kSchemaVersion = 1;

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

/// What a task returns: named scalars and named arrays (flat vectors of reals).
struct TaskOutput {
  std::map<std::string, double> scalars;
  std::map<std::string, std::vector<double>> arrays;
};

/// A task kind: a function of the parameters and the task seed. Must be thread-safe and
/// deterministic (same inputs, bit-identical output); it runs single-threaded.
struct TaskKind {
  std::string name;
  std::string description;
  int version = 1;  ///< bump when results change; part of the study hash
  std::function<Result<TaskOutput>(const Params&, std::uint64_t seed)> run;
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
  /// Empty if available; else "task kind 'tilt' is not available in this build (...)".
  std::string unavailable_reason(const std::string& name) const;
  std::vector<std::string> names() const;

 private:
  std::map<std::string, TaskKind> kinds_;
  std::map<std::string, std::string> unavailable_;
  std::map<std::string, int> unavailable_version_;
};
/// The kinds of this build: koch-signature, wm-pair-statistics; tilt and divider declared
/// unavailable until their engines are merged.
TaskRegistry default_registry();

/// Built-in kinds (exposed for tests and benchmarks).
Result<TaskOutput> run_koch_signature(const Params& p, std::uint64_t seed);
Result<TaskOutput> run_wm_pair_statistics(const Params& p, std::uint64_t seed);
Result<TaskOutput> run_tilt_task(const Params& p, std::uint64_t seed);
Result<TaskOutput> run_divider_task(const Params& p, std::uint64_t seed);

// ---------------------------------------------------------------- study definition and grid

struct Task {
  std::int64_t id = 0;   ///< index in grid order, stable for a given definition
  std::string part;      ///< part name
  std::string kind;      ///< task kind
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
Result<Study> load_study(const std::string& path, bool quick, const TaskRegistry& registry);

// ---------------------------------------------------------------- store

enum class TaskStatus { Pending, Done, Failed };

struct TaskRecord {
  std::int64_t id = 0;
  TaskStatus status = TaskStatus::Pending;
  std::string error;
  double wall_s = 0;
  std::string worker;  ///< e.g. "thread 1", "rank 2"
  int attempts = 1;    ///< executions this record stands for (failed ones reassigned under MPI + 1)
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
  struct Row {
    std::int64_t id = 0;
    std::string part, kind, params_json, status;
    Params params;
    TaskOutput output;
  };
  Result<std::vector<Row>> rows(const std::string& part = "", bool with_arrays = true);
  /// Runs a read-only query and returns a CSV text (header + rows); used by export.
  Result<std::string> query_csv(const std::string& sql);

  struct Impl;  // opaque (SQLite handle)

 private:
  Store() = default;
  std::unique_ptr<Impl> impl_;
};

// ---------------------------------------------------------------- running

struct Progress {
  std::int64_t total = 0;      ///< tasks in the study
  std::int64_t done = 0;       ///< done (including earlier runs)
  std::int64_t failed = 0;     ///< failed in this run
  std::int64_t this_run = 0;   ///< finished in this run
  std::int64_t to_run = 0;     ///< tasks this run set out to do
  double elapsed_s = 0;        ///< since this run started
};

struct RunOptions {
  unsigned threads = 1;               ///< compute threads (0 = hardware concurrency)
  bool skip_unavailable = false;      ///< leave tasks of unavailable kinds pending
  /// Pin compute thread i to CPU i mod (CPUs allowed), as mpirun binds ranks to cores. Results do
  /// not change; on a busy machine it can help the scheduler (see bench/results/studies.md).
  bool pin_threads = false;
  std::vector<std::string> parts;     ///< run only these parts (empty: all)
  std::function<void(const Progress&)> progress;  ///< called after each finished task
  const std::atomic<bool>* stop = nullptr;       ///< set to stop dispatching; in-flight tasks finish
  /// Testing (MPI only): this rank reports every task it gets as failed, to exercise the
  /// reassignment of failed tasks to other ranks. -1: off.
  int inject_failure_rank = -1;
};

struct RunSummary {
  std::int64_t ran = 0, failed = 0, skipped_unavailable = 0;
  bool interrupted = false;
  double wall_s = 0;
};

/// Runs every unfinished task of `study` on threads and records it in `store`.
Result<RunSummary> run_threads(const Study& study, Store& store, const TaskRegistry& registry,
                               const RunOptions& options);

/// Tasks of the study that this run will compute (unfinished, selected parts, available kinds),
/// or an error naming an unavailable kind if skip_unavailable is false.
Result<std::vector<std::int64_t>> plan(const Study& study, Store& store, const TaskRegistry& registry,
                                       const RunOptions& options, std::int64_t* skipped_unavailable);

/// Runs one task (timed, exceptions turned into failures). Used by every runner.
TaskRecord execute(const Task& task, const TaskRegistry& registry, const std::string& worker);

/// Binary (de)serialisation of a record for message passing (MPI). Lossless.
std::string serialize(const TaskRecord& r);
Result<TaskRecord> deserialize(const std::string& bytes);

/// MPI (only when built with FRICTAL_MPI): true if this process was started by mpirun/srun.
bool mpi_available();
bool launched_by_mpi();
/// Under MPI: rank 0 owns the store and runs `options.threads` compute threads besides the
/// message loop; other ranks compute one task at a time. Tasks are handed out dynamically; a
/// task that fails on a rank is retried on another rank (up to 3 attempts) before it is
/// recorded as failed. `store` is only used (and must be non-null) on rank 0. The caller owns
/// MPI_Init/Finalize (see mpi_init / mpi_finalize).
Result<RunSummary> run_mpi(const Study& study, Store* store, const TaskRegistry& registry,
                           const RunOptions& options);
/// Initialises MPI (thread level funneled); returns rank and size.
Status mpi_init(int* rank, int* size);
void mpi_finalize();

// ---------------------------------------------------------------- analysis of stored results

/// A finding of the paper checked against a store: the claim, whether the data support it, and
/// the numbers behind it (plain text lines).
struct Finding {
  std::string claim;
  bool supported = false;
  std::vector<std::string> evidence;
};
struct Report {
  std::string title;
  std::vector<std::string> lines;  ///< summary tables
  std::vector<Finding> findings;
};
/// A probability density pooled over replicates: every done task of `part` whose parameters
/// equal `params` except `pair`, rebinned onto common edges (assuming uniform density inside
/// each source bin) and averaged with equal weights (paper Fig. 16 pools the 20 pairs).
struct PooledPdf {
  std::string part;
  Params params;             ///< the group's parameters (without pair)
  std::string name;          ///< array prefix, e.g. "contact_slope_pdf"
  int members = 0;           ///< tasks pooled
  std::vector<double> edges;    ///< common bin edges (unit of the source edges)
  std::vector<double> density;  ///< pooled density (integrates to 1)
};
/// Pools every array pair "<prefix>_edges_<unit>" / "<prefix>_density_per_<unit>" of a part.
Result<std::vector<PooledPdf>> pooled_pdfs(Store& store, const std::string& part);

/// Summarises a store: per-part tables, and for wm-pair-statistics / koch-signature the paper's
/// findings (Sec. III, V.C-D) with supporting numbers.
Result<Report> report(Store& store);

}  // namespace frictal::study
