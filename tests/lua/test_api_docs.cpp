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
    const auto* doc = seismpm::lua::find_doc(name);
    REQUIRE(doc != nullptr);
    CHECK(std::string(doc->example).size() > 5);
    ++count;
  }
  CHECK(count >= 30);
}
