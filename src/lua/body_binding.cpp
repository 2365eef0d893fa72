// Methods of a body: count, centroid, field, name, set_velocity, and reaction for rigid bodies.
#include <sstream>

#include "binding.hpp"
#include "core/particle_fields.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

BodyObject& self(lua_State* L) { return check_object<BodyObject>(L, 1, kBodyType, "self"); }

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
  const auto& b = self(L);
  std::ostringstream os;
  const auto& body = b.handle->model.bodies()[b.body];
  os << (body.rigid ? "rigid body '" : "body '") << body.name << "': " << particles_of(b).size() << " particles";
  lua_pushstring(L, os.str().c_str());
  return 1;
}

int body_name(lua_State* L) {
  const auto& b = self(L);
  lua_pushstring(L, b.handle->model.bodies()[b.body].name.c_str());
  return 1;
}

int body_count(lua_State* L) {
  lua_pushinteger(L, static_cast<lua_Integer>(particles_of(self(L)).size()));
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
  const auto& b = self(L);
  return push_point(L, b.handle->model.centroid(b.body));
}

int body_field(lua_State* L) {
  const auto& b = self(L);
  const Field f = field_argument(L, 2);
  const auto list = particles_of(b);
  lua_createtable(L, static_cast<int>(list.size()), 0);
  for (std::size_t k = 0; k < list.size(); ++k) {
    lua_pushnumber(L, field_value(b.handle->model.particles(), list[k], f));
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
  return 1;
}

// body:set_velocity{vx, vy} or body:set_velocity(function(x, y) return vx, vy end); for a rigid
// body {vx, vy} with numbers or histories replaces the velocity it follows.
int body_set_velocity(lua_State* L) {
  auto& b = self(L);
  if (b.handle->model.bodies()[b.body].rigid) {
    b.handle->model.set_rigid_velocity(b.body, rigid_velocity(L, 2, "the velocity"));
    return 0;
  }
  auto& p = b.handle->model.particles();
  const auto list = particles_of(b);
  if (lua_isfunction(L, 2)) {
    for (std::size_t k : list) {
      lua_pushvalue(L, 2);
      lua_pushnumber(L, p.x[k][0]);
      lua_pushnumber(L, p.x[k][1]);
      if (lua_pcall(L, 2, 2, 0) != LUA_OK) {
        std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "error";
        lua_pop(L, 1);
        throw Error("the velocity function failed: " + msg);
      }
      if (!lua_isnumber(L, -2) || !lua_isnumber(L, -1))
        throw Error("the velocity function must return two numbers vx, vy");
      p.v[k] = Vec<2>(lua_tonumber(L, -2), lua_tonumber(L, -1));
      lua_pop(L, 2);
      if (!p.v[k].allFinite()) throw Error("the velocity function returned a non-finite value");
    }
  } else {
    const Vec<2> v = to_point(L, 2, "the velocity");
    for (std::size_t k : list) p.v[k] = v;
  }
  return 0;
}

// rigid:reaction() -> {fx, fy}: the force the rigid body exerted on the deformable bodies in the last step.
int body_reaction(lua_State* L) {
  const auto& b = self(L);
  const auto& body = b.handle->model.bodies()[b.body];
  if (!body.rigid) throw Error("body '" + body.name + "' is not rigid: only rigid bodies (m:rigid) report a reaction");
  return push_point(L, b.handle->model.rigid_motion(b.body).force);
}

}  // namespace

void open_body(lua_State* L) {
  new_type<BodyObject, body_tostring>(L, kBodyType);
  set_function<body_name>(L, -1, "name", "body:name");
  set_function<body_count>(L, -1, "count", "body:count");
  set_function<body_centroid>(L, -1, "centroid", "body:centroid");
  set_function<body_field>(L, -1, "field", "body:field");
  set_function<body_set_velocity>(L, -1, "set_velocity", "body:set_velocity");
  set_function<body_reaction>(L, -1, "reaction", "body:reaction");
  lua_pop(L, 1);
}

}  // namespace seismpm::lua
