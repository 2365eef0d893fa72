// Rayleigh damping of a material, C = alpha M + beta K: a viscous damping whose critical-damping ratio
// at circular frequency w is xi(w) = alpha / (2 w) + beta w / 2. The step applies the mass part as a
// particle force -alpha m v and the stiffness part as a viscous stress beta D : (de / dt).
#pragma once

#include <cmath>
#include <numbers>

#include "parameter.hpp"

namespace seismpm {

// The ranges the kernel checks (and the Lua help shows).
inline constexpr Interval kRayleighRatioRange = closed_open(0.0, 1.0);  // of critical damping
inline constexpr Interval kRayleighFrequencyRange = above(0.0);         // Hz
inline constexpr Interval kRayleighAlphaRange = at_least(0.0);          // 1/s
inline constexpr Interval kRayleighBetaRange = at_least(0.0);           // s

struct Rayleigh {
  double alpha = 0.0;  // mass-proportional coefficient (1/s)
  double beta = 0.0;   // stiffness-proportional coefficient (s)

  bool any() const { return alpha > 0.0 || beta > 0.0; }
  // The critical-damping ratio at circular frequency w (rad/s).
  double ratio_at(double w) const { return alpha / (2.0 * w) + beta * w / 2.0; }

  // Throws ParameterError naming "alpha" or "beta" when either is negative or not finite.
  static Rayleigh coefficients(double alpha, double beta) {
    return Rayleigh{check_parameter("alpha", alpha, kRayleighAlphaRange, "1/s"),
                    check_parameter("beta", beta, kRayleighBetaRange, "s")};
  }
  // The pair that gives the ratio `ratio` at both f1 and f2 (Hz, f1 < f2), and less between them:
  // alpha = 2 xi w1 w2 / (w1 + w2), beta = 2 xi / (w1 + w2).
  static Rayleigh from_ratio(double ratio, double f1, double f2) {
    check_parameter("ratio", ratio, kRayleighRatioRange);
    check_parameter("frequencies", f1, kRayleighFrequencyRange, "Hz");
    check_parameter("frequencies", f2, kRayleighFrequencyRange, "Hz");
    if (!(f1 < f2))
      throw ParameterError({"frequencies"}, "must be {f1, f2} with f1 < f2 (Hz), got {" + number_text(f1) + ", " +
                                                number_text(f2) + "}");
    const double w1 = 2.0 * std::numbers::pi * f1, w2 = 2.0 * std::numbers::pi * f2;
    return Rayleigh{2.0 * ratio * w1 * w2 / (w1 + w2), 2.0 * ratio / (w1 + w2)};
  }
};

}  // namespace seismpm
