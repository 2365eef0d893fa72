// A model's output directory: particles_NNNNNN.vtu at each write, with particles.pvd listing them by
// simulated time (rewritten whole after every file, so it is always valid); rigid bodies in
// rigid_NNNNNN.vtu + rigid.pvd, so they can be hidden; optional grid_NNNNNN.vtu + grid.pvd; and
// probes.csv with every field of every probe; reactions.csv with the mean force of each rigid body on
// the deformable bodies over each output interval; phases.csv with the model time at which each phase
// began (src/io/phases_file.hpp); with the first particle file, open_in_paraview.py, which opens the run
// in ParaView (src/io/paraview_script.hpp). The two tables are written whole once, then only their new
// rows are appended (a run's cost stays linear in its length). The directory is locked for as long as
// the Output lives (DirectoryLock). When to write (every `every` seconds, at the end of
// runs) is the simulation's event schedule (src/run).
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/model.hpp"
#include "directory_lock.hpp"
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
  // Creates and locks the directory; throws OutputError naming it when that fails or another process
  // writes there.
  explicit Output(OutputSettings settings);
  const OutputSettings& settings() const { return settings_; }
  // True when nothing was written at this time yet.
  bool behind(double time) const { return files_.empty() || files_.back().first < time; }
  // Writes the files for the model's current state. Throws OutputError; files written before stay valid.
  void write(const Model<Dim>& model, const std::vector<std::shared_ptr<Probe<Dim>>>& probes, const std::string& phase);
  int files_written() const { return static_cast<int>(files_.size()); }
  // Brings probes.csv up to date with the probes' samples: appends the rows not on file yet.
  void write_probes(const std::vector<std::shared_ptr<Probe<Dim>>>& probes);
  // Puts the phase in progress, begun at model time `start`, in phases.csv (unless it is there).
  void note_phase(const std::string& phase, double start);
  // Writes probes.csv and reactions.csv whole (atomically) from the state in memory: the probes'
  // samples and the reaction rows kept here. After a restart from a checkpoint this drops the rows
  // written after it; appending goes on from there.
  void rewrite_tables(const std::vector<std::shared_ptr<Probe<Dim>>>& probes);

 private:
  template <int>
  friend class CheckpointAccess;
  OutputSettings settings_;
  DirectoryLock lock_;
  // What is on file, in plain members so that a checkpoint can save and restore them.
  std::vector<std::pair<double, std::string>> files_;  // time, particle file name
  std::vector<std::pair<double, std::string>> grid_files_;
  std::vector<std::pair<double, std::string>> rigid_files_;
  // reactions.csv: its text so far (a row per output) and the impulses at the last write.
  std::string reactions_;
  double last_time_ = 0.0;
  std::vector<Vec<Dim>> last_impulse_;
  // probes.csv: its header line ("" before the first write), the samples of each probe on file, its
  // size in bytes and where its last row starts (a probe sampled later at that row's time fills the
  // row in: the row is written again).
  std::string probes_header_;
  std::vector<std::size_t> probe_samples_written_;
  std::uint64_t probes_bytes_ = 0, probes_last_row_ = 0;
  double probes_last_row_time_ = std::numeric_limits<double>::quiet_NaN();
  // The last phase put in phases.csv, so that the file is read only when a phase begins (not saved
  // in checkpoints: after a restart the file is read again).
  std::string phase_on_file_;
  double phase_start_on_file_ = 0.0;
  void write_reactions(const Model<Dim>& model, const std::string& phase);
  void write_probes_whole(const std::vector<std::shared_ptr<Probe<Dim>>>& probes);
};

// What a particle file says of the model's state beside its arrays: the time, the phase, and the names
// of the material and body indices.
template <int Dim>
VtuMeta particle_meta(const Model<Dim>& model, const std::string& phase);

// The PVD collection text for (time, file) pairs.
std::string pvd_text(const std::vector<std::pair<double, std::string>>& files);
// probes.csv: "time (s)", "phase" (run, gravity, dynamic), "phase_time (s)" (the time since that phase
// began), then "<probe>.<field>" columns (quoted as CSV needs), each probe's fields followed, for a
// probe with a reference, by "<probe>.ux_rel" ... ; a row per sampled time.
template <int Dim>
std::string probes_csv_text(const std::vector<std::shared_ptr<Probe<Dim>>>& probes);
// Its header line; and the rows of the samples from index first[k] on of each probe k, merged by time
// (a probe without a sample at a row's time leaves its cells empty).
template <int Dim>
std::string probes_csv_header(const std::vector<std::shared_ptr<Probe<Dim>>>& probes);
template <int Dim>
std::string probes_csv_rows(const std::vector<std::shared_ptr<Probe<Dim>>>& probes,
                            const std::vector<std::size_t>& first);

extern template class Output<2>;
extern template class Output<3>;

}  // namespace seismpm
