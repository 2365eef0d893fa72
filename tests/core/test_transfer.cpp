// Particle-to-grid and back conserve mass and linear momentum to round-off.
#include <catch2/catch.hpp>
#include <random>

#include "support/models.hpp"

using namespace seismpm;

TEMPLATE_TEST_CASE_SIG("transfers conserve mass and linear momentum", "[core][transfer]", ((int Dim), Dim), 2, 3) {
  const auto shape = GENERATE(ShapeKind::Linear, ShapeKind::Gimp);
  const double flip = GENERATE(1.0, 0.0, 0.5);
  const auto scheme = GENERATE(Scheme::Musl, Scheme::Usl);
  CAPTURE(to_string(shape), flip, scheme == Scheme::Musl);
  ModelSettings<Dim> s;
  s.upper = Vec<Dim>::Constant(1.0);
  s.cell = 0.1;
  s.shape = shape;
  s.flip = flip;
  s.scheme = scheme;
  auto m = test::elastic_block<Dim>(s, Vec<Dim>::Constant(0.2), Vec<Dim>::Constant(0.8));
  auto& p = m->particles();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double scale = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int d = 0; d < Dim; ++d) p.v[i][d] = u(rng);
    scale += p.mass[i] * p.v[i].norm();
  }
  double particle_mass = 0.0;
  for (double mp : p.mass) particle_mass += mp;
  const auto grid_mass = [&] {
    double sum = 0.0;
    for (double mi : m->grid().mass) sum += mi;
    return sum;
  };

  SECTION("stress-free: mass and momentum to round-off") {
    // One step: particle momentum to the grid, back to the particles, and (MUSL) to the grid again.
    const Vec<Dim> before = m->momentum();
    m->step();
    CHECK(std::abs(grid_mass() - particle_mass) < 1e-14 * particle_mass);
    Vec<Dim> grid_momentum = Vec<Dim>::Zero();
    for (const auto& mv : m->grid().momentum) grid_momentum += mv;
    CHECK((grid_momentum - before).norm() < 1e-14 * scale);
    CHECK((m->momentum() - before).norm() < 1e-14 * scale);
  }

  SECTION("stressed: internal forces sum to zero to round-off") {
    for (auto& sigma : p.stress)
      for (int c = 0; c < 6; ++c) sigma[c] = 1e3 * u(rng);
    const Vec<Dim> before = m->momentum();
    m->step();
    Vec<Dim> total = Vec<Dim>::Zero();
    double magnitude = 0.0;
    for (const auto& f : m->grid().force) {
      total += f;
      magnitude += f.norm();
    }
    CAPTURE(total.norm() / magnitude);
    CHECK(total.norm() < 1e-14 * magnitude);
    CHECK(std::abs(grid_mass() - particle_mass) < 1e-14 * particle_mass);
    // Nodes below the mass threshold (1e-12 of a particle mass) take no acceleration; the
    // momentum they hold back is far below any physical scale.
    CHECK((m->momentum() - before).norm() < 1e-9 * scale);
  }
}
