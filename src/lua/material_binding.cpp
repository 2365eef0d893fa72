// mpm.material.*: constitutive models. Soil models plug in here the same way.
#include <cmath>
#include <sstream>

#include "binding.hpp"
#include "core/error.hpp"
#include "materials/drucker_prager.hpp"
#include "materials/linear_elastic.hpp"
#include "materials/mohr_coulomb.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

int material_tostring(lua_State* L) {
  lua_pushstring(L, check_object<MaterialObject>(L, 1, kMaterialType, "self").summary.c_str());
  return 1;
}

int material_kind(lua_State* L) {
  lua_pushstring(L, std::string(check_object<MaterialObject>(L, 1, kMaterialType, "self").material->kind()).c_str());
  return 1;
}

int linear_elastic(lua_State* L) {
  Args a(L, 1, {"density", "young", "poisson"});
  const double density = Args::positive("density", a.number("density"), "kg/m^3");
  const double young = Args::positive("young", a.number("young"), "Pa");
  const double poisson = Args::in_range("poisson", a.number("poisson"), 0.0, 0.5, true);
  std::ostringstream os;
  os << "linear_elastic: density " << density << " kg/m3, E " << young << " Pa, nu " << poisson;
  push_object(L, kMaterialType, MaterialObject{std::make_shared<LinearElastic>(density, young, poisson), os.str()});
  return 1;
}

// Reads and range-checks the strength keys shared by the soil models.
template <class P>
void read_strength(Args& a, P& p) {
  p.density = Args::positive("density", a.number("density"), "kg/m^3");
  p.young = Args::positive("young", a.number("young"), "Pa");
  p.poisson = Args::in_range("poisson", a.number("poisson"), 0.0, 0.5, true);
  p.cohesion = Args::at_least("cohesion", a.number("cohesion", 0.0), 0.0, "Pa");
  p.friction = Args::in_range("friction", a.number("friction"), 0.0, 90.0, true, "degrees");
  p.dilation = Args::in_range("dilation", a.number("dilation", 0.0), 0.0, p.friction, false, "degrees, at most friction");
  p.tension = Args::at_least("tension", a.number("tension", 0.0), 0.0, "Pa");
  if (p.friction == 0.0 && p.cohesion == 0.0) throw Error("keys 'cohesion' and 'friction' cannot both be zero");
}

int mohr_coulomb(lua_State* L) {
  Args a(L, 1, {"density", "young", "poisson", "cohesion", "friction", "dilation", "tension", "softening"});
  MohrCoulombParameters p;
  read_strength(a, p);
  if (p.friction > 0.0) {
    const double apex = p.cohesion / std::tan(p.friction * 3.14159265358979323846 / 180.0);
    if (p.tension > apex * (1 + 1e-12))
      throw Error("key 'tension' must be in [0, c cot(phi) = " + std::to_string(apex) + "] (Pa), got " +
                  std::to_string(p.tension));
  }
  if (a.push("softening") != LUA_TNIL) {
    Args soft(L, -1, {"cohesion", "friction", "strain"});
    p.softening = true;
    p.residual_cohesion = Args::in_range("softening.cohesion", soft.number("cohesion", p.cohesion), 0.0, p.cohesion, false, "Pa");
    p.residual_friction =
        Args::in_range("softening.friction", soft.number("friction", p.friction), 0.0, p.friction, false, "degrees");
    p.softening_strain = Args::positive("softening.strain", soft.number("strain"));
  }
  lua_pop(L, 1);
  std::ostringstream os;
  os << "mohr_coulomb: density " << p.density << " kg/m3, E " << p.young << " Pa, nu " << p.poisson << ", c "
     << p.cohesion << " Pa, phi " << p.friction << ", psi " << p.dilation << ", tension " << p.tension << " Pa";
  if (p.softening)
    os << ", softening to c " << p.residual_cohesion << " Pa, phi " << p.residual_friction << " at plastic strain "
       << p.softening_strain;
  push_object(L, kMaterialType, MaterialObject{std::make_shared<MohrCoulomb>(p), os.str()});
  return 1;
}

int drucker_prager(lua_State* L) {
  Args a(L, 1, {"density", "young", "poisson", "cohesion", "friction", "dilation", "tension", "fit"});
  DruckerPragerParameters p;
  read_strength(a, p);
  const std::string fit = a.choice("fit", {"plane_strain", "outer", "inner"}, "plane_strain");
  p.fit = parse_fit(fit);
  std::ostringstream os;
  os << "drucker_prager (" << fit << " fit): density " << p.density << " kg/m3, E " << p.young << " Pa, nu "
     << p.poisson << ", c " << p.cohesion << " Pa, phi " << p.friction << ", psi " << p.dilation;
  push_object(L, kMaterialType, MaterialObject{std::make_shared<DruckerPrager>(p), os.str()});
  return 1;
}

}  // namespace

void open_material(lua_State* L, int mpm) {
  new_type<MaterialObject, material_tostring>(L, kMaterialType);
  set_function<material_kind>(L, -1, "kind", "material:kind");
  lua_pop(L, 1);
  lua_newtable(L);
  set_function<linear_elastic>(L, -1, "linear_elastic", "mpm.material.linear_elastic");
  set_function<mohr_coulomb>(L, -1, "mohr_coulomb", "mpm.material.mohr_coulomb");
  set_function<drucker_prager>(L, -1, "drucker_prager", "mpm.material.drucker_prager");
  lua_setfield(L, mpm, "material");
}

}  // namespace seismpm::lua
