// Likely mistakes that still run: a unit weight typed as a density, a modulus in kPa, a friction angle
// in radians, a --set the script never reads, overlapping bodies: each a warning naming the script line
// and the value; and a probe away from its body, an error naming both positions.
#include <catch2/catch.hpp>

#include "lua/input_checks.hpp"
#include "lua_fixture.hpp"

using seismpm::test::LuaFixture;

namespace {
bool any_holds(const std::vector<std::string>& warnings, const std::string& text) {
  for (const auto& w : warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}
}  // namespace

TEST_CASE("a unit weight, a modulus in kPa and an angle in radians are warned about, with the line", "[lua][input]") {
  LuaFixture f;
  REQUIRE(f.error_of("local soil = mpm.material.mohr_coulomb{ density = 19, young = 5e4, poisson = 0.3,\n"
                     "  cohesion = 0, friction = 0.576, dilation = 0, tension = 0 }") == "");
  const auto& w = f.session.warnings;
  REQUIRE(w.size() == 3);
  CHECK(w[0].rfind("test:1: mohr_coulomb: density = 19 kg/m3 is below 100: a unit weight in kN/m3?", 0) == 0);
  CHECK(any_holds(w, "a density of 1937 kg/m3"));
  CHECK(any_holds(w, "young = 50000 Pa is below 0.1 MPa"));
  CHECK(any_holds(w, "friction = 0.576 is below 1 degree: radians?"));
  CHECK(any_holds(w, "(0.576 rad = 33.0024 degrees)"));
}

TEST_CASE("ordinary soils, phi = 0 and rock give no warning", "[lua][input]") {
  LuaFixture f;
  REQUIRE(f.error_of(R"(
    mpm.material.mohr_coulomb{ density = 1900, young = 2e7, poisson = 0.3, cohesion = 0, friction = 33,
                               dilation = 0, tension = 0 }
    mpm.material.mohr_coulomb{ density = 1800, young = 5e6, poisson = 0.45, cohesion = 20e3, friction = 0,
                               dilation = 0, tension = 0 }
    mpm.material.drucker_prager{ density = 2650, young = 8.4e5, poisson = 0.3, cohesion = 0, friction = 19.8,
                                 dilation = 0, tension = 0 }
    mpm.material.linear_elastic{ density = 2550, young = 5e8, poisson = 0.19 }
  )") == "");
  CHECK(f.session.warnings.empty());
}

TEST_CASE("a linear elastic rock and Drucker-Prager are checked too", "[lua][input]") {
  LuaFixture f;
  REQUIRE(f.error_of("mpm.material.linear_elastic{ density = 25, young = 5e8, poisson = 0.2 }\n"
                     "mpm.material.drucker_prager{ density = 2000, young = 1e7, poisson = 0.3, cohesion = 0,\n"
                     "  friction = 30, dilation = 0.1, tension = 0 }") == "");
  const auto& w = f.session.warnings;
  REQUIRE(w.size() == 2);
  CHECK(w[0].rfind("test:1: linear_elastic: density = 25 kg/m3", 0) == 0);
  CHECK(w[1].rfind("test:2: drucker_prager: dilation = 0.1 is below 1 degree", 0) == 0);
}

TEST_CASE("a --set name the script never reads is reported, with the closest name it reads", "[lua][input]") {
  LuaFixture f;
  f.session.params = {{"cel", "0.3"}, {"cell_size", "1"}, {"duration", "2"}, {"zzz", "1"}};
  REQUIRE(f.error_of("cell = mpm.param('cell', 0.25) ; t = mpm.param('duration', 1)") == "");
  CHECK(f.number("cell") == 0.25);  // the typo changed nothing
  seismpm::lua::warn_unread_params(f.runtime.state());
  const auto& w = f.session.warnings;
  REQUIRE(w.size() == 3);
  CHECK(w[0] == "--set cel=0.3 was never read by the script (mpm.param): did you mean 'cell'?");
  CHECK(w[1] == "--set cell_size=1 was never read by the script (mpm.param); it reads: cell duration");
  CHECK(w[2] == "--set zzz=1 was never read by the script (mpm.param); it reads: cell duration");
}

TEST_CASE("a probe away from its body is an error naming both positions; one on its surface is not", "[lua][input]") {
  LuaFixture f;
  const std::string build = R"(
    m = mpm.model{ domain = {{0, 0}, {40, 10}}, cell = 0.5 }
    local soil = mpm.material.linear_elastic{ density = 2000, young = 1e7, poisson = 0.3 }
    ground = m:body{ name = "ground", material = soil, shape = mpm.shape.rectangle{0, 0, 30, 2.5}, ppc = 2 }
  )";
  REQUIRE(f.error_of(build) == "");
  const std::string far = f.error_of("m:probe{ name = 'p', body = ground, at = {100, 100} }");
  CHECK(far.find("key 'at': {100, 100} is 120.2 m from the nearest particle of body 'ground', at {29.875, 2.375}; "
                 "a probe must lie within one cell (0.5 m) of its body") != std::string::npos);
  const std::string air = f.error_of("m:probe{ name = 'p', body = ground, at = {10, 4} }");
  CHECK(air.find("{10, 4} is 1.63 m from the nearest particle") != std::string::npos);
  CHECK(f.error_of("crest = m:probe{ name = 'crest', body = ground, at = {30, 2.5} }") ==
        "");  // the corner, 0.18 m from the nearest particle
}

TEST_CASE("overlapping bodies are warned about by name; touching ones, layers and a rigid base are not",
          "[lua][input]") {
  LuaFixture f;
  REQUIRE(f.error_of(R"(
    local m = mpm.model{ domain = {{-1, -1}, {5, 3}}, cell = 0.25 }
    local soil = mpm.material.linear_elastic{ density = 2000, young = 1e7, poisson = 0.3 }
    local clay = mpm.material.linear_elastic{ density = 1800, young = 5e6, poisson = 0.3 }
    m:rigid{ name = "base", shape = mpm.shape.rectangle{-1, -0.25, 5, 0}, ppc = 2, velocity = {0, 0} }
    m:body{ name = "lower", material = clay, shape = mpm.shape.rectangle{0, 0, 4, 0.34}, ppc = 2 }
    m:body{ name = "upper", material = soil, shape = mpm.shape.rectangle{0, 0.34, 4, 1}, ppc = 4 }
    m:body{ name = "ground", shape = mpm.shape.rectangle{0, 1, 4, 2}, ppc = 2,
            regions = mpm.geometry.layers{ left = 0, right = 4, base = 1,
                                           { top = 1.5, material = clay }, { top = 2, material = soil } } }
  )") == "");
  CHECK(f.session.warnings.empty());
  REQUIRE(f.error_of("local m = mpm.model{ domain = {{0, 0}, {4, 2}}, cell = 0.25 }\n"
                     "local soil = mpm.material.linear_elastic{ density = 2000, young = 1e7, poisson = 0.3 }\n"
                     "m:body{ name = 'a', material = soil, shape = mpm.shape.rectangle{0, 0, 2, 1}, ppc = 2 }\n"
                     "m:body{ name = 'b', material = soil, shape = mpm.shape.rectangle{1.5, 0.5, 3, 1.5}, ppc = 3 }") ==
          "");
  REQUIRE(f.session.warnings.size() == 1);
  CHECK(f.session.warnings[0].rfind("test:4: body 'b' overlaps body 'a': 36 of its particles lie inside the shape of "
                                    "'a' (the first at {1.54167, 0.541667})",
                                    0) == 0);
}
