// Drucker-Prager: the fits to Mohr-Coulomb and the limit loads they promise.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "element_test.hpp"
#include "materials/drucker_prager.hpp"
#include "materials/mohr_coulomb.hpp"

using namespace seismpm;

namespace {
const double kDeg = std::numbers::pi / 180.0;

DruckerPragerParameters dp_soil(DruckerPragerFit fit, double psi) {
  DruckerPragerParameters p;
  p.density = 2000, p.young = 50e6, p.poisson = 0.3;
  p.cohesion = 10e3, p.friction = 30, p.dilation = psi, p.tension = 0;
  p.fit = fit;
  return p;
}

MohrCoulombParameters mc_soil(double psi) {
  MohrCoulombParameters p;
  p.density = 2000, p.young = 50e6, p.poisson = 0.3;
  p.cohesion = 10e3, p.friction = 30, p.dilation = psi, p.tension = 0;
  return p;
}

Sym hydrostatic(double p) {
  Sym s = Sym::Zero();
  s[0] = s[1] = s[2] = p;
  return s;
}
}  // namespace

TEST_CASE("Drucker-Prager fits have their closed forms", "[materials][drucker_prager]") {
  const double s = std::sin(30 * kDeg), t = std::tan(30 * kDeg), c = 10e3;
  auto k0 = drucker_prager_constants(dp_soil(DruckerPragerFit::PlaneStrain, 0.0));
  CHECK(k0.alpha == Approx(s / 3));
  CHECK(k0.k == Approx(c * std::cos(30 * kDeg)));
  CHECK(k0.beta == 0.0);
  auto ka = drucker_prager_constants(dp_soil(DruckerPragerFit::PlaneStrain, 30.0));
  CHECK(ka.alpha == Approx(t / std::sqrt(9 + 12 * t * t)));
  CHECK(ka.k == Approx(3 * c / std::sqrt(9 + 12 * t * t)));
  auto ko = drucker_prager_constants(dp_soil(DruckerPragerFit::Outer, 0.0));
  CHECK(ko.alpha == Approx(2 * s / (std::sqrt(3.0) * (3 - s))));
  CHECK_THROWS_WITH(parse_fit("middle"), Catch::Contains("plane_strain|outer|inner"));
}

TEST_CASE("plane-strain biaxial test: the plane_strain fit gives the Mohr-Coulomb limit load",
          "[materials][drucker_prager]") {
  const double psi = GENERATE(0.0, 10.0);
  const DruckerPrager dp(dp_soil(DruckerPragerFit::PlaneStrain, psi));
  const MohrCoulomb mc(mc_soil(psi));
  const double lambda = ElasticConstants{50e6, 0.3}.lambda(), G = dp.shear_modulus();
  const test::PointUpdate dp_update = [&](const Sym& s, const Sym& de, bool) { return dp.integrate(s, de).stress; };
  const test::PointUpdate mc_update = [&](const Sym& s, const Sym& de, bool) {
    return mc.integrate(s, de, 0.0).stress;
  };
  for (double p0 : {50e3, 200e3}) {
    CAPTURE(psi, p0);
    // sigma_xx held at -p0, eps_zz = 0 (plane strain), yy shortened well past the peak.
    const auto a = test::element_test(dp_update, hydrostatic(-p0), 1, -2e-4, 400, {0}, lambda, G);
    const auto b = test::element_test(mc_update, hydrostatic(-p0), 1, -2e-4, 400, {0}, lambda, G);
    CHECK(a.back() == Approx(b.back()).epsilon(0.01));
    const double s = std::sin(30 * kDeg), k = (1 + s) / (1 - s), sc = 2 * 10e3 * std::cos(30 * kDeg) / (1 - s);
    CHECK(b.back() == Approx(-p0 * k - sc).epsilon(0.005));  // MC's own plane-strain limit
  }
}

TEST_CASE("outer and inner fits match Mohr-Coulomb in triaxial compression and extension",
          "[materials][drucker_prager]") {
  const DruckerPrager outer(dp_soil(DruckerPragerFit::Outer, 0.0));
  const DruckerPrager inner(dp_soil(DruckerPragerFit::Inner, 0.0));
  const double lambda = ElasticConstants{50e6, 0.3}.lambda(), G = outer.shear_modulus();
  const double s = std::sin(30 * kDeg), k = (1 + s) / (1 - s), sc = 2 * 10e3 * std::cos(30 * kDeg) / (1 - s);
  const double p0 = 100e3;
  const test::PointUpdate o = [&](const Sym& st, const Sym& de, bool) { return outer.integrate(st, de).stress; };
  const test::PointUpdate i = [&](const Sym& st, const Sym& de, bool) { return inner.integrate(st, de).stress; };
  const auto comp = test::element_test(o, hydrostatic(-p0), 1, -2e-4, 150, {0, 2}, lambda, G);
  CHECK(comp.back() == Approx(-p0 * k - sc).epsilon(0.005));
  const auto ext = test::element_test(i, hydrostatic(-p0), 1, 2e-4, 150, {0, 2}, lambda, G);
  CHECK(ext.back() == Approx((-p0 + sc) / k).epsilon(0.005));
}

TEST_CASE("Drucker-Prager returns lie on the cone, the apex or the cut-off", "[materials][drucker_prager]") {
  const DruckerPrager dp(dp_soil(DruckerPragerFit::PlaneStrain, 0.0));
  Sym de = Sym::Zero();
  de[0] = -3e-3, de[1] = 1e-3, de[3] = 2e-3;
  const auto r = dp.integrate(hydrostatic(-100e3), de);
  CHECK(r.plastic);
  CHECK(std::abs(dp.yield_function(r.stress)) < 1e-8 * 100e3);
  CHECK(std::abs(trace(r.stress) - trace(hydrostatic(-100e3)) -
                 3 * ElasticConstants{50e6, 0.3}.bulk() * (de[0] + de[1])) <
        1e-6);  // psi = 0: no plastic volume change
  // Pulled apart: the mean stress stops at the cut-off (0), the result stays admissible.
  de.setZero();
  de[0] = de[1] = de[2] = 1e-3;
  const auto t = dp.integrate(Sym::Zero(), de);
  CHECK(trace(t.stress) / 3 == Approx(0.0).margin(1e-9));
  CHECK(dp.yield_function(t.stress) <= 1e-9);
  CHECK(t.stress.allFinite());
  DruckerPragerParameters bad = dp_soil(DruckerPragerFit::PlaneStrain, 0.0);
  bad.tension = 1e9;
  CHECK_THROWS_WITH(DruckerPrager(bad), Catch::Contains("tension"));
}
