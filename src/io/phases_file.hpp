// phases.csv of an output directory: "phase,start (s)", a row per phase of the run in the order they
// began, with the model time at which each began ("run" before any phase, then "gravity", "dynamic").
// The plots read it to put their time axis in the shaking's time and to mark the phases.
#pragma once

#include <string>
#include <vector>

namespace seismpm {

struct PhaseStart {
  std::string phase;
  double start = 0.0;  // model time (s) at which the phase began
};

// The rows of DIR/phases.csv; none when it does not exist. Throws OutputError for a malformed file.
std::vector<PhaseStart> read_phases(const std::string& dir);

// Puts `phase`, begun at model time `start`, on file as the last phase: rows that began at or after
// `start` (from a run this one replaces, or one past the checkpoint it restarted from) are dropped,
// and nothing is written when the last row is this phase already. Atomic.
void record_phase(const std::string& dir, const std::string& phase, double start);

// Whether two phase starts are the same time (they are differences of model times: rounding apart).
bool same_start(double a, double b);

// The start of the first dynamic phase (the time axis' zero of plots); NaN when the run had none.
double shaking_start(const std::vector<PhaseStart>& phases);

}  // namespace seismpm
