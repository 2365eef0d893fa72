// The paper's shaking-table slope (Bhandari et al. 2016, §3) built in C++ as scenarios/shaking_table.lua
// builds it: a 45-degree Masa-soil slope (Mohr-Coulomb, c = 0.78 kPa, phi = 23 deg, no tension) in a
// box 0.9 m x 0.6 m of prescribed-velocity particles, a rough base (mu = 1) and smooth walls, uGIMP,
// FLIP 0.98. For the benchmark: the soil starts from K0 stresses and the box shakes at a sine
// velocity strong enough to fail the slope.
#pragma once

#include <cmath>
#include <memory>
#include <numbers>

#include "core/region.hpp"
#include "materials/mohr_coulomb.hpp"
#include "run/gravity_phase.hpp"
#include "run/simulation.hpp"

namespace seismpm::cases {

struct ShakingTable {
  double cell = 0.0075;     // m: 24,880 soil particles (the paper's 0.75 cm mesh)
  double amplitude = 0.15;  // m/s, table velocity amplitude
  double frequency = 5.0;   // Hz: peak acceleration 4.7 m/s^2, well above the slope's critical one
  bool profile = false;

  struct Built {
    std::unique_ptr<Simulation<2>> simulation;
    Model<2>* model = nullptr;  // the simulation's
    int soil = -1;
  };

  Built build() const {
    constexpr double L = 0.9, H = 0.6, crest_x = 0.35, crest_y = 0.53, toe_y = 0.2;
    const double t = cell;
    ModelSettings<2> s;
    s.lower = Vec<2>(-2 * t, -2 * t);
    s.upper = Vec<2>(L + 2 * t, H + 2 * t);
    s.cell = cell;
    s.shape = ShapeKind::Gimp;
    s.flip = 0.98;
    s.gravity = Vec<2>(0.0, -9.81);
    s.profile = profile;
    Built b;
    b.simulation = std::make_unique<Simulation<2>>(s);
    b.model = &b.simulation->model();
    auto& m = *b.model;
    MohrCoulombParameters p;
    p.density = 1680, p.young = 2.57e6, p.poisson = 0.33;
    p.cohesion = 780, p.friction = 23, p.dilation = 0, p.tension = 0;
    const int mat = m.add_material(std::make_shared<MohrCoulomb>(p));
    b.soil = m.add_body("soil", 2);
    const PolygonRegion slope(
        {{0, 0}, {L, 0}, {L, toe_y}, {crest_x + (crest_y - toe_y), toe_y}, {crest_x, crest_y}, {0, crest_y}});
    m.fill(b.soil, mat, slope.lower(), slope.upper(), [&](const Vec<2>& x) { return slope.contains(x); });
    const double a = amplitude, w = 2.0 * std::numbers::pi * frequency;
    const std::array<std::shared_ptr<const History>, 2> shake = {
        std::make_shared<FunctionHistory>([a, w](double time) { return a * std::sin(w * time); }, "sine"),
        std::make_shared<ConstantHistory>(0.0)};
    struct Wall {
      const char* name;
      Vec<2> lo, hi;
      double friction;
    };
    for (const Wall& wall : {Wall{"base", {-t, -t}, {L + t, 0}, 1.0}, Wall{"left_wall", {-t, 0}, {0, H}, 0.0},
                             Wall{"right_wall", {L, 0}, {L + t, H}, 0.0}}) {
      const int body = m.add_rigid_body(wall.name, 1, 7850.0, shake);
      m.fill_box(body, -1, wall.lo, wall.hi);
      m.add_contact(b.soil, body, wall.friction);
    }
    set_k0_stresses(m, p.poisson / (1.0 - p.poisson));
    b.simulation->dynamic_phase(0.0, 0.0);  // the table moves from the phase's start
    return b;
  }
};

}  // namespace seismpm::cases
