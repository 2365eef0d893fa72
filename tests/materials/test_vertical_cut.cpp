// An MPM run of a vertical cut in cohesive-frictional soil: it stands at 0.7 and collapses at 1.3 times
// the critical height H_c = 3.83 c / gamma tan(45 + phi/2) (the classical upper bound). 16 cells over the
// height: without the cell-averaged volumetric strain this mesh locks and the 1.3 H_c cut stands.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "core/local_damping.hpp"
#include "core/model.hpp"
#include "materials/mohr_coulomb.hpp"

using namespace seismpm;

namespace {

// Largest displacement of the cut's crest region after the soil settles under gravity for `duration`.
double crest_displacement(double H, double duration, double& kinetic) {
  const double rho = 2000, g = 9.81;
  const double h = H / 16;
  ModelSettings<2> s;
  s.lower = Vec<2>(0, 0);
  s.upper = Vec<2>(3.5 * H, 1.25 * H);
  s.cell = h;
  s.gravity = Vec<2>(0, -g);
  Model<2> m(s);
  MohrCoulombParameters p;
  p.density = rho, p.young = 50e6, p.poisson = 0.3;
  // H_c = 3.83 c / gamma tan(45 + phi/2) assumes the soil takes tension: no cut-off below the apex.
  p.cohesion = 10e3, p.friction = 20, p.dilation = 0, p.tension = 10e3 / std::tan(20 * std::numbers::pi / 180);
  const int mat = m.add_material(std::make_shared<MohrCoulomb>(p));
  const int body = m.add_body("soil", 2);
  m.fill_box(body, mat, Vec<2>(0, 0), Vec<2>(2 * H, H));  // the cut face is x = 2H
  m.grid().fix(Side::Left, FixX);
  m.grid().fix(Side::Bottom, FixX | FixY);
  m.add_fix(std::make_shared<LocalDamping<2>>(0.7));
  m.run(duration);
  double worst = 0.0;
  const auto& P = m.particles();
  for (std::size_t i = 0; i < P.size(); ++i) {
    const Vec<2> x0 = P.x[i] - P.u[i];
    if (x0[0] > 2 * H - 0.5 * H && x0[1] > 0.5 * H) worst = std::max(worst, P.u[i].norm());
  }
  kinetic = m.kinetic_energy();
  return worst;
}

}  // namespace

TEST_CASE("a vertical cut stands at 0.7 H_c and collapses at 1.3 H_c", "[materials][mohr_coulomb][verification]") {
  const double c = 10e3, phi = 20, gamma = 2000 * 9.81;
  const double Hc = 3.83 * c / gamma * std::tan((45 + phi / 2) * std::numbers::pi / 180);
  double ke_low = 0, ke_high = 0;
  const double low = crest_displacement(0.7 * Hc, 3.0, ke_low);
  const double high = crest_displacement(1.3 * Hc, 3.0, ke_high);
  CAPTURE(Hc, low, high, ke_low, ke_high);
  CHECK(low < 0.01 * 0.7 * Hc);   // stands: crest moves less than 1 % of the height
  CHECK(high > 0.05 * 1.3 * Hc);  // collapses: crest moves more than 5 % of the height (and goes on)
}
