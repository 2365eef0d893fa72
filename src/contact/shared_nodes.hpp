// Per-field nodal data where contact fields meet: only the grid nodes that particles of two or more
// contact fields touch get their own slots (up to kSlots fields each), so memory grows with the
// contact interface, not with the number of bodies times the grid.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "contact_rules.hpp"
#include "core/types.hpp"

namespace seismpm {

// Up to 4 contact fields, -1 for an empty place.
using FieldSet = std::array<std::int16_t, 4>;

// Adds `field` to the set; false when it is full with other fields.
inline bool add_field(FieldSet& set, int field) {
  for (auto& f : set) {
    if (f == field) return true;
    if (f < 0) {
      f = static_cast<std::int16_t>(field);
      return true;
    }
  }
  return false;
}

template <int Dim>
class SharedNodes {
 public:
  static constexpr int kSlots = 4;

  // Forgets every node's fields (start of a step): only the nodes the last step marked, so that the
  // cost follows the bodies, not the grid.
  void clear(int node_count);
  // Records that `field` touches grid node `node`, and appends the node to `touched` the first time
  // it is marked this step. Race-free when no two threads mark the same node (the coloured scatter).
  // Returns false when the node has kSlots other fields already.
  bool mark(int node, int field, std::vector<int>& touched) {
    if (present_[node][0] < 0) touched.push_back(node);
    return add_field(present_[node], field);
  }
  // The same from one thread, into touched().
  bool mark(int node, int field) { return mark(node, field, touched_); }
  // The nodes marked this step (build() and the next clear() read them), in a fixed order: the
  // marking threads' lists concatenated slab by slab.
  std::vector<int>& touched() { return touched_; }
  const std::vector<int>& touched() const { return touched_; }
  // Lists the nodes where fields meet that must be kept apart (a rigid field, or two fields with a
  // declared contact) and zeroes their slots. Where only glued deformable fields meet, the common
  // grid fields serve: they are one body there.
  void build(const ContactRules& rules);

  int count() const { return static_cast<int>(node_.size()); }
  // Shared-node index of grid node i, or -1.
  int index(int node) const { return index_[node]; }
  int node(int k) const { return node_[k]; }
  int fields(int k) const { return fields_[k]; }
  // Slot of shared node k that belongs to `field`, or -1.
  int slot(int k, int field) const {
    const auto& p = present_[node_[k]];
    for (int j = 0; j < kSlots; ++j)
      if (p[j] == field) return k * kSlots + j;
    return -1;
  }
  int field_of_slot(int s) const { return present_[node_[s / kSlots]][s % kSlots]; }

  // Per slot (shared node k, slot j at k * kSlots + j).
  std::vector<double> mass;        // deformable: sum N m; rigid: sum N V
  std::vector<Vec<Dim>> momentum;  // deformable: sum N m v; rigid: sum N V v
  std::vector<Vec<Dim>> force;     // deformable: internal + external
  std::vector<Vec<Dim>> gradient;  // deformable: sum m grad N; rigid: sum V grad N
  std::vector<Vec<Dim>> velocity;
  std::vector<Vec<Dim>> acceleration;
  std::vector<Vec<Dim>> face;  // rigid: the outward gradient of its face, set when contact is resolved

 private:
  std::vector<FieldSet> present_;   // per grid node
  std::vector<int> touched_;        // the grid nodes marked this step
  std::vector<int> index_;          // per grid node
  std::vector<int> node_, fields_;  // per shared node
};

extern template class SharedNodes<2>;
extern template class SharedNodes<3>;

}  // namespace seismpm
