// A model: background grid, particles, materials, bodies and fixes, and the explicit MPM step.
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "fix.hpp"
#include "grid.hpp"
#include "material.hpp"
#include "particles.hpp"
#include "scatter_schedule.hpp"
#include "shape_function.hpp"
#include "stencil.hpp"
#include "types.hpp"

namespace seismpm {

enum class Scheme { Usl, Musl };

template <int Dim>
struct ModelSettings {
  Vec<Dim> lower = Vec<Dim>::Zero();
  Vec<Dim> upper = Vec<Dim>::Ones();
  double cell = 0.1;                       // m
  ShapeKind shape = ShapeKind::Gimp;
  Scheme scheme = Scheme::Musl;
  Vec<Dim> gravity = Vec<Dim>::Zero();     // m/s^2
  double cfl = 0.4;                        // dt = cfl h / max(c_p + |v_p|)
  double flip = 1.0;                       // 1 = FLIP, 0 = PIC
  double fixed_dt = 0.0;                   // > 0 overrides the CFL time step (s)
  int sort_every = 20;                     // steps between sorting particles by cell
  // Average the volumetric strain increment over each cell (B-bar style): removes the volumetric
  // locking that isochoric plastic flow (psi = 0) and near-incompressibility cause in low-order cells.
  bool cell_volumetric_strain = true;
  bool profile = false;                    // time each stage of the step (Model::stage_times)
};

struct Body {
  std::string name;
  int ppc = 2;         // particles per cell per axis at creation
  bool rigid = false;  // prescribed-velocity particles (shaking-table box, sliding surface)
};

template <int Dim>
class Model {
 public:
  explicit Model(const ModelSettings<Dim>& settings);

  // --- building ---
  int add_material(std::shared_ptr<const Material> material);
  int add_body(const std::string& name, int ppc, bool rigid = false);
  // Fills every cell sub-point (ppc per axis) that lies inside `inside` and the box [lo, hi]
  // with a particle of `body` and `material`. Returns the number of particles added.
  std::size_t fill(int body, int material, const Vec<Dim>& lo, const Vec<Dim>& hi,
                   const std::function<bool(const Vec<Dim>&)>& inside);
  std::size_t fill_box(int body, int material, const Vec<Dim>& lo, const Vec<Dim>& hi);
  void add_fix(std::shared_ptr<Fix<Dim>> fix);

  // --- running ---
  // One explicit step, no longer than dt_max.
  void step(double dt_max = std::numeric_limits<double>::infinity());
  // Steps until `duration` more seconds have passed (the last step is shortened to land on it).
  void run(double duration);

  // --- state ---
  const ModelSettings<Dim>& settings() const { return settings_; }
  Grid<Dim>& grid() { return grid_; }
  const Grid<Dim>& grid() const { return grid_; }
  Particles<Dim>& particles() { return particles_; }
  const Particles<Dim>& particles() const { return particles_; }
  const std::vector<Body>& bodies() const { return bodies_; }
  const Material& material(int index) const { return *materials_[index]; }
  int material_count() const { return static_cast<int>(materials_.size()); }
  double time() const { return time_; }
  double dt() const { return dt_; }
  long steps() const { return steps_; }
  // Nodes with less mass than this are inactive for the step (no division by a tiny mass).
  double mass_threshold() const { return mass_threshold_; }
  // The time step the CFL condition allows for the current particle state.
  double stable_time_step() const;

  // Wall seconds spent in each stage of the step so far (when settings.profile is on).
  const std::vector<std::pair<const char*, double>>& stage_times() const { return stage_times_; }

  // Current index of the particle created as number `id` (particles are reordered by sorting).
  std::size_t index_of(int id) const;

  double kinetic_energy() const;
  // Elastic strain energy recovered from the stresses, sum V [(tr s)^2 / 18K + dev s : dev s / 4G].
  double strain_energy() const;
  Vec<Dim> centroid(int body) const;  // mass-weighted
  Vec<Dim> momentum() const;

 private:
  template <class Shape>
  void step_with(double dt);
  template <class Shape>
  void compute_stencils();
  template <class Shape>
  void particles_to_grid();
  void update_nodal_velocities();
  void constrain_velocities(VelocityStage stage);
  template <class Shape>
  void grid_to_particles();
  template <class Shape>
  void remap_momentum();
  template <class Shape>
  void update_stress();
  void accumulate_cell_dilation();
  // Index of the cell holding x, clamped to the grid; the slab axis varies slowest, so each scatter
  // slab is a contiguous range of cells (and, after sorting, of particles).
  int cell_index(const Vec<Dim>& x) const;
  void check_particles() const;
  void sort_particles();
  void rebuild_material_lists();

  template <class Shape>
  std::vector<Stencil<Dim, Shape::K>>& stencils();
  [[noreturn]] void fail(std::size_t p, const std::string& what) const;

  ModelSettings<Dim> settings_;
  Grid<Dim> grid_;
  Particles<Dim> particles_;
  std::vector<std::shared_ptr<const Material>> materials_;
  std::vector<double> p_wave_modulus_;  // per material
  std::vector<Body> bodies_;
  std::vector<std::shared_ptr<Fix<Dim>>> fixes_;

  // Per-step scratch.
  std::vector<Stencil<Dim, LinearShape::K>> linear_stencils_;
  std::vector<Stencil<Dim, GimpShape::K>> gimp_stencils_;
  std::vector<Sym> strain_increment_;
  std::vector<Eigen::Vector3d> spin_;   // dt skw(L) as (w_xy, w_yz, w_xz)
  std::vector<int> cell_of_;            // cell of each particle at the start of the step
  std::vector<double> cell_volume_, cell_dilation_;
  std::vector<std::vector<int>> material_particles_;
  bool material_lists_valid_ = false;
  mutable std::vector<int> index_of_id_;  // rebuilt on demand after a sort
  ScatterSchedule schedule_;
  int slab_axis_ = Dim - 1;  // the axis with the most cells: the most slabs to share among threads

  std::vector<std::pair<const char*, double>> stage_times_;
  void lap(const char* stage, double& since);

  double time_ = 0.0;
  double dt_ = 0.0;
  double first_dt_ = 0.0;
  long steps_ = 0;
  double mass_threshold_ = 0.0;
};

extern template class Model<2>;
extern template class Model<3>;

}  // namespace seismpm
