// mpm.material.*: constitutive models. Soil models plug in here the same way. The materials check
// their own parameters (ranges and how they depend on each other); the binding reads and forwards.
#include <sstream>

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

// Shown in outputs beside the material index particles carry.
const Key kName =
    arg::string("name", "a label for outputs: the .vtu files' material_names, m:materials()").shown("its kind");

const Key kLinearElasticKeys[] = {kDensity, kYoung, kPoisson, kName};
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

// The material object, its summary led by its name when it has one.
int push_material(lua_State* L, const Args& a, std::shared_ptr<const Material> material, const std::string& summary) {
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
};

}  // namespace

std::span<const Function> material_functions() { return kMaterial; }

void open_material(lua_State* L) { open_type<MaterialObject, material_tostring>(L, kMaterial); }

}  // namespace seismpm::lua
