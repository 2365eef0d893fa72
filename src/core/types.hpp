// Small fixed-size linear-algebra types shared by the whole kernel.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace seismpm {

template <int Dim>
using Vec = Eigen::Matrix<double, Dim, 1>;

template <int Dim>
using Mat = Eigen::Matrix<double, Dim, Dim>;

using Mat3 = Eigen::Matrix3d;

// Symmetric tensor in Voigt order xx, yy, zz, xy, yz, xz (VTK's order). Shear entries are tensor
// components (eps_xy, not gamma_xy). Plane strain keeps zz and leaves yz, xz at zero.
using Sym = Eigen::Matrix<double, 6, 1>;

inline Mat3 to_matrix(const Sym& s) {
  Mat3 m;
  m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  return m;
}

inline Sym to_voigt(const Mat3& m) {
  Sym s;
  s << m(0, 0), m(1, 1), m(2, 2), 0.5 * (m(0, 1) + m(1, 0)), 0.5 * (m(1, 2) + m(2, 1)), 0.5 * (m(0, 2) + m(2, 0));
  return s;
}

inline double trace(const Sym& s) { return s[0] + s[1] + s[2]; }

// Embeds an in-plane (Dim x Dim) tensor into 3x3; the out-of-plane entries are zero.
template <int Dim>
Mat3 embed(const Mat<Dim>& m) {
  Mat3 r = Mat3::Zero();
  r.template topLeftCorner<Dim, Dim>() = m;
  return r;
}

// The in-plane (Dim x Dim) block of a symmetric tensor times `scale`: what acts on the grid in plane
// strain. Scaled and built column by column: built entry by entry and scaled after, the matrix went to
// memory in pieces that the transfer's loads of whole columns straddled, which the store buffer cannot
// forward (the particles-to-grid loop stalled there, 15 % of its time).
template <int Dim>
Mat<Dim> in_plane(const Sym& s, double scale = 1.0) {
  Mat<Dim> m;
  if constexpr (Dim == 2) {
    m.col(0) = scale * Vec<2>(s[0], s[3]);
    m.col(1) = scale * Vec<2>(s[3], s[1]);
  } else {
    m.col(0) = scale * Vec<3>(s[0], s[3], s[5]);
    m.col(1) = scale * Vec<3>(s[3], s[1], s[4]);
    m.col(2) = scale * Vec<3>(s[5], s[4], s[2]);
  }
  return m;
}

}  // namespace seismpm
