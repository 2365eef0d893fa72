#include "ground_motion.hpp"

#include <Eigen/Dense>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace seismpm {

namespace {

std::string where(const std::string& file, int line) { return file + ":" + std::to_string(line) + ": "; }

bool parse_number(const std::string& text, double& out) {
  char* end = nullptr;
  errno = 0;
  out = std::strtod(text.c_str(), &end);
  return end != text.c_str() && *end == '\0' && errno != ERANGE && std::isfinite(out);
}

std::ifstream open(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file + ": cannot open (" + std::strerror(errno) + ")");
  return in;
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
  std::ifstream in = open(file);
  AccelerationRecord r;
  r.source = file;
  std::string line;
  int number = 0;
  for (int k = 0; k < 3; ++k)
    if (!std::getline(in, line))
      throw InputError(where(file, number + 1) + "AT2 header ends early (3 text lines, then NPTS= n, DT= dt SEC)");
    else
      ++number;
  if (!std::getline(in, line)) throw InputError(where(file, 4) + "missing the line NPTS= n, DT= dt SEC");
  ++number;
  long npts = -1;
  double dt = -1;
  {
    std::string s = line;
    for (char& c : s)
      if (c == ',' || c == '=') c = ' ';
    std::istringstream is(s);
    for (std::string word; is >> word;) {
      if (word == "NPTS")
        is >> npts;
      else if (word == "DT")
        is >> dt;
    }
  }
  if (npts <= 1 || !(dt > 0.0) || !std::isfinite(dt))
    throw InputError(where(file, 4) + "expected 'NPTS= n, DT= dt SEC' with n > 1 and dt > 0, got '" + line + "'");
  r.a.reserve(npts);
  while (std::getline(in, line)) {
    ++number;
    std::istringstream is(line);
    for (std::string word; is >> word;) {
      double v;
      if (!parse_number(word, v)) throw InputError(where(file, number) + "'" + word + "' is not a number");
      r.a.push_back(v * kStandardGravity);
    }
  }
  if (static_cast<long>(r.a.size()) != npts)
    throw InputError(where(file, number) + "the header says NPTS= " + std::to_string(npts) + " but the file holds " +
                     std::to_string(r.a.size()) + " values");
  r.t.resize(r.a.size());
  for (std::size_t k = 0; k < r.t.size(); ++k) r.t[k] = k * dt;
  return r;
}

AccelerationRecord read_acceleration_columns(const std::string& file, double to_si) {
  std::ifstream in = open(file);
  AccelerationRecord r;
  r.source = file;
  std::vector<int> lines;
  std::string line;
  int number = 0;
  bool header_allowed = true;
  while (std::getline(in, line)) {
    ++number;
    std::string s = line;
    const auto hash = s.find('#');
    if (hash != std::string::npos) s.erase(hash);
    for (char& c : s)
      if (c == ',' || c == ';' || c == '\t' || c == '\r') c = ' ';
    std::istringstream is(s);
    std::vector<std::string> cells;
    for (std::string w; is >> w;) cells.push_back(w);
    if (cells.empty()) continue;
    double t, a;
    const bool numeric = cells.size() >= 2 && parse_number(cells[0], t) && parse_number(cells[1], a);
    if (!numeric && header_allowed) {  // one header line of column names
      header_allowed = false;
      continue;
    }
    if (cells.size() < 2) throw InputError(where(file, number) + "expected two columns: time, acceleration");
    if (!numeric)
      throw InputError(where(file, number) + "not a number: '" + (parse_number(cells[0], t) ? cells[1] : cells[0]) +
                       "'");
    header_allowed = false;
    r.t.push_back(t);
    r.a.push_back(a * to_si);
    lines.push_back(number);
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
  return out;
}

}  // namespace seismpm
