// Overlapping bodies: the particles of a new body inside the shapes of earlier ones, counted by hand
// from the lattice (cell 0.25 m: ppc 2 puts particles at 0.0625 + 0.125 k, ppc 3 at 0.25/6 + 0.25/3 k).
#include <catch2/catch.hpp>

#include "core/body_overlap.hpp"
#include "support/models.hpp"

using namespace seismpm;

namespace {
ModelSettings<2> settings() {
  ModelSettings<2> s;
  s.lower = Vec<2>::Zero();
  s.upper = Vec<2>(4.0, 2.0);
  s.cell = 0.25;
  return s;
}

std::vector<const Region*> shapes_of(const std::vector<std::unique_ptr<Region>>& regions) {
  std::vector<const Region*> out;
  for (const auto& r : regions) out.push_back(r.get());
  return out;
}

int add(Model<2>& m, int mat, const Region& r, int ppc) {
  const int b = m.add_body("b" + std::to_string(m.bodies().size()), ppc);
  m.fill(b, mat, r.lower(), r.upper(), [&](const Vec<2>& x) { return r.contains(x); });
  return b;
}
}  // namespace

TEST_CASE("a body over another overlaps it by the particles inside its shape", "[core][overlap]") {
  Model<2> m(settings());
  const int mat = m.add_material(std::make_shared<LinearElastic>(1800.0, 1e7, 0.3));
  std::vector<std::unique_ptr<Region>> r;
  r.push_back(std::make_unique<RectangleRegion>(0.0, 0.0, 2.0, 1.0));
  r.push_back(std::make_unique<RectangleRegion>(1.5, 0.5, 3.0, 1.5));  // its corner 0.5 x 0.5 inside the first
  add(m, mat, *r[0], 2);
  const int b = add(m, mat, *r[1], 3);
  const auto o = overlaps_of_body(m.particles(), shapes_of(r), b);
  REQUIRE(o.size() == 1);
  CHECK(o[0].body == 0);
  CHECK(o[0].particles == 6 * 6);  // 2 x 2 cells of 3 x 3 particles
  CHECK(o[0].first.x() == Approx(1.5 + 0.25 / 6));
  CHECK(o[0].first.y() == Approx(0.5 + 0.25 / 6));
}

TEST_CASE("bodies that only touch do not overlap, whatever their particle spacings", "[core][overlap]") {
  Model<2> m(settings());
  const int mat = m.add_material(std::make_shared<LinearElastic>(1800.0, 1e7, 0.3));
  std::vector<std::unique_ptr<Region>> r;
  // A boundary at y = 0.34 between cell edges: the lower body's last sub-cell (0.25-0.375) reaches past
  // it, the upper body's first particle (0.34375, ppc 4) lies inside that sub-cell, yet above the line.
  r.push_back(std::make_unique<RectangleRegion>(0.0, 0.0, 4.0, 0.34));
  r.push_back(std::make_unique<RectangleRegion>(0.0, 0.34, 4.0, 1.0));
  r.push_back(std::make_unique<RectangleRegion>(0.0, 1.0, 4.0, 1.25));  // on a cell edge
  add(m, mat, *r[0], 2);
  const int upper = add(m, mat, *r[1], 4);
  const int top = add(m, mat, *r[2], 3);
  CHECK(overlaps_of_body(m.particles(), shapes_of(r), upper).empty());
  CHECK(overlaps_of_body(m.particles(), shapes_of(r), top).empty());
}

TEST_CASE("a shared edge through particle positions is an overlap: both bodies hold those particles",
          "[core][overlap]") {
  Model<2> m(settings());
  const int mat = m.add_material(std::make_shared<LinearElastic>(1800.0, 1e7, 0.3));
  std::vector<std::unique_ptr<Region>> r;
  // y = 0.5625 is a row of ppc-2 particle positions (0.0625 + 0.125 * 4): both rectangles hold it.
  r.push_back(std::make_unique<RectangleRegion>(0.0, 0.0, 1.0, 0.5625));
  r.push_back(std::make_unique<RectangleRegion>(0.0, 0.5625, 1.0, 1.0));
  add(m, mat, *r[0], 2);
  const int b = add(m, mat, *r[1], 2);
  const auto o = overlaps_of_body(m.particles(), shapes_of(r), b);
  REQUIRE(o.size() == 1);
  CHECK(o[0].particles == 8);  // the row's 8 particles across 1 m
  CHECK(o[0].first.y() == Approx(0.5625));
}
