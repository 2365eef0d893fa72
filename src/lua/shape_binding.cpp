// mpm.shape.*: regions that bodies are filled from.
#include "api_docs.hpp"
#include "binding.hpp"
#include "core/error.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

const Key kRectangleKeys[] = {
    arg::positional("x0, y0, x1, y1", "the lower-left and upper-right corners (m)"),
    arg::point("lower", "m", "the lower-left corner, instead of x0, y0 (with upper)"),
    arg::point("upper", "m", "the upper-right corner, instead of x1, y1 (with lower)"),
};
const Key kPolygonKeys[] = {
    arg::positional("{x, y}, {x, y}, {x, y}, ...", "the corners (m): at least 3, edges must not cross"),
};
const Key kPolylineKeys[] = {
    arg::positional("{x, y}, {x, y}, ...", "the points of the line (m)"),
    arg::number("thickness", "m", "the band's width").in(above(0)).required(),
    arg::choice("side", "both|left|right", "both",
                "where the band lies: thickness/2 each side, or all of it on the left or right, walking from the "
                "first point to the last"),
};

// Positional list of points {{x, y}, ...} in the argument table itself.
std::vector<Vec<2>> positional_points(const Args& a) {
  std::vector<Vec<2>> pts;
  for (lua_Integer i = 1; i <= a.length(); ++i) pts.push_back(a.point_at(i, "point " + std::to_string(i)));
  return pts;
}

int shape_tostring(lua_State* L) {
  lua_pushstring(L, self<ShapeObject>(L).region->describe().c_str());
  return 1;
}

int shape_contains(lua_State* L) {
  const auto& s = self<ShapeObject>(L);
  lua_pushboolean(L, s.region->contains(to_point(L, 2, "the point")));
  return 1;
}

// mpm.shape.rectangle{x0, y0, x1, y1} or {lower = {x0, y0}, upper = {x1, y1}}
int rectangle(lua_State* L) {
  const Args a(L, 1, kRectangleKeys);
  std::vector<double> c;
  if (a.has("lower") || a.has("upper")) {
    const Vec<2> lo = a.point("lower"), hi = a.point("upper");
    c = {lo[0], lo[1], hi[0], hi[1]};
  } else {
    if (a.length() != 4) throw Error("expects {x0, y0, x1, y1} (m) or {lower = {x0, y0}, upper = {x1, y1}}");
    for (lua_Integer i = 1; i <= 4; ++i) c.push_back(a.number_at(i));
  }
  auto region = std::make_shared<RectangleRegion>(c[0], c[1], c[2], c[3]);
  push_object(L, ShapeObject{std::move(region)});
  return 1;
}

// mpm.shape.polygon{{x, y}, {x, y}, {x, y}, ...}
int polygon(lua_State* L) {
  const Args a(L, 1, kPolygonKeys);
  auto region = std::make_shared<PolygonRegion>(positional_points(a));
  push_object(L, ShapeObject{std::move(region)});
  return 1;
}

// mpm.shape.polyline{{x, y}, {x, y}, ..., thickness = t, side = "both"|"left"|"right"}
int polyline(lua_State* L) {
  const Args a(L, 1, kPolylineKeys);
  const std::string side = a.choice("side");
  const auto s = side == "left"    ? PolylineRegion::Side::Left
                 : side == "right" ? PolylineRegion::Side::Right
                                   : PolylineRegion::Side::Both;
  auto region = std::make_shared<PolylineRegion>(positional_points(a), a.number("thickness"), s);
  push_object(L, ShapeObject{std::move(region)});
  return 1;
}

const Function kShape[] = {
    {"mpm.shape.rectangle", &guarded<rectangle>, nullptr, kRectangleKeys, "An axis-aligned rectangle.",
     "local s = mpm.shape.rectangle{ 0, 0, 0.9, 0.2 }"},
    {"mpm.shape.polygon", &guarded<polygon>, nullptr, kPolygonKeys,
     "A simple polygon, convex or concave, in either orientation.",
     "local s = mpm.shape.polygon{ {0, 0}, {0.9, 0}, {0.9, 0.2}, {0.3, 0.5}, {0, 0.5} }"},
    {"mpm.shape.polyline", &guarded<polyline>, nullptr, kPolylineKeys,
     "A band along a polyline. A one-sided band under a slope gives its particles the line's normal, so contact "
     "follows the true surface.",
     "local base = mpm.shape.polyline{ {0, 0.1}, {1, 0.1}, thickness = 0.02, side = \"right\" }"},
    {"shape:contains",
     &guarded<shape_contains>,
     "s:contains{x, y}",
     {},
     "Whether the point lies inside the shape.",
     "print(s:contains{0.1, 0.1})"},
};

}  // namespace

std::span<const Function> shape_functions() { return kShape; }

void open_shape(lua_State* L) { open_type<ShapeObject, shape_tostring>(L, kShape); }

}  // namespace seismpm::lua
