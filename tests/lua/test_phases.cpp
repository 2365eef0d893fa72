// Calculation phases from Lua: the damped gravity phase to equilibrium (and K0), the dynamic phase
// with its own clock for rigid-body histories.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "lua_fixture.hpp"

using seismpm::test::LuaFixture;

TEST_CASE("gravity phase: an elastic column reaches sigma_v = rho g depth within 2 %", "[lua][phases][verification]") {
  LuaFixture f;
  const std::string error = f.error_of(R"(
    local H, rho, g = 1.0, 2000, 9.81
    local m = mpm.model{ domain = {{0, 0}, {0.2, 1.1}}, cell = 0.02, gravity = {0, -g} }
    local mat = mpm.material.linear_elastic{ density = rho, young = 1e7, poisson = 0.3 }
    local col = m:body{ name = "column", material = mat, shape = mpm.shape.rectangle{ 0, 0, 0.2, H } }
    m:fix{ side = "left", dof = "x" }; m:fix{ side = "right", dof = "x" }; m:fix{ side = "bottom", dof = "xy" }
    local eq = m:gravity_phase{ damping = 0.7, tolerance = 0.005, max_time = 5 }
    assert(eq.unbalanced < 0.005 and eq.kinetic < 0.005 and eq.steps > 10, "ratios")
    assert(m:phase() == "gravity" and math.abs(m:phase_time() - eq.time) < 1e-12)
    -- Mean vertical stress of the particles of each cell row against rho g depth at the row's centre
    -- (MPM strain is nearly constant in a cell, so single particles sit up to rho g h / 4 off).
    local h = 0.02
    local ys, syy = col:field("y"), col:field("syy")
    local rows = {}
    for i = 1, #ys do
      local k = math.floor(ys[i] / h)
      rows[k] = rows[k] or { sum = 0, n = 0 }
      rows[k].sum, rows[k].n = rows[k].sum + syy[i], rows[k].n + 1
    end
    -- The top cell row, at the free surface, sits about rho g h / 25 off (4 % of its own small stress,
    -- 0.04 % of the base's): it is held to 1 % of rho g H, every other row to 2 % of its own value.
    local worst, top = 0, 0
    for k, r in pairs(rows) do
      local exact = -rho * g * (H - (k + 0.5) * h)
      if k == math.floor(H / h) - 1 then
        top = math.abs(r.sum / r.n - exact) / (rho * g * H)
      else
        worst = math.max(worst, math.abs(r.sum / r.n - exact) / math.abs(exact))
      end
    end
    assert(top < 0.01, "top row " .. top)
    print(string.format("elastic column: equilibrium after %.3f s, %d steps; worst row error %.3f %%, top row %.3f %% of rho g H",
                        eq.time, eq.steps, 100 * worst, 100 * top))
    assert(worst < 0.02, "row error " .. worst)
    -- Displacements and strains start again from zero; stresses stay.
    for _, u in ipairs(col:field("uy")) do assert(u == 0, "uy not reset") end
    for _, e in ipairs(col:field("shear_strain")) do assert(e == 0, "strain not reset") end
  )");
  CHECK(error == "");
}

TEST_CASE("gravity phase with k0: the stresses are set, then settle", "[lua][phases]") {
  LuaFixture f;
  const std::string error = f.error_of(R"(
    local rho, g = 1800, 9.81
    local m = mpm.model{ domain = {{0, 0}, {2, 1.2}}, cell = 0.05, gravity = {0, -g} }
    -- nu = 1/3: the elastic K0 = nu / (1 - nu) = 0.5, so the settling should hardly change anything.
    local mat = mpm.material.linear_elastic{ density = rho, young = 2e7, poisson = 1 / 3 }
    local ground = m:body{ name = "ground", material = mat, shape = mpm.shape.rectangle{ 0, 0, 2, 1 } }
    m:fix{ side = "left", dof = "x" }; m:fix{ side = "right", dof = "x" }; m:fix{ side = "bottom", dof = "xy" }
    local eq = m:gravity_phase{ k0 = 0.5, max_time = 2 }
    local ys, sxx, syy = ground:field("y"), ground:field("sxx"), ground:field("syy")
    local worst_v, worst_ratio = 0, 0
    for i = 1, #ys do
      local depth = 1 - ys[i]
      if depth > 0.25 then
        worst_v = math.max(worst_v, math.abs(-syy[i] - rho * g * depth) / (rho * g * depth))
        worst_ratio = math.max(worst_ratio, math.abs(sxx[i] / syy[i] - 0.5))
      end
    end
    print(string.format("k0: settled in %d steps; sigma_v error %.3f %%, |sigma_h/sigma_v - 0.5| %.4f",
                        eq.steps, 100 * worst_v, worst_ratio))
    assert(worst_v < 0.02, "sigma_v " .. worst_v)
    assert(worst_ratio < 0.02, "ratio " .. worst_ratio)
  )");
  CHECK(error == "");
}

TEST_CASE("gravity phase: a dry slope flatter than phi stands, a steeper one keeps moving",
          "[lua][phases][materials]") {
  const std::string setup = R"(
    function slope(angle, max_time)
      local m = mpm.model{ domain = {{0, 0}, {3, 1.1}}, cell = 0.05, gravity = {0, -9.81} }
      local sand = mpm.material.mohr_coulomb{ density = 1800, young = 5e6, poisson = 0.3, cohesion = 0,
                                              friction = 30, dilation = 0 }
      local s = mpm.geometry.slope{ left = 0, right = 3, crest = {0.6, 1.0}, toe_level = 0.2, angle = angle }
      m:body{ name = "sand", material = sand, shape = s }
      m:fix{ side = "left", dof = "x" }; m:fix{ side = "right", dof = "x" }; m:fix{ side = "bottom", dof = "xy" }
      return m:gravity_phase{ max_time = max_time }
    end
  )";
  SECTION("20 degrees against phi = 30 reaches equilibrium") {
    LuaFixture f;
    CHECK(f.error_of(setup + "local eq = slope(20, 3) print('20 deg: equilibrium after ' .. eq.time .. ' s')") == "");
  }
  SECTION("40 degrees with c = 0 does not") {
    LuaFixture f;
    const std::string error = f.error_of(setup + "slope(40, 0.6)");
    CHECK_THAT(error, Catch::Contains("no static equilibrium within max_time = 0.6 s"));
  }
}

TEST_CASE("phases: histories run on the phase clock; the gravity phase holds rigid bodies", "[lua][phases][rigid]") {
  LuaFixture f;
  const auto dir = std::filesystem::temp_directory_path() / "seismpm_phases";
  std::filesystem::remove_all(dir);
  const std::string error = f.error_of(R"(
    local m = mpm.model{ domain = {{-0.5, -0.2}, {2, 1}}, cell = 0.1 }
    local mat = mpm.material.linear_elastic{ density = 1000, young = 1e7, poisson = 0.3 }
    local blk = m:body{ name = "block", material = mat, shape = mpm.shape.rectangle{0, 0, 0.5, 0.5} }
    -- 1 m/s from t = 0 of each phase that lets it move: a gravity phase must not.
    local base = m:rigid{ name = "base", ppc = 1, velocity = {mpm.history.table{{0, 1}, {10, 1}}, 0},
                          shape = mpm.shape.rectangle{-0.4, -0.1, 1.0, 0} }
    m:output{ dir = ")" + dir.string() +
                                       R"(", every = 0.1 }
    local x0 = base:centroid()[1]
    local eq = m:gravity_phase{ max_time = 2 }
    assert(math.abs(base:centroid()[1] - x0) < 1e-12, "the base moved in the gravity phase")
    local t_gravity = m:time()
    m:dynamic_phase{ duration = 0.25 }
    assert(m:phase() == "dynamic")
    assert(math.abs(m:phase_time() - 0.25) < 1e-12 and math.abs(m:time() - t_gravity - 0.25) < 1e-12)
    assert(math.abs(base:centroid()[1] - x0 - 0.25) < 1e-9, "base moved " .. base:centroid()[1] - x0)
    m:run{ duration = 0.05 }  -- continues the phase: its clock goes on
    assert(math.abs(m:phase_time() - 0.3) < 1e-12)
    -- A second dynamic phase restarts the clock: the table (zero after t = 10 s) is read from its start.
    m:dynamic_phase{ duration = 0.1 }
    assert(math.abs(m:phase_time() - 0.1) < 1e-12 and math.abs(base:centroid()[1] - x0 - 0.4) < 1e-9)
  )");
  CHECK(error == "");
  // The outputs carry the phase names.
  std::ifstream in(dir / "reactions.csv");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(text.find(",gravity,") != std::string::npos);
  CHECK(text.find(",dynamic,") != std::string::npos);
}

TEST_CASE("dynamic phase with damping 0: an elastic bar keeps its amplitude", "[lua][phases][verification]") {
  LuaFixture f;
  const std::string error = f.error_of(R"(
    -- The vibrating bar (Sulsky 1994): L = 25 m, E = 100 Pa, rho = 1, v0 = 0.1; T = 4 L / c = 10 s.
    local L = 25
    local m = mpm.model{ domain = {{0, 0}, {L + 4, 2}}, cell = 1, gravity = {0, 0}, cfl = 0.1 }
    local mat = mpm.material.linear_elastic{ density = 1, young = 100, poisson = 0 }
    local bar = m:body{ name = "bar", material = mat, shape = mpm.shape.rectangle{0, 0, L, 1} }
    m:fix{ side = "left", dof = "x" }
    bar:set_velocity(function(x, y) return 0.1 * math.sin(math.pi * x / (2 * L)), 0 end)
    m:run{ duration = 0.01, damping = 0.5 }  -- damping set before: the dynamic phase must turn it off
    local function mean_vx()
      local s = 0
      local v = bar:field("vx")
      for i = 1, #v do s = s + v[i] end
      return s / #v
    end
    local first, second = 0, 0
    m:dynamic_phase{ duration = 0.01 }
    for k = 1, 80 do  -- two periods in steps of T/40
      m:run{ duration = 0.25 }
      local v = math.abs(mean_vx())
      if k <= 40 then first = math.max(first, v) else second = math.max(second, v) end
    end
    print(string.format("bar: peak centre-of-mass velocity %.5f then %.5f m/s", first, second))
    assert(second > 0.99 * first, "amplitude lost: " .. first .. " -> " .. second)
  )");
  CHECK(error == "");
}

TEST_CASE("phase arguments are checked", "[lua][phases][errors]") {
  const std::string model = "m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 } ";
  const std::string body =
      "mat = mpm.material.linear_elastic{ density = 1000, young = 1e6, poisson = 0.3 } "
      "b = m:body{ material = mat, shape = mpm.shape.rectangle{0.1, 0.1, 0.5, 0.5} } ";
  struct Case {
    std::string code, expected;
  };
  for (const Case& c : std::vector<Case>{
           {model + "m:gravity_phase{}", "the model has no particles"},
           {model + body + "m:gravity_phase{ damping = 1 }", "key 'damping' must be in [0, 1)"},
           {model + body + "m:gravity_phase{ tolerance = 0 }", "key 'tolerance' must be in"},
           {model + body + "m:gravity_phase{ max_time = -1 }", "key 'max_time' must be > 0 (s)"},
           {model + body + "m:gravity_phase{ k0 = 0 }", "key 'k0' must be in"},
           {model + body + "m:gravity_phase{ tol = 0.01 }", "unknown key 'tol'"},
           {model + body + "m:dynamic_phase{}", "missing key 'duration'"},
           {model + body + "m:dynamic_phase{ duration = 1, damping = -0.1 }", "key 'damping' must be in [0, 1)"},
       }) {
    LuaFixture f;
    CAPTURE(c.code);
    CHECK_THAT(f.error_of(c.code), Catch::Contains(c.expected));
  }
}
