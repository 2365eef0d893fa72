// Methods of a probe: get (the current value of a field), series (its recorded history), name.
#include <sstream>

#include "binding.hpp"
#include "core/particle_fields.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

ProbeObject& self(lua_State* L) { return check_object<ProbeObject>(L, 1, kProbeType, "self"); }

int probe_tostring(lua_State* L) {
  const auto& p = self(L);
  std::ostringstream os;
  os << "probe '" << p.probe->name() << "': particle " << p.probe->particle_id() << ", " << p.probe->samples()
     << " samples every " << p.handle->simulation.probe_every(*p.probe) << " s";
  lua_pushstring(L, os.str().c_str());
  return 1;
}

int probe_name(lua_State* L) {
  lua_pushstring(L, std::string(self(L).probe->name()).c_str());
  return 1;
}

int probe_get(lua_State* L) {
  const auto& p = self(L);
  const Field f = field_argument(L, 2);
  const auto& m = p.handle->model;
  lua_pushnumber(L, field_value(m.particles(), m.index_of(p.probe->particle_id()), f));
  return 1;
}

// Returns two arrays: times and values.
int probe_series(lua_State* L) {
  const auto& p = self(L);
  const Field f = field_argument(L, 2);
  const auto& t = p.probe->times();
  const auto v = p.probe->series(f);
  for (const auto* column : {&t, &v}) {
    lua_createtable(L, static_cast<int>(column->size()), 0);
    for (std::size_t k = 0; k < column->size(); ++k) {
      lua_pushnumber(L, (*column)[k]);
      lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
    }
  }
  return 2;
}

}  // namespace

void open_probe(lua_State* L) {
  new_type<ProbeObject, probe_tostring>(L, kProbeType);
  set_function<probe_name>(L, -1, "name", "probe:name");
  set_function<probe_get>(L, -1, "get", "probe:get");
  set_function<probe_series>(L, -1, "series", "probe:series");
  lua_pop(L, 1);
}

}  // namespace seismpm::lua
