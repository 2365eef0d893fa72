// The nodes a particle touches and its shape-function values there, per axis; evaluated once
// per step at the start-of-step positions and used by every transfer of the step.
#pragma once

#include <algorithm>
#include <cassert>
#include <cmath>

#include "grid.hpp"
#include "shape_function.hpp"
#include "types.hpp"

namespace seismpm {

template <int Dim, int K>
struct Stencil {
  int base;           // linear index of the first node
  double w[Dim][K];   // per-axis weights
  double dw[Dim][K];  // per-axis derivatives (1/m)
};

// The grid's domain (edges included, ghost layers not), taken once for a loop over particles: the
// grid's bounds are computed, not stored, and asking for them per particle cost a call each time.
template <int Dim>
struct DomainBox {
  explicit DomainBox(const Grid<Dim>& grid) : lo(grid.domain_lower()), hi(grid.domain_upper()) {}
  // True while x lies in the domain; false for a NaN coordinate.
  bool contains(const Vec<Dim>& x) const {
    bool in = true;
    for (int d = 0; d < Dim; ++d) in &= (x[d] >= lo[d]) & (x[d] <= hi[d]);
    return in;
  }
  Vec<Dim> lo, hi;
};

// True while the particle's centre lies in the grid's domain (edges included, ghost layers not).
template <int Dim>
bool inside_domain(const Grid<Dim>& grid, const Vec<Dim>& x) {
  return DomainBox<Dim>(grid).contains(x);
}

// Per-axis first node and weights for a particle at x with uGIMP half-width l (cell units).
// Returns false when the particle's centre is outside the grid. A model's grid has a ghost layer,
// so a particle in its domain always has its whole support; on a grid without one, a uGIMP stencil
// reaching past the edge is clipped there (which breaks sum grad N = 0 for that particle).
// With `cell` (Dim ints), also the coordinates of the cell holding x, clamped to the grid (CellIndex::coords_of's,
// from the same scaled coordinate).
template <class Shape, int Dim>
bool make_stencil(const Grid<Dim>& grid, const Vec<Dim>& x, double l, Stencil<Dim, Shape::K>& st, int* cell = nullptr) {
  const double inv_h = 1.0 / grid.cell();
  st.base = 0;
  for (int d = 0; d < Dim; ++d) {
    const double xi = (x[d] - grid.origin()[d]) * inv_h;
    const int cells = grid.cells(d);
    if (!(xi >= 0.0 && xi <= cells)) return false;
    if (cell) cell[d] = std::min(static_cast<int>(std::floor(xi)), cells - 1);  // xi >= 0 here
    int first = Shape::first_node(xi, l);
    if (first < 0) first = 0;
    if (first > cells + 1 - Shape::K) first = cells + 1 - Shape::K;
    // Evaluated into locals and stored once: scaling the derivatives in place re-read them straight
    // after their scalar stores, and the wider load that could not take them from the store buffer
    // stalled (over half of this loop's time).
    double w[Shape::K], dw[Shape::K];
    Shape::eval(xi, l, first, w, dw);
    for (int k = 0; k < Shape::K; ++k) {
      st.w[d][k] = w[k];
      st.dw[d][k] = dw[k] * inv_h;
    }
    st.base += first * grid.stride(d);
  }
  return true;
}

// What make_stencils reads of the grid, taken once: read through the grid inside the loop, every
// store of a stencil could have changed them, and each was loaded again per particle.
template <int Dim>
struct StencilFrame {
  explicit StencilFrame(const Grid<Dim>& grid) : inv_h(1.0 / grid.cell()) {
    for (int d = 0; d < Dim; ++d) origin[d] = grid.origin()[d], cells[d] = grid.cells(d), stride[d] = grid.stride(d);
  }
  double origin[Dim];
  double inv_h;
  int cells[Dim], stride[Dim];
};

constexpr int kStencilBlock = 32;  // particles per make_stencils call

// make_stencil for `count` (at most kStencilBlock) particles together, with the same values, and
// each particle's cell coordinates (Dim ints, clamped to the grid) in `cell`. Each axis's arithmetic
// runs over the block lane by lane, which the compiler vectorises (particle by particle it ran as
// scalar code: the sand column's stencil stage took 0.32 instead of 0.26 ms a step); the stencils are
// written out after. Returns false, having written no stencil, where a particle's centre is outside
// the grid or its stencil is clipped: the caller then makes that block one particle at a time.
template <class Shape, int Dim, class CellCoords>
bool make_stencils(const StencilFrame<Dim>& f, const Vec<Dim>* x, const double* l, int count,
                   Stencil<Dim, Shape::K>* st, CellCoords* cell) {
  constexpr int B = kStencilBlock, K = Shape::K;
  // Every value a double, the node and cell numbers too: with ints beside them the vectoriser found
  // no vector type for the loop.
  alignas(64) double w[Dim][K][B], dw[Dim][K][B], first[Dim][B], at[Dim][B];
  assert(count <= B);
  // Flags of 64 bits, as wide as the doubles, joined by OR: the vectoriser reduces that lane-wise (a
  // sum of doubles it must add in order, one lane at a time).
  long long bad = 0;
  alignas(64) double coordinate[B], width[B];  // copied first: the vectoriser loads no member in place
  for (int j = 0; j < count; ++j) width[j] = l[j];
  for (int d = 0; d < Dim; ++d) {
    const double origin = f.origin[d], inv_h = f.inv_h, top = f.cells[d];
    const double last_first = f.cells[d] + 1 - K, last_cell = f.cells[d] - 1;
    for (int j = 0; j < count; ++j) coordinate[j] = x[j][d];
    for (int j = 0; j < count; ++j) {
      const double xi = (coordinate[j] - origin) * inv_h;
      // Held within [-1, cells + 1] (a NaN at -1), so that the integer values below stay small; such
      // a particle is flagged, and its block made again one by one.
      const double xs = std::min(xi >= -1.0 ? xi : -1.0, top + 1.0);
      const double lj = width[j];
      const double fn = std::min(std::max(Shape::first_node_value(xs, lj), 0.0), last_first);
      const double a0 = xs - fn;
      // Bitwise, not short-circuit: a branch in the loop keeps it from being vectorised.
      const bool inside = (xi >= 0.0) & (xi <= top);
      bad |= static_cast<long long>(!(inside & Shape::regular(a0, lj)));
      at[d][j] = std::min(floor_small(xs), last_cell);
      first[d][j] = fn;
      double wk[K], dwk[K];
      Shape::eval_regular(a0, lj, wk, dwk);
      for (int k = 0; k < K; ++k) w[d][k][j] = wk[k], dw[d][k][j] = dwk[k] * inv_h;
    }
  }
  if (bad) return false;
  for (int j = 0; j < count; ++j) {
    Stencil<Dim, K>& s = st[j];
    s.base = 0;
    for (int d = 0; d < Dim; ++d) {
      for (int k = 0; k < K; ++k) s.w[d][k] = w[d][k][j], s.dw[d][k] = dw[d][k][j];
      s.base += static_cast<int>(first[d][j]) * f.stride[d];
      cell[j][d] = static_cast<int>(at[d][j]);
    }
  }
  return true;
}

namespace stencil_detail {
// The nodes of a stencil with N and grad N, and with Offsets also x_node - x_p.
template <bool Offsets, int Dim, int K, class F>
inline void visit(const Stencil<Dim, K>& st, const Grid<Dim>& grid, F&& f) {
  [[maybe_unused]] double off[Dim][K];
  if constexpr (Offsets) {
    const double h = grid.cell();
    for (int d = 0; d < Dim; ++d) {
      double centre = 0.0;  // in node steps from the stencil's first node
      for (int k = 0; k < K; ++k) centre += k * st.w[d][k];
      for (int k = 0; k < K; ++k) off[d][k] = h * (k - centre);
    }
  }
  if constexpr (Dim == 2) {
    const int sy = grid.stride(1);
    for (int b = 0; b < K; ++b)
      for (int a = 0; a < K; ++a) {
        const Vec<2> dN(st.dw[0][a] * st.w[1][b], st.w[0][a] * st.dw[1][b]);
        if constexpr (Offsets)
          f(st.base + a + b * sy, st.w[0][a] * st.w[1][b], dN, Vec<2>(off[0][a], off[1][b]));
        else
          f(st.base + a + b * sy, st.w[0][a] * st.w[1][b], dN);
      }
  } else {
    static_assert(Dim == 3);
    const int sy = grid.stride(1), sz = grid.stride(2);
    for (int c = 0; c < K; ++c)
      for (int b = 0; b < K; ++b)
        for (int a = 0; a < K; ++a) {
          const Vec<3> dN(st.dw[0][a] * st.w[1][b] * st.w[2][c], st.w[0][a] * st.dw[1][b] * st.w[2][c],
                          st.w[0][a] * st.w[1][b] * st.dw[2][c]);
          const int node = st.base + a + b * sy + c * sz;
          const double N = st.w[0][a] * st.w[1][b] * st.w[2][c];
          if constexpr (Offsets)
            f(node, N, dN, Vec<3>(off[0][a], off[1][b], off[2][c]));
          else
            f(node, N, dN);
        }
  }
}
}  // namespace stencil_detail

// Calls f(node, N) for the stencil's nodes whose local index along `axis` is `layer` (one plane of it).
template <int Dim, int K, class F>
inline void for_each_in_layer(const Stencil<Dim, K>& st, const Grid<Dim>& grid, int axis, int layer, F&& f) {
  int k[Dim] = {};
  for (;;) {
    if (k[axis] == layer) {
      double N = 1.0;
      int i = st.base;
      for (int d = 0; d < Dim; ++d) N *= st.w[d][k[d]], i += k[d] * grid.stride(d);
      f(i, N);
    }
    int d = 0;
    while (d < Dim && ++k[d] == K) k[d++] = 0;
    if (d == Dim) return;
  }
}

// Calls f(node, N, gradN) for every node of the stencil.
template <int Dim, int K, class F>
inline void for_each_node(const Stencil<Dim, K>& st, const Grid<Dim>& grid, F&& f) {
  stencil_detail::visit<false>(st, grid, f);
}

// Calls f(node, N, gradN, dx) for every node of the stencil, dx = x_node - x_p. The centre is
// recovered from the weights themselves (sum N x_node = x_p for linear and uGIMP shapes inside the
// grid), so this serves the positions the stencil was made at, also after the particles moved.
template <int Dim, int K, class F>
inline void for_each_node_offset(const Stencil<Dim, K>& st, const Grid<Dim>& grid, F&& f) {
  stencil_detail::visit<true>(st, grid, f);
}

// Calls f(node, N, gradN, momentum) with the momentum a particle maps to each node of its stencil:
// its own, mv, or with APIC's affine field (mC = m C, null under FLIP) mv + mC (x_node - x_p).
template <int Dim, int K, class F>
inline void for_each_node_momentum(const Stencil<Dim, K>& st, const Grid<Dim>& grid, const Vec<Dim>& mv,
                                   const Mat<Dim>* mC, F&& f) {
  if (mC)
    for_each_node_offset(st, grid, [&](int i, double N, const Vec<Dim>& dN, const Vec<Dim>& dx) {
      f(i, N, dN, Vec<Dim>(mv + *mC * dx));
    });
  else
    for_each_node(st, grid, [&](int i, double N, const Vec<Dim>& dN) { f(i, N, dN, mv); });
}

// sum_i N_i u_i over the stencil for a nodal field u, factorised along the axes: each row of nodes
// along x is summed with the x weights first, then the rows with the other axes' weights. The node
// by node sum was one chain of K^Dim dependent multiply-adds per particle, which the transfers waited
// on; the rows are independent and need K^(Dim-1) + K^Dim products instead of twice K^Dim.
template <int Dim, int K>
inline Vec<Dim> interpolate(const Stencil<Dim, K>& st, const Grid<Dim>& grid, const Vec<Dim>* u) {
  auto row_sum = [&](int first) {
    Vec<Dim> r = st.w[0][0] * u[first];
    for (int a = 1; a < K; ++a) r += st.w[0][a] * u[first + a];
    return r;
  };
  const int sy = grid.stride(1);
  if constexpr (Dim == 2) {
    Vec<2> total = st.w[1][0] * row_sum(st.base);
    for (int b = 1; b < K; ++b) total += st.w[1][b] * row_sum(st.base + b * sy);
    return total;
  } else {
    static_assert(Dim == 3);
    const int sz = grid.stride(2);
    Vec<3> total = Vec<3>::Zero();
    for (int c = 0; c < K; ++c) {
      Vec<3> plane = st.w[1][0] * row_sum(st.base + c * sz);
      for (int b = 1; b < K; ++b) plane += st.w[1][b] * row_sum(st.base + b * sy + c * sz);
      total += st.w[2][c] * plane;
    }
    return total;
  }
}

// L = sum_i u_i grad N_i^T over the stencil for a nodal field u (the velocity gradient), factorised
// as interpolate is: per row of nodes along x, the sums with the x weights and with their
// derivatives, then the rows with the other axes' weights and derivatives.
template <int Dim, int K>
inline Mat<Dim> gradient(const Stencil<Dim, K>& st, const Grid<Dim>& grid, const Vec<Dim>* u) {
  const int sy = grid.stride(1);
  Mat<Dim> L = Mat<Dim>::Zero();
  auto add_row = [&](int first, double wy, double dwy, [[maybe_unused]] double wz, [[maybe_unused]] double dwz) {
    Vec<Dim> r = st.w[0][0] * u[first], d = st.dw[0][0] * u[first];
    for (int a = 1; a < K; ++a) r += st.w[0][a] * u[first + a], d += st.dw[0][a] * u[first + a];
    if constexpr (Dim == 2) {
      L.col(0) += wy * d;
      L.col(1) += dwy * r;
    } else {
      L.col(0) += (wy * wz) * d;
      L.col(1) += (dwy * wz) * r;
      L.col(2) += (wy * dwz) * r;
    }
  };
  if constexpr (Dim == 2) {
    for (int b = 0; b < K; ++b) add_row(st.base + b * sy, st.w[1][b], st.dw[1][b], 1.0, 0.0);
  } else {
    static_assert(Dim == 3);
    const int sz = grid.stride(2);
    for (int c = 0; c < K; ++c)
      for (int b = 0; b < K; ++b) add_row(st.base + b * sy + c * sz, st.w[1][b], st.dw[1][b], st.w[2][c], st.dw[2][c]);
  }
  return L;
}

}  // namespace seismpm
