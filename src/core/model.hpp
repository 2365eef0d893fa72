// A model: background grid, particles, materials, bodies and fixes, and the explicit MPM step.
// Contact between bodies and rigid prescribed-velocity bodies live in src/contact (ContactFields),
// which the step calls at its named stages only when contact fields exist.
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "active_nodes.hpp"
#include "body.hpp"
#include "contact/contact_fields.hpp"
#include "diagnostics.hpp"
#include "fix.hpp"
#include "grid.hpp"
#include "material.hpp"
#include "particle_support.hpp"
#include "particles.hpp"
#include "stage_timer.hpp"
#include "step_context.hpp"
#include "time_step.hpp"
#include "types.hpp"

namespace seismpm {

enum class Scheme { Usl, Musl };
// How particle velocities are updated from the grid: FLIP (blended with PIC by ModelSettings::flip)
// or APIC, the grid velocity plus the affine velocity field (gradient) around the particle.
enum class Transfer { Flip, Apic };

template <int Dim>
struct ModelSettings {
  Vec<Dim> lower = Vec<Dim>::Zero();
  Vec<Dim> upper = Vec<Dim>::Ones();
  double cell = 0.1;  // m
  ShapeKind shape = ShapeKind::Gimp;
  Scheme scheme = Scheme::Musl;
  Vec<Dim> gravity = Vec<Dim>::Zero();  // m/s^2
  double cfl = 0.4;                     // dt = cfl h / max(c_p + |v_p|)
  Transfer transfer = Transfer::Flip;
  double flip = 1.0;      // Transfer::Flip: 1 = FLIP, 0 = PIC
  double fixed_dt = 0.0;  // > 0 overrides the CFL time step (s)
  int sort_every = 20;    // steps between sorting particles by cell
  // Average the volumetric strain increment over each cell (B-bar style): removes the volumetric
  // locking that isochoric plastic flow (psi = 0) and near-incompressibility cause in low-order cells.
  bool cell_volumetric_strain = true;
  // Largest particle volume as a multiple of its initial one (0: no limit). A cohesionless particle at
  // the tension apex carries no stress and would otherwise swell without bound where the soil breaks
  // up (30x seen on a failing slope), shrinking the time step through its falling density.
  double max_dilation = 2.0;
  // Crack closure for materials without tensile strength (Material::tensionless): a particle whose
  // volume exceeds its stress-free one m / rho_0 has opened through the tension cut-off; compressing
  // it closes that opening first, without raising its mean stress (shear still loads it). Without it
  // the elastic law resists closing what opened freely, so every load cycle opens the soil further
  // (ratcheting dilation: a shaking-table slope doubled its volume at the wall).
  bool crack_closure = true;
  bool profile = false;  // time each stage of the step (Model::stage_times)
  // Refuse a grid or a fill whose arrays would need more memory than the system has available.
  bool check_memory = true;
};

template <int Dim>
class CheckpointAccess;  // reads and restores the private state (src/run/checkpoint.cpp)

template <int Dim>
class Model {
 public:
  explicit Model(const ModelSettings<Dim>& settings);
  Model(Model&&) = default;
  Model& operator=(Model&&) = default;

  // A copy for a trial run that must leave this model as it is (strength reduction): grid, particles,
  // materials (shared: they are immutable), bodies, contact and the clock. Fixes are not copied: each
  // belongs to the run that attached it (a simulation's damping) and the trial attaches its own.
  Model copy_without_fixes() const;

  // --- building ---
  // Returns the material's index, which particles carry; `name` labels it in outputs (default: its kind).
  int add_material(std::shared_ptr<const Material> material, const std::string& name = "");
  // Puts `material` in the place of material `index` for the particles that have it. Its density must
  // be the same (the particles' masses come from it); its moduli may differ.
  void replace_material(int index, std::shared_ptr<const Material> material);
  // A deformable body, or a rigid one at rest (density 1000 kg/m^3 for show).
  int add_body(const std::string& name, int ppc, bool rigid = false);
  // A rigid body of prescribed-velocity particles following `velocity` (m/s per axis, histories read
  // at the phase time); `density` only gives its particles a mass to show.
  int add_rigid_body(const std::string& name, int ppc, double density,
                     const std::array<std::shared_ptr<const History>, Dim>& velocity);
  void set_rigid_velocity(int body, const std::array<std::shared_ptr<const History>, Dim>& velocity);
  // Frictional contact between two bodies (Bardenhagen). Bodies without a declared pair share one
  // velocity field where they meet (no slip, no separation).
  void add_contact(int a, int b, double friction);
  // A declared pair's new Coulomb coefficient (strength loss between phases: peak, then residual).
  void set_contact_friction(int a, int b, double friction);
  // Fills every cell sub-point (ppc per axis) that lies inside `inside` and the box [lo, hi]
  // with a particle of `body` and `material` (for a rigid body, -1: its own). Returns the number of
  // particles added.
  // `outward` (rigid bodies) gives the outward normal of the body's face nearest to a point: contact
  // normals then follow the true surface instead of the grid's staircase of cells.
  std::size_t fill(int body, int material, const Vec<Dim>& lo, const Vec<Dim>& hi,
                   const std::function<bool(const Vec<Dim>&)>& inside,
                   const std::function<Vec<Dim>(const Vec<Dim>&)>& outward = {});
  // The same with each particle's material chosen by its position (material regions in one body):
  // material_at(x) gives a material index. Throws InputError naming the body and the point, adding
  // nothing, where it gives none that exists (-1).
  std::size_t fill(int body, const std::function<int(const Vec<Dim>&)>& material_at, const Vec<Dim>& lo,
                   const Vec<Dim>& hi, const std::function<bool(const Vec<Dim>&)>& inside,
                   const std::function<Vec<Dim>(const Vec<Dim>&)>& outward = {});
  std::size_t fill_box(int body, int material, const Vec<Dim>& lo, const Vec<Dim>& hi);
  // The memory one particle takes (its fields and the step's per-particle arrays), and the memory of a
  // grid built with `settings` (its nodes' fields and the step's per-cell arrays), in bytes.
  std::size_t bytes_per_particle() const;
  static double grid_bytes(const ModelSettings<Dim>& settings);
  // The positions a fill with ppc particles per cell per axis would give particles, in creation
  // order; adds nothing.
  std::vector<Vec<Dim>> fill_points(int ppc, const Vec<Dim>& lo, const Vec<Dim>& hi,
                                    const std::function<bool(const Vec<Dim>&)>& inside) const;
  void add_fix(std::shared_ptr<Fix<Dim>> fix);
  // Detaches a fix (a phase's damping or monitor when the phase ends); false when it was not attached.
  bool remove_fix(const Fix<Dim>* fix);

  // The acceleration of the frame the model moves in (m/s^2): every particle feels gravity - a. A
  // compliant base computes the model relative to its outcrop motion (EdgeBoundary), so that the ground
  // stays where the grid is however far a record carries it; set for each step by that fix.
  void set_frame_acceleration(const Vec<Dim>& a) { frame_acceleration_ = a; }
  const Vec<Dim>& frame_acceleration() const { return frame_acceleration_; }

  // --- phases ---
  // Starts a calculation phase now: histories of rigid bodies are read at the time since this call,
  // and rigid bodies stay at rest unless `rigid_bodies_move`.
  void begin_phase(bool rigid_bodies_move);
  double phase_time() const { return time_ - phase_start_; }
  bool rigid_bodies_move() const { return rigid_bodies_move_; }

  // --- equilibrium ---
  // When on, every step measures the out-of-balance force (before damping) over the free degrees of
  // freedom of nodes not held by a rigid body, and the external (gravity) force, as Euclidean norms.
  void set_balance_measure(bool on) { measure_balance_ = on; }
  double out_of_balance_force() const { return balance_.out_of_balance; }
  double external_force() const { return balance_.external; }

  // --- running ---
  // One explicit step, no longer than dt_max.
  void step(double dt_max = std::numeric_limits<double>::infinity());
  // Steps until `duration` more seconds have passed (the last step is shortened to land on it).
  void run(double duration);

  // --- state ---
  const ModelSettings<Dim>& settings() const { return settings_; }
  Grid<Dim>& grid() { return grid_; }
  const Grid<Dim>& grid() const { return grid_; }
  // The nodes this step's particles reach, as spans per row of nodes (every node when a fix may
  // write to others); valid from the particles' location to the end of the step.
  const ActiveNodes<Dim>& active_nodes() const { return active_; }
  Particles<Dim>& particles() { return particles_; }
  const Particles<Dim>& particles() const { return particles_; }
  const std::vector<Body>& bodies() const { return bodies_; }
  const std::vector<ContactPair>& contacts() const { return contact_.pairs(); }
  const RigidMotion<Dim>& rigid_motion(int body) const { return contact_.motion(body); }
  // Contact fields, their rules and their per-field nodal data, as of the last step.
  ContactFields<Dim>& contact() { return contact_; }
  const ContactFields<Dim>& contact() const { return contact_; }
  const Material& material(int index) const { return *materials_[index]; }
  const std::string& material_name(int index) const { return material_names_[index]; }
  int material_count() const { return static_cast<int>(materials_.size()); }
  double time() const { return time_; }
  double dt() const { return dt_; }  // the last step's
  long steps() const { return steps_; }
  // Nodes with less mass than this are inactive for the step (no division by a tiny mass).
  double mass_threshold() const { return mass_threshold_; }
  // The time step the CFL condition allows for the current particle state.
  double stable_time_step() const;

  // Wall seconds spent in each stage of the step so far (when settings.profile is on).
  std::vector<std::pair<const char*, double>> stage_times() const { return timer_.times(); }

  // Current index of the particle created as number `id` (particles are reordered by sorting).
  std::size_t index_of(int id) const;

  // Energies and momentum of the deformable bodies (rigid ones have infinite mass).
  double kinetic_energy() const;
  // Elastic strain energy recovered from the stresses, sum V [(tr s)^2 / 18K + dev s : dev s / 4G].
  double strain_energy() const;
  Vec<Dim> centroid(int body) const;  // mass-weighted
  Vec<Dim> momentum() const;

 private:
  template <int>
  friend class CheckpointAccess;
  Model(const Model&) = default;  // through copy_without_fixes only

  // The step, stage by stage (model.cpp, transfer.cpp, stress_update.cpp).
  // `may_close`: per particle, whether crack closure may leave it stress-free (closable_particles).
  StepContext next_step(double dt_max, const char* may_close);
  template <class Shape, bool Contact>
  void step_with(double dt_max);
  void prescribe_rigid_velocities(const StepContext& c);
  void reset_grid(bool limited);
  template <class Shape>
  void locate_particles(bool limited);
  template <class Shape, bool Contact>
  void particles_to_grid();
  template <bool Contact>
  void nodal_forces(const StepContext& c);
  template <bool Contact>
  void update_nodal_velocities(const StepContext& c);
  template <bool Contact>
  void constrain(VelocityStage stage, const StepContext& c);
  template <class Shape, bool Contact>
  void grid_to_particles(const StepContext& c, bool remap);
  template <class Shape, bool Contact>
  void remap_momentum();
  template <class Shape, bool Contact>
  void update_stress(const StepContext& c);
  template <class Shape, bool Contact>
  void velocity_gradients(const StepContext& c);
  template <bool Contact>
  void sum_cell_volumes();
  template <bool Contact>
  void sum_cell_dilation();
  const char* closable_in_step() const;
  template <bool Contact>
  void rotate_close_and_update_volume(bool average);
  void integrate_materials();
  void rayleigh_stresses(const StepContext& c);
  void finish_step(const StepContext& c);

  // Upkeep (particle_order.cpp, particle_checks.cpp).
  int new_body(const std::string& name, int ppc, bool rigid);
  // `s`, after refusing a grid that needs more memory than is available (check_memory).
  static const ModelSettings<Dim>& with_grid_memory_checked(const ModelSettings<Dim>& s);
  double fill_candidates(int ppc, const Vec<Dim>& lo, const Vec<Dim>& hi) const;
  // Throws InputError when the particles a fill would add need more memory than is available.
  void check_fill_memory(const Body& b, const Vec<Dim>& lo, const Vec<Dim>& hi,
                         const std::function<bool(const Vec<Dim>&)>& inside) const;
  void rebuild_material_lists();
  void sort_particles();
  void check_particles() const;
  [[noreturn]] void fail(std::size_t p, const std::string& what) const;
  // A particle of a tensionless material looser than its initial density: opened by the tension
  // cut-off, to be closed first when compressed (crack closure).
  bool opened(std::size_t p) const {
    const int m = particles_.material[p];
    return settings_.crack_closure && constants_.tensionless[m] &&
           particles_.volume[p] * constants_.initial_density[m] > (1.0 + 1e-9) * particles_.mass[p];
  }
  // A volume above its stress-free volume by more than round-off: something opened to close.
  static bool exceeds_free_volume(double volume, double free_volume) { return volume > (1.0 + 1e-9) * free_volume; }
  // The volume a particle has without stress: m / rho_0 for a tensionless material (what it may close
  // back to), its volume for any other (it has nothing to close).
  double free_volume(std::size_t p) const {
    const int m = particles_.material[p];
    return constants_.tensionless[m] ? particles_.mass[p] / constants_.initial_density[m] : particles_.volume[p];
  }
  // With the cell-averaged volumetric strain: a compressed tensionless particle closes where its cell
  // is open (its volume above its stress-free volume; cell sums from sum_cell_volumes).
  bool closes_by_cell(std::size_t p, int cell) const {
    return settings_.crack_closure && constants_.tensionless[particles_.material[p]] &&
           exceeds_free_volume(cell_sums_[cell].volume, cell_sums_[cell].free_volume);
  }
  // Per particle, 1 where crack closure may leave it stress-free (looser than its initial density, in
  // an open cell), for the time step; nullptr where closure is judged particle by particle or no
  // particle is looser (stress_update.cpp). From the particles' positions, for a time step asked for
  // outside the step; the step itself takes the same flags from its own cell sums (closable_in_step).
  const char* closable_particles() const;
  // Crack closure judged by the cell (the cell-averaged volumetric strain), for some material.
  bool closure_by_cell() const {
    return settings_.cell_volumetric_strain && settings_.crack_closure && constants_.any_tensionless;
  }
  // Per cell, the sums the cell-averaged volumetric strain and crack closure read (one record: a
  // particle reads and writes them together).
  struct CellSums {
    double volume, free_volume, dilation;
  };
  template <class CellOf>
  const char* closable_flags(CellOf&& cell_of, const std::vector<CellSums>& sums) const;
  // A deformable particle's share of its cell's volume and stress-free volume.
  void add_volumes(CellSums& cell, std::size_t p) const {
    cell.volume += particles_.volume[p];
    cell.free_volume += free_volume(p);
  }

  ModelSettings<Dim> settings_;
  Grid<Dim> grid_;
  Particles<Dim> particles_;
  std::vector<std::shared_ptr<const Material>> materials_;
  std::vector<std::string> material_names_;
  MaterialConstants constants_;  // per material, what the step reads
  std::vector<Body> bodies_;
  std::vector<std::shared_ptr<Fix<Dim>>> fixes_;
  ContactFields<Dim> contact_;
  double phase_start_ = 0.0;
  bool rigid_bodies_move_ = true;
  bool measure_balance_ = false;
  Vec<Dim> frame_acceleration_ = Vec<Dim>::Zero();
  Balance balance_;
  std::vector<double> balance_scratch_;

  // Per-step scratch.
  ParticleSupport<Dim> support_;
  // The nodes the step's particles reach; the whole-grid loops walk only these. `active_valid_`: every
  // node outside the last step's spans is zero in every field (the spans were built, not covering).
  ActiveNodes<Dim> active_;
  bool active_valid_ = false;
  std::vector<Sym> strain_increment_;
  std::vector<Eigen::Vector3d> spin_;    // dt skw(L) as (w_xy, w_yz, w_xz)
  std::vector<CellSums> cell_sums_;      // valid only in the cells the step's particles are in
  mutable std::vector<char> may_close_;  // closable_flags' result (the time step runs on a const model)
  std::vector<std::vector<int>> material_particles_;
  bool material_lists_valid_ = false;
  mutable std::vector<int> index_of_id_;  // rebuilt on demand after a sort
  std::vector<int> sort_key_, sort_start_, sort_order_;
  PermuteBuffer sort_buffer_;
  StageTimer timer_;

  TimeStepControl time_step_;
  double time_ = 0.0;
  double dt_ = 0.0;
  long steps_ = 0;
  double mass_threshold_ = 0.0;
};

// Calls X(Dim, Shape, Contact) and Y(Dim, Contact) for every variant of the step, to instantiate the
// stages that the step's files define.
// clang-format off
#define SEISMPM_FOR_EACH_STEP_VARIANT(X, Y)                                                      \
  X(2, LinearShape, false) X(2, LinearShape, true) X(2, GimpShape, false) X(2, GimpShape, true) \
  X(3, LinearShape, false) X(3, LinearShape, true) X(3, GimpShape, false) X(3, GimpShape, true) \
  Y(2, false) Y(2, true) Y(3, false) Y(3, true)
// clang-format on

extern template class Model<2>;
extern template class Model<3>;

}  // namespace seismpm
