// Private: a prepared SQLite statement with RAII and the UTC time stamp of rows, shared by the
// study store (store.cpp) and the result cache (cache.cpp).
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <string>
#include <thread>

#include <sqlite3.h>

namespace frictal::study {

/// sqlite3_exec, retried while the database is busy or locked, for at most timeout_ms (ms).
/// Some statements fail with SQLITE_BUSY at once, without calling the busy handler: switching a
/// new file to WAL (`PRAGMA journal_mode=WAL`) while another process opens or converts it, or a
/// WAL recovery after a killed writer. Several runs that open one store at the same moment would
/// otherwise stop with "database is locked". Returns the last result code; *msg as sqlite3_exec.
inline int exec_waiting(sqlite3* db, const char* sql, char** msg, int timeout_ms = 30000) {
  using clock = std::chrono::steady_clock;
  const auto deadline = clock::now() + std::chrono::milliseconds(timeout_ms);
  auto pause = std::chrono::milliseconds(1);
  for (;;) {
    const int rc = sqlite3_exec(db, sql, nullptr, nullptr, msg);
    const int primary = rc & 0xff;
    if ((primary != SQLITE_BUSY && primary != SQLITE_LOCKED) || clock::now() + pause > deadline) return rc;
    if (msg && *msg) {
      sqlite3_free(*msg);
      *msg = nullptr;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::milliseconds(50));
  }
}

/// A prepared statement with RAII.
class Stmt {
 public:
  Stmt(sqlite3* db, const char* sql) { rc_ = sqlite3_prepare_v2(db, sql, -1, &s_, nullptr); }
  ~Stmt() { sqlite3_finalize(s_); }
  Stmt(const Stmt&) = delete;
  Stmt& operator=(const Stmt&) = delete;
  bool ok() const { return rc_ == SQLITE_OK; }
  sqlite3_stmt* get() { return s_; }
  void bind(int i, const std::string& v) {
    sqlite3_bind_text(s_, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
  }
  void bind(int i, std::int64_t v) { sqlite3_bind_int64(s_, i, v); }
  void bind(int i, double v) {
    if (std::isfinite(v))
      sqlite3_bind_double(s_, i, v);
    else
      sqlite3_bind_null(s_, i);
  }
  void bind_null(int i) { sqlite3_bind_null(s_, i); }
  void bind_blob(int i, const std::string& bytes) {
    sqlite3_bind_blob(s_, i, bytes.data(), static_cast<int>(bytes.size()), SQLITE_TRANSIENT);
  }
  int step() { return sqlite3_step(s_); }
  void reset() {
    sqlite3_reset(s_);
    sqlite3_clear_bindings(s_);
  }
  std::string text(int c) {
    auto* p = sqlite3_column_text(s_, c);
    return p ? std::string(reinterpret_cast<const char*>(p), static_cast<std::size_t>(sqlite3_column_bytes(s_, c)))
             : std::string{};
  }
  std::string blob(int c) {
    const void* p = sqlite3_column_blob(s_, c);
    return p ? std::string(static_cast<const char*>(p), static_cast<std::size_t>(sqlite3_column_bytes(s_, c)))
             : std::string{};
  }
  std::int64_t i64(int c) { return sqlite3_column_int64(s_, c); }
  double real(int c) { return sqlite3_column_type(s_, c) == SQLITE_NULL ? std::nan("") : sqlite3_column_double(s_, c); }

 private:
  sqlite3_stmt* s_ = nullptr;
  int rc_;
};

/// The current time as ISO 8601 UTC ("2026-11-23T18:58:16Z"), as both files store it.
inline std::string now_utc() {
  const auto t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace frictal::study
