// mpm.plot: a line plot of CSV columns (gnuplot), PNG and SVG.
#include "api_docs.hpp"
#include "binding.hpp"
#include "io/csv_plot.hpp"
#include "objects.hpp"
#include "sandbox.hpp"

namespace seismpm::lua {

namespace {

const Key kPlotKeys[] = {
    arg::string("file", "the CSV file, with a header line ('#' comment lines before it are skipped)").required(),
    arg::string("x", "the column along x (its name in the header)").required(),
    arg::names("y", "the columns plotted against x, one curve each").required(),
    arg::names("reference", "columns drawn against x as dashed black reference curves (a closed form, a measurement)"),
    arg::string("png", "the picture written, with an SVG of the same name beside it").shown("the CSV's name with .png"),
    arg::string("title", "the plot's title").def_text(""),
    arg::string("xlabel", "the x axis' label, with its unit: \"time since the dynamic phase began (s)\"").shown("x"),
    arg::string("ylabel", "the y axis' label, with its unit").shown("the first y column"),
    arg::string("color", "a column: one point per row at (x, y[1]) coloured by it, axes to scale").def_text(""),
};

// mpm.plot{ file, x, y = {...}, reference = {...}, png, title, xlabel, ylabel, color } -> png path
int plot(lua_State* L) {
  const Args a(L, 1, kPlotKeys);
  CsvPlot p;
  p.csv = a.string("file");
  p.x = a.string("x");
  p.y = *a.names("y");
  if (auto r = a.names("reference")) p.reference = *r;
  const std::string stem =
      p.csv.size() > 4 && p.csv.substr(p.csv.size() - 4) == ".csv" ? p.csv.substr(0, p.csv.size() - 4) : p.csv;
  p.png = a.string("png", stem + ".png");
  p.title = a.string("title");
  p.xlabel = a.string("xlabel", "");
  p.ylabel = a.string("ylabel", "");
  p.color = a.string("color");
  const std::pair<const char*, const std::string*> texts[] = {
      {"file", &p.csv},      {"x", &p.x},           {"png", &p.png},    {"title", &p.title},
      {"xlabel", &p.xlabel}, {"ylabel", &p.ylabel}, {"color", &p.color}};
  for (const auto& [key, text] : texts) refuse_control_characters(*text, std::string("key '") + key + "'");
  for (const auto& y : p.y) refuse_control_characters(y, "key 'y'");
  for (const auto& r : p.reference) refuse_control_characters(r, "key 'reference'");
  check_readable(L, p.csv, "key 'file'");
  check_writable(L, p.png, "key 'png'");
  plot_csv(p);
  lua_pushstring(L, p.png.c_str());
  return 1;
}

const Function kPlot[] = {
    {"mpm.plot", &guarded<plot>, nullptr, kPlotKeys,
     "A line plot (gnuplot) of columns of a CSV file, as a PNG and an SVG beside it; returns the PNG's path. The "
     "key (legend) sits outside the curves and only when there are two or more; the curves keep a margin from the "
     "frame. Give the axis labels their units.",
     "mpm.plot{ file = \"out/block/motion.csv\", x = \"time (s)\", y = {\"ux (m)\"}, reference = {\"closed form "
     "(m)\"}, "
     "ylabel = \"displacement (m)\", title = \"Block\" }"},
};

}  // namespace

std::span<const Function> plot_functions() { return kPlot; }

void open_plot(lua_State* L) { register_functions(L, kPlot); }

}  // namespace seismpm::lua
