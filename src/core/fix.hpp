// A feature that acts inside a step (damping, test drivers, later absorbing boundaries) attaches to
// named stages of the step, the way a LAMMPS "fix" does. Adding one never edits the loop. Each hook is
// handed the step's context (dt, time, phase time) rather than reading the model's clock.
#pragma once

#include <string_view>

#include "step_context.hpp"

namespace seismpm {

template <int Dim>
class Model;

template <int Dim>
class Fix {
 public:
  virtual ~Fix() = default;
  virtual std::string_view name() const = 0;
  // Before the grid is reset (assign prescribed velocities, read histories).
  virtual void before_step(Model<Dim>&, const StepContext&) {}
  // After particles-to-grid, on the nodal out-of-balance forces (local damping).
  virtual void nodal_forces(Model<Dim>&, const StepContext&) {}
  // After every fix's nodal_forces (damping included), before the nodal velocity update: tractions and
  // dashpots on grid edges, which must see the complete force (an implicit dashpot) and, on held
  // nodes, the support's reaction undamped.
  virtual void edge_forces(Model<Dim>&, const StepContext&) {}
  // After contact and the grid fixities were applied to a nodal velocity field (prescribed nodes).
  virtual void nodal_velocities(Model<Dim>&, const StepContext&, VelocityStage) {}
  // After the stress update and the clock, when the step is complete.
  virtual void after_step(Model<Dim>&, const StepContext&) {}
  // True when the fix writes to no grid node but those carrying particle mass (local damping): the
  // step may then keep its grid loops to the nodes the particles reach (Model::active_nodes). A fix
  // that may write elsewhere (an edge boundary's reaction on an empty edge node) keeps them on the
  // whole grid.
  virtual bool writes_only_nodes_with_mass() const { return false; }
};

}  // namespace seismpm
