#include "input_checks.hpp"

#include <lua.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/format.hpp"
#include "session.hpp"

namespace seismpm::lua {

namespace {

// Edits (insert, delete, replace) between two names: a typo is one or two.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace

void warn(lua_State* L, const std::string& what) {
  luaL_where(L, 1);
  std::string text = lua_tostring(L, -1);
  lua_pop(L, 1);
  text += what;
  std::fprintf(stderr, "seismpm: warning: %s\n", text.c_str());
  session(L).warnings.push_back(text);
}

void check_plausible_density(lua_State* L, const char* material, double density) {
  // Water is 1000 kg/m3 and dry soils 1200-2200; below 100 the number is most likely a unit weight.
  if (density > 0.0 && density < 100.0)
    warn(L, std::string(material) + ": density = " + format_number(density) +
                " kg/m3 is below 100: a unit weight in kN/m3? density is a mass per volume (a unit weight of " +
                format_number(density) + " kN/m3 is a density of " +
                format_number(std::round(density * 1000.0 / 9.81)) + " kg/m3)");
}

void check_plausible_young(lua_State* L, const char* material, double young) {
  // The softest soils modelled (loose sand, soft clay) are about 1 MPa; below 0.1 MPa, kPa or MPa typed?
  if (young > 0.0 && young < 1e5)
    warn(L, std::string(material) + ": young = " + format_number(young) +
                " Pa is below 0.1 MPa, softer than any soil: kPa or MPa typed? young is in Pa (e.g. 2.5e7 for 25 MPa)");
}

void check_plausible_friction(lua_State* L, const char* material, const char* key, double degrees) {
  // phi = 0 is a legitimate undrained (Tresca-like) soil; between 0 and 1 degree it is radians typed.
  if (degrees > 0.0 && degrees < 1.0)
    warn(L, std::string(material) + ": " + key + " = " + format_number(degrees) +
                " is below 1 degree: radians? angles are in degrees (" + format_number(degrees) +
                " rad = " + format_number(degrees * 180.0 / 3.14159265358979323846) + " degrees)");
}

void warn_unread_params(lua_State* L) {
  const Session& s = session(L);
  for (const auto& [name, value] : s.params) {
    if (s.params_read.count(name)) continue;
    std::string what = "--set " + name + "=" + value + " was never read by the script (mpm.param)";
    std::string closest;
    std::size_t best = 3;  // two edits at most
    for (const auto& read : s.params_read)
      if (const std::size_t d = edit_distance(name, read); d < best && d < std::min(name.size(), read.size()))
        best = d, closest = read;
    if (!closest.empty()) {
      what += ": did you mean '" + closest + "'?";
    } else if (!s.params_read.empty()) {
      what += "; it reads:";
      for (const auto& read : s.params_read) what += " " + read;
    } else {
      what += "; it reads no parameters";
    }
    std::fprintf(stderr, "seismpm: warning: %s\n", what.c_str());
    session(L).warnings.push_back(what);
  }
}

}  // namespace seismpm::lua
