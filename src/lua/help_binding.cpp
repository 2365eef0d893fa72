// help(): the API documentation in the console, from the same tables that check the calls.
#include <algorithm>
#include <cstdio>
#include <sstream>

#include "api_docs.hpp"
#include "binding.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

// The documented methods of an object type ("model:" prefix), one line each.
std::string methods_of(const std::string& type) {
  std::vector<const Function*> methods;
  for (const Function* f : api_functions())
    if (std::string(f->name).rfind(type + ":", 0) == 0) methods.push_back(f);
  return type + " methods (help(\"" + type + ":name\") shows one in full):\n" + listing(methods);
}

bool is_object_type(const std::string& name) {
  for (const char* t : {kModelType, kBodyType, kProbeType, kHistoryType, kShapeType, kMaterialType})
    if (name == t) return true;
  return false;
}

// Whether a documented function sits in the table `prefix` ("mpm", "mpm.history"), directly or below.
bool below(const Function& f, const std::string& prefix) { return std::string(f.name).rfind(prefix + ".", 0) == 0; }

// What help(mpm.history) or help("mpm.history") shows: the table's functions, its tables, and the methods
// of the objects its functions make (mpm.history: the history methods); "" when no documented name is in it.
std::string table_help(const std::string& prefix) {
  std::vector<const Function*> direct;
  std::vector<std::string> tables;
  for (const Function* f : api_functions()) {
    if (!below(*f, prefix)) continue;
    const std::string rest = std::string(f->name).substr(prefix.size() + 1);
    const auto dot = rest.find('.');
    if (dot == std::string::npos) {
      direct.push_back(f);
    } else if (std::find(tables.begin(), tables.end(), rest.substr(0, dot)) == tables.end()) {
      tables.push_back(rest.substr(0, dot));
    }
  }
  if (direct.empty() && tables.empty()) return "";
  std::ostringstream os;
  os << prefix << " (help(\"name\") shows one in full, help(\"word\") searches):\n" << listing(direct);
  for (const auto& t : tables) {
    int n = 0;
    for (const Function* f : api_functions()) n += below(*f, prefix + "." + t);
    os << "  " << prefix << "." << t << ".*: " << n << (n == 1 ? " function" : " functions") << ", help(" << prefix
       << "." << t << ")\n";
  }
  const std::string type = prefix.substr(prefix.rfind('.') + 1);
  if (prefix != "mpm" && is_object_type(type)) os << methods_of(type);
  return os.str();
}

// The name of the table at `index` in the API: "mpm", "mpm.<key>" for a table of mpm, or "" (raw traversal).
std::string table_name(lua_State* L, int index) {
  index = lua_absindex(L, index);
  std::string found;
  const int top = lua_gettop(L);
  if (raw_global(L, "mpm") == LUA_TTABLE) {
    if (lua_rawequal(L, -1, index)) found = "mpm";
    lua_pushnil(L);
    while (found.empty() && lua_next(L, -2) != 0) {
      if (lua_type(L, -2) == LUA_TSTRING && lua_rawequal(L, -1, index))
        found = std::string("mpm.") + lua_tostring(L, -2);
      lua_pop(L, 1);
    }
  }
  lua_settop(L, top);
  return found;
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

// "m:run" (as the listings and the reference write a method) as "model:run"; other names as they are.
const Function* function_by_written_name(const std::string& name) {
  if (const Function* f = find_function(name)) return f;
  const auto colon = name.find(':');
  if (colon == std::string::npos) return nullptr;
  static const std::pair<const char*, const char*> kReceivers[] = {
      {"m", kModelType},   {"b", kBodyType},  {"r", kBodyType},      {"p", kProbeType},
      {"h", kHistoryType}, {"s", kShapeType}, {"mat", kMaterialType}};
  for (const auto& [receiver, type] : kReceivers)
    if (name.substr(0, colon) == receiver)
      if (const Function* f = find_function(type + name.substr(colon))) return f;
  return nullptr;
}

std::string overview() {
  std::ostringstream os;
  os << "seismpm Lua API. help(x) documents a function, a table of the API or an object (help(mpm.model), "
        "help(mpm.history), help(m)); help(\"model:run\") one by name; help(\"word\") searches.\n";
  for (const auto& section : api_sections()) {
    std::vector<const Function*> functions;
    for (const Function& f : section.functions) functions.push_back(&f);
    os << section.title << ":\n" << listing(functions);
  }
  return os.str();
}

const char* const kNotApi = "; help() lists the API, help(\"word\") searches it\n";

}  // namespace

std::string help_for(lua_State* L, int index) {
  index = lua_absindex(L, index);
  switch (lua_type(L, index)) {
    case LUA_TNONE:
    case LUA_TNIL:
      return overview();
    case LUA_TSTRING: {
      const std::string name = lua_tostring(L, index);
      if (const Function* f = function_by_written_name(name)) return help_text(*f);
      if (is_object_type(name)) return methods_of(name);
      if (name == "mpm" || name.rfind("mpm.", 0) == 0)
        if (std::string text = table_help(name); !text.empty()) return text;
      return search_text(name);
    }
    case LUA_TUSERDATA:
      if (const std::string type = type_name(L, index); is_object_type(type)) return methods_of(type);
      return "no help for this " + type_name(L, index) + kNotApi;
    case LUA_TTABLE: {
      const std::string name = table_name(L, index);
      if (std::string text = name.empty() ? "" : table_help(name); !text.empty()) return text;
      return "no help for this table: it is not one of the API's (mpm and its tables)" + std::string(kNotApi);
    }
    case LUA_TFUNCTION: {
      const std::string name = function_name(L, index);
      if (const Function* f = name.empty() ? nullptr : find_function(name)) return help_text(*f);
      return "no help for this function: it is not one of the API's" + std::string(kNotApi);
    }
    default:
      return "no help for a " + type_name(L, index) + " value" + kNotApi;
  }
}

namespace {

int help(lua_State* L) {
  const std::string text = help_for(L, 1);
  std::fputs(text.c_str(), stdout);
  std::fflush(stdout);
  return 0;
}

const Function kHelp[] = {
    {"help",
     &guarded<help>,
     "help() | help(object) | help(\"name\") | help(\"word\")",
     {},
     "Lists the API with a line per function, or shows the documentation and an example of one function (its "
     "keys with types, ranges, units and defaults), the functions of a table of the API (mpm, mpm.history, "
     "mpm.material, ...) or an object's methods (help(m)). A word that names nothing searches the names, "
     "descriptions and keys, ignoring case, and lists what matches.",
     "help(mpm.model); help(mpm.history); help(m); help(\"model:run\"); help(\"friction\")"},
};

}  // namespace

std::span<const Function> help_functions() { return kHelp; }

void open_help(lua_State* L) { register_functions(L, kHelp); }

}  // namespace seismpm::lua
