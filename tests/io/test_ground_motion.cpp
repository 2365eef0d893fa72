// Ground-motion records: AT2 and column readers, trapezoidal integration against the closed form,
// baseline correction, and errors that name file and line.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "core/error.hpp"
#include "io/ground_motion.hpp"
#include "lua/lua_fixture.hpp"

using namespace seismpm;

namespace {

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path) << text;
  return path;
}

// An AT2 file of a(t) = amp sin(omega t) in g, 5 values per line, as PEER writes them.
std::string sine_at2(double amp_g, double omega, double dt, int n) {
  std::ostringstream os;
  os << "PEER NGA STRONG MOTION DATABASE RECORD\nSYNTHETIC SINE, TEST\nACCELERATION TIME SERIES IN UNITS OF G\n";
  os << "NPTS=  " << n << ", DT=   " << dt << " SEC\n";
  os.precision(10);
  for (int k = 0; k < n; ++k)
    os << "  " << std::scientific << amp_g * std::sin(omega * k * dt) << ((k + 1) % 5 ? "" : "\n");
  os << "\n";
  return write_temp("seismpm_sine.AT2", os.str());
}

}  // namespace

TEST_CASE("an AT2 sine integrates to the closed-form velocity", "[io][ground_motion]") {
  const double amp = 0.3, omega = 2 * std::numbers::pi * 2.0, dt = 0.005;  // 0.3 g at 2 Hz, 10 s
  const auto record = read_at2(sine_at2(amp, omega, dt, 2001));
  REQUIRE(record.t.size() == 2001);
  CHECK(record.t.back() == Approx(10.0));
  CHECK(record.a[50] == Approx(amp * kStandardGravity * std::sin(omega * 0.25)).margin(1e-9));
  const auto v = integrate_record(record, Baseline::None);
  const double peak = 2 * amp * kStandardGravity / omega;  // v = A (1 - cos wt) / w
  double worst = 0.0;
  for (std::size_t k = 0; k < v.t.size(); ++k)
    worst = std::max(worst, std::abs(v.v[k] - amp * kStandardGravity * (1 - std::cos(omega * v.t[k])) / omega));
  CAPTURE(worst / peak);
  CHECK(worst < 0.005 * peak);  // 0.5 %
}

TEST_CASE("baseline correction brings the end velocity and displacement to zero", "[io][ground_motion]") {
  // A sine with an offset and a slope in the acceleration: the raw record drifts.
  AccelerationRecord r;
  r.source = "drifting";
  for (int k = 0; k <= 4000; ++k) {
    const double t = 0.005 * k;
    r.t.push_back(t);
    r.a.push_back(2.0 * std::sin(2 * std::numbers::pi * 1.5 * t) + 0.02 + 0.001 * t);
  }
  const auto raw = integrate_record(r, Baseline::None);
  CHECK(std::abs(raw.v.back()) > 0.5);
  CHECK(std::abs(raw.d.back()) > 5.0);
  for (Baseline b : {Baseline::Linear, Baseline::Quadratic}) {
    const auto c = integrate_record(r, b);
    CAPTURE(b == Baseline::Linear, c.v.back(), c.d.back());
    CHECK(std::abs(c.v.back()) < 1e-9);
    CHECK(std::abs(c.d.back()) < 1e-6);
    double peak = 0.0;  // the shaking itself stays: peak velocity 2 / (pi 1.5) * 2 ~ 0.42 m/s
    for (double v : c.v) peak = std::max(peak, std::abs(v));
    CHECK(peak == Approx(2.0 * 2.0 / (2 * std::numbers::pi * 1.5)).epsilon(0.1));
  }
}

TEST_CASE("bad records are refused naming the file and the line", "[io][ground_motion]") {
  const std::string h = "A\nB\nC\n";
  CHECK_THROWS_WITH(read_at2(write_temp("s1.AT2", h + "NPTS= 3 DT\n1 2 3\n")),
                    Catch::Contains("s1.AT2:4: expected 'NPTS= n, DT= dt SEC'"));
  CHECK_THROWS_WITH(read_at2(write_temp("s2.AT2", h + "NPTS= 4, DT= 0.01 SEC\n1 2 3\n")),
                    Catch::Contains("s2.AT2:5: the header says NPTS= 4 but the file holds 3 values"));
  CHECK_THROWS_WITH(read_at2(write_temp("s3.AT2", h + "NPTS= 3, DT= 0.01 SEC\n1 x 3\n")),
                    Catch::Contains("s3.AT2:5: 'x' is not a number"));
  CHECK_THROWS_WITH(read_at2(write_temp("s4.AT2", "A\nB\n")), Catch::Contains("s4.AT2:3: AT2 header ends early"));
  CHECK_THROWS_WITH(read_acceleration_columns(write_temp("c1.csv", "# t, a\n0, 0\n0.1, 1\n0.1, 2\n"), 1.0),
                    Catch::Contains("c1.csv:4: times must increase"));
  CHECK_THROWS_WITH(read_acceleration_columns(write_temp("c2.csv", "time, acc\n0, 0\n0.1\n"), 1.0),
                    Catch::Contains("c2.csv:3: expected two columns"));
  CHECK_THROWS_WITH(read_acceleration_columns(write_temp("c3.csv", "0 0\n0.1 abc\n"), 1.0),
                    Catch::Contains("c3.csv:2: not a number: 'abc'"));
  CHECK_THROWS_WITH(read_acceleration_columns(write_temp("c4.csv", "# only comments\n\n"), 1.0),
                    Catch::Contains("c4.csv: empty record"));
  CHECK_THROWS_WITH(read_acceleration_columns("/nonexistent/record.csv", 1.0),
                    Catch::Contains("/nonexistent/record.csv: cannot open"));
  CHECK_THROWS_WITH(parse_baseline("cubic"), Catch::Contains("none|linear|quadratic"));
}

TEST_CASE("records from Lua: units, scale, peak, duration, write_csv", "[io][ground_motion][lua]") {
  const std::string file =
      write_temp("seismpm_record.txt", "# time (s)  acceleration (gal)\n0 0\n1 100\n2 0\n3 -100\n4 0\n");
  const std::string out = write_temp("seismpm_record_out.csv", "");
  test::LuaFixture f;
  const std::string error = f.error_of(R"(
    local a = mpm.history.at2{ file = ")" +
                                       file + R"(", units = "gal", integrate = "none", scale = 2 }
    assert(math.abs(a:at(1) - 2.0) < 1e-12 and math.abs(a:peak() - 2.0) < 1e-12 and a:duration() == 4)
    local v = mpm.history.at2{ file = ")" +
                                       file + R"(", units = "gal" }
    assert(math.abs(v:at(2) - 1.0) < 1e-12 and math.abs(v:at(4)) < 1e-12)   -- trapezoid: 0.5 + 0.5
    assert(tostring(v):find("PGA 0.102 g"))
    v:write_csv(")" + out + R"(")
    assert(not pcall(mpm.history.at2, { file = ")" +
                                       file + R"(", units = "furlong" }))
    assert(not pcall(function() return mpm.history.fn(function(t) return t end):peak() end))
  )");
  CHECK(error == "");
  std::ifstream in(out);
  std::string header, line;
  std::getline(in, header);
  CHECK(header == "t,value");
  int rows = 0;
  while (std::getline(in, line)) ++rows;
  CHECK(rows == 5);
}

TEST_CASE("the Chi-Chi TCU068 record: PGA 0.566 g, raw PGV 1.77 m/s", "[io][ground_motion][data]") {
  // Public strong-motion data kept outside the project tree (../shared/data); checked where present.
  const std::string file = SEISMPM_SHARED_DATA "/ground_motions/Chi-Chi_1999_TCU068-090.csv";
  if (!std::filesystem::exists(file)) {
    WARN("not found, skipped: " << file);
    return;
  }
  const auto r = read_acceleration_columns(file, kStandardGravity);
  CHECK(r.t.size() == 13102);
  double pga = 0.0, pgv = 0.0;
  for (double a : r.a) pga = std::max(pga, std::abs(a));
  const auto v = integrate_record(r, Baseline::None);
  for (double x : v.v) pgv = std::max(pgv, std::abs(x));
  CHECK(pga / kStandardGravity == Approx(0.566).epsilon(0.001));
  CHECK(pgv == Approx(1.77).epsilon(0.003));
  const auto c = integrate_record(r, Baseline::Linear);
  CHECK(std::abs(c.v.back()) < 1e-9);
  CHECK(std::abs(c.d.back()) < 1e-6);
}
