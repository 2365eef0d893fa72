#include "runtime.hpp"

#include <lua.hpp>

#include <cstdio>
#include <filesystem>

#include "api_docs.hpp"
#include "binding.hpp"
#include "input_checks.hpp"
#include "lua_function.hpp"
#include "objects.hpp"
#include "sandbox.hpp"

namespace seismpm::lua {

namespace {

constexpr const char* kSessionKey = "seismpm.session";

// mpm.param(name, default)
int param(lua_State* L) {
  if (lua_type(L, 1) != LUA_TSTRING) throw Error("expects a parameter name (string) and a default");
  const char* name = lua_tostring(L, 1);
  session(L).params_read.insert(name);
  const auto& params = session(L).params;
  const auto it = params.find(name);
  if (it == params.end()) {
    lua_settop(L, 2);
    return 1;
  }
  const std::string& v = it->second;
  switch (lua_type(L, 2)) {
    case LUA_TNUMBER: {
      if (!lua_stringtonumber(L, v.c_str()))
        throw Error(std::string("--set ") + name + "=" + v + ": a number is expected");
      return 1;
    }
    case LUA_TBOOLEAN:
      if (v == "true" || v == "1" || v == "yes") {
        lua_pushboolean(L, 1);
      } else if (v == "false" || v == "0" || v == "no") {
        lua_pushboolean(L, 0);
      } else {
        throw Error(std::string("--set ") + name + "=" + v + ": true or false is expected");
      }
      return 1;
    default:
      lua_pushstring(L, v.c_str());
      return 1;
  }
}

int version(lua_State* L) {
  lua_pushstring(L, kVersion);
  return 1;
}

int out_dir(lua_State* L) {
  const Session& s = session(L);
  if (s.out_dir.empty())
    lua_settop(L, 1);  // the default as given, whatever its type (nil when none)
  else
    lua_pushstring(L, s.output_dir("").c_str());
  if (lua_type(L, -1) == LUA_TSTRING) allow_writes_under(L, lua_tostring(L, -1));  // the script's output goes there
  return 1;
}

const Function kSession[] = {
    {"mpm.param",
     &guarded<param>,
     "mpm.param(name, default)",
     {},
     "A scenario parameter: the value given on the command line with --set name=value, converted to the type of "
     "default (number, boolean or string), or default when not given.",
     "local cell = mpm.param(\"cell\", 0.01)"},
    {"mpm.version", &guarded<version>, "mpm.version()", {}, "The seismpm version as a string.", "print(mpm.version())"},
    {"mpm.out_dir",
     &guarded<out_dir>,
     "mpm.out_dir(default)",
     {},
     "The output directory: the one given with --out, or default. --out replaces such defaults only: m:output "
     "writes into the dir it is given, so a script that honours --out passes dir = mpm.out_dir(...).",
     "local dir = mpm.out_dir(\"out/column\")"},
};

}  // namespace

int Runtime::traceback(lua_State* L) {
  const char* msg = lua_tostring(L, 1);
  if (!msg) {
    if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING) return 1;
    msg = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
  }
  luaL_traceback(L, L, msg, 1);
  return 1;
}

std::string data_path(lua_State* L, const std::string& file) {
  namespace fs = std::filesystem;
  const std::string& dir = session(L).script_dir;
  if (file.empty() || fs::path(file).is_absolute() || fs::exists(file) || dir.empty()) return file;
  const fs::path beside = fs::path(dir) / file;
  return fs::exists(beside) ? beside.string() : file;
}

std::span<const Function> session_functions() { return kSession; }

Session& session(lua_State* L) {
  lua_pushstring(L, kSessionKey);
  lua_rawget(L, LUA_REGISTRYINDEX);
  auto* s = static_cast<Session*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  return *s;
}

Runtime::Runtime(Session& session, const std::vector<std::string>& library_dirs) : session_(session) {
  L_ = luaL_newstate();
  if (!L_) throw std::runtime_error("cannot create a Lua state (out of memory)");
  luaL_openlibs(L_);
  open_state_life(L_);  // first: see lua_function.hpp
  lua_pushlightuserdata(L_, &session_);
  lua_setfield(L_, LUA_REGISTRYINDEX, kSessionKey);
  install_text_only_loading(L_);

  lua_newtable(L_);
  lua_setglobal(L_, "mpm");
  open_model(L_);  // first: it makes the model type that the next three add methods to
  open_model_building(L_);
  open_phases(L_);
  open_output(L_);
  open_body(L_);
  open_probe(L_);
  open_material(L_);
  open_shape(L_);
  open_history(L_);
  open_methods(L_);
  open_plot(L_);
  open_lem(L_);
  open_strength_reduction(L_);
  open_checkpoint(L_);
  open_help(L_);
  open_library_support(L_);
  register_functions(L_, kSession);

  // The Lua library: `require "seismpm"` finds lua/seismpm.lua in the first directory that has it.
  std::string path;
  for (const auto& dir : library_dirs) path += dir + "/?.lua;";
  lua_getglobal(L_, "package");
  lua_getfield(L_, -1, "path");
  path += lua_tostring(L_, -1);
  lua_pop(L_, 1);
  lua_pushstring(L_, path.c_str());
  lua_setfield(L_, -2, "path");
  lua_pop(L_, 1);
  if (!run_string("require 'seismpm'", "=(seismpm library)"))
    std::fprintf(stderr, "seismpm: the Lua library lua/seismpm.lua was not loaded (searched: %s)\n", path.c_str());
  if (session_.sandbox) install_sandbox(L_);  // after the library: it is ours, loaded from the library dirs
}

Runtime::~Runtime() { lua_close(L_); }

const char* Runtime::lua_version() { return LUA_VERSION_MAJOR "." LUA_VERSION_MINOR; }

int Runtime::call(int nargs, int nresults, int (*handler)(lua_State*)) {
  const int base = lua_gettop(L_) - nargs;
  lua_pushcfunction(L_, handler ? handler : traceback);
  lua_insert(L_, base);
  const int status = lua_pcall(L_, nargs, nresults, base);
  lua_remove(L_, base);
  return status;
}

bool Runtime::run_file(const std::string& file, const std::vector<std::string>& args, bool keep_locals) {
  lua_createtable(L_, static_cast<int>(args.size()), 1);
  lua_pushstring(L_, file.c_str());
  lua_rawseti(L_, -2, 0);
  for (std::size_t i = 0; i < args.size(); ++i) {
    lua_pushstring(L_, args[i].c_str());
    lua_rawseti(L_, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_rawgeti(L_, LUA_REGISTRYINDEX, LUA_RIDX_GLOBALS);  // raw: an earlier chunk may have set a metatable on _G
  lua_pushstring(L_, "arg");
  lua_pushvalue(L_, -3);
  lua_rawset(L_, -3);
  lua_pop(L_, 2);
  std::error_code ec;
  session_.script_dir = std::filesystem::absolute(file, ec).parent_path().string();
  const bool loaded = luaL_loadfilex(L_, file.c_str(), "t") == LUA_OK;
  if (loaded && keep_locals) watch_locals();
  const bool ok = loaded && call(0, 0, keep_locals ? traceback_keeping_locals : nullptr) == LUA_OK;
  if (!ok) {
    std::fprintf(stderr, "seismpm: %s\n", lua_tostring(L_, -1));
    std::fflush(stderr);
    lua_pop(L_, 1);
  }
  if (loaded && keep_locals) this->keep_locals(ok);
  if (ok) warn_unread_params(L_);  // after a failure the script may not have reached its parameters
  return ok;
}

bool Runtime::execute(const std::string& code, const std::string& name, std::string& error) {
  if (luaL_loadbufferx(L_, code.data(), code.size(), name.c_str(), "t") != LUA_OK || call(0, 0) != LUA_OK) {
    error = lua_tostring(L_, -1) ? lua_tostring(L_, -1) : "(error object is not a string)";
    lua_pop(L_, 1);
    return false;
  }
  return true;
}

bool Runtime::run_string(const std::string& code, const std::string& name) {
  std::string error;
  if (execute(code, name, error)) return true;
  std::fprintf(stderr, "seismpm: %s\n", error.c_str());
  return false;
}

}  // namespace seismpm::lua
