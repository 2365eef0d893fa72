// What Lua code may load and touch. Always: chunks are text, never precompiled bytecode (a bytecode
// file can crash the Lua virtual machine at will), for the main script, the console, load, loadfile,
// dofile and require alike. Under --sandbox (Session::sandbox), for a scenario file someone sent: no
// shell (os.execute, io.popen), no native code (package.loadlib, C modules), no debug library (a
// stand-in keeps debug.traceback and debug.getinfo without functions), and files only where the user
// put them: read under the script's folder, the working directory and the output directories, written
// under the output directories (--out, or a directory the script gives m:output{ dir } or
// mpm.out_dir(default) that lies inside the working directory or --out), never in hidden folders or
// through a symbolic link out of them. The model's own writers (particle files, probes.csv) write
// where m:output says, as without the sandbox.
#pragma once

#include <string>

struct lua_State;

namespace seismpm::lua {

// Replaces load, loadfile, dofile and require's Lua searcher with text-only versions.
void install_text_only_loading(lua_State* L);

// Takes the blocked functions out and puts the checked ones in (Session::sandbox).
void install_sandbox(lua_State* L);

// Under --sandbox: throws Error unless the script may read (write) `file`; `what` names it in the
// message ("key 'file'", or "" for nothing). Does nothing without the sandbox.
void check_readable(lua_State* L, const std::string& file, const char* what);
void check_writable(lua_State* L, const std::string& file, const char* what);

// Under --sandbox: `dir` (m:output{ dir }, mpm.out_dir's answer) becomes writable when it lies inside
// the working directory or the --out directory, outside hidden folders; elsewhere it stays closed to
// the script's own files.
void allow_writes_under(lua_State* L, const std::string& dir);

// Under --sandbox: throws Error naming `what` unless `dir` may be an output directory (inside the working
// directory, outside hidden folders, or inside the --out directory): the run's own files (particle
// files, tables, checkpoints) are written there. Does nothing without the sandbox.
void check_output_dir(lua_State* L, const std::string& dir, const char* what);

}  // namespace seismpm::lua
