// Methods of a probe: get (the current value of a field), series (its recorded history), name.
#include <optional>
#include <sstream>

#include "api_docs.hpp"
#include "binding.hpp"
#include "core/particle_fields.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

int probe_tostring(lua_State* L) {
  const auto& p = self<ProbeObject>(L);
  std::ostringstream os;
  os << "probe '" << p.probe->name() << "': particle " << p.probe->particle_id();
  if (p.probe->relative_to().active()) os << " relative to " << p.probe->relative_to().what;
  os << ", " << p.probe->samples() << " samples every " << p.handle->simulation.probe_every(*p.probe) << " s";
  lua_pushstring(L, os.str().c_str());
  return 1;
}

int probe_name(lua_State* L) {
  lua_pushstring(L, std::string(self<ProbeObject>(L).probe->name()).c_str());
  return 1;
}

// The component of a relative field name at `index` ("ux_rel" -> 0), none for any other value.
std::optional<int> relative_argument(lua_State* L, int index) {
  if (lua_type(L, index) != LUA_TSTRING) return std::nullopt;
  return parse_relative_field(lua_tostring(L, index), 2);
}

int probe_get(lua_State* L) {
  const auto& p = self<ProbeObject>(L);
  const auto& m = p.handle->model;
  if (const auto d = relative_argument(L, 2)) {
    lua_pushnumber(L, p.probe->relative_now(m, *d));
    return 1;
  }
  const Field f = field_argument(L, 2);
  lua_pushnumber(L, field_value(m.particles(), m.index_of(p.probe->particle_id()), f));
  return 1;
}

// Returns two arrays: times and values.
int probe_series(lua_State* L) {
  const auto& p = self<ProbeObject>(L);
  const auto relative = relative_argument(L, 2);
  const auto& t = p.probe->times();
  const auto v = relative ? p.probe->relative_series(*relative) : p.probe->series(field_argument(L, 2));
  for (const auto* column : {&t, &v}) {
    lua_createtable(L, static_cast<int>(column->size()), 0);
    for (std::size_t k = 0; k < column->size(); ++k) {
      lua_pushnumber(L, (*column)[k]);
      lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
    }
  }
  return 2;
}

const Function kProbe[] = {
    {"probe:name", &guarded<probe_name>, "p:name()", {}, "The probe's name.", "print(p1:name())"},
    {"probe:get",
     &guarded<probe_get>,
     "p:get(field)",
     {},
     "The current value of a field of the probe's particle; for a probe with relative_to, also ux_rel and uy_rel "
     "(its displacement less the reference's).",
     "print(p1:get(\"uy\"))"},
    {"probe:series",
     &guarded<probe_series>,
     "p:series(field)",
     {},
     "The recorded history: two arrays, times (s, model time) and values; fields as p:get takes them (ux_rel, "
     "uy_rel with relative_to).",
     "local t, uy = p1:series(\"uy\")"},
};

}  // namespace

std::span<const Function> probe_functions() { return kProbe; }

void open_probe(lua_State* L) { open_type<ProbeObject, probe_tostring>(L, kProbe); }

}  // namespace seismpm::lua
