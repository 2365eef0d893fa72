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
    const char* name = lua_tostring(L, -1);
    const ApiDoc* d = name ? find_doc(name) : nullptr;
    if (!d) {
      // Lua-library functions are documented by name in mpm.geometry.
      throw Error("no help for this " + type_name(L, 1) + "; help() lists everything");
    }
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
