#include "linear_elastic.hpp"

namespace seismpm {

void validate_elastic(double density, const ElasticConstants& e) {
  check_parameter("density", density, kDensityRange, "kg/m^3");
  check_parameter("young", e.young, kYoungRange, "Pa");
  check_parameter("poisson", e.poisson, kPoissonRange);
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
