// Objective stress rotation. The Jaumann rate sigma* = sigma + W sigma - sigma W integrated with the
// Hughes-Winget rule: sigma* = Q sigma Q^T with Q = (I - W/2)^-1 (I + W/2), an exact rotation, so a
// spinning body neither gains nor loses stress magnitude (the plain first-order form grows it by
// (1 + |W|^2) every step).
#pragma once

#include "types.hpp"

namespace seismpm {

// w: spin increment dt * skw(L) as a 3x3 skew matrix.
inline Sym rotate_objectively(const Sym& stress, const Mat3& w) {
  // Cayley transform of A = W/2 with axial vector a: Q = I + 2 / (1 + a.a) (A + A^2).
  const Mat3 a = 0.5 * w;
  const double aa = a(2, 1) * a(2, 1) + a(0, 2) * a(0, 2) + a(1, 0) * a(1, 0);
  if (aa == 0.0) return stress;
  const Mat3 q = Mat3::Identity() + (2.0 / (1.0 + aa)) * (a + a * a);
  return to_voigt(q * to_matrix(stress) * q.transpose());
}

}  // namespace seismpm
