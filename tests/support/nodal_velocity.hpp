// A test fix that drives the grid: every node with mass takes the velocity v(x) of a given field
// (a rigid spin, a uniform dilation), with the acceleration rebuilt so that FLIP sees it too. Where
// contact fields meet, every deformable field's slot takes it as well (after contact has acted).
#pragma once

#include <algorithm>
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
    auto& S = m.contact().nodes();
    for (int k = 0; k < S.count(); ++k)
      for (int j = 0; j < S.fields(k); ++j) {
        const int s = k * SharedNodes<Dim>::kSlots + j;
        if (m.contact().rules().rigid(S.field_of_slot(s)) || !(S.mass[s] > 0.0)) continue;
        const Vec<Dim> v = field(g.node_position(S.node(k)));
        if (stage == VelocityStage::Updated) S.acceleration[s] = (v - S.momentum[s] / S.mass[s]) / c.dt;
        S.velocity[s] = v;
      }
  }
  Field field;  // may be replaced between runs
};

// A uniform compression toward the plane x[axis] = plane from the side below it (upper) or above it, at
// strain rate `rate` (1/s): the normal velocity -rate * (distance from the plane), zero beyond it.
template <int Dim>
Vec<Dim> towards_plane(const Vec<Dim>& x, int axis, bool upper, double plane, double rate) {
  Vec<Dim> v = Vec<Dim>::Zero();
  const double distance = upper ? plane - x[axis] : x[axis] - plane;
  v[axis] = (upper ? rate : -rate) * std::max(distance, 0.0);
  return v;
}

}  // namespace seismpm::test
