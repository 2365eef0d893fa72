// What keeps the centre of a deformable particle out of a rigid body it is in contact with, wherever
// the body's faces lie on the grid.
//
// Contact acts at nodes, and a centre moves with sum N_i v_i over its stencil. Where the nodal normals
// are clean (a face on a grid plane, away from corners) that keeps centres out (rigid_face_mirror.hpp
// makes it exact for uGIMP). Where they are not, nothing did: a box on a shaking table moves its walls
// up to a cell off the grid planes, and at the box's inner corner, where the rough base meets a smooth
// wall one cell thick, the node inside the wall's foot gets from base, wall and soil three normals
// tilted by about 45 degrees, none of them the wall's inner face. The soil at that node slid up and
// into the wall along the tilted smooth normal, and the corner particle, reading it with a weight of
// 0.02-0.1, crept through the wall and out of the grid (0.375 cm shaking-table run, at 13.9 s).
//
// The rule is geometric and needs no normal: a rigid body's material is the union of its particles'
// domains (a box of half-width l_p cells about each), and a deformable centre that was outside such a
// box at the start of a step ends the step on its face instead of inside it: the displacement's
// component along the axis it entered through stops at the face (the axis with the least depth when
// it entered through an edge). Only the position and displacement change; the particle keeps its
// velocity, which the nodal contact set. A centre already inside at the start (filled into a rigid
// body, or glued to it) is left alone, as are glued pairs.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include <omp.h>

#include "contact_rules.hpp"
#include "core/cell_index.hpp"
#include "core/grid.hpp"
#include "core/particles.hpp"

namespace seismpm {

template <int Dim>
class RigidExclusion {
 public:
  // The domains, at the end of the step, of the rigid particles (is_rigid(body)) of fields that a
  // deformable field is in contact with; each particle moves by dt * v this step. field_of(body)
  // gives a body's contact field.
  template <class IsRigid, class FieldOf>
  void build(const Particles<Dim>& particles, const Grid<Dim>& grid, const ContactRules& rules, double dt,
             IsRigid&& is_rigid, FieldOf&& field_of) {
    boxes_.clear();
    keys_.clear();
    rules_ = &rules;
    for (int d = 0; d < Dim; ++d) cells_[d] = grid.cells(d);
    const CellIndex<Dim> cells(grid);
    touching_.resize(rules.fields());
    for (int q = 0; q < rules.fields(); ++q) touching_[q] = in_contact(rules, q);
    const auto& P = particles;
    // The rigid particles in contact, in particle order: each thread lists those of its block of a
    // static schedule, and the lists join in thread order. Scanned serially, the particles of a
    // 25,000-particle slope kept the other thread waiting for 1 % of the run.
    const int n = static_cast<int>(P.size()), threads = omp_get_max_threads();
    found_.resize(threads);
    for (auto& list : found_) list.clear();
#pragma omp parallel num_threads(threads)
    {
      auto& mine = found_[omp_get_thread_num()];
#pragma omp for schedule(static)
      for (int p = 0; p < n; ++p) {
        const int body = P.body[p];
        if (is_rigid(body) && touching_[field_of(body)]) mine.push_back(p);
      }
    }
    for (const auto& list : found_)
      for (const int p : list) {
        Box b;
        b.field = field_of(P.body[p]);
        b.id = P.id[p];
        b.shift = dt * P.v[p];
        b.centre = P.x[p] + b.shift;
        b.half = P.half_width[p] * grid.cell();
        keys_.emplace_back(cells.of(b.centre), static_cast<int>(boxes_.size()));
        boxes_.push_back(b);
      }
    std::sort(keys_.begin(), keys_.end());  // by cell, then by particle order: a fixed visiting order
    cell_index_.emplace(cells);
    mark_near();
    mark_seams(grid.cell(), P);
  }
  bool any() const { return !boxes_.empty(); }

  // Shortens dx, the step's displacement of a particle of deformable field `field` at x, so that its
  // centre does not enter a rigid particle's domain it was outside of.
  void keep_out(int field, const Vec<Dim>& x, Vec<Dim>& dx) const {
    Vec<Dim> xn = x + dx;
    if (!near_[cell_index_->of(xn)]) return;
    bool moved = false;
    for_each_box_near(xn, [&](const Box& b) {
      if (!rules_->glued(field, b.field)) moved |= clip(b, x, xn);
    });
    if (moved) dx = xn - x;
  }

 private:
  struct Box {
    Vec<Dim> centre;  // at the end of the step
    Vec<Dim> shift;   // this step's displacement
    double half;      // m
    int field;
    int id;             // the rigid particle's
    unsigned open = 0;  // bit 2d + side: the face on that side of axis d is the body's surface
  };
  // A centre this close to a face (relative to the half-width) counts as on it: the clipped position,
  // re-read against the moved box, neither counts as inside nor as having entered.
  static constexpr double kOnFace = 1e-12;

  static bool in_contact(const ContactRules& rules, int q) {
    for (int f = 0; f < rules.fields(); ++f)
      if (!rules.rigid(f) && !rules.glued(f, q)) return true;
    return false;
  }
  // g(cell) for the cells next to cell coordinates c (c's own included), clipped to the grid.
  template <class G>
  void for_each_neighbour_cell(const std::array<int, Dim>& c, G&& g) const {
    std::array<int, Dim> lo, n;
    int count = 1;
    for (int d = 0; d < Dim; ++d) {
      lo[d] = std::max(c[d] - 1, 0);
      n[d] = std::min(c[d] + 1, cells_[d] - 1) - lo[d] + 1;
      count *= n[d];
    }
    for (int k = 0; k < count; ++k) {
      std::array<int, Dim> cc;
      int rest = k;
      for (int d = 0; d < Dim; ++d) cc[d] = lo[d] + rest % n[d], rest /= n[d];
      g(cell_index_->of_coords(cc));
    }
  }
  // f(box) for every box whose domain may hold x. A box's centre lies within half a cell of any point
  // inside it, so its cell is a neighbour of the point's.
  template <class F>
  void for_each_box_near(const Vec<Dim>& x, F&& f) const {
    for_each_neighbour_cell(cell_index_->coords_of(x), [&](int cell) {
      for (int k = first_key_[cell]; k >= 0 && k < static_cast<int>(keys_.size()) && keys_[k].first == cell; ++k)
        f(boxes_[keys_[k].second]);
    });
  }
  // near_[cell]: some box's centre lies in a neighbour of the cell, so a point in it may be inside a
  // box. Nearly every particle of a step is far from any rigid body, and one look-up settles it.
  // first_key_[cell]: the cell's first key, -1 for a cell that holds no box's centre.
  void mark_near() {
    for (int cell : near_marked_) near_[cell] = 0, first_key_[cell] = -1;
    near_marked_.clear();
    int total = 1;
    for (int d = 0; d < Dim; ++d) total *= cells_[d];
    if (static_cast<int>(near_.size()) != total) near_.assign(total, 0), first_key_.assign(total, -1);
    for (std::size_t k = 0; k < keys_.size(); ++k) {
      if (k > 0 && keys_[k].first == keys_[k - 1].first) continue;
      first_key_[keys_[k].first] = static_cast<int>(k);
      for_each_neighbour_cell(cell_index_->coords(keys_[k].first), [&](int cell) {
        if (!near_[cell]) near_[cell] = 1, near_marked_.push_back(cell);
      });
    }
  }
  // Moves xn (from x) back onto the face of box b it entered by, if it ended inside b (a seam with a
  // neighbour of the same body counts as inside) having come in through the body's surface. The face is
  // the last one the path crossed, as for a ray entering a box. True if xn changed.
  static bool clip(const Box& b, const Vec<Dim>& x, Vec<Dim>& xn) {
    const Vec<Dim> rn = xn - b.centre;
    for (int d = 0; d < Dim; ++d)
      if (!(std::abs(rn[d]) <= b.half * (1.0 + kOnFace))) return false;
    const Vec<Dim> ro = x - (b.centre - b.shift);
    int axis = -1;
    double last = -1.0;
    for (int d = 0; d < Dim; ++d) {
      const double o = std::abs(ro[d]), n = std::abs(rn[d]);
      if (!(o >= b.half * (1.0 - kOnFace)) || !(n < o)) continue;  // inside its slab at the start, or not going in
      if (!(b.open >> (2 * d + (ro[d] > 0.0)) & 1u)) continue;     // a seam
      const double entry = (o - b.half) / (o - n);                 // when in the step it crossed the face's plane
      if (entry > last) axis = d, last = entry;
    }
    if (axis < 0) return false;
    const double face = b.centre[axis] + (ro[axis] > 0.0 ? b.half : -b.half);
    if (xn[axis] == face) return false;
    xn[axis] = face;
    return true;
  }

  // A face shared with a box of the same body is a seam inside it, not a face a centre can enter by.
  // A rigid body moves as a whole, so which faces are seams never changes for the same particles: the
  // search runs again only when the set of rigid particles did.
  void mark_seams(double cell, const Particles<Dim>& P) {
    bool known = boxes_.size() == seams_known_;
    for (const Box& b : boxes_)
      known = known && b.id < static_cast<int>(open_of_id_.size()) && open_of_id_[b.id] & kKnown;
    if (known) {
      for (Box& b : boxes_) b.open = open_of_id_[b.id] & ~kKnown;
      return;
    }
    std::fill(open_of_id_.begin(), open_of_id_.end(), 0u);
    if (!P.id.empty())
      open_of_id_.resize(
          std::max(open_of_id_.size(), static_cast<std::size_t>(*std::max_element(P.id.begin(), P.id.end())) + 1), 0u);
    const double tol = 1e-9 * cell;
    for (Box& b : boxes_) {
      b.open = 0;
      for (int d = 0; d < Dim; ++d)
        for (int side = 0; side < 2; ++side) {
          Vec<Dim> next = b.centre;
          next[d] += (side ? 2.0 : -2.0) * b.half;
          bool seam = false;
          for_each_box_near(next, [&](const Box& o) {
            seam |= o.field == b.field && std::abs(o.half - b.half) <= tol &&
                    (o.centre - next).cwiseAbs().maxCoeff() <= tol;
          });
          if (!seam) b.open |= 1u << (2 * d + side);
        }
      open_of_id_[b.id] = b.open | kKnown;
    }
    seams_known_ = boxes_.size();
  }

  static constexpr unsigned kKnown = 1u << 31;
  std::vector<Box> boxes_;
  std::vector<unsigned> open_of_id_;  // per particle id: the open faces, with kKnown once searched
  std::size_t seams_known_ = 0;
  std::vector<std::pair<int, int>> keys_;  // (cell of the box's centre, box)
  std::optional<CellIndex<Dim>> cell_index_;
  std::vector<unsigned char> near_;      // per cell (mark_near)
  std::vector<int> first_key_;           // per cell (mark_near)
  std::vector<int> near_marked_;         // the cells near_ marks (every cell with a first key among them)
  std::vector<char> touching_;           // per field: some deformable field is in contact with it
  std::vector<std::vector<int>> found_;  // per thread: build's rigid particles in contact
  std::array<int, Dim> cells_{};
  const ContactRules* rules_ = nullptr;
};

}  // namespace seismpm
