// The gravity phase: K0 stresses from the overburden, the equilibrium measure, and the phase itself
// (Simulation::gravity_phase) bringing a column to rest.
#include <catch2/catch.hpp>

#include "core/error.hpp"
#include "core/local_damping.hpp"
#include "materials/linear_elastic.hpp"
#include "run/gravity_phase.hpp"
#include "run/simulation.hpp"

using namespace seismpm;

TEST_CASE("K0 stresses: sigma_v is the overburden of the layers above, sigma_h = k0 sigma_v", "[run][gravity]") {
  const int dim_case = GENERATE(2, 3);
  CAPTURE(dim_case);
  auto check = [](auto dim) {
    constexpr int Dim = decltype(dim)::value;
    ModelSettings<Dim> s;
    s.upper = Vec<Dim>::Constant(1.0);
    s.cell = 0.05;
    s.gravity = Vec<Dim>::Zero();
    s.gravity[Dim - 1] = -9.81;
    Model<Dim> m(s);
    // A clay layer 0.4 m thick (1600 kg/m3) under 0.3 m of sand (2000 kg/m3), different ppc; a rigid
    // base below that must not count.
    const int clay = m.add_material(std::make_shared<LinearElastic>(1600.0, 1e7, 0.3));
    const int sand = m.add_material(std::make_shared<LinearElastic>(2000.0, 1e7, 0.3));
    Vec<Dim> lo = Vec<Dim>::Zero(), hi = Vec<Dim>::Constant(1.0);
    lo[Dim - 1] = 0.1, hi[Dim - 1] = 0.5;
    m.fill_box(m.add_body("clay", 2), clay, lo, hi);
    lo[Dim - 1] = 0.5, hi[Dim - 1] = 0.8;
    m.fill_box(m.add_body("sand", 3), sand, lo, hi);
    lo[Dim - 1] = 0.0, hi[Dim - 1] = 0.1;
    m.fill_box(m.add_body("base", 1, true), -1, lo, hi);
    set_k0_stresses(m, 0.6);
    const auto& P = m.particles();
    double worst = 0.0;
    for (std::size_t p = 0; p < P.size(); ++p) {
      if (m.bodies()[P.body[p]].rigid) {
        CHECK(P.stress[p].norm() == 0.0);
        continue;
      }
      const double y = P.x[p][Dim - 1];
      const double exact = 9.81 * (y >= 0.5 ? 2000.0 * (0.8 - y) : 2000.0 * 0.3 + 1600.0 * (0.5 - y));
      worst = std::max(worst, std::abs(-P.stress[p][Dim - 1] - exact) / exact);
      CHECK(P.stress[p][0] == Approx(0.6 * P.stress[p][Dim - 1]).epsilon(1e-12));
      CHECK(P.stress[p][2 - (Dim == 3 ? 1 : 0)] == Approx(0.6 * P.stress[p][Dim - 1]).epsilon(1e-12));
      CHECK(P.stress[p].template tail<3>().norm() == 0.0);
    }
    CAPTURE(worst);
    CHECK(worst < 1e-12);
  };
  if (dim_case == 2)
    check(std::integral_constant<int, 2>{});
  else
    check(std::integral_constant<int, 3>{});
}

TEST_CASE("K0 needs gravity pointing down and k0 > 0", "[run][gravity][errors]") {
  ModelSettings<2> s;
  s.gravity = Vec<2>(9.81, 0.0);
  Model<2> m(s);
  CHECK_THROWS_WITH(set_k0_stresses(m, 0.5), Catch::Contains("gravity pointing down"));
  CHECK_THROWS_WITH(set_k0_stresses(m, 0.0), Catch::Contains("k0 must be > 0"));
}

namespace {

// A 0.4 m x 1 m elastic column on a fixed base between smooth walls.
void column(Model<2>& m) {
  const int mat = m.add_material(std::make_shared<LinearElastic>(2000.0, 1e7, 0.3));
  m.fill_box(m.add_body("column", 2), mat, Vec<2>(0.0, 0.0), Vec<2>(0.4, 1.0));
  m.grid().fix(Side::Bottom, FixX | FixY);
  m.grid().fix(Side::Left, FixX);
  m.grid().fix(Side::Right, FixX);
}

ModelSettings<2> column_settings() {
  ModelSettings<2> s;
  s.upper = Vec<2>(0.4, 1.2);
  s.cell = 0.05;
  s.gravity = Vec<2>(0.0, -9.81);
  return s;
}

}  // namespace

TEST_CASE("the equilibrium measure: all of the self-weight is unbalanced after the first step", "[run][gravity]") {
  Model<2> m(column_settings());
  column(m);
  m.add_fix(std::make_shared<LocalDamping<2>>(0.7));
  m.set_balance_measure(true);
  EquilibriumMonitor<2> eq(0.005);
  m.step();
  eq.update(m);
  CHECK(eq.force_ratio() == Approx(1.0).epsilon(0.05));
  CHECK(eq.energy_ratio() == Approx(1.0));  // the kinetic energy is its own peak so far
  CHECK_FALSE(eq.reached());
  CHECK_THAT(equilibrium_text(eq), Catch::StartsWith("unbalanced ") && Catch::EndsWith("of peak (tol 5e-03)"));
}

TEST_CASE("the gravity phase brings a column to rest: the base carries its weight", "[run][gravity]") {
  Simulation<2> sim(column_settings());
  column(sim.model());
  const GravityPhaseResult r = sim.gravity_phase(GravityPhaseSettings{0.7, 0.005, 3.0});
  const auto& m = sim.model();
  CAPTURE(r.time, r.steps, r.force_ratio, r.energy_ratio);
  CHECK(sim.phase() == "gravity");
  CHECK(r.time == m.time());
  CHECK(r.steps == m.steps());
  CHECK(r.steps > 10);
  CHECK(r.force_ratio < 0.005);
  CHECK(r.energy_ratio < 0.005);
  // At the end the column is where statics puts it (tested in Lua too), with displacements reset.
  const auto& P = m.particles();
  double bottom = 0.0, moved = 0.0;
  int n = 0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (P.x[p][1] < 0.05) bottom += P.stress[p][1], ++n;
    moved = std::max(moved, P.u[p].norm());
  }
  CHECK(-bottom / n == Approx(2000.0 * 9.81 * (1.0 - 0.025)).epsilon(0.02));
  CHECK(moved == 0.0);
}

TEST_CASE("a gravity phase that finds no equilibrium says so", "[run][gravity][errors]") {
  ModelSettings<2> s = column_settings();
  Simulation<2> sim(s);
  const int mat = sim.model().add_material(std::make_shared<LinearElastic>(2000.0, 1e7, 0.3));
  sim.model().fill_box(sim.model().add_body("falling", 2), mat, Vec<2>(0.1, 0.6), Vec<2>(0.3, 0.9));
  CHECK_THROWS_WITH(sim.gravity_phase(GravityPhaseSettings{0.7, 0.005, 0.05}),
                    Catch::StartsWith("no static equilibrium within max_time = 0.05 s: out-of-balance force") &&
                        Catch::Contains("the outputs show the state at t = 0.05 s") &&
                        Catch::Contains("; the fastest particles: 'falling' at (") &&
                        Catch::Contains("(largest speed per body: 'falling' "));
  CHECK(sim.model().time() == Approx(0.05).epsilon(1e-12));
  CHECK_FALSE(sim.running());
  Simulation<2> empty(s);
  CHECK_THROWS_WITH(empty.gravity_phase({}), "the model has no particles");
}
