// The contact unit's bookkeeping (src/contact/contact_fields.*): which bodies get a field of their own,
// how declared pairs are checked and numbered, the rigid bodies' prescribed velocities, and which
// nodes become shared when a block rests on a rigid base.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <set>

#include "contact/contact_fields.hpp"
#include "core/error.hpp"
#include "core/model.hpp"
#include "materials/linear_elastic.hpp"

using namespace seismpm;

namespace {

std::vector<Body> four_bodies() {
  return {Body{"soil", 2, false, -1}, Body{"block", 2, false, -1}, Body{"base", 1, true, -1},
          Body{"fill", 2, false, -1}};
}

ContactFields<2> fields_for(const std::vector<Body>& bodies) {
  ContactFields<2> c;
  for (std::size_t b = 0; b < bodies.size(); ++b) c.add_body();
  return c;
}

}  // namespace

TEST_CASE("contact fields: unpaired deformable bodies share field 0, rigid and paired ones get their own",
          "[contact]") {
  const auto bodies = four_bodies();
  auto c = fields_for(bodies);
  c.add_pair(bodies, 1, 2, 0.3);
  REQUIRE(c.prepare(bodies));
  CHECK(c.field_of(0) == 0);
  CHECK(c.field_of(1) == 1);
  CHECK(c.field_of(2) == 2);
  CHECK(c.field_of(3) == 0);  // glued to the soil: one velocity field
  CHECK(c.rules().fields() == 3);
  CHECK(c.rules().rigid(2));
  CHECK_FALSE(c.rules().rigid(1));
  CHECK(c.rules().friction(1, 2) == 0.3);
  CHECK(c.rules().friction(2, 1) == 0.3);
  CHECK(c.rules().glued(0, 2));  // the soil meets the base without a declared pair
  CHECK(c.any_rigid());
  CHECK(c.rigid(2));
  CHECK_FALSE(c.rigid(0));

  SECTION("a new friction is numbered at the next step") {
    c.set_friction(bodies, 2, 1, 0.0);  // either order names the pair
    REQUIRE(c.prepare(bodies));
    CHECK(c.rules().friction(1, 2) == 0.0);
    CHECK_FALSE(c.rules().glued(1, 2));
  }
}

TEST_CASE("contact fields: deformable bodies without pairs need no contact at all", "[contact]") {
  const std::vector<Body> bodies = {Body{"a", 2, false, -1}, Body{"b", 2, false, -1}};
  auto c = fields_for(bodies);
  CHECK_FALSE(c.prepare(bodies));
  CHECK(c.rules().fields() == 1);
  CHECK_FALSE(c.any_rigid());
}

TEST_CASE("contact fields: declarations are checked and name the bodies", "[contact][errors]") {
  const auto bodies = four_bodies();
  auto c = fields_for(bodies);
  CHECK_THROWS_WITH(c.add_pair(bodies, 1, 1, 0.3), Catch::Contains("'block' cannot be in contact with itself"));
  CHECK_THROWS_WITH(c.add_pair(bodies, 1, 7, 0.3), Catch::Contains("unknown body"));
  CHECK_THROWS_WITH(c.add_pair(bodies, 0, 1, -0.1), Catch::Contains("finite number >= 0"));
  CHECK_THROWS_WITH(c.add_pair(bodies, 0, 1, NAN), Catch::Contains("finite number >= 0"));
  CHECK_THROWS_WITH(c.set_friction(bodies, 0, 1, 0.2),
                    Catch::Contains("no contact is declared between 'soil' and 'block'"));
  c.add_pair(bodies, 0, 1, 0.3);
  CHECK_THROWS_WITH(c.add_pair(bodies, 1, 0, 0.5), Catch::Contains("'block', 'soil' is declared already"));
  std::vector<Body> two_rigid = bodies;
  two_rigid[3].rigid = true;
  CHECK_THROWS_WITH(c.add_pair(two_rigid, 2, 3, 0.1), Catch::Contains("are both rigid"));
}

TEST_CASE("contact fields: rigid particles take their history at the middle of the step", "[contact][rigid]") {
  const std::vector<Body> bodies = {Body{"soil", 2, false, -1}, Body{"base", 1, true, -1}};
  auto c = fields_for(bodies);
  // v_x(t) = 2 t, v_y = -1: at the mid-step phase time 0.5 + 0.05 the base moves at (1.1, -1).
  c.set_velocity(1, {std::make_shared<TableHistory>(std::vector<double>{0.0, 10.0}, std::vector<double>{0.0, 20.0}),
                     std::make_shared<ConstantHistory>(-1.0)});
  REQUIRE(c.prepare(bodies));
  Grid<2> grid(Vec<2>(0, 0), Vec<2>(1, 1), 0.1, 1);
  Particles<2> P;
  P.add(Vec<2>(0.5, 0.5), 1.0, 0.01, 0.25, 0, 0);
  P.add(Vec<2>(0.5, 0.3), 1.0, 0.01, 0.25, 1, 0);
  const StepContext step{0.1, 3.0, 0.5, 7};
  CHECK(c.prescribe_rigid_velocities(P, grid, bodies, step, true) == 2);  // none leaves
  CHECK(P.v[1][0] == Approx(1.1).epsilon(1e-14));
  CHECK(P.v[1][1] == -1.0);
  CHECK(P.v[0] == Vec<2>::Zero());  // the soil is not touched
  CHECK(c.motion(1).current == P.v[1]);

  SECTION("held at rest outside a moving phase") {
    c.prescribe_rigid_velocities(P, grid, bodies, step, false);
    CHECK(P.v[1] == Vec<2>::Zero());
  }
  SECTION("one that would cross the domain's edge in this step is named") {
    P.x[1] = Vec<2>(0.5, 0.01);  // 0.1 s at -1 m/s takes it to y = -0.09
    CHECK(c.prescribe_rigid_velocities(P, grid, bodies, step, true) == 1);
  }
  SECTION("a history that is not finite stops the run with the body's name and the time") {
    c.set_velocity(1, {std::make_shared<ConstantHistory>(NAN), std::make_shared<ConstantHistory>(0.0)});
    CHECK_THROWS_WITH(c.prescribe_rigid_velocities(P, grid, bodies, step, true),
                      Catch::Contains("step 7 (t = 3 s)") && Catch::Contains("rigid body 'base'"));
  }
}

TEST_CASE("contact fields: a block on a rigid base shares exactly the nodes where both reach", "[contact][rigid]") {
  // A 0.4 m block of 2x2 particles per 0.1 m cell on one row of base particles (y in [-0.1, 0]), linear
  // shapes: the base marks the nodes of its cells (rows y = -0.1 and 0), the block the nodes its cells'
  // particles reach (rows 0 .. 0.4). Shared: the row y = 0 under the block, x = 0 .. 0.4, 5 nodes.
  ModelSettings<2> s;
  s.lower = Vec<2>(-0.5, -0.5);
  s.upper = Vec<2>(1.0, 1.0);
  s.cell = 0.1;
  s.shape = ShapeKind::Linear;
  s.gravity = Vec<2>(0, -9.81);
  Model<2> m(s);
  const int mat = m.add_material(std::make_shared<LinearElastic>(2000.0, 1e7, 0.3));
  const int block = m.add_body("block", 2);
  m.fill_box(block, mat, Vec<2>(0.0, 0.0), Vec<2>(0.4, 0.4));
  const int base = m.add_body("base", 1, true);
  m.fill_box(base, -1, Vec<2>(-0.2, -0.1), Vec<2>(0.6, 0.0));
  m.add_contact(block, base, 0.5);
  m.step();
  const auto& c = m.contact();
  const auto& S = c.nodes();
  int on_interface = 0;
  for (int k = 0; k < S.count(); ++k) {
    const Vec<2> x = m.grid().node_position(S.node(k));
    CHECK(S.fields(k) == 2);
    CHECK(c.held(k));  // every shared node here has the base
    if (std::abs(x[1]) < 1e-9 && x[0] > -1e-9 && x[0] < 0.4 + 1e-9) ++on_interface;
  }
  CHECK(on_interface == 5);
  CHECK(S.count() == 5);
}

namespace {

// The shared nodes by their definition: every node that some particle's field reaches (uGIMP: its cell
// c, nodes c - 1 .. c + 2; a rigid particle: its cell's nodes) where two or more fields meet and one of
// them is rigid or a pair of them is not glued. Node -> its fields, from the positions at the start of
// the step.
std::map<int, std::set<int>> shared_by_definition(const Model<2>& m, const std::vector<Vec<2>>& x,
                                                  const std::vector<std::uint16_t>& body) {
  const auto& g = m.grid();
  const auto& c = m.contact();
  std::map<int, std::set<int>> reached;
  for (std::size_t p = 0; p < x.size(); ++p) {
    const int f = c.field_of(body[p]);
    const bool rigid = c.rigid(body[p]);
    int cell[2];
    for (int d = 0; d < 2; ++d) cell[d] = static_cast<int>(std::floor((x[p][d] - g.origin()[d]) / g.cell()));
    const int lo = rigid ? 0 : GimpShape::kReachLo, hi = rigid ? 1 : GimpShape::kReachHi;
    for (int i = lo; i <= hi; ++i)
      for (int j = lo; j <= hi; ++j) reached[(cell[0] + i) * g.stride(0) + (cell[1] + j) * g.stride(1)].insert(f);
  }
  std::map<int, std::set<int>> shared;
  for (const auto& [node, fields] : reached) {
    bool apart = false;
    for (const int a : fields)
      for (const int b : fields) apart = apart || c.rules().rigid(a) || (a != b && !c.rules().glued(a, b));
    if (fields.size() > 1 && apart) shared[node] = fields;
  }
  return shared;
}

std::map<int, std::set<int>> shared_in_step(const Model<2>& m) {
  const auto& S = m.contact().nodes();
  std::map<int, std::set<int>> shared;
  for (int k = 0; k < S.count(); ++k)
    for (int j = 0; j < S.fields(k); ++j) shared[S.node(k)].insert(S.field_of_slot(k * SharedNodes<2>::kSlots + j));
  return shared;
}

}  // namespace

TEST_CASE("contact fields: soil that only rigid bodies are kept apart from shares the nodes of their definition",
          "[contact][rigid]") {
  // Two soil layers, each in contact with a rigid box (base and walls one cell thick), glued to each
  // other: both are plain fields, which mark nodes only near the box. Where the layers meet away from
  // the box no node is shared; along the box every node both reach is, with every field there. The
  // second section pairs the layers with each other as well: then they are kept apart everywhere.
  ModelSettings<2> s;
  s.lower = Vec<2>(-0.2, -0.2);
  s.upper = Vec<2>(1.2, 1.0);
  s.cell = 0.05;
  s.shape = ShapeKind::Gimp;
  s.gravity = Vec<2>(0, -9.81);
  Model<2> m(s);
  const int mat = m.add_material(std::make_shared<LinearElastic>(2000.0, 1e7, 0.3));
  const int lower = m.add_body("lower", 2);
  m.fill_box(lower, mat, Vec<2>(0.0, 0.0), Vec<2>(1.0, 0.25));
  const int upper = m.add_body("upper", 2);
  m.fill_box(upper, mat, Vec<2>(0.0, 0.25), Vec<2>(1.0, 0.5));
  const int box = m.add_body("box", 2, true);
  m.fill_box(box, -1, Vec<2>(-0.05, -0.05), Vec<2>(1.05, 0.0));
  m.fill_box(box, -1, Vec<2>(-0.05, 0.0), Vec<2>(0.0, 0.6));
  m.fill_box(box, -1, Vec<2>(1.0, 0.0), Vec<2>(1.05, 0.6));
  m.add_contact(lower, box, 0.5);
  m.add_contact(upper, box, 0.0);
  bool pair_layers = false;
  SECTION("the layers glued") {}
  SECTION("the layers in contact with each other") { pair_layers = true; }
  if (pair_layers) m.add_contact(lower, upper, 0.3);
  const std::vector<Vec<2>> x = m.particles().x;
  const std::vector<std::uint16_t> body = m.particles().body;
  m.step();
  const auto expected = shared_by_definition(m, x, body);
  const auto found = shared_in_step(m);
  CHECK(found == expected);
  // The interface between the layers, away from the walls (x = 0.35 .. 0.65 m, y = 0.25 m).
  int interface_shared = 0;
  for (const auto& [node, fields] : found) {
    const Vec<2> p = m.grid().node_position(node);
    if (std::abs(p[1] - 0.25) < 1e-9 && p[0] > 0.325 && p[0] < 0.675) ++interface_shared;
  }
  CHECK(interface_shared == (pair_layers ? 7 : 0));
  CHECK(found.size() > 40);  // the box's inner faces
  // Glued, the layers' nodes away from the box were not marked at all (the box holds under a quarter
  // of the occupied cells); paired, every node the fields reach was (303 with the box's).
  const std::size_t marked = m.contact().nodes().touched().size();
  const std::size_t reached = 23 * 13;  // the layers reach x = -0.05 .. 1.05 m and y = -0.05 .. 0.55 m
  if (pair_layers)
    CHECK(marked >= reached);
  else
    CHECK(marked < reached * 3 / 4);  // 199 of 303: the nodes within 3 of the box (all 303 before)
}
