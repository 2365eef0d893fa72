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
  int evaluations = 0;        // value functions being evaluated now (EvaluationScope)
};

// Creates the state's life token (a registry userdata whose finalizer, run by lua_close, clears it).
void open_state_life(lua_State* L);

// A value function runs: Lua code that computes a value for a model while C++ code is in the middle of
// using it (a history function inside a step, b:set_velocity's function between two particles). Such a
// function may read models, never change or step one (model_guard.cpp asks). Counted while it lives.
class EvaluationScope {
 public:
  explicit EvaluationScope(lua_State* L);
  explicit EvaluationScope(std::shared_ptr<StateLife> life);
  ~EvaluationScope();
  EvaluationScope(const EvaluationScope&) = delete;
  EvaluationScope& operator=(const EvaluationScope&) = delete;

 private:
  std::shared_ptr<StateLife> life_;
};

// Whether a value function is being evaluated now.
bool inside_a_value_function(lua_State* L);

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
