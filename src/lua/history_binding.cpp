// mpm.history.*: time histories (velocity records, load factors) and h:at(t).
#include <sstream>

#include "binding.hpp"
#include "core/error.hpp"
#include "io/csv_table.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

HistoryObject& self(lua_State* L) { return check_object<HistoryObject>(L, 1, kHistoryType, "self"); }

int history_tostring(lua_State* L) {
  lua_pushstring(L, ("history: " + self(L).history->describe()).c_str());
  return 1;
}

int history_at(lua_State* L) {
  const auto& h = self(L);
  if (!lua_isnumber(L, 2)) throw Error("expects a time t (s), got " + type_name(L, 2));
  lua_pushnumber(L, h.history->at(lua_tonumber(L, 2)));
  return 1;
}

// mpm.history.table{{t, v}, {t, v}, ...}
int table(lua_State* L) {
  Args a(L, 1, {}, true);
  std::vector<double> t, v;
  for (lua_Integer i = 1; i <= a.length(); ++i) {
    const Vec<2> p = a.point_at(i, "point " + std::to_string(i) + " {t, value}");
    t.push_back(p[0]);
    v.push_back(p[1]);
  }
  push_object(L, kHistoryType, HistoryObject{std::make_shared<TableHistory>(std::move(t), std::move(v), "table")});
  return 1;
}

// mpm.history.csv{file =, time = "t", value = "v", scale = 1, shift = 0}
int csv(lua_State* L) {
  Args a(L, 1, {"file", "time", "value", "scale", "shift"});
  const std::string file = a.string("file");
  const std::string time = a.string("time", "t");
  const std::string value = a.string("value");
  const double scale = a.number("scale", 1.0);
  const double shift = a.number("shift", 0.0);
  auto c = read_csv_columns(file, {time, value});
  for (std::size_t k = 1; k < c.columns[0].size(); ++k)
    if (!(c.columns[0][k] > c.columns[0][k - 1]))
      throw Error(file + ":" + std::to_string(c.lines[k]) + ": times must increase (" + std::to_string(c.columns[0][k]) +
                  " after " + std::to_string(c.columns[0][k - 1]) + ")");
  for (auto& t : c.columns[0]) t += shift;
  for (auto& v : c.columns[1]) v *= scale;
  push_object(L, kHistoryType,
              HistoryObject{std::make_shared<TableHistory>(std::move(c.columns[0]), std::move(c.columns[1]), file)});
  return 1;
}

// mpm.history.fn(function(t) return ... end): evaluated in Lua when asked, never per particle.
int fn(lua_State* L) {
  if (!lua_isfunction(L, 1)) throw Error("expects a function of time, function(t) return value end");
  lua_pushvalue(L, 1);
  const int ref = luaL_ref(L, LUA_REGISTRYINDEX);
  lua_State* main = L;
  auto f = [main, ref](double t) {
    lua_rawgeti(main, LUA_REGISTRYINDEX, ref);
    lua_pushnumber(main, t);
    if (lua_pcall(main, 1, 1, 0) != LUA_OK) {
      std::string msg = lua_tostring(main, -1) ? lua_tostring(main, -1) : "error";
      lua_pop(main, 1);
      throw Error("history function failed at t = " + std::to_string(t) + ": " + msg);
    }
    if (!lua_isnumber(main, -1)) {
      lua_pop(main, 1);
      throw Error("history function must return a number (at t = " + std::to_string(t) + ")");
    }
    const double v = lua_tonumber(main, -1);
    lua_pop(main, 1);
    return v;
  };
  push_object(L, kHistoryType, HistoryObject{std::make_shared<FunctionHistory>(f, "Lua function")});
  return 1;
}

}  // namespace

std::shared_ptr<const History> to_history(lua_State* L, int index, const std::string& what) {
  if (lua_type(L, index) == LUA_TNUMBER) return std::make_shared<ConstantHistory>(lua_tonumber(L, index));
  if (auto* h = test_object<HistoryObject>(L, index, kHistoryType)) return h->history;
  throw Error(what + " must be a number or a history (mpm.history.*), got " + type_name(L, index));
}

void open_history(lua_State* L, int mpm) {
  new_type<HistoryObject, history_tostring>(L, kHistoryType);
  set_function<history_at>(L, -1, "at", "history:at");
  lua_pop(L, 1);
  lua_newtable(L);
  set_function<table>(L, -1, "table", "mpm.history.table");
  set_function<csv>(L, -1, "csv", "mpm.history.csv");
  set_function<fn>(L, -1, "fn", "mpm.history.fn");
  lua_setfield(L, mpm, "history");
}

}  // namespace seismpm::lua
