// Drawing pictures with gnuplot, each as a PNG and an SVG beside it, in one style meant for reports:
// quoting strings for its scripts, the shared settings and running a script.
#pragma once

#include <string>

namespace seismpm {

// A gnuplot single-quoted string. Control characters become spaces: a line break inside the quotes
// would end the command and let the rest of the text (a probe name, a CSV column) run as gnuplot
// commands, `system` among them.
std::string gnuplot_quote(const std::string& s);

// Where the SVG copy of a picture goes: "dir/a.png" -> "dir/a.svg"; any other name gets ".svg" added.
std::string svg_path(const std::string& png);

// The settings every plot shares: comma-separated data, a grid, the key (legend) outside the plotting
// area, below it (the pictures are wide, the probes' names long), x spanning the data exactly and a margin of 8 % of
// the data's range above and below the curves, so that no peak touches the frame. A plot's own settings come after it.
std::string report_style();

// The whole script of a picture: `body` (settings, then one `plot` command) drawn as a PNG into
// png + ".tmp", then again as an SVG into svg_path(png) + ".tmp", both 960 x 540.
std::string picture_script(const std::string& body, const std::string& png);

// Throws OutputError when gnuplot is not installed.
void require_gnuplot();

// Runs picture_script(body, png) and moves both pictures into place, so a failed plot never leaves
// half a file. Throws OutputError naming the log when gnuplot fails.
void run_gnuplot(const std::string& body, const std::string& png);

}  // namespace seismpm
