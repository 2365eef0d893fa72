// Mohr-Coulomb: stress-point returns against the closed form, and drained triaxial tests.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <omp.h>

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

// The batch update settles elastic trials per thread block and shares the plastic returns among the
// threads: every particle must get exactly what a batch of itself alone gives (and a return exactly
// where integrate() makes one), whatever the number of threads and however the yielding particles are
// spread over the blocks (here all in the first third).
TEST_CASE("the batch update is one integrate() per particle for any number of threads",
          "[materials][mohr_coulomb][parallel]") {
  const int saved = omp_get_max_threads();
  for (const bool softening : {false, true}) {
    auto p = soil(5e3, 30, 5, 0.0);
    p.softening = softening;
    p.residual_cohesion = 1e3;
    p.residual_friction = 25;
    p.softening_strain = 0.05;
    const MohrCoulomb mc(p);
    const int n = 900;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Sym> stress(n), de(n);
    std::vector<double> plastic(n);
    for (int k = 0; k < n; ++k) {
      stress[k] = diagonal(-100e3, -100e3, -100e3);
      // Large increments (plastic) in the first third, small ones (elastic) after; a third of them 3D.
      const double size = k < n / 3 ? 2e-3 : 1e-6;
      for (int i = 0; i < 4; ++i) de[k][i] = size * u(rng);
      de[k][4] = de[k][5] = k % 3 == 0 ? size * u(rng) : 0.0;
      plastic[k] = 0.02 * (u(rng) + 1.0);
    }
    // The batch visits particles in a shuffled order, as a material's list over a sorted model would.
    std::vector<int> index(n);
    for (int k = 0; k < n; ++k) index[k] = (k * 7) % n;
    auto update = [&](const int* list, int count, std::vector<Sym>& s, std::vector<double>& e,
                      std::vector<std::uint8_t>& yield) {
      StressUpdate b;
      b.index = list;
      b.count = count;
      b.stress = s.data();
      b.strain_increment = de.data();
      b.plastic_strain = e.data();
      b.yield = yield.data();
      mc.update_stress(b);
    };
    omp_set_num_threads(1);
    std::vector<Sym> s1 = stress;
    std::vector<double> e1 = plastic;
    std::vector<std::uint8_t> yield1(n, 2);
    for (int k = 0; k < n; ++k) update(&k, 1, s1, e1, yield1);
    for (const int threads : {1, 2, 3, 5}) {
      omp_set_num_threads(threads);
      std::vector<Sym> s = stress;
      std::vector<double> e = plastic;
      std::vector<std::uint8_t> yield(n, 2);
      update(index.data(), n, s, e, yield);
      int plastic_count = 0, mismatches = 0, kinds = 0;
      for (int k = 0; k < n; ++k) {
        const bool yielded = mc.integrate(stress[k], de[k], plastic[k]).kind != MohrCoulomb::Return::Elastic;
        plastic_count += yielded;
        kinds += yield1[k] == yielded;
        mismatches += !(s[k] == s1[k] && e[k] == e1[k] && yield[k] == yield1[k]);
      }
      CHECK(kinds == n);
      CAPTURE(softening, threads, plastic_count);
      CHECK(mismatches == 0);
      CHECK(plastic_count > n / 6);      // the test exercises the shared returns ...
      CHECK(plastic_count < 2 * n / 3);  // ... and the inline elastic ones
    }
  }
  omp_set_num_threads(saved);
}

// The batch update makes plane-strain returns at fixed strength in a vectorised form of its own: every
// one must be integrate()'s (the general return's) to round-off, the face, the edges, the apex and
// the tension planes alike. Random plane-strain trials around the surface, with and without dilation
// and a tension cut-off, in a batch whose size leaves the vector loop and its remainder some entries.
TEST_CASE("the batch's plane-strain returns are integrate()'s to round-off", "[materials][mohr_coulomb]") {
  for (const auto& p : {soil(0.0, 19.8, 0.0, 0.0), soil(10e3, 30, 10, 2e3), soil(5e3, 35, 35, 0.0)}) {
    const MohrCoulomb mc(p);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const int n = 1001;
    std::vector<Sym> stress(n), de(n);
    std::vector<double> plastic(n, 0.0);
    for (int k = 0; k < n; ++k) {
      const double mean = -50e3 * (1.0 + u(rng));  // 0 to -100 kPa: near the apex too
      stress[k] = diagonal(mean * (1.0 + 0.3 * u(rng)), mean * (1.0 + 0.3 * u(rng)), mean * (1.0 + 0.3 * u(rng)));
      stress[k][3] = 0.2 * mean * u(rng);
      for (int i = 0; i < 4; ++i) de[k][i] = 2e-3 * u(rng);
      de[k][4] = de[k][5] = 0.0;
    }
    std::vector<int> index(n);
    for (int k = 0; k < n; ++k) index[k] = k;
    std::vector<Sym> s = stress;
    std::vector<double> e = plastic;
    std::vector<std::uint8_t> yield(n, 2);
    StressUpdate b{index.data(), n, s.data(), de.data(), e.data(), yield.data()};
    mc.update_stress(b);
    int faces = 0, others = 0;
    double worst = 0.0, worst_shear = 0.0;
    for (int k = 0; k < n; ++k) {
      const auto r = mc.integrate(stress[k], de[k], plastic[k]);
      faces += r.kind == MohrCoulomb::Return::Face;
      others += r.kind != MohrCoulomb::Return::Face && r.kind != MohrCoulomb::Return::Elastic;
      // Relative to the stress level: near the apex the result is round-off of the trial's size.
      const double size = std::max(stress[k].cwiseAbs().maxCoeff(), 1.0);
      worst = std::max(worst, (s[k] - r.stress).cwiseAbs().maxCoeff() / size);
      worst_shear = std::max(worst_shear, std::abs(e[k] - r.shear_increment) / std::max(r.shear_increment, 1e-12));
      REQUIRE(yield[k] == (r.kind != MohrCoulomb::Return::Elastic));
    }
    CAPTURE(p.cohesion, p.friction, faces, others);
    CHECK(faces > n / 10);   // the face ...
    CHECK(others > n / 50);  // ... and the other returns are exercised
    CHECK(worst < 1e-12);
    CHECK(worst_shear < 1e-9);
  }
}
