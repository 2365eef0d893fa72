#include "sandbox.hpp"

#include <lua.hpp>

#include <cerrno>
#include <filesystem>
#include <optional>
#include <vector>

#include "binding.hpp"
#include "session.hpp"

namespace seismpm::lua {

namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------- paths

enum class Access { Read, Write };

constexpr const char* kSandboxedKey = "seismpm.sandboxed";  // registry: true once install_sandbox ran

// Whether the sandbox is on: the checks start with install_sandbox, after the library has loaded.
bool sandboxed(lua_State* L) {
  lua_getfield(L, LUA_REGISTRYINDEX, kSandboxedKey);
  const bool on = lua_toboolean(L, -1);
  lua_pop(L, 1);
  return on;
}

// The canonical path of an existing file; for writing, also that of a new file in an existing
// folder (its folder canonical, then its name). nullopt when it resolves to neither, or when it is a
// link that leads nowhere (writing through it would create its target anywhere).
std::optional<fs::path> resolved(const std::string& file, Access access) {
  std::error_code ec;
  const fs::path p = fs::absolute(file, ec);
  if (ec || file.empty()) return std::nullopt;
  if (fs::path c = fs::canonical(p, ec); !ec) return c;
  if (access == Access::Read || fs::symlink_status(p, ec).type() != fs::file_type::not_found) return std::nullopt;
  const fs::path name = p.filename();
  if (name.empty() || name == "." || name == "..") return std::nullopt;
  const fs::path parent = fs::canonical(p.parent_path(), ec);
  if (ec) return std::nullopt;
  return parent / name;
}

// A folder as the policy compares it: its existing part canonical (links resolved), the rest as written.
std::optional<fs::path> root_path(const std::string& dir) {
  std::error_code ec;
  if (dir.empty()) return std::nullopt;
  const fs::path p = fs::weakly_canonical(fs::absolute(dir, ec), ec);
  if (ec) return std::nullopt;
  return p.filename().empty() ? p.parent_path() : p;  // no trailing separator
}

// Whether `p` lies inside `root` (or is it) with no hidden folder or file below it (".ssh", ".bashrc").
bool inside(const fs::path& p, const fs::path& root, bool strictly = false) {
  auto q = p.begin();
  for (auto r = root.begin(); r != root.end(); ++r, ++q)
    if (q == p.end() || *q != *r) return false;
  if (strictly && q == p.end()) return false;
  for (; q != p.end(); ++q)
    if (!q->empty() && q->string()[0] == '.') return false;
  return true;
}

std::vector<fs::path> write_roots(const Session& s) {
  std::vector<fs::path> roots;
  if (auto out = root_path(s.out_dir)) roots.push_back(*out);
  for (const auto& d : s.writable_dirs)
    if (auto r = root_path(d)) roots.push_back(*r);
  return roots;
}

std::vector<fs::path> read_roots(const Session& s) {
  std::vector<fs::path> roots = write_roots(s);
  if (auto dir = root_path(s.script_dir)) roots.push_back(*dir);
  std::error_code ec;
  if (auto cwd = root_path(fs::current_path(ec).string()); cwd && !ec) roots.push_back(*cwd);
  return roots;
}

// "" when the sandboxed script may read (write) `file`, else why not, naming `function` ("io.open",
// "key 'file'"; "" names nothing).
std::string refusal(const Session& s, const std::string& file, Access access, const char* function) {
  const auto p = resolved(file, access);
  if (p)
    for (const auto& root : access == Access::Read ? read_roots(s) : write_roots(s))
      if (inside(*p, root)) return "";
  const std::string quoted = (*function ? std::string(function) + ": '" : std::string("'")) + file + "'";
  if (access == Access::Read)
    return quoted + (p ? " is outside what a script may read under --sandbox (its folder, the working directory, "
                         "the output directory; no hidden files)"
                       : ": no such file (or a link out of the folders a script may read under --sandbox)");
  return quoted +
         " is outside what a script may write under --sandbox: the output directory (--out DIR, or an "
         "m:output{ dir } inside the working directory; no hidden folders), in an existing folder";
}

// ---------------------------------------------------------------- the functions that replace Lua's

// Pushes why the call may not touch the file named by argument `index` and returns true, or returns
// false (also when the argument is no file name: the original function reports that). No C++ object
// outlives it: the caller may raise the message.
bool push_refusal(lua_State* L, int index, Access access, const char* function) {
  if (!lua_isstring(L, index)) return false;
  std::string why;
  try {
    why = refusal(session(L), lua_tostring(L, index), access, function);
  } catch (const std::exception& e) {
    why = std::string(function) + ": " + e.what();
  }
  if (why.empty()) return false;
  lua_pushstring(L, why.c_str());
  return true;
}

// Calls the original function (upvalue 1) with the call's arguments and returns what it returns.
int call_original(lua_State* L) {
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

// A failure as Lua's file functions report one: nil, the message (on top), EACCES.
int fail(lua_State* L) {
  lua_pushnil(L);
  lua_insert(L, -2);
  lua_pushinteger(L, EACCES);
  return 3;
}

// The name a wrapper was made for (upvalue 2), for its messages.
const char* own_name(lua_State* L) {
  const char* name = lua_tostring(L, lua_upvalueindex(2));
  return name ? name : "?";
}

bool writes(const char* mode) {
  for (const char* c = mode; *c; ++c)
    if (*c == 'w' || *c == 'a' || *c == '+') return true;
  return false;
}

// io.open(file, mode): reads and writes checked; a refusal fails as a missing file does (nil, message).
int sandboxed_open(lua_State* L) {
  const char* mode = lua_type(L, 2) == LUA_TSTRING ? lua_tostring(L, 2) : "r";
  if (push_refusal(L, 1, writes(mode) ? Access::Write : Access::Read, "io.open")) return fail(L);
  return call_original(L);
}

// io.lines(file, ...), io.input(file), dofile's check: a refusal raises.
int sandboxed_read_or_raise(lua_State* L) {
  if (push_refusal(L, 1, Access::Read, own_name(L))) return lua_error(L);
  return call_original(L);
}

// io.output(file): raises when the file may not be written.
int sandboxed_write_or_raise(lua_State* L) {
  if (push_refusal(L, 1, Access::Write, own_name(L))) return lua_error(L);
  return call_original(L);
}

// os.remove(file): a write.
int sandboxed_remove(lua_State* L) {
  if (push_refusal(L, 1, Access::Write, "os.remove")) return fail(L);
  return call_original(L);
}

// os.rename(from, to): both ends are writes.
int sandboxed_rename(lua_State* L) {
  if (push_refusal(L, 1, Access::Write, "os.rename") || push_refusal(L, 2, Access::Write, "os.rename")) return fail(L);
  return call_original(L);
}

// os.exit(code): exits as asked, but closes the Lua state first (as os.exit(code, true) does), so that
// finalizers run and files are closed.
int sandboxed_exit(lua_State* L) {
  lua_settop(L, 1);
  lua_pushboolean(L, 1);
  return call_original(L);
}

// A function taken out: raises, naming it and why (upvalue 1).
int blocked(lua_State* L) {
  return luaL_error(L, "%s is not available under --sandbox", lua_tostring(L, lua_upvalueindex(1)));
}

// The stand-in debug table's missing functions: reading one raises, naming it.
int blocked_debug_field(lua_State* L) {
  const char* key = lua_tostring(L, 2);
  return luaL_error(L, "debug.%s is not available under --sandbox (only debug.traceback and debug.getinfo)",
                    key ? key : "?");
}

// debug.getinfo([thread,] f [, what]) without the options that hand out functions or their lines
// ("f", "L"): what scripts use it for (their own file name, a line) stays.
int sandboxed_getinfo(lua_State* L) {
  const bool of_thread = lua_type(L, 1) == LUA_TTHREAD;
  const int what = of_thread ? 3 : 2;
  int is_level = 0;
  const lua_Integer level = of_thread ? 0 : lua_tointegerx(L, 1, &is_level);
  if (is_level && lua_type(L, 1) == LUA_TNUMBER) {  // a level of this thread: this function is one more
    lua_pushinteger(L, level + 1);
    lua_replace(L, 1);
  }
  if (lua_isnoneornil(L, what)) {
    lua_settop(L, what);
    lua_pushstring(L, "Slnrtu");
    lua_replace(L, what);
  } else if (lua_type(L, what) == LUA_TSTRING) {
    const char* options = lua_tostring(L, what);
    for (const char* c = options; *c; ++c)
      if (*c == 'f' || *c == 'L' || *c == '>')
        return luaL_error(L, "debug.getinfo: option '%c' is not available under --sandbox", *c);
  }
  return call_original(L);
}

// ---------------------------------------------------------------- text-only loading

// Sets argument `index` (the mode of load, loadfile) to "t", keeping the arguments after it as they are.
void force_text_mode(lua_State* L, int index) {
  if (lua_gettop(L) < index) lua_settop(L, index);
  lua_pushstring(L, "t");
  lua_replace(L, index);
}

// load(chunk, name, mode, env) in text mode.
int text_load(lua_State* L) {
  force_text_mode(L, 3);
  return call_original(L);
}

// loadfile(file, mode, env) in text mode (checked under --sandbox: nil and the message when refused).
int text_loadfile(lua_State* L) {
  if (sandboxed(L) && push_refusal(L, 1, Access::Read, "loadfile")) {
    lua_pushnil(L);
    lua_insert(L, -2);
    return 2;  // nil and the message, as loadfile fails
  }
  force_text_mode(L, 2);
  return call_original(L);
}

int dofile_continuation(lua_State* L, int, lua_KContext) { return lua_gettop(L) - 1; }

// dofile(file) in text mode (checked under --sandbox).
int text_dofile(lua_State* L) {
  if (sandboxed(L) && push_refusal(L, 1, Access::Read, "dofile")) return lua_error(L);
  const char* file = luaL_optstring(L, 1, nullptr);
  lua_settop(L, 1);
  if (luaL_loadfilex(L, file, "t") != LUA_OK) return lua_error(L);
  lua_callk(L, 0, LUA_MULTRET, 0, dofile_continuation);
  return dofile_continuation(L, 0, 0);
}

// require's searcher of Lua files along package.path (upvalue 1: the package table), in text mode;
// under --sandbox a file outside the readable folders is not found.
int text_searcher(lua_State* L) {
  const char* name = luaL_checkstring(L, 1);
  lua_getfield(L, lua_upvalueindex(1), "searchpath");
  lua_pushvalue(L, 1);
  if (lua_getfield(L, lua_upvalueindex(1), "path") != LUA_TSTRING)
    return luaL_error(L, "'package.path' must be a string");
  lua_call(L, 2, 2);
  if (lua_isnil(L, -2)) return 1;  // the message: not found along the path
  lua_pop(L, 1);
  const int file = lua_gettop(L);
  if (sandboxed(L) && push_refusal(L, file, Access::Read, "require")) {
    lua_pushstring(L, "\n\t");
    lua_insert(L, -2);
    lua_concat(L, 2);
    return 1;
  }
  if (luaL_loadfilex(L, lua_tostring(L, file), "t") != LUA_OK)
    return luaL_error(L, "error loading module '%s' from file '%s':\n\t%s", name, lua_tostring(L, file),
                      lua_tostring(L, -1));
  lua_pushvalue(L, file);
  return 2;
}

// ---------------------------------------------------------------- installing

// Replaces table[key] (table at the top) by `f` with the original as upvalue 1 and `name` as upvalue 2.
void wrap(lua_State* L, const char* key, lua_CFunction f, const char* name) {
  lua_getfield(L, -1, key);
  lua_pushstring(L, name);
  lua_pushcclosure(L, f, 2);
  lua_setfield(L, -2, key);
}

// Replaces table[key] (table at the top) by a function that raises "name is not available ...".
void block(lua_State* L, const char* key, const char* name) {
  lua_pushstring(L, name);
  lua_pushcclosure(L, blocked, 1);
  lua_setfield(L, -2, key);
}

void push_library(lua_State* L, const char* name) {
  lua_rawgeti(L, LUA_REGISTRYINDEX, LUA_RIDX_GLOBALS);
  lua_getfield(L, -1, name);
  lua_remove(L, -2);
}

// The debug table scripts see: traceback and a getinfo without functions; anything else raises.
void install_debug_stand_in(lua_State* L) {
  push_library(L, "debug");
  const int original = lua_gettop(L);
  lua_createtable(L, 0, 2);
  lua_getfield(L, original, "traceback");
  lua_setfield(L, -2, "traceback");
  lua_getfield(L, original, "getinfo");
  lua_pushstring(L, "debug.getinfo");
  lua_pushcclosure(L, sandboxed_getinfo, 2);
  lua_setfield(L, -2, "getinfo");
  lua_createtable(L, 0, 2);
  lua_pushcfunction(L, blocked_debug_field);
  lua_setfield(L, -2, "__index");
  lua_pushboolean(L, 0);
  lua_setfield(L, -2, "__metatable");  // the metatable stays as it is
  lua_setmetatable(L, -2);
  lua_pushvalue(L, -1);
  lua_setglobal(L, "debug");
  lua_getfield(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);
  lua_insert(L, -2);
  lua_setfield(L, -2, "debug");
  lua_settop(L, original - 1);
}

}  // namespace

void install_text_only_loading(lua_State* L) {
  lua_rawgeti(L, LUA_REGISTRYINDEX, LUA_RIDX_GLOBALS);
  wrap(L, "load", text_load, "load");
  wrap(L, "loadfile", text_loadfile, "loadfile");
  lua_pushcfunction(L, text_dofile);
  lua_setfield(L, -2, "dofile");
  lua_getfield(L, -1, "package");
  lua_getfield(L, -1, "searchers");
  lua_pushvalue(L, -2);
  lua_pushcclosure(L, text_searcher, 1);
  lua_rawseti(L, -2, 2);  // 1: package.preload, 2: Lua files, 3 and 4: C libraries
  lua_pop(L, 3);
}

void install_sandbox(lua_State* L) {
  push_library(L, "os");
  block(L, "execute", "os.execute (shell commands)");
  block(L, "tmpname", "os.tmpname (write into the output directory instead)");
  wrap(L, "remove", sandboxed_remove, "os.remove");
  wrap(L, "rename", sandboxed_rename, "os.rename");
  wrap(L, "exit", sandboxed_exit, "os.exit");
  lua_pop(L, 1);

  push_library(L, "io");
  block(L, "popen", "io.popen (shell commands)");
  wrap(L, "open", sandboxed_open, "io.open");
  wrap(L, "lines", sandboxed_read_or_raise, "io.lines");
  wrap(L, "input", sandboxed_read_or_raise, "io.input");
  wrap(L, "output", sandboxed_write_or_raise, "io.output");
  lua_pop(L, 1);

  push_library(L, "package");
  block(L, "loadlib", "package.loadlib (native code)");
  lua_getfield(L, -1, "searchers");
  for (lua_Integer k = static_cast<lua_Integer>(lua_rawlen(L, -1)); k > 2; --k) {  // the C searchers
    lua_pushnil(L);
    lua_rawseti(L, -2, k);
  }
  lua_pop(L, 2);

  install_debug_stand_in(L);
  lua_pushboolean(L, 1);
  lua_setfield(L, LUA_REGISTRYINDEX, kSandboxedKey);
}

void check_readable(lua_State* L, const std::string& file, const char* what) {
  if (!sandboxed(L)) return;
  if (std::string why = refusal(session(L), file, Access::Read, what); !why.empty()) throw Error(why);
}

void check_writable(lua_State* L, const std::string& file, const char* what) {
  if (!sandboxed(L)) return;
  if (std::string why = refusal(session(L), file, Access::Write, what); !why.empty()) throw Error(why);
}

namespace {
// Where a sandboxed run may put an output directory: inside the working directory (outside hidden
// folders) or inside the --out directory.
bool output_dir_allowed(const Session& s, const std::optional<fs::path>& d) {
  if (!d) return false;
  std::error_code ec;
  const auto cwd = root_path(fs::current_path(ec).string());
  const auto out = root_path(s.out_dir);
  return (cwd && inside(*d, *cwd, true)) || (out && inside(*d, *out));
}
}  // namespace

void check_output_dir(lua_State* L, const std::string& dir, const char* what) {
  if (!sandboxed(L)) return;
  if (!output_dir_allowed(session(L), root_path(dir)))
    throw Error(std::string(what) + ": the output directory '" + dir +
                "' is outside the working directory and the --out directory: under --sandbox a run writes only "
                "there");
}

void allow_writes_under(lua_State* L, const std::string& dir) {
  if (!sandboxed(L)) return;
  Session& s = session(L);
  const auto d = root_path(dir);
  if (output_dir_allowed(s, d)) s.writable_dirs.push_back(d->string());
}

}  // namespace seismpm::lua
