#include "checkpoint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <type_traits>

#include "contact/rigid_body.hpp"
#include "core/error.hpp"
#include "core/parameter.hpp"
#include "io/atomic_file.hpp"
#include "materials/drucker_prager.hpp"
#include "materials/linear_elastic.hpp"
#include "materials/mohr_coulomb.hpp"
#include "simulation.hpp"

namespace seismpm {

namespace {

// Section tags, in the order they are written.
constexpr const char* kMeta = "META";
constexpr const char* kSettings = "SETTINGS";
constexpr const char* kMaterials = "MATERIAL";
constexpr const char* kBodies = "BODIES";
constexpr const char* kParticles = "PARTICLE";
constexpr const char* kGrid = "GRID";
constexpr const char* kContact = "CONTACT";
constexpr const char* kClock = "CLOCK";
constexpr const char* kSchedule = "SCHEDULE";
constexpr const char* kProbes = "PROBES";
// Each probe's phases, phase times and reference (ux_rel, ...): optional, so that a checkpoint written
// before them still restores (its probes' earlier samples then have no phase).
constexpr const char* kProbeExtra = "PROBEXT";
// The edge boundaries (m:boundary): optional, a checkpoint without them has none.
constexpr const char* kBoundaries = "EDGES";
constexpr const char* kOutput = "OUTPUT";
constexpr const char* kRun = "RUN";

enum class HistoryKind : std::uint8_t { Constant = 0, Table = 1, Function = 2 };

// Writes and reads a Vec/Sym as its doubles.
template <class T>
constexpr int doubles_of() {
  if constexpr (std::is_arithmetic_v<T>)
    return 0;
  else
    return T::SizeAtCompileTime;
}

template <class T>
void put_vector(SectionWriter& w, const std::vector<T>& v) {
  w.count(v.size());
  w.u32(sizeof(T));
  if constexpr (std::is_arithmetic_v<T>) {
    w.raw(v.data(), v.size() * sizeof(T));
  } else {
    static_assert(sizeof(T) == doubles_of<T>() * sizeof(double), "an Eigen type with padding");
    for (const T& x : v) w.raw(x.data(), sizeof(T));
  }
}

template <class T>
std::vector<T> get_vector(SectionReader& r, const char* what) {
  const std::size_t n = r.count(sizeof(T));
  const std::uint32_t size = r.u32();
  if (size != sizeof(T))
    r.fail(std::string(what) + ": elements of " + std::to_string(size) + " bytes, expected " +
           std::to_string(sizeof(T)));
  std::vector<T> v(n);
  if constexpr (std::is_arithmetic_v<T>) {
    r.raw(v.data(), n * sizeof(T));
  } else {
    for (T& x : v) r.raw(x.data(), sizeof(T));
  }
  return v;
}

template <int Dim>
void put_point(SectionWriter& w, const Vec<Dim>& x) {
  for (int d = 0; d < Dim; ++d) w.f64(x[d]);
}

template <int Dim>
Vec<Dim> get_point(SectionReader& r) {
  Vec<Dim> x;
  for (int d = 0; d < Dim; ++d) x[d] = r.f64();
  return x;
}

void put_history(SectionWriter& w, const History& h) {
  if (const auto* c = dynamic_cast<const ConstantHistory*>(&h)) {
    w.u8(static_cast<std::uint8_t>(HistoryKind::Constant));
    w.f64(c->value());
  } else if (const auto* t = dynamic_cast<const TableHistory*>(&h)) {
    w.u8(static_cast<std::uint8_t>(HistoryKind::Table));
    w.text(t->source());
    w.array(t->times());
    w.array(t->values());
  } else {
    w.u8(static_cast<std::uint8_t>(HistoryKind::Function));
    w.text(h.describe());
  }
}

// A saved history, or the supplied one for its key; a function without one is an error naming the key.
std::shared_ptr<const History> get_history(SectionReader& r, const std::string& key, const std::string& owner,
                                           const SuppliedHistories& supplied) {
  const auto kind = static_cast<HistoryKind>(r.u8());
  std::shared_ptr<const History> saved;
  switch (kind) {
    case HistoryKind::Constant:
      saved = std::make_shared<ConstantHistory>(r.f64());
      break;
    case HistoryKind::Table: {
      std::string source = r.text();
      auto times = r.array<double>();
      auto values = r.array<double>();
      try {
        saved = std::make_shared<TableHistory>(std::move(times), std::move(values), std::move(source));
      } catch (const InputError& e) {
        r.fail("the history " + key + ": " + e.what());
      }
      break;
    }
    case HistoryKind::Function: {
      const std::string description = r.text();
      if (!supplied.count(key))
        throw CheckpointError("checkpoint " + r.file() + ": " + owner + " follows a history made by a function (" +
                              description + "), which a checkpoint cannot hold: give it again when restoring, " +
                              "histories = { [\"" + key + "\"] = h }");
      break;
    }
    default:
      r.fail("the history " + key + " is of an unknown kind " + std::to_string(static_cast<int>(kind)));
  }
  const auto it = supplied.find(key);
  return it != supplied.end() ? it->second : saved;
}

void put_material(SectionWriter& w, const Material& m) {
  w.text(m.kind());
  if (const auto* e = dynamic_cast<const LinearElastic*>(&m)) {
    w.f64(e->density());
    w.f64(e->young());
    w.f64(e->poisson());
  } else if (const auto* mc = dynamic_cast<const MohrCoulomb*>(&m)) {
    const MohrCoulombParameters& p = mc->parameters();
    for (double v : {p.density, p.young, p.poisson, p.cohesion, p.friction, p.dilation, p.tension}) w.f64(v);
    w.boolean(p.softening);
    for (double v : {p.residual_cohesion, p.residual_friction, p.softening_strain}) w.f64(v);
  } else if (const auto* dp = dynamic_cast<const DruckerPrager*>(&m)) {
    const DruckerPragerParameters& p = dp->parameters();
    for (double v : {p.density, p.young, p.poisson, p.cohesion, p.friction, p.dilation, p.tension}) w.f64(v);
    w.u8(static_cast<std::uint8_t>(p.fit));
  } else if (dynamic_cast<const RigidMaterial*>(&m)) {
    w.f64(m.density());
    return;  // never damped
  } else {
    throw CheckpointError("checkpoint: a material of kind '" + std::string(m.kind()) +
                          "' cannot be saved (the format knows linear_elastic, mohr_coulomb, drucker_prager, rigid)");
  }
  w.f64(m.rayleigh().alpha);
  w.f64(m.rayleigh().beta);
}

// A deformable material of `kind`, from its parameters.
std::shared_ptr<Material> get_deformable(SectionReader& r, const std::string& kind) {
  if (kind == "linear_elastic") {
    const double density = r.f64(), young = r.f64(), poisson = r.f64();
    return std::make_shared<LinearElastic>(density, young, poisson);
  }
  if (kind == "mohr_coulomb") {
    MohrCoulombParameters p;
    for (double* v : {&p.density, &p.young, &p.poisson, &p.cohesion, &p.friction, &p.dilation, &p.tension})
      *v = r.f64();
    p.softening = r.boolean();
    for (double* v : {&p.residual_cohesion, &p.residual_friction, &p.softening_strain}) *v = r.f64();
    return std::make_shared<MohrCoulomb>(p);
  }
  if (kind == "drucker_prager") {
    DruckerPragerParameters p;
    for (double* v : {&p.density, &p.young, &p.poisson, &p.cohesion, &p.friction, &p.dilation, &p.tension})
      *v = r.f64();
    const std::uint8_t fit = r.u8();
    if (fit > static_cast<std::uint8_t>(DruckerPragerFit::Inner)) r.fail("an unknown Drucker-Prager fit");
    p.fit = static_cast<DruckerPragerFit>(fit);
    return std::make_shared<DruckerPrager>(p);
  }
  r.fail("a material of unknown kind '" + kind + "'");
}

// A material: a rigid one's density, or a deformable one's parameters and (from version 3) its Rayleigh
// damping.
std::shared_ptr<const Material> get_material(SectionReader& r, std::uint16_t version) {
  const std::string kind = r.text();
  try {
    if (kind == "rigid") {
      const double density = r.f64();
      if (!(density > 0.0 && std::isfinite(density))) r.fail("a rigid material's density is not > 0");
      return std::make_shared<RigidMaterial>(density);
    }
    std::shared_ptr<Material> m = get_deformable(r, kind);
    if (version >= 3) {
      const double alpha = r.f64(), beta = r.f64();
      m->set_rayleigh(Rayleigh::coefficients(alpha, beta));
    }
    return m;
  } catch (const InputError& e) {
    r.fail("material '" + kind + "': " + e.what());
  }
}

}  // namespace

std::string velocity_history_key(const std::string& body, int axis) {
  static const char* names[] = {"vx", "vy", "vz"};
  return body + "." + names[axis];
}

std::string boundary_history_key(Side side, int axis) {
  return "boundary." + std::string(side_name(side)) + "." + std::string(1, "xyz"[axis]);
}

// The one place that reads and restores the private state of the model, the schedule, the probes, the
// output and the simulation: each function mirrors its writer, section by section.
template <int Dim>
class CheckpointAccess {
 public:
  static void write(const Simulation<Dim>& sim, const std::string& path) {
    CheckpointWriter file;
    const Model<Dim>& m = sim.model_;
    write_meta(file.section(kMeta), sim);
    write_settings(file.section(kSettings), m.settings_);
    write_materials(file.section(kMaterials), m);
    write_bodies(file.section(kBodies), m);
    write_particles(file.section(kParticles), m.particles_);
    write_grid(file.section(kGrid), m.grid_);
    write_contact(file.section(kContact), m);
    write_clock(file.section(kClock), m);
    write_schedule(file.section(kSchedule), sim.schedule_);
    write_probes(file.section(kProbes), sim);
    write_probe_extra(file.section(kProbeExtra), sim);
    if (!sim.boundaries_.empty()) write_boundaries(file.section(kBoundaries), sim);
    write_output(file.section(kOutput), sim);
    write_run(file.section(kRun), sim);
    file.write(path);
  }

  static ModelSettings<Dim> settings(const CheckpointReader& file) {
    SectionReader meta = file.section(kMeta);
    meta.text();  // the program that wrote it
    const std::uint32_t dim = meta.u32();
    if (dim != Dim)
      throw CheckpointError("checkpoint " + file.path() + ": a " + std::to_string(dim) + "D model, not " +
                            std::to_string(Dim) + "D");
    SectionReader r = file.section(kSettings);
    ModelSettings<Dim> s;
    s.lower = get_point<Dim>(r);
    s.upper = get_point<Dim>(r);
    s.cell = r.f64();
    const std::uint8_t shape = r.u8(), scheme = r.u8();
    if (shape > static_cast<std::uint8_t>(ShapeKind::Gimp) || scheme > static_cast<std::uint8_t>(Scheme::Musl))
      r.fail("an unknown shape function or scheme");
    s.shape = static_cast<ShapeKind>(shape);
    s.scheme = static_cast<Scheme>(scheme);
    s.gravity = get_point<Dim>(r);
    s.cfl = r.f64();
    const std::uint8_t transfer = r.u8();
    if (transfer > static_cast<std::uint8_t>(Transfer::Apic)) r.fail("an unknown velocity transfer");
    s.transfer = static_cast<Transfer>(transfer);
    s.flip = r.f64();
    s.fixed_dt = r.f64();
    s.sort_every = r.i32();
    s.cell_volumetric_strain = r.boolean();
    s.max_dilation = r.f64();
    s.crack_closure = r.boolean();
    s.profile = r.boolean();
    s.check_memory = r.boolean();
    r.finish();
    // A domain of more cells than memory holds is refused by the model's memory check (check_memory).
    double cells = 1.0;
    for (int d = 0; d < Dim; ++d) cells *= (s.upper[d] - s.lower[d]) / s.cell;
    if (!(s.cell > 0.0) || !(cells > 0.0) || cells > 1e9)
      r.fail("a domain of " + std::to_string(cells) + " cells is not a model this program could have saved");
    return s;
  }

  static void restore(const CheckpointReader& file, Simulation<Dim>& sim, const SuppliedHistories& histories) {
    Model<Dim>& m = sim.model_;
    if (!m.bodies_.empty() || m.material_count() || sim.output_ || !sim.probes_.empty())
      throw std::logic_error("restore_checkpoint: the simulation must be new");
    try {
      read_materials(file.section(kMaterials), m, file.version());
      read_bodies(file.section(kBodies), m);
      read_particles(file.section(kParticles), m, file.version());
      read_grid(file.section(kGrid), m.grid_);
      std::vector<std::string> keys;  // the model's histories, for the supplied ones to name
      read_contact(file.section(kContact), m, histories, keys);
      if (file.has(kBoundaries)) read_boundaries(file.section(kBoundaries), sim, histories, keys);
      check_supplied_histories(file.path(), histories, keys);
      read_clock(file.section(kClock), m);
      read_schedule(file.section(kSchedule), sim.schedule_);
      read_probes(file.section(kProbes), sim);
      if (file.has(kProbeExtra)) read_probe_extra(file.section(kProbeExtra), sim);
      read_output(file.section(kOutput), sim);
      read_run(file.section(kRun), sim);
    } catch (const CheckpointError&) {
      throw;
    } catch (const std::exception& e) {  // what the kernel refused of the content (a pair twice, ...)
      throw CheckpointError("checkpoint " + file.path() + ": " + e.what());
    }
  }

  static void rewrite_output_files(Simulation<Dim>& sim) {
    Output<Dim>* out = sim.output_.get();
    if (!out) return;
    const std::string& dir = out->settings_.dir;
    write_file_atomically(dir + "/particles.pvd", pvd_text(out->files_));
    if (!out->rigid_files_.empty()) write_file_atomically(dir + "/rigid.pvd", pvd_text(out->rigid_files_));
    if (!out->grid_files_.empty()) write_file_atomically(dir + "/grid.pvd", pvd_text(out->grid_files_));
    // The tables whole, which also restarts their appending from the restored rows.
    out->rewrite_tables(sim.probes_);
  }

 private:
  // --- writing, section by section

  static void write_meta(SectionWriter& w, const Simulation<Dim>& sim) {
    w.text("seismpm");
    w.u32(Dim);
    w.f64(sim.model_.time_);
    w.i64(sim.model_.steps_);
    w.text(sim.phase_);
  }

  static void write_settings(SectionWriter& w, const ModelSettings<Dim>& s) {
    put_point<Dim>(w, s.lower);
    put_point<Dim>(w, s.upper);
    w.f64(s.cell);
    w.u8(static_cast<std::uint8_t>(s.shape));
    w.u8(static_cast<std::uint8_t>(s.scheme));
    put_point<Dim>(w, s.gravity);
    w.f64(s.cfl);
    w.u8(static_cast<std::uint8_t>(s.transfer));
    w.f64(s.flip);
    w.f64(s.fixed_dt);
    w.i32(s.sort_every);
    w.boolean(s.cell_volumetric_strain);
    w.f64(s.max_dilation);
    w.boolean(s.crack_closure);
    w.boolean(s.profile);
    w.boolean(s.check_memory);
  }

  static void write_materials(SectionWriter& w, const Model<Dim>& m) {
    w.count(m.materials_.size());
    for (std::size_t k = 0; k < m.materials_.size(); ++k) {
      w.text(m.material_names_[k]);
      put_material(w, *m.materials_[k]);
    }
  }

  static void write_bodies(SectionWriter& w, const Model<Dim>& m) {
    w.count(m.bodies_.size());
    for (const Body& b : m.bodies_) {
      w.text(b.name);
      w.i32(b.ppc);
      w.boolean(b.rigid);
      w.i32(b.material);
    }
  }

  static void write_particles(SectionWriter& w, const Particles<Dim>& p) {
    w.count(p.size());
    p.for_each_member([&](const auto& member) { put_vector(w, member); });
  }

  static void write_grid(SectionWriter& w, const Grid<Dim>& g) {
    w.count(g.fixed_nodes_.size());
    for (const int node : g.fixed_nodes_) {
      w.i32(node);
      w.u8(g.fixity_[node]);
    }
  }

  static void write_contact(SectionWriter& w, const Model<Dim>& m) {
    const ContactFields<Dim>& c = m.contact_;
    w.count(c.pairs_.size());
    for (const ContactPair& p : c.pairs_) {
      w.i32(p.a);
      w.i32(p.b);
      w.f64(p.friction);
    }
    w.count(c.motion_.size());
    for (const RigidMotion<Dim>& r : c.motion_) {
      for (int d = 0; d < Dim; ++d) {
        w.boolean(static_cast<bool>(r.velocity[d]));
        if (r.velocity[d]) put_history(w, *r.velocity[d]);
      }
      put_point<Dim>(w, r.current);
      put_point<Dim>(w, r.force);
      put_point<Dim>(w, r.impulse);
    }
  }

  static void write_clock(SectionWriter& w, const Model<Dim>& m) {
    w.f64(m.time_);
    w.f64(m.dt_);
    w.i64(m.steps_);
    w.f64(m.phase_start_);
    w.boolean(m.rigid_bodies_move_);
    w.boolean(m.measure_balance_);
    w.f64(m.balance_.out_of_balance);
    w.f64(m.balance_.external);
    w.f64(m.mass_threshold_);
    w.f64(m.time_step_.first_);
  }

  static void write_schedule(SectionWriter& w, const EventSchedule& s) {
    w.count(s.streams_.size());
    for (const auto& e : s.streams_) {
      w.u8(static_cast<std::uint8_t>(e.spacing));
      w.f64(e.every);
      w.f64(e.anchor);
      w.f64(e.next);
      w.i64(e.count);
      w.boolean(e.active);
    }
    w.f64(s.end_);
    w.f64(s.duration_);
  }

  static void write_probes(SectionWriter& w, const Simulation<Dim>& sim) {
    w.count(sim.probes_.size());
    for (std::size_t k = 0; k < sim.probes_.size(); ++k) {
      const Probe<Dim>& p = *sim.probes_[k];
      w.text(p.name_);
      w.i32(p.id_);
      w.i32(sim.probe_streams_[k]);
      w.array(p.times_);
      w.array(p.values_);
    }
  }

  static void write_probe_extra(SectionWriter& w, const Simulation<Dim>& sim) {
    w.count(sim.probes_.size());
    for (const auto& probe : sim.probes_) {
      const Probe<Dim>& p = *probe;
      w.u8(static_cast<std::uint8_t>(p.relative_.kind));
      w.i32(p.relative_.index);
      w.text(p.relative_.what);
      w.array(p.phase_times_);
      w.count(p.phases_.size());
      for (const auto& [first, phase] : p.phases_) {
        w.count(first);
        w.text(phase);
      }
      w.array(p.relative_values_);
    }
  }

  static void write_files(SectionWriter& w, const std::vector<std::pair<double, std::string>>& files) {
    w.count(files.size());
    for (const auto& [t, name] : files) {
      w.f64(t);
      w.text(name);
    }
  }

  static void write_output(SectionWriter& w, const Simulation<Dim>& sim) {
    w.boolean(static_cast<bool>(sim.output_));
    if (sim.output_) {
      const Output<Dim>& o = *sim.output_;
      w.text(o.settings_.dir);
      w.f64(o.settings_.every);
      w.count(o.settings_.arrays.size());
      for (const VtuArray a : o.settings_.arrays) w.u8(static_cast<std::uint8_t>(a));
      w.boolean(o.settings_.grid);
      write_files(w, o.files_);
      write_files(w, o.grid_files_);
      write_files(w, o.rigid_files_);
      w.text(o.reactions_);
      w.f64(o.last_time_);
      w.count(o.last_impulse_.size());
      for (const auto& i : o.last_impulse_) put_point<Dim>(w, i);
      w.i32(sim.output_stream_);
      w.boolean(sim.write_at_run_end_);
    }
    w.text(sim.checkpoint_path_);
    w.f64(sim.checkpoint_every_);
  }

  static void write_run(SectionWriter& w, const Simulation<Dim>& sim) {
    w.text(sim.phase_);
    w.boolean(static_cast<bool>(sim.damping_));
    w.f64(sim.damping_ ? sim.damping_->alpha() : 0.0);
    // The run in progress: the one stepping now, or the one a restore left unfinished.
    const auto* run = sim.running_ ? &sim.active_ : sim.interrupted_ ? &*sim.interrupted_ : nullptr;
    w.boolean(run != nullptr);
    if (!run) return;
    w.u8(static_cast<std::uint8_t>(run->kind));
    w.f64(run->start);
    w.f64(run->duration);
    w.i64(run->max_steps);
    w.i64(run->taken);
    w.boolean(run->final_output);
    w.i32(run->call);
    w.boolean(sim.gravity_.has_value());
    if (!sim.gravity_) return;
    const auto& g = *sim.gravity_;
    for (double v : {g.settings.damping, g.settings.tolerance, g.settings.max_time, g.settings.k0}) w.f64(v);
    w.f64(g.start_time);
    w.i64(g.start_steps);
    const EquilibriumMonitor<Dim>& e = g.equilibrium;
    for (double v : {e.tolerance_, e.force_ratio_, e.energy_ratio_, e.peak_energy_}) w.f64(v);
    w.i64(e.steps_);
  }

  // --- reading, in the same order

  static void read_materials(SectionReader r, Model<Dim>& m, std::uint16_t version) {
    const std::size_t n = r.count(5);
    for (std::size_t k = 0; k < n; ++k) {
      const std::string name = r.text();
      m.add_material(get_material(r, version), name);
    }
    r.finish();
  }

  static void read_bodies(SectionReader r, Model<Dim>& m) {
    const std::size_t n = r.count(13);
    for (std::size_t k = 0; k < n; ++k) {
      Body b;
      b.name = r.text();
      b.ppc = r.i32();
      b.rigid = r.boolean();
      b.material = r.i32();
      if (b.ppc < 1 || b.ppc > kMaxParticlesPerCell) r.fail("body '" + b.name + "': ppc out of range");
      if (b.rigid != (b.material >= 0) || b.material >= m.material_count())
        r.fail("body '" + b.name + "': its material " + std::to_string(b.material) + " does not fit");
      m.bodies_.push_back(b);
      m.contact_.add_body();
    }
    r.finish();
  }

  static void read_particles(SectionReader r, Model<Dim>& m, std::uint16_t version) {
    Particles<Dim>& p = m.particles_;
    const std::size_t n = r.count(1);
    p.for_each_member([&](auto& member) {
      using T = typename std::decay_t<decltype(member)>::value_type;
      if constexpr (std::is_same_v<T, Sym>)
        if (&member == &p.damping_stress && version < 3) {  // not in version 2: undamped
          member.assign(n, Sym::Zero());
          return;
        }
      member = get_vector<T>(r, "a particle field");
      if (member.size() != n)
        r.fail("a particle field has " + std::to_string(member.size()) + " values, not " + std::to_string(n));
    });
    r.finish();
    std::vector<char> seen(n, 0);
    for (std::size_t k = 0; k < n; ++k) {
      const auto id = p.id[k];
      if (id < 0 || static_cast<std::size_t>(id) >= n || seen[id]) r.fail("the particle ids are not 0 .. n-1");
      seen[id] = 1;
      if (p.body[k] >= m.bodies_.size() || p.material[k] >= m.material_count())
        r.fail("particle " + std::to_string(id) + " names a body or material that does not exist");
      // 1 / (2 ppc) at creation: wider, a uGIMP support would reach nodes its 3-node stencil lacks.
      if (!(p.half_width[k] > 0.0 && p.half_width[k] <= 0.5))
        r.fail("particle " + std::to_string(id) + " has a half-width of " + number_text(p.half_width[k]) +
               " cells, outside (0, 0.5]");
    }
    m.index_of_id_.clear();
    m.material_lists_valid_ = false;
  }

  static void read_grid(SectionReader r, Grid<Dim>& g) {
    const std::size_t n = r.count(5);
    for (std::size_t k = 0; k < n; ++k) {
      const int node = r.i32();
      const std::uint8_t mask = r.u8();
      if (node < 0 || node >= g.node_count() || mask == 0 || mask >= (1u << Dim) || g.fixity_[node] ||
          (!g.fixed_nodes_.empty() && node <= g.fixed_nodes_.back()))
        r.fail("a fixity on node " + std::to_string(node) + " that the grid does not have");
      g.fixity_[node] = mask;
      g.fixed_nodes_.push_back(node);
    }
    r.finish();
  }

  static void read_contact(SectionReader r, Model<Dim>& m, const SuppliedHistories& supplied,
                           std::vector<std::string>& keys) {
    const std::size_t pairs = r.count(16);
    for (std::size_t k = 0; k < pairs; ++k) {
      const int a = r.i32(), b = r.i32();
      const double friction = r.f64();
      m.add_contact(a, b, friction);
    }
    const std::size_t n = r.count(Dim * 3 * 8);
    if (n != m.bodies_.size())
      r.fail("rigid motions for " + std::to_string(n) + " bodies, not " + std::to_string(m.bodies_.size()));
    for (std::size_t b = 0; b < n; ++b) {
      RigidMotion<Dim>& motion = m.contact_.motion_[b];
      for (int d = 0; d < Dim; ++d) {
        if (!r.boolean()) continue;
        const std::string key = velocity_history_key(m.bodies_[b].name, d);
        keys.push_back(key);
        motion.velocity[d] =
            get_history(r, key, "the velocity " + key + " of rigid body '" + m.bodies_[b].name + "'", supplied);
      }
      motion.current = get_point<Dim>(r);
      motion.force = get_point<Dim>(r);
      motion.impulse = get_point<Dim>(r);
    }
    r.finish();
  }

  static void check_supplied_histories(const std::string& file, const SuppliedHistories& supplied,
                                       const std::vector<std::string>& keys) {
    for (const auto& [key, history] : supplied) {
      if (std::find(keys.begin(), keys.end(), key) != keys.end()) continue;
      std::string known;
      for (const auto& k : keys) known += (known.empty() ? "" : ", ") + k;
      throw CheckpointError("checkpoint " + file + ": histories: '" + key + "' names no history of the model (" +
                            (known.empty() ? "it has none" : "its histories: " + known) + ")");
    }
  }

  // --- edge boundaries: their settings, what they recorded and their free-field columns

  static void write_boundaries(SectionWriter& w, const Simulation<Dim>& sim) {
    w.count(sim.boundaries_.size());
    for (const auto& edge : sim.boundaries_) {
      const EdgeBoundary<Dim>& b = *edge;
      const BoundarySettings<Dim>& s = b.settings_;
      w.u8(static_cast<std::uint8_t>(s.side));
      w.u8(static_cast<std::uint8_t>(s.kind));
      for (double v : {s.density, s.vs, s.vp}) w.f64(v);
      w.boolean(s.moving_frame);
      for (int d = 0; d < Dim; ++d) {
        w.boolean(static_cast<bool>(s.input[d]));
        if (s.input[d]) put_history(w, *s.input[d]);
      }
      w.boolean(b.holding_);
      w.boolean(b.prepared_);
      w.array(b.own_);
      w.count(b.reaction_.size());
      for (const auto& r : b.reaction_) put_point<Dim>(w, r);
      w.array(b.area_);
      w.array(b.rho_vs_);
      w.array(b.rho_vp_);
      w.array(b.column_node_);
      put_point<Dim>(w, b.frame_velocity_);
      put_point<Dim>(w, b.last_force_);
      w.boolean(b.column_.has_value());
      if (!b.column_) continue;
      const FreeFieldColumn<Dim>& c = *b.column_;
      w.count(c.layers_.size());
      for (const ColumnLayer& L : c.layers_)
        for (double v : {L.density, L.shear_modulus, L.p_wave_modulus, L.lame, L.rayleigh_alpha, L.rayleigh_beta})
          w.f64(v);
      w.f64(c.spacing_);
      w.u8(static_cast<std::uint8_t>(c.base_.kind));
      w.f64(c.base_.rho_vs);
      w.f64(c.base_.rho_vp);
      w.boolean(c.base_.moving_frame);
      for (const auto* field : {&c.u_, &c.v_, &c.stress_}) {
        w.count(field->size());
        for (const auto& x : *field) put_point<Dim>(w, x);
      }
    }
  }

  static std::vector<Vec<Dim>> get_points(SectionReader& r, std::size_t expected) {
    const std::size_t n = r.count(Dim * 8);
    if (n != expected) r.fail("an edge boundary's arrays of different lengths");
    std::vector<Vec<Dim>> v(n);
    for (auto& x : v) x = get_point<Dim>(r);
    return v;
  }

  static void read_boundaries(SectionReader r, Simulation<Dim>& sim, const SuppliedHistories& supplied,
                              std::vector<std::string>& keys) {
    Model<Dim>& m = sim.model_;
    const std::size_t n = r.count(16);
    for (std::size_t k = 0; k < n; ++k) {
      BoundarySettings<Dim> s;
      const std::uint8_t side = r.u8(), kind = r.u8();
      if (side >= 2 * Dim || kind > static_cast<std::uint8_t>(BoundaryKind::FreeField))
        r.fail("an edge boundary of an unknown side or kind");
      s.side = static_cast<Side>(side);
      s.kind = static_cast<BoundaryKind>(kind);
      s.density = r.f64(), s.vs = r.f64(), s.vp = r.f64();
      s.moving_frame = r.boolean();
      for (int d = 0; d < Dim; ++d) {
        if (!r.boolean()) continue;
        const std::string key = boundary_history_key(s.side, d);
        keys.push_back(key);
        s.input[d] = get_history(r, key, "the input " + key + " of a compliant edge", supplied);
      }
      auto edge = std::make_shared<EdgeBoundary<Dim>>(m.grid_, s);  // checks the settings again
      EdgeBoundary<Dim>& b = *edge;
      for (const auto& other : sim.boundaries_)
        if (other->settings().side == s.side) r.fail("two edge boundaries on one side");
      b.holding_ = r.boolean();
      b.prepared_ = r.boolean();
      b.own_ = r.array<unsigned char>();
      if (b.holding_ && b.own_.size() != b.held_nodes_.size()) r.fail("an edge boundary's held nodes do not fit");
      b.reaction_ = get_points(r, b.held_nodes_.size());
      const std::size_t edge_nodes = b.prepared_ ? b.edge_nodes_.size() : 0;
      b.area_ = r.array<double>();
      b.rho_vs_ = r.array<double>();
      b.rho_vp_ = r.array<double>();
      b.column_node_ = r.array<int>();
      for (std::size_t size : {b.area_.size(), b.rho_vs_.size(), b.rho_vp_.size(), b.column_node_.size()})
        if (size != edge_nodes) r.fail("an edge boundary's node arrays do not fit the grid");
      b.frame_velocity_ = get_point<Dim>(r);
      b.last_force_ = get_point<Dim>(r);
      if (r.boolean()) {
        std::vector<ColumnLayer> layers(r.count(6 * 8));
        for (ColumnLayer& L : layers) {
          L.density = r.f64(), L.shear_modulus = r.f64(), L.p_wave_modulus = r.f64(), L.lame = r.f64();
          L.rayleigh_alpha = r.f64(), L.rayleigh_beta = r.f64();
          if (!(L.density >= 0.0) || (L.density > 0.0 && !(L.p_wave_modulus > 0.0)))
            r.fail("a free-field column layer without stiffness");
        }
        const double spacing = r.f64();
        ColumnBase<Dim> base;
        const std::uint8_t base_kind = r.u8();
        if (base_kind > static_cast<std::uint8_t>(ColumnBase<Dim>::Kind::Dashpot)) r.fail("an unknown column base");
        base.kind = static_cast<typename ColumnBase<Dim>::Kind>(base_kind);
        base.rho_vs = r.f64(), base.rho_vp = r.f64();
        base.moving_frame = r.boolean();
        const std::size_t nodes = layers.size() + 1;
        FreeFieldColumn<Dim> column(std::move(layers), spacing, base);
        column.u_ = get_points(r, nodes);
        column.v_ = get_points(r, nodes);
        column.stress_ = get_points(r, nodes - 1);
        for (int j : b.column_node_)
          if (j >= static_cast<int>(nodes)) r.fail("an edge node of a column node that does not exist");
        b.column_.emplace(std::move(column));
      } else if (b.prepared_ && s.kind == BoundaryKind::FreeField) {
        r.fail("a free-field edge without its column");
      }
      m.add_fix(edge);
      sim.boundaries_.push_back(edge);
    }
    r.finish();
    sim.link_boundaries();
    // The columns' base input is the base's own (saved with it).
    for (const auto& b : sim.boundaries_)
      if (b->column_ && b->column_base_ && b->column_base_->settings().kind == BoundaryKind::Compliant)
        b->column_->base_.input = b->column_base_->settings().input;
  }

  static void read_clock(SectionReader r, Model<Dim>& m) {
    m.time_ = r.f64();
    m.dt_ = r.f64();
    m.steps_ = r.i64();
    m.phase_start_ = r.f64();
    m.rigid_bodies_move_ = r.boolean();
    m.measure_balance_ = r.boolean();
    m.balance_.out_of_balance = r.f64();
    m.balance_.external = r.f64();
    m.mass_threshold_ = r.f64();
    m.time_step_.first_ = r.f64();
    r.finish();
    if (!std::isfinite(m.time_) || m.steps_ < 0) r.fail("a clock that is not finite");
  }

  static void read_schedule(SectionReader r, EventSchedule& s) {
    const std::size_t n = r.count(34);
    s.streams_.clear();
    for (std::size_t k = 0; k < n; ++k) {
      EventSchedule::Entry e{};
      const std::uint8_t spacing = r.u8();
      if (spacing > static_cast<std::uint8_t>(EventSchedule::Spacing::FromStart)) r.fail("an unknown event spacing");
      e.spacing = static_cast<EventSchedule::Spacing>(spacing);
      e.every = r.f64();
      e.anchor = r.f64();
      e.next = r.f64();
      e.count = r.i64();
      e.active = r.boolean();
      s.streams_.push_back(e);
    }
    s.end_ = r.f64();
    s.duration_ = r.f64();
    r.finish();
  }

  // A stream index that the schedule holds and that is active.
  static EventSchedule::Stream stream_of(SectionReader& r, const EventSchedule& s, std::int32_t k, const char* what) {
    if (k < 0 || k >= static_cast<std::int32_t>(s.streams_.size()) || !s.streams_[k].active)
      r.fail(std::string(what) + " names no event stream of the schedule");
    return k;
  }

  static void read_probes(SectionReader r, Simulation<Dim>& sim) {
    const std::size_t n = r.count(28);
    const std::size_t fields = particle_fields(Dim).size();
    for (std::size_t k = 0; k < n; ++k) {
      const std::string name = r.text();
      const int id = r.i32();
      const auto stream = stream_of(r, sim.schedule_, r.i32(), "a probe");
      auto times = r.array<double>();
      auto values = r.array<double>();
      if (values.size() != times.size() * fields || times.empty())
        r.fail("probe '" + name + "': " + std::to_string(values.size()) + " values for " +
               std::to_string(times.size()) + " samples");
      auto probe = std::make_shared<Probe<Dim>>(sim.model_, name, id);  // checks the id
      probe->times_ = std::move(times);
      probe->values_ = std::move(values);
      // Unknown unless the section of their phases follows (read_probe_extra).
      probe->phase_times_.assign(probe->times_.size(), std::numeric_limits<double>::quiet_NaN());
      probe->phases_.clear();
      sim.probes_.push_back(std::move(probe));
      sim.probe_streams_.push_back(stream);
    }
    r.finish();
  }

  static void read_probe_extra(SectionReader r, Simulation<Dim>& sim) {
    if (r.count(1) != sim.probes_.size()) r.fail("not one entry per probe");
    using Kind = ProbeRelativeTo::Kind;
    for (const auto& probe : sim.probes_) {
      Probe<Dim>& p = *probe;
      const std::string who = "probe '" + p.name_ + "': ";
      ProbeRelativeTo rel;
      const std::uint8_t kind = r.u8();
      if (kind > static_cast<std::uint8_t>(Kind::Body)) r.fail(who + "an unknown kind of reference");
      rel.kind = static_cast<Kind>(kind);
      rel.index = r.i32();
      rel.what = r.text();
      const int limit =
          static_cast<int>(rel.kind == Kind::Body ? sim.model_.bodies().size() : sim.model_.particles().size());
      if (rel.active() && (rel.index < 0 || rel.index >= limit)) r.fail(who + "a reference the model does not hold");
      auto phase_times = r.array<double>();
      if (phase_times.size() != p.times_.size()) r.fail(who + "not one phase time per sample");
      std::vector<std::pair<std::size_t, std::string>> phases(r.count(12));
      for (std::size_t k = 0; k < phases.size(); ++k) {
        const std::int64_t at = r.i64();
        const auto first = static_cast<std::size_t>(std::max<std::int64_t>(at, 0));
        if (at < 0 || first >= p.times_.size() || (k > 0 && first <= phases[k - 1].first) || (k == 0 && first != 0))
          r.fail(who + "phases out of order");
        phases[k] = {first, r.text()};
      }
      auto relative = r.array<double>();
      if (relative.size() != (rel.active() ? p.times_.size() * Dim : 0))
        r.fail(who + "not one relative displacement per sample");
      p.relative_ = std::move(rel);
      p.phase_times_ = std::move(phase_times);
      p.phases_ = std::move(phases);
      p.relative_values_ = std::move(relative);
    }
    r.finish();
  }

  static std::vector<std::pair<double, std::string>> read_files(SectionReader& r) {
    std::vector<std::pair<double, std::string>> files(r.count(12));
    for (auto& [t, name] : files) {
      t = r.f64();
      name = r.text();
    }
    return files;
  }

  static void read_output(SectionReader r, Simulation<Dim>& sim) {
    if (r.boolean()) {
      OutputSettings s;
      s.dir = r.text();
      s.every = r.f64();
      s.arrays.resize(r.count(1));
      for (VtuArray& a : s.arrays) {
        const std::uint8_t q = r.u8();
        if (q == 0 || q >= std::size(kQuantities) || !kQuantities[q].vtu_array) r.fail("an unknown output array");
        a = static_cast<VtuArray>(q);
      }
      s.grid = r.boolean();
      auto files = read_files(r), grid_files = read_files(r), rigid_files = read_files(r);
      std::string reactions = r.text();
      const double last_time = r.f64();
      std::vector<Vec<Dim>> last_impulse(r.count(Dim * 8));
      for (auto& i : last_impulse) i = get_point<Dim>(r);
      const auto stream = stream_of(r, sim.schedule_, r.i32(), "the output");
      const bool at_run_end = r.boolean();
      auto output = std::make_unique<Output<Dim>>(s);  // creates the directory, or throws naming it
      output->files_ = std::move(files);
      output->grid_files_ = std::move(grid_files);
      output->rigid_files_ = std::move(rigid_files);
      output->reactions_ = std::move(reactions);
      output->last_time_ = last_time;
      output->last_impulse_ = std::move(last_impulse);
      sim.output_ = std::move(output);
      sim.output_stream_ = stream;
      sim.write_at_run_end_ = at_run_end;
    }
    const std::string path = r.text();
    const double every = r.f64();
    r.finish();
    if (!path.empty()) sim.set_periodic_checkpoint(path, every);
  }

  static void read_run(SectionReader r, Simulation<Dim>& sim) {
    sim.phase_ = r.text();
    const bool damping = r.boolean();
    const double alpha = r.f64();
    if (damping) sim.set_damping(alpha);
    if (r.boolean()) {
      typename Simulation<Dim>::ActiveRun run;
      const std::uint8_t kind = r.u8();
      if (kind > static_cast<std::uint8_t>(RunKind::Dynamic)) r.fail("an unknown kind of run");
      run.kind = static_cast<RunKind>(kind);
      run.start = r.f64();
      run.duration = r.f64();
      run.max_steps = r.i64();
      run.taken = r.i64();
      run.final_output = r.boolean();
      const std::int32_t call = r.i32();
      run.call = call < 0 ? -1 : stream_of(r, sim.schedule_, call, "the run's call");
      if (r.boolean()) {
        GravityPhaseSettings g;
        for (double* v : {&g.damping, &g.tolerance, &g.max_time, &g.k0}) *v = r.f64();
        const double start_time = r.f64();
        const long start_steps = r.i64();
        EquilibriumMonitor<Dim> e(g.tolerance);
        for (double* v : {&e.tolerance_, &e.force_ratio_, &e.energy_ratio_, &e.peak_energy_}) *v = r.f64();
        e.steps_ = r.i64();
        sim.gravity_.emplace(typename Simulation<Dim>::GravityRun{g, start_time, start_steps, e});
      }
      if ((run.kind == RunKind::Gravity) != sim.gravity_.has_value())
        r.fail("a gravity phase without its state, or that state without the phase");
      sim.interrupted_ = run;
    }
    r.finish();
  }
};

template <int Dim>
void write_checkpoint(const Simulation<Dim>& simulation, const std::string& path) {
  try {
    CheckpointAccess<Dim>::write(simulation, path);
  } catch (const CheckpointError& e) {
    throw CheckpointError(std::string(e.what()) + " (writing " + path + ")");
  }
}

std::optional<std::string> checkpoint_output_dir(const CheckpointReader& file) {
  SectionReader r = file.section(kOutput);
  if (!r.boolean()) return std::nullopt;
  return r.text();
}

template <int Dim>
ModelSettings<Dim> checkpoint_settings(const CheckpointReader& file) {
  return CheckpointAccess<Dim>::settings(file);
}

template <int Dim>
void restore_checkpoint(const CheckpointReader& file, Simulation<Dim>& simulation, const SuppliedHistories& histories) {
  CheckpointAccess<Dim>::restore(file, simulation, histories);
  rewrite_output_files(simulation);
}

template <int Dim>
void rewrite_output_files(Simulation<Dim>& simulation) {
  CheckpointAccess<Dim>::rewrite_output_files(simulation);
}

template void write_checkpoint<2>(const Simulation<2>&, const std::string&);
template void write_checkpoint<3>(const Simulation<3>&, const std::string&);
template ModelSettings<2> checkpoint_settings<2>(const CheckpointReader&);
template ModelSettings<3> checkpoint_settings<3>(const CheckpointReader&);
template void restore_checkpoint<2>(const CheckpointReader&, Simulation<2>&, const SuppliedHistories&);
template void restore_checkpoint<3>(const CheckpointReader&, Simulation<3>&, const SuppliedHistories&);
template void rewrite_output_files<2>(Simulation<2>&);
template void rewrite_output_files<3>(Simulation<3>&);

}  // namespace seismpm
