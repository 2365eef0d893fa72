// Wall time spent in each stage of the step, when profiling is on (ModelSettings::profile).
#pragma once

#include <array>
#include <utility>
#include <vector>

#include <omp.h>

namespace seismpm {

enum class Stage {
  Reset,
  Stencils,
  TimeStep,
  ContactFields,
  ParticlesToGrid,
  Nodes,
  GridToParticles,
  Remap,
  Stress,
  Checks,
  Count
};

inline const char* stage_name(Stage s) {
  static constexpr const char* kNames[] = {
      "reset", "stencils",          "time step",   "contact fields", "particles to grid",
      "nodes", "grid to particles", "MUSL re-map", "stress",         "checks and sorting"};
  return kNames[static_cast<int>(s)];
}

class StageTimer {
 public:
  // Ends the stage that began at the last lap (or at start) and charges it to `s`.
  void lap(Stage s) {
    if (!on_) return;
    const double now = omp_get_wtime();
    seconds_[static_cast<int>(s)] += now - since_;
    seen_[static_cast<int>(s)] = true;
    since_ = now;
  }
  void start(bool on) {
    on_ = on;
    if (on_) since_ = omp_get_wtime();
  }
  // The stages timed so far, in step order.
  std::vector<std::pair<const char*, double>> times() const {
    std::vector<std::pair<const char*, double>> out;
    for (int s = 0; s < static_cast<int>(Stage::Count); ++s)
      if (seen_[s]) out.emplace_back(stage_name(static_cast<Stage>(s)), seconds_[s]);
    return out;
  }

 private:
  bool on_ = false;
  double since_ = 0.0;
  std::array<double, static_cast<int>(Stage::Count)> seconds_{};
  std::array<bool, static_cast<int>(Stage::Count)> seen_{};
};

}  // namespace seismpm
