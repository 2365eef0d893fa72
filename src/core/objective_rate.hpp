// Objective stress rotation. The Jaumann rate sigma* = sigma + W sigma - sigma W integrated with the
// Hughes-Winget rule: sigma* = Q sigma Q^T with Q = (I - W/2)^-1 (I + W/2), an exact rotation, so a
// spinning body neither gains nor loses stress magnitude (the plain first-order form grows it by
// (1 + |W|^2) every step).
#pragma once

#include "types.hpp"

namespace seismpm {

// w: spin increment dt * skw(L) as a 3x3 skew matrix.
[[gnu::always_inline]] inline Sym rotate_objectively(const Sym& stress, const Mat3& w) {
  // Cayley transform of A = W/2 with axial vector a: Q = I + 2 / (1 + a.a) (A + A^2).
  const double axy = 0.5 * w(0, 1), ayz = 0.5 * w(1, 2), axz = 0.5 * w(0, 2);
  if (ayz == 0.0 && axz == 0.0) {
    // In-plane spin (every 2D step): Q = [[c, s, 0], [-s, c, 0], [0, 0, 1]].
    if (axy == 0.0) return stress;
    const double d = 1.0 / (1.0 + axy * axy);
    const double c = (1.0 - axy * axy) * d, s = 2.0 * axy * d;
    const double cc = c * c, ss = s * s, cs = c * s;
    const double xx = stress[0], yy = stress[1], xy = stress[3];
    Sym r;
    r[0] = cc * xx + 2.0 * cs * xy + ss * yy;
    r[1] = ss * xx - 2.0 * cs * xy + cc * yy;
    r[2] = stress[2];
    r[3] = -cs * xx + (cc - ss) * xy + cs * yy;
    r[4] = -s * stress[5] + c * stress[4];  // (xz, yz) turn as a vector
    r[5] = c * stress[5] + s * stress[4];
    return r;
  }
  const Mat3 a = 0.5 * w;
  const double aa = axy * axy + ayz * ayz + axz * axz;
  const Mat3 q = Mat3::Identity() + (2.0 / (1.0 + aa)) * (a + a * a);
  return to_voigt(q * to_matrix(stress) * q.transpose());
}

}  // namespace seismpm
