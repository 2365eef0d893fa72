#include "csv_table.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "core/error.hpp"

namespace seismpm {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\"");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\"");
  return s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const auto comma = line.find(',', start);
    out.push_back(trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

}  // namespace

CsvColumns read_csv_columns(const std::string& file, const std::vector<std::string>& names) {
  std::ifstream in(file);
  if (!in) throw InputError(file + ": cannot open (" + std::strerror(errno) + ")");
  std::string line;
  int number = 0;
  std::vector<int> index;
  std::vector<std::string> header;
  CsvColumns out;
  out.columns.resize(names.size());
  while (std::getline(in, line)) {
    ++number;
    const std::string t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    const auto cells = split(line);
    if (header.empty()) {
      header = cells;
      for (const auto& name : names) {
        int found = -1;
        for (std::size_t c = 0; c < header.size(); ++c)
          if (header[c] == name) found = static_cast<int>(c);
        if (found < 0) {
          std::string have;
          for (const auto& h : header) have += (have.empty() ? "" : ", ") + h;
          throw InputError(file + ":" + std::to_string(number) + ": no column '" + name +
                           "' in the header (columns: " + have + ")");
        }
        index.push_back(found);
      }
      continue;
    }
    for (std::size_t k = 0; k < names.size(); ++k) {
      const std::size_t c = index[k];
      if (c >= cells.size() || cells[c].empty())
        throw InputError(file + ":" + std::to_string(number) + ": column '" + names[k] + "' is missing");
      char* end = nullptr;
      errno = 0;
      const double v = std::strtod(cells[c].c_str(), &end);
      if (end == cells[c].c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
        throw InputError(file + ":" + std::to_string(number) + ": column '" + names[k] + "' is not a number ('" +
                         cells[c] + "')");
      out.columns[k].push_back(v);
    }
    out.lines.push_back(number);
  }
  if (header.empty()) throw InputError(file + ": empty file (no header line)");
  if (out.lines.empty()) throw InputError(file + ":" + std::to_string(number) + ": no data rows after the header");
  return out;
}

}  // namespace seismpm
