#include "console.hpp"

#include <poll.h>
#include <readline/history.h>
#include <readline/readline.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

namespace seismpm {

namespace {

lua::Runtime* g_runtime = nullptr;
// Ctrl-C while the console waits for a line: the line and the entry pending at ">> " are dropped.
volatile std::sig_atomic_t g_reading = 0, g_interrupted_at_prompt = 0;

void on_interrupt(int) {
  if (g_reading) g_interrupted_at_prompt = 1;
  if (g_runtime) g_runtime->interrupt();
}

// readline's key reader: readline's own, except that Ctrl-C at the prompt ends the line (as Return
// would; the console drops it). readline's rl_getc would go on reading after the signal, with the text
// typed so far still there. Waiting here, outside rl_getc, sees the signal: readline caught it (it shows
// ^C and passes it on to on_interrupt once this returns).
// The wait wakes up every 0.1 s: a Ctrl-C that reached on_interrupt before this wait began (while
// readline set up the prompt) interrupts no poll, and would otherwise leave the console waiting for a
// key (seen once in 315 tests under load: "^C" shown, no fresh prompt).
int read_key(FILE* in) {
  for (;;) {
    rl_check_signals();  // any other signal caught meanwhile (a resized window)
    if (g_interrupted_at_prompt) return '\n';
    pollfd p{fileno(in), POLLIN, 0};
    const int ready = poll(&p, 1, 100);
    if (ready > 0 || (ready < 0 && errno != EINTR)) return rl_getc(in);
    if (ready < 0 && rl_pending_signal() == SIGINT) {
      g_interrupted_at_prompt = 1;
      return '\n';
    }
  }
}

// Completion through the runtime (the Lua library's mpm._complete).
char** complete(const char* text, int, int) {
  rl_attempted_completion_over = 1;
  rl_completion_append_character = '\0';  // "m:run" then "{": no space in between (reset by readline each time)
  static std::vector<std::string> matches;
  matches = g_runtime ? g_runtime->complete(text) : std::vector<std::string>{};
  if (matches.empty()) return nullptr;
  return rl_completion_matches(text, [](const char*, int state) -> char* {
    return state < static_cast<int>(matches.size()) ? strdup(matches[state].c_str()) : nullptr;
  });
}

std::string history_file() {
  const char* home = std::getenv("HOME");
  return home ? std::string(home) + "/.seismpm_history" : std::string();
}

// Reads a line; false at the end of the input. `interrupted`: Ctrl-C came instead of the line's end.
bool read_line(bool terminal, const char* prompt, std::string& line, bool& interrupted) {
  g_interrupted_at_prompt = 0;
  g_reading = 1;
  bool got;
  if (terminal) {
    char* raw = readline(prompt);
    got = raw != nullptr;
    line = raw ? raw : "";
    std::free(raw);
  } else {
    got = static_cast<bool>(std::getline(std::cin, line));
    if (!got && g_interrupted_at_prompt && !std::feof(stdin)) {  // a read cut short by the signal
      std::cin.clear();
      std::clearerr(stdin);
      got = true;
    }
  }
  g_reading = 0;
  interrupted = g_interrupted_at_prompt != 0;
  return got || interrupted;
}

}  // namespace

void install_interrupt_handler(lua::Runtime& runtime) {
  g_runtime = &runtime;
  struct sigaction sa {};
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
}

int run_console(lua::Runtime& runtime) {
  runtime.clear_interrupt();  // a Ctrl-C that stopped the script (-i) must not stop completion
  const bool terminal = isatty(STDIN_FILENO);
  const std::string hist = history_file();
  if (terminal) {
    rl_readline_name = "seismpm";
    rl_getc_function = read_key;
    rl_attempted_completion_function = complete;
    rl_basic_word_break_characters = const_cast<char*>(" \t\n\"'()[]{},;=+-*/<>~#");
    // append_history needs the file to exist.
    if (!hist.empty() && read_history(hist.c_str()) != 0) write_history(hist.c_str());
    std::printf("seismpm %s: Lua %s console. help() lists the API; Ctrl-D quits.\n", lua::kVersion,
                lua::Runtime::lua_version());
  }
  std::string chunk, line, output;
  bool interrupted = false;
  while (read_line(terminal, chunk.empty() ? "seismpm> " : ">> ", line, interrupted)) {
    if (interrupted) {  // a fresh entry: nothing typed before Ctrl-C runs
      runtime.clear_interrupt();
      if (!chunk.empty() && !terminal) std::fprintf(stderr, "(Ctrl-C: the unfinished entry was dropped)\n");
      chunk.clear();
      continue;
    }
    chunk += (chunk.empty() ? "" : "\n") + line;
    if (chunk.find_first_not_of(" \t") == std::string::npos) {
      chunk.clear();
      continue;
    }
    const auto result = runtime.run_entry(chunk, output);
    if (result == lua::Runtime::Entry::Incomplete) continue;
    if (terminal) {
      add_history(chunk.c_str());
      if (!hist.empty()) append_history(1, hist.c_str());
    }
    chunk.clear();
    if (result == lua::Runtime::Entry::Failed) {
      std::fprintf(stderr, "%s\n", output.c_str());
      std::fflush(stderr);
    } else if (!output.empty()) {
      std::printf("%s\n", output.c_str());
      std::fflush(stdout);
    }
  }
  if (terminal) {
    std::printf("\n");
    if (!hist.empty()) history_truncate_file(hist.c_str(), 1000);
  }
  return 0;
}

}  // namespace seismpm
