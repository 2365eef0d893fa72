// Crack closure: a soil without tensile strength that opened under tension closes again without
// building mean stress until it is back at its initial density; only then does it take load,
// elastically from zero.
#include <catch2/catch.hpp>

#include "materials/mohr_coulomb.hpp"
#include "support/models.hpp"
#include "support/nodal_velocity.hpp"

using namespace seismpm;

namespace {

struct Cycle {
  double at_initial_volume;  // largest |stress| when back at the initial volume (Pa)
  double mean_stress_after;  // mean stress after the net compression (Pa, tension positive)
  double net_volumetric;     // net volumetric strain of the block at the end
};

// Opens a Mohr-Coulomb block (tension 0) by 4 % in volume, closes it back and then compresses it
// by 0.4 % more.
Cycle open_close_compress(bool crack_closure) {
  ModelSettings<2> s;
  s.lower = Vec<2>::Zero();
  s.upper = Vec<2>::Constant(2.0);
  s.cell = 0.1;
  s.fixed_dt = 1e-4;
  s.crack_closure = crack_closure;
  Model<2> m(s);
  MohrCoulombParameters mc;
  mc.density = 1000, mc.young = 1e7, mc.poisson = 0.3, mc.cohesion = 5e3, mc.friction = 30, mc.tension = 0;
  const int mat = m.add_material(std::make_shared<MohrCoulomb>(mc));
  const int body = m.add_body("soil", 2);
  m.fill_box(body, mat, Vec<2>::Constant(0.8), Vec<2>::Constant(1.2));
  // A uniform dilation v = rate (x - centre): every particle sees the same volumetric strain rate.
  auto drive = std::make_shared<test::NodalVelocityField<2>>(nullptr);
  m.add_fix(drive);
  auto dilate = [&](double rate) {
    drive->field = [rate](const Vec<2>& x) { return Vec<2>(rate * (x - Vec<2>::Constant(1.0))); };
  };
  auto& P = m.particles();
  auto volume = [&] {
    double v = 0.0;
    for (double vp : P.volume) v += vp;
    return v;
  };
  const double v0 = volume();
  auto largest_stress = [&] {
    double worst = 0.0;
    for (const auto& sp : P.stress) worst = std::max(worst, sp.cwiseAbs().maxCoeff());
    return worst;
  };
  const double rate = 0.1, open_time = 0.2, extra_time = 0.02;  // 2 % per axis open, 0.2 % per axis more
  dilate(rate);
  m.run(open_time);
  CHECK(volume() / v0 == Approx(std::exp(2 * rate * open_time)).epsilon(1e-3));
  CHECK(largest_stress() < 1e-6 * mc.young);  // at the tension cut-off while opening
  dilate(-rate);
  m.run(open_time);
  Cycle c;
  c.at_initial_volume = largest_stress();
  m.run(extra_time);
  double mean = 0.0;
  for (const auto& sp : P.stress) mean += (sp[0] + sp[1] + sp[2]) / 3.0;
  c.mean_stress_after = mean / static_cast<double>(P.size());
  c.net_volumetric = volume() / v0 - 1.0;
  return c;
}

}  // namespace

TEST_CASE("an opened tensionless soil closes freely, then loads elastically", "[core][crack_closure]") {
  const Cycle with = open_close_compress(true);
  const Cycle without = open_close_compress(false);
  CAPTURE(with.at_initial_volume, without.at_initial_volume, with.mean_stress_after, with.net_volumetric);
  const double E = 1e7, nu = 0.3;
  const double K = E / (3 * (1 - 2 * nu));
  // Back at its initial volume the closed soil is (all but) stress-free ...
  CHECK(with.at_initial_volume < 1e-3 * E * 0.002);
  // ... where without closure the elastic law resisted closing the whole 4 % it had opened.
  CHECK(without.at_initial_volume > 0.2 * E * 0.02);
  // Then plane-strain elastic compression from zero: eps_xx = eps_yy = eps, eps_zz = 0, so
  // sxx = syy = 2 (lambda + G) eps, szz = 2 lambda eps, mean (6 lambda + 4 G) eps / 3 = 2 K eps.
  const double eps = with.net_volumetric / 2;
  CHECK(with.net_volumetric == Approx(std::exp(-2 * 0.1 * 0.02) - 1).epsilon(0.02));
  CHECK(with.mean_stress_after == Approx(2 * K * eps).epsilon(0.01));
}
