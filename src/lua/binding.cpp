#include "binding.hpp"

#include <sstream>

#include "core/parameter.hpp"

namespace seismpm::lua {

namespace {

constexpr const char* kNamesKey = "seismpm.names";  // registry: function -> its API name, for help()

// Pushes registry[key] (raw), creating an empty table there when it is missing.
void push_registry_table(lua_State* L, const char* key) {
  lua_pushstring(L, key);
  if (lua_rawget(L, LUA_REGISTRYINDEX) == LUA_TTABLE) return;
  lua_pop(L, 1);
  lua_newtable(L);
  lua_pushstring(L, key);
  lua_pushvalue(L, -2);
  lua_rawset(L, LUA_REGISTRYINDEX);
}

// Pushes t[key] of the table on top (raw), creating an empty table there when it is missing.
void push_subtable(lua_State* L, const std::string& key) {
  lua_pushstring(L, key.c_str());
  if (lua_rawget(L, -2) == LUA_TTABLE) return;
  lua_pop(L, 1);
  lua_newtable(L);
  lua_pushstring(L, key.c_str());
  lua_pushvalue(L, -2);
  lua_rawset(L, -4);
}

// Pushes the table that the function `name` goes into and returns its key there.
std::string push_home(lua_State* L, const std::string& name) {
  if (const auto colon = name.find(':'); colon != std::string::npos) {
    const std::string type = name.substr(0, colon);
    if (luaL_getmetatable(L, type.c_str()) != LUA_TTABLE)
      throw std::logic_error("register_functions: no type '" + type + "' (open_type makes it)");
    lua_pushstring(L, "__index");
    lua_rawget(L, -2);
    lua_remove(L, -2);
    return name.substr(colon + 1);
  }
  lua_rawgeti(L, LUA_REGISTRYINDEX, LUA_RIDX_GLOBALS);
  std::size_t start = 0;
  for (std::size_t dot = name.find('.'); dot != std::string::npos; dot = name.find('.', start)) {
    push_subtable(L, name.substr(start, dot - start));
    lua_remove(L, -2);
    start = dot + 1;
  }
  return name.substr(start);
}

}  // namespace

std::string script_message(const std::exception& e) {
  if (const auto* p = dynamic_cast<const ParameterError*>(&e))
    return (p->names().size() > 1 ? "keys " : "key ") + std::string(e.what());
  return e.what();
}

void push_function(lua_State* L, lua_CFunction f, const char* name) {
  lua_pushstring(L, name);
  lua_pushcclosure(L, f, 1);
  push_registry_table(L, kNamesKey);
  lua_pushvalue(L, -2);
  lua_pushstring(L, name);
  lua_rawset(L, -3);
  lua_pop(L, 1);
}

void register_functions(lua_State* L, std::span<const Function> functions) {
  for (const Function& f : functions) {
    if (!f.fn) continue;  // a function of the Lua library, documented here
    const std::string key = push_home(L, f.name);
    lua_pushstring(L, key.c_str());
    push_function(L, f.fn, f.name);
    lua_rawset(L, -3);
    lua_pop(L, 1);
  }
}

std::string dead_object_message(const char* type) {
  return std::string(type) + " used after it was collected or closed (its __gc ran)";
}

void refuse_control_characters(const std::string& text, const std::string& what) {
  for (const char c : text)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      throw Error(what + ": '" + text.substr(0, 40) + "' holds a control character (a line break, a tab, ...)");
}

std::string type_name(lua_State* L, int index) {
  if (luaL_getmetafield(L, index, "__name") == LUA_TSTRING) {  // raw
    std::string s = lua_tostring(L, -1);
    lua_pop(L, 1);
    return s;
  }
  return luaL_typename(L, index);
}

std::string point_text(const Vec<2>& p) {
  std::ostringstream os;
  os << "{" << p[0] << ", " << p[1] << "}";
  return os.str();
}

int raw_global(lua_State* L, const char* name) {
  lua_rawgeti(L, LUA_REGISTRYINDEX, LUA_RIDX_GLOBALS);
  lua_pushstring(L, name);
  const int t = lua_rawget(L, -2);
  lua_remove(L, -2);
  return t;
}

Field field_argument(lua_State* L, int index) {
  if (lua_type(L, index) != LUA_TSTRING) throw Error("expects a field name, one of: " + field_names(2));
  const char* name = lua_tostring(L, index);
  const auto f = parse_field(name, 2);
  if (!f) throw Error(std::string("unknown field '") + name + "' (fields: " + field_names(2) + ")");
  return *f;
}

}  // namespace seismpm::lua
