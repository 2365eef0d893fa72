// Time-history plots of the probes in DIR/probes.csv, drawn with gnuplot as PNG and SVG: one picture
// per quantity (DIR/probe_<quantity>.png and .svg) with every probe's curve, axes labelled with units.
// By default the time axis is the shaking's when the run had a dynamic phase ("time since the dynamic
// phase began (s)", the phases before it at negative times, shaded and named), the model time
// otherwise; the phases come from DIR/phases.csv. Options keep one phase's rows and choose the time
// axis (ProbePlotOptions). A closed form can be drawn beside the probes as a reference curve.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace seismpm {

// A curve drawn with the probes of one quantity, dashed and black: columns x and y of a CSV file, x
// in the plot's time axis (the time since the dynamic phase began, when the run had one).
struct ProbeReference {
  std::string quantity;  // the probe field whose picture gets the curve ("ux")
  std::string csv, x, y;
  std::string title;  // its key entry; empty: the column's name
};

// The time axis and the rows of the probe plots.
struct ProbePlotOptions {
  // "auto": after a dynamic phase the time since the (first) dynamic phase began, the phases before it
  // at negative times, shaded; the model time otherwise; with a phase kept, that phase's own time.
  // "time": the model time. "phase_time": the time since the phase kept began (the probes.csv column
  // phase_time (s)).
  std::string x = "auto";
  // The rows kept: "" all of them; "current" the last phase of the run (phases.csv); a phase name
  // ("gravity", "dynamic", "run"): the last phase of that name. x = "phase_time" keeps the current
  // phase unless a phase is given.
  std::string phase;
};
// The x choices and the phase choices the options take (for messages and argument checks).
inline constexpr const char* kProbePlotX = "auto|time|phase_time";
inline constexpr const char* kProbePlotPhases = "current|run|gravity|dynamic";

// Returns the PNG paths written (each with its SVG beside it). Throws OutputError (missing
// probes.csv, no gnuplot, gnuplot failed) or InputError (a quantity no probe has, a reference column
// its file lacks, a phase the run did not have, a probes.csv without phase columns for a phase plot).
std::vector<std::string> plot_probes(const std::string& dir, const std::vector<std::string>& quantities,
                                     const std::vector<ProbeReference>& references = {},
                                     const ProbePlotOptions& options = {});

// The gnuplot settings and plot command of quantity `q`'s picture (for picture_script).
std::string probe_plot_body(const std::string& dir, const std::string& q,
                            const std::vector<ProbeReference>& references = {}, const ProbePlotOptions& options = {});

// The columns of a probes.csv (`csv`) holding field `q` of a probe, as gnuplot numbers them (from 1),
// with the probe's name; its header is read as CSV (probe names may hold commas and quotes). Throws
// OutputError when `csv` is missing or is no probes file.
std::vector<std::pair<std::size_t, std::string>> probe_columns(const std::string& csv, const std::string& q);

// Unit of a particle field for axis labels ("m", "Pa", "m/s", "-").
std::string field_unit(const std::string& field);

}  // namespace seismpm
