// Numbers and points in messages.
#pragma once

#include <sstream>
#include <string>

#include "types.hpp"

namespace seismpm {

// A number with `digits` significant digits.
inline std::string format_number(double v, int digits = 6) {
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

// "(x, y)" with 6 significant digits.
template <int Dim>
std::string format_point(const Vec<Dim>& x) {
  std::ostringstream os;
  os.precision(6);
  os << "(";
  for (int d = 0; d < Dim; ++d) os << (d ? ", " : "") << x[d];
  os << ")";
  return os.str();
}

}  // namespace seismpm
