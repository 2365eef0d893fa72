// A Lua state with the `mpm` module, the Lua-side library (lua/) and help() loaded.
#pragma once

#include <lua.hpp>

#include <string>
#include <vector>

#include "session.hpp"

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

  // Runs a file with `args` as the global `arg`; on error prints "file:line: message" and a
  // traceback to stderr and returns false.
  bool run_file(const std::string& file, const std::vector<std::string>& args);
  // Runs a chunk; `name` appears in messages.
  bool run_string(const std::string& code, const std::string& name);
  // Runs a chunk; on failure returns false and leaves the message (with traceback) in `error`.
  bool execute(const std::string& code, const std::string& name, std::string& error);
  // Compiles and runs a chunk, printing any error; used by the console. Returns the status.
  int call(int nargs, int nresults);

 private:
  lua_State* L_;
  Session& session_;
};

}  // namespace seismpm::lua
