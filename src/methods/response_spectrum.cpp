#include "response_spectrum.hpp"

#include <Eigen/Core>
#include <cmath>
#include <numbers>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>

#include "core/error.hpp"
#include "core/parameter.hpp"

namespace seismpm {

namespace {

void check_record(const std::vector<double>& t, const std::vector<double>& a) {
  if (t.size() != a.size()) throw InputError("response spectrum: unequal numbers of times and accelerations");
  if (t.size() < 2) throw InputError("response spectrum: the record needs at least 2 samples");
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (!std::isfinite(t[k]) || !std::isfinite(a[k]))
      throw InputError("response spectrum: sample " + std::to_string(k + 1) + " is not a finite number");
    if (k > 0 && !(t[k] > t[k - 1]))
      throw InputError("response spectrum: times must increase (sample " + std::to_string(k + 1) + ")");
  }
}

// One step of length dt: (u, v) at its end from (u, v) at its start and the ground acceleration, a at
// the start and a + da at the end, linear in between.
struct Step {
  double dt = 0.0;
  Eigen::Matrix2d state;  // on (u, v)
  Eigen::Matrix2d input;  // on (a, da)

  Step(double omega, double zeta, double step) : dt(step) {
    // d/ds (u, v, a, da) over the step's fraction s in [0, 1]: u' = dt v, v' = -dt (omega^2 u +
    // 2 zeta omega v + a), a' = da, da' = 0. Its exponential maps the state at s = 0 to s = 1.
    Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
    m(0, 1) = dt;
    m(1, 0) = -omega * omega * dt;
    m(1, 1) = -2.0 * zeta * omega * dt;
    m(1, 2) = -dt;
    m(2, 3) = 1.0;
    const Eigen::Matrix4d e = m.exp();
    state = e.topLeftCorner<2, 2>();
    input = e.topRightCorner<2, 2>();
  }
};

// Calls visit(u_k) for each sample k, the oscillator at rest at the first.
template <class Visit>
void step_oscillator(const std::vector<double>& t, const std::vector<double>& a, double period, double damping,
                     Visit&& visit) {
  const double omega = 2.0 * std::numbers::pi / period;
  Step step(omega, damping, t[1] - t[0]);
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  visit(0.0);
  for (std::size_t k = 1; k < t.size(); ++k) {
    const double dt = t[k] - t[k - 1];
    // A uniform record's steps differ only in the last digits of its times: the same coefficients.
    if (std::abs(dt - step.dt) > 1e-9 * step.dt) step = Step(omega, damping, dt);
    x = step.state * x + step.input * Eigen::Vector2d(a[k - 1], a[k] - a[k - 1]);
    visit(x[0]);
  }
}

void check_settings(double period, double damping) {
  check_parameter("periods", period, above(0), "s");
  check_parameter("damping", damping, closed_open(0, 1), "ratio of critical damping");
}

}  // namespace

std::vector<SpectrumOrdinate> response_spectrum(const std::vector<double>& times,
                                                const std::vector<double>& acceleration,
                                                const std::vector<double>& periods, double damping) {
  check_record(times, acceleration);
  for (double p : periods) check_settings(p, damping);
  std::vector<SpectrumOrdinate> out;
  out.reserve(periods.size());
  for (double period : periods) {
    double peak = 0.0;
    step_oscillator(times, acceleration, period, damping, [&](double u) { peak = std::max(peak, std::abs(u)); });
    const double omega = 2.0 * std::numbers::pi / period;
    out.push_back({period, peak, omega * peak, omega * omega * peak});
  }
  return out;
}

std::vector<double> oscillator_response(const std::vector<double>& times, const std::vector<double>& acceleration,
                                        double period, double damping) {
  check_record(times, acceleration);
  check_settings(period, damping);
  std::vector<double> u;
  u.reserve(times.size());
  step_oscillator(times, acceleration, period, damping, [&](double x) { u.push_back(x); });
  return u;
}

std::vector<double> log_spaced_periods(double first, double last, int count) {
  std::vector<double> p(count);
  for (int k = 0; k < count; ++k)
    p[k] = count == 1 ? first : first * std::pow(last / first, static_cast<double>(k) / (count - 1));
  return p;
}

}  // namespace seismpm
