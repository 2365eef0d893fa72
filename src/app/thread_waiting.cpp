#include "thread_waiting.hpp"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace seismpm::app {

namespace {

// The cores this process may run on.
int usable_cpus() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return CPU_COUNT(&set);
  const long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? static_cast<int>(n) : 1;
}

// The 1-minute load average: the runnable programs before this one starts.
double load_average() {
  double load = 0.0;
  if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &load) != 1) load = 0.0;
    std::fclose(f);
  }
  return load;
}

}  // namespace

bool wait_passively(double load, int cpus, int threads) {
  // Half a core of slack: a shell or an editor ticking along does not make a machine busy.
  return load + threads > cpus + 0.5;
}

void use_default_thread_waiting(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  const int cpus = usable_cpus();
  int threads = cpus;
  if (const char* n = std::getenv("OMP_NUM_THREADS")) threads = std::max(1, std::min(cpus, std::atoi(n)));
  const bool passive = wait_passively(load_average(), cpus, threads);
  if ((passive ? setenv("OMP_WAIT_POLICY", "passive", 0) : setenv("GOMP_SPINCOUNT", "1000", 0)) != 0) return;
  execv("/proc/self/exe", argv);
  // Still here: no /proc or no permission. The run goes on with libgomp's default.
}

}  // namespace seismpm::app
