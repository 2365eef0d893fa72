// The functions of the Lua library (lua/seismpm.lua): their key tables, and mpm._check_args, with
// which the library checks a call against them as the bindings do.
#include "api_docs.hpp"
#include "binding.hpp"

namespace seismpm::lua {

namespace {

const Key kSlopeKeys[] = {
    arg::number("left", "m", "left end of the box").required(),
    arg::number("right", "m", "right end of the box").required(),
    arg::number("base", "m", "bottom of the box").def(0),
    arg::point("crest", "m", "the crest's edge, where the face starts").required(),
    arg::number("toe_level", "m", "height of the toe ground, between base and the crest").required(),
    arg::number("angle", "degrees", "the face's inclination").in(Interval{0, 90, true, true}).required(),
};
const Key kLayersKeys[] = {
    arg::positional("{top = y or thickness = t, name = ..., material = ...}, ...",
                    "the layers from the bottom up, each by its top elevation or its thickness (m), with its "
                    "material (mpm.material.*) for m:body's regions; name defaults to layerN"),
    arg::number("left", "m", "left end").required(),
    arg::number("right", "m", "right end").required(),
    arg::number("base", "m", "bottom of the lowest layer").def(0),
};

const Function kLibrary[] = {
    {"mpm.geometry.slope", nullptr, nullptr, kSlopeKeys,
     "The polygon of a slope in a box from x = left to right above `base`: level crest ground at height crest[2] "
     "from `left` to crest[1], a face falling to the right at `angle` degrees down to toe_level, then level toe "
     "ground to `right`. Returns an mpm.shape.polygon.",
     "local s = mpm.geometry.slope{ left = 0, right = 0.9, crest = {0.35, 0.53}, toe_level = 0.2, angle = 45 }"},
    {"mpm.geometry.layers", nullptr, nullptr, kLayersKeys,
     "Horizontal layers from `left` to `right`, listed from the bottom up by their top elevation or their "
     "thickness: returns a list of { name =, shape = rectangle, material = }, which m:body takes as its regions: "
     "layered ground as one body, without interfaces (its shape, a slope say, cuts the layers).",
     "local ground = m:body{ name = \"ground\", shape = slope, regions = mpm.geometry.layers{ left = 0, right = 0.9, "
     "{top = 0.2, name = \"clay\", material = clay}, {thickness = 0.4, material = sand} } }"},
};

// The message of a failed check of mpm._check_args(name, t), or "" when t passes.
std::string check_args(lua_State* L) {
  try {
    if (lua_type(L, 1) != LUA_TSTRING) throw std::logic_error("mpm._check_args(name, t): name must be a string");
    const Function* f = find_function(lua_tostring(L, 1));
    if (!f) throw std::logic_error(std::string("mpm._check_args: no key table for '") + lua_tostring(L, 1) + "'");
    const Args a(L, 2, f->keys);
    return "";
  } catch (const std::exception& e) {
    return std::string(lua_type(L, 1) == LUA_TSTRING ? lua_tostring(L, 1) : "mpm._check_args") + ": " + e.what();
  }
}

// Pushes the value of each named key of `f` in the table at 2, or its default: {left =, base = 0, ...}.
void push_with_defaults(lua_State* L, const Function& f) {
  lua_createtable(L, 0, static_cast<int>(f.keys.size()));
  for (const Key& k : f.keys) {
    if (k.type == Type::Positional) continue;
    lua_pushstring(L, k.name);
    lua_pushvalue(L, -1);
    if (lua_rawget(L, 2) == LUA_TNIL) {
      lua_pop(L, 1);
      if (k.has_number_default())
        lua_pushnumber(L, k.number);
      else if (k.text)
        lua_pushstring(L, k.text);
      else
        lua_pushnil(L);
    }
    lua_rawset(L, -3);
  }
}

// mpm._check_args(name, t) -> t's named values with the defaults filled in. A bad call raises the
// bindings' error at the line of the library function's caller (the script, not lua/seismpm.lua).
int check_args_binding(lua_State* L) {
  {
    const std::string message = check_args(L);
    if (message.empty()) {
      push_with_defaults(L, *find_function(lua_tostring(L, 1)));
      return 1;
    }
    luaL_where(L, 2);
    lua_pushstring(L, message.c_str());
  }
  lua_concat(L, 2);
  return lua_error(L);
}

}  // namespace

std::span<const Function> library_functions() { return kLibrary; }

// Not an API function: registered without a name for help().
void open_library_support(lua_State* L) {
  raw_global(L, "mpm");
  lua_pushstring(L, "_check_args");
  lua_pushcfunction(L, check_args_binding);
  lua_rawset(L, -3);
  lua_pop(L, 1);
}

}  // namespace seismpm::lua
