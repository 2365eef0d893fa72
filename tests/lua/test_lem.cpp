// mpm.lem on a model's slope: the same factor as the core solver on the same geometry, and its errors.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "lua_fixture.hpp"
#include "methods/limit_equilibrium.hpp"

using seismpm::test::LuaFixture;

namespace {

// A 2:1 slope 10 m high over 2 m of the same soil (c = 10 kPa, phi = 20, gamma = 20 kN/m3).
const char* kSlope = R"(
  local m = mpm.model{ domain = {{-20, 0}, {45, 14}}, cell = 0.5, gravity = {0, -10} }
  local soil = mpm.material.mohr_coulomb{ density = 2000, young = 50e6, poisson = 0.3, cohesion = 10e3,
                                          friction = 20 }
  m:body{ name = "slope", material = soil,
          shape = mpm.shape.polygon{ {-20, 0}, {45, 0}, {45, 2}, {20, 2}, {0, 12}, {-20, 12} } }
)";

}  // namespace

TEST_CASE("mpm.lem on a model's slope matches the core solver on the same geometry within 2 %", "[lua][lem]") {
  using namespace seismpm;
  const LemSlope slope{{{-20, 12}, {0, 12}, {20, 2}, {45, 2}}, {{0, {20e3, 10e3, 20}}}, 0};
  const LemResult core = limit_equilibrium(slope, 0);
  LuaFixture f;
  const std::string error = f.error_of(std::string(kSlope) + R"(
    local r = mpm.lem{ model = m }
    fos, ky, xc, yc, radius, points = r.fos, r.ky, r.circle.xc, r.circle.yc, r.circle.r, #r.surface
    first_x, last_x = r.surface[1][1], r.surface[#r.surface][1]
    listed = r.circle[1] == r.circle.xc and r.circle[2] == r.circle.yc and r.circle[3] == r.circle.r
    fos_kh = mpm.lem{ model = m, kh = 0.1, search = { centres = {{0, 12}, {25, 40}}, radii = {5, 40} } }.fos
  )");
  REQUIRE(error == "");
  auto global = [&f](const char* name) { return f.number(name); };
  CHECK(global("fos") == Approx(core.fos).epsilon(0.02));
  CHECK(global("ky") == Approx(core.ky).epsilon(0.05));
  CHECK(global("points") == 81);
  CHECK(f.truth("listed"));  // circle = {xc, yc, r} as a list too
  CHECK(global("first_x") < global("last_x"));
  CHECK(global("yc") - global("radius") >= -1e-9);
  CHECK(global("fos_kh") == Approx(critical_circle(slope, 0.1).fos).epsilon(0.02));
  CHECK(global("fos_kh") < global("fos") - 0.1);
}

TEST_CASE("mpm.lem with Spencer's method matches the core solver, on circles and on a given surface",
          "[lua][lem][spencer]") {
  using namespace seismpm;
  const LemSlope slope{{{-20, 12}, {0, 12}, {20, 2}, {45, 2}}, {{0, {20e3, 10e3, 20}}}, 0};
  LemSettings spencer;
  spencer.method = LemMethod::spencer;
  // A non-circular surface from behind the crest to the toe (20, 2), beyond which it rises out of the
  // ground again (the particles' surface there is a staircase).
  const std::vector<LemPoint> plane{{-14, 14}, {-6, 6}, {8, 2}, {20, 2}, {25, 3}};
  const LemResult core_plane = surface_equilibrium(slope, plane, 0, spencer);
  const LemResult core_circle = critical_circle(slope, 0, {}, spencer);
  LuaFixture f;
  const std::string error = f.error_of(std::string(kSlope) + R"(
    local c = mpm.lem{ model = m, method = "spencer", search = { levels = 3 } }
    circle_fos, theta = c.fos, c.theta
    local p = mpm.lem{ model = m, method = "spencer", surface = {{-14, 14}, {-6, 6}, {8, 2}, {20, 2}, {25, 3}} }
    plane_fos, plane_ky, no_circle, points = p.fos, p.ky, p.circle == nil, #p.surface
  )");
  REQUIRE(error == "");
  auto global = [&f](const char* name) { return f.number(name); };
  CHECK(global("circle_fos") == Approx(core_circle.fos).epsilon(0.02));
  CHECK(global("theta") == Approx(core_circle.theta).margin(5));
  CHECK(global("plane_fos") == Approx(core_plane.fos).epsilon(0.02));
  CHECK(global("plane_ky") == Approx(core_plane.ky).epsilon(0.05));
  CHECK(global("points") == 81);
  CHECK(f.truth("no_circle"));
}

TEST_CASE("mpm.lem: errors name the key or the material", "[lua][lem][errors]") {
  LuaFixture f;
  CHECK_THAT(f.error_of(std::string(kSlope) + "mpm.lem{ model = m, kh = -1 }"), Catch::Contains("kh"));
  CHECK_THAT(f.error_of(std::string(kSlope) + "mpm.lem{ model = m, surface = {{-15, 14}, {20, 2}} }"),
             Catch::Contains("needs method = \"spencer\""));
  CHECK_THAT(f.error_of(std::string(kSlope) +
                        "mpm.lem{ model = m, method = 'spencer', surface = {{-15, 14}, {20, 2}}, search = {} }"),
             Catch::Contains("key 'search'"));
  CHECK_THAT(
      f.error_of(std::string(kSlope) + "mpm.lem{ model = m, method = 'spencer', surface = {{-15, 14}, {10, 4}} }"),
      Catch::Contains("start and end at or above the ground"));
  CHECK_THAT(f.error_of(std::string(kSlope) + "mpm.lem{ model = m, method = 'spencer', surface = {{-15, 14}, 3} }"),
             Catch::Contains("surface[2]"));
  CHECK_THAT(f.error_of(std::string(kSlope) + "mpm.lem{ model = m, search = { radii = {5} } }"),
             Catch::Contains("radii"));
  CHECK_THAT(f.error_of(std::string(kSlope) + "mpm.lem{ model = m, serch = {} }"), Catch::Contains("serch"));
  CHECK_THAT(f.error_of("mpm.lem{ kh = 0 }"), Catch::Contains("model"));
  CHECK_THAT(f.error_of(R"(
    local m = mpm.model{ domain = {{0, 0}, {10, 5}}, cell = 0.5 }
    local e = mpm.material.linear_elastic{ density = 2000, young = 1e7, poisson = 0.3 }
    m:body{ name = "b", material = e, shape = mpm.shape.polygon{ {0, 0}, {10, 0}, {10, 1}, {0, 4} } }
    mpm.lem{ model = m })"),
             Catch::Contains("has no shear strength"));
}

TEST_CASE("mpm.lem: bodies of two materials make two horizontal bands", "[lua][lem]") {
  using namespace seismpm;
  // The slope above y = 6 m is of a weaker soil (c = 5 kPa).
  const LemSlope slope{{{-20, 12}, {0, 12}, {20, 2}, {45, 2}}, {{6, {20e3, 5e3, 20}}, {0, {20e3, 10e3, 20}}}, 0};
  LuaFixture f;
  const std::string error = f.error_of(R"(
    local m = mpm.model{ domain = {{-20, 0}, {45, 14}}, cell = 0.5, gravity = {0, -10} }
    local function soil(c)
      return mpm.material.mohr_coulomb{ density = 2000, young = 50e6, poisson = 0.3, cohesion = c, friction = 20 }
    end
    m:body{ name = "lower", material = soil(10e3),
            shape = mpm.shape.polygon{ {-20, 0}, {45, 0}, {45, 2}, {20, 2}, {12, 6}, {-20, 6} } }
    m:body{ name = "upper", material = soil(5e3), shape = mpm.shape.polygon{ {-20, 6}, {12, 6}, {0, 12}, {-20, 12} } }
    fos = mpm.lem{ model = m }.fos
  )");
  REQUIRE(error == "");
  const double fos = f.number("fos");
  CHECK(fos == Approx(critical_circle(slope, 0).fos).epsilon(0.02));
  CHECK(fos < 1.3);
}

TEST_CASE("mpm.lem: a Drucker-Prager slope on a rigid base gives the Mohr-Coulomb factor", "[lua][lem]") {
  using namespace seismpm;
  // The rigid base's particles are not soil: the surface and the base come from the slope alone.
  const LemSlope slope{{{-20, 12}, {0, 12}, {20, 2}, {45, 2}}, {{0, {20e3, 10e3, 20}}}, 0};
  LuaFixture f;
  const std::string error = f.error_of(R"(
    local m = mpm.model{ domain = {{-20, -1}, {45, 14}}, cell = 0.5, gravity = {0, -10} }
    local soil = mpm.material.drucker_prager{ density = 2000, young = 50e6, poisson = 0.3, cohesion = 10e3,
                                              friction = 20 }
    m:rigid{ name = "base", shape = mpm.shape.rectangle{ -20, -1, 45, 0 }, velocity = {0, 0} }
    m:body{ name = "slope", material = soil,
            shape = mpm.shape.polygon{ {-20, 0}, {45, 0}, {45, 2}, {20, 2}, {0, 12}, {-20, 12} } }
    fos = mpm.lem{ model = m }.fos
  )");
  REQUIRE(error == "");
  CHECK(f.number("fos") == Approx(critical_circle(slope, 0).fos).epsilon(0.02));
}
