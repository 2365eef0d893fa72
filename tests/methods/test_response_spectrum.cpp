// Response spectra against closed forms: the exact step response of a damped oscillator, resonance
// (the steady amplitude A / (2 zeta omega^2)), the rigid limit (Sa -> PGA at short periods) and the
// flexible limit (Sd -> peak ground displacement at long periods). Bad settings name the key.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "io/ground_motion.hpp"
#include "methods/response_spectrum.hpp"

using namespace seismpm;
using Catch::Contains;
using std::numbers::pi;

namespace {

struct Samples {
  std::vector<double> t, a;
};

template <class F>
Samples sampled(double dt, int n, F&& f) {
  Samples s;
  for (int k = 0; k < n; ++k) {
    s.t.push_back(k * dt);
    s.a.push_back(f(k * dt));
  }
  return s;
}

double peak(const std::vector<double>& x) {
  double p = 0.0;
  for (double v : x) p = std::max(p, std::abs(v));
  return p;
}

}  // namespace

TEST_CASE("an oscillator follows the exact solution for a ramp, then a constant, at any step", "[methods][spectrum]") {
  // a = A t / t1 up to t1, then A: piecewise linear, so the recursion must be exact at the samples.
  // For a constant A from rest: u = -A/w^2 (1 - e^{-z w t} (cos wd t + z / sqrt(1 - z^2) sin wd t)).
  // Checked on the constant part by starting the ramp at t1 = one step (a step of zero width is not a
  // record): the ramp's own closed form is the integral of that one, checked as u(t1) below.
  const double A = 2.0, period = GENERATE(0.05, 0.5, 5.0), zeta = GENERATE(0.0, 0.05, 0.3);
  const double dt = GENERATE(0.001, 0.02);
  const double w = 2 * pi / period, wd = w * std::sqrt(1 - zeta * zeta);
  auto step_response = [&](double t) {  // u for a constant A applied at t = 0 from rest
    return -A / (w * w) *
           (1 - std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta / std::sqrt(1 - zeta * zeta) * std::sin(wd * t)));
  };
  // Ramp of A over [0, dt]: u = (1/dt) * integral_0^dt step_response(t - s) ds (Duhamel), by Simpson.
  auto ramp_response = [&](double t) {
    const int n = 2000;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
      const double s = dt * i / n;
      sum += (i == 0 || i == n ? 1 : i % 2 ? 4 : 2) * step_response(t - s);
    }
    return sum * (dt / n) / 3 / dt;
  };
  const auto rec = sampled(dt, 200, [&](double t) { return t > 0 ? A : 0.0; });
  const auto u = oscillator_response(rec.t, rec.a, period, zeta);
  CAPTURE(period, zeta, dt);
  double worst = 0.0;
  for (std::size_t k = 1; k < u.size(); ++k) worst = std::max(worst, std::abs(u[k] - ramp_response(rec.t[k])));
  CHECK(worst < 1e-9 * A / (w * w));
}

TEST_CASE("at resonance the peak displacement reaches A / (2 zeta omega^2)", "[methods][spectrum]") {
  // a_g = A sin(w0 t) from rest, 40 cycles: the transient has decayed by exp(-2 pi zeta 40) ~ 3e-6.
  const double A = 1.5, T0 = GENERATE(0.1, 1.0, 4.0), zeta = 0.05;
  const int per_cycle = GENERATE(20, 100);
  const double dt = T0 / per_cycle, w0 = 2 * pi / T0;
  const auto rec = sampled(dt, 40 * per_cycle + 1, [&](double t) { return A * std::sin(w0 * t); });
  const auto s = response_spectrum(rec.t, rec.a, {T0}, zeta);
  const double exact = A / (2 * zeta * w0 * w0);
  const double error = s[0].sd / exact - 1;
  CAPTURE(T0, per_cycle, error);
  // The oscillator is stepped exactly; what remains is the record itself: linear interpolation of a sine
  // lowers its fundamental by (w0 dt)^2 / 12 (0.82 % at 20 steps a cycle, 0.033 % at 100).
  const double interpolation = -std::pow(w0 * dt, 2) / 12;
  CHECK(std::abs(error) < (per_cycle == 100 ? 5e-4 : 0.01));
  CHECK(std::abs(error - interpolation) < 1e-4);
  CHECK(s[0].sv == Approx(w0 * s[0].sd));
  CHECK(s[0].sa == Approx(w0 * w0 * s[0].sd));
  // Off resonance, the steady amplitude A / w^2 / sqrt((1 - r^2)^2 + (2 zeta r)^2) at r = w0 / w.
  if (per_cycle == 100) {
    for (double r : {0.5, 2.0}) {
      const double w = w0 / r;
      const double steady = A / (w * w) / std::sqrt(std::pow(1 - r * r, 2) + std::pow(2 * zeta * r, 2));
      const auto u = oscillator_response(rec.t, rec.a, 2 * pi / w, zeta);
      // The last 5 cycles: the transient (free vibration at w) has died out.
      const std::vector<double> tail(u.end() - 5 * per_cycle, u.end());
      CAPTURE(r);
      // r = 2: the slower oscillator's free vibration still has exp(-zeta w t) ~ 0.4 % of its start.
      CHECK(peak(tail) == Approx(steady).epsilon(r < 1 ? 0.002 : 0.01));
    }
  }
}

TEST_CASE("at very short periods Sa is the peak ground acceleration", "[methods][spectrum]") {
  // Two sines, 1 and 2.7 Hz, sampled at 200 Hz: a stiff oscillator moves with the ground.
  const auto rec = sampled(
      0.005, 2001, [](double t) { return 3.0 * std::sin(2 * pi * t) - 1.2 * std::sin(2 * pi * 2.7 * t + 0.4); });
  const double pga = peak(rec.a);
  const auto s = response_spectrum(rec.t, rec.a, {0.002, 0.01, 0.02}, 0.05);
  CAPTURE(s[0].sa / pga, s[1].sa / pga, s[2].sa / pga);
  // Measured: 4e-6 at 0.002 s (below the record's step: still exact), 5e-6 at 0.01 s, 6e-4 at 0.02 s.
  CHECK(s[0].sa == Approx(pga).epsilon(1e-4));
  CHECK(s[1].sa == Approx(pga).epsilon(1e-4));
  CHECK(s[2].sa == Approx(pga).epsilon(2e-3));
}

TEST_CASE("at very long periods Sd is the peak ground displacement", "[methods][spectrum]") {
  // u_g = D (1 - cos(2 pi t / Tp)) / 2 on [0, Tp]: from rest to rest, peak D at Tp / 2.
  const double D = 0.1, Tp = 2.0;
  const auto rec =
      sampled(0.001, 2001, [&](double t) { return D * 2 * pi * pi / (Tp * Tp) * std::cos(2 * pi * t / Tp); });
  AccelerationRecord r{rec.t, rec.a, "pulse"};
  const auto ground = integrate_record(r, Baseline::None);
  const double pgd = peak(ground.d);
  CHECK(pgd == Approx(D).epsilon(1e-4));
  const auto s = response_spectrum(rec.t, rec.a, {20.0, 100.0, 1000.0}, 0.05);
  CAPTURE(s[0].sd / pgd, s[1].sd / pgd, s[2].sd / pgd);
  // The oscillator lags the ground by about zeta omega D (its damping) plus omega^2 D / 4 (its spring)
  // at the peak: 4 % at 20 s, 0.4 % at 100 s, 0.03 % at 1000 s, where omega^3 dt ~ 2.5e-10 and
  // Nigam & Jennings' closed forms would have lost their digits.
  CHECK(s[0].sd == Approx(pgd).epsilon(0.05));
  CHECK(s[1].sd == Approx(pgd).epsilon(0.006));
  CHECK(s[2].sd == Approx(pgd).epsilon(0.0005));
  CHECK(s[0].sd < s[1].sd);
  CHECK(s[1].sd < s[2].sd);
}

TEST_CASE("spectra: default periods and bad settings", "[methods][spectrum]") {
  const auto p = log_spaced_periods();
  REQUIRE(p.size() == 100);
  CHECK(p.front() == Approx(0.02));
  CHECK(p.back() == Approx(5.0));
  CHECK(p[1] / p[0] == Approx(p[99] / p[98]));
  const auto rec = sampled(0.01, 101, [](double t) { return std::sin(5 * t); });
  CHECK_THROWS_WITH(response_spectrum(rec.t, rec.a, {0.1, 0.0}, 0.05), Contains("'periods' must be > 0 (s), got 0"));
  CHECK_THROWS_WITH(response_spectrum(rec.t, rec.a, {0.1}, 1.0), Contains("'damping' must be in [0, 1)"));
  CHECK_THROWS_WITH(response_spectrum(rec.t, rec.a, {0.1}, -0.01), Contains("'damping'"));
  CHECK_THROWS_AS(response_spectrum({0.0}, {1.0}, {0.1}, 0.05), InputError);
  CHECK_THROWS_WITH(response_spectrum({0.0, 0.1, 0.1}, {1, 2, 3}, {0.1}, 0.05), Contains("times must increase"));
  CHECK_THROWS_WITH(response_spectrum({0.0, 0.1}, {1}, {0.1}, 0.05), Contains("unequal"));
}
