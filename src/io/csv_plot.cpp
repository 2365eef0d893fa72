#include "csv_plot.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "atomic_file.hpp"
#include "core/error.hpp"

namespace seismpm {

namespace {

std::string quote(const std::string& s) {  // gnuplot single-quoted string
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

void plot_csv(const CsvPlot& p) {
  std::ifstream in(p.csv);
  if (!in) throw InputError("cannot plot: " + p.csv + " cannot be opened");
  std::string header;
  while (std::getline(in, header) && (header.empty() || header[0] == '#')) {
  }  // '#' lines are comments, for gnuplot too
  std::vector<std::string> columns;
  {
    std::istringstream hs(header);
    for (std::string c; std::getline(hs, c, ',');) columns.push_back(c);
  }
  auto column = [&](const std::string& name) {
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (columns[c] == name) return c + 1;  // gnuplot counts from 1
    throw InputError(p.csv + ":1: no column '" + name + "' (the header is: " + header + ")");
  };
  const std::size_t xc = column(p.x);
  if (p.y.empty()) throw InputError("cannot plot: no y columns given");
  std::ostringstream plot;
  if (!p.color.empty()) {
    plot << "set size ratio -1\nset cblabel " << quote(p.color) << "\nset palette rgb 33,13,10\nplot " << quote(p.csv)
         << " every ::1 using " << xc << ':' << column(p.y.front()) << ':' << column(p.color)
         << " with points pt 7 ps 0.35 palette notitle";
  } else {
    for (std::size_t k = 0; k < p.y.size(); ++k)
      plot << (k ? ", \\\n     " : "plot ") << quote(p.csv) << " every ::1 using " << xc << ':' << column(p.y[k])
           << " with lines lw 2 title " << quote(p.y[k]);
  }
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0)
    throw OutputError("cannot plot: gnuplot is not installed (apt-get install gnuplot-nox)");
  std::ostringstream script;
  script << "set terminal pngcairo size 960,540 noenhanced font 'sans,11'\n"
         << "set output " << quote(p.png + ".tmp") << "\n"
         << "set datafile separator ','\n"
         << "set title " << quote(p.title) << "\n"
         << "set xlabel " << quote(p.xlabel.empty() ? p.x : p.xlabel) << "\n"
         << "set ylabel " << quote(p.ylabel.empty() ? p.y.front() : p.ylabel) << "\n"
         << "set grid\nset key top left\n"
         << plot.str() << "\n";
  const std::string script_path = p.png + ".gp";
  write_file_atomically(script_path, script.str());
  const std::string log = p.png + ".log";
  const int rc = std::system(("gnuplot " + shell_quote(script_path) + " 2>" + shell_quote(log)).c_str());
  std::remove(script_path.c_str());
  if (rc != 0) throw OutputError("gnuplot failed drawing " + p.png + " (see " + log + ")");
  std::remove(log.c_str());
  commit_file(p.png + ".tmp", p.png);
}

}  // namespace seismpm
