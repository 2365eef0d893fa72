// What a deformable particle maps to its nodes' force, f_i += N m_g - V_sigma grad N: its weight and its
// stress times its volume. Rayleigh damping enters here, once per particle and not per node: the mass
// part as a drag -alpha m v on the weight term, the stiffness part as the viscous stress beside sigma.
// Shared by the common fields' transfer and the contact fields' own.
#pragma once

#include "particles.hpp"
#include "time_step.hpp"
#include "types.hpp"

namespace seismpm {

template <int Dim>
struct ParticleForceTerms {
  Vec<Dim> mg;  // m g (- alpha m v)
  Mat<Dim> vs;  // V (sigma + sigma_v), in plane
};

// `damped` is the model's material constants when some material is Rayleigh-damped, else null (the
// undamped arithmetic, unchanged).
template <int Dim>
inline ParticleForceTerms<Dim> particle_force_terms(const Particles<Dim>& P, const MaterialConstants* damped,
                                                    const Vec<Dim>& g, int p) {
  const double m = P.mass[p];
  if (!damped) return {m * g, in_plane<Dim>(P.stress[p], P.volume[p])};
  const double alpha = damped->rayleigh_alpha[P.material[p]];
  return {m * (g - alpha * P.v[p]), in_plane<Dim>(Sym(P.stress[p] + P.damping_stress[p]), P.volume[p])};
}

}  // namespace seismpm
