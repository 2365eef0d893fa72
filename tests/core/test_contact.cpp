// Multi-body frictional contact (Bardenhagen) and prescribed-velocity rigid bodies: whole bodies against
// closed-form answers (the correction at one node: tests/contact/test_node_contact.cpp).
#include <catch2/catch.hpp>
#include <cmath>

#include "cases/moving_base_block.hpp"
#include "core/error.hpp"
#include "core/history.hpp"
#include "core/local_damping.hpp"
#include "core/model.hpp"
#include "materials/linear_elastic.hpp"
#include "materials/mohr_coulomb.hpp"

using namespace seismpm;

TEST_CASE("moving base: a smooth base leaves the block behind", "[core][contact][rigid]") {
  cases::MovingBaseBlock c;
  c.friction = 0.0;
  auto b = c.build();
  c.settle_and_start(b);
  const Vec<2> x0 = b.model->centroid(b.block);
  double vmax = 0.0;
  while (b.model->phase_time() < 0.8) {
    b.model->step(0.8 - b.model->phase_time());
    const auto& P = b.model->particles();
    double p = 0.0, m = 0.0;
    for (std::size_t i = 0; i < P.size(); ++i)
      if (P.body[i] == b.block) p += P.mass[i] * P.v[i][0], m += P.mass[i];
    vmax = std::max(vmax, std::abs(p / m));
  }
  CAPTURE(vmax, b.model->centroid(b.block) - x0);
  CHECK(vmax < 1e-3);
  CHECK(std::abs(b.model->centroid(b.block)[0] - x0[0]) < 1e-3);
  CHECK(b.model->centroid(b.base)[0] == Approx(-0.25 + 2.0 * 0.8).epsilon(1e-9));
}

TEST_CASE("moving base: Coulomb friction accelerates the block at mu g, then it rides along",
          "[core][contact][rigid][verification]") {
  cases::MovingBaseBlock c;
  c.friction = 0.3;
  auto b = c.build();
  c.settle_and_start(b);
  const double x0 = b.model->centroid(b.block)[0];
  const double t_star = c.base_speed / (c.friction * c.gravity);  // 0.680 s
  double worst = 0.0;
  for (double t : {0.2, 0.4, 0.6, t_star, 0.8, 1.0}) {
    b.simulation->run(t - b.model->phase_time());
    const double u = b.model->centroid(b.block)[0] - x0;
    const double exact = c.exact_displacement(t);
    CAPTURE(t, u, exact);
    worst = std::max(worst, std::abs(u - exact) / exact);
    CHECK(std::abs(u - exact) < 0.03 * exact);
  }
  WARN("largest relative error of the centroid displacement: " << worst);
}

TEST_CASE("moving base: without contact the block is carried along", "[core][contact][rigid]") {
  cases::MovingBaseBlock c;
  c.contact = cases::BaseContact::None;
  auto b = c.build();
  c.settle_and_start(b);
  const double x0 = b.model->centroid(b.block)[0];
  b.simulation->run(0.5);
  // The bottom moves with the base at once; shear waves make the rest oscillate about it.
  const double u = b.model->centroid(b.block)[0] - x0;
  CAPTURE(u);
  CHECK(u == Approx(2.0 * 0.5).epsilon(0.05));
}

TEST_CASE("a rigid base carries the weight of a block: reaction = weight", "[core][contact][rigid]") {
  for (auto mode : {cases::BaseContact::None, cases::BaseContact::Friction}) {
    cases::MovingBaseBlock c;
    c.contact = mode;
    auto b = c.build();
    b.simulation->gravity_phase(c.settle);  // at rest, still damped after it
    const Vec<2> impulse0 = b.model->rigid_motion(b.base).impulse;
    b.simulation->run(0.1);
    const Vec<2> mean = (b.model->rigid_motion(b.base).impulse - impulse0) / 0.1;
    const double weight = c.unit_weight * 1.0;  // N per metre out of plane
    CAPTURE(mean, weight);
    CHECK(mean[1] == Approx(weight).epsilon(0.01));
    CHECK(std::abs(mean[0]) < 1e-3 * weight);
  }
}

namespace {

// Two elastic blocks side by side, no gravity, no walls; A on [0, 0.5] and B on [0.5, 0.8] (one body
// ends where the other starts, on a cell boundary), each with its own initial velocity.
struct TwoBlocks {
  std::unique_ptr<Model<2>> m;
  int a, b;
  TwoBlocks(double va, double vb, bool contact, ShapeKind shape = ShapeKind::Gimp) {
    ModelSettings<2> s;
    s.lower = Vec<2>(-1.0, -0.3);
    s.upper = Vec<2>(2.0, 0.6);
    s.cell = 0.1;
    s.shape = shape;
    m = std::make_unique<Model<2>>(s);
    const int mat = m->add_material(std::make_shared<LinearElastic>(1000.0, 1e6, 0.3));
    a = m->add_body("a", 2);
    b = m->add_body("b", 2);
    m->fill_box(a, mat, Vec<2>(0.0, 0.0), Vec<2>(0.5, 0.3));
    m->fill_box(b, mat, Vec<2>(0.5, 0.0), Vec<2>(0.8, 0.3));
    if (contact) m->add_contact(a, b, 0.0);
    auto& P = m->particles();
    for (std::size_t p = 0; p < P.size(); ++p) P.v[p] = Vec<2>(P.body[p] == a ? va : vb, 0.0);
  }
  double velocity(int body) const {
    const auto& P = m->particles();
    double p = 0.0, mass = 0.0;
    for (std::size_t i = 0; i < P.size(); ++i)
      if (P.body[i] == body) p += P.mass[i] * P.v[i][0], mass += P.mass[i];
    return p / mass;
  }
  // Distance from A's rightmost particle to B's leftmost one.
  double gap() const {
    const auto& P = m->particles();
    double right_a = -1e9, left_b = 1e9;
    for (std::size_t i = 0; i < P.size(); ++i)
      if (P.body[i] == a)
        right_a = std::max(right_a, P.x[i][0]);
      else
        left_b = std::min(left_b, P.x[i][0]);
    return left_b - right_a;
  }
  double max_stress() const {
    double s = 0.0;
    for (const auto& sig : m->particles().stress) s = std::max(s, sig.cwiseAbs().maxCoeff());
    return s;
  }
};

}  // namespace

TEST_CASE("bodies in contact pulled apart separate freely; glued ones do not", "[core][contact]") {
  SECTION("contact: no tension across the interface") {
    TwoBlocks t(-0.5, 0.5, true);
    t.m->run(0.2);
    CAPTURE(t.velocity(t.a), t.velocity(t.b), t.max_stress());
    CHECK(t.velocity(t.a) == Approx(-0.5).epsilon(1e-9));
    CHECK(t.velocity(t.b) == Approx(0.5).epsilon(1e-9));
    CHECK(t.max_stress() < 1e-6);
    CHECK(t.gap() == Approx(0.05 + 0.2 * 1.0).epsilon(1e-6));  // half a particle spacing + 0.2 s at 1 m/s
  }
  SECTION("no contact declared: one field, the bodies hold together") {
    TwoBlocks t(-0.5, 0.5, false);
    t.m->run(0.2);
    CAPTURE(t.velocity(t.a), t.velocity(t.b), t.max_stress());
    CAPTURE(t.gap());
    CHECK(t.gap() < 0.06);  // the particles next to the interface stay at their spacing
    CHECK(t.max_stress() > 1e3);
  }
}

TEST_CASE("colliding bodies conserve momentum, bounce and separate", "[core][contact][verification]") {
  const auto shape = GENERATE(ShapeKind::Gimp, ShapeKind::Linear);
  TwoBlocks t(0.3, -0.6, true, shape);
  const Vec<2> p0 = t.m->momentum();
  double worst = 0.0;
  for (int k = 0; k < 20; ++k) {
    t.m->run(0.02);
    worst = std::max(worst, (t.m->momentum() - p0).norm() / p0.norm());
  }
  CAPTURE(worst, t.velocity(t.a), t.velocity(t.b));
  WARN("momentum drift over the collision: " << std::scientific << worst << " relative");
  CHECK(worst < 1e-10);
  // After the collision A moves left relative to B: they separated.
  CHECK(t.velocity(t.a) < t.velocity(t.b));
}

TEST_CASE("a rigid body leaving the grid stops the run, naming it", "[core][contact][rigid][failures]") {
  cases::MovingBaseBlock c;
  auto b = c.build();
  b.model->set_rigid_velocity(b.base,
                              {std::make_shared<ConstantHistory>(-50.0), std::make_shared<ConstantHistory>(0.0)});
  try {
    b.simulation->run(0.1);
    FAIL("the run went on");
  } catch (const SimulationError& e) {
    const std::string what = e.what();
    CAPTURE(what);
    CHECK(what.find("rigid body 'base'") != std::string::npos);
    CHECK(what.find("t = ") != std::string::npos);
    CHECK(what.find("leave the grid") != std::string::npos);
  }
}

TEST_CASE("contact declarations are checked", "[core][contact][errors]") {
  ModelSettings<2> s;
  Model<2> m(s);
  const int a = m.add_body("a", 2), b = m.add_body("b", 2), r = m.add_body("r", 2, true), q = m.add_body("q", 2, true);
  CHECK_THROWS_WITH(m.add_contact(a, b, -0.1), Catch::Contains("friction"));
  CHECK_THROWS_WITH(m.add_contact(a, a, 0.1), Catch::Contains("itself"));
  CHECK_THROWS_WITH(m.add_contact(a, 7, 0.1), Catch::Contains("unknown body"));
  CHECK_THROWS_WITH(m.add_contact(r, q, 0.1), Catch::Contains("both rigid"));
  m.add_contact(a, r, 0.5);
  CHECK_THROWS_WITH(m.add_contact(r, a, 0.5), Catch::Contains("declared already"));
}

TEST_CASE("a rough base and a smooth wall meeting at a corner share the load without double counting",
          "[core][contact][rigid]") {
  ModelSettings<2> s;
  s.lower = Vec<2>(-0.3, -0.3);
  s.upper = Vec<2>(1.0, 1.0);
  s.cell = 0.1;
  s.gravity = Vec<2>(-3.0, -9.81);  // leaning on the wall
  Model<2> m(s);
  const int mat = m.add_material(std::make_shared<LinearElastic>(1000.0, 5e6, 0.3));
  const int soil = m.add_body("soil", 2);
  m.fill_box(soil, mat, Vec<2>(0.0, 0.0), Vec<2>(0.5, 0.5));
  const int base = m.add_body("base", 2, true), wall = m.add_body("wall", 2, true);
  m.fill_box(base, -1, Vec<2>(-0.2, -0.1), Vec<2>(0.9, 0.0));
  m.fill_box(wall, -1, Vec<2>(-0.1, 0.0), Vec<2>(0.0, 0.8));
  m.add_contact(soil, base, 1.0);
  m.add_contact(soil, wall, 0.0);
  auto damping = std::make_shared<LocalDamping<2>>(0.7);
  m.add_fix(damping);
  m.run(1.0);
  const Vec<2> b0 = m.rigid_motion(base).impulse, w0 = m.rigid_motion(wall).impulse;
  m.run(0.1);
  const Vec<2> on_base = (m.rigid_motion(base).impulse - b0) / 0.1, on_wall = (m.rigid_motion(wall).impulse - w0) / 0.1;
  const double mass = 1000.0 * 0.25;
  CAPTURE(on_base, on_wall);
  CHECK(on_base[1] + on_wall[1] == Approx(mass * 9.81).epsilon(0.01));
  CHECK(on_base[0] + on_wall[0] == Approx(mass * 3.0).epsilon(0.01));
  CHECK(std::abs(on_wall[1]) < 0.01 * mass * 9.81);  // a smooth wall takes no shear
  CHECK(on_wall[0] > 0.5 * mass * 3.0);              // and most of the push
}

TEST_CASE("a shaken box: the soil in the corner of a rough base and a smooth wall stays out of the wall",
          "[core][contact][rigid]") {
  // Masa soil (the shaking-table case) 0.1 m deep in a 0.2 m box with one-cell walls, shaken at
  // 4 Hz, 0.15 m/s. At the wall's foot the wall's own gradient tilts toward the base; taken as the
  // wall's normal it pushed the sliding soil off the wall into tension, and the corner particle
  // ratcheted toward the wall: 5 % of its distance in 1.5 s here, and through it in the 0.375 cm
  // shaking-table run.
  const double h = 0.01, L = 0.2;
  ModelSettings<2> s;
  s.lower = Vec<2>(-2 * h - 0.03, -2 * h);
  s.upper = Vec<2>(L + 2 * h + 0.03, 0.15);
  s.cell = h;
  s.gravity = Vec<2>(0.0, -9.81);
  s.flip = 0.98;
  Model<2> m(s);
  MohrCoulombParameters mc;
  mc.density = 1680, mc.young = 2.57e6, mc.poisson = 0.33, mc.cohesion = 780, mc.friction = 23;
  const int mat = m.add_material(std::make_shared<MohrCoulomb>(mc));
  const int soil = m.add_body("soil", 2);
  m.fill_box(soil, mat, Vec<2>(0.0, 0.0), Vec<2>(L, 0.1));
  const auto table = std::make_shared<FunctionHistory>(
      [](double t) { return 0.15 * std::sin(2 * std::acos(-1.0) * 4.0 * t); }, "table");
  const std::array<std::shared_ptr<const History>, 2> v{table, std::make_shared<ConstantHistory>(0.0)};
  const int base = m.add_rigid_body("base", 1, 7800, v);
  const int left = m.add_rigid_body("left", 1, 7800, v), right = m.add_rigid_body("right", 1, 7800, v);
  m.fill_box(base, -1, Vec<2>(-h, -h), Vec<2>(L + h, 0.0));
  m.fill_box(left, -1, Vec<2>(-h, 0.0), Vec<2>(0.0, 0.12));
  m.fill_box(right, -1, Vec<2>(L, 0.0), Vec<2>(L + h, 0.12));
  m.add_contact(soil, base, 1.0);
  m.add_contact(soil, left, 0.0);
  m.add_contact(soil, right, 0.0);
  m.begin_phase(false);
  auto damping = std::make_shared<LocalDamping<2>>(0.7);
  m.add_fix(damping);
  m.run(0.3);
  m.remove_fix(damping.get());
  m.begin_phase(true);
  // The corner particle (the first one filled) against the wall's inner face.
  const auto gap = [&] {
    const auto& P = m.particles();
    std::size_t p = 0;
    while (P.id[p] != 0) ++p;  // the model sorts its particles by cell
    return P.x[p][0] - (m.centroid(left)[0] + 0.5 * h);
  };
  const double gap0 = gap();
  REQUIRE(gap0 == Approx(0.25 * h).epsilon(0.01));
  double smallest = gap0;
  while (m.phase_time() < 1.5) {
    m.run(0.05);
    smallest = std::min(smallest, gap());
  }
  CAPTURE(gap0, smallest, gap());
  // The wall's elastic squeeze of the soil is under a micrometre; plastic flow at the corner squeezes
  // the particle a little (0.18 % of a cell measured), the chamfer made it 1.3 %.
  CHECK(smallest > gap0 - 0.005 * h);
}
