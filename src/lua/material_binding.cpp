// mpm.material.*: constitutive models. Soil models plug in here the same way. The materials check
// their own parameters (ranges and how they depend on each other); the binding reads and forwards.
#include <cmath>
#include <optional>
#include <sstream>
#include <utility>

#include "api_docs.hpp"
#include "binding.hpp"
#include "input_checks.hpp"
#include "materials/drucker_prager.hpp"
#include "materials/linear_elastic.hpp"
#include "materials/mohr_coulomb.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

const Key kDensity = arg::number("density", "kg/m3", "mass density").checked_by_kernel(kDensityRange).required();
const Key kYoung = arg::number("young", "Pa", "Young's modulus").checked_by_kernel(kYoungRange).required();
const Key kPoisson = arg::number("poisson", "", "Poisson's ratio").checked_by_kernel(kPoissonRange).required();
const Key kCohesion = arg::number("cohesion", "Pa", "cohesion c").checked_by_kernel(kCohesionRange).def(0);
const Key kFriction = arg::number("friction", "degrees", "friction angle phi (not both c and phi zero)")
                          .checked_by_kernel(kFrictionRange)
                          .required();
const Key kDilation = arg::number("dilation", "degrees", "dilation angle psi (0: no volume change in plastic flow)")
                          .in_text("in [0, friction]")
                          .def(0);

// Rayleigh damping, either form: a ratio at two frequencies, or the coefficients themselves.
const Key kRayleighKeys[] = {
    arg::number("ratio", "", "critical-damping ratio at both frequencies (0.02-0.05 for soil)")
        .in(kRayleighRatioRange)
        .shown("with frequencies"),
    arg::custom("frequencies", "{f1, f2} with 0 < f1 < f2", "Hz",
                "where the ratio holds (bracket the site's f1 = Vs / 4H and the motion's main frequency); "
                "between them the damping is lower, outside higher")
        .shown("with ratio"),
    arg::number("alpha", "1/s", "mass-proportional coefficient (instead of ratio)").in(kRayleighAlphaRange).def(0),
    arg::number("beta", "s", "stiffness-proportional coefficient (instead of ratio)").in(kRayleighBetaRange).def(0),
};
const Key kRayleigh = arg::table("rayleigh", kRayleighKeys,
                                 "Rayleigh damping C = alpha M + beta K, xi(w) = alpha / 2w + beta w / 2: "
                                 "{ ratio =, frequencies = {f1, f2} } or { alpha =, beta = } (none when absent)");

// Shown in outputs beside the material index particles carry.
const Key kName =
    arg::string("name", "a label for outputs: the .vtu files' material_names, m:materials()").shown("its kind");

const Key kLinearElasticKeys[] = {kDensity, kYoung, kPoisson, kRayleigh, kName};
const Key kSofteningKeys[] = {
    arg::number("cohesion", "Pa", "residual cohesion").in_text("in [0, cohesion]").shown("cohesion (not softened)"),
    arg::number("friction", "degrees", "residual friction angle")
        .in_text("in [0, friction]")
        .shown("friction (not softened)"),
    arg::number("strain", "", "accumulated plastic shear strain at which the residual values are reached")
        .in(above(0))
        .required(),
};
const Key kMohrCoulombKeys[] = {
    kDensity,
    kYoung,
    kPoisson,
    kCohesion,
    kFriction,
    kDilation,
    arg::number("tension", "Pa", "tensile strength (0: none)").in_text("in [0, c cot(phi)]").def(0),
    arg::table("softening", kSofteningKeys, "linear softening of c and phi with accumulated plastic shear strain"),
    kRayleigh,
    kName,
};
const Key kDruckerPragerKeys[] = {
    kDensity,
    kYoung,
    kPoisson,
    kCohesion,
    kFriction,
    kDilation,
    arg::number("tension", "Pa", "limit of the mean stress (0: no tension)").in_text("in [0, the cone's apex]").def(0),
    arg::choice("fit", "plane_strain|outer|inner", "plane_strain",
                "how the cone fits Mohr-Coulomb: the same plane-strain limit load, or through its compression "
                "(outer) or extension (inner) corners"),
    kRayleigh,
    kName,
};

int material_tostring(lua_State* L) {
  lua_pushstring(L, self<MaterialObject>(L).summary.c_str());
  return 1;
}

int material_kind(lua_State* L) {
  lua_pushstring(L, std::string(self<MaterialObject>(L).material->kind()).c_str());
  return 1;
}

int material_rayleigh(lua_State* L) {
  const Rayleigh& r = self<MaterialObject>(L).material->rayleigh();
  lua_createtable(L, 0, 2);
  lua_pushnumber(L, r.alpha);
  lua_setfield(L, -2, "alpha");
  lua_pushnumber(L, r.beta);
  lua_setfield(L, -2, "beta");
  return 1;
}

template <class P>
void read_elastic(lua_State* L, const char* kind, const Args& a, P& p) {
  p.density = a.number("density");
  p.young = a.number("young");
  p.poisson = a.number("poisson");
  check_plausible_density(L, kind, p.density);
  check_plausible_young(L, kind, p.young);
}

void read_strength(lua_State* L, const char* kind, const Args& a, StrengthParameters& s) {
  s.cohesion = a.number("cohesion");
  s.friction = a.number("friction");
  s.dilation = a.number("dilation");
  s.tension = a.number("tension");
  check_plausible_friction(L, kind, "friction", s.friction);
  check_plausible_friction(L, kind, "dilation", s.dilation);
}

// {f1, f2} of the rayleigh table: two numbers, 0 < f1 < f2.
std::pair<double, double> read_frequencies(const Args& r) {
  lua_State* L = r.state();
  const std::string what = "key 'rayleigh': key 'frequencies' must be {f1, f2} with 0 < f1 < f2 (Hz)";
  const int t = r.push("frequencies");
  double f[2] = {0.0, 0.0};
  bool ok = t == LUA_TTABLE && lua_rawlen(L, -1) == 2;
  for (int k = 0; ok && k < 2; ++k) {
    ok = lua_rawgeti(L, -1, k + 1) == LUA_TNUMBER;
    f[k] = ok ? lua_tonumber(L, -1) : 0.0;
    lua_pop(L, 1);
  }
  const std::string got = ok ? "{" + number_text(f[0]) + ", " + number_text(f[1]) + "}" : type_name(L, -1);
  lua_pop(L, 1);
  if (!ok || !(f[0] > 0.0 && f[0] < f[1] && std::isfinite(f[1]))) throw Error(what + ", got " + got);
  return {f[0], f[1]};
}

// The rayleigh key, when given: the coefficients, and how they were given for the summary.
std::optional<std::pair<Rayleigh, std::string>> read_rayleigh(const Args& a) {
  if (!a.has("rayleigh")) return std::nullopt;
  const Args r = a.table("rayleigh");
  const bool by_ratio = r.has("ratio") || r.has("frequencies");
  const bool by_coefficients = r.has("alpha") || r.has("beta");
  if (by_ratio == by_coefficients)
    throw Error("key 'rayleigh': give either ratio and frequencies = {f1, f2}, or alpha and/or beta");
  std::ostringstream os;
  try {
    if (by_coefficients) return std::pair{Rayleigh::coefficients(r.number("alpha"), r.number("beta")), std::string()};
    if (!r.has("ratio")) throw Error("key 'rayleigh': missing key 'ratio' (with frequencies)");
    if (!r.has("frequencies")) throw Error("key 'rayleigh': missing key 'frequencies' = {f1, f2} (with ratio)");
    const auto [f1, f2] = read_frequencies(r);
    const double ratio = r.number("ratio");
    os << " (ratio " << ratio << " at " << f1 << " and " << f2 << " Hz)";
    return std::pair{Rayleigh::from_ratio(ratio, f1, f2), os.str()};
  } catch (const ParameterError& e) {
    throw Error("key 'rayleigh': key " + std::string(e.what()));
  }
}

// The material object, its summary led by its name when it has one and ended by its damping.
int push_material(lua_State* L, const Args& a, std::shared_ptr<Material> material, std::string summary) {
  if (const auto rayleigh = read_rayleigh(a)) {
    material->set_rayleigh(rayleigh->first);
    std::ostringstream os;
    os << ", Rayleigh alpha " << rayleigh->first.alpha << " 1/s, beta " << rayleigh->first.beta << " s"
       << rayleigh->second;
    summary += os.str();
  }
  const std::string name = a.string("name", "");
  push_object(L, MaterialObject{std::move(material), name.empty() ? summary : "'" + name + "' " + summary, name});
  return 1;
}

int linear_elastic(lua_State* L) {
  const Args a(L, 1, kLinearElasticKeys);
  const double density = a.number("density"), young = a.number("young"), poisson = a.number("poisson");
  check_plausible_density(L, "linear_elastic", density);
  check_plausible_young(L, "linear_elastic", young);
  auto material = std::make_shared<LinearElastic>(density, young, poisson);
  std::ostringstream os;
  os << "linear_elastic: density " << density << " kg/m3, E " << young << " Pa, nu " << poisson;
  return push_material(L, a, std::move(material), os.str());
}

int mohr_coulomb(lua_State* L) {
  const Args a(L, 1, kMohrCoulombKeys);
  MohrCoulombParameters p;
  read_elastic(L, "mohr_coulomb", a, p);
  read_strength(L, "mohr_coulomb", a, p);
  if (a.has("softening")) {
    const Args soft = a.table("softening");
    p.softening = true;
    p.residual_cohesion = soft.number("cohesion", p.cohesion);
    p.residual_friction = soft.number("friction", p.friction);
    p.softening_strain = soft.number("strain");
  }
  auto material = std::make_shared<MohrCoulomb>(p);
  std::ostringstream os;
  os << "mohr_coulomb: density " << p.density << " kg/m3, E " << p.young << " Pa, nu " << p.poisson << ", c "
     << p.cohesion << " Pa, phi " << p.friction << ", psi " << p.dilation << ", tension " << p.tension << " Pa";
  if (p.softening)
    os << ", softening to c " << p.residual_cohesion << " Pa, phi " << p.residual_friction << " at plastic strain "
       << p.softening_strain;
  return push_material(L, a, std::move(material), os.str());
}

int drucker_prager(lua_State* L) {
  const Args a(L, 1, kDruckerPragerKeys);
  DruckerPragerParameters p;
  read_elastic(L, "drucker_prager", a, p);
  read_strength(L, "drucker_prager", a, p);
  const std::string fit = a.choice("fit");
  p.fit = parse_fit(fit);
  auto material = std::make_shared<DruckerPrager>(p);
  std::ostringstream os;
  os << "drucker_prager (" << fit << " fit): density " << p.density << " kg/m3, E " << p.young << " Pa, nu "
     << p.poisson << ", c " << p.cohesion << " Pa, phi " << p.friction << ", psi " << p.dilation;
  return push_material(L, a, std::move(material), os.str());
}

const Function kMaterial[] = {
    {"mpm.material.linear_elastic", &guarded<linear_elastic>, nullptr, kLinearElasticKeys,
     "Isotropic linear elasticity (plane strain keeps sigma_zz).",
     "local rock = mpm.material.linear_elastic{ density = 2550, young = 5e8, poisson = 0.19 }"},
    {"mpm.material.mohr_coulomb", &guarded<mohr_coulomb>, nullptr, kMohrCoulombKeys,
     "Elastic-perfectly plastic Mohr-Coulomb, non-associated, with a tension cut-off. softening = { cohesion =, "
     "friction =, strain = } softens c and phi linearly to these residual values at that accumulated plastic shear "
     "strain. Particle fields plastic_strain and yield show the state.",
     "local soil = mpm.material.mohr_coulomb{ density = 1680, young = 2.57e6, poisson = 0.33, cohesion = 780, "
     "friction = 23, dilation = 0, tension = 0 }"},
    {"mpm.material.drucker_prager", &guarded<drucker_prager>, nullptr, kDruckerPragerKeys,
     "Drucker-Prager fitted to Mohr-Coulomb's c, phi, psi, with a tension cut-off on the mean stress.",
     "local sand = mpm.material.drucker_prager{ density = 2650, young = 8.4e5, poisson = 0.3, friction = 19.8, "
     "fit = \"plane_strain\" }"},
    {"material:kind",
     &guarded<material_kind>,
     "mat:kind()",
     {},
     "The constitutive model's name.",
     "print(rock:kind())"},
    {"material:rayleigh",
     &guarded<material_rayleigh>,
     "mat:rayleigh()",
     {},
     "Its Rayleigh damping coefficients { alpha = (1/s), beta = (s) }; both 0 without damping.",
     "local r = soil:rayleigh(); print(r.alpha, r.beta)"},
};

}  // namespace

std::span<const Function> material_functions() { return kMaterial; }

void open_material(lua_State* L) { open_type<MaterialObject, material_tostring>(L, kMaterial); }

}  // namespace seismpm::lua
