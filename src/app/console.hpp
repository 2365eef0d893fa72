// The interactive console: prompt, history, multi-line input, expressions printed, completion. It
// reaches Lua only through the runtime (src/lua).
#pragma once

#include "lua/runtime.hpp"

namespace seismpm {

// Reads entries from standard input until end of file; with a terminal through readline (history in
// ~/.seismpm_history, tab completion), otherwise line by line. Returns the exit status.
int run_console(lua::Runtime& runtime);

// Ctrl-C: stops a run at the next step boundary and interrupts running Lua code.
void install_interrupt_handler(lua::Runtime& runtime);

}  // namespace seismpm
