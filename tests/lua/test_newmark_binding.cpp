// mpm.newmark: the displacement and its history from Lua, and the errors that name the key.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "lua_fixture.hpp"

namespace {

// A 0.5 g pulse of 0.2 s with a 1 us edge, sampled every 5 ms to 1 s: 0.1470998 m against ky = 0.2 g
// (the closed form V^2 / (2 g ky) (1 - ky/A) with g = 9.80665 m/s2).
const char* kPulse = R"(
  local g = 9.80665
  local points = { {0, 0.5 * g}, {0.2, 0.5 * g}, {0.200001, 0} }
  for k = 41, 200 do points[#points + 1] = { 0.005 * k, 0 } end
  pulse = mpm.history.table(points)
)";

}  // namespace

TEST_CASE("mpm.newmark: a pulse's displacement and its history", "[lua][methods][newmark]") {
  seismpm::test::LuaFixture f;
  REQUIRE(f.error_of(kPulse) == "");
  CHECK(f.error_of(R"(
    local d, h = mpm.newmark{ acceleration = pulse, ky = 0.2 }
    assert(math.abs(d - 0.1470998) < 1e-5 * 0.1470998, "d = " .. d)
    assert(math.abs(h:at(1) - d) < 1e-12 and h:at(0) == 0, "the history ends at d")
    assert(math.abs(h:duration() - 1) < 1e-12 and h:peak() == d)
    assert(tostring(h):find("ky = 0.2 g, normal", 1, true), tostring(h))
    -- one-way: the same pulse upslope does not move the block; inverse turns it back downslope
    local up = mpm.history.table{ {0, -4.903325}, {0.2, -4.903325}, {0.200001, 0}, {1, 0} }
    assert(mpm.newmark{ acceleration = up, ky = 0.2 } == 0)
    assert(mpm.newmark{ acceleration = up, ky = 0.2, direction = "inverse" } > 0.1)
  )") == "");
}

TEST_CASE("mpm.newmark: the record from a file, as SLAMMER scales it", "[lua][methods][newmark][data]") {
  const std::string file = SEISMPM_SHARED_DATA "/ground_motions/Chi-Chi_1999_TCU068-090.csv";
  if (!std::filesystem::exists(file)) {
    WARN("not found, skipped: " << file);
    return;
  }
  seismpm::test::LuaFixture f;
  // SLAMMER 1.1: 477.763 cm for PGA 0.5 g, ky = 0.05 g, normal polarity.
  CHECK(f.error_of("local file = '" + file + R"('
    local raw = mpm.history.at2{ file = file, integrate = "none" }
    local a = mpm.history.at2{ file = file, integrate = "none", scale = 0.5 * 9.80665 / raw:peak() }
    local d = mpm.newmark{ acceleration = a, ky = 0.05 }
    assert(math.abs(d / 4.77763 - 1) < 0.005, "d = " .. d)
    -- pga = 0.5 is the same scale.
    local p = mpm.newmark{ acceleration = mpm.history.at2{ file = file, integrate = "none", pga = 0.5 }, ky = 0.05 }
    assert(math.abs(p / d - 1) < 1e-12, "pga: " .. p .. " vs scale: " .. d)
  )") == "");
}

TEST_CASE("mpm.newmark: errors name the key", "[lua][methods][newmark]") {
  seismpm::test::LuaFixture f;
  REQUIRE(f.error_of(kPulse) == "");
  CHECK_THAT(f.error_of("mpm.newmark{ acceleration = pulse }"), Catch::Contains("mpm.newmark: missing key 'ky'"));
  CHECK_THAT(f.error_of("mpm.newmark{ acceleration = pulse, ky = 0 }"),
             Catch::Contains("key 'ky' must be > 0 (g), got 0"));
  CHECK_THAT(f.error_of("mpm.newmark{ acceleration = pulse, ky = -0.1 }"), Catch::Contains("key 'ky' must be > 0"));
  CHECK_THAT(f.error_of("mpm.newmark{ acceleration = pulse, ky = 0.1, direction = 'up' }"),
             Catch::Contains("'direction'") && Catch::Contains("normal"));
  CHECK_THAT(f.error_of("mpm.newmark{ acceleration = mpm.history.fn(function(t) return 0 end), ky = 0.1 }"),
             Catch::Contains("key 'acceleration' must be a tabulated history"));
  CHECK_THAT(f.error_of("mpm.newmark{ acceleration = 3, ky = 0.1 }"),
             Catch::Contains("'acceleration' must be a history, got number"));
  CHECK_THAT(f.error_of("mpm.newmark{ ky = 0.1 }"), Catch::Contains("'acceleration'"));
  CHECK_THAT(f.error_of("mpm.newmark{ acceleration = pulse, ky = 0.1, kh = 0 }"), Catch::Contains("kh"));
}
