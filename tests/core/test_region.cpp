// Regions that bodies are filled from: rectangles, polygons (convex, concave, either orientation) and
// polyline bands, their bounds, outward normals, descriptions and bad input. Every expected value is
// worked out by hand from the coordinates in the comments.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/region.hpp"

using namespace seismpm;

namespace {
Vec<2> P(double x, double y) { return Vec<2>(x, y); }

std::vector<Vec<2>> reversed(std::vector<Vec<2>> v) {
  std::reverse(v.begin(), v.end());
  return v;
}
}  // namespace

TEST_CASE("a rectangle holds its interior and its edges", "[core][region]") {
  const RectangleRegion r(0.5, 0.0, 2.0, 1.0);
  CHECK(r.contains(P(1.0, 0.5)));
  CHECK(r.contains(P(0.5, 0.0)));  // corners and edges count as inside
  CHECK(r.contains(P(2.0, 1.0)));
  CHECK(r.contains(P(2.0, 0.3)));
  CHECK_FALSE(r.contains(P(2.0 + 1e-12, 0.5)));
  CHECK_FALSE(r.contains(P(1.0, -1e-12)));
  CHECK_FALSE(r.contains(P(0.4, 0.5)));
  CHECK(r.lower() == P(0.5, 0.0));
  CHECK(r.upper() == P(2.0, 1.0));
  CHECK(r.outward_normal(P(2.0, 0.5)) == Vec<2>::Zero());  // contact takes normals from the particles' volume
  CHECK(r.describe() == "rectangle {0.5, 0} to {2, 1}");
}

TEST_CASE("a rectangle needs x0 < x1 and y0 < y1, finite", "[core][region]") {
  CHECK_THROWS_AS(RectangleRegion(1.0, 0.0, 0.0, 1.0), InputError);
  CHECK_THROWS_AS(RectangleRegion(0.0, 0.0, 1.0, 0.0), InputError);  // zero height
  CHECK_THROWS_WITH(RectangleRegion(0.0, 0.0, std::numeric_limits<double>::infinity(), 1.0),
                    Catch::Contains("x0 < x1 and y0 < y1"));
  CHECK_THROWS_AS(RectangleRegion(std::nan(""), 0.0, 1.0, 1.0), InputError);
}

TEST_CASE("a convex polygon in either orientation", "[core][region]") {
  // The right triangle (0,0), (4,0), (0,3): area 4 * 3 / 2 = 6, positive counter-clockwise; its
  // hypotenuse is x/4 + y/3 = 1.
  const std::vector<Vec<2>> ccw = {P(0, 0), P(4, 0), P(0, 3)};
  const bool counter_clockwise = GENERATE(true, false);
  const PolygonRegion t(counter_clockwise ? ccw : reversed(ccw));
  CHECK(t.area() == (counter_clockwise ? 6.0 : -6.0));
  CHECK(t.vertices().size() == 3);
  CHECK(t.contains(P(1, 1)));        // 1/4 + 1/3 < 1
  CHECK_FALSE(t.contains(P(3, 2)));  // 3/4 + 2/3 > 1
  CHECK(t.contains(P(2, 1.5)));      // on the hypotenuse: 1/2 + 1/2 = 1, edges count as inside
  CHECK(t.contains(P(4, 0)));        // a vertex
  CHECK(t.contains(P(2, 0)));        // on the bottom edge
  CHECK_FALSE(t.contains(P(-0.1, 1)));
  CHECK_FALSE(t.contains(P(1, -0.1)));
  CHECK(t.lower() == P(0, 0));
  CHECK(t.upper() == P(4, 3));
  CHECK(t.outward_normal(P(2, 1.5)) == Vec<2>::Zero());
  CHECK(t.describe() == "polygon of 3 points, area 6.000000");
}

TEST_CASE("a concave polygon in either orientation", "[core][region]") {
  // A U: the 3 x 3 square with the notch 1 <= x <= 2, 1 <= y <= 3 cut from its top; area 9 - 2 = 7.
  const std::vector<Vec<2>> ccw = {P(0, 0), P(3, 0), P(3, 3), P(2, 3), P(2, 1), P(1, 1), P(1, 3), P(0, 3)};
  const bool counter_clockwise = GENERATE(true, false);
  const PolygonRegion u(counter_clockwise ? ccw : reversed(ccw));
  CHECK(u.area() == (counter_clockwise ? 7.0 : -7.0));
  CHECK(u.contains(P(1.5, 0.5)));        // the bottom of the U
  CHECK(u.contains(P(0.5, 2.5)));        // the left arm
  CHECK(u.contains(P(2.5, 2.5)));        // the right arm
  CHECK_FALSE(u.contains(P(1.5, 2.0)));  // in the notch
  CHECK(u.contains(P(1.5, 1.0)));        // the notch's floor is an edge
  CHECK(u.contains(P(1.0, 2.0)));        // and so are its walls
  CHECK_FALSE(u.contains(P(1.5, 3.0)));  // the open top of the notch, between the arms
  CHECK(u.lower() == P(0, 0));
  CHECK(u.upper() == P(3, 3));
  CHECK(u.describe() == "polygon of 8 points, area 7.000000");
}

TEST_CASE("a polygon's closing point may repeat its first", "[core][region]") {
  const PolygonRegion t({P(0, 0), P(1, 0), P(0, 1), P(0, 0)});
  CHECK(t.vertices().size() == 3);
  CHECK(t.area() == 0.5);
}

TEST_CASE("bad polygons are refused with the reason", "[core][region]") {
  CHECK_THROWS_WITH(PolygonRegion({P(0, 0), P(1, 0)}), Catch::Contains("at least 3 points"));
  CHECK_THROWS_WITH(PolygonRegion({P(0, 0), P(1, 0), P(1, 0), P(0, 1)}), Catch::Contains("repeats point 2"));
  CHECK_THROWS_WITH(PolygonRegion({P(0, 0), P(std::nan(""), 0), P(0, 1)}), Catch::Contains("non-finite"));
  // A bow tie: the edges (0,0)-(1,1) and (1,0)-(0,1) cross at (0.5, 0.5).
  CHECK_THROWS_WITH(PolygonRegion({P(0, 0), P(1, 1), P(1, 0), P(0, 1)}), Catch::Contains("cross"));
  // Three points on a line: the closing edge (2,0)-(0,0) lies over the first one.
  CHECK_THROWS_AS(PolygonRegion({P(0, 0), P(1, 0), P(2, 0)}), InputError);
}

TEST_CASE("polygon self-intersection", "[core][region]") {
  CHECK_FALSE(polygon_self_intersects({P(0, 0), P(1, 0), P(1, 1), P(0, 1)}));
  CHECK(polygon_self_intersects({P(0, 0), P(1, 1), P(1, 0), P(0, 1)}));
  // The second edge (2,0)-(1,0) folds back onto the first (0,0)-(2,0).
  CHECK(polygon_self_intersects({P(0, 0), P(2, 0), P(1, 0), P(1, 1)}));
  // A notch from the top whose tip (2,0) reaches the bottom edge (0,0)-(4,0): touching counts.
  CHECK(polygon_self_intersects({P(0, 0), P(4, 0), P(4, 4), P(3, 4), P(2, 0), P(1, 4), P(0, 4)}));
  // The same notch stopping at y = 1 leaves a simple polygon.
  CHECK_FALSE(polygon_self_intersects({P(0, 0), P(4, 0), P(4, 4), P(3, 4), P(2, 1), P(1, 4), P(0, 4)}));
}

TEST_CASE("a polyline band of both sides", "[core][region]") {
  // The segment (0,0)-(4,0), thickness 1: points within 0.5 of it, round caps at the ends.
  const PolylineRegion b({P(0, 0), P(4, 0)}, 1.0, PolylineRegion::Side::Both);
  CHECK(b.contains(P(2, 0.5)));
  CHECK(b.contains(P(2, -0.5)));
  CHECK_FALSE(b.contains(P(2, 0.6)));
  CHECK(b.contains(P(4.4, 0)));          // 0.4 beyond the end
  CHECK(b.contains(P(4.3, 0.4)));        // sqrt(0.3^2 + 0.4^2) = 0.5 from the end point
  CHECK_FALSE(b.contains(P(4.4, 0.4)));  // sqrt(0.32) = 0.566 > 0.5
  CHECK(b.lower() == P(-0.5, -0.5));     // the points' box padded by the half thickness
  CHECK(b.upper() == P(4.5, 0.5));
  CHECK(b.outward_normal(P(2, 0.3)) == Vec<2>::Zero());  // a two-sided band has no single face
  CHECK(b.describe() == "polyline of 2 points, thickness 1.000000");
}

TEST_CASE("a one-sided polyline band faces its free side", "[core][region]") {
  // Walking from (0,0) to (4,0), the left is +y. A left band fills 0 <= y <= 1 and its contact face
  // (the line) looks down, -y; a right band fills -1 <= y <= 0 and looks up, +y.
  SECTION("left") {
    const PolylineRegion b({P(0, 0), P(4, 0)}, 1.0, PolylineRegion::Side::Left);
    CHECK(b.contains(P(2, 0.9)));
    CHECK(b.contains(P(2, 1.0)));
    CHECK_FALSE(b.contains(P(2, 1.1)));
    CHECK_FALSE(b.contains(P(2, -0.1)));
    CHECK(b.contains(P(2, 0.0)));  // on the line itself
    CHECK(b.outward_normal(P(2, 0.5)) == P(0, -1));
    CHECK(b.lower() == P(-1, -1));  // padded by the full thickness, either side
    CHECK(b.upper() == P(5, 1));
  }
  SECTION("right") {
    const PolylineRegion b({P(0, 0), P(4, 0)}, 1.0, PolylineRegion::Side::Right);
    CHECK(b.contains(P(2, -0.9)));
    CHECK_FALSE(b.contains(P(2, 0.1)));
    CHECK_FALSE(b.contains(P(2, -1.1)));
    CHECK(b.outward_normal(P(2, -0.5)) == P(0, 1));
  }
}

TEST_CASE("a bent polyline band: the nearest segment gives side and normal", "[core][region]") {
  // (0,0) -> (2,0) -> (2,2): a left turn at the corner (2,0). For a right band the right of the first
  // segment is -y and of the second +x; the outward normals are the segments' left normals, (0,1)
  // and (-2,0)/2 = (-1,0).
  const PolylineRegion b({P(0, 0), P(2, 0), P(2, 2)}, 1.0, PolylineRegion::Side::Right);
  CHECK(b.contains(P(1, -0.5)));
  CHECK(b.outward_normal(P(1, -0.5)) == P(0, 1));
  CHECK(b.contains(P(2.5, 1)));
  CHECK(b.outward_normal(P(2.5, 1)) == P(-1, 0));
  CHECK_FALSE(b.contains(P(1.5, 0.5)));  // inside the turn: the left of both segments
  // Outside the corner, (2.5, -0.5) is sqrt(0.5) = 0.707 from the corner point of both segments; the
  // tie goes to the first segment: right of it (cross((2,0), (2.5,-0.5)) = -1 < 0), normal (0,1).
  CHECK(b.contains(P(2.5, -0.5)));
  CHECK(b.outward_normal(P(2.5, -0.5)) == P(0, 1));
  CHECK(b.contains(P(2, 0)));  // the corner itself: on the line
  CHECK(b.describe() == "polyline of 3 points, thickness 1.000000");
}

TEST_CASE("bad polylines are refused with the reason", "[core][region]") {
  using Side = PolylineRegion::Side;
  CHECK_THROWS_WITH(PolylineRegion({P(0, 0)}, 1.0, Side::Both), Catch::Contains("at least 2 points"));
  const double thickness = GENERATE(0.0, -1.0, std::numeric_limits<double>::infinity(), std::nan(""));
  CHECK_THROWS_WITH(PolylineRegion({P(0, 0), P(1, 0)}, thickness, Side::Left),
                    Catch::Contains("thickness must be > 0"));
  CHECK_THROWS_WITH(PolylineRegion({P(0, 0), P(1, 0), P(1, 0)}, 1.0, Side::Both), Catch::Contains("repeats point 2"));
}
