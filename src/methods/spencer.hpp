// Spencer's method of slices: force and moment equilibrium of the whole sliding mass, the interslice
// forces all at one inclination theta. Works on any slip surface cut into slices (circular or not).
#pragma once

#include <optional>
#include <vector>

#include "methods/limit_equilibrium.hpp"

namespace seismpm {

// One slice of a sliding mass that moves towards +x. The base descends towards +x where sin_a > 0.
struct LemSlice {
  double weight = 0;    // per unit width (N/m)
  double centroid = 0;  // elevation of its centre of gravity (m)
  double x = 0;         // its mid-line (m)
  double base_y = 0;    // elevation of the base's middle (m)
  double width = 0;     // horizontal (m)
  double sin_a = 0, cos_a = 1;
  double cohesion = 0, tan_phi = 0;
};

struct SpencerSolution {
  double fos = 0;
  double theta = 0;  // interslice force inclination (radians, positive: rising towards +x)
};

// nullopt when no inclination in (-60, 80) degrees satisfies both equilibria, or the mass does not
// drive towards +x.
std::optional<SpencerSolution> spencer(const std::vector<LemSlice>& slices, double kh, const LemSettings& s);

}  // namespace seismpm
