// PNG time-history plots of the probes in DIR/probes.csv, drawn with gnuplot: one file per quantity
// (DIR/probe_<quantity>.png) with every probe's curve, axes labelled with units.
#pragma once

#include <string>
#include <vector>

namespace seismpm {

// Returns the PNG paths written. Throws OutputError (missing probes.csv, no gnuplot, gnuplot failed)
// or InputError (a quantity no probe has).
std::vector<std::string> plot_probes(const std::string& dir, const std::vector<std::string>& quantities);

// Unit of a particle field for axis labels ("m", "Pa", "m/s", "-").
std::string field_unit(const std::string& field);

}  // namespace seismpm
