// The strength of a frictional soil as Mohr-Coulomb's cohesion, friction and dilation angles and a
// tensile strength, shared by the soil models (mohr_coulomb, drucker_prager) and checked here, once.
// Each model bounds the tensile strength by the apex of its own yield surface, so that check is its own.
#pragma once

#include "core/parameter.hpp"

namespace seismpm {

struct StrengthParameters {
  double cohesion = 0;   // Pa
  double friction = 30;  // degrees
  double dilation = 0;   // degrees, 0 <= psi <= phi: more dilation than friction would create energy
  double tension = 0;    // tensile strength (Pa)
};

inline constexpr Interval kCohesionRange = at_least(0.0);           // Pa
inline constexpr Interval kFrictionRange = closed_open(0.0, 90.0);  // degrees; tan(90) is infinite
inline constexpr Interval kTensionRange = at_least(0.0);            // Pa; each model adds its apex

// Throws ParameterError naming the parameter out of range: cohesion >= 0, friction in [0, 90),
// dilation in [0, friction], tension >= 0, and not both cohesion and friction zero (no strength).
void validate_strength(const StrengthParameters& s);

// The strength divided by a strength reduction factor srf > 0: c / srf, tan(phi) / srf, tension / srf
// (so the apex c cot(phi) stays where it is), and the dilation angle kept unless it would exceed the
// reduced friction angle, then equal to it (more dilation than friction would create energy).
StrengthParameters reduced_strength(const StrengthParameters& s, double srf);
// A friction angle (degrees) with tan(phi) / srf.
double reduced_friction(double friction, double srf);

}  // namespace seismpm
