// Bishop's simplified method against closed forms and a published chart value.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "methods/limit_equilibrium.hpp"

using namespace seismpm;

namespace {

double rad(double deg) { return deg * std::numbers::pi / 180; }

// A long face at angle beta (1000 m horizontally) between two flats, dry cohesionless soil.
LemSlope infinite_slope(double beta, double phi) {
  const double h = 1000 * std::tan(rad(beta));
  return {{{-100, h}, {0, h}, {1000, 0}, {1100, 0}}, {{0, {20e3, 0, phi}}}, 0};
}

// A circle of radius 10 km whose chord lies on the face, 2 m deep at its middle: a near-planar slip
// parallel to the surface, its base inclined within +-1.2 degrees of beta.
LemCircle shallow_circle(double beta) {
  const double b = rad(beta), r = 1e4, depth = 2;
  const double mx = 500, my = 500 * std::tan(b);
  return {mx + (r - depth) * std::sin(b), my + (r - depth) * std::cos(b), r};
}

// Griffiths & Lane (1999) example 1: a 2:1 slope 10 m high, firm base at the toe's level (D = 1),
// gamma = 20 kN/m3, c' = 10 kPa (c'/gamma H = 0.05), phi' = 20 degrees.
LemSlope griffiths_lane() { return {{{-40, 10}, {0, 10}, {20, 0}, {60, 0}}, {{0, {20e3, 10e3, 20}}}, 0}; }

}  // namespace

TEST_CASE("Bishop on a near-planar slip in a dry cohesionless slope gives tan(phi)/tan(beta)", "[lem]") {
  // The slices' bases are inclined beta +- 1.2 degrees: the curvature changes F at second order, well
  // under 0.1 %.
  const double beta = 20, phi = 30;
  const double expected = std::tan(rad(phi)) / std::tan(rad(beta));
  const auto f = bishop_fos(infinite_slope(beta, phi), shallow_circle(beta), 0);
  REQUIRE(f);
  CHECK(*f == Approx(expected).epsilon(1e-3));
  // Pseudo-static: F = tan(phi) (cos b - kh sin b) / (sin b + kh cos b), Bishop's vertical equilibrium
  // being exact for a planar base.
  const double kh = 0.1, b = rad(beta);
  const auto fk = bishop_fos(infinite_slope(beta, phi), shallow_circle(beta), kh);
  REQUIRE(fk);
  CHECK(*fk ==
        Approx(std::tan(rad(phi)) * (std::cos(b) - kh * std::sin(b)) / (std::sin(b) + kh * std::cos(b))).epsilon(1e-3));
}

TEST_CASE("The circle search in a cohesionless slope tends to the infinite-slope value", "[lem]") {
  // Without cohesion the critical circle is the shallowest: the search finds F within 1 % above it.
  const double beta = 20, phi = 30;
  const double expected = std::tan(rad(phi)) / std::tan(rad(beta));
  const auto r = critical_circle(infinite_slope(beta, phi), 0);
  CHECK(r.fos >= expected * 0.999);
  CHECK(r.fos == Approx(expected).epsilon(0.01));
}

TEST_CASE("Bishop on Griffiths & Lane example 1 matches Bishop & Morgenstern's 1.38", "[lem]") {
  const auto r = critical_circle(griffiths_lane(), 0);
  CHECK(r.fos == Approx(1.38).epsilon(0.02));
  // The critical circle passes through (or at) the toe and stays above the base.
  REQUIRE(r.surface.size() == 81);
  CHECK(r.surface.back().x == Approx(20).margin(0.5));
  CHECK(r.circle.yc - r.circle.r >= -1e-9);
  for (const auto& p : r.surface) CHECK(p.y >= -1e-9);
}

TEST_CASE("A mirrored slope gives the same factor of safety and a mirrored circle", "[lem]") {
  LemSlope m = griffiths_lane();
  for (auto& p : m.surface) p.x = -p.x;
  std::reverse(m.surface.begin(), m.surface.end());
  const auto r = critical_circle(griffiths_lane(), 0), rm = critical_circle(m, 0);
  CHECK(rm.fos == Approx(r.fos).epsilon(1e-9));
  CHECK(rm.circle.xc == Approx(-r.circle.xc).epsilon(1e-9));
  CHECK(rm.surface.front().x == Approx(-r.surface.back().x).epsilon(1e-9));
}

TEST_CASE("Bands: two equal bands are one soil, and a weak upper band lowers the factor", "[lem]") {
  const LemCircle c{8, 22, 22};
  const auto one = bishop_fos(griffiths_lane(), c, 0);
  LemSlope two = griffiths_lane();
  two.bands = {{5, {20e3, 10e3, 20}}, {0, {20e3, 10e3, 20}}};
  const auto same = bishop_fos(two, c, 0);
  two.bands[0].soil.cohesion = 2e3;
  const auto weak = bishop_fos(two, c, 0);
  REQUIRE(one);
  REQUIRE(same);
  REQUIRE(weak);
  CHECK(*same == Approx(*one).epsilon(1e-12));
  CHECK(*weak < *one - 0.05);
}

TEST_CASE("Circles that enter the firm base or miss the slope are not admissible", "[lem]") {
  CHECK_FALSE(bishop_fos(griffiths_lane(), {8, 22, 25}, 0));    // reaches 3 m below the base
  CHECK_FALSE(bishop_fos(griffiths_lane(), {8, 40, 5}, 0));     // stays in the air
  CHECK_FALSE(bishop_fos(griffiths_lane(), {-40, 20, 15}, 0));  // runs past the surface's left end
  LemSlope bad = griffiths_lane();
  bad.surface[1].x = -50;
  CHECK_THROWS_AS(critical_circle(bad, 0), InputError);
}

TEST_CASE("kh lowers the factor of safety, and at kh = ky the factor is 1", "[lem]") {
  const auto r = limit_equilibrium(griffiths_lane(), 0);
  const auto k = critical_circle(griffiths_lane(), 0.1);
  CHECK(k.fos < r.fos - 0.1);
  CHECK(r.ky > 0.05);
  CHECK(r.ky < 0.5);
  CHECK(critical_circle(griffiths_lane(), r.ky).fos == Approx(1).margin(1e-3));
  // A slope that fails statically has no yield acceleration.
  LemSlope weak = griffiths_lane();
  weak.bands[0].soil = {20e3, 2e3, 15};
  const auto w = limit_equilibrium(weak, 0);
  CHECK(w.fos < 1);
  CHECK(w.ky == 0);
}

TEST_CASE("A vertical cut in purely cohesive soil stands to Taylor's H_c = 3.83 c / gamma", "[lem]") {
  // Taylor's stability number c / (gamma H F) = 0.261 for beta = 90 degrees, phi = 0: a toe circle (for
  // slopes steeper than 53 degrees the depth factor does not matter, so the base lies deep here). The
  // face is vertical within 1 mm.
  const LemSlope cut{{{-40, 10}, {0, 10}, {1e-3, 0}, {40, 0}}, {{-30, {20e3, 20e3, 0}}}, -20};
  const auto r = critical_circle(cut, 0);
  CHECK(20e3 / (20e3 * 10 * r.fos) == Approx(0.261).epsilon(0.01));
  CHECK(r.circle.yc - std::sqrt(r.circle.r * r.circle.r - r.circle.xc * r.circle.xc) == Approx(0).margin(0.05));
}
