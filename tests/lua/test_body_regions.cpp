// Material regions inside one body (m:body{ regions = ... }, mpm.geometry.layers): which particle takes
// which material, that the step uses each particle's own, the names outputs show, and the errors.
#include <catch2/catch.hpp>

#include "lua_fixture.hpp"
#include "methods/limit_equilibrium.hpp"

using seismpm::test::LuaFixture;

TEST_CASE("each particle takes the material of the last region holding it, else the body's", "[lua][regions]") {
  LuaFixture f;
  const std::string error = f.error_of(R"(
    local m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
    local fill = mpm.material.linear_elastic{ density = 1000, young = 1e6, poisson = 0.2 }
    local clay = mpm.material.linear_elastic{ name = "clay", density = 1800, young = 1e6, poisson = 0.2 }
    local lens = mpm.material.linear_elastic{ name = "lens", density = 2500, young = 1e6, poisson = 0.2 }
    local b = m:body{ name = "ground", material = fill, ppc = 2, shape = mpm.shape.rectangle{ 0, 0, 1, 0.8 },
                      regions = { { shape = mpm.shape.rectangle{ -1, -1, 2, 0.4 }, material = clay },
                                  { shape = mpm.shape.rectangle{ 0.2, 0.2, 0.6, 0.6 }, material = lens } } }
    local names = m:materials()
    assert(#names == 3 and names[1] == "linear_elastic" and names[2] == "clay" and names[3] == "lens",
           table.concat(names, " "))
    local x, y, mat, mass = b:field("x"), b:field("y"), b:field("material"), b:field("mass")
    local rho = { [0] = 1000, [1] = 1800, [2] = 2500 }
    local count = { [0] = 0, [1] = 0, [2] = 0 }
    for i = 1, #x do
      local want = 0
      if y[i] <= 0.4 then want = 1 end
      if x[i] >= 0.2 and x[i] <= 0.6 and y[i] >= 0.2 and y[i] <= 0.6 then want = 2 end  -- the later region wins
      assert(mat[i] == want, string.format("particle at (%g, %g): material %d, expected %d", x[i], y[i], mat[i], want))
      assert(math.abs(mass[i] - rho[want] * 0.05 ^ 2) < 1e-12, "mass from the particle's own density")
      count[want] = count[want] + 1
    end
    -- 8 x 16 particles below 0.4 less the lens' 8 x 4 there; the lens 8 x 8; the rest of the 20 x 16.
    assert(count[1] == 20 * 8 - 8 * 4 and count[2] == 8 * 8 and count[0] == 20 * 16 - 128 - 64,
           count[0] .. " " .. count[1] .. " " .. count[2])
  )");
  CHECK(error == "");
}

// Two layers of one body in an oedometer (smooth walls, fixed base) settle under their own weight as
// the layered column does: u(y) = -int_0^y sigma_v / M, M = E (1 - nu) / ((1 + nu)(1 - 2 nu)) of the
// layer. With one material for both the soft layer's settlement would be 10x off.
TEST_CASE("a two-layer body settles as the layered oedometer", "[lua][regions]") {
  LuaFixture f;
  const std::string error = f.error_of(R"(
    local m = mpm.model{ domain = {{0, 0}, {0.2, 0.4}}, cell = 0.025, shape = "gimp" }
    local E1, E2, nu, r1, r2, g = 2e7, 2e6, 0.25, 2400, 1600, 9.81
    local stiff = mpm.material.linear_elastic{ name = "stiff", density = r1, young = E1, poisson = nu }
    local soft = mpm.material.linear_elastic{ name = "soft", density = r2, young = E2, poisson = nu }
    m:fix{ side = "left", dof = "x" }; m:fix{ side = "right", dof = "x" }; m:fix{ side = "bottom", dof = "xy" }
    local ground = m:body{ name = "ground", shape = mpm.shape.rectangle{ 0, 0, 0.2, 0.4 }, ppc = 2,
                           regions = mpm.geometry.layers{ left = 0, right = 0.2, {thickness = 0.2, material = stiff},
                                                          {top = 0.4, material = soft} } }
    local y0 = ground:field("y")
    m:run{ duration = 0.5, damping = 0.7 }
    local function M(E) return E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) end
    local function sigma_v(y) return g * (y < 0.2 and r2 * 0.2 + r1 * (0.2 - y) or r2 * (0.4 - y)) end
    local function u(y)
      local a = math.min(y, 0.2)
      local s = g * (r2 * 0.2 * a + r1 * (0.2 * a - a * a / 2)) / M(E1)
      if y > 0.2 then
        local b = y - 0.2
        s = s + g * r2 * (0.2 * b - b * b / 2) / M(E2)
      end
      return -s
    end
    local uy, syy = ground:field("uy"), ground:field("syy")
    local worst_u, worst_s = 0, 0
    for i = 1, #uy do
      worst_u = math.max(worst_u, math.abs(uy[i] - u(y0[i])) / math.abs(u(0.4)))
      worst_s = math.max(worst_s, math.abs(-syy[i] - sigma_v(y0[i])) / sigma_v(0))
    end
    -- measured: 0.24 % and 1.9 %
    assert(worst_u < 0.02, "settlement off by " .. worst_u .. " of the top's")
    assert(worst_s < 0.03, "sigma_v off by " .. worst_s .. " of the base's")
  )");
  CHECK(error == "");
}

TEST_CASE("mpm.geometry.layers: tops, thicknesses and materials", "[lua][regions]") {
  LuaFixture f;
  const std::string error = f.error_of(R"(
    local clay = mpm.material.linear_elastic{ density = 1800, young = 1e6, poisson = 0.2 }
    local l = mpm.geometry.layers{ left = -1, right = 3, base = 1, {top = 2, material = clay}, {thickness = 0.5},
                                   {thickness = 1, name = "cap"} }
    assert(#l == 3 and l[1].material == clay and l[2].material == nil and l[3].name == "cap" and l[2].name == "layer2")
    assert(l[1].shape:contains{-1, 1} and l[1].shape:contains{3, 2} and not l[1].shape:contains{0, 2.1})
    assert(l[2].shape:contains{0, 2.4} and not l[2].shape:contains{0, 2.6})
    assert(l[3].shape:contains{0, 3.5} and not l[3].shape:contains{0, 3.6})
  )");
  CHECK(error == "");
  using Catch::Contains;
  CHECK_THAT(f.error_of("mpm.geometry.layers{ left = 0, right = 1, {top = 1, thickness = 1} }"),
             Contains("test:1: mpm.geometry.layers: layer 1: give top or thickness, not both"));
  CHECK_THAT(f.error_of("mpm.geometry.layers{ left = 0, right = 1, {top = 1}, {thickness = -1} }"),
             Contains("layer 2: thickness must be a number > 0"));
  CHECK_THAT(f.error_of("mpm.geometry.layers{ left = 0, right = 1, {top = 1, materal = 1} }"),
             Contains("layer 1: unknown key 'materal'"));
  CHECK_THAT(f.error_of("mpm.geometry.layers{ left = 1, right = 0, {top = 1} }"),
             Contains("key 'right' must exceed 'left'"));
}

TEST_CASE("bad regions are errors naming the body and the region, and add nothing", "[lua][regions][errors]") {
  LuaFixture f;
  REQUIRE(f.error_of(R"(
    m = mpm.model{ domain = {{0, 0}, {1, 1}}, cell = 0.1 }
    sand = mpm.material.linear_elastic{ density = 1000, young = 1e6, poisson = 0.2 }
    box = mpm.shape.rectangle{ 0, 0, 1, 0.5 }
    low = mpm.shape.rectangle{ 0, 0, 1, 0.2 }
  )") == "");
  using Catch::Contains;
  CHECK_THAT(f.error_of("m:body{ name = 'a', shape = box, regions = { { shape = low, material = sand } } }"),
             Contains("body 'a': the particle at {0.025, 0.225} lies in none of its regions, and the body has no "
                      "material of its own"));
  CHECK_THAT(f.error_of("m:body{ name = 'b', shape = box, material = sand, regions = { { shape = low, material = "
                        "sand }, { name = 'all', shape = box, material = sand } } }"),
             Contains("body 'b': region 'region1' (rectangle {0, 0} to {1, 0.2}) gives none of its particles"));
  CHECK_THAT(
      f.error_of("m:body{ name = 'c', shape = box, material = sand, regions = { shape = low, material = sand } }"),
      Contains("key 'regions' must be a list"));
  CHECK_THAT(f.error_of("m:body{ name = 'd', shape = box, material = sand, regions = { { shape = low } } }"),
             Contains("key 'regions[1]': key 'material' must be a material, got nil"));
  CHECK_THAT(f.error_of("m:body{ name = 'e', shape = box, regions = { { shape = low, material = 1 } } }"),
             Contains("regions[1]"));
  CHECK_THAT(f.error_of("m:body{ name = 'f', shape = box }"),
             Contains("key 'material' must be a material, got nil (or give regions"));
  CHECK(f.error_of("assert(m:count() == 0, 'particles added'); assert(next(m:bodies()) == nil, 'a body added')") == "");
}

// mpm.lem reads each particle's material: a layered slope as one body with regions gives the factor of
// two bodies of the same layers, and the core solver's on the layered geometry.
TEST_CASE("mpm.lem reads the layers of one body's regions", "[lua][regions][lem]") {
  using namespace seismpm;
  const LemSlope slope{{{-20, 12}, {0, 12}, {20, 2}, {45, 2}}, {{0, {20e3, 20e3, 10}}, {6, {18e3, 5e3, 30}}}, 0};
  LemSearch search;  // coarser than the default: this compares, it does not hunt the last digit
  search.centres = 6;
  search.zoom_levels = 3;
  search.radii = 8;
  const double core = limit_equilibrium(slope, 0, search).fos;
  LuaFixture f;
  const std::string error = f.error_of(R"(
    local function model()
      return mpm.model{ domain = {{-20, 0}, {45, 14}}, cell = 0.5, gravity = {0, -10} }
    end
    local clay = mpm.material.mohr_coulomb{ density = 2000, young = 50e6, poisson = 0.3, cohesion = 20e3,
                                            friction = 10 }
    local sand = mpm.material.mohr_coulomb{ density = 1800, young = 50e6, poisson = 0.3, cohesion = 5e3,
                                            friction = 30 }
    local shape = mpm.shape.polygon{ {-20, 0}, {45, 0}, {45, 2}, {20, 2}, {0, 12}, {-20, 12} }
    local one = model()
    one:body{ name = "slope", shape = shape,
              regions = mpm.geometry.layers{ left = -20, right = 45, {top = 6, material = clay},
                                             {top = 12, material = sand} } }
    local two = model()
    two:body{ name = "lower", material = clay,
              shape = mpm.shape.polygon{ {-20, 0}, {45, 0}, {45, 2}, {20, 2}, {12, 6}, {-20, 6} } }
    two:body{ name = "upper", material = sand, shape = mpm.shape.polygon{ {-20, 6}, {12, 6}, {0, 12},
                                                                          {-20, 12} } }
    assert(one:count() == two:count(), one:count() .. " vs " .. two:count())
    local search = { grid = 6, levels = 3, samples = 8 }
    fos_one = mpm.lem{ model = one, search = search }.fos
    fos_two = mpm.lem{ model = two, search = search }.fos
  )");
  REQUIRE(error == "");
  lua_State* L = f.runtime.state();
  lua_getglobal(L, "fos_one");
  lua_getglobal(L, "fos_two");
  const double one = lua_tonumber(L, -2), two = lua_tonumber(L, -1);
  lua_pop(L, 2);
  CHECK(one == two);
  CHECK(one == Approx(core).epsilon(0.02));
}
