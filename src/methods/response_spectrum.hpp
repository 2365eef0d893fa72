// Elastic response spectra of a ground acceleration record: the peak relative displacement Sd of
// damped linear oscillators (one degree of freedom) of given natural periods, and from it the pseudo
// spectral velocity Sv = omega Sd and the pseudo spectral acceleration Sa = omega^2 Sd.
//
// Each oscillator, u'' + 2 zeta omega u' + omega^2 u = -a_g(t) from rest, is stepped from sample to
// sample with the exact solution for an excitation linear between the samples (Nigam & Jennings
// 1969): exact for the record as the history reads it, at any ratio of time step to period. The
// recursion's coefficients are the exponential of the step's matrix for the state (u, v, a, delta a),
// computed numerically: Nigam & Jennings' closed forms of them subtract terms of order
// zeta / (omega^3 dt) and lose digits at long periods, the exponential does not. The peaks are taken
// at the record's samples, over the record's duration (no free vibration after it).
#pragma once

#include <vector>

namespace seismpm {

struct SpectrumOrdinate {
  double period = 0.0;  // s
  double sd = 0.0;      // m: peak |u|
  double sv = 0.0;      // m/s: omega Sd
  double sa = 0.0;      // m/s^2: omega^2 Sd
};

// `times` (s) increasing, any spacing; `acceleration` (m/s^2); `periods` (s) > 0; `damping` the
// ratio of critical damping in [0, 1). Throws ParameterError naming 'periods' or 'damping', and
// InputError for a record of fewer than 2 samples, unequal lengths, non-finite values or times that do
// not increase.
std::vector<SpectrumOrdinate> response_spectrum(const std::vector<double>& times,
                                                const std::vector<double>& acceleration,
                                                const std::vector<double>& periods, double damping);

// The oscillator's relative displacement u at each sample (m), for the tests and for plots of one
// oscillator; same arguments and errors as response_spectrum for one period.
std::vector<double> oscillator_response(const std::vector<double>& times, const std::vector<double>& acceleration,
                                        double period, double damping);

// `count` periods spaced evenly in log between `first` and `last` (s): by default 100 from 0.02 to 5 s,
// the range of buildings and slopes.
std::vector<double> log_spaced_periods(double first = 0.02, double last = 5.0, int count = 100);

}  // namespace seismpm
