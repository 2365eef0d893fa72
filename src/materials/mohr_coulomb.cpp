#include "mohr_coulomb.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>
#include <type_traits>
#include <utility>
#include <vector>

#include <omp.h>

#include "core/error.hpp"
#include "core/thread_shares.hpp"
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
  const double m = e.sum() * (1.0 / 3.0);
  return std::sqrt(2.0 / 3.0 * (e.array() - m).square().sum());
}

}  // namespace

void validate(const MohrCoulombParameters& p) {
  validate_elastic(p.density, {p.young, p.poisson});
  validate_strength(p);
  if (p.friction > 0.0) {
    const double apex = p.cohesion / std::tan(p.friction * kDeg);
    // The relative slack forgives a tension computed as c / tan(phi) in another order.
    if (p.tension > apex * (1.0 + 1e-12))
      throw ParameterError({"tension"}, "must be in [0, c cot(phi) = " + number_text(apex) +
                                            "] (Pa, at most the apex of the yield surface), got " +
                                            number_text(p.tension));
  }
  if (!p.softening) return;
  check_parameter("softening.cohesion", p.residual_cohesion, closed(0.0, p.cohesion),
                  "Pa, the residual cohesion at most the peak");
  check_parameter("softening.friction", p.residual_friction, closed(0.0, p.friction),
                  "degrees, the residual friction at most the peak");
  check_parameter("softening.strain", p.softening_strain, above(0.0));
  if (p.residual_friction == 0.0 && p.residual_cohesion == 0.0)
    throw ParameterError({"softening.cohesion", "softening.friction"}, "cannot both be zero");
}

// Active sets, from the simplest: the first whose multipliers are >= 0 and whose result is admissible
// and keeps s1 >= s2 >= s3 is the return (Koiter's rule at the corners).
struct Candidate {
  int n;
  int set[3];
  MohrCoulomb::Return kind;
};
constexpr Candidate kCandidates[8] = {
    {1, {0}, MohrCoulomb::Return::Face},
    {1, {3}, MohrCoulomb::Return::Tension},
    {2, {0, 1}, MohrCoulomb::Return::CompressionEdge},
    {2, {0, 2}, MohrCoulomb::Return::ExtensionEdge},
    {2, {3, 4}, MohrCoulomb::Return::TensionEdge},
    {2, {0, 3}, MohrCoulomb::Return::Mixed},
    {3, {0, 3, 4}, MohrCoulomb::Return::Mixed},
    {3, {0, 2, 3}, MohrCoulomb::Return::Mixed},
};

std::shared_ptr<const Material> MohrCoulomb::with_reduced_strength(double srf) const {
  MohrCoulombParameters r = p_;
  static_cast<StrengthParameters&>(r) = reduced_strength(p_, srf);
  // The residual strength is reduced alike, so softening goes from the reduced peak to the reduced
  // residual (both divided by the same factor keep their order).
  r.residual_cohesion = p_.residual_cohesion / srf;
  r.residual_friction = reduced_friction(p_.residual_friction, srf);
  // tension / srf <= (c / srf) / tan(phi_r) = c cot(phi): the apex does not move; the clamp only
  // absorbs round-off.
  if (r.friction > 0.0) r.tension = std::min(r.tension, r.cohesion / std::tan(r.friction * kDeg));
  return with_my_damping(std::make_shared<MohrCoulomb>(r));  // damping is not strength: kept
}

MohrCoulomb::MohrCoulomb(const MohrCoulombParameters& p) : Material(p.density), p_(p), elastic_{p.young, p.poisson} {
  validate(p_);
  fixed_ = tables(0.0);
  const double lambda = elastic_.lambda(), two_g = 2.0 * elastic_.shear();
  volumetric_compliance_ = lambda / (3.0 * lambda + two_g);
  inverse_two_g_ = 1.0 / two_g;
}

// The elastic strain a return of ds in principal stress removed: D^-1 ds, with
// D^-1 = (I - lambda / (3 lambda + 2G) 1 1^T) / 2G.
Eigen::Vector3d MohrCoulomb::plastic_principal_strain(const Eigen::Vector3d& ds) const {
  return (ds.array() - volumetric_compliance_ * ds.sum()).matrix() * inverse_two_g_;
}

MohrCoulomb::ReturnTables MohrCoulomb::tables(double plastic) const {
  const Strength st = strength(p_, plastic);
  const double k = st.k(), kpsi = (1.0 + st.sin_psi) / (1.0 - st.sin_psi), sc = st.sigma_c(), T = p_.tension;
  // Surfaces for ordered principal stresses: 0 the face (1,3); with it, 1 makes the compression edge
  // s1 = s2 and 2 the extension edge s2 = s3; 3-5 the tension planes s_i <= T.
  const Surface s[6] = {
      {{k, 0, -1}, {kpsi, 0, -1}, sc}, {{0, k, -1}, {0, kpsi, -1}, sc}, {{k, -1, 0}, {kpsi, -1, 0}, sc},
      {{1, 0, 0}, {1, 0, 0}, T},       {{0, 1, 0}, {0, 1, 0}, T},       {{0, 0, 1}, {0, 0, 1}, T},
  };
  Eigen::Matrix3d D = Eigen::Matrix3d::Constant(elastic_.lambda());
  D.diagonal().array() += 2.0 * elastic_.shear();
  ReturnTables t;
  for (int j = 0; j < 6; ++j) {
    t.a[j] = s[j].a;
    t.Db[j] = D * s[j].b;
    t.r[j] = s[j].r;
  }
  for (int c = 0; c < 8; ++c) {
    const Candidate& cand = kCandidates[c];
    Eigen::Matrix3d A = Eigen::Matrix3d::Identity();  // identity outside the active block
    for (int i = 0; i < cand.n; ++i)
      for (int j = 0; j < cand.n; ++j) A(i, j) = t.a[cand.set[i]].dot(t.Db[cand.set[j]]);
    double size = 0.0;  // of the active block only
    for (int i = 0; i < cand.n; ++i)
      for (int j = 0; j < cand.n; ++j) size = std::max(size, std::abs(A(i, j)));
    t.usable[c] = std::abs(A.determinant()) > 1e-14 * std::pow(size, cand.n);
    t.inverse[c] = t.usable[c] ? Eigen::Matrix3d(A.inverse()) : Eigen::Matrix3d::Zero();
  }
  t.apex = st.sin_phi > 0.0 ? st.c * st.cos_phi / st.sin_phi : std::numeric_limits<double>::infinity();
  t.sigma_c = sc;
  return t;
}

double MohrCoulomb::yield_function(const Sym& stress, double plastic) const {
  const Strength s = strength(p_, plastic);
  const Eigen::Vector3d v = principal_values(stress);
  return (v[0] - v[2]) + (v[0] + v[2]) * s.sin_phi - 2.0 * s.c * s.cos_phi;
}

MohrCoulomb::Return MohrCoulomb::return_in_principal(const ReturnTables& t, const Eigen::Vector3d& sb,
                                                     Eigen::Vector3d& result) const {
  const double scale = std::max({sb.cwiseAbs().maxCoeff(), t.sigma_c, p_.tension, 1e-300});
  const double tol = 1e-10 * scale;
  auto violated = [&](const Eigen::Vector3d& v, double margin) {
    for (int j = 0; j < 6; ++j)
      if (t.a[j].dot(v) - t.r[j] > margin) return true;
    return false;
  };
  for (int c = 0; c < 8; ++c) {
    if (!t.usable[c]) continue;
    const Candidate& cand = kCandidates[c];
    Eigen::Vector3d f = Eigen::Vector3d::Zero();
    for (int i = 0; i < cand.n; ++i) f[i] = t.a[cand.set[i]].dot(sb) - t.r[cand.set[i]];
    const Eigen::Vector3d dl = t.inverse[c] * f;
    if ((dl.head(cand.n).array() < -1e-12).any()) continue;
    Eigen::Vector3d v = sb;
    for (int j = 0; j < cand.n; ++j) v -= dl[j] * t.Db[cand.set[j]];
    if (v[0] < v[1] - tol || v[1] < v[2] - tol || violated(v, tol)) continue;
    result = v;
    return cand.kind;
  }
  // The apex: of the Mohr-Coulomb cone (c cot phi), or of the tension cut-off when it is lower.
  const double a = std::min(t.apex, p_.tension);
  result = Eigen::Vector3d::Constant(a);
  return a < t.apex ? Return::TensionApex : Return::Apex;
}

// plastic_tables with softening: the strength at `plastic`, its tables only where the trial yields.
const MohrCoulomb::ReturnTables* MohrCoulomb::softened_tables(const Eigen::Vector3d& sb, double plastic,
                                                              ReturnTables& softened) const {
  const Strength st = strength(p_, plastic);
  if (st.k() * sb[0] - sb[2] - st.sigma_c() <= 0.0 && sb[0] <= p_.tension) return nullptr;
  softened = tables(plastic);
  return &softened;
}

// Plane-strain states (xz = yz = 0): the in-plane principal values m +- r take their directions from
// the angle 2 theta (cos = d / r, sin = xy / r), and sigma_zz is the third value in any order, so the
// return rotates back in closed form, with neither eigenvectors nor a square root beyond r's. Always
// inlined: called, it returned its result through memory, and update_stress read it back with one wide
// load that waited for the callee's narrow stores (a third of update_stress's samples under perf).
[[gnu::always_inline]] inline MohrCoulomb::PlanePrincipal MohrCoulomb::plane_principal(const Sym& trial) {
  PlanePrincipal pp;
  pp.m = 0.5 * (trial[0] + trial[1]), pp.d = 0.5 * (trial[0] - trial[1]);
  pp.r = std::sqrt(pp.d * pp.d + trial[3] * trial[3]);
  double* v = pp.v;
  int* slot = pp.slot;
  v[0] = pp.m + pp.r, v[1] = pp.m - pp.r, v[2] = trial[2];
  slot[0] = 0, slot[1] = 1, slot[2] = 2;
  if (v[1] < v[2]) std::swap(v[1], v[2]), std::swap(slot[1], slot[2]);
  if (v[0] < v[1]) std::swap(v[0], v[1]), std::swap(slot[0], slot[1]);
  if (v[1] < v[2]) std::swap(v[1], v[2]), std::swap(slot[1], slot[2]);
  return pp;
}

template <bool WithPlasticStrain>
MohrCoulomb::Result MohrCoulomb::integrate_plane(const Sym& trial, const PlanePrincipal& pp, double plastic) const {
  const double d = pp.d, r = pp.r;
  const int* slot = pp.slot;
  const Eigen::Vector3d sb(pp.v[0], pp.v[1], pp.v[2]);
  Result out;
  ReturnTables softened;
  const ReturnTables* t = plastic_tables(sb, plastic, softened);
  if (!t) {
    out.stress = trial;
    out.kind = Return::Elastic;
    out.plastic_strain.setZero();
    out.shear_increment = 0.0;
    return out;
  }
  Eigen::Vector3d result;
  out.kind = return_in_principal(*t, sb, result);
  const double inv_r = r > 0.0 ? 1.0 / r : 0.0;
  const double cos2 = r > 0.0 ? d * inv_r : 1.0, sin2 = trial[3] * inv_r;
  // sum_i value_i n_i n_i^T for in-plane values (major, minor) and zz.
  auto to_tensor = [&](const Eigen::Vector3d& ordered) {
    double by_slot[3];
    for (int i = 0; i < 3; ++i) by_slot[slot[i]] = ordered[i];
    const double mean = 0.5 * (by_slot[0] + by_slot[1]), half = 0.5 * (by_slot[0] - by_slot[1]);
    Sym s;
    s << mean + half * cos2, mean - half * cos2, by_slot[2], half * sin2, 0.0, 0.0;
    return s;
  };
  out.stress = to_tensor(result);
  const Eigen::Vector3d dep = plastic_principal_strain(sb - result);
  if constexpr (WithPlasticStrain)
    out.plastic_strain = to_tensor(dep);
  else
    out.plastic_strain.setZero();  // not asked for: defined all the same
  out.shear_increment = equivalent_shear(dep);
  return out;
}

// From the elastic trial: the plane-strain closed form, else the principal directions of the eigen
// solver. Without WithPlasticStrain the plastic strain tensor is left zero (only its shear is kept).
template <bool WithPlasticStrain>
MohrCoulomb::Result MohrCoulomb::integrate_trial(const Sym& trial, double plastic) const {
  if (trial[4] == 0.0 && trial[5] == 0.0)
    return integrate_plane<WithPlasticStrain>(trial, plane_principal(trial), plastic);
  const Principal pb = principal_stress(trial);
  const Eigen::Vector3d& sb = pb.value;
  ReturnTables softened;
  const ReturnTables* t = plastic_tables(sb, plastic, softened);
  if (!t) return {trial, Sym::Zero(), 0.0, Return::Elastic};
  Eigen::Vector3d result;
  Result out;
  out.kind = return_in_principal(*t, sb, result);
  out.stress = from_principal(result, pb.direction);
  const Eigen::Vector3d dep = plastic_principal_strain(sb - result);
  if constexpr (WithPlasticStrain)
    out.plastic_strain = from_principal(dep, pb.direction);
  else
    out.plastic_strain.setZero();
  out.shear_increment = equivalent_shear(dep);
  return out;
}

MohrCoulomb::Result MohrCoulomb::integrate(const Sym& stress, const Sym& de, double plastic) const {
  return integrate_trial<true>(elastic_trial(stress, de, elastic_.lambda(), 2.0 * elastic_.shear()), plastic);
}

// integrate_plane at fixed strength for many entries at once: return_in_principal's candidates in
// its order, each one's tests written as it writes them (a NaN passes them alike, and goes on to the
// particle checks), the first that passes taken, else the apex; then the rotation back and the plastic
// shear. The same tests in the same order, with every candidate computed and the first that passes
// chosen by selects instead of branches, so that the loops vectorise (the results agree with
// integrate_plane's to round-off: the compiler may fuse the products differently). The entries'
// values are first copied into arrays a chunk at a time (the vectoriser does not load fields of the
// entries in place).
void MohrCoulomb::plane_returns(const PlaneTrial* entries, int count, const PlaneReturns& out) const {
  const ReturnTables& t = fixed_;
  double a[6][3], db[6][3], r[6], inverse[8][3][3];
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i < 3; ++i) a[j][i] = t.a[j][i], db[j][i] = t.Db[j][i];
    r[j] = t.r[j];
  }
  bool usable[8];
  for (int c = 0; c < 8; ++c) {
    usable[c] = t.usable[c];
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) inverse[c][i][k] = t.inverse[c](i, k);
  }
  const double apex = std::min(t.apex, p_.tension);
  const double floor = std::max({t.sigma_c, p_.tension, 1e-300});
  const double vc = volumetric_compliance_, inv_2g = inverse_two_g_;
  // Every array of doubles, the slots too: with narrower types beside them the vectoriser found no
  // vector type for the loop.
  constexpr int kChunk = kPlaneChunk;
  alignas(64) double v0s[kChunk], v1s[kChunk], v2s[kChunk], ds[kChunk], rs[kChunk], xys[kChunk];
  alignas(64) double s0s[kChunk], s1s[kChunk];
  alignas(64) double tols[kChunk], res0[kChunk], res1[kChunk], res2[kChunk], done[kChunk];
  assert(count <= kChunk);  // the caller's chunk
  const int n = count;
  for (int i = 0; i < n; ++i) {
    const PlaneTrial& e = entries[i];
    v0s[i] = e.v[0], v1s[i] = e.v[1], v2s[i] = e.v[2];
    ds[i] = e.d, rs[i] = e.r, xys[i] = e.xy;
    s0s[i] = e.slot0, s1s[i] = e.slot1;
  }
  // Local, unaliased pointers: read through `out` in the loop, each store could have changed them.
  double* __restrict xx = out.xx;
  double* __restrict yy = out.yy;
  double* __restrict zz = out.zz;
  double* __restrict xy = out.xy;
  double* __restrict shear = out.shear;
  // Candidate c for every entry not yet settled; the caller takes the candidates in order and stops
  // once every entry of the chunk has its return. Most chunks settle early (a shaken slope's returns go
  // mostly to the tension plane, a collapsing column's to the compression edge, the second and third
  // candidates), and each candidate after that cost every entry as much again; a settled entry is never
  // changed, so stopping changes no result.
  auto try_candidate = [&](auto candidate) {
    constexpr int c = decltype(candidate)::value;
    constexpr Candidate cand = kCandidates[c];
    double missing = 0.0;
    for (int i = 0; i < n; ++i) {
      const double sb[3] = {v0s[i], v1s[i], v2s[i]};
      double res[3] = {res0[i], res1[i], res2[i]};
      bool found = done[i] != 0.0;
      double f[3] = {0.0, 0.0, 0.0};
#pragma GCC unroll 8
      for (int k = 0; k < cand.n; ++k) {
        const int j = cand.set[k];
        f[k] = a[j][0] * sb[0] + a[j][1] * sb[1] + a[j][2] * sb[2] - r[j];
      }
      double dl[3];
#pragma GCC unroll 8
      for (int k = 0; k < 3; ++k) dl[k] = inverse[c][k][0] * f[0] + inverse[c][k][1] * f[1] + inverse[c][k][2] * f[2];
      bool take = usable[c] & !found;
#pragma GCC unroll 8
      for (int k = 0; k < cand.n; ++k) take &= !(dl[k] < -1e-12);
      double v[3] = {sb[0], sb[1], sb[2]};
#pragma GCC unroll 8
      for (int k = 0; k < cand.n; ++k) {
        const int j = cand.set[k];
#pragma GCC unroll 8
        for (int m = 0; m < 3; ++m) v[m] -= dl[k] * db[j][m];
      }
      const double tol = tols[i];
      take &= !(v[0] < v[1] - tol) & !(v[1] < v[2] - tol);
#pragma GCC unroll 8
      for (int j = 0; j < 6; ++j) take &= !(a[j][0] * v[0] + a[j][1] * v[1] + a[j][2] * v[2] - r[j] > tol);
#pragma GCC unroll 8
      for (int m = 0; m < 3; ++m) res[m] = take ? v[m] : res[m];
      found |= take;
      res0[i] = res[0], res1[i] = res[1], res2[i] = res[2];
      done[i] = found ? 1.0 : 0.0;
      missing += found ? 0.0 : 1.0;
    }
    return missing;
  };
  for (int i = 0; i < n; ++i) {
    tols[i] = 1e-10 * std::max(std::max(std::abs(v0s[i]), std::abs(v1s[i])), std::max(std::abs(v2s[i]), floor));
    res0[i] = res1[i] = res2[i] = apex;  // where no candidate passes
    done[i] = 0.0;
  }
  [&]<int... c>(std::integer_sequence<int, c...>) {
    // && stops at the first candidate after which no entry is missing.
    (void)((try_candidate(std::integral_constant<int, c>{}) > 0.0) && ...);
  }
  (std::make_integer_sequence<int, 8>{});
  for (int i = 0; i < n; ++i) {
    const double sb[3] = {v0s[i], v1s[i], v2s[i]};
    const double res[3] = {res0[i], res1[i], res2[i]};
    // Back to tensor components: value i belongs to slot[i] (0 in-plane major, 1 minor, 2 zz).
    const double s0 = s0s[i], s1 = s1s[i];
    const double major = s0 == 0 ? res[0] : (s1 == 0 ? res[1] : res[2]);
    const double minor = s0 == 1 ? res[0] : (s1 == 1 ? res[1] : res[2]);
    const double out_zz = s0 == 2 ? res[0] : (s1 == 2 ? res[1] : res[2]);
    // r = 0 (then d = xy = 0): cos 2 theta = 1 and sin 2 theta = 0, by arithmetic on round = (r > 0).
    const double rr = rs[i], round = rr > 0.0;  // 1 or 0
    const double inv_r = 1.0 / (rr + (1.0 - round));
    const double cos2 = round * (ds[i] * inv_r) + (1.0 - round), sin2 = xys[i] * inv_r;
    const double mean = 0.5 * (major + minor), half = 0.5 * (major - minor);
    xx[i] = mean + half * cos2;
    yy[i] = mean - half * cos2;
    zz[i] = out_zz;
    xy[i] = half * sin2;
    // The plastic strain D^-1 (trial - result) and its equivalent shear.
    const double e0 = sb[0] - res[0], e1 = sb[1] - res[1], e2 = sb[2] - res[2];
    const double vol = vc * (e0 + e1 + e2);
    const double p0 = (e0 - vol) * inv_2g, p1 = (e1 - vol) * inv_2g, p2 = (e2 - vol) * inv_2g;
    const double m = (p0 + p1 + p2) * (1.0 / 3.0);
    shear[i] = std::sqrt(2.0 / 3.0 * ((p0 - m) * (p0 - m) + (p1 - m) * (p1 - m) + (p2 - m) * (p2 - m)));
  }
}

// Two passes in one parallel region. The first, each thread over its own block of particles (its
// share of the material's loops, ThreadShares, timed there), settles the elastic trials and lists the
// rest in order in its block's part of the scratch lists. The second shares the listed returns in the
// same proportions: the yielding particles of a slope lie together in the cell-sorted order, and left
// to the thread whose block held them they kept the other one waiting. Each particle's update is the
// same function of its own state either way, so the results do not depend on the threads.
void MohrCoulomb::update_stress(const StressUpdate& b) const {
  const double lambda = elastic_.lambda(), two_g = 2.0 * elastic_.shear();
  const bool fixed_strength = !p_.softening;
  std::vector<int>& deferred = deferred_;
  std::vector<PlaneTrial>& plane_trials = plane_trials_;
  deferred.resize(b.count);
  plane_trials.resize(b.count);
  std::vector<int>& listed = listed_;
  const int threads = omp_get_max_threads();
  listed.assign(threads + 1, 0);
  const double face_a0 = fixed_.a[0][0], face_a1 = fixed_.a[0][1], face_a2 = fixed_.a[0][2];
  const double face_r = fixed_.r[0], tension = p_.tension;
  auto& shares = ThreadShares::of(LoopKind::Material);
  const auto start = ThreadShares::Clock::now();
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    const auto block_start = [&](int j) { return static_cast<int>(shares.first(j, nt, b.count)); };
    const int lo = block_start(t), hi = block_start(t + 1);
    int found = 0;
    // A chunk at a time: the trials gathered into arrays, then their principal values (plane_principal's
    // arithmetic, its compare-and-swaps as selects) and the elastic test lane by lane, which the compiler
    // vectorises (particle by particle, the swaps' branches were mispredicted and the trial was read
    // back through memory), then each trial settled or listed.
    constexpr int C = kPlaneChunk;
    alignas(64) double t0[C], t1[C], t2[C], t3[C], t4[C], t5[C];
    alignas(64) double dd[C], rr[C], v0[C], v1[C], v2[C], sl0[C], sl1[C], fast[C], elastic[C];
    for (int k0 = lo; k0 < hi; k0 += C) {
      const int n = std::min(C, hi - k0);
      for (int i = 0; i < n; ++i) {
        const int p = b.index[k0 + i];
        const Sym trial = elastic_trial(b.stress[p], b.strain_increment[p], lambda, two_g);
        t0[i] = trial[0], t1[i] = trial[1], t2[i] = trial[2], t3[i] = trial[3], t4[i] = trial[4], t5[i] = trial[5];
      }
      for (int i = 0; i < n; ++i) {
        // 0.5 (xx + yy) is exact, so m +- r rounds as plane_principal's does, fused or not.
        const double m = 0.5 * (t0[i] + t1[i]), d = 0.5 * (t0[i] - t1[i]);
        const double r = std::sqrt(d * d + t3[i] * t3[i]);
        dd[i] = d, rr[i] = r;
        double a = m + r, bb = m - r, c = t2[i], sa = 0.0, sb = 1.0, sc = 2.0;
        // Where the first value is below the second, the two swap, with their slots.
        bool swap = bb < c;
        double up = swap ? c : bb, down = swap ? bb : c, up_slot = swap ? sc : sb, down_slot = swap ? sb : sc;
        bb = up, c = down, sb = up_slot, sc = down_slot;
        swap = a < bb;
        up = swap ? bb : a, down = swap ? a : bb, up_slot = swap ? sb : sa, down_slot = swap ? sa : sb;
        a = up, bb = down, sa = up_slot, sb = down_slot;
        swap = bb < c;
        up = swap ? c : bb, down = swap ? bb : c, up_slot = swap ? sc : sb;
        bb = up, c = down, sb = up_slot;
        v0[i] = a, v1[i] = bb, v2[i] = c, sl0[i] = sa, sl1[i] = sb;
        // Plane strain (integrate_trial's first case) at fixed strength: plane_returns' entries.
        fast[i] = fixed_strength & (t4[i] == 0.0) & (t5[i] == 0.0);
        // elastic_at_fixed_strength's test, in its order of operations, without its branch.
        const double face = (face_a0 * a + face_a1 * bb) + face_a2 * c - face_r;
        elastic[i] = !((face > 0.0) | (a - tension > 0.0));
      }
      for (int i = 0; i < n; ++i) {
        const int k = k0 + i, p = b.index[k];
        if (fast[i] != 0.0 && elastic[i] != 0.0) {  // the test the full update makes (plastic_tables)
          Sym& s = b.stress[p];
          s[0] = t0[i], s[1] = t1[i], s[2] = t2[i], s[3] = t3[i], s[4] = t4[i], s[5] = t5[i];
          b.yield[p] = 0;
          continue;
        }
        const int slot = lo + found++;
        if (fast[i] != 0.0) {
          deferred[slot] = k;
          plane_trials[slot] = PlaneTrial{{v0[i], v1[i], v2[i]}, dd[i], rr[i], t3[i], sl0[i], sl1[i]};
        } else {
          deferred[slot] = ~k;
          plane_trials[slot] = PlaneTrial{};  // plane_returns computes with it; nothing reads the result
        }
      }
    }
    listed[t + 1] = found;
    shares.finished(start, hi - lo);
#pragma omp barrier
    // Block j's listed entries are at [block_start(j), block_start(j) + listed[j + 1]) of the lists;
    // this thread takes its share, entries [first, last), of their concatenation.
    int total = 0;
    for (int j = 0; j < nt; ++j) total += listed[j + 1];
    const int first = static_cast<int>(shares.first(t, nt, total));
    const int last = static_cast<int>(shares.first(t + 1, nt, total));
    // This thread's entries block by block (each block's entries are contiguous), a chunk at a time:
    // the chunk's plane-strain returns at fixed strength together (plane_returns), then each entry's
    // result written or its general return made. The results of one chunk at a time: kept for every
    // listed entry, they cost 24 bytes a particle of peak memory in bench/memory.sh's block.
    alignas(64) double xx[kPlaneChunk], yy[kPlaneChunk], zz[kPlaneChunk], xy[kPlaneChunk], shear[kPlaneChunk];
    const PlaneReturns plane{xx, yy, zz, xy, shear};
    int block = 0, before = 0;  // entries in the blocks before `block`
    while (block < nt && before + listed[block + 1] <= first) before += listed[++block];
    for (int e = first; e < last;) {
      const int block_end = std::min(last, before + listed[block + 1]);
      const int offset = block_start(block) + (e - before);
      const int* ks = deferred.data() + offset;
      const int n = std::min(kPlaneChunk, block_end - e);
      bool any_fast = false;  // none in a 3D model or a softening one: no plane-strain returns
      for (int i = 0; i < n; ++i) any_fast |= ks[i] >= 0;
      if (any_fast) plane_returns(plane_trials.data() + offset, n, plane);
      for (int i = 0; i < n; ++i) {
        const bool plane_entry = ks[i] >= 0;
        const int p = b.index[plane_entry ? ks[i] : ~ks[i]];
        if (plane_entry) {  // plastic: the trial was not elastic
          Sym& s = b.stress[p];
          s[0] = xx[i], s[1] = yy[i], s[2] = zz[i], s[3] = xy[i], s[4] = 0.0, s[5] = 0.0;
          b.plastic_strain[p] += shear[i];
          b.yield[p] = 1;
          continue;
        }
        // The step's plastic strain tensor is not kept: only its equivalent shear accumulates.
        const Sym trial = elastic_trial(b.stress[p], b.strain_increment[p], lambda, two_g);
        const Result r = integrate_trial<false>(trial, b.plastic_strain[p]);
        b.stress[p] = r.stress;
        b.plastic_strain[p] += r.shear_increment;
        b.yield[p] = r.kind != Return::Elastic;
      }
      e += n;
      if (e == before + listed[block + 1]) before += listed[++block];  // the block is done
    }
  }
}

}  // namespace seismpm
