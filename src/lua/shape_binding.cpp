// mpm.shape.*: regions that bodies are filled from.
#include "binding.hpp"
#include "core/error.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

// Positional list of points {{x, y}, ...} in the argument table itself.
std::vector<Vec<2>> positional_points(Args& a) {
  std::vector<Vec<2>> pts;
  for (lua_Integer i = 1; i <= a.length(); ++i) pts.push_back(a.point_at(i, "point " + std::to_string(i)));
  return pts;
}

int shape_tostring(lua_State* L) {
  lua_pushstring(L, check_object<ShapeObject>(L, 1, kShapeType, "self").region->describe().c_str());
  return 1;
}

int shape_contains(lua_State* L) {
  const auto& s = check_object<ShapeObject>(L, 1, kShapeType, "self");
  lua_pushboolean(L, s.region->contains(to_point(L, 2, "the point")));
  return 1;
}

// mpm.shape.rectangle{x0, y0, x1, y1} or {lower = {x0, y0}, upper = {x1, y1}}
int rectangle(lua_State* L) {
  Args a(L, 1, {"lower", "upper"}, true);
  std::vector<double> c;
  if (a.has("lower") || a.has("upper")) {
    const Vec<2> lo = a.point("lower"), hi = a.point("upper");
    c = {lo[0], lo[1], hi[0], hi[1]};
  } else {
    if (a.length() != 4) throw Error("expects {x0, y0, x1, y1} (m) or {lower = {x0, y0}, upper = {x1, y1}}");
    for (lua_Integer i = 1; i <= 4; ++i) c.push_back(a.number_at(i));
  }
  push_object(L, kShapeType, ShapeObject{std::make_shared<RectangleRegion>(c[0], c[1], c[2], c[3])});
  return 1;
}

// mpm.shape.polygon{{x, y}, {x, y}, {x, y}, ...}
int polygon(lua_State* L) {
  Args a(L, 1, {}, true);
  auto pts = positional_points(a);
  push_object(L, kShapeType, ShapeObject{std::make_shared<PolygonRegion>(std::move(pts))});
  return 1;
}

// mpm.shape.polyline{{x, y}, {x, y}, ..., thickness = t, side = "both"|"left"|"right"}
int polyline(lua_State* L) {
  Args a(L, 1, {"thickness", "side"}, true);
  auto pts = positional_points(a);
  const double thickness = Args::positive("thickness", a.number("thickness"), "m");
  const std::string side = a.choice("side", {"both", "left", "right"}, "both");
  const auto s = side == "left" ? PolylineRegion::Side::Left
                                : side == "right" ? PolylineRegion::Side::Right : PolylineRegion::Side::Both;
  push_object(L, kShapeType, ShapeObject{std::make_shared<PolylineRegion>(std::move(pts), thickness, s)});
  return 1;
}

}  // namespace

void open_shape(lua_State* L, int mpm) {
  new_type<ShapeObject, shape_tostring>(L, kShapeType);
  set_function<shape_contains>(L, -1, "contains", "shape:contains");
  lua_pop(L, 1);
  lua_newtable(L);
  set_function<rectangle>(L, -1, "rectangle", "mpm.shape.rectangle");
  set_function<polygon>(L, -1, "polygon", "mpm.shape.polygon");
  set_function<polyline>(L, -1, "polyline", "mpm.shape.polyline");
  lua_setfield(L, mpm, "shape");
}

}  // namespace seismpm::lua
