// Race-free, deterministic particle-to-grid scatter. The grid is cut into slabs of whole cells
// along its last axis; slabs of one colour (even or odd) never touch the same node, so each colour
// runs in parallel, and every node sums its contributions in the same order whatever the number
// of threads: results are bit-identical for any thread count.
#pragma once

#include <vector>

namespace seismpm {

class ScatterSchedule {
 public:
  // 4 cells: a uGIMP particle in cell c touches nodes c-1 .. c+2, so slabs 2 apart need >= 3 cells.
  static constexpr int kSlabCells = 4;

  // `cell_of(p)` gives the particle's cell index along the last axis, already clamped to the grid.
  template <class CellOf>
  void build(int particle_count, int cells_last_axis, CellOf&& cell_of) {
    const int slabs = (cells_last_axis + kSlabCells - 1) / kSlabCells;
    slab_of_.resize(particle_count);
    begin_.assign(slabs + 1, 0);
    for (int p = 0; p < particle_count; ++p) {
      const int s = cell_of(p) / kSlabCells;
      slab_of_[p] = s;
      ++begin_[s + 1];
    }
    for (int s = 0; s < slabs; ++s) begin_[s + 1] += begin_[s];
    order_.resize(particle_count);
    std::vector<int> next(begin_.begin(), begin_.end() - 1);
    for (int p = 0; p < particle_count; ++p) order_[next[slab_of_[p]]++] = p;
  }

  // Calls f(p) for every particle; slabs in parallel. For work that touches only the particle's own
  // cell: slabs hold disjoint cells, so no colouring is needed.
  template <class F>
  void for_each_in_own_cell(F&& f) const {
    const int slabs = static_cast<int>(begin_.size()) - 1;
#pragma omp parallel for schedule(dynamic, 1)
    for (int s = 0; s < slabs; ++s)
      for (int k = begin_[s]; k < begin_[s + 1]; ++k) f(order_[k]);
  }

  // Calls f(p) for every particle; in parallel over slabs of one colour at a time.
  template <class F>
  void for_each(F&& f) const {
    const int slabs = static_cast<int>(begin_.size()) - 1;
    for (int colour = 0; colour < 2; ++colour) {
#pragma omp parallel for schedule(dynamic, 1)
      for (int s = colour; s < slabs; s += 2)
        for (int k = begin_[s]; k < begin_[s + 1]; ++k) f(order_[k]);
    }
  }

 private:
  std::vector<int> slab_of_;
  std::vector<int> begin_;
  std::vector<int> order_;
};

}  // namespace seismpm
