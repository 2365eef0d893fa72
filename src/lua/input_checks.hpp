// Values that are legal but most likely a mistake (a unit weight typed as a density, a friction angle
// in radians, --set of a name the script never reads): a warning naming the script line, the value and
// the probable slip, printed to stderr and kept in Session::warnings. The run goes on, since each can be
// meant (a light foam, phi = 0.5 degree).
#pragma once

#include <string>

struct lua_State;

namespace seismpm::lua {

// "seismpm: warning: script.lua:12: <what>" on stderr, the line being the Lua code that called the
// running function.
void warn(lua_State* L, const std::string& what);

// A soil or rock's density (kg/m3), Young's modulus (Pa) and friction angle (degrees), checked for
// the slips above; `material` names it in the warning ("mohr_coulomb").
void check_plausible_density(lua_State* L, const char* material, double density);
void check_plausible_young(lua_State* L, const char* material, double young);
void check_plausible_friction(lua_State* L, const char* material, const char* key, double degrees);

// After a script: each --set name it never read through mpm.param, with the closest name it did read.
void warn_unread_params(lua_State* L);

}  // namespace seismpm::lua
