// What a deformable particle maps to its nodes' force, f_i += N m_g - V_sigma grad N: its weight and its
// stress times its volume. Rayleigh damping enters here, once per particle and not per node: the mass
// part as a drag -alpha m v on the weight term, the stiffness part as the viscous stress beside sigma.
// Shared by the common fields' transfer and the contact fields' own.
#pragma once

#include "particles.hpp"
#include "time_step.hpp"
#include "types.hpp"

namespace seismpm {

// v s in plane, the same values as v * in_plane(s), built column by column. Built entry by entry, the
// matrix went to memory in pieces that the transfer's loads of whole columns straddled, and the store
// buffer cannot forward such a load: the particles-to-grid loop stalled there (15 % of its time).
template <int Dim>
inline Mat<Dim> scaled_in_plane(double v, const Sym& s) {
  Mat<Dim> m;
  if constexpr (Dim == 2) {
    m.col(0) = v * Vec<2>(s[0], s[3]);
    m.col(1) = v * Vec<2>(s[3], s[1]);
  } else {
    m.col(0) = v * Vec<3>(s[0], s[3], s[5]);
    m.col(1) = v * Vec<3>(s[3], s[1], s[4]);
    m.col(2) = v * Vec<3>(s[5], s[4], s[2]);
  }
  return m;
}

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
  if (!damped) return {m * g, scaled_in_plane<Dim>(P.volume[p], P.stress[p])};
  const double alpha = damped->rayleigh_alpha[P.material[p]];
  return {m * (g - alpha * P.v[p]), scaled_in_plane<Dim>(P.volume[p], Sym(P.stress[p] + P.damping_stress[p]))};
}

}  // namespace seismpm
