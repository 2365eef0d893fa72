#include "binding.hpp"

#include <cmath>
#include <sstream>

namespace seismpm::lua {

namespace {
std::string format(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}
std::string unit_suffix(const char* unit) { return unit && *unit ? std::string(" (") + unit + ")" : ""; }
}  // namespace

void push_function(lua_State* L, lua_CFunction f, const char* name) {
  lua_pushstring(L, name);
  lua_pushcclosure(L, f, 1);
  // help() finds a function's name through this registry table.
  if (lua_getfield(L, LUA_REGISTRYINDEX, "seismpm.names") != LUA_TTABLE) {
    lua_pop(L, 1);
    lua_newtable(L);
    lua_pushvalue(L, -1);
    lua_setfield(L, LUA_REGISTRYINDEX, "seismpm.names");
  }
  lua_pushvalue(L, -2);
  lua_pushstring(L, name);
  lua_rawset(L, -3);
  lua_pop(L, 1);
}

std::string type_name(lua_State* L, int index) {
  if (luaL_getmetafield(L, index, "__name") == LUA_TSTRING) {
    std::string s = lua_tostring(L, -1);
    lua_pop(L, 1);
    return s;
  }
  return luaL_typename(L, index);
}

Args::Args(lua_State* L, int index, std::initializer_list<const char*> allowed, bool positional)
    : L_(L), index_(lua_absindex(L, index)) {
  if (!lua_istable(L, index_))
    throw Error("expects a table of named arguments { key = value, ... }, got " + type_name(L, index_));
  const lua_Integer n = positional ? luaL_len(L, index_) : 0;
  lua_pushnil(L_);
  while (lua_next(L_, index_) != 0) {
    lua_pop(L_, 1);  // value
    bool ok = false;
    std::string key;
    if (lua_type(L_, -1) == LUA_TSTRING) {
      key = lua_tostring(L_, -1);
      for (const char* a : allowed) ok = ok || key == a;
    } else if (lua_isinteger(L_, -1)) {
      const lua_Integer i = lua_tointeger(L_, -1);
      ok = i >= 1 && i <= n;
      key = "[" + std::to_string(i) + "]";
    } else {
      key = "[" + type_name(L_, -1) + "]";
    }
    if (!ok) {
      lua_pop(L_, 1);
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      if (positional) list += (list.empty() ? "" : ", ") + std::string("positional entries");
      throw Error("unknown key '" + key + "' (allowed: " + (list.empty() ? "none" : list) + ")");
    }
  }
}

bool Args::has(const char* key) {
  const bool present = lua_getfield(L_, index_, key) != LUA_TNIL;
  lua_pop(L_, 1);
  return present;
}

int Args::push(const char* key) { return lua_getfield(L_, index_, key); }

lua_Integer Args::length() const { return luaL_len(L_, index_); }

double Args::number_at(lua_Integer i) {
  lua_rawgeti(L_, index_, i);
  if (lua_type(L_, -1) != LUA_TNUMBER) {
    const std::string got = type_name(L_, -1);
    lua_pop(L_, 1);
    throw Error("entry " + std::to_string(i) + " must be a number, got " + got);
  }
  const double v = lua_tonumber(L_, -1);
  lua_pop(L_, 1);
  if (!std::isfinite(v)) throw Error("entry " + std::to_string(i) + " must be a finite number");
  return v;
}

Vec<2> Args::point_at(lua_Integer i, const std::string& what) {
  lua_rawgeti(L_, index_, i);
  try {
    const Vec<2> p = to_point(L_, -1, what);
    lua_pop(L_, 1);
    return p;
  } catch (...) {
    lua_pop(L_, 1);
    throw;
  }
}

std::optional<double> Args::optional_number(const char* key) {
  const int t = push(key);
  if (t == LUA_TNIL) {
    lua_pop(L_, 1);
    return std::nullopt;
  }
  if (t != LUA_TNUMBER) {
    const std::string got = type_name(L_, -1);
    lua_pop(L_, 1);
    throw Error(std::string("key '") + key + "' must be a number, got " + got);
  }
  const double v = lua_tonumber(L_, -1);
  lua_pop(L_, 1);
  if (!std::isfinite(v)) throw Error(std::string("key '") + key + "' must be a finite number, got " + format(v));
  return v;
}

double Args::number(const char* key) {
  if (auto v = optional_number(key)) return *v;
  throw Error(std::string("missing key '") + key + "'");
}

double Args::number(const char* key, double fallback) { return optional_number(key).value_or(fallback); }

int Args::integer(const char* key, int fallback) {
  const auto v = optional_number(key);
  if (!v) return fallback;
  if (*v != std::floor(*v) || std::abs(*v) > 1e9)
    throw Error(std::string("key '") + key + "' must be a whole number, got " + format(*v));
  return static_cast<int>(*v);
}

std::string Args::string(const char* key) {
  const int t = push(key);
  if (t != LUA_TSTRING) {
    const std::string got = type_name(L_, -1);
    lua_pop(L_, 1);
    if (t == LUA_TNIL) throw Error(std::string("missing key '") + key + "'");
    throw Error(std::string("key '") + key + "' must be a string, got " + got);
  }
  std::string s = lua_tostring(L_, -1);
  lua_pop(L_, 1);
  return s;
}

std::string Args::string(const char* key, const std::string& fallback) { return has(key) ? string(key) : fallback; }

std::string Args::choice(const char* key, const std::vector<std::string>& allowed, const std::string& fallback) {
  if (fallback.empty() && !has(key)) throw Error(std::string("missing key '") + key + "'");
  const std::string v = string(key, fallback);
  std::string list;
  for (const auto& a : allowed) {
    if (a == v) return v;
    list += (list.empty() ? "" : "|") + a;
  }
  throw Error(std::string("key '") + key + "' must be one of " + list + ", got '" + v + "'");
}

bool Args::boolean(const char* key, bool fallback) {
  const int t = push(key);
  bool v = fallback;
  if (t == LUA_TBOOLEAN) {
    v = lua_toboolean(L_, -1);
  } else if (t != LUA_TNIL) {
    const std::string got = type_name(L_, -1);
    lua_pop(L_, 1);
    throw Error(std::string("key '") + key + "' must be true or false, got " + got);
  }
  lua_pop(L_, 1);
  return v;
}

Vec<2> to_point(lua_State* L, int index, const std::string& what) {
  index = lua_absindex(L, index);
  if (!lua_istable(L, index)) throw Error(what + " must be a point {x, y}, got " + type_name(L, index));
  if (luaL_len(L, index) != 2) throw Error(what + " must be a point {x, y} with 2 numbers");
  Vec<2> p;
  for (int d = 0; d < 2; ++d) {
    lua_rawgeti(L, index, d + 1);
    if (!lua_isnumber(L, -1)) {
      lua_pop(L, 1);
      throw Error(what + " must be a point {x, y} of numbers");
    }
    p[d] = lua_tonumber(L, -1);
    lua_pop(L, 1);
    if (!std::isfinite(p[d])) throw Error(what + " has a non-finite coordinate");
  }
  return p;
}

Vec<2> Args::point(const char* key) {
  const int t = push(key);
  if (t == LUA_TNIL) {
    lua_pop(L_, 1);
    throw Error(std::string("missing key '") + key + "'");
  }
  try {
    const Vec<2> p = to_point(L_, -1, std::string("key '") + key + "'");
    lua_pop(L_, 1);
    return p;
  } catch (...) {
    lua_pop(L_, 1);
    throw;
  }
}

std::vector<Vec<2>> Args::points(const char* key) {
  const int top = lua_gettop(L_);
  const int t = push(key);
  std::vector<Vec<2>> out;
  try {
    if (t != LUA_TTABLE) throw Error(std::string("key '") + key + "' must be a list of points {{x, y}, ...}");
    const lua_Integer n = luaL_len(L_, -1);
    for (lua_Integer i = 1; i <= n; ++i) {
      lua_rawgeti(L_, -1, i);
      out.push_back(to_point(L_, -1, std::string("point ") + std::to_string(i) + " of '" + key + "'"));
      lua_pop(L_, 1);
    }
  } catch (...) {
    lua_settop(L_, top);
    throw;
  }
  lua_settop(L_, top);
  return out;
}

std::optional<std::vector<std::string>> Args::names(const char* key) {
  const int top = lua_gettop(L_);
  if (push(key) == LUA_TNIL) {
    lua_settop(L_, top);
    return std::nullopt;
  }
  std::vector<std::string> out;
  try {
    if (!lua_istable(L_, -1)) throw Error(std::string("key '") + key + "' must be a list of names such as {\"ux\", \"uy\"}");
    for (lua_Integer i = 1; i <= luaL_len(L_, -1); ++i) {
      lua_rawgeti(L_, -1, i);
      if (lua_type(L_, -1) != LUA_TSTRING)
        throw Error(std::string("key '") + key + "': entry " + std::to_string(i) + " must be a name");
      out.emplace_back(lua_tostring(L_, -1));
      lua_pop(L_, 1);
    }
    if (out.empty()) throw Error(std::string("key '") + key + "' is empty");
  } catch (...) {
    lua_settop(L_, top);
    throw;
  }
  lua_settop(L_, top);
  return out;
}

Field field_argument(lua_State* L, int index) {
  if (lua_type(L, index) != LUA_TSTRING) throw Error("expects a field name, one of: " + field_names(2));
  const char* name = lua_tostring(L, index);
  const auto f = parse_field(name, 2);
  if (!f) throw Error(std::string("unknown field '") + name + "' (fields: " + field_names(2) + ")");
  return *f;
}

double Args::positive(const char* key, double v, const char* unit) {
  if (!(v > 0.0)) throw Error(std::string("key '") + key + "' must be > 0" + unit_suffix(unit) + ", got " + format(v));
  return v;
}

double Args::at_least(const char* key, double v, double lo, const char* unit) {
  if (!(v >= lo))
    throw Error(std::string("key '") + key + "' must be >= " + format(lo) + unit_suffix(unit) + ", got " + format(v));
  return v;
}

double Args::in_range(const char* key, double v, double lo, double hi, bool hi_open, const char* unit) {
  if (!(v >= lo && (hi_open ? v < hi : v <= hi)))
    throw Error(std::string("key '") + key + "' must be in [" + format(lo) + ", " + format(hi) + (hi_open ? ")" : "]") +
                unit_suffix(unit) + ", got " + format(v));
  return v;
}

}  // namespace seismpm::lua
