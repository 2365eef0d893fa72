// The paper's validation of the non-zero kinematic condition (Bhandari et al. 2016, §2.4.2): a 1 m x 1 m
// elastic block of unit weight 10 kN/m^3 rests on a layer of prescribed-velocity particles; after it has
// settled under gravity the base suddenly moves at 2 m/s to the right.
// Closed forms: with Coulomb friction mu the block accelerates at mu g until it has the base's speed,
// so its centroid moves 0.5 mu g t^2 up to t* = v / (mu g), then v (t - t*) more; with a smooth base it
// stays put; glued to the base (no contact) it moves with the base.
#pragma once

#include <cmath>
#include <memory>

#include "materials/linear_elastic.hpp"
#include "run/simulation.hpp"

namespace seismpm::cases {

enum class BaseContact { None, Friction };

struct MovingBaseBlock {
  double cell = 0.1;          // m
  int ppc = 2;                // block particles per cell per axis
  double unit_weight = 10e3;  // N/m^3
  double gravity = 9.81;      // m/s^2
  double young = 10e6;        // Pa
  double poisson = 0.3;
  double base_speed = 2.0;  // m/s
  BaseContact contact = BaseContact::Friction;
  double friction = 0.3;  // mu (0: smooth)
  // The block settles under gravity as in the scenario: local damping 0.7 to equilibrium.
  GravityPhaseSettings settle{0.7, 0.005, 2.0};
  ShapeKind shape = ShapeKind::Gimp;
  bool with_base = true;  // false: the block alone (falls freely), for timing comparisons
  bool profile = false;

  double density() const { return unit_weight / gravity; }
  // Centroid x displacement of the block at time t after the base starts, for Coulomb friction.
  double exact_displacement(double t) const {
    const double a = friction * gravity;
    if (a == 0.0) return 0.0;
    const double t_star = base_speed / a;
    if (t <= t_star) return 0.5 * a * t * t;
    return 0.5 * a * t_star * t_star + base_speed * (t - t_star);
  }

  struct Built {
    std::unique_ptr<Simulation<2>> simulation;
    Model<2>* model = nullptr;  // the simulation's
    int block = -1, base = -1;
  };

  // Block on [0, 1] x [0, 1]; the base, one row of particles per cell, spans 2.5 m to the left of
  // the block's left edge and 1 m to its right, so the block keeps its support for 1 s of motion.
  Built build() const {
    ModelSettings<2> s;
    s.lower = Vec<2>(-2.7, -0.3);
    s.upper = Vec<2>(4.3, 1.3);
    s.cell = cell;
    s.shape = shape;
    s.gravity = Vec<2>(0.0, -gravity);
    s.profile = profile;
    Built b;
    b.simulation = std::make_unique<Simulation<2>>(s);
    b.model = &b.simulation->model();
    auto& m = *b.model;
    const int mat = m.add_material(std::make_shared<LinearElastic>(density(), young, poisson));
    b.block = m.add_body("block", ppc);
    m.fill_box(b.block, mat, Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0));
    std::array<std::shared_ptr<const History>, 2> rest = {std::make_shared<ConstantHistory>(0.0),
                                                          std::make_shared<ConstantHistory>(0.0)};
    if (with_base) {
      b.base = m.add_rigid_body("base", 1, 7850.0, rest);
      m.fill_box(b.base, -1, Vec<2>(-2.5, -cell), Vec<2>(2.0, 0.0));
      if (contact == BaseContact::Friction) m.add_contact(b.block, b.base, friction);
    }
    return b;
  }

  // The gravity phase (the block at rest on the base held still; displacements reset at its end),
  // then the base set moving at base_speed: a dynamic phase (no damping) starts, of no length yet, so
  // that the caller runs it on in the stretches it wants to look at.
  void settle_and_start(Built& b) const {
    b.simulation->gravity_phase(settle);
    b.model->set_rigid_velocity(
        b.base, {std::make_shared<ConstantHistory>(base_speed), std::make_shared<ConstantHistory>(0.0)});
    b.simulation->dynamic_phase(0.0, 0.0);
  }
};

}  // namespace seismpm::cases
