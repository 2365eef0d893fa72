// Isotropic linear elasticity (Hooke), applied to the objectively rotated stress:
// sigma += lambda tr(de) I + 2 G de. In plane strain de_zz = 0 and sigma_zz follows from nu.
#pragma once

#include "core/material.hpp"
#include "core/parameter.hpp"

namespace seismpm {

// Lame constants from Young's modulus and Poisson's ratio.
struct ElasticConstants {
  double young, poisson;
  double shear() const { return young / (2.0 * (1.0 + poisson)); }
  double bulk() const { return young / (3.0 * (1.0 - 2.0 * poisson)); }
  double lambda() const { return young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson)); }
  double p_wave() const { return bulk() + 4.0 / 3.0 * shear(); }
};

// The ranges validate_elastic checks (and the Lua help shows): Poisson's ratio below 0.5, where the
// bulk modulus becomes infinite.
inline constexpr Interval kDensityRange = above(0.0);  // kg/m^3
inline constexpr Interval kYoungRange = above(0.0);    // Pa
inline constexpr Interval kPoissonRange = closed_open(0.0, 0.5);

// Throws ParameterError naming the bad parameter ("density", "young", "poisson").
void validate_elastic(double density, const ElasticConstants& e);

// The product as it is, never fused with the sum it feeds into a multiply-add. Whether GCC fuses
// lambda tr(de) into the normal entries of a trial depends on the loop it is inlined into (where the
// product is also broadcast to a vector it is not), and a trial must have the same bits wherever it
// is formed: Mohr-Coulomb forms it in two loops, and its vectorised first pass, where GCC fused it,
// changed the trials in round-off until the product was kept apart here.
inline double unfused(double product) {
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12
  return __builtin_assoc_barrier(product);
#else
  return product;
#endif
}

// Adds the elastic response to the strain increment de: sigma + D de.
inline Sym elastic_trial(const Sym& stress, const Sym& de, double lambda, double two_g) {
  const double lt = unfused(lambda * trace(de));
  Sym s = stress + two_g * de;
  s[0] += lt;
  s[1] += lt;
  s[2] += lt;
  return s;
}

class LinearElastic : public Material {
 public:
  LinearElastic(double density, double young, double poisson);
  std::string_view kind() const override { return "linear_elastic"; }
  double p_wave_modulus() const override { return elastic_.p_wave(); }
  double shear_modulus() const override { return elastic_.shear(); }
  double bulk_modulus() const override { return elastic_.bulk(); }
  double young() const { return elastic_.young; }
  double poisson() const { return elastic_.poisson; }
  void update_stress(const StressUpdate& batch) const override;

 private:
  ElasticConstants elastic_;
};

}  // namespace seismpm
