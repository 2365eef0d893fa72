// CSV tables (RFC 4180 fields: quoted with "", a doubled quote inside): reading numeric columns, named
// by a header line or numbered, and quoting the fields that outputs write. '#' lines and blank lines
// are skipped. Every error names the file and the line.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace seismpm {

// A column to read: by its header name, or by its number (1-based; then a header line is optional).
struct CsvColumn {
  std::string name;
  int number = 0;
  CsvColumn(std::string n) : name(std::move(n)) {}  // NOLINT: a name reads as a column
  CsvColumn(const char* n) : name(n) {}             // NOLINT
  static CsvColumn numbered(int n) {
    CsvColumn c("");
    c.number = n;
    return c;
  }
  std::string describe() const;  // "'vx'" or "2"
};

struct CsvColumns {
  std::vector<std::vector<double>> columns;  // in the order asked for
  std::vector<int> lines;                    // file line of each row
};

// Throws InputError ("FILE:LINE: ...") for a missing file, a missing column, a non-numeric value.
// With every column numbered, a first line with a number in any of those cells is data, not a header.
CsvColumns read_csv_columns(const std::string& file, const std::vector<CsvColumn>& columns);

// The fields of one CSV line; quotes removed, spaces around unquoted fields trimmed. Throws
// InputError (without a place: the caller adds it) for a quote left open.
std::vector<std::string> split_csv_fields(std::string_view line);
// A field as CSV writes it: quoted (quotes doubled) when it holds a comma, a quote, a line break or
// leading or trailing spaces; as it is otherwise.
std::string csv_field(std::string_view text);

}  // namespace seismpm
