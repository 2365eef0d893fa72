// Record processing: a window keeps the right samples and starts at 0, a taper zeroes the ends and
// leaves the middle alone, pga scaling hits its target, the Arias intensity of a sine is the closed
// form, and the baseline correction after a window brings the cut record to rest. Bad settings are
// errors naming the key.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <numbers>

#include "core/parameter.hpp"
#include "io/ground_motion.hpp"
#include "io/record_processing.hpp"

using namespace seismpm;
using Catch::Contains;

namespace {

// t = 0, dt, ..., (n - 1) dt with a_k = f(t_k).
template <class F>
AccelerationRecord sampled(double dt, int n, F&& f) {
  AccelerationRecord r;
  r.source = "synthetic";
  for (int k = 0; k < n; ++k) {
    r.t.push_back(k * dt);
    r.a.push_back(f(k * dt));
  }
  return r;
}

// a_k = k on t_k = k / 100, 0 .. 10 s: each value names its sample.
AccelerationRecord numbered() {
  return sampled(0.01, 1001, [](double t) { return std::round(100 * t); });
}

}  // namespace

TEST_CASE("a window keeps its samples and starts at time 0", "[io][record]") {
  const auto r = numbered();
  SECTION("ends on samples: exactly those samples, times shifted by t0") {
    const auto w = window_record(r, 2.0, 5.0);
    REQUIRE(w.t.size() == 301);  // samples 200 .. 500
    CHECK(w.t.front() == 0.0);
    CHECK(w.t.back() == Approx(3.0).margin(1e-12));
    for (std::size_t k = 0; k < w.t.size(); ++k) {
      CAPTURE(k);
      CHECK(w.a[k] == 200.0 + k);  // the samples' own values
      CHECK(w.t[k] == Approx(0.01 * k).margin(1e-12));
    }
    CHECK(w.source == r.source);
  }
  SECTION("ends between samples: interpolated end samples, the span exactly t1 - t0") {
    const auto w = window_record(r, 2.005, 4.995);
    REQUIRE(w.t.size() == 301);  // the two ends, and samples 201 .. 499 strictly inside
    CHECK(w.t.front() == 0.0);
    CHECK(w.t.back() == Approx(2.99).margin(1e-12));
    CHECK(w.a.front() == Approx(200.5));
    CHECK(w.a.back() == Approx(499.5));
    CHECK(w.a[1] == 201.0);
    CHECK(w.t[1] == Approx(0.005).margin(1e-12));
    CHECK(w.a[299] == 499.0);
  }
  SECTION("the whole record is the record") {
    const auto w = window_record(r, 0.0, 10.0);
    CHECK(w.t.size() == r.t.size());
    CHECK(w.a == r.a);
  }
  SECTION("a window inside one step: its two interpolated ends") {
    const auto w = window_record(r, 3.002, 3.007);
    REQUIRE(w.t.size() == 2);
    CHECK(w.a[0] == Approx(300.2));
    CHECK(w.a[1] == Approx(300.7));
    CHECK(w.t[1] == Approx(0.005));
  }
}

TEST_CASE("a window outside the record, empty or not finite is an error naming 'window'", "[io][record]") {
  const auto r = numbered();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(window_record(r, -1, 2), Contains("'window' must lie within the record's 0 .. 10 s"));
  CHECK_THROWS_WITH(window_record(r, 5, 10.5), Contains("'window' must lie within") && Contains("got {5, 10.5}"));
  CHECK_THROWS_WITH(window_record(r, 5, 5), Contains("'window' must be {t0, t1} (s) with t1 > t0, got {5, 5}"));
  CHECK_THROWS_WITH(window_record(r, 5, 4), Contains("with t1 > t0"));
  CHECK_THROWS_WITH(window_record(r, nan, 4), Contains("'window'"));
  CHECK_THROWS_AS(window_record(r, 0, std::numeric_limits<double>::infinity()), ParameterError);
}

TEST_CASE("a taper brings both ends to zero and leaves the middle untouched", "[io][record]") {
  // A sine with an offset: values that are not 1, so an untouched one is recognisable.
  auto r = sampled(0.01, 1001, [](double t) { return 1.5 + std::sin(2 * std::numbers::pi * 0.7 * t); });
  const auto original = r;
  taper_record(r, 1.0);
  CHECK(r.a.front() == 0.0);
  CHECK(r.a.back() == 0.0);
  for (std::size_t k = 100; k <= 900; ++k) {  // t in [1, 9]: weight 1
    CAPTURE(k);
    REQUIRE(r.a[k] == original.a[k]);
  }
  // Half way up the ramp the weight is 1/2, a quarter of the way (1 - cos(pi/4))/2.
  CHECK(r.a[50] == Approx(0.5 * original.a[50]));
  CHECK(r.a[950] == Approx(0.5 * original.a[950]));
  CHECK(r.a[25] == Approx((1 - std::cos(std::numbers::pi / 4)) / 2 * original.a[25]));
  for (std::size_t k = 1; k < 100; ++k) CHECK(std::abs(r.a[k]) < std::abs(original.a[k]));

  auto same = original;
  taper_record(same, 0.0);
  CHECK(same.a == original.a);
  auto half = original;
  taper_record(half, 5.0);  // half the record: the ramps meet in the middle
  CHECK(half.a[500] == original.a[500]);
  CHECK(half.a.front() == 0.0);
  CHECK(half.a.back() == 0.0);
}

TEST_CASE("a negative taper or one over half the record is an error naming 'taper'", "[io][record]") {
  auto r = numbered();
  CHECK_THROWS_WITH(taper_record(r, -0.5), Contains("'taper' must be >= 0 (s), got -0.5"));
  CHECK_THROWS_WITH(taper_record(r, 5.01),
                    Contains("'taper' must be at most half the record's length (10 s: at most 5 s), got 5.01 s"));
  CHECK_THROWS_WITH(taper_record(r, std::numeric_limits<double>::quiet_NaN()), Contains("'taper'"));
  CHECK(r.a == numbered().a);  // nothing changed by a refused taper
}

TEST_CASE("scaling to a pga hits the target and keeps the shape", "[io][record]") {
  auto r = sampled(0.005, 2001, [](double t) { return 2.0 * std::sin(3 * t) - 0.7 * std::cos(11 * t); });
  const auto original = r;
  const double pga = GENERATE(0.05, 0.3, 1.2);
  scale_to_pga(r, pga);
  CHECK(peak_magnitude(r.a) == Approx(pga * kStandardGravity).epsilon(1e-14));
  const double factor = r.a[123] / original.a[123];
  for (std::size_t k = 0; k < r.a.size(); k += 97) CHECK(r.a[k] == Approx(factor * original.a[k]).epsilon(1e-14));
}

TEST_CASE("a pga <= 0, or a record of zeros, is an error naming 'pga'", "[io][record]") {
  auto r = numbered();
  CHECK_THROWS_WITH(scale_to_pga(r, 0), Contains("'pga' must be > 0 (g), got 0"));
  CHECK_THROWS_WITH(scale_to_pga(r, -0.3), Contains("'pga' must be > 0 (g), got -0.3"));
  CHECK_THROWS_AS(scale_to_pga(r, std::numeric_limits<double>::infinity()), ParameterError);
  auto zeros = sampled(0.01, 10, [](double) { return 0.0; });
  CHECK_THROWS_WITH(scale_to_pga(zeros, 0.3), Contains("'pga' cannot scale synthetic: its acceleration is zero"));
}

TEST_CASE("the Arias intensity of a sine over whole cycles is pi A^2 t / (4 g)", "[io][record]") {
  // integral of A^2 sin^2(w t) over whole cycles = A^2 t / 2.
  const double amplitude = GENERATE(0.5, 3.0), f = 2.0;
  const int cycles = GENERATE(1, 10);
  const double duration = cycles / f;
  const auto r = sampled(0.001, static_cast<int>(std::lround(duration / 0.001)) + 1,
                         [&](double t) { return amplitude * std::sin(2 * std::numbers::pi * f * t); });
  const double exact = std::numbers::pi * amplitude * amplitude * duration / (4 * kStandardGravity);
  CAPTURE(amplitude, cycles);
  CHECK(arias_intensity(r.t, r.a) == Approx(exact).epsilon(1e-9));
  // Scaling by s multiplies it by s^2.
  auto scaled = r;
  scale_to_pga(scaled, 2 * amplitude / kStandardGravity);
  CHECK(arias_intensity(scaled.t, scaled.a) == Approx(4 * exact).epsilon(1e-9));
}

TEST_CASE("the baseline correction after a window and a taper ends the cut record at rest", "[io][record]") {
  // A sine with an offset and a slope in the acceleration: any part of it drifts.
  auto r =
      sampled(0.005, 4001, [](double t) { return 2.0 * std::sin(2 * std::numbers::pi * 1.5 * t) + 0.02 + 0.001 * t; });
  auto w = window_record(r, 4.0, 14.0);
  taper_record(w, 0.5);
  scale_to_pga(w, 0.3);
  const auto raw = integrate_record(w, Baseline::None);
  CHECK(std::abs(raw.v.back()) > 0.02);
  for (Baseline b : {Baseline::Linear, Baseline::Quadratic}) {
    const auto c = integrate_record(w, b);
    CAPTURE(b == Baseline::Linear, c.v.back(), c.d.back());
    CHECK(c.t.front() == 0.0);
    CHECK(c.t.back() == Approx(10.0));
    CHECK(std::abs(c.v.back()) < 1e-9);
    CHECK(std::abs(c.d.back()) < 1e-6);
    // The corrected acceleration is what integrates to that velocity.
    REQUIRE(c.a.size() == c.t.size());
    double v = 0.0;
    for (std::size_t k = 1; k < c.t.size(); ++k) v += 0.5 * (c.t[k] - c.t[k - 1]) * (c.a[k - 1] + c.a[k]);
    CHECK(v == Approx(c.v.back()).margin(1e-12));
  }
}
