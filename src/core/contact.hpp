// Bardenhagen frictional contact at one grid node (PHYSICS.md, "Multi-body frictional contact").
// Bodies that need their own velocity at a node are "contact fields": every rigid body, and every
// deformable body named in a contact pair; all other deformable bodies share field 0. Two fields
// without a declared pair are glued (one velocity, "standard MPM"); a declared pair slides with
// Coulomb friction and separates freely. A rigid field has a prescribed velocity and infinite mass.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "types.hpp"

namespace seismpm {

// How each pair of contact fields interacts.
class ContactRules {
 public:
  static constexpr double kGlued = -1.0;

  void reset(int fields) {
    fields_ = fields;
    friction_.assign(static_cast<std::size_t>(fields) * fields, kGlued);
    rigid_.assign(fields, false);
  }
  int fields() const { return fields_; }
  void set_rigid(int field, bool rigid) { rigid_[field] = rigid; }
  bool rigid(int field) const { return rigid_[field]; }
  void set_friction(int a, int b, double mu) { friction_[a * fields_ + b] = friction_[b * fields_ + a] = mu; }
  // Coulomb coefficient of the pair, or kGlued when no contact is declared between them.
  double friction(int a, int b) const { return friction_[a * fields_ + b]; }
  bool glued(int a, int b) const { return friction(a, b) < 0.0; }

 private:
  int fields_ = 0;
  std::vector<double> friction_;
  std::vector<char> rigid_;
};

// The fields at one shared node. For a deformable field: mass, the sum m_p grad N_ip and the field's
// own nodal velocity, corrected in place. For a rigid field: `mass` is the weight sum N V (Eq. 9),
// `gradient` sum V_p grad N_ip and `velocity` the prescribed nodal velocity, never changed.
// grad N_ip is the derivative with respect to the particle's position, so these sums point OUT of the
// field's material at the node (the nodal mass grows as the node moves into the body, the opposite
// way): they are outward normals. Taking them as pointing inward flips every approach test.
template <int Dim>
struct NodeFields {
  static constexpr int kMax = 4;
  int count = 0;
  int field[kMax];
  double mass[kMax];
  Vec<Dim> gradient[kMax];
  Vec<Dim> velocity[kMax];
};

namespace contact_detail {

// One Bardenhagen correction of velocity v (mass m) against a partner moving at v_cm, along the
// normal n that points from this body toward the partner. Returns the velocity change.
template <int Dim>
Vec<Dim> correction(const Vec<Dim>& v, const Vec<Dim>& v_cm, const Vec<Dim>& n, double mu) {
  const Vec<Dim> dv = v - v_cm;
  const double dn = dv.dot(n);
  if (!(dn > 0.0)) return Vec<Dim>::Zero();  // separating or at rest relative to each other: free
  const Vec<Dim> dt = dv - dn * n;
  const double tangential = dt.norm();
  if (tangential <= mu * dn) return -dv;  // friction suffices: stick to the centre of mass
  return -dn * n - (mu * dn / tangential) * dt;
}

}  // namespace contact_detail

// Applies the contact rules to the fields at one node: glued deformable fields share their centre-of-mass
// velocity; declared deformable pairs get the Bardenhagen correction with equal and opposite momentum
// changes; then every deformable field is corrected against each rigid field in turn (a corner where
// a base and a wall meet sees both). `min_mass` skips fields with (almost) no mass at the node.
// Adds to force_on[j] of each rigid slot j the momentum per unit time it gave the deformable fields
// (divided by `dt` when dt > 0; pass dt = 0 to skip the bookkeeping). `cell` is the grid spacing.
template <int Dim>
void resolve_contact(NodeFields<Dim>& n, const ContactRules& rules, double min_mass, double cell, double dt,
                     Vec<Dim>* force_on) {
  constexpr int kMax = NodeFields<Dim>::kMax;
  int group[kMax];  // union of glued deformable fields: group[j] = representative slot
  for (int j = 0; j < n.count; ++j) group[j] = j;
  auto active = [&](int j) { return !rules.rigid(n.field[j]) && n.mass[j] > min_mass; };

  // Glued deformable fields move together.
  for (int a = 0; a < n.count; ++a)
    for (int b = a + 1; b < n.count; ++b)
      if (active(a) && active(b) && rules.glued(n.field[a], n.field[b])) {
        const int ra = group[a], rb = group[b];
        if (ra == rb) continue;
        for (int j = 0; j < n.count; ++j)
          if (group[j] == rb) group[j] = ra;
      }
  // Group totals, held in the representative's place.
  double gm[kMax];
  Vec<Dim> gp[kMax], gg[kMax];
  for (int j = 0; j < n.count; ++j) gm[j] = 0.0, gp[j].setZero(), gg[j].setZero();
  for (int j = 0; j < n.count; ++j)
    if (active(j)) {
      gm[group[j]] += n.mass[j];
      gp[group[j]] += n.mass[j] * n.velocity[j];
      gg[group[j]] += n.gradient[j];
    }
  Vec<Dim> gv[kMax];
  for (int j = 0; j < n.count; ++j)
    if (active(j) && group[j] == j) gv[j] = gp[j] / gm[j];

  // Deformable pairs in contact.
  for (int a = 0; a < n.count; ++a) {
    if (!active(a) || group[a] != a) continue;
    for (int b = a + 1; b < n.count; ++b) {
      if (!active(b) || group[b] != b) continue;
      const Vec<Dim> dg = gg[a] - gg[b];  // out of A toward B, the same line for both
      const double len = dg.norm();
      if (!(len * cell > 1e-6 * std::min(gm[a], gm[b]))) continue;  // no direction to speak of
      const Vec<Dim> normal = dg / len;
      const Vec<Dim> v_cm = (gm[a] * gv[a] + gm[b] * gv[b]) / (gm[a] + gm[b]);
      const double mu = rules.friction(n.field[a], n.field[b]);
      const Vec<Dim> dva = contact_detail::correction<Dim>(gv[a], v_cm, normal, mu);
      gv[a] += dva;
      gv[b] -= (gm[a] / gm[b]) * dva;  // equal and opposite momentum change
    }
  }

  // Each rigid field in turn; where two meet (a base and a wall at a corner) one's correction can undo
  // the other's (a wall's normal tilts at its foot), so the passes repeat until neither changes anything.
  constexpr int kPasses = 24;
  for (int pass = 0; pass < kPasses; ++pass) {
    bool changed = false;
    for (int r = 0; r < n.count; ++r) {
      if (!rules.rigid(n.field[r]) || !(n.mass[r] > 0.0)) continue;
      const Vec<Dim>& v_r = n.velocity[r];
      // A gradient this small against sum N V / h means the node is deep inside the rigid body.
      const double rlen = n.gradient[r].norm();
      const bool rigid_normal = rlen * cell > 1e-6 * n.mass[r];
      for (int a = 0; a < n.count; ++a) {
        if (!active(a) || group[a] != a) continue;
        // Glued when any member of the group has no contact declared with the rigid field.
        bool glued = false;
        double mu = 0.0;
        for (int j = 0; j < n.count; ++j)
          if (active(j) && group[j] == a) {
            const double f = rules.friction(n.field[j], n.field[r]);
            if (f < 0.0) glued = true;
            mu = std::max(mu, f);
          }
        Vec<Dim> dv;
        if (glued) {
          dv = v_r - gv[a];
        } else {
          // From the soil toward the rigid body: against the rigid body's outward normal, which is the
          // cleanest; deep inside it, or where both outward normals point nearly the same way (within
          // 60 degrees: a node beyond a thin rigid layer, on its far face, that the soil's support reaches
          // through it), along the soil's own outward normal: taking the far face's normal there would
          // let the soil through. (The soil's normal follows the grid's staircase; looser tests picked it
          // at the risers of an inclined surface and locked a block that should slide.)
          Vec<Dim> normal;
          const double slen = gg[a].norm();
          if (rigid_normal && n.gradient[r].dot(gg[a]) <= 0.5 * rlen * gg[a].norm())
            normal = -n.gradient[r] / rlen;
          else if (slen * cell > 1e-6 * gm[a])
            normal = gg[a] / slen;
          else
            normal.setZero();
          dv = normal.squaredNorm() > 0.0 ? contact_detail::correction<Dim>(gv[a], v_r, normal, mu) : Vec<Dim>(v_r - gv[a]);
        }
        if (dv.squaredNorm() > 1e-28 * (gv[a].squaredNorm() + v_r.squaredNorm())) changed = true;
        gv[a] += dv;
        if (dt > 0.0 && force_on) force_on[r] += (gm[a] / dt) * dv;
      }
    }
    if (!changed) break;
  }

  for (int j = 0; j < n.count; ++j)
    if (active(j)) n.velocity[j] = gv[group[j]];
}

}  // namespace seismpm
