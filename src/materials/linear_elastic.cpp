#include "linear_elastic.hpp"

#include <cmath>

#include "core/error.hpp"

namespace seismpm {

void validate_elastic(double density, const ElasticConstants& e) {
  if (!(density > 0.0) || !std::isfinite(density)) throw InputError("density must be > 0 (kg/m^3)");
  if (!(e.young > 0.0) || !std::isfinite(e.young)) throw InputError("young must be > 0 (Pa)");
  if (!(e.poisson >= 0.0 && e.poisson < 0.5)) throw InputError("poisson must be in [0, 0.5)");
}

LinearElastic::LinearElastic(double density, double young, double poisson)
    : Material(density), elastic_{young, poisson} {
  validate_elastic(density, elastic_);
}

void LinearElastic::update_stress(const StressUpdate& b) const {
  const double lambda = elastic_.lambda(), two_g = 2.0 * elastic_.shear();
#pragma omp parallel for schedule(static)
  for (int k = 0; k < b.count; ++k) {
    const int p = b.index[k];
    b.stress[p] = elastic_trial(b.stress[p], b.strain_increment[p], lambda, two_g);
    b.yield[p] = 0;
  }
}

}  // namespace seismpm
