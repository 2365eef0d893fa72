// mpm.lem: limit equilibrium (Bishop's simplified or Spencer's method, a circle search or a given slip
// surface, ky) on a model's slope.
#include <cmath>
#include <string>
#include <vector>

#include "api_docs.hpp"
#include "args.hpp"
#include "binding.hpp"
#include "core/error.hpp"
#include "methods/lem_model.hpp"
#include "methods/limit_equilibrium.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

const Key kSearchKeys[] = {
    arg::custom("centres", "{{x0, y0}, {x1, y1}}", "m", "corners of the box of circle centres")
        .shown("from one slope height behind the crest to one beyond the toe, a quarter height above the toe "
               "to three above the crest"),
    arg::custom("radii", "{r0, r1}", "m", "the range of radii")
        .shown("from the smallest circle cutting the slope to the one touching the firm base"),
    arg::integer("grid", "centres per direction in each of the search's zoom levels").def(15).in(closed(2, 200)),
    arg::integer("levels", "zoom levels: each grid spans 1.5 spacings around the last best centre")
        .def(5)
        .in(closed(1, 20)),
    arg::integer("samples", "radii sampled per centre before a golden-section refinement").def(16).in(closed(3, 500)),
};
const Key kLemKeys[] = {
    arg::object("model", kModelType, "the model: its deformable particles are the slope").required(),
    arg::choice("method", "bishop|spencer", "bishop",
                "the method of slices: bishop (moment equilibrium, circles) or spencer (force and moment "
                "equilibrium, circles or a given surface)"),
    arg::number("kh", "g", "pseudo-static horizontal seismic coefficient, out of the slope").def(0).in(at_least(0)),
    arg::integer("slices", "slices between the slip surface's entry and exit").def(80).in(closed(4, 10000)),
    arg::table("search", kSearchKeys, "narrows the circle search"),
    arg::custom("surface", "{{x, y}, ...}", "m",
                "a slip surface of your own (spencer only): x increasing, from above the ground to above it "
                "again; no search then"),
};

// Two numbers {a, b} or two points {{x, y}, {x, y}} under `key` of the search table.
std::pair<double, double> read_pair(lua_State* L, const Args& a, const char* key) {
  a.push(key);
  const std::string what = std::string("key '") + key + "'";
  if (!lua_istable(L, -1) || lua_rawlen(L, -1) != 2) throw Error(what + " must be a table of two entries");
  lua_rawgeti(L, -1, 1);
  lua_rawgeti(L, -2, 2);
  if (!lua_isnumber(L, -2) || !lua_isnumber(L, -1)) throw Error(what + " must hold two numbers");
  std::pair<double, double> r{lua_tonumber(L, -2), lua_tonumber(L, -1)};
  lua_pop(L, 3);
  return r;
}

LemSearch search_of(lua_State* L, const Args& call) {
  LemSearch s;
  if (!call.has("search")) return s;
  const Args a = call.table("search");
  if (a.has("centres")) {
    a.push("centres");
    if (!lua_istable(L, -1) || lua_rawlen(L, -1) != 2) throw Error("key 'centres' must be {{x0, y0}, {x1, y1}}");
    lua_rawgeti(L, -1, 1);
    const Vec<2> p0 = to_point(L, -1, "centres[1]");
    lua_rawgeti(L, -2, 2);
    const Vec<2> p1 = to_point(L, -1, "centres[2]");
    lua_pop(L, 3);
    s.centre_lower = LemPoint{p0[0], p0[1]};
    s.centre_upper = LemPoint{p1[0], p1[1]};
  }
  if (a.has("radii")) {
    const auto [r0, r1] = read_pair(L, a, "radii");
    if (!(r0 >= 0 && r1 > r0)) throw Error("key 'radii' must be {r0, r1} with 0 <= r0 < r1");
    s.radius_min = r0;
    s.radius_max = r1;
  }
  s.centres = a.integer("grid");
  s.zoom_levels = a.integer("levels");
  s.radii = a.integer("samples");
  return s;
}

std::vector<LemPoint> surface_of(lua_State* L, const Args& a) {
  a.push("surface");
  if (!lua_istable(L, -1) || lua_rawlen(L, -1) < 2) throw Error("key 'surface' must be a list of two points or more");
  std::vector<LemPoint> out;
  for (lua_Integer i = 1; i <= static_cast<lua_Integer>(lua_rawlen(L, -1)); ++i) {
    lua_rawgeti(L, -1, i);
    const Vec<2> p = to_point(L, -1, ("surface[" + std::to_string(i) + "]").c_str());
    lua_pop(L, 1);
    out.push_back({p[0], p[1]});
  }
  lua_pop(L, 1);
  return out;
}

void push_number_field(lua_State* L, const char* name, double v) {
  lua_pushnumber(L, v);
  lua_setfield(L, -2, name);
}

void push_result(lua_State* L, const LemResult& r) {
  lua_createtable(L, 0, 4);
  push_number_field(L, "fos", r.fos);
  push_number_field(L, "ky", r.ky);
  push_number_field(L, "theta", r.theta);
  // The circle both as {xc, yc, r} (a list, as the API writes it) and by name; none for a given surface.
  if (r.circle.r > 0) {
    lua_createtable(L, 3, 3);
    const double circle[3] = {r.circle.xc, r.circle.yc, r.circle.r};
    for (int k = 0; k < 3; ++k) {
      lua_pushnumber(L, circle[k]);
      lua_rawseti(L, -2, k + 1);
    }
    push_number_field(L, "xc", r.circle.xc);
    push_number_field(L, "yc", r.circle.yc);
    push_number_field(L, "r", r.circle.r);
    lua_setfield(L, -2, "circle");
  }
  lua_createtable(L, static_cast<int>(r.surface.size()), 0);
  for (std::size_t i = 0; i < r.surface.size(); ++i) {
    lua_createtable(L, 2, 0);
    lua_pushnumber(L, r.surface[i].x);
    lua_rawseti(L, -2, 1);
    lua_pushnumber(L, r.surface[i].y);
    lua_rawseti(L, -2, 2);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "surface");
}

// mpm.lem{ model, method = "bishop", kh = 0, slices = 80, search = { centres, radii, ... } }
int lem(lua_State* L) {
  const Args a(L, 1, kLemKeys);
  const auto handle = object_argument<ModelObject>(a, "model").handle;
  LemSettings settings;
  settings.method = a.choice("method") == "spencer" ? LemMethod::spencer : LemMethod::bishop;
  settings.slices = a.integer("slices");
  try {
    if (a.has("surface")) {
      if (settings.method != LemMethod::spencer)
        throw Error("key 'surface': a slip surface of your own needs method = \"spencer\"");
      if (a.has("search")) throw Error("key 'search': there is no search on a given surface (key 'surface')");
      push_result(L, surface_equilibrium(slope_of_model(handle->model), surface_of(L, a), a.number("kh"), settings));
    } else {
      push_result(L, limit_equilibrium(slope_of_model(handle->model), a.number("kh"), search_of(L, a), settings));
    }
  } catch (const InputError& e) {
    throw Error(e.what());
  }
  return 1;
}

const Function kLem[] = {
    {"mpm.lem", &guarded<lem>, nullptr, kLemKeys,
     "Limit equilibrium of the model's slope by Bishop's simplified method or Spencer's method (force and moment "
     "equilibrium, interslice forces at one inclination theta): the ground surface is the top of the "
     "deformable particles in each grid column, the soil their materials' c, phi and density (in horizontal "
     "bands, one per run of grid rows of one material), the firm base the bottom of the soil (or a rigid body's "
     "top under it). Searches slip circles (or, with surface and spencer, takes that surface) and returns { fos, "
     "circle = {xc, yc, r}, ky, surface = {{x, y}, ...}, theta }: the least factor of safety under kh, its circle "
     "and slip surface, ky (g), the kh at which the least factor is 1 (0 when the slope fails statically), and "
     "Spencer's interslice force inclination theta (degrees, positive: an upslope slice pushes the next one down "
     "towards the toe; 0 for Bishop). See docs/methods.md.",
     "local r = mpm.lem{ model = m, kh = 0.1 }  print(r.fos, r.ky)"},
};

}  // namespace

std::span<const Function> lem_functions() { return kLem; }

void open_lem(lua_State* L) { register_functions(L, kLem); }

}  // namespace seismpm::lua
