// mpm.plot: a PNG line plot of CSV columns (gnuplot).
#include "binding.hpp"
#include "io/csv_plot.hpp"
#include "objects.hpp"

namespace seismpm::lua {

namespace {

// mpm.plot{ file, x, y = {...}, png, title, xlabel, ylabel, color } -> png path
int plot(lua_State* L) {
  Args a(L, 1, {"file", "x", "y", "png", "title", "xlabel", "ylabel", "color"});
  CsvPlot p;
  p.csv = a.string("file");
  p.x = a.string("x");
  const auto y = a.names("y");
  if (!y || y->empty()) throw Error("missing key 'y' (a list of column names)");
  p.y = *y;
  const std::string stem = p.csv.size() > 4 && p.csv.substr(p.csv.size() - 4) == ".csv" ? p.csv.substr(0, p.csv.size() - 4) : p.csv;
  p.png = a.string("png", stem + ".png");
  p.title = a.string("title", "");
  p.xlabel = a.string("xlabel", "");
  p.ylabel = a.string("ylabel", "");
  p.color = a.string("color", "");
  plot_csv(p);
  lua_pushstring(L, p.png.c_str());
  return 1;
}

}  // namespace

void open_plot(lua_State* L, int mpm) { set_function<plot>(L, mpm, "plot", "mpm.plot"); }

}  // namespace seismpm::lua
