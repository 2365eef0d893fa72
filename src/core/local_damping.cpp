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
  const double eps = model.mass_threshold(), alpha = alpha_;
  model.active_nodes().for_each_range([&](int first, int end) {  // every node with mass lies in them
    for (int i = first; i < end; ++i) {
      if (!(g.mass[i] > eps)) continue;
      const unsigned held = g.fixity(i);  // a held component's force is the support's reaction: left as it is
      for (int d = 0; d < Dim; ++d) {
        if (held & (1u << d)) continue;
        const double v = g.momentum[i][d];  // same sign as the nodal velocity
        const double s = (v > 0.0) - (v < 0.0);
        g.force[i][d] -= alpha * std::abs(g.force[i][d]) * s;
      }
    }
  });
  model.contact().damp_forces(alpha, eps);
}

template class LocalDamping<2>;
template class LocalDamping<3>;

}  // namespace seismpm
