// m:strength_reduction: the factor of safety of Griffiths & Lane's example 1 through Lua, beside mpm.lem on
// the same model, the model left as it was, the mechanism on file, and errors naming the key.
#include <catch2/catch.hpp>
#include <filesystem>

#include "lua_fixture.hpp"

using seismpm::test::LuaFixture;

namespace {

// Griffiths & Lane (1999) example 1: a 2:1 slope 10 m high on a firm base at the toe (D = 1),
// c' = 10 kPa, phi' = 20 degrees, gamma = 20 kN/m3, E = 1e5 kPa, nu = 0.3; cells of 1 m.
const char* kSlope = R"(
  local m = mpm.model{ domain = {{-15, 0}, {35, 12}}, cell = 1, gravity = {0, -10} }
  local soil = mpm.material.mohr_coulomb{ density = 2000, young = 1e8, poisson = 0.3, cohesion = 10e3,
                                          friction = 20 }
  m:body{ name = "slope", material = soil, shape = mpm.shape.polygon{ {-15, 0}, {20, 0}, {0, 10}, {-15, 10} } }
  m:fix{ side = "bottom", dof = "xy" }
  m:fix{ side = "left", dof = "x" }
  m:fix{ side = "right", dof = "x" }
)";

double global(lua_State* L, const char* name) {
  lua_getglobal(L, name);
  const double v = lua_tonumber(L, -1);
  lua_pop(L, 1);
  return v;
}

}  // namespace

TEST_CASE("m:strength_reduction on Griffiths & Lane example 1: 1.4 within 5 %, beside Bishop's", "[lua][srf]") {
  const auto dir = std::filesystem::temp_directory_path() / "seismpm_strength_reduction";
  std::filesystem::remove_all(dir);
  LuaFixture f;
  const std::string error = f.error_of(std::string(kSlope) + "m:output{ dir = '" + dir.string() + R"(' }
    local r = m:strength_reduction{ srf = {1, 2}, tolerance = 0.05, write = true }
    fos, holds, fails, trials, file = r.fos, r.holds, r.fails, #r.trials, r.file
    first = r.trials[1]
    first_srf, first_converged, first_ended = first.srf, first.converged, first.ended
    second_converged, second_ended = r.trials[2].converged, r.trials[2].ended
    complete = first.displacement >= 0 and first.kinetic_energy >= 0 and first.time > 0 and first.steps > 0
               and first.unbalanced >= 0 and first.kinetic >= 0 and type(r.criterion) == "string"
               and r.max_displacement > 0
    time_after, steps_after = m:time(), m:steps()
    lem = mpm.lem{ model = m }.fos
  )");
  REQUIRE(error == "");
  lua_State* L = f.runtime.state();
  CHECK(global(L, "fos") == Approx(1.4).epsilon(0.05));
  CHECK(global(L, "fos") == Approx(global(L, "lem")).epsilon(0.05));  // Bishop: 1.378 on this model
  CHECK(global(L, "fails") - global(L, "holds") <= 0.05);
  CHECK(global(L, "trials") >= 4);
  CHECK(global(L, "first_srf") == 1);
  lua_getglobal(L, "first_converged");
  CHECK(lua_toboolean(L, -1));
  lua_getglobal(L, "second_converged");
  CHECK_FALSE(lua_toboolean(L, -1));
  lua_getglobal(L, "first_ended");
  CHECK(std::string(lua_tostring(L, -1)) == "equilibrium");
  lua_getglobal(L, "complete");
  CHECK(lua_toboolean(L, -1));
  lua_pop(L, 4);
  // The model itself never ran: the trials ran on copies.
  CHECK(global(L, "time_after") == 0);
  CHECK(global(L, "steps_after") == 0);
  lua_getglobal(L, "file");
  REQUIRE(lua_isstring(L, -1));
  const std::string file = lua_tostring(L, -1);
  lua_pop(L, 1);
  CHECK(file == (dir / "strength_reduction_mechanism.vtu").string());
  CHECK(std::filesystem::file_size(file) > 1000);
  std::filesystem::remove_all(dir);
}

TEST_CASE("m:strength_reduction: errors name the key", "[lua][srf][errors]") {
  LuaFixture f;
  const std::string slope(kSlope);
  CHECK_THAT(f.error_of(slope + "m:strength_reduction{ srff = {1, 2} }"), Catch::Contains("srff"));
  CHECK_THAT(f.error_of(slope + "m:strength_reduction{ srf = {2, 1} }"), Catch::Contains("srf"));
  CHECK_THAT(f.error_of(slope + "m:strength_reduction{ srf = {1} }"), Catch::Contains("srf"));
  CHECK_THAT(f.error_of(slope + "m:strength_reduction{ tolerance = 0 }"), Catch::Contains("tolerance"));
  CHECK_THAT(f.error_of(slope + "m:strength_reduction{ damping = 1 }"), Catch::Contains("damping"));
  CHECK_THAT(f.error_of(slope + "m:strength_reduction{ max_displacement = -1 }"), Catch::Contains("max_displacement"));
  CHECK_THAT(f.error_of(slope + "m:strength_reduction{ write = true }"), Catch::Contains("write"));
  CHECK_THAT(f.error_of(slope + "m:strength_reduction{ srf = {1, 1.2}, tolerance = 0.1 }"),
             Catch::Contains("still holds at srf = 1.2"));
}
