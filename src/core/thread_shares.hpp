// How the step's parallel loops share their work among threads. A virtual machine's cores do not always
// run at one speed: on the 2-core VM the same loop ran 30-40 % faster on one core than on the other for
// tens of milliseconds at a time (either core, in turns), and with equal shares the faster thread waited
// at the end of every loop for the slower one. Each thread therefore takes a contiguous share in
// proportion to the speed it showed in the last steps: the loops that time themselves note how much
// work each thread did and when it finished (most from the region's start, so that a late wake-up counts
// as slowness), and update() moves the shares toward the measured speeds between steps. Each kind of loop
// has shares of its own: a thread that was faster at arithmetic was not always faster at the scatters.
//
// Which thread computes which particle or slab never changes a result: every loop that takes its share
// here computes each item by itself, reduces by min or max, or sums in an order fixed by the items (the
// scatter slabs), so results stay bit-identical whatever the shares and the number of threads.
#pragma once

#include <omp.h>

#include <array>
#include <chrono>
#include <vector>

namespace seismpm {

enum class LoopKind {
  Locate,     // stencils and cells (blocks of particles)
  Scatter,    // the coloured slab loops (particles, or cells for contact's marking)
  Slabs,      // slab loops over the particles' own cells
  Particles,  // plain loops over the particles
  Material,   // a material's stress update
};
constexpr int kLoopKinds = 5;

class ThreadShares {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr int kMaxThreads = 64;  // beyond this, equal shares

  // Thread t's range [first(t), first(t + 1)) of n items in a team of `team` threads (t <= team):
  // contiguous ranges in thread order that cover [0, n). Equal shares for a team other than the
  // prepared one.
  long first(int t, int team, long n) const {
    if (team != threads_ || team > kMaxThreads) return static_cast<long>(static_cast<long long>(n) * t / team);
    return static_cast<long>((static_cast<long long>(n) * cumulative_[t]) >> kBits);
  }
  struct Range {
    long begin, end;
  };
  // The calling thread's range of n items, inside a parallel region.
  Range mine(long n) const {
    const int t = omp_get_thread_num(), team = omp_get_num_threads();
    return {first(t, team, n), first(t + 1, team, n)};
  }

  // The calling thread has done `work` items (in the kind's unit) of a timed loop whose region, or part
  // of a region, started at `start`.
  void finished(Clock::time_point start, long work) {
    record(std::chrono::duration<double>(Clock::now() - start).count(), work);
  }
  // The calling thread did `work` items in `seconds` (ignored in a team other than the prepared one).
  void record(double seconds, long work) {
    const int t = omp_get_thread_num();
    if (omp_get_num_threads() != threads_ || t >= kMaxThreads) return;
    busy_[t].seconds += seconds;
    busy_[t].work += static_cast<double>(work);
  }

  // Equal shares for a team of `threads` when the team changes (serial).
  void prepare(int threads);
  // Between steps (serial): moves the shares toward the speeds measured since the last call.
  void update();
  double share(int t) const { return share_[t]; }
  // Shares as given (normalised, and for the team the shares were prepared for): for tests that make
  // them uneven on purpose.
  void set(const std::vector<double>& shares);

  // The process's shares for one kind of loop (the cores' speeds are the machine's, whatever the
  // model), and prepare and update for every kind.
  static ThreadShares& of(LoopKind kind);
  static void prepare_all(int threads);
  static void update_all();

 private:
  static constexpr int kBits = 20;  // fixed point, so every thread computes the same bounds (n 2^20 < 2^63)
  struct alignas(64) Busy {         // a cache line per thread: each writes its own
    double seconds = 0.0, work = 0.0;
  };
  static constexpr int kWindow = 9;  // the timed steps whose speeds count (kAgreeing of them must agree)
  int threads_ = 0;
  int measured_ = 0;  // timed steps (up to kWindow), then kWindow + the next slot
  std::array<std::array<double, kWindow>, kMaxThreads> proportion_{};  // per thread, of each measured step
  std::array<double, kMaxThreads> share_{};
  std::array<long long, kMaxThreads + 1> cumulative_{};  // in units of 2^-kBits; the team's last is 2^kBits
  std::array<Busy, kMaxThreads> busy_{};
  void set_cumulative();
};

}  // namespace seismpm
