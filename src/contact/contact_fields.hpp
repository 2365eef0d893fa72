// Contact fields of a model: which bodies get their own nodal velocity and how pairs interact
// (contact_rules.hpp), the nodes where fields meet with their per-field data (shared_nodes.hpp), the
// Bardenhagen resolution there (node_contact.hpp), and the rigid bodies' prescribed motion and
// reactions. The model calls it at named stages of a step, and only when contact fields exist.
// It reads the model's data (grid, particles, their support), never the model itself.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "contact_rules.hpp"
#include "core/body.hpp"
#include "core/grid.hpp"
#include "core/particle_support.hpp"
#include "core/particles.hpp"
#include "core/step_context.hpp"
#include "node_contact.hpp"
#include "rigid_body.hpp"
#include "rigid_exclusion.hpp"
#include "shared_nodes.hpp"

namespace seismpm {

struct MaterialConstants;  // core/time_step.hpp

struct ContactPair {
  int a, b;
  double friction;  // Coulomb mu >= 0
};

template <int Dim>
class CheckpointAccess;  // reads and restores the private state (src/run/checkpoint.cpp)

template <int Dim>
class ContactFields {
 public:
  using Velocity = std::array<std::shared_ptr<const History>, Dim>;

  // --- building (bodies by their index in the model)
  // A new body, deformable or rigid (rigid ones start at rest).
  void add_body();
  void set_velocity(int body, const Velocity& velocity) { motion_.at(body).velocity = velocity; }
  // Frictional contact between two bodies; the messages name them.
  void add_pair(const std::vector<Body>& bodies, int a, int b, double friction);
  void set_friction(const std::vector<Body>& bodies, int a, int b, double friction);
  const std::vector<ContactPair>& pairs() const { return pairs_; }
  const RigidMotion<Dim>& motion(int body) const { return motion_.at(body); }

  // --- stages of a step, in their order
  // Numbers the fields anew after bodies or pairs changed. True when there is more than one field:
  // only then does contact act in the step.
  bool prepare(const std::vector<Body>& bodies);
  // Sets v_R (at the middle of the step, so a rigid body travels the integral of its history) on the
  // rigid particles; zero when `move` is false; and the rigid domains that deformable centres keep out
  // of (exclusion()). Returns the first rigid particle that would leave the grid in this step, or the
  // particle count.
  int prescribe_rigid_velocities(Particles<Dim>& particles, const Grid<Dim>& grid, const std::vector<Body>& bodies,
                                 const StepContext& c, bool move);
  // Which nodes more than one field touches this step; their slots start at zero.
  template <class Shape>
  void mark_shared_nodes(const Particles<Dim>& particles, const Grid<Dim>& grid, const ParticleSupport<Dim>& support,
                         const StepContext& c);
  // Each field's own mass, momentum, force and normal at the shared nodes (the model maps the common
  // fields, without rigid particles). `damped`: the materials' constants when some material is
  // Rayleigh-damped, else null.
  template <class Shape>
  void particles_to_fields(const Particles<Dim>& particles, const Grid<Dim>& grid, const ParticleSupport<Dim>& support,
                           const Vec<Dim>& gravity, bool apic, const MaterialConstants* damped = nullptr);
  // Each field's velocity at the shared nodes: a rigid field's the weighted average of its particles'
  // (the paper's Eq. 9), a deformable field's from its momentum and force.
  void update_velocities(double dt, double min_mass);
  // Contact at every shared node, then the grid fixities on each deformable field. After the force
  // update the accelerations are rebuilt from the corrected velocities (so FLIP sees the correction)
  // and the force each rigid body exerts is summed.
  void resolve(VelocityStage stage, const Grid<Dim>& grid, double dt, double min_mass);
  // Local (Cundall) damping alpha of the fields' own forces at the shared nodes without a rigid
  // field, glued groups on their net force (the model damps the common fields).
  void damp_forces(double alpha, double min_mass);
  // The MUSL re-map of each deformable field's momentum at the shared nodes; rigid slots keep theirs.
  template <class Shape>
  void remap_momentum(const Particles<Dim>& particles, const Grid<Dim>& grid, const ParticleSupport<Dim>& support,
                      double min_mass, bool apic);

  // --- what the model's transfers read
  bool rigid(int body) const { return body_rigid_[body]; }
  bool any_rigid() const { return any_rigid_; }
  int field_of(int body) const { return field_of_body_[body]; }
  // The cell's particles may touch a shared node (then they read their own field's slots).
  bool near_shared(int cell) const { return near_shared_[cell]; }
  // A rigid field is present at the shared node k (its force is the support's to take).
  bool held(int k) const;
  const ContactRules& rules() const { return rules_; }
  // The rigid particles' domains at the end of this step (set with the rigid velocities).
  const RigidExclusion<Dim>& exclusion() const { return exclusion_; }
  SharedNodes<Dim>& nodes() { return shared_; }
  const SharedNodes<Dim>& nodes() const { return shared_; }

 private:
  template <int>
  friend class CheckpointAccess;
  ContactPair* find_pair(int a, int b);
  int mark_cell_fields(const Particles<Dim>& particles, const Grid<Dim>& grid, const ParticleSupport<Dim>& support);
  template <class Shape>
  int mark_nodes(const Grid<Dim>& grid, const CellIndex<Dim>& cells);
  void find_plain_fields();
  template <class Shape>
  bool flag_cells_near_kept_apart(const Grid<Dim>& grid, const CellIndex<Dim>& cells);
  template <class Shape>
  void flag_cells_near_shared(const Grid<Dim>& grid, const CellIndex<Dim>& cells);
  NodeFields<Dim> node_fields(int k) const;
  void resolve_node(int k, bool updated, const Grid<Dim>& grid, double dt, double min_mass);
  Vec<Dim> group_start_velocity(int k, const NodeFields<Dim>& nf, int j, double min_mass) const;
  void sum_reactions(double dt);

  std::vector<ContactPair> pairs_;
  std::vector<RigidMotion<Dim>> motion_;  // per body; used by rigid ones
  bool numbered_ = false;
  std::vector<int> field_of_body_;
  std::vector<int> body_of_field_;  // a rigid or paired body's own field; field 0 may hold many
  std::vector<char> body_rigid_;
  bool any_rigid_ = false;
  ContactRules rules_;
  SharedNodes<Dim> shared_;
  std::vector<Vec<Dim>> slot_reaction_;  // per slot: force a rigid field gave this step
  std::vector<FieldSet> cell_fields_;    // per cell: the contact fields of its particles
  std::vector<char> near_shared_;        // per cell
  // This step's occupied cells and newly marked nodes per scatter slab, and the cells flagged near a
  // shared node: what the next step empties instead of the whole grid.
  std::vector<std::vector<int>> slab_cells_, slab_nodes_;
  std::vector<std::vector<int>> slab_kept_apart_;  // per slab, its cells holding a field kept apart
  std::vector<int> near_cells_;
  ScatterSchedule::Selection near_particles_;  // this step's rigid particles and those near a shared node
  std::vector<char> plain_;                    // per field: deformable, glued to every deformable field
  std::vector<char> near_kept_apart_;          // per cell: its plain fields' nodes may be shared
  std::vector<int> near_kept_apart_cells_;     // the cells flagged
  RigidExclusion<Dim> exclusion_;
};

extern template class ContactFields<2>;
extern template class ContactFields<3>;

}  // namespace seismpm
