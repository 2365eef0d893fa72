#include "time_step.hpp"

#include <algorithm>

namespace seismpm {

template <int Dim>
double stable_time_step(const Particles<Dim>& particles, const MaterialConstants& c, double cfl, double cell,
                        const char* may_close) {
  const int n = static_cast<int>(particles.size());
  double max_speed = 0.0;
  if (may_close) {
#pragma omp parallel for schedule(static) reduction(max : max_speed)
    for (int p = 0; p < n; ++p) max_speed = std::max(max_speed, signal_speed(particles, c, p, cell, may_close[p] != 0));
  } else {
#pragma omp parallel for schedule(static) reduction(max : max_speed)
    for (int p = 0; p < n; ++p) max_speed = std::max(max_speed, signal_speed(particles, c, p, cell));
  }
  return cfl * cell / max_speed;
}

template <int Dim>
std::pair<std::size_t, double> fastest_signal(const Particles<Dim>& particles, const MaterialConstants& c, double cell,
                                              const char* may_close) {
  std::size_t fastest = 0;
  double speed = -1.0;
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const double s = signal_speed(particles, c, p, cell, !may_close || may_close[p] != 0);
    if (!(s <= speed)) fastest = p, speed = s;  // a NaN speed is the one to name
  }
  return {fastest, speed};
}

template double stable_time_step<2>(const Particles<2>&, const MaterialConstants&, double, double, const char*);
template double stable_time_step<3>(const Particles<3>&, const MaterialConstants&, double, double, const char*);
template std::pair<std::size_t, double> fastest_signal<2>(const Particles<2>&, const MaterialConstants&, double,
                                                          const char*);
template std::pair<std::size_t, double> fastest_signal<3>(const Particles<3>&, const MaterialConstants&, double,
                                                          const char*);

}  // namespace seismpm
