// Time histories: constants, piecewise-linear tables (zero outside them), their descriptions and bad
// input; peak and duration as the Lua history offers them. Every expected value is interpolated by
// hand from the table in the comment.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/history.hpp"
#include "lua/lua_fixture.hpp"

using namespace seismpm;

TEST_CASE("a constant history is the same at every time", "[core][history]") {
  const ConstantHistory h(2.5);
  const double t = GENERATE(-1.0, 0.0, 3.25, 1e6);
  CHECK(h.at(t) == 2.5);
  CHECK(h.describe() == "constant 2.5");
}

TEST_CASE("a table interpolates linearly between its points", "[core][history]") {
  // (0, 0), (1, 2), (3, -2): slope 2 on [0, 1], slope -2 on [1, 3].
  const TableHistory h({0.0, 1.0, 3.0}, {0.0, 2.0, -2.0});
  CHECK(h.at(0.0) == 0.0);
  CHECK(h.at(0.25) == 0.5);
  CHECK(h.at(1.0) == 2.0);   // at a point: its value
  CHECK(h.at(2.0) == 0.0);   // halfway between 2 and -2
  CHECK(h.at(2.5) == -1.0);  // 2 + 0.75 * (-4)
  CHECK(h.at(3.0) == -2.0);  // the last point still counts
  CHECK(h.start() == 0.0);
  CHECK(h.end() == 3.0);
  CHECK(h.describe() == "table: 3 points, t = 0 .. 3 s");
}

TEST_CASE("a table is zero before it starts and after it ends", "[core][history]") {
  // (0.5, 1), (1.5, 3): a record between 0.5 s and 1.5 s.
  const TableHistory h({0.5, 1.5}, {1.0, 3.0}, "data/vx.csv");
  CHECK(h.at(0.4999) == 0.0);
  CHECK(h.at(-10.0) == 0.0);
  CHECK(h.at(0.5) == 1.0);
  CHECK(h.at(1.0) == 2.0);
  CHECK(h.at(1.5) == 3.0);
  CHECK(h.at(1.5001) == 0.0);
  CHECK(h.describe() == "data/vx.csv: 2 points, t = 0.5 .. 1.5 s");
}

TEST_CASE("a one-point table holds its value at that instant only", "[core][history]") {
  const TableHistory h({2.0}, {7.0});
  CHECK(h.at(2.0) == 7.0);
  CHECK(h.at(1.999) == 0.0);
  CHECK(h.at(2.001) == 0.0);
}

TEST_CASE("bad tables are refused naming their source and point", "[core][history]") {
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(TableHistory({}, {}, "v.csv"), "v.csv: history has no points");
  CHECK_THROWS_WITH(TableHistory({0.0, 1.0}, {0.0}), "table: history has unequal numbers of times and values");
  CHECK_THROWS_WITH(TableHistory({0.0, nan}, {0.0, 1.0}), "table: point 2 is not a finite number");
  CHECK_THROWS_WITH(TableHistory({0.0, 1.0}, {inf, 1.0}), "table: point 1 is not a finite number");
  CHECK_THROWS_WITH(TableHistory({0.0, 1.0, 1.0}, {0.0, 1.0, 2.0}), "table: times must increase (point 3)");
  CHECK_THROWS_AS(TableHistory({1.0, 0.0}, {0.0, 0.0}), InputError);
}

TEST_CASE("a function history evaluates its function", "[core][history]") {
  const FunctionHistory h([](double t) { return 3.0 * t - 1.0; }, "3 t - 1");
  CHECK(h.at(2.0) == 5.0);
  CHECK(h.describe() == "3 t - 1");
}

TEST_CASE("peak and duration of a tabulated history", "[core][history][lua]") {
  // The Lua history computes them from the table: peak = max |v| = |-3| = 3, duration = 4.5 - 0.5 = 4.
  test::LuaFixture f;
  CHECK(f.error_of(R"(
    local h = mpm.history.table{ {0.5, 1}, {2, -3}, {4.5, 2} }
    assert(h:peak() == 3, 'peak ' .. h:peak())
    assert(h:duration() == 4, 'duration ' .. h:duration())
  )") == "");
  CHECK_THAT(f.error_of("mpm.history.fn(function(t) return t end):peak()"), Catch::Contains("tabulated history"));
}
