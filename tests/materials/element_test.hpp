// Stress-point laboratory tests with mixed control: drive one strain component and hold chosen
// stress components at fixed values by iterating their strains (secant steps with the elastic
// stiffness). Used for triaxial and biaxial tests of the soil models.
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Dense>

#include "core/types.hpp"

namespace seismpm::test {

// update(stress, strain increment, commit) -> new stress; the model's state lives in the closure and
// advances only when commit is true (once per increment, after the iterations).
using PointUpdate = std::function<Sym(const Sym&, const Sym&, bool)>;

// Drives component `axial` by `step` per increment for `steps` increments. Components in `held`
// keep the stress they start with; components in `fixed` keep zero strain (plane strain);
// shear components stay zero. Returns the axial stress after every increment.
inline std::vector<double> element_test(const PointUpdate& update, Sym stress, int axial, double step, int steps,
                                        const std::vector<int>& held, double lambda, double shear) {
  std::vector<double> axial_stress;
  const Sym target = stress;
  for (int n = 0; n < steps; ++n) {
    Sym de = Sym::Zero();
    de[axial] = step;
    Sym trial = update(stress, de, false);
    for (int it = 0; it < 200; ++it) {
      // Elastic secant: d sigma_h = (lambda + 2G) d eps_h + lambda sum of the other held d eps.
      double worst = 0.0;
      Eigen::VectorXd r(held.size());
      for (std::size_t i = 0; i < held.size(); ++i) {
        r[i] = trial[held[i]] - target[held[i]];
        worst = std::max(worst, std::abs(r[i]));
      }
      if (worst < 1e-10 * std::max(1.0, std::abs(target[held[0]]))) break;
      Eigen::MatrixXd J = Eigen::MatrixXd::Constant(held.size(), held.size(), lambda);
      J.diagonal().array() += 2.0 * shear;
      const Eigen::VectorXd d = J.ldlt().solve(r);
      for (std::size_t i = 0; i < held.size(); ++i) de[held[i]] -= d[i];
      trial = update(stress, de, false);
    }
    stress = update(stress, de, true);
    axial_stress.push_back(stress[axial]);
  }
  return axial_stress;
}

}  // namespace seismpm::test
