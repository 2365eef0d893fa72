// Edge boundaries through the phases (Simulation::add_boundary): they hold like fixities in the gravity
// phase and keep its reaction afterwards, so the ground neither sinks nor jumps when shaking starts.
#include <catch2/catch.hpp>

#include "core/error.hpp"
#include "materials/linear_elastic.hpp"
#include "run/simulation.hpp"

using namespace seismpm;

namespace {

// A slope 20 m wide, 10 m high at the left and 6 m at the right, elastic soil (Vs 100 m/s), gravity.
std::unique_ptr<Simulation<2>> field_slope(ShapeKind shape) {
  ModelSettings<2> s;
  s.lower = Vec<2>(0.0, 0.0);
  s.upper = Vec<2>(20.0, 10.0);
  s.cell = 0.5;
  s.shape = shape;
  s.gravity = Vec<2>(0.0, -9.81);
  auto sim = std::make_unique<Simulation<2>>(s);
  auto& m = sim->model();
  const int soil = m.add_material(std::make_shared<LinearElastic>(2000.0, 5e7, 0.25));
  m.fill(m.add_body("soil", 2), soil, Vec<2>(0.0, 0.0), Vec<2>(20.0, 10.0),
         [](const Vec<2>& x) { return x[1] < 10.0 - std::max(0.0, x[0] - 12.0) * 0.5; });
  return sim;
}

}  // namespace

TEST_CASE("after a gravity phase on absorbing and compliant edges the ground stays where it settled",
          "[run][boundary]") {
  const auto shape = GENERATE(ShapeKind::Linear, ShapeKind::Gimp);
  const bool compliant = GENERATE(true, false);
  CAPTURE(to_string(shape), compliant);
  auto sim = field_slope(shape);
  BoundarySettings<2> base;
  base.side = Side::Bottom;
  base.kind = compliant ? BoundaryKind::Compliant : BoundaryKind::Absorbing;
  if (compliant) base.density = 2400.0, base.vs = 400.0, base.vp = 700.0;
  sim->add_boundary(base);
  for (Side side : {Side::Left, Side::Right}) {
    BoundarySettings<2> b;
    b.side = side;
    b.kind = compliant ? BoundaryKind::FreeField : BoundaryKind::Absorbing;
    sim->add_boundary(b);
  }
  GravityPhaseSettings g;
  g.tolerance = 5e-4;
  sim->gravity_phase(g);
  // The edges are released, the grid holds nothing.
  for (const auto& b : sim->boundaries()) CHECK_FALSE(b->holding());
  CHECK(sim->model().grid().fixed_nodes().empty());
  const auto& P = sim->model().particles();
  std::vector<Sym> settled(P.size());  // by particle id: the dynamic phase sorts particles
  for (std::size_t p = 0; p < P.size(); ++p) settled[P.id[p]] = P.stress[p];
  double weight = 0.0;  // the overburden at the base, for the stress scale
  for (std::size_t p = 0; p < P.size(); ++p) weight = std::max(weight, std::abs(P.stress[p][1]));
  sim->dynamic_phase(1.0, 0.0);
  double moved = 0.0, changed = 0.0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    moved = std::max(moved, P.u[p].norm());
    changed = std::max(changed, (P.stress[p] - settled[P.id[p]]).norm() / weight);
  }
  // Without the kept reaction the base's dashpots alone carry the weight: the ground sinks at
  // rho g H / (rho_r Vp_r), 0.12 m/s on the compliant base, 0.11 m in the second.
  CAPTURE(moved, changed);
  CHECK(moved < 1e-4);  // m, of 16 mm of elastic settlement in the gravity phase
  CHECK(changed < 1e-3);
}

TEST_CASE("an edge is either fixed or a boundary; boundaries name what is wrong", "[run][boundary]") {
  auto sim = field_slope(ShapeKind::Linear);
  BoundarySettings<2> b;
  b.side = Side::Bottom;
  b.kind = BoundaryKind::Compliant;
  CHECK_THROWS_WITH(sim->add_boundary(b), Catch::Contains("half-space"));
  b.kind = BoundaryKind::FreeField;
  CHECK_THROWS_WITH(sim->add_boundary(b), Catch::Contains("lateral side"));
  b.kind = BoundaryKind::Absorbing;
  sim->add_boundary(b);
  CHECK_THROWS_WITH(sim->add_boundary(b), Catch::Contains("has a boundary already"));
  sim->model().grid().fix(Side::Left, FixX);
  b.side = Side::Left;
  CHECK_THROWS_WITH(sim->add_boundary(b), Catch::Contains("held by m:fix"));
}
