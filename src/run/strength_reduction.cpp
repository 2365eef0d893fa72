#include "strength_reduction.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include "core/error.hpp"
#include "core/local_damping.hpp"
#include "gravity_phase.hpp"
#include "io/output.hpp"
#include "io/vtu_writer.hpp"
#include "simulation.hpp"

namespace seismpm {

namespace {

void check_settings(const StrengthReductionSettings& s) {
  if (!(s.srf_low > 0.0 && std::isfinite(s.srf_low))) throw InputError("srf: the lower end must be > 0");
  if (!(s.srf_high > s.srf_low && std::isfinite(s.srf_high)))
    throw InputError("srf: the upper end must be larger than the lower end");
  if (!(s.tolerance > 0.0)) throw InputError("tolerance must be > 0 (on the SRF)");
  if (!(s.damping >= 0.0 && s.damping < 1.0)) throw InputError("damping must be in [0, 1)");
  if (!(s.equilibrium > 0.0 && s.equilibrium < 1.0)) throw InputError("equilibrium must be in (0, 1)");
  if (!(s.max_time > 0.0 && std::isfinite(s.max_time))) throw InputError("max_time must be > 0 (s)");
  if (!(s.max_displacement >= 0.0 && std::isfinite(s.max_displacement)))
    throw InputError("max_displacement must be >= 0 (m; 0: a tenth of the slope's height)");
}

template <int Dim>
bool deformable(const Model<Dim>& m, std::size_t p) {
  return !m.bodies()[m.particles().body[p]].rigid;
}

// The deformable bodies' extent along gravity: the height a displacement limit is a fraction of.
template <int Dim>
double height_along_gravity(const Model<Dim>& model) {
  const Vec<Dim> g = model.settings().gravity;
  if (!(g.norm() > 0.0)) throw InputError("strength reduction needs gravity (the model's gravity is zero)");
  const Vec<Dim> down = g / g.norm();
  double lo = INFINITY, hi = -INFINITY;
  const auto& P = model.particles();
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (!deformable(model, p)) continue;
    const double d = P.x[p].dot(down);
    lo = std::min(lo, d), hi = std::max(hi, d);
  }
  if (!(hi >= lo)) throw InputError("strength reduction: the model has no deformable particles");
  return hi - lo;
}

template <int Dim>
double largest_displacement(const Model<Dim>& model) {
  const auto& P = model.particles();
  double largest = 0.0;
  for (std::size_t p = 0; p < P.size(); ++p)
    if (deformable(model, p)) largest = std::max(largest, P.u[p].squaredNorm());
  return std::sqrt(largest);
}

// Each material's own strength, and the reduced copies for one SRF.
class Strengths {
 public:
  template <int Dim>
  explicit Strengths(const Model<Dim>& model) {
    bool any = false;
    for (int i = 0; i < model.material_count(); ++i) {
      // The model shares its materials; a trial's copy only swaps them, so the user's stay untouched.
      original_.push_back(&model.material(i));
      any = any || model.material(i).with_reduced_strength(1.0) != nullptr;
    }
    if (!any)
      throw InputError(
          "strength reduction: the model has no material with a frictional strength (mohr_coulomb, drucker_prager)");
  }
  template <int Dim>
  void reduce(Model<Dim>& model, double srf) const {
    for (std::size_t i = 0; i < original_.size(); ++i)
      if (auto reduced = original_[i]->with_reduced_strength(srf)) model.replace_material(static_cast<int>(i), reduced);
  }

 private:
  std::vector<const Material*> original_;
};

// One trial: a damped phase with rigid bodies at rest from `start`'s state with strengths divided by srf.
template <int Dim>
class Trial {
 public:
  Trial(const Model<Dim>& start, const Strengths& strengths, double srf) : model_(start.copy_without_fixes()) {
    strengths.reduce(model_, srf);
    record_.srf = srf;
  }
  // `limit`: the displacement that ends it as failed (infinite: none); `peak`: the kinetic energy the
  // equilibrium ratio is measured against at least (the initial-stress trial's peak; 0: its own).
  void run(const StrengthReductionSettings& s, double limit, double peak);
  double peak_energy() const { return peak_energy_; }
  const StrengthReductionTrial& record() const { return record_; }
  Model<Dim>& model() { return model_; }

 private:
  TrialEnd steps_until_an_end(const StrengthReductionSettings& s, double limit, EquilibriumMonitor<Dim>& equilibrium,
                              Progress& progress);

  Model<Dim> model_;
  StrengthReductionTrial record_;
  double peak_energy_ = 0.0;
};

template <int Dim>
void Trial<Dim>::run(const StrengthReductionSettings& s, double limit, double peak) {
  model_.begin_phase(false);
  auto damping = std::make_shared<LocalDamping<Dim>>(s.damping);
  model_.add_fix(damping);
  model_.set_balance_measure(true);
  EquilibriumMonitor<Dim> equilibrium(s.equilibrium, peak);
  Progress progress(stderr, s.progress);
  char label[64];
  std::snprintf(label, sizeof label, "srf %.4g", record_.srf);
  const double t0 = model_.time();
  const long n0 = model_.steps();
  progress.start(label, t0, t0 + s.max_time, model_.particles().size(), n0, true);
  try {
    record_.end = steps_until_an_end(s, limit, equilibrium, progress);
  } catch (const SimulationError& e) {
    record_.end = TrialEnd::Error;
    record_.error = e.what();
  }
  model_.set_balance_measure(false);
  model_.remove_fix(damping.get());
  record_.holds = record_.end == TrialEnd::Equilibrium;
  record_.displacement = largest_displacement(model_);
  record_.kinetic_energy = model_.kinetic_energy();
  record_.time = model_.time() - t0;
  record_.steps = model_.steps() - n0;
  record_.force_ratio = equilibrium.force_ratio();
  record_.energy_ratio = equilibrium.energy_ratio();
  peak_energy_ = equilibrium.peak_energy();
  progress.finish(model_.time(), model_.steps(), record_.holds ? "holds" : "fails");
}

template <int Dim>
TrialEnd Trial<Dim>::steps_until_an_end(const StrengthReductionSettings& s, double limit,
                                        EquilibriumMonitor<Dim>& equilibrium, Progress& progress) {
  const double end = model_.time() + s.max_time;
  while (end - model_.time() > 1e-9 * s.max_time) {
    if (s.interrupt && s.interrupt->load()) {
      progress.finish(model_.time(), model_.steps(), "interrupted");
      throw RunInterrupted("strength reduction interrupted (Ctrl-C); the model is as it was");
    }
    model_.step(end - model_.time());
    equilibrium.update(model_);
    progress.update(model_.time(), model_.steps(), model_.dt(), equilibrium_text(equilibrium));
    if (equilibrium.reached()) return TrialEnd::Equilibrium;
    if (largest_displacement(model_) > limit) return TrialEnd::Displacement;
  }
  return TrialEnd::MaxTime;
}

void report(const StrengthReductionSettings& s, const StrengthReductionTrial& t, double lo, double hi) {
  if (s.progress == Progress::Mode::Quiet) return;
  std::fprintf(stderr,
               "strength reduction: srf %.4f %s (%s after %.3g s, %ld steps; largest displacement %.3g m); "
               "factor of safety in [%.4f, %.4f]\n",
               t.srf, t.holds ? "holds" : "fails", to_string(t.end), t.time, t.steps, t.displacement, lo, hi);
}

std::string srf_text(double srf) {
  std::ostringstream os;
  os << srf;
  return os.str();
}

// The initial-stress trial at srf_low: the start of every other trial, with displacements reset.
template <int Dim>
std::unique_ptr<Model<Dim>> reference_state(const Model<Dim>& model, const Strengths& strengths,
                                            const StrengthReductionSettings& s, StrengthReductionResult& result,
                                            double& peak) {
  Trial<Dim> trial(model, strengths, s.srf_low);
  trial.run(s, INFINITY, 0.0);  // the self-weight's own settlement is no mechanism
  result.trials.push_back(trial.record());
  report(s, trial.record(), s.srf_low, s.srf_high);
  if (!trial.record().holds) {
    std::string why = trial.record().end == TrialEnd::Error ? ": " + trial.record().error : "";
    throw InputError(
        "strength reduction: the slope does not reach equilibrium at srf = " + srf_text(s.srf_low) + " (" +
        to_string(trial.record().end) + why +
        "): the factor of safety is below it; give srf = {lo, hi} with a smaller lo, or a longer max_time");
  }
  trial.model().particles().reset_kinematics();
  peak = trial.peak_energy();
  return std::make_unique<Model<Dim>>(std::move(trial.model()));
}

template <int Dim>
void write_mechanism(const Model<Dim>& model, const std::string& path, double srf) {
  write_particles_vtu<Dim>(path, model.particles(), all_vtu_arrays(),
                           particle_meta(model, "strength_reduction srf=" + srf_text(srf)),
                           [&](std::size_t p) { return deformable(model, p); });
}

}  // namespace

const char* to_string(TrialEnd end) {
  switch (end) {
    case TrialEnd::Equilibrium:
      return "equilibrium";
    case TrialEnd::MaxTime:
      return "max_time";
    case TrialEnd::Displacement:
      return "max_displacement";
    case TrialEnd::Error:
      return "error";
  }
  return "?";
}

std::string strength_reduction_criterion() {
  return "a trial holds when its damped phase reaches static equilibrium (out-of-balance force and kinetic energy "
         "ratios below the equilibrium tolerance) within max_time while no deformable particle moves farther than "
         "max_displacement from its start; it fails when max_time passes first, when a particle moves farther "
         "(a slide), or when a step cannot go on";
}

template <int Dim>
StrengthReductionResult strength_reduction(const Model<Dim>& model, const StrengthReductionSettings& s) {
  check_settings(s);
  if (model.particles().size() == 0) throw InputError("strength reduction: the model has no particles");
  const Strengths strengths(model);
  StrengthReductionResult result;
  result.max_displacement = s.max_displacement > 0.0 ? s.max_displacement : 0.1 * height_along_gravity(model);
  // A trial starts at rest and its own kinetic peak is tiny: its kinetic energy is measured against
  // the peak of the initial-stress trial (the scale of the self-weight's motion).
  double peak = 0.0;
  const auto reference = reference_state(model, strengths, s, result, peak);
  double lo = s.srf_low, hi = s.srf_high;
  std::unique_ptr<Model<Dim>> mechanism;  // the end of the failing trial at the smallest SRF so far
  auto attempt = [&](double srf) {
    Trial<Dim> trial(*reference, strengths, srf);
    trial.run(s, result.max_displacement, peak);
    result.trials.push_back(trial.record());
    if (trial.record().holds)
      lo = srf;
    else {
      hi = srf;
      if (!s.mechanism_file.empty()) mechanism = std::make_unique<Model<Dim>>(std::move(trial.model()));
    }
    report(s, trial.record(), lo, hi);
  };
  attempt(s.srf_high);
  if (result.trials.back().holds)
    throw InputError("strength reduction: the slope still holds at srf = " + srf_text(s.srf_high) +
                     ": the factor of safety is above it; give srf = {lo, hi} with a larger hi");
  while (hi - lo > s.tolerance) attempt(0.5 * (lo + hi));
  result.holds = lo;
  result.fails = hi;
  result.fos = 0.5 * (lo + hi);
  if (mechanism) {
    write_mechanism(*mechanism, s.mechanism_file, hi);
    result.mechanism_file = s.mechanism_file;
  }
  return result;
}

template StrengthReductionResult strength_reduction<2>(const Model<2>&, const StrengthReductionSettings&);
template StrengthReductionResult strength_reduction<3>(const Model<3>&, const StrengthReductionSettings&);

}  // namespace seismpm
