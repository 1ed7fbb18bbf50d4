// The result cache shared by the stores of one folder (cache.hpp; docs/studies.md "Result cache").
#include "study/cache.hpp"

#include <sys/stat.h>

#include <fmt/core.h>
#include <sqlite3.h>

#include "frictal/io.hpp"
#include "frictal/version.hpp"
#include "study/liveness.hpp"
#include "study/sqlite_stmt.hpp"

namespace frictal::study {
namespace {

const char* kCacheSchema = R"sql(
CREATE TABLE IF NOT EXISTS meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);
INSERT OR IGNORE INTO meta(key, value) VALUES ('cache_version', '1');
CREATE TABLE IF NOT EXISTS results(
  address         TEXT PRIMARY KEY,
  kind            TEXT NOT NULL,
  kind_version    INTEGER NOT NULL,
  params          TEXT NOT NULL,
  seed            TEXT,
  output          BLOB NOT NULL,
  wall_s          REAL,
  study           TEXT,
  frictal_version TEXT,
  created_at      TEXT
);
CREATE INDEX IF NOT EXISTS results_kind_params ON results(kind, params);
CREATE TABLE IF NOT EXISTS claims(
  address   TEXT PRIMARY KEY,
  owner     TEXT NOT NULL,
  host      TEXT NOT NULL,
  pid       INTEGER NOT NULL,
  pid_start INTEGER NOT NULL,
  heartbeat REAL NOT NULL
) WITHOUT ROWID;
)sql";

}  // namespace

struct ResultCache::Impl {
  sqlite3* db = nullptr;
  std::string path;
  liveness::Identity me;  // the holder of this connection's claims
  ~Impl() {
    if (db) sqlite3_close_v2(db);
  }
  Error err(const std::string& what) const {
    return make_error(ErrorCode::Io, fmt::format("{}: {}: {}", path, what, db ? sqlite3_errmsg(db) : "out of memory"));
  }
  Status exec(const char* sql, bool wait_if_busy = false) {
    char* msg = nullptr;
    if ((wait_if_busy ? exec_waiting(db, sql, &msg) : sqlite3_exec(db, sql, nullptr, nullptr, &msg)) != SQLITE_OK) {
      std::string m = msg ? msg : "?";
      sqlite3_free(msg);
      return make_error(ErrorCode::Io, fmt::format("{}: {}", path, m));
    }
    return Ok{};
  }
};

ResultCache::~ResultCache() = default;

Result<std::unique_ptr<ResultCache>> ResultCache::open(const std::string& path) {
  if (struct stat sb{}; ::stat(path.c_str(), &sb) == 0 && !S_ISREG(sb.st_mode)) {
    if (auto st = check_input_file(path, "a result cache (SQLite file)"); !st) return st.error();
  }
  auto im = std::make_unique<Impl>();
  im->path = path;
  im->me = liveness::Identity::make();
  if (sqlite3_open_v2(path.c_str(), &im->db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_FULLMUTEX,
                      nullptr) != SQLITE_OK)
    return im->err("cannot open the result cache");
  sqlite3_busy_timeout(im->db, 30000);
  for (const char* p : {"PRAGMA journal_mode=WAL;", "PRAGMA synchronous=NORMAL;"})
    if (auto s = im->exec(p, true); !s) return with_prefix("result cache: ", s.error());
  if (auto s = im->exec("BEGIN IMMEDIATE"); !s) return with_prefix("result cache: ", s.error());
  if (auto s = im->exec(kCacheSchema); !s) {
    (void)im->exec("ROLLBACK");
    return make_error(ErrorCode::Io, fmt::format("{} (not a result cache?)", s.error().message));
  }
  {
    Stmt q(im->db, "SELECT value FROM meta WHERE key = 'cache_version'");
    if (!q.ok() || q.step() != SQLITE_ROW || q.text(0) != "1") {
      (void)im->exec("ROLLBACK");
      return make_error(ErrorCode::Io, fmt::format("{}: not a result cache of this build (cache_version)", path));
    }
  }
  if (auto s = im->exec("COMMIT"); !s) {
    (void)im->exec("ROLLBACK");
    return s.error();
  }
  std::unique_ptr<ResultCache> c(new ResultCache());
  c->impl_ = std::move(im);
  return c;
}

const std::string& ResultCache::path() const { return impl_->path; }

Result<std::optional<TaskOutput>> ResultCache::find(const std::string& address, const Task& task) {
  Stmt q(impl_->db, "SELECT kind, kind_version, params, output FROM results WHERE address = ?");
  if (!q.ok()) return impl_->err("reading the result cache");
  q.bind(1, address);
  const int rc = q.step();
  if (rc == SQLITE_DONE) return std::optional<TaskOutput>{};
  if (rc != SQLITE_ROW) return impl_->err("reading the result cache");
  // The address is a 128-bit digest; the entry must also name the same computation.
  if (q.text(0) != task.kind || q.i64(1) != task.kind_version || q.text(2) != canonical(task.params))
    return std::optional<TaskOutput>{};
  auto r = deserialize(q.blob(3));
  if (!r || r->status != TaskStatus::Done) return std::optional<TaskOutput>{};  // damaged entry: compute again
  return std::optional<TaskOutput>{std::move(r->output)};
}

Status ResultCache::put(const std::string& address, const Task& task, bool uses_seed, const TaskRecord& record,
                        const std::string& study) {
  TaskRecord kept;  // only what the result is: the output (the run's bookkeeping stays in the store)
  kept.status = TaskStatus::Done;
  kept.output = record.output;
  kept.wall_s = record.wall_s;
  Stmt w(impl_->db,
         "INSERT OR IGNORE INTO results(address, kind, kind_version, params, seed, output, wall_s, study, "
         "frictal_version, created_at) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  if (!w.ok()) return impl_->err("writing the result cache");
  w.bind(1, address);
  w.bind(2, task.kind);
  w.bind(3, static_cast<std::int64_t>(task.kind_version));
  w.bind(4, canonical(task.params));
  if (uses_seed)
    w.bind(5, std::to_string(task.seed));
  else
    w.bind_null(5);
  w.bind_blob(6, serialize(kept));
  w.bind(7, record.wall_s);
  w.bind(8, study);
  w.bind(9, std::string(frictal::version()));
  w.bind(10, now_utc());
  if (w.step() != SQLITE_DONE) return impl_->err("writing the result cache");
  return release(address);
}

Result<ResultCache::Claim> ResultCache::claim(const std::string& address, double lease_s) {
  Impl& im = *impl_;
  if (auto s = im.exec("BEGIN IMMEDIATE"); !s) return with_prefix("result cache: ", s.error());
  auto done = [&](Claim c) -> Result<Claim> {
    if (auto s = im.exec("COMMIT"); !s) {
      (void)im.exec("ROLLBACK");
      return with_prefix("result cache: ", s.error());
    }
    return c;
  };
  auto fail = [&](const char* what) -> Error {
    Error e = im.err(what);
    (void)im.exec("ROLLBACK");
    return e;
  };
  {
    Stmt r(im.db, "SELECT 1 FROM results WHERE address = ?");
    r.bind(1, address);
    const int rc = r.step();
    if (rc == SQLITE_ROW) return done(Claim::Stored);
    if (rc != SQLITE_DONE) return fail("claiming a result");
  }
  {
    Stmt c(im.db, "SELECT owner, host, pid, pid_start, heartbeat FROM claims WHERE address = ?");
    c.bind(1, address);
    const int rc = c.step();
    if (rc == SQLITE_ROW &&
        im.me.held_by_other(c.text(0), c.text(1), static_cast<long>(c.i64(2)), c.i64(3), c.real(4), lease_s))
      return done(Claim::Busy);
    if (rc != SQLITE_ROW && rc != SQLITE_DONE) return fail("claiming a result");
  }
  Stmt w(im.db,
         "INSERT OR REPLACE INTO claims(address, owner, host, pid, pid_start, heartbeat) VALUES (?, ?, ?, ?, ?, ?)");
  w.bind(1, address);
  im.me.bind_claim(w, 2);
  if (w.step() != SQLITE_DONE) return fail("claiming a result");
  return done(Claim::Claimed);
}

Status ResultCache::release(const std::string& address) {
  Stmt d(impl_->db, "DELETE FROM claims WHERE address = ? AND owner = ?");
  d.bind(1, address);
  d.bind(2, impl_->me.owner);
  if (d.step() != SQLITE_DONE) return impl_->err("releasing a claim in the result cache");
  return Ok{};
}

Status ResultCache::heartbeat() {
  Stmt u(impl_->db, "UPDATE claims SET heartbeat = ? WHERE owner = ?");
  u.bind(1, liveness::now_s());
  u.bind(2, impl_->me.owner);
  if (u.step() != SQLITE_DONE) return impl_->err("refreshing claims in the result cache");
  return Ok{};
}

Status ResultCache::release_claims() {
  Stmt d(impl_->db, "DELETE FROM claims WHERE owner = ?");
  d.bind(1, impl_->me.owner);
  if (d.step() != SQLITE_DONE) return impl_->err("releasing claims in the result cache");
  return Ok{};
}

Result<std::vector<ResultCache::Timing>> ResultCache::timings() {
  Stmt q(impl_->db, "SELECT kind, params, wall_s FROM results WHERE wall_s > 0");
  if (!q.ok()) return impl_->err("reading the result cache");
  std::vector<Timing> out;
  int rc;
  while ((rc = q.step()) == SQLITE_ROW) out.push_back({q.text(0), q.text(1), q.real(2)});
  if (rc != SQLITE_DONE) return impl_->err("reading the result cache");
  return out;
}

std::string content_address(const Task& task, const TaskRegistry& registry) {
  const TaskKind* k = registry.find(task.kind);
  return content_address(task.kind, task.kind_version, task.params, k ? k->uses_seed : true, task.seed);
}

std::string default_cache_path(const std::string& store_path) {
  const auto slash = store_path.rfind('/');
  return (slash == std::string::npos ? std::string() : store_path.substr(0, slash + 1)) + "results-cache.sqlite";
}

}  // namespace frictal::study
