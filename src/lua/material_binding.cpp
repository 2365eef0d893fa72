// mpm.material.*: constitutive models. Soil models plug in here the same way.
#include <sstream>

#include "binding.hpp"
#include "core/error.hpp"
#include "materials/linear_elastic.hpp"
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

}  // namespace

void open_material(lua_State* L, int mpm) {
  new_type<MaterialObject>(L, kMaterialType);
  set_function<material_kind>(L, -1, "kind", "material:kind");
  lua_pop(L, 1);
  luaL_getmetatable(L, kMaterialType);
  set_function<material_tostring>(L, -1, "__tostring", "material:__tostring");
  lua_pop(L, 1);
  lua_newtable(L);
  set_function<linear_elastic>(L, -1, "linear_elastic", "mpm.material.linear_elastic");
  lua_setfield(L, mpm, "material");
}

}  // namespace seismpm::lua
