// Private: the result cache shared by the study stores of one folder (RunOptions::cache,
// docs/studies.md "Result cache"). One SQLite file (WAL, like a store) with one row per content
// address (content_address: kind, kind version, parameters, and the seed for a kind that uses
// it): the exact output (the lossless binary record of serialize()) and what computed it. Several
// processes may share the file; claims on addresses (as the store's on tasks) keep two runs of
// different studies from computing one address at the same time. Callers serialise their calls
// on one object (the coordinator's cache mutex).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "frictal/study.hpp"

namespace frictal::study {

class ResultCache {
 public:
  /// Opens or creates the cache file.
  static Result<std::unique_ptr<ResultCache>> open(const std::string& path);
  ~ResultCache();
  ResultCache(const ResultCache&) = delete;
  ResultCache& operator=(const ResultCache&) = delete;

  /// The output recorded under `address`, if any. The entry's kind, kind version and canonical
  /// parameters must equal the task's (else it is not a hit).
  Result<std::optional<TaskOutput>> find(const std::string& address, const Task& task);
  /// Adds a done task's output (kept if the address is there already) and releases this
  /// object's claim on the address.
  Status put(const std::string& address, const Task& task, bool uses_seed, const TaskRecord& record,
             const std::string& study);
  enum class Claim {
    Claimed,  ///< this object computes it now (until put() or release())
    Busy,     ///< another live run computes it: look again later
    Stored,   ///< a result is stored under the address already (read it with find())
  };
  /// Claims `address` for computing. A claim of a run that died (same host: its process is gone)
  /// or whose heartbeat is older than `lease_s` (unit: s) is taken over.
  Result<Claim> claim(const std::string& address, double lease_s);
  /// Gives up this object's claim on `address` (e.g. after a failed attempt).
  Status release(const std::string& address);
  /// Refreshes the heartbeat of every claim of this object; release_claims() drops them all.
  Status heartbeat();
  Status release_claims();
  /// Recorded compute times, whatever the kind version (for the scheduler's estimates).
  struct Timing {
    std::string kind, params;  ///< params: canonical text
    double wall_s = 0;
  };
  Result<std::vector<Timing>> timings();
  const std::string& path() const;

  struct Impl;

 private:
  ResultCache() = default;
  std::unique_ptr<Impl> impl_;
};

/// Content address of a task of `registry` (its kind's uses_seed decides whether the seed enters).
std::string content_address(const Task& task, const TaskRegistry& registry);

}  // namespace frictal::study
