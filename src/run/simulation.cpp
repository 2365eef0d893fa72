#include "simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "checkpoint.hpp"
#include "core/error.hpp"

namespace seismpm {

namespace {

// Sets a flag for as long as it lives: a run's `running` state, cleared however the run ends.
struct FlagScope {
  explicit FlagScope(bool& f) : flag(f) { flag = true; }
  ~FlagScope() { flag = false; }
  FlagScope(const FlagScope&) = delete;
  FlagScope& operator=(const FlagScope&) = delete;
  bool& flag;
};

// A run's part of the schedule (its end, its call's times), removed however the run ends. A resumed
// run brings its call's stream along; a new one gets its stream here.
struct RunScope {
  RunScope(EventSchedule& s, double start, double duration, EventSchedule::Stream& run_call, const RunCall* call)
      : schedule(s), stream(run_call) {
    schedule.begin_run(start, duration);
    if (stream < 0 && call && call->active())
      stream = schedule.add(EventSchedule::Spacing::FromStart, call->every, start);
  }
  ~RunScope() {
    if (stream >= 0) schedule.remove(stream);
    stream = -1;
    schedule.end_run();
  }
  RunScope(const RunScope&) = delete;
  RunScope& operator=(const RunScope&) = delete;
  EventSchedule& schedule;
  EventSchedule::Stream& stream;
};

}  // namespace

// --- what runs record ---

template <int Dim>
std::shared_ptr<Probe<Dim>> Simulation<Dim>::add_probe(const std::string& name, int particle_id, double every,
                                                       ProbeRelativeTo relative_to) {
  if (!(every >= 0.0)) throw InputError("probe '" + name + "': every must be >= 0 (s)");
  auto probe = std::make_shared<Probe<Dim>>(model_, name, particle_id, phase_, std::move(relative_to));  // sampled
  const auto stream = schedule_.add(EventSchedule::Spacing::Multiples, every, 0.0);
  schedule_.fired(stream, model_.time());
  probes_.push_back(probe);
  probe_streams_.push_back(stream);
  return probe;
}

template <int Dim>
double Simulation<Dim>::probe_every(const Probe<Dim>& probe) const {
  for (std::size_t k = 0; k < probes_.size(); ++k)
    if (probes_[k].get() == &probe) return schedule_.every(probe_streams_[k]);
  throw std::invalid_argument("probe '" + std::string(probe.name()) + "' belongs to another simulation");
}

template <int Dim>
void Simulation<Dim>::set_probe_every(double every) {
  if (!(every >= 0.0)) throw InputError("probe_every must be >= 0 (s)");
  for (std::size_t k = 0; k < probes_.size(); ++k) {
    schedule_.remove(probe_streams_[k]);
    probe_streams_[k] = schedule_.add(EventSchedule::Spacing::Multiples, every, 0.0);
    schedule_.fired(probe_streams_[k], probes_[k]->times().back());  // counted on from the last sample
  }
}

template <int Dim>
void Simulation<Dim>::set_output(const OutputSettings& settings, bool at_run_end) {
  auto output = std::make_unique<Output<Dim>>(settings);  // creates the directory, or throws naming it
  output_ = std::move(output);
  write_at_run_end_ = at_run_end;
  if (output_stream_ >= 0) schedule_.remove(output_stream_);
  // Output times run from t = 0 whenever the output starts; the state as it is now goes first.
  output_stream_ = schedule_.add(EventSchedule::Spacing::Running, settings.every, 0.0);
  write_output();
}

template <int Dim>
void Simulation<Dim>::write() {
  if (!output_) throw InputError("no output directory yet");
  for (std::size_t k = 0; k < probes_.size(); ++k) sample_probe(k);
  if (output_->behind(model_.time())) write_output();
}

template <int Dim>
void Simulation<Dim>::write_probes() {
  if (!output_) throw InputError("no output directory yet");
  output_->note_phase(phase_, model_.time() - model_.phase_time());
  output_->write_probes(probes_);
}

template <int Dim>
void Simulation<Dim>::sample_probe(std::size_t k) {
  probes_[k]->sample(model_, phase_);
  schedule_.fired(probe_streams_[k], model_.time());
}

template <int Dim>
void Simulation<Dim>::write_output() {
  output_->write(model_, probes_, phase_);
  schedule_.fired(output_stream_, model_.time());
}

template <int Dim>
void Simulation<Dim>::set_damping(double alpha) {
  if (!damping_) {
    damping_ = std::make_shared<LocalDamping<Dim>>(0.0);
    model_.add_fix(damping_);
  }
  damping_->set_alpha(alpha);
}

template <int Dim>
std::shared_ptr<EdgeBoundary<Dim>> Simulation<Dim>::add_boundary(const BoundarySettings<Dim>& settings) {
  if (running_) throw std::logic_error("a run's call may not add a boundary");
  for (const auto& b : boundaries_)
    if (b->settings().side == settings.side) throw InputError("boundary: that side has a boundary already");
  if (model_.grid().held_on(settings.side) != 0)
    throw InputError("boundary: that side is held by m:fix; an edge is either fixed or a boundary");
  auto boundary = std::make_shared<EdgeBoundary<Dim>>(model_.grid(), settings);
  if (gravity_) boundary->hold(model_.grid());  // added while a gravity phase is interrupted
  model_.add_fix(boundary);
  boundaries_.push_back(boundary);
  link_boundaries();
  return boundary;
}

template <int Dim>
void Simulation<Dim>::link_boundaries() {
  std::shared_ptr<const EdgeBoundary<Dim>> base;
  for (const auto& b : boundaries_)
    if (b->settings().side == static_cast<Side>(2 * (Dim - 1))) base = b;
  for (const auto& b : boundaries_)
    if (b->settings().kind == BoundaryKind::FreeField) b->set_column_base(base);
}

// While a gravity phase runs, the boundaries hold their edges as fixities and record the reactions.
template <int Dim>
void Simulation<Dim>::hold_boundaries(bool hold) {
  for (const auto& b : boundaries_) hold ? b->hold(model_.grid()) : b->release(model_.grid());
}

// --- runs and phases ---

template <int Dim>
RunEnd Simulation<Dim>::run(double duration, const RunCall& call) {
  RunSpec spec{duration};
  spec.call = &call;
  return run_for(spec);
}

template <int Dim>
void Simulation<Dim>::step(long n) {
  RunSpec spec{std::numeric_limits<double>::infinity(), n, false};
  spec.kind = RunKind::Steps;
  run_for(spec);
}

template <int Dim>
GravityPhaseResult Simulation<Dim>::gravity_phase(const GravityPhaseSettings& g) {
  if (model_.particles().size() == 0) throw InputError("the model has no particles");
  begin_phase("gravity", false);  // rigid bodies at rest
  set_damping(g.damping);
  if (g.k0 > 0.0) set_k0_stresses(model_, g.k0);
  gravity_.emplace(GravityRun{g, model_.time(), model_.steps(), EquilibriumMonitor<Dim>(g.tolerance)});
  model_.set_balance_measure(true);
  hold_boundaries(true);
  return run_gravity_phase(nullptr);
}

// The gravity phase's run (new, or resumed from a checkpoint) and its end: the equilibrium check and
// the reset of displacements and strains.
template <int Dim>
GravityPhaseResult Simulation<Dim>::run_gravity_phase(const ActiveRun* resumed) {
  RunSpec spec{gravity_->settings.max_time};
  spec.kind = RunKind::Gravity;
  spec.done = [this] {
    gravity_->equilibrium.update(model_);
    return gravity_->equilibrium.reached();
  };
  spec.extra = [this] { return equilibrium_text(gravity_->equilibrium); };
  RunEnd how = RunEnd::Completed;
  try {
    how = run_for(spec, resumed);
  } catch (...) {
    model_.set_balance_measure(false);
    gravity_.reset();
    hold_boundaries(false);
    throw;
  }
  model_.set_balance_measure(false);
  balance_recorded_reactions(model_, boundaries_);  // the supports carry the whole weight from now on
  hold_boundaries(false);
  const GravityRun phase = std::move(*gravity_);
  gravity_.reset();
  const GravityPhaseSettings& g = phase.settings;
  const EquilibriumMonitor<Dim>& equilibrium = phase.equilibrium;
  if (how != RunEnd::Reached) {
    std::ostringstream os;
    os << "no static equilibrium within max_time = " << g.max_time << " s: out-of-balance force "
       << equilibrium.force_ratio() << " of the external force, kinetic energy " << equilibrium.energy_ratio()
       << " of its peak (tolerance " << g.tolerance << "); " << motion_summary(model_)
       << ". Something keeps moving there: a slope steeper than its strength allows, a body without support, or too "
          "short a max_time; the outputs show the state at t = "
       << model_.time() << " s";
    throw SimulationError(os.str());
  }
  // Displacements and strains start from zero in the next phase; stresses and plastic state are kept.
  model_.particles().reset_kinematics();
  const GravityPhaseResult result{model_.time() - phase.start_time, model_.steps() - phase.start_steps,
                                  equilibrium.force_ratio(), equilibrium.energy_ratio()};
  if (progress_mode_ != Progress::Mode::Quiet)
    std::fprintf(stderr, "gravity phase: equilibrium after %.4g s (%ld steps): %s\n", result.time, result.steps,
                 equilibrium_text(equilibrium).c_str());
  return result;
}

template <int Dim>
RunEnd Simulation<Dim>::dynamic_phase(double duration, double damping, const RunCall& call) {
  if (model_.particles().size() == 0) throw InputError("the model has no particles");
  begin_phase("dynamic", true);  // histories start now
  set_damping(damping);
  RunSpec spec{duration};
  spec.call = &call;
  spec.kind = RunKind::Dynamic;
  return run_for(spec);
}

template <int Dim>
void Simulation<Dim>::begin_phase(const char* name, bool rigid_bodies_move) {
  if (running_) throw std::logic_error("a run's call may not start a phase");
  drop_interrupted_run();
  phase_ = name;
  model_.begin_phase(rigid_bodies_move);
}

// --- the run loop ---

// Steps until the run's end (or max_steps, or done() after a step), landing exactly on every event of
// the schedule on the way: probe samples, outputs, the run's call. The end of the run is sampled and,
// for runs and phases, on file.
template <int Dim>
RunEnd Simulation<Dim>::run_for(const RunSpec& spec, const ActiveRun* resumed) {
  if (running_) throw std::logic_error("a run's call may not step the model");
  if (spec.call && spec.call->active() && !spec.call->function) throw InputError("run: a call without a function");
  if (!resumed) drop_interrupted_run();
  check_intervals();
  FlagScope running(running_);
  Progress progress(stderr, progress_mode_);
  active_ =
      resumed ? *resumed : ActiveRun{spec.kind, model_.time(), spec.duration, spec.max_steps, 0, spec.final_output, -1};
  RunScope scope(schedule_, active_.start, active_.duration, active_.call, spec.call);
  progress.start(phase_, model_.time(), schedule_.run_end(), model_.particles().size(), model_.steps(),
                 static_cast<bool>(spec.done));
  RunEnd how = RunEnd::Completed;
  try {
    while (!schedule_.run_over(model_.time()) && active_.taken < active_.max_steps) {
      stop_if_interrupted(progress);
      model_.step(schedule_.next_time() - model_.time());
      ++active_.taken;
      how = after_step(spec, active_.call, progress);
      if (how != RunEnd::Completed) break;
      // Only while the run goes on (a restart takes it up from here); after its last step it is over.
      if (!schedule_.run_over(model_.time()) && active_.taken < active_.max_steps) checkpoint_if_due();
    }
  } catch (const SimulationError&) {
    // The files written so far stay as they are: valid, up to the last output time.
    progress.finish(model_.time(), model_.steps(), "failed");
    throw;
  }
  finish_run(spec, how, progress);
  return how;
}

// An interval below the time step would cut every step short to land on it: the run would crawl at that
// interval and, for files, fill the disk. Refused at the run's start, naming both figures, instead.
template <int Dim>
void Simulation<Dim>::check_intervals() const {
  if (model_.particles().size() == 0) return;
  const double fixed = model_.settings().fixed_dt;
  const double dt = fixed > 0.0 ? fixed : model_.stable_time_step();
  if (!(dt > 0.0) || !std::isfinite(dt)) return;  // the step itself reports a broken state
  auto text = [](double v) {
    std::ostringstream os;
    os.precision(4);
    os << v;
    return os.str();
  };
  if (output_ && output_->settings().every < dt)
    throw InputError("m:output: every = " + text(output_->settings().every) + " s is shorter than the time step (" +
                     text(dt) + " s): every step would be cut short to write a file. Give every >= " + text(dt) + " s");
  for (std::size_t k = 0; k < probes_.size(); ++k) {
    const double every = schedule_.every(probe_streams_[k]);
    if (every > 0.0 && every < dt)
      throw InputError("probe '" + std::string(probes_[k]->name()) + "': every = " + text(every) +
                       " s is shorter than the time step (" + text(dt) +
                       " s): every step would be cut short to sample it. Give every = 0 to sample every step, or "
                       "every >= " +
                       text(dt) + " s");
  }
}

// What a step reached: probe samples, an output, the end criterion, the run's call (at its times and
// at the run's end).
template <int Dim>
RunEnd Simulation<Dim>::after_step(const RunSpec& spec, EventSchedule::Stream call, Progress& progress) {
  const double t = model_.time();
  for (std::size_t k = 0; k < probes_.size(); ++k)
    if (schedule_.reached(probe_streams_[k], t)) sample_probe(k);
  if (output_ && schedule_.reached(output_stream_, t)) write_output();
  const bool done = spec.done && spec.done();
  bool by_call = false;
  if (call >= 0 && (schedule_.reached(call, t) || schedule_.run_over(t))) {
    schedule_.fired(call, t);
    by_call = spec.call->function();
  }
  progress.update(t, model_.steps(), model_.dt(), spec.extra ? spec.extra() : std::string());
  return by_call ? RunEnd::ByCall : done ? RunEnd::Reached : RunEnd::Completed;
}

template <int Dim>
void Simulation<Dim>::finish_run(const RunSpec& spec, RunEnd how, Progress& progress) {
  for (std::size_t k = 0; k < probes_.size(); ++k) sample_probe(k);
  // The end of a run is always on file, so ParaView and probes.csv show the final state.
  if (spec.final_output && write_at_run_end_ && output_ && output_->behind(model_.time())) write_output();
  const char* text = how == RunEnd::ByCall                  ? "stopped by its call"
                     : how == RunEnd::Reached || !spec.done ? "done"
                                                            : "stopped at its time limit";
  progress.finish(model_.time(), model_.steps(), text);
}

template <int Dim>
void Simulation<Dim>::stop_if_interrupted(Progress& progress) const {
  if (!interrupt_ || !interrupt_->load()) return;
  progress.finish(model_.time(), model_.steps(), "interrupted");
  std::ostringstream os;
  os << "interrupted (Ctrl-C) at t = " << model_.time() << " s, step " << model_.steps() << "; the model is intact";
  throw RunInterrupted(os.str());
}

// --- checkpoints ---

template <int Dim>
void Simulation<Dim>::set_periodic_checkpoint(const std::string& path, double every, std::function<bool()> due) {
  if (!(every >= 0.0 && std::isfinite(every))) throw InputError("checkpoint_every must be >= 0 (s of wall time)");
  checkpoint_path_ = path;
  checkpoint_every_ = every;
  checkpoint_due_ = std::move(due);
  last_checkpoint_ = std::chrono::steady_clock::now();
}

template <int Dim>
void Simulation<Dim>::checkpoint_if_due() {
  if (checkpoint_path_.empty() || (checkpoint_every_ <= 0.0 && !checkpoint_due_)) return;
  const auto now = std::chrono::steady_clock::now();
  const bool due = checkpoint_due_ ? checkpoint_due_()
                                   : std::chrono::duration<double>(now - last_checkpoint_).count() >= checkpoint_every_;
  if (!due) return;
  write_checkpoint(*this, checkpoint_path_);
  last_checkpoint_ = std::chrono::steady_clock::now();
}

template <int Dim>
std::optional<RunKind> Simulation<Dim>::interrupted_run() const {
  if (!interrupted_) return std::nullopt;
  return interrupted_->kind;
}

template <int Dim>
double Simulation<Dim>::interrupted_call_every() const {
  return interrupted_ && interrupted_->call >= 0 ? schedule_.every(interrupted_->call) : 0.0;
}

template <int Dim>
void Simulation<Dim>::drop_interrupted_run() {
  if (!interrupted_) return;
  if (interrupted_->call >= 0) schedule_.remove(interrupted_->call);
  schedule_.end_run();
  if (interrupted_->kind == RunKind::Gravity) {
    gravity_.reset();
    model_.set_balance_measure(false);
    hold_boundaries(false);
  }
  interrupted_.reset();
}

template <int Dim>
ResumedRun Simulation<Dim>::resume(const RunCall& call) {
  if (running_) throw std::logic_error("a run's call may not step the model");
  if (!interrupted_)
    throw InputError(
        "there is no interrupted run to finish: the model was not restored from a checkpoint written "
        "during a run, or that run was finished or dropped (give a duration)");
  const double every = interrupted_call_every();
  if (every > 0.0 && !call.active()) {
    std::ostringstream os;
    os << "the interrupted run called a function every " << every << " s; give the call again (every = " << every
       << ")";
    throw InputError(os.str());
  }
  if (every == 0.0 && call.active()) throw InputError("the interrupted run had no call; finish it without one");
  if (every > 0.0 && call.every != every) {
    std::ostringstream os;
    os << "the interrupted run called its function every " << every << " s, not every " << call.every << " s";
    throw InputError(os.str());
  }
  const ActiveRun r = *interrupted_;
  interrupted_.reset();
  if (r.kind == RunKind::Gravity) {
    const GravityPhaseResult g = run_gravity_phase(&r);
    return {r.kind, RunEnd::Reached, g};
  }
  RunSpec spec{r.duration, r.max_steps, r.final_output};
  spec.call = &call;
  spec.kind = r.kind;
  return {r.kind, run_for(spec, &r), std::nullopt};
}

template class Simulation<2>;
template class Simulation<3>;

}  // namespace seismpm
