#include "model.hpp"

#include <algorithm>
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
}

// ---------------------------------------------------------------- building

template <int Dim>
int Model<Dim>::add_material(std::shared_ptr<const Material> material) {
  if (!material) throw InputError("model: null material");
  if (materials_.size() >= 65535) throw InputError("model: too many materials");
  p_wave_modulus_.push_back(material->p_wave_modulus());
  materials_.push_back(std::move(material));
  material_lists_valid_ = false;
  return static_cast<int>(materials_.size()) - 1;
}

template <int Dim>
int Model<Dim>::add_body(const std::string& name, int ppc, bool rigid) {
  if (ppc < 1 || ppc > 16) throw InputError("body '" + name + "': ppc must be in [1, 16]");
  if (bodies_.size() >= 65535) throw InputError("model: too many bodies");
  bodies_.push_back(Body{name, ppc, rigid});
  return static_cast<int>(bodies_.size()) - 1;
}

template <int Dim>
std::size_t Model<Dim>::fill(int body, int material, const Vec<Dim>& lo, const Vec<Dim>& hi,
                             const std::function<bool(const Vec<Dim>&)>& inside) {
  if (body < 0 || body >= static_cast<int>(bodies_.size())) throw InputError("fill: unknown body");
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
        particles_.add(x, mass, volume, half_width, body, material);
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
  if (added) {
    mass_threshold_ = std::max(mass_threshold_, 1e-12 * mass);
    material_lists_valid_ = false;
  }
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
      const double c = std::sqrt(p_wave_modulus_[particles_.material[p]] / particles_.density(p)) + particles_.v[p].norm();
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

// One explicit MPM step, in the order of the method (PHYSICS.md, "One explicit step").
template <int Dim>
template <class Shape>
void Model<Dim>::step_with(double dt) {
  double t = settings_.profile ? omp_get_wtime() : 0.0;
  dt_ = dt;
  for (auto& f : fixes_) f->before_step(*this);
  grid_.reset();
  lap("reset", t);
  compute_stencils<Shape>();        // shape functions at the start-of-step positions
  lap("stencils", t);
  particles_to_grid<Shape>();       // nodal mass, momentum, internal + external force
  lap("particles to grid", t);
  for (auto& f : fixes_) f->nodal_forces(*this);  // e.g. local damping
  update_nodal_velocities();        // a = f/m, v^L = mv/m + dt a
  constrain_velocities(VelocityStage::Updated);
  lap("nodes", t);
  grid_to_particles<Shape>();       // FLIP/PIC velocity, position, displacement
  lap("grid to particles", t);
  if (settings_.scheme == Scheme::Musl) {
    remap_momentum<Shape>();        // nodal velocity from the updated particle momentum
    constrain_velocities(VelocityStage::Remapped);
  }
  lap("MUSL re-map", t);
  update_stress<Shape>();           // velocity gradient, objective rate, constitutive model, volume
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
    const double c = std::sqrt(p_wave_modulus_[particles_.material[p]] / particles_.density(p));
    max_speed = std::max(max_speed, c + particles_.v[p].norm());
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

template <int Dim>
template <class Shape>
void Model<Dim>::particles_to_grid() {
  const auto& st = stencils<Shape>();
  const Vec<Dim> g = settings_.gravity;
  auto& P = particles_;
  auto& G = grid_;
  schedule_.for_each([&](int p) {
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

template <int Dim>
void Model<Dim>::constrain_velocities(VelocityStage stage) {
  grid_.apply_fixities(grid_.velocity);
  if (stage == VelocityStage::Updated) grid_.apply_fixities(grid_.acceleration);
  for (auto& f : fixes_) f->nodal_velocities(*this, stage);
}

template <int Dim>
template <class Shape>
void Model<Dim>::grid_to_particles() {
  const auto& st = stencils<Shape>();
  const int n = static_cast<int>(particles_.size());
  const double dt = dt_, alpha = settings_.flip;
  auto& P = particles_;
  const auto& G = grid_;
#pragma omp parallel for schedule(static)
  for (int p = 0; p < n; ++p) {
    Vec<Dim> a = Vec<Dim>::Zero(), vl = Vec<Dim>::Zero();
    for_each_node(st[p], G, [&](int i, double N, const Vec<Dim>&) {
      a += N * G.acceleration[i];
      vl += N * G.velocity[i];
    });
    P.v[p] = alpha * (P.v[p] + dt * a) + (1.0 - alpha) * vl;
    P.x[p] += dt * vl;
    P.u[p] += dt * vl;
  }
}

template <int Dim>
template <class Shape>
void Model<Dim>::remap_momentum() {
  const auto& st = stencils<Shape>();
  auto& P = particles_;
  auto& G = grid_;
  const int nn = G.node_count();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < nn; ++i) G.momentum[i].setZero();
  schedule_.for_each([&](int p) {
    const Vec<Dim> mv = P.mass[p] * P.v[p];
    for_each_node(st[p], G, [&](int i, double N, const Vec<Dim>&) { G.momentum[i] += N * mv; });
  });
  const double eps = mass_threshold_;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < nn; ++i)
    G.velocity[i] = G.mass[i] > eps ? Vec<Dim>(G.momentum[i] / G.mass[i]) : Vec<Dim>::Zero();
}

template <int Dim>
template <class Shape>
void Model<Dim>::update_stress() {
  const auto& st = stencils<Shape>();
  const int n = static_cast<int>(particles_.size());
  const double dt = dt_;
  auto& P = particles_;
  const auto& G = grid_;
  strain_increment_.resize(n);
  spin_.resize(n);
#pragma omp parallel for schedule(static)
  for (int p = 0; p < n; ++p) {
    Mat<Dim> L = Mat<Dim>::Zero();  // velocity gradient, L_ab = dv_a / dx_b
    for_each_node(st[p], G, [&](int i, double, const Vec<Dim>& dN) { L.noalias() += G.velocity[i] * dN.transpose(); });
    const Mat<Dim> dL = dt * L;
    strain_increment_[p] = to_voigt(embed<Dim>(Mat<Dim>(0.5 * (dL + dL.transpose()))));
    const Mat3 w = embed<Dim>(Mat<Dim>(0.5 * (dL - dL.transpose())));
    spin_[p] = Eigen::Vector3d(w(0, 1), w(1, 2), w(0, 2));
  }
  const bool average = settings_.cell_volumetric_strain;
  if (average) accumulate_cell_dilation();
#pragma omp parallel for schedule(static)
  for (int p = 0; p < n; ++p) {
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
    P.volume[p] *= F.template topLeftCorner<Dim, Dim>().determinant();
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
  schedule_.for_each_in_own_cell([&](int p) {
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
  for (std::size_t p = 0; p < particles_.size(); ++p) e += 0.5 * particles_.mass[p] * particles_.v[p].squaredNorm();
  return e;
}

template <int Dim>
double Model<Dim>::strain_energy() const {
  double e = 0.0;
  for (std::size_t p = 0; p < particles_.size(); ++p) {
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
  for (std::size_t p = 0; p < particles_.size(); ++p) s += particles_.mass[p] * particles_.v[p];
  return s;
}

template class Model<2>;
template class Model<3>;

}  // namespace seismpm
