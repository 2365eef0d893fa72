// The time step's wave speed (src/core/time_step.hpp): an opened particle, a tensionless soil looser than
// its initial density, carries no mean stress until compression closes it back to that density, so its
// p-wave speed is the one at the initial density; its falling density no longer shortens the step.
#include <catch2/catch.hpp>
#include <cmath>

#include "core/time_step.hpp"
#include "materials/linear_elastic.hpp"
#include "materials/mohr_coulomb.hpp"

using namespace seismpm;

TEST_CASE("an opened particle's wave speed is the one at its initial density", "[core][time_step]") {
  MohrCoulombParameters p;
  p.density = 2000;
  p.young = 5e7;
  p.poisson = 0.3;
  p.friction = 30;  // cohesionless, no tension: tensionless
  const MohrCoulomb sand(p);
  const LinearElastic rock(2000, 5e7, 0.3);
  REQUIRE(sand.tensionless());
  MaterialConstants c;
  c.add(sand);
  c.add(rock);
  Particles<2> P;
  const double volume = 0.01, mass = 2000 * volume;
  P.add(Vec<2>(0.5, 0.5), mass, volume, 0.25, 0, 0);        // sand at its initial density
  P.add(Vec<2>(0.5, 0.5), mass, 1.8 * volume, 0.25, 0, 0);  // sand opened: density 2000 / 1.8
  P.add(Vec<2>(0.5, 0.5), mass, 1.8 * volume, 0.25, 0, 1);  // elastic, as loose: it still resists
  P.add(Vec<2>(0.5, 0.5), mass, 0.9 * volume, 0.25, 0, 0);  // sand compressed
  const double M = sand.p_wave_modulus(), G = sand.shear_modulus();
  CHECK(wave_speed(P, c, 0) == Approx(std::sqrt(M / 2000)));
  CHECK(wave_speed(P, c, 1) == Approx(std::sqrt(M / 2000)));  // was sqrt(1.8) = 1.34x faster
  CHECK(wave_speed(P, c, 2) == Approx(std::sqrt(M / (2000 / 1.8))));
  CHECK(wave_speed(P, c, 3) == Approx(std::sqrt(M / (2000 / 0.9))));
  // Shear at the current density bounds it where the soil opens further than M / G allows.
  P.add(Vec<2>(0.5, 0.5), mass, 10.0 * volume, 0.25, 0, 0);
  CHECK(wave_speed(P, c, 4) == Approx(std::max(std::sqrt(M / 2000), std::sqrt(G / 200))));
  // Without crack closure the elastic law resists closing at the current density: no exception.
  c.crack_closure = false;
  CHECK(wave_speed(P, c, 1) == Approx(std::sqrt(M / (2000 / 1.8))));
}

// The vectorised time step (stable_time_step) against the particle-by-particle speeds (signal_speed
// through fastest_signal), exactly: with crack closure and a tensionless material (opened particles
// at their initial density), without closure, and with no tensionless material (where the loop skips
// the unloaded speed altogether).
TEST_CASE("the step's fastest signal is the particles' own, with and without crack closure", "[core][time_step]") {
  MohrCoulombParameters p;
  p.density = 2000;
  p.young = 5e7;
  p.poisson = 0.3;
  p.friction = 30;
  const MohrCoulomb sand(p);
  const LinearElastic rock(2500, 1e6, 0.25);  // soft: the loosest sand particles set the step
  for (const bool with_sand : {true, false})
    for (const bool closure : {true, false}) {
      MaterialConstants c;
      c.add(with_sand ? static_cast<const Material&>(sand) : rock);
      c.add(rock);
      c.crack_closure = closure;
      Particles<2> P;
      for (int k = 0; k < 37; ++k) {  // looser and denser than the initial density, moving
        const double volume = 0.01 * (0.8 + 0.05 * k);
        const int material = k % 3 == 0 ? 1 : 0;
        P.add(Vec<2>(0.5, 0.5), 2000 * 0.01, volume, 0.25, 0, material);
        P.v.back() = Vec<2>(0.01 * k, -0.02 * (k % 5));
      }
      const double cfl = 0.4, cell = 0.01;
      const auto [fastest, speed] = fastest_signal(P, c, cell, nullptr);
      CAPTURE(with_sand, closure, fastest);
      CHECK(stable_time_step(P, c, cfl, cell, nullptr) == cfl * cell / speed);
    }
}
