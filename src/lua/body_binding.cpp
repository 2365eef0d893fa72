// Methods of a body: count, centroid, field, name, set_velocity, and reaction for rigid bodies.
#include <sstream>

#include "api_docs.hpp"
#include "binding.hpp"
#include "core/particle_fields.hpp"
#include "lua_function.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

// Indices of the body's particles in creation (id) order.
std::vector<std::size_t> particles_of(const BodyObject& b) {
  const auto& m = b.handle->model;
  std::vector<std::size_t> out;
  for (std::size_t id = 0; id < m.particles().size(); ++id) {
    const std::size_t p = m.index_of(static_cast<int>(id));
    if (m.particles().body[p] == b.body) out.push_back(p);
  }
  return out;
}

int body_tostring(lua_State* L) {
  const auto& b = self<BodyObject>(L);
  std::ostringstream os;
  const auto& body = b.handle->model.bodies()[b.body];
  os << (body.rigid ? "rigid body '" : "body '") << body.name << "': " << particles_of(b).size() << " particles";
  lua_pushstring(L, os.str().c_str());
  return 1;
}

int body_name(lua_State* L) {
  const auto& b = self<BodyObject>(L);
  lua_pushstring(L, b.handle->model.bodies()[b.body].name.c_str());
  return 1;
}

int body_count(lua_State* L) {
  lua_pushinteger(L, static_cast<lua_Integer>(particles_of(self<BodyObject>(L)).size()));
  return 1;
}

// {x, y} as a Lua array.
int push_point(lua_State* L, const Vec<2>& p) {
  lua_createtable(L, 2, 0);
  lua_pushnumber(L, p[0]);
  lua_rawseti(L, -2, 1);
  lua_pushnumber(L, p[1]);
  lua_rawseti(L, -2, 2);
  return 1;
}

int body_centroid(lua_State* L) {
  const auto& b = self<BodyObject>(L);
  return push_point(L, b.handle->model.centroid(b.body));
}

int body_field(lua_State* L) {
  const auto& b = self<BodyObject>(L);
  const Field f = field_argument(L, 2);
  const auto list = particles_of(b);
  lua_createtable(L, static_cast<int>(list.size()), 0);
  for (std::size_t k = 0; k < list.size(); ++k) {
    lua_pushnumber(L, field_value(b.handle->model.particles(), list[k], f));
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
  return 1;
}

// Sets each particle's velocity from function(x, y) return vx, vy end at stack index 2 (protected call).
void set_velocity_from_function(lua_State* L, Particles<2>& p, const std::vector<std::size_t>& list) {
  const EvaluationScope scope(L);  // the function may not change the particles under this loop
  for (std::size_t k : list) {
    lua_pushvalue(L, 2);
    lua_pushnumber(L, p.x[k][0]);
    lua_pushnumber(L, p.x[k][1]);
    if (lua_pcall(L, 2, 2, 0) != LUA_OK) {
      std::string msg = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "an error object that is not a string";
      lua_pop(L, 1);
      throw Error("the velocity function failed: " + msg);
    }
    const bool numbers = lua_type(L, -2) == LUA_TNUMBER && lua_type(L, -1) == LUA_TNUMBER;
    const Vec<2> v = numbers ? Vec<2>(lua_tonumber(L, -2), lua_tonumber(L, -1)) : Vec<2>::Zero();
    lua_pop(L, 2);
    if (!numbers) throw Error("the velocity function must return two numbers vx, vy");
    if (!v.allFinite()) throw Error("the velocity function returned a non-finite value");
    p.v[k] = v;
  }
}

// body:set_velocity{vx, vy} or body:set_velocity(function(x, y) return vx, vy end); for a rigid
// body {vx, vy} with numbers or histories replaces the velocity it follows.
int body_set_velocity(lua_State* L) {
  const BodyObject b = self<BodyObject>(L);  // a copy: the velocity function may destroy the userdata
  refuse_inside_a_step(L, "set velocities");
  if (b.handle->model.bodies()[b.body].rigid) {
    b.handle->model.set_rigid_velocity(b.body, rigid_velocity(L, 2, "the velocity"));
    return 0;
  }
  auto& p = b.handle->model.particles();
  const auto list = particles_of(b);
  if (lua_isfunction(L, 2)) {
    set_velocity_from_function(L, p, list);
  } else {
    const Vec<2> v = to_point(L, 2, "the velocity");
    for (std::size_t k : list) p.v[k] = v;
  }
  return 0;
}

// rigid:reaction() -> {fx, fy}: the force the rigid body exerted on the deformable bodies in the last step.
int body_reaction(lua_State* L) {
  const auto& b = self<BodyObject>(L);
  const auto& body = b.handle->model.bodies()[b.body];
  if (!body.rigid) throw Error("body '" + body.name + "' is not rigid: only rigid bodies (m:rigid) report a reaction");
  return push_point(L, b.handle->model.rigid_motion(b.body).force);
}

const Function kBody[] = {
    {"body:name", &guarded<body_name>, "b:name()", {}, "The body's name.", "print(soil:name())"},
    {"body:count", &guarded<body_count>, "b:count()", {}, "Number of particles of the body.", "print(soil:count())"},
    {"body:centroid",
     &guarded<body_centroid>,
     "b:centroid()",
     {},
     "Mass centre {x, y} (m).",
     "local c = soil:centroid(); print(c[1], c[2])"},
    {"body:field",
     &guarded<body_field>,
     "b:field(name)",
     {},
     "A particle field as a Lua array in particle creation order. Fields: id body material mass volume density x y "
     "ux uy vx vy sxx syy szz sxy pressure q shear_strain plastic_strain yield (SI units, stress tension-positive, "
     "pressure compression-positive; units and meanings under Particle fields).",
     "local uy = soil:field(\"uy\"); print(#uy, uy[1])"},
    {"body:set_velocity",
     &guarded<body_set_velocity>,
     "b:set_velocity{vx, vy} | b:set_velocity(function(x, y) return vx, vy end)",
     {},
     "Sets the particles' velocity (m/s), uniform or as a function of position (which may read models, not "
     "change one). For a rigid body: {vx, vy} with numbers or histories replaces the velocity it follows from the "
     "next step on.",
     "bar:set_velocity(function(x, y) return 0.1 * math.sin(math.pi * x / 50), 0 end)"},
    {"body:reaction",
     &guarded<body_reaction>,
     "r:reaction()",
     {},
     "For a rigid body: the force {fx, fy} it exerted on the deformable bodies in the last step (N per metre out "
     "of plane; a base carrying soil reads its weight, upward). The output directory's reactions.csv holds its "
     "mean over each output interval.",
     "local f = base:reaction(); print(f[1], f[2])"},
};

}  // namespace

std::span<const Function> body_functions() { return kBody; }

void open_body(lua_State* L) { open_type<BodyObject, body_tostring>(L, kBody); }

}  // namespace seismpm::lua
