// A fresh Lua runtime per test, quiet, with the project's Lua library.
#pragma once

#include <lua.hpp>

#include <string>

#include "lua/runtime.hpp"

namespace seismpm::test {

struct LuaFixture {
  lua::Session session;
  lua::Runtime runtime;

  // `sandbox`: as --sandbox, with the script's folder and the output directory given (else none).
  explicit LuaFixture(bool sandbox = false, const std::string& script_dir = "", const std::string& out_dir = "")
      : runtime(init(session, sandbox, script_dir, out_dir), {SEISMPM_SOURCE_LUA_DIR}) {}

  static lua::Session& init(lua::Session& s, bool sandbox, const std::string& script_dir, const std::string& out_dir) {
    s.progress = Progress::Mode::Quiet;
    s.sandbox = sandbox;
    s.script_dir = script_dir;
    s.out_dir = out_dir;
    return s;
  }

  // A global the chunks set, as a number (0 when it is not one) or as a truth value.
  double number(const char* name) {
    lua_State* L = runtime.state();
    lua_getglobal(L, name);
    const double v = lua_tonumber(L, -1);
    lua_pop(L, 1);
    return v;
  }
  bool truth(const char* name) {
    lua_State* L = runtime.state();
    lua_getglobal(L, name);
    const bool v = lua_toboolean(L, -1);
    lua_pop(L, 1);
    return v;
  }

  // Runs a chunk; returns "" on success, the error message otherwise.
  std::string error_of(const std::string& code) {
    std::string error;
    return runtime.execute(code, "=test", error) ? std::string() : error;
  }
};

}  // namespace seismpm::test
