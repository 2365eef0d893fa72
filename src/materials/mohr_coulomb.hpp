// Elastic-perfectly plastic Mohr-Coulomb with non-associated flow, a tension cut-off and optional
// linear softening of c and phi with accumulated plastic shear strain. The return is made in principal
// stresses with the trial directions kept: to the face, to either edge (triaxial compression s1 = s2,
// extension s2 = s3), to the apex, or to the tension planes. A return to the face alone, everywhere,
// would leave stresses outside the yield surface near its edges and apex, where a slope's failing soil
// (low confinement, tension crack) spends much of its time.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/material.hpp"
#include "linear_elastic.hpp"
#include "strength_parameters.hpp"

namespace seismpm {

// The strength (c, phi, psi, tension; tension at most the apex c cot(phi)) and its softening.
struct MohrCoulombParameters : StrengthParameters {
  double density = 0, young = 0, poisson = 0;
  bool softening = false;  // linear from (c, phi) to (residual_cohesion, residual_friction) ...
  double residual_cohesion = 0, residual_friction = 0;
  double softening_strain = 0;  // ... reached at this accumulated plastic shear strain
};

// Throws ParameterError naming the parameter that is out of range; the softening parameters are named
// softening.cohesion, softening.friction and softening.strain.
void validate(const MohrCoulombParameters& p);

class MohrCoulomb : public Material {
 public:
  explicit MohrCoulomb(const MohrCoulombParameters& p);
  std::string_view kind() const override { return "mohr_coulomb"; }
  double p_wave_modulus() const override { return elastic_.p_wave(); }
  double shear_modulus() const override { return elastic_.shear(); }
  double bulk_modulus() const override { return elastic_.bulk(); }
  const MohrCoulombParameters& parameters() const { return p_; }
  void update_stress(const StressUpdate& batch) const override;
  bool tensionless() const override { return p_.tension == 0.0; }
  std::shared_ptr<const Material> with_reduced_strength(double srf) const override;

  // Which return the last integrate() made.
  enum class Return { Elastic, Face, CompressionEdge, ExtensionEdge, Apex, Tension, TensionEdge, TensionApex, Mixed };
  struct Result {
    Sym stress;
    Sym plastic_strain;      // plastic strain increment (tensor components)
    double shear_increment;  // equivalent plastic shear strain increment sqrt(2/3 e:e)
    Return kind;
  };
  // One stress-point update from `stress` with strain increment `de` at accumulated plastic
  // shear strain `plastic`. Allocates nothing.
  Result integrate(const Sym& stress, const Sym& de, double plastic) const;
  // Yield function (s1 - s3) + (s1 + s3) sin(phi) - 2 c cos(phi) at the given softening state.
  double yield_function(const Sym& stress, double plastic = 0.0) const;

 public:
  // Everything the return needs that depends only on the strength: the six surfaces in principal
  // space (face, edge planes, tension planes), their plastic directions through D, and the inverted
  // matrix of every active set. Built once without softening; per update with it.
  struct ReturnTables {
    Eigen::Vector3d a[6], Db[6];
    double r[6];
    Eigen::Matrix3d inverse[8];
    bool usable[8];
    double apex, sigma_c;
  };

 private:
  ReturnTables tables(double plastic) const;
  // The tables to return with, nullptr where the ordered trial principal stresses sb are elastic
  // (`softened` holds the tables of a softening material). For ordered values the face and s1 <= T
  // imply the other five planes (k >= 1, s1 >= s2 >= s3), exactly in floating point too (rounding is
  // monotone). Inline: most trials are elastic, and a call took sb through memory, where reading the
  // pair back whole waited for its two scalar stores (a third of the update's samples under perf).
  const ReturnTables* plastic_tables(const Eigen::Vector3d& sb, double plastic, ReturnTables& softened) const {
    if (p_.softening) return softened_tables(sb, plastic, softened);
    return elastic_at_fixed_strength(sb) ? nullptr : &fixed_;
  }
  // Without softening: whether the ordered trial principal stresses sb lie inside the surface.
  bool elastic_at_fixed_strength(const Eigen::Vector3d& sb) const {
    return !(fixed_.a[0].dot(sb) - fixed_.r[0] > 0.0 || sb[0] - p_.tension > 0.0);
  }
  const ReturnTables* softened_tables(const Eigen::Vector3d& sb, double plastic, ReturnTables& softened) const;
  // The return of ordered trial principal stresses sb (the directions stay): sets `result`.
  Return return_in_principal(const ReturnTables& t, const Eigen::Vector3d& sb, Eigen::Vector3d& result) const;
  Eigen::Vector3d plastic_principal_strain(const Eigen::Vector3d& ds) const;
  // integrate() from an elastic trial, and its case xz = yz = 0 (every 2D update) in closed form.
  template <bool WithPlasticStrain>
  Result integrate_trial(const Sym& trial, double plastic) const;
  // A plane-strain trial's principal values, ordered: the in-plane ones m +- r and sigma_zz. slot[i]
  // says where value i came from: 0 in-plane major, 1 in-plane minor, 2 zz.
  struct PlanePrincipal {
    double m, d, r;
    double v[3];
    int slot[3];
  };
  static PlanePrincipal plane_principal(const Sym& trial);
  template <bool WithPlasticStrain>
  Result integrate_plane(const Sym& trial, const PlanePrincipal& pp, double plastic) const;

  MohrCoulombParameters p_;
  ElasticConstants elastic_;
  ReturnTables fixed_;                                    // without softening
  double volumetric_compliance_ = 0, inverse_two_g_ = 0;  // lambda / (3 lambda + 2G), 1 / 2G
  // update_stress's scratch: the trials that need a return, to share among the threads. Per listed
  // entry, its index k in the batch, or ~k for a return made by integrate_trial / integrate_plane (a
  // softening material or a 3D trial: its trial is formed again from the particle's state, which the
  // first pass leaves as it was), and for the others, plane-strain trials at fixed strength, what
  // plane_returns reads: the ordered principal values, the in-plane half-difference d and radius r,
  // sigma_xy and the slots of values 0 and 1 (doubles: the vectoriser wants one type). 64 bytes, a
  // cache line: the whole trial and its principal values, 128 bytes, were read back from beyond the
  // cache (a third of update_stress's samples under perf).
  struct PlaneTrial {
    double v[3], d, r, xy, slot0, slot1;
  };
  mutable std::vector<int> deferred_;
  mutable std::vector<PlaneTrial> plane_trials_;
  // integrate_plane at fixed strength for `count` (at most kPlaneChunk) plane-strain trials that
  // yield, in arithmetic the compiler vectorises over the entries: entry i's stress (xx, yy, zz, xy;
  // xz = yz = 0) and its equivalent plastic shear increment.
  struct PlaneReturns {
    double *xx, *yy, *zz, *xy, *shear;
  };
  void plane_returns(const PlaneTrial* entries, int count, const PlaneReturns& out) const;
  static constexpr int kPlaneChunk = 128;  // entries plane_returns takes at a time
  mutable std::vector<int> listed_;        // per thread t, at t + 1: how many of its block's entries are listed
};

}  // namespace seismpm
