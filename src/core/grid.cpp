#include "grid.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "error.hpp"

namespace seismpm {

template <int Dim>
Grid<Dim>::Grid(const Vec<Dim>& lower, const Vec<Dim>& upper, double cell, int ghost)
    : origin_(lower.array() - ghost * cell), h_(cell), ghost_(ghost) {
  if (!(cell > 0.0) || !std::isfinite(cell)) throw InputError("grid: cell size must be > 0");
  if (ghost < 0) throw InputError("grid: ghost layers must be >= 0");
  long total = 1;
  for (int d = 0; d < Dim; ++d) {
    const double extent = upper[d] - lower[d];
    if (!(extent > 0.0) || !std::isfinite(extent))
      throw InputError("grid: empty domain along axis " + std::to_string(d) + " (upper must exceed lower)");
    // Round up to whole cells, forgiving round-off in extent / h.
    const double n = std::ceil(extent / cell - 1e-9);
    if (n > 1e7) throw InputError("grid: too many cells along axis " + std::to_string(d));
    cells_[d] = std::max(1, static_cast<int>(n)) + 2 * ghost;
    stride_[d] = static_cast<int>(total);
    total *= cells_[d] + 1;
    if (total > 100'000'000L) throw InputError("grid: over 100 million nodes; use a larger cell");
  }
  mass.assign(total, 0.0);
  momentum.assign(total, Vec<Dim>::Zero());
  force.assign(total, Vec<Dim>::Zero());
  velocity.assign(total, Vec<Dim>::Zero());
  acceleration.assign(total, Vec<Dim>::Zero());
  fixity_.assign(total, 0);
}

template <int Dim>
Vec<Dim> Grid<Dim>::upper() const {
  Vec<Dim> u = origin_;
  for (int d = 0; d < Dim; ++d) u[d] += cells_[d] * h_;
  return u;
}

template <int Dim>
int Grid<Dim>::cell_count() const {
  int n = 1;
  for (int d = 0; d < Dim; ++d) n *= cells_[d];
  return n;
}

template <int Dim>
std::array<int, Dim> Grid<Dim>::node_coords(int node) const {
  std::array<int, Dim> c{};
  for (int d = 0; d < Dim; ++d) {
    c[d] = node % nodes(d);
    node /= nodes(d);
  }
  return c;
}

template <int Dim>
Vec<Dim> Grid<Dim>::node_position(int node) const {
  const auto c = node_coords(node);
  Vec<Dim> x = origin_;
  for (int d = 0; d < Dim; ++d) x[d] += c[d] * h_;
  return x;
}

template <int Dim>
void Grid<Dim>::reset_nodes(int first, int end) {
  for (int i = first; i < end; ++i) {
    mass[i] = 0.0;
    momentum[i].setZero();
    force[i].setZero();
    velocity[i].setZero();
    acceleration[i].setZero();
  }
}

template <int Dim>
void Grid<Dim>::reset(bool kinematics) {
  const int n = node_count();
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    mass[i] = 0.0;
    momentum[i].setZero();
    force[i].setZero();
    if (kinematics) {
      velocity[i].setZero();
      acceleration[i].setZero();
    }
  }
}

template <int Dim>
void Grid<Dim>::fix(Side side, unsigned dof_mask) {
  const int axis = static_cast<int>(side) / 2;
  if (axis >= Dim) throw InputError("grid: side does not exist in " + std::to_string(Dim) + "D");
  if (dof_mask == 0 || dof_mask >= (1u << Dim)) throw InputError("grid: fixity names a missing direction");
  const bool low = static_cast<int>(side) % 2 == 0;
  for (int node = 0; node < node_count(); ++node) {
    const int c = node_coords(node)[axis];
    if (low ? c > ghost_ : c < cells_[axis] - ghost_) continue;
    if (fixity_[node] == 0) fixed_nodes_.push_back(node);
    fixity_[node] |= static_cast<unsigned char>(dof_mask);
  }
  std::sort(fixed_nodes_.begin(), fixed_nodes_.end());
}

template <int Dim>
unsigned Grid<Dim>::held_on(Side side) const {
  const int axis = static_cast<int>(side) / 2;
  if (axis >= Dim) return 0;
  int node = 0;
  for (int d = 0; d < Dim; ++d) {
    int c = nodes(d) / 2;  // away from the other edges (a domain spans at least 2 cells)
    if (d == axis) c = static_cast<int>(side) % 2 == 0 ? ghost_ : cells_[axis] - ghost_;
    node += c * stride_[d];
  }
  return fixity_[node];
}

template <int Dim>
void Grid<Dim>::release(Side side, unsigned dof_mask) {
  std::array<unsigned, 2 * Dim> held{};
  for (int s = 0; s < 2 * Dim; ++s) held[s] = held_on(static_cast<Side>(s));
  held[static_cast<int>(side)] &= ~dof_mask;
  std::fill(fixity_.begin(), fixity_.end(), 0);
  fixed_nodes_.clear();
  for (int s = 0; s < 2 * Dim; ++s)
    if (held[s]) fix(static_cast<Side>(s), held[s]);
}

template <int Dim>
void Grid<Dim>::apply_fixities(std::vector<Vec<Dim>>& field) const {
  for (const int node : fixed_nodes_) {
    const unsigned f = fixity_[node];
    for (int d = 0; d < Dim; ++d)
      if (f & (1u << d)) field[node][d] = 0.0;
  }
}

template <int Dim>
void Grid<Dim>::hold_updated_velocities(double dt) {
  for (const int node : fixed_nodes_) {
    const unsigned f = fixity_[node];
    for (int d = 0; d < Dim; ++d)
      if (f & (1u << d)) {
        acceleration[node][d] -= velocity[node][d] / dt;  // v^L = mv/m + dt a, so a - v^L/dt = -(mv/m)/dt
        velocity[node][d] = 0.0;
      }
  }
}

namespace {
constexpr std::string_view kSideNames[] = {"left", "right", "bottom", "top", "back", "front"};
}  // namespace

std::string_view side_name(Side side) { return kSideNames[static_cast<int>(side)]; }

Side parse_side(std::string_view name, int dim) {
  for (int i = 0; i < 2 * dim; ++i)
    if (name == kSideNames[i]) return static_cast<Side>(i);
  throw InputError("side must be one of left|right|bottom|top" + std::string(dim == 3 ? "|back|front" : "") +
                   ", got '" + std::string(name) + "'");
}

unsigned parse_dof(std::string_view name, int dim) {
  unsigned mask = 0;
  for (char c : name) {
    const int axis = c - 'x';
    if (axis < 0 || axis >= dim || (mask & (1u << axis)))
      throw InputError("dof must be " + std::string(dim == 3 ? "x|y|z|xy|xz|yz|xyz" : "x|y|xy") + ", got '" +
                       std::string(name) + "'");
    mask |= 1u << axis;
  }
  if (mask == 0) throw InputError("dof must not be empty");
  return mask;
}

template class Grid<2>;
template class Grid<3>;

}  // namespace seismpm
