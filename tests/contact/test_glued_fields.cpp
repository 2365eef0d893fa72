// Bodies that take part in contact pairs but are not paired with each other are one continuum where
// they meet. Two soil layers, each in smooth contact with a rigid box, must settle like one layer:
// as fast, and with the overburden stress across their interface.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>

#include "core/history.hpp"
#include "materials/linear_elastic.hpp"
#include "run/simulation.hpp"

using namespace seismpm;

namespace {

constexpr double kWidth = 4.0, kHeight = 4.0, kCell = 0.25, kG = 9.81;
constexpr double kRhoLower = 2000.0, kRhoUpper = 1800.0;

// The ground [0, 4] x [0, 4] m in a rigid box one cell thick whose walls rise `rim` cells above it;
// `layers` = 1: one body of the lower soil, 2: the upper half a second body of a lighter, softer soil.
// Each soil body is in smooth contact with the box.
std::unique_ptr<Simulation<2>> ground_in_box(int layers, double rim) {
  ModelSettings<2> s;
  s.lower = Vec<2>(-2 * kCell, -2 * kCell);
  s.upper = Vec<2>(kWidth + 2 * kCell, kHeight + 3 * kCell);
  s.cell = kCell;
  s.gravity = Vec<2>(0.0, -kG);
  auto sim = std::make_unique<Simulation<2>>(s);
  auto& m = sim->model();
  const int lower_soil = m.add_material(std::make_shared<LinearElastic>(kRhoLower, 20e6, 0.3));
  const int upper_soil = m.add_material(std::make_shared<LinearElastic>(kRhoUpper, 10e6, 0.3));
  const auto still = std::make_shared<ConstantHistory>(0.0);
  const int box = m.add_rigid_body("box", 2, 2000.0, {still, still});
  const double top = kHeight + rim * kCell;
  m.fill(box, -1, Vec<2>(-kCell, -kCell), Vec<2>(kWidth + kCell, top),
         [&](const Vec<2>& x) { return x[1] < 0.0 || x[0] < 0.0 || x[0] > kWidth; });
  if (layers == 1) {
    const int ground = m.add_body("ground", 2);
    m.fill_box(ground, lower_soil, Vec<2>(0, 0), Vec<2>(kWidth, kHeight));
    m.add_contact(ground, box, 0.0);
  } else {
    const int lower = m.add_body("lower", 2), upper = m.add_body("upper", 2);
    m.fill_box(lower, lower_soil, Vec<2>(0, 0), Vec<2>(kWidth, kHeight / 2));
    m.fill_box(upper, upper_soil, Vec<2>(0, kHeight / 2), Vec<2>(kWidth, kHeight));
    m.add_contact(lower, box, 0.0);
    m.add_contact(upper, box, 0.0);
  }
  return sim;
}

double overburden(int layers, double y) {
  if (layers == 1 || y < kHeight / 2) {
    const double above_lower = (layers == 1 ? kHeight : kHeight / 2) - y;
    return kG * (kRhoLower * above_lower + (layers == 1 ? 0.0 : kRhoUpper * kHeight / 2));
  }
  return kG * kRhoUpper * (kHeight - y);
}

// The worst error of the cell rows' mean sigma_v against the overburden at their mean height, over
// the rows below the top one (the free surface's row carries a small stress, off by a large share).
double worst_row_error(const Model<2>& m, int layers) {
  struct Row {
    double stress = 0.0, y = 0.0;
    int n = 0;
  };
  std::map<int, Row> rows;
  const auto& P = m.particles();
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (m.bodies()[P.body[p]].rigid) continue;
    Row& r = rows[static_cast<int>(std::floor(P.x[p][1] / kCell))];
    r.stress -= P.stress[p][1], r.y += P.x[p][1], ++r.n;
  }
  double worst = 0.0;
  for (const auto& [k, r] : rows) {
    if (k >= static_cast<int>(kHeight / kCell) - 1) continue;
    const double exact = overburden(layers, r.y / r.n);
    worst = std::max(worst, std::abs(r.stress / r.n - exact) / exact);
  }
  return worst;
}

}  // namespace

TEST_CASE("glued bodies in different contact fields: a two-layer ground in a smooth box settles as one layer does",
          "[contact][glued][verification]") {
  const GravityPhaseSettings phase{0.7, 0.005, 5.0};
  const double rim = 2.0;  // the walls rise two cells above the ground
  auto one = ground_in_box(1, rim);
  const GravityPhaseResult r1 = one->gravity_phase(phase);
  auto two = ground_in_box(2, rim);
  const GravityPhaseResult r2 = two->gravity_phase(phase);  // threw "no static equilibrium" before
  INFO("one layer: " << r1.time << " s, two layers: " << r2.time << " s");
  CHECK(r2.time < 1.25 * r1.time);
  const double e1 = worst_row_error(one->model(), 1), e2 = worst_row_error(two->model(), 2);
  INFO("worst row error of sigma_v: one layer " << e1 << ", two layers " << e2);
  CHECK(e1 < 0.03);
  CHECK(e2 < 0.03);
  // At rest as the one layer is: no faster particle anywhere (before, the rows at the interface still
  // moved at 0.03 m/s after 5 s).
  const auto fastest = [](const Model<2>& m) {
    double v = 0.0;
    for (std::size_t p = 0; p < m.particles().size(); ++p) v = std::max(v, m.particles().v[p].norm());
    return v;
  };
  INFO("fastest particle: one layer " << fastest(one->model()) << " m/s, two layers " << fastest(two->model()));
  CHECK(fastest(two->model()) < 1.5 * fastest(one->model()));
}
