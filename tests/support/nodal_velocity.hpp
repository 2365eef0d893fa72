// A test fix that drives the grid: every node with mass takes the velocity v(x) of a given field
// (a rigid spin, a uniform dilation), with the acceleration rebuilt so that FLIP sees it too.
#pragma once

#include <functional>
#include <string_view>

#include "core/fix.hpp"
#include "core/model.hpp"

namespace seismpm::test {

template <int Dim>
class NodalVelocityField : public Fix<Dim> {
 public:
  using Field = std::function<Vec<Dim>(const Vec<Dim>&)>;
  explicit NodalVelocityField(Field f) : field(std::move(f)) {}
  std::string_view name() const override { return "nodal_velocity_field"; }
  void nodal_velocities(Model<Dim>& m, const StepContext& c, VelocityStage stage) override {
    auto& g = m.grid();
    for (int i = 0; i < g.node_count(); ++i) {
      if (!(g.mass[i] > m.mass_threshold())) continue;
      const Vec<Dim> v = field(g.node_position(i));
      if (stage == VelocityStage::Updated) g.acceleration[i] = (v - g.momentum[i] / g.mass[i]) / c.dt;
      g.velocity[i] = v;
    }
  }
  Field field;  // may be replaced between runs
};

}  // namespace seismpm::test
