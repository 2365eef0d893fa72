#include "contact_fields.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/particle_forces.hpp"
#include "node_contact.hpp"

namespace seismpm {

namespace {

// Calls f(node, offset) for every node at offsets from[d]..to[d] along each axis d of `base` that lies
// in the grid.
template <int Dim, class F>
void for_each_node_in(const Grid<Dim>& grid, const std::array<int, Dim>& base, const std::array<int, Dim>& from,
                      const std::array<int, Dim>& to, F&& f) {
  std::array<int, Dim> o = from;
  for (;;) {
    int i = 0;
    bool inside = true;
    for (int d = 0; d < Dim; ++d) {
      const int n = base[d] + o[d];
      inside = inside && n >= 0 && n < grid.nodes(d);
      i += n * grid.stride(d);
    }
    if (inside) f(i, o);
    int d = 0;
    while (d < Dim && ++o[d] > to[d]) o[d] = from[d], ++d;
    if (d == Dim) break;
  }
}

// Per-cell flags that a step sets and the next one clears: `set` lists the cells flagged. Clears the
// last step's (all of them where the grid has another cell count).
void reset_cell_flags(std::vector<char>& flag, std::vector<int>& set, int cell_count) {
  if (static_cast<int>(flag.size()) != cell_count)
    flag.assign(cell_count, 0);
  else
    for (const int c : set) flag[c] = 0;
  set.clear();
}

// Flags the cells base + o, for the offsets o from..to that lie in the grid's cells.
template <int Dim, class Cells>
void flag_cells_in(const Grid<Dim>& grid, const Cells& cells, const std::array<int, Dim>& base,
                   const std::array<int, Dim>& from, const std::array<int, Dim>& to, std::vector<char>& flag,
                   std::vector<int>& set) {
  for_each_node_in<Dim>(grid, base, from, to, [&](int, const std::array<int, Dim>& o) {
    std::array<int, Dim> c;
    for (int d = 0; d < Dim; ++d) {
      c[d] = base[d] + o[d];
      if (c[d] < 0 || c[d] >= grid.cells(d)) return;
    }
    const int cell = cells.of_coords(c);
    if (!flag[cell]) flag[cell] = 1, set.push_back(cell);
  });
}

}  // namespace

// ---------------------------------------------------------------- building

template <int Dim>
void ContactFields<Dim>::add_body() {
  motion_.emplace_back();
  numbered_ = false;
}

template <int Dim>
ContactPair* ContactFields<Dim>::find_pair(int a, int b) {
  for (auto& c : pairs_)
    if ((c.a == a && c.b == b) || (c.a == b && c.b == a)) return &c;
  return nullptr;
}

template <int Dim>
void ContactFields<Dim>::add_pair(const std::vector<Body>& bodies, int a, int b, double friction) {
  const int n = static_cast<int>(bodies.size());
  if (a < 0 || a >= n || b < 0 || b >= n) throw InputError("contact: unknown body");
  if (a == b) throw InputError("contact: body '" + bodies[a].name + "' cannot be in contact with itself");
  if (!(friction >= 0.0 && std::isfinite(friction))) throw InputError("contact: friction must be a finite number >= 0");
  if (bodies[a].rigid && bodies[b].rigid)
    throw InputError("contact: '" + bodies[a].name + "' and '" + bodies[b].name +
                     "' are both rigid; contact acts between a rigid and a deformable body or two deformable ones");
  if (find_pair(a, b))
    throw InputError("contact: the pair '" + bodies[a].name + "', '" + bodies[b].name + "' is declared already");
  pairs_.push_back(ContactPair{a, b, friction});
  numbered_ = false;
}

template <int Dim>
void ContactFields<Dim>::set_friction(const std::vector<Body>& bodies, int a, int b, double friction) {
  if (!(friction >= 0.0 && std::isfinite(friction))) throw InputError("contact: friction must be a finite number >= 0");
  ContactPair* c = find_pair(a, b);
  if (!c)
    throw InputError("contact: no contact is declared between '" + bodies.at(a).name + "' and '" + bodies.at(b).name +
                     "' (m:contact first)");
  c->friction = friction;
  numbered_ = false;
}

// Field 0 is shared by every deformable body named in no contact pair; every rigid body and every
// body named in a pair gets its own.
template <int Dim>
bool ContactFields<Dim>::prepare(const std::vector<Body>& bodies) {
  if (numbered_) return rules_.fields() > 1;
  const int n = static_cast<int>(bodies.size());
  field_of_body_.assign(n, 0);
  body_rigid_.assign(n, 0);
  int fields = 1;
  for (int b = 0; b < n; ++b) {
    body_rigid_[b] = bodies[b].rigid;
    const bool paired =
        std::any_of(pairs_.begin(), pairs_.end(), [&](const ContactPair& c) { return c.a == b || c.b == b; });
    if (bodies[b].rigid || paired) field_of_body_[b] = fields++;
  }
  if (fields > 32000) throw InputError("model: too many bodies in contact pairs");
  any_rigid_ = std::any_of(body_rigid_.begin(), body_rigid_.end(), [](char r) { return r; });
  rules_.reset(fields);
  body_of_field_.assign(fields, -1);
  for (int b = 0; b < n; ++b) {
    rules_.set_rigid(field_of_body_[b], bodies[b].rigid);
    if (field_of_body_[b] > 0) body_of_field_[field_of_body_[b]] = b;
  }
  for (const auto& c : pairs_) rules_.set_friction(field_of_body_[c.a], field_of_body_[c.b], c.friction);
  numbered_ = true;
  return fields > 1;
}

// ---------------------------------------------------------------- rigid bodies

template <int Dim>
int ContactFields<Dim>::prescribe_rigid_velocities(Particles<Dim>& particles, const Grid<Dim>& grid,
                                                   const std::vector<Body>& bodies, const StepContext& c, bool move) {
  const double t_mid = c.phase_time + 0.5 * c.dt;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (!bodies[b].rigid) continue;
    auto& m = motion_[b];
    for (int d = 0; d < Dim; ++d) m.current[d] = move ? m.velocity[d]->at(t_mid) : 0.0;
    m.force.setZero();
    if (!m.current.allFinite()) {
      std::ostringstream os;
      os << "step " << c.step << " (t = " << c.time << " s): the velocity history of rigid body '" << bodies[b].name
         << "' gave " << format_point<Dim>(m.current) << " m/s at phase time " << t_mid << " s";
      throw SimulationError(os.str());
    }
  }
  const int n = static_cast<int>(particles.size());
  auto& P = particles;
  int leaving = n;
  const DomainBox<Dim> domain(grid);
#pragma omp parallel for schedule(static) reduction(min : leaving)
  for (int p = 0; p < n; ++p) {
    const int b = P.body[p];
    if (!body_rigid_[b]) continue;
    P.v[p] = motion_[b].current;
    if (!domain.contains(Vec<Dim>(P.x[p] + c.dt * P.v[p]))) leaving = std::min(leaving, p);
  }
  if (any_rigid_)
    exclusion_.build(
        P, grid, rules_, c.dt, [&](int b) { return body_rigid_[b] != 0; }, [&](int b) { return field_of_body_[b]; });
  return leaving;
}

// ---------------------------------------------------------------- shared nodes

// Which contact fields touch each node. Marked per cell rather than per particle (a cell's particles
// mostly share a body): a deformable field marks every node its cell's particles can reach, a superset
// whose extra slots stay massless; a rigid field marks the nodes of its cells only (the paper's
// boundary nodes of the rigid body). Then every cell whose particles can reach a shared node is
// flagged, so the transfers look up slots only there.
template <int Dim>
template <class Shape>
void ContactFields<Dim>::mark_shared_nodes(const Particles<Dim>& particles, const Grid<Dim>& grid,
                                           const ParticleSupport<Dim>& support, const StepContext& c) {
  find_plain_fields();
  const int full_cell = mark_cell_fields(particles, grid, support);
  shared_.clear(grid.node_count());
  int overflow = mark_nodes<Shape>(grid, support.cells);
  if (full_cell >= 0) {  // name the cell by its lower corner node
    const auto x = support.cells.coords(full_cell);
    int i = 0;
    for (int d = 0; d < Dim; ++d) i += x[d] * grid.stride(d);
    overflow = i;
  }
  if (overflow >= 0) {
    std::ostringstream os;
    os << "step " << c.step << " (t = " << c.time << " s): more than " << SharedNodes<Dim>::kSlots
       << " contact fields (rigid bodies and bodies in contact pairs) meet near "
       << format_point<Dim>(grid.node_position(overflow));
    throw SimulationError(os.str());
  }
  shared_.build(rules_);
  slot_reaction_.assign(shared_.mass.size(), Vec<Dim>::Zero());
  flag_cells_near_shared<Shape>(grid, support.cells);
  // The particles that the step's contact scatters visit: rigid ones and those near a shared node.
  const auto& P = particles;
  near_particles_.select(support.schedule,
                         [&](int p) { return body_rigid_[P.body[p]] || near_shared_[support.cell_of[p]]; });
}

// The fields of each cell's particles; returns a cell that holds more than FieldSet can, or -1.
// Only the cells the last step occupied are emptied, and each slab lists the cells its particles
// occupy (in the order of its particles: fixed whatever the number of threads), so the marking costs
// what the bodies occupy, not the grid (a block on a base 7 m wide has 11 times fewer cells).
template <int Dim>
int ContactFields<Dim>::mark_cell_fields(const Particles<Dim>& particles, const Grid<Dim>& grid,
                                         const ParticleSupport<Dim>& support) {
  FieldSet empty;
  empty.fill(-1);
  if (static_cast<int>(cell_fields_.size()) != grid.cell_count()) {
    cell_fields_.assign(grid.cell_count(), empty);
  } else {
    for (const auto& list : slab_cells_)
      for (const int c : list) cell_fields_[c] = empty;
  }
  slab_cells_.resize(support.schedule.slabs());
  for (auto& list : slab_cells_) list.clear();
  slab_kept_apart_.resize(support.schedule.slabs());
  for (auto& list : slab_kept_apart_) list.clear();
  std::atomic<int> full_cell{-1};
  const auto& cell_of = support.cell_of;
  support.schedule.for_each_in_own_cell_by_slab([&](int slab, int p) {  // slabs hold disjoint cells
    const int cell = cell_of[p], f = field_of_body_[particles.body[p]];
    FieldSet& fs = cell_fields_[cell];
    if (fs[0] < 0) slab_cells_[slab].push_back(cell);
    if (!plain_[f] && std::all_of(fs.begin(), fs.end(), [&](int g) { return g < 0 || plain_[g]; }))
      slab_kept_apart_[slab].push_back(cell);  // its first field kept apart from others
    if (!add_field(fs, f)) full_cell.store(cell, std::memory_order_relaxed);
  });
  return full_cell.load();
}

// Every node each cell's fields reach; returns a node that more than kSlots fields meet at, or -1.
// Slabs of one colour never reach the same node (ScatterSchedule), so the nodes they mark never meet. A cell that
// follows its left neighbour in the list with the same fields marks only its last column of nodes: the neighbour has
// marked the others with those fields already, so the marks, and the order in which nodes are first
// marked, are those of marking every node (the slab's particles are sorted by cell, so most cells
// follow their left neighbour).
//
// A plain field (flag_cells_near_kept_apart) marks only from the cells whose nodes a field kept apart
// from others may reach: a node no such field reaches is never shared, whatever plain fields meet
// there. Every plain cell that reaches a shared node is one of those, so each shared node gets the
// same fields in the same order, and comes first in the same place, as when every cell marks; only
// nodes that can never be shared go unmarked (most of a slope in a rigid box: its nodes cost a mark,
// a clear and a look in build every step).
template <int Dim>
template <class Shape>
int ContactFields<Dim>::mark_nodes(const Grid<Dim>& grid, const CellIndex<Dim>& cells) {
  const bool some_plain = flag_cells_near_kept_apart<Shape>(grid, cells);
  const int slabs = static_cast<int>(slab_cells_.size());
  slab_nodes_.resize(slabs);
  for (auto& list : slab_nodes_) list.clear();  // also of slabs without cells now, which no thread visits
  std::atomic<int> overflow{-1};
  // Each thread a contiguous run of a colour's slabs, shared by their cells (handed out one by one,
  // the slabs went to the threads in no order and two threads gained little over one).
  auto cells_of = [&](int sl) { return static_cast<long>(slab_cells_[sl].size()); };
  ScatterSchedule::by_colour(slabs, cells_of, [&](int sl) {
    auto& touched = slab_nodes_[sl];
    std::array<int, Dim> last{};
    const FieldSet* last_fields = nullptr;
    bool last_near = false;
    for (const int c : slab_cells_[sl]) {
      const FieldSet& fs = cell_fields_[c];
      const auto coords = cells.coords(c);
      bool follows = last_fields && *last_fields == fs && coords[0] == last[0] + 1;
      for (int d = 1; d < Dim; ++d) follows = follows && coords[d] == last[d];
      const bool near = !some_plain || near_kept_apart_[c];
      last = coords;
      last_fields = &fs;
      for (const int f : fs) {
        if (f < 0) break;
        const bool plain = some_plain && plain_[f];
        if (plain && !near) continue;
        const bool rigid = rules_.rigid(f);
        std::array<int, Dim> lo, hi;
        lo.fill(rigid ? 0 : Shape::kReachLo);
        hi.fill(rigid ? 1 : Shape::kReachHi);
        if (follows && (!plain || last_near)) lo[0] = hi[0];  // the neighbour marked the rest
        for_each_node_in<Dim>(grid, coords, lo, hi, [&](int i, const std::array<int, Dim>&) {
          if (!shared_.mark(i, f, touched)) overflow.store(i, std::memory_order_relaxed);
        });
      }
      last_near = near;
    }
  });
  auto& all = shared_.touched();
  for (const auto& list : slab_nodes_) all.insert(all.end(), list.begin(), list.end());
  return overflow.load();
}

// Plain fields: deformable ones glued to every other deformable field (no contact pair between
// them, or one glued), such as the soil in a rigid box. Only where a field that is kept apart from
// others (rigid, or in a contact pair with another deformable field that is not glued) also reaches
// can their nodes be shared.
template <int Dim>
void ContactFields<Dim>::find_plain_fields() {
  const int fields = rules_.fields();
  plain_.assign(fields, 1);
  for (int f = 0; f < fields; ++f)
    if (rules_.rigid(f)) plain_[f] = 0;
  for (const auto& c : pairs_) {
    const int a = field_of_body_[c.a], b = field_of_body_[c.b];
    if (!rules_.rigid(a) && !rules_.rigid(b) && !rules_.glued(a, b)) plain_[a] = plain_[b] = 0;
  }
}

// Flags the cells from which a plain field's nodes (Shape's reach) meet those of a field kept apart
// (a rigid field: its own cell's nodes); returns false, flagging nothing, where no field is plain or
// the kept-apart fields fill more than a quarter of the occupied cells (deformable bodies in contact
// pairs): flagging around each of their cells would cost more than the marks it saves. Serial: the
// kept-apart fields are mostly rigid walls and bases, a few cells.
template <int Dim>
template <class Shape>
bool ContactFields<Dim>::flag_cells_near_kept_apart(const Grid<Dim>& grid, const CellIndex<Dim>& cells) {
  reset_cell_flags(near_kept_apart_, near_kept_apart_cells_, grid.cell_count());
  if (std::none_of(plain_.begin(), plain_.end(), [](char p) { return p; })) return false;
  std::size_t occupied = 0, kept_apart = 0;
  for (std::size_t s = 0; s < slab_cells_.size(); ++s)
    occupied += slab_cells_[s].size(), kept_apart += slab_kept_apart_[s].size();
  if (kept_apart * 4 > occupied) return false;
  for (const auto& list : slab_kept_apart_)
    for (const int c : list) {
      bool rigid = true;  // reaching only its own cell's nodes: every kept-apart field of the cell rigid
      for (const int f : cell_fields_[c]) {
        if (f < 0) break;
        if (!plain_[f]) rigid = rigid && rules_.rigid(f);
      }
      // A plain cell c' reaches nodes c' + kReachLo .. c' + kReachHi, this one c + lo .. c + hi: they
      // meet for c' in c + lo - kReachHi .. c + hi - kReachLo.
      std::array<int, Dim> from, to;
      from.fill((rigid ? 0 : Shape::kReachLo) - Shape::kReachHi);
      to.fill((rigid ? 1 : Shape::kReachHi) - Shape::kReachLo);
      flag_cells_in<Dim>(grid, cells, cells.coords(c), from, to, near_kept_apart_, near_kept_apart_cells_);
    }
  return true;
}

// Cells whose deformable particles can reach a shared node: c - hi .. c - lo around it.
template <int Dim>
template <class Shape>
void ContactFields<Dim>::flag_cells_near_shared(const Grid<Dim>& grid, const CellIndex<Dim>& cells) {
  reset_cell_flags(near_shared_, near_cells_, grid.cell_count());
  std::array<int, Dim> from, to;
  from.fill(-Shape::kReachHi);
  to.fill(-Shape::kReachLo);
  for (int k = 0; k < shared_.count(); ++k)
    flag_cells_in<Dim>(grid, cells, grid.node_coords(shared_.node(k)), from, to, near_shared_, near_cells_);
}

template <int Dim>
bool ContactFields<Dim>::held(int k) const {
  bool rigid = false;
  for (int j = 0; j < shared_.fields(k); ++j)
    rigid = rigid || rules_.rigid(shared_.field_of_slot(k * SharedNodes<Dim>::kSlots + j));
  return rigid;
}

// ---------------------------------------------------------------- transfers

// The second, short pass of particles to grid, over the particles that can reach a shared node: it
// keeps the common one as lean as with a single field.
template <int Dim>
template <class Shape>
void ContactFields<Dim>::particles_to_fields(const Particles<Dim>& particles, const Grid<Dim>& grid,
                                             const ParticleSupport<Dim>& support, const Vec<Dim>& gravity, bool apic,
                                             const MaterialConstants* damped) {
  const auto& st = support.template stencils<Shape>();
  const auto& P = particles;
  const auto& G = grid;
  auto& S = shared_;
  const Vec<Dim> g = gravity;
  near_particles_.for_each([&](int p) {
    const int b = P.body[p];
    const int f = field_of_body_[b];
    if (body_rigid_[b]) {
      // Only the rigid body's own slots: weights N V for Eq. 9, and for contact normals either the
      // weighted average of the particles' face normals or, without them, sum V grad N.
      const double w = P.volume[p];
      const Vec<Dim> wv = w * P.v[p];
      const Vec<Dim>& face = P.normal[p];
      const bool has_face = face.squaredNorm() > 0.0;
      for_each_node(st[p], G, [&](int i, double N, const Vec<Dim>& dN) {
        const int k = S.index(i);
        const int s = k >= 0 ? S.slot(k, f) : -1;
        if (s < 0) return;
        S.mass[s] += N * w;
        S.momentum[s] += N * wv;
        if (has_face)
          S.gradient[s] += (N * w) * face;
        else
          S.gradient[s] += w * dN;
      });
      return;
    }
    const double m = P.mass[p];
    const Vec<Dim> mv = m * P.v[p];
    const ParticleForceTerms<Dim> t = particle_force_terms(P, damped, g, p);  // with Rayleigh damping's
    const Vec<Dim>& mg = t.mg;
    const Mat<Dim>& vs = t.vs;
    const Mat<Dim> mC = apic ? Mat<Dim>(m * P.affine[p]) : Mat<Dim>::Zero();
    for_each_node_momentum(st[p], G, mv, apic ? &mC : nullptr,
                           [&](int i, double N, const Vec<Dim>& dN, const Vec<Dim>& mvi) {
                             const int k = S.index(i);
                             if (k < 0) return;
                             const int s = S.slot(k, f);
                             S.mass[s] += N * m;
                             S.momentum[s] += N * mvi;
                             S.force[s] += N * mg - vs * dN;
                             S.gradient[s] += m * dN;
                           });
  });
}

template <int Dim>
void ContactFields<Dim>::update_velocities(double dt, double min_mass) {
  auto& S = shared_;
  const int count = S.count();
  const double eps = min_mass;
#pragma omp parallel for schedule(static)
  for (int k = 0; k < count; ++k)
    for (int j = 0; j < S.fields(k); ++j) {
      const int s = k * SharedNodes<Dim>::kSlots + j;
      S.acceleration[s].setZero();
      S.velocity[s].setZero();
      if (rules_.rigid(S.field_of_slot(s))) {
        if (S.mass[s] > 0.0) S.velocity[s] = S.momentum[s] / S.mass[s];
      } else if (S.mass[s] > eps) {
        S.acceleration[s] = S.force[s] / S.mass[s];
        S.velocity[s] = S.momentum[s] / S.mass[s] + dt * S.acceleration[s];
      }
    }
}

template <int Dim>
void ContactFields<Dim>::resolve(VelocityStage stage, const Grid<Dim>& grid, double dt, double min_mass) {
  const int count = shared_.count();
  const bool updated = stage == VelocityStage::Updated;
#pragma omp parallel for schedule(static)
  for (int k = 0; k < count; ++k) resolve_node(k, updated, grid, dt, min_mass);
  if (updated) sum_reactions(dt);
}

// The fields at shared node k as the node-level contact code takes them.
template <int Dim>
NodeFields<Dim> ContactFields<Dim>::node_fields(int k) const {
  constexpr int kSlots = SharedNodes<Dim>::kSlots;
  const auto& S = shared_;
  NodeFields<Dim> nf;
  nf.count = S.fields(k);
  for (int j = 0; j < nf.count; ++j) {
    const int s = k * kSlots + j;
    nf.field[j] = S.field_of_slot(s);
    nf.mass[j] = S.mass[s];
    nf.gradient[j] = S.gradient[s];
    nf.velocity[j] = S.velocity[s];
  }
  return nf;
}

template <int Dim>
void ContactFields<Dim>::resolve_node(int k, bool updated, const Grid<Dim>& grid, double dt, double min_mass) {
  constexpr int kSlots = SharedNodes<Dim>::kSlots;
  auto& S = shared_;
  NodeFields<Dim> nf = node_fields(k);
  Vec<Dim> force_on[kSlots];
  for (auto& f : force_on) f.setZero();
  resolve_contact<Dim>(nf, rules_, min_mass, grid.cell(), updated ? dt : 0.0, force_on);
  const unsigned mask = grid.fixity(S.node(k));
  for (int j = 0; j < nf.count; ++j) {
    const int s = k * kSlots + j;
    if (rules_.rigid(nf.field[j])) {
      if (updated) slot_reaction_[s] = force_on[j];
      // The position update reads it (rigid_face_mirror.hpp).
      S.face[s] = contact_detail::rigid_face_gradient(nf, rules_, j, grid.cell());
      continue;
    }
    if (!(S.mass[s] > min_mass)) continue;
    S.velocity[s] = nf.velocity[j];
    for (int d = 0; d < Dim; ++d)
      if (mask >> d & 1) S.velocity[s][d] = 0.0;
    if (updated) S.acceleration[s] = (S.velocity[s] - group_start_velocity(k, nf, j, min_mass)) / dt;
  }
}

// The velocity at the start of the step of the glued group slot j belongs to. Glued fields move as
// one body: a particle's FLIP increment must be the group's velocity change, as in a single field;
// measured from its own field's start velocity it would pull every particle at the interface toward
// the group's velocity on each step.
template <int Dim>
Vec<Dim> ContactFields<Dim>::group_start_velocity(int k, const NodeFields<Dim>& nf, int j, double min_mass) const {
  constexpr int kSlots = SharedNodes<Dim>::kSlots;
  const auto& S = shared_;
  double mass = 0.0;
  Vec<Dim> momentum = Vec<Dim>::Zero();
  for (int l = 0; l < nf.count; ++l) {
    const int s = k * kSlots + l;
    if (nf.group[l] != nf.group[j] || rules_.rigid(nf.field[l]) || !(S.mass[s] > min_mass)) continue;
    mass += S.mass[s];
    momentum += S.momentum[s];
  }
  return momentum / mass;
}

// Local damping of the fields' own forces where fields meet, except where a rigid field is present.
// A glued group is damped as the one body it is, on its net force: damping each member on its own
// force would act on the large, opposite internal forces across the interface, which do not vanish
// at equilibrium, and keep the interface moving.
template <int Dim>
void ContactFields<Dim>::damp_forces(double alpha, double min_mass) {
  constexpr int kSlots = SharedNodes<Dim>::kSlots;
  auto& S = shared_;
  const int count = S.count();
#pragma omp parallel for schedule(static)
  for (int k = 0; k < count; ++k) {
    if (held(k)) continue;
    const NodeFields<Dim> nf = node_fields(k);
    const contact_detail::FieldGroups<Dim> g(nf, rules_, min_mass);
    for (int j = 0; j < nf.count; ++j) {
      // A field below the minimum mass is in no group: it is damped on its own force.
      const bool alone = !g.active[j];
      if (!alone && !g.representative(j)) continue;
      const auto member = [&](int l) { return alone ? l == j : g.active[l] && g.group[l] == j; };
      Vec<Dim> force = Vec<Dim>::Zero(), momentum = Vec<Dim>::Zero();
      for (int l = 0; l < nf.count; ++l)
        if (member(l)) force += S.force[k * kSlots + l], momentum += S.momentum[k * kSlots + l];
      for (int d = 0; d < Dim; ++d) {
        const double v = momentum[d];  // same sign as the group's velocity
        const double sign = (v > 0.0) - (v < 0.0);
        const double damping = -(alpha * std::abs(force[d]) * sign);
        for (int l = 0; l < nf.count; ++l)
          if (member(l)) {
            const int s = k * kSlots + l;
            S.force[s][d] += alone ? damping : (S.mass[s] / g.mass[j]) * damping;
          }
      }
    }
  }
}

// The force of each rigid body on the deformable ones, summed in a fixed order.
template <int Dim>
void ContactFields<Dim>::sum_reactions(double dt) {
  constexpr int kSlots = SharedNodes<Dim>::kSlots;
  const auto& S = shared_;
  for (int s = 0, n = static_cast<int>(slot_reaction_.size()); s < n; ++s) {
    if (s % kSlots >= S.fields(s / kSlots)) continue;
    const int f = S.field_of_slot(s);
    if (rules_.rigid(f)) motion_[body_of_field_[f]].force += slot_reaction_[s];
  }
  for (std::size_t b = 0; b < motion_.size(); ++b)
    if (body_rigid_[b]) motion_[b].impulse += dt * motion_[b].force;
}

template <int Dim>
template <class Shape>
void ContactFields<Dim>::remap_momentum(const Particles<Dim>& particles, const Grid<Dim>& grid,
                                        const ParticleSupport<Dim>& support, double min_mass, bool apic) {
  constexpr int kSlots = SharedNodes<Dim>::kSlots;
  const auto& st = support.template stencils<Shape>();
  const auto& P = particles;
  auto& S = shared_;
  for (std::size_t s = 0; s < S.momentum.size(); ++s)
    if (s % kSlots < static_cast<std::size_t>(S.fields(static_cast<int>(s / kSlots))) &&
        !rules_.rigid(S.field_of_slot(static_cast<int>(s))))
      S.momentum[s].setZero();
  near_particles_.for_each([&](int p) {
    const int b = P.body[p];
    if (body_rigid_[b]) return;  // the selection holds only these and particles near a shared node
    const int f = field_of_body_[b];
    const Vec<Dim> mv = P.mass[p] * P.v[p];
    const Mat<Dim> mC = apic ? Mat<Dim>(P.mass[p] * P.affine[p]) : Mat<Dim>::Zero();
    for_each_node_momentum(st[p], grid, mv, apic ? &mC : nullptr,
                           [&](int i, double N, const Vec<Dim>&, const Vec<Dim>& mvi) {
                             const int k = S.index(i);
                             if (k >= 0) S.momentum[S.slot(k, f)] += N * mvi;
                           });
  });
  const int count = S.count();
#pragma omp parallel for schedule(static)
  for (int k = 0; k < count; ++k)
    for (int j = 0; j < S.fields(k); ++j) {
      const int s = k * kSlots + j;
      if (rules_.rigid(S.field_of_slot(s))) continue;
      S.velocity[s] = S.mass[s] > min_mass ? Vec<Dim>(S.momentum[s] / S.mass[s]) : Vec<Dim>::Zero();
    }
}

#define SEISMPM_CONTACT_SHAPE(D, S)                                                                                    \
  template void ContactFields<D>::mark_shared_nodes<S>(const Particles<D>&, const Grid<D>&, const ParticleSupport<D>&, \
                                                       const StepContext&);                                            \
  template void ContactFields<D>::particles_to_fields<S>(                                                              \
      const Particles<D>&, const Grid<D>&, const ParticleSupport<D>&, const Vec<D>&, bool, const MaterialConstants*);  \
  template void ContactFields<D>::remap_momentum<S>(const Particles<D>&, const Grid<D>&, const ParticleSupport<D>&,    \
                                                    double, bool);
SEISMPM_CONTACT_SHAPE(2, LinearShape)
SEISMPM_CONTACT_SHAPE(2, GimpShape)
SEISMPM_CONTACT_SHAPE(3, LinearShape)
SEISMPM_CONTACT_SHAPE(3, GimpShape)
#undef SEISMPM_CONTACT_SHAPE

template class ContactFields<2>;
template class ContactFields<3>;

}  // namespace seismpm
