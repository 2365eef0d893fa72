#include "drucker_prager.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace seismpm {

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;

double sqrt_j2(const Sym& s, double mean) {
  const double dx = s[0] - mean, dy = s[1] - mean, dz = s[2] - mean;
  return std::sqrt(0.5 * (dx * dx + dy * dy + dz * dz) + s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
}
}  // namespace

DruckerPragerFit parse_fit(const std::string& name) {
  if (name == "plane_strain") return DruckerPragerFit::PlaneStrain;
  if (name == "outer") return DruckerPragerFit::Outer;
  if (name == "inner") return DruckerPragerFit::Inner;
  throw InputError("fit must be one of plane_strain|outer|inner, got '" + name + "'");
}

DruckerPragerConstants drucker_prager_constants(const DruckerPragerParameters& p) {
  const double sf = std::sin(p.friction * kDeg), cf = std::cos(p.friction * kDeg);
  const double sp = std::sin(p.dilation * kDeg);
  const double r3 = std::sqrt(3.0);
  switch (p.fit) {
    case DruckerPragerFit::Outer:
      return {2.0 * sf / (r3 * (3.0 - sf)), 6.0 * p.cohesion * cf / (r3 * (3.0 - sf)), 2.0 * sp / (r3 * (3.0 - sp))};
    case DruckerPragerFit::Inner:
      return {2.0 * sf / (r3 * (3.0 + sf)), 6.0 * p.cohesion * cf / (r3 * (3.0 + sf)), 2.0 * sp / (r3 * (3.0 + sp))};
    case DruckerPragerFit::PlaneStrain:
    default: {
      // Plane strain at the limit: the flow rule fixes sigma_zz (no out-of-plane plastic strain), so
      // sqrt(J2) = d / sqrt(1 - 3 beta^2) with d = (s1 - s3)/2 and I1 = 3m - 3 beta sqrt(J2), m = (s1 + s3)/2.
      // Matching d + m sin(phi) - c cos(phi) = 0 gives alpha and k below; beta matches MC's plane-strain
      // dilation ratio sin(psi). psi = 0 gives alpha = sin(phi)/3, k = c cos(phi); psi = phi the
      // classical tan(phi)/sqrt(9 + 12 tan^2 phi), 3c/sqrt(9 + 12 tan^2 phi).
      const double beta = sp / std::sqrt(9.0 + 3.0 * sp * sp);
      const double root = std::sqrt(1.0 - 3.0 * beta * beta);
      const double alpha = sf / (3.0 * (root + beta * sf));
      return {alpha, p.cohesion * cf * (1.0 - 3.0 * alpha * beta) / root, beta};
    }
  }
}

void validate(const DruckerPragerParameters& p) {
  validate_elastic(p.density, {p.young, p.poisson});
  validate_strength(p);
  if (p.friction > 0.0) {
    const auto c = drucker_prager_constants(p);
    const double apex = c.k / (3.0 * c.alpha);  // mean stress at the cone's apex
    if (p.tension > apex * (1.0 + 1e-12))
      throw ParameterError({"tension"}, "must be in [0, " + number_text(apex) +
                                            "] (Pa, at most the apex mean stress of the cone), got " +
                                            number_text(p.tension));
  }
}

DruckerPrager::DruckerPrager(const DruckerPragerParameters& p)
    : Material(p.density), p_(p), elastic_{p.young, p.poisson}, c_{} {
  validate(p_);
  c_ = drucker_prager_constants(p_);
}

std::shared_ptr<const Material> DruckerPrager::with_reduced_strength(double srf) const {
  DruckerPragerParameters r = p_;
  static_cast<StrengthParameters&>(r) = reduced_strength(p_, srf);
  // The fitted cone's apex moves with a reduced dilation angle (plane_strain fit): the reduced tensile
  // strength stays at most that apex.
  if (r.friction > 0.0) {
    const auto c = drucker_prager_constants(r);
    r.tension = std::min(r.tension, c.k / (3.0 * c.alpha));
  }
  return with_my_damping(std::make_shared<DruckerPrager>(r));  // damping is not strength: kept
}

double DruckerPrager::yield_function(const Sym& s) const {
  const double i1 = trace(s);
  return sqrt_j2(s, i1 / 3.0) + c_.alpha * i1 - c_.k;
}

DruckerPrager::Result DruckerPrager::integrate(const Sym& stress, const Sym& de) const {
  const double G = elastic_.shear(), K = elastic_.bulk();
  const Sym trial = elastic_trial(stress, de, elastic_.lambda(), 2.0 * G);
  const double i1 = trace(trial), mean = i1 / 3.0;
  const double q = sqrt_j2(trial, mean);
  const double f = q + c_.alpha * i1 - c_.k;
  const bool tension = mean > p_.tension && (p_.friction > 0.0 || p_.tension > 0.0);
  if (f <= 0.0 && !tension) return {trial, 0.0, false};

  Sym dev = trial;
  dev[0] -= mean, dev[1] -= mean, dev[2] -= mean;
  double new_q = q, new_mean = mean;
  if (f > 0.0) {
    // Return to the cone: sqrt(J2) and I1 shrink together; dl from f(sigma) = 0.
    const double dl = f / (G + 9.0 * K * c_.alpha * c_.beta);
    new_q = q - G * dl;
    new_mean = mean - 3.0 * K * c_.beta * dl;
    if (new_q < 0.0) {  // beyond the apex: the apex itself
      new_q = 0.0;
      new_mean = c_.alpha > 0.0 ? c_.k / (3.0 * c_.alpha) : mean;
    }
  }
  if (new_mean > p_.tension && c_.alpha > 0.0) {
    // Tension cut-off on the mean stress; the shear stays within the cone there.
    new_mean = p_.tension;
    new_q = std::min(new_q, std::max(0.0, c_.k - 3.0 * c_.alpha * new_mean));
  }
  Sym s = q > 0.0 ? Sym(dev * (new_q / q)) : Sym(Sym::Zero());
  s[0] += new_mean, s[1] += new_mean, s[2] += new_mean;
  // Plastic shear strain from the deviatoric stress removed: dgamma = (q - q_new) / G, as sqrt(2/3 e:e).
  const double shear = (q - new_q) / G / std::sqrt(3.0);
  return {s, shear, true};
}

void DruckerPrager::update_stress(const StressUpdate& b) const {
#pragma omp parallel for schedule(static)
  for (int k = 0; k < b.count; ++k) {
    const int p = b.index[k];
    const Result r = integrate(b.stress[p], b.strain_increment[p]);
    b.stress[p] = r.stress;
    b.plastic_strain[p] += r.shear_increment;
    b.yield[p] = r.plastic;
  }
}

}  // namespace seismpm
