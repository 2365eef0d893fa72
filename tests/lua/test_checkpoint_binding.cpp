// m:checkpoint, mpm.restart and m:output{ checkpoint_every } from Lua: the restored model, function
// histories given again by key, m:run{} finishing an interrupted run, the sandbox's folders, and damaged
// files as named errors.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "lua/lua_fixture.hpp"

using namespace seismpm;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("seismpm_ckpt_lua_" + std::to_string(getpid()) + "_" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::string quoted(const std::string& s) { return "[[" + s + "]]"; }

// A block on a rigid base that follows a Lua function, with a probe and an output in `dir`.
std::string model_code(const std::string& dir) {
  return "m = mpm.model{ domain = {{0, -0.2}, {1, 1}}, cell = 0.1 }\n"
         "local rock = mpm.material.linear_elastic{ density = 2000, young = 1e7, poisson = 0.3 }\n"
         "block = m:body{ name = 'block', material = rock, shape = mpm.shape.rectangle{0.2, 0, 0.8, 0.4} }\n"
         "shake = mpm.history.fn(function(t) return 0.05 * t end)\n"
         "m:rigid{ name = 'base', shape = mpm.shape.rectangle{0, -0.1, 1, 0}, velocity = { shake, 0 } }\n"
         "m:probe{ name = 'top', body = block, at = {0.5, 0.4} }\n"
         "m:output{ dir = " +
         quoted(dir) + ", every = 0.05 }\n";
}

}  // namespace

TEST_CASE("checkpoint binding: a model saved and restored in Lua", "[lua][checkpoint]") {
  const fs::path dir = temp_dir("roundtrip");
  const std::string file = (dir / "a.chk").string();
  test::LuaFixture f;
  REQUIRE(f.error_of(model_code(dir.string()) +
                     "m:dynamic_phase{ duration = 0.1 }\n"
                     "m:checkpoint{ file = " +
                     quoted(file) +
                     " }\n"
                     "t, n, ux = m:time(), m:steps(), block:field('ux')[5]\n"
                     "m:run{ duration = 0.05 }\n"
                     "after = block:field('ux')[5]") == "");

  // Without the function, the error names the key and says how to give it.
  CHECK_THAT(f.error_of("mpm.restart{ file = " + quoted(file) + " }"),
             Contains("mpm.restart") && Contains(file) && Contains("base.vx") &&
                 Contains("histories = { [\"base.vx\"] = h }"));
  CHECK_THAT(f.error_of("mpm.restart{ file = " + quoted(file) + ", histories = { [1] = shake } }"),
             Contains("its keys are strings"));
  CHECK(f.error_of("r = mpm.restart{ file = " + quoted(file) +
                   ", histories = { ['base.vx'] = shake } }\n"
                   "assert(r:time() == t and r:steps() == n, 'clock')\n"
                   "assert(r:phase() == 'dynamic')\n"
                   "local b = r:bodies()\n"
                   "assert(b.block and b.base, 'bodies')\n"
                   "assert(b.block:field('ux')[5] == ux, 'field')\n"
                   "r:run{ duration = 0.05 }\n"
                   "assert(b.block:field('ux')[5] == after, 'continued bit for bit')") == "");
  // Between runs there is nothing to finish.
  CHECK_THAT(f.error_of("r:run{}"), Contains("key 'duration' must be a number") && Contains("mpm.restart"));
  // Not from a run's call, which a restart could not take up.
  CHECK_THAT(f.error_of("m:run{ duration = 0.02, every = 0.01, call = function() m:checkpoint{ file = " + quoted(file) +
                        " } end }"),
             Contains("may not write a checkpoint"));
}

TEST_CASE("checkpoint binding: checkpoint_every writes a checkpoint during runs, m:run{} finishes the run",
          "[lua][checkpoint]") {
  const fs::path dir = temp_dir("periodic");
  test::LuaFixture f;
  // A checkpoint at a tiny wall-clock interval: one after every step, the last one after the run's
  // last step, before the run's end (its last samples and file) is done.
  REQUIRE(f.error_of(model_code(dir.string()) + "m:output{ dir = " + quoted(dir.string()) +
                     ", every = 0.05, checkpoint_every = 1e-9 }\n"
                     "m:dynamic_phase{ duration = 0.1, every = 0.04, call = function() end }\n"
                     "final = block:field('vx')[3]") == "");
  REQUIRE(fs::exists(dir / "checkpoint.chk"));
  const std::string file = quoted((dir / "checkpoint.chk").string());
  CHECK_THAT(f.error_of("r = mpm.restart{ file = " + file + ", histories = { ['base.vx'] = shake } }; r:run{}"),
             Contains("every 0.04 s") && Contains("m:run{ every = 0.04, call = f }"));
  CHECK_THAT(f.error_of("r = mpm.restart{ file = " + file +
                        ", histories = { ['base.vx'] = shake } }; r:run{ every = 0.05, call = function() end }"),
             Contains("not every 0.05 s"));
  CHECK(f.error_of("r = mpm.restart{ file = " + file +
                   ", histories = { ['base.vx'] = shake } }\n"
                   "assert(r:time() <= m:time())\n"
                   "r:run{ every = 0.04, call = function() end }\n"
                   "assert(r:time() == m:time(), 'the end of the phase')\n"
                   "assert(r:bodies().block:field('vx')[3] == final, 'bit for bit')") == "");
  CHECK_THAT(f.error_of("m:output{ dir = " + quoted(dir.string()) + ", checkpoint_every = 0 }"),
             Contains("checkpoint_every"));
}

TEST_CASE("checkpoint binding: damaged files and the sandbox's folders", "[lua][checkpoint][robustness]") {
  const fs::path dir = temp_dir("damaged");
  const fs::path out = temp_dir("sandbox_out"), elsewhere = temp_dir("sandbox_elsewhere");
  const std::string file = (dir / "x.chk").string();
  test::LuaFixture f;
  std::ofstream(file) << "SEISMPMCHK but not really";
  CHECK_THAT(f.error_of("mpm.restart{ file = " + quoted(file) + " }"),
             Contains("mpm.restart") && Contains("checkpoint " + file));
  CHECK_THAT(f.error_of("mpm.restart{ file = " + quoted((dir / "none.chk").string()) + " }"),
             Contains("none.chk") && Contains("cannot open"));
  CHECK_THAT(f.error_of("mpm.restart{ file = " + quoted(dir.string()) + " }"), Contains("is a directory"));

  test::LuaFixture sandboxed(true, "", out.string());
  const std::string model = model_code(out.string());
  REQUIRE(sandboxed.error_of(model) == "");
  CHECK(sandboxed.error_of("m:checkpoint{ file = " + quoted((out / "ok.chk").string()) + " }") == "");
  CHECK_THAT(sandboxed.error_of("m:checkpoint{ file = " + quoted((elsewhere / "no.chk").string()) + " }"),
             Contains("key 'file'") && Contains("--sandbox"));
  CHECK_FALSE(fs::exists(elsewhere / "no.chk"));
  fs::copy_file(out / "ok.chk", elsewhere / "copy.chk");
  CHECK_THAT(sandboxed.error_of("mpm.restart{ file = " + quoted((elsewhere / "copy.chk").string()) + " }"),
             Contains("key 'file'") && Contains("--sandbox"));
  CHECK(sandboxed.error_of("mpm.restart{ file = " + quoted((out / "ok.chk").string()) +
                           ", histories = { ['base.vx'] = 0 } }") == "");

  // A checkpoint is data: one that names an output directory outside the sandbox's is refused before
  // the restore creates or rewrites anything there.
  const fs::path victim = temp_dir("sandbox_victim");
  test::LuaFixture unconfined;
  REQUIRE(unconfined.error_of(model_code(victim.string()) + "m:checkpoint{ file = " +
                              quoted((out / "elsewhere.chk").string()) + " }\nm = nil; collectgarbage()") == "");
  fs::remove(victim / "particles.pvd");
  CHECK_THAT(sandboxed.error_of("mpm.restart{ file = " + quoted((out / "elsewhere.chk").string()) +
                                ", histories = { ['base.vx'] = 0 } }"),
             Contains("checkpoint's output: the output directory '" + victim.string() + "' is outside"));
  CHECK_FALSE(fs::exists(victim / "particles.pvd"));
}
