// A simulation: the model and what a run adds to it (probes, the output directory, the local damping,
// the current phase's name), with ONE event schedule that every step lands on: output times, probe
// samples, a run's periodic call, the run's end. Runs and calculation phases live here; the Lua layer
// reads arguments and calls them, and C++ tests and examples use them as they are.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/edge_boundary.hpp"
#include "core/local_damping.hpp"
#include "core/model.hpp"
#include "event_schedule.hpp"
#include "gravity_phase.hpp"
#include "io/output.hpp"
#include "io/probe.hpp"
#include "io/progress.hpp"

namespace seismpm {

// A function a run calls every `every` s of simulated time (hit exactly) and at its end, between steps;
// the run ends when it returns true. It may not run the simulation itself.
struct RunCall {
  double every = 0.0;  // s; 0: no call
  std::function<bool()> function;
  bool active() const { return every > 0.0; }
};

// How a run ended.
enum class RunEnd {
  Completed,  // its duration (or its number of steps) is done
  Reached,    // its end criterion was met (the gravity phase: equilibrium)
  ByCall,     // its call returned true
};

// What a run is: a checkpoint written during one records it, and resume() after a restore finishes it.
enum class RunKind : std::uint8_t {
  Run,      // a duration in the current phase (m:run)
  Steps,    // a number of steps (m:step)
  Gravity,  // a gravity phase: to equilibrium, then the reset of displacements
  Dynamic,  // a dynamic phase: its duration
};

// What resume() finished: how the run ended and, for a gravity phase, its result.
struct ResumedRun {
  RunKind kind;
  RunEnd how;
  std::optional<GravityPhaseResult> gravity;
};

template <int Dim>
class CheckpointAccess;

// A run stopped by its interrupt flag (Ctrl-C) before a step; the model is intact, as after any step.
class RunInterrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

template <int Dim>
class Simulation {
 public:
  explicit Simulation(const ModelSettings<Dim>& settings) : model_(settings) {}
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  Model<Dim>& model() { return model_; }
  const Model<Dim>& model() const { return model_; }

  // --- what runs record ---
  // A control point on the particle created as number `particle_id`: sampled now, every `every` s
  // (0: every step) and at the end of every run; with a reference, it also records its displacement
  // relative to it (ux_rel, ...).
  std::shared_ptr<Probe<Dim>> add_probe(const std::string& name, int particle_id, double every,
                                        ProbeRelativeTo relative_to = {});
  const std::vector<std::shared_ptr<Probe<Dim>>>& probes() const { return probes_; }
  double probe_every(const Probe<Dim>& probe) const;
  void set_probe_every(double every);  // every probe's interval, from its last sample on
  // The output directory: written now, every settings.every s, and (at_run_end) at the end of each run.
  void set_output(const OutputSettings& settings, bool at_run_end = true);
  const Output<Dim>* output() const { return output_.get(); }
  // Samples the probes and writes the current state, unless it is on file already.
  void write();
  // probes.csv up to date with the probes' samples (before plotting it).
  void write_probes();

  // --- the ground beyond the model ---
  // An absorbing, compliant or free-field edge (one per side; not on a side held by Grid::fix). It holds
  // like a fixity while a gravity phase runs and acts in every other run. A free-field side's column
  // stands on the base's boundary when there is one.
  std::shared_ptr<EdgeBoundary<Dim>> add_boundary(const BoundarySettings<Dim>& settings);
  const std::vector<std::shared_ptr<EdgeBoundary<Dim>>>& boundaries() const { return boundaries_; }
  // Holds (true) or releases the boundaries' edges as fixities. The gravity phase does it itself; a
  // static analysis on a copy of the model (strength reduction) needs them held too, else its ground
  // stands on nothing.
  void hold_boundaries(bool hold);

  // --- how runs behave ---
  // The local damping coefficient for this and later runs (in [0, 1)).
  void set_damping(double alpha);
  // The progress display of runs (on stderr); quiet unless set.
  void set_progress(Progress::Mode mode) { progress_mode_ = mode; }
  // A run stops with RunInterrupted before the next step once *flag is true (Ctrl-C); null: never.
  void set_interrupt(const std::atomic<bool>* flag) { interrupt_ = flag; }
  // "run" before any phase, then "gravity" or "dynamic"; written into every output file.
  const std::string& phase() const { return phase_; }
  // True while a run steps (its call is being made): another run may not start.
  bool running() const { return running_; }

  // --- runs and phases ---
  // Continues the current phase for `duration` s.
  RunEnd run(double duration, const RunCall& call = {});
  // Takes n steps (the end of a number of steps is not written to the output).
  void step(long n);
  // Self-weight with rigid bodies at rest and local damping until static equilibrium; displacements
  // and strains reset at its end. Throws SimulationError when max_time passes first.
  GravityPhaseResult gravity_phase(const GravityPhaseSettings& settings);
  // Shaking: rigid bodies follow their histories, read at the phase time, which starts now.
  RunEnd dynamic_phase(double duration, double damping, const RunCall& call = {});

  // --- checkpoints (written and read by src/run/checkpoint.hpp) ---
  // During runs, after a step, a checkpoint to `path` once `every` s of wall time have passed since the
  // last one (or since this call); `due`, when given, decides instead (a test's own rule). every = 0
  // and no `due`: none.
  void set_periodic_checkpoint(const std::string& path, double every, std::function<bool()> due = {});
  const std::string& checkpoint_path() const { return checkpoint_path_; }
  double checkpoint_every() const { return checkpoint_every_; }
  // Restored from a checkpoint written during a run: that run, not finished yet. It is dropped when
  // another run or phase starts.
  bool has_interrupted_run() const { return interrupted_.has_value(); }
  std::optional<RunKind> interrupted_run() const;
  // The interrupted run's call interval (s; 0: it had no call).
  double interrupted_call_every() const;
  // Finishes the interrupted run the way it would have gone on: to its end time or its number of steps,
  // a gravity phase to equilibrium (or its max_time error) with the reset at its end, landing on the
  // same events. A run that had a call needs it again, with the same interval. Throws InputError
  // without an interrupted run.
  ResumedRun resume(const RunCall& call = {});

 private:
  template <int>
  friend class CheckpointAccess;
  // One run: up to `duration` s or `max_steps` steps, or until `done()` says so after a step.
  struct RunSpec {
    double duration;
    long max_steps = std::numeric_limits<long>::max();
    bool final_output = true;                 // the end of the run on file (when at_run_end)
    std::function<bool()> done = {};          // the end criterion; none: the run ends at its duration
    std::function<std::string()> extra = {};  // more text for the progress line
    const RunCall* call = nullptr;
    RunKind kind = RunKind::Run;
  };
  // The run in progress, as far as it has come (what a checkpoint written during it saves).
  struct ActiveRun {
    RunKind kind = RunKind::Run;
    double start = 0.0, duration = 0.0;
    long max_steps = std::numeric_limits<long>::max();
    long taken = 0;  // steps so far
    bool final_output = true;
    EventSchedule::Stream call = -1;  // its call's stream in the schedule (-1: none)
  };
  // The gravity phase in progress: its settings, where it started and its equilibrium monitor.
  struct GravityRun {
    GravityPhaseSettings settings;
    double start_time = 0.0;
    long start_steps = 0;
    EquilibriumMonitor<Dim> equilibrium;
  };
  // `resumed`: an interrupted run to go on with instead of a new one.
  RunEnd run_for(const RunSpec& spec, const ActiveRun* resumed = nullptr);
  GravityPhaseResult run_gravity_phase(const ActiveRun* resumed);
  void drop_interrupted_run();
  void checkpoint_if_due();
  // Throws InputError for an output or probe interval shorter than the time step.
  void check_intervals() const;
  RunEnd after_step(const RunSpec& spec, EventSchedule::Stream call, Progress& progress);
  void finish_run(const RunSpec& spec, RunEnd how, Progress& progress);
  void stop_if_interrupted(Progress& progress) const;
  void sample_probe(std::size_t k);
  void write_output();
  void begin_phase(const char* name, bool rigid_bodies_move);
  // Free-field columns stand on the base's boundary (the lower edge of the vertical axis).
  void link_boundaries();

  Model<Dim> model_;
  EventSchedule schedule_;
  std::vector<std::shared_ptr<Probe<Dim>>> probes_;
  std::vector<EventSchedule::Stream> probe_streams_;  // per probe
  std::unique_ptr<Output<Dim>> output_;
  EventSchedule::Stream output_stream_ = -1;
  bool write_at_run_end_ = true;
  std::shared_ptr<LocalDamping<Dim>> damping_;  // attached on first use
  std::vector<std::shared_ptr<EdgeBoundary<Dim>>> boundaries_;
  std::string phase_ = "run";
  Progress::Mode progress_mode_ = Progress::Mode::Quiet;
  const std::atomic<bool>* interrupt_ = nullptr;
  bool running_ = false;
  ActiveRun active_;                      // while running_
  std::optional<GravityRun> gravity_;     // while a gravity phase runs, or is interrupted
  std::optional<ActiveRun> interrupted_;  // restored from a checkpoint written during a run
  std::string checkpoint_path_;
  double checkpoint_every_ = 0.0;  // s of wall time
  std::function<bool()> checkpoint_due_;
  std::chrono::steady_clock::time_point last_checkpoint_;
};

extern template class Simulation<2>;
extern template class Simulation<3>;

}  // namespace seismpm
