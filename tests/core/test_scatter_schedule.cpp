// The scatter schedule: every particle once, each slab's particles in order, slabs of one colour
// never at the same time as a slab of another, and threads sharing the particles evenly by whole
// slabs, whatever the number of threads.
#include <omp.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <random>
#include <vector>

#include "core/scatter_schedule.hpp"

using namespace seismpm;

namespace {

// Slab cells of `n` particles crowded into a few slabs of a 200-cell axis, most slabs empty (a block
// in a grid much larger than itself).
std::vector<int> crowded_cells(int n) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> dense(40, 79), sparse(0, 199);
  std::vector<int> cell(n);
  for (int p = 0; p < n; ++p) cell[p] = p % 10 ? dense(rng) : sparse(rng);
  return cell;
}

// The schedule of particles in the given cells along the slab axis.
void build(ScatterSchedule& schedule, const std::vector<int>& cell, int cells) {
  const int n = static_cast<int>(cell.size());
  std::copy(cell.begin(), cell.end(), schedule.layers(n));
  schedule.build(n, cells);
}

struct Visit {
  int thread, slab, particle, colour_round;  // colour_round: the slab's colour, 0 runs first
};

}  // namespace

TEST_CASE("scatter schedule: every particle once, in order per slab, colours apart, work shared evenly") {
  const int n = 5000, cells = 200;
  const auto cell = crowded_cells(n);
  ScatterSchedule schedule;
  const int saved = omp_get_max_threads();
  for (int threads : {1, 2, 3, 4}) {
    omp_set_num_threads(threads);
    build(schedule, cell, cells);
    std::vector<std::vector<Visit>> seen(threads);
    schedule.for_each([&](int p) {
      const int t = omp_get_thread_num();
      const int slab = cell[p] / ScatterSchedule::kSlabCells;
      seen[t].push_back({t, slab, p, slab % ScatterSchedule::kColours});
    });
    std::vector<int> count(n, 0);
    std::vector<long> load(threads, 0);
    for (int t = 0; t < threads; ++t) {
      const auto& v = seen[t];
      load[t] = static_cast<long>(v.size());
      for (std::size_t k = 0; k < v.size(); ++k) {
        ++count[v[k].particle];
        if (k == 0) continue;
        // Colour 0 first; within a colour, slabs in increasing order, a slab's particles increasing.
        REQUIRE(v[k - 1].colour_round <= v[k].colour_round);
        if (v[k - 1].colour_round == v[k].colour_round) {
          REQUIRE(v[k - 1].slab <= v[k].slab);
          if (v[k - 1].slab == v[k].slab) REQUIRE(v[k - 1].particle < v[k].particle);
        }
      }
    }
    for (int p = 0; p < n; ++p) REQUIRE(count[p] == 1);
    // A slab belongs to one thread only.
    std::vector<int> owner(cells / ScatterSchedule::kSlabCells, -1);
    for (int t = 0; t < threads; ++t)
      for (const auto& v : seen[t]) {
        if (owner[v.slab] < 0) owner[v.slab] = t;
        REQUIRE(owner[v.slab] == t);
      }
    // Even shares: no thread more than its share of each colour plus the largest slab of that colour.
    long largest = 0;
    for (int s = 0; s < schedule.slabs(); ++s)
      largest = std::max<long>(largest, std::count_if(cell.begin(), cell.end(),
                                                      [&](int c) { return c / ScatterSchedule::kSlabCells == s; }));
    for (int t = 0; t < threads; ++t) CHECK(load[t] <= n / threads + ScatterSchedule::kColours * largest);
    if (threads == 2) CHECK(std::min(load[0], load[1]) > n / 4);  // both threads work
  }
  omp_set_num_threads(saved);
}

TEST_CASE("scatter schedule: each colour ends before the next starts") {
  const int n = 4000, cells = 120;
  constexpr int colours = ScatterSchedule::kColours;
  std::vector<int> cell(n);
  for (int p = 0; p < n; ++p) cell[p] = (p * 7) % cells;
  auto colour_of = [&](int p) { return cell[p] / ScatterSchedule::kSlabCells % colours; };
  ScatterSchedule schedule;
  const int saved = omp_get_max_threads();
  for (int threads : {2, 3}) {
    omp_set_num_threads(threads);
    build(schedule, cell, cells);
    int total[colours] = {}, in_colour[colours] = {};
    for (int p = 0; p < n; ++p) ++total[colour_of(p)];
    bool overlap = false;
    schedule.for_each([&](int p) {
      const int colour = colour_of(p);
      for (int earlier = 0; earlier < colour; ++earlier) {
        int done;
#pragma omp atomic read
        done = in_colour[earlier];
        if (done < total[earlier]) overlap = true;  // a slab of this colour while an earlier one still runs
      }
#pragma omp atomic
      in_colour[colour] += 1;
    });
    CHECK_FALSE(overlap);
    for (int c = 0; c < colours; ++c) CHECK(in_colour[c] == total[c]);
  }
  omp_set_num_threads(saved);
}

// Slab s's particles reach nodes from its first cell - 1 to its last cell + 2 (uGIMP), and no other
// slab of its colour may reach any of them.
TEST_CASE("scatter schedule: slabs of one colour reach disjoint nodes") {
  constexpr int w = ScatterSchedule::kSlabCells, colours = ScatterSchedule::kColours;
  for (int s = 0; s < 20; ++s) {
    const int last_node = (s + 1) * w - 1 + 2;
    const int next_first_node = (s + colours) * w - 1;
    CHECK(last_node < next_first_node);
  }
}

TEST_CASE("scatter schedule: own-cell walk visits every particle once, slabs on one thread each") {
  const int n = 3000, cells = 200;
  const auto cell = crowded_cells(n);
  ScatterSchedule schedule;
  const int saved = omp_get_max_threads();
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    build(schedule, cell, cells);
    std::vector<int> count(n, 0), owner(schedule.slabs(), -1);
    bool shared_slab = false;
    schedule.for_each_in_own_cell_by_slab([&](int slab, int p) {
      const int t = omp_get_thread_num();
      int previous;
#pragma omp atomic capture
      {
        previous = owner[slab];
        owner[slab] = t;
      }
      if (previous >= 0 && previous != t) shared_slab = true;
#pragma omp atomic
      ++count[p];
    });
    CHECK_FALSE(shared_slab);
    for (int p = 0; p < n; ++p) REQUIRE(count[p] == 1);
  }
  omp_set_num_threads(saved);
}

TEST_CASE("scatter schedule: a share by weight visits every weighted slab of the colour once, in runs") {
  // Weights like the cells each slab of a contact field holds: many empty, a few heavy.
  const int slabs = 60;
  std::vector<long> weight(slabs, 0);
  for (int s = 10; s < 40; ++s) weight[s] = (s * 37) % 11 + (s == 25 ? 400 : 0);
  const int saved = omp_get_max_threads();
  for (int threads : {1, 2, 3, 5}) {
    omp_set_num_threads(threads);
    ThreadShares shares;
    shares.prepare(threads);
    for (int colour = 0; colour < 2; ++colour) {
      std::vector<int> owner(slabs, -1), visits(slabs, 0);
#pragma omp parallel
      ScatterSchedule::for_my_share(
          shares, colour, 2, slabs, [&](int s) { return weight[s]; },
          [&](int s) {
#pragma omp atomic
            ++visits[s];
            owner[s] = omp_get_thread_num();  // one visit each, checked below
          });
      long total = 0, largest = 0;
      for (int s = colour; s < slabs; s += 2) total += weight[s], largest = std::max(largest, weight[s]);
      std::vector<long> load(threads, 0);
      int last_owner = 0;
      for (int s = 0; s < slabs; ++s) {
        const bool mine = s % 2 == colour && weight[s] > 0;
        REQUIRE(visits[s] == (mine ? 1 : 0));
        if (!mine) continue;
        REQUIRE(owner[s] >= last_owner);  // contiguous runs: threads in order along the axis
        last_owner = owner[s];
        load[owner[s]] += weight[s];
      }
      for (int t = 0; t < threads; ++t) CHECK(load[t] <= total / threads + largest);
    }
  }
  omp_set_num_threads(saved);
}
