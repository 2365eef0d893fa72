#include "phases_file.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include "atomic_file.hpp"
#include "core/error.hpp"
#include "csv_table.hpp"
#include "text_lines.hpp"

namespace seismpm {

namespace {
constexpr const char* kHeader = "phase,start (s)";
}

bool same_start(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(a) + std::abs(b)); }

std::vector<PhaseStart> read_phases(const std::string& dir) {
  const std::string file = dir + "/phases.csv";
  std::vector<PhaseStart> out;
  if (!std::filesystem::is_regular_file(file)) return out;
  TextLines in(file);
  std::string line;
  if (!in.next(line) || line != kHeader)
    throw OutputError(file + ":1: not a phases file (the header must be '" + kHeader + "')");
  while (in.next(line)) {
    if (line.empty()) continue;
    std::vector<std::string> cells;
    try {
      cells = split_csv_fields(line);
    } catch (const InputError& e) {
      throw OutputError(in.where() + e.what());
    }
    PhaseStart p;
    if (cells.size() != 2 || !parse_number(cells[1], p.start))
      throw OutputError(in.where() + "expected a phase name and its start time, got '" + printable(line) + "'");
    p.phase = cells[0];
    out.push_back(p);
  }
  return out;
}

void record_phase(const std::string& dir, const std::string& phase, double start) {
  auto phases = read_phases(dir);
  if (!phases.empty() && phases.back().phase == phase && same_start(phases.back().start, start)) return;
  std::erase_if(phases, [&](const PhaseStart& p) { return p.start > start || same_start(p.start, start); });
  phases.push_back({phase, start});
  std::ostringstream os;
  os.precision(17);
  os << kHeader << '\n';
  for (const auto& p : phases) os << csv_field(p.phase) << ',' << p.start << '\n';
  write_file_atomically(dir + "/phases.csv", os.str());
}

double shaking_start(const std::vector<PhaseStart>& phases) {
  for (const auto& p : phases)
    if (p.phase == "dynamic") return p.start;
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace seismpm
