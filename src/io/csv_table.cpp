#include "csv_table.hpp"

#include "core/error.hpp"
#include "text_lines.hpp"

namespace seismpm {

namespace {

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

}  // namespace

std::string CsvColumn::describe() const { return number > 0 ? std::to_string(number) : "'" + name + "'"; }

std::vector<std::string> split_csv_fields(std::string_view line) {
  std::vector<std::string> out;
  std::size_t k = 0;
  for (;;) {
    while (k < line.size() && (line[k] == ' ' || line[k] == '\t')) ++k;
    std::string field;
    if (k < line.size() && line[k] == '"') {
      for (++k;; ++k) {
        if (k >= line.size()) throw InputError("a quoted field is not closed (a line break inside quotes is not read)");
        if (line[k] == '"') {
          if (k + 1 < line.size() && line[k + 1] == '"') {
            field += '"';
            ++k;
          } else {
            ++k;
            break;
          }
        } else {
          field += line[k];
        }
      }
      while (k < line.size() && line[k] != ',') {
        if (line[k] != ' ' && line[k] != '\t') throw InputError("text after a quoted field");
        ++k;
      }
    } else {
      const auto comma = line.find(',', k);
      field = std::string(trim(line.substr(k, comma == std::string_view::npos ? std::string_view::npos : comma - k)));
      k = comma == std::string_view::npos ? line.size() : comma;
    }
    out.push_back(std::move(field));
    if (k >= line.size()) break;
    ++k;  // the comma
  }
  return out;
}

std::string csv_field(std::string_view text) {
  const bool quote =
      text.find_first_of(",\"\r\n") != std::string_view::npos ||
      (!text.empty() && (text.front() == ' ' || text.back() == ' ' || text.front() == '\t' || text.back() == '\t'));
  if (!quote) return std::string(text);
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

CsvColumns read_csv_columns(const std::string& file, const std::vector<CsvColumn>& wanted) {
  TextLines in(file);
  std::string line;
  std::vector<std::size_t> index;
  bool header_read = false;
  bool all_numbered = !wanted.empty();
  for (const auto& c : wanted) all_numbered = all_numbered && c.number > 0;
  CsvColumns out;
  out.columns.resize(wanted.size());
  while (in.next(line)) {
    const std::string_view t = trim(line);
    if (t.empty() || t[0] == '#') continue;
    std::vector<std::string> cells;
    try {
      cells = split_csv_fields(line);
    } catch (const InputError& e) {
      throw InputError(in.where() + e.what());
    }
    if (!header_read) {
      header_read = true;
      // With every column numbered, the first line is a header only when none of its cells there is a
      // number: a broken first row of a header-less file is an error, not a line skipped.
      bool any_number = false;
      double v;
      for (const auto& c : wanted) {
        index.push_back(c.number > 0 ? static_cast<std::size_t>(c.number - 1) : cells.size());
        if (c.number > 0) {
          any_number = any_number || (index.back() < cells.size() && parse_number(cells[index.back()], v));
          continue;
        }
        for (std::size_t k = 0; k < cells.size(); ++k)
          if (cells[k] == c.name) index.back() = k;
        if (index.back() == cells.size()) {
          std::string have;
          for (const auto& h : cells) have += (have.empty() ? "" : ", ") + h;
          throw InputError(in.where() + "no column '" + printable(c.name) +
                           "' in the header (columns: " + printable(have, 200) + ")");
        }
      }
      if (!all_numbered || !any_number) continue;  // a header line (or, with numbered columns, a line of names)
    }
    for (std::size_t k = 0; k < wanted.size(); ++k) {
      const std::size_t c = index[k];
      if (c >= cells.size() || cells[c].empty())
        throw InputError(in.where() + "column " + wanted[k].describe() + " is missing");
      double v;
      if (!parse_number(cells[c], v))
        throw InputError(in.where() + "column " + wanted[k].describe() + " is not a number ('" + printable(cells[c]) +
                         "')");
      out.columns[k].push_back(v);
    }
    out.lines.push_back(in.number());
  }
  if (!header_read) throw InputError(file + ": empty file (no header line)");
  if (out.lines.empty()) throw InputError(file + ":" + std::to_string(in.number()) + ": no data rows after the header");
  return out;
}

}  // namespace seismpm
