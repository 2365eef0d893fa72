#include "probe_plot.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
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
  if (q == "ux_rel") return "Horizontal displacement relative to the reference";
  if (q == "uy_rel") return "Vertical displacement relative to the reference";
  if (q == "uz_rel") return "Displacement z relative to the reference";
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

namespace {

bool one_of(const std::string& value, const char* choices) {
  std::istringstream in(choices);
  for (std::string c; std::getline(in, c, '|');)
    if (c == value) return true;
  return false;
}

// The phase kept by the options, with its start; none when every row is kept.
std::optional<PhaseStart> kept_phase(const std::string& dir, const std::vector<PhaseStart>& phases,
                                     const ProbePlotOptions& o) {
  const std::string phase = o.phase.empty() && o.x == "phase_time" ? "current" : o.phase;
  if (phase.empty()) return std::nullopt;
  std::string names;
  for (const auto& p : phases) names += (names.empty() ? "" : ", ") + p.phase;
  if (phases.empty())
    throw InputError("phase '" + phase + "': " + dir + "/phases.csv lists no phase (written with the outputs)");
  if (phase == "current") return phases.back();
  for (auto it = phases.rbegin(); it != phases.rend(); ++it)
    if (it->phase == phase) return *it;
  throw InputError("phase '" + phase + "': the run had no such phase (" + dir + "/phases.csv: " + names + ")");
}

// The columns phase and phase_time (s) as gnuplot numbers them; throws InputError for a probes.csv
// without them (written before they were added).
std::pair<std::size_t, std::size_t> phase_columns(const std::string& csv) {
  TextLines in(csv);
  std::string header;
  in.next(header);
  const auto columns = split_csv_fields(header);
  if (columns.size() < 3 || columns[1] != "phase" || columns[2] != "phase_time (s)")
    throw InputError(csv +
                     ":1: no columns 'phase' and 'phase_time (s)' (a probes.csv of an older version): plot it "
                     "with x = \"auto\" or \"time\" and no phase");
  return {2, 3};
}

}  // namespace

std::string probe_plot_body(const std::string& dir, const std::string& q, const std::vector<ProbeReference>& references,
                            const ProbePlotOptions& options) {
  const std::string csv = dir + "/probes.csv";
  if (!one_of(options.x, kProbePlotX))
    throw InputError("x '" + options.x + "': the time axis is one of " + std::string(kProbePlotX));
  if (!options.phase.empty() && !one_of(options.phase, kProbePlotPhases))
    throw InputError("phase '" + options.phase + "': one of " + std::string(kProbePlotPhases));
  const auto curves = probe_columns(csv, q);
  if (curves.empty()) throw InputError("cannot plot '" + q + "': no probe column ends in ." + q + " in " + csv);
  const auto phases = read_phases(dir);
  const auto kept = kept_phase(dir, phases, options);
  const double t0 = shaking_start(phases);
  // The axis: a phase's own time, the model time, or the shaking's time (auto, all rows).
  const bool own_time = options.x == "phase_time" || (options.x == "auto" && kept);
  const bool shaking = options.x == "auto" && !kept && t0 == t0;  // not NaN: the run had a dynamic phase
  std::ostringstream time;  // the x of a row: its model time (less the shaking's start), or its phase time
  time.precision(15);
  if (kept || own_time) {
    const auto [phase_column, phase_time_column] = phase_columns(csv);
    std::ostringstream x;
    x.precision(15);
    if (own_time)
      x << '$' << phase_time_column;
    else
      x << '$' << 1;
    if (kept) {
      // A row of the phase kept: its phase's name, and its phase's start (time - phase_time) that of
      // the last phase of the name (an earlier phase of the same name began earlier).
      const double s = kept->start, tol = 1e-6 * std::max(1.0, std::abs(s));
      time << "((strcol(" << phase_column << ") eq " << gnuplot_quote(kept->phase) << " && abs($1 - $"
           << phase_time_column << " - " << s << ") <= " << tol << ") ? " << x.str() << " : NaN)";
    } else {
      time << x.str();
    }
  } else if (shaking) {
    time << "($1 - " << t0 << ")";
  } else {
    time << "1";
  }

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
  std::string xlabel;
  if (own_time)
    xlabel =
        kept->phase == "run" ? "time since the run began (s)" : "time since the " + kept->phase + " phase began (s)";
  else if (shaking)
    xlabel = "time since the dynamic phase began (s)" + shaded_phases(phases, t0);
  else
    xlabel = phases.size() > 1 || kept ? "model time (s)" : "time (s)";
  std::ostringstream body;
  body << "set title "
       << gnuplot_quote((what.empty() ? q : what) + " of the control points" +
                        (kept ? ", " + phase_label(kept->phase) : std::string()))
       << "\nset xlabel " << gnuplot_quote(xlabel) << "\nset ylabel "
       << gnuplot_quote((what.empty() ? "" : what + " ") + q + " (" + field_unit(q) + ")") << "\n"
       << (kept ? std::string() : phase_marks(phases, shaking ? t0 : 0.0)) << plot.str() << "\n";
  return body.str();
}

std::vector<std::string> plot_probes(const std::string& dir, const std::vector<std::string>& quantities,
                                     const std::vector<ProbeReference>& references, const ProbePlotOptions& options) {
  probe_columns(dir + "/probes.csv", "");                         // a probes file, before gnuplot is looked for
  for (const auto& r : references) CsvHeader(r.csv).column(r.y);  // before any picture is drawn
  for (const auto& q : quantities) probe_plot_body(dir, q, references, options);  // every input checked first
  require_gnuplot();
  std::vector<std::string> written;
  for (const auto& q : quantities) {
    const std::string body = probe_plot_body(dir, q, references, options);
    const std::string png = dir + "/probe_" + q + ".png";
    run_gnuplot(body, png);
    written.push_back(png);
  }
  return written;
}

}  // namespace seismpm
