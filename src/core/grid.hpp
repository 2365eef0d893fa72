// Uniform structured background grid of square (cube) cells with nodal fields and edge fixities.
#pragma once

#include <array>
#include <string_view>
#include <vector>

#include "types.hpp"

namespace seismpm {

// Grid edges: left/right are -x/+x, bottom/top -y/+y, back/front -z/+z.
enum class Side { Left, Right, Bottom, Top, Back, Front };

// Degrees of freedom a fixity holds, as a bit mask.
enum DofMask : unsigned { FixX = 1u, FixY = 2u, FixZ = 4u };

template <int Dim>
class CheckpointAccess;  // reads and restores the private state (src/run/checkpoint.cpp)

template <int Dim>
class Grid {
 public:
  // Covers the domain [lower, upper] with cells of size `cell` (the upper edge rounded up to whole
  // cells) plus `ghost` layers of cells beyond it on every side, so that a particle anywhere in the
  // domain has its whole support on the grid.
  Grid(const Vec<Dim>& lower, const Vec<Dim>& upper, double cell, int ghost = 0);

  const Vec<Dim>& origin() const { return origin_; }  // the first node, ghost layers included
  Vec<Dim> upper() const;                             // the last node
  // The user's domain: the grid without its ghost layers.
  Vec<Dim> domain_lower() const { return origin_.array() + ghost_ * h_; }
  Vec<Dim> domain_upper() const { return upper().array() - ghost_ * h_; }
  int ghost() const { return ghost_; }
  int domain_cells(int axis) const { return cells_[axis] - 2 * ghost_; }
  double cell() const { return h_; }
  int cells(int axis) const { return cells_[axis]; }
  int nodes(int axis) const { return cells_[axis] + 1; }
  int node_count() const { return static_cast<int>(mass.size()); }
  int cell_count() const;
  // Step in the linear node index for one node along `axis` (axis 0 varies fastest).
  int stride(int axis) const { return stride_[axis]; }
  std::array<int, Dim> node_coords(int node) const;
  Vec<Dim> node_position(int node) const;

  // Zeroes mass, momentum and force before a transfer, and with `kinematics` velocity and
  // acceleration too (every field: what a step over the active nodes only takes for granted).
  void reset(bool kinematics = false);
  // Zeroes every field of nodes [first, end).
  void reset_nodes(int first, int end);

  // Holds the given degrees of freedom at zero on every node of a domain edge and of the ghost
  // layers beyond it.
  void fix(Side side, unsigned dof_mask);
  // Lets go of the given degrees of freedom on one domain edge (an edge boundary that held like a
  // fixity in the gravity phase); what the other edges hold, corners included, stays held.
  void release(Side side, unsigned dof_mask);
  // The degrees of freedom held on a domain edge, read at its middle node.
  unsigned held_on(Side side) const;
  // Nodes with at least one fixed degree of freedom and their masks.
  const std::vector<int>& fixed_nodes() const { return fixed_nodes_; }
  unsigned fixity(int node) const { return fixity_[node]; }
  // Zeroes the fixed components of `field` (velocities, accelerations).
  void apply_fixities(std::vector<Vec<Dim>>& field) const;
  // Holds the fixed components of the updated velocity at zero and sets the acceleration there to the
  // change that brings the start velocity mv/m to it, (0 - mv/m) / dt. A FLIP update adds
  // sum N a dt to the particle velocity: with a zeroed acceleration instead, the particles beside a
  // held edge kept the velocity the support had taken from the grid and pushed it into the edge again
  // on every step (a floor under a granular flow kept a store of motion that never dissipated).
  void hold_updated_velocities(double dt);

  // Nodal fields, indexed by the linear node index.
  std::vector<double> mass;
  std::vector<Vec<Dim>> momentum;
  std::vector<Vec<Dim>> force;         // internal + external: the out-of-balance force
  std::vector<Vec<Dim>> velocity;      // updated (Lagrangian) velocity v^L, then the MUSL re-map
  std::vector<Vec<Dim>> acceleration;  // for the FLIP update of particle velocities

 private:
  template <int>
  friend class CheckpointAccess;
  Vec<Dim> origin_;
  double h_;
  int ghost_ = 0;
  std::array<int, Dim> cells_{};
  std::array<int, Dim> stride_{};
  std::vector<unsigned char> fixity_;
  std::vector<int> fixed_nodes_;
};

// Parses "left" | "right" | "bottom" | "top" | "back" | "front"; throws InputError otherwise.
Side parse_side(std::string_view name, int dim);
// The side's name, as parse_side reads it.
std::string_view side_name(Side side);
// Parses "x" | "y" | "z" | "xy" | "xz" | "yz" | "xyz" into a DofMask; throws InputError otherwise.
unsigned parse_dof(std::string_view name, int dim);

extern template class Grid<2>;
extern template class Grid<3>;

}  // namespace seismpm
