#include "active_nodes.hpp"

#include <omp.h>

#include <algorithm>
#include <climits>

namespace seismpm {

template <int Dim>
void ActiveNodes<Dim>::start(const Grid<Dim>& grid, int threads) {
  int cell_rows = 1;
  for (int d = 1; d < Dim; ++d) cell_rows *= grid.cells(d);
  for (int d = 0; d < Dim; ++d) cells_[d] = grid.cells(d);
  threads_ = static_cast<std::size_t>(std::max(threads, 1));
  cell_min_.assign(threads_ * cell_rows, INT_MAX);
  cell_max_.assign(threads_ * cell_rows, -1);
}

template <int Dim>
void ActiveNodes<Dim>::build(const Grid<Dim>& grid, const CellIndex<Dim>& cells, const std::vector<Vec<Dim>>& x, int lo,
                             int hi) {
  const int threads = omp_get_max_threads();
  start(grid, threads);
  const int n = static_cast<int>(x.size());
#pragma omp parallel num_threads(threads)
  {
    Marker m = marker(omp_get_thread_num());
#pragma omp for schedule(static) nowait
    for (int p = 0; p < n; ++p) m.add(cells.coords_of(x[p]));
    m.flush();
  }
  finish(grid, lo, hi);
}

template <int Dim>
void ActiveNodes<Dim>::finish(const Grid<Dim>& grid, int lo, int hi) {
  row_length_ = grid.nodes(0);
  int cell_rows = 1, node_rows = 1;
  for (int d = 1; d < Dim; ++d) cell_rows *= grid.cells(d), node_rows *= grid.nodes(d);
  for (std::size_t t = 1; t < threads_; ++t)
    for (int r = 0; r < cell_rows; ++r) {
      cell_min_[r] = std::min(cell_min_[r], cell_min_[t * cell_rows + r]);
      cell_max_[r] = std::max(cell_max_[r], cell_max_[t * cell_rows + r]);
    }
  // A row of nodes j is reached from the rows of cells j - hi .. j - lo (along every axis but x).
  begin_.assign(node_rows, 0);
  end_.assign(node_rows, 0);
  for (int r = 0; r < node_rows; ++r) {
    int j[Dim] = {};  // the row's node indices along axes 1 .. Dim-1
    for (int d = 1, rest = r; d < Dim; ++d) j[d] = rest % grid.nodes(d), rest /= grid.nodes(d);
    int first = INT_MAX, last = -1;
    int o[Dim] = {};  // cell row offset per axis, lo .. hi
    for (int d = 1; d < Dim; ++d) o[d] = lo;
    for (;;) {
      bool inside = true;
      int row = 0;
      for (int d = Dim - 1; d >= 1; --d) {
        const int c = j[d] - o[d];
        inside = inside && c >= 0 && c < grid.cells(d);
        row = row * grid.cells(d) + c;
      }
      if (inside && cell_max_[row] >= 0) {
        first = std::min(first, cell_min_[row] + lo);
        last = std::max(last, cell_max_[row] + hi);
      }
      int d = 1;
      while (d < Dim && ++o[d] > hi) o[d] = lo, ++d;
      if (d == Dim) break;
    }
    if (last >= 0) {
      begin_[r] = std::max(first, 0);
      end_[r] = std::min(last, row_length_ - 1) + 1;
    }
  }
}

template <int Dim>
void ActiveNodes<Dim>::cover(const Grid<Dim>& grid) {
  row_length_ = grid.nodes(0);
  const int node_rows = grid.node_count() / row_length_;
  begin_.assign(node_rows, 0);
  end_.assign(node_rows, row_length_);
}

template <int Dim>
long ActiveNodes<Dim>::count() const {
  long n = 0;
  for (std::size_t r = 0; r < begin_.size(); ++r) n += end_[r] - begin_[r];
  return n;
}

template class ActiveNodes<2>;
template class ActiveNodes<3>;

}  // namespace seismpm
