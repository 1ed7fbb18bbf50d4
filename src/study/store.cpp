// The SQLite store of a study. Layout (schema version 1) is documented in docs/studies.md.
//
// Durability: WAL journal with synchronous=NORMAL. Every finished task is one transaction
// (its scalars, arrays and status together), so after SIGKILL or power loss a task is either
// fully recorded or still pending; a transaction cut short rolls back on the next open.
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <mutex>
#include <sstream>

#include <fmt/core.h>
#include <sqlite3.h>
#include <nlohmann/json.hpp>

#include "frictal/io.hpp"
#include "frictal/study.hpp"
#include "frictal/version.hpp"
#include "study/liveness.hpp"
#include "study/sqlite_stmt.hpp"
#include "util/json_text.hpp"

namespace frictal::study {

using util::json_array;
using util::json_real;
using util::json_string;

namespace {

const char* kSchema = R"sql(
CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE tasks(
  task_id     INTEGER PRIMARY KEY,
  part        TEXT NOT NULL,
  kind        TEXT NOT NULL,
  params      TEXT NOT NULL,
  task_key    TEXT NOT NULL UNIQUE,
  seed        TEXT NOT NULL,
  status      TEXT NOT NULL DEFAULT 'pending' CHECK (status IN ('pending', 'done', 'failed')),
  attempts    INTEGER NOT NULL DEFAULT 0,
  error       TEXT,
  scalars     TEXT,
  worker      TEXT,
  started_at  TEXT,
  finished_at TEXT,
  wall_s      REAL,
  kind_version    INTEGER,
  frictal_version TEXT,
  study_hash      TEXT
);
CREATE TABLE params(task_id INTEGER NOT NULL REFERENCES tasks(task_id), name TEXT NOT NULL, value,
                    PRIMARY KEY (task_id, name)) WITHOUT ROWID;
CREATE TABLE scalars(task_id INTEGER NOT NULL REFERENCES tasks(task_id), name TEXT NOT NULL, value REAL,
                     PRIMARY KEY (task_id, name)) WITHOUT ROWID;
CREATE TABLE arrays(task_id INTEGER NOT NULL REFERENCES tasks(task_id), name TEXT NOT NULL,
                    length INTEGER NOT NULL, json TEXT NOT NULL, PRIMARY KEY (task_id, name)) WITHOUT ROWID;
CREATE INDEX tasks_status ON tasks(status);
CREATE TABLE claims(task_id INTEGER PRIMARY KEY REFERENCES tasks(task_id), owner TEXT NOT NULL, host TEXT NOT NULL,
                    pid INTEGER NOT NULL, pid_start INTEGER NOT NULL, heartbeat REAL NOT NULL);
CREATE VIEW results AS
  SELECT t.task_id, t.part, t.kind, t.params, s.name, s.value FROM tasks t JOIN scalars s USING (task_id)
  WHERE t.status = 'done';
)sql";

// Schema 1 -> 2: per-task versions and the claims table (columns added; nothing rewritten).
const char* kUpgrade1to2 = R"sql(
ALTER TABLE tasks ADD COLUMN kind_version INTEGER;
ALTER TABLE tasks ADD COLUMN frictal_version TEXT;
ALTER TABLE tasks ADD COLUMN study_hash TEXT;
CREATE TABLE IF NOT EXISTS claims(task_id INTEGER PRIMARY KEY REFERENCES tasks(task_id), owner TEXT NOT NULL,
                    host TEXT NOT NULL, pid INTEGER NOT NULL, pid_start INTEGER NOT NULL, heartbeat REAL NOT NULL);
UPDATE meta SET value = '2' WHERE key = 'schema_version';
)sql";

const char* status_text(TaskStatus s) {
  switch (s) {
    case TaskStatus::Pending: return "pending";
    case TaskStatus::Done: return "done";
    case TaskStatus::Failed: return "failed";
  }
  return "pending";
}

Value from_json(const nlohmann::json& j) {
  if (j.is_boolean()) return Value{j.get<bool>()};
  if (j.is_number_integer()) return Value{j.get<std::int64_t>()};
  if (j.is_number()) return Value{j.get<double>()};
  if (j.is_string()) return Value{j.get<std::string>()};
  return Value{std::string(j.dump())};
}

}  // namespace

struct Store::Impl {
  sqlite3* db = nullptr;
  std::string path;
  // Claims: this run's identity.
  liveness::Identity me;
  // Attempts of each unfinished task when this run listed them (unfinished()): a task whose
  // count grew since was recorded by another run.
  std::map<std::int64_t, std::int64_t> seen_attempts;
  // Versions written with each result.
  std::vector<int> kind_versions;
  std::string study_hash;
  // One transaction at a time on the connection (compute threads claim, the owner records).
  std::recursive_mutex mu;
  ~Impl() {
    if (db) sqlite3_close_v2(db);
  }
  /// What went wrong, in words, for the conditions a user must act on.
  std::string what_happened(int rc) const {
    const int sys = db ? sqlite3_system_errno(db) : 0;
    if ((rc & 0xff) == SQLITE_IOERR && (sys == ENOSPC || sys == EFBIG || sys == EDQUOT)) rc = SQLITE_FULL;
    if ((rc & 0xff) == SQLITE_IOERR && (sys == EROFS || sys == EPERM || sys == EACCES)) rc = SQLITE_READONLY;
    // SQLite keeps no reliable errno for a failed write (ENOSPC is reported as SQLITE_FULL,
    // EFBIG and a failed device as SQLITE_IOERR_WRITE).
    if (rc == SQLITE_IOERR_WRITE || rc == SQLITE_IOERR_FSYNC || rc == SQLITE_IOERR_TRUNCATE)
      return "writing failed: the disk is full, the file size limit is reached or the device failed; tasks recorded "
             "before are kept: free space and run the same command again to resume";
    switch (rc & 0xff) {
      case SQLITE_FULL:
        return "the disk is full (or the file size limit is reached); tasks recorded before are kept: free space and "
               "run the same command again to resume";
      case SQLITE_READONLY:
        return "the store is read-only (file, directory or file system not writable); tasks recorded before are kept: "
               "make it writable or copy it elsewhere and run again";
      case SQLITE_CANTOPEN: return "cannot open the store or its journal (is the directory writable?)";
      case SQLITE_IOERR:
        return "an I/O error (disk, network file system); tasks recorded before are kept: run again to resume";
      case SQLITE_CORRUPT:
      case SQLITE_NOTADB: return "the file is not a valid SQLite study store";
      default: return {};
    }
  }
  Error err(const std::string& what) const {
    const int rc = sqlite3_extended_errcode(db);
    const std::string why = what_happened(rc);
    return make_error(ErrorCode::Io, why.empty() ? fmt::format("{}: {}: {}", path, what, sqlite3_errmsg(db))
                                                 : fmt::format("{}: {}: {} ({})", path, what, why, sqlite3_errmsg(db)));
  }
  Status exec(const char* sql, bool wait_if_busy = false) {
    char* msg = nullptr;
    const int rc = wait_if_busy ? exec_waiting(db, sql, &msg) : sqlite3_exec(db, sql, nullptr, nullptr, &msg);
    if (rc != SQLITE_OK) {
      std::string m = msg ? msg : "?";
      sqlite3_free(msg);
      const std::string why = what_happened(sqlite3_extended_errcode(db));
      return make_error(ErrorCode::Io,
                        why.empty() ? fmt::format("{}: {}", path, m) : fmt::format("{}: {} ({})", path, why, m));
    }
    return Ok{};
  }
};

namespace {
Result<std::unique_ptr<Store::Impl>> open_db(const std::string& path, bool create) {
  // An existing path must be a regular file: SQLite would block forever on a FIFO with no writer
  // and give a vague message for a directory or a device. A missing one is created (create) or
  // reported by the caller.
  if (struct stat sb{}; ::stat(path.c_str(), &sb) == 0 && !S_ISREG(sb.st_mode)) {
    if (auto st = check_input_file(path, "a study store (SQLite file)"); !st) return st.error();
  }
  auto impl = std::make_unique<Store::Impl>();
  impl->path = path;
  impl->me = liveness::Identity::make();
  const int flags = SQLITE_OPEN_READWRITE | (create ? SQLITE_OPEN_CREATE : 0) | SQLITE_OPEN_FULLMUTEX;
  if (sqlite3_open_v2(path.c_str(), &impl->db, flags, nullptr) != SQLITE_OK) {
    std::string m = impl->db ? sqlite3_errmsg(impl->db) : "out of memory";
    return make_error(ErrorCode::Io, fmt::format("{}: cannot open the store: {}", path, m));
  }
  sqlite3_busy_timeout(impl->db, 30000);
  sqlite3_extended_result_codes(impl->db, 1);
  for (const char* p : {"PRAGMA journal_mode=WAL;", "PRAGMA synchronous=NORMAL;", "PRAGMA foreign_keys=ON;"})
    if (auto s = impl->exec(p, true); !s)
      return make_error(ErrorCode::Io, fmt::format("{} (is it an SQLite file?)", s.error().message));
  return impl;
}

bool has_meta(Store::Impl& im) {
  Stmt q(im.db, "SELECT count(*) FROM sqlite_master WHERE type='table' AND name='meta'");
  return q.ok() && q.step() == SQLITE_ROW && q.i64(0) > 0;
}
}  // namespace

Store::~Store() = default;

Result<std::unique_ptr<Store>> Store::open(const std::string& path, const Study& study) {
  auto im = open_db(path, true);
  if (!im) return im.error();
  Impl& db = **im;
  db.study_hash = study.hash;
  for (const Task& t : study.tasks) db.kind_versions.push_back(t.kind_version);
  if (sqlite3_db_readonly(db.db, "main") == 1)
    return make_error(ErrorCode::Io, fmt::format("{}: cannot run: {}", path, db.what_happened(SQLITE_READONLY)));
  if (auto s = db.exec("BEGIN IMMEDIATE"); !s) return with_prefix("cannot start the run: ", s.error());
  if (!has_meta(db)) {
    // New store: schema, meta and every task in one transaction.
    if (auto s = db.exec(kSchema); !s) {
      (void)db.exec("ROLLBACK");
      return make_error(fmt::format("{}: not an empty or frictal study store ({})", path, s.error().message));
    }
    Stmt m(db.db, "INSERT INTO meta(key, value) VALUES (?, ?)");
    const std::pair<std::string, std::string> meta[] = {
        {"schema_version", std::to_string(kSchemaVersion)},
        {"study_name", study.name},
        {"study_description", study.description},
        {"study_hash", study.hash},
        {"study_definition", study.definition},
        {"scale", study.quick ? "quick" : "full"},
        {"study_seed", std::to_string(study.seed)},
        {"created_at", now_utc()},
        {"frictal_version", frictal::version()},
    };
    for (const auto& [k, v] : meta) {
      m.reset();
      m.bind(1, k);
      m.bind(2, v);
      if (m.step() != SQLITE_DONE) {
        (void)db.exec("ROLLBACK");
        return db.err("writing meta");
      }
    }
    Stmt t(db.db, "INSERT INTO tasks(task_id, part, kind, params, task_key, seed) VALUES (?, ?, ?, ?, ?, ?)");
    Stmt pa(db.db, "INSERT INTO params(task_id, name, value) VALUES (?, ?, ?)");
    for (const Task& task : study.tasks) {
      t.reset();
      t.bind(1, task.id);
      t.bind(2, task.part);
      t.bind(3, task.kind);
      t.bind(4, canonical(task.params));
      t.bind(5, task.key);
      t.bind(6, std::to_string(task.seed));
      if (t.step() != SQLITE_DONE) {
        (void)db.exec("ROLLBACK");
        return db.err("writing tasks");
      }
      for (const auto& [name, v] : task.params) {
        pa.reset();
        pa.bind(1, task.id);
        pa.bind(2, name);
        if (auto* i = std::get_if<std::int64_t>(&v))
          pa.bind(3, *i);
        else if (auto* d = std::get_if<double>(&v))
          pa.bind(3, *d);
        else if (auto* s = std::get_if<std::string>(&v))
          pa.bind(3, *s);
        else
          pa.bind(3, static_cast<std::int64_t>(std::get<bool>(v)));
        if (pa.step() != SQLITE_DONE) {
          (void)db.exec("ROLLBACK");
          return db.err("writing params");
        }
      }
    }
  } else {
    std::map<std::string, std::string> meta;
    {
      Stmt q(db.db, "SELECT key, value FROM meta");
      while (q.step() == SQLITE_ROW) meta[q.text(0)] = q.text(1);
    }
    if (meta["schema_version"] == "1" && meta["study_hash"] == study.hash) {
      // Upgrade in place (columns added, nothing rewritten); results of schema 1 keep no versions.
      if (auto s = db.exec(kUpgrade1to2); !s) {
        (void)db.exec("ROLLBACK");
        return with_prefix("upgrading the store from schema 1: ", s.error());
      }
      if (auto s = db.exec("COMMIT"); !s) {
        (void)db.exec("ROLLBACK");
        return s.error();
      }
      meta["schema_version"] = std::to_string(kSchemaVersion);
    } else {
      (void)db.exec("ROLLBACK");
    }
    if (meta["schema_version"] != std::to_string(kSchemaVersion))
      return make_error(fmt::format("{}: store schema version {} is not supported by this build (version {})", path,
                                    meta["schema_version"], kSchemaVersion));
    if (meta["study_hash"] != study.hash)
      return make_error(fmt::format(
          "{}: this store belongs to another study definition: it holds '{}' ({} scale, definition hash {}), "
          "but the study file defines '{}' ({} scale, hash {}); use another --store file, or delete this one to start "
          "over",
          path, meta["study_name"], meta["scale"], meta["study_hash"], study.name, study.quick ? "quick" : "full",
          study.hash));
    std::unique_ptr<Store> st(new Store());
    st->impl_ = std::move(*im);
    return st;
  }
  if (auto s = db.exec("COMMIT"); !s) {
    (void)db.exec("ROLLBACK");
    return s.error();
  }
  std::unique_ptr<Store> st(new Store());
  st->impl_ = std::move(*im);
  return st;
}

Result<std::unique_ptr<Store>> Store::open_existing(const std::string& path) {
  if (auto st = check_input_file(path, "a study store (SQLite file)"); !st) {
    // Decided on the code, never on the text: a directory, FIFO or device (InvalidInput) keeps
    // its message, as does an I/O error other than a missing file (permissions); nothing there
    // at all is "no such store file".
    if (st.error().code != ErrorCode::Io) return st.error();
    struct stat sb {};
    if (::stat(path.c_str(), &sb) == 0 || errno != ENOENT) return st.error();
    return make_error(ErrorCode::Io, fmt::format("{}: no such store file", path));
  }
  auto im = open_db(path, false);
  if (!im) return im.error();
  if (!has_meta(**im)) return make_error(fmt::format("{}: not a frictal study store (no meta table)", path));
  std::unique_ptr<Store> st(new Store());
  st->impl_ = std::move(*im);
  auto m = st->meta();
  if (!m) return m.error();
  if ((*m)["schema_version"] != std::to_string(kSchemaVersion) && (*m)["schema_version"] != "1")
    return make_error(fmt::format("{}: store schema version {} is not supported by this build (version {})", path,
                                  (*m)["schema_version"], kSchemaVersion));
  return st;
}

Result<std::vector<std::int64_t>> Store::unfinished() {
  std::lock_guard lk(impl_->mu);
  Stmt q(impl_->db, "SELECT task_id, attempts FROM tasks WHERE status != 'done' ORDER BY task_id");
  if (!q.ok()) return impl_->err("reading tasks");
  std::vector<std::int64_t> ids;
  int rc;
  impl_->seen_attempts.clear();
  while ((rc = q.step()) == SQLITE_ROW) {
    ids.push_back(q.i64(0));
    impl_->seen_attempts[q.i64(0)] = q.i64(1);
  }
  if (rc != SQLITE_DONE) return impl_->err("reading tasks");
  return ids;
}

Status Store::record(const TaskRecord& r) {
  Impl& db = *impl_;
  std::lock_guard lk(db.mu);
  if (auto s = db.exec("BEGIN IMMEDIATE"); !s) return with_prefix(fmt::format("recording task {}: ", r.id), s.error());
  auto fail = [&](const char* what) -> Status {
    Error e = db.err(what);
    (void)db.exec("ROLLBACK");
    return e;
  };
  {
    // This run's claim is done with, whatever happens below.
    Stmt dc(db.db, "DELETE FROM claims WHERE task_id = ? AND owner = ?");
    dc.bind(1, r.id);
    dc.bind(2, db.me.owner);
    if (dc.step() != SQLITE_DONE) return fail("recording a task");
    // Another run (same store) may have recorded it meanwhile (e.g. after taking over an
    // expired claim): a done result is never replaced, nor a newer outcome by a failure.
    Stmt cur(db.db, "SELECT status, attempts FROM tasks WHERE task_id = ?");
    cur.bind(1, r.id);
    if (cur.step() == SQLITE_ROW) {
      const std::string st = cur.text(0);
      const auto seen = db.seen_attempts.find(r.id);
      const bool newer = seen != db.seen_attempts.end() && cur.i64(1) > seen->second;
      if (st == "done" || (newer && r.status != TaskStatus::Done)) {
        cur.reset();
        if (auto s = db.exec("COMMIT"); !s) {
          (void)db.exec("ROLLBACK");
          return s.error();
        }
        return Ok{};
      }
    }
  }
  {
    Stmt d1(db.db, "DELETE FROM scalars WHERE task_id = ?");
    d1.bind(1, r.id);
    if (d1.step() != SQLITE_DONE) return fail("recording a task");
    Stmt d2(db.db, "DELETE FROM arrays WHERE task_id = ?");
    d2.bind(1, r.id);
    if (d2.step() != SQLITE_DONE) return fail("recording a task");
    if (r.status == TaskStatus::Done) {
      Stmt s(db.db, "INSERT INTO scalars(task_id, name, value) VALUES (?, ?, ?)");
      for (const auto& [k, v] : r.output.scalars) {
        s.reset();
        s.bind(1, r.id);
        s.bind(2, k);
        s.bind(3, v);
        if (s.step() != SQLITE_DONE) return fail("recording scalars");
      }
      Stmt a(db.db, "INSERT INTO arrays(task_id, name, length, json) VALUES (?, ?, ?, ?)");
      for (const auto& [k, v] : r.output.arrays) {
        a.reset();
        a.bind(1, r.id);
        a.bind(2, k);
        a.bind(3, static_cast<std::int64_t>(v.size()));
        a.bind(4, json_array(v));
        if (a.step() != SQLITE_DONE) return fail("recording arrays");
      }
    }
    const auto fin = std::chrono::system_clock::now();
    const auto t = std::chrono::system_clock::to_time_t(fin);
    const auto t0 = std::chrono::system_clock::to_time_t(
        fin - std::chrono::duration_cast<std::chrono::system_clock::duration>(std::chrono::duration<double>(r.wall_s)));
    auto iso = [](std::time_t x) {
      std::tm tm{};
      gmtime_r(&x, &tm);
      char buf[32];
      std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
      return std::string(buf);
    };
    Stmt u(db.db,
           "UPDATE tasks SET status = ?, attempts = attempts + ?, error = ?, worker = ?, started_at = ?, "
           "finished_at = ?, wall_s = ?, scalars = ?, kind_version = ?, frictal_version = ?, study_hash = ? "
           "WHERE task_id = ?");
    u.bind(1, std::string(status_text(r.status)));
    u.bind(2, static_cast<std::int64_t>(std::max(1, r.attempts)));
    if (r.error.empty())
      u.bind_null(3);
    else
      u.bind(3, r.error);
    u.bind(4, r.worker);
    u.bind(5, iso(t0));
    u.bind(6, iso(t));
    u.bind(7, r.wall_s);
    if (r.status == TaskStatus::Done) {
      std::string js = "{";
      for (const auto& [k, v] : r.output.scalars) {
        if (js.size() > 1) js += ',';
        js += json_string(k);
        js += ':';
        js += json_real(v);
      }
      u.bind(8, js + "}");
    } else {
      u.bind_null(8);
    }
    if (r.id >= 0 && static_cast<std::size_t>(r.id) < db.kind_versions.size())
      u.bind(9, static_cast<std::int64_t>(db.kind_versions[static_cast<std::size_t>(r.id)]));
    else
      u.bind_null(9);
    u.bind(10, std::string(frictal::version()));
    u.bind(11, db.study_hash);
    u.bind(12, r.id);
    if (u.step() != SQLITE_DONE) return fail("recording a task");
    if (sqlite3_changes(db.db) != 1) {
      (void)db.exec("ROLLBACK");
      return make_error(fmt::format("{}: task {} is not in the store", db.path, r.id));
    }
  }
  if (auto s = db.exec("COMMIT"); !s) {
    (void)db.exec("ROLLBACK");
    return s.error();
  }
  if (r.status == TaskStatus::Done)
    db.seen_attempts.erase(r.id);
  else
    db.seen_attempts[r.id] += std::max(1, r.attempts);
  return Ok{};
}

Result<Store::Claim> Store::claim(std::int64_t id, double lease_s) {
  Impl& db = *impl_;
  std::lock_guard lk(db.mu);
  if (auto s = db.exec("BEGIN IMMEDIATE"); !s) return with_prefix(fmt::format("claiming task {}: ", id), s.error());
  auto fail = [&](const char* what) -> Error {
    Error e = db.err(what);
    (void)db.exec("ROLLBACK");
    return e;
  };
  auto commit = [&](Claim c) -> Result<Claim> {
    if (auto s = db.exec("COMMIT"); !s) {
      (void)db.exec("ROLLBACK");
      return with_prefix(fmt::format("claiming task {}: ", id), s.error());
    }
    return c;
  };
  {
    Stmt t(db.db, "SELECT status, attempts FROM tasks WHERE task_id = ?");
    t.bind(1, id);
    const int rc = t.step();
    if (rc != SQLITE_ROW) {
      if (rc == SQLITE_DONE) {
        (void)db.exec("ROLLBACK");
        return make_error(fmt::format("{}: task {} is not in the store", db.path, id));
      }
      return fail("claiming a task");
    }
    const auto seen = db.seen_attempts.find(id);
    if (t.text(0) == "done" || (seen != db.seen_attempts.end() && t.i64(1) > seen->second)) {
      t.reset();
      return commit(Claim::Finished);
    }
  }
  Claim result = Claim::Claimed;
  {
    Stmt c(db.db, "SELECT owner, host, pid, pid_start, heartbeat FROM claims WHERE task_id = ?");
    c.bind(1, id);
    const int rc = c.step();
    if (rc == SQLITE_ROW) {
      const std::string owner = c.text(0);
      if (owner != db.me.owner) {
        if (db.me.held_by_other(owner, c.text(1), static_cast<long>(c.i64(2)), c.i64(3), c.real(4), lease_s)) {
          c.reset();
          return commit(Claim::Busy);
        }
        result = Claim::TakenOver;
      }
    } else if (rc != SQLITE_DONE) {
      return fail("claiming a task");
    }
  }
  Stmt w(db.db,
         "INSERT OR REPLACE INTO claims(task_id, owner, host, pid, pid_start, heartbeat) VALUES (?, ?, ?, ?, ?, ?)");
  w.bind(1, id);
  db.me.bind_claim(w, 2);
  if (w.step() != SQLITE_DONE) return fail("claiming a task");
  return commit(result);
}

Status Store::heartbeat() {
  std::lock_guard lk(impl_->mu);
  Stmt u(impl_->db, "UPDATE claims SET heartbeat = ? WHERE owner = ?");
  u.bind(1, liveness::now_s());
  u.bind(2, impl_->me.owner);
  if (u.step() != SQLITE_DONE) return impl_->err("refreshing claims");
  return Ok{};
}

Status Store::release_claims() {
  std::lock_guard lk(impl_->mu);
  Stmt d(impl_->db, "DELETE FROM claims WHERE owner = ?");
  d.bind(1, impl_->me.owner);
  if (d.step() != SQLITE_DONE) return impl_->err("releasing claims");
  return Ok{};
}

const std::string& Store::owner() const { return impl_->me.owner; }

Status Store::limit_pages(std::int64_t pages) {
  std::lock_guard lk(impl_->mu);
  const std::string sql = fmt::format("PRAGMA max_page_count = {};", pages);
  return impl_->exec(sql.c_str());
}

Result<std::vector<Store::VersionCount>> Store::version_counts() {
  std::lock_guard lk(impl_->mu);
  std::vector<VersionCount> out;
  Stmt probe(impl_->db, "SELECT kind_version, frictal_version FROM tasks LIMIT 0");
  if (!probe.ok()) return out;  // schema 1: no versions recorded
  Stmt q(impl_->db,
         "SELECT part, coalesce(kind_version, 0), coalesce(frictal_version, ''), count(*) FROM tasks WHERE status = "
         "'done' "
         "GROUP BY part, kind_version, frictal_version ORDER BY min(task_id)");
  if (!q.ok()) return impl_->err("reading task versions");
  int rc;
  while ((rc = q.step()) == SQLITE_ROW) out.push_back({q.text(0), static_cast<int>(q.i64(1)), q.text(2), q.i64(3)});
  if (rc != SQLITE_DONE) return impl_->err("reading task versions");
  return out;
}

Result<std::int64_t> Store::claimed() {
  std::lock_guard lk(impl_->mu);
  Stmt probe(impl_->db, "SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = 'claims'");
  if (!probe.ok() || probe.step() != SQLITE_ROW || probe.i64(0) == 0) return std::int64_t{0};
  Stmt q(impl_->db, "SELECT count(*) FROM claims");
  if (!q.ok() || q.step() != SQLITE_ROW) return impl_->err("counting claims");
  return q.i64(0);
}

Result<StoreCounts> Store::counts() {
  Stmt q(impl_->db, "SELECT status, count(*) FROM tasks GROUP BY status");
  if (!q.ok()) return impl_->err("counting tasks");
  StoreCounts c;
  int rc;
  while ((rc = q.step()) == SQLITE_ROW) {
    const std::string s = q.text(0);
    const auto n = q.i64(1);
    c.total += n;
    if (s == "done")
      c.done += n;
    else if (s == "failed")
      c.failed += n;
    else
      c.pending += n;  // 'pending' (or anything a damaged store holds: not done)
  }
  if (rc != SQLITE_DONE) return impl_->err("counting tasks");
  return c;
}

Result<std::map<std::string, std::string>> Store::meta() {
  Stmt q(impl_->db, "SELECT key, value FROM meta");
  if (!q.ok()) return impl_->err("reading meta");
  std::map<std::string, std::string> m;
  int rc;
  while ((rc = q.step()) == SQLITE_ROW) m[q.text(0)] = q.text(1);
  if (rc != SQLITE_DONE) return impl_->err("reading meta");
  return m;
}

Result<std::vector<Store::PartCount>> Store::part_counts() {
  Stmt q(impl_->db, "SELECT part, kind, status, count(*) FROM tasks GROUP BY part, kind, status ORDER BY min(task_id)");
  if (!q.ok()) return impl_->err("counting tasks");
  std::vector<PartCount> out;
  int rc;
  while ((rc = q.step()) == SQLITE_ROW) {
    const std::string part = q.text(0), kind = q.text(1), st = q.text(2);
    auto it = std::find_if(out.begin(), out.end(), [&](const PartCount& p) { return p.part == part; });
    if (it == out.end()) {
      out.push_back({part, kind});
      it = out.end() - 1;
    }
    (st == "done" ? it->done : st == "failed" ? it->failed : it->pending) += q.i64(3);
  }
  if (rc != SQLITE_DONE) return impl_->err("counting tasks");
  return out;
}

Result<std::vector<Store::Row>> Store::rows(const std::string& part, bool with_arrays) {
  std::vector<Row> out;
  std::map<std::int64_t, std::size_t> at;
  {
    Stmt q(impl_->db,
           "SELECT task_id, part, kind, params, status FROM tasks WHERE status = 'done' AND (?1 = '' OR part = ?1) "
           "ORDER BY task_id");
    q.bind(1, part);
    int rc;
    while ((rc = q.step()) == SQLITE_ROW) {
      Row r;
      r.id = q.i64(0);
      r.part = q.text(1);
      r.kind = q.text(2);
      r.params_json = q.text(3);
      r.status = q.text(4);
      try {
        const nlohmann::json j = nlohmann::json::parse(r.params_json);
        for (const auto& [k, v] : j.items()) r.params[k] = from_json(v);
      } catch (const std::exception& e) {
        return make_error(fmt::format("{}: task {}: malformed params text: {}", impl_->path, r.id, e.what()));
      }
      at[r.id] = out.size();
      out.push_back(std::move(r));
    }
    if (rc != SQLITE_DONE) return impl_->err("reading results");
  }
  {
    Stmt q(impl_->db,
           "SELECT s.task_id, s.name, s.value FROM scalars s JOIN tasks t USING (task_id) "
           "WHERE t.status = 'done' AND (?1 = '' OR t.part = ?1)");
    q.bind(1, part);
    int rc;
    while ((rc = q.step()) == SQLITE_ROW)
      if (auto it = at.find(q.i64(0)); it != at.end()) out[it->second].output.scalars[q.text(1)] = q.real(2);
    if (rc != SQLITE_DONE) return impl_->err("reading results");
  }
  if (with_arrays) {
    Stmt q(impl_->db,
           "SELECT a.task_id, a.name, a.json FROM arrays a JOIN tasks t USING (task_id) "
           "WHERE t.status = 'done' AND (?1 = '' OR t.part = ?1)");
    q.bind(1, part);
    int rc;
    while ((rc = q.step()) == SQLITE_ROW) {
      auto it = at.find(q.i64(0));
      if (it == at.end()) continue;
      std::vector<double> v;
      try {
        const nlohmann::json j = nlohmann::json::parse(q.text(2));
        for (const auto& e : j) v.push_back(e.is_number() ? e.get<double>() : std::nan(""));
      } catch (const std::exception& e) {
        return make_error(fmt::format("{}: task {}: malformed array text: {}", impl_->path, q.i64(0), e.what()));
      }
      out[it->second].output.arrays[q.text(1)] = std::move(v);
    }
    if (rc != SQLITE_DONE) return impl_->err("reading results");
  }
  return out;
}

namespace {
/// A read-only query as CSV text (header + rows; NULL empty, reals shortest round-trip). The
/// SQL stays here: the public API offers what the front ends need (tasks, rows, content).
Result<std::string> query_csv(Store::Impl& im, const char* sql) {
  Stmt q(im.db, sql);
  if (!q.ok()) return im.err("query");
  const int n = sqlite3_column_count(q.get());
  std::string csv;
  auto quote = [](const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string o = "\"";
    for (char c : s) o += (c == '"') ? std::string("\"\"") : std::string(1, c);
    return o + "\"";
  };
  for (int c = 0; c < n; ++c) {
    if (c) csv += ',';
    csv += quote(sqlite3_column_name(q.get(), c));
  }
  csv += '\n';
  int rc;
  while ((rc = q.step()) == SQLITE_ROW) {
    for (int c = 0; c < n; ++c) {
      if (c) csv += ',';
      switch (sqlite3_column_type(q.get(), c)) {
        case SQLITE_NULL: break;
        case SQLITE_INTEGER: csv += std::to_string(q.i64(c)); break;
        case SQLITE_FLOAT: csv += json_real(q.real(c)); break;
        default: csv += quote(q.text(c));
      }
    }
    csv += '\n';
  }
  if (rc != SQLITE_DONE) return im.err("query");
  return csv;
}
}  // namespace

Result<std::string> Store::tasks_csv() {
  return query_csv(*impl_,
                   "SELECT task_id, part, kind, params, seed, status, attempts, error, worker, started_at, "
                   "finished_at, wall_s FROM tasks ORDER BY task_id");
}

Result<std::string> Store::failures_csv() {
  return query_csv(*impl_, "SELECT task_id, part, params, error FROM tasks WHERE status = 'failed' ORDER BY task_id");
}

Result<std::vector<Store::TaskInfo>> Store::tasks() {
  Stmt q(impl_->db, "SELECT task_id, part, kind, status, attempts, error, worker, wall_s FROM tasks ORDER BY task_id");
  if (!q.ok()) return impl_->err("reading tasks");
  std::vector<TaskInfo> out;
  int rc;
  while ((rc = q.step()) == SQLITE_ROW) {
    TaskInfo t;
    t.id = q.i64(0);
    t.part = q.text(1);
    t.kind = q.text(2);
    const std::string st = q.text(3);
    t.status = st == "done" ? TaskStatus::Done : st == "failed" ? TaskStatus::Failed : TaskStatus::Pending;
    t.attempts = static_cast<int>(q.i64(4));
    t.error = q.text(5);
    t.worker = q.text(6);
    t.wall_s = q.real(7);
    out.push_back(std::move(t));
  }
  if (rc != SQLITE_DONE) return impl_->err("reading tasks");
  return out;
}

Result<std::string> Store::content() {
  std::string d;
  for (const char* q :
       {"SELECT key, value FROM meta WHERE key NOT IN ('created_at') ORDER BY key",
        "SELECT task_id, part, kind, params, task_key, seed, status, error, scalars FROM tasks ORDER BY task_id",
        "SELECT task_id, name, value FROM params ORDER BY task_id, name",
        "SELECT task_id, name, value FROM scalars ORDER BY task_id, name",
        "SELECT task_id, name, length, json FROM arrays ORDER BY task_id, name"}) {
    auto r = query_csv(*impl_, q);
    if (!r) return r.error();
    d += *r;
  }
  return d;
}

}  // namespace frictal::study
