// The one description of each Lua function: its named arguments (type, default, range, unit, a doc
// line), its summary and example. The same table checks a call's arguments (Args), answers help() and
// writes docs/lua-api.md, so the three cannot drift apart. Each binding file holds the table of its
// functions; api_docs() concatenates them.
#pragma once

#include <lua.hpp>

#include <limits>
#include <span>

#include "core/parameter.hpp"

namespace seismpm::lua {

enum class Type {
  Number,   // a finite number, checked against `range`
  Integer,  // a whole number, checked against `range`
  String,
  Boolean,
  Choice,  // one of the strings in `choices` ("gimp|linear")
  Point,   // {x, y}
  Names,   // a non-empty list of strings {"ux", "uy"}
  Table,   // a table of named arguments of its own, described by `keys`
  Object,  // a userdata of Lua type `object` ("material", "body")
  Function,
  Custom,      // read by the binding itself (a domain, a velocity); `type_text` says what it is
  Positional,  // the entries 1..n of the table; `name` shows them ("{x, y}, {x, y}, ...")
};

struct Key {
  const char* name = "";
  Type type = Type::Number;
  const char* doc = "";                                               // one line: what the key means
  const char* unit = "";                                              // "m", "Pa", "degrees"
  bool mandatory = false;                                             // required: no default
  double number = std::numeric_limits<double>::quiet_NaN();           // default of a Number or Integer
  double point[2] = {std::numeric_limits<double>::quiet_NaN(), 0.0};  // default of a Point
  const char* text = nullptr;           // default of a String or Choice; of Names as "ux|uy"
  const char* shown_default = nullptr;  // describes a default that no value states ("from cfl", "unchanged")
  Interval range{};                     // Number and Integer
  const char* range_text = nullptr;     // a range that depends on other keys ("[0, friction]"), shown only
  bool forwarded = false;               // the kernel checks the range (a material its strength): Args does not
  const char* choices = nullptr;        // Choice
  const char* object = nullptr;         // Object: the userdata's type name
  const char* type_text = nullptr;      // Custom: what the value is ("{vx, vy}: numbers or histories")
  std::span<const Key> keys{};          // Table

  // Modifiers, so that a table reads as one line per key: arg::number("cell", "m", "cell size").in(above(0)).required()
  constexpr Key required() const { return with(&Key::mandatory, true); }
  constexpr Key def(double v) const { return with(&Key::number, v); }
  constexpr Key def_point(double x, double y) const {
    Key k = *this;
    k.point[0] = x;
    k.point[1] = y;
    return k;
  }
  constexpr Key def_text(const char* v) const { return with(&Key::text, v); }
  constexpr Key shown(const char* about) const { return with(&Key::shown_default, about); }
  constexpr Key in(Interval r) const { return with(&Key::range, r); }
  constexpr Key in_text(const char* t) const { return with(&Key::range_text, t); }
  // The kernel checks `r`: the help shows it, Args leaves it to the kernel.
  constexpr Key checked_by_kernel(Interval r) const { return in(r).with(&Key::forwarded, true); }
  // A copy with one member set.
  template <class T, class V>
  constexpr Key with(T Key::*member, V value) const {
    Key k = *this;
    k.*member = value;
    return k;
  }
  constexpr bool has_number_default() const { return number == number; }  // not NaN
  constexpr bool has_point_default() const { return point[0] == point[0]; }
};

// Builders of keys, one per type.
namespace arg {

constexpr Key key(const char* name, Type type, const char* unit, const char* doc) {
  Key k;
  k.name = name;
  k.type = type;
  k.unit = unit;
  k.doc = doc;
  return k;
}
constexpr Key number(const char* name, const char* unit, const char* doc) { return key(name, Type::Number, unit, doc); }
constexpr Key integer(const char* name, const char* doc) { return key(name, Type::Integer, "", doc); }
constexpr Key string(const char* name, const char* doc) { return key(name, Type::String, "", doc); }
constexpr Key boolean(const char* name, bool fallback, const char* doc) {
  return key(name, Type::Boolean, "", doc).def_text(fallback ? "true" : "false");
}
constexpr Key point(const char* name, const char* unit, const char* doc) { return key(name, Type::Point, unit, doc); }
constexpr Key names(const char* name, const char* doc) { return key(name, Type::Names, "", doc); }
constexpr Key function(const char* name, const char* doc) { return key(name, Type::Function, "", doc); }
// One of `choices` ("gimp|linear"), `fallback` when absent (nullptr: required).
constexpr Key choice(const char* name, const char* choices, const char* fallback, const char* doc) {
  Key k = key(name, Type::Choice, "", doc);
  k.choices = choices;
  k.text = fallback;
  k.mandatory = fallback == nullptr;
  return k;
}
constexpr Key object(const char* name, const char* type, const char* doc) {
  Key k = key(name, Type::Object, "", doc);
  k.object = type;
  return k;
}
constexpr Key custom(const char* name, const char* type_text, const char* unit, const char* doc) {
  Key k = key(name, Type::Custom, unit, doc);
  k.type_text = type_text;
  return k;
}
constexpr Key table(const char* name, std::span<const Key> keys, const char* doc) {
  Key k = key(name, Type::Table, "", doc);
  k.keys = keys;
  return k;
}
// The positional entries, shown in the signature as `shown` ("body_a, body_b").
constexpr Key positional(const char* shown, const char* doc) { return key(shown, Type::Positional, "", doc); }

}  // namespace arg

// A function of the API as help() and docs/lua-api.md show it.
struct Function {
  const char* name;           // where it is registered and what help("...") takes: "mpm.model", "model:run"
  lua_CFunction fn;           // guarded<...>; nullptr for functions of the Lua library (lua/seismpm.lua)
  const char* call;           // the whole signature ("m:step(n = 1)") when it takes no table; nullptr:
                              // the name, a method's object abbreviated ("m:run{ ... }")
  std::span<const Key> keys;  // its table of named arguments; empty when it takes none
  const char* summary;
  const char* example;  // a line of Lua
};

}  // namespace seismpm::lua
