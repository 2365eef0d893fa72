// The allowed range of a named input parameter, and the error that names a parameter out of it.
// Kernel code checks its inputs with these (a material its strength, say); the Lua bindings show the
// same ranges in their help and add "key" in front of the message, so each rule is written once.
#pragma once

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "error.hpp"

namespace seismpm {

// [lo, hi], either end open or unbounded (infinite); `or_zero` also admits 0 (as "0 (off) or >= 1").
struct Interval {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false, or_zero = false;

  constexpr bool bounded() const {
    return lo > -std::numeric_limits<double>::infinity() || hi < std::numeric_limits<double>::infinity();
  }
  bool contains(double v) const {
    if (or_zero && v == 0.0) return true;
    return std::isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  // "> 0", ">= 0", "<= 1", "in [0, 0.5)", "0 or >= 1"; "" when unbounded.
  std::string text() const;
};

constexpr Interval above(double lo) { return {lo, std::numeric_limits<double>::infinity(), true, false, false}; }
constexpr Interval at_least(double lo) { return {lo, std::numeric_limits<double>::infinity(), false, false, false}; }
constexpr Interval closed(double lo, double hi) { return {lo, hi, false, false, false}; }
constexpr Interval closed_open(double lo, double hi) { return {lo, hi, false, true, false}; }
constexpr Interval open_closed(double lo, double hi) { return {lo, hi, true, false, false}; }
constexpr Interval zero_or_at_least(double lo) {
  return {lo, std::numeric_limits<double>::infinity(), false, false, true};
}

// Shortest text of a number as messages show it (6 significant digits: 1e-06, 0.5, 1837.6).
inline std::string number_text(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

inline std::string Interval::text() const {
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::string t;
  if (hi == inf && lo > -inf)
    t = (lo_open ? "> " : ">= ") + number_text(lo);
  else if (lo == -inf && hi < inf)
    t = (hi_open ? "< " : "<= ") + number_text(hi);
  else if (lo > -inf)
    t = std::string("in ") + (lo_open ? "(" : "[") + number_text(lo) + ", " + number_text(hi) + (hi_open ? ")" : "]");
  return or_zero ? "0 or " + t : t;
}

// A parameter (or a pair that must agree) out of its range. what(): "'friction' must be in [0, 90)
// (degrees), got 90"; "'cohesion' and 'friction' cannot both be zero".
class ParameterError : public InputError {
 public:
  ParameterError(std::vector<std::string> names, const std::string& requirement)
      : InputError(quoted(names) + " " + requirement), names_(std::move(names)) {}
  const std::vector<std::string>& names() const { return names_; }

 private:
  static std::string quoted(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "'" : " and '") + n + "'";
    return s;
  }
  std::vector<std::string> names_;
};

// Returns v when `range` holds it; otherwise throws ParameterError naming `name`, the range, the unit
// (with any note, "degrees, at most friction") and v.
inline double check_parameter(const std::string& name, double v, const Interval& range, const std::string& unit = "") {
  if (range.contains(v)) return v;
  throw ParameterError({name},
                       "must be " + range.text() + (unit.empty() ? "" : " (" + unit + ")") + ", got " + number_text(v));
}

}  // namespace seismpm
