#include "time_step.hpp"

#include "thread_shares.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace seismpm {

namespace {

// The fastest signal without Rayleigh damping (signal_speed's first part), in straight-line arithmetic
// over raw arrays that the compiler vectorises over the particles: the divisions and square roots of
// one particle after another, scalar, were most of this loop's time. Max is exact, so the result is
// the same for any grouping of the particles. Without Closure (no crack closure, or no tensionless
// material) no particle can be opened, and the unloaded speed, two more divisions a particle, is not
// computed (a third of the moving-base block's time in this loop).
template <bool Flags, bool Closure, int Dim>
double fastest_undamped_signal(const Particles<Dim>& P, const MaterialConstants& c, const char* may_close) {
  const int n = static_cast<int>(P.size());
  const double* const mass = P.mass.data();
  const double* const volume = P.volume.data();
  const double* const velocity = P.v[0].data();  // Dim contiguous components per particle
  const std::uint16_t* const material = P.material.data();
  const double* const rho0 = c.initial_density.data();
  const double* const M = c.p_wave_modulus.data();
  const double* const G = c.shear_modulus.data();
  const double* const tensionless = c.tensionless.data();
  const double* const intact = c.intact_wave_squared.data();  // M / rho0
  double max_speed = 0.0;
  auto& shares = ThreadShares::of(LoopKind::Particles);
  const auto start = ThreadShares::Clock::now();
#pragma omp parallel reduction(max : max_speed)
  {
    const auto mine = shares.mine(n);
#pragma omp simd reduction(max : max_speed)
    for (int p = static_cast<int>(mine.begin); p < static_cast<int>(mine.end); ++p) {
      const int m = material[p];
      const double rho = mass[p] / volume[p];
      const double loaded = M[m] / rho;
      double squared = loaded;
      if constexpr (Closure) {
        bool opened = (tensionless[m] != 0.0) & looser_than_initial(rho, rho0[m]);  // as wave_speed
        if constexpr (Flags) opened &= may_close[p] != 0;
        const double unloaded = std::max(intact[m], G[m] / rho);
        squared = opened ? unloaded : loaded;
      }
      double v2 = 0.0;
      for (int d = 0; d < Dim; ++d) v2 += velocity[Dim * p + d] * velocity[Dim * p + d];
      const double speed = std::sqrt(squared) + std::sqrt(v2);
      max_speed = std::max(max_speed, speed);
    }
    shares.finished(start, mine.end - mine.begin);
  }
  return max_speed;
}

}  // namespace

template <int Dim>
double stable_time_step(const Particles<Dim>& particles, const MaterialConstants& c, double cfl, double cell,
                        const char* may_close) {
  const int n = static_cast<int>(particles.size());
  double max_speed = 0.0;
  if (!c.any_rayleigh) {
    if (!(c.crack_closure && c.any_tensionless))
      max_speed = fastest_undamped_signal<false, false>(particles, c, may_close);
    else if (may_close)
      max_speed = fastest_undamped_signal<true, true>(particles, c, may_close);
    else
      max_speed = fastest_undamped_signal<false, true>(particles, c, may_close);
  } else if (may_close) {
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
