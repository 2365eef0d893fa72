#include "edge_boundary.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "error.hpp"
#include "model.hpp"

namespace seismpm {

BoundaryKind parse_boundary_kind(std::string_view name) {
  if (name == "absorbing") return BoundaryKind::Absorbing;
  if (name == "compliant") return BoundaryKind::Compliant;
  if (name == "free_field") return BoundaryKind::FreeField;
  throw InputError("kind must be absorbing|compliant|free_field, got '" + std::string(name) + "'");
}

std::string_view boundary_kind_name(BoundaryKind kind) {
  switch (kind) {
    case BoundaryKind::Absorbing:
      return "absorbing";
    case BoundaryKind::Compliant:
      return "compliant";
    case BoundaryKind::FreeField:
      return "free_field";
  }
  return "?";
}

template <int Dim>
EdgeBoundary<Dim>::EdgeBoundary(const Grid<Dim>& grid, const BoundarySettings<Dim>& s) : settings_(s) {
  const int a = axis();
  if (a >= Dim) throw InputError("boundary: the side does not exist in " + std::to_string(Dim) + "D");
  constexpr int V = Dim - 1;
  if (s.kind == BoundaryKind::FreeField && a == V)
    throw InputError("boundary: a free_field edge is a lateral side (left|right" +
                     std::string(Dim == 3 ? "|bottom|top" : "") + "); the base is compliant or absorbing");
  for (double v : {s.density, s.vs, s.vp})
    if (!(v >= 0.0 && std::isfinite(v))) throw InputError("boundary: density, vs and vp must be >= 0");
  const bool given = s.density > 0.0 || s.vs > 0.0 || s.vp > 0.0;
  if ((given || s.kind == BoundaryKind::Compliant) && !(s.density > 0.0 && s.vs > 0.0 && s.vp > 0.0))
    throw InputError(s.kind == BoundaryKind::Compliant
                         ? "boundary: a compliant edge needs the half-space below: density, vs and vp > 0"
                         : "boundary: give density, vs and vp together (or none: the material next to the edge)");
  if (given && !(s.vp > s.vs)) throw InputError("boundary: vp must exceed vs");
  if (given && !std::isfinite(s.density * s.vp))
    throw InputError("boundary: the impedance density * vp overflows; give SI units (kg/m3, m/s)");
  if (s.kind != BoundaryKind::Compliant)
    for (const auto& h : s.input)
      if (h) throw InputError("boundary: only a compliant edge takes an input motion");
  const bool low = static_cast<int>(s.side) % 2 == 0;
  const int g = grid.ghost();
  const int edge = low ? g : grid.cells(a) - g;
  for (int node = 0; node < grid.node_count(); ++node) {
    const auto c = grid.node_coords(node);
    if (low ? c[a] <= g : c[a] >= grid.cells(a) - g) held_nodes_.push_back(node);
    if (c[a] != edge) continue;
    bool inside = true;
    for (int d = 0; d < Dim; ++d)
      if (d != a) inside = inside && c[d] >= g && c[d] <= grid.cells(d) - g;
    if (!inside) continue;
    edge_nodes_.push_back(node);
    for (int layer = 1; layer <= g; ++layer) behind_.push_back(node + (low ? -layer : layer) * grid.stride(a));
  }
  reaction_.assign(held_nodes_.size(), Vec<Dim>::Zero());
}

template <int Dim>
unsigned EdgeBoundary<Dim>::held_dofs() const {
  // The base holds every direction (it carries the ground's weight and its static shear); a side only
  // its normal, as rollers do.
  if (axis() == Dim - 1) return (1u << Dim) - 1u;
  return 1u << axis();
}

template <int Dim>
void EdgeBoundary<Dim>::hold(Grid<Dim>& grid) {
  // A corner held already (by another edge or an m:fix) is that one's to carry: its reaction is not
  // recorded twice.
  own_.resize(held_nodes_.size());
  for (std::size_t k = 0; k < held_nodes_.size(); ++k)
    own_[k] = static_cast<unsigned char>(held_dofs() & ~grid.fixity(held_nodes_[k]));
  grid.fix(settings_.side, held_dofs());
  holding_ = true;
}

template <int Dim>
void EdgeBoundary<Dim>::release(Grid<Dim>& grid) {
  if (!holding_) return;
  grid.release(settings_.side, held_dofs());
  holding_ = false;
}

// The input velocity at t, refused when not finite (a record or a function gone wrong would otherwise
// show up as particles with a NaN state, far from its cause).
template <int Dim>
double EdgeBoundary<Dim>::input_at(int axis, double t) const {
  if (!settings_.input[axis]) return 0.0;
  const double v = settings_.input[axis]->at(t);
  if (!std::isfinite(v))
    throw InputError("boundary on the " + std::string(side_name(settings_.side)) + " edge: its input velocity " +
                     "xyz"[axis] + " is " + std::to_string(v) + " at t = " + std::to_string(t) + " s");
  return v;
}

template <int Dim>
bool EdgeBoundary<Dim>::moves_frame() const {
  if (settings_.kind != BoundaryKind::Compliant || !settings_.moving_frame) return false;
  for (const auto& h : settings_.input)
    if (h) return true;
  return false;
}

template <int Dim>
void EdgeBoundary<Dim>::before_step(Model<Dim>& model, const StepContext& c) {
  if (!moves_frame()) return;
  Vec<Dim> a = Vec<Dim>::Zero();
  if (!holding_)
    for (int d = 0; d < Dim; ++d) {
      const double v = input_at(d, c.phase_time + c.dt);
      a[d] = (v - frame_velocity_[d]) / c.dt;  // from the frame's own velocity: it starts at rest
      frame_velocity_[d] = v;
    }
  model.set_frame_acceleration(a);
}

template <int Dim>
ColumnBase<Dim> EdgeBoundary<Dim>::column_base(const Model<Dim>& model) const {
  ColumnBase<Dim> base;
  if (column_base_) {
    const BoundarySettings<Dim>& b = column_base_->settings();
    base.kind = ColumnBase<Dim>::Kind::Dashpot;
    if (b.density > 0.0) {
      base.rho_vs = b.density * b.vs;
      base.rho_vp = b.density * b.vp;
    } else if (!column_base_->rho_vs_.empty()) {  // an absorbing base: the impedance next to it
      base.rho_vs = column_base_->rho_vs_.front();
      base.rho_vp = column_base_->rho_vp_.front();
    }
    if (b.kind == BoundaryKind::Compliant) base.input = b.input, base.moving_frame = column_base_->moves_frame();
    return base;
  }
  if (model.grid().held_on(static_cast<Side>(2 * (Dim - 1))) != 0) base.kind = ColumnBase<Dim>::Kind::Fixed;
  return base;
}

template <int Dim>
void EdgeBoundary<Dim>::prepare(const Model<Dim>& model) {
  const Grid<Dim>& G = model.grid();
  const Particles<Dim>& P = model.particles();
  const int a = axis(), g = G.ghost();
  const double h = G.cell();
  const bool low = static_cast<int>(settings_.side) % 2 == 0;
  const double edge = low ? G.domain_lower()[a] : G.domain_upper()[a];
  // Edge nodes by their coordinates along the other axes.
  auto edge_index = [&](const std::array<int, Dim>& c) {
    int k = 0, scale = 1;
    for (int d = 0; d < Dim; ++d) {
      if (d == a) continue;
      const int n = G.cells(d) - 2 * g + 1;
      if (c[d] < g || c[d] > G.cells(d) - g) return -1;
      k += (c[d] - g) * scale;
      scale *= n;
    }
    return k;
  };
  const std::size_t n_edge = edge_nodes_.size();
  area_.assign(n_edge, 0.0);
  std::vector<double> nearest(n_edge, std::numeric_limits<double>::infinity());
  std::vector<int> material(n_edge, -1);
  // The area a node stands for: the particles of the first cell layer, V/h each, shared by the edge's
  // linear hat functions (a full layer gives h^(Dim-1) per node, half at an end).
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (model.bodies()[P.body[p]].rigid) continue;
    const double depth = low ? P.x[p][a] - edge : edge - P.x[p][a];
    if (depth >= h) continue;
    std::array<int, Dim> c0{};
    for (int d = 0; d < Dim; ++d) c0[d] = static_cast<int>(std::floor((P.x[p][d] - G.origin()[d]) / h));
    for (int corner = 0; corner < (1 << (Dim - 1)); ++corner) {
      std::array<int, Dim> c = c0;
      double N = 1.0, dist2 = depth * depth;
      int bit = 0;
      for (int d = 0; d < Dim; ++d) {
        if (d == a) continue;
        c[d] += (corner >> bit++) & 1;
        const double offset = P.x[p][d] - (G.origin()[d] + c[d] * h);
        N *= std::max(0.0, 1.0 - std::abs(offset) / h);
        dist2 += offset * offset;
      }
      const int k = edge_index(c);
      if (k < 0 || !(N > 0.0)) continue;
      area_[k] += P.volume[p] / h * N;
      if (dist2 < nearest[k]) nearest[k] = dist2, material[k] = P.material[p];
    }
  }
  rho_vs_.assign(n_edge, 0.0);
  rho_vp_.assign(n_edge, 0.0);
  for (std::size_t k = 0; k < n_edge; ++k) {
    if (settings_.density > 0.0) {
      rho_vs_[k] = settings_.density * settings_.vs;
      rho_vp_[k] = settings_.density * settings_.vp;
    } else if (material[k] >= 0) {  // rho c = sqrt(rho M): the impedance of the soil next to the node
      const Material& m = model.material(material[k]);
      rho_vs_[k] = std::sqrt(m.density() * m.shear_modulus());
      rho_vp_[k] = std::sqrt(m.density() * m.p_wave_modulus());
    }
  }
  column_node_.assign(n_edge, -1);
  if (settings_.kind == BoundaryKind::FreeField) {
    constexpr int V = Dim - 1;
    const int elements = G.cells(V) - 2 * g;
    std::vector<ColumnLayer> layers(elements);
    std::vector<double> closest(elements, std::numeric_limits<double>::infinity());
    const double bottom = G.domain_lower()[V];
    for (std::size_t p = 0; p < P.size(); ++p) {
      if (model.bodies()[P.body[p]].rigid) continue;
      const double depth = low ? P.x[p][a] - edge : edge - P.x[p][a];
      const int e = static_cast<int>(std::floor((P.x[p][V] - bottom) / h));
      if (depth >= h || e < 0 || e >= elements || !(depth < closest[e])) continue;
      closest[e] = depth;
      const Material& m = model.material(P.material[p]);
      ColumnLayer& L = layers[e];
      L.density = m.density();
      L.shear_modulus = m.shear_modulus();
      L.p_wave_modulus = m.p_wave_modulus();
      L.lame = m.p_wave_modulus() - 2.0 * m.shear_modulus();
      L.rayleigh_alpha = m.rayleigh().alpha;  // the column damps as the soil beside it does
      L.rayleigh_beta = m.rayleigh().beta;
    }
    while (!layers.empty() && !(layers.back().density > 0.0)) layers.pop_back();
    if (layers.empty())
      throw InputError("boundary: the free_field edge has no soil beside it (side " +
                       std::string(side_name(settings_.side)) + ")");
    column_.emplace(std::move(layers), h, column_base(model));
    for (std::size_t k = 0; k < n_edge; ++k) {
      const int j = G.node_coords(edge_nodes_[k])[V] - g;
      if (j >= 0 && j < column_->node_count()) column_node_[k] = j;
    }
  }
  prepared_ = true;
}

template <int Dim>
void EdgeBoundary<Dim>::edge_forces(Model<Dim>& model, const StepContext& c) {
  Grid<Dim>& G = model.grid();
  if (holding_) {  // the support's reaction on what this edge holds (local damping leaves it alone)
    for (std::size_t k = 0; k < held_nodes_.size(); ++k)
      for (int d = 0; d < Dim; ++d) reaction_[k][d] = (own_[k] & (1u << d)) ? -G.force[held_nodes_[k]][d] : 0.0;
    return;
  }
  if (!prepared_) prepare(model);
  last_force_.setZero();
  for (std::size_t k = 0; k < held_nodes_.size(); ++k) {
    G.force[held_nodes_[k]] += reaction_[k];
    last_force_ += reaction_[k];
  }
  const double dt = c.dt, t_end = c.phase_time + c.dt, eps = model.mass_threshold();
  if (column_) column_->advance(dt, t_end, model.frame_acceleration());
  const int a = axis();
  Vec<Dim> input = Vec<Dim>::Zero();
  if (settings_.kind == BoundaryKind::Compliant && !moves_frame())
    for (int d = 0; d < Dim; ++d) input[d] = input_at(d, t_end);
  const int g = G.ghost();
  for (std::size_t k = 0; k < edge_nodes_.size(); ++k) {
    const int i = edge_nodes_[k];
    // The edge node with the ghost nodes behind it, as one: their mass, momentum and force.
    double m = G.mass[i];
    Vec<Dim> p = G.momentum[i], f = G.force[i];
    for (int l = 0; l < g; ++l) {
      const int j = behind_[k * g + l];
      m += G.mass[j], p += G.momentum[j], f += G.force[j];
    }
    const double A = area_[k];
    if (!(m > eps)) continue;
    if (A > 0.0) {
      Vec<Dim> target = input;
      if (column_node_[k] >= 0 && column_->has_soil(column_node_[k])) {
        const int j = column_node_[k];
        target = column_->velocity(j);
        const Vec<Dim> traction = outward() * A * column_->face_stress(j, a);  // t = sigma n of the ground beyond
        f += traction;
        last_force_ += traction;
      }
      for (int d = 0; d < Dim; ++d) {
        // Implicit dashpot: the force that ends the step at (p + dt (f + C target)) / (m + dt C).
        const double C = (d == a ? rho_vp_[k] : rho_vs_[k]) * A;
        const double df = C * (m * target[d] - p[d] - dt * f[d]) / (m + dt * C);
        f[d] += df;
        last_force_[d] += df;
      }
    }
    // Each node gets the force that brings it to the common end velocity.
    const Vec<Dim> v = (p + dt * f) / m;
    auto drive = [&](int node) {
      if (G.mass[node] > eps) G.force[node] = (G.mass[node] * v - G.momentum[node]) / dt;
    };
    drive(i);
    for (int l = 0; l < g; ++l) drive(behind_[k * g + l]);
  }
}

// The MUSL re-map makes a nodal velocity from the particles' new momentum for the strain increment. On a
// held node it is held again; on an edge node the dashpot's end velocity is what the edge moved at, so it
// is kept: a re-mapped velocity there, free of the dashpot, gave the strains a motion the positions did
// not make, and under FLIP that fed a mode inside the cells next to a compliant base that grew 2.2x
// per second (a 10 m column on 0.5 m cells at 10 Hz; USL, or a PIC share of 1 %, had none).
template <int Dim>
void EdgeBoundary<Dim>::nodal_velocities(Model<Dim>& model, const StepContext&, VelocityStage stage) {
  if (holding_) return;
  Grid<Dim>& G = model.grid();
  const int g = G.ghost();
  const double eps = model.mass_threshold();
  const std::size_t n = edge_nodes_.size();
  if (stage == VelocityStage::Updated) {
    updated_.resize(n);
    for (std::size_t k = 0; k < n; ++k) updated_[k] = G.velocity[edge_nodes_[k]];
    return;
  }
  if (updated_.size() != n) return;  // no updated stage seen (a restart between the two)
  for (std::size_t k = 0; k < n; ++k) {
    const int i = edge_nodes_[k];
    if (G.mass[i] > eps) G.velocity[i] = updated_[k];
    for (int l = 0; l < g; ++l)
      if (G.mass[behind_[k * g + l]] > eps) G.velocity[behind_[k * g + l]] = updated_[k];
  }
}

template <int Dim>
Vec<Dim> EdgeBoundary<Dim>::reaction_magnitude() const {
  Vec<Dim> sum = Vec<Dim>::Zero();
  for (const auto& r : reaction_) sum += r.cwiseAbs();
  return sum;
}

template <int Dim>
void EdgeBoundary<Dim>::correct_reaction(const Vec<Dim>& delta, const Vec<Dim>& magnitude) {
  for (auto& r : reaction_)
    for (int d = 0; d < Dim; ++d)
      if (magnitude[d] > 0.0) r[d] += delta[d] * std::abs(r[d]) / magnitude[d];
}

template <int Dim>
void balance_recorded_reactions(const Model<Dim>& model, const std::vector<std::shared_ptr<EdgeBoundary<Dim>>>& edges) {
  if (edges.empty()) return;
  for (const Body& b : model.bodies())
    if (b.rigid) return;
  const Particles<Dim>& P = model.particles();
  Vec<Dim> weight = Vec<Dim>::Zero();
  for (std::size_t p = 0; p < P.size(); ++p) weight += P.mass[p] * model.settings().gravity;
  // What every held component carried in the last step (the edges' and m:fix's alike).
  const Grid<Dim>& G = model.grid();
  Vec<Dim> carried = Vec<Dim>::Zero();
  for (const int node : G.fixed_nodes())
    for (int d = 0; d < Dim; ++d)
      if (G.fixity(node) & (1u << d)) carried[d] -= G.force[node][d];
  Vec<Dim> magnitude = Vec<Dim>::Zero();
  for (const auto& e : edges) magnitude += e->reaction_magnitude();
  const Vec<Dim> missing = -weight - carried;
  for (const auto& e : edges) e->correct_reaction(missing, magnitude);
}

template void balance_recorded_reactions<2>(const Model<2>&, const std::vector<std::shared_ptr<EdgeBoundary<2>>>&);
template void balance_recorded_reactions<3>(const Model<3>&, const std::vector<std::shared_ptr<EdgeBoundary<3>>>&);

template class EdgeBoundary<2>;
template class EdgeBoundary<3>;

}  // namespace seismpm
