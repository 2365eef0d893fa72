// Fixed grid edges as the position update sees them: what keeps particle centres inside a domain edge
// whose normal velocity is held.
//
// Why a centre crosses a held edge at all: the position moves with sum N_i v_i over the particle's
// stencil. The edge's nodes and the ghost nodes beyond it hold v_n = 0, but a uGIMP particle whose
// domain (half-width l, cell units) reaches past the edge keeps the weight (d + l)^2 / 4l at the
// first interior node, d its centre's distance from the edge: l/4 with the centre on the edge. So the
// centre still moves at l/4 of that node's velocity there and passes the edge whenever the flow beside
// it pushes that way (a random walk near a floor under a granular flow leaks). A linear particle has
// the weight d, which vanishes on the edge.
//
// The remedy: beyond a held edge the position update reads the normal velocity as the mirror image of
// the inside (odd in the distance, as on a symmetry plane), so each ghost node's weight moves to its
// mirror node with the opposite sign. The centre's normal velocity is then exactly d v_1 (cell units),
// the linear interpolant, zero on the edge: per step the distance changes by the factor
// 1 + dt v_1 / h, positive under the CFL limit, so the centre approaches the edge geometrically and
// never reaches it. Particles whose domain stays inside have no ghost weight and are untouched;
// velocities and strains are untouched everywhere.
#pragma once

#include <algorithm>

#include "grid.hpp"
#include "stencil.hpp"
#include "types.hpp"

namespace seismpm {

template <int Dim>
class HeldEdges {
 public:
  // Reads, for each domain edge, whether its normal velocity is held (Grid::fix on that side).
  explicit HeldEdges(const Grid<Dim>& grid) : grid_(grid), lower_(grid.domain_lower()), upper_(grid.domain_upper()) {
    const bool ghosts = grid.ghost() > 0;
    for (int d = 0; d < Dim; ++d) {
      held_[d][0] = ghosts && (grid.held_on(static_cast<Side>(2 * d)) & (1u << d));
      held_[d][1] = ghosts && (grid.held_on(static_cast<Side>(2 * d + 1)) & (1u << d));
      any_ = any_ || held_[d][0] || held_[d][1];
    }
  }

  bool any() const { return any_; }

  // True when a centre at x may have weight beyond a held edge (within half a cell of it: l <= 1/2).
  bool near(const Vec<Dim>& x) const {
    const double reach = 0.5 * grid_.cell();
    for (int d = 0; d < Dim; ++d)
      if ((held_[d][0] && x[d] < lower_[d] + reach) || (held_[d][1] && x[d] > upper_[d] - reach)) return true;
    return false;
  }

  // Replaces, in the centre velocity v = sum N_i v_i of stencil st, the normal component each ghost
  // node beyond a held edge contributes by minus its mirror node's. node_velocity(i) is the velocity
  // the particle reads at node i (its own contact field's where fields meet).
  template <int K, class NodeVelocity>
  void mirror(const Stencil<Dim, K>& st, Vec<Dim>& v, NodeVelocity&& node_velocity) const {
    const int g = grid_.ghost();
    for (int d = 0; d < Dim; ++d) {
      const int first = (st.base / grid_.stride(d)) % grid_.nodes(d);
      const int wall[2] = {g, grid_.cells(d) - g};
      for (int side = 0; side < 2; ++side) {
        if (!held_[d][side]) continue;
        const int out = side == 0 ? -1 : 1;  // towards the ghost layer
        const int ghost = wall[side] + out - first, image = wall[side] - out - first;
        if (ghost < 0 || ghost >= K || image < 0 || image >= K) continue;
        for_each_in_layer(st, grid_, d, ghost, [&](int node, double N) {
          const int image_node = node + (image - ghost) * grid_.stride(d);
          v[d] -= N * (node_velocity(node)[d] + node_velocity(image_node)[d]);
        });
      }
    }
  }

  // The last safeguard: a centre beyond a held edge is put back on it (x and u alike). With the mirror
  // only round-off in the weights (about 1e-16 of a cell) can put it there.
  void keep_inside(Vec<Dim>& x, Vec<Dim>& u) const {
    for (int d = 0; d < Dim; ++d) {
      double to = x[d];
      if (held_[d][0]) to = std::max(to, lower_[d]);
      if (held_[d][1]) to = std::min(to, upper_[d]);
      u[d] += to - x[d];
      x[d] = to;
    }
  }

 private:
  const Grid<Dim>& grid_;
  Vec<Dim> lower_, upper_;
  bool held_[Dim][2] = {};
  bool any_ = false;
};

}  // namespace seismpm
