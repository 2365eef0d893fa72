// Local (Cundall) damping: each nodal force component is reduced by alpha times its magnitude
// against the direction of the nodal velocity, f <- f - alpha |f| sign(v). Brings a body to
// static equilibrium without changing the equilibrium itself.
#pragma once

#include "fix.hpp"

namespace seismpm {

template <int Dim>
class LocalDamping : public Fix<Dim> {
 public:
  explicit LocalDamping(double alpha);
  std::string_view name() const override { return "local_damping"; }
  void nodal_forces(Model<Dim>& model, const StepContext& c) override;
  bool writes_only_nodes_with_mass() const override { return true; }
  double alpha() const { return alpha_; }
  void set_alpha(double alpha);

 private:
  double alpha_;
};

extern template class LocalDamping<2>;
extern template class LocalDamping<3>;

}  // namespace seismpm
