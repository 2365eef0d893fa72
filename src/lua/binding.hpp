// What every binding file shares: C++ exceptions turned into Lua errors at the boundary, userdata
// with metatables, self(), and the registration of a file's table of functions (arg_spec.hpp).
// This directory is the only place that knows Lua's C API.
//
// The boundary rule: a Lua error is a longjmp, which would skip the destructors of the C++ objects of
// every frame it crosses. So no code here calls a Lua function that can raise (luaL_check*, luaL_len,
// lua_getfield on a table a script made, lua_call) while a C++ object with a destructor is alive:
// arguments are read raw (args.hpp), Lua code is called with lua_pcall, and a failure throws a C++
// exception that `guarded` turns into a Lua error after the C++ frame is gone.
#pragma once

#include <lua.hpp>

#include <memory>
#include <new>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>

#include "arg_spec.hpp"
#include "args.hpp"
#include "core/particle_fields.hpp"
#include "core/types.hpp"

namespace seismpm::lua {

// A bad argument or a failed call; becomes a Lua error "file:line: function: message".
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The message of a C++ exception as the script sees it: a kernel's ParameterError ("'friction' must
// be ...") names a key of the call.
std::string script_message(const std::exception& e);

// Calls F; a C++ exception becomes a Lua error prefixed with the caller's position and the
// function's name (upvalue 1). No C++ object is alive when lua_error unwinds.
template <int (*F)(lua_State*)>
int guarded(lua_State* L) {
  try {
    return F(L);
  } catch (const std::exception& e) {
    const std::string message = script_message(e);  // destroyed at the end of this block
    luaL_where(L, 1);
    const char* name = lua_tostring(L, lua_upvalueindex(1));
    lua_pushfstring(L, "%s: %s", name ? name : "seismpm", message.c_str());
    lua_concat(L, 2);
  } catch (...) {  // nothing may unwind through Lua's C frames
    lua_pushstring(L, "seismpm: an unknown C++ exception");
  }
  return lua_error(L);
}

// Pushes F as a closure named `name` (for messages and help) and records the name for help().
void push_function(lua_State* L, lua_CFunction f, const char* name);

// Registers each function of a table where its name says: "model:run" among the methods of type
// "model" (made by open_type), "mpm.material.linear_elastic" in the mpm.material table (created when
// missing), "help" as a global.
void register_functions(lua_State* L, std::span<const Function> functions);

// Lua's type name of each object behind a userdata; specialised next to the objects.
template <class T>
struct LuaType;

// The block of a userdata: the object and whether it still lives. Its __gc destroys the object once
// and marks it dead; the memory stays until Lua frees it, which may be much later (a finalizer of
// another object can keep it reachable, and a script can call __gc by hand), so every access asks.
template <class T>
struct Userdata {
  T object;
  bool alive = true;
};

// The message for an object used after its __gc ran.
std::string dead_object_message(const char* type);

// __gc of T: destroys the object the first time, does nothing after; called by hand on a value that
// is no T, a Lua error (raised with no C++ object alive).
template <class T>
int destroy(lua_State* L) {
  if (auto* u = static_cast<Userdata<T>*>(luaL_testudata(L, 1, LuaType<T>::name))) {
    if (u->alive) {
      u->alive = false;
      u->object.~T();
    }
    return 0;
  }
  const char* got = luaL_getmetafield(L, 1, "__name") == LUA_TSTRING ? lua_tostring(L, -1) : luaL_typename(L, 1);
  return luaL_error(L, "%s:__gc: expects a %s, got %s", LuaType<T>::name, LuaType<T>::name, got);
}

// The metatable of T: __name, __gc, __tostring (a one-line summary), __index (its methods, empty).
template <class T, int (*ToString)(lua_State*)>
void make_type(lua_State* L, const char* type) {
  luaL_newmetatable(L, type);
  lua_pushcfunction(L, &destroy<T>);
  lua_setfield(L, -2, "__gc");
  push_function(L, &guarded<ToString>, (std::string(type) + ":__tostring").c_str());
  lua_setfield(L, -2, "__tostring");
  lua_newtable(L);
  lua_setfield(L, -2, "__index");
  lua_pop(L, 1);
}

// Creates the metatable of T and registers the functions of its binding file.
template <class T, int (*ToString)(lua_State*)>
void open_type(lua_State* L, std::span<const Function> functions) {
  make_type<T, ToString>(L, LuaType<T>::name);
  register_functions(L, functions);
}

template <class T>
T& push_object(lua_State* L, T value) {
  void* mem = lua_newuserdatauv(L, sizeof(Userdata<T>), 0);
  auto* u = new (mem) Userdata<T>{std::move(value)};
  luaL_setmetatable(L, LuaType<T>::name);
  return u->object;
}

// The T at `index`, or nullptr when the value is no T; throws Error when it is a T whose __gc ran.
template <class T>
T* test_object(lua_State* L, int index) {
  auto* u = static_cast<Userdata<T>*>(luaL_testudata(L, index, LuaType<T>::name));  // compares metatables: raw
  if (!u) return nullptr;
  if (!u->alive) throw Error(dead_object_message(LuaType<T>::name));
  return &u->object;
}

// Lua's name for the type of the value at `index` ("number", "table", "model", ...).
std::string type_name(lua_State* L, int index);

// The T at `index`; `what` names the value in messages ("self" for the object a method is called on).
template <class T>
T& check_object(lua_State* L, int index, const std::string& what) {
  auto* u = static_cast<Userdata<T>*>(luaL_testudata(L, index, LuaType<T>::name));
  if (!u) throw Error(what + " must be a " + LuaType<T>::name + ", got " + type_name(L, index));
  if (!u->alive) throw Error((what == "self" ? "" : what + ": ") + dead_object_message(LuaType<T>::name));
  return u->object;
}

// The object a method is called on (m:run: m).
template <class T>
T& self(lua_State* L) {
  return check_object<T>(L, 1, "self");
}

// The object under `key` of a call's arguments (an Object key of its table).
template <class T>
T& object_argument(const Args& a, const char* key) {
  lua_State* L = a.state();
  a.push(key);
  T& obj = check_object<T>(L, -1, std::string("key '") + key + "'");
  lua_pop(L, 1);  // the argument table keeps the userdata alive
  return obj;
}

// Throws when `text` holds a control character (a line break would end a line of a gnuplot script and
// start a command of the script's choosing); `what` names it.
void refuse_control_characters(const std::string& text, const std::string& what);

// A particle field name at `index` (body:field, probe:get); the error lists the names.
Field field_argument(lua_State* L, int index);

// "{x, y}" for messages.
std::string point_text(const Vec<2>& p);

// Pushes the global `name` without running a metamethod of the globals table; returns its type.
int raw_global(lua_State* L, const char* name);

}  // namespace seismpm::lua
