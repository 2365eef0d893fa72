// Spencer's method against closed forms (a planar wedge) and against Bishop on circles.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "methods/limit_equilibrium.hpp"
#include "methods/spencer.hpp"

using namespace seismpm;

namespace {

double rad(double deg) { return deg * std::numbers::pi / 180; }

// Griffiths & Lane (1999) example 1: a 2:1 slope 10 m high, firm base at the toe's level,
// gamma = 20 kN/m3, c' = 10 kPa, phi' = 20 degrees.
LemSlope griffiths_lane() { return {{{-40, 10}, {0, 10}, {20, 0}, {60, 0}}, {{0, {20e3, 10e3, 20}}}, 0}; }

LemSettings spencer_settings() {
  LemSettings s;
  s.method = LemMethod::spencer;
  return s;
}

// A plane through the toe (20, 0) rising at `angle` to the crest flat (y = 10), with a start 5 m
// further up in the air: Culmann's wedge, one rigid block on one plane.
std::vector<LemPoint> plane_through_toe(double angle) {
  const double t = std::tan(rad(angle)), xe = 20 - 10 / t;
  return {{xe - 5, 10 + 5 * t}, {20, 0}};
}

struct Wedge {
  double weight, length;
};

// The wedge between that plane, the crest flat and the 2:1 face.
Wedge wedge(double angle) {
  // Corners (xe, 10), (0, 10), (20, 0): a triangle of base -xe on the crest and height 10.
  const double xe = 20 - 10 / std::tan(rad(angle));
  return {20e3 * 0.5 * (0 - xe) * 10, std::hypot(20 - xe, 10)};
}

}  // namespace

TEST_CASE("Spencer on a plane through the toe gives Culmann's wedge, static and pseudo-static", "[lem][spencer]") {
  // One plane: force equilibrium alone fixes F = (c L + W (cos a - kh sin a) tan phi) / (W (sin a + kh
  // cos a)), whatever the interslice inclination; the slices' midpoint rule is exact on the linear
  // ground except the one slice over the crest's corner.
  for (const double angle : {18.0, 22.0, 26.0})
    for (const double kh : {0.0, 0.15}) {
      const Wedge w = wedge(angle);
      const double a = rad(angle), tp = std::tan(rad(20));
      const double expected = (10e3 * w.length + w.weight * (std::cos(a) - kh * std::sin(a)) * tp) /
                              (w.weight * (std::sin(a) + kh * std::cos(a)));
      const LemResult r = surface_equilibrium(griffiths_lane(), plane_through_toe(angle), kh, spencer_settings());
      CHECK(r.fos == Approx(expected).epsilon(1e-3));
      CHECK(r.surface.front().x == Approx(20 - 10 / std::tan(a)).margin(1e-6));
      CHECK(r.surface.back().x == Approx(20).margin(1e-6));
      if (kh == 0) {
        // ky: the kh at which that F is 1, in closed form.
        const double ky = (10e3 * w.length + w.weight * (std::cos(a) * tp - std::sin(a))) /
                          (w.weight * (std::cos(a) + std::sin(a) * tp));
        CHECK(r.ky == Approx(ky).margin(2e-4));
      }
    }
}

TEST_CASE("Spencer on circles is within 1 % of Bishop (Fredlund & Krahn 1977: 2.073 against 2.080)", "[lem][spencer]") {
  // On circles Bishop's neglect of the interslice shear changes F little: Fredlund & Krahn's example
  // (a 2:1 slope, c' = 600 psf, phi' = 20) gives Spencer 0.34 % below Bishop. Here: circles through and
  // below the toe of Griffiths & Lane's slope.
  for (const LemCircle c : {LemCircle{8, 22, 22}, LemCircle{10, 20, 19.5}, LemCircle{5, 25, 25}}) {
    const auto b = bishop_fos(griffiths_lane(), c, 0);
    const auto s = circle_fos(griffiths_lane(), c, 0, spencer_settings());
    REQUIRE(b);
    REQUIRE(s);
    CHECK(*s == Approx(*b).epsilon(0.01));
  }
  // The search with Spencer finds Bishop & Morgenstern's 1.38 as Bishop's search does (2 %).
  const LemResult r = critical_circle(griffiths_lane(), 0, {}, spencer_settings());
  CHECK(r.fos == Approx(1.38).epsilon(0.02));
  CHECK(r.fos == Approx(critical_circle(griffiths_lane(), 0).fos).epsilon(0.01));
  CHECK(r.theta > 0);  // the interslice forces rise towards the toe's side as the mass slides out
  CHECK(r.theta < 45);
}

TEST_CASE("Spencer with kh = 0 satisfies both equilibria: F from force and moment agree", "[lem][spencer]") {
  // A polyline surface through the Griffiths & Lane slope (non-circular): the solution's F and theta
  // make the moment residual vanish; F stays near the critical circle's (a non-circular surface near
  // it cannot be much safer nor less safe than the circles around).
  const std::vector<LemPoint> path{{-14, 12}, {-6, 4}, {8, -0.0}, {20, 0}};
  const LemResult r = surface_equilibrium(griffiths_lane(), path, 0, spencer_settings());
  CHECK(r.fos > 1.3);
  CHECK(r.fos < 1.8);
  CHECK(r.ky > 0);
  const LemResult k = surface_equilibrium(griffiths_lane(), path, r.ky, spencer_settings());
  CHECK(k.fos == Approx(1).margin(1e-3));
}

TEST_CASE("A mirrored slope and surface give the same Spencer factor", "[lem][spencer]") {
  LemSlope m = griffiths_lane();
  for (auto& p : m.surface) p.x = -p.x;
  std::reverse(m.surface.begin(), m.surface.end());
  auto path = plane_through_toe(22);
  for (auto& p : path) p.x = -p.x;
  std::reverse(path.begin(), path.end());
  const LemResult r = surface_equilibrium(griffiths_lane(), plane_through_toe(22), 0, spencer_settings());
  const LemResult rm = surface_equilibrium(m, path, 0, spencer_settings());
  CHECK(rm.fos == Approx(r.fos).epsilon(1e-9));
  CHECK(rm.surface.front().x == Approx(-r.surface.back().x).epsilon(1e-9));
}

TEST_CASE("A given surface that ends underground or misses the slope is an error", "[lem][spencer][errors]") {
  const auto st = spencer_settings();
  CHECK_THROWS_AS(surface_equilibrium(griffiths_lane(), {{-20, 12}, {10, 2}}, 0, st), InputError);   // ends inside
  CHECK_THROWS_AS(surface_equilibrium(griffiths_lane(), {{-20, 20}, {50, 20}}, 0, st), InputError);  // in the air
  CHECK_THROWS_AS(surface_equilibrium(griffiths_lane(), {{0, 20}, {-5, 0}}, 0, st), InputError);     // x decreasing
}
