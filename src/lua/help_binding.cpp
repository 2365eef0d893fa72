// help(): the API documentation in the console, from the same tables that check the calls.
#include <cstdio>
#include <sstream>

#include "api_docs.hpp"
#include "binding.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

// The documented methods of an object type ("model:" prefix).
std::string methods_of(const std::string& type) {
  std::ostringstream os;
  os << type << " methods:\n";
  for (const Function* f : api_functions())
    if (std::string(f->name).rfind(type + ":", 0) == 0) os << "  " << signature(*f) << "\n";
  os << "help(\"" << type << ":name\") shows one of them.\n";
  return os.str();
}

bool is_object_type(const std::string& name) {
  for (const char* t : {kModelType, kBodyType, kProbeType, kHistoryType, kShapeType, kMaterialType})
    if (name == t) return true;
  return false;
}

// "mpm.<table>.<key>" where the value at `index` sits in a table of mpm, or "" (raw traversal).
std::string library_name(lua_State* L, int index) {
  index = lua_absindex(L, index);
  std::string found;
  const int top = lua_gettop(L);
  if (raw_global(L, "mpm") == LUA_TTABLE) {
    lua_pushnil(L);
    while (found.empty() && lua_next(L, -2) != 0) {
      if (lua_type(L, -2) == LUA_TSTRING && lua_istable(L, -1)) {
        lua_pushnil(L);
        while (lua_next(L, -2) != 0) {
          if (found.empty() && lua_type(L, -2) == LUA_TSTRING && lua_rawequal(L, -1, index))
            found = std::string("mpm.") + lua_tostring(L, -4) + "." + lua_tostring(L, -2);
          lua_pop(L, 1);
        }
      }
      lua_pop(L, 1);
    }
  }
  lua_settop(L, top);
  return found;
}

// The API name of the function at `index`: the one it was registered under, or where the Lua library put it.
std::string function_name(lua_State* L, int index) {
  lua_pushstring(L, "seismpm.names");
  std::string name;
  if (lua_rawget(L, LUA_REGISTRYINDEX) == LUA_TTABLE) {
    lua_pushvalue(L, index);
    if (lua_rawget(L, -2) == LUA_TSTRING) name = lua_tostring(L, -1);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  return name.empty() ? library_name(L, index) : name;
}

std::string help_of(lua_State* L) {
  if (lua_isnoneornil(L, 1)) {
    std::ostringstream os;
    os << "seismpm Lua API (help(x) for one function or object, e.g. help(mpm.model), help(m), help(\"model:run\")):\n";
    for (const Function* f : api_functions()) os << "  " << signature(*f) << "\n";
    return os.str();
  }
  if (lua_type(L, 1) == LUA_TSTRING) {
    const std::string name = lua_tostring(L, 1);
    if (const Function* f = find_function(name)) return help_text(*f);
    if (is_object_type(name)) return methods_of(name);
    throw Error("no help for '" + name + "'; help() lists everything");
  }
  if (lua_type(L, 1) == LUA_TUSERDATA) return methods_of(type_name(L, 1));
  const std::string name = lua_isfunction(L, 1) ? function_name(L, 1) : "";
  const Function* f = name.empty() ? nullptr : find_function(name);
  if (!f) throw Error("no help for this " + type_name(L, 1) + "; help() lists everything");
  return help_text(*f);
}

int help(lua_State* L) {
  const std::string text = help_of(L);
  std::fputs(text.c_str(), stdout);
  std::fflush(stdout);
  return 0;
}

const Function kHelp[] = {
    {"help",
     &guarded<help>,
     "help() | help(object) | help(\"name\")",
     {},
     "Lists the API, or shows the documentation and an example of one function (its keys with types, ranges, "
     "units and defaults) or of an object's methods.",
     "help(mpm.model); help(m); help(\"model:run\")"},
};

}  // namespace

std::span<const Function> help_functions() { return kHelp; }

void open_help(lua_State* L) { register_functions(L, kHelp); }

}  // namespace seismpm::lua
