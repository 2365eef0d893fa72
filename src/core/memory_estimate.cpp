#include "memory_estimate.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "error.hpp"

namespace seismpm {

std::uint64_t available_memory() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  std::string unit;
  while (in >> key >> kib) {
    std::getline(in, unit);
    if (key == "MemAvailable:") return kib * 1024;
  }
  return 0;
}

std::string format_bytes(std::uint64_t bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB"};
  double value = static_cast<double>(bytes);
  int u = 0;
  while (value >= 1024.0 && u < 5) {
    value /= 1024.0;
    ++u;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.3g %s", value, units[u]);
  return buf;
}

void check_memory(std::uint64_t need, const std::string& what) {
  const std::uint64_t available = available_memory();
  if (available == 0 || need <= available) return;
  throw InputError(what + " needs about " + format_bytes(need) + " of memory, more than the " +
                   format_bytes(available) +
                   " available now: use a larger cell, fewer particles per cell or a smaller domain "
                   "(mpm.model{ check_memory = false } builds it anyway)");
}

}  // namespace seismpm
