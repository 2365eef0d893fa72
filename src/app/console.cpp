#include "console.hpp"

#include <readline/history.h>
#include <readline/readline.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

namespace seismpm {

namespace {

lua_State* g_state = nullptr;
lua::Session* g_session = nullptr;

void stop_hook(lua_State* L, lua_Debug*) {
  lua_sethook(L, nullptr, 0, 0);
  luaL_error(L, "interrupted (Ctrl-C)");
}

void on_interrupt(int) {
  if (g_session) g_session->interrupted = true;
  // As lua.c does: a hook stops Lua code at its next instruction.
  if (g_state) lua_sethook(g_state, stop_hook, LUA_MASKCALL | LUA_MASKRET | LUA_MASKCOUNT, 1);
}

// Completion through the Lua library's mpm._complete(text).
char** complete(const char* text, int, int) {
  rl_attempted_completion_over = 1;
  rl_completion_append_character = '\0';  // "m:run" then "{": no space in between (reset by readline each time)
  static std::vector<std::string> matches;
  matches.clear();
  lua_State* L = g_state;
  lua_getglobal(L, "mpm");
  if (lua_istable(L, -1) && lua_getfield(L, -1, "_complete") == LUA_TFUNCTION) {
    lua_pushstring(L, text);
    if (lua_pcall(L, 1, 1, 0) == LUA_OK && lua_istable(L, -1)) {
      const lua_Integer n = luaL_len(L, -1);
      for (lua_Integer i = 1; i <= n; ++i) {
        lua_rawgeti(L, -1, i);
        if (const char* s = lua_tostring(L, -1)) matches.emplace_back(s);
        lua_pop(L, 1);
      }
    }
  }
  lua_settop(L, 0);
  if (matches.empty()) return nullptr;
  return rl_completion_matches(text, [](const char*, int state) -> char* {
    return state < static_cast<int>(matches.size()) ? strdup(matches[state].c_str()) : nullptr;
  });
}

std::string history_file() {
  const char* home = std::getenv("HOME");
  return home ? std::string(home) + "/.seismpm_history" : std::string();
}

bool read_line(bool terminal, const char* prompt, std::string& line) {
  if (terminal) {
    char* raw = readline(prompt);
    if (!raw) return false;
    line = raw;
    std::free(raw);
    return true;
  }
  return static_cast<bool>(std::getline(std::cin, line));
}

// A chunk that failed to compile only because it ended early continues on the next line.
bool incomplete(lua_State* L, int status) {
  if (status != LUA_ERRSYNTAX) return false;
  const char* msg = lua_tostring(L, -1);
  const std::size_t n = msg ? std::strlen(msg) : 0;
  return n >= 5 && std::strcmp(msg + n - 5, "<eof>") == 0;
}

void print_results(lua_State* L, int base) {
  const int n = lua_gettop(L) - base;
  if (n <= 0) return;
  std::string out;
  lua_getglobal(L, "mpm");
  lua_getfield(L, -1, "_show");
  const int show = lua_gettop(L);
  for (int i = 1; i <= n; ++i) {
    lua_pushvalue(L, show);
    lua_pushvalue(L, base + i);
    const char* s = lua_pcall(L, 1, 1, 0) == LUA_OK ? lua_tostring(L, -1) : nullptr;
    out += (i > 1 ? "\t" : "") + std::string(s ? s : luaL_tolstring(L, base + i, nullptr));
    lua_settop(L, show);
  }
  std::printf("%s\n", out.c_str());
  std::fflush(stdout);
}

}  // namespace

void install_interrupt_handler(lua::Runtime& runtime, lua::Session& session) {
  g_state = runtime.state();
  g_session = &session;
  struct sigaction sa{};
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
}

void clear_interrupt(lua::Runtime& runtime, lua::Session& session) {
  lua_sethook(runtime.state(), nullptr, 0, 0);
  session.interrupted = false;
}

int run_console(lua::Runtime& runtime) {
  lua_State* L = runtime.state();
  const bool terminal = isatty(STDIN_FILENO);
  const std::string hist = history_file();
  if (terminal) {
    rl_readline_name = "seismpm";
    rl_attempted_completion_function = complete;
    rl_basic_word_break_characters = const_cast<char*>(" \t\n\"'()[]{},;=+-*/<>~#");
    // append_history needs the file to exist.
    if (!hist.empty() && read_history(hist.c_str()) != 0) write_history(hist.c_str());
    std::printf("seismpm %s: Lua %s console. help() lists the API; Ctrl-D quits.\n", lua::kVersion,
                LUA_VERSION_MAJOR "." LUA_VERSION_MINOR);
  }
  std::string chunk, line;
  while (read_line(terminal, chunk.empty() ? "seismpm> " : ">> ", line)) {
    chunk += (chunk.empty() ? "" : "\n") + line;
    if (chunk.find_first_not_of(" \t") == std::string::npos) {
      chunk.clear();
      continue;
    }
    lua_settop(L, 0);
    // An expression prints its value: try "return <chunk>" first.
    const std::string expr = "return " + chunk;
    int status = luaL_loadbuffer(L, expr.data(), expr.size(), "=stdin");
    if (status != LUA_OK) {
      lua_pop(L, 1);
      status = luaL_loadbuffer(L, chunk.data(), chunk.size(), "=stdin");
      if (incomplete(L, status)) {
        lua_pop(L, 1);
        continue;
      }
    }
    if (terminal) {
      add_history(chunk.c_str());
      if (!hist.empty()) append_history(1, hist.c_str());
    }
    chunk.clear();
    if (status == LUA_OK) {
      clear_interrupt(runtime, *g_session);
      status = runtime.call(0, LUA_MULTRET);
    }
    if (status == LUA_OK) {
      print_results(L, 0);
    } else {
      std::fprintf(stderr, "%s\n", lua_tostring(L, -1) ? lua_tostring(L, -1) : "(error)");
      std::fflush(stderr);
    }
    lua_settop(L, 0);
  }
  if (terminal) {
    std::printf("\n");
    if (!hist.empty()) history_truncate_file(hist.c_str(), 1000);
  }
  return 0;
}

}  // namespace seismpm
