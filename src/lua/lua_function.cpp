#include "lua_function.hpp"

#include <string>

#include "binding.hpp"

namespace seismpm::lua {

namespace {

constexpr const char* kLifeKey = "seismpm.state_life";

struct LifeToken {
  std::shared_ptr<StateLife> life;
};

// The token's finalizer: lua_close runs it, and only lua_close (the registry holds the token).
int close_life(lua_State* L) {
  auto* token = static_cast<LifeToken*>(lua_touserdata(L, 1));
  token->life->main = nullptr;
  token->~LifeToken();
  return 0;
}

std::shared_ptr<StateLife> life_of(lua_State* L) {
  lua_pushstring(L, kLifeKey);
  lua_rawget(L, LUA_REGISTRYINDEX);
  auto* token = static_cast<LifeToken*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  if (!token) throw std::logic_error("the Lua state has no life token (open_state_life)");
  return token->life;
}

std::string error_text(lua_State* L) {
  return lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "(an error object that is not a string)";
}

}  // namespace

void open_state_life(lua_State* L) {
  lua_rawgeti(L, LUA_REGISTRYINDEX, LUA_RIDX_MAINTHREAD);
  lua_State* main = lua_tothread(L, -1);
  lua_pop(L, 1);
  void* mem = lua_newuserdatauv(L, sizeof(LifeToken), 0);
  auto life = std::make_shared<StateLife>();
  life->main = main;
  new (mem) LifeToken{std::move(life)};
  lua_createtable(L, 0, 1);
  lua_pushcfunction(L, close_life);
  lua_setfield(L, -2, "__gc");
  lua_setmetatable(L, -2);
  lua_pushstring(L, kLifeKey);
  lua_insert(L, -2);
  lua_rawset(L, LUA_REGISTRYINDEX);
}

EvaluationScope::EvaluationScope(lua_State* L) : EvaluationScope(life_of(L)) {}

EvaluationScope::EvaluationScope(std::shared_ptr<StateLife> life) : life_(std::move(life)) { ++life_->evaluations; }

EvaluationScope::~EvaluationScope() { --life_->evaluations; }

bool inside_a_value_function(lua_State* L) { return life_of(L)->evaluations > 0; }

LuaFunction::LuaFunction(lua_State* L, int index) : life_(life_of(L)) {
  lua_pushvalue(L, index);
  ref_ = luaL_ref(L, LUA_REGISTRYINDEX);
}

LuaFunction::~LuaFunction() {
  if (lua_State* L = life_->main) luaL_unref(L, LUA_REGISTRYINDEX, ref_);
}

double LuaFunction::operator()(double t) const {
  lua_State* L = life_->main;
  if (!L) throw Error("the Lua state of this function is closed");
  // The main thread may be waiting in coroutine.resume (a coroutine asks): its stack is free above the top.
  if (!lua_checkstack(L, 3)) throw Error("no room on the Lua stack to call the function (too deep a recursion?)");
  const EvaluationScope scope(life_);
  const int top = lua_gettop(L);
  lua_rawgeti(L, LUA_REGISTRYINDEX, ref_);
  lua_pushnumber(L, t);
  if (lua_pcall(L, 1, 1, 0) != LUA_OK) {  // the main thread cannot yield: a yield fails here too
    const std::string msg = error_text(L);
    lua_settop(L, top);
    throw Error("history function failed at t = " + number_text(t) + ": " + msg);
  }
  const bool is_number = lua_isnumber(L, -1);  // a numeric string too, as Lua's arithmetic takes it
  const double v = is_number ? lua_tonumber(L, -1) : 0.0;
  lua_settop(L, top);
  if (!is_number) throw Error("history function must return a number (at t = " + number_text(t) + ")");
  return v;
}

}  // namespace seismpm::lua
