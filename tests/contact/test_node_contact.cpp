// Bardenhagen contact at one node (src/contact/node_contact.hpp): approach and separation, stick and
// slip, glued fields, rigid fields and their reactions, a thin layer's far face, a corner, a wall's foot.
#include <catch2/catch.hpp>
#include <cmath>

#include "contact/node_contact.hpp"

using namespace seismpm;

namespace {

// Two deformable fields 1 and 2 (and a rigid field 3) at one node.
ContactRules rules(double mu) {
  ContactRules r;
  r.reset(4);
  r.set_rigid(3, true);
  r.set_friction(1, 2, mu);
  r.set_friction(1, 3, mu);
  return r;
}

NodeFields<2> pair(const Vec<2>& va, const Vec<2>& vb, double ma = 2.0, double mb = 1.0) {
  NodeFields<2> n;
  n.count = 2;
  n.field[0] = 1, n.field[1] = 2;
  n.mass[0] = ma, n.mass[1] = mb;
  n.gradient[0] = Vec<2>(0.0, -5.0);  // A's mass lies above the node (outward normal down) ...
  n.gradient[1] = Vec<2>(0.0, 4.0);   // ... B's below: the normal out of A toward B is -y
  n.velocity[0] = va, n.velocity[1] = vb;
  return n;
}

Vec<2> momentum(const NodeFields<2>& n) {
  Vec<2> p = Vec<2>::Zero();
  for (int j = 0; j < n.count; ++j) p += n.mass[j] * n.velocity[j];
  return p;
}

}  // namespace

TEST_CASE("contact at a node: approach, separation, stick and slip", "[contact]") {
  SECTION("approaching bodies get one normal velocity; momentum is kept") {
    auto n = pair(Vec<2>(0.0, -1.0), Vec<2>(0.0, 0.5));
    const Vec<2> before = momentum(n);
    resolve_contact<2>(n, rules(0.0), 1e-12, 0.1, 0.0, nullptr);
    CHECK(n.velocity[0][1] == Approx(n.velocity[1][1]).epsilon(1e-14));
    CHECK(n.velocity[0][1] == Approx((2.0 * -1.0 + 1.0 * 0.5) / 3.0));
    CHECK((momentum(n) - before).norm() < 1e-14);
  }
  SECTION("separating bodies keep their own velocities") {
    auto n = pair(Vec<2>(0.3, 1.0), Vec<2>(-0.2, -0.5));
    resolve_contact<2>(n, rules(1.0), 1e-12, 0.1, 0.0, nullptr);
    CHECK(n.velocity[0] == Vec<2>(0.3, 1.0));
    CHECK(n.velocity[1] == Vec<2>(-0.2, -0.5));
  }
  SECTION("smooth: the tangential velocities are untouched") {
    auto n = pair(Vec<2>(1.0, -1.0), Vec<2>(-2.0, 0.0));
    resolve_contact<2>(n, rules(0.0), 1e-12, 0.1, 0.0, nullptr);
    CHECK(n.velocity[0][0] == 1.0);
    CHECK(n.velocity[1][0] == -2.0);
  }
  SECTION("slip: the tangential change is mu times the normal one") {
    const double mu = 0.2;
    auto n = pair(Vec<2>(3.0, -1.0), Vec<2>(0.0, 0.0));
    const Vec<2> v0 = n.velocity[0], p0 = momentum(n);
    resolve_contact<2>(n, rules(mu), 1e-12, 0.1, 0.0, nullptr);
    const Vec<2> dv = n.velocity[0] - v0;
    CHECK(-dv[0] == Approx(mu * dv[1]).epsilon(1e-14));  // slows along x by mu |dv_n|
    CHECK(n.velocity[0][1] == Approx(n.velocity[1][1]).epsilon(1e-14));
    CHECK((momentum(n) - p0).norm() < 1e-14);
  }
  SECTION("stick: with enough friction both move with the centre of mass") {
    auto n = pair(Vec<2>(0.1, -1.0), Vec<2>(0.0, 0.0));
    const Vec<2> v_cm = momentum(n) / 3.0;
    resolve_contact<2>(n, rules(1.0), 1e-12, 0.1, 0.0, nullptr);
    CHECK((n.velocity[0] - v_cm).norm() < 1e-14);
    CHECK((n.velocity[1] - v_cm).norm() < 1e-14);
  }
  SECTION("without a declared pair the fields are glued, even when separating") {
    ContactRules glued;
    glued.reset(3);
    auto n = pair(Vec<2>(0.0, 1.0), Vec<2>(0.0, -1.0));
    const Vec<2> v_cm = momentum(n) / 3.0;
    resolve_contact<2>(n, glued, 1e-12, 0.1, 0.0, nullptr);
    CHECK((n.velocity[0] - v_cm).norm() < 1e-14);
    CHECK((n.velocity[1] - v_cm).norm() < 1e-14);
  }
  SECTION("a rigid field keeps its velocity and reports the force it gave") {
    NodeFields<2> n;
    n.count = 2;
    n.field[0] = 1, n.field[1] = 3;
    n.mass[0] = 2.0, n.mass[1] = 0.01;  // soil mass; rigid weight sum N V
    n.gradient[0] = Vec<2>(0.0, -5.0);
    n.gradient[1] = Vec<2>(0.0, 0.1);   // rigid material below (outward normal up)
    n.velocity[0] = Vec<2>(0.0, -0.4);  // soil falling onto ...
    n.velocity[1] = Vec<2>(2.0, 0.0);   // ... a base sliding at 2 m/s
    Vec<2> force[4] = {Vec<2>::Zero(), Vec<2>::Zero(), Vec<2>::Zero(), Vec<2>::Zero()};
    const double mu = 0.3, dt = 1e-3;
    resolve_contact<2>(n, rules(mu), 1e-12, 0.1, dt, force);
    CHECK(n.velocity[1] == Vec<2>(2.0, 0.0));
    CHECK(n.velocity[0][1] == Approx(0.0).margin(1e-15));        // no penetration
    CHECK(n.velocity[0][0] == Approx(mu * 0.4).epsilon(1e-14));  // dragged by mu |dv_n|
    CHECK(force[1][1] == Approx(2.0 * 0.4 / dt).epsilon(1e-14));
    CHECK(force[1][0] == Approx(2.0 * mu * 0.4 / dt).epsilon(1e-14));
  }
}

TEST_CASE("contact at a node: a thin rigid layer's far face and a corner of two rigid bodies", "[contact]") {
  ContactRules r;
  r.reset(3);
  r.set_rigid(1, true);
  r.set_rigid(2, true);
  r.set_friction(0, 1, 0.3);
  r.set_friction(0, 2, 0.0);
  SECTION("beyond a one-cell layer the soil's own normal keeps it from falling through") {
    NodeFields<2> n;
    n.count = 2;
    n.field[0] = 0, n.field[1] = 1;
    n.mass[0] = 0.01, n.mass[1] = 0.5;
    n.gradient[0] = Vec<2>(0.0, -0.2);  // soil far above the node: outward normal down
    n.gradient[1] = Vec<2>(0.0, -3.0);  // the layer just above the node: its outward normal down too
    n.velocity[0] = Vec<2>(0.0, -0.5);
    n.velocity[1] = Vec<2>(0.0, 0.0);
    resolve_contact<2>(n, r, 1e-12, 0.1, 0.0, nullptr);
    CHECK(n.velocity[0][1] == Approx(0.0).margin(1e-15));
  }
  SECTION("at a corner both constraints hold after the passes") {
    NodeFields<2> n;
    n.count = 3;
    n.field[0] = 0, n.field[1] = 1, n.field[2] = 2;
    n.mass[0] = 1.0, n.mass[1] = 0.3, n.mass[2] = 0.2;
    n.gradient[0] = Vec<2>(-1.0, -1.0);  // soil up and to the right of the corner
    n.gradient[1] = Vec<2>(0.0, 2.0);    // base below: outward up
    const Vec<2> wall_out = Vec<2>(1.0, -0.6).normalized();
    n.gradient[2] = 1.5 * wall_out;      // wall foot: outward tilted down
    n.velocity[0] = Vec<2>(-0.8, -0.2);  // sliding left and down into both
    n.velocity[1] = n.velocity[2] = Vec<2>::Zero();
    resolve_contact<2>(n, r, 1e-12, 0.1, 0.0, nullptr);
    const Vec<2>& v = n.velocity[0];
    CAPTURE(v);
    CHECK(v.dot(Vec<2>(0.0, -1.0)) <= 1e-12);  // not into the base
    CHECK(v.dot(-wall_out) <= 1e-12);          // not into the wall
  }
  SECTION("at a wall's foot the soil slides along the smooth wall, not off it") {
    // The wall stops at the base, so its gradient at the corner tilts down 45 degrees; the base's face
    // is flat there (a larger gradient). The wall's normal is its face's, -x, not the chamfer's.
    const Vec<2> wall_foot = std::sqrt(0.5) * Vec<2>(1.0, -1.0);
    for (const Vec<2>& v0 : {Vec<2>(0.0, 0.5), Vec<2>(-0.4, 0.5), Vec<2>(-0.4, 0.1)}) {
      NodeFields<2> n;
      n.count = 3;
      n.field[0] = 0, n.field[1] = 1, n.field[2] = 2;
      n.mass[0] = 1.0, n.mass[1] = 0.3, n.mass[2] = 0.2;
      n.gradient[0] = Vec<2>(-1.0, -1.0);
      n.gradient[1] = Vec<2>(0.0, 2.0);
      n.gradient[2] = 1.4 * wall_foot;
      n.velocity[0] = v0;
      n.velocity[1] = n.velocity[2] = Vec<2>::Zero();
      Vec<2> force[3] = {Vec<2>::Zero(), Vec<2>::Zero(), Vec<2>::Zero()};
      resolve_contact<2>(n, r, 1e-12, 0.1, 1e-3, force);
      CAPTURE(v0, n.velocity[0], force[2]);
      CHECK(n.velocity[0][0] == Approx(0.0).margin(1e-15));    // the push into the wall stopped, no more
      CHECK(n.velocity[0][1] == Approx(v0[1]).margin(1e-15));  // sliding up a smooth wall: untouched
      CHECK(force[2][1] == Approx(0.0).margin(1e-12));         // and the wall takes no shear
      CHECK(force[1].norm() == Approx(0.0).margin(1e-12));     // nor does the base, moving away from it
    }
  }
}
