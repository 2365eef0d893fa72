// A rigid face keeps the centres of the particles in contact with it out of the rigid body
// (src/contact/rigid_face_mirror.hpp). Failed before the mirror: a uGIMP centre whose domain reached
// past the face kept a weight at the first node on its own side and crossed the face.
#include <catch2/catch.hpp>
#include <cmath>

#include "core/history.hpp"
#include "support/models.hpp"
#include "support/nodal_velocity.hpp"

using namespace seismpm;

// An elastic block against a smooth rigid wall one cell thick (at rest), squeezed toward the wall's
// face by a nodal velocity field v_n = -c d (d: distance from the face, zero beyond it). Every centre,
// wherever its domain lies, then moves as forward Euler of that field: d_{k+1} = (1 - c dt) d_k.
// Before the mirror, uGIMP centres whose domain reached past the face ran ahead: with ppc 2 the
// first row ended 0.66 % of its distance from the face expected and crossed it instead.
TEMPLATE_TEST_CASE_SIG("a centre squeezed against a rigid face approaches it as the exact field moves it",
                       "[contact][rigid_face_mirror]", ((int Dim), Dim), 2, 3) {
  const auto shape = GENERATE(ShapeKind::Gimp, ShapeKind::Linear);
  const int ppc = GENERATE(1, 2, 3);
  const int axis = GENERATE(0, Dim - 1);
  const bool upper = GENERATE(false, true);  // the wall above the block along `axis`, or below it
  CAPTURE(to_string(shape), ppc, axis, upper);
  const double h = 0.1, rate = 10.0, dt = 1e-3;  // c dt = 0.01 per step
  ModelSettings<Dim> s;
  s.upper = Vec<Dim>::Constant(0.6);
  s.cell = h;
  s.shape = shape;
  s.fixed_dt = dt;
  // The block fills [0.1, 0.5] across and [0.2, 0.5] (wall below: [0.1, 0.2]) or [0.1, 0.4] (wall
  // above: [0.4, 0.5]) along the axis; the wall spans the whole domain across, so that its corners,
  // where its normal tilts, lie beyond the block's reach.
  Vec<Dim> lo = Vec<Dim>::Constant(0.1), hi = Vec<Dim>::Constant(0.5);
  Vec<Dim> wall_lo = Vec<Dim>::Zero(), wall_hi = Vec<Dim>::Constant(0.6);
  (upper ? hi : lo)[axis] = upper ? 0.4 : 0.2;
  wall_lo[axis] = upper ? 0.4 : 0.1;
  wall_hi[axis] = upper ? 0.5 : 0.2;
  const double face = upper ? 0.4 : 0.2;
  auto m = test::elastic_block<Dim>(s, lo, hi, ppc);
  std::array<std::shared_ptr<const History>, Dim> at_rest;
  at_rest.fill(std::make_shared<ConstantHistory>(0.0));
  const int wall = m->add_rigid_body("wall", 1, 7800, at_rest);
  m->fill_box(wall, -1, wall_lo, wall_hi);
  m->add_contact(0, wall, 0.0);
  m->add_fix(std::make_shared<test::NodalVelocityField<Dim>>(
      [&](const Vec<Dim>& x) { return test::towards_plane<Dim>(x, axis, upper, face, rate); }));

  auto& p = m->particles();
  std::vector<double> d0(p.size(), -1.0);
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.body[i] == 0) d0[p.id[i]] = std::abs(p.x[i][axis] - face);
  const int steps = 500;  // squeezed to 0.99^500 = 0.66 % of the distance
  REQUIRE_NOTHROW(m->run(steps * dt));
  REQUIRE(m->steps() == steps);
  const double factor = std::pow(1.0 - rate * dt, steps);
  double worst = 0.0, closest = INFINITY;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] != 0) continue;
    const double d = upper ? face - p.x[i][axis] : p.x[i][axis] - face;
    closest = std::min(closest, d);
    worst = std::max(worst, std::abs(d / (factor * d0[p.id[i]]) - 1.0));
  }
  CAPTURE(worst, closest);
  CHECK(closest > 0.0);
  CHECK(worst < 1e-9);  // round-off only
}

// The mirror acts on the normal component only: a block sliding along a smooth wall (the field
// tangential, uniform) keeps its speed to round-off, however close its centres are to the face.
TEST_CASE("sliding along a rigid face is left as it is", "[contact][rigid_face_mirror]") {
  const int ppc = GENERATE(1, 2, 3);
  CAPTURE(ppc);
  const double h = 0.1, dt = 1e-3, speed = 0.5;
  ModelSettings<2> s;
  s.upper = Vec<2>(1.2, 0.6);
  s.cell = h;
  s.fixed_dt = dt;
  auto m = test::elastic_block<2>(s, Vec<2>(0.1, 0.2), Vec<2>(0.5, 0.5), ppc);
  std::array<std::shared_ptr<const History>, 2> at_rest;
  at_rest.fill(std::make_shared<ConstantHistory>(0.0));
  const int base = m->add_rigid_body("base", 1, 7800, at_rest);
  m->fill_box(base, -1, Vec<2>(0.0, 0.1), Vec<2>(1.2, 0.2));
  m->add_contact(0, base, 0.0);
  // Sliding, and squeezed toward the base so that the lowest centres' domains reach past its face.
  m->add_fix(std::make_shared<test::NodalVelocityField<2>>(
      [&](const Vec<2>& x) { return Vec<2>(speed, -10.0 * std::max(x[1] - 0.2, 0.0)); }));
  auto& p = m->particles();
  std::vector<double> x0(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) x0[p.id[i]] = p.x[i][0];
  const int steps = 300;
  REQUIRE_NOTHROW(m->run(steps * dt));
  double worst = 0.0, lowest = INFINITY;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.body[i] == 0) {
      worst = std::max(worst, std::abs(p.x[i][0] - x0[p.id[i]] - speed * steps * dt));
      lowest = std::min(lowest, p.x[i][1]);
    }
  CAPTURE(worst, lowest);
  CHECK(worst < 1e-12);
  CHECK(lowest > 0.2);
}
