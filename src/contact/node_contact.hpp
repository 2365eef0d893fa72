// Bardenhagen frictional contact at one grid node: the fields that meet there (contact_rules.hpp),
// each with its own mass, normal and velocity, corrected in place.
#pragma once

#include <algorithm>
#include <cmath>

#include "contact_rules.hpp"
#include "core/types.hpp"

namespace seismpm {

// The fields at one shared node. For a deformable field: mass, the sum m_p grad N_ip and the field's
// own nodal velocity, corrected in place. For a rigid field: `mass` is the weight sum N V (the paper's
// Eq. 9), `gradient` sum V_p grad N_ip and `velocity` the prescribed nodal velocity, never changed.
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
  // Out: the representative slot of each field's glued group (its own slot when alone or inactive).
  int group[kMax];
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

// The deformable fields at a node with mass, glued ones merged into groups that move as one. A
// group's mass, outward gradient and velocity are held at its representative slot.
template <int Dim>
struct FieldGroups {
  static constexpr int kMax = NodeFields<Dim>::kMax;
  bool active[kMax];  // deformable with more than the minimum mass
  int group[kMax];    // representative slot
  double mass[kMax];
  Vec<Dim> gradient[kMax], velocity[kMax];

  FieldGroups(const NodeFields<Dim>& n, const ContactRules& rules, double min_mass) {
    for (int j = 0; j < n.count; ++j) {
      group[j] = j;
      active[j] = !rules.rigid(n.field[j]) && n.mass[j] > min_mass;
    }
    for (int a = 0; a < n.count; ++a)
      for (int b = a + 1; b < n.count; ++b)
        if (active[a] && active[b] && rules.glued(n.field[a], n.field[b])) merge(n.count, group[a], group[b]);
    Vec<Dim> momentum[kMax];
    for (int j = 0; j < n.count; ++j) mass[j] = 0.0, momentum[j].setZero(), gradient[j].setZero();
    for (int j = 0; j < n.count; ++j)
      if (active[j]) {
        mass[group[j]] += n.mass[j];
        momentum[group[j]] += n.mass[j] * n.velocity[j];
        gradient[group[j]] += n.gradient[j];
      }
    for (int j = 0; j < n.count; ++j)
      if (representative(j)) velocity[j] = momentum[j] / mass[j];
  }
  bool representative(int j) const { return active[j] && group[j] == j; }

 private:
  void merge(int count, int ra, int rb) {
    if (ra == rb) return;
    for (int j = 0; j < count; ++j)
      if (group[j] == rb) group[j] = ra;
  }
};

// Declared deformable pairs: the Bardenhagen correction with equal and opposite momentum changes.
template <int Dim>
void resolve_deformable_pairs(FieldGroups<Dim>& g, const NodeFields<Dim>& n, const ContactRules& rules, double cell) {
  for (int a = 0; a < n.count; ++a) {
    if (!g.representative(a)) continue;
    for (int b = a + 1; b < n.count; ++b) {
      if (!g.representative(b)) continue;
      const Vec<Dim> dg = g.gradient[a] - g.gradient[b];  // out of A toward B, the same line for both
      const double len = dg.norm();
      if (!(len * cell > 1e-6 * std::min(g.mass[a], g.mass[b]))) continue;  // no direction to speak of
      const Vec<Dim> normal = dg / len;
      const Vec<Dim> v_cm = (g.mass[a] * g.velocity[a] + g.mass[b] * g.velocity[b]) / (g.mass[a] + g.mass[b]);
      const double mu = rules.friction(n.field[a], n.field[b]);
      const Vec<Dim> dva = correction<Dim>(g.velocity[a], v_cm, normal, mu);
      g.velocity[a] += dva;
      g.velocity[b] -= (g.mass[a] / g.mass[b]) * dva;
    }
  }
}

// The Coulomb coefficient between group `a` and rigid field `r`; `glued` when any member of the group
// has no contact declared with it.
template <int Dim>
double rigid_pair_friction(const FieldGroups<Dim>& g, const NodeFields<Dim>& n, const ContactRules& rules, int a, int r,
                           bool& glued) {
  glued = false;
  double mu = 0.0;
  for (int j = 0; j < n.count; ++j)
    if (g.active[j] && g.group[j] == a) {
      const double f = rules.friction(n.field[j], n.field[r]);
      if (f < 0.0) glued = true;
      mu = std::max(mu, f);
    }
  return mu;
}

// Rigid field r's outward gradient at the node without the part that points into another rigid field
// whose face there is cleaner. A wall standing on a base stops at the base, so at the wall's foot its
// gradient tilts down toward the base: a 45-degree chamfer at the corner node. Soil sliding along a
// smooth wall there was pushed off it into tension, and over many cycles of shaking the corner particle
// ratcheted into the wall. The face two rigid bodies share is no face soil can touch, so that part goes.
// A flat face gives the larger gradient (a half plane's particles against a quadrant's, about 2 : 1.4),
// which tells the clean face from the tilted one; near ties change nothing.
template <int Dim>
Vec<Dim> rigid_face_gradient(const NodeFields<Dim>& n, const ContactRules& rules, int r, double cell) {
  Vec<Dim> grad = n.gradient[r];
  const double len = grad.norm();
  for (int q = 0; q < n.count; ++q) {
    if (q == r || !rules.rigid(n.field[q]) || !(n.mass[q] > 0.0)) continue;
    const double qlen = n.gradient[q].norm();
    if (!(qlen * cell > 1e-6 * n.mass[q]) || !(qlen > 1.2 * len)) continue;
    const Vec<Dim> face = n.gradient[q] / qlen;
    const double into = grad.dot(face);
    if (into < 0.0) grad -= into * face;
  }
  return grad;
}

// The normal from group `a` toward rigid field `r`: against the rigid body's outward normal (its
// face's, `rgrad`: rigid_face_gradient), which is the cleanest; deep inside it, or where both outward normals
// point nearly the same way (within 60 degrees: a node beyond a thin rigid layer, on its far face, that
// the soil's support reaches through it), along the soil's own outward normal: taking the far face's
// normal there would let the soil through. (The soil's normal follows the grid's staircase; looser
// tests picked it at the risers of an inclined surface and locked a block that should slide.) Zero
// when neither gives a direction.
template <int Dim>
Vec<Dim> rigid_contact_normal(const FieldGroups<Dim>& g, const NodeFields<Dim>& n, const Vec<Dim>& rgrad, int a, int r,
                              double cell) {
  // A gradient this small against sum N V / h means the node is deep inside the rigid body.
  const double rlen = rgrad.norm();
  const bool rigid_normal = rlen * cell > 1e-6 * n.mass[r];
  const double slen = g.gradient[a].norm();
  if (rigid_normal && rgrad.dot(g.gradient[a]) <= 0.5 * rlen * g.gradient[a].norm()) return -rgrad / rlen;
  if (slen * cell > 1e-6 * g.mass[a]) return g.gradient[a] / slen;
  return Vec<Dim>::Zero();
}

// Every group corrected against rigid field `r` once; adds the momentum per unit time it gave them to
// force_on[r] (when dt > 0). Returns whether anything changed.
template <int Dim>
bool resolve_rigid_field(FieldGroups<Dim>& g, const NodeFields<Dim>& n, const ContactRules& rules, int r, double cell,
                         double dt, Vec<Dim>* force_on) {
  bool changed = false;
  const Vec<Dim>& v_r = n.velocity[r];
  const Vec<Dim> face = rigid_face_gradient(n, rules, r, cell);
  for (int a = 0; a < n.count; ++a) {
    if (!g.representative(a)) continue;
    bool glued;
    const double mu = rigid_pair_friction(g, n, rules, a, r, glued);
    Vec<Dim> dv;
    if (glued) {
      dv = v_r - g.velocity[a];
    } else {
      const Vec<Dim> normal = rigid_contact_normal(g, n, face, a, r, cell);
      dv = normal.squaredNorm() > 0.0 ? correction<Dim>(g.velocity[a], v_r, normal, mu) : Vec<Dim>(v_r - g.velocity[a]);
    }
    if (dv.squaredNorm() > 1e-28 * (g.velocity[a].squaredNorm() + v_r.squaredNorm())) changed = true;
    g.velocity[a] += dv;
    if (dt > 0.0 && force_on) force_on[r] += (g.mass[a] / dt) * dv;
  }
  return changed;
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
  contact_detail::FieldGroups<Dim> g(n, rules, min_mass);
  contact_detail::resolve_deformable_pairs(g, n, rules, cell);
  // Where two rigid fields meet (a base and a wall at a corner) one's correction can undo the other's
  // (friction on one pushes along the other's face), so the passes repeat until neither changes anything.
  constexpr int kPasses = 24;
  for (int pass = 0; pass < kPasses; ++pass) {
    bool changed = false;
    for (int r = 0; r < n.count; ++r)
      if (rules.rigid(n.field[r]) && n.mass[r] > 0.0)
        changed = contact_detail::resolve_rigid_field(g, n, rules, r, cell, dt, force_on) || changed;
    if (!changed) break;
  }
  for (int j = 0; j < n.count; ++j) {
    n.group[j] = g.group[j];
    if (g.active[j]) n.velocity[j] = g.velocity[g.group[j]];
  }
}

}  // namespace seismpm
