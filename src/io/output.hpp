// A model's output directory: particles_NNNNNN.vtu at each write, with particles.pvd listing them by
// simulated time (rewritten whole after every file, so it is always valid); rigid bodies in
// rigid_NNNNNN.vtu + rigid.pvd, so they can be hidden; optional grid_NNNNNN.vtu + grid.pvd; and
// probes.csv with every field of every probe; reactions.csv with the mean force of each rigid body on
// the deformable bodies over each output interval. When to write (every `every` seconds, at the end of
// runs) is the simulation's event schedule (src/run).
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/model.hpp"
#include "probe.hpp"
#include "vtu_writer.hpp"

namespace seismpm {

struct OutputSettings {
  std::string dir;
  double every = 0.1;  // s of simulated time between writes (> 0)
  std::vector<VtuArray> arrays = all_vtu_arrays();
  bool grid = false;  // also write the active grid nodes
};

template <int Dim>
class CheckpointAccess;  // reads and restores the private state (src/run/checkpoint.cpp)

template <int Dim>
class Output {
 public:
  // Creates the directory; throws OutputError naming it when that fails.
  explicit Output(OutputSettings settings);
  const OutputSettings& settings() const { return settings_; }
  // True when nothing was written at this time yet.
  bool behind(double time) const { return files_.empty() || files_.back().first < time; }
  // Writes the files for the model's current state. Throws OutputError; files written before stay valid.
  void write(const Model<Dim>& model, const std::vector<std::shared_ptr<Probe<Dim>>>& probes, const std::string& phase);
  int files_written() const { return static_cast<int>(files_.size()); }

 private:
  template <int>
  friend class CheckpointAccess;
  OutputSettings settings_;
  std::vector<std::pair<double, std::string>> files_;  // time, particle file name
  std::vector<std::pair<double, std::string>> grid_files_;
  std::vector<std::pair<double, std::string>> rigid_files_;
  // reactions.csv: its rows so far and the impulses at the last write.
  std::string reactions_;
  double last_time_ = 0.0;
  std::vector<Vec<Dim>> last_impulse_;
  void write_reactions(const Model<Dim>& model, const std::string& phase);
};

// What a particle file says of the model's state beside its arrays: the time, the phase, and the names
// of the material and body indices.
template <int Dim>
VtuMeta particle_meta(const Model<Dim>& model, const std::string& phase);

// The PVD collection text for (time, file) pairs.
std::string pvd_text(const std::vector<std::pair<double, std::string>>& files);
// probes.csv: "time (s)" and "<probe>.<field>" columns; a row per sampled time.
template <int Dim>
std::string probes_csv_text(const std::vector<std::shared_ptr<Probe<Dim>>>& probes);

extern template class Output<2>;
extern template class Output<3>;

}  // namespace seismpm
