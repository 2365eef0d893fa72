// The transfers of the step: particles to grid, the nodal update and constraints, grid to particles
// and the MUSL re-map. With Contact, the bodies' own fields at shared nodes are handled by
// ContactFields, and the particles near them read their own field's slots.
#include "contact/rigid_face_mirror.hpp"
#include "held_edges.hpp"
#include "model.hpp"
#include "particle_forces.hpp"

namespace seismpm {

// Nodal mass, momentum and force f = sum N m g - V sigma grad N from every deformable particle: the
// common fields. Rigid particles map only to their own field's slots (ContactFields). Rayleigh damping
// adds to the particle's two terms, before the node loop: f = sum N (m g - alpha m v) - V (sigma + sigma_v) grad N.
template <int Dim>
template <class Shape, bool Contact>
void Model<Dim>::particles_to_grid() {
  const auto& st = support_.template stencils<Shape>();
  const Vec<Dim> g = settings_.gravity - frame_acceleration_;  // the frame's acceleration as a body force
  const bool apic = settings_.transfer == Transfer::Apic;
  const MaterialConstants* damped = constants_.any_rayleigh ? &constants_ : nullptr;
  auto& P = particles_;
  auto& G = grid_;
  support_.schedule.for_each([&](int p) {
    if constexpr (Contact)
      if (contact_.rigid(P.body[p])) return;
    const double m = P.mass[p];
    const Vec<Dim> mv = m * P.v[p];
    const ParticleForceTerms<Dim> t = particle_force_terms(P, damped, g, p);
    const Vec<Dim>& mg = t.mg;
    const Mat<Dim>& vs = t.vs;
    const Mat<Dim> mC = apic ? Mat<Dim>(m * P.affine[p]) : Mat<Dim>::Zero();
    for_each_node_momentum(st[p], G, mv, apic ? &mC : nullptr,
                           [&](int i, double N, const Vec<Dim>& dN, const Vec<Dim>& mvi) {
                             G.mass[i] += N * m;
                             G.momentum[i] += N * mvi;
                             G.force[i] += N * mg - vs * dN;  // f_ext + f_int, f_int = -V sigma . grad N
                           });
  });
  if constexpr (Contact) contact_.template particles_to_fields<Shape>(P, G, support_, g, apic, damped);
}

template <int Dim>
template <bool Contact>
void Model<Dim>::update_nodal_velocities(const StepContext& c) {
  const double dt = c.dt, eps = mass_threshold_;
  auto& G = grid_;
  active_.for_each_range([&](int first, int end) {
    for (int i = first; i < end; ++i) {
      if (G.mass[i] > eps) {
        const double inv_m = 1.0 / G.mass[i];
        G.acceleration[i] = G.force[i] * inv_m;
        G.velocity[i] = G.momentum[i] * inv_m + dt * G.acceleration[i];
      } else {
        G.acceleration[i].setZero();
        G.velocity[i].setZero();
      }
    }
  });
  if constexpr (Contact) contact_.update_velocities(dt, eps);
}

// Contact, then the grid fixities (after the force update with the acceleration that matches them), then
// the fixes.
template <int Dim>
template <bool Contact>
void Model<Dim>::constrain(VelocityStage stage, const StepContext& c) {
  if constexpr (Contact) contact_.resolve(stage, grid_, c.dt, mass_threshold_);
  if (stage == VelocityStage::Updated)
    grid_.hold_updated_velocities(c.dt);
  else
    grid_.apply_fixities(grid_.velocity);
  for (auto& f : fixes_) f->nodal_velocities(*this, c, stage);
}

// FLIP/PIC velocity, position and displacement of every particle; rigid particles move at v_R. With
// `remap` (MUSL), each deformable particle's new momentum goes straight on to the zeroed nodal momentum:
// one pass over the particles instead of two. The gather reads velocity and acceleration, the scatter
// writes only momentum, and the coloured schedule keeps both race-free and every node's sum in the same
// order for any thread count.
template <int Dim>
template <class Shape, bool Contact>
void Model<Dim>::grid_to_particles(const StepContext& c, bool remap) {
  const auto& st = support_.template stencils<Shape>();
  const double dt = c.dt, alpha = settings_.flip;
  const bool apic = settings_.transfer == Transfer::Apic;
  auto& P = particles_;
  auto& G = grid_;
  const auto& S = contact_.nodes();
  const HeldEdges<Dim> held(G);
  if (remap)
    active_.for_each_range([&](int first, int end) {
      for (int i = first; i < end; ++i) G.momentum[i].setZero();
    });
  auto scatter = [&](int p) {
    const Vec<Dim> mv = P.mass[p] * P.v[p];
    const Mat<Dim> mC = apic ? Mat<Dim>(P.mass[p] * P.affine[p]) : Mat<Dim>::Zero();
    for_each_node_momentum(st[p], G, mv, apic ? &mC : nullptr,
                           [&](int i, double N, const Vec<Dim>&, const Vec<Dim>& mvi) { G.momentum[i] += N * mvi; });
  };
  auto update = [&](int p) {
    [[maybe_unused]] int f = 0;
    if constexpr (Contact) {
      const int b = P.body[p];
      if (contact_.rigid(b)) {  // prescribed: moves at v_R, whatever the grid says
        P.x[p] += dt * P.v[p];
        P.u[p] += dt * P.v[p];
        return false;
      }
      f = contact_.field_of(b);
    }
    Vec<Dim> a = Vec<Dim>::Zero(), vl = Vec<Dim>::Zero();
    Mat<Dim> C = Mat<Dim>::Zero();
    Vec<Dim> D = Vec<Dim>::Zero();  // uGIMP: the diagonal of APIC's inertia sum N (x_i - x_p)(x_i - x_p)^T
    bool alone = true;              // APIC: no other particle's (or body's) mass at any node of the stencil
    auto gather = [&](auto slotted, auto affine) {
      auto visit = [&](int i, double N, const Vec<Dim>& dN, const Vec<Dim>& dx) {
        const Vec<Dim>* vi = &G.velocity[i];
        const Vec<Dim>* ai = &G.acceleration[i];
        bool constrained = false;
        if constexpr (decltype(slotted)::value) {
          const int k = S.index(i);
          if (k >= 0) {  // the particle's own field where fields meet
            const int s = S.slot(k, f);
            vi = &S.velocity[s];
            ai = &S.acceleration[s];
            constrained = true;  // contact set this velocity: the gradient must see it
          }
        }
        a += N * *ai;
        vl += N * *vi;
        if constexpr (decltype(affine)::value) {
          // The gradient is measured against the other particles' motion: the part of node i's
          // mass that is this particle's own, share = N m_p / m_i, counts with the particle's own
          // affine velocity. At a node the particle nearly alone reaches, v^L = v + dt f / m_i with
          // m_i ~ N m_p is its own force over a vanishing mass, while grad N stays of order 1/h: that
          // gradient fed back through the affine momentum and threw a particle at a flow front out of
          // the grid (13,000 1/s, 80 m/s at the node ahead of it, in three steps). An affine field is
          // unchanged by this (there the node's velocity and the particle's prediction agree).
          // (P.v and P.affine are still the step's start values here.)
          const double share = constrained ? 0.0 : G.mass[i] > 0.0 ? std::min(1.0, N * P.mass[p] / G.mass[i]) : 1.0;
          if (N > 0.0 && share < 1.0 - 1e-9) alone = false;
          // A node lighter than the particle itself is trusted with no more acceleration than the
          // particle's own mass would give it: where two particles each reach a node with a sliver of
          // weight, the share rule alone still took half of their force over that sliver of mass (a
          // grain at rest at a flow front, touched by one arriving beside it, had its volume turn
          // negative in two steps).
          Vec<Dim> vn = *vi;
          if (!constrained && G.mass[i] < P.mass[p]) vn -= (dt * (1.0 - G.mass[i] / P.mass[p])) * *ai;
          Vec<Dim> vc = (1.0 - share) * vn + share * (P.v[p] + P.affine[p] * dx);
          const unsigned held_dofs = G.fixity(i);  // a held component is the edge's: the gradient must see it
          for (int d = 0; d < Dim; ++d)
            if (held_dofs >> d & 1) vc[d] = (*vi)[d];
          // Linear shapes: sum v grad N^T, which is B D^-1 for them and stays finite where D vanishes
          // (a centre on a node line). uGIMP: B D^-1 itself (B = sum N v (x_i - x_p)^T). There grad N
          // is the hat's gradient averaged over the particle's domain and differs from D^-1 N (x_i - x_p)
          // once the domain straddles a node line, and with it the shear of a flow spread where it
          // should not (a layer sliding on a rough floor sheared through its depth and slid 10 % too far).
          if constexpr (Shape::K > 2) {
            C.noalias() += (N * vc) * dx.transpose();
            D += N * dx.cwiseProduct(dx);
          } else {
            C.noalias() += vc * dN.transpose();
          }
        }
      };
      if constexpr (decltype(affine)::value)
        for_each_node_offset(st[p], G, visit);
      else  // FLIP needs no node offsets
        for_each_node(st[p], G, [&](int i, double N, const Vec<Dim>& dN) { visit(i, N, dN, Vec<Dim>::Zero()); });
    };
    const bool slotted = Contact && contact_.near_shared(support_.cell_of[p]);
    if (slotted)
      apic ? gather(std::true_type{}, std::true_type{}) : gather(std::true_type{}, std::false_type{});
    else if (apic)
      gather(std::false_type{}, std::true_type{});
    else  // FLIP on the common field alone: the row-by-row sums
      a = interpolate(st[p], G, G.acceleration.data()), vl = interpolate(st[p], G, G.velocity.data());
    if (apic) {
      P.v[p] = vl;
      // A particle alone on its nodes has no neighbours to make a gradient with: it carries none. Kept,
      // nothing would ever take it away (no neighbour, no stress), and a grain alone on a floor held in
      // x and y slid on in a shear mode of its own, velocity = C x its height with the floor's zero
      // inside that field (uGIMP, 2 mm cells: 1,160 1/s, 1.2 m/s, out of the grid at 0.57 s).
      if constexpr (Shape::K > 2) C = C * D.cwiseInverse().asDiagonal();  // D > 0: the domain has width
      P.affine[p] = alone ? Mat<Dim>::Zero() : C;
    } else {
      P.v[p] = alpha * (P.v[p] + dt * a) + (1.0 - alpha) * vl;
    }
    // The velocity the particle reads at node i: its own field's where fields meet.
    const auto own_velocity = [&](int i) -> const Vec<Dim>& {
      if constexpr (Contact) {
        const int k = slotted ? S.index(i) : -1;
        if (k >= 0) return S.velocity[S.slot(k, f)];
      }
      return G.velocity[i];
    };
    // The centre must not cross a rigid face it is in contact with (rigid_face_mirror.hpp), nor a held
    // edge (held_edges.hpp). Linear shapes give a node beyond either no weight: their centres near it
    // already move at the linear d v_1 and never reach it.
    if constexpr (Contact && Shape::K == 3)
      if (slotted && contact_.any_rigid()) mirror_rigid_faces(contact_, G, st[p], f, vl, own_velocity);
    const bool near_held = Shape::K > 2 && held.any() && held.near(P.x[p]);
    if (near_held) held.mirror(st[p], vl, own_velocity);
    Vec<Dim> dx = dt * vl;
    // Nor may it enter a rigid body anywhere else (rigid_exclusion.hpp).
    if constexpr (Contact)
      if (slotted && contact_.exclusion().any()) contact_.exclusion().keep_out(f, P.x[p], dx);
    P.x[p] += dx;
    P.u[p] += dx;
    if (near_held) held.keep_inside(P.x[p], P.u[p]);
    return true;
  };
  if (remap) {
    support_.schedule.for_each([&](int p) {
      if (update(p)) scatter(p);
    });
  } else {
    const int n = static_cast<int>(particles_.size());
#pragma omp parallel for schedule(static)
    for (int p = 0; p < n; ++p) update(p);
  }
}

// MUSL: the nodal velocity from the updated particle momentum (scattered by grid_to_particles), for
// the strain increment.
template <int Dim>
template <class Shape, bool Contact>
void Model<Dim>::remap_momentum() {
  auto& G = grid_;
  const double eps = mass_threshold_;
  active_.for_each_range([&](int first, int end) {
    for (int i = first; i < end; ++i)
      G.velocity[i] = G.mass[i] > eps ? Vec<Dim>(G.momentum[i] / G.mass[i]) : Vec<Dim>::Zero();
  });
  if constexpr (Contact)
    contact_.template remap_momentum<Shape>(particles_, G, support_, eps, settings_.transfer == Transfer::Apic);
}

#define SEISMPM_TRANSFERS(D, S, C)                                           \
  template void Model<D>::particles_to_grid<S, C>();                         \
  template void Model<D>::grid_to_particles<S, C>(const StepContext&, bool); \
  template void Model<D>::remap_momentum<S, C>();
#define SEISMPM_NODAL(D, C)                                               \
  template void Model<D>::update_nodal_velocities<C>(const StepContext&); \
  template void Model<D>::constrain<C>(VelocityStage, const StepContext&);
SEISMPM_FOR_EACH_STEP_VARIANT(SEISMPM_TRANSFERS, SEISMPM_NODAL)
#undef SEISMPM_TRANSFERS
#undef SEISMPM_NODAL

}  // namespace seismpm
