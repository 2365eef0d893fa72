// mpm.history.at2 and mpm.history.csv with the record keys (window, taper, pga, kind = "acceleration"),
// h:arias() and h:spectrum{} from Lua: numbers against closed forms, files as they come (comments, no
// header, a BOM, CRLF), and errors that name the key.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "io/ground_motion.hpp"
#include "lua_fixture.hpp"

using Catch::Contains;

namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("seismpm_history_" + name)).string();
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = temp_path(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// a = 2 sin(2 pi t) m/s2 on 0 .. 10 s, dt = 0.01, as a CSV the way records come: a UTF-8 BOM, CRLF,
// '#' comment lines, no header; and as an AT2 file in g.
// `tag` names the file per test case: ctest runs them side by side.
std::string sine_csv(const std::string& tag) {
  std::ostringstream os;
  os.precision(17);
  os << "\xEF\xBB\xBF# synthetic record\r\n# time (s), acceleration (m/s2)\r\n";
  for (int k = 0; k <= 1000; ++k) os << 0.01 * k << "," << 2.0 * std::sin(2 * std::numbers::pi * 0.01 * k) << "\r\n";
  return write_temp(tag + "_sine.csv", os.str());
}
std::string sine_at2(const std::string& tag) {
  std::ostringstream os;
  os << "PEER\nSINE\nUNITS OF G\nNPTS= 1001, DT= 0.01 SEC\n";
  os.precision(17);
  for (int k = 0; k <= 1000; ++k)
    os << 2.0 * std::sin(2 * std::numbers::pi * 0.01 * k) / seismpm::kStandardGravity << ((k + 1) % 5 ? " " : "\n");
  os << "\n";
  return write_temp(tag + "_sine.AT2", os.str());
}

std::string lua_string(const std::string& s) { return "'" + s + "'"; }

}  // namespace

TEST_CASE("mpm.history.csv of an acceleration record: comments, no header, BOM, CRLF; window, taper, pga",
          "[lua][history][record]") {
  seismpm::test::LuaFixture f;
  const std::string csv = sine_csv("csv_keys");
  CHECK(f.error_of("file = " + lua_string(csv) + R"(
    local g = 9.80665
    -- As it is: the acceleration in m/s2.
    local a = mpm.history.csv{ file = file, time = 1, value = 2, kind = "acceleration", units = "m/s2",
                               integrate = "none" }
    assert(a:duration() == 10 and math.abs(a:at(0.25) - 2) < 1e-12, tostring(a))
    -- Arias intensity of 10 whole cycles: pi A^2 t / (4 g).
    local exact = math.pi * 4 * 10 / (4 * g)
    assert(math.abs(a:arias() / exact - 1) < 1e-9, a:arias() .. " vs " .. exact)
    -- The window 2.25 .. 7.25 s starts at time 0 with the sample of 2.25 s (the peak, 2 m/s2).
    local w = mpm.history.csv{ file = file, time = 1, value = 2, kind = "acceleration", units = "m/s2",
                               integrate = "none", window = { 2.25, 7.25 } }
    assert(math.abs(w:duration() - 5) < 1e-12 and math.abs(w:at(0) - 2) < 1e-12, tostring(w))
    assert(math.abs(w:at(1.5) - a:at(3.75)) < 1e-12)
    assert(tostring(w):find("window 2.25 .. 7.25 s", 1, true), tostring(w))
    -- Tapered by 1 s: zero at both ends, untouched in the middle; then scaled to 0.1 g exactly.
    local t = mpm.history.csv{ file = file, time = 1, value = 2, kind = "acceleration", units = "m/s2",
                               integrate = "none", window = { 2.25, 7.25 }, taper = 1, pga = 0.1 }
    assert(t:at(0) == 0 and t:at(5) == 0, t:at(0) .. " " .. t:at(5))
    assert(math.abs(t:peak() - 0.1 * g) < 1e-12 * g, t:peak())
    local s = 0.1 * g / 2
    for _, x in ipairs{ 1, 1.37, 2.5, 3.99 } do
      assert(math.abs(t:at(x) - s * w:at(x)) < 1e-12, x)
    end
    assert(math.abs(t:at(0.5) - 0.5 * s * w:at(0.5)) < 1e-12)  -- half way up the ramp
    -- The default integrates to velocity, v = A (1 - cos(2 pi t)) / (2 pi): the trapezoidal rule at 100
    -- steps a cycle is within (2 pi dt)^2 / 12 = 0.03 % of it.
    local v = mpm.history.csv{ file = file, time = 1, value = 2, kind = "acceleration", units = "m/s2" }
    assert(math.abs(v:at(0.5) / (2 / math.pi) - 1) < 4e-4, v:at(0.5))
    -- A plain column: the values as they are, cut and shifted.
    local p = mpm.history.csv{ file = file, time = 1, value = 2, window = { 2, 4 }, shift = 1, scale = 3 }
    assert(math.abs(p:at(1) - 3 * a:at(2)) < 1e-12 and p:at(0.5) == 0 and math.abs(p:duration() - 2) < 1e-12)
    assert(not pcall(p.arias, p))
  )") == "");
}

TEST_CASE("mpm.history.at2: window, taper and pga before the baseline, which ends the cut record at rest",
          "[lua][history][record]") {
  seismpm::test::LuaFixture f;
  CHECK(f.error_of("file = " + lua_string(sine_at2("at2_keys")) + R"(
    local g = 9.80665
    local raw = mpm.history.at2{ file = file, integrate = "none" }
    assert(math.abs(raw:peak() - 2) < 1e-9)
    -- A window that starts at a peak of the acceleration: the raw velocity drifts by 2 / (2 pi) * ...
    local drift = mpm.history.at2{ file = file, window = { 1.25, 6.4 }, pga = 0.3 }
    local v = mpm.history.at2{ file = file, window = { 1.25, 6.4 }, taper = 0.5, pga = 0.3, baseline = "linear" }
    assert(math.abs(drift:at(drift:duration())) > 0.1, tostring(drift))
    assert(math.abs(v:at(v:duration())) < 1e-9, tostring(v))
    assert(tostring(v):find("window 1.25 .. 6.4 s, taper 0.5 s, scaled to PGA 0.3 g", 1, true), tostring(v))
    -- pga is exact before the correction; the correction (here a large one: 5 s cut at a peak) then
    -- moves the peak. The acceleration as used is the corrected one: integrate = "none" returns it.
    local scaled = mpm.history.at2{ file = file, integrate = "none", window = { 1.25, 6.4 }, taper = 0.5, pga = 0.3 }
    assert(math.abs(scaled:peak() - 0.3 * g) < 1e-12, scaled:peak())
    local a = mpm.history.at2{ file = file, integrate = "none", window = { 1.25, 6.4 }, taper = 0.5, pga = 0.3,
                               baseline = "linear" }
    assert(a:peak() ~= scaled:peak() and math.abs(a:peak() / (0.3 * g) - 1) < 0.1, a:peak())
    assert(math.abs(a:arias() - v:arias()) < 1e-12 * a:arias())
    -- scale still works, alone
    local s = mpm.history.at2{ file = file, integrate = "none", scale = 0.5 }
    assert(math.abs(s:peak() - 1) < 1e-9 and math.abs(s:arias() - raw:arias() / 4) < 1e-9 * raw:arias())
  )") == "");
}

TEST_CASE("h:spectrum: the table returned, the CSV and its plot", "[lua][history][spectrum]") {
  const std::string dir = temp_path("spectrum");
  std::filesystem::remove_all(dir);
  seismpm::test::LuaFixture f;
  CHECK(f.error_of("file = " + lua_string(sine_at2("spectrum")) + "; dir = " + lua_string(dir) + R"(
    local a = mpm.history.at2{ file = file, integrate = "none" }
    -- Resonance after 10 cycles of A sin(w t): A / (2 zeta w^2) (1 - e^{-2 pi zeta 10}) = 0.957 of it.
    local s = a:spectrum{ periods = { 0.001, 1, 1000 }, damping = 0.05 }
    assert(#s == 3 and s[2][1] == 1, #s)
    assert(math.abs(s[1][2] * 9.80665 / 2 - 1) < 0.001, "short period: Sa = PGA, got " .. s[1][2])
    local sa_resonance = 2 / (2 * 0.05) * (1 - math.exp(-2 * math.pi * 0.05 * 10)) / 9.80665
    assert(math.abs(s[2][2] / sa_resonance - 1) < 0.01, s[2][2] .. " vs " .. sa_resonance)
    local d = a:spectrum{ file = dir .. "/spectrum.csv" }
    assert(#d == 100 and math.abs(d[1][1] - 0.02) < 1e-12 and math.abs(d[100][1] - 5) < 1e-9)
    local v = mpm.history.at2{ file = file }  -- a velocity history keeps its acceleration
    local same = v:spectrum{ periods = { 0.3 } }
    assert(same[1][2] == a:spectrum{ periods = { 0.3 } }[1][2])
    a:spectrum{ file = dir .. "/no_plot.csv", plot = false, periods = { 0.5, 1 } }
  )") == "");
  std::ifstream in(dir + "/spectrum.csv");
  std::string header, line;
  std::getline(in, header);
  CHECK(header == "period (s),Sa (g),Sv (m/s),Sd (m)");
  int rows = 0;
  while (std::getline(in, line)) ++rows;
  CHECK(rows == 100);
  CHECK(std::filesystem::exists(dir + "/spectrum.png"));
  CHECK(std::filesystem::exists(dir + "/spectrum.svg"));
  CHECK(std::filesystem::exists(dir + "/no_plot.csv"));
  CHECK_FALSE(std::filesystem::exists(dir + "/no_plot.png"));
}

TEST_CASE("record keys: bad values and keys that do not fit the history are errors naming the key",
          "[lua][history][record][robustness]") {
  seismpm::test::LuaFixture f;
  const std::string at2 = "mpm.history.at2{ file = " + lua_string(sine_at2("errors_at2")) + ", ";
  const std::string csv = "mpm.history.csv{ file = " + lua_string(sine_csv("errors_csv")) + ", time = 1, value = 2, ";
  const std::string acc = csv + "kind = 'acceleration', ";
  const std::pair<std::string, std::string> cases[] = {
      {at2 + "window = { 5, 11 } }", "key 'window' must lie within the record's 0 .. 10 s"},
      {at2 + "window = { -1, 2 } }", "key 'window' must lie within"},
      {at2 + "window = { 4, 4 } }", "key 'window' must be {t0, t1} (s) with t1 > t0, got {4, 4}"},
      {at2 + "window = { 5, 2 } }", "with t1 > t0"},
      {at2 + "window = { 5 } }", "key 'window' must be {t0, t1}, two times (s), got table"},
      {at2 + "window = { 1, 'x' } }", "key 'window' must be {t0, t1}"},
      {at2 + "window = 3 }", "key 'window' must be {t0, t1}, two times (s), got number"},
      {at2 + "taper = -1 }", "key 'taper' must be >= 0 (s), got -1"},
      {at2 + "window = { 1, 3 }, taper = 1.5 }", "key 'taper' must be at most half the record's length (2 s"},
      {at2 + "pga = 0 }", "key 'pga' must be > 0 (g), got 0"},
      {at2 + "pga = -0.2 }", "key 'pga' must be > 0 (g)"},
      {at2 + "pga = 0.3, scale = 2 }", "keys 'scale' and 'pga' cannot both be given"},
      {acc + "pga = 0.3, scale = 2 }", "keys 'scale' and 'pga' cannot both be given"},
      {acc + "window = { 0, 20 } }", "key 'window' must lie within"},
      {acc + "taper = 6 }", "key 'taper' must be at most half"},
      {acc + "kind = 'velocity' }", "'kind'"},
      {csv + "pga = 0.3 }", "key 'pga' is for an acceleration record: add kind = \"acceleration\""},
      {csv + "taper = 1 }", "key 'taper' is for an acceleration record"},
      {csv + "baseline = 'linear' }", "key 'baseline' is for an acceleration record"},
      {csv + "integrate = 'none' }", "key 'integrate' is for an acceleration record"},
      {csv + "units = 'gal' }", "key 'units' is for an acceleration record"},
      {csv + "window = { 3, 2 } }", "key 'window' must be {t0, t1} (s) with t1 > t0"},
      {"mpm.history.table{ {0, 0}, {1, 1} }:arias()", "needs a history made from an acceleration record"},
      {"mpm.history.fn(function(t) return t end):spectrum{}", "needs a history made from an acceleration record"},
      {"mpm.history.table{ {0, 0}, {1, 1} }:spectrum()", "history:spectrum: needs a history"},
  };
  for (const auto& [code, message] : cases) {
    CAPTURE(code);
    CHECK_THAT(f.error_of(code), Contains(message));
  }
  REQUIRE(f.error_of("a = " + at2 + "integrate = 'none' }") == "");
  const std::pair<std::string, std::string> spectrum_cases[] = {
      {"a:spectrum{ damping = 1 }", "key 'damping' must be in [0, 1)"},
      {"a:spectrum{ damping = -0.1 }", "key 'damping'"},
      {"a:spectrum{ periods = {} }", "key 'periods' must be a list of 1 to 10000 periods (s), got a table of 0"},
      {"a:spectrum{ periods = 0.5 }", "key 'periods' must be a list"},
      {"a:spectrum{ periods = { 0.5, 0 } }", "key 'periods': entry 2 must be a period (s) > 0 and above the one"},
      {"a:spectrum{ periods = { 0.5, 0.2 } }", "entry 2 must be a period (s) > 0 and above the one before (0.5)"},
      {"a:spectrum{ periods = { 'x' } }", "key 'periods': entry 1 must be a period (s) > 0"},
      {"a:spectrum{ periods = { 0 / 0 } }", "key 'periods': entry 1"},
      {"a:spectrum{ dampng = 0.05 }", "dampng"},
      {"a:spectrum{ file = 'x.csv', plot = false, png = 'x.png' }", "key 'png' asks for a plot, but plot = false"},
  };
  for (const auto& [code, message] : spectrum_cases) {
    CAPTURE(code);
    CHECK_THAT(f.error_of(code), Contains(message));
  }
}

TEST_CASE("the Chi-Chi TCU068 record loads as it is through mpm.history.csv", "[lua][history][record][data]") {
  const std::string file = SEISMPM_SHARED_DATA "/ground_motions/Chi-Chi_1999_TCU068-090.csv";
  if (!std::filesystem::exists(file)) {
    WARN("not found, skipped: " << file);
    return;
  }
  seismpm::test::LuaFixture f;
  CHECK(f.error_of("file = " + lua_string(file) + R"(
    local g = 9.80665
    local a = mpm.history.csv{ file = file, time = 1, value = 2, kind = "acceleration", integrate = "none" }
    assert(math.abs(a:peak() / g - 0.566) < 0.001 and math.abs(a:duration() - 65.505) < 1e-9, tostring(a))
    -- The same as the two-column reader of mpm.history.at2.
    local b = mpm.history.at2{ file = file, integrate = "none" }
    assert(a:arias() == b:arias(), a:arias() .. " " .. b:arias())
    arias = a:arias()
    local s = a:spectrum{ periods = { 0.005, 1, 100 } }
    assert(math.abs(s[1][2] / 0.566 - 1) < 0.01, "Sa(0.005 s) = " .. s[1][2])
    -- A window of the strong motion (the PGA is at 13.84 s) scaled to 0.3 g: its intensity is the
    -- window's times (0.3 / 0.566)^2.
    local w = mpm.history.csv{ file = file, time = 1, value = 2, kind = "acceleration", integrate = "none",
                               window = { 5, 35 } }
    local w3 = mpm.history.csv{ file = file, time = 1, value = 2, kind = "acceleration", integrate = "none",
                                window = { 5, 35 }, pga = 0.3 }
    assert(math.abs(w3:arias() / (w:arias() * (0.3 * g / w:peak()) ^ 2) - 1) < 1e-12)
    assert(w:arias() < a:arias())
    -- Tapered and corrected as well: at rest at its end.
    local v = mpm.history.csv{ file = file, time = 1, value = 2, kind = "acceleration", window = { 5, 35 },
                               taper = 2, pga = 0.3, baseline = "linear" }
    assert(math.abs(v:duration() - 30) < 1e-9 and math.abs(v:at(30)) < 1e-9, tostring(v))
  )") == "");
  // The whole record's intensity (trapezoidal rule on a^2, g = 9.80665 m/s2).
  CHECK(f.number("arias") == Approx(3.3008).epsilon(0.001));
}

TEST_CASE("h:spectrum under --sandbox writes only where a script may", "[lua][history][spectrum][robustness]") {
  const std::string at2 = sine_at2("sandbox");
  const std::string dir = std::filesystem::path(at2).parent_path().string();
  seismpm::test::LuaFixture f(true, dir, temp_path("sandbox_out"));
  REQUIRE(f.error_of("a = mpm.history.at2{ file = " + lua_string(at2) + ", integrate = 'none' }") == "");
  CHECK_THAT(f.error_of("a:spectrum{ file = '/etc/seismpm_spectrum.csv' }"),
             Contains("key 'file'") && Contains("is outside what a script may write under --sandbox"));
  CHECK_FALSE(std::filesystem::exists("/etc/seismpm_spectrum.csv"));
}
