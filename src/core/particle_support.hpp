// Where each particle acts this step: its stencil (nodes and shape-function values at the
// start-of-step position), its cell, and the coloured scatter schedule over cell slabs. Computed once
// per step and read by every transfer of the step (and by contact).
#pragma once

#include <algorithm>
#include <array>
#include <type_traits>
#include <vector>

#include <omp.h>

#include "active_nodes.hpp"
#include "cell_index.hpp"
#include "particles.hpp"
#include "scatter_schedule.hpp"
#include "shape_function.hpp"
#include "stencil.hpp"
#include "thread_shares.hpp"

namespace seismpm {

template <int Dim>
class ParticleSupport {
 public:
  explicit ParticleSupport(const Grid<Dim>& grid) : cells(grid) {}

  // Evaluates everything for the particles' current positions, and with `active` marks the cells
  // they occupy (the caller finishes the spans: ActiveNodes::finish). Returns the index of the first
  // particle outside the grid, or the particle count when all are inside. One parallel region: each
  // thread makes the stencils of a contiguous chunk of blocks and counts its chunk's particles per
  // slab, then, once every chunk is known to be inside the grid, places them in the schedule.
  template <class Shape>
  int locate(const Grid<Dim>& grid, const Particles<Dim>& particles, ActiveNodes<Dim>* active = nullptr) {
    auto& st = stencils<Shape>();
    const int n = static_cast<int>(particles.size());
    st.resize(n);
    cell_of.resize(n);
    int* layer = schedule.layers(n);  // the cell index along the slab axis, for the schedule
    const int axis = cells.slab_axis();
    const StencilFrame<Dim> frame(grid);
    const int blocks = (n + kStencilBlock - 1) / kStencilBlock;
    const int threads = omp_get_max_threads();
    schedule.prepare(n, grid.cells(axis), threads);
    first_outside_.assign(threads, n);
    if (active) active->start(grid, threads);
    auto& shares = ThreadShares::of(LoopKind::Locate);
    const auto start = ThreadShares::Clock::now();
#pragma omp parallel num_threads(threads)
    {
      const int t = omp_get_thread_num(), team = omp_get_num_threads();
      const int first_block = static_cast<int>(shares.first(t, team, blocks));
      const int end_block = static_cast<int>(shares.first(t + 1, team, blocks));
      const int lo = std::min(first_block * kStencilBlock, n), hi = std::min(end_block * kStencilBlock, n);
      typename ActiveNodes<Dim>::Marker marker;
      if (active) marker = active->marker(t);
      const auto place = [&](int p, const std::array<int, Dim>& cell) {
        cell_of[p] = cells.of_coords(cell);
        layer[p] = cell[axis];
        if (active) marker.add(cell);
      };
      int outside = n;
      for (int b = first_block; b < end_block; ++b) {
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
      if (active) marker.flush();
      if (outside == n) schedule.count(t, lo, hi);  // an outside particle has no layer
      first_outside_[t] = outside;
      shares.finished(start, end_block - first_block);
#pragma omp barrier
      // Every thread reads the same values, so all go on or all stop.
      if (*std::min_element(first_outside_.begin(), first_outside_.begin() + team) == n) schedule.place(t, lo, hi);
    }
    return *std::min_element(first_outside_.begin(), first_outside_.end());
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
  std::vector<int> first_outside_;  // per thread, in locate
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
