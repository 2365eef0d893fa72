// Preparing a ground acceleration record before it drives a run or an analysis: the part of it that
// matters (a window, whose start becomes time 0), a cosine taper at both ends so that the cut record
// starts and ends at rest, and a scale to a target peak ground acceleration; and the Arias intensity,
// the measure of the shaking's energy that the scale changes.
//
// mpm.history.at2 and mpm.history.csv apply them in this order: window, taper, scale, then the
// baseline correction (ground_motion.hpp), so that the velocity of the record as used ends at zero.
// Bad settings throw ParameterError naming 'window', 'taper' or 'pga', the keys of those calls.
#pragma once

#include <vector>

#include "ground_motion.hpp"

namespace seismpm {

// The part t0 <= t <= t1 of the record, shifted so that t0 is time 0. The samples inside keep their
// values; a window end that falls between two samples gets a sample of its own, interpolated linearly
// (as the history reads the record), so the cut record spans exactly t1 - t0. An end within 1e-9 of
// the record's length of a sample is that sample. Throws ParameterError ('window') for a window that
// is not finite, has t1 <= t0 or reaches outside the record.
AccelerationRecord window_record(const AccelerationRecord& record, double t0, double t1);

// Multiplies the first and the last `seconds` of the record by a half-cosine (Tukey) ramp,
// w(s) = (1 - cos(pi s / seconds)) / 2 with s the time from the nearer end: exactly 0 at both ends,
// exactly 1 (the values untouched) from `seconds` in. 0 leaves the record as it is. Throws
// ParameterError ('taper') for a negative or non-finite length or one over half the record's.
void taper_record(AccelerationRecord& record, double seconds);

// The largest |a| (m/s^2).
double peak_magnitude(const std::vector<double>& a);

// Scales the acceleration so that its peak |a| is `pga` g (kStandardGravity). Throws ParameterError
// ('pga') for pga <= 0 or not finite, and for a record that is zero everywhere (nothing to scale).
void scale_to_pga(AccelerationRecord& record, double pga);

// Arias intensity I_a = pi / (2 g) * integral a(t)^2 dt (m/s; a in m/s^2, g = kStandardGravity), the
// integral by the trapezoidal rule on a^2 over the record's own samples.
double arias_intensity(const std::vector<double>& t, const std::vector<double>& a);

}  // namespace seismpm
