#include "thread_waiting.hpp"

#include <unistd.h>

#include <cstdlib>

namespace seismpm::app {

void use_default_thread_waiting(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 0) != 0) return;
  execv("/proc/self/exe", argv);
  // Still here: no /proc or no permission. The run goes on with libgomp's default.
}

}  // namespace seismpm::app
