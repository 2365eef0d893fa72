// A control point: follows one particle (by its stable id) and records every particle field whenever
// it is sampled, in memory. When it is sampled is the simulation's business (src/run: its event
// schedule samples each probe every so many seconds and at the end of every run).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/particle_fields.hpp"

namespace seismpm {

template <int Dim>
class Model;

template <int Dim>
class CheckpointAccess;  // reads and restores the private state (src/run/checkpoint.cpp)

template <int Dim>
class Probe {
 public:
  // Throws InputError when the model has no particle with that id; takes the first sample now.
  Probe(const Model<Dim>& model, std::string name, int particle_id);
  std::string_view name() const { return name_; }
  int particle_id() const { return id_; }
  // Records every field of the particle now (once per model time: a second call at the same time is a no-op).
  void sample(const Model<Dim>& model);
  const std::vector<double>& times() const { return times_; }
  std::vector<double> series(Field f) const;
  std::size_t samples() const { return times_.size(); }

 private:
  template <int>
  friend class CheckpointAccess;
  std::string name_;
  int id_;
  std::vector<Field> fields_;
  std::vector<double> times_;
  std::vector<double> values_;  // samples x fields
};

extern template class Probe<2>;
extern template class Probe<3>;

}  // namespace seismpm
