// The console's side of the runtime: entries run with their values shown, completion, Ctrl-C, and
// the script's top-level locals kept for the console (-i).
#include <lua.hpp>

#include <cstdio>
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

// -i: registry keys of the watched chunk and of what was read of its locals (a table by name, and the
// names in the order the script declared them).
constexpr const char* kWatchedChunk = "seismpm.watched_chunk";
constexpr const char* kLocalValues = "seismpm.local_values";
constexpr const char* kLocalNames = "seismpm.local_names";

// Whether the function running at `ar` is the watched chunk.
bool is_watched_chunk(lua_State* L, lua_Debug* ar) {
  if (!lua_getinfo(L, "f", ar)) return false;
  lua_pushstring(L, kWatchedChunk);
  lua_rawget(L, LUA_REGISTRYINDEX);
  const bool same = lua_type(L, -1) == LUA_TFUNCTION && lua_rawequal(L, -1, -2);
  lua_pop(L, 2);
  return same;
}

// Reads the locals active at `ar` into the registry: a later local of the same name shadows an earlier
// one; Lua's own temporaries ("(for state)") are left out, and so are locals that hold nil.
void read_locals(lua_State* L, lua_Debug* ar) {
  lua_newtable(L);
  const int values = lua_gettop(L);
  lua_newtable(L);
  const int names = values + 1;
  for (int i = 1;; ++i) {
    const char* name = lua_getlocal(L, ar, i);
    if (!name) break;
    if (name[0] == '(') {
      lua_pop(L, 1);
      continue;
    }
    lua_setfield(L, values, name);
    if (lua_getfield(L, names, name) == LUA_TNIL) {  // names[name] = true marks a name listed already
      lua_pushstring(L, name);
      lua_rawseti(L, names, static_cast<lua_Integer>(lua_rawlen(L, names)) + 1);
      lua_pushboolean(L, 1);
      lua_setfield(L, names, name);
    }
    lua_pop(L, 1);
  }
  lua_setfield(L, LUA_REGISTRYINDEX, kLocalNames);
  lua_setfield(L, LUA_REGISTRYINDEX, kLocalValues);
}

// The return hook while a script runs under -i: reads the locals when the watched chunk returns (the
// outermost function of the thread: a cheap test first).
void locals_hook(lua_State* L, lua_Debug* ar) {
  lua_Debug caller;
  if (ar->event != LUA_HOOKRET || lua_getstack(L, 1, &caller)) return;
  if (is_watched_chunk(L, ar)) read_locals(L, ar);
}

}  // namespace

void Runtime::watch_locals() {
  lua_pushvalue(L_, -1);
  lua_setfield(L_, LUA_REGISTRYINDEX, kWatchedChunk);
  for (const char* key : {kLocalValues, kLocalNames}) {
    lua_pushnil(L_);
    lua_setfield(L_, LUA_REGISTRYINDEX, key);
  }
  lua_sethook(L_, locals_hook, LUA_MASKRET, 0);
}

int Runtime::traceback_keeping_locals(lua_State* L) {
  lua_Debug ar;
  for (int level = 0; lua_getstack(L, level, &ar); ++level) {
    if (is_watched_chunk(L, &ar)) {
      read_locals(L, &ar);
      break;
    }
  }
  return traceback(L);
}

void Runtime::keep_locals(bool completed) {
  const bool hook_replaced = lua_gethook(L_) != locals_hook;  // by Ctrl-C (an error follows) or the script
  if (!hook_replaced) lua_sethook(L_, nullptr, 0, 0);
  const int top = lua_gettop(L_);
  lua_pushnil(L_);
  lua_setfield(L_, LUA_REGISTRYINDEX, kWatchedChunk);
  lua_getfield(L_, LUA_REGISTRYINDEX, kLocalValues);
  lua_getfield(L_, LUA_REGISTRYINDEX, kLocalNames);
  if (!lua_istable(L_, -1)) {
    lua_settop(L_, top);
    std::printf("the script's locals could not be read (%s): only its globals are at the prompt\n",
                hook_replaced ? "it set a debug hook of its own" : "it did not end in its main chunk");
    std::fflush(stdout);
    return;
  }
  std::string kept, clashing;
  lua_rawgeti(L_, LUA_REGISTRYINDEX, LUA_RIDX_GLOBALS);  // raw: a script may have set a metatable on _G
  const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L_, -2));
  for (lua_Integer i = 1; i <= n; ++i) {
    lua_rawgeti(L_, -2, i);
    const std::string name = lua_tostring(L_, -1);
    lua_getfield(L_, -4, name.c_str());  // its value
    lua_pushvalue(L_, -2);
    lua_rawget(L_, -4);  // the global of that name
    if (lua_isnil(L_, -2)) {
      // nil when the script left it so
    } else if (lua_isnil(L_, -1) || lua_rawequal(L_, -1, -2)) {
      lua_pushvalue(L_, -3);
      lua_pushvalue(L_, -3);
      lua_rawset(L_, -6);
      kept += (kept.empty() ? "" : ", ") + name;
    } else {
      clashing += (clashing.empty() ? "" : ", ") + name;
    }
    lua_pop(L_, 3);
  }
  lua_settop(L_, top);
  for (const char* key : {kLocalValues, kLocalNames}) {
    lua_pushnil(L_);
    lua_setfield(L_, LUA_REGISTRYINDEX, key);
  }
  const char* when = completed ? "" : " (those defined before the error)";
  if (!kept.empty()) std::printf("locals kept for the console%s: %s\n", when, kept.c_str());
  if (!clashing.empty())
    std::printf("locals not kept, a global of the same name holds something else: %s\n", clashing.c_str());
  std::fflush(stdout);
}

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
