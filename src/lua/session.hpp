// Settings of one Lua session that the command line gives (threads, --set parameters, --out,
// --quiet, --sandbox) and the Ctrl-C flag that stops a run at the next step boundary.
#pragma once

#include <atomic>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "io/progress.hpp"

struct lua_State;

namespace seismpm::lua {

struct Session {
  std::map<std::string, std::string> params;  // --set name=value
  std::set<std::string> params_read;          // the names mpm.param was asked for (a --set of another is a typo)
  // Input warnings (input_checks.hpp) given so far, as printed: a likely mistake that still runs.
  std::vector<std::string> warnings;
  // --out. The one rule for it: it replaces a DEFAULT output directory, never one a script names.
  // mpm.out_dir(default) and m:output without dir both ask output_dir(); m:output{ dir } writes into dir.
  std::string out_dir;
  std::string output_dir(const std::string& fallback) const { return out_dir.empty() ? fallback : out_dir; }
  Progress::Mode progress = Progress::Mode::Log;
  std::atomic<bool> interrupted{false};
  std::string script_dir;  // directory of the script being run, for its data files
  // --sandbox (sandbox.hpp): no shell, native code or debug library; the script's own files only in the
  // folders the user gave it. writable_dirs: the output directories the script named that qualify.
  bool sandbox = false;
  std::vector<std::string> writable_dirs;
};

// A data file named in a script: as given when it exists (or is absolute), otherwise next to the script.
std::string data_path(lua_State* L, const std::string& file);

// The session stored in the state's registry by open_seismpm.
Session& session(lua_State* L);

}  // namespace seismpm::lua
