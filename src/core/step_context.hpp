// What the stages of one step are given explicitly, instead of reading the model's clock.
#pragma once

namespace seismpm {

// Which nodal velocity field a constraint stage sees.
enum class VelocityStage {
  Updated,   // v^L = mv/m + dt a, with a, just after the nodal force update
  Remapped,  // the MUSL re-map of particle momentum (velocity only)
};

struct StepContext {
  double dt = 0.0;          // length of this step (s)
  double time = 0.0;        // model time at the start of the step (s)
  double phase_time = 0.0;  // time since the current phase began, at the start of the step (s)
  long step = 0;            // steps completed before this one
};

}  // namespace seismpm
