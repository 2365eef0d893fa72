// The console's side of the runtime: entries run with their values shown, completion, Ctrl-C.
#include <lua.hpp>

#include <cstring>

#include "binding.hpp"
#include "runtime.hpp"

namespace seismpm::lua {

namespace {

void stop_hook(lua_State* L, lua_Debug*) {
  lua_sethook(L, nullptr, 0, 0);
  luaL_error(L, "interrupted (Ctrl-C)");  // inside Lua code: the entry's protected call catches it
}

// A chunk that failed to compile only because it ended early continues on the next line.
bool incomplete(lua_State* L, int status) {
  if (status != LUA_ERRSYNTAX) return false;
  const char* msg = lua_tostring(L, -1);
  const std::size_t n = msg ? std::strlen(msg) : 0;
  return n >= 5 && std::strcmp(msg + n - 5, "<eof>") == 0;
}

// Pushes tostring(value at 1) (its __tostring may fail: call it protected).
int to_text(lua_State* L) {
  luaL_tolstring(L, 1, nullptr);
  return 1;
}

// Pushes mpm[name] (raw), or nil.
void push_library_function(lua_State* L, const char* name) {
  if (raw_global(L, "mpm") == LUA_TTABLE) {
    lua_pushstring(L, name);
    lua_rawget(L, -2);
    lua_remove(L, -2);
  }
}

}  // namespace

std::string Runtime::shown(int index) {
  index = lua_absindex(L_, index);
  const int top = lua_gettop(L_);
  push_library_function(L_, "_show");
  lua_pushvalue(L_, index);
  if (lua_pcall(L_, 1, 1, 0) != LUA_OK || lua_type(L_, -1) != LUA_TSTRING) {
    lua_settop(L_, top);
    lua_pushcfunction(L_, to_text);
    lua_pushvalue(L_, index);
    if (lua_pcall(L_, 1, 1, 0) != LUA_OK || lua_type(L_, -1) != LUA_TSTRING) {
      lua_settop(L_, top);
      return "(a value that cannot be shown)";
    }
  }
  std::string text = lua_tostring(L_, -1);
  lua_settop(L_, top);
  return text;
}

Runtime::Entry Runtime::run_entry(const std::string& entry, std::string& output) {
  lua_settop(L_, 0);
  const std::string expr = "return " + entry;
  int status = luaL_loadbufferx(L_, expr.data(), expr.size(), "=stdin", "t");
  if (status != LUA_OK) {
    lua_pop(L_, 1);
    status = luaL_loadbufferx(L_, entry.data(), entry.size(), "=stdin", "t");
    if (incomplete(L_, status)) {
      lua_settop(L_, 0);
      return Entry::Incomplete;
    }
  }
  if (status == LUA_OK) {
    clear_interrupt();
    status = call(0, LUA_MULTRET);
  }
  output.clear();
  if (status != LUA_OK) {
    output = lua_type(L_, -1) == LUA_TSTRING ? lua_tostring(L_, -1) : "(error)";
    lua_settop(L_, 0);
    return Entry::Failed;
  }
  const int n = lua_gettop(L_);
  for (int i = 1; i <= n; ++i) output += (i > 1 ? "\t" : "") + shown(i);
  lua_settop(L_, 0);
  return Entry::Done;
}

std::vector<std::string> Runtime::complete(const std::string& text) {
  std::vector<std::string> matches;
  const int top = lua_gettop(L_);
  push_library_function(L_, "_complete");
  if (lua_type(L_, -1) == LUA_TFUNCTION) {
    lua_pushstring(L_, text.c_str());
    if (lua_pcall(L_, 1, 1, 0) == LUA_OK && lua_istable(L_, -1)) {
      const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L_, -1));
      for (lua_Integer i = 1; i <= n; ++i) {
        if (lua_rawgeti(L_, -1, i) == LUA_TSTRING) matches.emplace_back(lua_tostring(L_, -1));
        lua_pop(L_, 1);
      }
    }
  }
  lua_settop(L_, top);
  return matches;
}

void Runtime::interrupt() {
  session_.interrupted = true;
  lua_sethook(L_, stop_hook, LUA_MASKCALL | LUA_MASKRET | LUA_MASKCOUNT, 1);
}

void Runtime::clear_interrupt() {
  lua_sethook(L_, nullptr, 0, 0);
  session_.interrupted = false;
}

}  // namespace seismpm::lua
