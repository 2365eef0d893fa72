#include "local_damping.hpp"

#include <cmath>

#include "error.hpp"
#include "model.hpp"

namespace seismpm {

template <int Dim>
LocalDamping<Dim>::LocalDamping(double alpha) : alpha_(0.0) {
  set_alpha(alpha);
}

template <int Dim>
void LocalDamping<Dim>::set_alpha(double alpha) {
  if (!(alpha >= 0.0 && alpha < 1.0)) throw InputError("damping must be in [0, 1)");
  alpha_ = alpha;
}

template <int Dim>
void LocalDamping<Dim>::nodal_forces(Model<Dim>& model, const StepContext&) {
  if (alpha_ == 0.0) return;
  auto& g = model.grid();
  const int n = g.node_count();
  const double eps = model.mass_threshold(), alpha = alpha_;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    if (!(g.mass[i] > eps)) continue;
    for (int d = 0; d < Dim; ++d) {
      const double v = g.momentum[i][d];  // same sign as the nodal velocity
      const double s = (v > 0.0) - (v < 0.0);
      g.force[i][d] -= alpha * std::abs(g.force[i][d]) * s;
    }
  }
  // Each contact field's own forces where fields meet; not where a rigid body is present: there the
  // out-of-balance force is what the contact must carry (damping it first would under-read the normal
  // force, the friction limit and the reaction), and the rigid body fixes the motion anyway.
  auto& contact = model.contact();
  auto& sh = contact.nodes();
  const int count = sh.count();
  constexpr int kSlots = SharedNodes<Dim>::kSlots;
#pragma omp parallel for schedule(static)
  for (int k = 0; k < count; ++k) {
    if (contact.held(k)) continue;
    for (int j = 0; j < sh.fields(k); ++j) {
      const int s = k * kSlots + j;
      for (int d = 0; d < Dim; ++d) {
        const double v = sh.momentum[s][d];
        const double sign = (v > 0.0) - (v < 0.0);
        sh.force[s][d] -= alpha * std::abs(sh.force[s][d]) * sign;
      }
    }
  }
}

template class LocalDamping<2>;
template class LocalDamping<3>;

}  // namespace seismpm
