// The free field beside a model: a 1D soil column of the layering found at a lateral edge, stepped
// with the model, whose motion and stresses the edge follows (EdgeBoundary, kind free_field).
//
// Why a column: under vertically incident waves the ground beyond a model's side moves as a 1D column.
// A side held in its normal direction (rollers) forbids the horizontal motion of that column and
// reflects what reaches it; a free side lets the layer spread. Driving the side with the column's
// velocity (through dashpots) and its stresses keeps the model's motion one-dimensional at the side,
// while what the model radiates sideways leaves through the same dashpots.
//
// The column is linear elastic with each layer's small-strain moduli (and its Rayleigh damping): it
// carries the dynamic part of the motion only, the static stresses being the gravity phase's (kept by
// the edge as a constant force). Strong yielding at the side is not modelled: keep the sides far from
// where the slope fails.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "history.hpp"
#include "types.hpp"

namespace seismpm {

// One element of the column, between two nodes one cell apart: its density and moduli.
struct ColumnLayer {
  double density = 0.0;         // kg/m^3; 0: no soil there
  double shear_modulus = 0.0;   // G (Pa)
  double p_wave_modulus = 0.0;  // M = K + 4G/3 (Pa)
  double lame = 0.0;            // lambda = K - 2G/3 (Pa): the lateral normal stress of 1D compression
  double rayleigh_alpha = 0.0;  // 1/s, mass-proportional
  double rayleigh_beta = 0.0;   // s, stiffness-proportional
};

// How the column's bottom node is held.
template <int Dim>
struct ColumnBase {
  enum class Kind { Free, Fixed, Dashpot } kind = Kind::Free;
  // Dashpot: the impedances rho c of the medium below (tangential rho Vs, normal rho Vp, kg/m^2/s) and
  // the outcrop velocity it brings in (null: none, an absorbing base).
  double rho_vs = 0.0, rho_vp = 0.0;
  std::array<std::shared_ptr<const History>, Dim> input{};
  bool moving_frame = false;  // the column moves relative to the input: its base dashpot targets zero
};

template <int Dim>
class CheckpointAccess;

template <int Dim>
class FreeFieldColumn {
 public:
  // Nodes every `spacing` m from the bottom up, layers[e] between nodes e and e+1; the vertical axis is
  // the last one (y in 2D, z in 3D).
  FreeFieldColumn(std::vector<ColumnLayer> layers, double spacing, ColumnBase<Dim> base);

  // One explicit step of length dt; `t_end` is the phase time at its end (the base input is read there);
  // `frame_acceleration` that of the frame the column moves in (a body force -rho a).
  void advance(double dt, double t_end, const Vec<Dim>& frame_acceleration);

  int node_count() const { return static_cast<int>(u_.size()); }
  const Vec<Dim>& velocity(int node) const { return v_[node]; }
  // The dynamic stress at a node, the mean over the elements beside it, as the traction components on a
  // vertical face with normal along `axis` (a lateral axis): t = sigma e_axis, without its sign.
  Vec<Dim> face_stress(int node, int axis) const;
  bool has_soil(int node) const { return mass_[node] > 0.0; }

 private:
  template <int>
  friend class CheckpointAccess;
  static constexpr int V = Dim - 1;  // the vertical axis
  std::vector<ColumnLayer> layers_;
  double spacing_ = 1.0;
  ColumnBase<Dim> base_;
  std::vector<double> mass_, alpha_mass_;  // per unit area; alpha_mass: sum of alpha rho dz / 2
  std::vector<Vec<Dim>> u_, v_, force_;
  std::vector<Vec<Dim>> stress_;  // per element: shear sigma_dV for d != V, normal sigma_VV at V
};

extern template class FreeFieldColumn<2>;
extern template class FreeFieldColumn<3>;

}  // namespace seismpm
