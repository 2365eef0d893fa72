// Reads named numeric columns from a CSV file with a header line. '#' lines and blank lines are
// skipped. Every error names the file and the line.
#pragma once

#include <string>
#include <vector>

namespace seismpm {

struct CsvColumns {
  std::vector<std::vector<double>> columns;  // in the order asked for
  std::vector<int> lines;                    // file line of each row
};

// Throws InputError ("FILE:LINE: ...") for a missing file, a missing column, a non-numeric value.
CsvColumns read_csv_columns(const std::string& file, const std::vector<std::string>& names);

}  // namespace seismpm
