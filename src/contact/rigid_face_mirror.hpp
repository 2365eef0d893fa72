// Rigid faces as the position update sees them: what keeps a uGIMP particle centre out of a rigid body
// it is in contact with, as held_edges.hpp does for a held grid edge.
//
// Why a centre crosses a rigid face at all: contact holds the soil's normal velocity at the face's
// nodes and at the nodes beyond it (inside the rigid body) to the rigid body's, but the position moves
// with sum N_i v_i over the particle's stencil, and a uGIMP particle whose domain (half-width l, cell
// units) reaches past the face keeps the weight (d + l)^2 / 4l at the first node on its own side, d its
// centre's distance from the face: l / 4 with the centre on the face. Where the soil beside the face
// is squeezed toward it (plastic flow at the foot of a wall on a shaken table) the centre keeps moving
// toward the face at l / 4 of that node's velocity and passes it: in the 0.375 cm shaking-table run the
// corner particle crept 1 mm into the smooth wall over 13 s and left the grid.
//
// The remedy, for a face that lies on a grid plane with its normal along the axis: the position update
// reads the normal velocity relative to the rigid body beyond the face as the mirror image of the
// inside, so each node beyond it gives its weight, with the opposite sign, to its mirror node. The
// centre's relative normal velocity is then w_f u_f + d u_1: the face node's (which contact keeps from
// approaching) plus the linear interpolant of the first inner node's. A centre approaches the face at
// most geometrically (factor 1 + dt u_1 / h per step) and never reaches it. Only the position and
// displacement of particles whose domain reaches past such a face change; velocities, strains and
// stresses read the grid as before. Inclined faces (normal more than 8 degrees off the axis) are left
// alone: there the axis component mixes sliding with approach.
#pragma once

#include "contact_fields.hpp"
#include "core/grid.hpp"
#include "core/stencil.hpp"

namespace seismpm {

// Applies the mirror to v = sum N_i v_i of a particle of deformable field `field` with stencil st (3
// nodes per axis: uGIMP). node_velocity(i) is the velocity the particle reads at node i (its own
// field's where fields meet).
template <int Dim, class NodeVelocity>
void mirror_rigid_faces(const ContactFields<Dim>& contact, const Grid<Dim>& grid, const Stencil<Dim, 3>& st, int field,
                        Vec<Dim>& v, NodeVelocity&& node_velocity) {
  const auto& S = contact.nodes();
  const auto& rules = contact.rules();
  for (int d = 0; d < Dim; ++d) {
    // The centre relative to the stencil's middle node plane, in cells (sum N x_node = x_p).
    const double r = st.w[d][1] + 2.0 * st.w[d][2] - 1.0;
    int ghost;
    if (r >= 0.0 && st.w[d][0] > 0.0)
      ghost = 0;  // the domain reaches past the middle plane downward: a face there with its body below
    else if (r < 0.0 && st.w[d][2] > 0.0)
      ghost = 2;
    else
      continue;
    const int step = (ghost == 0 ? 1 : -1) * grid.stride(d);  // from the ghost layer toward the particle
    const double sign = ghost == 0 ? 1.0 : -1.0;              // the face's outward normal along d
    for_each_in_layer(st, grid, d, ghost, [&](int i, double N) {
      const int kg = S.index(i), kf = S.index(i + step);
      if (!(N > 0.0) || kg < 0 || kf < 0) return;
      const int km = S.index(i + 2 * step);
      for (int j = 0; j < S.fields(kf); ++j) {
        const int sf = kf * SharedNodes<Dim>::kSlots + j, q = S.field_of_slot(sf);
        if (!rules.rigid(q) || rules.glued(field, q) || !(S.mass[sf] > 0.0)) continue;
        const int sg = S.slot(kg, q);
        if (sg < 0 || !(S.mass[sg] > 0.0)) continue;  // the body does not reach beyond its face
        const int sm = km >= 0 ? S.slot(km, q) : -1;
        if (sm >= 0 && S.mass[sm] > 0.0) continue;  // nor the particle's side of it
        const Vec<Dim>& n = S.face[sf];
        const double len = n.norm();
        if (!(len > 0.0) || !(sign * n[d] >= 0.99 * len)) continue;  // no face along this axis here
        // u_ghost := -u_mirror, relative to the rigid body's velocity at its face.
        v[d] += N * (2.0 * S.velocity[sf][d] - node_velocity(i + 2 * step)[d] - node_velocity(i)[d]);
        return;
      }
    });
  }
}

}  // namespace seismpm
