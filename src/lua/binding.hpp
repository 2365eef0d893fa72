// What every binding file shares: C++ exceptions turned into Lua errors at the boundary, userdata
// with metatables, and `Args`, the validator of a function's table of named arguments.
// This directory is the only place that knows Lua's C API.
#pragma once

#include <lua.hpp>

#include <memory>
#include <new>
#include <optional>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/particle_fields.hpp"
#include "core/types.hpp"

namespace seismpm::lua {

// A bad argument or a failed call; becomes a Lua error "file:line: function: message".
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Calls F; a C++ exception becomes a Lua error prefixed with the caller's position and the
// function's name (upvalue 1). No C++ object is alive when lua_error unwinds.
template <int (*F)(lua_State*)>
int guarded(lua_State* L) {
  try {
    return F(L);
  } catch (const std::exception& e) {
    luaL_where(L, 1);
    const char* name = lua_tostring(L, lua_upvalueindex(1));
    lua_pushfstring(L, "%s: %s", name ? name : "seismpm", e.what());
    lua_concat(L, 2);
  }
  return lua_error(L);
}

// Pushes F as a closure named `name` (for messages and help) and records it for help().
void push_function(lua_State* L, lua_CFunction f, const char* name);

template <int (*F)(lua_State*)>
void set_function(lua_State* L, int table, const char* key, const char* full_name) {
  table = lua_absindex(L, table);
  push_function(L, &guarded<F>, full_name);
  lua_setfield(L, table, key);
}

// Userdata holding a T; the metatable `type` must have been made with new_type<T>.
template <class T>
int destroy(lua_State* L) {
  static_cast<T*>(lua_touserdata(L, 1))->~T();
  return 0;
}

// Creates the metatable for a type: __name, __gc, __tostring (a one-line summary) and
// __index = a methods table, which is left on the stack for the caller to fill.
template <class T, int (*ToString)(lua_State*)>
void new_type(lua_State* L, const char* type) {
  luaL_newmetatable(L, type);
  lua_pushcfunction(L, &destroy<T>);
  lua_setfield(L, -2, "__gc");
  push_function(L, &guarded<ToString>, (std::string(type) + ":__tostring").c_str());
  lua_setfield(L, -2, "__tostring");
  lua_newtable(L);
  lua_pushvalue(L, -1);
  lua_setfield(L, -3, "__index");
  lua_remove(L, -2);  // leave the methods table
}

template <class T>
T& push_object(lua_State* L, const char* type, T value) {
  void* mem = lua_newuserdatauv(L, sizeof(T), 0);
  T* obj = new (mem) T(std::move(value));
  luaL_setmetatable(L, type);
  return *obj;
}

template <class T>
T* test_object(lua_State* L, int index, const char* type) {
  return static_cast<T*>(luaL_testudata(L, index, type));
}

// Lua's name for the type of the value at `index` ("number", "table", "model", ...).
std::string type_name(lua_State* L, int index);

template <class T>
T& check_object(lua_State* L, int index, const char* type, const std::string& what) {
  if (T* obj = test_object<T>(L, index, type)) return *obj;
  throw Error(what + " must be a " + type + ", got " + type_name(L, index));
}

// The table of named arguments at `index`. The constructor rejects any key not in `allowed`
// (positional entries 1..n only when `positional`), so a misspelt key is named before a missing
// one. Messages name the key and the allowed range.
class Args {
 public:
  Args(lua_State* L, int index, std::initializer_list<const char*> allowed, bool positional = false);

  bool has(const char* key);
  // Pushes the value of `key` (nil if absent) and returns its Lua type.
  int push(const char* key);

  double number(const char* key);                 // required
  double number(const char* key, double fallback);
  std::optional<double> optional_number(const char* key);
  int integer(const char* key, int fallback);
  std::string string(const char* key);
  std::string string(const char* key, const std::string& fallback);
  std::string choice(const char* key, const std::vector<std::string>& allowed, const std::string& fallback);
  bool boolean(const char* key, bool fallback);
  Vec<2> point(const char* key);                    // {x, y}
  std::vector<Vec<2>> points(const char* key);      // {{x, y}, ...}
  // A non-empty list of strings {"a", "b"}; nullopt when the key is absent.
  std::optional<std::vector<std::string>> names(const char* key);

  // Range checks with messages such as "key 'cell' must be > 0 (m), got -1".
  static double positive(const char* key, double v, const char* unit = "");
  static double at_least(const char* key, double v, double lo, const char* unit = "");
  static double in_range(const char* key, double v, double lo, double hi, bool hi_open, const char* unit = "");

  // Number of positional entries (the table's length).
  lua_Integer length() const;
  // Reads positional entry i: a number, or a point {x, y}.
  double number_at(lua_Integer i);
  Vec<2> point_at(lua_Integer i, const std::string& what);

  lua_State* state() const { return L_; }
  int index() const { return index_; }

 private:
  lua_State* L_;
  int index_;
};

// A particle field name at `index` (body:field, probe:get); the error lists the names.
Field field_argument(lua_State* L, int index);

// Reads {x, y} at the top of the stack; `what` names it in messages.
Vec<2> to_point(lua_State* L, int index, const std::string& what);

}  // namespace seismpm::lua
