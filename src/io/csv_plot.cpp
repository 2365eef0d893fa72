#include "csv_plot.hpp"

#include <cstdio>
#include <sstream>

#include "atomic_file.hpp"
#include "core/error.hpp"
#include "csv_table.hpp"
#include "gnuplot.hpp"
#include "text_lines.hpp"

namespace seismpm {

void plot_csv(const CsvPlot& p) {
  if (std::FILE* f = std::fopen(p.csv.c_str(), "rb"))
    std::fclose(f);
  else
    throw InputError("cannot plot: " + p.csv + " cannot be opened");
  TextLines in(p.csv);
  std::string header;
  while (in.next(header) && (header.empty() || header[0] == '#')) {
  }  // '#' lines are comments, for gnuplot too
  std::vector<std::string> columns;
  try {
    columns = split_csv_fields(header);
  } catch (const InputError& e) {
    throw InputError(in.where() + e.what());
  }
  auto column = [&](const std::string& name) {
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (columns[c] == name) return c + 1;  // gnuplot counts from 1
    throw InputError(p.csv + ":" + std::to_string(in.number()) + ": no column '" + printable(name) +
                     "' (the header is: " + printable(header, 200) + ")");
  };
  const std::size_t xc = column(p.x);
  if (p.y.empty()) throw InputError("cannot plot: no y columns given");
  std::ostringstream plot;
  if (!p.color.empty()) {
    plot << "set size ratio -1\nset cblabel " << gnuplot_quote(p.color) << "\nset palette rgb 33,13,10\nplot "
         << gnuplot_quote(p.csv) << " every ::1 using " << xc << ':' << column(p.y.front()) << ':' << column(p.color)
         << " with points pt 7 ps 0.35 palette notitle";
  } else {
    for (std::size_t k = 0; k < p.y.size(); ++k)
      plot << (k ? ", \\\n     " : "plot ") << gnuplot_quote(p.csv) << " every ::1 using " << xc << ':'
           << column(p.y[k]) << " with lines lw 2 title " << gnuplot_quote(p.y[k]);
  }
  std::ostringstream script;
  script << "set terminal pngcairo size 960,540 noenhanced font 'sans,11'\n"
         << "set output " << gnuplot_quote(p.png + ".tmp") << "\n"
         << "set datafile separator ','\n"
         << "set title " << gnuplot_quote(p.title) << "\n"
         << "set xlabel " << gnuplot_quote(p.xlabel.empty() ? p.x : p.xlabel) << "\n"
         << "set ylabel " << gnuplot_quote(p.ylabel.empty() ? p.y.front() : p.ylabel) << "\n"
         << "set grid\nset key top left\n"
         << plot.str() << "\n";
  run_gnuplot(script.str(), p.png);
}

}  // namespace seismpm
