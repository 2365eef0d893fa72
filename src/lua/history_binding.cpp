// mpm.history.*: time histories (velocity records, load factors) and h:at(t).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>

#include "api_docs.hpp"
#include "binding.hpp"
#include "core/error.hpp"
#include "core/parameter.hpp"
#include "io/atomic_file.hpp"
#include "io/csv_plot.hpp"
#include "io/csv_table.hpp"
#include "io/ground_motion.hpp"
#include "io/record_processing.hpp"
#include "lua_function.hpp"
#include "methods/response_spectrum.hpp"
#include "objects.hpp"
#include "sandbox.hpp"
#include "session.hpp"

namespace seismpm::lua {

namespace {

const Key kTableKeys[] = {arg::positional("{t, v}, {t, v}, ...", "the points: times (s) must increase")};

// The record processing keys of mpm.history.at2 and mpm.history.csv (kind = "acceleration"), applied
// in this order: window, taper, scale or pga, baseline, integrate.
constexpr Key kWindowKey =
    arg::custom("window", "{t0, t1}", "s",
                "only this part of the record is kept (t0 < t1, within the record); t0 becomes time 0, an end "
                "between two samples gets a sample interpolated there")
        .shown("the whole record");
constexpr Key kTaperKey = arg::number("taper", "s",
                                      "a half-cosine (Tukey) taper of the acceleration over this long at each end "
                                      "(after the window): the record starts and ends at zero; at most half its "
                                      "length")
                              .def(0)
                              .checked_by_kernel(at_least(0));
constexpr Key kPgaKey = arg::number("pga", "g",
                                    "scales the acceleration (after the taper) so that its peak |a| is this; "
                                    "not with scale")
                            .checked_by_kernel(above(0))
                            .shown("as recorded");
constexpr Key kAccelerationScaleKey = arg::number("scale", "", "factor on the acceleration; not with pga").def(1);
constexpr Key kIntegrateKey =
    arg::choice("integrate", "velocity|none", "velocity",
                "velocity (trapezoidal rule) or none (the acceleration, m/s2, after any baseline correction)");
constexpr Key kBaselineKey =
    arg::choice("baseline", "none|linear|quadratic", "none",
                "after the window, taper and scale: linear removes the drift so velocity and displacement end at "
                "zero; quadratic first removes a least-squares quadratic trend of the velocity");

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
    arg::choice("kind", "plain|acceleration", "plain",
                "plain: the values as they are (a velocity, a load factor); acceleration: a ground acceleration "
                "record in `units`, processed as mpm.history.at2 processes one (the keys units, taper, pga, "
                "baseline and integrate are for it only)"),
    arg::choice("units", "g|m/s2|gal", "g", "units of an acceleration record (kind = \"acceleration\")"),
    kWindowKey,
    kTaperKey,
    kPgaKey,
    arg::number("scale", "", "factor on the values (on the acceleration of an acceleration record; not with pga)")
        .def(1),
    kBaselineKey,
    kIntegrateKey,
    arg::number("shift", "s", "added to the times, last (after the window)").def(0),
};
const Key kAt2Keys[] = {
    arg::string("file", "the record: PEER NGA .AT2 (in g) or two columns time, acceleration").required(),
    kIntegrateKey,
    kBaselineKey,
    kWindowKey,
    kTaperKey,
    kPgaKey,
    kAccelerationScaleKey,
    arg::choice("units", "g|m/s2|gal", "g", "units of a columns file (AT2 files are in g)"),
    arg::choice("format", "at2|columns", "", "the file's format").shown("from the extension (.AT2: at2)"),
};
const Key kSpectrumKeys[] = {
    arg::string("file",
                "the CSV written (atomically), columns period (s),Sa (g),Sv (m/s),Sd (m), with a plot of Sa "
                "against the period (log axis) as a PNG and an SVG beside it")
        .shown("none: only the table returned"),
    arg::number("damping", "", "the oscillators' ratio of critical damping")
        .def(0.05)
        .checked_by_kernel(closed_open(0, 1)),
    arg::custom("periods", "{T, T, ...}", "s", "the oscillators' natural periods, > 0 and increasing")
        .shown("100 periods log-spaced from 0.02 to 5 s"),
    arg::string("png", "the plot written with the CSV (an SVG of the same name beside it)")
        .shown("the CSV's name with .png"),
    arg::boolean("plot", true, "false: the CSV without the plot (gnuplot is then not needed)"),
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

// key 'window': {t0, t1} in seconds, or nullopt when absent.
std::optional<std::pair<double, double>> window_key(const Args& a) {
  lua_State* L = a.state();
  if (!a.has("window")) return std::nullopt;
  a.push("window");
  const std::string got = type_name(L, -1);
  bool ok = lua_type(L, -1) == LUA_TTABLE && lua_rawlen(L, -1) == 2;
  double t[2] = {0, 0};
  for (int i = 0; ok && i < 2; ++i) {
    ok = lua_rawgeti(L, -1, i + 1) == LUA_TNUMBER;
    t[i] = lua_tonumber(L, -1);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  if (!ok) throw Error("key 'window' must be {t0, t1}, two times (s), got " + got);
  return std::make_pair(t[0], t[1]);
}

// A record's values for a history after the processing keys (window, taper, scale or pga, baseline,
// integrate), the acceleration as used, and what tostring(h) reports about them.
struct ProcessedRecord {
  std::vector<double> t, values;
  std::shared_ptr<const AccelerationRecord> acceleration;
  std::string about;
};

// The keys' combinations, checked before the file is read.
void check_scale_keys(const Args& a) {
  if (a.has("pga") && a.has("scale"))
    throw ParameterError({"scale", "pga"},
                         "cannot both be given: pga scales the record to a peak acceleration, scale by a factor");
}

ProcessedRecord process_record(const Args& a, AccelerationRecord record) {
  std::ostringstream about;
  about.precision(4);
  about << record.source << " (";
  if (const auto w = window_key(a)) {
    record = window_record(record, w->first, w->second);
    about << "window " << w->first << " .. " << w->second << " s, ";
  }
  const double taper = a.number("taper");
  taper_record(record, taper);
  if (taper > 0) about << "taper " << taper << " s, ";
  if (a.has("pga")) {
    scale_to_pga(record, a.number("pga"));
    about << "scaled to ";
  } else if (const double scale = a.number("scale"); scale != 1.0) {
    for (double& v : record.a) v *= scale;
    about << "scaled by " << scale << ", ";
  }
  about << "PGA " << peak_magnitude(record.a) / kStandardGravity << " g";
  const Baseline baseline = parse_baseline(a.choice("baseline"));
  const auto raw = integrate_record(record, Baseline::None);
  auto used = integrate_record(record, baseline);
  const bool velocity = a.choice("integrate") == "velocity";
  if (velocity || baseline != Baseline::None) {
    about << "; velocity: peak " << peak_magnitude(raw.v) << " m/s, end " << raw.v.back() << " m/s, end displacement "
          << raw.d.back() << " m";
    if (baseline != Baseline::None)
      about << "; after the " << (baseline == Baseline::Linear ? "linear" : "quadratic") << " baseline: peak "
            << peak_magnitude(used.v) << " m/s, end " << used.v.back() << " m/s, end displacement " << used.d.back()
            << " m";
  }
  about << ")";
  auto acceleration = std::make_shared<AccelerationRecord>(AccelerationRecord{used.t, used.a, record.source});
  return {std::move(used.t), velocity ? std::move(used.v) : used.a, std::move(acceleration), about.str()};
}

// A history made from a ground acceleration record, with the acceleration as used (windowed, tapered,
// scaled, corrected): what h:arias() and h:spectrum{} read. Elsewhere it is a table like any other.
class RecordHistory final : public TableHistory {
 public:
  RecordHistory(std::vector<double> t, std::vector<double> values, std::string about,
                std::shared_ptr<const AccelerationRecord> acceleration)
      : TableHistory(std::move(t), std::move(values), std::move(about)), acceleration_(std::move(acceleration)) {}
  const AccelerationRecord& acceleration() const { return *acceleration_; }

 private:
  std::shared_ptr<const AccelerationRecord> acceleration_;
};

void push_history(lua_State* L, std::vector<double> t, std::vector<double> values, const std::string& about,
                  std::shared_ptr<const AccelerationRecord> acceleration = nullptr) {
  std::shared_ptr<const History> history;
  if (acceleration)
    history = std::make_shared<RecordHistory>(std::move(t), std::move(values), about, std::move(acceleration));
  else
    history = std::make_shared<TableHistory>(std::move(t), std::move(values), about);
  push_object(L, HistoryObject{std::move(history)});
}

// The keys that make sense for an acceleration record only: named when a plain column has them.
void refuse_acceleration_keys(const Args& a) {
  for (const char* key : {"units", "taper", "pga", "baseline", "integrate"})
    if (a.has(key))
      throw Error("key '" + std::string(key) +
                  "' is for an acceleration record: add kind = \"acceleration\" (a plain column's values are "
                  "used as they are)");
}

// mpm.history.csv{file =, time = "t" or 1, value = "v" or 2, kind = "plain", scale = 1, shift = 0, ...}
int history_csv(lua_State* L) {
  const Args a(L, 1, kCsvKeys);
  const CsvColumn time = column_key(a, "time", "t"), value = column_key(a, "value", nullptr);
  const bool acceleration = a.choice("kind") == "acceleration";
  if (!acceleration) refuse_acceleration_keys(a);
  check_scale_keys(a);
  const std::string file = data_path(L, a.string("file"));
  check_readable(L, file, "key 'file'");
  auto c = read_csv_columns(file, {time, value});
  for (std::size_t k = 1; k < c.columns[0].size(); ++k)
    if (!(c.columns[0][k] > c.columns[0][k - 1]))
      throw Error(file + ":" + std::to_string(c.lines[k]) + ": times must increase (" +
                  std::to_string(c.columns[0][k]) + " after " + std::to_string(c.columns[0][k - 1]) + ")");
  if (c.columns[0].size() < 2 && (acceleration || a.has("window")))
    throw Error(file + ": a record needs at least 2 rows, the file has " + std::to_string(c.columns[0].size()));
  // The cut works on any tabulated values: the record type only carries them.
  AccelerationRecord record{std::move(c.columns[0]), std::move(c.columns[1]), file};
  const double shift = a.number("shift");
  if (acceleration) {
    const std::string units = a.choice("units");
    const double to_si = units == "g" ? kStandardGravity : units == "gal" ? 0.01 : 1.0;
    for (double& v : record.a) v *= to_si;
    auto r = process_record(a, std::move(record));
    for (auto& t : r.t) t += shift;
    push_history(L, std::move(r.t), std::move(r.values), r.about, std::move(r.acceleration));
    return 1;
  }
  std::string about = file;
  if (const auto w = window_key(a)) {
    record = window_record(record, w->first, w->second);
    std::ostringstream os;
    os << file << " (window " << w->first << " .. " << w->second << " s)";
    about = os.str();
  }
  const double scale = a.number("scale");
  for (auto& t : record.t) t += shift;
  for (auto& v : record.a) v *= scale;
  push_history(L, std::move(record.t), std::move(record.a), about);
  return 1;
}

// The table behind a history, for the calls that need one.
const TableHistory& table_of(lua_State* L, const char* what) {
  const auto* t = dynamic_cast<const TableHistory*>(self<HistoryObject>(L).history.get());
  if (!t)
    throw Error(std::string(what) + " needs a tabulated history (table, csv or record), not a function or constant");
  return *t;
}

int history_peak(lua_State* L) {
  lua_pushnumber(L, peak_magnitude(table_of(L, "peak").values()));
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

// mpm.history.at2{ file, integrate = "velocity", baseline = "none", window, taper, pga, scale = 1, units = "g",
// format }
int history_at2(lua_State* L) {
  const Args a(L, 1, kAt2Keys);
  check_scale_keys(a);
  const std::string file = data_path(L, a.string("file"));
  check_readable(L, file, "key 'file'");
  const bool is_at2 =
      file.size() > 4 && (file.substr(file.size() - 4) == ".AT2" || file.substr(file.size() - 4) == ".at2");
  const std::string format = a.choice("format", is_at2 ? "at2" : "columns");
  const std::string units = a.choice("units");
  if (format == "at2" && units != "g") throw Error("key 'units': AT2 files are in g");
  const double to_si = units == "g" ? kStandardGravity : units == "gal" ? 0.01 : 1.0;
  auto r = process_record(a, format == "at2" ? read_at2(file) : read_acceleration_columns(file, to_si));
  push_history(L, std::move(r.t), std::move(r.values), r.about, std::move(r.acceleration));
  return 1;
}

// The history with the acceleration behind it, for h:arias() and h:spectrum{}; held by the caller.
std::shared_ptr<const RecordHistory> record_of(lua_State* L) {
  const auto& h = self<HistoryObject>(L).history;
  auto record = std::dynamic_pointer_cast<const RecordHistory>(h);
  if (!record)
    throw Error(
        "needs a history made from an acceleration record (mpm.history.at2, or mpm.history.csv with "
        "kind = \"acceleration\"), not " +
        h->describe());
  return record;
}

// h:arias() -> Arias intensity (m/s)
int history_arias(lua_State* L) {
  const auto record = record_of(L);
  const AccelerationRecord& r = record->acceleration();
  lua_pushnumber(L, arias_intensity(r.t, r.a));
  return 1;
}

// key 'periods': a list of increasing periods (s).
std::vector<double> periods_key(const Args& a) {
  if (!a.has("periods")) return log_spaced_periods();
  lua_State* L = a.state();
  a.push("periods");
  const std::string got = type_name(L, -1);
  constexpr lua_Integer kMostPeriods = 10000;  // each one is a pass over the record
  const lua_Integer n = lua_type(L, -1) == LUA_TTABLE ? static_cast<lua_Integer>(lua_rawlen(L, -1)) : 0;
  if (n < 1 || n > kMostPeriods) {
    lua_pop(L, 1);
    throw Error("key 'periods' must be a list of 1 to " + std::to_string(kMostPeriods) + " periods (s), got " +
                (got == "table" ? "a table of " + std::to_string(n) : got));
  }
  std::vector<double> periods;
  for (lua_Integer i = 1; i <= n; ++i) {
    const bool number = lua_rawgeti(L, -1, i) == LUA_TNUMBER;
    const double p = lua_tonumber(L, -1);
    lua_pop(L, 1);
    if (!number || !(p > 0) || !std::isfinite(p) || (i > 1 && !(p > periods.back()))) {
      lua_pop(L, 1);
      std::ostringstream os;
      os << "key 'periods': entry " << i << " must be a period (s) > 0";
      if (i > 1) os << " and above the one before (" << periods.back() << ")";
      if (number) os << ", got " << p;
      throw Error(os.str());
    }
    periods.push_back(p);
  }
  lua_pop(L, 1);
  return periods;
}

std::string spectrum_csv(const std::vector<SpectrumOrdinate>& spectrum) {
  std::ostringstream os;
  os.precision(10);
  os << "period (s),Sa (g),Sv (m/s),Sd (m)\n";
  for (const auto& o : spectrum) os << o.period << ',' << o.sa / kStandardGravity << ',' << o.sv << ',' << o.sd << '\n';
  return os.str();
}

// h:spectrum{ file, damping = 0.05, periods, png, plot = true } -> { {T, Sa (g)}, ... }
int history_spectrum(lua_State* L) {
  const auto record = record_of(L);
  const AccelerationRecord& r = record->acceleration();
  if (lua_isnoneornil(L, 2)) {  // h:spectrum(): every default
    lua_settop(L, 1);
    lua_newtable(L);
  }
  const Args a(L, 2, kSpectrumKeys);
  const double damping = a.number("damping");
  const auto periods = periods_key(a);
  const auto spectrum = response_spectrum(r.t, r.a, periods, damping);
  if (a.has("file")) {
    const std::string file = a.string("file");
    refuse_control_characters(file, "key 'file'");
    check_writable(L, file, "key 'file'");
    const bool draw = a.boolean("plot");
    CsvPlot p;
    if (draw) {
      const std::string stem =
          file.size() > 4 && file.substr(file.size() - 4) == ".csv" ? file.substr(0, file.size() - 4) : file;
      p.png = a.string("png", stem + ".png");
      refuse_control_characters(p.png, "key 'png'");
      check_writable(L, p.png, "key 'png'");
    } else if (a.has("png")) {
      throw Error("key 'png' asks for a plot, but plot = false");
    }
    const auto dir = std::filesystem::path(file).parent_path();
    if (!dir.empty()) ensure_directory(dir.string());
    write_file_atomically(file, spectrum_csv(spectrum));
    if (draw) {
      std::ostringstream title;
      title << "Response spectrum, " << damping * 100
            << " % damping: " << std::filesystem::path(r.source).filename().string();
      p.csv = file;
      p.x = "period (s)";
      p.y = {"Sa (g)"};
      p.title = title.str();
      p.ylabel = "pseudo-spectral acceleration Sa (g)";
      p.log_x = true;
      plot_csv(p);
    }
  }
  lua_createtable(L, static_cast<int>(spectrum.size()), 0);
  for (std::size_t k = 0; k < spectrum.size(); ++k) {
    lua_createtable(L, 2, 0);
    lua_pushnumber(L, spectrum[k].period);
    lua_rawseti(L, -2, 1);
    lua_pushnumber(L, spectrum[k].sa / kStandardGravity);
    lua_rawseti(L, -2, 2);
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
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
     "(time = 1, value = 2: the header line is then optional); '#' lines are skipped, quoted fields are read, a "
     "UTF-8 byte order mark and CRLF line ends are accepted. Errors name the file and line. The values are used as "
     "they are (scale, then shift; a window cuts the part wanted); with kind = \"acceleration\" the column is a "
     "ground acceleration record, processed as mpm.history.at2 processes one: window, taper, scale or pga, "
     "baseline, then integrate (to velocity by default), and h:arias() and h:spectrum{} can read it.",
     "local a = mpm.history.csv{ file = \"data/TCU068-090.csv\", time = 1, value = 2, kind = \"acceleration\", "
     "units = \"g\", window = { 10, 40 }, taper = 1, pga = 0.3, baseline = \"linear\" }"},
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
     "white space, '#' comments). The acceleration is processed in this order: window (the part kept, its start "
     "becoming time 0), taper (the ends brought smoothly to zero), scale or pga, baseline correction, then "
     "integration to velocity (or none: the acceleration). tostring(h) reports what was done, the PGA and the peak "
     "and end values before and after the baseline correction; h:arias() and h:spectrum{} read the acceleration "
     "as used. Errors name the file and line, or the key.",
     "local vx = mpm.history.at2{ file = \"data/TCU068-E.AT2\", window = { 10, 40 }, taper = 1, pga = 0.3, "
     "baseline = \"linear\" }"},
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
    {"history:arias",
     &guarded<history_arias>,
     "h:arias()",
     {},
     "The Arias intensity I_a = pi / (2 g) * integral of a(t)^2 dt (m/s) of the acceleration a history was made "
     "from (mpm.history.at2, or mpm.history.csv with kind = \"acceleration\"), as used: after its window, taper, "
     "scale and baseline correction. An error for any other history.",
     "print(vx:arias())"},
    {"history:spectrum", &guarded<history_spectrum>, nullptr, kSpectrumKeys,
     "The elastic response spectrum of the acceleration a history was made from (as h:arias() reads it): the "
     "peak relative displacement Sd of damped linear oscillators of each period, stepped exactly for an "
     "acceleration linear between the record's samples (Nigam & Jennings 1969), the pseudo-spectral velocity "
     "Sv = omega Sd and acceleration Sa = omega^2 Sd. Returns a list of {period (s), Sa (g)}; with file, also "
     "writes the CSV and a plot of Sa (log period axis). The peaks are taken over the record's duration.",
     "local sa = vx:spectrum{ file = \"out/record/spectrum.csv\", damping = 0.05 }  -- sa[k][1] period, sa[k][2] Sa"},
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
