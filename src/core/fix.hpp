// A feature that acts inside a step (damping, rigid bodies, contact, later absorbing boundaries)
// attaches to named stages of the step, the way a LAMMPS "fix" does. Adding one never edits the loop.
#pragma once

#include <string_view>

namespace seismpm {

template <int Dim>
class Model;

// Which nodal velocity field a constraint stage sees.
enum class VelocityStage {
  Updated,   // v^L = mv/m + dt a, with a, just after the nodal force update
  Remapped,  // the MUSL re-map of particle momentum (velocity only)
};

template <int Dim>
class Fix {
 public:
  virtual ~Fix() = default;
  virtual std::string_view name() const = 0;
  // Before the grid is reset (assign prescribed velocities, read histories).
  virtual void before_step(Model<Dim>&) {}
  // After particles-to-grid, on the nodal out-of-balance forces (local damping).
  virtual void nodal_forces(Model<Dim>&) {}
  // After the grid fixities were applied to a nodal velocity field (prescribed nodes, contact).
  virtual void nodal_velocities(Model<Dim>&, VelocityStage) {}
  // After the stress update, when the step is complete.
  virtual void after_step(Model<Dim>&) {}
};

}  // namespace seismpm
