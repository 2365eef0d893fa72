// Elastic-perfectly plastic Drucker-Prager, f = sqrt(J2) + alpha I1 - k (tension positive), with
// non-associated flow g = sqrt(J2) + beta I1 and a tension cut-off on the mean stress, fitted to
// Mohr-Coulomb's c, phi, psi by name:
//   outer        - through the compression corners of the MC pyramid;
//   inner        - through its extension corners;
//   plane_strain - the same plane-strain limit load as MC with the same dilation.
#pragma once

#include <string>

#include "core/material.hpp"
#include "linear_elastic.hpp"
#include "strength_parameters.hpp"

namespace seismpm {

enum class DruckerPragerFit { PlaneStrain, Outer, Inner };

// Mohr-Coulomb's strength; here `tension` limits the mean stress I1/3 (Pa), at most the cone's apex.
struct DruckerPragerParameters : StrengthParameters {
  double density = 0, young = 0, poisson = 0;
  DruckerPragerFit fit = DruckerPragerFit::PlaneStrain;
};

// Throws ParameterError naming the parameter that is out of range.
void validate(const DruckerPragerParameters& p);
DruckerPragerFit parse_fit(const std::string& name);  // throws InputError

// alpha, k and beta of the named fit.
struct DruckerPragerConstants {
  double alpha, k, beta;
};
DruckerPragerConstants drucker_prager_constants(const DruckerPragerParameters& p);

class DruckerPrager : public Material {
 public:
  explicit DruckerPrager(const DruckerPragerParameters& p);
  std::string_view kind() const override { return "drucker_prager"; }
  double p_wave_modulus() const override { return elastic_.p_wave(); }
  double shear_modulus() const override { return elastic_.shear(); }
  double bulk_modulus() const override { return elastic_.bulk(); }
  const DruckerPragerParameters& parameters() const { return p_; }
  const DruckerPragerConstants& constants() const { return c_; }
  void update_stress(const StressUpdate& batch) const override;
  bool tensionless() const override { return p_.tension == 0.0; }
  std::shared_ptr<const Material> with_reduced_strength(double srf) const override;

  struct Result {
    Sym stress;
    double shear_increment;
    bool plastic;
  };
  Result integrate(const Sym& stress, const Sym& de) const;
  double yield_function(const Sym& stress) const;

 private:
  DruckerPragerParameters p_;
  ElasticConstants elastic_;
  DruckerPragerConstants c_;
};

}  // namespace seismpm
