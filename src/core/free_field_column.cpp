#include "free_field_column.hpp"

#include "error.hpp"

namespace seismpm {

template <int Dim>
FreeFieldColumn<Dim>::FreeFieldColumn(std::vector<ColumnLayer> layers, double spacing, ColumnBase<Dim> base)
    : layers_(std::move(layers)), spacing_(spacing), base_(std::move(base)) {
  if (layers_.empty()) throw InputError("free-field column: no soil beside the edge");
  if (!(spacing_ > 0.0)) throw InputError("free-field column: spacing must be > 0");
  const std::size_t n = layers_.size() + 1;
  mass_.assign(n, 0.0);
  alpha_mass_.assign(n, 0.0);
  u_.assign(n, Vec<Dim>::Zero());
  v_.assign(n, Vec<Dim>::Zero());
  force_.assign(n, Vec<Dim>::Zero());
  stress_.assign(layers_.size(), Vec<Dim>::Zero());
  for (std::size_t e = 0; e < layers_.size(); ++e) {  // lumped: half an element's mass to each node
    const double half = 0.5 * layers_[e].density * spacing_;
    mass_[e] += half, mass_[e + 1] += half;
    alpha_mass_[e] += layers_[e].rayleigh_alpha * half, alpha_mass_[e + 1] += layers_[e].rayleigh_alpha * half;
  }
}

template <int Dim>
void FreeFieldColumn<Dim>::advance(double dt, double t_end, const Vec<Dim>& frame_acceleration) {
  const int n = node_count();
  for (auto& f : force_) f.setZero();
  for (int e = 0; e + 1 < n; ++e) {
    const ColumnLayer& L = layers_[e];
    if (!(L.density > 0.0)) {
      stress_[e].setZero();
      continue;
    }
    // Strain and strain rate of the element; the stiffness-proportional damping is beta times the
    // elastic stress of the rate.
    const Vec<Dim> strain = (u_[e + 1] - u_[e]) / spacing_;
    const Vec<Dim> rate = (v_[e + 1] - v_[e]) / spacing_;
    for (int d = 0; d < Dim; ++d) {
      const double modulus = d == V ? L.p_wave_modulus : L.shear_modulus;
      stress_[e][d] = modulus * (strain[d] + L.rayleigh_beta * rate[d]);
    }
    force_[e] += stress_[e];
    force_[e + 1] -= stress_[e];
  }
  for (int j = 0; j < n; ++j) force_[j] -= alpha_mass_[j] * v_[j] + mass_[j] * frame_acceleration;
  if (base_.kind == ColumnBase<Dim>::Kind::Dashpot && mass_[0] > 0.0) {
    // Implicit in the end velocity: the dashpot's force is the one that ends the step at the velocity
    // it drives towards, whatever its impedance (no time-step limit).
    for (int d = 0; d < Dim; ++d) {
      const double c = d == V ? base_.rho_vp : base_.rho_vs;
      const double target = base_.input[d] && !base_.moving_frame ? base_.input[d]->at(t_end) : 0.0;
      const double m = mass_[0];
      force_[0][d] += c * (m * target - m * v_[0][d] - dt * force_[0][d]) / (m + dt * c);
    }
  }
  for (int j = 0; j < n; ++j) {
    if (!(mass_[j] > 0.0) || (j == 0 && base_.kind == ColumnBase<Dim>::Kind::Fixed)) {
      v_[j].setZero();
      continue;
    }
    v_[j] += dt / mass_[j] * force_[j];
    u_[j] += dt * v_[j];
  }
}

template <int Dim>
Vec<Dim> FreeFieldColumn<Dim>::face_stress(int node, int axis) const {
  Vec<Dim> t = Vec<Dim>::Zero();
  int count = 0;
  for (int e = node - 1; e <= node; ++e) {
    if (e < 0 || e >= static_cast<int>(layers_.size()) || !(layers_[e].density > 0.0)) continue;
    const ColumnLayer& L = layers_[e];
    t[V] += stress_[e][axis];                              // shear sigma_axis,V
    t[axis] += L.lame / L.p_wave_modulus * stress_[e][V];  // 1D compression's lateral stress
    ++count;
  }
  return count > 0 ? Vec<Dim>(t / count) : t;
}

template class FreeFieldColumn<2>;
template class FreeFieldColumn<3>;

}  // namespace seismpm
