// Materials from Lua: the rayleigh key in both forms, its coefficients on the object, and bad values
// named with the key and the allowed range.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "lua_fixture.hpp"

using seismpm::test::LuaFixture;

TEST_CASE("rayleigh on a material: ratio at two frequencies or the coefficients", "[lua][material][rayleigh]") {
  LuaFixture f;
  REQUIRE(f.error_of(R"(
    local ratio = mpm.material.mohr_coulomb{ density = 1800, young = 5e7, poisson = 0.3, cohesion = 5e3,
                                             friction = 30, rayleigh = { ratio = 0.05, frequencies = { 1, 5 } } }
    local r = ratio:rayleigh()
    alpha, beta, text = r.alpha, r.beta, tostring(ratio)
    local given = mpm.material.linear_elastic{ density = 2000, young = 1e8, poisson = 0.25,
                                               rayleigh = { beta = 0.002 } }
    given_alpha, given_beta = given:rayleigh().alpha, given:rayleigh().beta
    local dp = mpm.material.drucker_prager{ density = 2000, young = 1e8, poisson = 0.25, friction = 30,
                                            rayleigh = { alpha = 0.5, beta = 0.001 } }
    dp_alpha = dp:rayleigh().alpha
    none = mpm.material.linear_elastic{ density = 2000, young = 1e8, poisson = 0.25 }:rayleigh().alpha
  )") == "");
  const double w1 = 2 * std::numbers::pi, w2 = 10 * std::numbers::pi;
  CHECK(f.number("alpha") == Approx(2 * 0.05 * w1 * w2 / (w1 + w2)));
  CHECK(f.number("beta") == Approx(2 * 0.05 / (w1 + w2)));
  CHECK(f.number("given_alpha") == 0.0);
  CHECK(f.number("given_beta") == 0.002);
  CHECK(f.number("dp_alpha") == 0.5);
  CHECK(f.number("none") == 0.0);
  lua_getglobal(f.runtime.state(), "text");
  const std::string text = lua_tostring(f.runtime.state(), -1);
  CHECK_THAT(text, Catch::Contains("Rayleigh alpha 0.52") && Catch::Contains("(ratio 0.05 at 1 and 5 Hz)"));
}

TEST_CASE("rayleigh on a material: bad values are named with the allowed range", "[lua][material][rayleigh]") {
  LuaFixture f;
  const auto error = [&](const std::string& rayleigh) {
    return f.error_of(
        "mpm.material.linear_elastic{ density = 2000, young = 1e8, poisson = 0.25, rayleigh = " + rayleigh + " }");
  };
  CHECK_THAT(error("{ ratio = 1.2, frequencies = {1, 5} }"),
             Catch::Contains("key 'rayleigh': key 'ratio' must be in [0, 1), got 1.2"));
  CHECK_THAT(error("{ ratio = -0.05, frequencies = {1, 5} }"), Catch::Contains("key 'ratio' must be in [0, 1)"));
  CHECK_THAT(error("{ ratio = 0.05, frequencies = {5, 1} }"),
             Catch::Contains("key 'rayleigh': key 'frequencies' must be {f1, f2} with 0 < f1 < f2 (Hz), got {5, 1}"));
  CHECK_THAT(error("{ ratio = 0.05, frequencies = {2, 2} }"), Catch::Contains("0 < f1 < f2"));
  CHECK_THAT(error("{ ratio = 0.05, frequencies = {0, 2} }"), Catch::Contains("0 < f1 < f2"));
  CHECK_THAT(error("{ ratio = 0.05, frequencies = 3 }"), Catch::Contains("{f1, f2}") && Catch::Contains("got number"));
  CHECK_THAT(error("{ ratio = 0.05 }"), Catch::Contains("key 'rayleigh': missing key 'frequencies'"));
  CHECK_THAT(error("{ frequencies = {1, 5} }"), Catch::Contains("key 'rayleigh': missing key 'ratio'"));
  CHECK_THAT(error("{ alpha = -1 }"), Catch::Contains("key 'rayleigh': key 'alpha' must be >= 0 (1/s), got -1"));
  CHECK_THAT(error("{ beta = -1e-3 }"), Catch::Contains("key 'beta' must be >= 0 (s)"));
  CHECK_THAT(error("{ ratio = 0.05, frequencies = {1, 5}, alpha = 1 }"),
             Catch::Contains("give either ratio and frequencies = {f1, f2}, or alpha and/or beta"));
  CHECK_THAT(error("{}"), Catch::Contains("give either"));
  CHECK_THAT(error("{ xi = 0.05 }"), Catch::Contains("unknown key 'xi'") && Catch::Contains("ratio, frequencies"));
  CHECK_THAT(error("0.05"), Catch::Contains("rayleigh"));
}
