// The stress update of the step: velocity gradients from the (re-mapped) nodal velocities, the
// cell-averaged volumetric strain, the objective rotation, crack closure and the volume, then the
// constitutive models, one batch per material, and Rayleigh damping's viscous stresses.
#include "model.hpp"
#include "objective_rate.hpp"
#include "thread_shares.hpp"

namespace seismpm {

template <int Dim>
template <class Shape, bool Contact>
void Model<Dim>::update_stress(const StepContext& c) {
  velocity_gradients<Shape, Contact>(c);
  const bool average = settings_.cell_volumetric_strain;
  if (average) sum_cell_dilation<Contact>();
  rotate_close_and_update_volume<Contact>(average);
  integrate_materials();
  if (constants_.any_rayleigh) rayleigh_stresses(c);
}

// Strain increment dt sym(L) and spin dt skw(L), L_ab = dv_a / dx_b, per particle; none for rigid ones.
template <int Dim>
template <class Shape, bool Contact>
void Model<Dim>::velocity_gradients(const StepContext& c) {
  const auto& st = support_.template stencils<Shape>();
  const int n = static_cast<int>(particles_.size());
  const double dt = c.dt;
  const auto& P = particles_;
  const auto& G = grid_;
  const auto& S = contact_.nodes();
  strain_increment_.resize(n);
  spin_.resize(n);
  auto& shares = ThreadShares::of(LoopKind::Particles);
  const auto start = ThreadShares::Clock::now();
#pragma omp parallel
  {
    const auto mine = shares.mine(n);
    for (int p = static_cast<int>(mine.begin); p < mine.end; ++p) {
      [[maybe_unused]] int f = 0;
      if constexpr (Contact) {
        if (contact_.rigid(P.body[p])) {  // no strain, no stress
          strain_increment_[p] = Sym::Zero();
          spin_[p].setZero();
          continue;
        }
        f = contact_.field_of(P.body[p]);
      }
      Mat<Dim> L = Mat<Dim>::Zero();
      auto gather = [&](auto slotted) {
        for_each_node(st[p], G, [&](int i, double, const Vec<Dim>& dN) {
          if constexpr (decltype(slotted)::value) {
            const int k = S.index(i);
            if (k >= 0) {
              L.noalias() += S.velocity[S.slot(k, f)] * dN.transpose();
              return;
            }
          }
          L.noalias() += G.velocity[i] * dN.transpose();
        });
      };
      if (Contact && contact_.near_shared(support_.cell_of[p]))
        gather(std::true_type{});
      else  // the common field alone: the row-by-row sums
        L = gradient(st[p], G, G.velocity.data());
      // Entry by entry: the matrix form stored L in halves and read it back whole, a load that waits
      // for both stores to retire (a third of this loop's time).
      auto dl = [&](int a, int b) { return a < Dim && b < Dim ? dt * L(a, b) : 0.0; };
      Sym& de = strain_increment_[p];
      de[0] = dl(0, 0), de[1] = dl(1, 1), de[2] = dl(2, 2);
      de[3] = 0.5 * (dl(0, 1) + dl(1, 0)), de[4] = 0.5 * (dl(1, 2) + dl(2, 1)), de[5] = 0.5 * (dl(0, 2) + dl(2, 0));
      spin_[p] = Eigen::Vector3d(0.5 * (dl(0, 1) - dl(1, 0)), 0.5 * (dl(1, 2) - dl(2, 1)), 0.5 * (dl(0, 2) - dl(2, 0)));
    }
    shares.finished(start, mine.end - mine.begin);
  }
}

// B-bar: the cell's volume-weighted mean volumetric increment replaces each particle's; the
// deviatoric part stays, and so does de_zz = 0 in plane strain. Removes the volumetric locking that
// isochoric plastic flow and near-incompressibility cause in low-order cells. Here the cells' sums;
// rotate_close_and_update_volume applies the mean on its pass over the particles.
//
// The volumes are summed as soon as the particles are located (the time step reads them too, and no
// volume changes before the stress update): each cell's volume and its particles' stress-free volume,
// slab by slab (slabs hold disjoint cells), the slab's cells cleared first, so only occupied cells are
// touched, and each cell summed in particle order, the same for any number of threads.
template <int Dim>
template <bool Contact>
void Model<Dim>::sum_cell_volumes() {
  cell_sums_.resize(grid_.cell_count());
  const auto& P = particles_;
  const auto& cell_of = support_.cell_of;
  support_.schedule.for_each_slab_of_own_cells([&](int, const int* first, const int* last) {
    for (const int* k = first; k != last; ++k) cell_sums_[cell_of[*k]] = CellSums{0.0, 0.0, 0.0};
    for (const int* k = first; k != last; ++k) {
      const int p = *k;
      if constexpr (Contact)
        if (contact_.any_rigid() && contact_.rigid(P.body[p])) continue;  // no strain of their own
      add_volumes(cell_sums_[cell_of[p]], p);
    }
  });
}

// Then, in the stress update, the volume-weighted volumetric increments.
template <int Dim>
template <bool Contact>
void Model<Dim>::sum_cell_dilation() {
  const auto& P = particles_;
  const auto& cell_of = support_.cell_of;
  support_.schedule.for_each_in_own_cell([&](int p) {
    if constexpr (Contact)
      if (contact_.any_rigid() && contact_.rigid(P.body[p])) return;
    cell_sums_[cell_of[p]].dilation += P.volume[p] * trace(strain_increment_[p]);
  });
}

// With `average`, the cell's mean volumetric increment (sum_cell_dilation) first; then the Jaumann
// rotation of the old stress, total strain, crack closure and the new volume (capped at max_dilation
// times the stress-free one).
template <int Dim>
template <bool Contact>
void Model<Dim>::rotate_close_and_update_volume(bool average) {
  const int n = static_cast<int>(particles_.size());
  const double max_volume_ratio = settings_.max_dilation;
  auto& P = particles_;
  const auto& cell_of = support_.cell_of;
  auto& shares = ThreadShares::of(LoopKind::Particles);
  const auto start = ThreadShares::Clock::now();
#pragma omp parallel
  {
    const auto mine = shares.mine(n);
    for (int p = static_cast<int>(mine.begin); p < mine.end; ++p) {
      if constexpr (Contact)
        if (contact_.rigid(P.body[p])) continue;
      Sym& de = strain_increment_[p];
      const CellSums* cell = average ? &cell_sums_[cell_of[p]] : nullptr;
      if (average) {
        const double correction = (cell->dilation / cell->volume - trace(de)) / Dim;
        for (int d = 0; d < Dim; ++d) de[d] += correction;
      }
      Mat3 w = Mat3::Zero();
      w(0, 1) = spin_[p][0], w(1, 0) = -spin_[p][0];
      w(1, 2) = spin_[p][1], w(2, 1) = -spin_[p][1];
      w(0, 2) = spin_[p][2], w(2, 0) = -spin_[p][2];
      P.stress[p] = rotate_objectively(P.stress[p], w);
      P.strain[p] += de;
      // Volume from the (averaged) strain increment: V <- V (1 + tr de) to first order, exactly as det(I + dt L)
      // when nothing is averaged.
      const Mat3 F = Mat3::Identity() + to_matrix(de) + w;
      // Crack closure: volumetric compression first closes what the tension cut-off opened (down to the
      // stress-free volume), at no change of mean stress; the rest, and all shear, loads the material.
      // Only a compressed particle can close (an opened one's opening is positive): the logarithm is
      // taken for those alone. With the cell-averaged volumetric strain the opening is the cell's, as the
      // volumetric increment is: judged particle by particle, the volume each particle drifts to in a
      // cell of unequal neighbours opened some while others carried the load, and stress-free particles
      // in a resting deposit's surface kept it creeping (docs/kernel.md).
      if (-trace(de) > 0.0 && (average ? closes_by_cell(p, cell_of[p]) : opened(p))) {
        const double opening = average ? std::log(cell->volume / cell->free_volume)
                                       : std::log(P.volume[p] * constants_.initial_density[P.material[p]] / P.mass[p]);
        const double closing = std::min(-trace(de), opening);
        for (int d = 0; d < Dim; ++d) de[d] += closing / Dim;
      }
      P.volume[p] *= F.template topLeftCorner<Dim, Dim>().determinant();
      if (max_volume_ratio > 0.0)
        P.volume[p] = std::min(P.volume[p], max_volume_ratio * P.mass[p] / constants_.initial_density[P.material[p]]);
    }
    shares.finished(start, mine.end - mine.begin);
  }
}

// The time step's view of crack closure by cell, asked for outside the step (before the first one, or
// naming the particle that set a collapsed step): each particle's cell from its position (the cell the
// stress update will average over) and the cells' volumes summed in particle order, as the step's
// sum_cell_volumes sums them, so the flags are the step's own. Rare: a plain serial pass.
template <int Dim>
const char* Model<Dim>::closable_particles() const {
  if (!closure_by_cell()) return nullptr;
  const CellIndex<Dim> cells(grid_);
  const auto& P = particles_;
  const bool any_rigid = contact_.any_rigid();
  std::vector<CellSums> sums(grid_.cell_count(), CellSums{0.0, 0.0, 0.0});
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (any_rigid && contact_.rigid(P.body[p])) continue;
    add_volumes(sums[cells.of(P.x[p])], p);
  }
  return closable_flags([&](int p) { return cells.of(P.x[p]); }, sums);
}

// The same within the step, from the located particles' cells and sum_cell_volumes' sums.
template <int Dim>
const char* Model<Dim>::closable_in_step() const {
  if (!closure_by_cell()) return nullptr;
  const auto& cell_of = support_.cell_of;
  return closable_flags([&](int p) { return cell_of[p]; }, cell_sums_);
}

// Per particle, 1 where it is looser than its initial density and its cell (cell_of(p), summed in
// `sums`) is open; nullptr where no particle is looser: every particle then counts at its current
// density anyway.
template <int Dim>
template <class CellOf>
const char* Model<Dim>::closable_flags(CellOf&& cell_of, const std::vector<CellSums>& sums) const {
  const int n = static_cast<int>(particles_.size());
  const bool any_rigid = contact_.any_rigid();
  may_close_.resize(n);
  int looser = 0;
  auto& shares = ThreadShares::of(LoopKind::Particles);
  const auto start = ThreadShares::Clock::now();
#pragma omp parallel reduction(+ : looser)
  {
    const auto mine = shares.mine(n);
    for (int p = static_cast<int>(mine.begin); p < mine.end; ++p) {
      const bool loose = opened(p) && !(any_rigid && contact_.rigid(particles_.body[p]));
      const CellSums& cell = sums[cell_of(p)];
      may_close_[p] = loose && exceeds_free_volume(cell.volume, cell.free_volume);
      looser += loose;
    }
    shares.finished(start, mine.end - mine.begin);
  }
  return looser == 0 ? nullptr : may_close_.data();
}

// Each material updates its own particles' stresses in one call: no virtual call per particle.
template <int Dim>
void Model<Dim>::integrate_materials() {
  if (!material_lists_valid_) rebuild_material_lists();
  auto& P = particles_;
  for (int m = 0; m < material_count(); ++m) {
    const auto& list = material_particles_[m];
    if (list.empty()) continue;
    StressUpdate batch;
    batch.index = list.data();
    batch.count = static_cast<int>(list.size());
    batch.stress = P.stress.data();
    batch.strain_increment = strain_increment_.data();
    batch.plastic_strain = P.plastic_strain.data();
    batch.yield = P.yield.data();
    materials_[m]->update_stress(batch);
  }
}

// The stiffness-proportional part of Rayleigh damping: sigma_v = beta D : (de / dt), D the elastic
// stiffness (K tr I + 2G dev), from the strain increment the material saw (after B-bar and crack
// closure). Elastic D also where the material yields: the damping is a small-strain (elastic) one.
template <int Dim>
void Model<Dim>::rayleigh_stresses(const StepContext& c) {
  const int n = static_cast<int>(particles_.size());
  const double inv_dt = 1.0 / c.dt;
  const auto& C = constants_;
  auto& P = particles_;
#pragma omp parallel for schedule(static)
  for (int p = 0; p < n; ++p) {
    const int m = P.material[p];
    const double beta = C.rayleigh_beta[m];
    if (!(beta > 0.0)) {
      P.damping_stress[p].setZero();
      continue;
    }
    const Sym rate = inv_dt * strain_increment_[p];
    const double vol = trace(rate) / 3.0;
    Sym dev = rate;
    for (int d = 0; d < 3; ++d) dev[d] -= vol;
    Sym s = (2.0 * beta * C.shear_modulus[m]) * dev;
    for (int d = 0; d < 3; ++d) s[d] += 3.0 * beta * C.bulk_modulus[m] * vol;
    P.damping_stress[p] = s;
  }
}

template <int Dim>
void Model<Dim>::rebuild_material_lists() {
  material_particles_.assign(materials_.size(), {});
  for (std::size_t p = 0; p < particles_.size(); ++p)
    material_particles_[particles_.material[p]].push_back(static_cast<int>(p));
  material_lists_valid_ = true;
}

#define SEISMPM_STRESS(D, S, C)                                    \
  template void Model<D>::update_stress<S, C>(const StepContext&); \
  template void Model<D>::velocity_gradients<S, C>(const StepContext&);
#define SEISMPM_STRESS_CELLS(D, C)                \
  template void Model<D>::sum_cell_volumes<C>();  \
  template void Model<D>::sum_cell_dilation<C>(); \
  template void Model<D>::rotate_close_and_update_volume<C>(bool);
SEISMPM_FOR_EACH_STEP_VARIANT(SEISMPM_STRESS, SEISMPM_STRESS_CELLS)
#undef SEISMPM_STRESS
#undef SEISMPM_STRESS_CELLS
template void Model<2>::integrate_materials();
template void Model<3>::integrate_materials();
template void Model<2>::rayleigh_stresses(const StepContext&);
template void Model<3>::rayleigh_stresses(const StepContext&);
template void Model<2>::rebuild_material_lists();
template void Model<3>::rebuild_material_lists();
template const char* Model<2>::closable_particles() const;
template const char* Model<3>::closable_particles() const;
template const char* Model<2>::closable_in_step() const;
template const char* Model<3>::closable_in_step() const;

}  // namespace seismpm
