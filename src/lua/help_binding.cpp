// help(): the API documentation in the console.
#include <sstream>

#include "api_docs.hpp"
#include "binding.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

std::string doc_text(const ApiDoc& d) {
  return std::string(d.signature) + "\n  " + d.summary + "\n  example: " + d.example + "\n";
}

// The documented methods of an object type ("model:" prefix).
std::string methods_of(const std::string& type) {
  std::ostringstream os;
  os << type << " methods:\n";
  for (const auto& d : api_docs())
    if (std::string(d.name).rfind(type + ":", 0) == 0) os << "  " << d.signature << "\n";
  os << "help(\"" << type << ":name\") shows one of them.\n";
  return os.str();
}

// "mpm.<table>.<key>" where the value at `index` sits in a table of mpm, or "".
std::string library_name(lua_State* L, int index) {
  index = lua_absindex(L, index);
  std::string found;
  lua_getglobal(L, "mpm");
  if (!lua_istable(L, -1)) {
    lua_pop(L, 1);
    return found;
  }
  lua_pushnil(L);
  while (found.empty() && lua_next(L, -2) != 0) {
    if (lua_type(L, -2) == LUA_TSTRING && lua_istable(L, -1)) {
      const std::string table = lua_tostring(L, -2);
      lua_pushnil(L);
      while (lua_next(L, -2) != 0) {
        if (found.empty() && lua_type(L, -2) == LUA_TSTRING && lua_rawequal(L, -1, index))
          found = "mpm." + table + "." + lua_tostring(L, -2);
        lua_pop(L, 1);
      }
    }
    lua_pop(L, 1);
  }
  lua_pop(L, found.empty() ? 1 : 2);  // mpm, and the outer key when the search stopped early
  return found;
}

int help(lua_State* L) {
  std::string text;
  if (lua_isnoneornil(L, 1)) {
    std::ostringstream os;
    os << "seismpm Lua API (help(x) for one function or object, e.g. help(mpm.model), help(m), help(\"model:run\")):\n";
    for (const auto& d : api_docs()) os << "  " << d.signature << "\n";
    text = os.str();
  } else if (lua_type(L, 1) == LUA_TSTRING) {
    const std::string name = lua_tostring(L, 1);
    if (const ApiDoc* d = find_doc(name))
      text = doc_text(*d);
    else if (name == "model" || name == "body" || name == "probe" || name == "history" || name == "shape" ||
             name == "material")
      text = methods_of(name);
    else
      throw Error("no help for '" + name + "'; help() lists everything");
  } else if (lua_type(L, 1) == LUA_TUSERDATA) {
    text = methods_of(type_name(L, 1));
  } else {
    // A function: its registered name.
    lua_getfield(L, LUA_REGISTRYINDEX, "seismpm.names");
    lua_pushvalue(L, 1);
    lua_rawget(L, -2);
    std::string name = lua_tostring(L, -1) ? lua_tostring(L, -1) : "";
    if (name.empty()) name = library_name(L, 1);  // a function of the Lua library (mpm.geometry.*)
    const ApiDoc* d = name.empty() ? nullptr : find_doc(name);
    if (!d) throw Error("no help for this " + type_name(L, 1) + "; help() lists everything");
    text = doc_text(*d);
  }
  std::fputs(text.c_str(), stdout);
  std::fflush(stdout);
  return 0;
}

}  // namespace

void open_help(lua_State* L, int /*mpm*/) {
  push_function(L, &guarded<help>, "help");
  lua_setglobal(L, "help");
}

}  // namespace seismpm::lua
