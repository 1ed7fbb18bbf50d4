// The persistent worker team (team.hpp): spin briefly, then block on a futex.
#include "util/team.hpp"

#include <chrono>
#include <system_error>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace frictal::util {

namespace {

// How long a waiting thread spins before it blocks (unit: ns). A DEM step is ~5 us and an
// occasional serial step (a full pass over the neighbour list) ~20-50 us, so a team member
// waiting for the next split step usually finds it while spinning (waking a blocked thread costs
// tens of us on a virtual machine); a longer pause (output, the end of the run, a descheduled
// caller on a loaded machine) puts it to sleep.
constexpr std::int64_t kSpinNs = 100000;

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

// Spins while `busy()` for up to kSpinNs; returns false if still busy then.
template <class Busy>
bool spin_while(Busy&& busy) {
  using Clock = std::chrono::steady_clock;
  Clock::time_point until{};
  for (unsigned i = 0;; ++i) {
    if (!busy()) return true;
    cpu_relax();
    if ((i & 63u) == 63u) {  // the clock every 64 pauses
      const auto now = Clock::now();
      if (until == Clock::time_point{})
        until = now + std::chrono::nanoseconds(kSpinNs);
      else if (now >= until)
        return false;
    }
  }
}

}  // namespace

Team::Team(unsigned members) {
  workers_.reserve(members > 1 ? members - 1 : 0);
  try {
    for (unsigned w = 1; w < members; ++w) workers_.emplace_back([this, w] { work(w); });
  } catch (...) {
    stop_.store(true);
    generation_.fetch_add(1);
    generation_.notify_all();
    for (auto& t : workers_) t.join();
    throw;
  }
}

Team::~Team() {
  stop_.store(true, std::memory_order_seq_cst);
  generation_.fetch_add(1, std::memory_order_seq_cst);
  generation_.notify_all();
  for (auto& t : workers_) t.join();
}

std::unique_ptr<Team> Team::make(unsigned members) noexcept {
  try {
    return std::make_unique<Team>(members);
  } catch (...) {
    return nullptr;
  }
}

void Team::run(unsigned n, void (*job)(void*, unsigned), void* context) {
  if (n > members()) n = members();
  if (n <= 1) {
    job(context, 0);
    return;
  }
  n_ = n;
  job_ = job;
  context_ = context;
  // Every worker acknowledges every section (those beyond n do no work), so that none can still
  // be reading this section's n_, job_ and context_ when the next one writes them.
  pending_.store(members() - 1, std::memory_order_relaxed);
  generation_.fetch_add(1, std::memory_order_seq_cst);  // publishes the section
  if (sleepers_.load(std::memory_order_seq_cst) > 0) generation_.notify_all();
  job(context, 0);
  if (!spin_while([&] { return pending_.load(std::memory_order_acquire) != 0; })) {
    caller_blocked_.store(true, std::memory_order_seq_cst);
    for (std::uint32_t p; (p = pending_.load(std::memory_order_seq_cst)) != 0;) pending_.wait(p);
    caller_blocked_.store(false, std::memory_order_relaxed);
  }
}

void Team::work(unsigned member) {
  std::uint32_t seen = 0;
  for (;;) {
    if (!spin_while([&] { return generation_.load(std::memory_order_acquire) == seen; })) {
      // Block. The caller bumps generation_ then reads sleepers_; we count ourselves then read
      // generation_ (both seq_cst): one of the two sees the other.
      sleepers_.fetch_add(1, std::memory_order_seq_cst);
      while (generation_.load(std::memory_order_seq_cst) == seen) generation_.wait(seen);
      sleepers_.fetch_sub(1, std::memory_order_seq_cst);
    }
    seen = generation_.load(std::memory_order_acquire);
    if (stop_.load(std::memory_order_acquire)) return;
    if (member < n_) job_(context_, member);
    if (pending_.fetch_sub(1, std::memory_order_seq_cst) == 1 && caller_blocked_.load(std::memory_order_seq_cst))
      pending_.notify_one();
  }
}

}  // namespace frictal::util
