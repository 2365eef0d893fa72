// Drawing PNG files with gnuplot: quoting strings for its scripts and running one.
#pragma once

#include <string>

namespace seismpm {

// A gnuplot single-quoted string. Control characters become spaces: a line break inside the quotes
// would end the command and let the rest of the text (a probe name, a CSV column) run as gnuplot
// commands, `system` among them.
std::string gnuplot_quote(const std::string& s);

// Throws OutputError when gnuplot is not installed.
void require_gnuplot();

// Runs `script` (which must write its output to png + ".tmp") and moves the picture into place, so a
// failed plot never leaves half a file. Throws OutputError naming the log when gnuplot fails.
void run_gnuplot(const std::string& script, const std::string& png);

}  // namespace seismpm
