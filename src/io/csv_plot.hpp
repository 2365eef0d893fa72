// A PNG line plot of columns of a CSV file (a header line of column names after any '#' comment
// lines), drawn with gnuplot: the
// landslide's front against time, a deposit profile, a table velocity.
#pragma once

#include <string>
#include <vector>

namespace seismpm {

struct CsvPlot {
  std::string csv;             // input file, header line first
  std::string png;             // output file (written atomically)
  std::string x;               // column for the horizontal axis
  std::vector<std::string> y;  // columns drawn against it, one curve each
  std::string title, xlabel, ylabel;
  // When set: one point per row at (x, y[0]) coloured by this column, equal axis scales (a picture of
  // particles, e.g. displacement over the slope).
  std::string color;
};

// Throws InputError for a column the file lacks, OutputError when gnuplot is missing or fails.
void plot_csv(const CsvPlot& plot);

}  // namespace seismpm
