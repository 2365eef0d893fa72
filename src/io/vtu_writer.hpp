// ParaView files (.vtu) of particles and grid nodes, written with VTK's XML writer: binary,
// zlib-compressed, appended raw data. The only translation unit that includes VTK.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "core/particle_fields.hpp"
#include "core/particles.hpp"

namespace seismpm {

// The particle point-data arrays: one per quantity of the field table (core/particle_fields.hpp),
// vectors with 3 components, tensors with 6 (xx, yy, zz, xy, yz, xz), the scalars under their own names.
using VtuArray = Quantity;
// Every quantity written as an array, in the table's order.
std::vector<VtuArray> all_vtu_arrays();
// The array a field name belongs to: "ux" -> Displacement, "sxx" -> Stress, "pressure" -> Pressure;
// array names ("displacement", "stress", ...) work too. Throws InputError listing the names.
VtuArray parse_vtu_array(const std::string& name);

struct VtuMeta {
  double time = 0.0;
  std::string phase;
  // The names of the material and body indices that the particle arrays "material" and "body" hold,
  // by index (field data arrays material_names and body_names; none when empty).
  std::vector<std::string> material_names, body_names;
  double phase_time = 0.0;  // s since the phase began (the shaking time in a dynamic phase)
};

// Writes the particles for which keep(p) is true to `path` atomically, in `id` order: the kernel
// re-sorts particles by cell, and ParaView's time filters (Plot Selection Over Time, Temporal
// Statistics, Pathlines) follow a point by its index. `id` is also the file's global-id array.
// Throws OutputError.
template <int Dim, class Keep>
void write_particles_vtu(const std::string& path, const Particles<Dim>& particles, const std::vector<VtuArray>& arrays,
                         const VtuMeta& meta, Keep&& keep) {
  // Ids are the creation indices 0..n-1, so a slot per id orders them in one pass.
  std::size_t slots = 0;
  for (std::size_t p = 0; p < particles.size(); ++p)
    slots = std::max(slots, static_cast<std::size_t>(particles.id[p]) + 1);
  std::vector<std::size_t> by_id(slots, particles.size());
  for (std::size_t p = 0; p < particles.size(); ++p)
    if (keep(p)) by_id[static_cast<std::size_t>(particles.id[p])] = p;
  std::vector<std::size_t> index;
  index.reserve(particles.size());
  for (std::size_t p : by_id)
    if (p < particles.size()) index.push_back(p);
  write_particles_vtu(path, particles, index, arrays, meta);
}

template <int Dim>
void write_particles_vtu(const std::string& path, const Particles<Dim>& particles,
                         const std::vector<std::size_t>& index, const std::vector<VtuArray>& arrays,
                         const VtuMeta& meta);

// Grid nodes that carry mass: nodal mass, velocity and fixity flags.
template <int Dim>
void write_grid_vtu(const std::string& path, const Grid<Dim>& grid, double mass_threshold, const VtuMeta& meta);

}  // namespace seismpm
