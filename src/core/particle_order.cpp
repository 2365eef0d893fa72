// Particle order: a counting sort by cell every few steps, and the stable ids that survive it.
#include "model.hpp"

namespace seismpm {

// Counting sort by cell (slab axis slowest): neighbours in memory are neighbours on the grid, and each
// scatter slab becomes a contiguous run. Stable, so the order is deterministic.
template <int Dim>
void Model<Dim>::sort_particles() {
  const int n = static_cast<int>(particles_.size());
  const int cells = grid_.cell_count();
  const auto& index = support_.cells;
  auto& key = sort_key_;
  auto& start = sort_start_;
  auto& order = sort_order_;
  key.resize(n);
#pragma omp parallel for schedule(static)
  for (int p = 0; p < n; ++p) key[p] = index.of(particles_.x[p]);
  start.assign(cells + 1, 0);
  for (int p = 0; p < n; ++p) ++start[key[p] + 1];
  for (int c = 0; c < cells; ++c) start[c + 1] += start[c];
  order.resize(n);
  for (int p = 0; p < n; ++p) order[start[key[p]]++] = p;
  particles_.permute(order, sort_buffer_);
  material_lists_valid_ = false;
  index_of_id_.clear();
}

template <int Dim>
std::size_t Model<Dim>::index_of(int id) const {
  if (index_of_id_.size() != particles_.size()) {
    index_of_id_.assign(particles_.size(), 0);
    for (std::size_t p = 0; p < particles_.size(); ++p) index_of_id_[particles_.id[p]] = static_cast<int>(p);
  }
  return index_of_id_.at(id);
}

template void Model<2>::sort_particles();
template void Model<3>::sort_particles();
template std::size_t Model<2>::index_of(int) const;
template std::size_t Model<3>::index_of(int) const;

}  // namespace seismpm
