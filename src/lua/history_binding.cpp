// mpm.history.*: time histories (velocity records, load factors) and h:at(t).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "binding.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/csv_table.hpp"
#include "io/ground_motion.hpp"
#include "objects.hpp"
#include "session.hpp"

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
  const std::string file = data_path(L, a.string("file"));
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

// The table behind a history, for the calls that need one.
const TableHistory& table_of(lua_State* L, const char* what) {
  const auto* t = dynamic_cast<const TableHistory*>(self(L).history.get());
  if (!t) throw Error(std::string(what) + " needs a tabulated history (table, csv or record), not a function or constant");
  return *t;
}

int history_peak(lua_State* L) {
  double peak = 0.0;
  for (double v : table_of(L, "peak").values()) peak = std::max(peak, std::abs(v));
  lua_pushnumber(L, peak);
  return 1;
}

int history_duration(lua_State* L) {
  const auto& t = table_of(L, "duration");
  lua_pushnumber(L, t.end() - t.start());
  return 1;
}

int history_write_csv(lua_State* L) {
  const auto& t = table_of(L, "write_csv");
  if (lua_type(L, 2) != LUA_TSTRING) throw Error("expects a file name (a string)");  // before lua_tostring converts numbers
  const char* file = lua_tostring(L, 2);
  std::ostringstream os;
  os.precision(10);
  os << "t,value\n";
  for (std::size_t k = 0; k < t.times().size(); ++k) os << t.times()[k] << ',' << t.values()[k] << '\n';
  write_file_atomically(file, os.str());
  return 0;
}

// mpm.history.at2{ file, integrate = "velocity", baseline = "none", scale = 1, units = "g", format }
int at2(lua_State* L) {
  Args a(L, 1, {"file", "integrate", "baseline", "scale", "units", "format"});
  const std::string file = data_path(L, a.string("file"));
  const std::string integrate = a.choice("integrate", {"velocity", "none"}, "velocity");
  const Baseline baseline = parse_baseline(a.choice("baseline", {"none", "linear", "quadratic"}, "none"));
  const double scale = a.number("scale", 1.0);
  const bool is_at2 = file.size() > 4 && (file.substr(file.size() - 4) == ".AT2" || file.substr(file.size() - 4) == ".at2");
  const std::string format = a.choice("format", {"at2", "columns"}, is_at2 ? "at2" : "columns");
  const std::string units = a.choice("units", {"g", "m/s2", "gal"}, "g");
  if (format == "at2" && units != "g") throw Error("key 'units': AT2 files are in g");
  const double to_si = units == "g" ? kStandardGravity : units == "gal" ? 0.01 : 1.0;
  AccelerationRecord record = format == "at2" ? read_at2(file) : read_acceleration_columns(file, to_si);
  for (double& v : record.a) v *= scale;
  std::ostringstream about;
  about.precision(4);
  double pga = 0.0;
  for (double v : record.a) pga = std::max(pga, std::abs(v));
  about << file << " (PGA " << pga / kStandardGravity << " g";
  std::vector<double> values = record.a;
  if (integrate == "velocity") {
    const auto raw = integrate_record(record, Baseline::None);
    const auto cor = integrate_record(record, baseline);
    auto peak = [](const std::vector<double>& x) {
      double p = 0.0;
      for (double v : x) p = std::max(p, std::abs(v));
      return p;
    };
    about << "; velocity: peak " << peak(raw.v) << " m/s, end " << raw.v.back() << " m/s, end displacement "
          << raw.d.back() << " m";
    if (baseline != Baseline::None)
      about << "; after the " << (baseline == Baseline::Linear ? "linear" : "quadratic") << " baseline: peak "
            << peak(cor.v) << " m/s, end " << cor.v.back() << " m/s, end displacement " << cor.d.back() << " m";
    values = cor.v;
  }
  about << ")";
  push_object(L, kHistoryType,
              HistoryObject{std::make_shared<TableHistory>(std::move(record.t), std::move(values), about.str())});
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
  if (lua_type(L, index) == LUA_TNUMBER) {
    const double v = lua_tonumber(L, index);
    if (!std::isfinite(v)) throw Error(what + " must be finite");
    return std::make_shared<ConstantHistory>(v);
  }
  if (auto* h = test_object<HistoryObject>(L, index, kHistoryType)) return h->history;
  throw Error(what + " must be a number or a history (mpm.history.*), got " + type_name(L, index));
}

void open_history(lua_State* L, int mpm) {
  new_type<HistoryObject, history_tostring>(L, kHistoryType);
  set_function<history_at>(L, -1, "at", "history:at");
  set_function<history_peak>(L, -1, "peak", "history:peak");
  set_function<history_duration>(L, -1, "duration", "history:duration");
  set_function<history_write_csv>(L, -1, "write_csv", "history:write_csv");
  lua_pop(L, 1);
  lua_newtable(L);
  set_function<table>(L, -1, "table", "mpm.history.table");
  set_function<csv>(L, -1, "csv", "mpm.history.csv");
  set_function<fn>(L, -1, "fn", "mpm.history.fn");
  set_function<at2>(L, -1, "at2", "mpm.history.at2");
  lua_setfield(L, mpm, "history");
}

}  // namespace seismpm::lua
