// Principal values and directions of a symmetric stress, ordered s1 >= s2 >= s3 (tension positive).
// Plane-strain states (yz = xz = 0) take a closed form: sigma_zz is one principal value, which is
// not assumed to be the intermediate one.
#pragma once

#include <Eigen/Eigenvalues>
#include <cmath>
#include <utility>

#include "core/types.hpp"

namespace seismpm {

struct Principal {
  Eigen::Vector3d value;  // s1 >= s2 >= s3
  Mat3 direction;         // column i belongs to value[i]
};

inline Principal principal_stress(const Sym& s) {
  Principal p;
  if (s[4] == 0.0 && s[5] == 0.0) {
    const double m = 0.5 * (s[0] + s[1]), d = 0.5 * (s[0] - s[1]);
    const double r = std::sqrt(d * d + s[3] * s[3]);
    // Eigenvector of the larger in-plane value m + r, from the better-conditioned row.
    double c = 1.0, sn = 0.0;
    if (r > 0.0) {
      const double ex = d >= 0.0 ? d + r : s[3], ey = d >= 0.0 ? s[3] : r - d;
      const double inv = 1.0 / std::sqrt(ex * ex + ey * ey);
      c = ex * inv, sn = ey * inv;
    }
    double v[3] = {m + r, m - r, s[2]};
    Eigen::Vector3d dir[3] = {{c, sn, 0.0}, {-sn, c, 0.0}, {0.0, 0.0, 1.0}};
    // Sort three values descending, carrying directions along.
    if (v[1] < v[2]) std::swap(v[1], v[2]), std::swap(dir[1], dir[2]);
    if (v[0] < v[1]) std::swap(v[0], v[1]), std::swap(dir[0], dir[1]);
    if (v[1] < v[2]) std::swap(v[1], v[2]), std::swap(dir[1], dir[2]);
    for (int i = 0; i < 3; ++i) {
      p.value[i] = v[i];
      p.direction.col(i) = dir[i];
    }
    return p;
  }
  Eigen::SelfAdjointEigenSolver<Mat3> eig;
  eig.computeDirect(to_matrix(s));  // ascending
  for (int i = 0; i < 3; ++i) {
    p.value[i] = eig.eigenvalues()[2 - i];
    p.direction.col(i) = eig.eigenvectors().col(2 - i);
  }
  return p;
}

// Principal values only (cheap check of the yield function), same ordering.
inline Eigen::Vector3d principal_values(const Sym& s) {
  if (s[4] == 0.0 && s[5] == 0.0) {
    const double m = 0.5 * (s[0] + s[1]), d = 0.5 * (s[0] - s[1]);
    const double r = std::sqrt(d * d + s[3] * s[3]);
    double v[3] = {m + r, m - r, s[2]};
    if (v[1] < v[2]) std::swap(v[1], v[2]);
    if (v[0] < v[1]) std::swap(v[0], v[1]);
    if (v[1] < v[2]) std::swap(v[1], v[2]);
    return {v[0], v[1], v[2]};
  }
  return principal_stress(s).value;
}

// sum_i value_i n_i n_i^T
inline Sym from_principal(const Eigen::Vector3d& value, const Mat3& direction) {
  return to_voigt(direction * value.asDiagonal() * direction.transpose());
}

}  // namespace seismpm
