// A control point: follows one particle (by its stable id) and records every particle field whenever
// it is sampled, in memory, with the phase it was sampled in and the time since that phase began. A
// probe made relative to a reference (another probe's particle, or a body) also records its
// displacement less the reference's: ux_rel, uy_rel (uz_rel). When to sample is the simulation's
// business (src/run: its event schedule samples each probe every so many seconds and at the end of
// every run).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/particle_fields.hpp"
#include "core/types.hpp"

namespace seismpm {

template <int Dim>
class Model;

template <int Dim>
class CheckpointAccess;  // reads and restores the private state (src/run/checkpoint.cpp)

// What a probe's displacement is also measured against. A particle's u is its displacement since it
// was made or since the last reset (the end of a gravity phase); the reference's displacement is
// measured the same way, so that ux_rel = 0 for two points that moved together since then: another
// probe's particle: its u; a body: the mass-weighted mean of its particles' u (the displacement of its
// centroid; a rigid body's own displacement).
struct ProbeRelativeTo {
  enum class Kind : std::uint8_t { None = 0, Particle = 1, Body = 2 };
  Kind kind = Kind::None;
  int index = -1;    // Particle: the particle's id; Body: the body's index
  std::string what;  // for messages and the probe's description: "probe 'base'", "body 'rock'"
  bool active() const { return kind != Kind::None; }
};

// The reference's displacement now (m). Throws InputError for a body without particles.
template <int Dim>
Vec<Dim> reference_displacement(const Model<Dim>& model, const ProbeRelativeTo& reference);

// The names of the relative columns: "ux_rel", "uy_rel" (, "uz_rel"); and the component a name is
// (0 for "ux_rel"), none for any other name.
std::vector<std::string> relative_field_names(int dim);
std::optional<int> parse_relative_field(std::string_view name, int dim);

template <int Dim>
class Probe {
 public:
  // Throws InputError when the model has no particle with that id, or the reference is not valid;
  // takes the first sample now, in phase `phase` ("run", "gravity", "dynamic").
  Probe(const Model<Dim>& model, std::string name, int particle_id, const std::string& phase = "run",
        ProbeRelativeTo relative_to = {});
  std::string_view name() const { return name_; }
  int particle_id() const { return id_; }
  const ProbeRelativeTo& relative_to() const { return relative_; }
  // Records every field of the particle now (once per model time: a second call at the same time is a no-op).
  void sample(const Model<Dim>& model, const std::string& phase);
  const std::vector<double>& times() const { return times_; }
  std::vector<double> series(Field f) const;
  std::size_t samples() const { return times_.size(); }
  // The phase of sample k and the time since that phase began (s; NaN when not known: a checkpoint of
  // an older version).
  const std::string& phase(std::size_t k) const;
  double phase_time(std::size_t k) const { return phase_times_[k]; }
  // The displacement relative to the reference, component d: now, and as recorded. Throws
  // InputError naming the probe when it has no reference.
  double relative_now(const Model<Dim>& model, int d) const;
  std::vector<double> relative_series(int d) const;

 private:
  template <int>
  friend class CheckpointAccess;
  void require_relative(int d) const;
  std::string name_;
  int id_;
  ProbeRelativeTo relative_;
  std::vector<Field> fields_;
  std::vector<double> times_;
  std::vector<double> values_;       // samples x fields
  std::vector<double> phase_times_;  // per sample
  // The phase of the samples from `first` on, up to the next entry's first: (first, phase).
  std::vector<std::pair<std::size_t, std::string>> phases_;
  std::vector<double> relative_values_;  // samples x Dim (empty without a reference)
};

extern template class Probe<2>;
extern template class Probe<3>;

}  // namespace seismpm
