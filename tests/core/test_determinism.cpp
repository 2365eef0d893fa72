// The parallel scatter is race-free and deterministic: any thread count gives bit-identical results.
#include <omp.h>
#include <catch2/catch.hpp>

#include <cstring>

#include "cases/moving_base_block.hpp"
#include "cases/shaking_table.hpp"
#include "core/thread_shares.hpp"
#include "support/models.hpp"

using namespace seismpm;

namespace {

template <int Dim>
std::unique_ptr<Model<Dim>> falling_block(ShapeKind shape, int threads, int steps) {
  omp_set_num_threads(threads);
  ModelSettings<Dim> s;
  s.upper = Vec<Dim>::Constant(1.0);
  s.cell = Dim == 2 ? 0.02 : 0.05;
  s.shape = shape;
  s.gravity = Vec<Dim>::Zero();
  s.gravity[Dim - 1] = -9.81;
  s.sort_every = 7;
  auto m = test::elastic_block<Dim>(s, Vec<Dim>::Constant(0.1), Vec<Dim>::Constant(0.8));
  m->grid().fix(Side::Bottom, FixX | FixY);
  auto& p = m->particles();
  for (std::size_t i = 0; i < p.size(); ++i) p.v[i][0] = 0.3 * std::sin(7.0 * p.x[i][Dim - 1]);
  for (int k = 0; k < steps; ++k) m->step();
  return m;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

// Positions, velocities and stresses, bit for bit: what every run here compares.
template <int Dim>
void check_same_particles(const Particles<Dim>& a, const Particles<Dim>& b) {
  CHECK(same_bits(a.x, b.x));
  CHECK(same_bits(a.v, b.v));
  CHECK(same_bits(a.stress, b.stress));
}

}  // namespace

TEMPLATE_TEST_CASE_SIG("results are bit-identical for any number of threads", "[core][parallel]", ((int Dim), Dim), 2,
                       3) {
  const auto shape = GENERATE(ShapeKind::Linear, ShapeKind::Gimp);
  CAPTURE(to_string(shape));
  const int saved = omp_get_max_threads();
  const auto one = falling_block<Dim>(shape, 1, 40);
  for (int threads : {2, 3, 4}) {
    CAPTURE(threads);
    const auto many = falling_block<Dim>(shape, threads, 40);
    check_same_particles(one->particles(), many->particles());
    CHECK(same_bits(one->particles().id, many->particles().id));
    CHECK(one->time() == many->time());
  }
  omp_set_num_threads(saved);
  // The run moved: a test of a model at rest would prove nothing.
  CHECK(one->particles().stress[0].norm() > 0.0);
}

TEST_CASE("contact and rigid bodies keep results bit-identical for any number of threads",
          "[core][parallel][contact]") {
  const int saved = omp_get_max_threads();
  auto run = [](int threads) {
    omp_set_num_threads(threads);
    cases::MovingBaseBlock c;
    c.cell = 0.05;
    auto b = c.build();
    c.settle_and_start(b);  // the gravity phase, then the base slides
    b.simulation->run(0.2);
    return b;
  };
  const auto one = run(1);
  for (int threads : {2, 3}) {
    CAPTURE(threads);
    const auto many = run(threads);
    check_same_particles(one.model->particles(), many.model->particles());
    CHECK(one.model->rigid_motion(one.base).impulse == many.model->rigid_motion(many.base).impulse);
  }
  omp_set_num_threads(saved);
  CHECK(one.model->centroid(one.block)[0] > 0.05);  // the block slid
}

// Slabs along the grid's last axis (it has 64 cells or more here: 0.636 m / 9.5 mm = 67), Mohr-Coulomb
// soil yielding in a rigid box with contact, and the contact marking over occupied cells only.
TEST_CASE("the shaking-table slope with slabs along y keeps results bit-identical for any number of threads",
          "[core][parallel][contact]") {
  const int saved = omp_get_max_threads();
  auto run = [](int threads) {
    omp_set_num_threads(threads);
    cases::ShakingTable c;
    c.cell = 0.0095;
    auto b = c.build();
    for (int k = 0; k < 150; ++k) b.model->step();
    return b;
  };
  const auto one = run(1);
  for (int threads : {2, 3}) {
    CAPTURE(threads);
    const auto many = run(threads);
    check_same_particles(one.model->particles(), many.model->particles());
    CHECK(same_bits(one.model->particles().yield, many.model->particles().yield));
  }
  omp_set_num_threads(saved);
  std::size_t yielding = 0;
  for (auto y : one.model->particles().yield) yielding += y;
  CHECK(yielding > 100);  // the soil yields: the plastic return is exercised
}

// Which thread computes which particle or slab follows the cores' measured speeds (ThreadShares): the
// results must not. Every kind of loop is given uneven shares, different at every step, and the
// slope in its rigid box (Mohr-Coulomb, contact, uGIMP) must end as on one thread.
TEST_CASE("uneven thread shares change no result", "[core][parallel][contact]") {
  const int saved = omp_get_max_threads();
  auto run = [](int threads, bool uneven) {
    omp_set_num_threads(threads);
    cases::ShakingTable c;
    c.cell = 0.0095;
    auto b = c.build();
    for (int k = 0; k < 120; ++k) {
      if (uneven) {
        ThreadShares::prepare_all(threads);
        for (int kind = 0; kind < kLoopKinds; ++kind)
          ThreadShares::of(static_cast<LoopKind>(kind)).set({k % 2 ? 0.27 : 0.71, 0.2 + 0.01 * kind, 0.5});
      }
      b.model->step();
    }
    return b;
  };
  const auto one = run(1, false);
  for (int threads : {2, 3}) {
    CAPTURE(threads);
    const auto uneven = run(threads, true);
    check_same_particles(one.model->particles(), uneven.model->particles());
    CHECK(same_bits(one.model->particles().yield, uneven.model->particles().yield));
  }
  omp_set_num_threads(saved);
  ThreadShares::prepare_all(0);  // even shares for the tests that follow
}
