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

template <class T>
int destroy(lua_State* L) {
  static_cast<T*>(lua_touserdata(L, 1))->~T();
  return 0;
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
  void* mem = lua_newuserdatauv(L, sizeof(T), 0);
  T* obj = new (mem) T(std::move(value));
  luaL_setmetatable(L, LuaType<T>::name);
  return *obj;
}

template <class T>
T* test_object(lua_State* L, int index) {
  return static_cast<T*>(luaL_testudata(L, index, LuaType<T>::name));  // compares metatables: raw
}

// Lua's name for the type of the value at `index` ("number", "table", "model", ...).
std::string type_name(lua_State* L, int index);

template <class T>
T& check_object(lua_State* L, int index, const std::string& what) {
  if (T* obj = test_object<T>(L, index)) return *obj;
  throw Error(what + " must be a " + LuaType<T>::name + ", got " + type_name(L, index));
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

// A particle field name at `index` (body:field, probe:get); the error lists the names.
Field field_argument(lua_State* L, int index);

// "{x, y}" for messages.
std::string point_text(const Vec<2>& p);

// Pushes the global `name` without running a metamethod of the globals table; returns its type.
int raw_global(lua_State* L, const char* name);

}  // namespace seismpm::lua
