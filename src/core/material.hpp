// The small interface every constitutive model implements. The kernel calls update_stress once
// per material per step with the list of its particles: no virtual call per particle.
#pragma once

#include <cstdint>
#include <memory>
#include <string_view>

#include "rayleigh.hpp"
#include "types.hpp"

namespace seismpm {

// Views into the particle arrays for one material's particles (`index` lists them).
struct StressUpdate {
  const int* index = nullptr;
  int count = 0;
  Sym* stress = nullptr;                  // in: old stress, already rotated objectively; out: new stress
  const Sym* strain_increment = nullptr;  // dt * sym(L) of this step
  double* plastic_strain = nullptr;       // model state: accumulated plastic shear strain
  std::uint8_t* yield = nullptr;          // out: 1 where the update was plastic
};

class Material {
 public:
  explicit Material(double density) : density_(density) {}
  virtual ~Material() = default;

  virtual std::string_view kind() const = 0;
  // Initial mass density (kg/m^3).
  double density() const { return density_; }
  // Constrained (p-wave) modulus K + 4G/3: sets the wave speed for the time step.
  virtual double p_wave_modulus() const = 0;
  // Shear modulus, for diagnostics and plastic models.
  virtual double shear_modulus() const = 0;
  // Bulk modulus.
  virtual double bulk_modulus() const = 0;
  virtual void update_stress(const StressUpdate& batch) const = 0;
  // True when the material can carry no tension at all (a tension cut-off at zero). The kernel then
  // treats a particle looser than the initial density as opened (a crack): compression closes it
  // without mean stress before loading the material (ModelSettings::crack_closure).
  virtual bool tensionless() const { return false; }
  // A copy with its shear strength divided by a strength reduction factor srf > 0 (the factor of safety
  // by strength reduction), density and elasticity unchanged; null for a material without a
  // frictional strength to reduce (elastic, rigid).
  virtual std::shared_ptr<const Material> with_reduced_strength(double /*srf*/) const { return nullptr; }

  // Rayleigh damping (none by default). Set once, before the material is shared with a model.
  const Rayleigh& rayleigh() const { return rayleigh_; }
  void set_rayleigh(const Rayleigh& r) { rayleigh_ = Rayleigh::coefficients(r.alpha, r.beta); }

 protected:
  // `copy` (a variant of this material, such as a strength-reduced one) with this material's damping.
  template <class M>
  std::shared_ptr<const Material> with_my_damping(std::shared_ptr<M> copy) const {
    copy->set_rayleigh(rayleigh_);
    return copy;
  }

 private:
  double density_;
  Rayleigh rayleigh_;
};

}  // namespace seismpm
