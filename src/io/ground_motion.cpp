#include "ground_motion.hpp"

#include <Eigen/Dense>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string_view>

#include "core/error.hpp"
#include "text_lines.hpp"

namespace seismpm {

namespace {

std::string where(const std::string& file, int line) { return file + ":" + std::to_string(line) + ": "; }

// Splits a line at white space (and, for column files, commas and semicolons); the rest of a line
// after '#' is a comment there.
std::vector<std::string_view> words(std::string_view line, bool columns) {
  if (columns) line = line.substr(0, line.find('#'));
  auto separator = [&](char c) {
    return c == ' ' || c == '\t' || c == '\v' || c == '\f' || (columns && (c == ',' || c == ';'));
  };
  std::vector<std::string_view> out;
  std::size_t k = 0;
  while (k < line.size()) {
    while (k < line.size() && separator(line[k])) ++k;
    const std::size_t b = k;
    while (k < line.size() && !separator(line[k])) ++k;
    if (k > b) out.push_back(line.substr(b, k - b));
  }
  return out;
}

void check_times(const AccelerationRecord& r, const std::vector<int>& lines) {
  if (r.t.size() < 2) throw InputError(r.source + ": the record needs at least 2 samples");
  for (std::size_t k = 1; k < r.t.size(); ++k)
    if (!(r.t[k] > r.t[k - 1]))
      throw InputError(where(r.source, lines[k]) + "times must increase (" + std::to_string(r.t[k]) + " after " +
                       std::to_string(r.t[k - 1]) + ")");
}

// Cumulative trapezoidal integral of y over t.
std::vector<double> integrate(const std::vector<double>& t, const std::vector<double>& y) {
  std::vector<double> out(t.size(), 0.0);
  for (std::size_t k = 1; k < t.size(); ++k) out[k] = out[k - 1] + 0.5 * (t[k] - t[k - 1]) * (y[k - 1] + y[k]);
  return out;
}

}  // namespace

AccelerationRecord read_at2(const std::string& file) {
  TextLines in(file);
  AccelerationRecord r;
  r.source = file;
  std::string line;
  for (int k = 0; k < 3; ++k)
    if (!in.next(line))
      throw InputError(where(file, in.number() + 1) + "AT2 header ends early (3 text lines, then NPTS= n, DT= dt SEC)");
  if (!in.next(line)) throw InputError(where(file, 4) + "missing the line NPTS= n, DT= dt SEC");
  double npts = -1, dt = -1;  // read as numbers: an absurd count is named, not wrapped
  {
    std::string s = line;
    for (char& c : s)
      if (c == ',' || c == '=') c = ' ';
    const auto w = words(s, false);
    for (std::size_t k = 0; k + 1 < w.size(); ++k) {
      if (w[k] == "NPTS" && !parse_number(w[k + 1], npts)) npts = -1;
      if (w[k] == "DT" && !parse_number(w[k + 1], dt)) dt = -1;
    }
  }
  if (!(npts > 1) || npts != std::floor(npts) || !(dt > 0.0))
    throw InputError(where(file, 4) + "expected 'NPTS= n, DT= dt SEC' with a whole n > 1 and dt > 0, got '" +
                     printable(line) + "'");
  // Each value takes at least two bytes (a digit and a separator): a count the file cannot hold is a
  // broken header, refused before anything is allocated for it.
  const double most = in.size() > 0 ? std::min<double>(kMaxRecordPoints, in.size() / 2.0 + 1) : kMaxRecordPoints;
  if (npts > most) {
    std::ostringstream os;
    os.precision(15);
    os << where(file, 4) << "NPTS= " << npts << " is more than "
       << (in.size() > 0 && in.size() / 2.0 + 1 < kMaxRecordPoints
               ? "a file of " + std::to_string(in.size()) + " bytes can hold"
               : "the " + std::to_string(kMaxRecordPoints) + " points a record may have");
    throw InputError(os.str());
  }
  r.a.reserve(static_cast<std::size_t>(npts));
  while (in.next(line)) {
    for (const auto word : words(line, false)) {
      double v;
      if (!parse_number(word, v)) throw InputError(in.where() + "'" + printable(word) + "' is not a number");
      r.a.push_back(v * kStandardGravity);
    }
  }
  if (r.a.size() != static_cast<std::size_t>(npts))
    throw InputError(where(file, in.number()) + "the header says NPTS= " + std::to_string(static_cast<long>(npts)) +
                     " but the file holds " + std::to_string(r.a.size()) + " values");
  r.t.resize(r.a.size());
  for (std::size_t k = 0; k < r.t.size(); ++k) r.t[k] = k * dt;
  return r;
}

AccelerationRecord read_acceleration_columns(const std::string& file, double to_si) {
  TextLines in(file);
  AccelerationRecord r;
  r.source = file;
  std::vector<int> lines;
  std::string line;
  bool header_allowed = true;
  while (in.next(line)) {
    const auto cells = words(line, true);
    if (cells.empty()) continue;
    double t, a;
    const bool t_number = parse_number(cells[0], t);
    const bool a_number = cells.size() >= 2 && parse_number(cells[1], a);
    // One header line of column names: no number among its first two words (a broken first row of a
    // header-less file is an error, not a header).
    if (header_allowed && !t_number && !a_number) {
      header_allowed = false;
      continue;
    }
    if (cells.size() < 2) throw InputError(in.where() + "expected two columns: time, acceleration");
    if (!t_number || !a_number)
      throw InputError(in.where() + "not a number: '" + printable(t_number ? cells[1] : cells[0]) + "'");
    if (r.t.size() >= kMaxRecordPoints)
      throw InputError(in.where() + "more than " + std::to_string(kMaxRecordPoints) + " points");
    header_allowed = false;
    r.t.push_back(t);
    r.a.push_back(a * to_si);
    lines.push_back(in.number());
  }
  if (r.t.empty()) throw InputError(file + ": empty record (no time, acceleration rows)");
  check_times(r, lines);
  return r;
}

Baseline parse_baseline(const std::string& name) {
  if (name == "none") return Baseline::None;
  if (name == "linear") return Baseline::Linear;
  if (name == "quadratic") return Baseline::Quadratic;
  throw InputError("baseline must be one of none|linear|quadratic, got '" + name + "'");
}

VelocityRecord integrate_record(const AccelerationRecord& record, Baseline baseline) {
  const auto& t = record.t;
  std::vector<double> a = record.a;
  const double t0 = t.front(), T = t.back() - t0;
  if (baseline == Baseline::Quadratic) {
    // Least-squares quadratic p(t) = b0 + b1 s + b2 s^2 (s = t - t0) of the velocity; remove p' from a.
    const auto v = integrate(t, a);
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < t.size(); ++k) {
      const double s = (t[k] - t0) / T;  // scaled for conditioning
      const Eigen::Vector3d phi(1.0, s, s * s);
      M += phi * phi.transpose();
      rhs += phi * v[k];
    }
    const Eigen::Vector3d b = M.ldlt().solve(rhs);
    for (std::size_t k = 0; k < t.size(); ++k) a[k] -= (b[1] + 2.0 * b[2] * (t[k] - t0) / T) / T;
  }
  if (baseline != Baseline::None) {
    // a_c = c0 + c1 s gives v_c(T) = c0 T + c1 T^2/2 and d_c(T) = c0 T^2/2 + c1 T^3/6 (s = t - t0);
    // choose them equal to the record's end velocity and displacement.
    const auto v = integrate(t, a);
    const auto d = integrate(t, v);
    Eigen::Matrix2d M;
    M << T, T * T / 2, T * T / 2, T * T * T / 6;
    const Eigen::Vector2d c = M.inverse() * Eigen::Vector2d(v.back(), d.back());
    for (std::size_t k = 0; k < t.size(); ++k) a[k] -= c[0] + c[1] * (t[k] - t0);
  }
  VelocityRecord out;
  out.t = t;
  out.v = integrate(t, a);
  out.d = integrate(t, out.v);
  out.a = std::move(a);
  return out;
}

}  // namespace seismpm
