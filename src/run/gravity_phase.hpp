// The gravity (initial stress) phase's parts: its settings and result, the equilibrium criterion that
// ends it, and the K0 shortcut for level ground. The phase itself, self-weight with local damping until
// static equilibrium, is Simulation::gravity_phase.
#pragma once

#include <string>

#include "core/model.hpp"

namespace seismpm {

struct GravityPhaseSettings {
  double damping = 0.7;      // local damping coefficient alpha
  double tolerance = 0.005;  // on both equilibrium ratios
  double max_time = 10.0;    // s of simulated time before the phase gives up
  double k0 = 0.0;           // > 0: set K0 stresses first, then settle
};

// How the phase ended: its duration and steps, and both equilibrium ratios at its end.
struct GravityPhaseResult {
  double time = 0.0;  // s
  long steps = 0;
  double force_ratio = 0.0, energy_ratio = 0.0;
};

// Watches a damped run for static equilibrium: the out-of-balance force relative to the external
// force, and the kinetic energy relative to its peak in the phase (at least 1e-3 of the elastic strain
// energy, so a body set in equilibrium by K0 does not chase round-off), both below the tolerance.
template <int Dim>
class CheckpointAccess;  // reads and restores the private state (src/run/checkpoint.cpp)

template <int Dim>
class EquilibriumMonitor {
 public:
  explicit EquilibriumMonitor(double tolerance) : tolerance_(tolerance) {}
  // Measures the kinetic energy against at least `peak`, an earlier phase's peak: a phase that starts
  // near equilibrium (a strength reduction trial) has a tiny peak of its own, below round-off motion.
  EquilibriumMonitor(double tolerance, double peak) : tolerance_(tolerance), peak_energy_(peak) {}
  // After each step of the phase (the model must measure its balance: Model::set_balance_measure).
  void update(const Model<Dim>& model);
  bool reached() const { return steps_ >= kMinSteps && force_ratio_ < tolerance_ && energy_ratio_ < tolerance_; }
  double force_ratio() const { return force_ratio_; }
  double energy_ratio() const { return energy_ratio_; }
  double tolerance() const { return tolerance_; }
  double peak_energy() const { return peak_energy_; }

 private:
  template <int>
  friend class CheckpointAccess;
  static constexpr int kMinSteps = 10;  // the first steps of a body at rest prove nothing
  double tolerance_;
  double force_ratio_ = 1.0, energy_ratio_ = 1.0, peak_energy_ = 0.0;
  long steps_ = 0;
};

// "unbalanced 1.2e-03, kinetic 3.4e-04 of peak (tol 5e-03)": the ratios for the progress line.
template <int Dim>
std::string equilibrium_text(const EquilibriumMonitor<Dim>& e);

// Where a model still moves: "the fastest particles: 'upper' at (1.94, 2.06) m, 0.031 m/s; ...", the
// `count` fastest deformable particles by speed with their body, position and speed, and each moving
// body's largest speed. For the message of a gravity phase that found no equilibrium.
template <int Dim>
std::string motion_summary(const Model<Dim>& model, int count = 3);

// K0 initial stresses for level ground: on every deformable particle sigma_v = rho g depth, where
// the overburden is the mass per unit width of the deformable particles above it in its grid column
// (its own half included), and sigma_h = k0 sigma_v (both horizontal axes, and sigma_zz in plane
// strain); no shear. Gravity must point down (-y in 2D, -z in 3D). Displacements and strains are zeroed.
template <int Dim>
void set_k0_stresses(Model<Dim>& model, double k0);

extern template class EquilibriumMonitor<2>;
extern template class EquilibriumMonitor<3>;

}  // namespace seismpm
