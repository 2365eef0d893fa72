// seismpm: the command line. Runs scenario scripts, chunks, and the interactive console.
#include <omp.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "console.hpp"
#include "io/probe_plot.hpp"
#include "io/progress.hpp"
#include "lua/api_docs.hpp"
#include "lua/runtime.hpp"
#include "thread_waiting.hpp"

#ifndef SEISMPM_SOURCE_LUA_DIR
#define SEISMPM_SOURCE_LUA_DIR ""
#endif

namespace {

// Where lua/seismpm.lua may be: $SEISMPM_LUA_PATH, next to the binary, one up, the source tree.
std::vector<std::string> library_dirs(const char* argv0) {
  std::vector<std::string> dirs;
  if (const char* env = std::getenv("SEISMPM_LUA_PATH")) dirs.emplace_back(env);
  std::error_code ec;
  auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) exe = std::filesystem::absolute(argv0, ec);
  const auto dir = exe.parent_path();
  dirs.push_back((dir / "lua").string());
  dirs.push_back((dir.parent_path() / "lua").string());
  if (*SEISMPM_SOURCE_LUA_DIR) dirs.emplace_back(SEISMPM_SOURCE_LUA_DIR);
  return dirs;
}

// The options a user writes after the script (`seismpm scenario.lua --set cell=0.01`, as the scenario
// headers show) are the same options: taken out of the script's words, which keep the rest. A lone
// "--" ends this, so a script can still receive "--set" as a word.
struct TrailingOptions {
  std::vector<std::string> sets;
  std::string out;
  int threads = 0;
  bool quiet = false, sandbox = false;
  std::string error;
};

TrailingOptions take_trailing_options(std::vector<std::string>& words) {
  TrailingOptions o;
  std::vector<std::string> kept;
  auto value = [&](std::size_t& i, const std::string& name, const std::string& word) -> std::string {
    if (word.size() > name.size() && word[name.size()] == '=') return word.substr(name.size() + 1);
    if (i + 1 < words.size()) return words[++i];
    o.error = name + " needs a value";
    return {};
  };
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::string& w = words[i];
    auto is = [&](const std::string& name) { return w == name || w.rfind(name + "=", 0) == 0; };
    if (w == "--") {
      kept.insert(kept.end(), words.begin() + static_cast<long>(i) + 1, words.end());
      break;
    } else if (is("--set")) {
      o.sets.push_back(value(i, "--set", w));
    } else if (is("--out")) {
      o.out = value(i, "--out", w);
    } else if (is("--threads")) {
      const std::string v = value(i, "--threads", w);
      try {
        std::size_t used = 0;
        o.threads = std::stoi(v, &used);
        if (used != v.size() || o.threads < 1 || o.threads > 1024) throw std::invalid_argument(v);
      } catch (const std::exception&) {
        o.error = "--threads expects a whole number in [1, 1024], got '" + v + "'";
      }
    } else if (w == "--quiet") {
      o.quiet = true;
    } else if (w == "--sandbox") {
      o.sandbox = true;
    } else {
      kept.push_back(w);
    }
    if (!o.error.empty()) break;
  }
  words = kept;
  return o;
}

// What the command line asks for, options written after the script included.
struct CommandLine {
  bool interactive = false, quiet = false, sandbox = false, version = false, api_doc = false;
  std::vector<std::string> chunks, sets;
  int threads = 0;
  std::string out;
  std::string script;                    // FILE.lua, or "plot"
  std::vector<std::string> script_args;  // the words after it
};

// Parses argv into `cl`; returns an exit status when the program should stop now (help, a bad
// option), -1 to go on.
int parse_command_line(int argc, char** argv, CommandLine& cl) {
  CLI::App app{
      "seismpm: Material Point Method for seismic slope failure and landslide run-out.\n"
      "  seismpm                   interactive console\n"
      "  seismpm FILE.lua [args]   run a scenario (`arg` holds the extra words; --set, --out,\n"
      "                            --threads, --quiet, --sandbox after FILE are options too)\n"
      "  seismpm --sandbox FILE.lua  run a scenario someone sent you: no shell, native code or\n"
      "                            debug library, its own files only in its folder, the working\n"
      "                            directory (read) and the output directory (write)\n"
      "  seismpm -i FILE.lua       run, then stay in the console\n"
      "  seismpm -e 'lua code'     run a chunk\n"
      "  seismpm plot DIR [q ...]  PNG plots of DIR/probes.csv (default quantities: ux uy;\n"
      "                            --phase current|gravity|dynamic keeps one phase's rows,\n"
      "                            --x phase_time|time chooses the time axis)",
      "seismpm"};
  app.prefix_command();  // everything after FILE.lua belongs to the script
  app.add_flag("-i,--interactive", cl.interactive, "Enter the console after running FILE and chunks");
  app.add_option("-e,--execute", cl.chunks, "Run a Lua chunk (may repeat)")->allow_extra_args(false);
  app.add_option("--threads", cl.threads, "OpenMP threads (default: all cores)")->check(CLI::Range(1, 1024));
  app.add_option("--out", cl.out, "Output directory in place of the script's default (mpm.out_dir)");
  app.add_flag("--quiet", cl.quiet, "No progress display");
  app.add_flag("--sandbox", cl.sandbox,
               "Run untrusted scripts: no os.execute, io.popen, package.loadlib, C modules or debug library; "
               "files read only under the script's folder, the working directory and the output directory, "
               "written only under the output directory (--out, or an m:output dir inside the working directory)");
  app.add_option("--set", cl.sets, "Scenario parameter name=value, read with mpm.param(name, default) (may repeat)")
      ->allow_extra_args(false);
  app.add_flag("--version", cl.version, "Print the version and exit");
  app.add_flag("--api-doc", cl.api_doc, "Print the Lua API reference (Markdown) and exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  const std::vector<std::string> rest = app.remaining();
  if (!rest.empty()) {
    cl.script = rest.front();
    cl.script_args.assign(rest.begin() + 1, rest.end());
  }
  if (cl.script.empty() || cl.script == "plot") return -1;
  const TrailingOptions trailing = take_trailing_options(cl.script_args);
  if (!trailing.error.empty()) {
    std::fprintf(stderr, "seismpm: %s\n", trailing.error.c_str());
    return 2;
  }
  cl.sets.insert(cl.sets.end(), trailing.sets.begin(), trailing.sets.end());
  if (!trailing.out.empty()) cl.out = trailing.out;
  if (trailing.threads > 0) cl.threads = trailing.threads;
  cl.quiet = cl.quiet || trailing.quiet;
  cl.sandbox = cl.sandbox || trailing.sandbox;
  return -1;
}

// The session's parameters, output directory and progress mode; false (with a message) on a bad --set.
bool fill_session(const CommandLine& cl, seismpm::lua::Session& session) {
  for (const auto& s : cl.sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0) {
      std::fprintf(stderr, "seismpm: --set expects name=value, got '%s'\n", s.c_str());
      return false;
    }
    session.params[s.substr(0, eq)] = s.substr(eq + 1);
  }
  session.out_dir = cl.out;
  session.sandbox = cl.sandbox;
  session.progress = seismpm::Progress::detect(stderr, cl.quiet);
  return true;
}

// seismpm plot DIR [quantities...]: plots of a finished run's probes.
int plot_command(const std::vector<std::string>& args) {
  if (args.empty()) {
    std::fprintf(stderr, "seismpm plot: give the output directory, e.g. seismpm plot out/shaking_table\n");
    return 2;
  }
  // Words are quantities, but --x AXIS and --phase NAME (also --x=AXIS, --phase=NAME).
  std::vector<std::string> quantities;
  seismpm::ProbePlotOptions options;
  for (std::size_t k = 1; k < args.size(); ++k) {
    const std::string& w = args[k];
    std::string* option = nullptr;
    std::string value;
    for (auto [flag, target] : {std::pair{"--x", &options.x}, std::pair{"--phase", &options.phase}}) {
      const std::string f = flag;
      if (w == f) {
        if (k + 1 >= args.size()) {
          std::fprintf(stderr, "seismpm plot: %s needs a value\n", flag);
          return 2;
        }
        option = target, value = args[++k];
      } else if (w.rfind(f + "=", 0) == 0) {
        option = target, value = w.substr(f.size() + 1);
      }
    }
    if (option) {
      *option = value;
    } else if (w.rfind("--", 0) == 0) {
      std::fprintf(stderr, "seismpm plot: unknown option %s (options: --x %s, --phase %s)\n", w.c_str(),
                   seismpm::kProbePlotX, seismpm::kProbePlotPhases);
      return 2;
    } else {
      quantities.push_back(w);
    }
  }
  if (quantities.empty()) quantities = {"ux", "uy"};
  try {
    for (const auto& png : seismpm::plot_probes(args[0], quantities, {}, options))
      std::printf("wrote %s\n", png.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "seismpm plot: %s\n", e.what());
    return 1;
  }
  return 0;
}

// The chunks, then the script, then (when asked, or when there was nothing to run) the console.
int run_lua(const CommandLine& cl, seismpm::lua::Session& session, const char* argv0) {
  seismpm::lua::Runtime runtime(session, library_dirs(argv0));
  seismpm::install_interrupt_handler(runtime);
  bool ok = true;
  for (std::size_t i = 0; ok && i < cl.chunks.size(); ++i) ok = runtime.run_string(cl.chunks[i], "=(command line)");
  if (ok && !cl.script.empty()) {
    if (!std::filesystem::is_regular_file(cl.script)) {
      std::fprintf(stderr, "seismpm: cannot open %s: no such file\n", cl.script.c_str());
      return 1;
    }
    ok = runtime.run_file(cl.script, cl.script_args, cl.interactive);  // -i: its locals stay for the console
  }
  if (cl.interactive || (cl.script.empty() && cl.chunks.empty())) return seismpm::run_console(runtime);
  return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  seismpm::app::use_default_thread_waiting(argv);
  CommandLine cl;
  if (const int status = parse_command_line(argc, argv, cl); status >= 0) return status;
  if (cl.version) {
    std::printf("seismpm %s (Lua %s)\n", seismpm::lua::kVersion, seismpm::lua::Runtime::lua_version());
    return 0;
  }
  if (cl.api_doc) {
    std::fputs(seismpm::lua::api_markdown().c_str(), stdout);
    return 0;
  }
  if (cl.threads > 0) omp_set_num_threads(cl.threads);
  seismpm::lua::Session session;
  if (!fill_session(cl, session)) return 2;
  if (cl.script == "plot" && !std::filesystem::is_regular_file(cl.script)) return plot_command(cl.script_args);
  return run_lua(cl, session, argv[0]);
}
