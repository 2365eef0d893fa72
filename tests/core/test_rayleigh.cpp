// Rayleigh damping: the coefficients from a ratio at two frequencies, the damping ratio the vibrating
// bar's first mode shows (logarithmic decrement) against xi(w) = alpha / 2w + beta w / 2 for the mass
// part, the stiffness part and the two-frequency form, the mass part through contact fields, and the
// stable time step that stiffness-proportional damping shortens, and strength reduction keeping it.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "cases/vibrating_bar.hpp"
#include "materials/drucker_prager.hpp"
#include "materials/mohr_coulomb.hpp"

using namespace seismpm;

namespace {

constexpr double kPi = std::numbers::pi;

// Damping ratio and circular frequency of a decaying oscillation v(t), from the extremes of |v| between
// its zero crossings (skipping the first half-cycle, which starts at the initial condition): successive
// extremes of A exp(-xi w t) cos(w_d t + phi) are half a damped period apart and fall by exp(-pi xi /
// sqrt(1 - xi^2)).
struct Decay {
  double ratio = 0.0, omega = 0.0;
  int extremes = 0;
};

Decay measure_decay(const std::vector<double>& t, const std::vector<double>& v) {
  std::vector<double> crossings, peaks;
  double peak = 0.0;
  for (std::size_t k = 1; k < v.size(); ++k) {
    if ((v[k - 1] > 0.0) != (v[k] > 0.0)) {
      crossings.push_back(t[k - 1] + (t[k] - t[k - 1]) * v[k - 1] / (v[k - 1] - v[k]));
      if (crossings.size() > 1) peaks.push_back(peak);
      peak = 0.0;
    }
    peak = std::max(peak, std::abs(v[k]));
  }
  Decay d;
  d.extremes = static_cast<int>(peaks.size());
  if (peaks.size() < 2) return d;
  const double delta = std::log(peaks.front() / peaks.back()) / static_cast<double>(peaks.size() - 1);
  d.ratio = delta / std::sqrt(kPi * kPi + delta * delta);
  const double damped_period = 2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  d.omega = 2.0 * kPi / damped_period / std::sqrt(1.0 - d.ratio * d.ratio);
  return d;
}

}  // namespace

TEST_CASE("rayleigh: a ratio at two frequencies gives that ratio at both, less between", "[core][rayleigh]") {
  const Rayleigh r = Rayleigh::from_ratio(0.05, 1.0, 5.0);
  const double w1 = 2 * kPi, w2 = 10 * kPi;
  CHECK(r.alpha == Approx(2 * 0.05 * w1 * w2 / (w1 + w2)));
  CHECK(r.beta == Approx(2 * 0.05 / (w1 + w2)));
  CHECK(r.ratio_at(w1) == Approx(0.05));
  CHECK(r.ratio_at(w2) == Approx(0.05));
  CHECK(r.ratio_at(std::sqrt(w1 * w2)) < 0.05);
  CHECK(r.ratio_at(0.5 * w1) > 0.05);
  CHECK(r.ratio_at(2.0 * w2) > 0.05);

  CHECK_THROWS_WITH(Rayleigh::from_ratio(-0.01, 1, 5), Catch::Contains("'ratio' must be in [0, 1)"));
  CHECK_THROWS_WITH(Rayleigh::from_ratio(1.0, 1, 5), Catch::Contains("'ratio' must be in [0, 1)"));
  CHECK_THROWS_WITH(Rayleigh::from_ratio(0.05, 5, 5), Catch::Contains("'frequencies'") && Catch::Contains("f1 < f2"));
  CHECK_THROWS_WITH(Rayleigh::from_ratio(0.05, 0, 5), Catch::Contains("'frequencies' must be > 0 (Hz)"));
  CHECK_THROWS_WITH(Rayleigh::coefficients(-1, 0), Catch::Contains("'alpha' must be >= 0 (1/s), got -1"));
  CHECK_THROWS_WITH(Rayleigh::coefficients(0, NAN), Catch::Contains("'beta' must be >= 0 (s)"));
}

TEST_CASE("rayleigh: the vibrating bar's first mode decays at xi(w) = alpha / 2w + beta w / 2",
          "[core][rayleigh][verification]") {
  cases::VibratingBar bar;  // uGIMP, first mode 0.1 Hz (w = 0.628 rad/s)
  bar.cells = 13;           // coarse and a long step: a second per case, the ratios still within 0.1 %
  bar.cfl = 0.4;
  const double w = bar.omega(), f = w / (2 * kPi);
  SECTION("undamped: the transfers' own damping is small beside the ratios checked below") {
    const auto r = cases::run_vibrating_bar(bar, 3.0);
    const Decay d = measure_decay(r.t, r.v);
    CAPTURE(d.ratio, d.extremes);
    CHECK(d.extremes >= 4);
    CHECK(std::abs(d.ratio) < 0.001);
  }
  struct Case {
    const char* name;
    Rayleigh rayleigh;
  };
  const Case c = GENERATE_COPY(Case{"mass-proportional, 5 %", Rayleigh{2 * 0.05 * w, 0.0}},
                               Case{"stiffness-proportional, 5 %", Rayleigh{0.0, 2 * 0.05 / w}},
                               Case{"5 % at f/2 and 3f", Rayleigh::from_ratio(0.05, 0.5 * f, 3.0 * f)});
  bar.rayleigh = c.rayleigh;
  const auto r = cases::run_vibrating_bar(bar, 3.0);
  const Decay d = measure_decay(r.t, r.v);
  const double expected = c.rayleigh.ratio_at(d.omega);
  CAPTURE(c.name, c.rayleigh.alpha, c.rayleigh.beta, d.ratio, expected, d.omega, w, d.extremes);
  CHECK(d.extremes >= 4);
  CHECK(d.omega == Approx(w).epsilon(0.03));
  CHECK(d.ratio == Approx(expected).epsilon(0.01));  // measured: within 0.1 %
}

TEST_CASE("rayleigh: the mass part acts on particles next to another body (contact fields)",
          "[core][rayleigh][contact]") {
  // Two elastic blocks side by side, in smooth contact, sliding together along their interface at v0:
  // no strain, so every particle, also those mapped to the contact fields' own slots, slows down as
  // dv/dt = -alpha v.
  ModelSettings<2> s;
  s.upper = Vec<2>(1.0, 1.0);
  s.cell = 0.05;
  auto m = std::make_unique<Model<2>>(s);
  auto material = std::make_shared<LinearElastic>(1000.0, 1e6, 0.3);
  const double alpha = 2.0;
  material->set_rayleigh(Rayleigh{alpha, 0.0});
  const int mat = m->add_material(material);
  const int a = m->add_body("a", 2), b = m->add_body("b", 2);
  m->fill_box(a, mat, Vec<2>(0.2, 0.3), Vec<2>(0.5, 0.7));
  m->fill_box(b, mat, Vec<2>(0.5, 0.3), Vec<2>(0.8, 0.7));
  m->add_contact(a, b, 0.0);
  for (auto& v : m->particles().v) v = Vec<2>(0.0, 0.1);
  m->run(0.2);
  const double expected = 0.1 * std::exp(-alpha * m->time());
  double lo = 1e9, hi = -1e9;
  for (const auto& v : m->particles().v) lo = std::min(lo, v[1]), hi = std::max(hi, v[1]);
  CAPTURE(lo, hi, expected, m->steps());
  CHECK(lo == Approx(expected).epsilon(0.005));
  CHECK(hi == Approx(expected).epsilon(0.005));
}

TEST_CASE("rayleigh: stiffness-proportional damping shortens the stable time step", "[core][rayleigh][time_step]") {
  // xi = beta c / h = 1 at the grid's highest mode: dt = cfl h / c (sqrt(1 + 1) - 1).
  cases::VibratingBar bar;
  auto plain = bar.build();
  for (auto& v : plain->particles().v) v.setZero();
  const double c = bar.wave_speed(), h = bar.length / bar.cells;
  bar.rayleigh = Rayleigh{0.0, h / c};
  auto damped = bar.build();
  for (auto& v : damped->particles().v) v.setZero();
  const double ratio = damped->stable_time_step() / plain->stable_time_step();
  CAPTURE(ratio);
  CHECK(plain->stable_time_step() == Approx(bar.cfl * h / c));
  CHECK(ratio == Approx(std::sqrt(2.0) - 1.0).epsilon(1e-12));
  bar.rayleigh = Rayleigh{50.0, 0.0};  // the mass part leaves it
  auto mass_damped = bar.build();
  for (auto& v : mass_damped->particles().v) v.setZero();
  CHECK(mass_damped->stable_time_step() == plain->stable_time_step());
}

TEST_CASE("rayleigh: a strength-reduced copy keeps the damping", "[core][rayleigh][strength_reduction]") {
  MohrCoulombParameters mc;
  mc.density = 1800, mc.young = 5e7, mc.poisson = 0.3, mc.cohesion = 5e3, mc.friction = 30;
  DruckerPragerParameters dp;
  dp.density = 1800, dp.young = 5e7, dp.poisson = 0.3, dp.cohesion = 5e3, dp.friction = 30;
  const Rayleigh r{0.7, 2e-3};
  for (std::shared_ptr<Material> m : {std::shared_ptr<Material>(std::make_shared<MohrCoulomb>(mc)),
                                      std::shared_ptr<Material>(std::make_shared<DruckerPrager>(dp))}) {
    CAPTURE(m->kind());
    m->set_rayleigh(r);
    const auto reduced = m->with_reduced_strength(1.5);
    REQUIRE(reduced);
    CHECK(reduced->rayleigh().alpha == r.alpha);
    CHECK(reduced->rayleigh().beta == r.beta);
  }
}
