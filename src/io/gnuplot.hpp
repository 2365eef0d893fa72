// Drawing PNG files with gnuplot: quoting strings for its scripts and running one.
#pragma once

#include <string>

namespace seismpm {

// A gnuplot single-quoted string.
std::string gnuplot_quote(const std::string& s);

// Throws OutputError when gnuplot is not installed.
void require_gnuplot();

// Runs `script` (which must write its output to png + ".tmp") and moves the picture into place, so a
// failed plot never leaves half a file. Throws OutputError naming the log when gnuplot fails.
void run_gnuplot(const std::string& script, const std::string& png);

}  // namespace seismpm
