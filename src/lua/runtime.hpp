// A Lua state with the `mpm` module, the Lua-side library (lua/) and help() loaded, and what the
// console needs of it (completion, Ctrl-C, running an entry), so that nothing outside src/lua uses
// Lua's C API.
#pragma once

#include <string>
#include <vector>

#include "session.hpp"

struct lua_State;

namespace seismpm::lua {

inline constexpr const char* kVersion = "0.1.0";

class Runtime {
 public:
  // `library_dirs`: where lua/seismpm.lua is looked for (next to the binary, the source tree).
  Runtime(Session& session, const std::vector<std::string>& library_dirs);
  ~Runtime();
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;

  lua_State* state() const { return L_; }
  // "5.4"
  static const char* lua_version();

  // Runs a file with `args` as the global `arg`; on error prints "file:line: message" and a
  // traceback to stderr and returns false. `keep_locals` (-i): the script's top-level locals become
  // globals for the console afterwards, those defined before an error when it stops on one; a line
  // on stdout names them.
  bool run_file(const std::string& file, const std::vector<std::string>& args, bool keep_locals = false);
  // Runs a chunk; `name` appears in messages.
  bool run_string(const std::string& code, const std::string& name);
  // Runs a chunk; on failure returns false and leaves the message (with traceback) in `error`.
  bool execute(const std::string& code, const std::string& name, std::string& error);

  // The console's side (runtime_console.cpp).
  enum class Entry { Done, Failed, Incomplete };
  // Runs one console entry: an expression prints its values ("return <entry>" is tried first), a
  // statement runs. Incomplete: the entry ended early (an open block) and runs nothing yet. `output`
  // gets the values shown (tab-separated) or the error with its traceback.
  Entry run_entry(const std::string& entry, std::string& output);
  // Completion candidates for the text before the cursor (mpm._complete of lua/seismpm.lua).
  std::vector<std::string> complete(const std::string& text);
  // Ctrl-C, from a signal handler: a run stops at its next step boundary, Lua code at its next
  // instruction (a hook, as lua.c does).
  void interrupt();
  // Clears a pending Ctrl-C before the next entry runs.
  void clear_interrupt();

 private:
  // Calls the function below `nargs` arguments with a message handler (`handler`, else `traceback`);
  // returns the status.
  int call(int nargs, int nresults, int (*handler)(lua_State*) = nullptr);
  // Message handler: adds a traceback to an error message.
  static int traceback(lua_State* L);
  // -i (runtime_console.cpp): the chunk on top of the stack is watched (a return hook, set from C) so
  // that its top-level locals are read when it returns or, through the message handler below, where an
  // error stops it; keep_locals then copies them into the globals and says which.
  void watch_locals();
  void keep_locals(bool completed);
  static int traceback_keeping_locals(lua_State* L);
  std::string shown(int index);  // a value as the console prints it

  lua_State* L_;
  Session& session_;
};

}  // namespace seismpm::lua
