// The nodes this step's particles can reach, as one span along x per row of nodes (a row: the nodes
// with the same indices along the other axes). The step's whole-grid loops (reset, nodal update, MUSL
// re-map) walk only these: where the bodies fill a small part of the grid (a block on a long moving
// base, a slope in a wide domain) most nodes are empty, and they stay zero.
#pragma once

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
};

extern template class ActiveNodes<2>;
extern template class ActiveNodes<3>;

}  // namespace seismpm
