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

TEST_CASE("records in any encoding: a BOM and CRLF read, the first row of a header-less file kept",
          "[io][ground_motion][robustness]") {
  SECTION("AT2 with a BOM and CRLF") {
    const auto r = read_at2(write_temp("seismpm_bom.AT2",
                                       "\xEF\xBB\xBFPEER\r\nB\r\nC\r\nNPTS= 3, DT= 0.01 SEC\r\n"
                                       "0.1 0.2\r\n0.3\r\n"));
    REQUIRE(r.a.size() == 3);
    CHECK(r.a[0] == Approx(0.1 * kStandardGravity));
    CHECK(r.a[2] == Approx(0.3 * kStandardGravity));
    CHECK(r.t[2] == Approx(0.02));
  }
  SECTION("two columns with a BOM and no header: the first row is data") {
    for (const std::string sep : {",", " ", "\t", ";"}) {
      CAPTURE(sep);
      const auto r = read_acceleration_columns(write_temp("seismpm_bom_cols.txt",
                                                          "\xEF\xBB\xBF"
                                                          "0" +
                                                              sep + "5\r\n0.1" + sep + "6\r\n0.2" + sep + "7\r\n"),
                                               1.0);
      CHECK(r.t == std::vector<double>{0, 0.1, 0.2});
      CHECK(r.a == std::vector<double>{5, 6, 7});
    }
  }
  SECTION("two columns with a BOM and a header line") {
    const auto r =
        read_acceleration_columns(write_temp("seismpm_bom_head.csv", "\xEF\xBB\xBFtime,acc\r\n0,5\r\n0.1,6\r\n"), 1.0);
    CHECK(r.a == std::vector<double>{5, 6});
  }
}

TEST_CASE("records: NUL bytes, tails and absurd counts are errors naming the file and the line",
          "[io][ground_motion][robustness]") {
  using namespace std::string_literals;
  const std::string h = "A\nB\nC\n";
  SECTION("NUL bytes and tails after a number") {
    CHECK_THROWS_WITH(read_at2(write_temp("n1.AT2", h + "NPTS= 3, DT= 0.01 SEC\n1 1.5\0\0 3\n"s)),
                      Catch::Contains("n1.AT2:5: '1.5\\x00\\x00' is not a number"));
    CHECK_THROWS_WITH(read_at2(write_temp("n2.AT2", h + "NPTS= 3, DT= 0.01 SEC\n1 2\n3g\n")),
                      Catch::Contains("n2.AT2:6: '3g' is not a number"));
    CHECK_THROWS_WITH(read_acceleration_columns(write_temp("n3.csv", "0,0\n0.1,1.5\0\0\n"s), 1.0),
                      Catch::Contains("n3.csv:2: not a number: '1.5\\x00\\x00'"));
    // A broken first row of a header-less file is named, not skipped as a header.
    CHECK_THROWS_WITH(read_acceleration_columns(write_temp("n4.csv", "0,1.5\0\0\n0.1,2\n0.2,3\n"s), 1.0),
                      Catch::Contains("n4.csv:1: not a number: '1.5\\x00\\x00'"));
    CHECK_THROWS_WITH(read_acceleration_columns(write_temp("n5.csv", "0 2.5e\n0.1 2\n"), 1.0),
                      Catch::Contains("n5.csv:1: not a number: '2.5e'"));
  }
  SECTION("counts no file can hold, and counts that are no whole numbers") {
    for (const std::string npts : {"999999999999", "1e300", "50000000"}) {
      CAPTURE(npts);
      try {
        read_at2(write_temp("big.AT2", h + "NPTS= " + npts + ", DT= 0.01 SEC\n1 2 3\n"));
        FAIL("no error");
      } catch (const InputError& e) {  // never std::bad_alloc or a length_error
        CHECK_THAT(e.what(), Catch::Contains("big.AT2:4: NPTS= ") && Catch::Contains(" is more than"));
      }
    }
    for (const std::string npts : {"-3", "2.5", "nan", "inf", "1", "12abc"}) {
      CAPTURE(npts);
      CHECK_THROWS_WITH(read_at2(write_temp("bad.AT2", h + "NPTS= " + npts + ", DT= 0.01 SEC\n1 2 3\n")),
                        Catch::Contains("bad.AT2:4: expected 'NPTS= n, DT= dt SEC'"));
    }
  }
  SECTION("a line over the cap") {
    const auto file = write_temp("long.AT2", h + "NPTS= 3, DT= 0.01 SEC\n" + std::string(2u << 20, '1'));
    CHECK_THROWS_WITH(read_at2(file), Catch::Contains("long.AT2:5: line longer than 1 MiB"));
  }
}

TEST_CASE("record and table errors reach Lua with the file and the line", "[io][ground_motion][lua][robustness]") {
  using namespace std::string_literals;
  const std::string csv = write_temp("seismpm_lua_bad.csv", "t,v\r\n0,1\r\n1,1.5\0\0\r\n"s);
  const std::string at2 = write_temp("seismpm_lua_bad.AT2", "A\nB\nC\nNPTS= 999999999999, DT= 0.01 SEC\n1\n");
  const std::string cols = write_temp("seismpm_lua_bad.txt",
                                      "\xEF\xBB\xBF"
                                      "0 1\n1 x\n");
  test::LuaFixture f;
  CHECK_THAT(f.error_of("mpm.history.csv{ file = '" + csv + "', time = 't', value = 'v' }"),
             Catch::Contains(csv + ":3: column 'v' is not a number ('1.5\\x00\\x00')"));
  CHECK_THAT(f.error_of("mpm.history.csv{ file = '" + csv + "', time = 1, value = 2 }"),
             Catch::Contains(csv + ":3: column 2 is not a number"));
  CHECK_THAT(f.error_of("mpm.history.at2{ file = '" + at2 + "' }"),
             Catch::Contains(at2 + ":4: NPTS= 999999999999 is more than"));
  CHECK_THAT(f.error_of("mpm.history.at2{ file = '" + cols + "', units = 'gal' }"),
             Catch::Contains(cols + ":2: not a number: 'x'"));
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
