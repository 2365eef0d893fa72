// The nodes this step's particles can reach, as one span along x per row of nodes (a row: the nodes
// with the same indices along the other axes). The step's whole-grid loops (reset, nodal update, MUSL
// re-map) walk only these: where the bodies fill a small part of the grid (a block on a long moving
// base, a slope in a wide domain) most nodes are empty, and they stay zero.
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "cell_index.hpp"
#include "grid.hpp"

namespace seismpm {

template <int Dim>
class ActiveNodes {
 public:
  // From the particles' positions: a particle in cell c (`cells`, clamped to the grid) reaches nodes
  // c + lo .. c + hi along each axis (lo, hi from the shape function).
  void build(const Grid<Dim>& grid, const CellIndex<Dim>& cells, const std::vector<Vec<Dim>>& x, int lo, int hi);

  // The same in three parts, for a caller that walks the particles in parallel already and knows
  // their cells (ParticleSupport::locate): start() before the walk, one Marker per thread noting its
  // particles' cell coordinates, finish() after it. A walk of its own over the particles cost a
  // parallel region and a pass that placed every particle in its cell again.
  void start(const Grid<Dim>& grid, int threads);
  class Marker {
   public:
    Marker() = default;
    Marker(int* min, int* max, const int* cells) : min_(min), max_(max), cells_(cells) {}
    // The extremes of the current row of cells stay in registers until the row changes: particles
    // sorted by cell come row by row, and updating the arrays per particle chained every update
    // through memory.
    void add(const std::array<int, Dim>& c) {
      int row = 0;
      for (int d = Dim - 1; d >= 1; --d) row = row * cells_[d] + c[d];
      if (row != row_) {
        flush();
        row_ = row;
        run_min_ = run_max_ = c[0];
      } else {
        run_min_ = std::min(run_min_, c[0]);
        run_max_ = std::max(run_max_, c[0]);
      }
    }
    void flush() {
      if (row_ < 0) return;
      min_[row_] = std::min(min_[row_], run_min_);
      max_[row_] = std::max(max_[row_], run_max_);
      row_ = -1;
    }

   private:
    int *min_ = nullptr, *max_ = nullptr;
    const int* cells_ = nullptr;
    int row_ = -1, run_min_ = 0, run_max_ = 0;
  };
  // Thread t's marker (t below start's `threads`).
  Marker marker(int t) {
    const std::size_t rows = cell_min_.size() / threads_;
    return Marker(cell_min_.data() + t * rows, cell_max_.data() + t * rows, cells_.data());
  }
  void finish(const Grid<Dim>& grid, int lo, int hi);
  // Every node of the grid (a step with fixes, which may write to nodes no particle reaches).
  void cover(const Grid<Dim>& grid);

  // Calls f(first, end) with each row's contiguous range of node indices [first, end), rows in
  // parallel (static schedule: the ranges are disjoint, so the order does not matter).
  template <class F>
  void for_each_range(F&& f) const {
    const int rows = static_cast<int>(begin_.size());
#pragma omp parallel for schedule(static)
    for (int r = 0; r < rows; ++r)
      if (begin_[r] < end_[r]) f(r * row_length_ + begin_[r], r * row_length_ + end_[r]);
  }

  // Nodes in the spans (for tests and the profile).
  long count() const;

 private:
  int row_length_ = 0;            // nodes along x
  std::vector<int> begin_, end_;  // per row of nodes, the x indices [begin, end) reached
  // Per row of cells and thread, the lowest and highest x cell index holding a particle.
  std::vector<int> cell_min_, cell_max_;
  std::size_t threads_ = 1;
  std::array<int, Dim> cells_{};  // the grid's cells per axis
};

extern template class ActiveNodes<2>;
extern template class ActiveNodes<3>;

}  // namespace seismpm
