// A cohesionless Mohr-Coulomb layer on a rough floor, set sliding at v0, shears on the floor and stops
// after d = v0^2 / (2 g sin phi): in plane-strain simple shear without dilatancy (psi = 0) the
// horizontal plane is the plane of no extension, where the stress at yield gives tau / sigma_n =
// sin phi. The distance does not depend on the elastic stiffness (the granular collapse's run-out on
// 4 mm cells does: not through the floor's friction, as this shows). With APIC on uGIMP the
// gradient a particle carries must be B D^-1: the gradient of the shape functions let the shear spread
// up through the layer, and its top slid 7 % too far on these cells.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "core/local_damping.hpp"
#include "core/model.hpp"
#include "materials/mohr_coulomb.hpp"

using namespace seismpm;

namespace {

constexpr double kFriction = 19.8;  // degrees, the aluminium bars of the granular collapse
constexpr double kG = 9.81;
// tau / sigma_n on the floor at yield.
double sin_phi() { return std::sin(kFriction * std::numbers::pi / 180); }

// How far the middle of a 1 m long, 0.02 m thick layer slides after it is set moving at v0 (m).
double sliding_distance(double young, ShapeKind shape, double v0) {
  ModelSettings<2> s;
  s.lower = Vec<2>(0, 0);
  s.upper = Vec<2>(1.5, 0.05);
  s.cell = 0.005;
  s.shape = shape;
  s.transfer = Transfer::Apic;
  s.gravity = Vec<2>(0, -kG);
  Model<2> m(s);
  MohrCoulombParameters p;
  p.density = 2650, p.young = young, p.poisson = 0.3, p.cohesion = 0, p.friction = kFriction, p.dilation = 0;
  const int mat = m.add_material(std::make_shared<MohrCoulomb>(p));
  // Ends at 12 degrees, flatter than the friction angle, so that the layer settles under gravity.
  const double thick = 0.02, x0 = 0.1, x1 = 1.1, run = thick / std::tan(12 * std::numbers::pi / 180);
  m.fill(m.add_body("layer", 2), mat, Vec<2>(x0, 0), Vec<2>(x1, thick), [&](const Vec<2>& x) {
    return x[1] <= thick * std::min({1.0, (x[0] - x0) / run, (x1 - x[0]) / run});
  });
  m.grid().fix(Side::Bottom, FixX | FixY);
  auto damping = std::make_shared<LocalDamping<2>>(0.7);
  m.add_fix(damping);
  m.run(0.3);
  m.remove_fix(damping.get());
  auto& P = m.particles();
  std::vector<double> start(P.size());  // by particle id: the model sorts its particles as they move
  for (std::size_t i = 0; i < P.size(); ++i) {
    start[P.id[i]] = P.x[i][0];
    P.v[i] = Vec<2>(v0, 0);
    P.affine[i].setZero();
  }
  m.run(1.5 * v0 / (kG * sin_phi()));  // 1.5 times the time to stop
  // The middle of the layer, away from its slumping ends, above the sheared cell row.
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < P.size(); ++i)
    if (const double s0 = start[P.id[i]]; std::abs(s0 - 0.5 * (x0 + x1)) < 0.05 && P.x[i][1] > 0.5 * thick)
      sum += P.x[i][0] - s0, ++count;
  REQUIRE(count > 0);
  return sum / count;
}

}  // namespace

TEST_CASE("a sheared layer stops after v0^2 / (2 g sin phi), whatever its stiffness",
          "[materials][mohr_coulomb][verification]") {
  const double v0 = 1.0;
  const double expected = v0 * v0 / (2 * kG * sin_phi());  // 0.150 m
  const double soft = sliding_distance(0.84e6, ShapeKind::Linear, v0);
  const double stiff = sliding_distance(8.4e6, ShapeKind::Linear, v0);
  const double gimp = sliding_distance(0.84e6, ShapeKind::Gimp, v0);
  CAPTURE(expected, soft, stiff, gimp);
  CHECK(soft == Approx(expected).epsilon(0.03));
  CHECK(stiff == Approx(expected).epsilon(0.03));
  CHECK(gimp == Approx(expected).epsilon(0.03));
  CHECK(std::abs(soft - stiff) < 0.01 * expected);
}
