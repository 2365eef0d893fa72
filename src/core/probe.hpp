// A control point: follows one particle (by its stable id) and records every particle field at a
// fixed interval of simulated time, in memory. Attached as a fix, sampling after a step.
#pragma once

#include <string>
#include <vector>

#include "fix.hpp"
#include "particle_fields.hpp"

namespace seismpm {

template <int Dim>
class Probe : public Fix<Dim> {
 public:
  // every: sampling interval in seconds of simulated time (0: every step).
  Probe(const Model<Dim>& model, std::string name, int particle_id, double every);
  std::string_view name() const override { return name_; }
  void after_step(Model<Dim>& model, const StepContext& c) override;

  int particle_id() const { return id_; }
  double every() const { return every_; }
  void set_every(double every) { every_ = every; }
  // The next sampling time, on the grid k * every (infinity when sampling every step).
  double next_sample_time() const;
  // Records now, whatever the interval (start and end of runs).
  void sample(const Model<Dim>& model);
  const std::vector<double>& times() const { return times_; }
  std::vector<double> series(Field f) const;
  std::size_t samples() const { return times_.size(); }

 private:
  std::string name_;
  int id_;
  double every_;
  std::vector<Field> fields_;
  std::vector<double> times_;
  std::vector<double> values_;  // samples x fields
};

extern template class Probe<2>;
extern template class Probe<3>;

}  // namespace seismpm
