#include "diagnostics.hpp"

#include <algorithm>
#include <cmath>

namespace seismpm {

template <int Dim>
double kinetic_energy(const Particles<Dim>& particles, const std::vector<Body>& bodies) {
  double e = 0.0;
  for (std::size_t p = 0; p < particles.size(); ++p)
    if (!bodies[particles.body[p]].rigid) e += 0.5 * particles.mass[p] * particles.v[p].squaredNorm();
  return e;
}

template <int Dim>
double strain_energy(const Particles<Dim>& particles, const std::vector<Body>& bodies, const MaterialConstants& c) {
  double e = 0.0;
  for (std::size_t p = 0; p < particles.size(); ++p) {
    if (bodies[particles.body[p]].rigid) continue;
    const int m = particles.material[p];
    const Sym& s = particles.stress[p];
    const double tr = s[0] + s[1] + s[2], mean = tr / 3.0;
    const double dev2 = (s[0] - mean) * (s[0] - mean) + (s[1] - mean) * (s[1] - mean) + (s[2] - mean) * (s[2] - mean) +
                        2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
    e += particles.volume[p] * (tr * tr / (18.0 * c.bulk_modulus[m]) + dev2 / (4.0 * c.shear_modulus[m]));
  }
  return e;
}

template <int Dim>
Vec<Dim> centroid(const Particles<Dim>& particles, int body) {
  Vec<Dim> s = Vec<Dim>::Zero();
  double m = 0.0;
  for (std::size_t p = 0; p < particles.size(); ++p)
    if (particles.body[p] == body) {
      s += particles.mass[p] * particles.x[p];
      m += particles.mass[p];
    }
  return m > 0.0 ? Vec<Dim>(s / m) : s;
}

template <int Dim>
Vec<Dim> momentum(const Particles<Dim>& particles, const std::vector<Body>& bodies) {
  Vec<Dim> s = Vec<Dim>::Zero();
  for (std::size_t p = 0; p < particles.size(); ++p)
    if (!bodies[particles.body[p]].rigid) s += particles.mass[p] * particles.v[p];
  return s;
}

// Summed in fixed chunks of nodes so the result (and the step at which a gravity phase ends) does not
// depend on the number of threads. Fixed components, and nodes where a rigid body carries the soil
// (their force is the support's to take), are left out of the out-of-balance force.
template <int Dim>
Balance measure_balance(const Grid<Dim>& grid, const ContactFields<Dim>* contact, double min_mass,
                        const Vec<Dim>& gravity, std::vector<double>& scratch) {
  const auto& G = grid;
  const int n = G.node_count();
  constexpr int kChunk = 4096;
  const int chunks = (n + kChunk - 1) / kChunk;
  scratch.assign(2 * chunks, 0.0);  // per chunk: out-of-balance, external
  const double eps = min_mass;
  const Vec<Dim> g = gravity;
#pragma omp parallel for schedule(static)
  for (int c = 0; c < chunks; ++c) {
    double u = 0.0, e = 0.0;
    for (int i = c * kChunk, end = std::min(n, (c + 1) * kChunk); i < end; ++i) {
      if (!(G.mass[i] > eps)) continue;
      e += (G.mass[i] * g).squaredNorm();
      if (contact) {
        const int k = contact->nodes().index(i);
        if (k >= 0 && contact->held(k)) continue;
      }
      const unsigned mask = G.fixity(i);
      for (int d = 0; d < Dim; ++d)
        if (!(mask >> d & 1)) u += G.force[i][d] * G.force[i][d];
    }
    scratch[2 * c] = u, scratch[2 * c + 1] = e;
  }
  double u = 0.0, e = 0.0;
  for (int c = 0; c < chunks; ++c) u += scratch[2 * c], e += scratch[2 * c + 1];
  return Balance{std::sqrt(u), std::sqrt(e)};
}

#define SEISMPM_DIAGNOSTICS(D)                                                                               \
  template double kinetic_energy<D>(const Particles<D>&, const std::vector<Body>&);                          \
  template double strain_energy<D>(const Particles<D>&, const std::vector<Body>&, const MaterialConstants&); \
  template Vec<D> centroid<D>(const Particles<D>&, int);                                                     \
  template Vec<D> momentum<D>(const Particles<D>&, const std::vector<Body>&);                                \
  template Balance measure_balance<D>(const Grid<D>&, const ContactFields<D>*, double, const Vec<D>&,        \
                                      std::vector<double>&);
SEISMPM_DIAGNOSTICS(2)
SEISMPM_DIAGNOSTICS(3)
#undef SEISMPM_DIAGNOSTICS

}  // namespace seismpm
