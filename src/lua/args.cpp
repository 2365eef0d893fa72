#include "args.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "binding.hpp"

namespace seismpm::lua {

namespace {

std::string unit_suffix(const char* unit) { return unit && *unit ? std::string(" (") + unit + ")" : ""; }

std::string quoted(const char* key) { return std::string("key '") + key + "'"; }

// The entries of "a|b|c".
std::vector<std::string> split(const char* list) {
  std::vector<std::string> out(1);
  for (const char* c = list; c && *c; ++c) {
    if (*c == '|')
      out.emplace_back();
    else
      out.back() += *c;
  }
  return out;
}

// Pops the value on top after reading it with `read`, also when `read` throws.
template <class F>
auto read_top(lua_State* L, F&& read) {
  const int top = lua_gettop(L) - 1;
  try {
    auto v = read();
    lua_settop(L, top);
    return v;
  } catch (...) {
    lua_settop(L, top);
    throw;
  }
}

}  // namespace

Args::Args(lua_State* L, int index, std::span<const Key> keys, const char* within)
    : L_(L), index_(lua_absindex(L, index)), keys_(keys), within_(within) {
  // A call whose every key may be left out may leave out the table too: m:gravity_phase().
  const bool all_optional =
      std::none_of(keys_.begin(), keys_.end(), [](const Key& k) { return k.mandatory || k.type == Type::Positional; });
  if (all_optional && !within_ && lua_isnoneornil(L_, index_)) {
    if (lua_gettop(L_) < index_) lua_settop(L_, index_);
    lua_newtable(L_);
    lua_replace(L_, index_);
  }
  if (!lua_istable(L_, index_))
    throw Error(context() + "expects a table of named arguments { key = value, ... }, got " + type_name(L_, index_));
  std::vector<std::string> known;
  bool positional = false;
  for (const Key& k : keys_) {
    if (k.type == Type::Positional)
      positional = true;
    else
      known.emplace_back(k.name);
  }
  reject_unknown_keys(known, positional);
  for (const Key& k : keys_) check(k);
}

void Args::reject_unknown_keys(const std::vector<std::string>& known, bool positional) const {
  const lua_Integer n = positional ? static_cast<lua_Integer>(lua_rawlen(L_, index_)) : 0;
  lua_pushnil(L_);
  while (lua_next(L_, index_) != 0) {  // raw traversal
    lua_pop(L_, 1);                    // the value; the key stays for the next lua_next
    std::string key;
    bool ok = false;
    if (lua_type(L_, -1) == LUA_TSTRING) {  // never lua_tostring on a number key: it would change the key
      key = lua_tostring(L_, -1);
      for (const auto& k : known) ok = ok || key == k;
    } else if (lua_isinteger(L_, -1)) {
      const lua_Integer i = lua_tointeger(L_, -1);
      ok = i >= 1 && i <= n;
      key = "[" + std::to_string(i) + "]";
    } else {
      key = "[" + type_name(L_, -1) + "]";
    }
    if (ok) continue;
    lua_pop(L_, 1);
    std::string list;
    for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
    if (positional) list += (list.empty() ? "" : ", ") + std::string("positional entries");
    throw Error(context() + "unknown key '" + key + "' (allowed: " + (list.empty() ? "none" : list) + ")");
  }
}

std::string Args::context() const { return within_ ? quoted(within_) + ": " : std::string(); }

const Key& Args::spec(const char* key) const {
  for (const Key& k : keys_)
    if (std::string(k.name) == key) return k;
  throw std::logic_error(std::string("the binding reads key '") + key + "', which its key table does not describe");
}

void Args::check(const Key& k) const {
  if (k.type == Type::Positional || k.type == Type::Custom) {
    if (k.mandatory && !has(k.name)) throw Error(context() + "missing " + quoted(k.name));
    return;
  }
  if (k.type == Type::Object) {
    push(k.name);
    const bool ok = luaL_testudata(L_, -1, k.object) != nullptr;  // raw: compares metatables
    const std::string got = type_name(L_, -1);
    lua_pop(L_, 1);
    if (ok || (!k.mandatory && got == "nil")) return;
    throw Error(context() + quoted(k.name) + " must be a " + k.object + ", got " + got);
  }
  if (!has(k.name)) {
    if (k.mandatory) throw Error(context() + "missing " + quoted(k.name));
    return;
  }
  switch (k.type) {
    case Type::Number:
      optional_number(k.name);
      break;
    case Type::Integer:
      integer(k.name, 0);
      break;
    case Type::String:
      string(k.name);
      break;
    case Type::Boolean:
      boolean(k.name, false);
      break;
    case Type::Choice:
      choice(k.name, split(k.choices), "");
      break;
    case Type::Point:
      point(k.name);
      break;
    case Type::Names:
      names(k.name);
      break;
    case Type::Table: {
      push(k.name);
      read_top(L_, [&] { return Args(L_, -1, k.keys, k.name).index(); });
      break;
    }
    case Type::Function:
      if (push(k.name) != LUA_TFUNCTION) {
        const std::string got = type_name(L_, -1);
        lua_pop(L_, 1);
        throw Error(context() + quoted(k.name) + " must be a function, got " + got);
      }
      lua_pop(L_, 1);
      break;
    default:
      break;
  }
}

bool Args::has(const char* key) const {
  const bool present = push(key) != LUA_TNIL;
  lua_pop(L_, 1);
  return present;
}

int Args::push(const char* key) const {
  lua_pushstring(L_, key);
  return lua_rawget(L_, index_);
}

lua_Integer Args::length() const { return static_cast<lua_Integer>(lua_rawlen(L_, index_)); }

double Args::number_at(lua_Integer i) const {
  lua_rawgeti(L_, index_, i);
  return read_top(L_, [&] {
    if (lua_type(L_, -1) != LUA_TNUMBER)
      throw Error("entry " + std::to_string(i) + " must be a number, got " + type_name(L_, -1));
    const double v = lua_tonumber(L_, -1);
    if (!std::isfinite(v)) throw Error("entry " + std::to_string(i) + " must be a finite number");
    return v;
  });
}

Vec<2> Args::point_at(lua_Integer i, const std::string& what) const {
  lua_rawgeti(L_, index_, i);
  return read_top(L_, [&] { return to_point(L_, -1, what); });
}

std::optional<double> Args::optional_number(const char* key) const {
  const int t = push(key);
  return read_top(L_, [&]() -> std::optional<double> {
    if (t == LUA_TNIL) return std::nullopt;
    if (t != LUA_TNUMBER) throw Error(context() + quoted(key) + " must be a number, got " + type_name(L_, -1));
    const double v = lua_tonumber(L_, -1);
    if (!std::isfinite(v)) throw Error(context() + quoted(key) + " must be a finite number, got " + number_text(v));
    const Key& k = spec(key);
    if (!k.forwarded && k.range.bounded() && !k.range.contains(v))
      throw Error(context() + quoted(key) + " must be " + k.range.text() + unit_suffix(k.unit) + ", got " +
                  number_text(v));
    return v;
  });
}

double Args::number(const char* key) const {
  if (auto v = optional_number(key)) return *v;
  const Key& k = spec(key);
  if (k.has_number_default()) return k.number;
  throw Error(context() + "missing " + quoted(key));
}

double Args::number(const char* key, double fallback) const { return optional_number(key).value_or(fallback); }

int Args::integer(const char* key, int fallback) const {
  const auto v = optional_number(key);
  if (!v) return fallback;
  if (*v != std::floor(*v) || std::abs(*v) > 1e9)
    throw Error(context() + quoted(key) + " must be a whole number, got " + number_text(*v));
  return static_cast<int>(*v);
}

int Args::integer(const char* key) const {
  const Key& k = spec(key);
  if (!has(key) && !k.has_number_default()) throw Error(context() + "missing " + quoted(key));
  return integer(key, static_cast<int>(k.number));
}

std::string Args::string(const char* key) const {
  const int t = push(key);
  return read_top(L_, [&]() -> std::string {
    if (t == LUA_TSTRING) return lua_tostring(L_, -1);
    const Key& k = spec(key);
    if (t == LUA_TNIL && k.text) return k.text;
    if (t == LUA_TNIL) throw Error(context() + "missing " + quoted(key));
    throw Error(context() + quoted(key) + " must be a string, got " + type_name(L_, -1));
  });
}

std::string Args::string(const char* key, const std::string& fallback) const {
  return has(key) ? string(key) : fallback;
}

std::string Args::choice(const char* key, const std::vector<std::string>& allowed, const std::string& fallback) const {
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : "|") + a;
  const int t = push(key);
  const std::string got = t == LUA_TSTRING ? "'" + std::string(lua_tostring(L_, -1)) + "'" : type_name(L_, -1);
  lua_pop(L_, 1);
  if (t == LUA_TNIL && fallback.empty()) throw Error(context() + "missing " + quoted(key));
  if (t != LUA_TNIL && t != LUA_TSTRING)
    throw Error(context() + quoted(key) + " must be one of " + list + ", got " + got);
  const std::string v = t == LUA_TNIL ? fallback : got.substr(1, got.size() - 2);
  for (const auto& a : allowed)
    if (a == v) return v;
  throw Error(context() + quoted(key) + " must be one of " + list + ", got '" + v + "'");
}

std::string Args::choice(const char* key, const std::string& fallback) const {
  return choice(key, split(spec(key).choices), fallback);
}

std::string Args::choice(const char* key) const {
  const Key& k = spec(key);
  return choice(key, split(k.choices), k.text ? k.text : "");
}

bool Args::boolean(const char* key, bool fallback) const {
  const int t = push(key);
  return read_top(L_, [&] {
    if (t == LUA_TNIL) return fallback;
    if (t != LUA_TBOOLEAN) throw Error(context() + quoted(key) + " must be true or false, got " + type_name(L_, -1));
    return static_cast<bool>(lua_toboolean(L_, -1));
  });
}

bool Args::boolean(const char* key) const {
  const Key& k = spec(key);
  return boolean(key, k.text && std::string(k.text) == "true");
}

Vec<2> Args::point(const char* key) const {
  if (push(key) == LUA_TNIL) {
    lua_pop(L_, 1);
    const Key& k = spec(key);
    if (k.has_point_default()) return Vec<2>(k.point[0], k.point[1]);
    throw Error(context() + "missing " + quoted(key));
  }
  return read_top(L_, [&] { return to_point(L_, -1, context() + quoted(key)); });
}

std::optional<std::vector<std::string>> Args::names(const char* key) const {
  if (push(key) == LUA_TNIL) {
    lua_pop(L_, 1);
    const Key& k = spec(key);
    if (k.text) return split(k.text);
    if (k.mandatory) throw Error(context() + "missing " + quoted(key));
    return std::nullopt;
  }
  return read_top(L_, [&] {
    if (!lua_istable(L_, -1))
      throw Error(context() + quoted(key) + " must be a list of names such as {\"ux\", \"uy\"}, got " +
                  type_name(L_, -1));
    std::vector<std::string> out;
    const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L_, -1));
    for (lua_Integer i = 1; i <= n; ++i) {
      const bool is_name = lua_rawgeti(L_, -1, i) == LUA_TSTRING;
      if (is_name) out.emplace_back(lua_tostring(L_, -1));
      lua_pop(L_, 1);
      if (!is_name) throw Error(context() + quoted(key) + ": entry " + std::to_string(i) + " must be a name");
    }
    if (out.empty()) throw Error(context() + quoted(key) + " is empty");
    return std::optional<std::vector<std::string>>(std::move(out));
  });
}

Args Args::table(const char* key) const {
  const Key& k = spec(key);
  push(key);
  return Args(L_, -1, k.keys, k.name);
}

Vec<2> to_point(lua_State* L, int index, const std::string& what) {
  index = lua_absindex(L, index);
  if (!lua_istable(L, index)) throw Error(what + " must be a point {x, y}, got " + type_name(L, index));
  if (lua_rawlen(L, index) != 2) throw Error(what + " must be a point {x, y} with 2 numbers");
  Vec<2> p;
  for (int d = 0; d < 2; ++d) {
    lua_rawgeti(L, index, d + 1);
    const bool ok = lua_isnumber(L, -1);
    p[d] = ok ? lua_tonumber(L, -1) : 0.0;
    lua_pop(L, 1);
    if (!ok) throw Error(what + " must be a point {x, y} of numbers");
    if (!std::isfinite(p[d])) throw Error(what + " has a non-finite coordinate");
  }
  return p;
}

}  // namespace seismpm::lua
