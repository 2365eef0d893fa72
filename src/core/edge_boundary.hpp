// A grid edge that stands for the ground beyond the model: viscous dashpots (Lysmer-Kuhlemeyer) that let
// waves leave, a compliant base that lets a recorded wave in and the reflected one out, or free-field
// sides that follow a 1D column of the same layering.
//
// On every node of the edge the traction is rho c (v_target - v) per component: c = Vp normal to the
// edge and Vs along it, v_target zero (absorbing), the outcrop velocity (compliant: a wave of velocity
// v_I coming up through rock of impedance rho_r c_r gives the traction rho_r c_r (2 v_I - v), and
// 2 v_I is what a record on rock outcrop measures), or the free field's velocity. The dashpot is
// implicit in the node's end-of-step velocity, so no impedance limits the time step.
//
// Static loads: while a gravity phase runs the edge holds like a fixity (all degrees of freedom on
// the base, the normal one on a side) and records the support's reaction on every held node; later
// that reaction acts as a constant force, so the ground neither sinks nor jumps when shaking starts.
// That constant force replaces the spring of a Kelvin-Voigt boundary: a spring would hold the static
// load only by a displacement it needs first (the ground settles when the fixity goes) and would
// stiffen the edge against low frequencies; the price is that a static load added after the gravity
// phase is carried by the dashpots alone, as a slow drift.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "fix.hpp"
#include "free_field_column.hpp"
#include "grid.hpp"
#include "history.hpp"

namespace seismpm {

enum class BoundaryKind { Absorbing, Compliant, FreeField };

// Parses "absorbing" | "compliant" | "free_field"; throws InputError otherwise.
BoundaryKind parse_boundary_kind(std::string_view name);
std::string_view boundary_kind_name(BoundaryKind kind);

template <int Dim>
struct BoundarySettings {
  Side side = Side::Bottom;
  BoundaryKind kind = BoundaryKind::Absorbing;
  // The medium beyond the edge (kg/m^3, m/s). Compliant: the elastic half-space below, required.
  // Absorbing, free field: > 0 overrides what the particles next to the edge have.
  double density = 0.0, vs = 0.0, vp = 0.0;
  // Compliant: the outcrop velocity per axis (m/s, read at the phase time); null: zero.
  std::array<std::shared_ptr<const History>, Dim> input{};
  // Compliant with an input: compute the model in the frame that moves with the outcrop motion (its
  // acceleration a body force, the dashpots on the velocity relative to it). A record carries the whole
  // ground by its displacement, metres for a near-fault one: on the fixed grid the particles at a side
  // left the domain. Relative displacements (crest to base) are the same in either frame.
  bool moving_frame = true;
};

template <int Dim>
class CheckpointAccess;

template <int Dim>
class EdgeBoundary : public Fix<Dim> {
 public:
  // Throws InputError for settings that do not fit the grid (a free field on the base, a compliant
  // edge without its half-space).
  EdgeBoundary(const Grid<Dim>& grid, const BoundarySettings<Dim>& settings);
  std::string_view name() const override { return "edge_boundary"; }
  const BoundarySettings<Dim>& settings() const { return settings_; }

  // The gravity phase: hold the edge as a fixity (held_dofs) and record its reaction; release: the
  // recorded reaction becomes a constant force and the dashpots act.
  void hold(Grid<Dim>& grid);
  void release(Grid<Dim>& grid);
  bool holding() const { return holding_; }
  unsigned held_dofs() const;

  // Free field: how the column's base is held: by the base's boundary (compliant, absorbing), else by
  // the grid (a fixity on the base) or not at all. Set before the first step that uses the column.
  void set_column_base(std::shared_ptr<const EdgeBoundary> base) { column_base_ = std::move(base); }

  void edge_forces(Model<Dim>& model, const StepContext& c) override;
  // A compliant edge in its moving frame: the frame's acceleration for the step, (v_in(t + dt) - v_in(t)) / dt,
  // so that the frame's velocity is the input's at every step's end.
  void before_step(Model<Dim>& model, const StepContext& c) override;
  bool moves_frame() const;
  // Per direction, the sum of |recorded reaction| over the nodes this edge holds, and the share `delta`
  // of a correction to spread over them in proportion to it (balance_recorded_reactions).
  Vec<Dim> reaction_magnitude() const;
  void correct_reaction(const Vec<Dim>& delta, const Vec<Dim>& magnitude);
  // The MUSL re-map: the edge's nodes and the ghost nodes behind each keep the velocity the dashpot gave.
  void nodal_velocities(Model<Dim>& model, const StepContext& c, VelocityStage stage) override;

  // The force the edge put on the grid in the last step (N per unit thickness in 2D): the static
  // reaction kept from the gravity phase plus tractions and dashpots.
  const Vec<Dim>& last_force() const { return last_force_; }

 private:
  template <int>
  friend class CheckpointAccess;
  // Per edge node: its area (from the particles next to it) and the impedances; the column.
  void prepare(const Model<Dim>& model);
  ColumnBase<Dim> column_base(const Model<Dim>& model) const;
  int axis() const { return static_cast<int>(settings_.side) / 2; }
  double input_at(int axis, double t) const;
  double outward() const { return static_cast<int>(settings_.side) % 2 == 0 ? -1.0 : 1.0; }

  BoundarySettings<Dim> settings_;
  std::vector<int> edge_nodes_;  // the edge's row of nodes within the domain
  std::vector<int> held_nodes_;  // the edge and the ghost layers beyond it
  // Per edge node, the ghost nodes behind it (ghost layers of them, flattened). A released edge moves
  // them with its node: a uGIMP particle that settles towards the edge puts ever more of its weight on
  // them, and a free ghost node, holding none of the recorded reaction, let the ground sink faster the
  // further it sank (an elastic slope on an absorbing base: 6 mm in 3.5 s, growing 1.7x per second).
  std::vector<int> behind_;
  std::vector<Vec<Dim>> reaction_;  // per held node: the support's force recorded while holding
  std::vector<unsigned char> own_;  // per held node: the directions this edge holds (not a corner's other)
  bool holding_ = false;
  bool prepared_ = false;
  std::vector<double> area_;             // per edge node: the edge's area it stands for (m in 2D)
  std::vector<double> rho_vs_, rho_vp_;  // per edge node: impedances (kg/m^2/s)
  std::vector<int> column_node_;         // per edge node: its column node (free field), -1: none
  std::optional<FreeFieldColumn<Dim>> column_;
  std::shared_ptr<const EdgeBoundary> column_base_;
  Vec<Dim> last_force_ = Vec<Dim>::Zero();
  Vec<Dim> frame_velocity_ = Vec<Dim>::Zero();  // the moving frame's velocity at the last step's end
  std::vector<Vec<Dim>> updated_;               // per edge node: its updated velocity this step (scratch)
};

// At the end of a gravity phase: the reactions the edges recorded, with those of the grid's other
// fixities, made to carry the whole weight of the deformable bodies. A damped gravity phase ends while
// the ground still settles a little and the supports do not yet carry all of it (the out-of-balance
// force within the tolerance); held, that does not matter, but on dashpots the missing part is a net
// force that makes the whole ground sink at a constant speed (0.8 mm/s for an elastic slope on an
// absorbing base after a phase ended at 5e-3). Internal forces sum to zero over the grid (a partition
// of unity), so the supports must carry sum m g. Left as recorded when rigid bodies also carry some.
template <int Dim>
void balance_recorded_reactions(const Model<Dim>& model, const std::vector<std::shared_ptr<EdgeBoundary<Dim>>>& edges);

extern template class EdgeBoundary<2>;
extern template class EdgeBoundary<3>;

}  // namespace seismpm
