// Where each particle acts this step: its stencil (nodes and shape-function values at the
// start-of-step position), its cell, and the coloured scatter schedule over cell slabs. Computed once
// per step and read by every transfer of the step (and by contact).
#pragma once

#include <algorithm>
#include <array>
#include <type_traits>
#include <vector>

#include "cell_index.hpp"
#include "particles.hpp"
#include "scatter_schedule.hpp"
#include "shape_function.hpp"
#include "stencil.hpp"

namespace seismpm {

template <int Dim>
class ParticleSupport {
 public:
  explicit ParticleSupport(const Grid<Dim>& grid) : cells(grid) {}

  // Evaluates everything for the particles' current positions. Returns the index of the first
  // particle outside the grid, or the particle count when all are inside.
  template <class Shape>
  int locate(const Grid<Dim>& grid, const Particles<Dim>& particles) {
    auto& st = stencils<Shape>();
    const int n = static_cast<int>(particles.size());
    st.resize(n);
    cell_of.resize(n);
    int* layer = schedule.layers(n);  // the cell index along the slab axis, for the schedule
    const int axis = cells.slab_axis();
    int outside = n;
    const StencilFrame<Dim> frame(grid);
    const auto place = [&](int p, const std::array<int, Dim>& cell) {
      cell_of[p] = cells.of_coords(cell);
      layer[p] = cell[axis];
    };
    const int blocks = (n + kStencilBlock - 1) / kStencilBlock;
#pragma omp parallel for schedule(static) reduction(min : outside)
    for (int b = 0; b < blocks; ++b) {
      const int first = b * kStencilBlock, count = std::min(kStencilBlock, n - first);
      std::array<int, Dim> cell[kStencilBlock];
      if (make_stencils<Shape>(frame, &particles.x[first], &particles.half_width[first], count, &st[first], cell)) {
        for (int j = 0; j < count; ++j) place(first + j, cell[j]);
        continue;
      }
      for (int p = first; p < first + count; ++p) {  // a particle outside, or a clipped stencil
        std::array<int, Dim> one;
        if (make_stencil<Shape>(grid, particles.x[p], particles.half_width[p], st[p], one.data()))
          place(p, one);
        else
          outside = std::min(outside, p);
      }
    }
    if (outside < n) return outside;
    schedule.build(n, grid.cells(axis));
    return n;
  }

  template <class Shape>
  std::vector<Stencil<Dim, Shape::K>>& stencils() {
    return of_shape<Shape>(*this);
  }
  template <class Shape>
  const std::vector<Stencil<Dim, Shape::K>>& stencils() const {
    return of_shape<Shape>(*this);
  }

  CellIndex<Dim> cells;
  std::vector<int> cell_of;  // cell of each particle at the start of the step
  ScatterSchedule schedule;

 private:
  // The stencils of one shape, for a const or a mutable support alike.
  template <class Shape, class Self>
  static auto& of_shape(Self& s) {
    if constexpr (std::is_same_v<Shape, LinearShape>)
      return s.linear_;
    else
      return s.gimp_;
  }

  std::vector<Stencil<Dim, LinearShape::K>> linear_;
  std::vector<Stencil<Dim, GimpShape::K>> gimp_;
};

}  // namespace seismpm
