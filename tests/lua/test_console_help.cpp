// The console's help: tables of the API listed with a line per function, searches; and -i's locals kept
// for the console (Runtime::run_file with keep_locals).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "lua/api_docs.hpp"
#include "lua_fixture.hpp"

namespace {

// What help(<expression>) prints.
std::string help_of(seismpm::test::LuaFixture& f, const std::string& expression) {
  lua_State* L = f.runtime.state();
  const std::string chunk = "return " + expression;
  REQUIRE(luaL_dostring(L, chunk.c_str()) == LUA_OK);
  std::string text = seismpm::lua::help_for(L, -1);
  lua_pop(L, 1);
  return text;
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A script in a fresh folder; returns its path.
std::string script(const std::string& name, const std::string& code) {
  const auto dir = std::filesystem::temp_directory_path() / "seismpm_console_help_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << code;
  return path.string();
}

const char* const kModelScript = R"(
local m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
local soil = mpm.material.linear_elastic{ density = 1000, young = 1e6, poisson = 0.3 }
local box = m:body{ material = soil, shape = mpm.shape.rectangle{ 0, 0, 1, 0.5 } }
do local hidden = 1 end
for i = 1, 2 do local inner = i end
local n = 1
local n = 2   -- the later local of a name is the one kept
)";

}  // namespace

TEST_CASE("help lists the functions of a table of the API with one-line summaries", "[lua][docs][help]") {
  seismpm::test::LuaFixture f;
  const std::string history = help_of(f, "mpm.history");
  CAPTURE(history);
  CHECK(has(history, "mpm.history.csv"));
  CHECK(has(history, "mpm.history.at2"));
  CHECK(has(history, "A piecewise-linear history; zero before the first and after the last point."));
  CHECK(has(history, "history:at"));  // the methods of the objects it makes
  CHECK_FALSE(has(history, "no help"));
  CHECK(help_of(f, "\"mpm.history\"") == history);

  const std::string material = help_of(f, "mpm.material");
  CHECK(has(material, "mpm.material.mohr_coulomb"));
  CHECK(has(material, "mpm.material.drucker_prager"));
  CHECK(has(help_of(f, "mpm.shape"), "mpm.shape.polygon"));

  const std::string mpm = help_of(f, "mpm");
  CAPTURE(mpm);
  CHECK(has(mpm, "mpm.model"));
  CHECK(has(mpm, "Creates a 2D plane-strain model on a background grid."));
  CHECK(has(mpm, "mpm.material.*: 3 functions, help(mpm.material)"));
  CHECK_FALSE(has(mpm, "mpm.material.mohr_coulomb"));  // one line per table below mpm

  const std::string model = help_of(f, "mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }");
  CAPTURE(model);
  CHECK(has(model, "model:run"));
  CHECK(has(model, "Takes n explicit steps."));

  // Every line of a listing is one line of at most about 100 characters of summary.
  for (const auto* fn : seismpm::lua::api_functions()) {
    const std::string line = seismpm::lua::summary_line(*fn);
    CAPTURE(fn->name, line);
    CHECK(line.find('\n') == std::string::npos);
    CHECK(line.size() <= 100);
    CHECK(line.size() > 5);
  }
}

TEST_CASE("help(\"word\") searches names, descriptions and keys, ignoring case", "[lua][docs][help]") {
  seismpm::test::LuaFixture f;
  const std::string friction = help_of(f, "\"FRICTION\"");
  CAPTURE(friction);
  CHECK(has(friction, "entries match 'FRICTION'"));
  CHECK(has(friction, "model:contact"));              // in its name's text and keys
  CHECK(has(friction, "mpm.material.mohr_coulomb"));  // a key
  CHECK_FALSE(has(friction, "mpm.history.csv"));
  CHECK(seismpm::lua::search("friction").size() == seismpm::lua::search("Friction").size());

  const std::string none = help_of(f, "\"quicksand\"");
  CHECK(has(none, "nothing in the API matches 'quicksand'"));
  // A name still shows the function, the short form of a method too; help never raises.
  CHECK(has(help_of(f, "\"model:run\""), "example:"));
  CHECK(help_of(f, "\"m:run\"") == help_of(f, "\"model:run\""));
  CHECK(has(help_of(f, "{}"), "no help for this table"));
  CHECK(has(help_of(f, "print"), "no help for this function"));
  CHECK(f.error_of("help('nonsense'); help({}); help(print); help(1); help(true)") == "");
}

TEST_CASE("-i keeps the script's top-level locals for the console", "[lua][console]") {
  SECTION("a script that ends") {
    seismpm::test::LuaFixture f;
    REQUIRE(f.runtime.run_file(script("ends.lua", kModelScript), {}, true));
    CHECK(f.error_of("assert(box:count() > 0 and m:count() == box:count() and type(soil:kind()) == 'string')") == "");
    CHECK(f.number("n") == 2);
    CHECK(f.error_of("assert(hidden == nil and inner == nil and i == nil)") == "");
    CHECK(f.error_of("m:step(2); assert(m:steps() == 2)") == "");
  }
  SECTION("a script that stops on an error keeps what it defined before") {
    seismpm::test::LuaFixture f;
    REQUIRE_FALSE(f.runtime.run_file(
        script("stops.lua", "local a = 1\nlocal t = { 2 }\nerror('half-way')\nlocal late = 3\n"), {}, true));
    CHECK(f.number("a") == 1);
    CHECK(f.error_of("assert(t[1] == 2 and late == nil)") == "");
  }
  SECTION("an explicit return, and a global of the same name is not replaced") {
    seismpm::test::LuaFixture f;
    REQUIRE(f.runtime.run_file(script("returns.lua", "local x = 5\nlocal print = 1\nreturn x\n"), {}, true));
    CHECK(f.number("x") == 5);
    CHECK(f.error_of("assert(type(print) == 'function')") == "");
  }
  SECTION("under --sandbox, without handing the script the debug library") {
    const std::string file =
        script("sandboxed.lua", "local y = 7\nassert(not pcall(function() return debug.getlocal end))\n");
    seismpm::test::LuaFixture f(true, std::filesystem::path(file).parent_path().string());
    REQUIRE(f.runtime.run_file(file, {}, true));
    CHECK(f.number("y") == 7);
  }
  SECTION("without -i a script's locals stay its own") {
    seismpm::test::LuaFixture f;
    REQUIRE(f.runtime.run_file(script("plain.lua", kModelScript), {}));
    CHECK(f.error_of("assert(m == nil and box == nil and n == nil)") == "");
    CHECK(lua_gethook(f.runtime.state()) == nullptr);
  }
}
