// Verification: the vibrating elastic bar (Sulsky et al. 1994), first mode, against its closed form.
#include <catch2/catch.hpp>

#include "cases/vibrating_bar.hpp"

using namespace seismpm;

TEST_CASE("vibrating bar: period and centre-of-mass velocity amplitude match the closed form",
          "[core][verification][bar]") {
  const auto shape = GENERATE(ShapeKind::Gimp, ShapeKind::Linear);
  CAPTURE(to_string(shape));
  cases::VibratingBar bar;  // default resolution: 25 cells, 2 x 2 particles per cell
  bar.shape = shape;
  const auto r = cases::run_vibrating_bar(bar);
  const double period_error = std::abs(r.period - bar.period()) / bar.period();
  const double amplitude_error = std::abs(r.amplitude - bar.amplitude()) / bar.amplitude();
  CAPTURE(r.period, bar.period(), period_error, r.amplitude, bar.amplitude(), amplitude_error);
  CHECK(period_error < 0.02);
  CHECK(amplitude_error < 0.02);

  SECTION("the error falls when the grid is refined") {
    bar.cells = 13;
    const auto coarse = cases::run_vibrating_bar(bar);
    bar.cells = 50;
    const auto fine = cases::run_vibrating_bar(bar);
    const double coarse_error = std::abs(coarse.period - bar.period()) / bar.period();
    const double fine_error = std::abs(fine.period - bar.period()) / bar.period();
    CAPTURE(coarse_error, period_error, fine_error);
    CHECK(fine_error < period_error);
    CHECK(period_error < coarse_error);
  }
}
