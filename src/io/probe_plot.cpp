#include "probe_plot.hpp"

#include <filesystem>
#include <sstream>

#include "atomic_file.hpp"
#include "core/error.hpp"
#include "csv_table.hpp"
#include "gnuplot.hpp"
#include "text_lines.hpp"

namespace seismpm {

namespace {

std::string describe(const std::string& q) {
  if (q == "ux") return "Horizontal displacement";
  if (q == "uy") return "Vertical displacement";
  if (q == "vx") return "Horizontal velocity";
  if (q == "vy") return "Vertical velocity";
  if (q == "pressure") return "Mean pressure";
  if (q == "q") return "Deviatoric stress q";
  return q;
}

}  // namespace

std::string field_unit(const std::string& f) {
  if (f == "x" || f == "y" || f == "z" || f[0] == 'u') return "m";
  if (f[0] == 'v' && f.size() == 2) return "m/s";
  if (f == "volume") return "m^3";
  if (f == "mass") return "kg";
  if (f == "density") return "kg/m^3";
  if ((f[0] == 's' && f.size() == 3) || f == "pressure" || f == "q") return "Pa";
  return "-";
}

std::vector<std::pair<std::size_t, std::string>> probe_columns(const std::string& csv, const std::string& q) {
  if (!std::filesystem::is_regular_file(csv))
    throw OutputError("cannot plot: " + csv + " does not exist (a model with probes and m:output writes it)");
  TextLines in(csv);
  std::string header;
  in.next(header);
  std::vector<std::string> columns;
  try {
    columns = split_csv_fields(header);  // probe names may hold commas and quotes
  } catch (const InputError& e) {
    throw OutputError(csv + ":1: " + e.what());
  }
  if (columns.size() < 2 || columns[0] != "time (s)")
    throw OutputError(csv + ":1: not a probes file (the first column must be 'time (s)')");
  std::vector<std::pair<std::size_t, std::string>> out;
  for (std::size_t c = 1; c < columns.size(); ++c) {
    const auto dot = columns[c].rfind('.');
    if (dot != std::string::npos && columns[c].substr(dot + 1) == q) out.emplace_back(c + 1, columns[c].substr(0, dot));
  }
  return out;
}

std::vector<std::string> plot_probes(const std::string& dir, const std::vector<std::string>& quantities) {
  const std::string csv = dir + "/probes.csv";
  probe_columns(csv, "");  // a probes file, before gnuplot is looked for
  require_gnuplot();

  std::vector<std::string> written;
  for (const auto& q : quantities) {
    std::ostringstream plot;
    const auto curves = probe_columns(csv, q);
    for (const auto& [column, probe] : curves)
      plot << (column == curves.front().first ? "plot " : ", \\\n     ") << gnuplot_quote(csv)
           << " every ::1 using 1:" << column << " with lines lw 2 title " << gnuplot_quote(probe);
    if (curves.empty()) throw InputError("cannot plot '" + q + "': no probe column ends in ." + q + " in " + csv);
    const std::string png = dir + "/probe_" + q + ".png";
    std::ostringstream script;
    script << "set terminal pngcairo size 960,540 noenhanced font 'sans,11'\n"
           << "set output " << gnuplot_quote(png + ".tmp") << "\n"
           << "set datafile separator ','\n"
           << "set title " << gnuplot_quote(describe(q) + " of the control points") << "\n"
           << "set xlabel 'time (s)'\nset ylabel " << gnuplot_quote(q + " (" + field_unit(q) + ")") << "\n"
           << "set grid\nset key top left\n"
           << plot.str() << "\n";
    run_gnuplot(script.str(), png);
    written.push_back(png);
  }
  return written;
}

}  // namespace seismpm
