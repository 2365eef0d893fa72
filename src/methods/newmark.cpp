#include "methods/newmark.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/parameter.hpp"

namespace seismpm {

Polarity parse_polarity(const std::string& name) {
  if (name == "normal") return Polarity::Normal;
  if (name == "inverse") return Polarity::Inverse;
  throw InputError("direction must be \"normal\" or \"inverse\", got \"" + name + "\"");
}

namespace {

void check_record(const std::vector<double>& times, const std::vector<double>& acceleration) {
  if (times.empty()) throw InputError("the acceleration record is empty");
  if (times.size() != acceleration.size())
    throw InputError("the acceleration record has " + std::to_string(times.size()) + " times but " +
                     std::to_string(acceleration.size()) + " values");
  for (std::size_t k = 0; k < times.size(); ++k) {
    if (!std::isfinite(times[k]) || !std::isfinite(acceleration[k]))
      throw InputError("the acceleration record has a non-finite time or value at sample " + std::to_string(k + 1));
    if (k > 0 && !(times[k] > times[k - 1]))
      throw InputError("the acceleration record's times must increase: " + number_text(times[k]) + " s after " +
                       number_text(times[k - 1]) + " s at sample " + std::to_string(k + 1));
  }
}

// The block's state after a sample.
struct BlockState {
  double y = 0.0;  // relative acceleration (m/s^2)
  double v = 0.0;  // relative velocity (m/s), never negative
  double d = 0.0;  // relative displacement (m)
};

// One trapezoidal step of length dt to a ground acceleration a; `yield` = ky g.
BlockState advance(const BlockState& s, double a, double yield, double dt) {
  BlockState n = s;
  // A block at rest stays with the ground unless the ground pulls it downslope harder than the
  // plane holds; a sliding one decelerates by the yield resistance whatever the ground does.
  const bool sliding = s.v > 0.0 || a > yield;
  n.y = sliding ? a - yield : 0.0;
  n.v = s.v + 0.5 * dt * (s.y + n.y);
  if (n.v <= 0.0) {  // one-way: the block stops instead of sliding back upslope
    n.v = 0.0;
    n.y = 0.0;
  }
  n.d = s.d + 0.5 * dt * (s.v + n.v);
  return n;
}

}  // namespace

NewmarkResult newmark_rigid_block(const std::vector<double>& times, const std::vector<double>& acceleration, double ky,
                                  Polarity polarity) {
  check_parameter("ky", ky, above(0), "g");
  check_record(times, acceleration);
  const double sign = polarity == Polarity::Inverse ? -1.0 : 1.0;
  const double yield = ky * kNewmarkGravity;

  NewmarkResult r;
  r.times = times;
  r.history.resize(times.size());
  BlockState s;
  const double a0 = sign * acceleration[0];
  s.y = a0 > yield ? a0 - yield : 0.0;  // at rest at t_0, already pulled when a_0 exceeds ky g
  r.history[0] = 0.0;
  for (std::size_t k = 1; k < times.size(); ++k) {
    const double dt = times[k] - times[k - 1];
    const bool was_sliding = s.v > 0.0;
    s = advance(s, sign * acceleration[k], yield, dt);
    if (was_sliding || s.v > 0.0) r.sliding_time += dt;
    if (s.v > r.max_velocity) r.max_velocity = s.v;
    r.history[k] = s.d;
  }
  r.displacement = s.d;
  return r;
}

}  // namespace seismpm
