#include "strength_parameters.hpp"

namespace seismpm {

void validate_strength(const StrengthParameters& s) {
  check_parameter("cohesion", s.cohesion, kCohesionRange, "Pa");
  check_parameter("friction", s.friction, kFrictionRange, "degrees");
  check_parameter("dilation", s.dilation, closed(0.0, s.friction), "degrees, at most friction");
  check_parameter("tension", s.tension, kTensionRange, "Pa");
  if (s.friction == 0.0 && s.cohesion == 0.0) throw ParameterError({"cohesion", "friction"}, "cannot both be zero");
}

}  // namespace seismpm
