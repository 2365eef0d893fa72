// The factor of safety by strength reduction: damped gravity phases on copies of a model, each with the
// strength of every frictional material (Mohr-Coulomb, Drucker-Prager) divided by a strength reduction
// factor (SRF), bisected between an SRF at which the slope holds and one at which it fails.
//
// A trial holds when its damped phase reaches static equilibrium (both ratios of the gravity phase's
// criterion below the equilibrium tolerance) within max_time while no deformable particle moves
// farther than max_displacement. It fails when the slope keeps moving (max_time passes first), when
// some particle has moved farther than max_displacement (a slide: a held state moves by elastic-plastic
// strain, a mechanism without bound), or when a step cannot go on (a particle leaving the grid).
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "core/model.hpp"
#include "io/progress.hpp"

namespace seismpm {

struct StrengthReductionSettings {
  double srf_low = 1.0;           // the slope must hold here: its state is the start of every trial
  double srf_high = 3.0;          // the slope must fail here
  double tolerance = 0.01;        // the bisection ends when the bracket is no wider (on the SRF)
  double damping = 0.7;           // local damping coefficient alpha of every trial
  double equilibrium = 1e-3;      // tolerance of both equilibrium ratios (the gravity phase's criterion)
  double max_time = 10.0;         // s of simulated time a trial may take to reach equilibrium
  double max_displacement = 0.0;  // m; 0: a tenth of the deformable bodies' height along gravity
  std::string mechanism_file;     // non-empty: the end of the failing trial at the smallest SRF (.vtu)
  Progress::Mode progress = Progress::Mode::Quiet;  // a line per trial on stderr
  const std::atomic<bool>* interrupt = nullptr;     // true: stop with RunInterrupted before a step
};

enum class TrialEnd {
  Equilibrium,   // holds
  MaxTime,       // no equilibrium within max_time: fails
  Displacement,  // moved farther than max_displacement: fails
  Error,         // a step could not go on (a particle left the grid): fails
};
const char* to_string(TrialEnd end);

struct StrengthReductionTrial {
  double srf = 0.0;
  bool holds = false;
  TrialEnd end = TrialEnd::MaxTime;
  double displacement = 0.0;    // m: the largest displacement of a deformable particle in the trial
  double kinetic_energy = 0.0;  // J (J/m in 2D) at the trial's end
  double time = 0.0;            // s of simulated time the trial took
  long steps = 0;
  double force_ratio = 0.0, energy_ratio = 0.0;  // the equilibrium ratios at its end
  std::string error;                             // the step's message (TrialEnd::Error)
};

struct StrengthReductionResult {
  double fos = 0.0;                            // the middle of the final bracket: within tolerance / 2 of both ends
  double holds = 0.0;                          // the largest SRF that held
  double fails = 0.0;                          // the smallest SRF that failed
  double max_displacement = 0;                 // m, the limit the trials used
  std::vector<StrengthReductionTrial> trials;  // in the order they ran, the first at srf_low
  std::string mechanism_file;                  // the file written, or empty
};

// The failure criterion in words (for the returned table and the docs).
std::string strength_reduction_criterion();

// Leaves `model` as it is. The first trial (at srf_low) starts from the model's state and gives the
// initial stresses: every later trial starts from its equilibrium, with displacements reset. Throws
// InputError for bad settings, for a model without a frictional material or gravity, when the slope
// fails at srf_low or holds at srf_high (naming the SRF); RunInterrupted when interrupted.
template <int Dim>
StrengthReductionResult strength_reduction(const Model<Dim>& model, const StrengthReductionSettings& settings);

extern template StrengthReductionResult strength_reduction<2>(const Model<2>&, const StrengthReductionSettings&);
extern template StrengthReductionResult strength_reduction<3>(const Model<3>&, const StrengthReductionSettings&);

}  // namespace seismpm
