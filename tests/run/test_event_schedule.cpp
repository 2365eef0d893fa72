// The event schedule: steps land exactly on events, events that coincide fire once, one tolerance.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/error.hpp"
#include "run/event_schedule.hpp"

using namespace seismpm;
using Spacing = EventSchedule::Spacing;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Steps a clock as a run does: each step at most dt_max, shortened to the next event; returns the
// times at which each stream fired, in order.
std::vector<std::vector<double>> fire_times(EventSchedule& s, const std::vector<EventSchedule::Stream>& streams,
                                            double dt_max) {
  std::vector<std::vector<double>> fired(streams.size());
  double t = 0.0;
  while (!s.run_over(t)) {
    t += std::min(dt_max, s.next_time() - t);
    for (std::size_t k = 0; k < streams.size(); ++k)
      if (s.reached(streams[k], t)) {
        fired[k].push_back(t);
        s.fired(streams[k], t);
      }
  }
  return fired;
}

}  // namespace

TEST_CASE("events: steps land exactly on every stream's times, counted as each stream counts", "[run][schedule]") {
  EventSchedule s;
  const auto output = s.add(Spacing::Running, 0.1, 0.0);
  s.fired(output, 0.0);  // written at the start
  // Intervals with no time in common (coinciding events fire together: the next test).
  const auto probe = s.add(Spacing::Multiples, 0.033, 0.0);
  s.fired(probe, 0.0);
  const auto call = s.add(Spacing::FromStart, 0.071, 0.0);
  s.begin_run(0.0, 0.5);
  const auto fired = fire_times(s, {output, probe, call}, 0.0123);
  // Output times are a running sum, probe times multiples, call times start + n every: bit for bit.
  std::vector<double> outputs, probes, calls;
  for (double t = 0.1; t < 0.5 + 1e-9; t += 0.1) outputs.push_back(t);
  for (int k = 1; k * 0.033 < 0.5; ++k) probes.push_back(k * 0.033);
  for (int n = 1; n * 0.071 < 0.5; ++n) calls.push_back(0.0 + n * 0.071);
  CHECK(fired[0] == outputs);
  CHECK(fired[1] == probes);
  CHECK(fired[2] == calls);
  // The ten-fold running sum is one bit short of 1.0: that is the time the file has always carried.
  double sum = 0.0;
  for (int k = 0; k < 10; ++k) sum += 0.1;
  CHECK(sum != 1.0);
  CHECK(outputs.size() == 5);
}

TEST_CASE("events: a run lands on its end exactly; an infinite run never ends by time", "[run][schedule]") {
  EventSchedule s;
  s.begin_run(0.37, 0.25);
  CHECK(s.run_end() == 0.37 + 0.25);
  CHECK(s.next_time() == 0.37 + 0.25);
  CHECK_FALSE(s.run_over(0.37));
  double t = 0.37;
  int steps = 0;
  while (!s.run_over(t)) t += std::min(0.06, s.next_time() - t), ++steps;
  CHECK(t == 0.37 + 0.25);
  CHECK(steps == 5);  // four of 0.06 s, then the remaining 0.01 s: no round-off step after it
  s.end_run();
  CHECK(s.next_time() == kInf);
  s.begin_run(1.0, kInf);
  CHECK_FALSE(s.run_over(1e300));
  CHECK(s.next_time() == kInf);
  CHECK_THROWS_AS(s.begin_run(0.0, -1.0), InputError);
}

TEST_CASE("events: events that coincide within the tolerance are reached by one step and fire once",
          "[run][schedule]") {
  EventSchedule s;
  const auto output = s.add(Spacing::Running, 0.1, 0.0);
  s.fired(output, 0.0);
  const auto probe = s.add(Spacing::Multiples, 0.05, 0.0);
  s.fired(probe, 0.0);
  s.begin_run(0.0, 1.0);
  const auto fired = fire_times(s, {output, probe}, 0.007);
  // The output's tenth time (the running sum, one bit below 1.0) and the probe's twentieth (1.0) and
  // the run's end: the step to the earliest reaches all three.
  REQUIRE(fired[0].size() == 10);
  REQUIRE(fired[1].size() == 20);
  CHECK(fired[0].back() == fired[1].back());
  CHECK(fired[1].back() < 1.0);
  for (std::size_t k = 0; k < 10; ++k) CHECK(fired[0][k] == fired[1][2 * k + 1]);  // shared times, once each
  // Once fired, neither stream is reached again at that time.
  const double t = fired[0].back();
  CHECK_FALSE(s.reached(output, t));
  CHECK_FALSE(s.reached(probe, t));
  CHECK(s.next_time(output) > t + 0.09);
  CHECK(s.next_time(probe) > t + 0.04);
}

TEST_CASE("events: one tolerance, kTolerance of the stream's interval", "[run][schedule]") {
  EventSchedule s;
  const auto probe = s.add(Spacing::Multiples, 0.1, 0.0);
  s.fired(probe, 0.0);
  REQUIRE(s.next_time(probe) == 0.1);
  const double tol = EventSchedule::kTolerance * 0.1;
  CHECK(s.reached(probe, 0.1));
  CHECK(s.reached(probe, 0.1 - 0.5 * tol));
  CHECK_FALSE(s.reached(probe, 0.1 - 2.0 * tol));
  CHECK(s.reached(probe, 0.25));  // passed: reached
  // A step the time step limit ended a hair short: 0.284 + 0.013 is one bit below 9 x 0.033. It has
  // reached the sample (no extra step of 1e-17 s), and the sample after it is 10 x 0.033.
  const auto sample = s.add(Spacing::Multiples, 0.033, 0.0);
  s.fired(sample, 0.264);
  REQUIRE(s.next_time(sample) == 9 * 0.033);
  REQUIRE(0.284 + 0.013 < 9 * 0.033);
  CHECK(s.reached(sample, 0.284 + 0.013));
  s.fired(sample, 0.284 + 0.013);
  CHECK(s.next_time(sample) == 10 * 0.033);
  // The run's end: relative to its duration.
  s.begin_run(0.0, 2.0);
  CHECK(s.run_over(2.0 - 0.5e-9 * 2.0));
  CHECK_FALSE(s.run_over(2.0 - 2e-9 * 2.0));
  CHECK(EventSchedule::tolerance(kInf) == 0.0);
}

TEST_CASE("events: firing moves a stream past the time, skipping what it passed", "[run][schedule]") {
  EventSchedule s;
  SECTION("a run's call counts from the run's start") {
    const auto call = s.add(Spacing::FromStart, 0.05, 0.37);
    CHECK(s.next_time(call) == 0.37 + 0.05);
    CHECK_FALSE(s.reached(call, 0.37));
    s.fired(call, 0.6);  // a late call (forced at a run's end) skips the times it passed
    CHECK(s.next_time(call) == 0.37 + 5 * 0.05);
    s.fired(call, 0.6);  // not reached: it stays
    CHECK(s.next_time(call) == 0.37 + 5 * 0.05);
  }
  SECTION("an output counts on from where its sum stands") {
    const auto output = s.add(Spacing::Running, 0.1, 0.0);
    CHECK(s.next_time(output) == 0.0);
    s.fired(output, 0.55);  // an output started at t = 0.55
    CHECK(s.next_time(output) == 0.1 + 0.1 + 0.1 + 0.1 + 0.1 + 0.1);
  }
  SECTION("a probe sampled off its times counts on from that sample") {
    const auto probe = s.add(Spacing::Multiples, 0.01, 0.0);
    s.fired(probe, 0.0237);
    CHECK(s.next_time(probe) == 3 * 0.01);
    // Just short of a time (within 1e-6 of the interval) the sample stands for it: no tiny step.
    s.fired(probe, 0.03 - 1e-9);
    CHECK(s.next_time(probe) == 4 * 0.01);
  }
  SECTION("a probe with every = 0 samples after every step and asks for no landing") {
    const auto probe = s.add(Spacing::Multiples, 0.0, 0.0);
    CHECK(s.reached(probe, 0.0));
    s.fired(probe, 0.1);
    CHECK(s.reached(probe, 0.1));
    CHECK(s.next_time(probe) == kInf);
    CHECK(s.next_time() == kInf);
  }
}

TEST_CASE("events: streams come and go; bad intervals are refused", "[run][schedule][errors]") {
  EventSchedule s;
  const auto a = s.add(Spacing::FromStart, 0.2, 0.0);
  const auto b = s.add(Spacing::FromStart, 0.3, 0.0);
  CHECK(s.next_time() == 0.2);
  s.remove(a);
  CHECK(s.next_time() == 0.3);
  CHECK_THROWS_AS(s.reached(a, 0.0), std::out_of_range);
  const auto c = s.add(Spacing::FromStart, 0.1, 0.0);
  CHECK(c == a);  // the slot is reused: a script running in many chunks does not grow the schedule
  CHECK(s.next_time() == 0.1);
  CHECK(s.every(b) == 0.3);
  CHECK_THROWS_AS(s.add(Spacing::Running, 0.0, 0.0), InputError);
  CHECK_THROWS_AS(s.add(Spacing::FromStart, -1.0, 0.0), InputError);
  CHECK_THROWS_AS(s.add(Spacing::Multiples, -0.1, 0.0), InputError);
  CHECK_THROWS_AS(s.add(Spacing::Multiples, kInf, 0.0), InputError);
}
