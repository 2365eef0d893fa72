// Every function the bindings register has help text with an example.
#include <catch2/catch.hpp>

#include "lua/api_docs.hpp"
#include "lua_fixture.hpp"

TEST_CASE("every registered API function is documented", "[lua][docs]") {
  seismpm::test::LuaFixture f;
  lua_State* L = f.runtime.state();
  lua_getfield(L, LUA_REGISTRYINDEX, "seismpm.names");
  REQUIRE(lua_istable(L, -1));
  int count = 0;
  lua_pushnil(L);
  while (lua_next(L, -2) != 0) {
    const std::string name = lua_tostring(L, -1);
    lua_pop(L, 1);
    if (name.find("__tostring") != std::string::npos) continue;
    CAPTURE(name);
    const auto* doc = seismpm::lua::find_function(name);
    REQUIRE(doc != nullptr);
    CHECK(std::string(doc->example).size() > 5);
    ++count;
  }
  CHECK(count >= 30);
}

TEST_CASE("help() knows every documented name, function and object", "[lua][docs]") {
  seismpm::test::LuaFixture f;
  std::string chunk = "help()\n";
  for (const auto* d : seismpm::lua::api_functions()) chunk += std::string("help('") + d->name + "')\n";
  chunk += R"(
    help(mpm.model); help(mpm.geometry.slope); help(mpm.material.mohr_coulomb)
    local m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
    help(m); help(m.run); help(mpm.history.table{ {0, 0} })
    assert(pcall(help, "nonsense"))  -- a search that finds nothing says so
  )";
  CHECK(f.error_of(chunk) == "");
}
