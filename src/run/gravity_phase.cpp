#include "gravity_phase.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <sstream>

#include "core/error.hpp"
#include "core/format.hpp"

namespace seismpm {

template <int Dim>
void EquilibriumMonitor<Dim>::update(const Model<Dim>& model) {
  ++steps_;
  const double external = model.external_force();
  force_ratio_ = external > 0.0 ? model.out_of_balance_force() / external : 0.0;
  const double kinetic = model.kinetic_energy();
  peak_energy_ = std::max(peak_energy_, kinetic);
  // A body that starts in equilibrium (K0 stresses) only ever has round-off motion: measured against
  // its own peak that never falls below the tolerance, so the peak counts as at least 1e-3 of the
  // elastic strain energy.
  const double scale = std::max(peak_energy_, 1e-3 * model.strain_energy());
  energy_ratio_ = scale > 0.0 ? kinetic / scale : 0.0;
}

template <int Dim>
std::string equilibrium_text(const EquilibriumMonitor<Dim>& e) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "unbalanced %.1e, kinetic %.1e of peak (tol %.0e)", e.force_ratio(), e.energy_ratio(),
                e.tolerance());
  return buf;
}

template <int Dim>
std::string motion_summary(const Model<Dim>& model, int count) {
  const auto& P = model.particles();
  const auto& bodies = model.bodies();
  std::vector<std::size_t> moving;
  std::vector<double> body_speed(bodies.size(), 0.0);
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (bodies[P.body[p]].rigid) continue;
    moving.push_back(p);
    body_speed[P.body[p]] = std::max(body_speed[P.body[p]], P.v[p].norm());
  }
  const auto faster = [&](std::size_t a, std::size_t b) {
    const double va = P.v[a].norm(), vb = P.v[b].norm();
    return va != vb ? va > vb : a < b;  // ties by index: the same text for any thread count
  };
  const std::size_t shown = std::min<std::size_t>(moving.size(), static_cast<std::size_t>(std::max(count, 0)));
  std::partial_sort(moving.begin(), moving.begin() + shown, moving.end(), faster);
  std::ostringstream os;
  os.precision(3);
  os << "the fastest particles:";
  for (std::size_t k = 0; k < shown; ++k) {
    const std::size_t p = moving[k];
    os << (k ? "; " : " ") << "'" << bodies[P.body[p]].name << "' at " << format_point<Dim>(P.x[p]) << " m, "
       << P.v[p].norm() << " m/s";
  }
  os << " (largest speed per body:";
  bool first = true;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (bodies[b].rigid) continue;
    os << (first ? " " : ", ") << "'" << bodies[b].name << "' " << body_speed[b] << " m/s";
    first = false;
  }
  os << ")";
  return os.str();
}

template <int Dim>
void set_k0_stresses(Model<Dim>& model, double k0) {
  if (!(k0 > 0.0 && std::isfinite(k0))) throw InputError("k0 must be > 0");
  const Vec<Dim> gravity = model.settings().gravity;
  const double g = -gravity[Dim - 1];
  if (!(g > 0.0)) throw InputError("k0 needs gravity pointing down (a negative last component)");
  auto& P = model.particles();
  const auto& bodies = model.bodies();
  const auto& grid = model.grid();
  const double h = grid.cell();
  const double column_width = std::pow(h, Dim - 1);

  // Deformable particles grouped by grid column, each column sorted from the top down.
  auto column_of = [&](std::size_t p) {
    int c = 0, stride = 1;
    for (int d = 0; d < Dim - 1; ++d) {
      c += std::clamp(static_cast<int>(std::floor((P.x[p][d] - grid.origin()[d]) / h)), 0, grid.cells(d) - 1) * stride;
      stride *= grid.cells(d);
    }
    return c;
  };
  std::vector<std::size_t> order;
  for (std::size_t p = 0; p < P.size(); ++p)
    if (!bodies[P.body[p]].rigid) order.push_back(p);
  std::vector<int> column(P.size(), 0);
  for (std::size_t p : order) column[p] = column_of(p);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (column[a] != column[b]) return column[a] < column[b];
    return P.x[a][Dim - 1] > P.x[b][Dim - 1];
  });
  // Walk each column down, accumulating the mass above; particles at one height share their row.
  for (std::size_t k = 0; k < order.size();) {
    const int c = column[order[k]];
    double above = 0.0;  // mass per column above the current row
    while (k < order.size() && column[order[k]] == c) {
      std::size_t end = k;
      const double y = P.x[order[k]][Dim - 1];
      double row = 0.0;
      while (end < order.size() && column[order[end]] == c && std::abs(P.x[order[end]][Dim - 1] - y) < 1e-9 * h) {
        row += P.mass[order[end]];
        ++end;
      }
      const double sigma_v = g * (above + 0.5 * row) / column_width;
      for (std::size_t j = k; j < end; ++j) {
        Sym& s = P.stress[order[j]];
        s.setZero();
        for (int d = 0; d < 3; ++d) s[d] = -k0 * sigma_v;
        s[Dim - 1] = -sigma_v;
      }
      above += row;
      k = end;
    }
  }
  P.reset_kinematics();
}

template class EquilibriumMonitor<2>;
template class EquilibriumMonitor<3>;
template std::string equilibrium_text<2>(const EquilibriumMonitor<2>&);
template std::string equilibrium_text<3>(const EquilibriumMonitor<3>&);
template std::string motion_summary<2>(const Model<2>&, int);
template std::string motion_summary<3>(const Model<3>&, int);
template void set_k0_stresses<2>(Model<2>&, double);
template void set_k0_stresses<3>(Model<3>&, double);

}  // namespace seismpm
