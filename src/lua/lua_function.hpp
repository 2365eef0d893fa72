// A Lua function that a C++ object keeps (the function of mpm.history.fn, held by a rigid body's
// velocity): a registry reference, called through the state's main thread so that it never points to
// the coroutine that created it (which may be collected), and released when the holder dies. A holder
// may outlive the Lua state (a C++ object destroyed after lua_close): then a call throws and the
// release is skipped, as lua_close has freed the registry already.
#pragma once

#include <lua.hpp>

#include <memory>

namespace seismpm::lua {

// Whether a Lua state is still open, shared by everything that keeps a reference into it.
struct StateLife {
  lua_State* main = nullptr;  // the main thread; nullptr once the state is closed
};

// Creates the state's life token (a registry userdata whose finalizer, run by lua_close, clears it).
void open_state_life(lua_State* L);

class LuaFunction {
 public:
  // References the function at `index` of L's stack (any thread of the state).
  LuaFunction(lua_State* L, int index);
  ~LuaFunction();
  LuaFunction(const LuaFunction&) = delete;
  LuaFunction& operator=(const LuaFunction&) = delete;

  // f(t) as a number, in a protected call on the main thread; throws Error when it fails, yields,
  // returns something else than a number, or the state is closed.
  double operator()(double t) const;

 private:
  std::shared_ptr<StateLife> life_;
  int ref_ = LUA_NOREF;
};

}  // namespace seismpm::lua
