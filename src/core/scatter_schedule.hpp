// Race-free, deterministic particle-to-grid scatter. The grid is cut into slabs of whole cells
// along one axis (CellIndex picks it); slab s has colour s mod kColours, and slabs of one colour never
// touch the same node, so each colour runs in parallel, and every node sums its contributions in the same order
// whatever the number of threads: results are bit-identical for any thread count.
#pragma once

#include <omp.h>

#include <vector>

#include "thread_shares.hpp"

namespace seismpm {

class ScatterSchedule {
 public:
  // A uGIMP particle in cell c touches nodes c-1 .. c+2, so slabs of one colour need more than 2 cells
  // between them: (kColours - 1) kSlabCells >= 3. Slabs of one cell layer in 4 colours share the
  // particles among threads in finer pieces than slabs of 4 layers in 2: the sand column (40 layers)
  // made 5 slabs a colour, split 3 to 2 between two threads, and both transfers waited on the larger.
  static constexpr int kSlabCells = 1;
  static constexpr int kColours = 4;
  static_assert((kColours - 1) * kSlabCells >= 3, "slabs of one colour must not reach the same node");

  // Room for each particle's cell index along the slab axis (clamped to the grid), which the caller
  // fills (in its own pass over the particles) before build.
  int* layers(int particle_count) {
    slab_of_.resize(particle_count);
    return slab_of_.data();
  }
  // A stable counting sort by slab: particles of a slab in increasing index. Threads count and place
  // contiguous chunks, which yields that same order whatever their number.
  void build(int particle_count, int cells_along_axis) {
    prepare(particle_count, cells_along_axis, omp_get_max_threads());
#pragma omp parallel
    {
      const int threads = omp_get_num_threads(), t = omp_get_thread_num();
      const int lo = static_cast<int>(static_cast<long>(particle_count) * t / threads);
      const int hi = static_cast<int>(static_cast<long>(particle_count) * (t + 1) / threads);
      count(t, lo, hi);
#pragma omp barrier
      place(t, lo, hi);
    }
  }
  // build in parts, for a caller that fills the layers in a parallel region of its own (locate): prepare
  // before the region; in it, each thread counts its chunk [lo, hi) (contiguous chunks in thread order
  // that cover the particles), then after a barrier places it.
  void prepare(int particle_count, int cells_along_axis, int max_threads) {
    const int slabs = (cells_along_axis + kSlabCells - 1) / kSlabCells;
    order_.resize(particle_count);
    begin_.assign(slabs + 1, 0);
    counts_.assign(static_cast<std::size_t>(max_threads) * slabs, 0);
  }
  // Particles sorted by cell come slab by slab, so each thread keeps the current slab's count (and
  // place) in a register until the slab changes: incremented in memory, every particle's update waited
  // for the last one's store.
  void count(int t, int lo, int hi) {
    const int slabs = this->slabs();
    int* of_slab = counts_.data() + static_cast<std::size_t>(t) * slabs;
    int run = -1, in_run = 0;
    for (int p = lo; p < hi; ++p) {
      const int s = slab_of_[p] /= kSlabCells;
      if (s != run) {
        if (run >= 0) of_slab[run] += in_run;
        run = s, in_run = 0;
      }
      ++in_run;
    }
    if (run >= 0) of_slab[run] += in_run;
  }
  // Inside the parallel region, after every thread's count: one thread sums the counts (an implicit
  // barrier follows), then each places its chunk.
  void place(int t, int lo, int hi) {
    const int slabs = this->slabs();
#pragma omp single
    {
      // Slab-major, thread-minor prefix sums: thread t's particles of slab s follow thread t-1's.
      const int threads = omp_get_num_threads();
      int running = 0;
      for (int sl = 0; sl < slabs; ++sl) {
        begin_[sl] = running;
        for (int th = 0; th < threads; ++th) {
          int& c = counts_[static_cast<std::size_t>(th) * slabs + sl];
          const int n = c;
          c = running;
          running += n;
        }
      }
      begin_[slabs] = running;
    }
    int* next_of_slab = counts_.data() + static_cast<std::size_t>(t) * slabs;
    int run = -1, next = 0;
    for (int p = lo; p < hi; ++p) {
      const int s = slab_of_[p];
      if (s != run) {
        if (run >= 0) next_of_slab[run] = next;
        run = s, next = next_of_slab[s];
      }
      order_[next++] = p;
    }
    if (run >= 0) next_of_slab[run] = next;
  }

  // Calls g(s, first, last) for every slab s with its particles [first, last) in order, slabs in
  // parallel. For work that touches only the particles' own cells (slabs hold disjoint cells, so no
  // colouring is needed), also in several passes over a slab: clear its cells, then sum into them.
  template <class G>
  void for_each_slab_of_own_cells(G&& g) const {
    const int slabs = static_cast<int>(begin_.size()) - 1;
    auto& shares = ThreadShares::of(LoopKind::Slabs);
    const auto start = ThreadShares::Clock::now();
#pragma omp parallel
    {
      const long work =
          for_my_slabs(0, 1, slabs, [&](int s) { g(s, order_.data() + begin_[s], order_.data() + begin_[s + 1]); });
      shares.finished(start, work);
    }
  }
  // Calls f(slab, p) for every particle, slabs in parallel, each slab's particles in order.
  template <class F>
  void for_each_in_own_cell_by_slab(F&& f) const {
    for_each_slab_of_own_cells([&](int s, const int* first, const int* last) {
      for (const int* k = first; k != last; ++k) f(s, *k);
    });
  }
  // The same without the slab.
  template <class F>
  void for_each_in_own_cell(F&& f) const {
    for_each_in_own_cell_by_slab([&](int, int p) { f(p); });
  }
  int slabs() const { return static_cast<int>(begin_.size()) - 1; }

  // Calls f(p) for every particle; in parallel over slabs of one colour at a time.
  template <class F>
  void for_each(F&& f) const {
    const int slabs = static_cast<int>(begin_.size()) - 1;
    by_colour(
        slabs, [&](int s) { return long{begin_[s + 1] - begin_[s]}; },
        [&](int s) {
          for (int k = begin_[s]; k < begin_[s + 1]; ++k) f(order_[k]);
        });
  }

  // Some of the particles, slab by slab in the schedule's order: for scatters that only a few particles
  // take part in (contact's, along the faces where bodies meet), which would otherwise pass every
  // particle through the coloured loop to find them.
  class Selection {
   public:
    // The particles p of each slab, in order, for which keep(p) holds; slabs in parallel.
    template <class Keep>
    void select(const ScatterSchedule& schedule, Keep&& keep) {
      const int slabs = schedule.slabs();
      of_slab_.resize(slabs);
#pragma omp parallel
      schedule.for_my_slabs(0, 1, slabs, [&](int s) {
        auto& list = of_slab_[s];
        list.clear();
        for (int k = schedule.begin_[s]; k < schedule.begin_[s + 1]; ++k)
          if (keep(schedule.order_[k])) list.push_back(schedule.order_[k]);
      });
      // Slabs without particles now may hold the last selection's: no thread visited them.
      for (int s = 0; s < slabs; ++s)
        if (schedule.begin_[s] == schedule.begin_[s + 1]) of_slab_[s].clear();
    }
    // Calls f(p) for every selected particle, as ScatterSchedule::for_each does for all: each slab's
    // in order, slabs of one colour at a time in parallel, so every node sums the same terms in the same
    // order as there.
    template <class F>
    void for_each(F&& f) const {
      const int slabs = static_cast<int>(of_slab_.size());
      by_colour(
          slabs, [&](int s) { return static_cast<long>(of_slab_[s].size()); },
          [&](int s) {
            for (const int p : of_slab_[s]) f(p);
          });
    }

   private:
    std::vector<std::vector<int>> of_slab_;
  };

  // Calls g(s) for every slab s with weight(s) > 0, in one parallel region: slabs of one colour at a
  // time, shared among the threads by weight in the scatter loops' shares (for_my_share; each thread's
  // work on a colour is timed, without its wait at the barrier), with a barrier between colours (the
  // region's end waits for the last). Slabs of one colour never reach the same node.
  template <class Weight, class G>
  static void by_colour(int slabs, Weight&& weight, G&& g) {
    auto& shares = ThreadShares::of(LoopKind::Scatter);
#pragma omp parallel
    for (int colour = 0; colour < kColours; ++colour) {
      const auto start = ThreadShares::Clock::now();  // each colour's work, without the wait after it
      shares.finished(start, for_my_share(shares, colour, kColours, slabs, weight, g));
      if (colour + 1 < kColours) {
#pragma omp barrier
      }
    }
  }

  // Inside a parallel region: calls g(s) for this thread's share of the slabs first, first + step, ...
  // below `slabs`, shared by weight(s) (the work of slab s) as for_my_slabs shares them by particles;
  // returns the weight of the slabs it called.
  template <class Weight, class G>
  static long for_my_share(const ThreadShares& shares, int first, int step, int slabs, Weight&& weight, G&& g) {
    const int threads = omp_get_num_threads(), t = omp_get_thread_num();
    long total = 0;
    for (int s = first; s < slabs; s += step) total += weight(s);
    const long lo = shares.first(t, threads, total), hi = shares.first(t + 1, threads, total);
    // A slab is the thread's whose share holds the slab's middle: by its start, a share a little over
    // an even split took a whole slab from the next thread (a tenth of a colour's work on the sand column).
    long start = 0, mine = 0;  // weight of this colour's slabs before slab s; of those called
    for (int s = first; s < slabs; s += step) {
      const long size = weight(s), middle = 2 * start + size;  // twice the slab's middle
      if (middle >= 2 * hi) break;
      if (size > 0 && middle >= 2 * lo) g(s), mine += size;
      start += size;
    }
    return mine;
  }

 private:
  // Inside a parallel region: calls g(s) for this thread's share of the slabs first, first + step, ...
  // below `slabs`, shared by their particles (the slab loops' shares): contiguous runs of slabs, so a
  // thread meets about the particles that the loops over particles give it (its cache may hold them;
  // each kind of loop has its own shares), and the work is even where slabs differ in size. Which thread runs a slab
  // changes no node's sum: a colour's slabs touch disjoint nodes. Returns the particles of the slabs it called.
  template <class G>
  long for_my_slabs(int first, int step, int slabs, G&& g) const {
    return for_my_share(
        ThreadShares::of(LoopKind::Slabs), first, step, slabs, [&](int s) { return long{begin_[s + 1] - begin_[s]}; },
        g);
  }

  std::vector<int> slab_of_;
  std::vector<int> begin_;
  std::vector<int> order_;
  std::vector<int> counts_;  // per thread and slab
};

}  // namespace seismpm
