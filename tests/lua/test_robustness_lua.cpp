// Ordinary Lua that used to crash the program, each now a Lua error that names what is wrong: objects
// used after their __gc (by hand, or resurrected by another finalizer), a model changed in the middle
// of a step, history functions from collected coroutines. Then bytecode, refused as a script, and
// --sandbox: what it blocks and which files it lets a script touch.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "lua_fixture.hpp"

using Catch::Contains;
using seismpm::test::LuaFixture;

namespace fs = std::filesystem;

namespace {

// A small model with a soil block on a rigid base whose velocity is the history `vx`.
const char* kModel = R"(
  m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
  sand = mpm.material.linear_elastic{ density = 1000, young = 1e6, poisson = 0.3 }
  soil = m:body{ name = "soil", material = sand, shape = mpm.shape.rectangle{0.2, 0.2, 0.6, 0.5} }
  box = mpm.shape.rectangle{0.6, 0.6, 0.9, 0.9}
)";

std::string run(const std::string& code) {
  LuaFixture f;
  return f.error_of(std::string(kModel) + code);
}

// A folder of its own under the system's temporary one, removed at the end.
struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& name)
      : path(fs::temp_directory_path() / ("seismpm_robustness_" + std::to_string(getpid()) + "_" + name)) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string file(const std::string& name, const std::string& text = "x\n") const {
    const fs::path p = path / name;
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
    return p.string();
  }
};

// Lua text for a string literal.
std::string quoted(const std::string& s) { return "[[" + s + "]]"; }

}  // namespace

// ---------------------------------------------------------------- objects after their __gc

TEST_CASE("an object whose __gc ran by hand is dead: every use is a named error", "[robustness][lua]") {
  struct Case {
    const char* make;  // sets x
    const char* use;   // uses x
    const char* expected;
  };
  const auto c =
      GENERATE(Case{"x = m", "x:count()", "model:count: model used after it was collected or closed"},
               Case{"x = m", "x:dt()", "model:dt: model used after it was collected or closed"},
               Case{"x = m", "tostring(x)", "model:__tostring: model used after"},
               Case{"x = m", "x:body{ material = sand, shape = box }", "model:body: model used after"},
               Case{"x = soil", "x:count()", "body:count: body used after it was collected or closed"},
               Case{"x = m:probe{ body = soil, at = {0.3, 0.3} }", "x:get('ux')", "probe:get: probe used after"},
               Case{"x = sand", "m:body{ material = x, shape = box }", "key 'material': material used after"},
               Case{"x = sand", "x:kind()", "material:kind: material used after"},
               Case{"x = box", "x:contains{0.7, 0.7}", "shape:contains: shape used after"},
               Case{"x = box", "m:body{ material = sand, shape = x }", "key 'shape': shape used after"},
               Case{"x = mpm.history.table{ {0, 0}, {1, 1} }", "x:at(0.5)", "history:at: history used after"},
               Case{"x = mpm.history.table{ {0, 0}, {1, 1} }", "m:rigid{ shape = box, velocity = {x, 0} }",
                    "history used after it was collected or closed"});
  CAPTURE(c.make, c.use);
  // __gc twice does nothing the second time.
  CHECK_THAT(run(std::string(c.make) + "; getmetatable(x).__gc(x); getmetatable(x).__gc(x); " + c.use),
             Contains(c.expected));
}

TEST_CASE("__gc called with a value of another type is a Lua error", "[robustness][lua]") {
  const auto c = GENERATE(as<std::string>{}, "m", "soil", "sand", "box", "mpm.history.table{ {0, 0} }");
  CAPTURE(c);
  const std::string error = run("local v = " + c + "\nlocal gc = getmetatable(v).__gc\n" + "gc(42)");
  CHECK_THAT(error, Contains(":__gc: expects a "));
  CHECK_THAT(error, Contains("got number"));
  CHECK_THAT(run("getmetatable(" + c + ").__gc({})"), Contains("got table"));
  CHECK_THAT(run("getmetatable(" + c + ").__gc()"), Contains("got no value"));
  // The wrong kind of userdata too: a model's __gc on a body.
  CHECK_THAT(run("getmetatable(m).__gc(soil); assert(soil:count() > 0)"), Contains("expects a model, got body"));
}

TEST_CASE("a model kept alive by another object's finalizer is dead when used", "[robustness][lua]") {
  // The table's finalizer runs first (finalizers run in the reverse order of marking) and resurrects
  // the model; the model's own finalizer runs in the same cycle: afterwards it is dead.
  LuaFixture f;
  CHECK(f.error_of(std::string("do\n") + kModel + R"(
      local model = m
      setmetatable({}, { __gc = function() keep = model end })
      m, soil, sand, box = nil
    end
    collectgarbage(); collectgarbage()
    assert(keep, "the finalizer ran")
    local ok, err = pcall(keep.dt, keep)
    assert(not ok and err:find("model used after it was collected or closed", 1, true), err)
    ok, err = pcall(keep.count, keep)
    assert(not ok and err:find("model used after", 1, true), err)
  )") == "");
}

TEST_CASE("a finalizer that uses a model finalized before it gets a named error", "[robustness][lua]") {
  LuaFixture f;
  CHECK(f.error_of(R"(
    do
      local m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
      -- marked after the model, finalized before it: resurrects nothing, sees it alive
      setmetatable({}, { __gc = function() first_ok = pcall(m.steps, m) end })
    end
    collectgarbage(); collectgarbage()
    assert(first_ok == true)
  )") == "");
  CHECK(f.error_of(R"(
    do
      local holder = setmetatable({}, { __gc = function(t) late_ok, late_err = pcall(t.m.steps, t.m) end })
      holder.m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }  -- marked after holder: finalized first
    end
    collectgarbage(); collectgarbage()
    assert(late_ok == false and late_err:find("model used after", 1, true), tostring(late_err))
  )") == "");
}

// ---------------------------------------------------------------- history functions

TEST_CASE("a history made inside a coroutine works after the coroutine is collected", "[robustness][lua]") {
  LuaFixture f;
  CHECK(f.error_of(std::string(kModel) + R"(
    local co = coroutine.create(function() h = mpm.history.fn(function(t) return 0.01 * t end) end)
    assert(coroutine.resume(co))
    co = nil
    collectgarbage(); collectgarbage()
    local base = m:rigid{ shape = mpm.shape.rectangle{0.2, 0.0, 0.6, 0.2}, velocity = {h, 0} }
    m:dynamic_phase{ duration = 0.01 }
    assert(math.abs(h:at(2) - 0.02) < 1e-12)
    -- evaluated while a coroutine runs: on the main thread, which may not yield
    local co2 = coroutine.wrap(function() return h:at(3) end)
    assert(math.abs(co2() - 0.03) < 1e-12)
  )") == "");
}

TEST_CASE("a failing, yielding or wrong history function is a clean error", "[robustness][lua]") {
  struct Case {
    const char* body;
    const char* expected;
  };
  const auto c = GENERATE(Case{"error('no value here')", "history function failed at t = "},
                          Case{"coroutine.yield(1)", "history function failed at t = "},
                          Case{"return 'abc'", "history function must return a number"});
  CAPTURE(c.body);
  const std::string code = std::string("local h = mpm.history.fn(function(t) ") + c.body + " end)\n";
  CHECK_THAT(run(code + "h:at(0)"), Contains(c.expected));
  CHECK_THAT(run(code + "coroutine.wrap(function() return h:at(0) end)()"), Contains(c.expected));
  CHECK_THAT(run(code + "m:rigid{ shape = mpm.shape.rectangle{0.2, 0.0, 0.6, 0.2}, velocity = {h, 0} }\n"
                        "m:dynamic_phase{ duration = 0.01 }"),
             Contains(c.expected));
}

TEST_CASE("a history function may not change or step a model in the middle of a step", "[robustness][lua]") {
  struct Case {
    const char* change;
    const char* what;
  };
  const auto c = GENERATE(
      Case{"m:body{ material = sand, shape = box }", "may not add a body"},
      Case{"m:rigid{ shape = box }", "may not add a rigid body"},
      Case{"m:contact{ soil, base, friction = 0.5 }", "may not declare a contact"},
      Case{"m:set_friction{ soil, base, friction = 0.5 }", "may not change a friction"},
      Case{"m:fix{ side = 'left' }", "may not fix an edge"},
      Case{"m:probe{ body = soil, at = {0.3, 0.3} }", "may not add a probe"},
      Case{"m:output{ dir = 'out/robustness_never' }", "may not set the output"},
      Case{"m:write()", "may not write the model's files"}, Case{"soil:set_velocity{1, 0}", "may not set velocities"},
      Case{"base:set_velocity{1, 0}", "may not set velocities"}, Case{"m:step()", "may not step the model"},
      Case{"m:run{ duration = 0.01 }", "may not step the model"}, Case{"m:gravity_phase{}", "may not start a phase"},
      Case{"m:dynamic_phase{ duration = 0.01 }", "may not start a phase"},
      Case{"m:strength_reduction{}", "may not run a strength reduction"},
      Case{"other:step()", "may not step the model"});
  CAPTURE(c.change);
  LuaFixture f;
  const std::string error = f.error_of(std::string(kModel) + R"(
    other = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
    other:body{ material = sand, shape = box }
    local h = mpm.history.fn(function(t) )" +
                                       c.change + R"( return 0 end)
    base = m:rigid{ name = "base", shape = mpm.shape.rectangle{0.2, 0.0, 0.6, 0.2}, velocity = {h, 0} }
    m:dynamic_phase{ duration = 0.01 }
  )");
  CHECK_THAT(error, Contains("history function failed at t = "));
  CHECK_THAT(error, Contains(std::string("a value function (mpm.history.fn, b:set_velocity(function)) ") + c.what));
  // The model is intact enough to be read and run again.
  CHECK(f.error_of("assert(m:count() > 0); assert(#soil:field('ux') == soil:count())") == "");
}

TEST_CASE("a run's call may change what the next step reads, not rebuild the model", "[robustness][lua]") {
  const std::string run_with =
      "base = m:rigid{ name = 'base', shape = mpm.shape.rectangle{0.2, 0.0, 0.6, 0.2} }\n"
      "m:contact{ soil, base, friction = 0.5 }\n"
      "m:dynamic_phase{ duration = 0.02, every = 0.01, call = function(m) ";
  CHECK_THAT(run(run_with + "m:body{ material = sand, shape = box } end }"),
             Contains("a run's call may not add a body while the model runs"));
  CHECK_THAT(run(run_with + "m:probe{ body = soil, at = {0.3, 0.3} } end }"),
             Contains("a run's call may not add a probe while the model runs"));
  CHECK_THAT(run(run_with + "m:output{ dir = 'out/robustness_never' } end }"),
             Contains("a run's call may not set the output while the model runs"));
  CHECK_THAT(run(run_with + "m:step() end }"), Contains("a run's call may not step the model"));
  // What the scenarios do between steps stays allowed.
  CHECK(run(run_with + "m:set_friction{ soil, base, friction = 0.2 }; base:set_velocity{0.1, 0} end }") == "");
}

TEST_CASE("a probe on a body of another model is refused", "[robustness][lua]") {
  CHECK_THAT(run("local other = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }\n"
                 "other:probe{ body = soil, at = {0.3, 0.3} }"),
             Contains("model:probe: key 'body' belongs to another model"));
}

TEST_CASE("a velocity function of b:set_velocity may not change the model", "[robustness][lua]") {
  CHECK_THAT(run("soil:set_velocity(function(x, y) m:body{ material = sand, shape = box } return 0, 0 end)"),
             Contains("may not add a body"));
  CHECK_THAT(run("soil:set_velocity(function(x, y) m:step() return 0, 0 end)"), Contains("may not step the model"));
  CHECK(run("soil:set_velocity(function(x, y) return m:time() + x, 0 end)") == "");
}

TEST_CASE("__gc by hand while a run or a history function uses the object does not crash", "[robustness][lua]") {
  LuaFixture f;
  // The run's call destroys the model's userdata: the run holds the model and ends normally.
  CHECK(f.error_of(std::string(kModel) + R"(
    m:dynamic_phase{ duration = 0.02, every = 0.01, call = function(mm) getmetatable(mm).__gc(mm) end }
    local ok, err = pcall(m.count, m)
    assert(not ok and err:find("model used after", 1, true), err)
    assert(soil:count() > 0)  -- the body still holds the model
  )") == "");
  // A history function destroys its own userdata, and the body's.
  CHECK(f.error_of(std::string(kModel) + R"(
    local h
    h = mpm.history.fn(function(t) getmetatable(h).__gc(h); getmetatable(soil).__gc(soil); return 0.01 end)
    local base = m:rigid{ shape = mpm.shape.rectangle{0.2, 0.0, 0.6, 0.2}, velocity = {h, 0} }
    m:dynamic_phase{ duration = 0.01 }
    assert(not pcall(h.at, h, 0))
  )") == "");
  // A velocity function destroys the body it sets.
  CHECK(f.error_of(std::string(kModel) + R"(
    soil:set_velocity(function(x, y) getmetatable(soil).__gc(soil); getmetatable(m).__gc(m); return 1, 0 end)
  )") == "");
}

// ---------------------------------------------------------------- bytecode

TEST_CASE("bytecode is never loaded: load, loadfile, dofile, require and the main script", "[robustness][lua]") {
  TempDir dir("bytecode");
  LuaFixture f;
  const std::string file = (dir.path / "chunk.luac").string();
  REQUIRE(f.error_of("local out = assert(io.open(" + quoted(file) +
                     ", 'wb')); out:write(string.dump(function() bytecode_ran = true end)); out:close()") == "");
  const char* binary = "attempt to load a binary chunk (mode is 't')";
  CHECK(f.error_of(R"(
    local dumped = string.dump(function() return 1 end)
    for _, mode in ipairs{ "b", "bt", "t" } do
      local fn, err = load(dumped, "dumped", mode)
      assert(fn == nil and err:find("binary chunk", 1, true), mode)
    end
    assert(load(dumped) == nil)
    assert(load("return 1")() == 1)  -- text still loads
  )") == "");
  CHECK_THAT(f.error_of("dofile(" + quoted(file) + ")"), Contains(binary));
  CHECK(f.error_of("local fn, err = loadfile(" + quoted(file) + ", 'b'); assert(fn == nil and err:find('binary'))") ==
        "");
  CHECK_THAT(f.error_of("package.path = " + quoted((dir.path / "?.luac").string()) + "; require 'chunk'"),
             Contains(binary));
  CHECK_FALSE(f.runtime.run_file(file, {}));
  CHECK_FALSE(f.truth("bytecode_ran"));
}

// ---------------------------------------------------------------- --sandbox

TEST_CASE("sandbox: the shell, native code and the debug library raise errors naming them", "[robustness][sandbox]") {
  const auto c =
      GENERATE(as<std::string>{}, "os.execute('true')", "os.execute()", "io.popen('ls')",
               "package.loadlib('libc.so.6', '*')", "os.tmpname()", "debug.sethook()", "debug.getlocal(1, 1)",
               "debug.getregistry()", "debug.getupvalue(print, 1)", "debug.setmetatable(1, {})");
  CAPTURE(c);
  LuaFixture f(true);
  const std::string name = c.substr(0, c.find('('));
  CHECK_THAT(f.error_of(c), Contains(name + " ") && Contains("not available under --sandbox"));
  // Without the sandbox they exist.
  LuaFixture open;
  CHECK(open.error_of("assert(type(" + name + ") == 'function')") == "");
}

TEST_CASE("sandbox: no C modules, and what scripts use debug for stays", "[robustness][sandbox]") {
  LuaFixture f(true);
  CHECK(f.error_of("assert(#package.searchers == 2)") == "");
  const std::string error = f.error_of("require 'socket'");
  CHECK_THAT(error, Contains("module 'socket' not found"));
  CHECK_THAT(error, !Contains(".so'"));
  CHECK(f.error_of(R"(
    assert(debug.getinfo(1, "S").source == "=test" and debug.getinfo(1.0, "S").source == "=test")
    assert(debug.getinfo(1).currentline == 3)
    assert(type(debug.traceback()) == "string")
    assert(package.loaded.debug == debug)
    assert(not pcall(debug.getinfo, 1, "f"))
  )") == "");
}

TEST_CASE("sandbox: files are read in the script's folder, the working directory and the output directory",
          "[robustness][sandbox]") {
  TempDir script("script"), out("out"), elsewhere("elsewhere");
  const std::string data = script.file("data/v.csv", "t,v\n0,0\n1,2\n");
  const std::string outside = elsewhere.file("secret.txt");
  const std::string hidden = script.file(".hidden/key.txt");
  const std::string in_out = out.file("summary.txt");
  fs::create_symlink(outside, script.path / "link.txt");
  LuaFixture f(true, script.path.string(), out.path.string());

  // Allowed: the script's folder (also through a relative data path), the output directory, the
  // working directory.
  CHECK(f.error_of("assert(io.open(" + quoted(data) + ")):close()") == "");
  CHECK(f.error_of("assert(io.open(" + quoted(in_out) + ")):close()") == "");
  CHECK(f.error_of("for line in io.lines(" + quoted(data) + ") do end") == "");
  CHECK(f.error_of("local h = mpm.history.csv{ file = " + quoted(data) + ", value = 'v' }; assert(h:at(0.5) == 1)") ==
        "");
  const fs::path here = fs::current_path() / "seismpm_robustness_cwd.txt";
  std::ofstream(here) << "x\n";
  CHECK(f.error_of("assert(io.open('seismpm_robustness_cwd.txt')):close()") == "");
  fs::remove(here);

  // Refused: elsewhere, through a link out, through .., hidden files.
  const std::string dotdot = (script.path / ".." / elsewhere.path.filename() / "secret.txt").string();
  for (const std::string& file : {outside, (script.path / "link.txt").string(), dotdot, hidden}) {
    CAPTURE(file);
    CHECK(f.error_of(
              "local fh, err = io.open(" + quoted(file) +
              "); assert(fh == nil and err:find('io.open: ', 1, true) and err:find('--sandbox', 1, true), err)") == "");
    CHECK_THAT(f.error_of("for l in io.lines(" + quoted(file) + ") do end"), Contains("io.lines: '"));
    CHECK_THAT(f.error_of("io.input(" + quoted(file) + ")"), Contains("io.input: '"));
    CHECK_THAT(f.error_of("dofile(" + quoted(file) + ")"), Contains("dofile: '"));
    CHECK(f.error_of("local fn, err = loadfile(" + quoted(file) + "); assert(fn == nil and err:find('loadfile: '))") ==
          "");
    CHECK_THAT(f.error_of("mpm.history.csv{ file = " + quoted(file) + ", value = 'v' }"),
               Contains("mpm.history.csv: key 'file': '"));
  }
  CHECK_THAT(f.error_of("package.path = " + quoted(elsewhere.path.string() + "/?.txt") + "; require 'secret'"),
             Contains("require: '"));
}

TEST_CASE("sandbox: files are written only in the output directories", "[robustness][sandbox]") {
  TempDir script("wscript"), out("wout"), elsewhere("welsewhere");
  const std::string outside = elsewhere.file("victim.txt", "intact\n");
  fs::create_symlink(outside, out.path / "link.txt");
  fs::create_directories(out.path / ".config");
  LuaFixture f(true, script.path.string(), out.path.string());
  const std::string o = out.path.string();

  CHECK(f.error_of("local fh = assert(io.open(" + quoted(o + "/new.txt") + ", 'w')); fh:write('ok'); fh:close()") ==
        "");
  CHECK(f.error_of("assert(io.open(" + quoted(o + "/new.txt") + ", 'a+')):close()") == "");
  CHECK(f.error_of("assert(os.rename(" + quoted(o + "/new.txt") + ", " + quoted(o + "/renamed.txt") + "))") == "");
  CHECK(f.error_of("assert(os.remove(" + quoted(o + "/renamed.txt") + "))") == "");
  CHECK(f.error_of("mpm.history.table{ {0, 0}, {1, 1} }:write_csv(" + quoted(o + "/h.csv") + ")") == "");
  CHECK(fs::exists(out.path / "h.csv"));

  for (const std::string& file : {(script.path / "x.txt").string(), outside, o + "/link.txt", o + "/../x.txt",
                                  o + "/.config/x.txt", o + "/no_such_folder/x.txt"}) {
    CAPTURE(file);
    CHECK(f.error_of("local fh, err = io.open(" + quoted(file) +
                     ", 'w'); assert(fh == nil and err:find('may write under --sandbox', 1, true), err)") == "");
    CHECK_THAT(f.error_of("io.output(" + quoted(file) + ")"), Contains("io.output: '"));
    CHECK(f.error_of("local ok, err = os.remove(" + quoted(file) + "); assert(not ok and err:find('os.remove: '))") ==
          "");
    CHECK_THAT(f.error_of("mpm.history.table{ {0, 0}, {1, 1} }:write_csv(" + quoted(file) + ")"),
               Contains("history:write_csv: '"));
  }
  CHECK(f.error_of("assert(not os.rename(" + quoted(outside) + ", " + quoted(o + "/stolen.txt") + "))") == "");
  std::ifstream victim(outside);
  std::string text;
  std::getline(victim, text);
  CHECK(text == "intact");
}

TEST_CASE("sandbox: an m:output dir inside the working directory opens it for writing", "[robustness][sandbox]") {
  TempDir elsewhere("odir");
  const fs::path inside = fs::current_path() / "seismpm_robustness_out";
  const fs::path by_default = fs::current_path() / "seismpm_robustness_default";
  fs::remove_all(inside);
  fs::remove_all(by_default);
  fs::create_directories(by_default);
  {
    LuaFixture f(true);  // no --out
    CHECK(f.error_of(std::string(kModel) + R"(
      local fh, err = io.open("seismpm_robustness_out/summary.txt", "w")
      assert(fh == nil, "not before m:output made it an output directory")
      m:output{ dir = "seismpm_robustness_out" }
      assert(io.open("seismpm_robustness_out/summary.txt", "w")):close()
      -- an output directory elsewhere is refused: the run's own files would land outside
      local ok, why = pcall(m.output, m, { dir = )" +
                     quoted(elsewhere.path.string()) + R"( })
      assert(not ok and why:find("is outside the working directory and the --out directory", 1, true), why)
      fh, err = io.open(")" +
                     elsewhere.path.string() + R"(/summary.txt", "w")
      assert(fh == nil and err:find("may write under --sandbox", 1, true), err)
      -- mpm.out_dir's answer is an output directory too
      assert(io.open("seismpm_robustness_default/a.txt", "w") == nil)
      assert(mpm.out_dir("seismpm_robustness_default") == "seismpm_robustness_default")
      assert(io.open("seismpm_robustness_default/a.txt", "w")):close()
      -- the working directory itself is none
      assert(mpm.out_dir(".") == ".")
      assert(io.open("seismpm_robustness_cwd_file.txt", "w") == nil)
    )") == "");
  }
  CHECK(fs::exists(inside / "summary.txt"));
  CHECK(fs::exists(by_default / "a.txt"));
  CHECK_FALSE(fs::exists(elsewhere.path / "summary.txt"));
  CHECK_FALSE(fs::exists(elsewhere.path / "particles.pvd"));
  CHECK_FALSE(fs::exists(fs::current_path() / "seismpm_robustness_cwd_file.txt"));
  fs::remove_all(inside);
  fs::remove_all(by_default);
}

TEST_CASE("mpm.plot and m:output refuse control characters (a line break would reach gnuplot's commands)",
          "[robustness][lua]") {
  CHECK_THAT(run("mpm.plot{ file = 'a.csv', x = 't', y = {'v'}, title = 'a\\nsystem \"touch x\"' }"),
             Contains("mpm.plot: key 'title': 'a") && Contains("holds a control character"));
  CHECK_THAT(run("mpm.plot{ file = 'a\\n.csv', x = 't', y = {'v'} }"), Contains("holds a control character"));
  CHECK_THAT(run("mpm.plot{ file = 'a.csv', x = 't', y = {'v\\r'} }"), Contains("holds a control character"));
  CHECK_THAT(run("m:output{ dir = 'out\\nsystem' }"), Contains("key 'dir'") && Contains("holds a control character"));
}

TEST_CASE("mpm.model: a grid larger than the machine's memory is a Lua error with both figures",
          "[lua][memory][robustness]") {
  LuaFixture f;
  const std::string message = f.error_of("mpm.model{ domain = {{0, 0}, {1e6, 1e6}}, cell = 1 }");
  CAPTURE(message);
  CHECK_THAT(message, Contains("the grid needs about ") && Contains("of memory, more than the ") &&
                          Contains("check_memory = false"));
}

TEST_CASE("an output or probe interval shorter than the time step is refused at the run's start", "[lua][robustness]") {
  // The soil's p-wave speed is about 37 m/s: the stable step on 0.1 m cells is about 1e-3 s.
  LuaFixture f;
  const std::string dir = (fs::temp_directory_path() / ("seismpm_interval_" + std::to_string(getpid()))).string();
  const std::string output =
      f.error_of(std::string(kModel) + "m:output{ dir = '" + dir + "', every = 1e-9 }\nm:run{ duration = 0.01 }");
  CAPTURE(output);
  CHECK_THAT(output,
             Contains("m:output: every = 1e-09 s is shorter than the time step (") && Contains("Give every >= "));
  const std::string probe = f.error_of(std::string(kModel) +
                                       "m:probe{ name = 'top', body = soil, at = {0.4, 0.5}, every = 1e-7 }\n"
                                       "m:run{ duration = 0.01 }");
  CAPTURE(probe);
  CHECK_THAT(probe, Contains("probe 'top': every = 1e-07 s is shorter than the time step (") &&
                        Contains("Give every = 0 to sample every step"));
  fs::remove_all(dir);
}
