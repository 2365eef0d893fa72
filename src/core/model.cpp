#include "model.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <type_traits>

#include "diagnostics.hpp"
#include "error.hpp"
#include "format.hpp"
#include "memory_estimate.hpp"
#include "thread_shares.hpp"

namespace seismpm {

template <int Dim>
Model<Dim>::Model(const ModelSettings<Dim>& settings)
    : settings_(with_grid_memory_checked(settings)),
      grid_(settings.lower, settings.upper, settings.cell, 1),
      support_(grid_) {
  for (int d = 0; d < Dim; ++d)
    if (grid_.domain_cells(d) < 2) throw InputError("model: the domain must span at least 2 cells along every axis");
  if (!(settings.cfl > 0.0 && settings.cfl <= 1.0)) throw InputError("model: cfl must be in (0, 1]");
  if (!(settings.flip >= 0.0 && settings.flip <= 1.0)) throw InputError("model: flip must be in [0, 1]");
  if (!(settings.fixed_dt >= 0.0)) throw InputError("model: fixed_dt must be >= 0");
  if (settings.sort_every < 1) throw InputError("model: sort_every must be >= 1");
  if (!(settings.max_dilation == 0.0 || settings.max_dilation >= 1.0))
    throw InputError("model: max_dilation must be 0 (no limit) or >= 1");
  constants_.crack_closure = settings.crack_closure;
}

// ---------------------------------------------------------------- memory

template <int Dim>
double Model<Dim>::grid_bytes(const ModelSettings<Dim>& s) {
  double nodes = 1.0, cells = 1.0;
  for (int d = 0; d < Dim; ++d) {
    const double n = std::ceil((s.upper[d] - s.lower[d]) / s.cell - 1e-9) + 2.0;  // one ghost cell each side
    if (!(n > 0.0)) return 0.0;  // an empty or broken domain: the grid names it
    nodes *= n + 1.0;
    cells *= n;
  }
  // Per node: mass, momentum, force, velocity, acceleration, fixity. Per cell: volume and dilation
  // (cell-averaged volumetric strain), its contact fields and the near-shared flag.
  const double per_node = sizeof(double) + 4.0 * sizeof(Vec<Dim>) + 1.0;
  const double per_cell = 2.0 * sizeof(double) + 8.0 + 1.0;
  return nodes * per_node + cells * per_cell;
}

template <int Dim>
const ModelSettings<Dim>& Model<Dim>::with_grid_memory_checked(const ModelSettings<Dim>& s) {
  if (s.check_memory && s.cell > 0.0) {
    const double bytes = grid_bytes(s);
    if (std::isfinite(bytes)) check_memory(static_cast<std::uint64_t>(std::min(bytes, 1.8e19)), "the grid");
  }
  return s;
}

template <int Dim>
std::size_t Model<Dim>::bytes_per_particle() const {
  std::size_t bytes = 0;
  particles_.for_each_member(
      [&](const auto& field) { bytes += sizeof(typename std::decay_t<decltype(field)>::value_type); });
  // The step's arrays: the stencil of the model's shape and the particle's cell, the strain increment
  // and spin, the id index, the per-material lists and the sort's permutation.
  bytes +=
      settings_.shape == ShapeKind::Linear ? sizeof(Stencil<Dim, LinearShape::K>) : sizeof(Stencil<Dim, GimpShape::K>);
  bytes += sizeof(int) + sizeof(Sym) + sizeof(Eigen::Vector3d) + 3 * sizeof(int);
  return bytes;
}

// ---------------------------------------------------------------- building

template <int Dim>
int Model<Dim>::add_material(std::shared_ptr<const Material> material, const std::string& name) {
  if (!material) throw InputError("model: null material");
  if (materials_.size() >= 65535) throw InputError("model: too many materials");
  constants_.add(*material);
  material_names_.push_back(name.empty() ? std::string(material->kind()) : name);
  materials_.push_back(std::move(material));
  material_lists_valid_ = false;
  return static_cast<int>(materials_.size()) - 1;
}

template <int Dim>
void Model<Dim>::replace_material(int index, std::shared_ptr<const Material> material) {
  if (index < 0 || index >= material_count()) throw InputError("replace_material: unknown material");
  if (!material) throw InputError("model: null material");
  if (material->density() != materials_[index]->density())
    throw InputError("replace_material: the density must stay the same (the particles' masses come from it)");
  materials_[index] = std::move(material);
  MaterialConstants constants;  // rebuilt whole: one source of truth for what the step reads
  constants.crack_closure = settings_.crack_closure;
  for (const auto& m : materials_) constants.add(*m);
  constants_ = std::move(constants);
  // Undamped now: no viscous stress of an earlier damping may wait for damping to come back.
  if (!constants_.any_rayleigh)
    for (auto& s : particles_.damping_stress) s.setZero();
}

template <int Dim>
Model<Dim> Model<Dim>::copy_without_fixes() const {
  Model copy(*this);
  copy.fixes_.clear();
  copy.frame_acceleration_.setZero();  // the fix that moved the frame stays behind
  return copy;
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
  if (ppc < 1 || ppc > kMaxParticlesPerCell)
    throw InputError("body '" + name + "': ppc must be in [1, " + std::to_string(kMaxParticlesPerCell) + "]");
  if (bodies_.size() >= 65535) throw InputError("model: too many bodies");
  bodies_.push_back(Body{name, ppc, rigid, -1});
  contact_.add_body();
  return static_cast<int>(bodies_.size()) - 1;
}

template <int Dim>
int Model<Dim>::add_rigid_body(const std::string& name, int ppc, double density,
                               const std::array<std::shared_ptr<const History>, Dim>& velocity) {
  if (!(density > 0.0 && std::isfinite(density))) throw InputError("rigid body '" + name + "': density must be > 0");
  const int body = new_body(name, ppc, true);
  bodies_[body].material = add_material(std::make_shared<RigidMaterial>(density), "rigid " + name);
  set_rigid_velocity(body, velocity);
  return body;
}

template <int Dim>
void Model<Dim>::set_rigid_velocity(int body, const std::array<std::shared_ptr<const History>, Dim>& velocity) {
  if (body < 0 || body >= static_cast<int>(bodies_.size()) || !bodies_[body].rigid)
    throw InputError("set_rigid_velocity: not a rigid body");
  for (const auto& h : velocity)
    if (!h) throw InputError("rigid body '" + bodies_[body].name + "': missing velocity history");
  contact_.set_velocity(body, velocity);
}

template <int Dim>
void Model<Dim>::add_contact(int a, int b, double friction) {
  contact_.add_pair(bodies_, a, b, friction);
}

template <int Dim>
void Model<Dim>::set_contact_friction(int a, int b, double friction) {
  contact_.set_friction(bodies_, a, b, friction);
}

namespace {

// Calls f(x) for every sub-point (ppc per axis) of the domain cells overlapping [lo, hi] that lies in
// that box, in the order particles are created: sub-points within a cell, cells, last axis slowest.
template <int Dim, class F>
void for_each_sub_point(const Grid<Dim>& grid, int ppc, const Vec<Dim>& lo, const Vec<Dim>& hi, F&& f) {
  const double h = grid.cell();
  const double sub = h / ppc;
  // Cells overlapping the box, clamped to the domain (not the ghost layers).
  const int g = grid.ghost();
  std::array<int, Dim> c0{}, c1{};
  for (int d = 0; d < Dim; ++d) {
    c0[d] = std::max(g, static_cast<int>(std::floor((lo[d] - grid.origin()[d]) / h)));
    c1[d] = std::min(grid.cells(d) - 1 - g, static_cast<int>(std::floor((hi[d] - grid.origin()[d]) / h)));
    if (c1[d] < c0[d]) return;
  }
  std::array<int, Dim> c = c0;
  std::array<int, Dim> k{};
  for (;;) {
    for (k.fill(0);;) {
      Vec<Dim> x;
      for (int d = 0; d < Dim; ++d) x[d] = grid.origin()[d] + c[d] * h + (k[d] + 0.5) * sub;
      bool in_box = true;
      for (int d = 0; d < Dim; ++d) in_box = in_box && x[d] >= lo[d] && x[d] <= hi[d];
      if (in_box) f(x);
      int d = 0;
      while (d < Dim && ++k[d] == ppc) k[d++] = 0;
      if (d == Dim) break;
    }
    int d = 0;
    while (d < Dim && ++c[d] > c1[d]) c[d] = c0[d], ++d;
    if (d == Dim) break;
  }
}

}  // namespace

template <int Dim>
std::size_t Model<Dim>::fill(int body, int material, const Vec<Dim>& lo, const Vec<Dim>& hi,
                             const std::function<bool(const Vec<Dim>&)>& inside,
                             const std::function<Vec<Dim>(const Vec<Dim>&)>& outward) {
  const bool rigid = body >= 0 && body < static_cast<int>(bodies_.size()) && bodies_[body].rigid;
  if (!rigid && (material < 0 || material >= material_count())) throw InputError("fill: unknown material");
  return fill(
      body, [material](const Vec<Dim>&) { return material; }, lo, hi, inside, outward);
}

// The sub-points a fill's box [lo, hi] holds at most (a cell's margin each side): an upper bound of the
// particles it adds, known before any is made.
template <int Dim>
double Model<Dim>::fill_candidates(int ppc, const Vec<Dim>& lo, const Vec<Dim>& hi) const {
  double candidates = 1.0;
  for (int d = 0; d < Dim; ++d) candidates *= std::max(0.0, (hi[d] - lo[d]) / grid_.cell() + 2.0) * ppc;
  return candidates;
}

template <int Dim>
std::vector<Vec<Dim>> Model<Dim>::fill_points(int ppc, const Vec<Dim>& lo, const Vec<Dim>& hi,
                                              const std::function<bool(const Vec<Dim>&)>& inside) const {
  if (ppc < 1 || ppc > kMaxParticlesPerCell) throw InputError("fill: ppc out of range");
  if (fill_candidates(ppc, lo, hi) > 2e8)
    throw InputError("fill: over 200 million particles; use a larger cell or fewer ppc");
  std::vector<Vec<Dim>> points;
  for_each_sub_point(grid_, ppc, lo, hi, [&](const Vec<Dim>& x) {
    if (inside(x)) points.push_back(x);
  });
  return points;
}

// Before a fill allocates anything: the sub-points of its box bound the particle count from above, and
// only when that bound does not fit are the points inside counted (a second pass over the shape).
template <int Dim>
void Model<Dim>::check_fill_memory(const Body& b, const Vec<Dim>& lo, const Vec<Dim>& hi,
                                   const std::function<bool(const Vec<Dim>&)>& inside) const {
  if (b.ppc < 1 || b.ppc > kMaxParticlesPerCell) return;  // fill_points names it
  // Per particle: its arrays and, while the fill runs, its position in the list of points.
  const double per_particle = static_cast<double>(bytes_per_particle() + sizeof(Vec<Dim>));
  const double candidates = fill_candidates(b.ppc, lo, hi);
  const std::uint64_t available = available_memory();
  if (available == 0 || candidates > 2e8 || candidates * per_particle <= static_cast<double>(available)) return;
  std::size_t count = 0;
  for_each_sub_point(grid_, b.ppc, lo, hi, [&](const Vec<Dim>& x) { count += inside(x) ? 1 : 0; });
  check_memory(static_cast<std::uint64_t>(static_cast<double>(count) * per_particle),
               "body '" + b.name + "' (" + std::to_string(count) + " particles)");
}

template <int Dim>
std::size_t Model<Dim>::fill(int body, const std::function<int(const Vec<Dim>&)>& material_at, const Vec<Dim>& lo,
                             const Vec<Dim>& hi, const std::function<bool(const Vec<Dim>&)>& inside,
                             const std::function<Vec<Dim>(const Vec<Dim>&)>& outward) {
  if (body < 0 || body >= static_cast<int>(bodies_.size())) throw InputError("fill: unknown body");
  const Body& b = bodies_[body];
  if (settings_.check_memory) check_fill_memory(b, lo, hi, inside);
  const auto points = fill_points(b.ppc, lo, hi, inside);
  particles_.reserve(particles_.size() + points.size());  // exactly: no doubling of every array
  // Every point's material first, so that a point without a valid one adds nothing.
  std::vector<int> material(points.size(), b.material);
  for (std::size_t k = 0; k < points.size() && !b.rigid; ++k) {
    material[k] = material_at(points[k]);
    if (material[k] < 0 || material[k] >= material_count())
      throw InputError("body '" + b.name + "': no known material for the particle at " + format_point<Dim>(points[k]));
  }
  const double volume = std::pow(grid_.cell() / b.ppc, Dim);
  const double half_width = 0.5 / b.ppc;  // cell units
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Vec<Dim>& x = points[k];
    const double mass = materials_[material[k]]->density() * volume;
    const std::size_t p = particles_.add(x, mass, volume, half_width, body, material[k]);
    if (outward && b.rigid) particles_.normal[p] = outward(x);
    if (!b.rigid) mass_threshold_ = std::max(mass_threshold_, 1e-15 * mass);
  }
  if (!points.empty()) {
    index_of_id_.clear();
    material_lists_valid_ = false;
  }
  return points.size();
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

template <int Dim>
bool Model<Dim>::remove_fix(const Fix<Dim>* fix) {
  const auto it = std::find_if(fixes_.begin(), fixes_.end(), [&](const auto& f) { return f.get() == fix; });
  if (it == fixes_.end()) return false;
  fixes_.erase(it);
  return true;
}

template <int Dim>
void Model<Dim>::begin_phase(bool rigid_bodies_move) {
  phase_start_ = time_;
  rigid_bodies_move_ = rigid_bodies_move;
}

// ---------------------------------------------------------------- the step

template <int Dim>
void Model<Dim>::step(double dt_max) {
  if (particles_.size() == 0) throw InputError("model: no particles to step");
  ThreadShares::prepare_all(omp_get_max_threads());
  const bool contact = contact_.prepare(bodies_);  // bodies or pairs may have changed
  const bool linear = settings_.shape == ShapeKind::Linear;
  if (linear)
    contact ? step_with<LinearShape, true>(dt_max) : step_with<LinearShape, false>(dt_max);
  else
    contact ? step_with<GimpShape, true>(dt_max) : step_with<GimpShape, false>(dt_max);
}

// One explicit MPM step in the order of the method. With contact fields (rigid bodies, contact
// pairs) the nodes where fields meet carry a velocity per field; without, none of that is compiled in.
// The particles are located before the time step is chosen (nothing moves them in between): the
// time step's view of crack closure then reads the cell sums the stress update uses, instead of
// placing every particle in its cell again and summing the cells in a serial pass of its own.
template <int Dim>
template <class Shape, bool Contact>
void Model<Dim>::step_with(double dt_max) {
  timer_.start(settings_.profile);
  // Unless a fix may write to other nodes, nothing writes to a node no particle reaches, so the grid
  // loops can skip those.
  const bool limited =
      std::all_of(fixes_.begin(), fixes_.end(), [](const auto& f) { return f->writes_only_nodes_with_mass(); });
  reset_grid(limited);
  active_valid_ = false;  // until the step completes: a step that throws leaves the grid unknown
  timer_.lap(Stage::Reset);
  locate_particles<Shape>(limited);
  if (settings_.cell_volumetric_strain) sum_cell_volumes<Contact>();
  timer_.lap(Stage::Stencils);
  const StepContext c = next_step(dt_max, settings_.fixed_dt > 0.0 ? nullptr : closable_in_step());
  timer_.lap(Stage::TimeStep);
  for (auto& f : fixes_) f->before_step(*this, c);
  if constexpr (Contact) prescribe_rigid_velocities(c);  // v_R(t) on the rigid particles
  if constexpr (Contact) {
    contact_.template mark_shared_nodes<Shape>(particles_, grid_, support_, c);
    timer_.lap(Stage::ContactFields);
  }
  particles_to_grid<Shape, Contact>();
  timer_.lap(Stage::ParticlesToGrid);
  nodal_forces<Contact>(c);             // balance measure, local damping
  update_nodal_velocities<Contact>(c);  // a = f/m, v^L = mv/m + dt a
  constrain<Contact>(VelocityStage::Updated, c);
  timer_.lap(Stage::Nodes);
  const bool musl = settings_.scheme == Scheme::Musl;
  grid_to_particles<Shape, Contact>(c, musl);  // with MUSL, also the updated momentum to the nodes
  timer_.lap(Stage::GridToParticles);
  if (musl) {  // nodal velocity from the updated momentum
    remap_momentum<Shape, Contact>();
    constrain<Contact>(VelocityStage::Remapped, c);
  }
  timer_.lap(Stage::Remap);
  update_stress<Shape, Contact>(c);
  timer_.lap(Stage::Stress);
  active_valid_ = limited;
  finish_step(c);
  timer_.lap(Stage::Checks);
}

// The step's length and clock, from the CFL condition (or the fixed step) and the caller's limit.
template <int Dim>
StepContext Model<Dim>::next_step(double dt_max, const char* may_close) {
  const double dt =
      time_step_.next(settings_.fixed_dt > 0.0
                          ? settings_.fixed_dt
                          : seismpm::stable_time_step(particles_, constants_, settings_.cfl, grid_.cell(), may_close),
                      dt_max);
  if (time_step_.collapsed(dt, dt_max)) {
    const auto [fastest, speed] = fastest_signal(particles_, constants_, grid_.cell(), closable_particles());
    std::ostringstream os;
    os << "the time step collapsed to " << dt << " s (first step " << time_step_.first()
       << " s): wave speed + velocity " << speed << " m/s";
    fail(fastest, "sets it: " + os.str());
  }
  return StepContext{dt, time_, phase_time(), steps_};
}

template <int Dim>
void Model<Dim>::prescribe_rigid_velocities(const StepContext& c) {
  const int leaving = contact_.prescribe_rigid_velocities(particles_, grid_, bodies_, c, rigid_bodies_move_);
  if (leaving < static_cast<int>(particles_.size())) {
    std::ostringstream os;
    os << "is about to leave the grid: rigid body '" << bodies_[particles_.body[leaving]].name << "' moves at "
       << format_point<Dim>(particles_.v[leaving]) << " m/s";
    fail(leaving, os.str());
  }
}

// Zeroes what the last step wrote: where it reached only some nodes (and everything else is zero),
// those; else the whole grid, velocities too when this step will visit only some nodes.
template <int Dim>
void Model<Dim>::reset_grid(bool limited) {
  if (!active_valid_) {
    grid_.reset(limited);
    return;
  }
  active_.for_each_range([&](int first, int end) { grid_.reset_nodes(first, end); });
}

// Shape functions at the start-of-step positions, each particle's cell and the scatter schedule;
// with `limited`, the nodes they reach (else every node).
template <int Dim>
template <class Shape>
void Model<Dim>::locate_particles(bool limited) {
  const int outside = support_.template locate<Shape>(grid_, particles_, limited ? &active_ : nullptr);
  if (outside < static_cast<int>(particles_.size())) fail(outside, "is outside the grid");
  if (limited) {
    active_.finish(grid_, Shape::kReachLo, Shape::kReachHi);  // locate marked the occupied cells
  } else {
    active_.cover(grid_);
  }
}

template <int Dim>
template <bool Contact>
void Model<Dim>::nodal_forces(const StepContext& c) {
  if (measure_balance_)
    balance_ =
        measure_balance(grid_, Contact ? &contact_ : nullptr, mass_threshold_, settings_.gravity, balance_scratch_);
  for (auto& f : fixes_) f->nodal_forces(*this, c);
  for (auto& f : fixes_) f->edge_forces(*this, c);
}

// The clock, the fixes' last word, the checks that the next step can start, and the periodic sort.
template <int Dim>
void Model<Dim>::finish_step(const StepContext& c) {
  dt_ = c.dt;
  time_ += c.dt;
  ++steps_;
  for (auto& f : fixes_) f->after_step(*this, c);
  check_particles();
  ThreadShares::update_all();
  if (steps_ % settings_.sort_every == 0) sort_particles();
}

template <int Dim>
void Model<Dim>::run(double duration) {
  if (!(duration >= 0.0)) throw InputError("run: duration must be >= 0");
  const double end = time_ + duration;
  // Steps shorter than 1e-9 of the duration are round-off, not time.
  while (end - time_ > 1e-9 * std::max(duration, 1e-300)) step(end - time_);
}

// ---------------------------------------------------------------- measures

template <int Dim>
double Model<Dim>::stable_time_step() const {
  return seismpm::stable_time_step(particles_, constants_, settings_.cfl, grid_.cell(), closable_particles());
}

template <int Dim>
double Model<Dim>::kinetic_energy() const {
  return seismpm::kinetic_energy(particles_, bodies_);
}

template <int Dim>
double Model<Dim>::strain_energy() const {
  return seismpm::strain_energy(particles_, bodies_, constants_);
}

template <int Dim>
Vec<Dim> Model<Dim>::centroid(int body) const {
  return seismpm::centroid(particles_, body);
}

template <int Dim>
Vec<Dim> Model<Dim>::momentum() const {
  return seismpm::momentum(particles_, bodies_);
}

template class Model<2>;
template class Model<3>;

}  // namespace seismpm
