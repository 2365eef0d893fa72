// The background grid: node counts and positions, edge fixities, and bad input.
#include <catch2/catch.hpp>

#include "core/error.hpp"
#include "core/grid.hpp"

using namespace seismpm;

TEST_CASE("grid covers the domain with whole cells", "[core][grid]") {
  const Grid<2> g(Vec<2>(-0.05, -0.05), Vec<2>(0.95, 0.70), 0.01);
  CHECK(g.cells(0) == 100);
  CHECK(g.cells(1) == 75);
  CHECK(g.node_count() == 101 * 76);
  CHECK(g.node_position(101 * 3 + 7).isApprox(Vec<2>(-0.05 + 0.07, -0.05 + 0.03)));
  CHECK(g.upper()[1] == Approx(0.70));
  const Grid<3> g3(Vec<3>::Zero(), Vec<3>(1.0, 0.5, 0.25), 0.1);
  CHECK(g3.node_count() == 11 * 6 * 4);
  CHECK(g3.stride(2) == 11 * 6);
}

TEST_CASE("a ghost layer surrounds the domain and edge fixities hold it too", "[core][grid]") {
  Grid<2> g(Vec<2>::Zero(), Vec<2>(1.0, 1.0), 0.25, 1);
  CHECK(g.cells(0) == 6);
  CHECK(g.domain_cells(0) == 4);
  CHECK(g.origin().isApprox(Vec<2>(-0.25, -0.25)));
  CHECK(g.domain_lower().isApprox(Vec<2>(0.0, 0.0)));
  CHECK(g.domain_upper().isApprox(Vec<2>(1.0, 1.0)));
  g.fix(Side::Right, FixX);
  CHECK(g.fixed_nodes().size() == 2 * 7);  // the edge x = 1 and the ghost layer x = 1.25
  CHECK(g.fixity(5) == FixX);
  CHECK(g.fixity(6) == FixX);
  CHECK(g.fixity(4) == 0);
}

TEST_CASE("grid-edge fixities hold the chosen directions", "[core][grid]") {
  Grid<2> g(Vec<2>::Zero(), Vec<2>(1.0, 1.0), 0.25);
  g.fix(Side::Left, FixX);
  g.fix(Side::Bottom, FixX | FixY);
  CHECK(g.fixed_nodes().size() == 5 + 4);
  std::vector<Vec<2>> v(g.node_count(), Vec<2>(1.0, 2.0));
  g.apply_fixities(v);
  CHECK(v[0] == Vec<2>(0.0, 0.0));      // corner: both
  CHECK(v[5] == Vec<2>(0.0, 2.0));      // left edge, y = 0.25: x only
  CHECK(v[2] == Vec<2>(0.0, 0.0));      // bottom edge
  CHECK(v[5 + 2] == Vec<2>(1.0, 2.0));  // interior: free
  CHECK(parse_side("top", 2) == Side::Top);
  CHECK(parse_dof("xy", 2) == (FixX | FixY));
  CHECK_THROWS_WITH(parse_side("front", 2), Catch::Contains("left|right|bottom|top"));
  CHECK_THROWS_WITH(parse_dof("z", 2), Catch::Contains("x|y|xy"));
  CHECK_THROWS_AS(Grid<2>(Vec<2>::Zero(), Vec<2>(1.0, 0.0), 0.1), InputError);
  CHECK_THROWS_AS(Grid<2>(Vec<2>::Zero(), Vec<2>(1.0, 1.0), 0.0), InputError);
}
