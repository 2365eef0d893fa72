#include "strength_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace seismpm {

void validate_strength(const StrengthParameters& s) {
  check_parameter("cohesion", s.cohesion, kCohesionRange, "Pa");
  check_parameter("friction", s.friction, kFrictionRange, "degrees");
  check_parameter("dilation", s.dilation, closed(0.0, s.friction), "degrees, at most friction");
  check_parameter("tension", s.tension, kTensionRange, "Pa");
  if (s.friction == 0.0 && s.cohesion == 0.0) throw ParameterError({"cohesion", "friction"}, "cannot both be zero");
}

double reduced_friction(double friction, double srf) {
  constexpr double deg = std::numbers::pi / 180.0;
  return std::atan(std::tan(friction * deg) / srf) / deg;
}

StrengthParameters reduced_strength(const StrengthParameters& s, double srf) {
  if (!(srf > 0.0 && std::isfinite(srf))) throw InputError("the strength reduction factor must be > 0");
  StrengthParameters r = s;
  r.cohesion = s.cohesion / srf;
  r.friction = reduced_friction(s.friction, srf);
  r.dilation = std::min(s.dilation, r.friction);
  r.tension = s.tension / srf;
  return r;
}

}  // namespace seismpm
