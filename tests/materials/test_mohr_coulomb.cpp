// Mohr-Coulomb: stress-point returns against the closed form, and drained triaxial tests.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>

#include "core/error.hpp"
#include "element_test.hpp"
#include "materials/mohr_coulomb.hpp"
#include "materials/principal_stress.hpp"

using namespace seismpm;

namespace {

MohrCoulombParameters soil(double c = 10e3, double phi = 30, double psi = 0, double tension = 0) {
  MohrCoulombParameters p;
  p.density = 2000;
  p.young = 50e6;
  p.poisson = 0.3;
  p.cohesion = c;
  p.friction = phi;
  p.dilation = psi;
  p.tension = tension;
  return p;
}

Sym diagonal(double a, double b, double c) {
  Sym s = Sym::Zero();
  s[0] = a, s[1] = b, s[2] = c;
  return s;
}

// Elastic strain increment that takes stress s0 to s (the trial the test wants).
Sym strain_to(const MohrCoulomb& m, const Sym& s0, const Sym& s) {
  const double G = m.shear_modulus(), K = m.bulk_modulus();
  const Sym ds = s - s0;
  const double tr = trace(ds);
  Sym e = ds / (2.0 * G);
  for (int i = 0; i < 3; ++i) e[i] += tr / 9.0 * (1.0 / K - 3.0 / (2.0 * G));
  return e;
}

const double kDeg = std::numbers::pi / 180.0;

}  // namespace

TEST_CASE("Mohr-Coulomb returns land on the yield surface: face, both edges, apex, tension",
          "[materials][mohr_coulomb]") {
  const double psi = GENERATE(0.0, 10.0);
  CAPTURE(psi);
  const MohrCoulomb mc(soil(10e3, 30, psi, 0.0));
  const double c_cot = 10e3 / std::tan(30 * kDeg);
  struct Case {
    const char* name;
    Sym trial;
    MohrCoulomb::Return expected;
  };
  const Case cases[] = {
      {"face", diagonal(-50e3, -150e3, -400e3), MohrCoulomb::Return::Face},
      {"compression edge (s1 = s2)", diagonal(-50e3, -50e3, -400e3), MohrCoulomb::Return::CompressionEdge},
      {"extension edge (s2 = s3)", diagonal(-20e3, -300e3, -300e3), MohrCoulomb::Return::ExtensionEdge},
      {"tension plane", diagonal(3e3, -20e3, -25e3), MohrCoulomb::Return::Tension},
  };
  for (const auto& c : cases) {
    CAPTURE(c.name);
    const auto r = mc.integrate(Sym::Zero(), strain_to(mc, Sym::Zero(), c.trial), 0.0);
    CHECK(r.kind == c.expected);
    const double f = mc.yield_function(r.stress);
    const Eigen::Vector3d v = principal_values(r.stress);
    if (c.expected == MohrCoulomb::Return::Tension) {
      CHECK(std::abs(v[0]) < 1e-8 * 25e3);  // s1 = T = 0
      CHECK(f < 0.0);
    } else {
      CHECK(std::abs(f) < 1e-8 * 400e3);  // relative |f| < 1e-8
    }
    if (psi == 0.0 && c.expected != MohrCoulomb::Return::Tension)
      CHECK(std::abs(trace(r.plastic_strain)) < 1e-12 * r.plastic_strain.norm());  // isochoric
    if (c.expected == MohrCoulomb::Return::CompressionEdge) CHECK(v[0] == Approx(v[1]).margin(1e-6));
    if (c.expected == MohrCoulomb::Return::ExtensionEdge) CHECK(v[1] == Approx(v[2]).margin(1e-6));
    CHECK(r.shear_increment > 0.0);
  }
  SECTION("apex: beyond c cot(phi) in tension, with the cut-off at the apex value") {
    const MohrCoulomb at_apex(soil(10e3, 30, psi, c_cot));
    const auto r = at_apex.integrate(Sym::Zero(), strain_to(at_apex, Sym::Zero(), diagonal(30e3, 25e3, 22e3)), 0.0);
    // With T at the apex value the tension planes pass through the apex too.
    CHECK((r.kind == MohrCoulomb::Return::Apex || r.kind == MohrCoulomb::Return::Mixed));
    const Eigen::Vector3d v = principal_values(r.stress);
    for (int i = 0; i < 3; ++i) CHECK(v[i] == Approx(c_cot).epsilon(1e-10));
  }
}

TEST_CASE("cohesionless soil at zero stress returns to the origin without NaN", "[materials][mohr_coulomb]") {
  const MohrCoulomb sand(soil(0.0, 19.8, 0.0, 0.0));
  // At rest at zero stress: elastic, exactly zero.
  auto r = sand.integrate(Sym::Zero(), Sym::Zero(), 0.0);
  CHECK(r.stress.allFinite());
  CHECK(r.stress.norm() == 0.0);
  // Stretched from zero stress: back to the apex, the origin.
  Sym de = Sym::Zero();
  de[0] = 1e-4, de[1] = 2e-5, de[3] = 3e-5;
  r = sand.integrate(Sym::Zero(), de, 0.0);
  CHECK(r.stress.allFinite());
  CHECK(r.stress.cwiseAbs().maxCoeff() < 1e-9);
  // Sheared from zero stress: onto the cone, finite.
  de.setZero();
  de[3] = 1e-4;
  r = sand.integrate(Sym::Zero(), de, 0.0);
  CHECK(r.stress.allFinite());
  CHECK(sand.yield_function(r.stress) < 1e-6);
}

TEST_CASE("Mohr-Coulomb does not depend on the orientation of the axes", "[materials][mohr_coulomb]") {
  const MohrCoulomb mc(soil(5e3, 25, 5, 0.0));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 50; ++k) {
    Sym s0 = Sym::Zero(), de = Sym::Zero();
    s0[0] = -100e3 + 20e3 * u(rng), s0[1] = -60e3 + 20e3 * u(rng), s0[2] = -80e3 + 10e3 * u(rng), s0[3] = 10e3 * u(rng);
    for (int i = 0; i < 4; ++i) de[i] = 2e-3 * u(rng);
    const Mat3 R =
        Eigen::AngleAxisd(3.0 * u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
    const auto rotate = [&](const Sym& s) { return to_voigt(R * to_matrix(s) * R.transpose()); };
    const auto a = mc.integrate(s0, de, 0.0);                  // plane-strain closed form
    const auto b = mc.integrate(rotate(s0), rotate(de), 0.0);  // general 3D eigen path
    CAPTURE(k);
    CHECK((rotate(a.stress) - b.stress).norm() < 1e-8 * std::max(a.stress.norm(), 1e3));
    CHECK(a.shear_increment == Approx(b.shear_increment).margin(1e-12));
  }
}

TEST_CASE("drained triaxial compression and extension reach the Mohr-Coulomb limit", "[materials][mohr_coulomb]") {
  const double psi = GENERATE(0.0, 10.0);
  const double c = 10e3, phi = 30;
  const MohrCoulomb mc(soil(c, phi, psi, 0.0));
  const double lambda = ElasticConstants{50e6, 0.3}.lambda(), G = mc.shear_modulus();
  const double s = std::sin(phi * kDeg), k = (1 + s) / (1 - s), sigma_c = 2 * c * std::cos(phi * kDeg) / (1 - s);
  const test::PointUpdate update = [&](const Sym& stress, const Sym& de, bool) {
    return mc.integrate(stress, de, 0.0).stress;
  };
  for (double p0 : {50e3, 100e3, 200e3}) {
    CAPTURE(psi, p0);
    const Sym start = diagonal(-p0, -p0, -p0);
    // Compression: axial (yy) shortening; radial xx and zz held at -p0.
    const auto comp = test::element_test(update, start, 1, -2e-4, 150, {0, 2}, lambda, G);
    const double q_limit = -p0 * (1 - k) + sigma_c;  // sigma_r - sigma_a at failure
    CHECK((-p0 - comp.back()) == Approx(q_limit).epsilon(0.005));
    // Extension: axial lengthening until sigma_a is the minor compressive stress.
    const auto ext = test::element_test(update, start, 1, 2e-4, 150, {0, 2}, lambda, G);
    const double a_limit = (-p0 + sigma_c) / k;  // sigma_r = k sigma_a - sigma_c
    CHECK(ext.back() == Approx(a_limit).epsilon(0.005));
  }
}

TEST_CASE("softening takes c and phi to their residual values", "[materials][mohr_coulomb]") {
  auto p = soil(20e3, 30, 0, 0.0);
  p.softening = true;
  p.residual_cohesion = 2e3;
  p.residual_friction = 20;
  p.softening_strain = 0.05;
  const MohrCoulomb mc(p);
  const double lambda = ElasticConstants{50e6, 0.3}.lambda(), G = mc.shear_modulus();
  double plastic = 0.0;
  const test::PointUpdate update = [&](const Sym& stress, const Sym& de, bool commit) {
    const auto r = mc.integrate(stress, de, plastic);
    if (commit) plastic += r.shear_increment;
    return r.stress;
  };
  // Triaxial compression at 100 kPa confinement: the peak, then the residual limit.
  const auto path = test::element_test(update, diagonal(-100e3, -100e3, -100e3), 1, -2e-4, 800, {0, 2}, lambda, G);
  double peak = 0.0;
  for (double a : path) peak = std::max(peak, -a);
  const double sp = std::sin(30 * kDeg), kp = (1 + sp) / (1 - sp), scp = 2 * 20e3 * std::cos(30 * kDeg) / (1 - sp);
  const double sr = std::sin(20 * kDeg), kr = (1 + sr) / (1 - sr), scr = 2 * 2e3 * std::cos(20 * kDeg) / (1 - sr);
  CAPTURE(peak, path.back(), plastic);
  CHECK(peak == Approx(100e3 * kp + scp).epsilon(0.01));  // the peak strength first
  CHECK(plastic > p.softening_strain);
  CHECK(-path.back() == Approx(100e3 * kr + scr).epsilon(0.005));  // then the residual one
}

TEST_CASE("Mohr-Coulomb parameters out of range are refused by name", "[materials][mohr_coulomb]") {
  auto p = soil();
  p.friction = 90;
  CHECK_THROWS_WITH(MohrCoulomb(p), Catch::Contains("friction"));
  p = soil();
  p.dilation = 40;
  CHECK_THROWS_WITH(MohrCoulomb(p), Catch::Contains("dilation"));
  p = soil();
  p.cohesion = -1;
  CHECK_THROWS_WITH(MohrCoulomb(p), Catch::Contains("cohesion"));
  p = soil();
  p.tension = 1e6;
  CHECK_THROWS_WITH(MohrCoulomb(p), Catch::Contains("apex"));
  p = soil();
  p.softening = true;
  p.residual_cohesion = 2 * p.cohesion;
  p.softening_strain = 0.1;
  CHECK_THROWS_WITH(MohrCoulomb(p), Catch::Contains("residual cohesion"));
}
