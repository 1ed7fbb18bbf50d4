// Private: who a run is and whether a run that left a claim still lives, for the claims of the
// study store (store.cpp: tasks) and of the result cache (cache.cpp: content addresses). A claim
// names its host, pid and the pid's start time; on the same host a dead process is seen at once,
// on another host its claim lapses when its heartbeat is older than the lease.
#pragma once

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <fmt/core.h>

namespace frictal::study::liveness {

/// Wall-clock time (unit: s since the epoch), for heartbeats shared between processes.
inline double now_s() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

inline std::string host_name() {
  char buf[256] = {0};
  if (::gethostname(buf, sizeof buf - 1) != 0) return "localhost";
  return buf;
}

/// Start time of a process (clock ticks since boot, /proc/PID/stat field 22), 0 if unknown: with
/// the pid it tells a live process from a later one that reuses the pid. `state` gets field 3
/// (R, S, D, Z for a zombie, ...), '?' if unknown.
inline std::int64_t process_start(long pid, char* state = nullptr) {
  if (state) *state = '?';
  std::ifstream f("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!f || !std::getline(f, line)) return 0;
  const auto close = line.rfind(')');
  if (close == std::string::npos || close + 2 >= line.size()) return 0;
  std::istringstream in(line.substr(close + 2));
  std::string field;
  for (int i = 3; i <= 22 && in >> field; ++i) {
    if (i == 3 && state && !field.empty()) *state = field[0];
    if (i == 22) return std::atoll(field.c_str());
  }
  return 0;
}

/// Whether the process (pid, start) of this host is alive (a zombie, killed but not yet reaped
/// by its parent, is not).
inline bool process_alive(long pid, std::int64_t start) {
  if (pid <= 0) return false;
  if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) return false;
  char state = '?';
  const std::int64_t now = process_start(pid, &state);
  if (state == 'Z' || state == 'X') return false;
  if (start != 0 && now != 0 && now != start) return false;  // the pid was reused
  return true;
}

/// This process as the holder of claims: one owner name per opened store or cache.
struct Identity {
  std::string owner, host;
  long pid = 0;
  std::int64_t pid_start = 0;
  static Identity make() {
    static std::atomic<int> counter{0};
    Identity id;
    id.host = host_name();
    id.pid = static_cast<long>(::getpid());
    id.pid_start = process_start(id.pid);
    id.owner = fmt::format("{}:{}:{}", id.host, id.pid, counter++);
    return id;
  }
  /// Binds owner, host, pid, pid_start and a fresh heartbeat to the parameters first..first+4
  /// of a claims INSERT (the column order of both claims tables).
  template <class Statement>
  void bind_claim(Statement& w, int first) const {
    w.bind(first, owner);
    w.bind(first + 1, host);
    w.bind(first + 2, static_cast<std::int64_t>(pid));
    w.bind(first + 3, pid_start);
    w.bind(first + 4, now_s());
  }
  /// Whether a claim by `owner` (host, pid, pid_start, heartbeat: s since the epoch) still holds
  /// against this one: not ours, its process alive (same host) and its heartbeat within lease_s.
  bool held_by_other(const std::string& other, const std::string& other_host, long other_pid, std::int64_t other_start,
                     double heartbeat, double lease_s) const {
    if (other == owner) return false;
    const bool gone = other_host == host && !process_alive(other_pid, other_start);
    const bool expired = now_s() - heartbeat > lease_s;
    return !gone && !expired;
  }
};

}  // namespace frictal::study::liveness
