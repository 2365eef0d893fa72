#include "probe_plot.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>

#include "atomic_file.hpp"
#include "core/error.hpp"
#include "csv_plot.hpp"
#include "csv_table.hpp"
#include "gnuplot.hpp"
#include "phases_file.hpp"
#include "text_lines.hpp"

namespace seismpm {

namespace {

std::string describe(const std::string& q) {
  if (q == "ux") return "Horizontal displacement";
  if (q == "uy") return "Vertical displacement";
  if (q == "vx") return "Horizontal velocity";
  if (q == "vy") return "Vertical velocity";
  if (q == "sxx" || q == "syy" || q == "szz") return "Normal stress";
  if (q == "sxy" || q == "syz" || q == "sxz") return "Shear stress";
  if (q == "pressure") return "Mean pressure";
  if (q == "q") return "Deviatoric stress";
  if (q == "shear_strain") return "Shear strain";
  if (q == "plastic_strain") return "Plastic strain";
  return "";
}

// "gravity" -> "gravity phase"; the name of a phase as a label.
std::string phase_label(const std::string& phase) { return phase == "run" ? "before the phases" : phase + " phase"; }

// A phase that began before t0 (the time axis's zero): shaded.
bool before_zero(const PhaseStart& p, double t0) { return p.start < t0 && !same_start(p.start, t0); }

// Settings that mark the phases on a time axis whose zero is model time t0 (the shaking's start, or
// 0): phases before t0 shaded and named, the start of each later phase (but the first) a dashed line.
std::string phase_marks(const std::vector<PhaseStart>& phases, double t0) {
  std::ostringstream os;
  os.precision(12);
  const std::string label_style = " left offset 0.5,0 font 'sans,9' tc rgb '#404040'\n";
  int object = 1;
  for (std::size_t k = 0; k < phases.size(); ++k) {
    const double from = phases[k].start - t0;
    if (before_zero(phases[k], t0)) {
      // Named on the time axis's label (shaded_phases), not in the band: a gravity phase is often a
      // sliver beside the shaking, and its name written there would lie over the next phase's curves.
      const double to = std::min(k + 1 < phases.size() ? phases[k + 1].start : t0, t0) - t0;
      os << "set object " << object++ << " rectangle from first " << from << ", graph 0 to first " << to
         << ", graph 1 behind fillcolor rgb '#e6e6e6' fillstyle solid 1.0 noborder\n";
    } else if (k > 0 && !same_start(phases[k].start, t0)) {
      os << "set arrow from first " << from << ", graph 0 to first " << from
         << ", graph 1 nohead dt 2 lc rgb '#606060'\nset label "
         << gnuplot_quote(phase_label(phases[k].phase) + " begins") << " at first " << from << ", graph 0.97"
         << label_style;
    }
  }
  return os.str();
}

// "; shaded: gravity phase" for the phases that phase_marks shades (those before t0), or "".
std::string shaded_phases(const std::vector<PhaseStart>& phases, double t0) {
  std::string names;
  for (const auto& p : phases)
    if (before_zero(p, t0)) names += (names.empty() ? "" : ", ") + phase_label(p.phase);
  return names.empty() ? "" : "; shaded: " + names;
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

std::string probe_plot_body(const std::string& dir, const std::string& q,
                            const std::vector<ProbeReference>& references) {
  const std::string csv = dir + "/probes.csv";
  const auto curves = probe_columns(csv, q);
  if (curves.empty()) throw InputError("cannot plot '" + q + "': no probe column ends in ." + q + " in " + csv);
  const auto phases = read_phases(dir);
  const double t0 = shaking_start(phases);
  const bool shaking = t0 == t0;  // not NaN: the run had a dynamic phase
  std::ostringstream time;        // the x of a row: its model time, less the shaking's start
  time.precision(15);
  if (shaking)
    time << "($1 - " << t0 << ")";
  else
    time << "1";

  std::ostringstream plot;
  for (const auto& [column, probe] : curves)
    plot << (column == curves.front().first ? "plot " : ", \\\n     ") << gnuplot_quote(csv) << " every ::1 using "
         << time.str() << ':' << column << " with lines lw 2 title " << gnuplot_quote(probe);
  for (const auto& r : references) {
    if (r.quantity != q) continue;
    const CsvHeader header(r.csv);
    plot << ", \\\n     " << gnuplot_quote(r.csv) << " every ::1 using " << header.column(r.x) << ':'
         << header.column(r.y) << " with lines lw 2 dt 2 lc rgb 'black' title "
         << gnuplot_quote(r.title.empty() ? r.y : r.title);
  }
  const std::string what = describe(q);
  std::ostringstream body;
  body << "set title " << gnuplot_quote((what.empty() ? q : what) + " of the control points") << "\n"
       << "set xlabel "
       << gnuplot_quote(shaking             ? "time since the dynamic phase began (s)" + shaded_phases(phases, t0)
                        : phases.size() > 1 ? "model time (s)"
                                            : "time (s)")
       << "\nset ylabel " << gnuplot_quote((what.empty() ? "" : what + " ") + q + " (" + field_unit(q) + ")") << "\n"
       << phase_marks(phases, shaking ? t0 : 0.0) << plot.str() << "\n";
  return body.str();
}

std::vector<std::string> plot_probes(const std::string& dir, const std::vector<std::string>& quantities,
                                     const std::vector<ProbeReference>& references) {
  probe_columns(dir + "/probes.csv", "");                         // a probes file, before gnuplot is looked for
  for (const auto& r : references) CsvHeader(r.csv).column(r.y);  // before any picture is drawn
  require_gnuplot();
  std::vector<std::string> written;
  for (const auto& q : quantities) {
    const std::string body = probe_plot_body(dir, q, references);
    const std::string png = dir + "/probe_" + q + ".png";
    run_gnuplot(body, png);
    written.push_back(png);
  }
  return written;
}

}  // namespace seismpm
