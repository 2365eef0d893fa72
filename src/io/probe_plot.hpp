// PNG time-history plots of the probes in DIR/probes.csv, drawn with gnuplot: one file per quantity
// (DIR/probe_<quantity>.png) with every probe's curve, axes labelled with units.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace seismpm {

// Returns the PNG paths written. Throws OutputError (missing probes.csv, no gnuplot, gnuplot failed)
// or InputError (a quantity no probe has).
std::vector<std::string> plot_probes(const std::string& dir, const std::vector<std::string>& quantities);

// The columns of a probes.csv (`csv`) holding field `q` of a probe, as gnuplot numbers them (from 1),
// with the probe's name; its header is read as CSV (probe names may hold commas and quotes). Throws
// OutputError when `csv` is missing or is no probes file.
std::vector<std::pair<std::size_t, std::string>> probe_columns(const std::string& csv, const std::string& q);

// Unit of a particle field for axis labels ("m", "Pa", "m/s", "-").
std::string field_unit(const std::string& field);

}  // namespace seismpm
