// The Lua API driving the kernel: good scripts give the physics, bad ones a named error.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "lua_fixture.hpp"

using seismpm::test::LuaFixture;

namespace {
const char* kBlock = R"(
  m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.05, gravity = {0, -9.81} }
  mat = mpm.material.linear_elastic{ density = 2000, young = 1e7, poisson = 0.3 }
  blk = m:body{ name = "block", material = mat, shape = mpm.shape.rectangle{ 0.3, 0.5, 0.7, 0.9 } }
)";
}

TEST_CASE("a free-falling block in Lua drops 0.5 g t^2", "[lua][model]") {
  LuaFixture f;
  const std::string error = f.error_of(std::string(kBlock) + R"(
    local y0, dt = blk:centroid()[2], m:dt()  -- the CFL step before the run: the largest one
    p = m:probe{ name = "top", body = blk, at = {0.5, 0.9}, every = 0.01 }
    m:run{ duration = 0.2 }
    -- Symplectic Euler: v exact, the drop between 0.5 g t^2 and 0.5 g t (t + dt).
    local drop = y0 - blk:centroid()[2]
    assert(drop > 0.5 * 9.81 * 0.2^2 and drop < 0.5 * 9.81 * 0.2 * (0.2 + 1.01 * dt), "drop " .. drop)
    assert(math.abs(m:time() - 0.2) < 1e-12, "time " .. m:time())
    assert(blk:count() == 256 and m:count() == 256, "count " .. blk:count())
    local t, uy = p:series("uy")
    assert(#t == 21 and #uy == 21, "samples " .. #t)
    assert(math.abs(uy[#uy] - p:get("uy")) < 1e-15)
    assert(math.abs(uy[#uy] + drop) < 1e-12, "probe uy " .. uy[#uy])
    local vy = blk:field("vy")
    assert(#vy == 256 and math.abs(vy[1] + 9.81 * 0.2) < 1e-9, "vy " .. vy[1])
    local e = m:energy()
    assert(math.abs(e.kinetic - 0.5 * 2000 * 0.16 * (9.81 * 0.2)^2) < 1e-6 * e.kinetic, "kinetic " .. e.kinetic)
    assert(m:steps() > 10 and m:dt() > 0)
    assert(tostring(m):find("256 particles") and tostring(blk):find("block"))
  )");
  CHECK(error == "");
}

TEST_CASE("a run's call comes at its times, takes the same steps as chunked runs, and can end the run",
          "[lua][model]") {
  LuaFixture f;
  const std::string error = f.error_of(std::string(kBlock) + R"(
    local function fresh()
      local m2 = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.05 }
      local b2 = m2:body{ name = "block", material = mat, shape = mpm.shape.rectangle{ 0.3, 0.5, 0.7, 0.9 } }
      return m2, b2
    end
    -- Calls every 0.05 s and at the end (0.12 is not a multiple).
    local times = {}
    m:run{ duration = 0.12, every = 0.05, call = function(model) times[#times + 1] = model:time() end }
    assert(#times == 3, "calls " .. #times)
    for k, t in ipairs{ 0.05, 0.10, 0.12 } do assert(math.abs(times[k] - t) < 1e-12, "call " .. k .. " at " .. times[k]) end
    -- The same steps as a script that runs in chunks: bit-identical state.
    local a, ablk = fresh()
    a:run{ duration = 0.05 }; a:run{ duration = 0.05 }; a:run{ duration = 0.02 }
    assert(a:steps() == m:steps(), "steps " .. a:steps() .. " vs " .. m:steps())
    local y1, y2 = blk:field("y"), ablk:field("y")
    for i = 1, #y1 do assert(y1[i] == y2[i], "particle " .. i .. " differs") end
    -- Returning true ends the run at that call.
    local b = fresh()
    b:run{ duration = 1, every = 0.02, call = function(model) return model:time() > 0.05 end }
    assert(math.abs(b:time() - 0.06) < 1e-12, "stopped at " .. b:time())
    -- The dynamic phase takes them too; its calls see the phase clock.
    local c = fresh()
    c:run{ duration = 0.01 }
    local phase_times = {}
    c:dynamic_phase{ duration = 0.04, every = 0.02, call = function(model) phase_times[#phase_times + 1] = model:phase_time() end }
    assert(#phase_times == 2 and math.abs(phase_times[2] - 0.04) < 1e-12, "phase calls " .. #phase_times)
  )");
  CHECK(error == "");
}

TEST_CASE("a run's call: bad keys and failing calls are named, and the model stays usable", "[lua][errors]") {
  LuaFixture f;
  CHECK_THAT(f.error_of(std::string(kBlock) + "m:run{ duration = 1, every = 0.1 }"),
             Catch::Contains("key 'every' needs key 'call'"));
  CHECK_THAT(f.error_of(std::string(kBlock) + "m:run{ duration = 1, call = print }"),
             Catch::Contains("key 'call' needs key 'every'"));
  CHECK_THAT(f.error_of(std::string(kBlock) + "m:run{ duration = 1, every = 0.1, call = 5 }"),
             Catch::Contains("key 'call' must be a function"));
  CHECK_THAT(f.error_of(std::string(kBlock) + "m:run{ duration = 1, every = -1, call = print }"),
             Catch::Contains("key 'every' must be > 0"));
  CHECK_THAT(f.error_of(std::string(kBlock) + "m:dynamic_phase{ duration = 1, every = 0.1 }"),
             Catch::Contains("key 'every' needs key 'call'"));
  const std::string error = f.error_of(std::string(kBlock) + R"(
    local ok, err = pcall(function() m:run{ duration = 0.1, every = 0.02, call = function() error("no data here") end } end)
    assert(not ok and err:find("the run's call failed at t = 0.02") and err:find("no data here"), err)
    ok, err = pcall(function() m:run{ duration = 0.1, every = 0.02, call = function(model) model:run{ duration = 1 } end } end)
    assert(not ok and err:find("may not step the model"), err)
    ok, err = pcall(function() m:run{ duration = 0.1, every = 0.02, call = function(model) model:dynamic_phase{ duration = 1 } end } end)
    assert(not ok and err:find("may not start a phase"), err)
    local t = m:time()
    m:run{ duration = 0.01 }
    assert(math.abs(m:time() - t - 0.01) < 1e-12, "the model runs on after a failed call")
  )");
  CHECK(error == "");
}

TEST_CASE("a concave polygon is filled exactly where it is", "[lua][shape]") {
  LuaFixture f;
  const std::string error = f.error_of(R"(
    local m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.02 }
    local mat = mpm.material.linear_elastic{ density = 1000, young = 1e6, poisson = 0.2 }
    -- An L: the square [0.1, 0.9]^2 without its upper-right quarter [0.5, 0.9]^2, clockwise.
    local L = mpm.shape.polygon{ {0.1, 0.1}, {0.1, 0.9}, {0.5, 0.9}, {0.5, 0.5}, {0.9, 0.5}, {0.9, 0.1} }
    assert(L:contains{0.3, 0.7} and not L:contains{0.7, 0.7} and L:contains{0.7, 0.3})
    local b = m:body{ material = mat, shape = L, ppc = 2 }
    local area = 0.8 * 0.8 - 0.4 * 0.4
    assert(b:count() == math.floor(area / 0.01^2 + 0.5), "count " .. b:count())
    for _, x in ipairs(b:field("x")) do end
    local xs, ys = b:field("x"), b:field("y")
    for i = 1, #xs do assert(not (xs[i] > 0.5 and ys[i] > 0.5), "particle in the notch") end
    local band = m:body{ name = "band", material = mat, ppc = 1,
                         shape = mpm.shape.polyline{ {0.05, 0.95}, {0.95, 0.95}, thickness = 0.03 } }
    assert(band:count() == 46, "band " .. band:count())  -- one row, x = 0.05 .. 0.95
    local slope = mpm.geometry.slope{ left = 0, right = 0.9, crest = {0.35, 0.53}, toe_level = 0.2, angle = 45 }
    assert(slope:contains{0.1, 0.5} and not slope:contains{0.8, 0.3} and slope:contains{0.8, 0.19})
    local layers = mpm.geometry.layers{ left = 0, right = 1, {top = 0.2, name = "clay"}, {top = 0.5} }
    assert(#layers == 2 and layers[1].name == "clay" and layers[2].name == "layer2")
  )");
  CHECK(error == "");
}

TEST_CASE("histories and parameters", "[lua][history]") {
  LuaFixture f;
  f.session.params["cell"] = "0.05";
  f.session.params["rough"] = "true";
  f.session.params["name"] = "slope";
  const std::string csv = "/tmp/seismpm_test_history.csv";
  {
    std::FILE* out = std::fopen(csv.c_str(), "w");
    std::fputs("# a table velocity\nt, vx\n0, 0\n1, 0.5\n2, 0.5\n", out);
    std::fclose(out);
  }
  const std::string error = f.error_of(R"(
    local h = mpm.history.table{ {0, 0}, {1, 2}, {3, 2} }
    assert(h:at(0.5) == 1 and h:at(2) == 2 and h:at(-1) == 0 and h:at(4) == 0)
    local c = mpm.history.csv{ file = "/tmp/seismpm_test_history.csv", time = "t", value = "vx", scale = 2, shift = 1 }
    assert(math.abs(c:at(1.5) - 0.5) < 1e-15 and c:at(2) == 1 and c:at(0.5) == 0)
    local s = mpm.history.fn(function(t) return 3 * t end)
    assert(s:at(2) == 6)
    assert(mpm.param("cell", 0.1) == 0.05 and mpm.param("rough", false) == true)
    assert(mpm.param("name", "x") == "slope" and mpm.param("missing", 7) == 7)
    assert(tostring(c):find("3 points"))
  )");
  CHECK(error == "");
  f.session.params["cell"] = "fine";
  CHECK_THAT(f.error_of("mpm.param('cell', 0.1)"), Catch::Contains("--set cell=fine: a number is expected"));
}

TEST_CASE("bad input gives an error naming the key and the range", "[lua][errors]") {
  using Catch::Contains;
  const char* domain = "domain = {{0, 0}, {1, 1}}";
  struct Case {
    std::string code, expected;
  };
  const std::string mat = "mat = mpm.material.linear_elastic{ density = 1000, young = 1e6, poisson = 0.3 } ";
  const std::string model = std::string("m = mpm.model{ ") + domain + ", cell = 0.1 } " + mat;
  const std::string rigid_pair =
      "b = m:body{ name = 'b', material = mat, shape = mpm.shape.rectangle{0.2, 0.2, 0.6, 0.6} } "
      "r = m:rigid{ name = 'r', shape = mpm.shape.rectangle{0, 0, 1, 0.2} } ";
  const std::vector<Case> cases = {
      {std::string("mpm.model{ ") + domain + ", cell = 0.1, foo = 1 }",
       "mpm.model: unknown key 'foo' (allowed: domain"},
      {"mpm.model{ cell = 0.1 }", "mpm.model: missing key 'domain'"},
      {std::string("mpm.model{ ") + domain + " }", "missing key 'cell'"},
      {std::string("mpm.model{ ") + domain + ", cell = 'fine' }", "key 'cell' must be a number, got string"},
      {std::string("mpm.model{ ") + domain + ", cell = 0 }", "key 'cell' must be > 0 (m), got 0"},
      {std::string("mpm.model{ ") + domain + ", cell = 0.1, shape = 'cubic' }",
       "key 'shape' must be one of linear|gimp"},
      {std::string("mpm.model{ ") + domain + ", cell = 0.1, cfl = 2 }", "key 'cfl' must be in (0, 1], got 2"},
      {"mpm.model{ domain = {{0, 0}, {0, 1}}, cell = 0.1 }", "key 'domain' is empty"},
      {"mpm.model{ domain = {{0, 0, 0}, {1, 1, 1}}, cell = 0.1 }", "3D models are not available"},
      {"mpm.model(5)", "expects a table of named arguments"},
      {std::string("mpm.model{ ") + domain + ", cell = 0.1, cfl = 0 }", "key 'cfl' must be in (0, 1], got 0"},
      {std::string("mpm.model{ ") + domain + ", cell = 0.1, max_dilation = 0.5 }",
       "key 'max_dilation' must be 0 or >= 1, got 0.5"},
      {std::string("mpm.model{ ") + domain + ", cell = 0.1, crack_closure = 'no' }",
       "key 'crack_closure' must be true or false, got string"},
      {std::string("mpm.model{ ") + domain + ", cell = 0.1, cell_volumetric_strain = 0 }",
       "key 'cell_volumetric_strain' must be true or false, got number"},
      // The kernel's rule, in the kernel: at least 2 cells after rounding up (Grid, Model).
      {"mpm.model{ domain = {{0, 0}, {1, 0.1}}, cell = 0.1 }",
       "mpm.model: model: the domain must span at least 2 cells"},
      {"mpm.material.linear_elastic{ density = 1000, young = 0, poisson = 0.3 }", "key 'young' must be > 0 (Pa)"},
      {"mpm.material.linear_elastic{ density = 1000, young = 1e6, poisson = 0.5 }",
       "key 'poisson' must be in [0, 0.5)"},
      {"mpm.material.linear_elastic{ density = 1000, young = 1e6, poisson = -0.1 }",
       "key 'poisson' must be in [0, 0.5)"},
      {"mpm.material.linear_elastic{ density = -1, young = 1e6, poisson = 0.3 }", "key 'density' must be > 0"},
      {"mpm.material.mohr_coulomb{ density = 1680, young = 2.57e6, poisson = 0.33, friction = 90 }",
       "key 'friction' must be in [0, 90) (degrees)"},
      {"mpm.material.mohr_coulomb{ density = 1680, young = 2.57e6, poisson = 0.33, friction = 23, dilation = 30 }",
       "key 'dilation' must be in [0, 23]"},
      {"mpm.material.mohr_coulomb{ density = 1680, young = 2.57e6, poisson = 0.33, friction = 23, cohesion = -1 }",
       "key 'cohesion' must be >= 0 (Pa)"},
      {"mpm.material.mohr_coulomb{ density = 1680, young = 2.57e6, poisson = 0.33, friction = 23, cohesion = 780, "
       "tension = 5000 }",
       "key 'tension' must be in [0, c cot(phi)"},
      {"mpm.material.mohr_coulomb{ density = 1680, young = 2.57e6, poisson = 0.33, friction = 0 }",
       "'cohesion' and 'friction' cannot both be zero"},
      {"mpm.material.mohr_coulomb{ density = 1680, young = 2.57e6, poisson = 0.33, friction = 23, softening = { "
       "friction = 30, strain = 0.1 } }",
       "key 'softening.friction' must be in [0, 23]"},
      {"mpm.material.mohr_coulomb{ density = 1680, young = 2.57e6, poisson = 0.33, friction = 23, softening = { "
       "friction = 10 } }",
       "missing key 'strain'"},
      {"mpm.material.mohr_coulomb{ density = 1680, young = 2.57e6, poisson = 0.33, friction = 23, softening = { "
       "frction = 10 } }",
       "unknown key 'frction'"},
      {"mpm.material.drucker_prager{ density = 1680, young = 2.57e6, poisson = 0.33, friction = 23, fit = 'middle' }",
       "key 'fit' must be one of plane_strain|outer|inner"},
      {"mpm.shape.polygon{ {0, 0}, {1, 0} }", "polygon needs at least 3 points"},
      {"mpm.shape.polygon{ {0, 0}, {1, 1}, {1, 0}, {0, 1} }", "self-intersecting"},
      {"mpm.shape.polygon{ {0, 0}, {1, 'a'}, {1, 0} }", "point 2 must be a point {x, y} of numbers"},
      {"mpm.shape.rectangle{ 1, 0, 0, 1 }", "x0 < x1"},
      {"mpm.shape.polyline{ {0, 0}, {1, 0}, thickness = 0 }", "key 'thickness' must be > 0"},
      {model + "m:body{ material = mat, shape = mpm.shape.rectangle{0.5, 0.5, 1.5, 0.9} }",
       "reaches outside the domain"},
      {model + "m:body{ material = mat, shape = mpm.shape.rectangle{0.1, 0.1, 0.5, 0.5}, ppc = 0 }",
       "key 'ppc' must be in [1, 16], got 0"},
      {model + "m:body{ material = mat, shape = mpm.shape.rectangle{0.1, 0.1, 0.5, 0.5}, ppc = 17 }",
       "key 'ppc' must be in [1, 16], got 17"},
      {model + "m:body{ material = mat, shape = mpm.shape.rectangle{0.1, 0.1, 0.5, 0.5}, ppc = 2.5 }",
       "key 'ppc' must be a whole number, got 2.5"},
      {model + "m:body{ shape = mpm.shape.rectangle{0.1, 0.1, 0.5, 0.5} }",
       "key 'material' must be a material, got nil"},
      {model + "m:body{ material = 5, shape = mpm.shape.rectangle{0.1, 0.1, 0.5, 0.5} }",
       "key 'material' must be a material, got number"},
      {model + "m:body{ material = mat }", "missing key 'shape'"},
      {model + "m:body{ material = mat, shape = mpm.shape.rectangle{0.1, 0.1, 0.11, 0.11} }", "holds no particle"},
      {model + "m:body{ name = 'a', material = mat, shape = mpm.shape.rectangle{0.1, 0.1, 0.5, 0.5} }"
               "m:body{ name = 'a', material = mat, shape = mpm.shape.rectangle{0.6, 0.6, 0.9, 0.9} }",
       "a body called 'a' exists"},
      {model + "m:fix{ side = 'up' }", "key 'side' must be one of left|right|bottom|top, got 'up'"},
      {model + "m:fix{ side = 'left', dof = 'z' }", "key 'dof' must be one of x|y|xy"},
      // Edge boundaries.
      {model + "m:boundary{ side = 'bottom', kind = 'sponge' }",
       "key 'kind' must be one of absorbing|compliant|free_field, got 'sponge'"},
      {model + "m:boundary{ kind = 'absorbing' }", "missing key 'side'"},
      {model + "m:boundary{ side = 'bottom', kind = 'compliant', density = 2400, vs = 800 }",
       "key 'vp': a compliant edge needs the half-space below it"},
      {model + "m:boundary{ side = 'bottom', kind = 'absorbing', vs = 800 }",
       "key 'density': give density, vs and vp together"},
      {model + "m:boundary{ side = 'bottom', kind = 'absorbing', density = 2000, vs = 800, vp = 500 }",
       "key 'vp': it must exceed vs"},
      {model + "m:boundary{ side = 'bottom', kind = 'absorbing', density = -1, vs = 1, vp = 2 }",
       "key 'density' must be > 0"},
      {model + "m:boundary{ side = 'bottom', kind = 'absorbing', input = { 1, 0 } }",
       "key 'input': only a compliant edge takes an input motion"},
      {model + "m:boundary{ side = 'left', kind = 'absorbing', frame = 'fixed' }",
       "key 'frame': only a compliant edge moves the frame"},
      {model +
           "m:boundary{ side = 'bottom', kind = 'compliant', density = 2400, vs = 800, vp = 1400, input = { 'x', 0 } }",
       "key 'input' vx"},
      {model + "m:boundary{ side = 'bottom', kind = 'free_field' }", "a free_field edge is a lateral side"},
      {model + "m:boundary{ side = 'bottom', kind = 'compliant', density = 1e308, vs = 1e308, vp = 1.7e308 }",
       "the impedance density * vp overflows"},
      {model + "b = m:body{ material = mat, shape = mpm.shape.rectangle{0.1, 0.1, 0.5, 0.5} } "
               "m:boundary{ side = 'bottom', kind = 'compliant', density = 2400, vs = 800, vp = 1400, "
               "input = { mpm.history.fn(function(t) return 0/0 end), 0 } } m:run{ duration = 0.01 }",
       "boundary on the bottom edge: its input velocity x is"},
      {model + "m:boundary{ side = 'left', kind = 'absorbing' } m:boundary{ side = 'left', kind = 'free_field' }",
       "that side has a boundary already"},
      {model + "m:fix{ side = 'left', dof = 'x' } m:boundary{ side = 'left', kind = 'absorbing' }", "held by m:fix"},
      {model + "m:boundary{ side = 'left', kind = 'absorbing' } m:fix{ side = 'left', dof = 'x' }",
       "key 'side': the left edge is a boundary (m:boundary, kind absorbing)"},
      {model + "m:run{ duration = -1 }", "key 'duration' must be > 0 (s)"},
      {model + "m:step(0)", "whole number >= 1"},
      {model + "m:probe{ at = {0.5, 0.5} }", "key 'body' must be a body, got nil"},
      {model + "b = m:body{ material = mat, shape = mpm.shape.rectangle{0.1, 0.1, 0.5, 0.5} } b:field('speed')",
       "unknown field 'speed'"},
      {model + "b = m:body{ material = mat, shape = mpm.shape.rectangle{0.1, 0.1, 0.5, 0.5} } b:set_velocity{5, 0} "
               "m:run{ duration = 1 }",
       "left the grid"},
      // Contact and rigid bodies.
      {model + rigid_pair + "m:contact{ b, r, friction = -0.1 }", "key 'friction' must be >= 0"},
      {model + rigid_pair + "m:contact{ b, r }", "missing key 'friction'"},
      {model + rigid_pair + "m:contact{ b, r, friction = 0.3 } m:contact{ r, b, friction = 0.5 }",
       "the pair 'r', 'b' is declared already"},
      {model + rigid_pair + "m:contact{ b, b, friction = 0.3 }", "body 'b' cannot be in contact with itself"},
      {model + rigid_pair + "m:contact{ b, 'r', friction = 0.3 }", "the second body must be a body, got string"},
      {model + rigid_pair + "m:contact{ b, friction = 0.3 }", "name the two bodies"},
      {model + rigid_pair + "m:set_friction{ b, r, friction = 0.3 }", "no contact is declared between 'b' and 'r'"},
      {model + rigid_pair + "m:contact{ b, r, friction = 0.3 } m:set_friction{ b, r, friction = -1 }",
       "key 'friction' must be >= 0"},
      {model + rigid_pair +
           "m2 = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 } "
           "o = m2:body{ material = mat, shape = mpm.shape.rectangle{0.1, 0.1, 0.5, 0.5} } m:contact{ b, o, friction = "
           "0 }",
       "the second body belongs to another model"},
      {model + "m:rigid{ shape = mpm.shape.rectangle{-0.5, 0, 0.5, 0.1} }", "key 'shape': rectangle"},
      {model + "m:rigid{ shape = mpm.shape.rectangle{0, 0, 0.5, 0.1}, velocity = {'fast', 0} }",
       "key 'velocity' vx must be a number or a history (mpm.history.*), got string"},
      {model + "m:rigid{ shape = mpm.shape.rectangle{0, 0, 0.5, 0.1}, velocity = 2 }",
       "key 'velocity' must be {vx, vy}: two numbers (m/s) or histories, got number"},
      {model + "m:rigid{ shape = mpm.shape.rectangle{0, 0, 0.5, 0.1}, velocity = {0, 0/0} }",
       "key 'velocity' vy must be finite"},
      {model + rigid_pair + "b:reaction()", "body 'b' is not rigid"},
      {model + rigid_pair + "r:set_velocity{ 50, 0 } m:run{ duration = 1 }",
       "is about to leave the grid: rigid body 'r' moves at (50, 0) m/s"},
      {"mpm.plot{ file = '/nonexistent.csv', x = 't', y = {'v'} }", "/nonexistent.csv cannot be opened"},
      {"mpm.plot{ file = '/nonexistent.csv', x = 't' }", "missing key 'y'"},
      {"mpm.history.table{ {0, 0}, {1, 1}, {1, 2} }", "times must increase (point 3)"},
      {"mpm.history.csv{ file = '/nonexistent.csv', value = 'v' }", "/nonexistent.csv: cannot open"},
      {"mpm.history.fn(5)", "expects a function of time"},
      {"mpm.history.table{ {0, 0} }:at('x')", "expects a time t (s), got string"},
      {model + "local time = getmetatable(m).__index.time; time(5)", "self must be a model, got number"},
  };
  for (const auto& c : cases) {
    LuaFixture f;
    CAPTURE(c.code);
    const std::string error = f.error_of(c.code);
    CHECK_THAT(error, Contains(c.expected) && Contains("test:1:"));
  }
}

TEST_CASE("the ranges are the kernel's: cfl above 0 and up to 1, ppc 1..16, a domain of 1.5 cells", "[lua][errors]") {
  LuaFixture f;
  CHECK(f.error_of(R"(
    -- 1.5 cells round up to 2, as Grid and Model take them.
    local m = mpm.model{ domain = {{0, 0}, {0.15, 1}}, cell = 0.1, cfl = 1e-7 }
    assert(tostring(m):find("2 x 10 cells"), tostring(m))
    local mat = mpm.material.linear_elastic{ density = 1000, young = 1e6, poisson = 0.3 }
    local b = m:body{ material = mat, shape = mpm.shape.rectangle{0, 0, 0.1, 0.1}, ppc = 16 }
    assert(b:count() == 256, "count " .. b:count())
    mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1, cfl = 1 }  -- the upper end is in
  )") == "");
}

TEST_CASE("a rigid base and frictional contact from Lua", "[lua][contact]") {
  LuaFixture f;
  const auto dir = std::filesystem::temp_directory_path() / "seismpm_lua_rigid";
  std::filesystem::remove_all(dir);
  const std::string error = f.error_of(R"(
    local m = mpm.model{ domain = {{-1, -0.2}, {2, 1}}, cell = 0.1 }
    local mat = mpm.material.linear_elastic{ density = 1000, young = 1e7, poisson = 0.3 }
    local blk = m:body{ name = "block", material = mat, shape = mpm.shape.rectangle{0, 0, 0.5, 0.5} }
    local base = m:rigid{ name = "base", ppc = 1, velocity = {mpm.history.table{{0, 0}, {10, 0}}, 0},
                          shape = mpm.shape.polyline{ {-0.9, -0.05}, {1.5, -0.05}, thickness = 0.1 } }
    assert(base:count() == 26, "base " .. base:count())  -- x = -0.95 .. 1.55: the band's ends are round
    assert(tostring(base):find("rigid body 'base'"))
    m:contact{ blk, base, friction = 0.5 }
    m:output{ dir = ")" + dir.string() +
                                       R"(", every = 0.1 }
    m:run{ duration = 0.5, damping = 0.7 }
    local f = base:reaction()
    assert(math.abs(f[2] - 1000 * 9.81 * 0.25) < 0.02 * 1000 * 9.81 * 0.25, "reaction " .. f[2])
    base:set_velocity{ 1, 0 }
    m:set_friction{ blk, base, friction = 0 }  -- smooth from now on: the base slides away underneath
    local x0, b0 = base:centroid()[1], blk:centroid()[1]
    m:run{ duration = 0.2 }
    assert(math.abs(base:centroid()[1] - x0 - 0.2) < 1e-9, "the base moves at its velocity")
    assert(math.abs(blk:centroid()[1] - b0) < 1e-3, "the block stays: " .. blk:centroid()[1] - b0)
  )");
  CHECK(error == "");
  const auto csv = dir / "reactions.csv";
  REQUIRE(std::filesystem::exists(csv));
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  CHECK(header == "time (s),phase,base.fx (N/m),base.fy (N/m)");
}

TEST_CASE("a block on a 22-degree rigid incline slides as Coulomb says, or sticks", "[lua][contact][verification]") {
  // The incline is a one-sided polyline band: its particles carry the line's normal, so contact follows
  // the true surface, not the grid's staircase of cells (with normals from the cells a block locked).
  const std::string setup = R"(
    function incline(mu, gravity_first)
      local th = math.rad(22)
      local m = mpm.model{ domain = {{-1, -1}, {12.5, 5.5}}, cell = 0.1 }
      local mat = mpm.material.linear_elastic{ density = 2000, young = 5e7, poisson = 0.3 }
      local function y_of(x) return (10 - x) * math.tan(th) end
      local c, s = math.cos(th), math.sin(th)
      local p = {1.0, y_of(1.0)}
      local blk = m:body{ name = "blk", material = mat, shape = mpm.shape.polygon{ {p[1], p[2]}, {p[1] + c, p[2] - s},
                          {p[1] + c + 0.5 * s, p[2] - s + 0.5 * c}, {p[1] + 0.5 * s, p[2] + 0.5 * c} } }
      local surface = m:rigid{ name = "incline", ppc = 1,
                               shape = mpm.shape.polyline{ {-0.3, y_of(-0.3)}, {11.5, y_of(11.5)}, thickness = 0.2, side = "right" } }
      m:contact{ blk, surface, friction = mu }
      if gravity_first then m:gravity_phase{ max_time = 5 } end
      local c0 = blk:centroid()
      m:dynamic_phase{ duration = 1.0 }
      local c1 = blk:centroid()
      return math.sqrt((c1[1] - c0[1])^2 + (c1[2] - c0[2])^2), 0.5 * 9.81 * (s - mu * c)
    end
  )";
  for (double mu : {0.0, 0.2}) {
    LuaFixture f;
    CAPTURE(mu);
    CHECK(f.error_of(setup + "local d, exact = incline(" + std::to_string(mu) +
                     ", false) print(string.format('incline mu = %g: %.4f m, exact %.4f m', " + std::to_string(mu) +
                     ", d, exact)) assert(math.abs(d - exact) < 0.02 * exact, d .. ' vs ' .. exact)") == "");
  }
  LuaFixture f;
  CHECK(f.error_of(setup + "local d = incline(0.5, true) assert(d < 1e-3, 'slipped ' .. d)") == "");
}

TEST_CASE("soil models from Lua: a dry sand column spreads and stays finite", "[lua][materials]") {
  LuaFixture f;
  const std::string error = f.error_of(R"(
    local m = mpm.model{ domain = {{0, 0}, {0.5, 0.12}}, cell = 0.005 }
    local sand = mpm.material.mohr_coulomb{ density = 2650, young = 0.84e6, poisson = 0.3, friction = 19.8 }
    assert(sand:kind() == "mohr_coulomb" and tostring(sand):find("phi 19.8"))
    local col = m:body{ name = "sand", material = sand, shape = mpm.shape.rectangle{ 0, 0, 0.2, 0.1 } }
    m:fix{ side = "left", dof = "x" }
    m:fix{ side = "bottom", dof = "xy" }
    m:run{ duration = 0.3 }
    local xs, ys, yield = col:field("x"), col:field("y"), col:field("yield")
    local front, top, yielding = 0, 0, 0
    for i = 1, #xs do front = math.max(front, xs[i]); top = math.max(top, ys[i]); yielding = yielding + yield[i] end
    assert(front > 0.25, "the column did not spread: front at " .. front)
    assert(top < 0.1, "the column did not slump: top at " .. top)
    assert(yielding > 0, "no particle yielded")
    local dp = mpm.material.drucker_prager{ density = 2650, young = 0.84e6, poisson = 0.3, friction = 19.8, fit = "outer" }
    assert(dp:kind() == "drucker_prager")
  )");
  CHECK(error == "");
}

TEST_CASE("csv histories name the file and the line of bad data", "[lua][errors]") {
  const std::string file = "/tmp/seismpm_test_bad.csv";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"t, v\n0, 0\n1, x\n", ":3: column 'v' is not a number ('x')"},
      {"t, w\n0, 0\n", ":1: no column 'v' in the header (columns: t, w)"},
      {"t, v\n0, 0\n2, 1\n1, 2\n", ":4: times must increase"},
      {"", ": empty file"},
      {"t, v\n", ":1: no data rows"},
      {"t, v\n0\n", ":2: column 'v' is missing"},
  };
  for (const auto& [text, expected] : cases) {
    std::FILE* out = std::fopen(file.c_str(), "w");
    std::fputs(text.c_str(), out);
    std::fclose(out);
    LuaFixture f;
    CAPTURE(text);
    CHECK_THAT(f.error_of("mpm.history.csv{ file = '" + file + "', time = 't', value = 'v' }"),
               Catch::Contains(file + expected));
  }
}

TEST_CASE("no input, however wrong, crashes the program", "[lua][errors][fuzz]") {
  // Calls that write files (h:write_csv("x")) do so in a scratch directory.
  const auto scratch = std::filesystem::temp_directory_path() / "seismpm_fuzz";
  std::filesystem::create_directories(scratch);
  const auto cwd = std::filesystem::current_path();
  std::filesystem::current_path(scratch);
  struct Restore {
    std::filesystem::path dir;
    ~Restore() { std::filesystem::current_path(dir); }
  } restore{cwd};
  LuaFixture f;
  // Every function and method with every kind of wrong value: each must raise a Lua error or work.
  const std::string error = f.error_of(std::string(kBlock) + R"(
    local values = { "nil", 1, -1, 0, 1e308, 0/0, "x", {}, {1, 2, 3}, {{}}, {{1, 2}, {1}}, true, print,
                     {domain = 5}, {cell = -1}, {name = {}}, blk, m, mat, mpm.shape.rectangle{0, 0, 1, 1} }
    local objects = { m = m, blk = blk, mat = mat, shape = mpm.shape.rectangle{0, 0, 1, 1},
                      h = mpm.history.table{{0, 0}, {1, 1}}, p = m:probe{ body = blk, at = {0.5, 0.5} } }
    local calls = 0
    local function try(f, ...)
      calls = calls + 1
      pcall(f, ...)
    end
    local function each_function(t, seen)
      for _, f in pairs(t) do
        if type(f) == "function" and f ~= help then
          for _, a in ipairs(values) do
            if a == "nil" then a = nil end
            try(f, a)
            for _, b in ipairs(values) do try(f, a, b ~= "nil" and b or nil) end
          end
        elseif type(f) == "table" and not seen[f] then
          seen[f] = true
          each_function(f, seen)
        end
      end
    end
    each_function(mpm, {})
    for _, obj in pairs(objects) do
      local methods = getmetatable(obj).__index
      for name, f in pairs(methods) do
        if name ~= "run" and name ~= "step" then
          for _, a in ipairs(values) do try(f, obj, a ~= "nil" and a or nil); try(f, a ~= "nil" and a or nil) end
        end
      end
    end
    assert(calls > 2000, "calls " .. calls)
  )");
  CHECK(error == "");
}

TEST_CASE("console completion offers globals, fields and methods", "[lua][console]") {
  LuaFixture f;
  const std::string error = f.error_of(std::string(kBlock) + R"(
    local function has(list, x) for _, v in ipairs(list) do if v == x then return true end end return false end
    assert(has(mpm._complete("mpm.ma"), "mpm.material"))
    assert(has(mpm._complete("mpm.material.lin"), "mpm.material.linear_elastic"))
    assert(has(mpm._complete("m:ru"), "m:run") and not has(mpm._complete("m:ru"), "m:body"))
    assert(has(mpm._complete("blk:cen"), "blk:centroid"))
    assert(has(mpm._complete("hel"), "help"))
    assert(#mpm._complete("nothing.here") == 0)
  )");
  CHECK(error == "");
}

TEST_CASE("mpm.model's kernel switches reach the kernel: a collapsing sand column differs without them",
          "[lua][model]") {
  LuaFixture f;
  const std::string error = f.error_of(R"(
    -- The same 60 steps of a c = 0 column collapsing at a free right side, with each switch on and off:
    -- the volumetric averaging changes the stresses, crack closure the volumes of opened particles.
    local function run(keys)
      local settings = { domain = {{0, 0}, {0.4, 0.2}}, cell = 0.02 }
      for k, v in pairs(keys) do settings[k] = v end
      local m = mpm.model(settings)
      local sand = mpm.material.mohr_coulomb{ density = 2650, young = 0.84e6, poisson = 0.3, friction = 20 }
      local b = m:body{ name = "sand", material = sand, shape = mpm.shape.rectangle{ 0, 0, 0.1, 0.1 } }
      m:fix{ side = "left", dof = "x" }; m:fix{ side = "bottom", dof = "xy" }
      m:step(60)
      return b:field("syy"), b:field("volume")
    end
    local function same(a, b)
      for i = 1, #a do if a[i] ~= b[i] then return false end end
      return true
    end
    local s0, v0 = run{}
    local s1 = run{ cell_volumetric_strain = false }
    local _, v2 = run{ crack_closure = false }
    local s3 = run{ cell_volumetric_strain = true, crack_closure = true }
    assert(same(s0, s3), "the defaults are the switches on")
    assert(not same(s0, s1), "cell_volumetric_strain = false changed nothing")
    assert(not same(v0, v2), "crack_closure = false changed nothing")
  )");
  CHECK(error == "");
}
