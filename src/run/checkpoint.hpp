// What a checkpoint holds (docs/checkpoint.md): the whole state of a simulation, so that a run
// restored from it ends bit for bit where the uninterrupted run ends. The model (settings, materials
// with their parameters, bodies, every particle field in the current particle order, grid fixities,
// contact pairs, rigid bodies with their velocity histories, reactions and impulses, the clock, the
// time step control), the local damping, the current phase, the event schedule, the probes with their
// samples, the output directory with the files written so far and the next output time, the periodic
// checkpoint, and the run in progress (a gravity phase with its equilibrium monitor).
//
// Not saved: per-step scratch (rebuilt by the next step), the progress display and the Ctrl-C flag
// (the session's), stage timings, and histories made of functions (Lua's), which are named by key and
// must be given again when restoring: "<rigid body>.vx", "<rigid body>.vy".
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/history.hpp"
#include "core/model.hpp"
#include "io/checkpoint_file.hpp"

namespace seismpm {

template <int Dim>
class Simulation;

// Histories given again when restoring, by key ("base.vx"): required for those a checkpoint could not
// hold (functions), and they replace the saved ones otherwise.
using SuppliedHistories = std::map<std::string, std::shared_ptr<const History>>;

// The key of a rigid body's velocity component: "<body>.vx", "<body>.vy", "<body>.vz".
std::string velocity_history_key(const std::string& body, int axis);

// Writes the simulation's state to `path` atomically (CheckpointWriter::write). Throws OutputError
// when the file cannot be written, and CheckpointError for state that cannot be saved (a material of
// a kind the format does not know).
template <int Dim>
void write_checkpoint(const Simulation<Dim>& simulation, const std::string& path);

// The output directory the checkpoint's simulation writes to (none: no output), read without restoring
// anything: a restore creates, locks and rewrites files in it, so a caller that confines writes checks
// it first.
std::optional<std::string> checkpoint_output_dir(const CheckpointReader& file);

// The checkpoint's model settings: what the simulation to restore into is built with.
template <int Dim>
ModelSettings<Dim> checkpoint_settings(const CheckpointReader& file);

// Fills a simulation built with checkpoint_settings(file) and nothing else yet with the checkpoint's
// state, then rewrites the output directory's lists to match it (rewrite_output_files). Throws
// CheckpointError naming the file: inconsistent content, a function history not supplied, a supplied
// key that names nothing.
template <int Dim>
void restore_checkpoint(const CheckpointReader& file, Simulation<Dim>& simulation,
                        const SuppliedHistories& histories = {});

// Makes the output directory's collected files match the simulation's output state after a restore:
// particles.pvd, rigid.pvd and grid.pvd list only the files written up to the checkpoint, probes.csv
// and reactions.csv hold only its rows (the run after the checkpoint may have written more before it
// stopped). Each is rewritten whole, atomically.
template <int Dim>
void rewrite_output_files(Simulation<Dim>& simulation);

}  // namespace seismpm
