// mpm.history.*: time histories (velocity records, load factors) and h:at(t).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "api_docs.hpp"
#include "binding.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/csv_table.hpp"
#include "io/ground_motion.hpp"
#include "lua_function.hpp"
#include "objects.hpp"
#include "sandbox.hpp"
#include "session.hpp"

namespace seismpm::lua {

namespace {

const Key kTableKeys[] = {arg::positional("{t, v}, {t, v}, ...", "the points: times (s) must increase")};
const Key kCsvKeys[] = {
    arg::string("file",
                "the CSV file; a relative one not found from the current directory is looked for next to "
                "the script")
        .required(),
    arg::custom("time", "name or number", "",
                "the column of times (s): its name in the header line, or its number counted from 1 (then the "
                "file may have no header)")
        .def_text("t"),
    arg::custom("value", "name or number", "", "the column of values: its name, or its number counted from 1")
        .required(),
    arg::number("scale", "", "factor on the values").def(1),
    arg::number("shift", "s", "added to the times").def(0),
};
const Key kAt2Keys[] = {
    arg::string("file", "the record: PEER NGA .AT2 (in g) or two columns time, acceleration").required(),
    arg::choice("integrate", "velocity|none", "velocity",
                "velocity (trapezoidal rule) or none (the acceleration, m/s2)"),
    arg::choice("baseline", "none|linear|quadratic", "none",
                "linear removes the drift so velocity and displacement end at zero; quadratic first removes a "
                "least-squares quadratic trend of the velocity"),
    arg::number("scale", "", "factor on the acceleration").def(1),
    arg::choice("units", "g|m/s2|gal", "g", "units of a columns file (AT2 files are in g)"),
    arg::choice("format", "at2|columns", "", "the file's format").shown("from the extension (.AT2: at2)"),
};

int history_tostring(lua_State* L) {
  lua_pushstring(L, ("history: " + self<HistoryObject>(L).history->describe()).c_str());
  return 1;
}

int history_at(lua_State* L) {
  const auto history = self<HistoryObject>(L).history;  // held: its function may destroy the userdata
  if (!lua_isnumber(L, 2)) throw Error("expects a time t (s), got " + type_name(L, 2));
  lua_pushnumber(L, history->at(lua_tonumber(L, 2)));
  return 1;
}

// mpm.history.table{{t, v}, {t, v}, ...}
int history_table(lua_State* L) {
  const Args a(L, 1, kTableKeys);
  std::vector<double> t, v;
  for (lua_Integer i = 1; i <= a.length(); ++i) {
    const Vec<2> p = a.point_at(i, "point " + std::to_string(i) + " {t, value}");
    t.push_back(p[0]);
    v.push_back(p[1]);
  }
  auto history = std::make_shared<TableHistory>(std::move(t), std::move(v), "table");
  push_object(L, HistoryObject{std::move(history)});
  return 1;
}

// A column key: a header name, or a whole number counted from 1.
CsvColumn column_key(const Args& a, const char* key, const char* fallback) {
  lua_State* L = a.state();
  const int type = a.push(key);
  const std::string got = type_name(L, -1);
  const double n = type == LUA_TNUMBER ? lua_tonumber(L, -1) : 0.0;
  const std::string name = type == LUA_TSTRING ? lua_tostring(L, -1) : "";
  lua_pop(L, 1);
  const std::string what = "key '" + std::string(key) + "'";
  if (type == LUA_TNUMBER) {
    if (!(n >= 1 && n <= 1e6 && n == std::floor(n))) {
      std::ostringstream os;
      os << what << ": a column number is a whole number from 1, got " << n;
      throw Error(os.str());
    }
    return CsvColumn::numbered(static_cast<int>(n));
  }
  if (type == LUA_TSTRING) return CsvColumn(name);
  if (type != LUA_TNIL) throw Error(what + " must be a column name or number, got " + got);
  if (!fallback) throw Error("missing " + what);
  return CsvColumn(fallback);
}

// mpm.history.csv{file =, time = "t" or 1, value = "v" or 2, scale = 1, shift = 0}
int history_csv(lua_State* L) {
  const Args a(L, 1, kCsvKeys);
  const CsvColumn time = column_key(a, "time", "t"), value = column_key(a, "value", nullptr);
  const std::string file = data_path(L, a.string("file"));
  check_readable(L, file, "key 'file'");
  const double scale = a.number("scale"), shift = a.number("shift");
  auto c = read_csv_columns(file, {time, value});
  for (std::size_t k = 1; k < c.columns[0].size(); ++k)
    if (!(c.columns[0][k] > c.columns[0][k - 1]))
      throw Error(file + ":" + std::to_string(c.lines[k]) + ": times must increase (" +
                  std::to_string(c.columns[0][k]) + " after " + std::to_string(c.columns[0][k - 1]) + ")");
  for (auto& t : c.columns[0]) t += shift;
  for (auto& v : c.columns[1]) v *= scale;
  auto history = std::make_shared<TableHistory>(std::move(c.columns[0]), std::move(c.columns[1]), file);
  push_object(L, HistoryObject{std::move(history)});
  return 1;
}

// The table behind a history, for the calls that need one.
const TableHistory& table_of(lua_State* L, const char* what) {
  const auto* t = dynamic_cast<const TableHistory*>(self<HistoryObject>(L).history.get());
  if (!t)
    throw Error(std::string(what) + " needs a tabulated history (table, csv or record), not a function or constant");
  return *t;
}

double peak(const std::vector<double>& x) {
  double p = 0.0;
  for (double v : x) p = std::max(p, std::abs(v));
  return p;
}

int history_peak(lua_State* L) {
  lua_pushnumber(L, peak(table_of(L, "peak").values()));
  return 1;
}

int history_duration(lua_State* L) {
  const auto& t = table_of(L, "duration");
  lua_pushnumber(L, t.end() - t.start());
  return 1;
}

int history_write_csv(lua_State* L) {
  const auto& t = table_of(L, "write_csv");
  if (lua_type(L, 2) != LUA_TSTRING)
    throw Error("expects a file name (a string)");  // before lua_tostring converts numbers
  const char* file = lua_tostring(L, 2);
  check_writable(L, file, "");
  std::ostringstream os;
  os.precision(10);
  os << "t,value\n";
  for (std::size_t k = 0; k < t.times().size(); ++k) os << t.times()[k] << ',' << t.values()[k] << '\n';
  write_file_atomically(file, os.str());
  return 0;
}

// The record's velocity (or acceleration), and what tostring(h) reports about it.
std::vector<double> record_values(const AccelerationRecord& record, bool velocity, Baseline baseline,
                                  std::ostringstream& about) {
  if (!velocity) return record.a;
  const auto raw = integrate_record(record, Baseline::None);
  const auto cor = integrate_record(record, baseline);
  about << "; velocity: peak " << peak(raw.v) << " m/s, end " << raw.v.back() << " m/s, end displacement "
        << raw.d.back() << " m";
  if (baseline != Baseline::None)
    about << "; after the " << (baseline == Baseline::Linear ? "linear" : "quadratic") << " baseline: peak "
          << peak(cor.v) << " m/s, end " << cor.v.back() << " m/s, end displacement " << cor.d.back() << " m";
  return cor.v;
}

// mpm.history.at2{ file, integrate = "velocity", baseline = "none", scale = 1, units = "g", format }
int history_at2(lua_State* L) {
  const Args a(L, 1, kAt2Keys);
  const std::string file = data_path(L, a.string("file"));
  check_readable(L, file, "key 'file'");
  const bool is_at2 =
      file.size() > 4 && (file.substr(file.size() - 4) == ".AT2" || file.substr(file.size() - 4) == ".at2");
  const std::string format = a.choice("format", is_at2 ? "at2" : "columns");
  const std::string units = a.choice("units");
  if (format == "at2" && units != "g") throw Error("key 'units': AT2 files are in g");
  const double to_si = units == "g" ? kStandardGravity : units == "gal" ? 0.01 : 1.0;
  AccelerationRecord record = format == "at2" ? read_at2(file) : read_acceleration_columns(file, to_si);
  const double scale = a.number("scale");
  for (double& v : record.a) v *= scale;
  std::ostringstream about;
  about.precision(4);
  about << file << " (PGA " << peak(record.a) / kStandardGravity << " g";
  auto values = record_values(record, a.choice("integrate") == "velocity", parse_baseline(a.choice("baseline")), about);
  about << ")";
  auto history = std::make_shared<TableHistory>(std::move(record.t), std::move(values), about.str());
  push_object(L, HistoryObject{std::move(history)});
  return 1;
}

// mpm.history.fn(function(t) return ... end): evaluated in Lua when asked, never per particle.
int history_fn(lua_State* L) {
  if (!lua_isfunction(L, 1)) throw Error("expects a function of time, function(t) return value end");
  auto function = std::make_shared<const LuaFunction>(L, 1);
  auto history = std::make_shared<FunctionHistory>([function](double t) { return (*function)(t); }, "Lua function");
  push_object(L, HistoryObject{std::move(history)});
  return 1;
}

const Function kHistory[] = {
    {"mpm.history.table", &guarded<history_table>, nullptr, kTableKeys,
     "A piecewise-linear history; zero before the first and after the last point.",
     "local vx = mpm.history.table{ {0, 0}, {0.1, 2}, {5, 2} }"},
    {"mpm.history.csv", &guarded<history_csv>, nullptr, kCsvKeys,
     "A history from two columns of a CSV file, by their names in its header line or by their numbers "
     "(time = 1, value = 2: the header line is then optional); '#' lines are skipped, quoted fields are read. "
     "Errors name the file and line.",
     "local vx = mpm.history.csv{ file = \"data/table_velocity.csv\", time = \"t\", value = \"vx\" }"},
    {"mpm.history.fn",
     &guarded<history_fn>,
     "mpm.history.fn(function(t) return value end)",
     {},
     "A history computed by a Lua function of time (s), called when the history is read (protected: an error, a "
     "yield or a value that is not a number stops the call with an error naming t). A step reads it halfway "
     "through: the function may read models, but changing or stepping one is an error.",
     "local vx = mpm.history.fn(function(t) return 0.1 * math.sin(2 * math.pi * 3 * t) end)"},
    {"mpm.history.at2", &guarded<history_at2>, nullptr, kAt2Keys,
     "A ground-motion record: PEER NGA .AT2 (acceleration in g) or a two-column time, acceleration file (comma or "
     "white space, '#' comments). tostring(h) reports the peak and end values before and after the baseline "
     "correction. Errors name the file and line.",
     "local table = mpm.history.at2{ file = \"data/TCU068-E.AT2\", baseline = \"linear\", scale = 0.5 }"},
    {"history:at", &guarded<history_at>, "h:at(t)", {}, "The history's value at time t (s).", "print(vx:at(0.5))"},
    {"history:peak",
     &guarded<history_peak>,
     "h:peak()",
     {},
     "The largest |value| of a tabulated history.",
     "print(vx:peak())"},
    {"history:duration",
     &guarded<history_duration>,
     "h:duration()",
     {},
     "Time from the first to the last point (s).",
     "print(vx:duration())"},
    {"history:write_csv",
     &guarded<history_write_csv>,
     "h:write_csv(file)",
     {},
     "Writes the points as t,value (atomically).",
     "vx:write_csv(\"out/table_velocity.csv\")"},
};

}  // namespace

std::shared_ptr<const History> to_history(lua_State* L, int index, const std::string& what) {
  if (lua_type(L, index) == LUA_TNUMBER) {
    const double v = lua_tonumber(L, index);
    if (!std::isfinite(v)) throw Error(what + " must be finite");
    return std::make_shared<ConstantHistory>(v);
  }
  if (auto* h = test_object<HistoryObject>(L, index)) return h->history;
  throw Error(what + " must be a number or a history (mpm.history.*), got " + type_name(L, index));
}

std::span<const Function> history_functions() { return kHistory; }

void open_history(lua_State* L) { open_type<HistoryObject, history_tostring>(L, kHistory); }

}  // namespace seismpm::lua
