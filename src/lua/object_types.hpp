// Lua's type name of each object behind a userdata (self<T>, push_object<T>, check_object<T>).
#pragma once

#include "binding.hpp"
#include "objects.hpp"

namespace seismpm::lua {

template <>
struct LuaType<ModelObject> {
  static constexpr const char* name = kModelType;
};
template <>
struct LuaType<BodyObject> {
  static constexpr const char* name = kBodyType;
};
template <>
struct LuaType<ProbeObject> {
  static constexpr const char* name = kProbeType;
};
template <>
struct LuaType<MaterialObject> {
  static constexpr const char* name = kMaterialType;
};
template <>
struct LuaType<ShapeObject> {
  static constexpr const char* name = kShapeType;
};
template <>
struct LuaType<HistoryObject> {
  static constexpr const char* name = kHistoryType;
};

}  // namespace seismpm::lua
