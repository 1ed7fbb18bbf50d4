// Running a study over MPI ranks (compiled only with FRICTAL_MPI): the MPI transport of the
// coordinator (coordinator.hpp), whose site r is rank r. Rank 0 owns the store and hands out task
// ids one at a time as ranks ask for work (dynamic load balancing); it also runs `threads` local
// compute threads. Only rank 0's main thread calls MPI (MPI_THREAD_FUNNELED).
//
// Failures: the coordinator's retry policy (a transient failure on a rank is retried on a rank it
// has not failed on, up to kMaxAttempts attempts). A rank that dies outright makes mpirun abort
// the job (standard MPI has no recovery from process loss); the store keeps every finished task
// and rerunning the command resumes the rest.
#ifdef FRICTAL_MPI
#include <mpi.h>

#include <chrono>
#include <cstdlib>
#include <map>
#include <set>
#include <thread>

#include <fmt/core.h>

#include "frictal/study.hpp"
#include "study/coordinator.hpp"
#include "util/parallel.hpp"

namespace frictal::study {
namespace {
constexpr int kTagReady = 1, kTagResult = 2, kTagTask = 3, kTagStop = 4;

std::string recv_bytes(int source, int tag, MPI_Status* st) {
  MPI_Status probe;
  MPI_Probe(source, tag, MPI_COMM_WORLD, &probe);
  int n = 0;
  MPI_Get_count(&probe, MPI_BYTE, &n);
  std::string buf(static_cast<std::size_t>(n), '\0');
  MPI_Recv(buf.data(), n, MPI_BYTE, probe.MPI_SOURCE, probe.MPI_TAG, MPI_COMM_WORLD, st);
  return buf;
}
}  // namespace

bool mpi_available() { return true; }

bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(v)) return true;
  return false;
}

Status mpi_init(int* rank, int* size) {
  int provided = 0;
  if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    return make_error("MPI_Init_thread failed");
  if (provided < MPI_THREAD_FUNNELED) return make_error("the MPI library does not provide MPI_THREAD_FUNNELED");
  MPI_Comm_rank(MPI_COMM_WORLD, rank);
  MPI_Comm_size(MPI_COMM_WORLD, size);
  return Ok{};
}

void mpi_finalize() {
  int fin = 0;
  MPI_Finalized(&fin);
  if (!fin) MPI_Finalize();
}

bool mpi_broadcast(bool value) {
  int v = value ? 1 : 0;
  MPI_Bcast(&v, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return v != 0;
}

Result<RunSummary> run_mpi(const Study& study, Store* store, const TaskRegistry& registry, const RunOptions& options) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const auto start = std::chrono::steady_clock::now();
  RunSummary sum;

  if (rank != 0) {  // worker: ask, compute, answer, until told to stop
    const std::string me = fmt::format("rank {}", rank);
    MPI_Send(nullptr, 0, MPI_BYTE, 0, kTagReady, MPI_COMM_WORLD);
    for (;;) {
      MPI_Status st;
      MPI_Probe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &st);
      if (st.MPI_TAG == kTagStop) {
        MPI_Recv(nullptr, 0, MPI_BYTE, 0, kTagStop, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        break;
      }
      long long id = -1;
      MPI_Recv(&id, 1, MPI_LONG_LONG, 0, kTagTask, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      TaskRecord r;
      if (id < 0 || id >= static_cast<long long>(study.tasks.size())) {
        r.id = id;
        r.status = TaskStatus::Failed;
        r.code = ErrorCode::Internal;  // another rank may have the right file: retried there
        r.error = fmt::format("{}: task id {} is not in this rank's study (different study file?)", me, id);
      } else {
        r = execute(study.tasks[static_cast<std::size_t>(id)], registry, me);
      }
      const std::string bytes = serialize(r);
      MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, 0, kTagResult, MPI_COMM_WORLD);
      ++sum.ran;
    }
    sum.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return sum;
  }

  // Rank 0. On a planning error, still release the workers before returning.
  auto release_all = [&](std::set<int>& stopped) {
    for (int r = 1; r < size; ++r) {
      if (stopped.count(r)) continue;
      // Each worker sends READY or RESULT before waiting; answer its last message with STOP.
      MPI_Status st;
      std::string b = recv_bytes(r, MPI_ANY_TAG, &st);
      (void)b;
      MPI_Send(nullptr, 0, MPI_BYTE, r, kTagStop, MPI_COMM_WORLD);
      stopped.insert(r);
    }
  };
  std::set<int> stopped;
  if (!store) {
    release_all(stopped);
    return make_error("run_mpi: rank 0 needs the store", ErrorCode::Internal);
  }
  auto todo = plan(study, *store, registry, options, &sum.skipped_unavailable);
  if (!todo) {
    release_all(stopped);
    return todo.error();
  }
  // Site r of the coordinator is rank r; rank 0 computes with T local threads while this (main)
  // thread owns the store and serves the other ranks (MPI_THREAD_FUNNELED: only it calls MPI).
  Coordinator co(study, *store, registry, options, std::move(*todo), size);
  if (auto s = co.start(); !s) {
    release_all(stopped);
    return s.error();
  }
  const unsigned T = options.threads ? options.threads : 1;
  sum.threads = T;
  std::set<int> idle;                    // ranks waiting for a task
  std::map<int, std::int64_t> inflight;  // rank -> the task it computes
  util::run_workers(
      T,
      [&](unsigned w) {
        const std::string me = fmt::format("rank 0 thread {}", w);
        for (std::int64_t id; (id = co.claim(0, true)) >= 0;)
          co.finish(execute(study.tasks[static_cast<std::size_t>(id)], registry, me), 0);
      },
      [&] {
        for (;;) {
          bool busy = co.record_finished(false) > 0;
          int flag = 0;
          MPI_Status st;
          MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st);
          if (flag) {
            busy = true;
            const int src = st.MPI_SOURCE;
            std::string bytes = recv_bytes(src, st.MPI_TAG, &st);
            if (st.MPI_TAG == kTagResult) {
              auto r = deserialize(bytes);
              if (r) r->id = inflight[src];  // the id this rank was given
              if (!r) {                      // cannot happen between ranks of one build; never lose the claim
                TaskRecord lost;
                lost.id = inflight[src];
                lost.worker = fmt::format("rank {}", src);
                lost.status = TaskStatus::Failed;
                lost.code = ErrorCode::Internal;
                lost.error = fmt::format("rank {}: {}", src, r.error().message);
                r = std::move(lost);
              }
              inflight.erase(src);
              co.finish(std::move(*r), src);
            }
            idle.insert(src);
          }
          // Dispatch to idle ranks (a rank stays idle if every queued task failed on it).
          for (auto it = idle.begin(); it != idle.end();) {
            const std::int64_t id = co.claim(*it, false);
            if (id < 0) {
              ++it;
              continue;
            }
            long long v = id;
            MPI_Send(&v, 1, MPI_LONG_LONG, *it, kTagTask, MPI_COMM_WORLD);
            inflight[*it] = id;
            it = idle.erase(it);
            busy = true;
          }
          if (co.over()) break;
          if (!busy) std::this_thread::sleep_for(std::chrono::microseconds(500));
        }
      });
  co.record_finished(false);
  // Stop every worker: idle ones now, the others after their next message.
  for (int w : idle) {
    MPI_Send(nullptr, 0, MPI_BYTE, w, kTagStop, MPI_COMM_WORLD);
    stopped.insert(w);
  }
  release_all(stopped);
  return co.summary(sum);
}

}  // namespace frictal::study
#endif  // FRICTAL_MPI
