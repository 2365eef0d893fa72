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
  // The slab axis is the one with the most cells: the most slabs to share among threads.
  explicit CellIndex(const Grid<Dim>& grid) : origin_(grid.origin()), h_(grid.cell()) {
    for (int d = 0; d < Dim; ++d) cells_[d] = grid.cells(d);
    for (int d = Dim - 1; d >= 0; --d)
      if (cells_[d] > cells_[slab_axis_]) slab_axis_ = d;
  }
  int slab_axis() const { return slab_axis_; }
  // Cells in one layer across the slab axis.
  int per_layer() const {
    int n = 1;
    for (int d = 0; d < Dim; ++d)
      if (d != slab_axis_) n *= cells_[d];
    return n;
  }
  // Index of the cell holding x, clamped to the grid.
  int of(const Vec<Dim>& x) const {
    std::array<int, Dim> c;
    for (int d = 0; d < Dim; ++d)
      c[d] = std::clamp(static_cast<int>(std::floor((x[d] - origin_[d]) / h_)), 0, cells_[d] - 1);
    return of_coords(c);
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
  double h_;
  std::array<int, Dim> cells_{};
  int slab_axis_ = Dim - 1;
};

}  // namespace seismpm
