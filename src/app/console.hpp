// The interactive console: prompt, history, multi-line input, expressions printed, completion.
#pragma once

#include "lua/runtime.hpp"

namespace seismpm {

// Reads chunks from standard input until end of file; with a terminal through readline (history in
// ~/.seismpm_history, tab completion), otherwise line by line. Returns the exit status.
int run_console(lua::Runtime& runtime);

// Ctrl-C: stops a run at the next step boundary and interrupts running Lua code.
void install_interrupt_handler(lua::Runtime& runtime, lua::Session& session);
// Clears a pending Ctrl-C before the next chunk runs.
void clear_interrupt(lua::Runtime& runtime, lua::Session& session);

}  // namespace seismpm
