// A line plot of columns of a CSV file (a header line of column names after any '#' comment lines),
// drawn with gnuplot as a PNG and an SVG beside it (gnuplot.hpp): the landslide's front against time,
// a deposit profile, a table velocity. Reference columns (a closed form, a measurement) are drawn as
// dashed black curves; a plot of one curve has no key.
#pragma once

#include <string>
#include <vector>

namespace seismpm {

struct CsvPlot {
  std::string csv;             // input file, header line first
  std::string png;             // output file (written atomically), with svg_path(png) beside it
  std::string x;               // column for the horizontal axis
  std::vector<std::string> y;  // columns drawn against it, one curve each
  // Columns drawn against x as reference curves (dashed, black): a closed form, a measurement.
  std::vector<std::string> reference;
  std::string title, xlabel, ylabel;
  // When set: one point per row at (x, y[0]) coloured by this column, equal axis scales (a picture of
  // particles, e.g. displacement over the slope).
  std::string color;
  bool log_x = false;  // a logarithmic x axis (periods of a response spectrum)
};

// The header line of a CSV file to plot, after any '#' comment lines. Throws InputError when the file
// cannot be read.
class CsvHeader {
 public:
  explicit CsvHeader(const std::string& csv);
  // The column's number as gnuplot counts (from 1); throws InputError naming the file and its header.
  std::size_t column(const std::string& name) const;

 private:
  std::string csv_, header_;
  int line_ = 0;
  std::vector<std::string> columns_;
};

// The gnuplot settings and plot command (for picture_script); reads the CSV's header. Throws
// InputError for a file that cannot be read or a column it lacks.
std::string csv_plot_body(const CsvPlot& plot);

// Throws InputError for a column the file lacks, OutputError when gnuplot is missing or fails.
void plot_csv(const CsvPlot& plot);

}  // namespace seismpm
