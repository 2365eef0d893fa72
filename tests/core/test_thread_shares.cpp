// The threads' shares of the step's loops: contiguous ranges that cover every item once, moved toward
// the speeds the loops measured, within bounds, and left even where the threads ran alike.
#include <omp.h>
#include <catch2/catch.hpp>

#include <cstdlib>

#include "core/thread_shares.hpp"

using namespace seismpm;

namespace {

// The ranges of a team cover [0, n) in thread order, each item once.
void check_cover(const ThreadShares& shares, int team, long n) {
  long next = 0;
  for (int t = 0; t < team; ++t) {
    const long first = shares.first(t, team, n), end = shares.first(t + 1, team, n);
    REQUIRE(first == next);
    REQUIRE(end >= first);
    next = end;
  }
  REQUIRE(next == n);
}

// One timed loop in which thread t did `work` items in seconds[t].
void time_loop(ThreadShares& shares, const std::vector<double>& seconds, long work) {
  const int team = static_cast<int>(seconds.size());
#pragma omp parallel num_threads(team)
  shares.record(seconds[omp_get_thread_num()], work);
}

}  // namespace

TEST_CASE("thread shares: contiguous ranges that cover every item once", "[core][parallel]") {
  for (int team : {1, 2, 3, 5, 8}) {
    CAPTURE(team);
    ThreadShares shares;
    shares.prepare(team);
    for (long n : {0L, 1L, 7L, 12800L, 2000000000L}) {
      CAPTURE(n);
      check_cover(shares, team, n);
      if (team > 1) shares.set({1.0, 3.0, 0.5});  // uneven, the missing ones zero
      check_cover(shares, team, n);
      check_cover(shares, team + 1, n);  // a team other than the prepared one: even shares
      shares.prepare(team + 1);
      shares.prepare(team);  // a changed team starts even
      // Even again, to the fixed point's 2^-20 of n.
      if (n > 0) CHECK(std::abs(shares.first(1, team, n) - (team > 1 ? n / team : n)) <= n / (1 << 19) + 1);
    }
  }
}

TEST_CASE("thread shares follow the measured speeds, within bounds", "[core][parallel]") {
  ThreadShares shares;
  shares.prepare(2);
  // Thread 0 does the same work in half the time. Nothing moves until nine steps are timed; then each
  // step moves the share 30 % of the way to 2/3.
  for (int step = 0; step < 8; ++step) {
    time_loop(shares, {1e-3, 2e-3}, 1000);
    shares.update();
  }
  CHECK(shares.share(0) == 0.5);
  time_loop(shares, {1e-3, 2e-3}, 1000);
  shares.update();
  CHECK(shares.share(0) == Approx(0.5 + 0.3 * (2.0 / 3.0 - 0.5)).epsilon(1e-9));
  // Slow in five steps of nine (preempted now and then by another program): not slow in the seven
  // steps that a share needs, so the shares stay even.
  shares.prepare(3);
  shares.prepare(2);
  for (int step = 0; step < 90; ++step) {
    time_loop(shares, {step % 9 < 5 ? 10e-3 : 1e-3, 1e-3}, 1000);
    shares.update();
  }
  CHECK(shares.share(0) == Approx(0.5).margin(1e-12));
  // Equal again after an uneven spell.
  for (int step = 0; step < 20; ++step) {
    time_loop(shares, {1e-3, 2e-3}, 1000);
    shares.update();
  }
  CHECK(shares.share(0) > 0.6);
  for (int step = 0; step < 100; ++step) {
    time_loop(shares, {1e-3, 1e-3}, 1000);
    shares.update();
  }
  CHECK(shares.share(0) == Approx(0.5).margin(1e-6));
  // A thread twenty times slower still keeps a quarter of the work (the bound).
  for (int step = 0; step < 100; ++step) {
    time_loop(shares, {1e-3, 20e-3}, 1000);
    shares.update();
  }
  CHECK(shares.share(0) == Approx(0.75).epsilon(1e-9));
  CHECK(shares.share(1) == Approx(0.25).epsilon(1e-9));
  // Speeds 3 % apart are noise: the shares stay even.
  shares.prepare(3);
  shares.prepare(2);
  for (int step = 0; step < 50; ++step) {
    time_loop(shares, {1e-3, 1.03e-3}, 1000);
    shares.update();
  }
  CHECK(shares.share(0) == Approx(0.5).margin(1e-12));
  // A loop timed by a team of another size is not counted.
  shares.prepare(3);
  shares.prepare(2);
  for (int step = 0; step < 20; ++step) {
    time_loop(shares, {1e-3}, 1000);
    shares.update();
  }
  CHECK(shares.share(0) == 0.5);
}
