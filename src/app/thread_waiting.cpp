#include "thread_waiting.hpp"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <thread>

namespace seismpm::app {

namespace {

// The cores this process may run on.
int usable_cpus() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return CPU_COUNT(&set);
  const long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? static_cast<int>(n) : 1;
}

// The 1-minute load average: the runnable programs of the last minutes.
double load_average() {
  double load = 0.0;
  if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &load) != 1) load = 0.0;
    std::fclose(f);
  }
  return load;
}

// The first line of /proc/stat (all cores' times since boot), or "" where it cannot be read.
std::string cpu_times() {
  std::string line;
  if (std::FILE* f = std::fopen("/proc/stat", "r")) {
    char buffer[512];
    if (std::fgets(buffer, sizeof buffer, f)) line = buffer;
    std::fclose(f);
  }
  return line;
}

// Online cores, which /proc/stat's first line sums over.
int online_cpus() {
  const long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? static_cast<int>(n) : 1;
}

}  // namespace

double busy_fraction(const std::string& before, const std::string& after) {
  // "cpu user nice system idle iowait irq softirq steal ...": idle and iowait are free time; the rest
  // (steal too: a core the hypervisor gave to another machine is not ours) is taken.
  auto parse = [](const std::string& line, long long& total, long long& free) {
    if (line.compare(0, 4, "cpu ") != 0) return false;
    std::istringstream in(line.substr(4));
    long long v[8] = {};
    for (auto& x : v)
      if (!(in >> x) || x < 0) return false;
    total = 0;
    for (const long long x : v) total += x;
    free = v[3] + v[4];
    return true;
  };
  long long t0, f0, t1, f1;
  if (!parse(before, t0, f0) || !parse(after, t1, f1) || t1 <= t0 || f1 < f0 || f1 - f0 > t1 - t0) return -1.0;
  return 1.0 - static_cast<double>(f1 - f0) / static_cast<double>(t1 - t0);
}

double busy_cores() {
  const std::string before = cpu_times();
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  const double fraction = busy_fraction(before, cpu_times());
  return fraction < 0.0 ? load_average() : fraction * online_cpus();
}

bool wait_passively(double load, int cpus, int threads) {
  // Half a core of slack: a shell or an editor ticking along does not make a machine busy.
  return load + threads > cpus + 0.5;
}

void use_default_thread_waiting(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  const int cpus = usable_cpus();
  int threads = cpus;
  if (const char* n = std::getenv("OMP_NUM_THREADS")) threads = std::max(1, std::min(cpus, std::atoi(n)));
  // On free cores libgomp's own spin: nothing to set, no new start.
  if (threads < 2 || !wait_passively(busy_cores(), cpus, threads)) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 0) != 0) return;
  execv("/proc/self/exe", argv);
  // Still here: no /proc or no permission. The run goes on with libgomp's default.
}

}  // namespace seismpm::app
