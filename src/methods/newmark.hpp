// Newmark's rigid sliding block (Newmark 1965), one-way (downslope) as SLAMMER's rigid-block method
// does it (Jibson 1993; Jibson et al. 2013): the permanent displacement of a rigid block on a plane
// that yields at a constant acceleration ky g, shaken by a recorded ground acceleration.
//
// The block rides with the ground until the ground acceleration exceeds ky g; it then slides
// downslope, its relative acceleration a - ky g integrated to the relative velocity and that to the
// displacement, until the relative velocity comes back to zero. It never slides upslope: a sliding
// block's velocity is clamped at zero, and a block at rest does not start on an upslope pulse.
#pragma once

#include <string>
#include <vector>

namespace seismpm {

// The standard gravity (m/s^2), the g that ky and SLAMMER's records are in. The same value as
// io/ground_motion.hpp's kStandardGravity, restated because the methods depend on the core only.
inline constexpr double kNewmarkGravity = 9.80665;

enum class Polarity {
  Normal,   // the record as it is
  Inverse,  // the record times -1: the same slope shaken the other way
};
Polarity parse_polarity(const std::string& name);  // "normal" | "inverse"

struct NewmarkResult {
  double displacement = 0.0;    // final permanent displacement (m)
  std::vector<double> times;    // s: the record's times
  std::vector<double> history;  // m: the displacement at each time
  double max_velocity = 0.0;    // largest relative velocity of the block (m/s)
  double sliding_time = 0.0;    // total time the block slid (s)
};

// `times` (s) increasing, any spacing; `acceleration` (m/s^2) of the ground, downslope positive; `ky`
// the yield acceleration in g. Integration between samples k-1 and k, dt = t_k - t_{k-1}, relative
// acceleration y, velocity v, displacement d (the trapezoidal rule, SLAMMER's):
//   y_k = a_k - ky g  while sliding, or at rest when a_k > ky g; 0 at rest otherwise
//   v_k = v_{k-1} + dt (y_{k-1} + y_k) / 2; when v_k <= 0 the block stops: v_k = 0, y_k = 0
//   d_k = d_{k-1} + dt (v_{k-1} + v_k) / 2
// The block starts at rest at t_0. Throws InputError (a ParameterError naming 'ky') for ky <= 0, an
// empty record, times and values of different lengths, times that do not increase, non-finite values.
NewmarkResult newmark_rigid_block(const std::vector<double>& times, const std::vector<double>& acceleration, double ky,
                                  Polarity polarity = Polarity::Normal);

}  // namespace seismpm
