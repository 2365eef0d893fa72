// Ground-motion records: acceleration from PEER NGA .AT2 files (in g) or two-column time/acceleration
// files, integrated to velocity with the trapezoidal rule and an optional baseline correction.
// Every error names the file and the line.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace seismpm {

inline constexpr double kStandardGravity = 9.80665;  // m/s^2

// The most points a record may have (about 1.6 GB for its time, acceleration, velocity and
// displacement): a count beyond it is a broken file.
inline constexpr std::size_t kMaxRecordPoints = 100'000'000;

struct AccelerationRecord {
  std::vector<double> t, a;  // s, m/s^2
  std::string source;
};

// PEER NGA .AT2: 3 text lines, then "NPTS= n, DT= dt SEC", then n values in g, several per line.
AccelerationRecord read_at2(const std::string& file);
// Two columns time, acceleration: comma or white space separated, '#' comment lines, an optional
// header line of words; `to_si` converts the acceleration unit (9.80665 for g, 0.01 for gal).
AccelerationRecord read_acceleration_columns(const std::string& file, double to_si);

enum class Baseline { None, Linear, Quadratic };
Baseline parse_baseline(const std::string& name);  // "none" | "linear" | "quadratic"

struct VelocityRecord {
  std::vector<double> t, v, d;  // s, m/s, m
  std::vector<double> a;        // m/s^2: the acceleration after the correction, whose integrals v and d are
};
// Trapezoidal rule, v_k = v_{k-1} + dt (a_{k-1} + a_k)/2 (and likewise d from v).
//  - Linear: subtracts an acceleration c0 + c1 t that brings the velocity and the displacement at the
//    end of the record exactly to zero.
//  - Quadratic: subtracts the least-squares quadratic fit of the velocity (its derivative from the
//    acceleration), then the linear correction for what remains at the end.
VelocityRecord integrate_record(const AccelerationRecord& record, Baseline baseline);

}  // namespace seismpm
