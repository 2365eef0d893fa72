// The default waiting policy of OpenMP threads: a short spin while the cores are free for this run's
// threads, passive waiting once other programs take them (figures in docs/kernel.md).
#include <catch2/catch.hpp>

#include "app/thread_waiting.hpp"

using seismpm::app::wait_passively;

TEST_CASE("threads spin briefly on free cores and sleep at once on busy ones", "[app][threads]") {
  CHECK_FALSE(wait_passively(0.0, 2, 2));   // an idle 2-core machine
  CHECK_FALSE(wait_passively(0.4, 2, 2));   // a shell ticking along
  CHECK(wait_passively(1.0, 2, 2));         // one core taken by another program
  CHECK(wait_passively(2.0, 2, 2));         // both taken
  CHECK_FALSE(wait_passively(1.0, 2, 1));   // one thread fits beside one busy core
  CHECK_FALSE(wait_passively(6.0, 16, 8));  // a workstation with room for the run
  CHECK(wait_passively(12.0, 16, 8));
}
