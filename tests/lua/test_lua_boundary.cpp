// The Lua boundary is safe: hostile scripts get a clean Lua error naming the key, never a crash, and no
// metamethod runs while a binding reads its arguments (a Lua error there would skip C++ destructors).
#include <catch2/catch.hpp>

#include <memory>

#include "lua/binding.hpp"
#include "lua/objects.hpp"
#include "lua_fixture.hpp"

using Catch::Contains;
using seismpm::test::LuaFixture;

namespace {

// Metatables whose every metamethod raises an error that says "hostile": a message with that word
// shows that a binding ran one.
const char* kHostile = R"(
  local function boom(what) return function() error("hostile " .. what, 0) end end
  hostile = { __index = boom("__index"), __newindex = boom("__newindex"), __len = boom("__len"),
              __eq = boom("__eq"), __lt = boom("__lt"), __le = boom("__le"), __tostring = boom("__tostring"),
              __concat = boom("__concat"), __call = boom("__call"), __pairs = boom("__pairs"),
              __close = boom("__close"), __name = "hostile table" }
  function evil(t) return setmetatable(t or {}, hostile) end
)";

std::string run(const std::string& code) {
  LuaFixture f;
  return f.error_of(std::string(kHostile) + code);
}

}  // namespace

TEST_CASE("argument tables are read raw: __index, __len and __pairs never run", "[lua][boundary]") {
  // __index would supply the missing key: read raw, it stays missing.
  CHECK_THAT(run("mpm.material.linear_elastic(evil{ density = 1000, young = 1e6 })"),
             Contains("mpm.material.linear_elastic: missing key 'poisson'"));
  CHECK_THAT(run("mpm.shape.polyline(evil{ {0, 0}, {1, 0} })"), Contains("missing key 'thickness'"));
  // __len and __pairs: the raw length and traversal work.
  CHECK(run(R"(
    local s = mpm.shape.polygon(evil{ evil{0, 0}, evil{1, 0}, evil{1, 1} })
    assert(s:contains{0.9, 0.5} and not s:contains{0.1, 0.5})
    local h = mpm.history.table(evil{ evil{0, 0}, evil{1, 2} })
    assert(h:at(0.5) == 1)
    local m = mpm.material.mohr_coulomb(evil{ density = 2000, young = 1e7, poisson = 0.3, friction = 30,
                                              softening = evil{ friction = 20, strain = 0.1 } })
    assert(tostring(m):find("softening to c 0 Pa, phi 20"))
  )") == "");
  // A point {x} whose __index would give y is one number short.
  CHECK_THAT(run("mpm.shape.polygon{ {0, 0}, evil{1}, {1, 1} }"),
             Contains("point 2 must be a point {x, y} with 2 numbers"));
  CHECK_THAT(run("mpm.material.mohr_coulomb{ density = 2000, young = 1e7, poisson = 0.3, friction = 30, "
                 "softening = evil{ friction = 20 } }"),
             Contains("key 'softening': missing key 'strain'"));
}

TEST_CASE("wrong values name the key and never run their metamethods", "[lua][boundary]") {
  struct Case {
    std::string code, expected;
  };
  const std::vector<Case> cases = {
      {"mpm.material.linear_elastic{ density = evil(), young = 1e6, poisson = 0.3 }",
       "key 'density' must be a number, got hostile table"},
      {"mpm.material.drucker_prager{ density = 1, young = 1e6, poisson = 0.3, friction = 30, fit = evil() }",
       "key 'fit' must be one of plane_strain|outer|inner"},
      {"mpm.shape.polyline{ {0, 0}, {1, 0}, thickness = 0.1, side = evil() }", "key 'side'"},
      {"mpm.shape.rectangle{ lower = evil{0}, upper = {1, 1} }", "key 'lower' must be a point {x, y} with 2 numbers"},
      {"mpm.history.csv{ file = evil(), value = 'v' }", "key 'file' must be a string, got hostile table"},
      {"mpm.history.at2{ file = 'x.AT2', scale = evil() }", "key 'scale' must be a number, got hostile table"},
      {"mpm.plot{ file = '/nonexistent.csv', x = 't', y = evil{'v'} }", "cannot be opened"},  // y read raw: {'v'}
      {"mpm.plot{ file = 'a.csv', x = 't', y = { evil() } }", "key 'y': entry 1 must be a name"},
      {"mpm.material.mohr_coulomb{ density = 2000, young = 1e7, poisson = 0.3, friction = 30, softening = 5 }",
       "key 'softening': expects a table of named arguments"},
      {"mpm.material.linear_elastic(evil())", "missing key 'density'"},
      {"mpm.material.linear_elastic{ [evil()] = 1 }", "unknown key '[hostile table]'"},
      {"mpm.material.linear_elastic{ density = 1000, young = 1e6, poisson = 0.3, [1.5] = 2 }",
       "unknown key '[number]'"},
      {"mpm.history.table{ {0, 0}, [5] = {1, 1} }", "unknown key '[5]'"},
      {"mpm.history.fn(evil())", "expects a function of time"},
      {"mpm.history.table{ {0, 0} }:at(evil())", "expects a time t (s), got hostile table"},
      {"local at = getmetatable(mpm.history.table{ {0, 0} }).__index.at; at(evil(), 1)",
       "self must be a history, got hostile table"},
      {"help(evil())", ""},  // help never raises, nor calls the hostile metamethods
      {"mpm.model{ domain = evil{ {0, 0}, {1, 1} }, cell = 0.1 }", ""},  // read raw: a domain
      {"mpm.model{ domain = evil{ {0, 0} }, cell = 0.1 }", "key 'domain' must hold 2 corner points"},
      {"mpm.model{ domain = {{0, 0}, {1, 1}}, cell = evil() }", "key 'cell' must be a number, got hostile table"},
      {"mpm.model(evil{ domain = {{0, 0}, {1, 1}} })", "mpm.model: missing key 'cell'"},
      {"m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 } m:rigid{ shape = mpm.shape.rectangle{0, 0, 1, 0.2}, "
       "velocity = evil{ 1, 0 } }",
       ""},
      {"m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 } m:rigid{ shape = mpm.shape.rectangle{0, 0, 1, 0.2}, "
       "velocity = evil{ 1 } }",
       "key 'velocity' must be {vx, vy}"},
      {"m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 } m:body{ material = evil(), shape = "
       "mpm.shape.rectangle{0, 0, 1, 0.2} }",
       "key 'material' must be a material, got hostile table"},
      {"m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 } m:contact(evil{ friction = 0.1 })",
       "name the two bodies"},
      {"m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 } m:run(evil{ duration = 1, every = 0.1 })",
       "key 'every' needs key 'call'"},
      {"m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 } m:output(evil{ every = evil() })",
       "key 'every' must be a number, got hostile table"},
      {"m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 } m:gravity_phase(evil{ k0 = 4 })",
       "key 'k0' must be in (0, 3], got 4"},
      {"mpm.shape.rectangle{0, 0, 1, 1}:contains(evil{0.5, 0.5})", ""},  // a plain point: works
  };
  for (const auto& c : cases) {
    CAPTURE(c.code);
    const std::string error = run(c.code);
    CHECK_THAT(error, Contains(c.expected) && !Contains("hostile __"));
    if (!c.expected.empty()) CHECK_THAT(error, Contains("test:"));
  }
}

TEST_CASE("a global table with a strict metatable does not break help() or the library", "[lua][boundary]") {
  CHECK(run(R"(
    setmetatable(_G, { __index = function(_, k) error("hostile strict global " .. tostring(k), 0) end })
    help(mpm.geometry.slope); help(mpm.material.linear_elastic); help()
    -- help never raises: a value outside the API gets a message
    local ok, err = pcall(help, print)
    assert(ok, err)
  )") == "");
}

TEST_CASE("history.fn: errors, yields and bad values are clean errors naming t", "[lua][boundary][history]") {
  CHECK_THAT(run("local h = mpm.history.fn(function(t) error('no data at ' .. t) end) h:at(0.5)"),
             Contains("history:at: history function failed at t = 0.5: test:") && Contains("no data at 0.5"));
  CHECK_THAT(run("local h = mpm.history.fn(function(t) error(evil()) end) h:at(1)"),
             Contains("history function failed at t = 1: (an error object that is not a string)"));
  CHECK_THAT(run("local h = mpm.history.fn(function(t) return evil() end) h:at(1)"),
             Contains("history function must return a number (at t = 1)"));
  CHECK_THAT(run("local h = mpm.history.fn(function(t) return coroutine.yield(t) end) h:at(1)"),
             Contains("history function failed at t = 1") && Contains("yield"));
  // Asked from inside a coroutine, it still runs on the main thread, where a yield cannot go anywhere.
  CHECK_THAT(run(R"(
    local h = mpm.history.fn(function(t) return coroutine.yield(t) end)
    local co = coroutine.wrap(function() return h:at(2) end)
    co()
  )"),
             Contains("history function failed at t = 2") && Contains("yield"));
  CHECK(run(R"(
    local h = mpm.history.fn(function(t) return 3 * t end)
    local co = coroutine.wrap(function() return h:at(2), h:at(3) end)
    local a, b = co()
    assert(a == 6 and b == 9)
  )") == "");
}

TEST_CASE("history.fn made in a coroutine that is collected still works", "[lua][boundary][history]") {
  CHECK(run(R"(
    local co = coroutine.create(function() h = mpm.history.fn(function(t) return 2 * t end); coroutine.yield() end)
    coroutine.resume(co)
    co = nil
    for _ = 1, 3 do collectgarbage("collect") end
    -- A fresh coroutine may reuse the collected one's memory.
    for _ = 1, 10 do coroutine.wrap(function() local x = {} end)() end
    assert(h:at(4) == 8, "h(4) = " .. h:at(4))
    -- As a rigid body's velocity, read inside the model's step.
    local m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1, gravity = {0, 0} }
    local mat = mpm.material.linear_elastic{ density = 1000, young = 1e6, poisson = 0.3 }
    m:body{ material = mat, shape = mpm.shape.rectangle{0.6, 0.6, 0.8, 0.8} }
    local r = m:rigid{ shape = mpm.shape.rectangle{0.2, 0.2, 0.4, 0.4}, velocity = {h, 0} }
    local x0 = r:centroid()[1]
    m:step(3)
    assert(r:centroid()[1] > x0, "the rigid body moves with its history")
  )") == "");
}

TEST_CASE("history.fn releases its registry reference when the history dies", "[lua][boundary][history]") {
  LuaFixture f;
  lua_State* L = f.runtime.state();
  auto registry_length = [&] {
    lua_pushvalue(L, LUA_REGISTRYINDEX);
    const auto n = lua_rawlen(L, -1);
    lua_pop(L, 1);
    return n;
  };
  // Freed references are reused, so the registry stops growing: its length is the most ever held.
  const char* histories = R"(
    for i = 1, 2000 do local h = mpm.history.fn(function(t) return i * t end); assert(h:at(1) == i) end
    collectgarbage("collect"); collectgarbage("collect")
  )";
  REQUIRE(f.error_of(histories) == "");
  const auto first = registry_length();
  REQUIRE(f.error_of(histories) == "");
  const auto second = registry_length();
  CAPTURE(first, second);
  CHECK(first > 100);          // they were held
  CHECK(second < first + 50);  // and released: without the release + 2000
}

TEST_CASE("a history kept by C++ after lua_close refuses to run and is released safely", "[lua][boundary][history]") {
  std::shared_ptr<const seismpm::History> kept;
  {
    LuaFixture f;
    REQUIRE(f.error_of("h = mpm.history.fn(function(t) return t + 1 end)") == "");
    lua_State* L = f.runtime.state();
    lua_getglobal(L, "h");
    kept = seismpm::lua::to_history(L, -1, "h");
    lua_pop(L, 1);
    CHECK(kept->at(1.0) == 2.0);
  }  // lua_close
  CHECK_THROWS_WITH(kept->at(1.0), Contains("the Lua state of this function is closed"));
  kept.reset();  // no unref into the freed state (AddressSanitizer would see it)
}

TEST_CASE("deep recursion through the bindings ends in a clean error", "[lua][boundary]") {
  // Each level: Lua -> h:at (C++) -> the function on the main thread -> Lua -> ...
  CHECK_THAT(run("h = mpm.history.fn(function(t) return h:at(t) end) h:at(1)"),
             Contains("history function failed at t = 1") && Contains("stack overflow"));
  CHECK_THAT(run(R"(
    local m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
    local mat = mpm.material.linear_elastic{ density = 1000, young = 1e6, poisson = 0.3 }
    local b = m:body{ material = mat, shape = mpm.shape.rectangle{0.2, 0.2, 0.4, 0.4} }
    local function v(x, y) b:set_velocity(v); return 0, 0 end
    b:set_velocity(v)
  )"),
             Contains("the velocity function failed") && Contains("may not set velocities"));  // before any depth
  // Deep plain Lua recursion with a binding at the bottom, then past Lua's limit.
  CHECK(run(R"(
    local function deep(n) if n == 0 then return mpm.shape.rectangle{0, 0, 1, 1} end return (deep(n - 1)) end
    assert(deep(10000):contains{0.5, 0.5})
    local function forever(n) return 1 + forever(n + 1) + (mpm.shape.rectangle{0, 0, 1, 1} and 0) end
    local ok, err = pcall(forever, 1)
    assert(not ok and err:find("stack overflow"), err)
  )") == "");
}

TEST_CASE("console support in the runtime: values shown even when __tostring fails, completion raw",
          "[lua][boundary][console]") {
  LuaFixture f;
  std::string out;
  using Entry = seismpm::lua::Runtime::Entry;
  CHECK(f.runtime.run_entry(std::string(kHostile), out) == Entry::Done);
  CHECK(f.runtime.run_entry("1 + 1, 'a'", out) == Entry::Done);
  CHECK(out == "2\t\"a\"");
  CHECK(f.runtime.run_entry("evil()", out) == Entry::Done);
  CHECK(out == "(a value that cannot be shown)");
  CHECK(f.runtime.run_entry("for i = 1, 2 do", out) == Entry::Incomplete);
  CHECK(f.runtime.run_entry("error('boom')", out) == Entry::Failed);
  CHECK_THAT(out, Contains("stdin:1: boom") && Contains("traceback"));
  CHECK(f.runtime.run_entry("setmetatable(_G, hostile)", out) == Entry::Done);
  const auto matches = f.runtime.complete("mpm.mat");
  REQUIRE(matches.size() == 1);
  CHECK(matches[0] == "mpm.material");
}

TEST_CASE("hostile values in every argument of every function: errors or results, never a crash",
          "[lua][boundary][fuzz]") {
  CHECK(run(R"(
    local m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
    local mat = mpm.material.linear_elastic{ density = 1000, young = 1e6, poisson = 0.3 }
    local blk = m:body{ material = mat, shape = mpm.shape.rectangle{0.2, 0.2, 0.6, 0.6} }
    local co = coroutine.create(function() end)
    local values = { evil(), evil{1, 2}, evil{evil{0, 0}, evil{1, 1}}, evil{ domain = evil(), cell = evil() },
                     evil{ name = evil(), material = evil(), shape = evil(), file = evil(), duration = evil() },
                     setmetatable({}, { __name = print }), co, io.stdout, 2^63, -0.0, 1/0, "", blk, mat }
    local objects = { m = m, blk = blk, mat = mat, shape = mpm.shape.rectangle{0, 0, 1, 1},
                      h = mpm.history.table{{0, 0}, {1, 1}}, p = m:probe{ body = blk, at = {0.5, 0.5} } }
    local calls, bad = 0, nil
    local function try(name, f, ...)
      calls = calls + 1
      local ok, err = pcall(f, ...)
      if not ok and tostring(err):find("hostile __") then bad = bad or (name .. ": " .. err) end
    end
    local skip = { run = true, step = true, gravity_phase = true, dynamic_phase = true, output = true, plot = true }
    for _, t in pairs{ mpm, mpm.material, mpm.shape, mpm.history } do
      for name, f in pairs(t) do
        if type(f) == "function" and name ~= "plot" and name:sub(1, 1) ~= "_" then  -- not the Lua library
          for _, a in ipairs(values) do
            try(name, f, a)
            for _, b in ipairs(values) do try(name, f, a, b) end
          end
        end
      end
    end
    for _, obj in pairs(objects) do
      for name, f in pairs(getmetatable(obj).__index) do
        if not skip[name] then for _, a in ipairs(values) do try(name, f, obj, a); try(name, f, a, obj) end end
      end
    end
    assert(calls > 2000, "calls " .. calls)
    assert(not bad, "a binding ran a metamethod: " .. tostring(bad))
  )") == "");
}

TEST_CASE("the Lua library checks its calls against the same key tables, at the script's line", "[lua][boundary]") {
  LuaFixture f;
  CHECK_THAT(
      f.error_of(
          "local s = 1\nmpm.geometry.slope{ left = 0, right = 1, crest = {0.3, 0.5}, toe_level = 0.2, angle = 95 }"),
      Contains("test:2: mpm.geometry.slope: key 'angle' must be in (0, 90) (degrees), got 95"));
  CHECK_THAT(
      f.error_of("mpm.geometry.layers{ left = 0, rigth = 1, {top = 1} }"),
      Contains("test:1: mpm.geometry.layers: unknown key 'rigth' (allowed: left, right, base, positional entries)"));
  CHECK_THAT(f.error_of("mpm.geometry.slope(evil)"),
             Contains("mpm.geometry.slope: expects a table of named arguments"));
  CHECK(f.error_of(R"(
    local layers = mpm.geometry.layers{ left = 0, right = 2, {top = 1}, {top = 3, name = "sand"} }
    assert(#layers == 2 and layers[2].name == "sand" and layers[1].shape:contains{1, 0.5})  -- base defaults to 0
  )") == "");
}

TEST_CASE("a script runs after a chunk that made the globals hostile", "[lua][boundary]") {
  const std::string file = "/tmp/seismpm_test_boundary_args.lua";
  {
    std::FILE* out = std::fopen(file.c_str(), "w");
    std::fputs("assert(rawget(_G, 'arg')[1] == 'word')\n", out);
    std::fclose(out);
  }
  LuaFixture f;
  REQUIRE(f.error_of("setmetatable(_G, { __newindex = function() error('hostile __newindex', 0) end })") == "");
  CHECK(f.runtime.run_file(file, {"word"}));  // `arg` set raw, outside any protected call
}

TEST_CASE("a call whose keys all have defaults needs no table; one with a required key still names it",
          "[lua][boundary]") {
  seismpm::test::LuaFixture f;
  REQUIRE(f.error_of(R"(
    m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
    local soil = mpm.material.linear_elastic{ density = 2000, young = 1e7, poisson = 0.3 }
    m:body{ name = "block", material = soil, shape = mpm.shape.rectangle{ 0, 0, 1, 0.5 } }
    m:fix{ side = "bottom" }
    eq = m:gravity_phase()
    t = eq.time
  )") == "");
  CHECK(f.number("t") > 0.0);  // it ran, with the default tolerance
  CHECK(f.error_of("m:gravity_phase(nil)") == "");
  CHECK(f.error_of("mpm.model()").find("expects a table of named arguments") != std::string::npos);
  CHECK(f.error_of("m:gravity_phase(3)").find("expects a table of named arguments { key = value, ... }, got number") !=
        std::string::npos);
}
