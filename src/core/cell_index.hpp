// Linear cell indices of a grid with the slab axis varying slowest, so that each scatter slab (whole
// layers of cells across that axis) is a contiguous range of cells and, after sorting, of particles.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "grid.hpp"

namespace seismpm {

template <int Dim>
class CellIndex {
 public:
  // The slab axis is the grid's last (its nodes' slowest in memory) when it has kSlabAxisCells cells,
  // else the one with the most cells (the most slabs to share among threads). Along the last axis,
  // particles sorted by cell walk the node arrays forward, and each slab's nodes are whole rows that
  // no other slab's share a cache line with: 9-16 % faster on one thread than slabs across x for a
  // block 100 cells high on a grid 700 wide, or a box 84 cells high. Slabs across x also share cache
  // lines between threads at their edges in every row (8 slabs along y still beat them on two
  // threads: the sand column, 200 x 48 cells, 7.8 -> 8.5-9.0 M particle-steps/s). The rule does not
  // depend on the number of threads, so neither do the results.
  static constexpr int kSlabAxisCells = 32;
  explicit CellIndex(const Grid<Dim>& grid) : origin_(grid.origin()), inv_h_(1.0 / grid.cell()) {
    for (int d = 0; d < Dim; ++d) cells_[d] = grid.cells(d);
    if (cells_[Dim - 1] < kSlabAxisCells)
      for (int d = Dim - 1; d >= 0; --d)
        if (cells_[d] > cells_[slab_axis_]) slab_axis_ = d;
  }
  int slab_axis() const { return slab_axis_; }
  // Index of the cell holding x, clamped to the grid.
  int of(const Vec<Dim>& x) const { return of_coords(coords_of(x)); }
  // Coordinates of the cell holding x, clamped to the grid.
  std::array<int, Dim> coords_of(const Vec<Dim>& x) const {
    std::array<int, Dim> c;
    for (int d = 0; d < Dim; ++d)
      c[d] = std::clamp(static_cast<int>(std::floor((x[d] - origin_[d]) * inv_h_)), 0, cells_[d] - 1);
    return c;
  }
  int of_coords(const std::array<int, Dim>& c) const {
    int index = c[slab_axis_];
    for (int d = Dim - 1; d >= 0; --d)
      if (d != slab_axis_) index = index * cells_[d] + c[d];
    return index;
  }
  // Inverse of of_coords.
  std::array<int, Dim> coords(int cell) const {
    std::array<int, Dim> x{};
    for (int d = 0; d < Dim; ++d) {
      if (d == slab_axis_) continue;
      x[d] = cell % cells_[d];
      cell /= cells_[d];
    }
    x[slab_axis_] = cell;
    return x;
  }

 private:
  Vec<Dim> origin_;
  double inv_h_;  // 1 / cell size: a product, not a division, per particle and step
  std::array<int, Dim> cells_{};
  int slab_axis_ = Dim - 1;
};

}  // namespace seismpm
