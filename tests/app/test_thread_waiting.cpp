// The default waiting policy of OpenMP threads: libgomp's spin while the cores are free for this run's
// threads, passive waiting once other programs take them (figures in docs/kernel.md).
#include <catch2/catch.hpp>

#include "app/thread_waiting.hpp"

using seismpm::app::wait_passively;

TEST_CASE("threads spin on free cores and sleep at once on busy ones", "[app][threads]") {
  CHECK_FALSE(wait_passively(0.0, 2, 2));   // an idle 2-core machine
  CHECK_FALSE(wait_passively(0.4, 2, 2));   // a shell ticking along
  CHECK(wait_passively(1.0, 2, 2));         // one core taken by another program
  CHECK(wait_passively(2.0, 2, 2));         // both taken
  CHECK_FALSE(wait_passively(1.0, 2, 1));   // one thread fits beside one busy core
  CHECK_FALSE(wait_passively(6.0, 16, 8));  // a workstation with room for the run
  CHECK(wait_passively(12.0, 16, 8));
}

TEST_CASE("the busy share of the cores comes from two looks at /proc/stat", "[app][threads]") {
  using seismpm::app::busy_fraction;
  // 200 ticks in all between the looks: 100 idle, 20 iowait (free), 60 user, 10 system, 10 steal.
  const std::string before = "cpu  1000 0 500 8000 100 0 0 0 0 0\n";
  const std::string after = "cpu  1060 0 510 8100 120 0 0 10 0 0\n";
  CHECK(busy_fraction(before, after) == Approx(0.4));
  CHECK(busy_fraction(before, before) < 0.0);                       // no time passed
  CHECK(busy_fraction(after, before) < 0.0);                        // counters went back
  CHECK(busy_fraction("cpu0 1 2 3 4 5 6 7 8\n", after) < 0.0);      // one core's line, not the sum
  CHECK(busy_fraction("", after) < 0.0);                            // unreadable
  CHECK(busy_fraction("cpu  1 2 three 4 5 6 7 8\n", after) < 0.0);  // damaged
  // A run that has just ended leaves the load average high but the cores idle now.
  const std::string idle_after = "cpu  1000 0 500 8200 100 0 0 0 0 0\n";
  CHECK(busy_fraction(before, idle_after) == Approx(0.0));
  CHECK_FALSE(seismpm::app::wait_passively(2.0 * busy_fraction(before, idle_after), 2, 2));
  const double cores = seismpm::app::busy_cores();
  CHECK(cores >= 0.0);
}
