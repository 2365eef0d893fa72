// The explicit time step: dt = cfl h / max_p (c_p + |v_p|), c_p = sqrt((K + 4G/3) / rho_p) (at the
// initial density for an opened particle), or a fixed one; and the guard that stops a run whose time step collapses.
// Stiffness-proportional Rayleigh damping shortens it (signal_speed).
#pragma once

#include <cmath>
#include <utility>
#include <vector>

#include "material.hpp"
#include "particles.hpp"

namespace seismpm {

// Per material, the constants the step reads without a virtual call.
struct MaterialConstants {
  std::vector<double> p_wave_modulus, initial_density, bulk_modulus, shear_modulus;
  std::vector<double> tensionless;                    // 1 or 0: doubles, which the vectorised time step can gather
  std::vector<double> intact_wave_squared;            // M / rho_0 (m2/s2): a division once, not per particle
  std::vector<double> rayleigh_alpha, rayleigh_beta;  // 1/s, s
  bool any_rayleigh = false;                          // some material is Rayleigh-damped
  bool any_tensionless = false;                       // some material has no tensile strength
  bool crack_closure = true;                          // ModelSettings::crack_closure (the time step reads it)
  void add(const Material& m) {
    p_wave_modulus.push_back(m.p_wave_modulus());
    initial_density.push_back(m.density());
    bulk_modulus.push_back(m.bulk_modulus());
    shear_modulus.push_back(m.shear_modulus());
    tensionless.push_back(m.tensionless() ? 1.0 : 0.0);
    intact_wave_squared.push_back(m.p_wave_modulus() / m.density());
    rayleigh_alpha.push_back(m.rayleigh().alpha);
    rayleigh_beta.push_back(m.rayleigh().beta);
    any_rayleigh = any_rayleigh || m.rayleigh().any();
    any_tensionless = any_tensionless || m.tensionless();
  }
};

// The p-wave speed that limits the step, sqrt(M / rho). An opened particle (a tensionless material
// looser than its initial density, under crack closure) carries no mean stress until compression has
// closed it back to that density, where its p-wave speed is sqrt(M / rho_0); until then only shear
// loads it, at sqrt(G / rho). Its falling density must not shorten the step: where a failing slope
// broke up, the particles at the swelling cap (density halved) set a step 1.25-1.4x shorter than the
// intact soil's, for no stiffness they had.
// One square root (sqrt is monotonic, so sqrt(max(a, b)) = max(sqrt a, sqrt b) exactly) and a select
// instead of a branch: this runs for every particle on every step.
// `may_close`: false where the particle's cell is not open (closure judged by the cell, with the
// cell-averaged volumetric strain): a particle looser than its own initial density there is loaded
// by compression like any other, at sqrt(M / rho).
// Looser than the initial density by more than round-off (density rho against rho0).
inline bool looser_than_initial(double rho, double rho0) { return rho * (1.0 + 1e-9) < rho0; }

template <int Dim>
[[gnu::always_inline]] inline double wave_speed(const Particles<Dim>& P, const MaterialConstants& c, std::size_t p,
                                                bool may_close = true) {
  const int m = P.material[p];
  const double rho = P.density(p), rho0 = c.initial_density[m], M = c.p_wave_modulus[m];
  const bool opened = may_close & c.crack_closure & (c.tensionless[m] != 0.0) & looser_than_initial(rho, rho0);
  return std::sqrt(opened ? std::max(M / rho0, c.shear_modulus[m] / rho) : M / rho);
}

// Speed of the fastest signal a particle carries: its p-wave (wave_speed) plus its own speed, c. With
// stiffness-proportional damping beta, the explicit limit of the highest grid mode w = 2c/h, damped at
// xi = beta w / 2 = beta c / h, is dt = (2/w)(sqrt(1 + xi^2) - xi): the speed is raised by the inverse of
// that factor, c (sqrt(1 + xi^2) + xi), so that dt = cfl h / speed still holds.
// Inlined into the loop over particles, where one particle's divisions and square roots can overlap
// the next one's.
template <int Dim>
[[gnu::always_inline]] inline double signal_speed(const Particles<Dim>& P, const MaterialConstants& c, std::size_t p,
                                                  double cell, bool may_close = true) {
  const int m = P.material[p];
  const double s = wave_speed(P, c, p, may_close) + P.v[p].norm();
  if (!(c.rayleigh_beta[m] > 0.0)) return s;
  const double xi = c.rayleigh_beta[m] * s / cell;
  return s * (std::sqrt(1.0 + xi * xi) + xi);
}

// The CFL time step of the particles' current state. `may_close` (per particle, optional): where it
// is 0 an opened particle counts as loaded (wave_speed).
template <int Dim>
double stable_time_step(const Particles<Dim>& particles, const MaterialConstants& c, double cfl, double cell,
                        const char* may_close = nullptr);

// The particle with the fastest signal, and that speed (the one that sets the CFL time step).
template <int Dim>
std::pair<std::size_t, double> fastest_signal(const Particles<Dim>& particles, const MaterialConstants& c, double cell,
                                              const char* may_close = nullptr);

template <int Dim>
class CheckpointAccess;  // reads and restores the private state (src/run/checkpoint.cpp)

class TimeStepControl {
 public:
  // The next step: `allowed` (CFL or fixed), no longer than `dt_max` (to land on an event).
  double next(double allowed, double dt_max) {
    const double dt = std::min(allowed, dt_max);
    if (first_ == 0.0) first_ = dt;
    return dt;
  }
  // A step that is not finite, or under 1e-6 of the first one without an event forcing it, means the
  // run cannot go on (a particle compressed to nothing, a velocity blowing up).
  bool collapsed(double dt, double dt_max) const { return !std::isfinite(dt) || (dt < 1e-6 * first_ && dt < dt_max); }
  double first() const { return first_; }

 private:
  template <int>
  friend class CheckpointAccess;
  double first_ = 0.0;
};

extern template double stable_time_step<2>(const Particles<2>&, const MaterialConstants&, double, double, const char*);
extern template double stable_time_step<3>(const Particles<3>&, const MaterialConstants&, double, double, const char*);
extern template std::pair<std::size_t, double> fastest_signal<2>(const Particles<2>&, const MaterialConstants&, double,
                                                                 const char*);
extern template std::pair<std::size_t, double> fastest_signal<3>(const Particles<3>&, const MaterialConstants&, double,
                                                                 const char*);

}  // namespace seismpm
