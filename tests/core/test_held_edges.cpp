// A held grid edge keeps particle centres inside (src/core/held_edges.hpp). Failed before the
// mirror: a uGIMP centre on the edge kept a quarter of its half-width as weight at the first interior
// node and crossed the edge ("left the grid").
#include <catch2/catch.hpp>
#include <cmath>

#include "materials/mohr_coulomb.hpp"
#include "support/models.hpp"
#include "support/nodal_velocity.hpp"

using namespace seismpm;

// The nodes follow v_n = -c d (d: distance from the held edge) exactly, so every centre, wherever its
// domain lies, moves as forward Euler of that field: d_{k+1} = (1 - c dt) d_k. Linear and uGIMP shapes
// reproduce a linear field exactly where a particle's domain lies inside the grid; with the mirror
// also where it reaches past the held edge. Before, uGIMP centres there ran ahead and crossed.
TEMPLATE_TEST_CASE_SIG("a centre squeezed against a held edge approaches it as the exact field moves it",
                       "[core][held_edges]", ((int Dim), Dim), 2, 3) {
  const auto shape = GENERATE(ShapeKind::Gimp, ShapeKind::Linear);
  const int ppc = GENERATE(1, 2, 3);
  const int axis = GENERATE(0, Dim - 1);
  const bool upper = GENERATE(false, true);
  CAPTURE(to_string(shape), ppc, axis, upper);
  const double size = 0.4, h = 0.1, rate = 10.0, dt = 1e-3;  // c dt = 0.01 per step
  ModelSettings<Dim> s;
  s.upper = Vec<Dim>::Constant(size);
  s.cell = h;
  s.shape = shape;
  s.fixed_dt = dt;
  auto m = test::elastic_block<Dim>(s, Vec<Dim>::Constant(0.0), Vec<Dim>::Constant(size), ppc);
  const Side side = static_cast<Side>(2 * axis + (upper ? 1 : 0));
  m->grid().fix(side, 1u << axis);
  const double edge = upper ? m->grid().domain_upper()[axis] : 0.0;
  m->add_fix(std::make_shared<test::NodalVelocityField<Dim>>(
      [&](const Vec<Dim>& x) { return test::towards_plane<Dim>(x, axis, upper, edge, rate); }));

  auto& p = m->particles();
  std::vector<double> d0(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) d0[p.id[i]] = std::abs(p.x[i][axis] - edge);
  const int steps = 500;  // squeezed to 0.99^500 = 0.66 % of the distance
  REQUIRE_NOTHROW(m->run(steps * dt));
  REQUIRE(m->steps() == steps);
  const double factor = std::pow(1.0 - rate * dt, steps);
  double worst = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double d = upper ? edge - p.x[i][axis] : p.x[i][axis] - edge;
    REQUIRE(d > 0.0);
    worst = std::max(worst, std::abs(d / (factor * d0[p.id[i]]) - 1.0));
  }
  CAPTURE(worst);
  CHECK(worst < 1e-9);  // round-off only: the weights of each step carry about 1e-16 of a cell
}

// The granular column of the collapse test (0.2 m x 0.1 m) against a held wall and floor, coarse: c = 0
// sand with phi = 19.8 deg flowing out over the floor. Before the mirror a centre under the flow
// crossed the floor (ppc 2: y = -2.6e-7 m at t = 0.88 s; ppc 3: y = -4.4e-7 m at t = 0.99 s) and the run
// stopped with "left the grid".
TEST_CASE("a granular column collapsing against a held wall and floor stays inside", "[core][held_edges]") {
  struct Case {
    int ppc;
    double cell, length;
  };
  const Case c = GENERATE(Case{2, 0.006, 1.0}, Case{3, 0.007, 1.2});
  CAPTURE(c.ppc, c.cell);
  ModelSettings<2> s;
  s.upper = Vec<2>(c.length, 0.12);
  s.cell = c.cell;
  s.shape = ShapeKind::Gimp;
  s.gravity = Vec<2>(0.0, -9.81);
  Model<2> m(s);
  MohrCoulombParameters sand;
  sand.density = 2650;
  sand.young = 8.4e5;
  sand.poisson = 0.3;
  sand.friction = 19.8;
  const int mat = m.add_material(std::make_shared<MohrCoulomb>(sand));
  m.fill_box(m.add_body("column", c.ppc), mat, Vec<2>(0.0, 0.0), Vec<2>(0.2, 0.1));
  m.grid().fix(Side::Left, FixX);
  m.grid().fix(Side::Bottom, FixX | FixY);
  REQUIRE_NOTHROW(m.run(1.1));
  double lowest = INFINITY, leftmost = INFINITY, front = 0.0;
  for (const auto& x : m.particles().x) {
    leftmost = std::min(leftmost, x[0]);
    lowest = std::min(lowest, x[1]);
    front = std::max(front, x[0]);
  }
  CAPTURE(leftmost, lowest, front);
  CHECK(leftmost >= 0.0);
  CHECK(lowest >= 0.0);
  CHECK(front > 0.3);  // it did flow out (run-out 0.44-0.46 m in the experiment)
}

// A FLIP update adds sum N a dt to a particle's velocity. Where a held edge stops the grid, its nodes'
// acceleration must be the change that stops them, (0 - mv/m) / dt; with the acceleration zeroed
// there (the old rule) the particles kept the momentum the edge had taken from the grid and pushed it
// into the edge again on every step. A stress-free block moving at v0 towards a held edge: after one
// step the particles hold exactly the momentum the grid kept, v0 (M - mass of the held nodes); the old
// rule left all of M v0 (a relative error equal to the held nodes' share of the mass, 10-25 % here).
TEMPLATE_TEST_CASE_SIG("under FLIP the particles lose the momentum a held edge takes from the grid",
                       "[core][held_edges]", ((int Dim), Dim), 2, 3) {
  const auto shape = GENERATE(ShapeKind::Gimp, ShapeKind::Linear);
  const int ppc = GENERATE(2, 3);
  const bool upper = GENERATE(false, true);
  CAPTURE(to_string(shape), ppc, upper);
  const double size = 0.4, h = 0.1, dt = 1e-5, v0 = 2.0;
  const int axis = Dim - 1;
  ModelSettings<Dim> s;
  s.upper = Vec<Dim>::Constant(size);
  s.cell = h;
  s.shape = shape;
  s.fixed_dt = dt;
  auto m = test::elastic_block<Dim>(s, Vec<Dim>::Constant(0.0), Vec<Dim>::Constant(size), ppc);
  m->grid().fix(upper ? Side::Top : Side::Bottom, 1u << axis);
  auto& p = m->particles();
  double total_mass = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.v[i].setZero();
    p.v[i][axis] = upper ? v0 : -v0;
    total_mass += p.mass[i];
  }
  REQUIRE_NOTHROW(m->run(dt));
  REQUIRE(m->steps() == 1);
  double held_mass = 0.0;  // the grid's nodal masses of this step, still in place after it
  for (const int node : m->grid().fixed_nodes()) held_mass += m->grid().mass[node];
  REQUIRE(held_mass > 0.05 * total_mass);
  double momentum = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) momentum += p.mass[i] * p.v[i][axis];
  const double expected = (upper ? v0 : -v0) * (total_mass - held_mass);
  CAPTURE(held_mass / total_mass, momentum, expected);
  // The stress the step's own strain adds is of order E dt v0 / h: its force acts in the next step.
  CHECK(std::abs(momentum / expected - 1.0) < 1e-9);
}
