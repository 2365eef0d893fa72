// The step's grid loops over the nodes the particles reach only: the spans hold every node a stencil
// touches, and a step over them gives bit for bit what a step over the whole grid gives.
#include <catch2/catch.hpp>

#include <random>
#include <set>

#include "core/active_nodes.hpp"
#include "core/fix.hpp"
#include "core/local_damping.hpp"
#include "core/stencil.hpp"
#include "support/models.hpp"

using namespace seismpm;

namespace {

template <int Dim, class Shape>
void check_spans_cover_stencils() {
  const Grid<Dim> grid(Vec<Dim>::Zero(), Vec<Dim>::Constant(2.0), 0.1, 1);
  std::mt19937 rng(7);
  // Two clusters and a few particles on the domain's edges: gaps inside a row, clamping at the ends.
  std::uniform_real_distribution<double> near_low(0.1, 0.5), near_high(1.3, 1.6);
  std::vector<Vec<Dim>> x;
  for (int k = 0; k < 200; ++k) {
    Vec<Dim> p;
    for (int d = 0; d < Dim; ++d) p[d] = k % 2 ? near_low(rng) : near_high(rng);
    x.push_back(p);
  }
  x.push_back(grid.domain_lower());
  x.push_back(grid.domain_upper());
  ActiveNodes<Dim> active;
  constexpr int lo = Shape::kReachLo, hi = Shape::kReachHi;
  active.build(grid, CellIndex<Dim>(grid), x, lo, hi);
  std::vector<char> in(grid.node_count(), 0);
  active.for_each_range([&](int first, int end) {
    for (int i = first; i < end; ++i) in[i] = 1;
  });
  std::set<int> reached;
  for (const auto& p : x) {
    Stencil<Dim, Shape::K> st;
    REQUIRE(make_stencil<Shape>(grid, p, 0.25, st));
    for_each_node(st, grid, [&](int i, double, const Vec<Dim>&) { reached.insert(i); });
  }
  for (const int i : reached) {
    INFO("node " << i);
    CHECK(in[i]);
  }
  // Tight: the spans reach no further than the particles' reach, and skip most of this grid.
  CHECK(active.count() < grid.node_count() / 2);
  CHECK(active.count() >= static_cast<long>(reached.size()));
}

// A fix that does nothing: with it, the step walks the whole grid.
template <int Dim>
class NoFix : public Fix<Dim> {
 public:
  std::string_view name() const override { return "nothing"; }
};

}  // namespace

TEST_CASE("the active spans hold every node a stencil reaches", "[core][active]") {
  check_spans_cover_stencils<2, LinearShape>();
  check_spans_cover_stencils<2, GimpShape>();
  check_spans_cover_stencils<3, LinearShape>();
  check_spans_cover_stencils<3, GimpShape>();
}

TEST_CASE("a step over the active nodes equals a step over the whole grid", "[core][active]") {
  const auto shape = GENERATE(ShapeKind::Linear, ShapeKind::Gimp);
  const auto scheme = GENERATE(Scheme::Musl, Scheme::Usl);
  const bool damped = GENERATE(false, true);  // local damping writes only where there is mass: still limited
  CAPTURE(to_string(shape), scheme == Scheme::Musl, damped);
  auto make = [&] {
    ModelSettings<2> s;
    s.lower = Vec<2>::Zero();
    s.upper = Vec<2>::Constant(2.0);
    s.cell = 0.05;
    s.shape = shape;
    s.scheme = scheme;
    s.gravity = Vec<2>(0.0, -9.81);
    auto m = test::elastic_block<2>(s, Vec<2>(0.2, 0.3), Vec<2>(0.5, 0.6));
    for (auto& v : m->particles().v) v = Vec<2>(10.0, 5.0);  // across the grid: nodes fall empty behind it
    if (damped) m->add_fix(std::make_shared<LocalDamping<2>>(0.2));
    return m;
  };
  auto limited = make();
  auto whole = make();
  const auto fix = std::make_shared<NoFix<2>>();
  for (int s = 0; s < 200; ++s) {
    // Switch the reference between whole-grid steps and limited ones now and then.
    if (s == 60) whole->remove_fix(fix.get());
    if (s == 0 || s == 120) whole->add_fix(fix);
    limited->step();
    whole->step();
    INFO("step " << s);
    const auto& a = limited->particles();
    const auto& b = whole->particles();
    for (std::size_t p = 0; p < a.size(); ++p) {
      REQUIRE(a.x[p] == b.x[p]);
      REQUIRE(a.v[p] == b.v[p]);
      REQUIRE(a.stress[p] == b.stress[p]);
    }
    const auto& ga = limited->grid();
    const auto& gb = whole->grid();
    for (int i = 0; i < ga.node_count(); ++i) {
      REQUIRE(ga.mass[i] == gb.mass[i]);
      REQUIRE(ga.velocity[i] == gb.velocity[i]);
    }
  }
  CHECK(limited->particles().x[0][0] > 0.6);                                  // the block has moved on by many cells
  CHECK(limited->active_nodes().count() < limited->grid().node_count() / 4);  // the limited one was
}
