// Shared nodes: the grid nodes that particles of two or more contact fields touch, their slots (one
// per field, kSlots per node) and the overflow beyond kSlots fields. The expected numbering follows
// from the marks in each test: shared nodes in grid order, slot k * kSlots + j for the j-th field
// that marked node k.
#include <catch2/catch.hpp>

#include "contact/shared_nodes.hpp"

using namespace seismpm;

namespace {
FieldSet empty_set() {
  FieldSet s;
  s.fill(-1);
  return s;
}

// `fields` deformable fields, every two in declared (smooth) contact: every meeting is kept apart.
ContactRules all_in_contact(int fields) {
  ContactRules r;
  r.reset(fields);
  for (int a = 0; a < fields; ++a)
    for (int b = a + 1; b < fields; ++b) r.set_friction(a, b, 0.0);
  return r;
}
}  // namespace

TEST_CASE("a field set takes up to four fields once each", "[contact][shared_nodes]") {
  FieldSet s = empty_set();
  CHECK(add_field(s, 2));
  CHECK(s == FieldSet{2, -1, -1, -1});
  CHECK(add_field(s, 2));  // already there: no second place
  CHECK(s == FieldSet{2, -1, -1, -1});
  CHECK(add_field(s, 0));
  CHECK(add_field(s, 5));
  CHECK(add_field(s, 7));
  CHECK(s == FieldSet{2, 0, 5, 7});
  CHECK_FALSE(add_field(s, 9));  // full with other fields
  CHECK(s == FieldSet{2, 0, 5, 7});
  CHECK(add_field(s, 5));  // a field it holds is still found when full
}

// clear() forgets only the nodes the last step marked: what it leaves must be as clean as a new grid.
TEST_CASE("a step's marks are all forgotten by the next clear", "[contact][shared_nodes]") {
  SharedNodes<2> sn;
  sn.clear(10);
  CHECK(sn.mark(3, 0));
  CHECK(sn.mark(3, 1));
  CHECK(sn.mark(8, 0));
  CHECK(sn.mark(8, 2));
  sn.build(all_in_contact(24));
  REQUIRE(sn.count() == 2);
  sn.clear(10);
  CHECK(sn.touched().empty());
  CHECK(sn.mark(5, 2));
  CHECK(sn.mark(5, 1));
  CHECK(sn.mark(3, 1));  // one field now: not shared
  sn.build(all_in_contact(24));
  REQUIRE(sn.count() == 1);
  CHECK(sn.node(0) == 5);
  CHECK(sn.index(5) == 0);
  CHECK(sn.index(3) == -1);
  CHECK(sn.index(8) == -1);
  CHECK(sn.touched() == std::vector<int>{5, 3});  // first-marked order
}

TEST_CASE("nodes of two or more fields are shared, in the order first marked", "[contact][shared_nodes]") {
  SharedNodes<2> sn;
  sn.clear(10);
  // Node 3: fields 0 and 1. Node 5: field 2 only. Node 7: fields 0, 2, 1 (0 twice).
  CHECK(sn.mark(3, 0));
  CHECK(sn.mark(3, 1));
  CHECK(sn.mark(5, 2));
  CHECK(sn.mark(7, 0));
  CHECK(sn.mark(7, 2));
  CHECK(sn.mark(7, 0));
  CHECK(sn.mark(7, 1));
  sn.build(all_in_contact(24));
  REQUIRE(sn.count() == 2);
  CHECK(sn.node(0) == 3);
  CHECK(sn.node(1) == 7);
  CHECK(sn.fields(0) == 2);
  CHECK(sn.fields(1) == 3);
  CHECK(sn.index(3) == 0);
  CHECK(sn.index(7) == 1);
  CHECK(sn.index(5) == -1);  // one field: the common grid fields serve it
  CHECK(sn.index(0) == -1);  // no field
  SECTION("slots: node k's j-th field at k * 4 + j") {
    CHECK(sn.slot(0, 0) == 0);
    CHECK(sn.slot(0, 1) == 1);
    CHECK(sn.slot(0, 2) == -1);  // field 2 never touched node 3
    CHECK(sn.slot(1, 0) == 4);
    CHECK(sn.slot(1, 2) == 5);
    CHECK(sn.slot(1, 1) == 6);
    CHECK(sn.field_of_slot(0) == 0);
    CHECK(sn.field_of_slot(5) == 2);
    CHECK(sn.field_of_slot(6) == 1);
    CHECK(sn.field_of_slot(3) == -1);  // an empty place
    CHECK(sn.field_of_slot(7) == -1);
  }
  SECTION("per-slot data: kSlots per shared node, zero") {
    CHECK(sn.mass.size() == 2 * SharedNodes<2>::kSlots);
    CHECK(sn.momentum.size() == 8);
    CHECK(sn.force.size() == 8);
    CHECK(sn.gradient.size() == 8);
    CHECK(sn.velocity.size() == 8);
    CHECK(sn.acceleration.size() == 8);
    sn.mass[6] = 1.5;
    sn.velocity[6] = Vec<2>(1.0, 2.0);
    sn.build(all_in_contact(24));  // zeroes them again
    CHECK(sn.mass[6] == 0.0);
    CHECK(sn.velocity[6] == Vec<2>::Zero());
  }
}

TEST_CASE("a node takes kSlots fields; a further one is refused", "[contact][shared_nodes]") {
  SharedNodes<3> sn;
  sn.clear(4);
  for (int f = 0; f < SharedNodes<3>::kSlots; ++f) CHECK(sn.mark(2, 10 + f));
  CHECK_FALSE(sn.mark(2, 20));
  CHECK(sn.mark(2, 12));  // one it has
  sn.build(all_in_contact(24));
  REQUIRE(sn.count() == 1);
  CHECK(sn.fields(0) == 4);
  CHECK(sn.slot(0, 13) == 3);
  CHECK(sn.slot(0, 20) == -1);
}

TEST_CASE("clear forgets every node's fields", "[contact][shared_nodes]") {
  SharedNodes<2> sn;
  sn.clear(6);
  sn.mark(1, 0);
  sn.mark(1, 1);
  sn.build(all_in_contact(24));
  REQUIRE(sn.count() == 1);
  const int node_count = GENERATE(6, 9);  // the grid may change size between steps
  sn.clear(node_count);
  CHECK(sn.index(1) == -1);
  sn.mark(4, 1);
  sn.build(all_in_contact(24));
  CHECK(sn.count() == 0);
  CHECK(sn.mass.empty());
  sn.mark(node_count - 1, 0);
  sn.mark(node_count - 1, 3);
  sn.build(all_in_contact(24));
  REQUIRE(sn.count() == 1);
  CHECK(sn.node(0) == node_count - 1);
  CHECK(sn.slot(0, 3) == 1);
}

TEST_CASE("where only glued deformable fields meet, no node is shared", "[contact][shared_nodes]") {
  // Fields 0, 1, 2 deformable; 1 and 2 in contact; field 3 rigid (glued to all: no pair declared).
  ContactRules rules;
  rules.reset(4);
  rules.set_friction(1, 2, 0.3);
  rules.set_rigid(3, true);
  SharedNodes<2> sn;
  sn.clear(8);
  sn.mark(1, 0), sn.mark(1, 1);                 // glued: one body there
  sn.mark(2, 1), sn.mark(2, 2);                 // a declared pair
  sn.mark(3, 0), sn.mark(3, 3);                 // a rigid field, glued or not, has its own velocity
  sn.mark(4, 0), sn.mark(4, 1), sn.mark(4, 2);  // a pair among glued fields
  sn.build(rules);
  REQUIRE(sn.count() == 3);
  CHECK(sn.index(1) == -1);
  CHECK(sn.node(0) == 2);
  CHECK(sn.node(1) == 3);
  CHECK(sn.node(2) == 4);
  CHECK(sn.fields(2) == 3);
}
