// Rigid bodies made of prescribed-velocity particles (the paper's non-zero kinematic condition):
// the velocity history each one follows, and the force it exerts on the deformable bodies.
#pragma once

#include <array>
#include <memory>
#include <string_view>

#include "core/history.hpp"
#include "core/material.hpp"
#include "core/types.hpp"

namespace seismpm {

template <int Dim>
struct RigidMotion {
  std::array<std::shared_ptr<const History>, Dim> velocity;  // m/s per axis, read at the phase time
  Vec<Dim> current = Vec<Dim>::Zero();                       // the velocity of the last step (m/s)
  // Force the rigid body exerted on the deformable bodies over the last step (N; N/m in 2D), and its
  // time integral since the model was built (N s), for averages over output intervals.
  Vec<Dim> force = Vec<Dim>::Zero();
  Vec<Dim> impulse = Vec<Dim>::Zero();
};

// The stand-in material of rigid particles: a density for their mass (shown in outputs, never used
// by the physics: a rigid body has infinite mass), no stiffness, no stress.
class RigidMaterial : public Material {
 public:
  explicit RigidMaterial(double density) : Material(density) {}
  std::string_view kind() const override { return "rigid"; }
  double p_wave_modulus() const override { return 0.0; }
  double shear_modulus() const override { return 0.0; }
  double bulk_modulus() const override { return 0.0; }
  void update_stress(const StressUpdate&) const override {}
};

}  // namespace seismpm
