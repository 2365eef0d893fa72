#include "record_processing.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/parameter.hpp"

namespace seismpm {

namespace {

std::string seconds_text(double t) { return number_text(t) + " s"; }

// The record as a history reads it at t (linear between samples), t within the record.
double interpolate(const AccelerationRecord& r, double t) {
  const auto it = std::upper_bound(r.t.begin(), r.t.end(), t);
  if (it == r.t.begin()) return r.a.front();
  if (it == r.t.end()) return r.a.back();
  const std::size_t k = it - r.t.begin();
  const double s = (t - r.t[k - 1]) / (r.t[k] - r.t[k - 1]);
  return r.a[k - 1] + s * (r.a[k] - r.a[k - 1]);
}

// The sample within `tol` of t, or -1.
long sample_at(const AccelerationRecord& r, double t, double tol) {
  const auto it = std::lower_bound(r.t.begin(), r.t.end(), t - tol);
  return it != r.t.end() && std::abs(*it - t) <= tol ? static_cast<long>(it - r.t.begin()) : -1;
}

}  // namespace

AccelerationRecord window_record(const AccelerationRecord& r, double t0, double t1) {
  const std::string got = "got {" + number_text(t0) + ", " + number_text(t1) + "}";
  if (!std::isfinite(t0) || !std::isfinite(t1) || !(t1 > t0))
    throw ParameterError({"window"}, "must be {t0, t1} (s) with t1 > t0, " + got);
  // Times read from text are off by an ulp or so: a window end that close to a sample is the sample.
  const double tol = 1e-9 * (r.t.back() - r.t.front());
  if (t0 < r.t.front() - tol || t1 > r.t.back() + tol)
    throw ParameterError({"window"}, "must lie within the record's " + number_text(r.t.front()) + " .. " +
                                         seconds_text(r.t.back()) + " (" + r.source + "), " + got);
  AccelerationRecord out;
  out.source = r.source;
  auto end_value = [&](double t) {
    const long k = sample_at(r, t, tol);
    return k >= 0 ? r.a[k] : interpolate(r, t);
  };
  out.t.push_back(0.0);
  out.a.push_back(end_value(t0));
  for (std::size_t k = 0; k < r.t.size(); ++k)
    if (r.t[k] > t0 + tol && r.t[k] < t1 - tol) {
      out.t.push_back(r.t[k] - t0);
      out.a.push_back(r.a[k]);
    }
  out.t.push_back(t1 - t0);
  out.a.push_back(end_value(t1));
  return out;
}

void taper_record(AccelerationRecord& r, double seconds) {
  const double length = r.t.back() - r.t.front();
  if (!std::isfinite(seconds) || seconds < 0.0)
    throw ParameterError({"taper"}, "must be >= 0 (s), got " + number_text(seconds));
  if (seconds > 0.5 * length)
    throw ParameterError({"taper"}, "must be at most half the record's length (" + seconds_text(length) + ": at most " +
                                        seconds_text(0.5 * length) + "), got " + seconds_text(seconds));
  if (seconds == 0.0) return;
  auto ramp = [&](double s) { return 0.5 * (1.0 - std::cos(std::numbers::pi * s / seconds)); };
  for (std::size_t k = 0; k < r.t.size(); ++k) {
    const double from_start = r.t[k] - r.t.front(), to_end = r.t.back() - r.t[k];
    if (from_start < seconds) r.a[k] *= ramp(from_start);
    if (to_end < seconds) r.a[k] *= ramp(to_end);
  }
}

double peak_magnitude(const std::vector<double>& a) {
  double p = 0.0;
  for (double v : a) p = std::max(p, std::abs(v));
  return p;
}

void scale_to_pga(AccelerationRecord& r, double pga) {
  check_parameter("pga", pga, above(0), "g");
  const double peak = peak_magnitude(r.a);
  if (!(peak > 0.0))
    throw ParameterError({"pga"}, "cannot scale " + r.source + ": its acceleration is zero everywhere");
  const double factor = pga * kStandardGravity / peak;
  for (double& v : r.a) v *= factor;
}

double arias_intensity(const std::vector<double>& t, const std::vector<double>& a) {
  double integral = 0.0;
  for (std::size_t k = 1; k < t.size(); ++k) integral += 0.5 * (t[k] - t[k - 1]) * (a[k - 1] * a[k - 1] + a[k] * a[k]);
  return std::numbers::pi / (2.0 * kStandardGravity) * integral;
}

}  // namespace seismpm
