#include "model.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>

#include "error.hpp"
#include "objective_rate.hpp"

#include <omp.h>

namespace seismpm {

namespace {

template <int Dim>
Mat<Dim> in_plane(const Sym& s) {
  Mat<Dim> m;
  if constexpr (Dim == 2) {
    m << s[0], s[3], s[3], s[1];
  } else {
    m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  }
  return m;
}

template <int Dim>
std::string format_point(const Vec<Dim>& x) {
  std::ostringstream os;
  os.precision(6);
  os << "(";
  for (int d = 0; d < Dim; ++d) os << (d ? ", " : "") << x[d];
  os << ")";
  return os.str();
}

}  // namespace

template <int Dim>
Model<Dim>::Model(const ModelSettings<Dim>& settings)
    : settings_(settings), grid_(settings.lower, settings.upper, settings.cell, 1) {
  for (int d = 0; d < Dim; ++d)
    if (grid_.domain_cells(d) < 2) throw InputError("model: the domain must span at least 2 cells along every axis");
  for (int d = Dim - 1; d >= 0; --d)
    if (grid_.cells(d) > grid_.cells(slab_axis_)) slab_axis_ = d;
  if (!(settings.cfl > 0.0 && settings.cfl <= 1.0)) throw InputError("model: cfl must be in (0, 1]");
  if (!(settings.flip >= 0.0 && settings.flip <= 1.0)) throw InputError("model: flip must be in [0, 1]");
  if (!(settings.fixed_dt >= 0.0)) throw InputError("model: fixed_dt must be >= 0");
  if (settings.sort_every < 1) throw InputError("model: sort_every must be >= 1");
  if (!(settings.max_dilation == 0.0 || settings.max_dilation >= 1.0))
    throw InputError("model: max_dilation must be 0 (no limit) or >= 1");
}

// ---------------------------------------------------------------- building

template <int Dim>
int Model<Dim>::add_material(std::shared_ptr<const Material> material) {
  if (!material) throw InputError("model: null material");
  if (materials_.size() >= 65535) throw InputError("model: too many materials");
  p_wave_modulus_.push_back(material->p_wave_modulus());
  initial_density_.push_back(material->density());
  tensionless_.push_back(material->tensionless());
  materials_.push_back(std::move(material));
  material_lists_valid_ = false;
  return static_cast<int>(materials_.size()) - 1;
}

template <int Dim>
int Model<Dim>::add_body(const std::string& name, int ppc, bool rigid) {
  if (rigid) {  // at rest until given a velocity
    std::array<std::shared_ptr<const History>, Dim> zero;
    zero.fill(std::make_shared<ConstantHistory>(0.0));
    return add_rigid_body(name, ppc, 1000.0, zero);
  }
  return new_body(name, ppc, false);
}

template <int Dim>
int Model<Dim>::new_body(const std::string& name, int ppc, bool rigid) {
  if (ppc < 1 || ppc > 16) throw InputError("body '" + name + "': ppc must be in [1, 16]");
  if (bodies_.size() >= 65535) throw InputError("model: too many bodies");
  bodies_.push_back(Body{name, ppc, rigid, -1});
  motion_.emplace_back();
  fields_valid_ = false;
  return static_cast<int>(bodies_.size()) - 1;
}

template <int Dim>
int Model<Dim>::add_rigid_body(const std::string& name, int ppc, double density,
                               const std::array<std::shared_ptr<const History>, Dim>& velocity) {
  if (!(density > 0.0 && std::isfinite(density))) throw InputError("rigid body '" + name + "': density must be > 0");
  const int body = new_body(name, ppc, true);
  bodies_[body].material = add_material(std::make_shared<RigidMaterial>(density));
  set_rigid_velocity(body, velocity);
  return body;
}

template <int Dim>
void Model<Dim>::set_rigid_velocity(int body, const std::array<std::shared_ptr<const History>, Dim>& velocity) {
  if (body < 0 || body >= static_cast<int>(bodies_.size()) || !bodies_[body].rigid)
    throw InputError("set_rigid_velocity: not a rigid body");
  for (const auto& h : velocity)
    if (!h) throw InputError("rigid body '" + bodies_[body].name + "': missing velocity history");
  motion_[body].velocity = velocity;
}

template <int Dim>
void Model<Dim>::add_contact(int a, int b, double friction) {
  const int n = static_cast<int>(bodies_.size());
  if (a < 0 || a >= n || b < 0 || b >= n) throw InputError("contact: unknown body");
  if (a == b) throw InputError("contact: body '" + bodies_[a].name + "' cannot be in contact with itself");
  if (!(friction >= 0.0 && std::isfinite(friction)))
    throw InputError("contact: friction must be a finite number >= 0");
  if (bodies_[a].rigid && bodies_[b].rigid)
    throw InputError("contact: '" + bodies_[a].name + "' and '" + bodies_[b].name +
                     "' are both rigid; contact acts between a rigid and a deformable body or two deformable ones");
  if (find_contact(a, b))
    throw InputError("contact: the pair '" + bodies_[a].name + "', '" + bodies_[b].name + "' is declared already");
  contacts_.push_back(ContactPair{a, b, friction});
  fields_valid_ = false;
}

template <int Dim>
void Model<Dim>::set_contact_friction(int a, int b, double friction) {
  if (!(friction >= 0.0 && std::isfinite(friction))) throw InputError("contact: friction must be a finite number >= 0");
  ContactPair* c = find_contact(a, b);
  if (!c)
    throw InputError("contact: no contact is declared between '" + bodies_.at(a).name + "' and '" + bodies_.at(b).name +
                     "' (m:contact first)");
  c->friction = friction;
  fields_valid_ = false;
}

template <int Dim>
ContactPair* Model<Dim>::find_contact(int a, int b) {
  for (auto& c : contacts_)
    if ((c.a == a && c.b == b) || (c.a == b && c.b == a)) return &c;
  return nullptr;
}

template <int Dim>
void Model<Dim>::begin_phase(bool rigid_bodies_move) {
  phase_start_ = time_;
  rigid_bodies_move_ = rigid_bodies_move;
}

// Field 0 is shared by every deformable body named in no contact pair; every rigid body and every
// body named in a pair gets its own.
template <int Dim>
void Model<Dim>::rebuild_contact_fields() {
  const int n = static_cast<int>(bodies_.size());
  field_of_body_.assign(n, 0);
  body_rigid_.assign(n, 0);
  int fields = 1;
  for (int b = 0; b < n; ++b) {
    body_rigid_[b] = bodies_[b].rigid;
    const bool paired = std::any_of(contacts_.begin(), contacts_.end(), [&](const ContactPair& c) { return c.a == b || c.b == b; });
    if (bodies_[b].rigid || paired) field_of_body_[b] = fields++;
  }
  if (fields > 32000) throw InputError("model: too many bodies in contact pairs");
  rules_.reset(fields);
  body_of_field_.assign(fields, -1);  // a rigid or paired body's own field; field 0 may hold many
  for (int b = 0; b < n; ++b) {
    rules_.set_rigid(field_of_body_[b], bodies_[b].rigid);
    if (field_of_body_[b] > 0) body_of_field_[field_of_body_[b]] = b;
  }
  for (const auto& c : contacts_) rules_.set_friction(field_of_body_[c.a], field_of_body_[c.b], c.friction);
  fields_valid_ = true;
}

template <int Dim>
std::size_t Model<Dim>::fill(int body, int material, const Vec<Dim>& lo, const Vec<Dim>& hi,
                             const std::function<bool(const Vec<Dim>&)>& inside,
                             const std::function<Vec<Dim>(const Vec<Dim>&)>& outward) {
  if (body < 0 || body >= static_cast<int>(bodies_.size())) throw InputError("fill: unknown body");
  if (bodies_[body].rigid) material = bodies_[body].material;
  if (material < 0 || material >= material_count()) throw InputError("fill: unknown material");
  double candidates = 1.0;  // sub-points in the box: refuse what would exhaust memory
  for (int d = 0; d < Dim; ++d) candidates *= std::max(0.0, (hi[d] - lo[d]) / grid_.cell() + 2.0) * bodies_[body].ppc;
  if (candidates > 2e8) throw InputError("fill: over 200 million particles; use a larger cell or fewer ppc");
  const int ppc = bodies_[body].ppc;
  const double h = grid_.cell();
  const double sub = h / ppc;
  const double volume = std::pow(sub, Dim);
  const double mass = materials_[material]->density() * volume;
  const double half_width = 0.5 / ppc;  // cell units

  // Cells overlapping the box, clamped to the domain (not the ghost layers).
  const int g = grid_.ghost();
  std::array<int, Dim> c0{}, c1{};
  for (int d = 0; d < Dim; ++d) {
    c0[d] = std::max(g, static_cast<int>(std::floor((lo[d] - grid_.origin()[d]) / h)));
    c1[d] = std::min(grid_.cells(d) - 1 - g, static_cast<int>(std::floor((hi[d] - grid_.origin()[d]) / h)));
    if (c1[d] < c0[d]) return 0;
  }
  std::size_t added = 0;
  std::array<int, Dim> c = c0;
  std::array<int, Dim> k{};
  // Odometer over cells x sub-points, last axis slowest.
  for (;;) {
    for (k.fill(0);;) {
      Vec<Dim> x;
      for (int d = 0; d < Dim; ++d) x[d] = grid_.origin()[d] + c[d] * h + (k[d] + 0.5) * sub;
      bool in_box = true;
      for (int d = 0; d < Dim; ++d) in_box = in_box && x[d] >= lo[d] && x[d] <= hi[d];
      if (in_box && inside(x)) {
        const std::size_t p = particles_.add(x, mass, volume, half_width, body, material);
        if (outward && bodies_[body].rigid) particles_.normal[p] = outward(x);
        index_of_id_.clear();
        ++added;
      }
      int d = 0;
      while (d < Dim && ++k[d] == ppc) k[d++] = 0;
      if (d == Dim) break;
    }
    int d = 0;
    while (d < Dim && ++c[d] > c1[d]) c[d] = c0[d], ++d;
    if (d == Dim) break;
  }
  if (added && !bodies_[body].rigid) {
    mass_threshold_ = std::max(mass_threshold_, 1e-15 * mass);
  }
  if (added) material_lists_valid_ = false;
  return added;
}

template <int Dim>
std::size_t Model<Dim>::fill_box(int body, int material, const Vec<Dim>& lo, const Vec<Dim>& hi) {
  return fill(body, material, lo, hi, [](const Vec<Dim>&) { return true; });
}

template <int Dim>
void Model<Dim>::add_fix(std::shared_ptr<Fix<Dim>> fix) {
  if (!fix) throw InputError("model: null fix");
  fixes_.push_back(std::move(fix));
}

// ---------------------------------------------------------------- the step

template <int Dim>
void Model<Dim>::step(double dt_max) {
  if (particles_.size() == 0) throw InputError("model: no particles to step");
  double dt = settings_.fixed_dt > 0.0 ? settings_.fixed_dt : stable_time_step();
  dt = std::min(dt, dt_max);
  if (first_dt_ == 0.0) first_dt_ = dt;
  if (!std::isfinite(dt) || (dt < 1e-6 * first_dt_ && dt < dt_max)) {
    // Name the particle that sets the time step: the fastest signal.
    std::size_t fastest = 0;
    double speed = -1.0;
    for (std::size_t p = 0; p < particles_.size(); ++p) {
      const double c = signal_speed(p);
      if (!(c <= speed)) fastest = p, speed = c;
    }
    std::ostringstream os;
    os << "the time step collapsed to " << dt << " s (first step " << first_dt_ << " s): wave speed + velocity "
       << speed << " m/s";
    fail(fastest, "sets it: " + os.str());
  }
  if (settings_.shape == ShapeKind::Linear)
    step_with<LinearShape>(dt);
  else
    step_with<GimpShape>(dt);
}

// One explicit MPM step, in the order of the method (PHYSICS.md, "One explicit step"). With contact
// fields (rigid bodies, contact pairs) the nodes where fields meet carry a velocity per field.
template <int Dim>
template <class Shape>
void Model<Dim>::step_with(double dt) {
  double t = settings_.profile ? omp_get_wtime() : 0.0;
  dt_ = dt;
  if (!fields_valid_) rebuild_contact_fields();
  const bool multi = rules_.fields() > 1;
  for (auto& f : fixes_) f->before_step(*this);
  if (multi) assign_rigid_velocities();  // v_R(t) on the rigid particles
  grid_.reset();
  lap("reset", t);
  compute_stencils<Shape>();        // shape functions at the start-of-step positions
  lap("stencils", t);
  if (multi) {
    mark_shared_nodes<Shape>();     // which nodes more than one contact field touches
    lap("contact fields", t);
    particles_to_grid<Shape, true>();
  } else {
    particles_to_grid<Shape, false>();  // nodal mass, momentum, internal + external force
  }
  lap("particles to grid", t);
  if (measure_balance_) measure_balance();
  for (auto& f : fixes_) f->nodal_forces(*this);  // e.g. local damping
  update_nodal_velocities();        // a = f/m, v^L = mv/m + dt a
  if (multi) update_shared_velocities();
  constrain_velocities(VelocityStage::Updated);  // contact, fixities, prescribed nodes
  lap("nodes", t);
  if (multi)
    grid_to_particles<Shape, true>();
  else
    grid_to_particles<Shape, false>();  // FLIP/PIC velocity, position, displacement
  lap("grid to particles", t);
  if (settings_.scheme == Scheme::Musl) {
    // Nodal velocity from the updated particle momentum.
    if (multi)
      remap_momentum<Shape, true>();
    else
      remap_momentum<Shape, false>();
    constrain_velocities(VelocityStage::Remapped);
  }
  lap("MUSL re-map", t);
  if (multi)
    update_stress<Shape, true>();
  else
    update_stress<Shape, false>();  // velocity gradient, objective rate, constitutive model, volume
  lap("stress", t);
  time_ += dt;
  ++steps_;
  for (auto& f : fixes_) f->after_step(*this);
  check_particles();
  if (steps_ % settings_.sort_every == 0) sort_particles();
  lap("checks and sorting", t);
}

template <int Dim>
void Model<Dim>::lap(const char* stage, double& since) {
  if (!settings_.profile) return;
  const double now = omp_get_wtime();
  auto it = std::find_if(stage_times_.begin(), stage_times_.end(), [&](const auto& s) { return s.first == stage; });
  if (it == stage_times_.end()) it = stage_times_.insert(stage_times_.end(), {stage, 0.0});
  it->second += now - since;
  since = now;
}

template <int Dim>
void Model<Dim>::run(double duration) {
  if (!(duration >= 0.0)) throw InputError("run: duration must be >= 0");
  const double end = time_ + duration;
  // Steps shorter than 1e-9 of the duration are round-off, not time.
  while (end - time_ > 1e-9 * std::max(duration, 1e-300)) step(end - time_);
}

template <int Dim>
double Model<Dim>::stable_time_step() const {
  const int n = static_cast<int>(particles_.size());
  double max_speed = 0.0;
#pragma omp parallel for schedule(static) reduction(max : max_speed)
  for (int p = 0; p < n; ++p) {
    max_speed = std::max(max_speed, signal_speed(p));
  }
  return settings_.cfl * grid_.cell() / max_speed;
}

template <int Dim>
template <class Shape>
std::vector<Stencil<Dim, Shape::K>>& Model<Dim>::stencils() {
  if constexpr (std::is_same_v<Shape, LinearShape>)
    return linear_stencils_;
  else
    return gimp_stencils_;
}

template <int Dim>
template <class Shape>
void Model<Dim>::compute_stencils() {
  auto& st = stencils<Shape>();
  const int n = static_cast<int>(particles_.size());
  st.resize(n);
  int outside = n;
#pragma omp parallel for schedule(static) reduction(min : outside)
  for (int p = 0; p < n; ++p)
    if (!make_stencil<Shape>(grid_, particles_.x[p], particles_.half_width[p], st[p])) outside = std::min(outside, p);
  if (outside < n) fail(outside, "is outside the grid");

  // Cell of each particle (last axis slowest), and the scatter slabs along the last axis.
  cell_of_.resize(n);
#pragma omp parallel for schedule(static)
  for (int p = 0; p < n; ++p) cell_of_[p] = cell_index(particles_.x[p]);
  const int per_layer = grid_.cell_count() / grid_.cells(slab_axis_);  // cells in one layer across the slab axis
  schedule_.build(n, grid_.cells(slab_axis_), [&](int p) { return cell_of_[p] / per_layer; });
}

// Sets v_R (at the middle of the step, so a rigid body travels the integral of its history) on the
// rigid particles, and stops before one would leave the grid.
template <int Dim>
void Model<Dim>::assign_rigid_velocities() {
  const double t_mid = phase_time() + 0.5 * dt_;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (!bodies_[b].rigid) continue;
    auto& m = motion_[b];
    for (int d = 0; d < Dim; ++d) m.current[d] = rigid_bodies_move_ ? m.velocity[d]->at(t_mid) : 0.0;
    m.force.setZero();
    if (!m.current.allFinite()) {
      std::ostringstream os;
      os << "step " << steps_ << " (t = " << time_ << " s): the velocity history of rigid body '" << bodies_[b].name
         << "' gave " << format_point<Dim>(m.current) << " m/s at phase time " << t_mid << " s";
      throw SimulationError(os.str());
    }
  }
  const int n = static_cast<int>(particles_.size());
  auto& P = particles_;
  int leaving = n;
#pragma omp parallel for schedule(static) reduction(min : leaving)
  for (int p = 0; p < n; ++p) {
    const int b = P.body[p];
    if (!body_rigid_[b]) continue;
    P.v[p] = motion_[b].current;
    if (!inside_domain(grid_, Vec<Dim>(P.x[p] + dt_ * P.v[p]))) leaving = std::min(leaving, p);
  }
  if (leaving < n) {
    std::ostringstream os;
    os << "is about to leave the grid: rigid body '" << bodies_[P.body[leaving]].name << "' moves at "
       << format_point<Dim>(P.v[leaving]) << " m/s";
    fail(leaving, os.str());
  }
}

template <int Dim>
std::array<int, Dim> Model<Dim>::cell_coords(int c) const {
  std::array<int, Dim> x{};
  for (int d = 0; d < Dim; ++d) {
    if (d == slab_axis_) continue;
    x[d] = c % grid_.cells(d);
    c /= grid_.cells(d);
  }
  x[slab_axis_] = c;
  return x;
}

// Which contact fields touch each node. Marked per cell rather than per particle (a cell's particles
// mostly share a body): a deformable field marks every node its cell's particles can reach (cell nodes
// -1 .. +2 for uGIMP, 0 .. +1 for linear shapes), a superset whose extra slots stay massless; a rigid
// field marks the nodes of its cells only (the paper's boundary nodes of the rigid body). Then every
// cell whose particles can reach a shared node is flagged, so the transfers look up slots only there.
template <int Dim>
template <class Shape>
void Model<Dim>::mark_shared_nodes() {
  const auto& P = particles_;
  const auto& G = grid_;
  const int cells = G.cell_count();
  FieldSet empty;
  empty.fill(-1);
  cell_fields_.assign(cells, empty);
  std::atomic<int> full_cell{-1};
  schedule_.for_each_in_own_cell([&](int p) {  // slabs hold disjoint cells
    if (!add_field(cell_fields_[cell_of_[p]], field_of_body_[P.body[p]])) full_cell.store(cell_of_[p], std::memory_order_relaxed);
  });
  constexpr int lo = Shape::K == 2 ? 0 : -1, hi = Shape::K == 2 ? 1 : 2;
  auto for_each_reach = [&](const std::array<int, Dim>& c, int from, int to, auto&& f) {
    std::array<int, Dim> o;
    o.fill(from);
    for (;;) {
      int i = 0;
      bool inside = true;
      for (int d = 0; d < Dim; ++d) {
        const int n = c[d] + o[d];
        inside = inside && n >= 0 && n < G.nodes(d);
        i += n * G.stride(d);
      }
      if (inside) f(i, o);
      int d = 0;
      while (d < Dim && ++o[d] > to) o[d] = from, ++d;
      if (d == Dim) break;
    }
  };
  shared_.clear(G.node_count());
  std::atomic<int> overflow{-1};
  // Slabs of one colour are 4 cells apart: the nodes they mark never meet.
  const int layer = cells / G.cells(slab_axis_);
  const int slab_cells = ScatterSchedule::kSlabCells;
  const int slabs = (G.cells(slab_axis_) + slab_cells - 1) / slab_cells;
  for (int colour = 0; colour < 2; ++colour) {
#pragma omp parallel for schedule(dynamic, 1)
    for (int sl = colour; sl < slabs; sl += 2) {
      const int end = std::min(cells, (sl + 1) * slab_cells * layer);
      for (int c = sl * slab_cells * layer; c < end; ++c) {
        const FieldSet& fs = cell_fields_[c];
        if (fs[0] < 0) continue;
        const auto coords = cell_coords(c);
        for (const int f : fs) {
          if (f < 0) break;
          const bool rigid = rules_.rigid(f);
          for_each_reach(coords, rigid ? 0 : lo, rigid ? 1 : hi, [&](int i, const std::array<int, Dim>&) {
            if (!shared_.mark(i, f)) overflow.store(i, std::memory_order_relaxed);
          });
        }
      }
    }
  }
  if (const int c = full_cell.load(); c >= 0) {  // name the cell by its lower corner node
    const auto x = cell_coords(c);
    int i = 0;
    for (int d = 0; d < Dim; ++d) i += x[d] * G.stride(d);
    overflow.store(i);
  }
  if (const int i = overflow.load(); i >= 0) {
    std::ostringstream os;
    os << "step " << steps_ << " (t = " << time_ << " s): more than " << SharedNodes<Dim>::kSlots
       << " contact fields (rigid bodies and bodies in contact pairs) meet near " << format_point<Dim>(G.node_position(i));
    throw SimulationError(os.str());
  }
  shared_.build();
  slot_reaction_.assign(shared_.mass.size(), Vec<Dim>::Zero());
  // Cells whose deformable particles can reach a shared node: c - hi .. c - lo around it.
  near_shared_.assign(cells, 0);
  for (int k = 0; k < shared_.count(); ++k) {
    const auto n = G.node_coords(shared_.node(k));
    for_each_reach(n, -hi, -lo, [&](int, const std::array<int, Dim>& o) {
      std::array<int, Dim> c;
      for (int d = 0; d < Dim; ++d) {
        c[d] = n[d] + o[d];
        if (c[d] < 0 || c[d] >= G.cells(d)) return;
      }
      int index = c[slab_axis_];
      for (int d = Dim - 1; d >= 0; --d)
        if (d != slab_axis_) index = index * G.cells(d) + c[d];
      near_shared_[index] = 1;
    });
  }
}

template <int Dim>
template <class Shape, bool Multi>
void Model<Dim>::particles_to_grid() {
  const auto& st = stencils<Shape>();
  const Vec<Dim> g = settings_.gravity;
  auto& P = particles_;
  auto& G = grid_;
  auto& S = shared_;
  // The common fields, from every deformable particle.
  schedule_.for_each([&](int p) {
    if constexpr (Multi)
      if (body_rigid_[P.body[p]]) return;
    const double m = P.mass[p];
    const Vec<Dim> mv = m * P.v[p];
    const Mat<Dim> vs = P.volume[p] * in_plane<Dim>(P.stress[p]);
    const Vec<Dim> mg = m * g;
    for_each_node(st[p], G, [&](int i, double N, const Vec<Dim>& dN) {
      G.mass[i] += N * m;
      G.momentum[i] += N * mv;
      G.force[i] += N * mg - vs * dN;  // f_ext + f_int, f_int = -V sigma . grad N
    });
  });
  if constexpr (!Multi) return;
  // Each field's own slots, from the particles that can reach a shared node: a second, short pass
  // keeps the common one as lean as with a single field.
  schedule_.for_each([&](int p) {
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
    if (!near_shared_[cell_of_[p]]) return;
    const double m = P.mass[p];
    const Vec<Dim> mv = m * P.v[p];
    const Mat<Dim> vs = P.volume[p] * in_plane<Dim>(P.stress[p]);
    const Vec<Dim> mg = m * g;
    for_each_node(st[p], G, [&](int i, double N, const Vec<Dim>& dN) {
      const int k = S.index(i);
      if (k < 0) return;
      const int s = S.slot(k, f);
      S.mass[s] += N * m;
      S.momentum[s] += N * mv;
      S.force[s] += N * mg - vs * dN;
      S.gradient[s] += m * dN;
    });
  });
}

// Norms of the out-of-balance and the external force, summed in fixed chunks of nodes so the result
// (and the step at which a gravity phase ends) does not depend on the number of threads. Fixed
// components, and nodes where a rigid body carries the soil (their force is the support's to take),
// are left out of the out-of-balance force.
template <int Dim>
void Model<Dim>::measure_balance() {
  const auto& G = grid_;
  const auto& S = shared_;
  const int n = G.node_count();
  constexpr int kChunk = 4096;
  const int chunks = (n + kChunk - 1) / kChunk;
  auto& unbalanced = balance_scratch_[0];
  auto& external = balance_scratch_[1];
  unbalanced.assign(chunks, 0.0);
  external.assign(chunks, 0.0);
  const double eps = mass_threshold_;
  const Vec<Dim> g = settings_.gravity;
  const bool multi = rules_.fields() > 1;
#pragma omp parallel for schedule(static)
  for (int c = 0; c < chunks; ++c) {
    double u = 0.0, e = 0.0;
    for (int i = c * kChunk, end = std::min(n, (c + 1) * kChunk); i < end; ++i) {
      if (!(G.mass[i] > eps)) continue;
      e += (G.mass[i] * g).squaredNorm();
      if (multi && S.index(i) >= 0) {
        const int k = S.index(i);
        bool held = false;
        for (int j = 0; j < S.fields(k); ++j) held = held || rules_.rigid(S.field_of_slot(k * SharedNodes<Dim>::kSlots + j));
        if (held) continue;
      }
      const unsigned mask = G.fixity(i);
      for (int d = 0; d < Dim; ++d)
        if (!(mask >> d & 1)) u += G.force[i][d] * G.force[i][d];
    }
    unbalanced[c] = u, external[c] = e;
  }
  double u = 0.0, e = 0.0;
  for (int c = 0; c < chunks; ++c) u += unbalanced[c], e += external[c];
  out_of_balance_ = std::sqrt(u);
  external_force_ = std::sqrt(e);
}

template <int Dim>
void Model<Dim>::update_nodal_velocities() {
  const int n = grid_.node_count();
  const double dt = dt_, eps = mass_threshold_;
  auto& G = grid_;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    if (G.mass[i] > eps) {
      const double inv_m = 1.0 / G.mass[i];
      G.acceleration[i] = G.force[i] * inv_m;
      G.velocity[i] = G.momentum[i] * inv_m + dt * G.acceleration[i];
    } else {
      G.acceleration[i].setZero();
      G.velocity[i].setZero();
    }
  }
}

// Each field's own velocity at the shared nodes: a rigid field's the weighted average of its
// particles' (the paper's Eq. 9), a deformable field's from its momentum and force.
template <int Dim>
void Model<Dim>::update_shared_velocities() {
  auto& S = shared_;
  const int count = S.count();
  const double dt = dt_, eps = mass_threshold_;
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

// Contact at every shared node, then the grid fixities on each deformable field. After the force
// update the accelerations are rebuilt from the corrected velocities (so FLIP sees the correction)
// and the force each rigid body exerts is summed.
template <int Dim>
void Model<Dim>::resolve_shared_nodes(VelocityStage stage) {
  constexpr int kSlots = SharedNodes<Dim>::kSlots;
  auto& S = shared_;
  const auto& G = grid_;
  const int count = S.count();
  const bool updated = stage == VelocityStage::Updated;
  const double dt = dt_, eps = mass_threshold_, h = grid_.cell();
#pragma omp parallel for schedule(static)
  for (int k = 0; k < count; ++k) {
    NodeFields<Dim> nf;
    nf.count = S.fields(k);
    for (int j = 0; j < nf.count; ++j) {
      const int s = k * kSlots + j;
      nf.field[j] = S.field_of_slot(s);
      nf.mass[j] = S.mass[s];
      nf.gradient[j] = S.gradient[s];
      nf.velocity[j] = S.velocity[s];
    }
    Vec<Dim> force_on[kSlots];
    for (auto& f : force_on) f.setZero();
    resolve_contact<Dim>(nf, rules_, eps, h, updated ? dt : 0.0, force_on);
    const unsigned mask = G.fixity(S.node(k));
    for (int j = 0; j < nf.count; ++j) {
      const int s = k * kSlots + j;
      if (rules_.rigid(nf.field[j])) {
        if (updated) slot_reaction_[s] = force_on[j];
        continue;
      }
      if (!(S.mass[s] > eps)) continue;
      S.velocity[s] = nf.velocity[j];
      for (int d = 0; d < Dim; ++d)
        if (mask >> d & 1) S.velocity[s][d] = 0.0;
      if (updated) S.acceleration[s] = (S.velocity[s] - S.momentum[s] / S.mass[s]) / dt;
    }
  }
  if (!updated) return;
  // The force of each rigid body on the deformable ones, summed in a fixed order.
  for (int s = 0, n = static_cast<int>(slot_reaction_.size()); s < n; ++s) {
    if (s % kSlots >= S.fields(s / kSlots)) continue;
    const int f = S.field_of_slot(s);
    if (rules_.rigid(f)) motion_[body_of_field_[f]].force += slot_reaction_[s];
  }
  for (std::size_t b = 0; b < bodies_.size(); ++b)
    if (bodies_[b].rigid) motion_[b].impulse += dt * motion_[b].force;
}

template <int Dim>
void Model<Dim>::constrain_velocities(VelocityStage stage) {
  if (rules_.fields() > 1) resolve_shared_nodes(stage);
  grid_.apply_fixities(grid_.velocity);
  if (stage == VelocityStage::Updated) grid_.apply_fixities(grid_.acceleration);
  for (auto& f : fixes_) f->nodal_velocities(*this, stage);
}

template <int Dim>
template <class Shape, bool Multi>
void Model<Dim>::grid_to_particles() {
  const auto& st = stencils<Shape>();
  const int n = static_cast<int>(particles_.size());
  const double dt = dt_, alpha = settings_.flip;
  auto& P = particles_;
  const auto& G = grid_;
  const auto& S = shared_;
#pragma omp parallel for schedule(static)
  for (int p = 0; p < n; ++p) {
    [[maybe_unused]] int f = 0;
    if constexpr (Multi) {
      const int b = P.body[p];
      if (body_rigid_[b]) {  // prescribed: moves at v_R, whatever the grid says
        P.x[p] += dt * P.v[p];
        P.u[p] += dt * P.v[p];
        continue;
      }
      f = field_of_body_[b];
    }
    Vec<Dim> a = Vec<Dim>::Zero(), vl = Vec<Dim>::Zero();
    auto gather = [&](auto slotted) {
      for_each_node(st[p], G, [&](int i, double N, const Vec<Dim>&) {
        if constexpr (decltype(slotted)::value) {
          const int k = S.index(i);
          if (k >= 0) {  // the particle's own field where fields meet
            const int s = S.slot(k, f);
            a += N * S.acceleration[s];
            vl += N * S.velocity[s];
            return;
          }
        }
        a += N * G.acceleration[i];
        vl += N * G.velocity[i];
      });
    };
    if (Multi && near_shared_[cell_of_[p]])
      gather(std::true_type{});
    else
      gather(std::false_type{});
    P.v[p] = alpha * (P.v[p] + dt * a) + (1.0 - alpha) * vl;
    P.x[p] += dt * vl;
    P.u[p] += dt * vl;
  }
}

template <int Dim>
template <class Shape, bool Multi>
void Model<Dim>::remap_momentum() {
  const auto& st = stencils<Shape>();
  auto& P = particles_;
  auto& G = grid_;
  auto& S = shared_;
  const int nn = G.node_count();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < nn; ++i) G.momentum[i].setZero();
  if constexpr (Multi) {
    // Rigid slots keep their prescribed velocity; deformable ones are re-mapped.
    for (std::size_t s = 0; s < S.momentum.size(); ++s)
      if (s % SharedNodes<Dim>::kSlots < static_cast<std::size_t>(S.fields(static_cast<int>(s / SharedNodes<Dim>::kSlots))) &&
          !rules_.rigid(S.field_of_slot(static_cast<int>(s))))
        S.momentum[s].setZero();
  }
  schedule_.for_each([&](int p) {
    if constexpr (Multi)
      if (body_rigid_[P.body[p]]) return;
    const Vec<Dim> mv = P.mass[p] * P.v[p];
    for_each_node(st[p], G, [&](int i, double N, const Vec<Dim>&) { G.momentum[i] += N * mv; });
  });
  if constexpr (Multi) {
    schedule_.for_each([&](int p) {
      const int b = P.body[p];
      if (body_rigid_[b] || !near_shared_[cell_of_[p]]) return;
      const int f = field_of_body_[b];
      const Vec<Dim> mv = P.mass[p] * P.v[p];
      for_each_node(st[p], G, [&](int i, double N, const Vec<Dim>&) {
        const int k = S.index(i);
        if (k >= 0) S.momentum[S.slot(k, f)] += N * mv;
      });
    });
  }
  const double eps = mass_threshold_;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < nn; ++i)
    G.velocity[i] = G.mass[i] > eps ? Vec<Dim>(G.momentum[i] / G.mass[i]) : Vec<Dim>::Zero();
  if constexpr (Multi) {
    const int count = S.count();
#pragma omp parallel for schedule(static)
    for (int k = 0; k < count; ++k)
      for (int j = 0; j < S.fields(k); ++j) {
        const int s = k * SharedNodes<Dim>::kSlots + j;
        if (rules_.rigid(S.field_of_slot(s))) continue;
        S.velocity[s] = S.mass[s] > eps ? Vec<Dim>(S.momentum[s] / S.mass[s]) : Vec<Dim>::Zero();
      }
  }
}

template <int Dim>
template <class Shape, bool Multi>
void Model<Dim>::update_stress() {
  const auto& st = stencils<Shape>();
  const int n = static_cast<int>(particles_.size());
  const double dt = dt_;
  auto& P = particles_;
  const auto& G = grid_;
  const auto& S = shared_;
  strain_increment_.resize(n);
  spin_.resize(n);
#pragma omp parallel for schedule(static)
  for (int p = 0; p < n; ++p) {
    [[maybe_unused]] int f = 0;
    if constexpr (Multi) {
      if (body_rigid_[P.body[p]]) {  // no strain, no stress
        strain_increment_[p] = Sym::Zero();
        spin_[p].setZero();
        continue;
      }
      f = field_of_body_[P.body[p]];
    }
    Mat<Dim> L = Mat<Dim>::Zero();  // velocity gradient, L_ab = dv_a / dx_b
    auto gather = [&](auto slotted) {
      for_each_node(st[p], G, [&](int i, double, const Vec<Dim>& dN) {
        if constexpr (decltype(slotted)::value) {
          const int k = S.index(i);
          if (k >= 0) {
            L.noalias() += S.velocity[S.slot(k, f)] * dN.transpose();
            return;
          }
        }
        L.noalias() += G.velocity[i] * dN.transpose();
      });
    };
    if (Multi && near_shared_[cell_of_[p]])
      gather(std::true_type{});
    else
      gather(std::false_type{});
    const Mat<Dim> dL = dt * L;
    strain_increment_[p] = to_voigt(embed<Dim>(Mat<Dim>(0.5 * (dL + dL.transpose()))));
    const Mat3 w = embed<Dim>(Mat<Dim>(0.5 * (dL - dL.transpose())));
    spin_[p] = Eigen::Vector3d(w(0, 1), w(1, 2), w(0, 2));
  }
  const bool average = settings_.cell_volumetric_strain;
  const double max_volume_ratio = settings_.max_dilation;
  if (average) accumulate_cell_dilation();
#pragma omp parallel for schedule(static)
  for (int p = 0; p < n; ++p) {
    if constexpr (Multi)
      if (body_rigid_[P.body[p]]) continue;
    Sym& de = strain_increment_[p];
    if (average) {
      // The cell's volume-weighted mean volumetric increment replaces the particle's (B-bar);
      // the deviatoric part stays, and so does de_zz = 0 in plane strain.
      const int c = cell_of_[p];
      const double correction = (cell_dilation_[c] / cell_volume_[c] - trace(de)) / Dim;
      for (int d = 0; d < Dim; ++d) de[d] += correction;
    }
    Mat3 w = Mat3::Zero();
    w(0, 1) = spin_[p][0], w(1, 0) = -spin_[p][0];
    w(1, 2) = spin_[p][1], w(2, 1) = -spin_[p][1];
    w(0, 2) = spin_[p][2], w(2, 0) = -spin_[p][2];
    P.stress[p] = rotate_objectively(P.stress[p], w);
    P.strain[p] += de;
    // Volume from the (averaged) strain increment: V <- V (1 + tr de) to first order, exactly as det(I + dt L)
    // when nothing is averaged.
    const Mat3 F = Mat3::Identity() + to_matrix(de) + w;
    if (opened(p)) {
      // Crack closure: volumetric compression first closes what the tension cut-off opened (down to the
      // stress-free volume), at no change of mean stress; the rest, and all shear, loads the material.
      const double opening = std::log(P.volume[p] * initial_density_[P.material[p]] / P.mass[p]);
      const double closing = std::min(-trace(de), opening);
      if (closing > 0.0)
        for (int d = 0; d < Dim; ++d) de[d] += closing / Dim;
    }
    P.volume[p] *= F.template topLeftCorner<Dim, Dim>().determinant();
    if (max_volume_ratio > 0.0)
      P.volume[p] = std::min(P.volume[p], max_volume_ratio * P.mass[p] / initial_density_[P.material[p]]);
  }
  if (!material_lists_valid_) rebuild_material_lists();
  for (int m = 0; m < material_count(); ++m) {
    const auto& list = material_particles_[m];
    if (list.empty()) continue;
    StressUpdate batch;
    batch.index = list.data();
    batch.count = static_cast<int>(list.size());
    batch.stress = P.stress.data();
    batch.strain_increment = strain_increment_.data();
    batch.plastic_strain = P.plastic_strain.data();
    batch.yield = P.yield.data();
    materials_[m]->update_stress(batch);
  }
}

// Volume and volume-weighted volumetric strain increment of the particles in each cell.
template <int Dim>
void Model<Dim>::accumulate_cell_dilation() {
  const int cells = grid_.cell_count();
  cell_volume_.assign(cells, 0.0);
  cell_dilation_.assign(cells, 0.0);
  const auto& P = particles_;
  const bool rigid_bodies = std::any_of(body_rigid_.begin(), body_rigid_.end(), [](char r) { return r; });
  schedule_.for_each_in_own_cell([&](int p) {
    if (rigid_bodies && body_rigid_[P.body[p]]) return;  // no strain of their own
    cell_volume_[cell_of_[p]] += P.volume[p];
    cell_dilation_[cell_of_[p]] += P.volume[p] * trace(strain_increment_[p]);
  });
}

template <int Dim>
void Model<Dim>::rebuild_material_lists() {
  material_particles_.assign(materials_.size(), {});
  for (std::size_t p = 0; p < particles_.size(); ++p)
    material_particles_[particles_.material[p]].push_back(static_cast<int>(p));
  material_lists_valid_ = true;
}

// ---------------------------------------------------------------- checks and upkeep

template <int Dim>
void Model<Dim>::fail(std::size_t p, const std::string& what) const {
  std::ostringstream os;
  os.precision(6);
  os << "step " << steps_ << " (t = " << time_ << " s): particle " << particles_.id[p] << " of body '"
     << bodies_[particles_.body[p]].name << "' at " << format_point<Dim>(particles_.x[p]) << " " << what;
  if (what.find("grid") != std::string::npos)
    os << " (the domain spans " << format_point<Dim>(grid_.domain_lower()) << " to "
       << format_point<Dim>(grid_.domain_upper()) << ")";
  throw SimulationError(os.str());
}

template <int Dim>
void Model<Dim>::check_particles() const {
  const int n = static_cast<int>(particles_.size());
  const auto& P = particles_;
  int bad = n;
#pragma omp parallel for schedule(static) reduction(min : bad)
  for (int p = 0; p < n; ++p) {
    const bool finite = P.x[p].allFinite() && P.v[p].allFinite() && P.stress[p].allFinite() &&
                        std::isfinite(P.volume[p]) && P.volume[p] > 0.0;
    if (!finite) bad = std::min(bad, p);
  }
  if (bad < n) {
    std::ostringstream os;
    os << "has a non-finite or invalid state (velocity " << format_point<Dim>(P.v[bad]) << ", volume "
       << P.volume[bad] << ")";
    fail(bad, os.str());
  }
  // The next step needs every particle's centre inside the domain.
#pragma omp parallel for schedule(static) reduction(min : bad)
  for (int p = 0; p < n; ++p)
    if (!inside_domain(grid_, P.x[p])) bad = std::min(bad, p);
  if (bad < n) fail(bad, "left the grid");
}

template <int Dim>
int Model<Dim>::cell_index(const Vec<Dim>& x) const {
  auto coord = [&](int d) {
    return std::clamp(static_cast<int>(std::floor((x[d] - grid_.origin()[d]) / grid_.cell())), 0, grid_.cells(d) - 1);
  };
  int c = coord(slab_axis_);
  for (int d = Dim - 1; d >= 0; --d)
    if (d != slab_axis_) c = c * grid_.cells(d) + coord(d);
  return c;
}

template <int Dim>
void Model<Dim>::sort_particles() {
  // Counting sort by cell (slab axis slowest): neighbours in memory are neighbours on the grid,
  // and each scatter slab becomes a contiguous run. Stable, so the order is deterministic.
  const int n = static_cast<int>(particles_.size());
  const int cells = grid_.cell_count();
  std::vector<int> key(n);
#pragma omp parallel for schedule(static)
  for (int p = 0; p < n; ++p) key[p] = cell_index(particles_.x[p]);
  std::vector<int> start(cells + 1, 0);
  for (int p = 0; p < n; ++p) ++start[key[p] + 1];
  for (int c = 0; c < cells; ++c) start[c + 1] += start[c];
  std::vector<int> order(n);
  for (int p = 0; p < n; ++p) order[start[key[p]]++] = p;
  particles_.permute(order);
  material_lists_valid_ = false;
  index_of_id_.clear();
}

// ---------------------------------------------------------------- diagnostics

template <int Dim>
std::size_t Model<Dim>::index_of(int id) const {
  if (index_of_id_.size() != particles_.size()) {
    index_of_id_.assign(particles_.size(), 0);
    for (std::size_t p = 0; p < particles_.size(); ++p) index_of_id_[particles_.id[p]] = static_cast<int>(p);
  }
  return index_of_id_.at(id);
}

template <int Dim>
double Model<Dim>::kinetic_energy() const {
  double e = 0.0;
  for (std::size_t p = 0; p < particles_.size(); ++p)
    if (!bodies_[particles_.body[p]].rigid) e += 0.5 * particles_.mass[p] * particles_.v[p].squaredNorm();
  return e;
}

template <int Dim>
double Model<Dim>::strain_energy() const {
  double e = 0.0;
  for (std::size_t p = 0; p < particles_.size(); ++p) {
    if (bodies_[particles_.body[p]].rigid) continue;
    const Material& m = *materials_[particles_.material[p]];
    const Sym& s = particles_.stress[p];
    const double tr = s[0] + s[1] + s[2], mean = tr / 3.0;
    const double dev2 = (s[0] - mean) * (s[0] - mean) + (s[1] - mean) * (s[1] - mean) + (s[2] - mean) * (s[2] - mean) +
                        2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
    e += particles_.volume[p] * (tr * tr / (18.0 * m.bulk_modulus()) + dev2 / (4.0 * m.shear_modulus()));
  }
  return e;
}

template <int Dim>
Vec<Dim> Model<Dim>::centroid(int body) const {
  Vec<Dim> s = Vec<Dim>::Zero();
  double m = 0.0;
  for (std::size_t p = 0; p < particles_.size(); ++p)
    if (particles_.body[p] == body) {
      s += particles_.mass[p] * particles_.x[p];
      m += particles_.mass[p];
    }
  return m > 0.0 ? Vec<Dim>(s / m) : s;
}

template <int Dim>
Vec<Dim> Model<Dim>::momentum() const {
  Vec<Dim> s = Vec<Dim>::Zero();
  for (std::size_t p = 0; p < particles_.size(); ++p)
    if (!bodies_[particles_.body[p]].rigid) s += particles_.mass[p] * particles_.v[p];
  return s;
}

template class Model<2>;
template class Model<3>;

}  // namespace seismpm
