#include "mohr_coulomb.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/error.hpp"
#include "principal_stress.hpp"

namespace seismpm {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// The strength at an accumulated plastic shear strain.
struct Strength {
  double c, sin_phi, cos_phi, sin_psi;
  double k() const { return (1.0 + sin_phi) / (1.0 - sin_phi); }          // (1 + sin phi) / (1 - sin phi)
  double sigma_c() const { return 2.0 * c * cos_phi / (1.0 - sin_phi); }  // uniaxial compressive strength
};

Strength strength(const MohrCoulombParameters& p, double plastic) {
  double c = p.cohesion, phi = p.friction;
  if (p.softening) {
    const double s = p.softening_strain > 0.0 ? std::min(plastic / p.softening_strain, 1.0) : 1.0;
    c += s * (p.residual_cohesion - p.cohesion);
    phi += s * (p.residual_friction - p.friction);
  }
  const double psi = std::min(p.dilation, phi);
  return {c, std::sin(phi * kDeg), std::cos(phi * kDeg), std::sin(psi * kDeg)};
}

// Linear surfaces in principal space, a . s <= r, with plastic potential gradient b.
struct Surface {
  Eigen::Vector3d a, b;
  double r;
};

double equivalent_shear(const Eigen::Vector3d& e) {
  const double m = e.sum() / 3.0;
  return std::sqrt(2.0 / 3.0 * (e.array() - m).square().sum());
}

}  // namespace

void validate(const MohrCoulombParameters& p) {
  validate_elastic(p.density, {p.young, p.poisson});
  if (!(p.cohesion >= 0.0) || !std::isfinite(p.cohesion)) throw InputError("cohesion must be >= 0 (Pa)");
  if (!(p.friction >= 0.0 && p.friction < 90.0)) throw InputError("friction must be in [0, 90) degrees");
  if (!(p.dilation >= 0.0 && p.dilation <= p.friction)) throw InputError("dilation must be in [0, friction] degrees");
  if (!(p.tension >= 0.0) || !std::isfinite(p.tension)) throw InputError("tension must be >= 0 (Pa)");
  if (p.friction > 0.0) {
    const double apex = p.cohesion / std::tan(p.friction * kDeg);
    if (p.tension > apex * (1.0 + 1e-12))
      throw InputError("tension must not exceed the apex value c cot(phi) = " + std::to_string(apex) + " Pa");
  }
  if (p.friction == 0.0 && p.cohesion == 0.0) throw InputError("cohesion and friction cannot both be zero");
  if (p.softening) {
    if (!(p.residual_cohesion >= 0.0 && p.residual_cohesion <= p.cohesion))
      throw InputError("softening: residual cohesion must be in [0, cohesion] (Pa)");
    if (!(p.residual_friction >= 0.0 && p.residual_friction <= p.friction))
      throw InputError("softening: residual friction must be in [0, friction] degrees");
    if (!(p.softening_strain > 0.0) || !std::isfinite(p.softening_strain))
      throw InputError("softening: strain must be > 0");
    if (p.residual_friction == 0.0 && p.residual_cohesion == 0.0)
      throw InputError("softening: residual cohesion and friction cannot both be zero");
  }
}

MohrCoulomb::MohrCoulomb(const MohrCoulombParameters& p) : Material(p.density), p_(p), elastic_{p.young, p.poisson} {
  validate(p_);
}

double MohrCoulomb::yield_function(const Sym& stress, double plastic) const {
  const Strength s = strength(p_, plastic);
  const Eigen::Vector3d v = principal_values(stress);
  return (v[0] - v[2]) + (v[0] + v[2]) * s.sin_phi - 2.0 * s.c * s.cos_phi;
}

MohrCoulomb::Result MohrCoulomb::integrate(const Sym& stress, const Sym& de, double plastic) const {
  const double lambda = elastic_.lambda(), two_g = 2.0 * elastic_.shear();
  const Sym trial = elastic_trial(stress, de, lambda, two_g);
  const Strength st = strength(p_, plastic);
  const double k = st.k(), kpsi = (1.0 + st.sin_psi) / (1.0 - st.sin_psi), sc = st.sigma_c();
  const double T = p_.tension;

  // Surfaces for ordered principal stresses: the MC face (1,3), the edges' second planes (2,3) and
  // (1,2), and the tension planes s_i <= T.
  const Surface s[6] = {
      {{k, 0, -1}, {kpsi, 0, -1}, sc},  // 0: face
      {{0, k, -1}, {0, kpsi, -1}, sc},  // 1: with 0, the compression edge s1 = s2
      {{k, -1, 0}, {kpsi, -1, 0}, sc},  // 2: with 0, the extension edge s2 = s3
      {{1, 0, 0}, {1, 0, 0}, T},        // 3: tension s1
      {{0, 1, 0}, {0, 1, 0}, T},        // 4: tension s2
      {{0, 0, 1}, {0, 0, 1}, T},        // 5: tension s3
  };
  const Eigen::Vector3d sb = principal_values(trial);
  const double scale = std::max({sb.cwiseAbs().maxCoeff(), sc, T, 1e-300});
  const double tol = 1e-10 * scale;
  auto violated = [&](const Eigen::Vector3d& v, double t) {
    for (const auto& f : s)
      if (f.a.dot(v) - f.r > t) return true;
    return false;
  };
  if (!violated(sb, 0.0)) return {trial, Sym::Zero(), 0.0, Return::Elastic};

  const Principal pb = principal_stress(trial);
  Eigen::Matrix3d D = Eigen::Matrix3d::Constant(lambda);
  D.diagonal().array() += two_g;

  // Active sets from the simplest: the first whose multipliers are >= 0 and whose result is
  // admissible and keeps s1 >= s2 >= s3 is the return (Koiter's rule for the corners).
  struct Candidate {
    int n;
    int set[3];
    Return kind;
  };
  static constexpr Candidate candidates[] = {
      {1, {0}, Return::Face},           {1, {3}, Return::Tension},
      {2, {0, 1}, Return::CompressionEdge}, {2, {0, 2}, Return::ExtensionEdge},
      {2, {3, 4}, Return::TensionEdge}, {2, {0, 3}, Return::Mixed},
      {3, {0, 3, 4}, Return::Mixed},    {3, {0, 2, 3}, Return::Mixed},
  };
  Eigen::Vector3d result = sb;
  Return kind = Return::Apex;
  bool found = false;
  for (const auto& c : candidates) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
    Eigen::Vector3d f = Eigen::Vector3d::Zero();
    Eigen::Vector3d Db[3];
    for (int j = 0; j < c.n; ++j) Db[j] = D * s[c.set[j]].b;
    for (int i = 0; i < c.n; ++i) {
      f[i] = s[c.set[i]].a.dot(sb) - s[c.set[i]].r;
      for (int j = 0; j < c.n; ++j) A(i, j) = s[c.set[i]].a.dot(Db[j]);
    }
    const double det = A.topLeftCorner(c.n, c.n).determinant();
    if (!(std::abs(det) > 1e-14 * std::pow(A.topLeftCorner(c.n, c.n).cwiseAbs().maxCoeff(), c.n))) continue;
    Eigen::Vector3d dl = Eigen::Vector3d::Zero();
    if (c.n == 1)
      dl[0] = f[0] / A(0, 0);
    else if (c.n == 2)
      dl.head<2>() = A.topLeftCorner<2, 2>().inverse() * f.head<2>();
    else
      dl = A.inverse() * f;
    if ((dl.head(c.n).array() < -1e-12).any()) continue;
    Eigen::Vector3d v = sb;
    for (int j = 0; j < c.n; ++j) v -= dl[j] * Db[j];
    if (v[0] < v[1] - tol || v[1] < v[2] - tol || violated(v, tol)) continue;
    result = v;
    kind = c.kind;
    found = true;
    break;
  }
  if (!found) {
    // The apex: of the Mohr-Coulomb cone (c cot phi), or of the tension cut-off when it is lower.
    const double apex = st.sin_phi > 0.0 ? st.c * st.cos_phi / st.sin_phi : std::numeric_limits<double>::infinity();
    const double a = std::min(apex, T);
    result = Eigen::Vector3d::Constant(a);
    kind = a < apex ? Return::TensionApex : Return::Apex;
  }
  Result out;
  out.stress = from_principal(result, pb.direction);
  out.kind = kind;
  // Plastic strain: the part of the trial's elastic strain that the return removed, D^-1 (sb - s).
  const Eigen::Vector3d dep = D.ldlt().solve(sb - result);
  out.plastic_strain = from_principal(dep, pb.direction);
  out.shear_increment = equivalent_shear(dep);
  return out;
}

void MohrCoulomb::update_stress(const StressUpdate& b) const {
#pragma omp parallel for schedule(static)
  for (int k = 0; k < b.count; ++k) {
    const int p = b.index[k];
    const Result r = integrate(b.stress[p], b.strain_increment[p], b.plastic_strain[p]);
    b.stress[p] = r.stress;
    b.plastic_strain[p] += r.shear_increment;
    b.yield[p] = r.kind != Return::Elastic;
  }
}

}  // namespace seismpm
