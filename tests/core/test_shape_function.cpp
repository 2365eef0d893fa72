// Shape functions: partition of unity, gradients summing to zero, linear reproduction,
// uGIMP values against the closed form and its limit l -> 0 (the tent).
#include <array>
#include <catch2/catch.hpp>
#include <limits>
#include <random>
#include <vector>

#include "core/grid.hpp"
#include "core/stencil.hpp"

using namespace seismpm;

namespace {

template <class Shape, int Dim>
void check_partition_of_unity(double l) {
  const Grid<Dim> grid(Vec<Dim>::Zero(), Vec<Dim>::Constant(1.0), 0.1);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  double worst_sum = 0.0, worst_grad = 0.0, worst_x = 0.0, worst_id = 0.0;
  for (int k = 0; k < 500; ++k) {
    Vec<Dim> x;
    for (int d = 0; d < Dim; ++d) x[d] = u(rng);
    Stencil<Dim, Shape::K> st;
    REQUIRE(make_stencil<Shape>(grid, x, l, st));
    double sum = 0.0;
    Vec<Dim> grad = Vec<Dim>::Zero(), xr = Vec<Dim>::Zero();
    Mat<Dim> id = Mat<Dim>::Zero();
    for_each_node(st, grid, [&](int i, double N, const Vec<Dim>& dN) {
      CHECK(N >= 0.0);
      sum += N;
      grad += dN;
      xr += N * grid.node_position(i);
      id += grid.node_position(i) * dN.transpose();
    });
    worst_sum = std::max(worst_sum, std::abs(sum - 1.0));
    worst_grad = std::max(worst_grad, grad.norm() * grid.cell());
    worst_x = std::max(worst_x, (xr - x).norm() / grid.cell());
    worst_id = std::max(worst_id, (id - Mat<Dim>::Identity()).norm());
  }
  CHECK(worst_sum < 1e-14);   // sum N = 1
  CHECK(worst_grad < 1e-13);  // sum grad N = 0 (scaled by h)
  CHECK(worst_x < 1e-13);     // sum N x_i = x
  CHECK(worst_id < 1e-12);    // sum x_i (x) grad N = I
}

}  // namespace

TEMPLATE_TEST_CASE_SIG("shape functions form a partition of unity and reproduce linear fields", "[core][shape]",
                       ((int Dim), Dim), 2, 3) {
  SECTION("linear") { check_partition_of_unity<LinearShape, Dim>(0.0); }
  SECTION("uGIMP, 1 particle per cell") { check_partition_of_unity<GimpShape, Dim>(0.5); }
  SECTION("uGIMP, 2 particles per cell") { check_partition_of_unity<GimpShape, Dim>(0.25); }
  SECTION("uGIMP, 4 particles per cell") { check_partition_of_unity<GimpShape, Dim>(0.125); }
}

TEST_CASE("uGIMP matches its closed form piece by piece", "[core][shape]") {
  const double l = 0.25;
  // |r| < l: 1 - (r^2 + l^2) / (2 l)
  CHECK(GimpShape::value(0.1, l) == Approx(1.0 - (0.01 + 0.0625) / 0.5).epsilon(1e-15));
  // l <= |r| < 1 - l: 1 - |r|
  CHECK(GimpShape::value(-0.6, l) == Approx(0.4).epsilon(1e-15));
  // 1 - l <= |r| < 1 + l: (1 + l - |r|)^2 / (4 l)
  CHECK(GimpShape::value(1.1, l) == Approx(0.15 * 0.15 / 1.0).epsilon(1e-12));
  CHECK(GimpShape::value(1.25, l) == 0.0);
  // Continuity of value and slope at the piece boundaries, and slope = finite difference.
  for (double r : {l, 1.0 - l, 1.0 + l, -l, -(1.0 - l)}) {
    CAPTURE(r);
    CHECK(GimpShape::value(r - 1e-12, l) == Approx(GimpShape::value(r + 1e-12, l)).margin(1e-10));
    CHECK(GimpShape::derivative(r - 1e-9, l) == Approx(GimpShape::derivative(r + 1e-9, l)).margin(1e-7));
  }
  for (double r = -1.3; r <= 1.3; r += 0.0173) {
    CAPTURE(r);
    const double fd = (GimpShape::value(r + 1e-7, l) - GimpShape::value(r - 1e-7, l)) / 2e-7;
    CHECK(GimpShape::derivative(r, l) == Approx(fd).margin(1e-6));
  }
  // The branch-free evaluation the kernel uses gives the piecewise numbers to round-off, at every
  // position in a cell (linear, tail and centre pieces, and the edges between them), for 1-3
  // particles per cell.
  for (const double half : {1.0 / 6.0, 0.25, 0.5}) {
    for (double xi = 2.0; xi < 3.0; xi += 0.0371) {
      for (const double at : {xi, 2.0 + half, 3.0 - half, 3.0, 3.0 + half - 1e-12}) {
        CAPTURE(half, at);
        double w[3], dw[3];
        const int first = GimpShape::first_node(at, half);
        GimpShape::eval(at, half, first, w, dw);
        for (int k = 0; k < 3; ++k) {
          CHECK(w[k] == Approx(GimpShape::value(at - (first + k), half)).margin(1e-15));
          CHECK(dw[k] == Approx(GimpShape::derivative(at - (first + k), half)).margin(1e-14));
        }
      }
    }
  }
}

TEST_CASE("uGIMP tends to the linear tent as the particle size goes to zero", "[core][shape]") {
  double previous = 1.0;
  for (double l : {1e-2, 1e-3, 1e-4, 1e-5}) {
    double worst = 0.0;
    for (double r = -1.2; r <= 1.2; r += 0.001)
      worst = std::max(worst, std::abs(GimpShape::value(r, l) - std::max(0.0, 1.0 - std::abs(r))));
    CAPTURE(l, worst);
    CHECK(worst <= l);              // the difference is O(l) ...
    CHECK(worst < 0.5 * previous);  // ... and falls with l
    previous = worst;
  }
}

TEST_CASE("a stencil is refused outside the grid and clipped at its edge", "[core][shape]") {
  const Grid<2> grid(Vec<2>::Zero(), Vec<2>(1.0, 1.0), 0.1);
  Stencil<2, GimpShape::K> g;
  Stencil<2, LinearShape::K> s;
  const auto weight_sum = [&](const auto& st) {
    double sum = 0.0;
    for_each_node(st, grid, [&](int, double N, const Vec<2>&) { sum += N; });
    return sum;
  };
  REQUIRE(make_stencil<GimpShape>(grid, Vec<2>(0.025, 0.5), 0.25, g));  // support [0, 0.05]: complete
  CHECK(weight_sum(g) == Approx(1.0).epsilon(1e-14));
  REQUIRE(make_stencil<GimpShape>(grid, Vec<2>(0.015, 0.5), 0.25, g));    // reaches 0.01 past the edge
  CHECK(weight_sum(g) == Approx(1.0 - 0.1 * 0.1 / 1.0).epsilon(1e-12));   // (l - xi)^2 / (4 l) clipped
  REQUIRE(make_stencil<GimpShape>(grid, Vec<2>(0.975, 0.975), 0.25, g));  // last node weight zero: shifted back
  CHECK(weight_sum(g) == Approx(1.0).epsilon(1e-14));
  CHECK(make_stencil<LinearShape>(grid, Vec<2>(1.0, 0.0), 0.0, s));
  CHECK(weight_sum(s) == Approx(1.0).epsilon(1e-14));
  CHECK_FALSE(make_stencil<LinearShape>(grid, Vec<2>(1.0 + 1e-9, 0.5), 0.0, s));
  CHECK_FALSE(make_stencil<GimpShape>(grid, Vec<2>(0.5, -1e-9), 0.25, g));
  CHECK(inside_domain(grid, Vec<2>(0.0, 1.0)));
  CHECK_FALSE(inside_domain(grid, Vec<2>(0.5, 1.0 + 1e-12)));
}

namespace {

// Blocks of particles inside (clear of the edges), or some on node lines and grid edges, at a
// clipped uGIMP edge, or outside.
template <class Shape, int Dim>
void check_block_matches_particles() {
  const Grid<Dim> grid(Vec<Dim>::Zero(), Vec<Dim>::Constant(1.0), 0.1);  // no ghost layer: clipping happens
  const StencilFrame<Dim> frame(grid);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double special[] = {0.0, 0.1, 0.5, 0.95, 1.0, 0.0125, 0.9875};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  int blocks_made = 0, blocks_refused = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int count = 1 + trial % kStencilBlock;
    std::vector<Vec<Dim>> x(count);
    std::vector<double> l(count);
    for (int j = 0; j < count; ++j) {
      for (int d = 0; d < Dim; ++d) x[j][d] = trial % 3 == 0 ? special[(j + d * trial) % 7] : 0.15 + 0.7 * u(rng);
      l[j] = j % 2 ? 0.25 : 1.0 / 6.0;
    }
    if (trial % 10 == 5) x[count / 2][0] = trial % 20 == 5 ? nan : 1.0 + 1e-9;  // outside: refused
    std::vector<Stencil<Dim, Shape::K>> block(count), one(count);
    std::vector<std::array<int, Dim>> cells(count), cell_one(count);
    bool all = true;
    for (int j = 0; j < count; ++j) all &= make_stencil<Shape>(grid, x[j], l[j], one[j], cell_one[j].data());
    const bool regular = make_stencils<Shape>(frame, x.data(), l.data(), count, block.data(), cells.data());
    if (!all) REQUIRE_FALSE(regular);  // never a stencil for a particle outside
    if (!regular) {
      ++blocks_refused;
      continue;
    }
    ++blocks_made;
    for (int j = 0; j < count; ++j) {
      CAPTURE(trial, j, x[j].transpose(), l[j]);
      CHECK(block[j].base == one[j].base);
      for (int d = 0; d < Dim; ++d) {
        CHECK(cells[j][d] == cell_one[j][d]);
        for (int k = 0; k < Shape::K; ++k) {
          CHECK(block[j].w[d][k] == one[j].w[d][k]);  // bit for bit
          CHECK(block[j].dw[d][k] == one[j].dw[d][k]);
        }
      }
    }
  }
  CHECK(blocks_made > 100);
  CHECK(blocks_refused >= 20);
}

}  // namespace

TEMPLATE_TEST_CASE_SIG("stencils made a block at a time equal those made one by one", "[core][shape]",
                       ((class Shape, int Dim), Shape, Dim), (LinearShape, 2), (GimpShape, 2), (LinearShape, 3),
                       (GimpShape, 3)) {
  check_block_matches_particles<Shape, Dim>();
}

namespace {

// The transfers' row-by-row sums (interpolate, gradient) against the node-by-node ones over the same
// stencil, for a random nodal field, and their reproduction of an affine field u = A x + b.
template <class Shape, int Dim>
void check_factorised_sums(double l) {
  const Grid<Dim> grid(Vec<Dim>::Zero(), Vec<Dim>::Constant(1.0), 0.1, 1);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), at(0.02, 0.98);
  std::vector<Vec<Dim>> random(grid.node_count()), affine(grid.node_count());
  Mat<Dim> A;
  Vec<Dim> b;
  for (int r = 0; r < Dim; ++r) {
    b[r] = u(rng);
    for (int c = 0; c < Dim; ++c) A(r, c) = u(rng);
  }
  for (int i = 0; i < grid.node_count(); ++i) {
    for (int d = 0; d < Dim; ++d) random[i][d] = u(rng);
    affine[i] = A * grid.node_position(i) + b;
  }
  double worst_value = 0.0, worst_gradient = 0.0, worst_affine_value = 0.0, worst_affine_gradient = 0.0;
  for (int k = 0; k < 500; ++k) {
    Vec<Dim> x;
    for (int d = 0; d < Dim; ++d) x[d] = at(rng);
    Stencil<Dim, Shape::K> st;
    REQUIRE(make_stencil<Shape>(grid, x, l, st));
    Vec<Dim> value = Vec<Dim>::Zero();
    Mat<Dim> gradient_by_node = Mat<Dim>::Zero();
    for_each_node(st, grid, [&](int i, double N, const Vec<Dim>& dN) {
      value += N * random[i];
      gradient_by_node += random[i] * dN.transpose();
    });
    worst_value = std::max(worst_value, (interpolate(st, grid, random.data()) - value).norm());
    worst_gradient =
        std::max(worst_gradient, (gradient(st, grid, random.data()) - gradient_by_node).norm() * grid.cell());
    worst_affine_value = std::max(worst_affine_value, (interpolate(st, grid, affine.data()) - (A * x + b)).norm());
    worst_affine_gradient = std::max(worst_affine_gradient, (gradient(st, grid, affine.data()) - A).norm());
  }
  CHECK(worst_value < 1e-14);            // the same sum, grouped by rows
  CHECK(worst_gradient < 1e-13);         // (scaled by h)
  CHECK(worst_affine_value < 1e-13);     // sum N (A x_i + b) = A x + b
  CHECK(worst_affine_gradient < 1e-12);  // sum (A x_i + b) grad N^T = A
}

}  // namespace

TEMPLATE_TEST_CASE_SIG("the transfers' row-by-row sums equal the node-by-node ones", "[core][shape]", ((int Dim), Dim),
                       2, 3) {
  SECTION("linear") { check_factorised_sums<LinearShape, Dim>(0.0); }
  SECTION("uGIMP, 2 particles per cell") { check_factorised_sums<GimpShape, Dim>(0.25); }
  SECTION("uGIMP, 3 particles per cell") { check_factorised_sums<GimpShape, Dim>(1.0 / 6.0); }
}
