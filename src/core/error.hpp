// Errors the kernel raises. A SimulationError says where and when a run went wrong.
#pragma once

#include <stdexcept>
#include <string>

namespace seismpm {

// Bad input to the kernel (a setting out of range, an empty domain).
class InputError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// A run that cannot go on: a particle left the grid, a NaN, a collapsing time step.
class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace seismpm
